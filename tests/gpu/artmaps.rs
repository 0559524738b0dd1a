//! Art-maps (Klein et al. 2000 §4.2) through the compiler and the runner:
//! the level each read selects with `sample_biased`, against the f64 level
//! of detail; stroke size on screen across distances, against a plain
//! mip-mapped texture of the same strokes; rip-maps; filter chains and
//! filter arguments. The cache is `tests/gpu/artmap_cache.rs`.

use crate::common;

use common::artmaps::{compile, grey_png, render, scene, scratch};
use common::{gpu, root};
use std::path::Path;

/// How a level-of-detail test reads its levels: `out v: rgba16float =
/// read(case)` from `texture levels = decl` (a 256² grey source, filtered
/// so that every level holds its own index or size), decoded by `got` from
/// the texel, against `want(case)` at `pixels`, within `tolerance` levels.
struct LevelReads<R, W, G> {
    decl: String,
    read: R,
    want: W,
    got: G,
    pixels: [(u32, u32); 3],
    tolerance: f64,
}

/// Every case of `reads` rendered into a 64² image and checked; the worst
/// error, in levels.
fn check_levels<C, R, W, G>(dir: &Path, cases: &[C], reads: LevelReads<R, W, G>) -> f64
where
    C: std::fmt::Debug,
    R: Fn(&C) -> String,
    W: Fn(&C) -> Vec<f64>,
    G: Fn([f32; 4]) -> Vec<f64>,
{
    grey_png(&dir.join("src.png"), 256, 128);
    let mut worst: f64 = 0.0;
    for case in cases {
        let text = format!(
            "style \"levels\"\ntexture levels = {}\n\
             pass read: image() {{\n  out v: rgba16float = {}\n}}\n\
             output read.v\n",
            reads.decl,
            (reads.read)(case)
        );
        let img = render(&compile(&text, dir), &npr_runner::scene::Scene::empty(), 64);
        let want = (reads.want)(case);
        for (x, y) in reads.pixels {
            let got = (reads.got)(img.texel(x, y));
            for (axis, (g, w)) in got.iter().zip(&want).enumerate() {
                let err = (g - w).abs();
                worst = worst.max(err);
                assert!(
                    err <= reads.tolerance,
                    "{case:?} at ({x}, {y}), axis {axis}: level {g:.4}, the reference {w:.4}"
                );
            }
        }
    }
    worst
}

#[test]
fn sample_biased_selects_the_level_of_detail_of_the_reference() {
    let filter = root().join("tests/data/artmaps/level_index.npr");
    let size = 64.0;
    // (k, bias): uv = screen_uv · k moves k / size per pixel along each axis.
    let cases = [
        (0.25, 0.0),
        (0.5, 0.0),
        (1.0, 0.0),
        (1.5, 0.0),
        (3.0, 0.0),
        (10.0, 0.0),
        (1.0, -1.0),
        (1.0, 0.5),
        (1.0, 2.0),
        (0.7, 3.3),
        (0.3, -2.0),
    ];
    // llvmpipe computes the level with a fast log2 approximation (0.04
    // level off seen at k = 10) and quantizes the trilinear weight; the
    // result is stored in half floats: 1/16 of a level. The reference is
    // clamped to levels 0..8, and each level holds its index / 16.
    let reads = LevelReads {
        decl: format!(
            "artmap(image(\"src.png\", linear), filter: \"{}\") {{ wrap: repeat }}",
            filter.display()
        ),
        read: |(k, bias): &(f64, f64)| format!("sample_biased(levels, screen_uv * {k:.4}, bias: {bias:.4})"),
        want: |&(k, bias): &(f64, f64)| {
            let lod = npr_stdlib::reference::sample_biased_lod([k / size, 0.0], [0.0, k / size], 256, 256, bias);
            vec![npr_stdlib::reference::sample_biased(lod, 9, 0.0625) / 0.0625]
        },
        got: |t: [f32; 4]| vec![f64::from(t[0]) / 0.0625],
        pixels: [(0, 0), (31, 17), (63, 63)],
        tolerance: 1.0 / 16.0,
    };
    let worst = check_levels(&scratch("lod"), &cases, reads);
    eprintln!("worst level error: {worst:.5}");
}

