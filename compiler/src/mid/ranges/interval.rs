//! Sound interval arithmetic on f32 values, computed in f64.
//!
//! An [`Iv`] is a closed set of extended reals `[lo, hi]` (either end may be
//! infinite) and a flag saying whether NaN is possible. A bound is *sound*
//! for f32 evaluation: every operation rounds its f64 bounds outward to the
//! f32 grid ([`down`], [`up`]), because round-to-nearest is monotone, so
//! the f32 result of an exact-real value in `[a, b]` lies in
//! `[down(a), up(b)]` (the f64 computation of `a` is off by one f64 ulp at
//! most, far below half an f32 ulp). A bound past `f32::MAX` is infinite:
//! the f32 value overflows there.
//!
//! WGSL's built-in functions are not correctly rounded (WGSL §15.4.4
//! "Floating Point Accuracy": `exp` 3 + 2·|x| ULP, `log` 2⁻²¹ absolute near
//! 1, `sin`/`cos` 2⁻¹¹ absolute in [−π, π], `pow` inherited from
//! `exp2(y·log2(x))`): their bounds are widened by those errors, then
//! intersected with the function's mathematical range (`exp ≥ 0`,
//! `|sin| ≤ 1`), which every implementation keeps (an assumption,
//! documented in docs/RANGES.md).
//!
//! The functions here are the single definition the analysis applies
//! (`eval.rs`) and the property test checks (`tests.rs`). The file passes
//! 600 lines on purpose: every function is short and shares the rounding
//! and NaN rules at its top, which one file keeps in view.

/// The largest finite f32, as f64.
pub const F32_MAX: f64 = f32::MAX as f64;

/// A set of f32 values: `[lo, hi]` and maybe NaN.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Iv {
    pub lo: f64,
    pub hi: f64,
    pub nan: bool,
}

/// The largest f32 ≤ `x` (−∞ below −f32::MAX, and for NaN).
pub fn down(x: f64) -> f64 {
    if x.is_nan() || x < -F32_MAX {
        return f64::NEG_INFINITY;
    }
    if x > F32_MAX {
        return F32_MAX;
    }
    let f = x as f32;
    if (f as f64) <= x {
        f as f64
    } else {
        f.next_down() as f64
    }
}

/// The smallest f32 ≥ `x` (+∞ above f32::MAX, and for NaN).
pub fn up(x: f64) -> f64 {
    -down(-x)
}

// Named methods, not `std::ops` operators: each rounds outward and tracks
// NaN, and `a.add(b)` reads as the interval operation it is.
#[allow(clippy::should_implement_trait)]
impl Iv {
    /// Every f32 value and NaN: what nothing is known of.
    pub const TOP: Iv = Iv {
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
        nan: true,
    };
    /// Every finite f32 value: finite but unbounded (a world position).
    pub const FINITE: Iv = Iv {
        lo: -F32_MAX,
        hi: F32_MAX,
        nan: false,
    };
    pub const UNIT: Iv = Iv {
        lo: 0.0,
        hi: 1.0,
        nan: false,
    };
    pub const SIGNED_UNIT: Iv = Iv {
        lo: -1.0,
        hi: 1.0,
        nan: false,
    };

    /// `[lo, hi]` rounded outward to f32 (NaN bounds widen to infinity).
    pub fn new(lo: f64, hi: f64) -> Iv {
        Iv {
            lo: down(lo),
            hi: up(hi),
            nan: false,
        }
    }

    pub fn point(x: f64) -> Iv {
        if x.is_nan() {
            return Iv {
                lo: f64::INFINITY,
                hi: f64::NEG_INFINITY,
                nan: true,
            };
        }
        Iv::new(x, x)
    }

    pub fn with_nan(self, nan: bool) -> Iv {
        Iv {
            nan: self.nan || nan,
            ..self
        }
    }

    /// No value but NaN (lo > hi).
    pub fn is_empty(self) -> bool {
        self.lo > self.hi
    }

