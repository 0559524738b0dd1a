//! The range of each IR node from its operands' ranges, and the domain
//! findings on the way: each operation whose operand's range reaches a
//! value where WGSL leaves the result undefined or non-finite
//! (`domains.rs` turns them into warnings).

use super::inputs;
use super::interval::Iv;
use super::value::{unit_norm, Val};
use crate::ir::*;
use npr_dsl::ast::{BinOp, UnOp};
use std::collections::HashMap;

/// Which rule of WGSL's a finding breaks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Domain {
    Log,
    Sqrt,
    Pow,
    Division,
    InverseTrig,
    Normalize,
    Atan2,
    /// A value stored into an f16 target past 65504 (∞ there).
    F16Overflow,
}

/// An operation whose operands' ranges reach its undefined case.
#[derive(Debug, Clone)]
pub struct Finding {
    pub domain: Domain,
    /// The call or division.
    pub at: ExprId,
    /// The operands that reach the bad case, with their ranges.
    pub operands: Vec<(ExprId, Val)>,
}

/// What the ranges of reads come from: targets (this frame and the
/// previous), per-object values, and state.
#[derive(Default)]
pub struct Reads {
    pub targets: HashMap<TargetRef, Val>,
    pub history: HashMap<TargetRef, Val>,
    pub values: HashMap<(PassId, u32), Val>,
    /// Each per-object state's old value (per compute pass and slot): its
    /// first value joined with every update so far, once a frame ran.
    pub states: HashMap<(PassId, u32), Val>,
}

/// Evaluates nodes in order, memoised: `vals[id]` once computed.
pub struct Eval<'a> {
    pub ir: &'a Ir,
    pub reads: &'a Reads,
    /// How each param ranges (by index), `inputs::param_range`.
    pub params: &'a [inputs::ParamRange],
    pub vals: HashMap<ExprId, Val>,
    pub findings: Vec<Finding>,
    /// The pass evaluated (whose states `StateOld` reads).
    pub pass: Option<PassId>,
}

fn n_of(ty: Ty) -> usize {
    ty.components().unwrap_or(4) as usize
}