/// The stroke period along the middle row of `img`, in px: the first strong
/// peak of the row's autocorrelation past its first dip, refined by a
/// parabola.
fn stroke_period(img: &npr_runner::TargetImage) -> Option<f64> {
    let y = img.height / 2;
    let row: Vec<f64> = (0..img.width)
        .map(|x| {
            let t = img.texel(x, y);
            0.2126 * t[0] as f64 + 0.7152 * t[1] as f64 + 0.0722 * t[2] as f64
        })
        .collect();
    let mean = row.iter().sum::<f64>() / row.len() as f64;
    let centred: Vec<f64> = row.iter().map(|v| v - mean).collect();
    let n = centred.len();
    let ac =
        |lag: usize| -> f64 { (0..n - lag).map(|i| centred[i] * centred[i + lag]).sum::<f64>() / (n - lag) as f64 };
    let max_lag = n / 3;
    let values: Vec<f64> = (0..=max_lag).map(ac).collect();
    let dip = (1..max_lag).find(|&l| values[l] < 0.0)?;
    // The first local maximum that is at least half the highest past the
    // dip: the period itself, not a multiple where beats line up.
    let highest = values[dip..max_lag].iter().cloned().fold(f64::MIN, f64::max);
    let peak = (dip.max(1)..max_lag)
        .find(|&l| values[l] >= values[l - 1] && values[l] >= values[l + 1] && values[l] >= 0.5 * highest)?;
    if peak == 0 || peak >= max_lag || values[peak] <= 0.1 * values[0] {
        return None;
    }
    let (a, b, c) = (values[peak - 1], values[peak], values[peak + 1]);
    let shift = 0.5 * (a - c) / (a - 2.0 * b + c);
    Some(peak as f64 + shift.clamp(-0.5, 0.5))
}

/// A plane facing the camera `d` m away, filling a 40° view.
fn plane_scene(d: f64) -> npr_runner::scene::Scene {
    scene(&format!(
        "[camera]\nposition = [0.0, 0.0, {d}]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\nnear = 0.1\nfar = 400.0\n\n\
         [[object]]\nname = \"wall\"\nprimitive = {{ kind = \"plane\", size = 200.0, subdivisions = 1 }}\nrotate = [90.0, 0.0, 0.0]\n"
    ))
}

/// The shipped hatching filter with strokes `spacing` texels apart, as a
/// `filter:` argument.
fn hatching_spaced(spacing: f64) -> String {
    format!(
        "filter(\"{}\", spacing: {spacing:?})",
        root().join("examples/filters/hatching.npr").display()
    )
}