    /// Every value finite and no NaN: `[lo, hi]` within the f32 range.
    pub fn is_finite(self) -> bool {
        !self.nan && (self.is_empty() || (self.lo >= -F32_MAX && self.hi <= F32_MAX))
    }

    pub fn contains(self, x: f64) -> bool {
        if x.is_nan() {
            self.nan
        } else {
            self.lo <= x && x <= self.hi
        }
    }

    pub fn join(self, o: Iv) -> Iv {
        Iv {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
            nan: self.nan || o.nan,
        }
    }

    /// The values of both (NaN if both may be NaN).
    pub fn meet(self, o: Iv) -> Iv {
        Iv {
            lo: self.lo.max(o.lo),
            hi: self.hi.min(o.hi),
            nan: self.nan && o.nan,
        }
    }

    fn can_be_pos_inf(self) -> bool {
        self.hi == f64::INFINITY
    }
    fn can_be_neg_inf(self) -> bool {
        self.lo == f64::NEG_INFINITY
    }
    fn can_be_inf(self) -> bool {
        self.can_be_pos_inf() || self.can_be_neg_inf()
    }

    /// `[lo, hi]` from candidate values (NaN candidates ignored), rounded outward.
    fn hull(cands: &[f64], nan: bool) -> Iv {
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for c in cands.iter().filter(|c| !c.is_nan()) {
            lo = lo.min(*c);
            hi = hi.max(*c);
        }
        if lo > hi {
            return Iv { lo, hi, nan: true };
        }
        Iv::new(lo, hi).with_nan(nan)
    }

    /// Widen by `abs` and by `rel` times the magnitude: a function's
    /// documented error.
    fn widen(self, abs: f64, rel: f64) -> Iv {
        if self.is_empty() {
            return self;
        }
        Iv {
            lo: down(self.lo - abs - rel * self.lo.abs()),
            hi: up(self.hi + abs + rel * self.hi.abs()),
            nan: self.nan,
        }
    }

    /// Clip to a function's mathematical range, keeping the NaN flag.
    fn within(self, lo: f64, hi: f64) -> Iv {
        if self.is_empty() {
            return self;
        }
        Iv {
            lo: self.lo.clamp(lo, hi),
            hi: self.hi.clamp(lo, hi),
            nan: self.nan,
        }
    }

    pub fn neg(self) -> Iv {
        Iv {
            lo: -self.hi,
            hi: -self.lo,
            nan: self.nan,
        }
    }

    pub fn add(self, o: Iv) -> Iv {
        if self.is_empty() || o.is_empty() {
            return Iv::point(f64::NAN);
        }
        // ∞ + (−∞) is NaN.
        let nan = (self.can_be_pos_inf() && o.can_be_neg_inf()) || (self.can_be_neg_inf() && o.can_be_pos_inf());
        let lo = self.lo + o.lo;
        let hi = self.hi + o.hi;
        Iv::new(
            if lo.is_nan() { f64::NEG_INFINITY } else { lo },
            if hi.is_nan() { f64::INFINITY } else { hi },
        )
        .with_nan(nan || self.nan || o.nan)
    }

    pub fn sub(self, o: Iv) -> Iv {
        self.add(o.neg())
    }

    pub fn mul(self, o: Iv) -> Iv {
        if self.is_empty() || o.is_empty() {
            return Iv::point(f64::NAN);
        }
        // 0 · ∞ is NaN; as a bound it counts as 0 (the limits either side).
        let nan = (self.contains(0.0) && o.can_be_inf()) || (o.contains(0.0) && self.can_be_inf());
        let m = |a: f64, b: f64| if a == 0.0 || b == 0.0 { 0.0 } else { a * b };
        Iv::hull(
            &[m(self.lo, o.lo), m(self.lo, o.hi), m(self.hi, o.lo), m(self.hi, o.hi)],
            nan || self.nan || o.nan,
        )
    }

