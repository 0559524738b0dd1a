//! What one pass reads: builtins, targets (this frame's, the other eye's, the
//! previous frame's),
//! textures, parameter blocks, operators, and whether a texture or a target
//! is read as a value. Kind-independent: the per-kind files decide what the
//! uses mean (attributes, the frame block, group 1).

use super::Emitter;
use crate::ir::*;
use npr_abi::manifest::ParamBinding;
use std::collections::{BTreeMap, BTreeSet};

/// Everything a pass's shaders read, collected from its live expressions.
#[derive(Debug, Default)]
pub(super) struct Uses {
    pub builtins: BTreeSet<Builtin>,
    /// Targets read, by copy: this frame's, the other eye's, the previous frame's.
    pub targets: BTreeSet<(TargetCopy, TargetRef)>,
    pub textures: BTreeSet<TextureId>,
    /// `project()` / `project_other_eye()`.
    pub project: bool,
    /// A style-uniform parameter (the `Params` block).
    pub style_params: bool,
    /// The live gradients `ramp` reads (`helpers::ramp_helper`).
    pub ramps: BTreeSet<ParamId>,
    /// `50%`: needs `frame.resolution`.
    pub percent: bool,
    /// Stdlib operators called directly (their dependencies come later).
    pub operators: BTreeSet<usize>,
    /// A target passed as a `SampledTexture`: needs the linear clamp sampler.
    pub linear_sampler: bool,
    /// A texture read as a value (sampled at the kind's texture coordinate).
    pub texture_as_value: bool,
    /// Compute passes whose per-object values are read.
    pub object_values: BTreeSet<PassId>,
    /// How many times each fragment node is read as a value (see
    /// `Emitter::value_uses`); `emit_lets` shares target loads by it.
    pub value_uses: BTreeMap<ExprId, usize>,
    /// Formats whose stored value a fused read repeats (`npr_stored_*`).
    pub stored: Vec<npr_abi::Format>,
    /// The vector `if`s whose condition is built from constants alone: each
    /// `select` takes its condition through `npr_runtime_bool` (see
    /// `needs_runtime_condition`, `helpers::RUNTIME_BOOL_HELPER`).
    pub runtime_conditions: BTreeSet<ExprId>,
}

impl Uses {
    /// Whether a fused read repeats a 16-bit float store: the pass declares
    /// `npr_abi::formats::HALF_ROUNDING_OVERRIDE`, which the runner sets.
    pub fn repeats_half_stores(&self) -> bool {
        self.stored
            .iter()
            .any(|f| f.storage() == npr_abi::formats::Storage::Half)
    }

    /// Whether an expression reads the `Frame` block: any builtin other
    /// than the varyings and the pixel position, `%`, or a projection.
    pub fn expressions_read_frame(&self) -> bool {
        let frame_builtin = self.builtins.iter().any(|b| {
            !matches!(
                b,
                Builtin::Uv
                    | Builtin::NormalWorld
                    | Builtin::PositionWorld
                    | Builtin::PositionPrevious
                    | Builtin::Tangent
                    | Builtin::FragCoord
                    | Builtin::ScreenUv
                    | Builtin::ObjectIndex
                    | Builtin::ObjectId
                    | Builtin::PatchWeight
            )
        });
        frame_builtin || self.percent || self.project
    }

    /// Adds what another function of the same module reads (a producer
    /// computed in this pass's tiles, `emit/tiled`), so the module declares
    /// and defines it. `value_uses` stays this pass's: it names the lets of
    /// one function.
    pub fn absorb(&mut self, other: Uses) {
        self.builtins.extend(other.builtins);
        self.targets.extend(other.targets);
        self.textures.extend(other.textures);
        self.project |= other.project;
        self.style_params |= other.style_params;
        self.ramps.extend(other.ramps);
        self.percent |= other.percent;
        self.operators.extend(other.operators);
        self.linear_sampler |= other.linear_sampler;
        self.texture_as_value |= other.texture_as_value;
        self.object_values.extend(other.object_values);
        for f in other.stored {
            self.store(f);
        }
        self.runtime_conditions.extend(other.runtime_conditions);
    }

    /// Records that the module repeats a `format` store (its `npr_stored_*`
    /// helper), for the formats that round.
    pub fn store(&mut self, format: npr_abi::Format) {
        let rounds = matches!(
            format.storage(),
            npr_abi::formats::Storage::Half | npr_abi::formats::Storage::Unorm8
        );
        if rounds && !self.stored.contains(&format) {
            self.stored.push(format);
        }
    }

    /// Whether any target is read as a value or a handle (`npr_load` is needed
    /// only for values, but the helper has always come with any target read).
    pub fn reads_targets(&self) -> bool {
        !self.targets.is_empty()
    }
}

