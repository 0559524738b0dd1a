//! Resolve: turn the AST into IR, binding every name to what it means.
//!
//! Names resolve, innermost first, to: block `let`s, pass `let`s, parameters,
//! textures, builtins, and enum variants. `pass.output` is a target;
//! `position.view` and `light.dir` are builtins; any other `.xyz` is a
//! swizzle. Calls bind to a WGSL intrinsic or a stdlib operator, and their
//! arguments are put in parameter order with defaults filled in. Types are
//! left for the typechecker, except for literals and leaves.

use crate::consteval::const_eval;
use crate::ir::*;
use crate::load::Loaded;
use crate::InternalError;
use abi::Format;
use dsl::ast::{self, ExprKind as AK, Item, UnitSuffix};
use dsl::diagnostic::did_you_mean;
use dsl::{codes, Diagnostic, Span};
use std::collections::HashMap;
use std::path::Path;
use stdlib::Unit;

mod compute;
mod kind_args;
mod lines;
mod settings;
mod swizzle;
mod texture_source;

/// Resolution limits, stated in the error messages (the table of every
/// limit is `dsl::limits`).
pub use dsl::limits::{MAX_PARAMS, MAX_PASSES, MAX_TARGETS_PER_PASS as MAX_OUTPUTS_PER_PASS};
pub const MAX_NOISE_SIZE: u32 = 4096;

pub fn resolve(
    loaded: &Loaded,
    scene: Option<&crate::SceneSummary>,
    paths: Option<&dsl::paths::PathPolicy>,
    diags: &mut Vec<Diagnostic>,
) -> Result<Ir, InternalError> {
    let mut r = Resolver {
        ir: Ir::default(),
        diags,
        scene,
        paths,
        names: HashMap::new(),
        pass_outputs: Vec::new(),
        pass_values: Vec::new(),
        compute_passes: Vec::new(),
        states: Vec::new(),
        has_object: false,
        scopes: Vec::new(),
        current_pass: None,
        draws_objects: false,
        in_vertex: false,
        internal: None,
    };
    r.ir.style_name = match &loaded.root.style {
        Some(h) => h.name.clone(),
        None => String::from("untitled"),
    };
    r.declare_all(&loaded.items);
    r.resolve_all(&loaded.items, loaded.root.style.as_ref().map(|h| h.span));
    match r.internal {
        Some(e) => Err(e),
        None => Ok(r.ir),
    }
}

#[derive(Debug, Clone, Copy)]
enum Symbol {
    Param(ParamId),
    Texture(TextureId),
    Pass(PassId),
}