    /// `x²`, never negative (tighter than `x · x`, whose operands are taken apart).
    pub fn sqr(self) -> Iv {
        if self.is_empty() {
            return self;
        }
        let a = self.lo * self.lo;
        let b = self.hi * self.hi;
        let lo = if self.contains(0.0) { 0.0 } else { a.min(b) };
        Iv::new(lo, a.max(b)).with_nan(self.nan)
    }

    pub fn div(self, o: Iv) -> Iv {
        if self.is_empty() || o.is_empty() {
            return Iv::point(f64::NAN);
        }
        let nan = self.nan || o.nan || (self.contains(0.0) && o.contains(0.0)) || (self.can_be_inf() && o.can_be_inf());
        if o.contains(0.0) {
            // A divisor that may be 0 may be −0 or +0 (−x of x = 0): a
            // non-zero numerator gives either infinity, 0 / 0 NaN.
            let mut c = Vec::new();
            if self.lo < 0.0 || self.hi > 0.0 {
                c.extend([f64::NEG_INFINITY, f64::INFINITY]);
            }
            if self.contains(0.0) && (o.lo < 0.0 || o.hi > 0.0) {
                c.push(0.0);
            }
            return Iv::hull(&c, nan);
        }
        let q = |a: f64, b: f64| a / b;
        Iv::hull(
            &[q(self.lo, o.lo), q(self.lo, o.hi), q(self.hi, o.lo), q(self.hi, o.hi)],
            nan,
        )
    }

    /// WGSL's float `%`: `x − y·trunc(x / y)`, with the sign of `x` and
    /// smaller in magnitude than `y` (NaN for `y = 0` or infinite `x`).
    pub fn rem(self, o: Iv) -> Iv {
        if self.is_empty() || o.is_empty() {
            return Iv::point(f64::NAN);
        }
        let m = o.lo.abs().max(o.hi.abs()).min(self.lo.abs().max(self.hi.abs()));
        let lo = if self.lo < 0.0 { -m } else { 0.0 };
        let hi = if self.hi > 0.0 { m } else { 0.0 };
        Iv::new(lo, hi).with_nan(self.nan || o.nan || o.contains(0.0) || self.can_be_inf())
    }

    pub fn min(self, o: Iv) -> Iv {
        // With a NaN operand WGSL may return either operand (or NaN).
        if self.nan || o.nan {
            return self.join(o);
        }
        Iv {
            lo: self.lo.min(o.lo),
            hi: self.hi.min(o.hi),
            nan: self.nan || o.nan,
        }
    }

    pub fn max(self, o: Iv) -> Iv {
        // With a NaN operand WGSL may return either operand (or NaN).
        if self.nan || o.nan {
            return self.join(o);
        }
        Iv {
            lo: self.lo.max(o.lo),
            hi: self.hi.max(o.hi),
            nan: self.nan || o.nan,
        }
    }

    /// A monotone non-decreasing function on `[dlo, dhi]`; outside it
    /// WGSL's result is indeterminate (any value: some drivers return NaN,
    /// others a number), so the range is [`Iv::TOP`].
    fn monotone(self, f: fn(f64) -> f64, dlo: f64, dhi: f64) -> Iv {
        if self.is_empty() {
            return self;
        }
        if self.lo < dlo || self.hi > dhi {
            return Iv::TOP;
        }
        Iv::hull(&[f(self.lo), f(self.hi)], self.nan)
    }

    /// `sin` (or `cos`, shifted by π/2): the extremes at the ends or at a
    /// crest inside.
    fn sine(self, shift: f64) -> Iv {
        if self.is_empty() {
            return self;
        }
        let nan = self.nan || self.can_be_inf();
        if self.hi - self.lo >= 2.0 * std::f64::consts::PI || !self.lo.is_finite() || !self.hi.is_finite() {
            return Iv::SIGNED_UNIT.with_nan(nan);
        }
        let (a, b) = (self.lo + shift, self.hi + shift);
        let mut c = vec![a.sin(), b.sin()];
        // Crests at π/2 + kπ.
        let half_pi = std::f64::consts::FRAC_PI_2;
        let mut k = ((a - half_pi) / std::f64::consts::PI).ceil();
        while half_pi + k * std::f64::consts::PI <= b {
            c.push((half_pi + k * std::f64::consts::PI).sin());
            k += 1.0;
        }
        Iv::hull(&c, nan).widen(1.0 / 2048.0, 0.0).within(-1.0, 1.0)
    }

