//! A tiled image pass (`schedule/tile.rs`): a compute module whose pixel
//! function, `npr_pixel`, is the fragment body, called by `cs_main` for the
//! pixel each invocation owns, after the workgroup has loaded its tiles
//! into workgroup memory.
//!
//! - Every call the emitter writes of a function that takes a texture or
//!   sampler (an operator, `npr_load`) calls that function's copy for the
//!   call's bindings ([`library`]), and in the copies `textureLoad(t, q,
//!   level)` of a tiled target `t` becomes `npr_tile_load_t(q, level)`: the
//!   tile's texel. A read outside the tile with its apron or outside the
//!   image is a miss: after its pixel, a workgroup where any invocation
//!   missed runs `npr_pixel` again with the tiles bypassed
//!   (`npr_tile_direct`: `textureLoad` itself), so a footprint that is too
//!   small costs speed, never a different image. The second run's
//!   condition is workgroup-uniform (`workgroupUniformLoad`), so a device
//!   that branches on uniform conditions skips it; a per-read fallback
//!   branch instead cost every read on llvmpipe, which executes both sides
//!   (docs/PERFORMANCE.md, "Recomputed tiles"). Every invocation, inside
//!   the image or not, reaches the barriers; one outside stores nothing.
//! - The outputs are written with `textureStore` (group 1, binding i =
//!   output i) after the target format's own rounding
//!   (`npr_stored_<format>`, the same helpers fusion uses), so a storage
//!   write holds what a colour attachment of the naive schedule would: a
//!   16-bit float is rounded as this device rounds attachment stores.
//! - A target computed in the tiles (`schedule/recompute.rs`) has no
//!   binding: its producer's expression becomes `npr_compute_<t>(q)`
//!   ([`recomputed`]), the texel a store would have left at q (the same
//!   arithmetic as the producer's fragment at q's centre, then the format's
//!   rounding). The workgroup fills the tile with it after the loaded tiles
//!   (which it may read); the second run evaluates it where it is read.
//!
//! The module's layout: the declarations, the functions that take no
//! handle (the library's, then `npr_pixel` and the producers'), the copies
//! by name, then the tiles, the storage outputs and `cs_main` ([`tiles`]).

mod library;
mod recomputed;
mod tiles;

use super::uses::Uses;
use super::{helpers, image, EmittedPass, Emitter, PassCtx};
use crate::ir::*;
use library::{Copies, Function, Piece};
use npr_abi::formats::Storage;
use npr_abi::manifest::TargetCopy;
use recomputed::Producer;
use std::collections::BTreeSet;
use std::fmt::Write;
use tiles::{entry, stored_formats, tile_declarations};

/// The copies of handle-taking functions that a tiled module's calls name:
/// (function, the bindings of its handle parameters, in order).
pub(super) type CopyCalls = BTreeSet<(String, Vec<String>)>;

/// The entry point of a tiled pass.
pub(crate) const TILED_ENTRY: &str = "cs_main";

impl Emitter<'_> {
    /// The module of image pass `pid`, which the schedule tiled as
    /// `tiling`, with `live_outputs` (index, output) its stored targets.
    pub(super) fn emit_tiled(
        &self,
        pid: PassId,
        tiling: &Tiling,
        live_outputs: &[(usize, &PassOutput)],
    ) -> EmittedPass {
        let pass = self.ir.pass(pid);
        let frag_roots: Vec<ExprId> = live_outputs.iter().map(|(_, o)| o.value).collect();
        let frag_nodes = self.ir.reachable(&frag_roots);
        let mut uses = self.uses(&frag_nodes, &frag_roots, &[]);
        // Targets computed in this pass's tiles: their producers' reads are
        // this module's too.
        let producers = self.recomputed_uses(tiling, &mut uses);
        // The prologue's `screen_uv` divides by the pass size: the frame is bound.
        let declared = self.declare(&pass.kind, &uses, true);
        let mut ctx = PassCtx::new(&pass.kind, declared.target_names, &uses);
        ctx.per_binding = Some(Default::default());
        for p in &producers {
            let t = (TargetCopy::This, p.target);
            ctx.target_names.insert(t, self.target_binding_name(t.0, t.1));
        }
        let outputs: Vec<&PassOutput> = live_outputs.iter().map(|(_, o)| *o).collect();
        let mut helpers = String::new();
        self.emit_helpers(&mut helpers, &uses);
        let pieces = library::split(&helpers).map(|library| {
            let mut pieces = vec![Piece::Text(format!("{}{}\n", self.module_header(pass), declared.text))];
            pieces.extend(library);
            pieces.extend(self.pixel_functions(pass, &outputs, &frag_nodes, &uses, &producers, &mut ctx));
            pieces
        });
        let calls = ctx.per_binding.take().unwrap_or_default().into_inner();
        let mut w = pieces
            .and_then(|pieces| layout(&pieces, &calls, tiling, &ctx))
            .unwrap_or_else(|why| {
                // naga's validation of the module reports it as E9001, with this line.
                format!("// npr internal error: the tiled module could not be made: {why}\nnpr_internal_error\n")
            });
        // Its 16-bit stores are rounded in the shader, as the device would.
        let stores_half = storage_outputs(&mut w, tiling, &outputs, &uses, &ctx);
        EmittedPass {
            wgsl: w,
            bindings: declared.bindings,
            object_bindings: declared.object_bindings,
            attributes: Vec::new(),
            device_half_rounding: uses.repeats_half_stores() || stores_half,
        }
    }

    /// What the module has after the library: the varyings and `FragOut`,
    /// then `npr_pixel` (the fragment body, which `cs_main` calls) and each
    /// producer's `npr_compute_<t>`, as the pieces of a module.
    fn pixel_functions(
        &self,
        pass: &Pass,
        outputs: &[&PassOutput],
        frag_nodes: &[ExprId],
        uses: &Uses,
        producers: &[Producer],
        ctx: &mut PassCtx,
    ) -> Vec<Piece> {
        let declarations = format!("{}{}", image::IMAGE_VARYINGS, super::fragment_outputs(outputs));
        let body = self.pixel_body(pass, frag_nodes, uses, outputs, ctx);
        let pixel = Function {
            doc: "// One pixel of the pass, for the invocation that owns it (`cs_main`).\n".into(),
            name: "npr_pixel".into(),
            params: vec![("in_raw".into(), "Varyings".into())],
            rest: format!(" -> FragOut {{\n{}{body}}}", image::pixel_prologue(pass.scale)),
        };
        let mut pieces = vec![
            Piece::Text(declarations),
            Piece::Function(pixel),
            Piece::Text("\n".into()),
        ];
        for p in producers {
            pieces.push(Piece::Text("\n".into()));
            pieces.push(Piece::Function(self.recompute_function(p, ctx)));
            pieces.push(Piece::Text("\n".into()));
        }
        pieces
    }
}

