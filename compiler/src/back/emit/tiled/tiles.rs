//! The tiles of a tiled pass: each target's workgroup array and its load
//! function (the tile's texel, or a miss), how a tile reaches its target
//! (`TileAccess`: the loaded target's texture, or the computed one's
//! producer), and `cs_main`, which fills the tiles, runs the pixel and
//! stores the outputs after the format's rounding.

use super::TILED_ENTRY;
use crate::ir::*;
use npr_abi::formats::Storage;
use npr_abi::manifest::TILE_SIZE;
use std::fmt::Write;

/// `cs_main`: the workgroup fills its tiles (`tiled`: each target's
/// binding name and tile; the loaded ones first, as a computed tile may
/// read them), runs `npr_pixel` for the pixel each invocation owns, again
/// with the tiles bypassed when any read of the workgroup missed, and
/// stores `outputs`.
pub(super) fn entry(out: &mut String, tiled: &[(String, &TileRead)], outputs: &[&PassOutput]) {
    let threads = TILE_SIZE * TILE_SIZE;
    let _ = writeln!(
        out,
        "@compute @workgroup_size({TILE_SIZE}, {TILE_SIZE}, 1)
fn {TILED_ENTRY}(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) li: u32) {{
    npr_tile_origin = vec2<i32>(wg.xy) * {TILE_SIZE};"
    );
    let first = outputs[0];
    let computed: Vec<&(String, &TileRead)> = tiled
        .iter()
        .filter(|(_, r)| r.source == TileSource::Recompute)
        .collect();
    let mut filled_barrier = false;
    if !computed.is_empty() {
        let _ = writeln!(
            out,
            "    npr_pass_dims = vec2<i32>(textureDimensions(npr_out_{}));",
            first.name
        );
    }
    // The loaded tiles first: a computed tile may read them.
    let loaded_first = tiled
        .iter()
        .filter(|(_, r)| r.source == TileSource::Load)
        .chain(computed.iter().copied());
    for (name, r) in loaded_first {
        if r.source == TileSource::Recompute && !filled_barrier {
            filled_barrier = true;
            if tiled.iter().any(|(_, r)| r.source == TileSource::Load) {
                out.push_str("    workgroupBarrier();\n");
            }
        }
        let side = r.side();
        let a = TileAccess::of(name, r);
        let _ = writeln!(
            out,
            "    // `{name}`{what} the tile and its {radius}-texel apron, {threads} texels per round.
{setup}    for (var k = i32(li); k < {count}; k += {threads}) {{
        let q = npr_tile_origin - vec2<i32>({radius}) + vec2<i32>(k % {side}, k / {side});
        if (all(q >= vec2<i32>(0)) && all(q < {dims})) {{
            npr_tile_{name}[k] = {fetch}{keep};
        }}
    }}",
            what = a.what,
            setup = a.setup,
            dims = a.dims,
            fetch = a.fetch,
            radius = r.radius,
            count = side * side,
            keep = kept_channels(r),
        );
    }
    let _ = writeln!(
        out,
        "    workgroupBarrier();
    let px = npr_tile_origin + vec2<i32>(i32(li % {TILE_SIZE}u), i32(li / {TILE_SIZE}u));
    // Every invocation takes part in the barriers below; one outside the
    // image stores nothing.
    let inside = all(px < vec2<i32>(textureDimensions(npr_out_{})));
    var v: Varyings;
    // The pixel centre, as a fragment's position.
    v.clip = vec4<f32>(vec2<f32>(px) + vec2<f32>(0.5), 0.0, 1.0);
    v.screen_uv = vec2<f32>(0.0); // npr_pixel's prologue sets it from clip
    var o = npr_pixel(v);
    // A read outside the tiles (a footprint too small, a read outside the
    // image): the whole workgroup runs again, reading the targets
    // themselves. The flag is workgroup-uniform, so no device runs that
    // path unless a read missed (a per-read fallback branch costs every
    // read on a device that executes both sides, as llvmpipe does).
    if (inside && npr_tile_missed) {{
        atomicOr(&npr_tile_misses, 1u);
    }}
    workgroupBarrier();
    if (li == 0u) {{
        npr_tile_any_missed = atomicLoad(&npr_tile_misses);
    }}
    if (workgroupUniformLoad(&npr_tile_any_missed) != 0u) {{
        npr_tile_direct = true;
        o = npr_pixel(v);
    }}
    if (!inside) {{
        return;
    }}",
        first.name
    );
    for o in outputs {
        let value = stored_texel(o.format, &format!("o.o_{}", o.name));
        let _ = writeln!(out, "    textureStore(npr_out_{}, px, {value});", o.name);
    }
    out.push_str("}\n");
}

/// What a `format` texel holds after `value` (of the format's channel
/// count) is stored in it, as a `vec4<f32>` as `textureLoad` returns it:
/// rounded where the format rounds (`npr_stored_<format>`), the missing
/// channels (0, 0, 1).
pub(super) fn stored_texel(format: npr_abi::Format, value: &str) -> String {
    let rounded = match format.storage() {
        Storage::Half | Storage::Unorm8 => format!("npr_stored_{}({value})", format.name()),
        Storage::Exact | Storage::Srgb8 => value.to_string(),
    };
    match format.channels() {
        1 => format!("vec4<f32>({rounded}, 0.0, 0.0, 1.0)"),
        2 => format!("vec4<f32>({rounded}, 0.0, 1.0)"),
        _ => rounded,
    }
}

/// The formats among `outputs` that round (their `npr_stored_*` helper).
pub(super) fn stored_formats(outputs: &[&PassOutput]) -> Vec<npr_abi::Format> {
    let mut formats = Vec::new();
    for o in outputs {
        if matches!(o.format.storage(), Storage::Half | Storage::Unorm8) && !formats.contains(&o.format) {
            formats.push(o.format);
        }
    }
    formats
}

/// The type of one tile texel: the target's channels.
fn tile_element(r: &TileRead) -> &'static str {
    match r.channels {
        1 => "f32",
        2 => "vec2<f32>",
        _ => "vec4<f32>",
    }
}

