//! Soundness of the interval arithmetic: random expressions evaluated in
//! f32 (IEEE, as a WGSL implementation that keeps infinities and NaN
//! does) at random points inside their inputs' intervals always land
//! inside the interval [`Iv`] computes, NaN only where it says NaN may be.

use super::interval::Iv;
use proptest::prelude::*;

const MAP1: &[&str] = &[
    "abs", "floor", "ceil", "round", "fract", "sqrt", "exp", "exp2", "log", "log2", "sin", "cos", "tan", "asin",
    "acos", "atan", "sign", "saturate",
];
const MAP2: &[&str] = &["min", "max", "pow", "step", "atan2"];
const MAP3: &[&str] = &["clamp", "smoothstep", "mix"];
const ARITH: &[&str] = &["+", "-", "*", "/", "%"];

#[derive(Debug, Clone)]
enum E {
    Var(usize),
    Const(f32),
    Neg(Box<E>),
    Sqr(Box<E>),
    Arith(&'static str, Box<E>, Box<E>),
    Map1(&'static str, Box<E>),
    Map2(&'static str, Box<E>, Box<E>),
    Map3(&'static str, Box<E>, Box<E>, Box<E>),
}

fn expr() -> impl Strategy<Value = E> {
    let leaf = prop_oneof![
        (0..3usize).prop_map(E::Var),
        prop_oneof![Just(0.0f32), Just(1.0), Just(-1.0), Just(0.5), -100.0f32..100.0].prop_map(E::Const),
    ];
    leaf.prop_recursive(5, 24, 3, |inner| {
        prop_oneof![
            inner.clone().prop_map(|a| E::Neg(Box::new(a))),
            inner.clone().prop_map(|a| E::Sqr(Box::new(a))),
            (prop::sample::select(ARITH), inner.clone(), inner.clone()).prop_map(|(o, a, b)| E::Arith(
                o,
                Box::new(a),
                Box::new(b)
            )),
            (prop::sample::select(MAP1), inner.clone()).prop_map(|(f, a)| E::Map1(f, Box::new(a))),
            (prop::sample::select(MAP2), inner.clone(), inner.clone()).prop_map(|(f, a, b)| E::Map2(
                f,
                Box::new(a),
                Box::new(b)
            )),
            (prop::sample::select(MAP3), inner.clone(), inner.clone(), inner).prop_map(|(f, a, b, c)| E::Map3(
                f,
                Box::new(a),
                Box::new(b),
                Box::new(c)
            )),
        ]
    })
}

/// An input interval: ends that matter (0, ±1) often, else random.
fn var_range() -> impl Strategy<Value = (f32, f32)> {
    let end = prop_oneof![Just(0.0f32), Just(1.0), Just(-1.0), -10.0f32..10.0, -1e4f32..1e4];
    (end.clone(), end).prop_map(|(a, b)| (a.min(b), a.max(b)))
}

fn interval(e: &E, vars: &[Iv]) -> Iv {
    match e {
        E::Var(i) => vars[*i],
        E::Const(c) => Iv::point(*c as f64),
        E::Neg(a) => interval(a, vars).neg(),
        E::Sqr(a) => interval(a, vars).sqr(),
        E::Arith(op, a, b) => {
            let (a, b) = (interval(a, vars), interval(b, vars));
            match *op {
                "+" => a.add(b),
                "-" => a.sub(b),
                "*" => a.mul(b),
                "/" => a.div(b),
                _ => a.rem(b),
            }
        }
        E::Map1(f, a) => interval(a, vars).map1(f).expect("known"),
        E::Map2(f, a, b) => interval(a, vars).map2(f, interval(b, vars)).expect("known"),
        E::Map3(f, a, b, c) => Iv::map3(f, interval(a, vars), interval(b, vars), interval(c, vars)).expect("known"),
    }
}

fn clamp(x: f32, lo: f32, hi: f32) -> f32 {
    x.max(lo).min(hi)
}

/// The expression in f32, as WGSL defines each function.
fn eval(e: &E, x: &[f32]) -> f32 {
    match e {
        E::Var(i) => x[*i],
        E::Const(c) => *c,
        E::Neg(a) => -eval(a, x),
        E::Sqr(a) => {
            let v = eval(a, x);
            v * v
        }
        E::Arith(op, a, b) => {
            let (a, b) = (eval(a, x), eval(b, x));
            match *op {
                "+" => a + b,
                "-" => a - b,
                "*" => a * b,
                "/" => a / b,
                _ => a % b,
            }
        }
        E::Map1(f, a) => {
            let v = eval(a, x);
            match *f {
                "abs" => v.abs(),
                "floor" => v.floor(),
                "ceil" => v.ceil(),
                "round" => v.round_ties_even(),
                "fract" => v - v.floor(),
                "sqrt" => v.sqrt(),
                "exp" => v.exp(),
                "exp2" => v.exp2(),
                "log" => v.ln(),
                "log2" => v.log2(),
                "sin" => v.sin(),
                "cos" => v.cos(),
                "tan" => v.tan(),
                "asin" => v.asin(),
                "acos" => v.acos(),
                "atan" => v.atan(),
                "sign" => {
                    if v > 0.0 {
                        1.0
                    } else if v < 0.0 {
                        -1.0
                    } else {
                        v * 0.0
                    }
                }
                _ => clamp(v, 0.0, 1.0),
            }
        }
        E::Map2(f, a, b) => {
            let (a, b) = (eval(a, x), eval(b, x));
            match *f {
                "min" => a.min(b),
                "max" => a.max(b),
                "pow" => a.powf(b),
                "step" => {
                    if b >= a {
                        1.0
                    } else {
                        0.0
                    }
                }
                _ => a.atan2(b),
            }
        }
        E::Map3(f, a, b, c) => {
            let (a, b, c) = (eval(a, x), eval(b, x), eval(c, x));
            match *f {
                "clamp" => clamp(a, b, c),
                "smoothstep" => {
                    let t = clamp((c - a) / (b - a), 0.0, 1.0);
                    t * t * (3.0 - 2.0 * t)
                }
                _ => a * (1.0 - c) + b * c,
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4000, ..ProptestConfig::default() })]

    #[test]
    fn every_f32_value_lies_in_the_computed_interval(
        e in expr(),
        ranges in prop::array::uniform3(var_range()),
        picks in prop::collection::vec(prop::array::uniform3(0.0f64..=1.0), 16),
    ) {
        let vars: Vec<Iv> = ranges.iter().map(|(lo, hi)| Iv::new(*lo as f64, *hi as f64)).collect();
        let iv = interval(&e, &vars);
        // The ends themselves, then points between.
        let ends = [[0.0; 3], [1.0; 3], [0.0, 1.0, 0.0], [1.0, 0.0, 1.0]];
        for t in ends.iter().chain(picks.iter()) {
            let x: Vec<f32> = (0..3)
                .map(|i| {
                    let (lo, hi) = ranges[i];
                    clamp((lo as f64 + t[i] * (hi as f64 - lo as f64)) as f32, lo, hi)
                })
                .collect();
            let y = eval(&e, &x);
            prop_assert!(
                iv.contains(y as f64),
                "{e:?} at {x:?} is {y}, outside {iv} (inputs {:?})",
                ranges
            );
        }
    }
}

#[test]
fn division_by_a_range_holding_zero_is_unbounded() {
    let q = Iv::new(1.0, 2.0).div(Iv::new(-1.0, 1.0));
    assert!(!q.is_finite());
    // 1 / −0 is −∞: a divisor range touching 0 gives both infinities.
    let q = Iv::new(1.0, 2.0).div(Iv::new(0.0, 1.0));
    assert_eq!((q.lo, q.hi), (f64::NEG_INFINITY, f64::INFINITY));
    let q = Iv::new(1.0, 2.0).div(Iv::new(0.5, 4.0));
    assert_eq!((q.lo, q.hi), (0.25, 4.0));
    assert!(Iv::new(0.0, 2.0).div(Iv::new(0.0, 1.0)).nan, "0 / 0 may be NaN");
}

#[test]
fn pow_outside_its_domain_may_be_anything() {
    // pow(0, y ≤ 0) and pow(x < 0, y) are undefined in WGSL.
    assert_eq!(Iv::new(0.0, 1.0).pow(Iv::new(-0.5, 3.0)), Iv::TOP);
    assert_eq!(Iv::new(-1.0, 1.0).pow(Iv::point(2.0)), Iv::TOP);
    let p = Iv::new(0.0, 1.0).pow(Iv::new(1.0, 3.0));
    assert!(p.is_finite() && p.lo == 0.0 && p.hi >= 1.0 && p.hi < 1.001, "{p}");
}

/// The proved range of each target of `text` (compiled from `examples/`).
fn target_ranges(text: &str) -> Vec<super::TargetRange> {
    let mut sources = npr_diag::SourceMap::new();
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples");
    crate::compile_source("case.npr", text, &dir, &mut sources, &crate::CompileOptions::default())
        .unwrap_or_else(|e| panic!("{e:?}"))
        .ranges
}

#[test]
fn a_history_that_grows_every_frame_is_not_proved_finite_in_a_float_target() {
    let r = target_ranges(
        "style \"Acc\"\npass acc: image() {\n  out a: r32float = previous(acc.a) + 1.0\n}\noutput acc.a\n",
    );
    assert_eq!(r.len(), 1);
    assert!(!r[0].value_finite, "x + 1 every frame has no bound: {}", r[0].range);
}

#[test]
fn a_history_through_a_unorm_target_stays_in_its_range_and_finite() {
    let r = target_ranges(
        "style \"Fade\"\nparam k: float = 0.5 in 0..0.9\npass f: image() {\n  out a: r8unorm = mix(screen_uv.x, previous(f.a), k)\n}\noutput f.a\n",
    );
    assert!(r[0].value_finite, "{}", r[0].range);
    assert_eq!(r[0].range.hull().to_string(), "[0, 1]");
}

#[test]
fn a_store_in_f16_is_bounded_by_the_values_range() {
    let r = target_ranges(
        "style \"H\"\nparam g: float = 2.0 in 1..10\npass p: image() {\n  out a: r16float = screen_uv.x * g\n}\noutput p.a\n",
    );
    assert!(r[0].value_finite);
    let c = r[0].range.comps[0];
    assert!(c.lo == 0.0 && (10.0..10.01).contains(&c.hi), "{}", r[0].range);
}

/// The range codes of the warnings compiling `text`, and its targets' ranges.
fn range_warnings(text: &str) -> (Vec<&'static str>, Vec<super::TargetRange>) {
    let mut sources = npr_diag::SourceMap::new();
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples");
    let c = crate::compile_source("case.npr", text, &dir, &mut sources, &crate::CompileOptions::default())
        .unwrap_or_else(|e| panic!("{e:?}"));
    let codes = c
        .warnings
        .iter()
        .map(|d| d.code)
        .filter(|c| c.starts_with("W02"))
        .collect();
    (codes, c.ranges)
}

fn tangent_style(axis: &str) -> String {
    format!(
        "style \"T\"\npass p: render(scene) {{\n  let t1 = normalize(cross(normal, {axis}))\n  out c: rgba16float = vec4(t1, 1.0)\n}}\noutput p.c\n"
    )
}

#[test]
fn a_tangent_from_an_axis_the_normal_is_kept_away_from_is_proved_non_zero() {
    // dynamic_pattern.npr's frame: in each branch of the `if`, the normal
    // is narrowed by the condition, and Lagrange's identity bounds the
    // cross product's length below (0.43 and 0.9).
    let guarded = "if abs(normal.x) < 0.9 { vec3(1.0, 0.0, 0.0) } else { vec3(0.0, 1.0, 0.0) }";
    let (codes, ranges) = range_warnings(&tangent_style(guarded));
    assert!(codes.is_empty(), "{codes:?}");
    assert!(ranges[0].value_finite, "{}", ranges[0].range);
    // The same with the comparison the other way round.
    let flipped = "if 0.9 > abs(normal.x) { vec3(1.0, 0.0, 0.0) } else { vec3(0.0, 1.0, 0.0) }";
    assert!(range_warnings(&tangent_style(flipped)).0.is_empty());
    // Controls: an axis the normal may lie along, and a guard on the wrong
    // component, stay warned (W0208).
    for unsafe_axis in [
        "vec3(1.0, 0.0, 0.0)",
        "if abs(normal.y) < 0.9 { vec3(1.0, 0.0, 0.0) } else { vec3(0.0, 1.0, 0.0) }",
        "if abs(normal.x) < 0.9 { vec3(0.0, 1.0, 0.0) } else { vec3(1.0, 0.0, 0.0) }",
    ] {
        let (codes, _) = range_warnings(&tangent_style(unsafe_axis));
        assert_eq!(codes, ["W0208"], "{unsafe_axis}");
    }
}

#[test]
fn a_filters_result_stays_within_its_inputs_texels() {
    let style = |read: &str| {
        format!(
            "style \"F\"\npass g: render(scene) {{\n  out d: r16float = saturate(depth) + 2.0\n}}\npass b: image(g) {{\n  out e: r32float = {read}\n}}\noutput b.e\n"
        )
    };
    // A target in [2, 3] where drawn, 0 where cleared: blurred and sampled
    // it stays in [0, 3] (an f16 step or so above), so sqrt and log(x + 1)
    // are safe.
    for read in [
        "sqrt(gaussian(g.d, sigma: 2.0, axis: x).r)",
        "log(sample(g.d, uv: screen_uv).r + 1.0)",
        "sqrt(downsample(g.d).r)",
        // A one-channel target reads as (r, 0, 0, 1): its alpha is 1.
        "log(sample(g.d, uv: screen_uv).a)",
    ] {
        let (codes, ranges) = range_warnings(&style(read));
        assert!(codes.is_empty(), "{read}: {codes:?}");
        let b = ranges.iter().find(|r| r.name == "b.e").expect("b.e");
        assert!(b.value_finite, "{read}: {}", b.range);
    }
    let (_, ranges) = range_warnings(&style("gaussian(g.d, sigma: 2.0, axis: x).r"));
    let c = ranges.iter().find(|r| r.name == "b.e").expect("b.e").range.comps[0];
    // (r16float rounds 3 up by 2⁻¹¹ of itself at most.)
    assert!(c.lo == 0.0 && c.hi > 3.0 && c.hi < 3.002, "{c}");
    // The cleared 0 is in the hull: x − 1 may be negative (W0204); and the
    // green of a one-channel target is 0 (W0203).
    assert_eq!(
        range_warnings(&style("sqrt(gaussian(g.d, sigma: 2.0, axis: x).r - 1.0)")).0,
        ["W0204"]
    );
    assert_eq!(range_warnings(&style("log(sample(g.d, uv: screen_uv).g)")).0, ["W0203"]);
    // A float target with no bound keeps its filter unbounded.
    let (_, ranges) =
        range_warnings(&style("gaussian(g.d, sigma: 2.0, axis: x).r").replace("saturate(depth) + 2.0", "depth * 1e30"));
    assert!(!ranges.iter().find(|r| r.name == "b.e").expect("b.e").value_finite);
}

fn state_style(update: &str) -> String {
    format!(
        "style \"S\"\npass st: compute(objects) {{\n  state s: float = 1.0\n  s = {update}\n}}\npass p: render(scene) {{\n  out c: r32float = sqrt(st.s)\n}}\noutput p.c\n"
    )
}

#[test]
fn a_per_object_state_is_followed_across_frames() {
    // Halved every frame from 1: in [0, 1] on every frame, so its sqrt is
    // safe and the target proved finite.
    let (codes, ranges) = range_warnings(&state_style("s * 0.5"));
    assert!(codes.is_empty(), "{codes:?}");
    let c = ranges.iter().find(|r| r.name == "p.c").expect("p.c");
    assert!(c.value_finite, "{}", c.range);
    assert_eq!(c.range.hull().to_string(), "[0, 1]");
    // Made negative from the second frame on (down to −1): sqrt is warned.
    assert_eq!(range_warnings(&state_style("max(s - 2.0, -1.0)")).0, ["W0204"]);
    // Doubled every frame: no bound, widened, not proved finite.
    let (_, ranges) = range_warnings(&state_style("s * 2.0 + 1.0"));
    assert!(!ranges.iter().find(|r| r.name == "p.c").expect("p.c").value_finite);
}

#[test]
fn the_dot_of_a_difference_with_itself_is_not_negative() {
    // `dot(a − b, a − b)` written twice is two nodes of one value: |a − b|².
    let style = "style \"D\"\npass p: render(scene) {\n  out c: r32float = sqrt(dot(normal - view_dir, normal - view_dir))\n}\noutput p.c\n";
    assert!(range_warnings(style).0.is_empty());
    // A different second operand is a dot product, which may be negative.
    let other = style.replace(
        "dot(normal - view_dir, normal - view_dir)",
        "dot(normal - view_dir, view_dir - normal)",
    );
    assert_eq!(range_warnings(&other).0, ["W0204"]);
}
