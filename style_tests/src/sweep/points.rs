//! The values a stability sweep gives each parameter, and the few pairs it
//! moves together: a declared range is a domain to search, not a default.
//!
//! A number (plain, with a unit, or each component of a vector) takes its
//! range's ends, its middle and then the next points of the van der Corput
//! sequence in base 2 (¼, ¾, ...), which fill the range evenly for any
//! count; an int is rounded and its repeats dropped. A bool and an enum
//! take every value, a colour black and white, a `range` parameter its
//! whole declared span, one point at each end and its middle (a zero-width
//! range is where `smoothstep(a, a, x)` divides by zero). A number without
//! a declared range has no domain to search and keeps its default. Every
//! pair of parameters meets at every pair of their ends in the rows of a
//! covering array (`covering.rs`).
//!
//! Every value is written as `--set` takes it (`format_literal`), so a
//! finding's reproduction is the text the sweep ran.

use npr_abi::param_value::{format_literal, ParamShape, ValueKind};

/// How many points of a numeric range the sweep renders: both ends, the
/// middle and two van der Corput points between (¼ and ¾).
pub const POINTS_PER_RANGE: usize = 5;

/// One parameter's values, as `--set` text, and why a parameter is not swept.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    pub name: String,
    /// The values to render, the two ends (or first and last value) first.
    pub values: Vec<String>,
    /// How many of the first values every other parameter's meet in the
    /// covering array: a number's two ends, every bool or enum value.
    pub levels: usize,
}

/// One rendering of the sweep: `name=value` settings over the defaults.
pub type Combination = Vec<(String, String)>;

/// The first `n` points of the van der Corput sequence in base 2 after 0
/// and 1: ½, ¼, ¾, ⅛, ⅝, ...
fn van_der_corput(n: usize) -> Vec<f64> {
    (1..=n as u32)
        .map(|mut i| {
            let (mut x, mut f) = (0.0, 0.5);
            while i > 0 {
                x += f * f64::from(i & 1);
                i >>= 1;
                f *= 0.5;
            }
            x
        })
        .collect()
}

/// The fractions of a range the sweep renders at: 0, 1, ½, ¼, ¾.
fn fractions() -> Vec<f64> {
    let mut f = vec![0.0, 1.0];
    f.extend(van_der_corput(POINTS_PER_RANGE - 2));
    f
}

/// The values of `p` the sweep renders, or `None` when it is not swept (a
/// per-object parameter, which the scene binds; a number without a range).
pub fn axis(p: &ParamShape) -> Option<Axis> {
    if p.per_object {
        return None;
    }
    let components = p.components.max(1) as usize;
    let mut values: Vec<Vec<f64>> = match p.kind {
        ValueKind::Bool => vec![vec![0.0], vec![1.0]],
        ValueKind::Enum => (0..p.variants.len()).map(|i| vec![i as f64]).collect(),
        ValueKind::Colour => vec![vec![0.0, 0.0, 0.0, 1.0], vec![1.0, 1.0, 1.0, 1.0]],
        ValueKind::Range => {
            let (lo, hi) = p.range?;
            let mid = lo + (hi - lo) * 0.5;
            vec![vec![lo, hi], vec![lo, lo], vec![hi, hi], vec![mid, mid]]
        }
        ValueKind::Float | ValueKind::Int | ValueKind::Unit(_) | ValueKind::Vector => {
            let (lo, hi) = p.range?;
            fractions()
                .into_iter()
                .map(|f| {
                    let v = lo + (hi - lo) * f;
                    let v = if p.kind == ValueKind::Int { v.round() } else { v };
                    vec![v; components]
                })
                .collect()
        }
        // A gradient's stops are a style's design, not a range to sweep.
        ValueKind::Gradient | ValueKind::Unsupported => return None,
    };
    let mut seen = Vec::new();
    values.retain(|v| {
        let fresh = !seen.contains(v);
        seen.push(v.clone());
        fresh
    });
    let values: Vec<String> = values.iter().filter_map(|v| format_literal(p, v)).collect();
    let levels = match p.kind {
        ValueKind::Bool | ValueKind::Enum => values.len(),
        _ => values.len().min(2),
    };
    (values.len() > 1 || (values.len() == 1 && p.kind == ValueKind::Range)).then(|| Axis {
        name: p.name.clone(),
        values,
        levels,
    })
}

