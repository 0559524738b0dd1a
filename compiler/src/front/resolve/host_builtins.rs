//! Geometry builtins in an image pass over a host's frame (issue 47): a
//! style that declares `input(depth)` reads `depth` and `position.view` in
//! its image passes, and one that declares `input(normal, view|world)` reads
//! `normal.view` or `normal` (world), as a render pass reads them from npr's
//! own geometry. Each is rewritten here into the reads of those inputs it
//! stands for, so every later stage (types, units, value ranges, bindings,
//! fusion) sees ordinary texture reads at the pixel:
//!
//! - `depth` = the depth input's r (distance along the view axis, metres;
//!   0 where the host hit nothing);
//! - `position.view` = (x_ndc·w / f_x, y_ndc·w / f_y, −d), with
//!   x_ndc = 2u − 1, y_ndc = 1 − 2v at `screen_uv` (u, v), f =
//!   `camera.focal` (P₀₀, P₁₁ of a symmetric projection) and w the clip w
//!   of view depth d: d through a perspective projection, 1 m through an
//!   orthographic one (w = d + (1 m − d)·`camera.orthographic`, decision
//!   0062): the point on the pixel's ray at view depth d;
//! - `position.world` = `camera.position` + right·x + up·y + forward·d,
//!   the view-space point turned back into the world (the view's rotation
//!   is orthonormal: its inverse is its transpose, whose columns are
//!   `camera.right`, `camera.up` and −`camera.forward`);
//! - `view_dir` = normalize(`camera.position` − `position.world`), towards
//!   the eye, or −`camera.forward` for an orthographic camera (n + (−f −
//!   n)·`camera.orthographic`, exact for its values 0 and 1);
//! - `normal.view` / `normal.world` = the normal input's rgb when it is
//!   declared in that space (the runner converts the host's at load).
//!
//! `uv` has no value over a host's frame (E0321): nothing carries the
//! host's surface parametrisation, and it cannot be rebuilt.
//!
//! A builtin that needs an input the style does not declare stays a
//! builtin, and the typechecker refuses it in an image pass (E0304) with a
//! help that names the input. Two inputs of one kind make the reading
//! ambiguous: E0304 here, naming both.

use super::Resolver;
use crate::ir::*;
use npr_abi::{InputKind, NormalSpace};
use npr_diag::{codes, Diagnostic, Span};
use npr_dsl::ast::BinOp;
use npr_stdlib::Unit;