impl Emitter<'_> {
    /// The uses of a pass whose fragment shader evaluates `frag_nodes` (for
    /// the outputs `frag_roots`) and whose vertex shader evaluates `vert_nodes`.
    pub(super) fn uses(&self, frag_nodes: &[ExprId], frag_roots: &[ExprId], vert_nodes: &[ExprId]) -> Uses {
        let mut u = Uses::default();
        for id in frag_nodes.iter().chain(vert_nodes) {
            match &self.ir.expr(*id).kind {
                ExprKind::Builtin(b) => {
                    u.builtins.insert(*b);
                }
                ExprKind::Target { target, copy } => {
                    u.targets.insert((*copy, *target));
                }
                ExprKind::Texture(t) => {
                    u.textures.insert(*t);
                }
                ExprKind::Call {
                    callee:
                        Callee::Intrinsic(Intrinsic::Project | Intrinsic::ProjectOtherEye | Intrinsic::ProjectPrevious),
                    ..
                } => u.project = true,
                ExprKind::ObjectValue { pass, .. } => {
                    u.object_values.insert(*pass);
                }
                ExprKind::Param(p) if self.bindings[p.0 as usize] == ParamBinding::Uniform => {
                    u.style_params = true;
                }
                ExprKind::Call {
                    callee: Callee::Intrinsic(Intrinsic::Ramp(g)),
                    ..
                } => {
                    u.style_params = true;
                    u.ramps.insert(*g);
                }
                ExprKind::PercentOfHeight(_) => u.percent = true,
                ExprKind::Select { cond, .. } if self.needs_runtime_condition(*id, *cond) => {
                    u.runtime_conditions.insert(*id);
                }
                ExprKind::Convert {
                    conversion: Conversion::Stored(f),
                    ..
                } if !u.stored.contains(f) => u.stored.push(*f),
                ExprKind::Call {
                    callee: Callee::Operator(i),
                    args,
                } => {
                    u.operators.insert(*i as usize);
                    let op = &npr_stdlib::all()[*i as usize];
                    for (p, a) in op.params.iter().zip(args) {
                        if p.ty == npr_stdlib::Ty::SampledTexture && self.ir.expr(*a).kind.any_target_read().is_some() {
                            u.linear_sampler = true;
                        }
                    }
                }
                _ => {}
            }
        }
        // A texture is a value unless every use is a texture parameter of an
        // operator; an output written straight from it reads it too.
        u.value_uses = self.value_uses(frag_nodes, frag_roots);
        u.texture_as_value = frag_nodes
            .iter()
            .any(|id| matches!(self.ir.expr(*id).kind, ExprKind::Texture(_)) && u.value_uses.contains_key(id));
        u
    }

    /// Whether the `select` of node `select` must not be a WGSL
    /// const-expression: a vector result and a condition made of constants
    /// alone (our folding could not evaluate it, e.g. `cos` of a constant).
    /// naga 30 evaluates such a `select` at parse time and panics
    /// (`unreachable!` in `constant_evaluator.rs`) when an operand is a
    /// vector built from a nested vector, `vec3(1.1, v2)`: soak case
    /// 272687 (docs/FUZZING.md).
    fn needs_runtime_condition(&self, select: ExprId, cond: ExprId) -> bool {
        let vector = !matches!(self.ir.expr(select).ty, Ty::Float | Ty::Int | Ty::Bool);
        vector
            && self.ir.reachable(&[cond]).iter().all(|n| {
                let operands = self.ir.operands(*n);
                !operands.is_empty() || matches!(self.ir.expr(*n).kind, ExprKind::Const(_))
            })
    }

    /// How many times each node is read as a value by `nodes` and `roots`
    /// (a node passed as an operator's texture parameter is a handle there,
    /// not a value read).
    pub(super) fn value_uses(&self, nodes: &[ExprId], roots: &[ExprId]) -> BTreeMap<ExprId, usize> {
        let mut uses: BTreeMap<ExprId, usize> = BTreeMap::new();
        for n in nodes {
            match &self.ir.expr(*n).kind {
                ExprKind::Call {
                    callee: Callee::Operator(i),
                    args,
                } => {
                    let op = &npr_stdlib::all()[*i as usize];
                    for (p, a) in op.params.iter().zip(args) {
                        if !matches!(p.ty, npr_stdlib::Ty::Texture | npr_stdlib::Ty::SampledTexture) {
                            *uses.entry(*a).or_default() += 1;
                        }
                    }
                }
                _ => {
                    for o in self.ir.operands(*n) {
                        *uses.entry(o).or_default() += 1;
                    }
                }
            }
        }
        for r in roots {
            *uses.entry(*r).or_default() += 1;
        }
        uses
    }
}
