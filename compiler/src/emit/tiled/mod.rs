//! A tiled image pass (`schedule/tile.rs`): the fragment body becomes
//! `npr_pixel`, called by `cs_main` for the pixel each invocation owns,
//! after the workgroup has loaded its tiles into workgroup memory.
//!
//! - Every function taking a texture is copied per binding ([`mono`]), and
//!   in the copies `textureLoad(t, q, level)` of a tiled target `t` becomes
//!   `npr_tile_load_t(q, level)`: the tile's texel when `q` lies in the
//!   tile with its apron and in the image, else `textureLoad` itself, so a
//!   footprint that is too small costs speed, never a different image.
//! - The outputs are written with `textureStore` (group 1, binding i =
//!   output i) after the target format's own rounding
//!   (`npr_stored_<format>`, the same helpers fusion uses), so a storage
//!   write holds what a colour attachment of the naive schedule would: a
//!   16-bit float is rounded as this device rounds attachment stores.

mod mono;

use super::uses::Uses;
use super::{helpers, Emitter, PassCtx};
use crate::ir::*;
use crate::schedule::tile::{TileRead, Tiling};
use abi::formats::Storage;
use abi::manifest::{TargetCopy, TILE_SIZE};
use std::fmt::Write;

/// The entry point of a tiled pass.
pub(crate) const TILED_ENTRY: &str = "cs_main";

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
        let rename = |g: &str| {
            tiled
                .iter()
                .find(|(name, _)| name == g)
                .map(|(name, _)| format!("npr_tile_load_{name}"))
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
            "\n// The first pixel of this invocation's workgroup.\nvar<private> npr_tile_origin: vec2<i32>;\n"
        );
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
        for (name, r) in tiled {
            let side = r.side();
            let _ = writeln!(
                out,
                "    // `{name}`: the tile and its {radius}-texel apron, {threads} texels per round.
    npr_tile_dims_{name} = vec2<i32>(textureDimensions({name}));
    for (var k = i32(li); k < {count}; k += {threads}) {{
        let q = npr_tile_origin - vec2<i32>({radius}) + vec2<i32>(k % {side}, k / {side});
        if (all(q >= vec2<i32>(0)) && all(q < npr_tile_dims_{name})) {{
            npr_tile_{name}[k] = textureLoad({name}, q, 0);
        }}
    }}",
                radius = r.radius,
                count = side * side,
            );
        }
        let first = outputs[0];
        let _ = writeln!(
            out,
            "    workgroupBarrier();
    let px = npr_tile_origin + vec2<i32>(i32(li % {TILE_SIZE}u), i32(li / {TILE_SIZE}u));
    if (any(px >= vec2<i32>(textureDimensions(npr_out_{})))) {{
        return;
    }}
    var v: Varyings;
    // The pixel centre, as a fragment's position.
    v.clip = vec4<f32>(vec2<f32>(px) + vec2<f32>(0.5), 0.0, 1.0);
    v.screen_uv = vec2<f32>(0.0); // npr_pixel's prologue sets it from clip
    let o = npr_pixel(v);",
            first.name
        );
        for o in outputs {
            let rounded = match o.format.storage() {
                Storage::Half | Storage::Unorm8 => format!("npr_stored_{}(o.o_{})", o.format.name(), o.name),
                Storage::Exact | Storage::Srgb8 => format!("o.o_{}", o.name),
            };
            let value = match o.format.channels() {
                1 => format!("vec4<f32>({rounded}, 0.0, 0.0, 1.0)"),
                2 => format!("vec4<f32>({rounded}, 0.0, 1.0)"),
                _ => rounded,
            };
            let _ = writeln!(out, "    textureStore(npr_out_{}, px, {value});", o.name);
        }
        out.push_str("}\n");
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

/// The workgroup array of one tiled target and its load function.
fn tile_declarations(out: &mut String, name: &str, r: &TileRead) {
    let side = r.side();
    let _ = writeln!(
        out,
        "var<workgroup> npr_tile_{name}: array<vec4<f32>, {count}>;
var<private> npr_tile_dims_{name}: vec2<i32>;
// `textureLoad({name}, q, level)` from the tile when q is in it and in the image.
fn npr_tile_load_{name}(q: vec2<i32>, level: i32) -> vec4<f32> {{
    let local = q - npr_tile_origin + vec2<i32>({radius});
    let in_tile = all(local >= vec2<i32>(0)) && all(local < vec2<i32>({side}));
    let in_image = all(q >= vec2<i32>(0)) && all(q < npr_tile_dims_{name});
    if (level == 0 && in_tile && in_image) {{
        return npr_tile_{name}[local.y * {side} + local.x];
    }}
    return textureLoad({name}, q, level);
}}
",
        count = side * side,
        radius = r.radius,
    );
}
