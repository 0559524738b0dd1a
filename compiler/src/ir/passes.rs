//! Passes in the IR: `PassKind` (each kind's own data), compute values,
//! vertex modifiers, depth, view, outputs, `let`s and `Pass`.

use super::*;

/// What a pass is, with the data only that kind has. Everything every kind
/// has (name, scale, clear, lets, outputs, spans) is on [`Pass`]; a stage
/// that behaves differently per kind matches on this, one arm per kind.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum PassKind {
    /// Draws scene objects.
    Render {
        /// `render(tag)`: the objects drawn; `None` (`render(scene)`) draws all.
        tag: Option<String>,
        /// Whose eye the pass sees the scene through: `view(light)`.
        view: PassView,
        /// `vertex { ... }`: expressions the vertex shader evaluates.
        vertex: VertexModifiers,
        /// `depth: keep` / `depth: test(pass, bias: ...)`.
        depth: PassDepth,
    },
    /// A fullscreen pass over its inputs.
    Image {
        inputs: Vec<PassId>,
        /// `schedule: naive | auto | tiled` in its body: the schedule the
        /// style asks of this pass (`crate::schedule`); `None` leaves it to
        /// `--schedule`, as `schedule: auto` does.
        schedule: Option<PassSchedule>,
    },
    /// A compute pass over a domain, producing per-object values.
    Compute {
        domain: ComputeDomain,
        /// `compute(vertices, tag)`: only objects with the tag; `None` runs over all.
        tag: Option<String>,
        /// `compute(pixels, ids.id)`: the read of the ID target whose pixels
        /// the pass runs over. `Some` exactly for `Pixels` (after a
        /// resolve error, `None` there too; such an IR is never emitted).
        key: Option<ExprId>,
        /// `compute(samples)`: the samples per object and their seed (the
        /// pass's `count:` and `seed:` settings). `Some` exactly for `Samples`.
        samples: Option<npr_abi::manifest::SampleSpec>,
        /// Its per-object values, one slot each, in slot order.
        values: Vec<ObjectValue>,
    },
    /// Wavy strips along the silhouettes and creases of scene objects
    /// (Klein et al. 2000, §5); see `lines`.
    Lines(LinesKind),
}

/// What a compute pass runs over: the manifest's definition, shared.
pub use npr_abi::manifest::ComputeDomain;

/// How a per-object value of a compute pass is made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum ValueRule {
    /// `reduce n: t = sum(v)` (and `min`, `max`) over the elements of each object.
    Reduce(npr_abi::manifest::ReduceOp),
    /// `out n: t = v`: computed once per object.
    Out,
    /// `state n: t = first` with its update `n = v`: kept across frames.
    State,
}

/// One per-object value of a compute pass.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct ObjectValue {
    pub name: String,
    /// Float, Vec2, Vec3 or Vec4 (stored as a `vec4<f32>` slot).
    pub ty: Ty,
    pub rule: ValueRule,
    /// The reduced element value, the `out` value, or the state's update.
    pub value: ExprId,
    /// A state's first value.
    pub first: Option<ExprId>,
    pub span: Span,
    pub name_span: Span,
}

impl ObjectValue {
    /// The expressions this value evaluates.
    pub fn roots(&self) -> Vec<ExprId> {
        std::iter::once(self.value).chain(self.first).collect()
    }
}

impl PassKind {
    /// The kind's name as a style writes it (`render`, `image`).
    pub fn name(&self) -> &'static str {
        match self {
            PassKind::Render { .. } => "render",
            PassKind::Image { .. } => "image",
            PassKind::Compute { .. } => "compute",
            PassKind::Lines(_) => "lines",
        }
    }

    /// Whether the pass runs per object, so that it has the `Object` block
    /// (per-object params, `object.id`, compute passes' per-object values).
    pub fn has_object(&self) -> bool {
        match self {
            PassKind::Render { .. } | PassKind::Compute { .. } => true,
            // Strips of every object are drawn at once: no object per fragment.
            PassKind::Image { .. } | PassKind::Lines(_) => false,
        }
    }

    /// The per-object values of a compute pass (none for other kinds).
    pub fn values(&self) -> &[ObjectValue] {
        match self {
            PassKind::Compute { values, .. } => values,
            PassKind::Render { .. } | PassKind::Image { .. } | PassKind::Lines(_) => &[],
        }
    }

    /// Whether the pass draws scene objects, so that it has geometry
    /// (`needs_geometry` builtins) and per-object data (the group-1 block,
    /// per-object params and textures).
    pub fn draws_objects(&self) -> bool {
        match self {
            PassKind::Render { .. } => true,
            PassKind::Image { .. } | PassKind::Compute { .. } | PassKind::Lines(_) => false,
        }
    }
}

