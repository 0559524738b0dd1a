//! WGSL text every pass kind may include: the helper functions the emitter calls (`npr_load`, `npr_project`,
//! `npr_project_dir`, `npr_unit`, `npr_ramp_*`; the `Frame` block is `npr_abi::FRAME_WGSL`). Constants only; which module includes
//! which is decided in `mod.rs` and the per-kind files.

/// `project(p)` and `project_other_eye(p)`.
pub(super) const PROJECT_HELPER: &str = "// World point -> (screen u, screen v, NDC depth) under `view_proj`; w <= 0
// (behind the eye) maps far outside the screen.
fn npr_project(view_proj: mat4x4<f32>, p: vec3<f32>) -> vec3<f32> {
    let c = view_proj * vec4<f32>(p, 1.0);
    if (c.w <= 1e-8) {
        return vec3<f32>(-1e9, -1e9, 1.0);
    }
    let ndc = c.xyz / c.w;
    return vec3<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5, ndc.z);
}
";

/// The identity on `bool`, which is not a WGSL const-expression (a
/// user function call never is), so a `select` over it is evaluated when
/// the shader runs rather than by naga's constant evaluator (`uses.rs`,
/// `needs_runtime_condition`).
pub(super) const RUNTIME_BOOL_HELPER: &str =
    "// The identity, to keep a select with a constant condition out of naga's constant evaluator.
fn npr_runtime_bool(c: bool) -> bool {
    return c;
}
";

/// Target reads as values (nearest texel at `screen_uv`).
pub(super) const LOAD_HELPER: &str = "// Nearest texel of `t` at `uv`, so targets of different scales line up.
fn npr_load(t: texture_2d<f32>, uv: vec2<f32>) -> vec4<f32> {
    let dims = vec2<i32>(textureDimensions(t));
    let p = clamp(vec2<i32>(floor(uv * vec2<f32>(dims))), vec2<i32>(0), dims - vec2<i32>(1));
    return textureLoad(t, p, 0);
}
";

/// The analytic Jacobian of projection + viewport applied to a world direction.
pub(super) const PROJECT_DIR_HELPER: &str =
    "// Pixels moved per metre along world direction `dir` at `world`: the derivative of
// pixel = (ndc.x, -ndc.y) * size / 2 + size / 2 with ndc = clip.xy / clip.w (quotient rule).
// Screen y points down, like frag_coord and dpdy.
fn npr_project_dir(vp: mat4x4<f32>, world: vec4<f32>, dir: vec3<f32>, size: vec2<f32>) -> vec2<f32> {
    let c = vp * world;
    let d = vp * vec4<f32>(dir, 0.0);
    // Behind or on the eye plane the triangle is clipped; stay finite.
    let w = max(c.w, 1e-6);
    let dndc = (d.xy * w - c.xy * d.w) / (w * w);
    return vec2<f32>(dndc.x, -dndc.y) * 0.5 * size;
}

";

/// `ramp(g, t)` of gradient param `name` kept live: the folded chain's
/// rule (`front/resolve/gradient.rs`, `npr_abi::gradient::ramp`) as a loop
/// over the param's slots of the style block, in the layout
/// `npr_abi::gradient` defines. One function per gradient, reading
/// `params.p_<name>` by a dynamic index into the uniform (valid WGSL for
/// naga and Tint), rather than taking the array: an array value is copied
/// per call, and its type's comma would not split as a parameter list
/// (`tiled/library.rs`).
pub(super) fn ramp_helper(name: &str) -> String {
    use npr_abi::gradient::{COLOUR_SLOT, MAX_STOPS, POSITION_SLOT};
    format!(
        "// Gradient `{name}` at t: slot 0 (count, constant), colours from slot {COLOUR_SLOT}, positions from
// slot {POSITION_SLOT} four to a slot. r = c0, then per next stop r = mix(r, c_i, f), as the folded ramp.
fn npr_ramp_{name}(t: f32) -> vec4<f32> {{
    let n = i32(params.p_{name}[0].x);
    let constant = params.p_{name}[0].y > 0.5;
    var r = params.p_{name}[{COLOUR_SLOT}];
    for (var i = 1; i < {MAX_STOPS}; i = i + 1) {{
        if (i >= n) {{
            break;
        }}
        let p0 = params.p_{name}[{POSITION_SLOT} + (i - 1) / 4][(i - 1) % 4];
        let p1 = params.p_{name}[{POSITION_SLOT} + i / 4][i % 4];
        var f: f32;
        if (constant || p1 == p0) {{
            f = step(p1, t);
        }} else {{
            f = saturate((t - p0) / (p1 - p0));
        }}
        r = mix(r, params.p_{name}[{COLOUR_SLOT} + i], f);
    }}
    return r;
}}
"
    )
}

/// Normalisation that never makes NaN: render passes' builtins use it.
pub(super) const UNIT_HELPER: &str = "// Unit vector, or zero for a zero input (never NaN).
fn npr_unit(v: vec3<f32>) -> vec3<f32> {
    return v * inverseSqrt(max(dot(v, v), 1e-30));
}