    /// The component-wise built-in `name` of one argument; `None` for a
    /// name this analysis does not know (the caller makes that TOP).
    pub fn map1(self, name: &str) -> Option<Iv> {
        use std::f64::consts::{FRAC_PI_2, PI};
        let x = self;
        // A NaN argument: WGSL's result is indeterminate (IEEE keeps some:
        // `pow(NaN, 0)` is 1), unless the function is exact.
        if x.nan && !matches!(name, "abs" | "floor" | "ceil" | "round" | "sign" | "saturate") {
            return Some(Iv::TOP);
        }
        // Outside a function's domain WGSL's result is indeterminate.
        let domain = match name {
            "sqrt" | "log" | "log2" => Some((0.0, f64::INFINITY)),
            "asin" | "acos" => Some((-1.0, 1.0)),
            _ => None,
        };
        if let Some((lo, hi)) = domain {
            if !x.is_empty() && (x.lo < lo || x.hi > hi) {
                return Some(Iv::TOP);
            }
        }
        Some(match name {
            "abs" => {
                if x.is_empty() || x.lo >= 0.0 {
                    x
                } else if x.hi <= 0.0 {
                    x.neg()
                } else {
                    Iv {
                        lo: 0.0,
                        hi: x.hi.max(-x.lo),
                        nan: x.nan,
                    }
                }
            }
            "floor" => x.monotone(f64::floor, f64::NEG_INFINITY, f64::INFINITY),
            "ceil" => x.monotone(f64::ceil, f64::NEG_INFINITY, f64::INFINITY),
            // WGSL rounds half to even.
            "round" => x.monotone(f64::round_ties_even, f64::NEG_INFINITY, f64::INFINITY),
            // x − floor(x): 1.0 itself for tiny negative x (f32 rounding).
            "fract" => Iv::UNIT.with_nan(x.nan || x.can_be_inf()),
            "sqrt" => x.monotone(f64::sqrt, 0.0, f64::INFINITY),
            "exp" => {
                let m = x.lo.abs().max(x.hi.abs()).min(200.0);
                x.monotone(f64::exp, f64::NEG_INFINITY, f64::INFINITY)
                    .widen(0.0, (3.0 + 2.0 * m) * f32::EPSILON as f64)
                    .within(0.0, f64::INFINITY)
            }
            "exp2" => {
                let m = x.lo.abs().max(x.hi.abs()).min(200.0);
                x.monotone(f64::exp2, f64::NEG_INFINITY, f64::INFINITY)
                    .widen(0.0, (3.0 + 2.0 * m) * f32::EPSILON as f64)
                    .within(0.0, f64::INFINITY)
            }
            "log" => x
                .monotone(f64::ln, 0.0, f64::INFINITY)
                .widen(2f64.powi(-21), 3.0 * f32::EPSILON as f64),
            "log2" => x
                .monotone(f64::log2, 0.0, f64::INFINITY)
                .widen(2f64.powi(-21), 3.0 * f32::EPSILON as f64),
            "sin" => x.sine(0.0),
            "cos" => x.sine(FRAC_PI_2),
            "tan" => {
                // Monotone between asymptotes at π/2 + kπ.
                let k = ((x.lo - FRAC_PI_2) / PI).ceil();
                if !x.lo.is_finite() || !x.hi.is_finite() || FRAC_PI_2 + k * PI <= x.hi {
                    Iv::TOP
                } else {
                    x.monotone(f64::tan, f64::NEG_INFINITY, f64::INFINITY)
                        .widen(1.0 / 2048.0, 4.0 * f32::EPSILON as f64)
                }
            }
            "asin" => x
                .monotone(f64::asin, -1.0, 1.0)
                .widen(1.0 / 2048.0, 0.0)
                .within(-FRAC_PI_2 - 1e-3, FRAC_PI_2 + 1e-3),
            "acos" => x
                .neg()
                .monotone(|t| (-t).acos(), -1.0, 1.0)
                .widen(1.0 / 2048.0, 0.0)
                .within(0.0, PI + 1e-3),
            "atan" => x
                .monotone(f64::atan, f64::NEG_INFINITY, f64::INFINITY)
                .widen(1.0 / 2048.0, 0.0)
                .within(-FRAC_PI_2 - 1e-3, FRAC_PI_2 + 1e-3),
            "sign" => x.monotone(
                |t| {
                    if t > 0.0 {
                        1.0
                    } else if t < 0.0 {
                        -1.0
                    } else {
                        0.0
                    }
                },
                f64::NEG_INFINITY,
                f64::INFINITY,
            ),
            "saturate" => x.clamp(Iv::point(0.0), Iv::point(1.0)),
            _ => return None,
        })
    }

