//! The shared expression emitter: WGSL for an IR node in value context, and
//! for handles (targets and textures passed to operators). It is the same
//! for every pass kind; the few things a kind decides (where a texture read
//! as a value is sampled) come from [`KindCtx`], chosen once per pass.

use super::{Emitter, PassCtx};
use crate::ir::*;
use npr_abi::manifest::ParamBinding;

/// What the expression emitter needs to know about the kind of the pass it
/// emits for. Decided in one place, [`KindCtx::of`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum KindCtx {
    /// Fragments of scene objects: textures are sampled at the mesh's `uv`.
    Render,
    /// Fullscreen fragments: textures are sampled at `screen_uv`.
    Image,
    /// Compute invocations: no texture is read as a value (the typechecker
    /// refuses it), only passed to operators.
    Compute,
    /// Fragments of strips: textures are sampled at `screen_uv`, as in image passes.
    Lines,
}

impl KindCtx {
    pub fn of(kind: &PassKind) -> KindCtx {
        match kind {
            PassKind::Render { .. } => KindCtx::Render,
            PassKind::Image { .. } => KindCtx::Image,
            PassKind::Compute { .. } => KindCtx::Compute,
            PassKind::Lines(_) => KindCtx::Lines,
        }
    }

    /// Where a texture read as a value is sampled.
    pub fn texture_uv(self) -> &'static str {
        match self {
            KindCtx::Render => "in.uv",
            KindCtx::Image | KindCtx::Lines => "in.screen_uv",
            KindCtx::Compute => "vec2<f32>(0.0) /* refused by the typechecker */",
        }
    }
}