struct Resolver<'d> {
    ir: Ir,
    diags: &'d mut Vec<Diagnostic>,
    /// The scene, when the caller knows it (for `scene_has`).
    scene: Option<&'d crate::SceneSummary>,
    /// The paths policy every `image("…")` is checked against before it is probed.
    paths: Option<&'d dsl::paths::PathPolicy>,
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
    /// Whether the pass being resolved draws objects (`render(...)`): only
    /// those may read per-object textures.
    draws_objects: bool,
    /// Resolving a `vertex { ... }` modifier: no texture may be sampled
    /// there (`textureSample` is fragment-only in WGSL).
    in_vertex: bool,
    /// The first impossible state met (a bug in npr, not in the style).
    internal: Option<InternalError>,
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
                        kind: PassKind::Image { inputs: Vec::new() },
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
        let mut pass_index = 0;
        let mut output_seen: Option<Span> = None;
        for (item, _) in items {
            match item {
                Item::Param(p) if is_texture_type(&p.ty) => {}
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

    // ---------------------------------------------------------------- params

    fn param_shell(&mut self, p: &ast::ParamDecl) -> Param {
        let (ty, value_ty, unit) = self.param_type(&p.ty);
        Param {
            name: p.name.name.clone(),
            doc: p.doc.clone(),
            ty,
            value_ty,
            unit,
            per_object: p.per_object,
            default: ExprId(0),
            range: None,
            keys: Vec::new(),
            interpolation: "linear".into(),
            span: p.span,
            name_span: p.name.span,
        }
    }

    fn param_type(&mut self, t: &ast::TypeExpr) -> (ParamTy, Ty, Unit) {
        match t {
            ast::TypeExpr::Enum { variants, .. } => (
                ParamTy::Enum(variants.iter().map(|v| v.name.clone()).collect()),
                Ty::Int,
                Unit::None,
            ),
            ast::TypeExpr::Named(id) => {
                let v = |ty| (ParamTy::Value(ty), ty, Unit::None);
                let u = |unit| (ParamTy::Value(Ty::Float), Ty::Float, unit);
                match id.name.as_str() {
                    "float" => v(Ty::Float),
                    "int" => v(Ty::Int),
                    "bool" => v(Ty::Bool),
                    "vec2" => v(Ty::Vec2),
                    "vec3" => v(Ty::Vec3),
                    "vec4" | "color" => v(Ty::Vec4),
                    "px" => u(Unit::Px),
                    "m" | "mm" => u(Unit::Meters),
                    "s" => u(Unit::Seconds),
                    "Hz" => u(Unit::Hertz),
                    "deg" => u(Unit::Radians),
                    "range" => (ParamTy::Range(Ty::Vec2), Ty::Vec2, Unit::None),
                    "blend" => (
                        ParamTy::Enum(vec!["linear".into(), "cubic".into(), "quintic".into()]),
                        Ty::Int,
                        Unit::None,
                    ),
                    other => {
                        let known = [
                            "float", "int", "bool", "vec2", "vec3", "vec4", "color", "px", "m", "mm", "s", "Hz", "deg",
                            "range", "blend",
                        ];
                        let mut d = Diagnostic::error(codes::UNKNOWN_TYPE, format!("unknown parameter type `{other}`"))
                            .with_primary(id.span, "not a type");
                        d = match did_you_mean(other, known) {
                            Some(s) => d.with_help(format!("did you mean `{s}`?")),
                            None if other == "texture" => d.with_help(
                                "textures are declared with `texture name = image(\"file.png\")`, not as parameters",
                            ),
                            None => {
                                d.with_help(format!("parameter types are: {}, or enum(a, b, ...)", known.join(", ")))
                            }
                        };
                        self.error(d);
                        (ParamTy::Value(Ty::Float), Ty::Unknown, Unit::None)
                    }
                }
            }
        }
    }

    fn param_body(&mut self, id: ParamId, p: &ast::ParamDecl) {
        let variants = match &self.ir.params[id.0 as usize].ty {
            ParamTy::Enum(v) => Some(v.clone()),
            _ => None,
        };
        let default = match (&variants, &p.default.kind) {
            (Some(vs), AK::Name(n)) => match vs.iter().position(|v| *v == n.name) {
                Some(i) => self
                    .ir
                    .add_typed(ExprKind::Const(Const::Int(i as i64)), Ty::Int, Unit::None, n.span),
                None => {
                    let mut d = Diagnostic::error(
                        codes::UNKNOWN_NAME,
                        format!("`{}` is not a variant of this enum", n.name),
                    )
                    .with_primary(n.span, "unknown variant");
                    d = match did_you_mean(&n.name, vs.iter().map(String::as_str)) {
                        Some(s) => d.with_help(format!("did you mean `{s}`?")),
                        None => d.with_help(format!("the variants are: {}", vs.join(", "))),
                    };
                    self.error(d);
                    self.ir.add(ExprKind::Error, n.span)
                }
            },
            _ => self.expr(&p.default),
        };
        let range = p.range.as_ref().and_then(|r| {
            let lo = self.expr(&r.lo);
            let hi = self.expr(&r.hi);
            let lo_v = self.const_scalar(lo, "a range bound");
            let hi_v = self.const_scalar(hi, "a range bound");
            let (lo_v, hi_v) = (lo_v?, hi_v?);
            if lo_v > hi_v {
                self.error(
                    Diagnostic::error(codes::OUT_OF_RANGE, "empty range")
                        .with_primary(r.span, format!("{lo_v} is greater than {hi_v}"))
                        .with_help("write the lower bound first: `in lo..hi`"),
                );
                return None;
            }
            Some((lo_v, hi_v))
        });
        let mut keys = Vec::new();
        let mut interpolation = String::from("linear");
        if let Some(anim) = &p.animate {
            if let Some(i) = &anim.interpolation {
                if !["linear", "step", "smooth"].contains(&i.name.as_str()) {
                    self.error(
                        Diagnostic::error(codes::UNKNOWN_NAME, format!("unknown interpolation `{}`", i.name))
                            .with_primary(i.span, "not an interpolation")
                            .with_help("use `linear`, `step` or `smooth`"),
                    );
                }
                interpolation = i.name.clone();
            }
            for k in &anim.keys {
                let t = self.expr(&k.time);
                let v = self.expr(&k.value);
                let t_unit = self.ir.expr(t).unit;
                if t_unit != Unit::Seconds && t_unit != Unit::None {
                    self.error(
                        Diagnostic::error(codes::UNIT_MISMATCH, "keyframe time must be in seconds")
                            .with_primary(k.time.span, format!("this is in {}", t_unit.name()))
                            .with_help("write times like `2s` or `0.5s`"),
                    );
                }
                let (Some(tv), Some(vv)) = (self.const_scalar(t, "a keyframe time"), self.const_values(v)) else {
                    continue;
                };
                if let Some(prev) = keys.last().map(|k: &Keyframe| k.time_s) {
                    if tv <= prev {
                        self.error(
                            Diagnostic::error(codes::OUT_OF_RANGE, "keyframe times must increase")
                                .with_primary(k.time.span, format!("{tv}s is not after {prev}s"))
                                .with_help("list keyframes in time order"),
                        );
                    }
                }
                if let Some((lo, hi)) = range {
                    if let Some(bad) = vv.iter().find(|x| **x < lo || **x > hi) {
                        self.error(
                            Diagnostic::error(codes::OUT_OF_RANGE, "keyframe value outside the parameter's range")
                                .with_primary(k.value.span, format!("{bad} is outside {lo}..{hi}"))
                                .with_secondary(
                                    p.range.as_ref().map(|r| r.span).unwrap_or(p.span),
                                    "range declared here",
                                ),
                        );
                    }
                }
                keys.push(Keyframe { time_s: tv, value: vv });
            }
        }
        let param = &mut self.ir.params[id.0 as usize];
        param.default = default;
        param.range = range;
        param.keys = keys;
        param.interpolation = interpolation;
    }

    fn const_scalar(&mut self, id: ExprId, what: &str) -> Option<f64> {
        let v = self.const_values(id)?;
        if v.len() != 1 {
            let span = self.ir.expr(id).span;
            self.error(
                Diagnostic::error(codes::TYPE_MISMATCH, format!("{what} must be a single number"))
                    .with_primary(span, format!("this has {} components", v.len())),
            );
            return None;
        }
        Some(v[0])
    }

    fn const_values(&mut self, id: ExprId) -> Option<Vec<f64>> {
        if matches!(self.ir.expr(id).kind, ExprKind::Error) {
            return None;
        }
        match const_eval(&self.ir, id) {
            Some(c) => Some(c.as_f64s()),
            None => {
                let span = self.ir.expr(id).span;
                self.error(
                    Diagnostic::error(codes::NOT_CONSTANT, "this must be a constant")
                        .with_primary(span, "not known at compile time")
                        .with_help("use literals such as `0.5`, `2px`, `#ff0000` or `vec2(0.1, 0.2)`"),
                );
                None
            }
        }
    }

    // -------------------------------------------------------------- textures

    /// `object param name: texture = image("file.png", srgb) { options }`:
    /// the default image and sampler options of a texture the scene may bind
    /// per object (`params = { name = "file.png" }`). A default is required,
    /// as for every parameter, so an object without a binding still draws.
    fn object_texture(&mut self, p: &ast::ParamDecl, dir: &Path) -> Option<Texture> {
        if !p.per_object {
            self.error(
                Diagnostic::error(codes::UNKNOWN_TYPE, "only object params may be textures")
                    .with_primary(p.ty.span(), "a style-wide texture parameter")
                    .with_help(format!(
                        "declare a style texture as `texture {0} = image(\"file.png\")`, or one the scene binds per object as `object param {0}: texture = image(\"file.png\")`",
                        p.name.name
                    )),
            );
            return None;
        }
        if let Some(extra) = p.range.as_ref().map(|r| r.span).or(p.animate.as_ref().map(|a| a.span)) {
            self.error(
                Diagnostic::error(
                    codes::BAD_ARGUMENT,
                    format!("texture param `{}` has no range or keyframes", p.name.name),
                )
                .with_primary(extra, "not for a texture")
                .with_help("remove it; a texture param only has a default image and `{ wrap, filter, mips }` options"),
            );
        }
        let AK::Call(call) = &p.default.kind else {
            self.error(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!("the default of texture param `{}` is not an image", p.name.name),
                )
                .with_primary(p.default.span, "expected `image(\"file.png\", srgb)`")
                .with_help("write `object param lit: texture = image(\"textures/paper.png\", srgb)`"),
            );
            return None;
        };
        let decl = ast::TextureDecl {
            doc: p.doc.clone(),
            name: p.name.clone(),
            source: call.clone(),
            options: p.options.clone(),
            span: p.span,
        };
        let mut tex = self.texture(&decl, dir);
        tex.per_object = true;
        Some(tex)
    }

    /// `scene_has(tag)`: whether any object in the scene carries `tag`. With a
    /// known scene this is a constant, so `if scene_has(casters) { ... }` lets
    /// the compiler drop a shadow-caster depth pass the scene cannot use; with
    /// no scene it is `true`, which is always safe (an empty `render(tag)` pass
    /// leaves its targets at their clear value).
    fn scene_has(&mut self, call: &ast::Call) -> ExprId {
        let span = call.span;
        let tag = match call.args.as_slice() {
            [a] if a.name.is_none() => match &a.value.kind {
                AK::Name(n) => Some(n.name.clone()),
                _ => None,
            },
            _ => None,
        };
        let Some(tag) = tag else {
            self.error(
                Diagnostic::error(codes::BAD_ARGUMENT, "`scene_has` takes one object tag")
                    .with_primary(span, "expected `scene_has(tag)`")
                    .with_help("write the tag as a bare name, as in `render(tag)`: `scene_has(casters)`"),
            );
            return self.ir.add(ExprKind::Error, span);
        };
        let present = match self.scene {
            Some(scene) => {
                let present = scene.tags.contains(&tag);
                if !self.ir.scene_queries.iter().any(|(t, _)| *t == tag) {
                    self.ir.scene_queries.push((tag, present));
                }
                present
            }
            None => true,
        };
        self.ir
            .add_typed(ExprKind::Const(Const::Bool(present)), Ty::Bool, Unit::None, span)
    }

    /// `other_eye(pass.target)` (the other eye of a stereo frame: LSA
    /// contours' reprojection and consistency passes) and
    /// `previous(pass.target)` (the previous frame: temporal filters,
    /// feedback): another copy of a target.
    fn target_copy(&mut self, call: &ast::Call, name: &str, copy: TargetCopy) -> ExprId {
        let span = call.span;
        let example = if copy == TargetCopy::Previous {
            "name a target of any pass, this one included, e.g. `previous(final.color)`"
        } else {
            "name a target of an earlier pass, e.g. `other_eye(lines.e)`"
        };
        if let [a] = call.args.as_slice() {
            if a.name.is_none() {
                let v = self.expr(&a.value);
                if let ExprKind::Target {
                    target,
                    copy: TargetCopy::This,
                } = self.ir.expr(v).kind
                {
                    return self
                        .ir
                        .add_typed(ExprKind::Target { target, copy }, Ty::Target(target), Unit::None, span);
                }
                if matches!(self.ir.expr(v).kind, ExprKind::Error) {
                    return v;
                }
            }
        }
        self.error(
            Diagnostic::error(codes::BAD_ARGUMENT, format!("`{name}` takes one pass target"))
                .with_primary(span, format!("expected `{name}(pass.target)`"))
                .with_help(example),
        );
        self.ir.add(ExprKind::Error, span)
    }

    // ---------------------------------------------------------------- passes

    fn pass_body(&mut self, id: PassId, p: &ast::PassDecl) {
        self.current_pass = Some(id);
        let kind = match p.kind.kind.name.as_str() {
            "render" => {
                let tag = self.scene_or_tag(p, "a render pass draws one set of objects");
                PassKind::Render {
                    tag,
                    view: PassView::Camera,
                    vertex: VertexModifiers::default(),
                    depth: PassDepth::Own,
                }
            }
            "image" => {
                let mut inputs = Vec::new();
                for a in self.plain_kind_args(p, "a pass") {
                    match self.names.get(&a.name).copied() {
                        Some((Symbol::Pass(pid), _)) => inputs.push(pid),
                        _ => {
                            let passes: Vec<String> = self.ir.passes.iter().map(|p| p.name.clone()).collect();
                            let mut d = Diagnostic::error(codes::UNKNOWN_NAME, format!("no pass named `{}`", a.name))
                                .with_primary(a.span, "not a pass");
                            if let Some(s) = did_you_mean(&a.name, passes.iter().map(String::as_str)) {
                                d = d.with_help(format!("did you mean `{s}`?"));
                            }
                            self.error(d);
                        }
                    }
                }
                PassKind::Image { inputs }
            }
            "compute" => self.compute_kind(p),
            "lines" => self.lines_kind(p),
            other => {
                let kinds = ["render", "image", "compute", "lines"];
                let mut d = Diagnostic::error(codes::UNKNOWN_NAME, format!("unknown pass kind `{other}`"))
                    .with_primary(p.kind.kind.span, "not a pass kind");
                d = match did_you_mean(other, kinds) {
                    Some(s) => d.with_help(format!("did you mean `{s}`?")),
                    None => d.with_help(
                        "passes are `render(scene)`, `image(inputs...)`, `compute(domain)` or `lines(scene)`",
                    ),
                };
                self.error(d);
                PassKind::Image { inputs: Vec::new() }
            }
        };
        self.draws_objects = kind.draws_objects();
        self.has_object = kind.has_object();
        let scale = match &p.scale {
            None => 1.0,
            Some(e) => {
                let sid = self.expr(e);
                match self.const_scalar(sid, "a pass scale") {
                    Some(s) if s > 0.0 && s <= 4.0 => s,
                    Some(s) => {
                        self.error(
                            Diagnostic::error(codes::OUT_OF_RANGE, "pass scale out of range")
                                .with_primary(e.span, format!("{s} is outside (0, 4]"))
                                .with_help("a scale is relative to the output size, e.g. `scale 1/2`"),
                        );
                        1.0
                    }
                    None => 1.0,
                }
            }
        };
        let mut kind = kind;
        self.pass_modifiers(&mut kind, p);
        self.vertex_modifiers(&mut kind, p);
        let mut clear = [0.0, 0.0, 0.0, 0.0];
        let mut depth_seen = None;
        let mut line_settings_seen = Vec::new();
        for s in &p.body.settings {
            match s.key.name.as_str() {
                "depth" => self.depth_setting(&mut kind, s, &mut depth_seen),
                key if lines::LINE_SETTINGS.contains(&key) => match &mut kind {
                    PassKind::Lines(l) => self.line_setting(l, s, &mut line_settings_seen),
                    _ => self.error(
                        Diagnostic::error(codes::BAD_ARGUMENT, format!("`{key}` is a setting of lines passes"))
                            .with_primary(s.key.span, format!("this is a {} pass", kind.name()))
                            .with_help("edges and their shape are drawn by `pass ink: lines(scene) { ... }`"),
                    ),
                },
                "count" | "seed" => self.sample_setting(&mut kind, s),
                "clear" => {
                    let cid = self.expr(&s.value);
                    if let Some(v) = self.const_values(cid) {
                        match v.len() {
                            1 => clear = [v[0], v[0], v[0], 1.0],
                            4 => clear = [v[0], v[1], v[2], v[3]],
                            3 => clear = [v[0], v[1], v[2], 1.0],
                            n => self.error(
                                Diagnostic::error(codes::TYPE_MISMATCH, "`clear` must be a colour")
                                    .with_primary(s.value.span, format!("this has {n} components")),
                            ),
                        }
                    }
                }
                other => {
                    let mut d = Diagnostic::error(codes::BAD_ARGUMENT, format!("unknown pass setting `{other}`"))
                        .with_primary(s.key.span, "not a pass setting");
                    let known = ["clear", "depth", "count", "seed"]
                        .into_iter()
                        .chain(lines::LINE_SETTINGS);
                    d = match did_you_mean(other, known) {
                        Some(k) => d.with_help(format!("did you mean `{k}`?")),
                        None if matches!(kind, PassKind::Lines(_)) => d.with_help(format!(
                            "lines passes take `clear`, `depth: test(pass)` and {}",
                            lines::LINE_SETTINGS.map(|k| format!("`{k}`")).join(", ")
                        )),
                        None => d.with_help("pass settings are: `clear: #rrggbb`, `depth: keep`, `depth: test(pass)`, and in `compute(samples)` passes `count: n` and `seed: n`"),
                    };
                    self.error(d)
                }
            }
        }
        let compute_domain = match &kind {
            PassKind::Compute { domain, .. } => Some(*domain),
            PassKind::Render { .. } | PassKind::Image { .. } | PassKind::Lines(_) => None,
        };
        match compute_domain {
            Some(_) => self.states_in_scope(id, p),
            None => self.refuse_compute_statements(p),
        }
        self.scopes.push(Vec::new());
        let mut lets = Vec::new();
        for l in &p.body.lets {
            let v = self.expr(&l.value);
            lets.push(Let {
                name: l.name.name.clone(),
                value: v,
                span: l.span,
            });
            if let Some(scope) = self.scopes.last_mut() {
                scope.push((l.name.name.clone(), v));
            }
        }
        if p.body.outputs.len() > MAX_OUTPUTS_PER_PASS {
            self.error(
                Diagnostic::error(codes::LIMIT_EXCEEDED, "too many outputs in one pass")
                    .with_primary(p.body.outputs[MAX_OUTPUTS_PER_PASS].span, "one too many")
                    .with_help(format!(
                        "a pass can write at most {MAX_OUTPUTS_PER_PASS} targets (the colour attachment limit); split it into two passes"
                    )),
            );
        }
        let mut outputs = Vec::new();
        let mut seen: Vec<&str> = Vec::new();
        if let (Some(domain), PassKind::Compute { values, .. }) = (compute_domain, &mut kind) {
            *values = self.compute_values(domain, p);
            self.check_value_names(values);
        }
        let targets = if compute_domain.is_some() {
            &[][..]
        } else {
            &p.body.outputs[..]
        };
        for o in targets.iter().take(MAX_OUTPUTS_PER_PASS) {
            if seen.contains(&o.name.name.as_str()) {
                self.error(
                    Diagnostic::error(
                        codes::DUPLICATE_NAME,
                        format!("output `{}` is declared twice", o.name.name),
                    )
                    .with_primary(o.name.span, "declared again here"),
                );
            }
            seen.push(&o.name.name);
            let format = match Format::parse(&o.format.name) {
                Some(f) => f,
                None => {
                    let names = Format::ALL.iter().map(|(n, _)| *n);
                    let mut d = Diagnostic::error(
                        codes::UNKNOWN_TYPE,
                        format!("unknown texture format `{}`", o.format.name),
                    )
                    .with_primary(o.format.span, "not a target format");
                    d = match did_you_mean(&o.format.name, names) {
                        Some(s) => d.with_help(format!("did you mean `{s}`?")),
                        None => d.with_help(format!(
                            "formats are: {}",
                            Format::ALL.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ")
                        )),
                    };
                    self.error(d);
                    Format::Rgba8unorm
                }
            };
            let value = self.expr(&o.value);
            let blend = self.output_blend(o, format);
            outputs.push(PassOutput {
                name: o.name.name.clone(),
                format,
                value,
                blend,
                span: o.span,
            });
        }
        self.scopes.pop();
        let pass = &mut self.ir.passes[id.0 as usize];
        pass.kind = kind;
        pass.scale = scale;
        pass.clear = clear;
        pass.lets = lets;
        pass.outputs = outputs;
        self.current_pass = None;
        self.draws_objects = false;
        self.has_object = false;
        self.states.clear();
    }

    /// `view(...)` and other modifiers after the pass kind.
    fn pass_modifiers(&mut self, kind: &mut PassKind, p: &ast::PassDecl) {
        for m in &p.modifiers {
            match (m.key.name.as_str(), &m.value.kind, &mut *kind) {
                ("view", ast::ExprKind::Name(n), PassKind::Render { view, .. })
                    if n.name == "light" || n.name == "camera" =>
                {
                    *view = if n.name == "light" {
                        PassView::Light
                    } else {
                        PassView::Camera
                    };
                }
                ("view", _, _) => self.error(
                    Diagnostic::error(
                        codes::BAD_ARGUMENT,
                        "`view(...)` takes `camera` or `light` on a render pass",
                    )
                    .with_primary(m.span, "not a view of a render pass")
                    .with_help("write `pass depth: render(casters) view(light) { ... }`"),
                ),
                _ => self.error(
                    Diagnostic::error(
                        codes::BAD_ARGUMENT,
                        format!("unsupported pass modifier `{}`", m.key.name),
                    )
                    .with_primary(m.span, "not supported yet")
                    .with_help(
                        "render passes take `view(light)`; stereo pass modifiers are reserved for a later version",
                    ),
                ),
            }
        }
    }

    /// `vertex { ... }`: only render passes have a vertex shader of their own.
    fn vertex_modifiers(&mut self, kind: &mut PassKind, p: &ast::PassDecl) {
        for s in &p.body.vertex {
            let slot = match (s.key.name.as_str(), &mut *kind) {
                ("inflate", PassKind::Render { vertex, .. }) => Some(&mut vertex.inflate),
                (
                    "shadow_warp",
                    PassKind::Render {
                        view: PassView::Light,
                        vertex,
                        ..
                    },
                ) => Some(&mut vertex.shadow_warp),
                _ => None,
            };
            match slot {
                Some(slot) => {
                    self.in_vertex = true;
                    *slot = Some(self.expr(&s.value));
                    self.in_vertex = false;
                }
                None => self.error(
                    Diagnostic::error(codes::BAD_ARGUMENT, format!("unknown vertex modifier `{}`", s.key.name))
                        .with_primary(s.key.span, "not a vertex modifier")
                        .with_help("render passes support `vertex { inflate: 2px }`; `view(light)` passes also `shadow_warp: k`"),
                ),
            }
        }
    }

    // ----------------------------------------------------------- expressions

    fn expr(&mut self, e: &ast::Expr) -> ExprId {
        let span = e.span;
        match &e.kind {
            AK::Number { value, is_int, unit } => {
                let (v, unit) = match unit {
                    None => (*value, Unit::None),
                    Some(UnitSuffix::Px) => (*value, Unit::Px),
                    Some(UnitSuffix::Percent) => {
                        return self
                            .ir
                            .add_typed(ExprKind::PercentOfHeight(*value / 100.0), Ty::Float, Unit::Px, span)
                    }
                    Some(UnitSuffix::M) => (*value, Unit::Meters),
                    Some(UnitSuffix::Mm) => (*value * 1e-3, Unit::Meters),
                    Some(UnitSuffix::S) => (*value, Unit::Seconds),
                    Some(UnitSuffix::Hz) => (*value, Unit::Hertz),
                    Some(UnitSuffix::Deg) => (value.to_radians(), Unit::Radians),
                };
                if *is_int && unit == Unit::None && v.abs() < 2f64.powi(31) {
                    self.ir
                        .add_typed(ExprKind::Const(Const::Int(v as i64)), Ty::Int, unit, span)
                } else {
                    self.ir
                        .add_typed(ExprKind::Const(Const::Float(v)), Ty::Float, unit, span)
                }
            }
            AK::Bool(b) => self
                .ir
                .add_typed(ExprKind::Const(Const::Bool(*b)), Ty::Bool, Unit::None, span),
            AK::Color(c) => self
                .ir
                .add_typed(ExprKind::Const(Const::Vec(c.to_vec())), Ty::Vec4, Unit::None, span),
            AK::Str(_) => {
                self.error(
                    Diagnostic::error(codes::TYPE_MISMATCH, "a string is not a value")
                        .with_primary(span, "strings are only used for file paths")
                        .with_help("to pick an enum variant, write its name without quotes"),
                );
                self.ir.add(ExprKind::Error, span)
            }
            AK::Name(id) => self.name(id),
            AK::Field { base, field } => self.field(base, field, span),
            AK::Call(call) => self.call(call),
            AK::Unary { op, operand } => {
                let o = self.expr(operand);
                self.ir.add(ExprKind::Unary { op: *op, operand: o }, span)
            }
            AK::Binary { op, lhs, rhs } => {
                let l = self.expr(lhs);
                let r = self.expr(rhs);
                self.ir.add(
                    ExprKind::Binary {
                        op: *op,
                        lhs: l,
                        rhs: r,
                    },
                    span,
                )
            }
            AK::If { cond, then, otherwise } => {
                let c = self.expr(cond);
                let t = self.expr(then);
                let o = self.expr(otherwise);
                self.ir.add(
                    ExprKind::Select {
                        cond: c,
                        then: t,
                        otherwise: o,
                    },
                    span,
                )
            }
            AK::Block { lets, value } => {
                self.scopes.push(Vec::new());
                for l in lets {
                    let v = self.expr(&l.value);
                    if let Some(s) = self.scopes.last_mut() {
                        s.push((l.name.name.clone(), v));
                    }
                }
                let v = self.expr(value);
                self.scopes.pop();
                v
            }
            AK::Range { lo, hi } => {
                let l = self.expr(lo);
                let h = self.expr(hi);
                self.ir.add(
                    ExprKind::Call {
                        callee: Callee::Intrinsic(Intrinsic::Construct(2)),
                        args: vec![l, h],
                    },
                    span,
                )
            }
        }
    }

    fn name(&mut self, id: &ast::Ident) -> ExprId {
        let span = id.span;
        for scope in self.scopes.iter().rev() {
            if let Some((_, v)) = scope.iter().rev().find(|(n, _)| *n == id.name) {
                return *v;
            }
        }
        if let Some(v) = self.state_read(id) {
            return v;
        }
        match self.names.get(&id.name).copied() {
            Some((Symbol::Param(p), _)) => {
                let param = &self.ir.params[p.0 as usize];
                let (ty, unit) = (param.value_ty, param.unit);
                return self.ir.add_typed(ExprKind::Param(p), ty, unit, span);
            }
            Some((Symbol::Texture(t), _)) => {
                if self.in_vertex {
                    let d = Diagnostic::error(
                        codes::BAD_PASS_INPUT,
                        format!("texture `{}` read in a `vertex {{ }}` modifier", id.name),
                    )
                    .with_primary(span, "textures are sampled per fragment, not per vertex")
                    .with_help("use a parameter or a per-object param for the vertex modifier");
                    self.error(d);
                    return self.ir.add(ExprKind::Error, span);
                }
                if self.ir.textures[t.0 as usize].per_object && !self.draws_objects {
                    let d = Diagnostic::error(
                        codes::BAD_PASS_INPUT,
                        format!("`{}` is a per-object texture, read outside a render pass", id.name),
                    )
                    .with_primary(span, "no object is being drawn here")
                    .with_help(format!(
                        "read `{}` in a `render(...)` pass, write what you need to a target, and read that target here",
                        id.name
                    ));
                    self.error(d);
                    return self.ir.add(ExprKind::Error, span);
                }
                return self
                    .ir
                    .add_typed(ExprKind::Texture(t), Ty::Texture(t), Unit::None, span);
            }
            Some((Symbol::Pass(p), _)) => {
                let outs = self.pass_outputs[p.0 as usize].clone();
                let d = Diagnostic::error(codes::TYPE_MISMATCH, format!("`{}` is a pass, not a value", id.name))
                    .with_primary(span, "a pass")
                    .with_help(match outs.first() {
                        Some(o) => format!("read one of its targets, e.g. `{}.{o}`", id.name),
                        None => "this pass has no outputs".to_string(),
                    });
                self.error(d);
                return self.ir.add(ExprKind::Error, span);
            }
            None => {}
        }
        if let Some((_, b)) = Builtin::SPELLINGS.iter().find(|(s, _)| *s == id.name) {
            let (ty, unit) = b.ty_unit();
            return self.ir.add_typed(ExprKind::Builtin(*b), ty, unit, span);
        }
        // Enum variants are global constants (their index).
        for p in &self.ir.params {
            if let ParamTy::Enum(vs) = &p.ty {
                if let Some(i) = vs.iter().position(|v| *v == id.name) {
                    return self
                        .ir
                        .add_typed(ExprKind::Const(Const::Int(i as i64)), Ty::Int, Unit::None, span);
                }
            }
        }
        let mut candidates: Vec<String> = self.names.keys().cloned().collect();
        candidates.extend(Builtin::SPELLINGS.iter().map(|(s, _)| s.to_string()));
        for scope in &self.scopes {
            candidates.extend(scope.iter().map(|(n, _)| n.clone()));
        }
        let mut d = Diagnostic::error(codes::UNKNOWN_NAME, format!("unknown name `{}`", id.name))
            .with_primary(span, "not found in this scope");
        if let Some(s) = did_you_mean(&id.name, candidates.iter().map(String::as_str)) {
            d = d.with_help(format!("did you mean `{s}`?"));
        } else {
            d = d.with_help("declare it with `param` or `let`, or use a builtin such as `uv`, `normal`, `time`");
        }
        self.error(d);
        self.ir.add(ExprKind::Error, span)
    }

    fn field(&mut self, base: &ast::Expr, field: &ast::Ident, span: Span) -> ExprId {
        if let AK::Name(b) = &base.kind {
            let shadowed = self.scopes.iter().any(|s| s.iter().any(|(n, _)| *n == b.name));
            if !shadowed {
                if let Some(p) = self.is_compute_pass(&b.name) {
                    return self.value_of(p, field, span);
                }
                if let Some((Symbol::Pass(p), _)) = self.names.get(&b.name).copied() {
                    return match self.target_of(p, field) {
                        Some(t) => self.ir.add_typed(
                            ExprKind::Target {
                                target: t,
                                copy: TargetCopy::This,
                            },
                            Ty::Target(t),
                            Unit::None,
                            span,
                        ),
                        None => self.ir.add(ExprKind::Error, span),
                    };
                }
                let spelled = format!("{}.{}", b.name, field.name);
                if let Some((_, bi)) = Builtin::SPELLINGS.iter().find(|(s, _)| *s == spelled) {
                    let (ty, unit) = bi.ty_unit();
                    return self.ir.add_typed(ExprKind::Builtin(*bi), ty, unit, span);
                }
                if matches!(b.name.as_str(), "light" | "camera") {
                    let members: Vec<&str> = Builtin::SPELLINGS
                        .iter()
                        .filter_map(|(s, _)| s.strip_prefix(&format!("{}.", b.name)))
                        .collect();
                    let mut d = Diagnostic::error(
                        codes::UNKNOWN_NAME,
                        format!("`{}` has no member `{}`", b.name, field.name),
                    )
                    .with_primary(field.span, "unknown member");
                    d = match did_you_mean(&field.name, members.iter().copied()) {
                        Some(s) => d.with_help(format!("did you mean `{}.{s}`?", b.name)),
                        None => d.with_help(format!("its members are: {}", members.join(", "))),
                    };
                    self.error(d);
                    return self.ir.add(ExprKind::Error, span);
                }
            }
        }
        let b = self.expr(base);
        if matches!(self.ir.expr(b).kind, ExprKind::Error) {
            // The base's error is reported; its field would only repeat it.
            return b;
        }
        match swizzle::parse(field) {
            swizzle::Swizzle::Components(c) => self.ir.add(ExprKind::Swizzle { base: b, components: c }, span),
            swizzle::Swizzle::Mixed(d) => {
                self.error(*d);
                self.ir.add(ExprKind::Error, span)
            }
            swizzle::Swizzle::NotOne => {
                self.error(
                    Diagnostic::error(codes::UNKNOWN_TYPE, format!("unknown field `{}`", field.name))
                        .with_primary(field.span, "not a swizzle or member")
                        .with_help("swizzles use up to four of x, y, z, w (or r, g, b, a)"),
                );
                self.ir.add(ExprKind::Error, span)
            }
        }
    }

    fn call(&mut self, call: &ast::Call) -> ExprId {
        let name = call.callee.name.as_str();
        let span = call.span;
        if name == "scene_has" {
            return self.scene_has(call);
        }
        if let Some(copy) = target_copy_call(name) {
            return self.target_copy(call, name, copy);
        }
        if let Some(intr) = Intrinsic::lookup(name) {
            let mut args = Vec::new();
            for a in &call.args {
                if let Some(n) = &a.name {
                    self.error(
                        Diagnostic::error(codes::BAD_ARGUMENT, format!("`{name}` takes no named arguments"))
                            .with_primary(n.span, "named argument")
                            .with_help("pass the arguments by position"),
                    );
                }
                args.push(self.expr(&a.value));
            }
            return self.ir.add(
                ExprKind::Call {
                    callee: Callee::Intrinsic(intr),
                    args,
                },
                span,
            );
        }
        let Some(index) = stdlib::all().iter().position(|o| o.name == name) else {
            let mut names: Vec<&str> = stdlib::all().iter().map(|o| o.name).collect();
            names.extend(Intrinsic::names());
            let mut d = Diagnostic::error(codes::UNKNOWN_OPERATOR, format!("unknown operator `{name}`"))
                .with_primary(call.callee.span, "no such operator or function");
            d = match did_you_mean(name, names) {
                Some(s) => d.with_help(format!("did you mean `{s}`?")),
                None => d.with_help("`npr doc` lists the stdlib operators"),
            };
            self.error(d);
            for a in &call.args {
                self.expr(&a.value);
            }
            return self.ir.add(ExprKind::Error, span);
        };
        let op = &stdlib::all()[index];
        let mut slots: Vec<Option<ExprId>> = vec![None; op.params.len()];
        let mut positional = 0usize;
        let mut ok = true;
        for a in &call.args {
            let slot = match &a.name {
                None => {
                    // Positional arguments fill the parameters not yet given, in order.
                    while positional < slots.len() && slots[positional].is_some() {
                        positional += 1;
                    }
                    if positional >= slots.len() {
                        self.error(
                            Diagnostic::error(codes::BAD_ARGUMENT, format!("too many arguments to `{name}`"))
                                .with_primary(a.span, "extra argument")
                                .with_help(format!("`{name}` takes {}", signature(op))),
                        );
                        ok = false;
                        continue;
                    }
                    positional
                }
                Some(n) => match op.params.iter().position(|p| p.name == n.name) {
                    Some(i) if slots[i].is_none() => i,
                    Some(_) => {
                        self.error(
                            Diagnostic::error(codes::BAD_ARGUMENT, format!("argument `{}` given twice", n.name))
                                .with_primary(n.span, "given again here"),
                        );
                        ok = false;
                        continue;
                    }
                    None => {
                        let mut d =
                            Diagnostic::error(codes::BAD_ARGUMENT, format!("`{name}` has no parameter `{}`", n.name))
                                .with_primary(n.span, "unknown argument name");
                        d = match did_you_mean(&n.name, op.params.iter().map(|p| p.name)) {
                            Some(s) => d.with_help(format!("did you mean `{s}`?")),
                            None => d.with_help(format!("`{name}` takes {}", signature(op))),
                        };
                        self.error(d);
                        ok = false;
                        continue;
                    }
                },
            };
            let param = &op.params[slot];
            let value = match (param.ty, &a.value.kind) {
                (stdlib::Ty::Enum(variants), AK::Name(v)) if !self.is_bound(&v.name) => {
                    match variants.iter().position(|x| *x == v.name) {
                        Some(i) => {
                            self.ir
                                .add_typed(ExprKind::Const(Const::Int(i as i64)), Ty::Int, Unit::None, v.span)
                        }
                        None => {
                            let mut d = Diagnostic::error(
                                codes::BAD_ARGUMENT,
                                format!("`{}` is not a choice of `{}`", v.name, param.name),
                            )
                            .with_primary(v.span, "unknown variant");
                            d = match did_you_mean(&v.name, variants.iter().copied()) {
                                Some(s) => d.with_help(format!("did you mean `{s}`?")),
                                None => d.with_help(format!("choices are: {}", variants.join(", "))),
                            };
                            self.error(d);
                            ok = false;
                            continue;
                        }
                    }
                }
                _ => self.expr(&a.value),
            };
            slots[slot] = Some(value);
        }
        let mut args = Vec::new();
        for (i, p) in op.params.iter().enumerate() {
            if let Some(v) = slots[i] {
                args.push(v);
                continue;
            }
            let v = match p.default {
                stdlib::Default::Required => {
                    if ok {
                        self.error(
                            Diagnostic::error(
                                codes::BAD_ARGUMENT,
                                format!("missing argument `{}` to `{name}`", p.name),
                            )
                            .with_primary(span, format!("`{}` is required", p.name))
                            .with_help(format!("`{name}` takes {}", signature(op))),
                        );
                    }
                    ok = false;
                    self.ir.add(ExprKind::Error, span)
                }
                _ => match operator_default(p) {
                    Ok((kind, ty, unit)) => self.ir.add_typed(kind, ty, unit, span),
                    Err(detail) => {
                        self.internal.get_or_insert(InternalError {
                            message: format!("the stdlib default of `{}` in `{name}` is invalid", p.name),
                            detail,
                            span: Some(span),
                            wgsl: None,
                        });
                        ok = false;
                        self.ir.add(ExprKind::Error, span)
                    }
                },
            };
            args.push(v);
        }
        if !ok {
            return self.ir.add(ExprKind::Error, span);
        }
        self.ir.add(
            ExprKind::Call {
                callee: Callee::Operator(index as u32),
                args,
            },
            span,
        )
    }

    fn is_bound(&self, name: &str) -> bool {
        self.scopes.iter().any(|s| s.iter().any(|(n, _)| n == name)) || self.names.contains_key(name)
    }
}

