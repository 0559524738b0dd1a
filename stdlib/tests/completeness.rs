//! Every operator is complete (issue 12): WGSL that naga accepts (with its
//! snippets and dependencies), a WGSL signature that matches its metadata,
//! a doc line, a paper or source reference, an f64 reference function under
//! its own name, at least one GPU-against-reference case that the generic
//! GPU test (`gpu_cases.rs`) can build from its signature, defaults inside
//! their ranges, a footprint per texture parameter, and a demo: a style
//! that calls it on a scene of `examples/` (which `npr doc` renders), or an
//! explicit reason why no image can show it.

use naga::valid::{Capabilities, ValidationFlags, Validator};
use npr_stdlib::ops::{style_calls as calls, Arg, Demo, Tol};
use npr_stdlib::{Default, Ty};

/// The order of `npr_stdlib::all()` when the operators moved into folders:
/// the IR names operators by their index, snapshots and compiled styles
/// follow it, so registrations only ever append.
const HISTORIC_ORDER: &[&str] = &[
    "lambert",
    "half_lambert",
    "toon",
    "threshold",
    "gaussian",
    "downsample",
    "sobel",
    "normal_depth_edges",
    "over",
    "luminance",
    "saturation",
    "overlay",
    "sample",
    "metatexture_grad",
    "metatexture",
    "metatexture4_grad",
    "metatexture4",
    "shadow",
    "contour_fade",
    "reprojection_mask",
    "stereo_consistency",
    "radial_alpha",
    "uv_gradients",
    "metatexture_contour_grad",
    "metatexture_contour",
    "live_texture",
    "line_boil",
    "roll_compensate",
    "distance_attenuate",
    "warp",
    "lsa",
    "lsa_sum",
    "lsa_curv_aa",
    "lsa_curv",
    "lsa_density",
    "id_share",
    "complex_mul",
    "pattern_uv",
    "halftone_screen",
    "halftone",
    "sample_biased",
    "sample_ripmap",
    "oct_encode",
    "oct_decode",
];

fn wgsl_with_deps(op: &npr_stdlib::Operator) -> String {
    let mut src = String::new();
    for s in op.snippets {
        src.push_str(npr_stdlib::snippets::find(s).unwrap_or_else(|| panic!("{}: unknown snippet {s}", op.name)));
        src.push('\n');
    }
    // Dependencies are transitive, as the emitter resolves them.
    let mut deps: Vec<&str> = Vec::new();
    let mut todo: Vec<&str> = op.depends.to_vec();
    while let Some(d) = todo.pop() {
        if deps.contains(&d) || d == op.name {
            continue;
        }
        deps.push(d);
        let dep = npr_stdlib::find(d).unwrap_or_else(|| panic!("{}: unknown dependency {d}", op.name));
        todo.extend(dep.depends);
        for s in dep.snippets {
            assert!(op.snippets.contains(s), "{}: needs snippet {s} of {d}", op.name);
        }
    }
    for d in deps {
        src.push_str(npr_stdlib::find(d).expect("checked above").wgsl);
        src.push('\n');
    }
    src.push_str(op.wgsl);
    src
}

fn naga_type_matches(module: &naga::Module, ty: naga::Handle<naga::Type>, want: Ty) -> bool {
    use naga::{ScalarKind, TypeInner, VectorSize};
    let inner = &module.types[ty].inner;
    match (want, inner) {
        (Ty::Float, TypeInner::Scalar(s)) => s.kind == ScalarKind::Float,
        (Ty::Int | Ty::Enum(_), TypeInner::Scalar(s)) => s.kind == ScalarKind::Sint,
        (Ty::Bool, TypeInner::Scalar(s)) => s.kind == ScalarKind::Bool,
        (
            Ty::Vec2,
            TypeInner::Vector {
                size: VectorSize::Bi, ..
            },
        ) => true,
        (
            Ty::Vec3,
            TypeInner::Vector {
                size: VectorSize::Tri, ..
            },
        ) => true,
        (
            Ty::Vec4 | Ty::Color,
            TypeInner::Vector {
                size: VectorSize::Quad, ..
            },
        ) => true,
        (Ty::Texture | Ty::SampledTexture, TypeInner::Image { .. }) => true,
        _ => false,
    }
}