";

/// `npr_round_f16(x)`: `x` rounded to binary16 as this device rounds a store
/// into a 16-bit float target, as an f32 (`npr_abi::formats::HalfRounding::round`
/// is the same definition in Rust). Vulkan lets a device round to nearest
/// even or toward zero, so the mode is the pipeline-overridable constant
/// `npr_abi::formats::HALF_ROUNDING_OVERRIDE`, measured and set by the runner;
/// it has no default, so a pipeline without it fails to build.
/// Bit arithmetic, because `pack2x16float` needs a capability naga does not
/// grant every adapter (and rounds as it likes).
pub(super) fn round_f16_helper() -> String {
    format!(
        "// x rounded to binary16 as this device's 16-bit float stores round, kept as f32: what such a target holds.
override {flag}: bool;
fn npr_round_f16(x: f32) -> f32 {{
    let a = abs(x);
    if (a != a) {{
        return x;
    }}
    if (a < 6.1035156e-5) {{
        // Below 2^-14 binary16 is subnormal: a multiple of 2^-24 (exact scalings; round() ties to even).
        let steps = select(round(a * 16777216.0), trunc(a * 16777216.0), {flag});
        return sign(x) * steps / 16777216.0;
    }}
    let bits = bitcast<u32>(x);
    // Drop 13 of f32's 23 mantissa bits: cut off, or ties to even with a carry into the exponent.
    let carry = select(0xfffu + ((bits >> 13u) & 1u), 0u, {flag});
    let rounded = bitcast<f32>((bits + carry) & 0xffffe000u);
    // Past binary16's largest finite value (65504): infinity with x's sign, or ±65504 when truncating.
    // The infinity is made from x's bits, not from constants: WGSL refuses a constant
    // expression whose value is infinite (Tint does; naga lets it through).
    let infinity = bitcast<f32>((bits & 0x80000000u) | 0x7f800000u);
    let past = select(infinity, sign(x) * 65504.0, {flag});
    return select(rounded, past, abs(rounded) > 65504.0);
}}
",
        flag = npr_abi::formats::HALF_ROUNDING_OVERRIDE
    )
}

/// `npr_stored_<format>(v)`: `v` as a target of `format` would give it back
/// (npr_abi::formats::Storage), so that a pass fused into its reader reads what
/// the target would have held: 16-bit floats by `npr_round_f16` per channel,
/// 8-bit unorm by WGSL's `pack4x8unorm` / `unpack4x8unorm`
/// (⌊255·saturate(x) + 0.5⌋ / 255).
pub(super) fn stored_helper(format: npr_abi::Format) -> String {
    use npr_abi::formats::Storage;
    let n = format.channels();
    let ty = crate::ir::Ty::float_vec(n).wgsl();
    let body = match (format.storage(), n) {
        (Storage::Half, 1) => "npr_round_f16(v)".to_string(),
        (Storage::Half, 2) => "vec2<f32>(npr_round_f16(v.x), npr_round_f16(v.y))".to_string(),
        (Storage::Half, _) => {
            "vec4<f32>(npr_round_f16(v.x), npr_round_f16(v.y), npr_round_f16(v.z), npr_round_f16(v.w))".to_string()
        }
        (Storage::Unorm8, 1) => "unpack4x8unorm(pack4x8unorm(vec4<f32>(v, 0.0, 0.0, 0.0))).x".to_string(),
        (Storage::Unorm8, 2) => "unpack4x8unorm(pack4x8unorm(vec4<f32>(v, 0.0, 0.0))).xy".to_string(),
        (Storage::Unorm8, _) => "unpack4x8unorm(pack4x8unorm(v))".to_string(),
        // Never inserted for these (schedule::fuse refuses sRGB and needs
        // nothing for 32-bit floats); the name stays undeclared, so naga's
        // validation reports it as an internal error if it ever is.
        (Storage::Exact | Storage::Srgb8, _) => return String::new(),
    };
    format!(
        "// A {name} target's stored value (a pass fused into its reader repeats the rounding).\nfn npr_stored_{name}(v: {ty}) -> {ty} {{\n    return {body};\n}}\n",
        name = format.name()
    )
}

/// Every helper text a module may include (each format's `npr_stored_*`):
/// the tests split them all (`tiled/library.rs`).
#[cfg(test)]
pub(super) fn library_texts() -> Vec<String> {
    let mut texts: Vec<String> = [
        PROJECT_HELPER,
        RUNTIME_BOOL_HELPER,
        LOAD_HELPER,
        PROJECT_DIR_HELPER,
        UNIT_HELPER,
    ]
    .map(String::from)
    .to_vec();
    texts.push(round_f16_helper());
    texts.push(ramp_helper("g"));
    texts.extend(npr_abi::Format::ALL.iter().map(|(_, f)| stored_helper(*f)));
    texts
}