/// `vertex { ... }` of a render pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct VertexModifiers {
    /// `inflate: width`, in px: push each vertex along its screen-space normal.
    pub inflate: Option<ExprId>,
    /// `shadow_warp: k`: the sigmoid warp of light-space x, y (Age of Sail §5,
    /// depth pass); only in `view(light)` passes.
    pub shadow_warp: Option<ExprId>,
}

impl VertexModifiers {
    /// The expressions, in the order the vertex shader evaluates them.
    pub fn roots(&self) -> Vec<ExprId> {
        self.inflate.into_iter().chain(self.shadow_warp).collect()
    }
}

/// What a render pass does with its depth buffer (`depth: ...`).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub enum PassDepth {
    /// Its own, cleared, discarded after the pass (the default).
    #[default]
    Own,
    /// `depth: keep`: stored for later passes' depth tests.
    Keep,
    /// `depth: test(pass, bias: b)`: test against the depth `pass` kept,
    /// or the host's `input(depth)`, without writing it. One of the biases
    /// is non-zero at most.
    Test {
        against: TestedDepth,
        /// `bias: N px`: slope-scaled, by the runner (`DepthBiasState`).
        bias_px: f64,
        /// `bias: b`: in window depth (0 near, 1 far), by the vertex shader.
        bias_depth: f64,
        /// The `depth: test(...)` setting.
        span: Span,
    },
}

/// What `depth: test(name)` names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum TestedDepth {
    /// An earlier render pass with `depth: keep`.
    Pass(PassId),
    /// An `input(depth)` texture: the host's depth, drawn by the runner
    /// through the camera's projection each frame.
    Input(TextureId),
}

impl Pass {
    /// The pass whose kept depth this pass tests against, if any, with the
    /// span of the setting (a test against the host's depth names none).
    pub fn depth_test(&self) -> Option<(PassId, Span)> {
        match self.kind {
            PassKind::Render {
                depth:
                    PassDepth::Test {
                        against: TestedDepth::Pass(pass),
                        span,
                        ..
                    },
                ..
            }
            | PassKind::Lines(LinesKind {
                depth:
                    PassDepth::Test {
                        against: TestedDepth::Pass(pass),
                        span,
                        ..
                    },
                ..
            }) => Some((pass, span)),
            _ => None,
        }
    }

    /// The `input(depth)` texture this pass tests against, if any, with
    /// the span of the setting.
    pub fn input_depth_test(&self) -> Option<(TextureId, Span)> {
        match self.kind {
            PassKind::Render {
                depth:
                    PassDepth::Test {
                        against: TestedDepth::Input(texture),
                        span,
                        ..
                    },
                ..
            }
            | PassKind::Lines(LinesKind {
                depth:
                    PassDepth::Test {
                        against: TestedDepth::Input(texture),
                        span,
                        ..
                    },
                ..
            }) => Some((texture, span)),
            _ => None,
        }
    }

    /// Whether the pass keeps its depth buffer (`depth: keep`).
    pub fn keeps_depth(&self) -> bool {
        matches!(
            self.kind,
            PassKind::Render {
                depth: PassDepth::Keep,
                ..
            }
        )
    }
}

/// An image pass's `schedule:` setting: the schedule it names and where.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct PassSchedule {
    pub schedule: Schedule,
    /// The whole setting, `schedule: tiled`: errors and the report point at it.
    pub span: Span,
}

/// The camera a render pass projects with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub enum PassView {
    /// The scene camera (the eye being rendered, in stereo).
    #[default]
    Camera,
    /// An orthographic camera looking along the light, fitted to the scene
    /// bounds (`Frame::light_view_proj`): for shadow-caster depth maps.
    Light,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassOutput {
    pub name: String,
    pub format: npr_abi::Format,
    pub value: ExprId,
    /// `{ blend: ... }`: how the value combines with the target.
    pub blend: npr_abi::manifest::Blend,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Let {
    pub name: String,
    pub value: ExprId,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Pass {
    pub name: String,
    pub doc: String,
    pub kind: PassKind,
    pub scale: f64,
    pub clear: [f64; 4],
    pub lets: Vec<Let>,
    pub outputs: Vec<PassOutput>,
    pub span: Span,
    pub name_span: Span,
}
