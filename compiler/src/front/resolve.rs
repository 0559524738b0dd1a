//! Resolve: turn the AST into IR, binding every name to what it means.
//!
//! Names resolve, innermost first, to: block `let`s, pass `let`s, parameters,
//! textures, builtins, and enum variants. `pass.output` is a target;
//! `position.view` and `light.dir` are builtins; any other `.xyz` is a
//! swizzle. Calls bind to a WGSL intrinsic or a stdlib operator, and their
//! arguments are put in parameter order with defaults filled in. Types are
//! left for the typechecker, except for literals and leaves.

use crate::front::load::Loaded;
use crate::ir::*;
use crate::mid::consteval::const_eval;
use crate::InternalError;
use npr_abi::Format;
use npr_diag::diagnostic::did_you_mean;
use npr_diag::{codes, Diagnostic, Span};
use npr_dsl::ast::{self, ExprKind as AK, Item, UnitSuffix};
use npr_stdlib::Unit;
use std::collections::HashMap;
use std::path::Path;

mod calls;
mod compute;
mod expr;
pub mod gradient;
mod host_builtins;
mod input_source;
mod kind_args;
mod line_sets;
mod lines;
mod params;
mod passes;
mod settings;
mod swizzle;
mod texture_source;

pub use calls::signature;

/// Resolution limits, stated in the error messages (the table of every
/// limit is `npr_diag::limits`).
pub use npr_diag::limits::{MAX_PARAMS, MAX_PASSES, MAX_TARGETS_PER_PASS as MAX_OUTPUTS_PER_PASS};
pub const MAX_NOISE_SIZE: u32 = 4096;

pub fn resolve(
    loaded: &Loaded,
    scene: Option<&crate::SceneSummary>,
    paths: Option<&npr_diag::paths::PathPolicy>,
    diags: &mut Vec<Diagnostic>,
) -> Result<Ir, InternalError> {
    resolve_with_settings(loaded, scene, paths, &npr_diag::files::Disk, &[], false, diags).map(|(ir, _)| ir)
}

/// [`resolve`], with the settings of `gradient` params (`--set g="0:#000,
/// 1:#fff"`) applied to their stops here, since a gradient is a constant of
/// the resolver (`resolve/gradient.rs`); also the names of the settings it
/// took, which the typing of the others after typecheck leaves out. With
/// `keep_params` (`CompileOptions::keep_params`) a gradient is also a
/// parameter of the IR, a uniform its `ramp`s read (`ParamTy::Gradient`).
/// Each `image("…")` is probed in `files`.
pub fn resolve_with_settings(
    loaded: &Loaded,
    scene: Option<&crate::SceneSummary>,
    paths: Option<&npr_diag::paths::PathPolicy>,
    files: &dyn npr_diag::files::FileSource,
    settings: &[ParamSetting],
    keep_params: bool,
    diags: &mut Vec<Diagnostic>,
) -> Result<(Ir, Vec<String>), InternalError> {
    let mut r = Resolver {
        ir: Ir::default(),
        diags,
        scene,
        paths,
        files,
        names: HashMap::new(),
        pass_outputs: Vec::new(),
        pass_values: Vec::new(),
        compute_passes: Vec::new(),
        states: Vec::new(),
        has_object: false,
        scopes: Vec::new(),
        current_pass: None,
        line_set_colors: None,
        draws_objects: false,
        in_vertex: false,
        in_image_pass: false,
        internal: None,
        gradients: Vec::new(),
        gradient_params: Vec::new(),
        keep_params,
        gradient_settings: settings,
        gradients_set: Vec::new(),
    };
    r.ir.style_name = match &loaded.root.style {
        Some(h) => h.name.clone(),
        None => String::from("untitled"),
    };
    r.declare_all(&loaded.items);
    r.resolve_all(&loaded.items, loaded.root.style.as_ref().map(|h| h.span));
    match r.internal {
        Some(e) => Err(e),
        None => Ok((r.ir, r.gradients_set)),
    }
}

#[derive(Debug, Clone, Copy)]
enum Symbol {
    Param(ParamId),
    Texture(TextureId),
    Pass(PassId),
    /// A `gradient` param: an index into `Resolver::gradients`.
    Gradient(usize),
}

