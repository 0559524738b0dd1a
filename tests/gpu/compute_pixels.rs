//! Compute passes over the pixels of an ID target (`compute(pixels, ids.id)`)
//! on the real runner: per-object sums, minima and maxima of pixel values
//! against a CPU f64 reduction of the read-back ID image, at sizes that are
//! not multiples of the 16 × 16 tile, with tiles holding many objects, with a
//! half-resolution ID target, with a tag, and with hundreds of objects (and
//! the workgroup count that the partials budget gives many objects).

use npr_abi::manifest::PassKindManifest;
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Renderer, StyleProgram};

use crate::common;
use common::{gpu, root};

fn program(text: &str) -> StyleProgram {
    common::compile_text(text)
}

fn scene_from(text: &str) -> Scene {
    npr_runner::scene::parse_scene(text, npr_diag::FileId(0), root()).unwrap_or_else(|d| panic!("{d:?}"))
}

/// A grid of `n × n` small spheres that overlap on screen (so tiles hold
/// several IDs), in front of a ground plane tagged `ground`.
fn crowd(n: usize) -> String {
    let mut s = String::from(
        "[camera]\nposition = [0.0, 0.0, 6.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\nnear = 0.1\nfar = 50.0\n\n\
         [light]\ndirection = [0.5, 1.0, 0.7]\ncolor = [1.0, 1.0, 1.0]\nintensity = 1.0\n\n",
    );
    let step = 3.6 / n as f64;
    for i in 0..n {
        for j in 0..n {
            let (x, y) = (-1.8 + step * (i as f64 + 0.5), -1.8 + step * (j as f64 + 0.5));
            s += &format!(
                "[[object]]\nprimitive = {{ kind = \"sphere\", radius = {:.4}, segments = 12, rings = 8 }}\ntranslate = [{x:.4}, {y:.4}, {:.3}]\n\n",
                step * 0.62,
                0.01 * ((i * 7 + j * 3) % 5) as f64
            );
        }
    }
    s += "[[object]]\nprimitive = { kind = \"plane\", size = 20.0, subdivisions = 1 }\nrotate = [90.0, 0.0, 0.0]\ntranslate = [0.0, 0.0, -1.0]\ntags = [\"ground\"]\n";
    s
}

/// The style under test: an ID image and a value image, reduced per object.
fn style(kind_args: &str, id_scale: &str) -> String {
    format!(
        r#"style "Pixels"
pass ids: render(scene) {id_scale} {{
  out id: r32float = object.id
  out v: r32float = position.world.x * 3.0 + position.world.y
}}
pass cover: compute({kind_args}) {{
  reduce count: float = sum(1.0)
  reduce centre: vec2 = sum(frag_coord)
  reduce lo: vec2 = min(frag_coord)
  reduce hi: vec2 = max(frag_coord)
  reduce v_sum: float = sum(ids.v)
  reduce v_max: float = max(ids.v + object.id)
}}
pass show: render(scene) {{
  out c: rgba32float = vec4(cover.count, cover.centre.x + cover.lo.x + cover.hi.y, cover.v_sum, cover.v_max)
}}
output show.c
"#
    )
}

/// Per object: count, Σx, Σy, min x, min y, max x, max y, Σv, max(v + id).
#[derive(Debug, Clone, Copy)]
struct Expected {
    count: f64,
    sum: [f64; 2],
    lo: [f64; 2],
    hi: [f64; 2],
    v_sum: f64,
    v_max: f64,
}

fn target_index(program: &StyleProgram, name: &str) -> usize {
    program
        .manifest
        .targets
        .iter()
        .position(|t| t.name == name)
        .unwrap_or_else(|| panic!("no target {name}"))
}

fn slot(program: &StyleProgram, name: &str) -> usize {
    let p = program
        .manifest
        .passes
        .iter()
        .find(|p| p.name == "cover")
        .expect("cover");
    match &p.kind {
        PassKindManifest::Compute { values, .. } => values.iter().position(|v| v.name == name).expect("value"),
        _ => panic!("not compute"),
    }
}