/// Every combination the sweep renders, the defaults (no setting) first:
/// each parameter alone at each of its values, then the rows of a
/// strength-2 covering array (`covering.rs`) over the parameters with two
/// levels or more, so that every pair of parameters meets at every pair of
/// their ends (and bool or enum values); a parameter a row leaves free
/// keeps its default.
pub fn combinations(axes: &[Axis]) -> Vec<Combination> {
    let mut all: Vec<Combination> = vec![Vec::new()];
    for a in axes {
        for v in &a.values {
            all.push(vec![(a.name.clone(), v.clone())]);
        }
    }
    let paired: Vec<&Axis> = axes.iter().filter(|a| a.levels >= 2).collect();
    let levels: Vec<usize> = paired.iter().map(|a| a.levels).collect();
    if paired.len() < 2 {
        return all;
    }
    for row in super::covering::covering_array(&levels) {
        let c: Combination = row
            .iter()
            .zip(&paired)
            .filter_map(|(l, a)| l.map(|l| (a.name.clone(), a.values[l].clone())))
            .collect();
        if c.len() >= 2 && !all.contains(&c) {
            all.push(c);
        }
    }
    all
}

/// How many pairs of ends the covering rows cover, of how many pairs.
pub fn pairs_covered(axes: &[Axis]) -> (usize, usize) {
    let levels: Vec<usize> = axes.iter().filter(|a| a.levels >= 2).map(|a| a.levels).collect();
    if levels.len() < 2 {
        return (0, 0);
    }
    let rows = super::covering::covering_array(&levels);
    (
        super::covering::covered_pairs(&levels, &rows),
        super::covering::pair_count(&levels),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shape(ty: &str, range: Option<(f64, f64)>, variants: &[&str]) -> ParamShape {
        ParamShape {
            name: "p".into(),
            ty: ty.into(),
            kind: ValueKind::of(ty),
            components: if ty == "vec2" { 2 } else { 1 },
            range,
            variants: variants.iter().map(|s| s.to_string()).collect(),
            per_object: false,
            default: vec![0.0],
            default_percent_of_height: false,
        }
    }

    #[test]
    fn a_range_gives_its_ends_its_middle_and_van_der_corput_points() {
        assert_eq!(van_der_corput(4), vec![0.5, 0.25, 0.75, 0.125]);
        let a = axis(&shape("float", Some((0.0, 2.0)), &[])).expect("swept");
        assert_eq!(a.values, ["0", "2", "1", "0.5", "1.5"]);
        let a = axis(&shape("int", Some((1.0, 3.0)), &[])).expect("swept");
        assert_eq!(a.values, ["1", "3", "2"], "rounded, repeats dropped");
        let a = axis(&shape("px", Some((0.0, 8.0)), &[])).expect("swept");
        assert_eq!(a.values[..2], ["0px", "8px"]);
        let a = axis(&shape("vec2", Some((-1.0, 1.0)), &[])).expect("swept");
        assert_eq!(a.values[0], "-1, -1");
    }

    #[test]
    fn bools_enums_colours_and_ranges_take_their_own_values() {
        assert_eq!(axis(&shape("bool", None, &[])).expect("bool").values, ["false", "true"]);
        let e = axis(&shape("enum(a|b|c)", None, &["a", "b", "c"])).expect("enum");
        assert_eq!(e.values, ["a", "b", "c"]);
        assert_eq!(
            axis(&shape("color", None, &[])).expect("colour").values,
            ["#000000", "#ffffff"]
        );
        let r = axis(&shape("range", Some((0.0, 1.0)), &[])).expect("range");
        assert_eq!(r.values, ["0..1", "0..0", "1..1", "0.5..0.5"]);
        assert_eq!(axis(&shape("float", None, &[])), None, "no range, no domain");
    }

    #[test]
    fn combinations_are_the_defaults_each_value_alone_and_every_pair_of_ends() {
        let names = ["a", "b", "c", "d", "e"];
        let axes: Vec<Axis> = names
            .iter()
            .map(|n| Axis {
                name: n.to_string(),
                values: vec!["0".into(), "1".into(), "0.5".into()],
                levels: 2,
            })
            .collect();
        let all = combinations(&axes);
        assert_eq!(all[0], Vec::new());
        // The blind spot: the first at its top with the last at its
        // bottom (not neighbours) is rendered together.
        for (x, y) in [("a", "e"), ("b", "d"), ("a", "b")] {
            for (vx, vy) in [("0", "0"), ("0", "1"), ("1", "0"), ("1", "1")] {
                assert!(
                    all.iter()
                        .any(|c| c.contains(&(x.into(), vx.into())) && c.contains(&(y.into(), vy.into()))),
                    "{x}={vx} with {y}={vy} is never rendered"
                );
            }
        }
        let rows = all.len() - 1 - 15;
        assert!(rows <= 8, "{rows} covering rows for 5 params");
        assert_eq!(pairs_covered(&axes), (40, 40));
    }
}