#[test]
fn art_map_strokes_keep_their_size_on_screen_where_plain_mips_shrink_as_one_over_distance() {
    let dir = scratch("stroke_size");
    let spacing = 8.0;
    // sRGB 200: linear 0.58, one layer of strokes (below `cross_above`).
    // 1024 texels: level 6, chosen at 64 m, is 16 texels, still two stroke
    // periods (a level smaller than one period cannot hold its strokes).
    let texels = 1024u32;
    grey_png(&dir.join("src.png"), texels, 200);

    let size = 128u32;
    // uv repeats so that one level-0 texel is one pixel 1 m away.
    let px_per_m = |d: f64| size as f64 / (2.0 * d * 20f64.to_radians().tan());
    let repeat = 200.0 * px_per_m(1.0) / texels as f64;
    let style = |texture: &str| {
        format!(
            "style \"strokes\"\n{texture}\n\
             pass shade: render(scene) {{\n  out color: rgba16float = vec4(sample_biased(t, uv * {repeat:.5}).rgb, 1.0)\n  clear: #ffffff\n}}\n\
             output shade.color\n"
        )
    };
    // The shipped hatching filter with strokes `spacing` texels apart.
    let artmap = compile(
        &style(&format!(
            "texture t = artmap(image(\"src.png\", srgb), filter: {}) {{ wrap: repeat }}",
            hatching_spaced(spacing)
        )),
        &dir,
    );
    // Level 0 of the art-map as a plain texture, mip-mapped by box filter:
    // the art-map's own filter run on the full-size level.
    let g = gpu();
    let filter_program = match &artmap.manifest.textures[0].source {
        npr_abi::manifest::TextureSourceManifest::Artmap(spec) => spec.filter.program(),
        other => panic!("not an art-map: {other:?}"),
    };
    let base = npr_runner::artmap::Level {
        width: texels,
        height: texels,
        pixels: vec![[0.58, 0.58, 0.58, 1.0]; (texels * texels) as usize],
    };
    let level0 = npr_runner::artmap::filter_level(&g.device, &g.queue, &filter_program, &base, 0).unwrap();
    let plain = image::Rgba32FImage::from_fn(texels, texels, |x, y| {
        image::Rgba(level0.pixels[(y * texels + x) as usize])
    });
    image::DynamicImage::ImageRgba32F(plain)
        .to_rgba16()
        .save(dir.join("plain.png"))
        .unwrap();
    let mipped = compile(
        &style("texture t = image(\"plain.png\", linear) { wrap: repeat, mips: on }"),
        &dir,
    );
    let mut rows = Vec::new();
    for d in [1.0, 1.5, 2.0, 3.0, 4.0, 5.7, 8.0, 11.0, 16.0, 23.0, 32.0, 45.0, 64.0] {
        let s = plane_scene(d);
        let art = stroke_period(&render(&artmap, &s, size));
        let plain = stroke_period(&render(&mipped, &s, size));
        rows.push((d, art, plain));
    }
    for (d, art, plain) in &rows {
        eprintln!(
            "d {d:>5} m: art-map period {art:?} px, plain mips {plain:?} px (target {spacing}, 1/d law {:.2})",
            spacing / d
        );
    }
    for (d, art, _) in &rows {
        let p = art.unwrap_or_else(|| panic!("no stroke period on the art-map at {d} m"));
        assert!(
            (0.7 * spacing..=1.5 * spacing).contains(&p),
            "art-map at {d} m: period {p:.2} px, outside [0.7, 1.5] × {spacing}"
        );
    }
    // Plain mips: the level-0 strokes shrink as 1/d while they are still
    // resolved (then the mips blur them to grey: no period at all).
    for (d, _, plain) in rows.iter().filter(|r| r.0 <= 3.0) {
        let p = plain.unwrap_or_else(|| panic!("no stroke period with plain mips at {d} m"));
        let law = spacing / d;
        assert!(
            (p / law - 1.0).abs() < 0.15,
            "plain mips at {d} m: period {p:.2} px, not {law:.2} (1/d)"
        );
    }
    let far_plain = rows
        .iter()
        .filter(|r| r.0 >= 8.0)
        .filter_map(|r| r.2)
        .collect::<Vec<_>>();
    assert!(
        far_plain.iter().all(|p| *p < 0.7 * spacing),
        "plain mips far away kept a stroke period near the target: {far_plain:?}"
    );
}

#[test]
fn sample_ripmap_selects_a_level_per_axis_as_the_reference() {
    let filter = root().join("tests/data/artmaps/level_size.npr");
    let size = 64.0;
    let cases = [
        (1.0, 1.0),
        (0.25, 4.0),
        (4.0, 0.25),
        (1.0, 16.0),
        (10.0, 0.7),
        (0.1, 0.1),
        (100.0, 3.0),
    ];
    // The shader's own log2 (not the sampler's LOD), the blend of four
    // levels and half-float storage: 1/64 of a level. Each level holds
    // log2 of its size / 16: 8 − level on a 256² source.
    let reads = LevelReads {
        decl: format!("ripmap(image(\"src.png\", linear), filter: \"{}\")", filter.display()),
        read: |(ku, kv): &(f64, f64)| {
            format!("sample_ripmap(levels, vec2(screen_uv.x * {ku:.4}, screen_uv.y * {kv:.4}))")
        },
        want: |&(ku, kv): &(f64, f64)| {
            let lods = npr_stdlib::reference::sample_ripmap_lods([ku / size, 0.0], [0.0, kv / size], 256, 256);
            npr_stdlib::reference::sample_ripmap(lods, [9, 9], 1.0).to_vec()
        },
        got: |t: [f32; 4]| vec![8.0 - 16.0 * f64::from(t[0]), 8.0 - 16.0 * f64::from(t[1])],
        pixels: [(0, 0), (40, 9), (63, 63)],
        tolerance: 1.0 / 64.0,
    };
    let worst = check_levels(&scratch("rip_lod"), &cases, reads);
    eprintln!("worst level error: {worst:.5}");
}

/// The stroke period along the middle column of `img`, in px.
fn column_period(img: &npr_runner::TargetImage) -> Option<f64> {
    let mut t = npr_runner::TargetImage {
        name: img.name.clone(),
        width: img.height,
        height: img.width,
        format: img.format,
        bytes: Vec::with_capacity(img.bytes.len()),
    };
    let bpp = img.format.bytes_per_pixel() as usize;
    for y in 0..t.height {
        for x in 0..t.width {
            let i = (x as usize * img.width as usize + y as usize) * bpp;
            t.bytes.extend_from_slice(&img.bytes[i..i + bpp]);
        }
    }
    stroke_period(&t)
}