/// Render at `w × h`, read the ID and value images back, and compare every
/// object's values with an f64 reduction of them. Returns how many objects
/// cover some pixel, and the most distinct IDs in one tile.
fn check(program: &StyleProgram, scene: &Scene, (w, h): (u32, u32), members: impl Fn(usize) -> bool) -> (usize, usize) {
    let mut r = Renderer::new(&gpu().device, &gpu().queue, program, scene).expect("renderer");
    let spec = FrameSpec::still(w, h, 0);
    let ids = r
        .render_until_target(scene, &spec, target_index(program, "ids.id"))
        .expect("ids");
    let vs = r
        .render_until_target(scene, &spec, target_index(program, "ids.v"))
        .expect("v");
    r.render(scene, &spec).expect("frame");
    let got = r.read_object_values("cover").expect("values");
    let n = scene.objects.len();
    let mut want = vec![
        Expected {
            count: 0.0,
            sum: [0.0; 2],
            lo: [f32::MAX as f64; 2],
            hi: [-f32::MAX as f64; 2],
            v_sum: 0.0,
            v_max: -f32::MAX as f64,
        };
        n
    ];
    let mut tiles: std::collections::BTreeMap<(u32, u32), std::collections::BTreeSet<u32>> = Default::default();
    for y in 0..ids.height {
        for x in 0..ids.width {
            let id = ids.texel(x, y)[0];
            assert_eq!(id, id.round(), "an ID is an integer: {id} at ({x}, {y})");
            if id < 1.0 {
                continue;
            }
            tiles.entry((x / 16, y / 16)).or_default().insert(id as u32);
            let o = id as usize - 1;
            let v = vs.texel(x, y)[0] as f64;
            let (fx, fy) = (x as f64 + 0.5, y as f64 + 0.5);
            let e = &mut want[o];
            e.count += 1.0;
            e.sum[0] += fx;
            e.sum[1] += fy;
            e.lo = [e.lo[0].min(fx), e.lo[1].min(fy)];
            e.hi = [e.hi[0].max(fx), e.hi[1].max(fy)];
            e.v_sum += v;
            // The GPU adds in f32; the maximum itself is exact.
            e.v_max = e.v_max.max((vs.texel(x, y)[0] + id) as f64);
        }
    }
    let s = |name| slot(program, name);
    let close = |got: f32, want: f64, scale: f64, what: &str, o: usize| {
        // f32 pairwise sums: a few ulps of the magnitude summed.
        let tol = 1e-6 * scale.max(1.0) * 8.0;
        assert!(
            (got as f64 - want).abs() <= tol,
            "object {o} {what}: GPU {got} vs f64 {want} (tolerance {tol:e})"
        );
    };
    for o in 0..n {
        let g = &got[o];
        if !members(o) {
            assert!(
                g.iter().flatten().all(|x| *x == 0.0),
                "object {o} is not a member: {g:?}"
            );
            continue;
        }
        let e = want[o];
        assert_eq!(g[s("count")][0] as f64, e.count, "object {o} pixel count");
        let (centre, lo, hi) = (g[s("centre")], g[s("lo")], g[s("hi")]);
        for k in 0..2 {
            close(centre[k], e.sum[k], e.count * w.max(h) as f64, "Σ frag_coord", o);
            assert_eq!(lo[k] as f64, e.lo[k], "object {o} min frag_coord[{k}]");
            assert_eq!(hi[k] as f64, e.hi[k], "object {o} max frag_coord[{k}]");
        }
        close(g[s("v_sum")][0], e.v_sum, e.count * 10.0, "Σ v", o);
        assert_eq!(g[s("v_max")][0] as f64, e.v_max, "object {o} max(v + id)");
    }
    let covered = want.iter().filter(|e| e.count > 0.0).count();
    let most = tiles.values().map(|t| t.len()).max().unwrap_or(0);
    (covered, most)
}

#[test]
fn pixel_reductions_match_a_cpu_f64_reduction_of_the_id_image() {
    let program = program(&style("pixels, ids.id", ""));
    let scene = scene_from(&crowd(5));
    // 100 × 75: neither side is a multiple of the 16-pixel tile.
    let (covered, most) = check(&program, &scene, (100, 75), |_| true);
    assert_eq!(covered, scene.objects.len(), "every object is on screen");
    assert!(most >= 4, "some tile holds several objects (most: {most})");
}

#[test]
fn a_half_resolution_id_target_and_a_tag() {
    // The ID target at scale 1/2: the pass runs over its pixels.
    let program = program(&style("pixels, ids.id, ground", "scale 1/2"));
    let scene = scene_from(&crowd(3));
    let ground = scene.objects.iter().position(|o| o.has_tag("ground")).expect("ground");
    let (covered, _) = check(&program, &scene, (90, 61), |o| o == ground);
    assert_eq!(covered, scene.objects.len());
}

#[test]
fn nine_hundred_objects_with_dozens_per_tile_stay_exact() {
    // 30 × 30 + 1 objects at 64 × 64: dozens of rounds in one tile.
    let program = program(&style("pixels, ids.id", ""));
    let scene = scene_from(&crowd(30));
    let (covered, most) = check(&program, &scene, (64, 64), |_| true);
    assert!(covered > 800, "most objects cover a pixel: {covered}");
    assert!(most >= 16, "tiles hold many objects (most: {most})");
}

#[test]
fn pixel_workgroups_follow_the_size_and_the_budget() {
    use npr_abi::manifest::{pixel_workgroups, MAX_PIXEL_WORKGROUPS, PIXEL_PARTIALS_BUDGET, PIXEL_TILE};
    assert_eq!(PIXEL_TILE, 32);
    assert_eq!(pixel_workgroups((1, 1), 1, 1), 1);
    assert_eq!(pixel_workgroups((32, 32), 3, 2), 1);
    assert_eq!(pixel_workgroups((33, 32), 3, 2), 2);
    assert_eq!(pixel_workgroups((100, 75), 3, 2), 4 * 3);
    assert_eq!(pixel_workgroups((4096, 4096), 3, 2), MAX_PIXEL_WORKGROUPS);
    // Many objects: the partials stay within the budget.
    let (objects, values) = (200_000u64, 8u64);
    let g = pixel_workgroups((4096, 4096), objects, values) as u64;
    assert!(g >= 1 && g * objects * values * 16 <= PIXEL_PARTIALS_BUDGET.max(objects * values * 16));
    assert!(g < MAX_PIXEL_WORKGROUPS as u64);
}