impl<'a> Eval<'a> {
    pub fn new(ir: &'a Ir, reads: &'a Reads, params: &'a [inputs::ParamRange]) -> Eval<'a> {
        Eval {
            ir,
            reads,
            params,
            vals: HashMap::new(),
            findings: Vec::new(),
            pass: None,
        }
    }

    /// The ranges of every node reachable from `roots`.
    pub fn run(&mut self, roots: &[ExprId]) {
        for id in self.ir.reachable(roots) {
            if !self.vals.contains_key(&id) {
                let mut v = self.node(id);
                // WGSL lets an implementation assume no infinity or NaN
                // arises (§14.6.2): past that, a value is indeterminate.
                for c in &mut v.comps {
                    if !c.is_finite() {
                        *c = Iv::TOP;
                    }
                }
                self.vals.insert(id, v);
            }
        }
    }

    pub fn val(&self, id: ExprId) -> Val {
        self.vals
            .get(&id)
            .cloned()
            .unwrap_or_else(|| Val::top(n_of(self.ir.expr(id).ty)))
    }

    /// The old value of state `slot` of the pass evaluated, as its reads
    /// see it this frame.
    pub fn val_of_state(&mut self, slot: u32, n: usize) -> Val {
        let Some(pass) = self.pass else {
            return Val::top(n);
        };
        if let Some(v) = self.reads.states.get(&(pass, slot)) {
            return fit(v, n);
        }
        match self
            .ir
            .pass(pass)
            .kind
            .values()
            .get(slot as usize)
            .and_then(|v| v.first)
        {
            Some(first) => {
                self.run(&[first]);
                fit(&self.val(first), n)
            }
            None => Val::top(n),
        }
    }

    fn find(&mut self, domain: Domain, at: ExprId, operands: &[ExprId]) {
        let operands = operands.iter().map(|o| (*o, self.val(*o))).collect();
        self.findings.push(Finding { domain, at, operands });
    }

    fn node(&mut self, id: ExprId) -> Val {
        let e = self.ir.expr(id);
        let n = n_of(e.ty);
        match &e.kind {
            ExprKind::Const(c) => Val {
                comps: c.as_f64s().into_iter().map(Iv::point).collect(),
                norm: None,
            },
            // `N%` of the image height in px: the height is 1 px at least.
            ExprKind::PercentOfHeight(f) => {
                let far = f * f32::MAX as f64;
                Val::scalar(Iv::new(f.min(far), f.max(far)))
            }
            ExprKind::Param(p) => {
                let param = &self.ir.params[p.0 as usize];
                match self
                    .params
                    .get(p.0 as usize)
                    .copied()
                    .unwrap_or(inputs::ParamRange::Declared)
                {
                    inputs::ParamRange::Declared => inputs::param(param),
                    inputs::ParamRange::Value => {
                        // Its value: the default's range, keyframes joined.
                        self.run(&[param.default]);
                        let mut v = self.val(param.default);
                        for k in &param.keys {
                            let kv = Val {
                                comps: k.value.iter().map(|x| Iv::point(*x)).collect(),
                                norm: None,
                            };
                            v = v.join(&kv);
                        }
                        v
                    }
                }
            }
            ExprKind::Builtin(b) => inputs::builtin(*b),
            ExprKind::Target { target, copy } => {
                let map = if *copy == TargetCopy::Previous {
                    &self.reads.history
                } else {
                    &self.reads.targets
                };
                match map.get(target) {
                    Some(v) => fit(v, n),
                    None => Val::top(n),
                }
            }
            ExprKind::Texture(t) => inputs::texture(self.ir, *t, n),
            ExprKind::ObjectValue { pass, slot } => match self.reads.values.get(&(*pass, *slot)) {
                Some(v) => fit(v, n),
                None => Val::top(n),
            },
            // A state's old value: what the frames before left, or on the
            // first frame (before any ran) its first value.
            ExprKind::StateOld { slot } => self.val_of_state(*slot, n),
            ExprKind::Swizzle { base, components } => {
                let b = self.val(*base);
                Val {
                    comps: components.iter().map(|c| b.at(*c as usize)).collect(),
                    norm: None,
                }
            }
            ExprKind::Unary { op, operand } => {
                let a = self.val(*operand);
                match op {
                    UnOp::Neg => Val {
                        comps: a.comps.iter().map(|c| c.neg()).collect(),
                        norm: a.norm,
                    },
                    UnOp::Not => Val::splat(Iv::UNIT, n),
                }
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let (a, b) = (self.val(*lhs), self.val(*rhs));
                match op {
                    BinOp::Add => Val::zip(&[&a, &b], |x| x[0].add(x[1])),
                    BinOp::Sub => Val::zip(&[&a, &b], |x| x[0].sub(x[1])),
                    BinOp::Mul => {
                        if lhs == rhs {
                            Val::zip(&[&a], |x| x[0].sqr())
                        } else {
                            Val::zip(&[&a, &b], |x| x[0].mul(x[1]))
                        }
                    }
                    BinOp::Div | BinOp::Rem => {
                        if b.comps.iter().any(|c| c.contains(0.0)) && e.ty != Ty::Int {
                            self.find(Domain::Division, id, &[*rhs]);
                        }
                        if *op == BinOp::Div {
                            Val::zip(&[&a, &b], |x| x[0].div(x[1]))
                        } else {
                            Val::zip(&[&a, &b], |x| x[0].rem(x[1]))
                        }
                    }
                    _ => Val::splat(Iv::UNIT, n),
                }
            }
            ExprKind::Select { then, otherwise, .. } => self.val(*then).join(&self.val(*otherwise)),
            ExprKind::Convert { conversion, operand } => {
                let a = self.val(*operand);
                match conversion {
                    Conversion::IntToFloat => a,
                    Conversion::Splat(k) => Val::splat(a.at(0), *k as usize),
                    Conversion::Rgb1 => {
                        let mut c: Vec<Iv> = (0..3).map(|i| a.at(i)).collect();
                        c.push(Iv::point(1.0));
                        Val { comps: c, norm: None }
                    }
                    Conversion::Rgb => Val {
                        comps: (0..3).map(|i| a.at(i)).collect(),
                        norm: None,
                    },
                    Conversion::Stored(f) => inputs::stored(*f, &a),
                }
            }
            ExprKind::Call { callee, args } => self.call(id, *callee, args, n),
            ExprKind::Error => Val::top(n),
        }
    }

    /// `a − b`'s range, exact for `x + c1` against `x + c0` (the same
    /// node plus or minus constants: `smoothstep(e − 0.05, e + 0.05, t)`),
    /// where intervals lose that both ends move together.
    fn difference(&self, a: ExprId, b: ExprId) -> Val {
        let (xa, ca) = self.offset(a);
        let (xb, cb) = self.offset(b);
        if self.same(xa, xb) && self.ir.expr(a).ty == Ty::Float {
            // Both rounded once in f32: the difference is within an ulp of
            // the largest magnitude of each side.
            let x = self.val(xa).hull();
            let m = x.lo.abs().max(x.hi.abs()) + ca.abs().max(cb.abs());
            let e = 4.0 * m * f32::EPSILON as f64;
            return Val::scalar(Iv::new(ca - cb - e, ca - cb + e).with_nan(x.nan || !x.is_finite()));
        }
        let general = Val::zip(&[&self.val(a), &self.val(b)], |x| x[0].sub(x[1]));
        // `max(y, b + c) − b ≥ c`: the safe form of a pair of edges.
        if let ExprKind::Call {
            callee: Callee::Intrinsic(Intrinsic::Map2("max")),
            args,
        } = &self.ir.expr(a).kind
        {
            for arg in args {
                let (x, c) = self.offset(*arg);
                if self.same(x, xb) && self.ir.expr(a).ty == Ty::Float && general.comps.len() == 1 {
                    let g = general.comps[0];
                    let e = 4.0 * (g.lo.abs().max(g.hi.abs()) + c.abs()) * f32::EPSILON as f64;
                    let lo = Iv::new(c - cb - e, c - cb - e).lo;
                    if g.is_finite() {
                        return Val::scalar(Iv { lo: lo.max(g.lo), ..g });
                    }
                }
            }
        }
        general
    }

    /// Whether two nodes are the same value: one node, or reads of the
    /// same param or builtin (each use is a node of its own).
    pub(super) fn same(&self, a: ExprId, b: ExprId) -> bool {
        if a == b {
            return true;
        }
        match (&self.ir.expr(a).kind, &self.ir.expr(b).kind) {
            (ExprKind::Param(p), ExprKind::Param(q)) => p == q,
            (ExprKind::Builtin(p), ExprKind::Builtin(q)) => p == q,
            _ => false,
        }
    }

    /// Whether two nodes compute the same value: [`Eval::same`], or the
    /// same operation on operands that are (`depth` levels down at most;
    /// `n1 - n0` written twice is two nodes).
    pub(super) fn same_tree(&self, a: ExprId, b: ExprId, depth: u32) -> bool {
        if self.same(a, b) {
            return true;
        }
        if depth == 0 {
            return false;
        }
        let (ea, eb) = (&self.ir.expr(a).kind, &self.ir.expr(b).kind);
        let shallow = match (ea, eb) {
            (ExprKind::Const(_), ExprKind::Const(_))
            | (ExprKind::Target { .. }, ExprKind::Target { .. })
            | (ExprKind::Texture(_), ExprKind::Texture(_)) => return ea == eb,
            (ExprKind::Binary { op: p, .. }, ExprKind::Binary { op: q, .. }) => p == q,
            (ExprKind::Unary { op: p, .. }, ExprKind::Unary { op: q, .. }) => p == q,
            (ExprKind::Swizzle { components: p, .. }, ExprKind::Swizzle { components: q, .. }) => p == q,
            (ExprKind::Call { callee: p, .. }, ExprKind::Call { callee: q, .. }) => p == q,
            (ExprKind::Convert { conversion: p, .. }, ExprKind::Convert { conversion: q, .. }) => p == q,
            (ExprKind::Select { .. }, ExprKind::Select { .. }) => true,
            _ => false,
        };
        let (oa, ob) = (self.ir.operands(a), self.ir.operands(b));
        shallow
            && self.ir.expr(a).ty == self.ir.expr(b).ty
            && oa.len() == ob.len()
            && oa.iter().zip(&ob).all(|(x, y)| self.same_tree(*x, *y, depth - 1))
    }

    /// `id` as `x + c` with a constant `c` (`x − c` too; `(x, 0)` otherwise).
    fn offset(&self, id: ExprId) -> (ExprId, f64) {
        if let ExprKind::Binary { op, lhs, rhs } = &self.ir.expr(id).kind {
            let c = |e: ExprId| match &self.ir.expr(e).kind {
                ExprKind::Const(Const::Float(v)) => Some(*v),
                _ => None,
            };
            match (op, c(*lhs), c(*rhs)) {
                (BinOp::Add, _, Some(k)) => return (*lhs, k),
                (BinOp::Add, Some(k), _) => return (*rhs, k),
                (BinOp::Sub, _, Some(k)) => return (*lhs, -k),
                _ => {}
            }
        }
        (id, 0.0)
    }

    fn call(&mut self, id: ExprId, callee: Callee, args: &[ExprId], n: usize) -> Val {
        let vals: Vec<Val> = args.iter().map(|a| self.val(*a)).collect();
        let any_nan = vals.iter().any(|v| v.comps.iter().any(|c| c.nan));
        let intrinsic = match callee {
            Callee::Operator(i) => {
                let Some(def) = npr_stdlib::ops::ALL.get(i as usize) else {
                    return Val::top(n);
                };
                if let Some(hull) = self.texel_hull(def, args, &vals, n) {
                    return hull;
                }
                // The range holds for arguments within the parameters'
                // declared ranges (and finite): checked here.
                let args_ok = def.op.params.iter().zip(&vals).all(|(p, v)| match p.range {
                    Some((lo, hi)) => v.comps.iter().all(|c| c.is_finite() && lo <= c.lo && c.hi <= hi),
                    None => v.comps.iter().all(|c| c.is_finite()),
                });
                return match def.range_with_slack() {
                    Some((lo, hi)) if args_ok => Val::splat(Iv::new(lo, hi), n),
                    _ => Val::top(n),
                };
            }
            Callee::Intrinsic(i) => i,
        };
        match intrinsic {
            Intrinsic::Construct(k) => {
                if vals.len() == 1 && vals[0].comps.len() == 1 {
                    return Val::splat(vals[0].comps[0], k as usize);
                }
                Val {
                    comps: vals.iter().flat_map(|v| v.comps.iter().copied()).collect(),
                    norm: None,
                }
            }
            Intrinsic::Map(name) => {
                let a = &vals[0];
                let bad = match name {
                    "log" | "log2" => a.comps.iter().any(|c| c.lo <= 0.0),
                    "sqrt" => a.comps.iter().any(|c| c.lo < 0.0),
                    "asin" | "acos" => a.comps.iter().any(|c| c.lo < -1.0 || c.hi > 1.0),
                    _ => false,
                };
                if bad {
                    let d = match name {
                        "log" | "log2" => Domain::Log,
                        "sqrt" => Domain::Sqrt,
                        _ => Domain::InverseTrig,
                    };
                    self.find(d, id, &args[..1]);
                }
                let mut out = Val::zip(&[a], |x| x[0].map1(name).unwrap_or(Iv::TOP));
                if name == "abs" || name == "saturate" {
                    // Neither changes the length of a unit-bounded vector upward.
                    out.norm = if name == "abs" { a.norm } else { None };
                }
                out
            }
            Intrinsic::Map2(name) => {
                let (a, b) = (&vals[0], &vals[1]);
                match name {
                    "pow" => {
                        let bad = (0..a.comps.len().max(b.comps.len())).any(|i| {
                            let (x, y) = (a.at(i), b.at(i));
                            x.lo < 0.0 || (x.contains(0.0) && y.lo <= 0.0)
                        });
                        if bad {
                            self.find(Domain::Pow, id, &args[..2]);
                        }
                    }
                    "atan2" => {
                        let bad = (0..a.comps.len().max(b.comps.len()))
                            .any(|i| a.at(i).contains(0.0) && b.at(i).contains(0.0));
                        if bad {
                            self.find(Domain::Atan2, id, &args[..2]);
                        }
                    }
                    _ => {}
                }
                Val::zip(&[a, b], |x| x[0].map2(name, x[1]).unwrap_or(Iv::TOP))
            }
            Intrinsic::Map3(name) => {
                if name == "smoothstep" {
                    let w = self.difference(args[1], args[0]);
                    if w.comps.iter().any(|c| c.contains(0.0)) {
                        self.find(Domain::Division, id, &args[..2]);
                    }
                }
                if name == "smoothstep" {
                    let w = self.difference(args[1], args[0]);
                    return Val::zip(&[&vals[0], &vals[1], &vals[2], &w], |x| {
                        Iv::smoothstep_width(x[0], x[1], x[2], x[3])
                    });
                }
                Val::zip(&[&vals[0], &vals[1], &vals[2]], |x| {
                    Iv::map3(name, x[0], x[1], x[2]).unwrap_or(Iv::TOP)
                })
            }
            Intrinsic::Length => Val::scalar(vals[0].length()),
            Intrinsic::Distance => {
                let d = Val::zip(&[&vals[0], &vals[1]], |x| x[0].sub(x[1]));
                Val::scalar(d.length())
            }
            // `dot(x, x)` is |x|² ≥ 0 (each term a square), not a sum of
            // products of independent ranges.
            Intrinsic::Dot if self.same_tree(args[0], args[1], 8) => Val::scalar(vals[0].length_sq()),
            Intrinsic::Dot => {
                let (a, b) = (&vals[0], &vals[1]);
                let k = a.comps.len().max(b.comps.len());
                let sum = (0..k).map(|i| a.at(i).mul(b.at(i))).reduce(Iv::add).unwrap_or(Iv::TOP);
                // Cauchy–Schwarz: |a·b| ≤ |a||b| (a few ulps of rounding out).
                let bound = a.length().mul(b.length());
                if bound.is_finite() && !bound.is_empty() && !sum.nan {
                    let m = bound.hi * (1.0 + 4.0 * k as f64 * f32::EPSILON as f64);
                    Val::scalar(sum.meet(Iv::new(-m, m)).with_nan(sum.nan))
                } else {
                    Val::scalar(sum)
                }
            }
            Intrinsic::Normalize => {
                let len = vals[0].length();
                if len.contains(0.0) {
                    self.find(Domain::Normalize, id, &args[..1]);
                }
                let c = unit_norm().hi;
                let mut v = Val::unit(n);
                if len.contains(0.0) || len.nan || len.hi == f64::INFINITY {
                    v.comps = vec![Iv::new(-c, c).with_nan(true); n];
                    v.norm = Some(unit_norm().with_nan(true));
                }
                v
            }
            // Per path of an `if` argument (`paths.rs`), joined.
            Intrinsic::Cross => self
                .paths(args, &vals)
                .iter()
                .map(|p| Eval::cross(&p[0], &p[1]))
                .reduce(|a, b| a.join(&b))
                .unwrap_or_else(|| Val::top(3)),
            // A point on the eye's plane projects to ±∞ or NaN.
            Intrinsic::Project | Intrinsic::ProjectOtherEye | Intrinsic::ProjectPrevious => Val::top(n),
            // A gradient's stops are colours: the ramp stays in their hull.
            Intrinsic::Ramp(_) => Val::splat(Iv::UNIT.with_nan(any_nan), n),
        }
    }
}

impl Eval<'_> {
    /// A filter's result when it declares it within its texture's texels
    /// (`OpDef::texel_hull`: `sample`, `gaussian`, `downsample`): each
    /// component in the hull of that component of what the texture holds
    /// (a target's proved stored range, an image's format's), widened by
    /// f32 rounding; `None` when that is not proved (texels or other
    /// arguments maybe NaN or infinite: a NaN coordinate reads anything).
    fn texel_hull(&self, def: &npr_stdlib::ops::OpDef, args: &[ExprId], vals: &[Val], n: usize) -> Option<Val> {
        let param = def.texel_hull?;
        let at = def.op.params.iter().position(|p| p.name == param)?;
        let others_finite = vals
            .iter()
            .enumerate()
            .all(|(i, v)| i == at || v.comps.iter().all(|c| c.is_finite()));
        let texels = self.texels(*args.get(at)?)?;
        if !others_finite || !texels.comps.iter().all(|c| c.is_finite()) {
            return None;
        }
        Some(Val {
            comps: (0..n)
                .map(|i| {
                    let c = texels.at(i);
                    let (lo, hi) = npr_stdlib::ops::OpDef::hull_with_slack(c.lo, c.hi);
                    Iv::new(lo, hi)
                })
                .collect(),
            norm: None,
        })
    }