/// `(x: float, steps: int = 3)` — an operator's signature for help lines.
/// The copy of a target a call selects: `other_eye(t)`, `previous(t)`.
fn target_copy_call(name: &str) -> Option<TargetCopy> {
    match name {
        "other_eye" => Some(TargetCopy::OtherEye),
        "previous" => Some(TargetCopy::Previous),
        _ => None,
    }
}

pub fn signature(op: &stdlib::Operator) -> String {
    let params: Vec<String> = op
        .params
        .iter()
        .map(|p| {
            let ty = match p.ty {
                stdlib::Ty::Enum(v) => v.join("|"),
                t => format!("{t:?}").to_lowercase(),
            };
            match p.default {
                stdlib::Default::Required => format!("{}: {ty}", p.name),
                stdlib::Default::Number(x) => format!("{}: {ty} = {x}", p.name),
                stdlib::Default::Builtin(b) => format!("{}: {ty} = {b}", p.name),
                stdlib::Default::Variant(v) => format!("{}: {ty} = {v}", p.name),
            }
        })
        .collect();
    format!("({})", params.join(", "))
}

/// The node an operator parameter's stdlib default stands for (any default
/// but `Required`). The defaults are stdlib data, not style text: one that
/// names no variant of its enum or no builtin is a bug in npr (E9001), so
/// it is an error here, never a silent fallback (and a test checks that
/// every operator's defaults resolve).
fn operator_default(p: &stdlib::Param) -> Result<(ExprKind, Ty, Unit), String> {
    match p.default {
        stdlib::Default::Required => Err(format!("`{}` has no default", p.name)),
        stdlib::Default::Number(x) => {
            let (ty, c) = match p.ty {
                stdlib::Ty::Int => (Ty::Int, Const::Int(x as i64)),
                stdlib::Ty::Bool => (Ty::Bool, Const::Bool(x != 0.0)),
                _ => (Ty::Float, Const::Float(x)),
            };
            Ok((ExprKind::Const(c), ty, p.unit))
        }
        stdlib::Default::Variant(v) => match p.ty {
            stdlib::Ty::Enum(vs) => match vs.iter().position(|x| *x == v) {
                Some(i) => Ok((ExprKind::Const(Const::Int(i as i64)), Ty::Int, Unit::None)),
                None => Err(format!("`{v}` is not one of its variants {}", vs.join("|"))),
            },
            other => Err(format!("the variant default `{v}` is on a parameter of type {other:?}")),
        },
        stdlib::Default::Builtin(b) => match Builtin::SPELLINGS.iter().find(|(s, _)| *s == b) {
            Some((_, bi)) => {
                let (ty, unit) = bi.ty_unit();
                Ok((ExprKind::Builtin(*bi), ty, unit))
            }
            None => Err(format!("`{b}` is not a builtin")),
        },
    }
}