#[test]
fn rip_maps_keep_the_strokes_aspect_on_oblique_planes_where_mipped_art_maps_stretch_them() {
    let dir = scratch("rip_aspect");
    let spacing = 8.0;
    let filter = hatching_spaced(spacing);
    grey_png(&dir.join("src.png"), 512, 200);
    let size = 128u32;
    let (d, fov) = (40.0f64, 6.0f64);
    // Two level-0 texels per pixel along u at the plane's centre.
    let px_per_m = size as f64 / (2.0 * d * (fov / 2.0).to_radians().tan());
    let repeat = 200.0 * px_per_m * 2.0 / 512.0;
    let style = |decl: &str, read: &str| {
        format!(
            "style \"aspect\"\n{decl}\n\
             pass shade: render(scene) {{\n  out color: rgba16float = vec4({read}.rgb, 1.0)\n  clear: #ffffff\n}}\n\
             output shade.color\n"
        )
    };
    let art = compile(
        &style(
            &format!("texture t = artmap(image(\"src.png\", srgb), filter: {filter}) {{ wrap: repeat }}"),
            &format!("sample_biased(t, uv * {repeat:.5})"),
        ),
        &dir,
    );
    let rip = compile(
        &style(
            &format!("texture t = ripmap(image(\"src.png\", srgb), filter: {filter})"),
            &format!("sample_ripmap(t, uv * {repeat:.5})"),
        ),
        &dir,
    );
    // Across / down stroke periods; `None` across when the strokes are
    // stretched past a third of the row (where the autocorrelation looks).
    let aspect = |program: &npr_runner::StyleProgram, tilt: f64| -> Option<f64> {
        let scene = scene(&format!(
            "[camera]\nposition = [0.0, 0.0, {d}]\ntarget = [0.0, 0.0, 0.0]\nfov = {fov}\nnear = 0.1\nfar = 400.0\n\n\
             [[object]]\nname = \"wall\"\nprimitive = {{ kind = \"plane\", size = 200.0, subdivisions = 1 }}\nrotate = [{:.3}, 0.0, 0.0]\n",
            90.0 - tilt
        ));
        let img = render(program, &scene, size);
        let down = column_period(&img).unwrap_or_else(|| panic!("no period down at {tilt}°"));
        stroke_period(&img).map(|across| across / down)
    };
    let art_face = aspect(&art, 0.0).expect("art-map face-on");
    let rip_face = aspect(&rip, 0.0).expect("rip-map face-on");
    eprintln!("face-on aspect: art-map {art_face:.3}, rip-map {rip_face:.3}");
    for tilt in [60.0, 70.0, 80.0, 85.0] {
        let r = aspect(&rip, tilt).unwrap_or_else(|| panic!("rip-map at {tilt}°: no stroke period across")) / rip_face;
        let a = aspect(&art, tilt).map(|a| a / art_face);
        eprintln!("{tilt}°: stroke aspect against face-on: art-map {a:?} (None: past the window), rip-map {r:.2}");
        assert!(
            (1.0 / 1.5..=1.5).contains(&r),
            "rip-map at {tilt}°: aspect {r:.2} × face-on"
        );
        if let Some(a) = a {
            assert!(
                a > 1.5,
                "mipped art-map at {tilt}°: aspect {a:.2} × face-on, expected stretched"
            );
        }
    }
}

#[test]
fn one_filter_renderer_for_a_whole_chain_gives_what_a_renderer_per_level_gives() {
    // `artmap::build` reuses one filter renderer across levels (pipelines
    // built once); each level must come out texel for texel as a fresh
    // renderer makes it, with `frame` the level's index. The ink-blot
    // filter has three passes and reads `frame`, hatching one.
    let g = gpu();
    for filter in ["ink_blot", "hatching"] {
        let text = std::fs::read_to_string(root().join(format!("examples/filters/{filter}.npr"))).unwrap();
        let program = compile(&text, &root().join("examples/filters"));
        let base = npr_runner::artmap::Level {
            width: 40,
            height: 24,
            pixels: (0..40 * 24)
                .map(|i| {
                    let v = ((i * 37) % 101) as f32 / 100.0;
                    [v, 1.0 - v, 0.5, 1.0]
                })
                .collect(),
        };
        let chain = npr_runner::artmap::mip_chain(base, u32::MAX);
        let mut reused = npr_runner::artmap::FilterRunner::new(&g.device, &g.queue, &program);
        for (index, level) in chain.iter().enumerate() {
            let fresh = npr_runner::artmap::filter_level(&g.device, &g.queue, &program, level, index as u32).unwrap();
            let again = reused.filter(level, index as u32).unwrap();
            assert_eq!(
                again, fresh,
                "{filter}: level {index} ({}x{})",
                level.width, level.height
            );
        }
    }
}

