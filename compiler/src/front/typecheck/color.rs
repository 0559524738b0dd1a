//! Arithmetic on colours keeps their coverage (docs/decisions/0039-colours-keep-their-coverage.md).
//!
//! A colour is a straight-alpha `vec4`: light in `.rgb`, coverage in `.a`.
//! As in compositing tools (Nuke's Grade and Multiply act on `rgb` by
//! default; Blender's and Photoshop's brightness and colour balance leave
//! alpha alone), a number applied to a colour changes its light, not its
//! coverage:
//!
//! - `c * k`, `k * c`, `c / k`, `c + k`, `c - k`, `k - c`, `c % k`:
//!   `vec4(c.rgb op k, c.a)` (so `base * lambert(...)` stays opaque);
//! - `a + b`, `a - b` of two colours: `vec4(a.rgb ± b.rgb, max(a.a, b.a))`,
//!   light added or taken where either covers;
//! - `a * b`, `a / b` of two colours: component-wise (a filter; two opaque
//!   colours give an opaque one);
//! - a colour with a `vec4(...)` that is not one: component-wise, as
//!   written, since the author wrote that vector's alpha. W0201 warns when
//!   that alpha is not the neutral one (1 for `*` `/`, 0 for `+` `-`).
//!
//! What is a colour: a colour literal (`#e07a3a`), a `color` parameter, an
//! image or art-map texture read as a value, a read of an 8-bit `rgba`
//! target, an operator whose result is a colour, and `if`, `mix`, `min`,
//! `max`, `clamp` or the arithmetic above over colours. `vec4(...)` and
//! everything else are plain vectors: arithmetic acts on all four
//! components.

use super::*;

