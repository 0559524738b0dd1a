//! Each operator's declared result range (`OpDef::range`, issue 49: the
//! compiler's range analysis takes it as proved) holds for its f64
//! reference at the ends of its arguments: every combination of hard
//! values (zero, tiny, ±1, huge, each parameter's declared range ends)
//! for each numeric parameter.

use npr_stdlib::ops::{Val, ALL};
// Rounding past a bound by a few f32 ulps is allowed (`RANGE_SLACK`).
use npr_stdlib::Ty;

/// Hard scalars: zero, tiny, ±1, between, and huge ones.
const SCALARS: &[f64] = &[-1e18, -2.0, -1.0, -1e-20, 0.0, 1e-20, 0.25, 0.5, 1.0, 2.0, 1e18];
const INTS: &[f64] = &[-5.0, 0.0, 1.0, 2.0, 3.0, 255.0];

/// The hard values of one parameter (its declared range ends added).
fn values(ty: Ty, range: Option<(f64, f64)>) -> Option<Vec<[f64; 4]>> {
    let within = |x: f64| range.is_none_or(|(lo, hi)| lo <= x && x <= hi);
    let mut scalars: Vec<f64> = match ty {
        Ty::Int | Ty::Enum(_) => INTS.to_vec(),
        Ty::Bool => vec![0.0, 1.0],
        _ => SCALARS.to_vec(),
    };
    if let Some((lo, hi)) = range {
        scalars.extend([lo, hi, 0.5 * (lo + hi)]);
    }
    scalars.retain(|x| within(*x));
    let n = match ty {
        Ty::Float | Ty::Int | Ty::Bool | Ty::Enum(_) => 1,
        Ty::Vec2 => 2,
        Ty::Vec3 => 3,
        Ty::Vec4 | Ty::Color => 4,
        Ty::Texture | Ty::SampledTexture => return None,
    };
    if n == 1 {
        return Some(scalars.iter().map(|x| [*x, 0.0, 0.0, 0.0]).collect());
    }
    // Vectors: every component at one hard value, each axis alone, and
    // opposite huge components.
    let mut out = Vec::new();
    for x in &scalars {
        out.push([*x, *x, if n > 2 { *x } else { 0.0 }, if n > 3 { *x } else { 0.0 }]);
        for axis in 0..n {
            let mut v = [0.0; 4];
            v[axis] = *x;
            out.push(v);
        }
    }
    out.push([1e18, -1e18, 0.0, 1.0]);
    Some(out)
}

#[test]
fn every_declared_result_range_holds_at_the_argument_ends() {
    let mut checked = 0;
    for def in ALL.iter().filter(|d| d.range.is_some()) {
        let (lo, hi) = def.range_with_slack().expect("filtered");
        let params: Vec<Vec<[f64; 4]>> = def
            .op
            .params
            .iter()
            .map(|p| values(p.ty, p.range))
            .collect::<Option<_>>()
            .unwrap_or_else(|| {
                panic!(
                    "`{}` declares a range but reads a texture: no test for that yet",
                    def.op.name
                )
            });
        let components = match def.op.returns {
            Ty::Vec2 => 2,
            Ty::Vec3 => 3,
            Ty::Vec4 | Ty::Color => 4,
            _ => 1,
        };
        // Every combination (odometer over the parameters' values).
        let mut idx = vec![0usize; params.len()];
        loop {
            let args: Vec<Val> = idx.iter().zip(&params).map(|(i, v)| Val::Num(v[*i])).collect();
            let r = (def.eval)(&args);
            for (c, y) in r.iter().take(components).enumerate() {
                assert!(
                    (lo..=hi).contains(y),
                    "`{}` at {:?} gives {y} in component {c}, outside its declared range [{lo}, {hi}]",
                    def.op.name,
                    args.iter().map(|a| a.v4()).collect::<Vec<_>>()
                );
            }
            checked += 1;
            let mut k = 0;
            while k < idx.len() {
                idx[k] += 1;
                if idx[k] < params[k].len() {
                    break;
                }
                idx[k] = 0;
                k += 1;
            }
            if k == idx.len() {
                break;
            }
        }
    }
    assert!(
        checked > 1000,
        "only {checked} calls checked: no operator declares a range?"
    );
}

/// Each filter that declares its result within its texels' hull
/// (`OpDef::texel_hull`, issue 49: the range analysis bounds a filter's
/// result by what its input holds) stays there for its f64 reference:
/// random textures with texels in boxes on either side of 0 and across
/// it, read anywhere (outside [0, 1]² too), its other parameters at
/// their hard values.
#[test]
fn every_texel_hull_filter_stays_within_its_texels() {
    use npr_stdlib::image_f64::ImageF64;
    use npr_stdlib::ops::OpDef;
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut random = move || {
        // xorshift64*: a fixed sequence, so a failure reproduces.
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut checked = 0;
    let mut filters = Vec::new();
    for def in ALL.iter().filter(|d| d.texel_hull.is_some()) {
        filters.push(def.op.name);
        let hull_param = def.texel_hull.expect("filtered");
        for (lo, hi) in [(0.0, 1.0), (-3.0, -1.0), (-2.0, 5.0), (2.0, 4.0), (0.0, 0.0)] {
            let (w, h) = (3 + (random() * 20.0) as u32, 2 + (random() * 20.0) as u32);
            let texels: Vec<[f64; 4]> = (0..w * h)
                .map(|_| std::array::from_fn(|_| lo + (hi - lo) * random()))
                .collect();
            let image = ImageF64::new(w, h, |x, y| texels[(y * w + x) as usize]);
            // Every texel at an end at once, too: the hull's corners.
            let corner = ImageF64::new(w, h, |x, y| if (x + y) % 2 == 0 { [lo; 4] } else { [hi; 4] });
            let (slo, shi) = OpDef::hull_with_slack(lo, hi);
            for tex in [&image, &corner] {
                let others: Vec<Vec<[f64; 4]>> = def
                    .op
                    .params
                    .iter()
                    .filter(|p| p.name != hull_param)
                    .map(|p| match p.ty {
                        Ty::Vec2 => (0..12)
                            .map(|_| [random() * 1.6 - 0.3, random() * 1.6 - 0.3, 0.0, 0.0])
                            .chain([[0.0; 4], [1.0, 1.0, 0.0, 0.0]])
                            .collect(),
                        _ => values(p.ty, p.range).expect("a number"),
                    })
                    .collect();
                let mut idx = vec![0usize; others.len()];
                loop {
                    let mut k = 0;
                    let args: Vec<Val> = def
                        .op
                        .params
                        .iter()
                        .map(|p| {
                            if p.name == hull_param {
                                Val::Tex(tex)
                            } else {
                                k += 1;
                                Val::Num(others[k - 1][idx[k - 1]])
                            }
                        })
                        .collect();
                    let r = (def.eval)(&args);
                    for (c, y) in r.iter().enumerate() {
                        assert!(
                            (slo..=shi).contains(y),
                            "`{}` over texels in [{lo}, {hi}] gives {y} in component {c}",
                            def.op.name
                        );
                    }
                    checked += 1;
                    let mut k = 0;
                    while k < idx.len() {
                        idx[k] += 1;
                        if idx[k] < others[k].len() {
                            break;
                        }
                        idx[k] = 0;
                        k += 1;
                    }
                    if k == idx.len() {
                        break;
                    }
                }
            }
        }
    }
    filters.sort();
    assert_eq!(
        filters,
        ["downsample", "gaussian", "sample"],
        "the filters that declare a hull"
    );
    assert!(checked > 500, "only {checked} calls checked");
}