impl Emitter<'_> {
    /// WGSL for a node in value context.
    pub(super) fn expr(&self, id: ExprId, ctx: &PassCtx) -> String {
        if let Some(n) = ctx.named.get(&id) {
            return n.clone();
        }
        let e = self.ir.expr(id);
        match &e.kind {
            ExprKind::Const(c) => const_wgsl(c, e.ty),
            ExprKind::PercentOfHeight(f) => format!("({} * frame.resolution.y)", fmt_f32(*f)),
            ExprKind::Param(p) => {
                let param = &self.ir.params[p.0 as usize];
                let block = if self.bindings[p.0 as usize] == ParamBinding::PerObject {
                    "object"
                } else {
                    "params"
                };
                let slot = format!("{block}.p_{}", param.name);
                match e.ty {
                    Ty::Int => format!("i32({slot}.x)"),
                    Ty::Bool => format!("({slot}.x > 0.5)"),
                    Ty::Float => format!("{slot}.x"),
                    Ty::Vec2 => format!("{slot}.xy"),
                    Ty::Vec3 => format!("{slot}.xyz"),
                    _ => slot,
                }
            }
            ExprKind::Builtin(b) => builtin_wgsl(*b),
            ExprKind::Target { target, copy } => {
                let name = ctx
                    .target_names
                    .get(&(*copy, *target))
                    .cloned()
                    .unwrap_or_else(|| "t_missing".into());
                let n = crate::front::typecheck::value_ty(self.ir, id).components().unwrap_or(4);
                let sw = match n {
                    1 => ".x",
                    2 => ".xy",
                    3 => ".xyz",
                    _ => "",
                };
                let load = call(
                    "npr_load",
                    vec![Arg::Handle(name), Arg::Value("in.screen_uv".into())],
                    ctx,
                );
                format!("{load}{sw}")
            }
            ExprKind::Texture(t) => {
                let name = &self.ir.textures[t.0 as usize].name;
                format!("textureSample(tex_{name}, samp_{name}, {})", ctx.kind.texture_uv())
            }
            ExprKind::ObjectValue { pass, slot } => {
                let name = &self.ir.pass(*pass).name;
                // Prune makes every value a live pass reads live, so both are
                // allocated; if not, the undeclared name fails naga validation
                // (E9001 naming the pass) instead of reading another slot.
                match (
                    self.alloc.value_slots.get(&(*pass, *slot)),
                    self.alloc.slots_per_object.get(pass),
                ) {
                    (Some(slot), Some(per_object)) => {
                        format!("v_{name}[object.ids.x * {per_object}u + {slot}u]{}", slot_swizzle(e.ty))
                    }
                    _ => format!("npr_unallocated_value_of_{name}"),
                }
            }
            ExprKind::StateOld { slot } => format!("npr_old_{slot}"),
            ExprKind::Swizzle { base, components } => {
                let letters: String = components
                    .iter()
                    .map(|c| ['x', 'y', 'z', 'w'][*c as usize & 3])
                    .collect();
                format!("{}.{letters}", self.expr(*base, ctx))
            }
            ExprKind::Unary { op, operand } => {
                let o = self.expr(*operand, ctx);
                match op {
                    npr_dsl::ast::UnOp::Neg => format!("(-{o})"),
                    npr_dsl::ast::UnOp::Not => format!("(!{o})"),
                }
            }
            ExprKind::Binary { op, lhs, rhs } => {
                format!("({} {} {})", self.expr(*lhs, ctx), op.as_str(), self.expr(*rhs, ctx))
            }
            ExprKind::Select { cond, then, otherwise } => {
                let c = self.expr(*cond, ctx);
                // Not a const-expression: see `Uses::runtime_conditions`.
                let c = if ctx.runtime_conditions.contains(&id) {
                    format!("npr_runtime_bool({c})")
                } else {
                    c
                };
                format!("select({}, {}, {c})", self.expr(*otherwise, ctx), self.expr(*then, ctx))
            }
            ExprKind::Convert { conversion, operand } => {
                let o = self.expr(*operand, ctx);
                match conversion {
                    Conversion::IntToFloat => format!("f32({o})"),
                    Conversion::Splat(n) => format!("vec{n}<f32>({o})"),
                    Conversion::Rgb1 => format!("vec4<f32>({o}, 1.0)"),
                    Conversion::Rgb => format!("({o}).xyz"),
                    Conversion::Stored(f) => format!("npr_stored_{}({o})", f.name()),
                }
            }
            ExprKind::Call { callee, args } => match callee {
                Callee::Intrinsic(i) => {
                    let a: Vec<String> = args.iter().map(|x| self.expr(*x, ctx)).collect();
                    match i {
                        Intrinsic::Construct(n) => format!("vec{n}<f32>({})", a.join(", ")),
                        // A zero vector normalizes to zero instead of NaN.
                        Intrinsic::Normalize => format!("({0} * inverseSqrt(max(dot({0}, {0}), 1e-30)))", a[0]),
                        Intrinsic::Project => format!("npr_project(frame.view_proj, {})", a[0]),
                        Intrinsic::ProjectOtherEye => format!("npr_project(frame.other_view_proj, {})", a[0]),
                        Intrinsic::ProjectPrevious => format!("npr_project(frame.previous_view_proj, {})", a[0]),
                        Intrinsic::Ramp(g) => {
                            format!("npr_ramp_{}({})", self.ir.params[g.0 as usize].name, a[0])
                        }
                        other => format!("{}({})", other.name(), a.join(", ")),
                    }
                }
                Callee::Operator(i) => {
                    let op = &npr_stdlib::all()[*i as usize];
                    let mut a = Vec::new();
                    for (p, x) in op.params.iter().zip(args) {
                        match p.ty {
                            npr_stdlib::Ty::Texture => a.push(Arg::Handle(self.handle(*x, ctx))),
                            npr_stdlib::Ty::SampledTexture => {
                                a.push(Arg::Handle(self.handle(*x, ctx)));
                                a.push(Arg::Handle(self.sampler(*x, ctx)));
                            }
                            _ => a.push(Arg::Value(self.expr(*x, ctx))),
                        }
                    }
                    call(&op.wgsl_fn(), a, ctx)
                }
            },
            ExprKind::Error => "0.0 /* error */".into(),
        }
    }

    pub(super) fn handle(&self, id: ExprId, ctx: &PassCtx) -> String {
        match self.ir.expr(id).kind {
            ExprKind::Target { target, copy } => ctx.target_names.get(&(copy, target)).cloned().unwrap_or_default(),
            ExprKind::Texture(t) => format!("tex_{}", self.ir.textures[t.0 as usize].name),
            _ => String::from("/* not a handle */"),
        }
    }

    fn sampler(&self, id: ExprId, ctx: &PassCtx) -> String {
        match self.ir.expr(id).kind {
            ExprKind::Texture(t) => format!("samp_{}", self.ir.textures[t.0 as usize].name),
            _ => {
                debug_assert!(
                    ctx.uses_linear_sampler,
                    "a target passed as a sampled texture needs the clamp sampler"
                );
                "samp_linear_clamp".into()
            }
        }
    }
}

/// One argument of a call the emitter writes: a binding passed as a
/// texture or sampler, or a value.
enum Arg {
    Handle(String),
    Value(String),
}