    pub fn clamp(self, lo: Iv, hi: Iv) -> Iv {
        self.max(lo).min(hi)
    }

    /// `pow(x, y)`: `exp2(y · log2(x))` in WGSL, undefined for x < 0 and
    /// for x = 0 with y ≤ 0 (any value there).
    pub fn pow(self, y: Iv) -> Iv {
        let x = self;
        if x.is_empty() || y.is_empty() {
            return Iv::point(f64::NAN);
        }
        // Outside WGSL's domain the result is indeterminate: any value.
        if x.lo < 0.0 || (x.contains(0.0) && y.lo <= 0.0) || (x.can_be_inf() && y.contains(0.0)) {
            return Iv::TOP;
        }
        let nan = x.nan || y.nan;
        let (xl, xh) = (x.lo, x.hi);
        // On x ≥ 0, x^y is monotone in each argument with the other fixed:
        // the extremes are at the corners (with 0^0 counted as 1 and 0).
        let p = |a: f64, b: f64| -> Vec<f64> {
            if a == 0.0 && b == 0.0 {
                vec![0.0, 1.0]
            } else {
                vec![a.powf(b)]
            }
        };
        let mut c = Vec::new();
        for a in [xl, xh] {
            for b in [y.lo, y.hi] {
                c.extend(p(a, b));
            }
        }
        // x = 1 is where the direction in y turns; y = 0 where it does in x.
        if x.contains(1.0) {
            c.push(1.0);
        }
        if y.contains(0.0) && xl > 0.0 {
            c.push(1.0);
        }
        let m = c
            .iter()
            .filter(|v| v.is_finite() && **v > 0.0)
            .map(|v| v.log2().abs())
            .fold(0.0, f64::max);
        Iv::hull(&c, nan)
            .widen(1e-7, (3.0 + 2.0 * m.min(200.0)) * f32::EPSILON as f64)
            .within(0.0, f64::INFINITY)
    }

    /// `atan2(y, x)` (self is y): within [−π, π]; undefined at (0, 0).
    pub fn atan2(self, x: Iv) -> Iv {
        if self.contains(0.0) && x.contains(0.0) {
            return Iv::TOP;
        }
        let nan = self.nan || x.nan || (self.can_be_inf() && x.can_be_inf());
        let pi = std::f64::consts::PI;
        if x.lo > 0.0 && !self.is_empty() {
            // The right half plane: atan(y / x), monotone in y / x.
            return self.div(x).map1("atan").expect("atan is known").with_nan(nan);
        }
        Iv::new(-pi - 1e-3, pi + 1e-3).with_nan(nan)
    }

    /// `step(edge, x)`: 1 where `x ≥ edge`.
    pub fn step(self, x: Iv) -> Iv {
        let edge = self;
        // A comparison with NaN is false: 0 or 1, never NaN.
        let nan = false;
        if edge.nan || x.nan {
            return Iv::UNIT;
        }
        if x.lo >= edge.hi {
            Iv::point(1.0).with_nan(nan)
        } else if x.hi < edge.lo {
            Iv::point(0.0).with_nan(nan)
        } else {
            Iv::UNIT.with_nan(nan)
        }
    }