#[test]
fn every_operator_is_complete() {
    assert!(!npr_stdlib::all().is_empty());
    for op in npr_stdlib::all() {
        let src = wgsl_with_deps(op);
        let module =
            naga::front::wgsl::parse_str(&src).unwrap_or_else(|e| panic!("{}: {}", op.name, e.emit_to_string(&src)));
        Validator::new(ValidationFlags::all(), Capabilities::all())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{}: {}", op.name, e.emit_to_string(&src)));
        let fname = op.wgsl_fn();
        let (_, f) = module
            .functions
            .iter()
            .find(|(_, f)| f.name.as_deref() == Some(fname.as_str()))
            .unwrap_or_else(|| panic!("{}: WGSL has no function {fname}", op.name));
        // Expand metadata parameters to WGSL arguments: a sampled texture is (texture, sampler).
        let mut expected: Vec<Option<Ty>> = Vec::new();
        for p in op.params {
            expected.push(Some(p.ty));
            if p.ty == Ty::SampledTexture {
                expected.push(None);
            }
        }
        assert_eq!(f.arguments.len(), expected.len(), "{}: argument count", op.name);
        for (arg, want) in f.arguments.iter().zip(&expected) {
            match want {
                Some(t) => assert!(
                    naga_type_matches(&module, arg.ty, *t),
                    "{}: argument {:?} is not {t:?}",
                    op.name,
                    arg.name
                ),
                None => assert!(
                    matches!(module.types[arg.ty].inner, naga::TypeInner::Sampler { .. }),
                    "{}: expected a sampler",
                    op.name
                ),
            }
        }
        let ret = f
            .result
            .as_ref()
            .unwrap_or_else(|| panic!("{}: no return value", op.name));
        assert!(
            naga_type_matches(&module, ret.ty, op.returns),
            "{}: return type is not {:?}",
            op.name,
            op.returns
        );
        assert!(
            !op.doc.is_empty() && !op.reference.is_empty(),
            "{}: missing doc or reference",
            op.name
        );
        assert!(
            !op.doc.trim().is_empty() && !op.doc.contains('\n'),
            "{}: the doc is one line",
            op.name
        );
        let def =
            npr_stdlib::ops::find(op.name).unwrap_or_else(|| panic!("{}: not registered in npr_stdlib::ops", op.name));
        assert_eq!(
            def.reference_fn, op.name,
            "{}: the f64 reference is not under its name",
            op.name
        );
        for p in op.params {
            assert!(!p.doc.is_empty(), "{}.{}: no doc", op.name, p.name);
            if let (Default::Number(v), Some((lo, hi))) = (p.default, p.range) {
                assert!(
                    lo <= v && v <= hi,
                    "{}.{}: default {v} outside {lo}..{hi}",
                    op.name,
                    p.name
                );
            }
            if let (Default::Variant(v), Ty::Enum(vs)) = (p.default, p.ty) {
                assert!(
                    vs.contains(&v),
                    "{}.{}: default variant {v} not in {vs:?}",
                    op.name,
                    p.name
                );
            }
        }
    }
}

#[test]
fn operator_names_are_unique() {
    let mut names: Vec<&str> = npr_stdlib::all().iter().map(|o| o.name).collect();
    names.sort();
    let n = names.len();
    names.dedup();
    assert_eq!(n, names.len());
}

#[test]
fn specializations_keep_the_remaining_parameters_in_order() {
    // The replacement takes the parameters of the original, matched by name
    // and in order, minus the specialized one (and parameters that only the
    // disabled feature reads, such as `band` when contour orientation is off).
    for op in npr_stdlib::all() {
        for s in op.specializations {
            let alt =
                npr_stdlib::find(s.use_operator).unwrap_or_else(|| panic!("{}: unknown {}", op.name, s.use_operator));
            assert!(
                alt.param(s.param).is_none(),
                "{} → {} keeps {}",
                op.name,
                alt.name,
                s.param
            );
            let mut rest = op.params.iter().filter(|p| p.name != s.param);
            for a in alt.params {
                assert!(
                    rest.any(|p| p == a),
                    "{} → {}: `{}` is not a parameter of the original in this order",
                    op.name,
                    alt.name,
                    a.name
                );
            }
            assert_eq!(alt.returns, op.returns, "{} → {}", op.name, alt.name);
            let p = op.param(s.param).expect("specialized parameter exists");
            assert!(p.range.is_none_or(|(lo, hi)| lo <= s.value && s.value <= hi));
        }
    }
}

/// Every texture parameter has exactly one footprint (issue 14), naming a
/// real `uv` parameter (a vec2) and, for a scaled radius, a numeric one.
#[test]
fn every_texture_parameter_has_a_footprint() {
    for op in npr_stdlib::all() {
        let textures: Vec<&str> = op
            .params
            .iter()
            .filter(|p| matches!(p.ty, Ty::Texture | Ty::SampledTexture))
            .map(|p| p.name)
            .collect();
        let declared: Vec<&str> = op.footprints.iter().map(|(n, _)| *n).collect();
        assert_eq!(
            declared, textures,
            "{}: footprints must list the texture parameters in order",
            op.name
        );
        for (name, f) in op.footprints {
            if let npr_stdlib::Footprint::Around { uv, radius } = f {
                let p = op
                    .param(uv)
                    .unwrap_or_else(|| panic!("{}.{name}: no parameter `{uv}`", op.name));
                assert_eq!(p.ty, Ty::Vec2, "{}.{name}: `{uv}` is not a vec2", op.name);
                if let npr_stdlib::Radius::Scaled { param, k, max } = radius {
                    let p = op
                        .param(param)
                        .unwrap_or_else(|| panic!("{}.{name}: no parameter `{param}`", op.name));
                    assert!(
                        matches!(p.ty, Ty::Float | Ty::Int),
                        "{}.{name}: `{param}` is not a number",
                        op.name
                    );
                    assert!(*k > 0.0 && *max > 0, "{}.{name}", op.name);
                }
            }
        }
    }
}

