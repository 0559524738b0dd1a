//! Resolve the parts of a `compute` pass: its domain, its per-object values
//! (`reduce`, `out`, `state` and the states' updates), the reads of those
//! values from other passes (`sums.area`), and the statements other kinds
//! do not have.
//!
//! Slots are numbered reductions first, then `out`s, then `state`s, each in
//! source order; the same numbering is declared before any body is resolved
//! (`declared_values`), so a pass may read a compute pass declared after it.

use super::{Resolver, Symbol};
use crate::ir::*;
use npr_abi::manifest::ReduceOp;
use npr_abi::validate::MAX_VALUE_SLOTS;
use npr_diag::diagnostic::did_you_mean;
use npr_diag::{codes, Diagnostic, Span};
use npr_dsl::ast;
use npr_stdlib::Unit;

/// The kind of a compute pass whose domain did not resolve (reported): a
/// pass over objects with no values, so later stages see a well-formed pass.
fn unresolved_kind() -> PassKind {
    PassKind::Compute {
        domain: ComputeDomain::Objects,
        tag: None,
        key: None,
        samples: None,
        values: Vec::new(),
    }
}

/// Samples per object when a `compute(samples)` pass says no `count:`
/// ("typically several hundred", Breslav et al. 2007 §3.1).
pub const DEFAULT_SAMPLES: u32 = 400;

const DOMAIN_HELP: &str = "write `compute(objects)` (once per object), `compute(vertices)` (every vertex of every object, reduced per object), `compute(pixels, ids.id)` (every pixel of an ID target, reduced per object) or `compute(samples)` (stratified points on every object's surface, reduced per object)";

/// The value types a per-object slot (one `vec4<f32>`) can hold.
pub(super) const VALUE_TYPES: [(&str, Ty); 4] = [
    ("float", Ty::Float),
    ("vec2", Ty::Vec2),
    ("vec3", Ty::Vec3),
    ("vec4", Ty::Vec4),
];

/// A per-object value as declared, before its pass body is resolved.
#[derive(Debug, Clone)]
pub(super) struct DeclaredValue {
    pub name: String,
    /// `Ty::Unknown` when the declared type is not a value type (reported
    /// when the owning pass is resolved).
    pub ty: Ty,
}

/// The values a pass declares, in slot order (none unless it is a compute pass).
pub(super) fn declared_values(p: &ast::PassDecl) -> Vec<DeclaredValue> {
    if p.kind.kind.name != "compute" {
        return Vec::new();
    }
    let b = &p.body;
    let reductions = b.reductions.iter().map(|r| (&r.name, &r.ty));
    let outs = b.outputs.iter().map(|o| (&o.name, &o.format));
    let states = b.states.iter().map(|s| (&s.name, &s.ty));
    reductions
        .chain(outs)
        .chain(states)
        .map(|(name, ty)| DeclaredValue {
            name: name.name.clone(),
            ty: value_type(&ty.name).unwrap_or(Ty::Unknown),
        })
        .collect()
}