    /// `smoothstep(e0, e1, x)`: in [0, 1]; NaN where `e1 − e0` may be 0.
    pub fn smoothstep(e0: Iv, e1: Iv, x: Iv) -> Iv {
        Iv::smoothstep_width(e0, e1, x, e1.sub(e0))
    }

    /// `smoothstep` given the range of `e1 − e0` (which the caller may
    /// know tighter than the difference of the edges' ranges); any value
    /// where the edges may meet or cross (WGSL leaves `low ≥ high` to the
    /// implementation).
    pub fn smoothstep_width(e0: Iv, e1: Iv, x: Iv, width: Iv) -> Iv {
        if width.lo <= 0.0 || width.is_empty() {
            return Iv::TOP;
        }
        // A NaN edge or x: the clamp may give any t in [0, 1], or NaN.
        if e0.nan || e1.nan || x.nan {
            return Iv::UNIT.with_nan(true);
        }
        // An infinite width (an edge at ±inf) makes t = inf/inf, a NaN that
        // the clamp may turn into any t in [0, 1], even past an edge.
        if width.can_be_inf() || !e0.is_finite() || !e1.is_finite() {
            return Iv::UNIT.with_nan(true);
        }
        let nan = width.contains(0.0);
        if width.lo > 0.0 && x.hi <= e0.lo {
            return Iv::point(0.0).with_nan(nan);
        }
        if width.lo > 0.0 && x.lo >= e1.hi {
            return Iv::point(1.0).with_nan(nan);
        }
        Iv::UNIT.with_nan(nan)
    }

    /// `mix(a, b, t)` as WGSL defines it, `a·(1 − t) + b·t`, and within
    /// the hull of `a` and `b` (an f32 ulp out) when `t` is in [0, 1].
    pub fn mix(a: Iv, b: Iv, t: Iv) -> Iv {
        if a.nan || b.nan || t.nan {
            return Iv::TOP;
        }
        let f = a.mul(Iv::point(1.0).sub(t)).add(b.mul(t));
        if t.lo >= 0.0 && t.hi <= 1.0 && !t.nan && a.is_finite() && b.is_finite() {
            let h = a.join(b);
            let h = Iv::new(
                h.lo - h.lo.abs() * 2.0 * f32::EPSILON as f64,
                h.hi + h.hi.abs() * 2.0 * f32::EPSILON as f64,
            );
            return f.meet(h).with_nan(f.nan);
        }
        f
    }

    /// The component-wise built-in `name` of two arguments.
    pub fn map2(self, name: &str, o: Iv) -> Option<Iv> {
        if (self.nan || o.nan) && matches!(name, "pow" | "atan2") {
            return Some(Iv::TOP);
        }
        Some(match name {
            "min" => self.min(o),
            "max" => self.max(o),
            "pow" => self.pow(o),
            "step" => self.step(o),
            "atan2" => self.atan2(o),
            _ => return None,
        })
    }

    /// The component-wise built-in `name` of three arguments.
    pub fn map3(name: &str, a: Iv, b: Iv, c: Iv) -> Option<Iv> {
        Some(match name {
            "clamp" => a.clamp(b, c),
            "smoothstep" => Iv::smoothstep(a, b, c),
            "mix" => Iv::mix(a, b, c),
            _ => return None,
        })
    }
}

impl std::fmt::Display for Iv {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let show = |x: f64| -> String {
            if x == f64::INFINITY {
                "+inf".into()
            } else if x == f64::NEG_INFINITY {
                "-inf".into()
            } else {
                format!("{}", x as f32)
            }
        };
        if self.is_empty() {
            return write!(f, "NaN");
        }
        write!(f, "[{}, {}]", show(self.lo), show(self.hi))?;
        if self.nan {
            write!(f, " or NaN")?;
        }
        Ok(())
    }
}