/// The module's text up to its tiles: the declarations of `pieces`
/// (everything between functions, in order), its functions that take no
/// handle, in order, and the copies `calls` name ((function, bindings)),
/// by name; never two blank lines in a row.
fn layout(pieces: &[Piece], calls: &CopyCalls, tiling: &Tiling, ctx: &PassCtx) -> Result<String, String> {
    let tiled = tiled_names(tiling, ctx);
    let redirect = |builtin: &str, binding: &str| {
        let (name, r) = tiled.iter().find(|(name, _)| name == binding)?;
        match (builtin, r.source) {
            ("textureLoad", _) => Some(format!("npr_tile_load_{name}")),
            // A computed target has no texture to ask.
            ("textureDimensions", TileSource::Recompute) => Some(format!("npr_computed_dims_{name}")),
            _ => None,
        }
    };
    let mut copies = Copies::new(pieces, &redirect);
    for (function, bindings) in calls {
        copies.make(function, bindings)?;
    }
    let mut declarations = String::new();
    let mut functions = String::new();
    for p in pieces {
        match p {
            Piece::Text(t) => declarations.push_str(t),
            Piece::Function(f) if !f.takes_handles() => {
                functions.push_str(&f.text());
                functions.push_str("\n\n");
            }
            // Called through its copies only.
            Piece::Function(_) => {}
        }
    }
    for c in copies.texts() {
        functions.push_str(c);
        functions.push_str("\n\n");
    }
    declarations.push_str(&functions);
    Ok(at_most_one_blank_line(&declarations))
}

/// Appends the tiles, the storage outputs and `cs_main` to `w`; whether
/// its stores round to binary16 (so it declares
/// `npr_abi::formats::HALF_ROUNDING_OVERRIDE`).
fn storage_outputs(w: &mut String, tiling: &Tiling, outputs: &[&PassOutput], uses: &Uses, ctx: &PassCtx) -> bool {
    let tiled = tiled_names(tiling, ctx);
    w.push_str("// ---- tiled schedule (issue 14): workgroup tiles and the storage outputs\n");
    let half = outputs.iter().any(|o| o.format.storage() == Storage::Half);
    if half && !uses.repeats_half_stores() {
        w.push_str(&helpers::round_f16_helper());
        w.push('\n');
    }
    for f in stored_formats(outputs) {
        if !uses.stored.contains(&f) {
            w.push_str(&helpers::stored_helper(f));
            w.push('\n');
        }
    }
    for (k, o) in outputs.iter().enumerate() {
        let _ = writeln!(
            w,
            "@group(1) @binding({k}) var npr_out_{}: texture_storage_2d<{}, write>;",
            o.name,
            o.format.name()
        );
    }
    let _ = writeln!(
        w,
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
            w,
            "// The pass's size in pixels: that of the targets computed in its tiles.\nvar<private> npr_pass_dims: vec2<i32>;\n"
        );
    }
    for (name, r) in &tiled {
        tile_declarations(w, name, r);
    }
    entry(w, &tiled, outputs);
    half
}

/// Each tile of `tiling` with its target's binding name (a computed
/// target's reads keep that name, `ctx.target_names`).
fn tiled_names<'t>(tiling: &'t Tiling, ctx: &PassCtx) -> Vec<(String, &'t TileRead)> {
    tiling
        .reads
        .iter()
        .map(|r| (ctx.target_names[&(TargetCopy::This, r.target)].clone(), r))
        .collect()
}

/// `text` with every run of blank lines shortened to one: the functions
/// gathered after the declarations leave their line breaks among them.
fn at_most_one_blank_line(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut blank_run = 0;
    for line in text.split_inclusive('\n') {
        blank_run = if line.trim().is_empty() { blank_run + 1 } else { 0 };
        if blank_run <= 1 {
            out.push_str(line);
        }
    }
    out
}