fn value_type(name: &str) -> Option<Ty> {
    VALUE_TYPES.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

/// The state being resolved in a `compute(objects)` pass: its name, slot,
/// type and where it is declared (a read before that is an error).
#[derive(Debug, Clone)]
pub(super) struct StateInScope {
    pub name: String,
    pub slot: u32,
    pub ty: Ty,
    pub declared_at: Span,
}

impl Resolver<'_> {
    /// `compute(objects)`, `compute(vertices)`, optionally with a tag
    /// (`compute(vertices, boats)`), and `compute(pixels, ids.id)` over the
    /// pixels of an ID target, optionally with a tag after it.
    pub(super) fn compute_kind(&mut self, p: &ast::PassDecl) -> PassKind {
        let domains = [
            ("objects", ComputeDomain::Objects),
            ("vertices", ComputeDomain::Vertices),
            ("pixels", ComputeDomain::Pixels),
            ("samples", ComputeDomain::Samples),
        ];
        let Some((first, rest)) = p.kind.args.split_first() else {
            self.error(
                Diagnostic::error(codes::BAD_PASS_INPUT, "a compute pass needs a domain")
                    .with_primary(p.kind.span, "no domain")
                    .with_help(DOMAIN_HELP),
            );
            return unresolved_kind();
        };
        let Some(domain) = domains.iter().find(|(n, _)| *n == first.name.name).map(|(_, d)| *d) else {
            let mut d = Diagnostic::error(codes::BAD_PASS_INPUT, "a compute pass needs a domain")
                .with_primary(first.span, format!("`{}` is not a compute domain", first.name.name));
            d = match did_you_mean(&first.name.name, domains.iter().map(|(n, _)| *n)) {
                Some(s) => d.with_help(format!("did you mean `{s}`?")),
                None => d.with_help(DOMAIN_HELP),
            };
            self.error(d);
            return unresolved_kind();
        };
        self.no_field(first, "a domain");
        let (key, rest) = match (domain, rest) {
            (ComputeDomain::Pixels, [target, more @ ..]) if target.field.is_some() => {
                (Some(self.id_target(target)), more)
            }
            (ComputeDomain::Pixels, _) => {
                let span = rest.first().map_or(p.kind.span, |a| a.span);
                self.error(
                    Diagnostic::error(
                        codes::BAD_PASS_INPUT,
                        "a pass over pixels needs the ID target it runs over",
                    )
                    .with_primary(span, "expected a pass's target, such as `ids.id`")
                    .with_help(
                        "write `compute(pixels, ids.id)`, where pass `ids` renders `out id: r32float = object.id`",
                    ),
                );
                (None, rest)
            }
            (_, rest) => (None, rest),
        };
        let tag = match rest {
            [] => None,
            [t] => {
                self.no_field(t, "a tag");
                Some(t.name.name.clone())
            }
            [_, extra, ..] => {
                self.error(
                    Diagnostic::error(codes::BAD_PASS_INPUT, "a compute pass runs over one domain and one tag")
                        .with_primary(extra.span, "unexpected")
                        .with_help(
                            "write `compute(vertices)`, `compute(vertices, tag)` or `compute(pixels, ids.id, tag)`",
                        ),
                );
                None
            }
        };
        PassKind::Compute {
            domain,
            tag,
            key: key.flatten(),
            // `count:` and `seed:` settings replace these (`sample_setting`).
            samples: (domain == ComputeDomain::Samples).then_some(npr_abi::manifest::SampleSpec {
                count: DEFAULT_SAMPLES,
                seed: 1,
            }),
            values: Vec::new(),
        }
    }

    /// `count: n` (samples per object) or `seed: n` in a `compute(samples)`
    /// pass: constant integers, since the runner draws the samples once.
    pub(super) fn sample_setting(&mut self, kind: &mut PassKind, s: &ast::Setting) {
        let PassKind::Compute {
            samples: Some(spec), ..
        } = kind
        else {
            self.error(
                Diagnostic::error(
                    codes::BAD_ARGUMENT,
                    format!("`{}` is a setting of passes over samples", s.key.name),
                )
                .with_primary(s.key.span, "not a setting of this pass")
                .with_help("write it in a `compute(samples)` pass: `count: 400` samples per object, `seed: 1`"),
            );
            return;
        };
        let id = self.expr(&s.value);
        let Some(v) = self.const_scalar(id, &format!("`{}`", s.key.name)) else {
            return;
        };
        let (lo, hi) = match s.key.name.as_str() {
            "count" => (1.0, npr_abi::manifest::MAX_SAMPLES_PER_OBJECT as f64),
            _ => (0.0, u32::MAX as f64),
        };
        if v.fract() != 0.0 || !(lo..=hi).contains(&v) {
            self.error(
                Diagnostic::error(
                    codes::OUT_OF_RANGE,
                    format!("`{}` must be a whole number in {lo}..={hi}", s.key.name),
                )
                .with_primary(s.value.span, format!("this is {v}"))
                .with_help("the runner draws this many stratified samples per object once, when it loads the scene"),
            );
            return;
        }
        match s.key.name.as_str() {
            "count" => spec.count = v as u32,
            _ => spec.seed = v as u32,
        }
    }

    /// The ID target of `compute(pixels, ids.id)`, resolved as the read
    /// `ids.id` would be in the pass body (so unknown passes and targets get
    /// the usual diagnostics; the typechecker checks its format).
    fn id_target(&mut self, arg: &ast::KindArg) -> Option<ExprId> {
        let field = arg.field.clone()?;
        let read = ast::Expr {
            kind: ast::ExprKind::Field {
                base: Box::new(ast::Expr {
                    kind: ast::ExprKind::Name(arg.name.clone()),
                    span: arg.name.span,
                }),
                field,
            },
            span: arg.span,
        };
        Some(self.expr(&read))
    }

    /// Before the lets of a `compute(objects)` pass: its states, so that
    /// names resolve to their previous values.
    pub(super) fn states_in_scope(&mut self, id: PassId, p: &ast::PassDecl) {
        let declared = &self.pass_values[id.0 as usize];
        let first_state = p.body.reductions.len() + p.body.outputs.len();
        self.states = p
            .body
            .states
            .iter()
            .enumerate()
            .map(|(i, s)| StateInScope {
                name: s.name.name.clone(),
                slot: (first_state + i) as u32,
                ty: declared.get(first_state + i).map_or(Ty::Unknown, |v| v.ty),
                declared_at: s.name.span,
            })
            .collect();
    }

    /// A name that is a state of the pass being resolved: its previous
    /// value (or its first value on the first frame).
    pub(super) fn state_read(&mut self, id: &ast::Ident) -> Option<ExprId> {
        let s = self.states.iter().find(|s| s.name == id.name)?.clone();
        if id.span.file == s.declared_at.file && id.span.start < s.declared_at.start {
            self.error(
                Diagnostic::error(
                    codes::STATE_ORDER,
                    format!("state `{}` is read before it is declared", id.name),
                )
                .with_primary(id.span, "read here")
                .with_secondary(s.declared_at, "declared here")
                .with_help(format!("move `state {}: ...` above its first use", id.name)),
            );
            return Some(self.ir.add(ExprKind::Error, id.span));
        }
        Some(
            self.ir
                .add_typed(ExprKind::StateOld { slot: s.slot }, s.ty, Unit::None, id.span),
        )
    }

    /// `pass.value` of a compute pass, read per object.
    pub(super) fn value_of(&mut self, pass: PassId, field: &ast::Ident, span: Span) -> ExprId {
        let declared = &self.pass_values[pass.0 as usize];
        let Some(slot) = declared.iter().position(|v| v.name == field.name) else {
            let names: Vec<String> = declared.iter().map(|v| v.name.clone()).collect();
            let mut d = Diagnostic::error(
                codes::UNKNOWN_NAME,
                format!(
                    "compute pass `{}` has no value `{}`",
                    self.ir.pass(pass).name,
                    field.name
                ),
            )
            .with_primary(field.span, "unknown value");
            d = match did_you_mean(&field.name, names.iter().map(String::as_str)) {
                Some(s) => d.with_help(format!("did you mean `{s}`?")),
                None => d.with_help(format!("its values are: {}", names.join(", "))),
            };
            self.error(d);
            return self.ir.add(ExprKind::Error, span);
        };
        let ty = declared[slot].ty;
        if !self.has_object {
            let pass_name = self.ir.pass(pass).name.clone();
            self.error(
                Diagnostic::error(
                    codes::BAD_PASS_INPUT,
                    format!("`{pass_name}.{}` is a per-object value, read outside a pass that has an object", field.name),
                )
                .with_primary(span, "no object is being drawn or computed here")
                .with_help(
                    "read it in a `render(...)` or `compute(...)` pass, write what you need to a target, and read that target here",
                ),
            );
            return self.ir.add(ExprKind::Error, span);
        }
        self.ir.add_typed(
            ExprKind::ObjectValue {
                pass,
                slot: slot as u32,
            },
            ty,
            Unit::None,
            span,
        )
    }

    /// The values of a compute pass, after its lets are resolved.
    pub(super) fn compute_values(&mut self, domain: ComputeDomain, p: &ast::PassDecl) -> Vec<ObjectValue> {
        let b = &p.body;
        let mut values = Vec::new();
        for r in &b.reductions {
            let op = ReduceOp::ALL.iter().find(|(n, _)| *n == r.op.name).map(|(_, o)| *o);
            let op = match op {
                Some(op) => op,
                None => {
                    let mut d = Diagnostic::error(codes::BAD_ARGUMENT, format!("`{}` is not a reduction", r.op.name))
                        .with_primary(r.op.span, "not `sum`, `min` or `max`");
                    d = match did_you_mean(&r.op.name, ReduceOp::ALL.iter().map(|(n, _)| *n)) {
                        Some(s) => d.with_help(format!("did you mean `{s}`?")),
                        None => d.with_help("reductions are `sum(v)`, `min(v)` and `max(v)`, per object"),
                    };
                    self.error(d);
                    ReduceOp::Sum
                }
            };
            if domain == ComputeDomain::Objects {
                self.wrong_statement(
                    r.span,
                    "`reduce`",
                    "a `compute(objects)` pass",
                    "reductions run over elements: write `compute(vertices)` or `compute(pixels, ids.id)`, or compute the value with `out` here",
                );
            }
            let value = self.expr(&r.value);
            values.push(self.object_value(&r.name, &r.ty, ValueRule::Reduce(op), value, None, r.span));
        }
        for o in &b.outputs {
            if domain.has_elements() {
                self.wrong_statement(o.span, "`out`", &format!("a `compute({})` pass", domain.name()), "a pass over elements makes per-object values with `reduce name: type = sum(value)`; compute per-object values from them in a `compute(objects)` pass");
            }
            let value = self.expr(&o.value);
            values.push(self.object_value(&o.name, &o.format, ValueRule::Out, value, None, o.span));
        }
        for s in &b.states {
            if domain.has_elements() {
                self.wrong_statement(
                    s.span,
                    "`state`",
                    &format!("a `compute({})` pass", domain.name()),
                    "state is kept per object: declare it in a `compute(objects)` pass",
                );
            }
            // The first value may not read the state itself.
            let saved = std::mem::take(&mut self.states);
            let first = self.expr(&s.first);
            self.states = saved;
            let updates: Vec<&ast::StateUpdate> = b.updates.iter().filter(|u| u.name.name == s.name.name).collect();
            let value = match updates.as_slice() {
                [u] => self.expr(&u.value),
                [] => {
                    self.error(
                        Diagnostic::error(codes::STATE_ORDER, format!("state `{}` is never updated", s.name.name))
                            .with_primary(s.name.span, "declared here")
                            .with_help(format!(
                                "give its new value each frame with `{} = ...`; a value that never changes is a `param`",
                                s.name.name
                            )),
                    );
                    self.ir.add(ExprKind::Error, s.span)
                }
                [first_update, again, ..] => {
                    self.error(
                        Diagnostic::error(codes::STATE_ORDER, format!("state `{}` is updated twice", s.name.name))
                            .with_primary(again.span, "updated again here")
                            .with_secondary(first_update.span, "first update")
                            .with_help("a state has one new value per frame; combine the two with `if`"),
                    );
                    self.ir.add(ExprKind::Error, s.span)
                }
            };
            values.push(self.object_value(&s.name, &s.ty, ValueRule::State, value, Some(first), s.span));
        }
        if values.len() > MAX_VALUE_SLOTS {
            self.error(
                Diagnostic::error(codes::LIMIT_EXCEEDED, "too many per-object values in one compute pass")
                    .with_primary(values[MAX_VALUE_SLOTS].name_span, "one too many")
                    .with_help(format!(
                        "a compute pass may make at most {MAX_VALUE_SLOTS} values; split it into two passes"
                    )),
            );
        }
        for u in &b.updates {
            if !b.states.iter().any(|s| s.name.name == u.name.name) {
                let names: Vec<&str> = b.states.iter().map(|s| s.name.name.as_str()).collect();
                let mut d = Diagnostic::error(
                    codes::STATE_ORDER,
                    format!("`{}` is not a state of this pass", u.name.name),
                )
                .with_primary(u.name.span, "assigned here");
                d = match did_you_mean(&u.name.name, names.iter().copied()) {
                    Some(s) => d.with_help(format!("did you mean `{s}`?")),
                    None => d.with_help(format!("declare it first: `state {}: vec2 = ...`", u.name.name)),
                };
                self.error(d);
                self.expr(&u.value);
            }
        }
        values
    }

    fn object_value(
        &mut self,
        name: &ast::Ident,
        ty: &ast::Ident,
        rule: ValueRule,
        value: ExprId,
        first: Option<ExprId>,
        span: Span,
    ) -> ObjectValue {
        let ty = match value_type(&ty.name) {
            Some(t) => t,
            None => {
                let mut d = Diagnostic::error(
                    codes::BAD_VALUE_TYPE,
                    format!("a per-object value cannot be of type `{}`", ty.name),
                )
                .with_primary(ty.span, "not float, vec2, vec3 or vec4");
                d = match did_you_mean(&ty.name, VALUE_TYPES.iter().map(|(n, _)| *n)) {
                    Some(s) => d.with_help(format!("did you mean `{s}`?")),
                    None => d.with_help(
                        "per-object values are float, vec2, vec3 or vec4 (an int or a bool is summed as a float: write `if c { 1.0 } else { 0.0 }`)",
                    ),
                };
                self.error(d);
                Ty::Unknown
            }
        };
        ObjectValue {
            name: name.name.clone(),
            ty,
            rule,
            value,
            first,
            span,
            name_span: name.span,
        }
    }

    /// Statements of compute passes outside one, and of the other domain.
    pub(super) fn wrong_statement(&mut self, span: Span, what: &str, place: &str, help: &str) {
        self.error(
            Diagnostic::error(codes::BAD_STATEMENT, format!("{what} has no meaning in {place}"))
                .with_primary(span, "not in this kind of pass")
                .with_help(help.to_string()),
        );
    }

    /// `state`, `reduce` and updates in a render or image pass.
    pub(super) fn refuse_compute_statements(&mut self, p: &ast::PassDecl) {
        let kind = format!("a `{}` pass", p.kind.kind.name);
        for s in &p.body.states {
            self.wrong_statement(s.span, "`state`", &kind, "state lives in `compute(objects)` passes");
        }
        for r in &p.body.reductions {
            self.wrong_statement(
                r.span,
                "`reduce`",
                &kind,
                "reductions live in `compute(vertices)` passes",
            );
        }
        for u in &p.body.updates {
            self.wrong_statement(
                u.span,
                "an assignment",
                &kind,
                "`name = value` updates a `state` of a `compute(objects)` pass; use `let` for a local value",
            );
        }
    }

    /// Whether `name` is a compute pass (for `field`).
    pub(super) fn is_compute_pass(&self, name: &str) -> Option<PassId> {
        match self.names.get(name) {
            Some((Symbol::Pass(p), _)) if self.compute_passes.contains(p) => Some(*p),
            _ => None,
        }
    }

    /// Two values of one pass with the same name.
    pub(super) fn check_value_names(&mut self, values: &[ObjectValue]) {
        for (i, v) in values.iter().enumerate() {
            if let Some(prev) = values[..i].iter().find(|w| w.name == v.name) {
                self.error(
                    Diagnostic::error(codes::DUPLICATE_NAME, format!("value `{}` is declared twice", v.name))
                        .with_primary(v.name_span, "declared again here")
                        .with_secondary(prev.name_span, "first declared here")
                        .with_help("rename one of them"),
                );
            }
        }
    }
}