/// The swizzle that keeps a texel's channels in its tile.
fn kept_channels(r: &TileRead) -> &'static str {
    match r.channels {
        1 => ".x",
        2 => ".xy",
        _ => "",
    }
}

/// A tile texel as `textureLoad` returns it: the missing channels (0, 0, 1).
fn padded_texel(r: &TileRead, texel: &str) -> String {
    match r.channels {
        1 => format!("vec4<f32>({texel}, 0.0, 0.0, 1.0)"),
        2 => format!("vec4<f32>({texel}, 0.0, 1.0)"),
        _ => texel.to_string(),
    }
}

/// How a tile reaches its target: the loaded one's texture, or the
/// computed one's producer (`npr_compute_<t>`).
struct TileAccess {
    /// Its fill loop's note after the name.
    what: &'static str,
    /// The fill loop's first statement (the loaded target's size).
    setup: String,
    /// The image's size, `vec2<i32>`.
    dims: String,
    /// The texel at an in-image `q`, for the fill.
    fetch: String,
    /// The read in the workgroup's second run, tiles bypassed.
    direct: String,
    /// The part of the hit test about `level`.
    level_hit: &'static str,
    /// The load function's doc.
    doc: String,
    /// Declarations after the load function.
    extra: String,
}

impl TileAccess {
    fn of(name: &str, r: &TileRead) -> TileAccess {
        match r.source {
            TileSource::Load => TileAccess {
                what: ":",
                setup: format!("    npr_tile_dims_{name} = vec2<i32>(textureDimensions({name}));\n"),
                dims: format!("npr_tile_dims_{name}"),
                fetch: format!("textureLoad({name}, q, 0)"),
                direct: format!("textureLoad({name}, q, level)"),
                level_hit: "level == 0 && ",
                doc: format!(
                    "// `textureLoad({name}, q, level)`: the tile's texel, a miss when q is outside the tile or
// the image (or level is not 0); in the workgroup's second run, `textureLoad` itself."
                ),
                extra: String::new(),
            },
            TileSource::Recompute => TileAccess {
                what: ", not stored: computed on",
                setup: String::new(),
                dims: "npr_pass_dims".into(),
                fetch: format!("npr_compute_{name}(q)"),
                direct: format!("npr_compute_{name}(clamp(q, vec2<i32>(0), npr_pass_dims - vec2<i32>(1)))"),
                level_hit: "",
                doc: format!(
                    "// `textureLoad({name}, q, level)` of the target this pass computes: the tile's texel, a miss
// when q is outside the tile or the image; in the workgroup's second run, computed at q. A load
// outside the image is the device's choice in WebGPU (a texel of the texture, or zero) and the
// stdlib makes none; the nearest edge texel is one. The target has one level, so `level`
// chooses nothing."
                ),
                extra: format!(
                    "// `textureDimensions({name})`: the pass's size, which is the target's.
fn npr_computed_dims_{name}() -> vec2<u32> {{
    return vec2<u32>(npr_pass_dims);
}}
"
                ),
            },
        }
    }
}

/// The workgroup array of one tiled target, its load function and what
/// else its source needs (`TileAccess`).
pub(super) fn tile_declarations(out: &mut String, name: &str, r: &TileRead) {
    let side = r.side();
    let a = TileAccess::of(name, r);
    let dims_var = match r.source {
        TileSource::Load => format!("var<private> npr_tile_dims_{name}: vec2<i32>;\n"),
        TileSource::Recompute => String::new(),
    };
    let _ = writeln!(
        out,
        "var<workgroup> npr_tile_{name}: array<{element}, {count}>;
{dims_var}{doc}
fn npr_tile_load_{name}(q: vec2<i32>, level: i32) -> vec4<f32> {{
    if (npr_tile_direct) {{
        return {direct};
    }}
    let local = q - npr_tile_origin + vec2<i32>({radius});
    let in_tile = all(local >= vec2<i32>(0)) && all(local < vec2<i32>({side}));
    let in_image = all(q >= vec2<i32>(0)) && all(q < {dims});
    npr_tile_missed = npr_tile_missed || !({level_hit}in_tile && in_image);
    let k = clamp(local, vec2<i32>(0), vec2<i32>({last}));
    return {texel};
}}
{extra}",
        doc = a.doc,
        direct = a.direct,
        dims = a.dims,
        level_hit = a.level_hit,
        extra = a.extra,
        count = side * side,
        radius = r.radius,
        last = side - 1,
        element = tile_element(r),
        texel = padded_texel(r, &format!("npr_tile_{name}[k.y * {side} + k.x]")),
    );
}