impl Checker<'_> {
    /// Whether `id`, read as a value, is a colour (see the module's list).
    pub(super) fn is_color(&self, id: ExprId) -> bool {
        if self.colors.contains(&id) {
            return true;
        }
        let e = self.ir.expr(id);
        match &e.kind {
            // The resolver makes a `Const::Vec` only of a colour literal.
            ExprKind::Const(Const::Vec(v)) => v.len() == 4,
            ExprKind::Param(p) => self.ir.params[p.0 as usize].ty == ParamTy::Color,
            ExprKind::Texture(t) => matches!(
                self.ir.textures[t.0 as usize].source,
                TextureSource::Image { .. }
                    | TextureSource::Artmap { .. }
                    | TextureSource::Input(npr_abi::InputKind::Color { .. })
            ),
            ExprKind::Target { target, .. } => self
                .ir
                .pass(target.pass)
                .outputs
                .get(target.output as usize)
                .is_some_and(|o| matches!(o.format, npr_abi::Format::Rgba8unorm | npr_abi::Format::Rgba8unormSrgb)),
            ExprKind::Convert { conversion, operand } => match conversion {
                Conversion::Rgb1 => true,
                Conversion::Stored(_) => self.is_color(*operand),
                _ => false,
            },
            _ => false,
        }
    }

    /// After `id` is typed: record it as a colour when it is built from
    /// colours by a function that keeps them colours.
    pub(super) fn note_color(&mut self, id: ExprId) {
        if self.vt(id) != Ty::Vec4 || self.colors.contains(&id) {
            return;
        }
        let derived = match &self.ir.expr(id).kind {
            ExprKind::Select { then, otherwise, .. } => self.is_color(*then) || self.is_color(*otherwise),
            ExprKind::Call {
                callee: Callee::Intrinsic(Intrinsic::Map2("min" | "max") | Intrinsic::Map3("mix" | "clamp")),
                args,
            } => args.iter().take(2).any(|a| self.is_color(*a)),
            ExprKind::Call {
                callee: Callee::Intrinsic(Intrinsic::Map("saturate" | "abs")),
                args,
            } => self.is_color(args[0]),
            // A live gradient's colour, as its folded `mix` chain of colour constants is.
            ExprKind::Call {
                callee: Callee::Intrinsic(Intrinsic::Ramp(_)),
                ..
            } => true,
            _ => false,
        };
        if derived {
            self.colors.insert(id);
        }
    }

    /// `lhs op rhs` (both typed, ints promoted) where the result is a
    /// `vec4`: rewrite node `id` as the colour rules say and return whether
    /// it did. Warns (W0201) on a colour combined with a plain `vec4` whose
    /// alpha is not neutral for `op`.
    pub(super) fn color_binary(&mut self, id: ExprId, op: BinOp, lhs: ExprId, rhs: ExprId, unit: Unit) -> bool {
        let (lc, rc) = (self.is_color(lhs), self.is_color(rhs));
        if !lc && !rc {
            return false;
        }
        let scalar = |c: &Self, x: ExprId| c.vt(x).components() == Some(1);
        let span = self.span(id);
        let lowered = if lc && scalar(self, rhs) {
            let rgb = self.swizzle(lhs, &[0, 1, 2]);
            let light = self
                .ir
                .add_typed(ExprKind::Binary { op, lhs: rgb, rhs }, Ty::Vec3, unit, span);
            Some((light, self.swizzle(lhs, &[3])))
        } else if rc && scalar(self, lhs) {
            let rgb = self.swizzle(rhs, &[0, 1, 2]);
            let light = self
                .ir
                .add_typed(ExprKind::Binary { op, lhs, rhs: rgb }, Ty::Vec3, unit, span);
            Some((light, self.swizzle(rhs, &[3])))
        } else if lc && rc && matches!(op, BinOp::Add | BinOp::Sub) {
            let (l, r) = (self.swizzle(lhs, &[0, 1, 2]), self.swizzle(rhs, &[0, 1, 2]));
            let light = self
                .ir
                .add_typed(ExprKind::Binary { op, lhs: l, rhs: r }, Ty::Vec3, unit, span);
            let (la, ra) = (self.swizzle(lhs, &[3]), self.swizzle(rhs, &[3]));
            let cover = self.ir.add_typed(
                ExprKind::Call {
                    callee: Callee::Intrinsic(Intrinsic::Map2("max")),
                    args: vec![la, ra],
                },
                Ty::Float,
                Unit::None,
                span,
            );
            Some((light, cover))
        } else {
            // Component-wise: two colours multiplied, or a colour with a plain vector.
            let plain = if lc { rhs } else { lhs };
            if !(lc && rc) {
                self.warn_plain_alpha(op, plain, span);
            }
            None
        };
        match lowered {
            Some((light, alpha)) => {
                self.ir.expr_mut(id).kind = ExprKind::Call {
                    callee: Callee::Intrinsic(Intrinsic::Construct(4)),
                    args: vec![light, alpha],
                };
            }
            None => self.ir.expr_mut(id).kind = ExprKind::Binary { op, lhs, rhs },
        }
        self.set(id, Ty::Vec4, unit);
        self.colors.insert(id);
        true
    }

    fn swizzle(&mut self, base: ExprId, components: &[u8]) -> ExprId {
        let (span, unit) = (self.span(base), self.unit(base));
        self.ir.add_typed(
            ExprKind::Swizzle {
                base,
                components: components.to_vec(),
            },
            Ty::float_vec(components.len() as u32),
            unit,
            span,
        )
    }

    /// W0201: a colour times (or plus) a plain `vec4` whose alpha is not
    /// the neutral one, known as written: a splat `vec4(k)` or a
    /// constructor whose last component is a constant.
    fn warn_plain_alpha(&mut self, op: BinOp, plain: ExprId, span: Span) {
        let neutral = match op {
            BinOp::Mul | BinOp::Div => 1.0,
            BinOp::Add | BinOp::Sub => 0.0,
            _ => return,
        };
        let alpha = match &self.ir.expr(plain).kind {
            ExprKind::Call {
                callee: Callee::Intrinsic(Intrinsic::Construct(4)),
                args,
            } => {
                let last = *args.last().unwrap_or(&plain);
                if self.vt(last).components() != Some(1) {
                    return;
                }
                last
            }
            ExprKind::Convert {
                conversion: Conversion::Splat(4),
                operand,
            } => *operand,
            _ => return,
        };
        let known = const_eval(self.ir, alpha).and_then(|c| c.scalar());
        if known == Some(neutral) {
            return;
        }
        let (verb, fix) = match op {
            BinOp::Mul | BinOp::Div => (
                "scales",
                "multiply by the number itself (`c * k` keeps alpha), or write the vector's alpha as 1.0",
            ),
            _ => (
                "shifts",
                "add the number itself (`c + k` keeps alpha), or write the vector's alpha as 0.0",
            ),
        };
        let what = match known {
            Some(v) => format!("the vector's alpha is {v}: it {verb} the colour's alpha"),
            None => format!("this is the vector's alpha too: it {verb} the colour's alpha"),
        };
        self.err(
            Diagnostic::warning(
                codes::COLOR_ALPHA_CHANGED,
                format!("this {verb} the colour's alpha, not only its light"),
            )
            .with_primary(span, "an opaque colour may come out transparent")
            .with_secondary(self.span(alpha), what)
            .with_help(fix),
        );
    }
}
