//! Typecheck what depends on the pass kind: which builtins a kind has, and
//! the per-object values of compute passes (their types, what they may read).

use super::Checker;
use crate::ir::*;
use npr_diag::{codes, Diagnostic, Span};
use std::collections::BTreeSet;

impl Checker<'_> {
    /// A builtin read in a pass of `kind`: refused where the kind does not have it.
    pub(super) fn builtin_in_kind(&mut self, b: Builtin, kind: &PassKind, span: Span) {
        let over_samples = matches!(
            kind,
            PassKind::Compute {
                domain: ComputeDomain::Samples,
                ..
            }
        );
        let refusal = match kind {
            PassKind::Lines(_) if b.needs_geometry() => Some((
                "no surface in a lines pass",
                "a lines pass's fragments lie on strips, not on a surface: they have `line.s`, `line.across`, `frag_coord`, `screen_uv`, the frame values and earlier passes' targets at this pixel",
            )),
            PassKind::Lines(_) if b.needs_object() => Some((
                "no object in a lines pass",
                "a lines pass draws every object's strips at once; tag the objects and use one lines pass per tag",
            )),
            PassKind::Lines(_) => None,
            _ if b.is_line_value() => Some((
                "only in `lines` passes",
                "`line.s` and `line.across` are values of a lines pass's strips",
            )),
            _ if b == Builtin::SampleSpacing && !over_samples => Some((
                "only in `compute(samples)` passes",
                "the sample spacing is an element value of passes over samples; pass what others need through a per-object value",
            )),
            _ if b == Builtin::PatchWeight && !matches!(kind, PassKind::Render { .. }) => Some((
                "only in `render` passes",
                "a patch's blending weight (Breslav et al. 2007 §3.6) exists where a render pass draws the patch over its n-ring; a compute pass sees each patch's own faces only",
            )),
            PassKind::Render { .. } if b == Builtin::PositionPrevious => Some((
                "only in `compute(vertices)` passes",
                "the previous position is an element value of compute passes; pass what a render pass needs through a per-object value",
            )),
            PassKind::Render { .. } => None,
            PassKind::Image { .. } if b.needs_geometry() => Some((
                "no geometry in an image pass",
                match b {
                    Builtin::Depth | Builtin::PositionView | Builtin::PositionWorld | Builtin::ViewDir => "declare the host's depth, `texture d = input(depth)`, to read `depth`, `position.view`, `position.world` and `view_dir` here; or write it to a target in a render pass and read that target here",
                    Builtin::NormalView => "declare the host's normals, `texture n = input(normal, view)`, to read `normal.view` here; or write it to a target in a render pass and read that target here",
                    Builtin::NormalWorld => "declare the host's normals, `texture n = input(normal, world)`, to read `normal` here; or write it to a target in a render pass and read that target here",
                    _ => "write it to a target in a render pass and read that target here",
                },
            )),
            PassKind::Image { .. } if b.needs_object() => Some((
                "no object in an image pass",
                "write `object.id` to a target in a render pass (an ID image) and read that target here",
            )),
            PassKind::Image { .. } => None,
            PassKind::Compute {
                domain: ComputeDomain::Pixels,
                ..
            } if b.is_per_fragment() && !b.in_pixel_elements() => Some((
                "no geometry in a pass over pixels",
                "write it to a target in a render pass and read that target here: a pass over pixels has `frag_coord`, `screen_uv`, the pixel's `object` and the frame values",
            )),
            PassKind::Compute {
                domain: ComputeDomain::Vertices | ComputeDomain::Samples,
                ..
            } if !b.in_vertex_elements() && b != Builtin::SampleSpacing => Some((
                "not a value of a vertex",
                "a pass over vertices has each vertex's `position`, `position.previous`, `normal`, `uv` and the frame values",
            )),
            PassKind::Compute {
                domain: ComputeDomain::Objects,
                ..
            } if b.is_per_fragment() => Some((
                "no geometry in a pass over objects",
                "reduce what you need over `compute(vertices)` and read its per-object values here",
            )),
            PassKind::Compute { .. } => None,
        };
        if let Some((label, help)) = refusal {
            self.err(
                Diagnostic::error(
                    codes::BAD_PASS_INPUT,
                    format!("`{}` is not available in a `{}` pass", b.name(), kind.name()),
                )
                .with_primary(span, label)
                .with_help(help),
            );
        }
    }

    /// W0302: a render pass that reads `patch.weight` draws each patch over
    /// its n-ring too (Breslav et al. 2007 §3.6), where the patches overlap
    /// on the same surface. Only a depth test against the depth an earlier
    /// pass kept makes those copies blend on the front surface alone: with
    /// the pass's own depth buffer a farther surface drawn first stays in
    /// the blend, and a ring drawn after its neighbour's own faces at the
    /// same depth may fail the test. `span` is the first `patch.weight` read.
    pub(super) fn patch_weight_occlusion(&mut self, pass: &Pass, span: Span) {
        let PassKind::Render { depth, .. } = &pass.kind else {
            return;
        };
        let setting = match depth {
            PassDepth::Test { .. } => return,
            PassDepth::Own => "its own depth buffer",
            PassDepth::Keep => "`depth: keep` (its own depth buffer, kept)",
        };
        self.err(
            Diagnostic::warning(
                codes::PATCH_BLEND_UNOCCLUDED,
                format!(
                    "pass `{}` blends patches over their n-rings without a depth test against an earlier pass",
                    pass.name
                ),
            )
            .with_primary(span, "each patch is drawn over its n-ring here, overlapping its neighbours")
            .with_secondary(pass.name_span, format!("this pass tests against {setting} only"))
            .with_help(
                "draw the objects first in a pass with `depth: keep` (an ID pass) and add `depth: test(<that pass>)` to this one, so that the overlapping copies blend on the front surface only",
            ),
        );
    }

    /// The values of compute pass `pi`: each evaluates to its declared type
    /// (an int converts to float; reductions sum float vectors only), and
    /// reads targets and textures only as operator arguments (a compute
    /// invocation has no pixel to read a value at).
    pub(super) fn compute_values(&mut self, pi: usize) {
        let PassKind::Compute {
            values, domain, key, ..
        } = &self.ir.passes[pi].kind
        else {
            return;
        };
        let (values, domain, key) = (values.clone(), *domain, *key);
        if let Some(key) = key {
            self.id_target(key);
        }
        let mut checked = values.clone();
        for (v, out) in values.iter().zip(checked.iter_mut()) {
            if v.ty == Ty::Unknown {
                continue;
            }
            out.value = self.value_of_type(v.value, v, "its value");
            if let Some(first) = v.first {
                out.first = Some(self.value_of_type(first, v, "its first value"));
                self.first_reads_no_state(first, v);
            }
        }
        if domain != ComputeDomain::Pixels {
            self.no_pixel_reads(&checked);
        } else {
            self.no_texture_values(&checked);
        }
        if let PassKind::Compute { values, .. } = &mut self.ir.passes[pi].kind {
            *values = checked;
        }
    }

    /// `id` brought to `v.ty`, or reported.
    fn value_of_type(&mut self, id: ExprId, v: &ObjectValue, what: &str) -> ExprId {
        if self.is_error(id) {
            return id;
        }
        if let Some(c) = self.coerce(id, v.ty) {
            return c;
        }
        let found = self.vt(id);
        let (code, message) = match v.rule {
            ValueRule::Reduce(op) if !found.is_numeric() => (
                codes::BAD_VALUE_TYPE,
                format!("cannot take the {} of {} over elements", op.name(), found.describe()),
            ),
            _ => (
                codes::TYPE_MISMATCH,
                format!(
                    "{what} is {}, but `{}` is {}",
                    found.describe(),
                    v.name,
                    v.ty.describe()
                ),
            ),
        };
        self.err(
            Diagnostic::error(code, message)
                .with_primary(self.ir.expr(id).span, format!("this is {}", found.describe()))
                .with_secondary(v.name_span, format!("`{}` is declared {}", v.name, v.ty.describe()))
                .with_help(match found {
                    Ty::Bool => "count a condition with `if c { 1.0 } else { 0.0 }`".to_string(),
                    _ => format!("give `{}` the type of its value, or convert the value", v.name),
                }),
        );
        id
    }

    /// A state's first value is what it holds before any frame wrote it,
    /// so it cannot depend on a state (through a `let`, say).
    fn first_reads_no_state(&mut self, first: ExprId, v: &ObjectValue) {
        let read = self
            .ir
            .reachable(&[first])
            .into_iter()
            .find(|n| matches!(self.ir.expr(*n).kind, ExprKind::StateOld { .. }));
        if let Some(n) = read {
            self.err(
                Diagnostic::error(
                    codes::STATE_ORDER,
                    format!("the first value of state `{}` reads a state", v.name),
                )
                .with_primary(
                    self.ir.expr(n).span,
                    "a state, which has no value before the first frame",
                )
                .with_secondary(v.name_span, "this state's first value")
                .with_help("compute the first value from per-object values, params and frame values only"),
            );
        }
    }

    /// The ID target of a pass over pixels holds `object.id` exactly: one
    /// `r32float` channel (integers up to 2²⁴ are exact in f32; a unorm
    /// or half-float target would round them).
    fn id_target(&mut self, key: ExprId) {
        let e = self.ir.expr(key);
        let ExprKind::Target { target, .. } = e.kind else {
            // Resolve reported what `ids.id` named if it is not a target.
            return;
        };
        let format = self.ir.pass(target.pass).outputs[target.output as usize].format;
        if format != npr_abi::Format::R32float {
            let name = self.ir.target_name(target);
            let written = self.ir.pass(target.pass).outputs[target.output as usize].value;
            let written = self.ir.expr(written).span;
            self.err(
                Diagnostic::error(
                    codes::BAD_ID_TARGET,
                    format!(
                        "a pass over pixels needs an ID target, but `{name}` is {}",
                        format.name()
                    ),
                )
                .with_primary(e.span, "not an r32float target")
                .with_secondary(written, format!("written as {} here", format.name()))
                .with_help("declare it `out id: r32float = object.id`: only r32float holds every object ID exactly"),
            );
        }
    }

    /// In a pass over pixels a target is read at the pixel, as in an image
    /// pass; a texture read as a value still needs a uv the pass does not have.
    fn no_texture_values(&mut self, values: &[ObjectValue]) {
        let roots: Vec<ExprId> = values.iter().flat_map(ObjectValue::roots).collect();
        let handles = self.operator_handles(&roots);
        for n in self.ir.reachable(&roots) {
            let e = self.ir.expr(n);
            if matches!(e.kind, ExprKind::Texture(_)) && !handles.contains(&n) {
                let span = e.span;
                self.err(
                    Diagnostic::error(codes::BAD_PASS_INPUT, "a texture read as a value in a compute pass")
                        .with_primary(span, "a pass over pixels has no uv to sample it at")
                        .with_help("pass it to an operator that reads it at a position you give"),
                );
            }
        }
    }

    /// The nodes passed to operators as texture handles.
    fn operator_handles(&self, roots: &[ExprId]) -> BTreeSet<ExprId> {
        let mut handles: BTreeSet<ExprId> = BTreeSet::new();
        for n in self.ir.reachable(roots) {
            if let ExprKind::Call {
                callee: Callee::Operator(i),
                args,
            } = &self.ir.expr(n).kind
            {
                for (p, a) in npr_stdlib::all()[*i as usize].params.iter().zip(args) {
                    if matches!(p.ty, npr_stdlib::Ty::Texture | npr_stdlib::Ty::SampledTexture) {
                        handles.insert(*a);
                    }
                }
            }
        }
        handles
    }

    fn no_pixel_reads(&mut self, values: &[ObjectValue]) {
        let roots: Vec<ExprId> = values.iter().flat_map(ObjectValue::roots).collect();
        let nodes = self.ir.reachable(&roots);
        let handles = self.operator_handles(&roots);
        for n in nodes {
            let e = self.ir.expr(n);
            let what = match e.kind {
                ExprKind::Target { .. } => "a target",
                ExprKind::Texture(_) => "a texture",
                _ => continue,
            };
            if handles.contains(&n) {
                continue;
            }
            let span = e.span;
            self.err(
                Diagnostic::error(
                    codes::BAD_PASS_INPUT,
                    format!("{what} read as a value in a compute pass"),
                )
                .with_primary(span, "a compute invocation has no pixel or uv to read it at")
                .with_help(
                    "pass it to an operator that reads it at a position you give; a `compute(pixels, ids.id)` pass reads targets at its pixels",
                ),
            );
        }
    }
}