/// `function(args)`, the arguments in parameter order. In a tiled module,
/// whose functions take no handle, a call with bindings calls the copy of
/// `function` for them with the values alone, recorded in `ctx` so that the
/// module includes it (`tiled/library.rs`).
fn call(function: &str, args: Vec<Arg>, ctx: &PassCtx) -> String {
    let handles: Vec<String> = args
        .iter()
        .filter_map(|a| match a {
            Arg::Handle(h) => Some(h.clone()),
            Arg::Value(_) => None,
        })
        .collect();
    let copies = ctx.per_binding.as_ref().filter(|_| !handles.is_empty());
    let written: Vec<String> = args
        .into_iter()
        .filter_map(|a| match a {
            Arg::Handle(h) => copies.is_none().then_some(h),
            Arg::Value(v) => Some(v),
        })
        .collect();
    let callee = match copies {
        Some(copies) => {
            let copy = super::copy_name(function, &handles);
            copies.borrow_mut().insert((function.to_string(), handles));
            copy
        }
        None => function.to_string(),
    };
    format!("{callee}({})", written.join(", "))
}

/// A builtin in value context; the same text in every kind (a pass kind
/// without geometry never reaches the geometry builtins: the typechecker
/// refuses them there).
pub(super) fn builtin_wgsl(b: Builtin) -> String {
    match b {
        Builtin::Uv => "in.uv".into(),
        Builtin::NormalWorld => "npr_unit(in.normal_world)".into(),
        Builtin::NormalView => "npr_unit((frame.view * vec4<f32>(in.normal_world, 0.0)).xyz)".into(),
        Builtin::PositionWorld => "in.position_world".into(),
        Builtin::PositionView => "(frame.view * vec4<f32>(in.position_world, 1.0)).xyz".into(),
        // The light camera is orthographic (w = 1), so this is already NDC.
        Builtin::PositionLight => "(frame.light_view_proj * vec4<f32>(in.position_world, 1.0)).xyz".into(),
        Builtin::Tangent => "npr_unit(in.tangent.xyz)".into(),
        // An orthographic camera's eye is at infinity behind it: every point
        // sees it along −forward (decision 0062).
        Builtin::ViewDir => {
            "select(npr_unit(frame.camera_pos.xyz - in.position_world), -frame.camera_forward.xyz, frame.ortho_height > 0.0)"
                .into()
        }
        Builtin::Depth => "(-(frame.view * vec4<f32>(in.position_world, 1.0)).z)".into(),
        Builtin::FragCoord => "in.clip.xy".into(),
        Builtin::ScreenUv => "in.screen_uv".into(),
        Builtin::Resolution => "frame.resolution".into(),
        Builtin::Time => "frame.time".into(),
        Builtin::Frame => "i32(frame.frame_index)".into(),
        Builtin::Eye => "i32(frame.eye)".into(),
        Builtin::LightDir => "frame.light_dir.xyz".into(),
        Builtin::LightColor => "frame.light_color.xyz".into(),
        Builtin::LightIntensity => "frame.light_dir.w".into(),
        Builtin::MoreLightDir(i) => format!("frame.more_light_dir[{i}].xyz"),
        Builtin::MoreLightColor(i) => format!("frame.more_light_color[{i}].xyz"),
        Builtin::MoreLightIntensity(i) => format!("frame.more_light_dir[{i}].w"),
        Builtin::CameraPosition => "frame.camera_pos.xyz".into(),
        Builtin::CameraNear => "frame.near".into(),
        Builtin::CameraFar => "frame.far".into(),
        Builtin::CameraFocal => "frame.focal.xy".into(),
        Builtin::CameraLeftEye => "frame.eye_left.xyz".into(),
        Builtin::CameraRightEye => "frame.eye_right.xyz".into(),
        Builtin::CameraForward => "frame.camera_forward.xyz".into(),
        // The view matrix's rows: its rotation's inverse is its transpose.
        Builtin::CameraRight => "vec3<f32>(frame.view[0].x, frame.view[1].x, frame.view[2].x)".into(),
        Builtin::CameraUp => "vec3<f32>(frame.view[0].y, frame.view[1].y, frame.view[2].y)".into(),
        Builtin::CameraOrthographic => "select(0.0, 1.0, frame.ortho_height > 0.0)".into(),
        Builtin::TangentScreen => "in.tangent_screen".into(),
        Builtin::BitangentScreen => "in.bitangent_screen".into(),
        Builtin::TangentScreenCenter => "in.tangent_screen_center".into(),
        Builtin::BitangentScreenCenter => "in.bitangent_screen_center".into(),
        Builtin::ObjectIndex => "i32(object.ids.x)".into(),
        Builtin::ObjectId => "i32(object.ids.y)".into(),
        Builtin::PositionPrevious => "in.position_previous".into(),
        Builtin::SampleSpacing => "in.spacing".into(),
        Builtin::LineArc => "in.line_s".into(),
        Builtin::LineAcross => "in.line_across".into(),
        Builtin::LineSet => "i32(in.line_set)".into(),
        Builtin::PatchWeight => "in.patch_weight".into(),
    }
}