/// `texture` as a parameter type (`object param lit: texture = image(...)`).
fn is_texture_type(ty: &ast::TypeExpr) -> bool {
    matches!(ty, ast::TypeExpr::Named(id) if id.name == "texture")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn param(ty: stdlib::Ty, default: stdlib::Default) -> stdlib::Param {
        stdlib::Param {
            name: "p",
            ty,
            unit: Unit::None,
            default,
            range: None,
            doc: "",
        }
    }

    #[test]
    fn every_stdlib_default_resolves() {
        for op in stdlib::all() {
            for p in op.params {
                if p.default != stdlib::Default::Required {
                    let r = operator_default(p);
                    assert!(r.is_ok(), "`{}({})`: {:?}", op.name, p.name, r.err());
                }
            }
        }
    }

    #[test]
    fn a_bad_stdlib_default_is_an_error_not_a_fallback() {
        let e = stdlib::Ty::Enum(&["x", "y"]);
        assert_eq!(
            operator_default(&param(e, stdlib::Default::Variant("y"))).map(|(k, ..)| k),
            Ok(ExprKind::Const(Const::Int(1)))
        );
        let err = operator_default(&param(e, stdlib::Default::Variant("z"))).unwrap_err();
        assert!(err.contains("`z` is not one of its variants x|y"), "{err}");
        let err = operator_default(&param(stdlib::Ty::Float, stdlib::Default::Variant("x"))).unwrap_err();
        assert!(err.contains("on a parameter of type Float"), "{err}");
        let err = operator_default(&param(stdlib::Ty::Vec2, stdlib::Default::Builtin("screen_xy"))).unwrap_err();
        assert!(err.contains("`screen_xy` is not a builtin"), "{err}");
        assert_eq!(
            operator_default(&param(stdlib::Ty::Vec2, stdlib::Default::Builtin("screen_uv"))).map(|(k, ..)| k),
            Ok(ExprKind::Builtin(Builtin::ScreenUv))
        );
    }
}