struct Resolver<'d> {
    ir: Ir,
    diags: &'d mut Vec<Diagnostic>,
    /// The scene, when the caller knows it (for `scene_has`).
    scene: Option<&'d crate::SceneSummary>,
    /// The paths policy every `image("…")` is checked against before it is probed.
    paths: Option<&'d npr_diag::paths::PathPolicy>,
    /// Where the files are: an `image("…")` must name one.
    files: &'d dyn npr_diag::files::FileSource,
    names: HashMap<String, (Symbol, Span)>,
    /// Output names of each pass, declared before bodies are resolved.
    pass_outputs: Vec<Vec<String>>,
    /// Per-object values of each pass (compute passes only), declared before bodies.
    pass_values: Vec<Vec<compute::DeclaredValue>>,
    /// The compute passes.
    compute_passes: Vec<PassId>,
    /// The states of the `compute(objects)` pass being resolved.
    states: Vec<compute::StateInScope>,
    /// Whether the pass being resolved runs per object (render, compute):
    /// only those may read per-object values of compute passes.
    has_object: bool,
    /// Let scopes: innermost last. Each maps a name to its value node.
    scopes: Vec<Vec<(String, ExprId)>>,
    current_pass: Option<PassId>,
    /// In a lines pass with line sets: each set's `color:` (highest priority
    /// first), what `line.color` chooses among; `None` in any other pass.
    line_set_colors: Option<Vec<Option<ExprId>>>,
    /// Whether the pass being resolved draws objects (`render(...)`): only
    /// those may read per-object textures.
    draws_objects: bool,
    /// Resolving a `vertex { ... }` modifier: no texture may be sampled
    /// there (`textureSample` is fragment-only in WGSL).
    in_vertex: bool,
    /// Whether the pass being resolved is an image pass: its geometry
    /// builtins are read from the host's inputs (`host_builtins.rs`).
    in_image_pass: bool,
    /// The first impossible state met (a bug in npr, not in the style).
    internal: Option<InternalError>,
    /// The declared gradients (`gradient.rs`): constants, read by `ramp`;
    /// `None` for one whose declaration was refused.
    gradients: Vec<Option<gradient::Gradient>>,
    /// Each gradient's IR param when it is kept live (`keep_params`).
    gradient_params: Vec<Option<ParamId>>,
    keep_params: bool,
    /// The caller's settings; those naming a gradient are applied here.
    gradient_settings: &'d [ParamSetting],
    /// The names of the gradients a setting set.
    gradients_set: Vec<String>,
}

