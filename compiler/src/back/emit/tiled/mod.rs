//! A tiled image pass (`schedule/tile.rs`): the fragment body becomes
//! `npr_pixel`, called by `cs_main` for the pixel each invocation owns,
//! after the workgroup has loaded its tiles into workgroup memory.
//!
//! - Every function taking a texture is copied per binding ([`mono`]), and
//!   in the copies `textureLoad(t, q, level)` of a tiled target `t` becomes
//!   `npr_tile_load_t(q, level)`: the tile's texel. A read outside the
//!   tile with its apron or outside the image is a miss: after its pixel,
//!   a workgroup where any invocation missed runs `npr_pixel` again with
//!   the tiles bypassed (`npr_tile_direct`: `textureLoad` itself), so a
//!   footprint that is too small costs speed, never a different image. The
//!   second run's condition is workgroup-uniform (`workgroupUniformLoad`),
//!   so a device that branches on uniform conditions skips it; a per-read
//!   fallback branch instead cost every read on llvmpipe, which executes
//!   both sides (docs/PERFORMANCE.md, "Recomputed tiles"). Every
//!   invocation, inside the image or not, reaches the barriers; one outside
//!   stores nothing.
//! - The outputs are written with `textureStore` (group 1, binding i =
//!   output i) after the target format's own rounding
//!   (`npr_stored_<format>`, the same helpers fusion uses), so a storage
//!   write holds what a colour attachment of the naive schedule would: a
//!   16-bit float is rounded as this device rounds attachment stores.
//! - A target computed in the tiles (`schedule/recompute.rs`) has no
//!   binding: its producer's expression becomes `npr_compute_<t>(q)`, the
//!   texel a store would have left at q (the same arithmetic as the
//!   producer's fragment at q's centre, then the format's rounding). The
//!   workgroup fills the tile with it after the loaded tiles (which it may
//!   read); the second run evaluates it where it is read.

mod mono;

use super::expr::KindCtx;
use super::uses::Uses;
use super::{helpers, Emitter, PassCtx};
use crate::ir::*;
use abi::formats::Storage;
use abi::manifest::{TargetCopy, TILE_SIZE};
use std::collections::BTreeMap;
use std::fmt::Write;

/// The entry point of a tiled pass.
pub(crate) const TILED_ENTRY: &str = "cs_main";

/// A target computed in a tiled pass's tiles: what its function evaluates.
pub(in crate::back::emit) struct Producer {
    pub target: TargetRef,
    /// The producer's expressions for the target, operands first.
    nodes: Vec<ExprId>,
    /// How often each is read as a value there (names its `let`s).
    value_uses: BTreeMap<ExprId, usize>,
}