/// Every registered operator has GPU cases that the generic test can run:
/// one argument per parameter, of a kind the parameter's type takes.
#[test]
fn every_registered_operator_has_gpu_cases() {
    let names: Vec<&str> = npr_stdlib::all().iter().map(|o| o.name).collect();
    assert!(
        names.starts_with(HISTORIC_ORDER),
        "npr_stdlib::all() reordered: register new operators at the end"
    );
    for def in npr_stdlib::ops::ALL {
        let op = &def.op;
        assert!(!def.cases.is_empty(), "{}: no GPU-against-reference case", op.name);
        for (c, case) in def.cases.iter().enumerate() {
            let label = format!("{} case {c} ({})", op.name, case.what);
            assert_eq!(case.args.len(), op.params.len(), "{label}: one argument per parameter");
            assert!(case.pixels.0 > 0 && case.pixels.1 > 0, "{label}: no pixels");
            assert!((0.0..1.0).contains(&case.max_skipped), "{label}: skips everything");
            let (Tol::Abs(t) | Tol::Rel(t)) = case.tol;
            assert!(t.is_finite() && t >= 0.0, "{label}: tolerance {t}");
            for (p, a) in op.params.iter().zip(case.args) {
                let fits = match a {
                    Arg::Texture(_) => matches!(p.ty, Ty::Texture | Ty::SampledTexture),
                    Arg::Uv => p.ty == Ty::Vec2,
                    Arg::ScreenUv { .. } => p.ty == Ty::Vec2,
                    Arg::Const(_) | Arg::Each(_) | Arg::Random { .. } => {
                        !matches!(p.ty, Ty::Texture | Ty::SampledTexture)
                    }
                    Arg::From { arg, .. } => {
                        !matches!(p.ty, Ty::Texture | Ty::SampledTexture)
                            && matches!(
                                case.args.get(*arg),
                                Some(Arg::Const(_) | Arg::Each(_) | Arg::Random { .. })
                            )
                    }
                };
                assert!(fits, "{label}: argument for `{}` ({:?}) does not fit", p.name, p.ty);
                if let Arg::Each(v) = a {
                    assert!(!v.is_empty(), "{label}: `{}` has no values", p.name);
                }
                if let Arg::Random { n, .. } = a {
                    assert!(*n > 0, "{label}: `{}` has no values", p.name);
                }
            }
        }
    }
}

/// Every operator has a demo for `npr doc`: a style that calls it, on a
/// scene of `examples/` that exists, with a one-sentence description (the
/// image's alt text); or `Demo::NoDemo` with its reason. A missing demo
/// fails here.
#[test]
fn every_operator_has_a_demo() {
    let examples = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples");
    for def in npr_stdlib::ops::ALL {
        let name = def.op.name;
        match def.demo {
            Demo::Missing => panic!(
                "{name}: no demo: add `.with_demo(demos::…)` with a style that calls it (ops/<family>/demos.rs), \
                 or `Demo::NoDemo(\"why no image can show it\")`"
            ),
            Demo::Render(d) => {
                assert!(calls(d.style, name), "{name}: the demo style does not call `{name}(`");
                assert!(
                    d.style.trim_start().starts_with("style "),
                    "{name}: the demo style does not start with `style \"…\"`"
                );
                let shows = d.shows.trim();
                assert!(
                    shows.len() >= 20 && shows.ends_with('.') && !shows.contains('\n'),
                    "{name}: say what the image shows in one sentence (its alt text): {shows:?}"
                );
                assert!(
                    examples.join(d.scene).is_file(),
                    "{name}: the demo's scene examples/{} does not exist",
                    d.scene
                );
                assert!(
                    d.time_s.is_finite() && d.time_s >= 0.0,
                    "{name}: demo time {}",
                    d.time_s
                );
            }
            Demo::NoDemo(why) => assert!(
                why.trim().len() >= 20,
                "{name}: `Demo::NoDemo` needs a reason in words, not {why:?}"
            ),
        }
    }
}

#[test]
fn a_call_is_found_by_its_whole_name() {
    assert!(calls("let x = sample(t, uv)", "sample"));
    assert!(calls("sample(t, uv)", "sample"));
    assert!(!calls("let x = sample_biased(t, uv)", "sample"));
    assert!(!calls("let x = resample(t, uv)", "sample"));
}