impl Resolver<'_> {
    /// `b` read at `span` in an image pass, as the reads of the style's
    /// inputs it stands for; `None` when no declared input provides it.
    pub(super) fn host_builtin(&mut self, b: Builtin, span: Span) -> Option<ExprId> {
        match b {
            Builtin::Depth => {
                let depth = self.host_input(b, span, |k| matches!(k, InputKind::Depth))?;
                Some(self.view_depth(depth, span))
            }
            Builtin::PositionView => {
                let depth = self.host_input(b, span, |k| matches!(k, InputKind::Depth))?;
                Some(self.view_position(depth, span))
            }
            Builtin::PositionWorld => {
                let depth = self.host_input(b, span, |k| matches!(k, InputKind::Depth))?;
                let offset = self.view_to_world_offset(depth, span);
                let camera = self.builtin(Builtin::CameraPosition, span);
                Some(self.binary(BinOp::Add, camera, offset, span))
            }
            Builtin::ViewDir => {
                let depth = self.host_input(b, span, |k| matches!(k, InputKind::Depth))?;
                let offset = self.view_to_world_offset(depth, span);
                let towards_eye = self.negate(offset, span);
                let perspective = self.ir.add(
                    ExprKind::Call {
                        callee: Callee::Intrinsic(Intrinsic::Normalize),
                        args: vec![towards_eye],
                    },
                    span,
                );
                let forward = self.builtin(Builtin::CameraForward, span);
                let orthographic = self.negate(forward, span);
                Some(self.by_projection(perspective, orthographic, span))
            }
            Builtin::Uv
                if self
                    .ir
                    .textures
                    .iter()
                    .any(|t| matches!(t.source, TextureSource::Input(_))) =>
            {
                self.error(
                    Diagnostic::error(
                        codes::NO_HOST_UV,
                        "`uv` has no value in an image pass over a host's frame",
                    )
                    .with_primary(span, "no surface coordinates here")
                    .with_help(
                        "a host's frame carries no texture coordinates, and npr cannot rebuild them from depth \
                         and normals as it rebuilds positions; use `screen_uv`, or take the host's UVs as an \
                         input: `texture host_uv = input(image, rg16float)`",
                    ),
                );
                Some(self.builtin(Builtin::ScreenUv, span))
            }
            Builtin::NormalView | Builtin::NormalWorld => {
                let space = if b == Builtin::NormalView {
                    NormalSpace::View
                } else {
                    NormalSpace::World
                };
                let normals = self.host_input(b, span, |k| *k == InputKind::Normal { space })?;
                let read = self.texture_read(normals, span);
                Some(self.ir.add(
                    ExprKind::Swizzle {
                        base: read,
                        components: vec![0, 1, 2],
                    },
                    span,
                ))
            }
            _ => None,
        }
    }

    /// The one declared input of a kind `fits`; `None` when there is none,
    /// and an error (with `None`) when there are several.
    fn host_input(&mut self, b: Builtin, span: Span, fits: impl Fn(&InputKind) -> bool) -> Option<TextureId> {
        let found: Vec<TextureId> = self
            .ir
            .textures
            .iter()
            .enumerate()
            .filter(|(_, t)| matches!(&t.source, TextureSource::Input(k) if fits(k)))
            .map(|(i, _)| TextureId(i as u32))
            .collect();
        match found.as_slice() {
            [] => None,
            [one] => Some(*one),
            several => {
                let names: Vec<String> = several
                    .iter()
                    .map(|t| format!("`{}`", self.ir.textures[t.0 as usize].name))
                    .collect();
                let mut d = Diagnostic::error(
                    codes::BAD_PASS_INPUT,
                    format!(
                        "`{}` could be read from any of the inputs {}",
                        b.name(),
                        names.join(", ")
                    ),
                )
                .with_primary(span, "which input is meant is ambiguous")
                .with_help(format!(
                    "read the input you mean yourself, e.g. `{}.r` for a depth",
                    self.ir.textures[several[0].0 as usize].name
                ));
                for t in several {
                    d = d.with_secondary(self.ir.textures[t.0 as usize].span, "one of them");
                }
                self.error(d);
                Some(several[0])
            }
        }
    }

    /// The input texture as a value at the pixel (an image pass samples it
    /// at `screen_uv`).
    fn texture_read(&mut self, t: TextureId, span: Span) -> ExprId {
        self.ir
            .add_typed(ExprKind::Texture(t), Ty::Texture(t), Unit::None, span)
    }

    /// The depth input's r, in metres (the language's depth convention).
    fn view_depth(&mut self, depth: TextureId, span: Span) -> ExprId {
        let read = self.texture_read(depth, span);
        let r = self.ir.add(
            ExprKind::Swizzle {
                base: read,
                components: vec![0],
            },
            span,
        );
        let metre = self
            .ir
            .add_typed(ExprKind::Const(Const::Float(1.0)), Ty::Float, Unit::Meters, span);
        self.binary(BinOp::Mul, r, metre, span)
    }

    /// (x_ndc·w / f_x, y_ndc·w / f_y, −d): the view-space point at depth d
    /// on the pixel's ray, w the clip w of depth d (d, or 1 m orthographic).
    fn view_position(&mut self, depth: TextureId, span: Span) -> ExprId {
        let d = self.view_depth(depth, span);
        let metre = self
            .ir
            .add_typed(ExprKind::Const(Const::Float(1.0)), Ty::Float, Unit::Meters, span);
        let w = self.by_projection(d, metre, span);
        let uv = self.builtin(Builtin::ScreenUv, span);
        let focal = self.builtin(Builtin::CameraFocal, span);
        let two = self.plain_number(2.0, span);
        let one = self.plain_number(1.0, span);
        let u = self.component(uv, 0, span);
        let v = self.component(uv, 1, span);
        // x_ndc = 2u − 1; y_ndc = 1 − 2v (screen_uv's v grows downwards).
        let two_u = self.binary(BinOp::Mul, two, u, span);
        let x_ndc = self.binary(BinOp::Sub, two_u, one, span);
        let two_v = self.binary(BinOp::Mul, two, v, span);
        let y_ndc = self.binary(BinOp::Sub, one, two_v, span);
        let fx = self.component(focal, 0, span);
        let fy = self.component(focal, 1, span);
        let xw = self.binary(BinOp::Mul, x_ndc, w, span);
        let x = self.binary(BinOp::Div, xw, fx, span);
        let yw = self.binary(BinOp::Mul, y_ndc, w, span);
        let y = self.binary(BinOp::Div, yw, fy, span);
        let z = self.negate(d, span);
        self.ir.add(
            ExprKind::Call {
                callee: Callee::Intrinsic(Intrinsic::Construct(3)),
                args: vec![x, y, z],
            },
            span,
        )
    }

    /// position.world − camera.position = right·x + up·y + forward·d for
    /// the rebuilt view-space point (x, y, −d): the view's rotation undone
    /// (its inverse is its transpose; `camera.right`, `camera.up` and
    /// `camera.forward` are its rows, the last negated).
    fn view_to_world_offset(&mut self, depth: TextureId, span: Span) -> ExprId {
        let p = self.view_position(depth, span);
        let x = self.component(p, 0, span);
        let y = self.component(p, 1, span);
        let d = self.view_depth(depth, span);
        let axes = [Builtin::CameraRight, Builtin::CameraUp, Builtin::CameraForward];
        let mut terms = [x, y, d].into_iter().zip(axes).map(|(along, axis)| {
            let axis = self.builtin(axis, span);
            self.binary(BinOp::Mul, axis, along, span)
        });
        let first = terms.next().expect("three terms");
        let rest: Vec<ExprId> = terms.collect();
        rest.into_iter()
            .fold(first, |sum, t| self.binary(BinOp::Add, sum, t, span))
    }

    /// `perspective` for a perspective camera, `orthographic` for an
    /// orthographic one: p + (o − p)·`camera.orthographic`, exact for its
    /// two values (p is finite wherever it is read: a safe normalise, or a
    /// depth).
    fn by_projection(&mut self, perspective: ExprId, orthographic: ExprId, span: Span) -> ExprId {
        let is_orthographic = self.builtin(Builtin::CameraOrthographic, span);
        let change = self.binary(BinOp::Sub, orthographic, perspective, span);
        let scaled = self.binary(BinOp::Mul, change, is_orthographic, span);
        self.binary(BinOp::Add, perspective, scaled, span)
    }

    fn negate(&mut self, operand: ExprId, span: Span) -> ExprId {
        self.ir.add(
            ExprKind::Unary {
                op: npr_dsl::ast::UnOp::Neg,
                operand,
            },
            span,
        )
    }

    fn builtin(&mut self, b: Builtin, span: Span) -> ExprId {
        let (ty, unit) = b.ty_unit();
        self.ir.add_typed(ExprKind::Builtin(b), ty, unit, span)
    }

    fn plain_number(&mut self, v: f64, span: Span) -> ExprId {
        self.ir
            .add_typed(ExprKind::Const(Const::Float(v)), Ty::Float, Unit::None, span)
    }

    fn component(&mut self, base: ExprId, c: u8, span: Span) -> ExprId {
        self.ir.add(
            ExprKind::Swizzle {
                base,
                components: vec![c],
            },
            span,
        )
    }

    fn binary(&mut self, op: BinOp, lhs: ExprId, rhs: ExprId, span: Span) -> ExprId {
        self.ir.add(ExprKind::Binary { op, lhs, rhs }, span)
    }
}