impl Emitter<'_> {
    /// The tiled module, from the fragment-style module `w` whose pixel
    /// function is `npr_pixel`, and whether its stores round to binary16
    /// (so it declares `abi::formats::HALF_ROUNDING_OVERRIDE`).
    pub(super) fn finish_tiled(
        &self,
        w: String,
        tiling: &Tiling,
        outputs: &[&PassOutput],
        uses: &Uses,
        ctx: &PassCtx,
    ) -> (String, bool) {
        let global = |r: &TileRead| ctx.target_names[&(TargetCopy::This, r.target)].clone();
        let tiled: Vec<(String, &TileRead)> = tiling.reads.iter().map(|r| (global(r), r)).collect();
        let rename = |builtin: &str, g: &str| {
            let (name, r) = tiled.iter().find(|(name, _)| name == g)?;
            match (builtin, r.source) {
                ("textureLoad", _) => Some(format!("npr_tile_load_{name}")),
                // A computed target has no texture to ask.
                ("textureDimensions", TileSource::Recompute) => Some(format!("npr_computed_dims_{name}")),
                _ => None,
            }
        };
        let mut out = match mono::monomorphize(&w, &rename) {
            Ok(m) => m,
            // naga's validation of the module reports it as E9001.
            Err(why) => format!("{w}\n// npr internal error: the tiled rewrite failed: {why}\n"),
        };
        out.push_str("// ---- tiled schedule (issue 14): workgroup tiles and the storage outputs\n");
        let half = outputs.iter().any(|o| o.format.storage() == Storage::Half);
        if half && !uses.repeats_half_stores() {
            out.push_str(&helpers::round_f16_helper());
            out.push('\n');
        }
        for f in stored_formats(outputs) {
            if !uses.stored.contains(&f) {
                out.push_str(&helpers::stored_helper(f));
                out.push('\n');
            }
        }
        for (k, o) in outputs.iter().enumerate() {
            let _ = writeln!(
                out,
                "@group(1) @binding({k}) var npr_out_{}: texture_storage_2d<{}, write>;",
                o.name,
                o.format.name()
            );
        }
        let _ = writeln!(
            out,
            "\n// The first pixel of this invocation's workgroup.\nvar<private> npr_tile_origin: vec2<i32>;
// Whether a read of this invocation fell outside the tiles.
var<private> npr_tile_missed: bool;
// Whether the tiles are bypassed: the workgroup's second run, after a miss.
var<private> npr_tile_direct: bool;
// Whether any invocation of the workgroup missed, and that, for a uniform load.
var<workgroup> npr_tile_misses: atomic<u32>;
var<workgroup> npr_tile_any_missed: u32;\n"
        );
        if tiled.iter().any(|(_, r)| r.source == TileSource::Recompute) {
            let _ = writeln!(
                out,
                "// The pass's size in pixels: that of the targets computed in its tiles.\nvar<private> npr_pass_dims: vec2<i32>;\n"
            );
        }
        for (name, r) in &tiled {
            tile_declarations(&mut out, name, r);
        }
        self.entry(&mut out, &tiled, outputs);
        (out, half)
    }

    fn entry(&self, out: &mut String, tiled: &[(String, &TileRead)], outputs: &[&PassOutput]) {
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

    /// The producers of the targets computed in `tiling`'s tiles, with what
    /// they read added to `uses` (the module declares it) and their formats'
    /// rounding helpers.
    pub(in crate::back::emit) fn recomputed_uses(&self, tiling: &Tiling, uses: &mut Uses) -> Vec<Producer> {
        let mut producers = Vec::new();
        for r in tiling.reads.iter().filter(|r| r.source == TileSource::Recompute) {
            let o = &self.ir.pass(r.target.pass).outputs[r.target.output as usize];
            let nodes = self.ir.reachable(&[o.value]);
            let mut own = self.uses(&nodes, &[o.value], &[]);
            let value_uses = std::mem::take(&mut own.value_uses);
            uses.absorb(own);
            uses.store(o.format);
            producers.push(Producer {
                target: r.target,
                nodes,
                value_uses,
            });
        }
        producers
    }

    /// `npr_compute_<t>(q)`: the texel producer `p`'s target would hold at
    /// q, as `textureLoad` would return it. Its pixel is set up as the tiled
    /// entry sets up the pass's own (`in.clip` at the texel centre, the
    /// prologue's `screen_uv`), which is how the producer's fragment saw it.
    pub(in crate::back::emit) fn recompute_function(&self, w: &mut String, p: &Producer, ctx: &PassCtx) {
        let pass = self.ir.pass(p.target.pass);
        let o = &pass.outputs[p.target.output as usize];
        let name = &ctx.target_names[&(TargetCopy::This, p.target)];
        let _ = writeln!(
            w,
            "\n// `{}` of pass `{}` ({}), computed at texel q instead of stored.
fn npr_compute_{name}(q: vec2<i32>) -> vec4<f32> {{
    var in: Varyings;
    in.clip = vec4<f32>(vec2<f32>(q) + vec2<f32>(0.5), 0.0, 1.0);
    in.screen_uv = in.clip.xy / {};",
            self.ir.target_name(p.target),
            pass.name,
            self.line_of(pass.name_span),
            super::render::pass_size_wgsl(pass.scale)
        );
        let mut own = PassCtx {
            kind: KindCtx::of(&pass.kind),
            named: BTreeMap::new(),
            target_names: ctx.target_names.clone(),
            uses_linear_sampler: ctx.uses_linear_sampler,
            runtime_conditions: ctx.runtime_conditions.clone(),
        };
        self.emit_lets(w, pass, &p.nodes, &p.value_uses, &mut own);
        self.output_comment(w, o);
        let v = self.expr(o.value, &own);
        let _ = writeln!(w, "    return {};\n}}", stored_texel(o.format, &v));
    }
}

/// What a `format` texel holds after `value` (of the format's channel
/// count) is stored in it, as a `vec4<f32>` as `textureLoad` returns it:
/// rounded where the format rounds (`npr_stored_<format>`), the missing
/// channels (0, 0, 1).
fn stored_texel(format: abi::Format, value: &str) -> String {
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
fn stored_formats(outputs: &[&PassOutput]) -> Vec<abi::Format> {
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
fn tile_declarations(out: &mut String, name: &str, r: &TileRead) {
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