    /// What a texture argument's texels hold, as the four components a
    /// read returns: a target's stored range, with a format of fewer
    /// channels read as (r, g, 0, 1) as WGSL does; an image's format's.
    fn texels(&self, tex: ExprId) -> Option<Val> {
        match &self.ir.expr(tex).kind {
            ExprKind::Target { target, copy } => {
                let map = if *copy == TargetCopy::Previous {
                    &self.reads.history
                } else {
                    &self.reads.targets
                };
                let stored = map.get(target)?;
                let channels = self.ir.pass(target.pass).outputs[target.output as usize]
                    .format
                    .channels() as usize;
                Some(Val {
                    comps: (0..4)
                        .map(|i| match stored.comps.get(i).filter(|_| i < channels) {
                            Some(c) => *c,
                            None if i == 3 => Iv::point(1.0),
                            None => Iv::point(0.0),
                        })
                        .collect(),
                    norm: None,
                })
            }
            ExprKind::Texture(t) => Some(inputs::texture(self.ir, *t, 4)),
            _ => None,
        }
    }
}

/// A value read at another width than stored (a swizzled target): the
/// stored components, the rest unknown.
fn fit(v: &Val, n: usize) -> Val {
    if v.comps.len() == n {
        return v.clone();
    }
    Val {
        comps: (0..n)
            .map(|i| {
                if v.comps.len() == 1 {
                    v.comps[0]
                } else {
                    v.comps.get(i).copied().unwrap_or(Iv::TOP)
                }
            })
            .collect(),
        norm: None,
    }
}