/// The components of a `vec4<f32>` value slot that hold a value of type `ty`.
pub(super) fn slot_swizzle(ty: Ty) -> &'static str {
    match ty {
        Ty::Float => ".x",
        Ty::Vec2 => ".xy",
        Ty::Vec3 => ".xyz",
        _ => "",
    }
}

/// A value of type `ty` widened to a `vec4<f32>` slot (zeros after it).
pub(super) fn to_slot(value: &str, ty: Ty) -> String {
    match ty {
        Ty::Float => format!("vec4<f32>({value}, 0.0, 0.0, 0.0)"),
        Ty::Vec2 => format!("vec4<f32>({value}, 0.0, 0.0)"),
        Ty::Vec3 => format!("vec4<f32>({value}, 0.0)"),
        _ => value.to_string(),
    }
}

/// An f32 literal every WGSL implementation accepts, e.g. `0.5f`, `1e-5f`:
/// a non-finite value is held at the largest finite one (NaN at 0), since
/// WGSL has no literal for either.
pub fn fmt_f32(v: f64) -> String {
    let f = v as f32;
    let f = if f.is_finite() {
        f
    } else if f.is_nan() {
        0.0
    } else {
        f32::MAX.copysign(f)
    };
    if f.abs() == f32::MAX {
        // Rust's shortest spelling of f32::MAX, `3.4028235e38`, names a
        // decimal just above it: naga rounds it down, Tint (Chrome) refuses
        // it as out of range. The hex float is the exact value.
        return format!("{}{F32_MAX_WGSL}", if f < 0.0 { "-" } else { "" });
    }
    let s = format!("{f:?}");
    format!("{s}f")
}

/// f32::MAX exactly, as a hex float: the one spelling of the largest
/// finite f32 that no WGSL implementation may read as out of range.
pub const F32_MAX_WGSL: &str = "0x1.fffffep+127f";

fn const_wgsl(c: &Const, ty: Ty) -> String {
    match (c, ty) {
        (Const::Int(i), Ty::Float) => fmt_f32(*i as f64),
        (Const::Int(i), _) => format!("{}i", (*i).clamp(i32::MIN as i64, i32::MAX as i64)),
        (Const::Float(f), Ty::Int) => format!("{}i", *f as i32),
        (Const::Float(f), _) => fmt_f32(*f),
        (Const::Bool(b), _) => b.to_string(),
        (Const::Vec(v), _) => {
            let n = v.len();
            let parts: Vec<String> = v.iter().map(|x| fmt_f32(*x)).collect();
            format!("vec{n}<f32>({})", parts.join(", "))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals_past_f32_are_held_at_its_exact_maximum() {
        assert_eq!(fmt_f32(0.5), "0.5f");
        assert_eq!(fmt_f32(f32::MAX as f64), F32_MAX_WGSL);
        assert_eq!(fmt_f32(f64::INFINITY), F32_MAX_WGSL);
        assert_eq!(fmt_f32(-1e300), format!("-{F32_MAX_WGSL}"));
        assert_eq!(fmt_f32(f64::NAN), "0.0f");
        // The hex spelling is f32::MAX, bit for bit: 0x1.fffffe × 2^127.
        let (digits, exponent) = F32_MAX_WGSL
            .trim_start_matches("0x")
            .trim_end_matches('f')
            .split_once("p+")
            .expect("a hex float");
        let (whole, fraction) = digits.split_once('.').expect("a hex point");
        let mantissa = u64::from_str_radix(&format!("{whole}{fraction}"), 16).expect("hex digits");
        let exponent: i32 = exponent.parse().expect("an exponent");
        let value = mantissa as f64 * 2f64.powi(exponent - 4 * fraction.len() as i32);
        assert_eq!(value, f32::MAX as f64);
    }

    #[test]
    fn per_fragment_builtins_are_exactly_those_read_from_the_fragment_inputs() {
        // The typechecker rejects `Builtin::is_per_fragment` values in vertex
        // modifiers; the vertex shader has no `in`, so the two must agree.
        for (spelling, b) in Builtin::SPELLINGS {
            let wgsl = builtin_wgsl(*b);
            assert_eq!(wgsl.contains("in."), b.is_per_fragment(), "`{spelling}` emits `{wgsl}`");
        }
    }
}