impl Resolver<'_> {
    fn error(&mut self, d: Diagnostic) {
        self.diags.push(d);
    }

    fn declare(&mut self, name: &ast::Ident, sym: Symbol) {
        if let Some((_, prev)) = self.names.get(&name.name) {
            let prev = *prev;
            self.error(
                Diagnostic::error(codes::DUPLICATE_NAME, format!("`{}` is declared twice", name.name))
                    .with_primary(name.span, "declared again here")
                    .with_secondary(prev, "first declared here")
                    .with_help("rename one of them"),
            );
            return;
        }
        self.names.insert(name.name.clone(), (sym, name.span));
    }

    /// First walk: give every param, texture and pass an id, so that any
    /// declaration can refer to any other regardless of order.
    fn declare_all(&mut self, items: &[(Item, std::path::PathBuf)]) {
        for (item, dir) in items {
            match item {
                Item::Param(p) if gradient::is_gradient_type(&p.ty) => {
                    // Declared even when bad (its error reported), so its
                    // `ramp`s do not cascade into unknown names.
                    let g = self.gradient_decl(p).and_then(|g| self.set_gradient(&p.name.name, g));
                    self.declare(&p.name, Symbol::Gradient(self.gradients.len()));
                    let live = match &g {
                        Some(g) if self.keep_params => self.live_gradient(p, g),
                        _ => None,
                    };
                    self.gradient_params.push(live);
                    self.gradients.push(g);
                }
                Item::Param(p) if is_texture_type(&p.ty) => {
                    // `object param t: texture = image(...)` is a texture, not a
                    // uniform slot: it lives with the declared textures, flagged
                    // per object, and the scene may rebind its image per object.
                    if let Some(tex) = self.object_texture(p, dir) {
                        let id = TextureId(self.ir.textures.len() as u32);
                        self.declare(&p.name, Symbol::Texture(id));
                        self.ir.textures.push(tex);
                    }
                }
                Item::Param(p) => {
                    if self.ir.params.len() == MAX_PARAMS {
                        self.error(
                            Diagnostic::error(codes::LIMIT_EXCEEDED, "too many parameters")
                                .with_primary(p.name.span, format!("parameter number {}", MAX_PARAMS + 1))
                                .with_help(format!("a style may have at most {MAX_PARAMS} parameters")),
                        );
                        continue;
                    }
                    let id = ParamId(self.ir.params.len() as u32);
                    self.declare(&p.name, Symbol::Param(id));
                    let param = self.param_shell(p);
                    self.ir.params.push(param);
                }
                Item::Texture(t) => {
                    let id = TextureId(self.ir.textures.len() as u32);
                    self.declare(&t.name, Symbol::Texture(id));
                    let tex = self.texture(t, dir);
                    self.ir.textures.push(tex);
                }
                Item::Pass(p) => {
                    if self.ir.passes.len() == MAX_PASSES {
                        self.error(
                            Diagnostic::error(codes::LIMIT_EXCEEDED, "too many passes")
                                .with_primary(p.name.span, format!("pass number {}", MAX_PASSES + 1))
                                .with_help(format!("a style may have at most {MAX_PASSES} passes")),
                        );
                        continue;
                    }
                    let id = PassId(self.ir.passes.len() as u32);
                    self.declare(&p.name, Symbol::Pass(id));
                    let values = compute::declared_values(p);
                    if p.kind.kind.name == "compute" {
                        // A compute pass's `out`s are per-object values, not targets.
                        self.compute_passes.push(id);
                        self.pass_outputs.push(Vec::new());
                    } else {
                        self.pass_outputs
                            .push(p.body.outputs.iter().map(|o| o.name.name.clone()).collect());
                    }
                    self.pass_values.push(values);
                    self.ir.passes.push(Pass {
                        name: p.name.name.clone(),
                        doc: p.doc.clone(),
                        kind: PassKind::Image {
                            inputs: Vec::new(),
                            schedule: None,
                        },
                        scale: 1.0,
                        clear: [0.0, 0.0, 0.0, 0.0],
                        lets: Vec::new(),
                        outputs: Vec::new(),
                        span: p.span,
                        name_span: p.name.span,
                    });
                }
                Item::Output(_) | Item::Use(_) => {}
            }
        }
    }

    fn resolve_all(&mut self, items: &[(Item, std::path::PathBuf)], header: Option<Span>) {
        let mut param_index = 0;
        let mut gradient_index = 0;
        let mut pass_index = 0;
        let mut output_seen: Option<Span> = None;
        for (item, _) in items {
            match item {
                Item::Param(p) if is_texture_type(&p.ty) => {}
                Item::Param(p) if gradient::is_gradient_type(&p.ty) => {
                    // A gradient kept live took the next param id in `declare_all`.
                    if self.gradient_params.get(gradient_index).is_some_and(Option::is_some) {
                        param_index += 1;
                    }
                    gradient_index += 1;
                }
                Item::Param(p) => {
                    // Params past MAX_PARAMS were refused and have no id.
                    if (param_index as usize) < self.ir.params.len() {
                        self.param_body(ParamId(param_index), p);
                    }
                    param_index += 1;
                }
                Item::Pass(p) => {
                    if pass_index < self.ir.passes.len() {
                        self.pass_body(PassId(pass_index as u32), p);
                    }
                    pass_index += 1;
                }
                Item::Output(o) => {
                    if let Some(prev) = output_seen {
                        self.error(
                            Diagnostic::error(codes::NO_OUTPUT, "more than one `output`")
                                .with_primary(o.span, "second output")
                                .with_secondary(prev, "first output")
                                .with_help("a style has exactly one final image"),
                        );
                        continue;
                    }
                    output_seen = Some(o.span);
                    self.ir.output_span = o.span;
                    self.ir.output = self.output(o);
                }
                Item::Texture(_) | Item::Use(_) => {}
            }
        }
        if output_seen.is_none() {
            // A style with no pass at all is labelled at its header; without
            // a header either, the missing header is already an error.
            let place = match self.ir.passes.last() {
                Some(last) => Some((last.name_span, "the last pass")),
                None => header.map(|h| (h, "this style has no passes and no `output`")),
            };
            if let Some((span, label)) = place {
                self.error(
                    Diagnostic::error(codes::NO_OUTPUT, "the style has no `output`")
                        .with_primary(span, label)
                        .with_help("add `output <pass>.<target>` to say which target is the final image"),
                );
            }
        }
    }

    fn output(&mut self, o: &ast::OutputDecl) -> Option<TargetRef> {
        let Some((Symbol::Pass(pass), _)) = self.names.get(&o.pass.name).copied() else {
            let passes: Vec<String> = self.ir.passes.iter().map(|p| p.name.clone()).collect();
            let mut d = Diagnostic::error(codes::UNKNOWN_NAME, format!("no pass named `{}`", o.pass.name))
                .with_primary(o.pass.span, "not a pass");
            if let Some(s) = did_you_mean(&o.pass.name, passes.iter().map(String::as_str)) {
                d = d.with_help(format!("did you mean `{s}`?"));
            }
            self.error(d);
            return None;
        };
        self.target_of(pass, &o.target)
    }

    fn target_of(&mut self, pass: PassId, field: &ast::Ident) -> Option<TargetRef> {
        let outs = &self.pass_outputs[pass.0 as usize];
        if let Some(i) = outs.iter().position(|o| *o == field.name) {
            return Some(TargetRef { pass, output: i as u32 });
        }
        let mut d = Diagnostic::error(
            codes::UNKNOWN_NAME,
            format!("pass `{}` has no output `{}`", self.ir.pass(pass).name, field.name),
        )
        .with_primary(field.span, "unknown output");
        if let Some(s) = did_you_mean(&field.name, outs.iter().map(String::as_str)) {
            d = d.with_help(format!("did you mean `{s}`?"));
        } else {
            d = d.with_help(format!("its outputs are: {}", outs.join(", ")));
        }
        self.error(d);
        None
    }

    fn is_bound(&self, name: &str) -> bool {
        self.scopes.iter().any(|s| s.iter().any(|(n, _)| n == name)) || self.names.contains_key(name)
    }
}

/// `texture` as a parameter type (`object param lit: texture = image(...)`).
fn is_texture_type(ty: &ast::TypeExpr) -> bool {
    matches!(ty, ast::TypeExpr::Named(id) if id.name == "texture")
}