#[test]
fn filter_arguments_at_the_call_site_are_the_filter_with_those_defaults() {
    // `filter("hatching.npr", spacing: 8)` against a copy of the filter file
    // whose default is 8: the same art-map, texel for texel, on a plane.
    let dir = scratch("filter-args");
    std::fs::create_dir_all(dir.join("filters")).unwrap();
    grey_png(&dir.join("src.png"), 64, 90);
    let hatching = std::fs::read_to_string(root().join("examples/filters/hatching.npr")).unwrap();
    std::fs::write(dir.join("filters/hatching.npr"), &hatching).unwrap();
    let copied = hatching.replace("param spacing: float = 4 in 2..32", "param spacing: float = 8 in 2..32");
    assert_ne!(copied, hatching, "the hatching filter's spacing default moved");
    std::fs::write(dir.join("filters/hatching8.npr"), copied).unwrap();
    let style = |filter: &str| {
        format!(
            "style \"Args\"\ntexture t = artmap(image(\"src.png\", srgb), filter: {filter})\npass p: render(scene) {{\n  out c: rgba8unorm = sample(t, uv * 2.0)\n}}\noutput p.c\n"
        )
    };
    let plane = scene(
        "[camera]\nposition = [0.0, 0.0, 2.2]\ntarget = [0.0, 0.0, 0.0]\n\n[[object]]\nprimitive = { kind = \"plane\", size = 2.0 }\nrotate = [90.0, 0.0, 0.0]\n",
    );
    let with_args = render(
        &compile(&style("filter(\"filters/hatching.npr\", spacing: 8)"), &dir),
        &plane,
        64,
    );
    let with_file = render(&compile(&style("\"filters/hatching8.npr\""), &dir), &plane, 64);
    let with_default = render(&compile(&style("\"filters/hatching.npr\""), &dir), &plane, 64);
    let texels = |img: &npr_runner::TargetImage| -> Vec<[f32; 4]> {
        (0..img.height)
            .flat_map(|y| (0..img.width).map(move |x| (x, y)))
            .map(|(x, y)| img.texel(x, y))
            .collect()
    };
    assert_eq!(texels(&with_args), texels(&with_file), "the argument is the default 8");
    assert_ne!(texels(&with_args), texels(&with_default), "and not the default 4");
}

#[test]
fn an_enum_filter_argument_chooses_the_filters_variant_by_name() {
    // `filter("tone.npr", tone: light)` as `--set tone=light` would: each
    // variant makes its own grey at every level; no argument keeps `mid`.
    let dir = scratch("filter-enum");
    grey_png(&dir.join("src.png"), 16, 90);
    std::fs::write(
        dir.join("tone.npr"),
        "style \"tone\"\ntexture level = filter_input()\n/// Which grey.\nparam tone: enum(dark, mid, light) = mid\n\
         pass p: image() {\n  let g = if tone == dark { 0.1 } else if tone == light { 0.9 } else { 0.5 }\n  \
         out c: rgba16float = vec4(g + level.r * 0.0, g, g, 1.0)\n}\noutput p.c\n",
    )
    .unwrap();
    let grey = |filter: &str| {
        let text = format!(
            "style \"enum arg\"\ntexture t = artmap(image(\"src.png\", linear), filter: {filter})\n\
             pass read: image() {{\n  out v: rgba16float = sample(t, screen_uv)\n}}\noutput read.v\n"
        );
        let img = render(&compile(&text, &dir), &npr_runner::scene::Scene::empty(), 16);
        f64::from(img.texel(8, 8)[0])
    };
    for (filter, want) in [
        ("filter(\"tone.npr\", tone: dark)", 0.1),
        ("filter(\"tone.npr\", tone: light)", 0.9),
        ("filter(\"tone.npr\", tone: mid)", 0.5),
        ("\"tone.npr\"", 0.5),
    ] {
        let got = grey(filter);
        // The art-map's levels are stored in 8 bits.
        assert!((got - want).abs() <= 1.0 / 255.0 + 1e-3, "{filter}: {got}, want {want}");
    }
}
