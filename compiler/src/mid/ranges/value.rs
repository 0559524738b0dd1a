//! [`Val`]: the range of one IR value, an interval per component, with a
//! bound on a vector's length where one is known (unit normals, results of
//! `normalize`), so that `dot` of unit vectors stays in [−1, 1].

use super::interval::Iv;

/// The range of a value: one interval per component (one for a scalar),
/// and for a vector maybe a bound on its length.
#[derive(Debug, Clone, PartialEq)]
pub struct Val {
    pub comps: Vec<Iv>,
    pub norm: Option<Iv>,
}

/// A few ulps around 1: the length of a vector normalized in f32.
pub fn unit_norm() -> Iv {
    Iv::new(1.0 - 4.0 * f32::EPSILON as f64, 1.0 + 4.0 * f32::EPSILON as f64)
}

impl Val {
    pub fn scalar(i: Iv) -> Val {
        Val {
            comps: vec![i],
            norm: None,
        }
    }

    pub fn splat(i: Iv, n: usize) -> Val {
        Val {
            comps: vec![i; n.max(1)],
            norm: None,
        }
    }

    /// A unit vector of `n` components, each within [−1, 1] (an ulp out).
    pub fn unit(n: usize) -> Val {
        let c = unit_norm().hi;
        Val {
            comps: vec![Iv::new(-c, c); n],
            norm: Some(unit_norm()),
        }
    }

    pub fn top(n: usize) -> Val {
        Val::splat(Iv::TOP, n)
    }

    pub fn join(&self, o: &Val) -> Val {
        let n = self.comps.len().max(o.comps.len());
        Val {
            comps: (0..n).map(|i| self.at(i).join(o.at(i))).collect(),
            norm: match (self.norm, o.norm) {
                (Some(a), Some(b)) => Some(a.join(b)),
                _ => None,
            },
        }
    }

    /// Component `i`, a scalar broadcast to any index.
    pub fn at(&self, i: usize) -> Iv {
        if self.comps.len() == 1 {
            self.comps[0]
        } else {
            self.comps.get(i).copied().unwrap_or(Iv::TOP)
        }
    }

    /// The union of every component.
    pub fn hull(&self) -> Iv {
        self.comps.iter().copied().reduce(Iv::join).unwrap_or(Iv::TOP)
    }

    pub fn is_finite(&self) -> bool {
        self.comps.iter().all(|c| c.is_finite())
    }

    /// Component-wise `f` over operands broadcast to the widest.
    pub fn zip(args: &[&Val], f: impl Fn(&[Iv]) -> Iv) -> Val {
        let n = args.iter().map(|a| a.comps.len()).max().unwrap_or(1);
        Val {
            comps: (0..n)
                .map(|i| f(&args.iter().map(|a| a.at(i)).collect::<Vec<_>>()))
                .collect(),
            norm: None,
        }
    }

    /// The squared length's range, from the components.
    pub fn length_sq(&self) -> Iv {
        self.comps
            .iter()
            .map(|c| c.sqr())
            .reduce(Iv::add)
            .unwrap_or(Iv::point(0.0))
    }

    /// The length's range: from the components, and the known bound.
    pub fn length(&self) -> Iv {
        let l = self.length_sq().map1("sqrt").expect("sqrt is known");
        match self.norm {
            Some(n) => l.meet(n).with_nan(l.nan),
            None => l,
        }
    }
}

impl std::fmt::Display for Val {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.comps.len() == 1 {
            return write!(f, "{}", self.comps[0]);
        }
        let all_same = self.comps.iter().all(|c| *c == self.comps[0]);
        if all_same {
            return write!(f, "{} in each component", self.comps[0]);
        }
        let parts: Vec<String> = self.comps.iter().map(|c| c.to_string()).collect();
        write!(f, "({})", parts.join(", "))
    }
}
