//! The screen-space tangent frame builtins (Age of Sail §3.2) end to end on
//! the GPU: `tangent.screen` / `bitangent.screen` computed in the vertex
//! shader and interpolated match the analytic Jacobian of the projection at
//! each pixel's surface point; `tangent.screen_center` is the centre camera's
//! in both stereo eyes (so both eyes pick the same MetaTexture levels) and
//! equals `tangent.screen` in mono; `camera.focal` is (P₀₀, P₁₁).

use glam::{DMat4, DVec3, DVec4};
use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use npr_runner::{FrameSpec, Gpu};
use std::path::Path;
use std::sync::OnceLock;

fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Gpu> = OnceLock::new();
    GPU.get_or_init(|| Gpu::headless().unwrap_or_else(|e| panic!("runner tests need a GPU adapter: {e}")))
}

const SIZE: u32 = 64;

/// `name` keeps the files of tests running in parallel apart.
fn scene(name: &str, ipd: Option<f64>) -> npr_runner::scene::Scene {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("screen-frame");
    std::fs::create_dir_all(&dir).expect("scratch");
    let ipd = ipd.map(|d| format!("ipd = {d}\n")).unwrap_or_default();
    // An oblique, finely subdivided ground plane filling most of the view.
    let text = format!(
        "[camera]\nposition = [1.2, 1.1, 2.4]\ntarget = [0.0, 0.0, 0.0]\nfov = 60.0\nnear = 0.1\nfar = 50.0\n{ipd}\n[light]\ndirection = [0.0, 1.0, 0.0]\n\n[[object]]\nname = \"ground\"\nprimitive = {{ kind = \"plane\", size = 8.0, subdivisions = 128 }}\n"
    );
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).expect("write scene");
    let mut sources = SourceMap::new();
    npr_runner::scene::load_scene(&path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

/// Render `value` (a vec4 expression) into an rgba32float target for `eye`.
fn render(value: &str, scene: &npr_runner::scene::Scene, eye: u32) -> Vec<[f32; 4]> {
    let text = format!(
        "style \"t\"\npass p: render(scene) {{\n  out o: rgba32float = {value}\n  clear: #000000\n}}\noutput p.o\n"
    );
    let mut sources = SourceMap::new();
    let c = match npr_compiler::compile_source("t.npr", &text, Path::new("."), &mut sources, &CompileOptions::default())
    {
        Ok(c) => c,
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(npr_compiler::CompileError::Internal(e)) => panic!("{e}"),
    };
    let spec = FrameSpec::still(SIZE, SIZE, eye);
    let img = npr_runner::render_frame(gpu(), &c.program(), scene, &spec).unwrap_or_else(|e| panic!("{e}"));
    (0..SIZE * SIZE).map(|i| img.texel(i % SIZE, i / SIZE)).collect()
}

/// px per metre along `dir` at `p` for view-projection `vp` (f64, central differences).
fn jacobian(vp: DMat4, p: DVec3, dir: DVec3) -> [f64; 2] {
    let px = |q: DVec3| {
        let c = vp * DVec4::new(q.x, q.y, q.z, 1.0);
        [
            (c.x / c.w * 0.5 + 0.5) * SIZE as f64,
            (0.5 - 0.5 * c.y / c.w) * SIZE as f64,
        ]
    };
    let h = 1e-5;
    let (a, b) = (px(p - dir * h), px(p + dir * h));
    [(b[0] - a[0]) / (2.0 * h), (b[1] - a[1]) / (2.0 * h)]
}

fn matrices(scene: &npr_runner::scene::Scene, eye: u32) -> (DMat4, DMat4) {
    let pose = scene.camera.pose(0.0);
    let proj = pose.projection(1.0).as_dmat4();
    (proj * pose.view(eye).as_dmat4(), proj * pose.center_view().as_dmat4())
}

/// Max relative error |gpu − expected| / |expected| over covered pixels.
fn check(name: &str, gpu: &[[f32; 4]], positions: &[[f32; 4]], expected: impl Fn(DVec3) -> [f64; 4], tol: f64) -> f64 {
    let mut worst = 0.0f64;
    let mut n = 0;
    for (g, p) in gpu.iter().zip(positions) {
        if p[3] != 2.0 {
            continue; // background
        }
        let e = expected(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64));
        for k in [0, 2] {
            let (gx, gy) = (g[k] as f64, g[k + 1] as f64);
            let err = (gx - e[k]).hypot(gy - e[k + 1]) / e[k].hypot(e[k + 1]).max(1e-9);
            worst = worst.max(err);
        }
        n += 1;
    }
    println!("{name}: {n} px, max relative error {worst:.2e}");
    assert!(n > (SIZE * SIZE / 3) as usize, "{name}: only {n} px covered");
    assert!(worst < tol, "{name}: {worst}");
    worst
}

#[test]
fn screen_tangent_frame_is_the_projection_jacobian_and_shared_in_stereo() {
    let tangent = DVec3::X; // the plane's u runs along +x ...
    for (ipd, eyes) in [(None, vec![0]), (Some(0.064), vec![0, 1])] {
        let s = scene(if ipd.is_some() { "stereo" } else { "mono" }, ipd);
        for eye in eyes {
            let (vp, center) = matrices(&s, eye);
            let positions = render("vec4(position.world, 2.0)", &s, eye);
            let t = render("vec4(tangent, 0.0)", &s, eye);
            // The mesh's own tangent and bitangent directions (+u, +v).
            let t_dir = DVec3::new(
                t[(SIZE * SIZE / 2 + SIZE / 2) as usize][0] as f64,
                t[(SIZE * SIZE / 2 + SIZE / 2) as usize][1] as f64,
                t[(SIZE * SIZE / 2 + SIZE / 2) as usize][2] as f64,
            );
            assert!(
                (t_dir - tangent).length() < 1e-4 || (t_dir + tangent).length() < 1e-4 || t_dir.y.abs() < 1e-4,
                "tangent {t_dir}"
            );
            let frame = render("vec4(tangent.screen, bitangent.screen)", &s, eye);
            // B = ±(n × t): the sign is the mesh's (+v); take it from the centre pixel.
            let b_dir = DVec3::Y.cross(t_dir).normalize();
            let g = frame[(SIZE * SIZE / 2 + SIZE / 2) as usize];
            let c = positions[(SIZE * SIZE / 2 + SIZE / 2) as usize];
            let jb = jacobian(vp, DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64), b_dir);
            let b_sign = if jb[0] * g[2] as f64 + jb[1] * g[3] as f64 >= 0.0 {
                1.0
            } else {
                -1.0
            };
            // Per-vertex values interpolated across 6 cm cells: ≤ 1% from the per-pixel Jacobian.
            let label = format!("ipd {ipd:?} eye {eye}: tangent.screen, bitangent.screen");
            check(
                &label,
                &frame,
                &positions,
                |p| {
                    let (a, b) = (jacobian(vp, p, t_dir), jacobian(vp, p, b_dir * b_sign));
                    [a[0], a[1], b[0], b[1]]
                },
                0.01,
            );
            let centre = render("vec4(tangent.screen_center, bitangent.screen_center)", &s, eye);
            let centre_expected = |p: DVec3| {
                let (a, b) = (jacobian(center, p, t_dir), jacobian(center, p, b_dir * b_sign));
                [a[0], a[1], b[0], b[1]]
            };
            let err = check(
                &format!("ipd {ipd:?} eye {eye}: *.screen_center"),
                &centre,
                &positions,
                centre_expected,
                0.01,
            );
            if ipd.is_none() {
                assert_eq!(frame, centre, "mono: the centre camera is the camera");
            } else {
                // Resolving power: the eye's own projection is further from the centre's than the GPU error.
                let mut sep = 0.0f64;
                for p in positions.iter().filter(|p| p[3] == 2.0) {
                    let p = DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64);
                    let (a, b) = (jacobian(vp, p, t_dir), centre_expected(p));
                    sep = sep.max((a[0] - b[0]).hypot(a[1] - b[1]) / b[0].hypot(b[1]));
                }
                println!("  eye {eye}: per-eye T_s differs from the centre camera's by up to {sep:.2e}");
                assert!(sep > 3.0 * err, "eye {eye}: separation {sep} vs error {err}");
            }
        }
    }
}

#[test]
fn camera_focal_is_the_projection_diagonal() {
    let s = scene("focal", None);
    let v = render(
        "vec4(camera.focal, radial_alpha(screen_uv: vec2(1.0, 0.0)), 1.0)",
        &s,
        0,
    );
    let f = 1.0 / (30f64.to_radians()).tan();
    let px = v[(SIZE * SIZE / 2) as usize];
    assert!(
        (px[0] as f64 - f).abs() < 1e-5 && (px[1] as f64 - f).abs() < 1e-5,
        "{px:?}"
    );
    // α in a corner of a square 60° view: 1 + 2·tan²30° (eqs. 12–13).
    assert!((px[2] as f64 - (1.0 + 2.0 / (f * f))).abs() < 1e-5, "{px:?}");
}

/// The edge-breakup warp field of Age of Sail §4.3 on the GPU: MetaTexture
/// noise with smooth gradients and radial compensation, roll-compensated,
/// 8 px strength, into an rg32float-precision target.
const WARP_FIELD: &str = "style \"roll\"\ntexture n = noise(size: 64, octaves: 3, seed: 5, channels: 2, kind: gradient) { wrap: repeat, filter: linear, mips: off }\npass p: render(scene) {\n  let g = uv_gradients(density: vec2(0.5, 0.5))\n  let m = metatexture_grad(n, uv, g.xy, g.zw, width: 24px * radial_alpha())\n  out o: rgba32float = vec4(roll_compensate(m.xy * 2.0 - 1.0, g.xy) * 8.0, m.xy * 2.0 - 1.0)\n  clear: #00000000\n}\noutput p.o\n";

fn roll_scene(name: &str, up: [f64; 3]) -> npr_runner::scene::Scene {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("screen-frame");
    std::fs::create_dir_all(&dir).expect("scratch");
    let text = format!(
        "[camera]\nposition = [0.4, 2.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nup = [{}, {}, {}]\nfov = 60.0\nnear = 0.1\nfar = 50.0\n\n[light]\ndirection = [0.0, 1.0, 0.0]\n\n[[object]]\nname = \"ground\"\nprimitive = {{ kind = \"plane\", size = 8.0, subdivisions = 64 }}\n",
        up[0], up[1], up[2]
    );
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).expect("write scene");
    let mut sources = SourceMap::new();
    npr_runner::scene::load_scene(&path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

fn render_style(text: &str, scene: &npr_runner::scene::Scene) -> Vec<[f32; 4]> {
    let mut sources = SourceMap::new();
    let c = match npr_compiler::compile_source(
        "roll.npr",
        text,
        Path::new("."),
        &mut sources,
        &CompileOptions::default(),
    ) {
        Ok(c) => c,
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(npr_compiler::CompileError::Internal(e)) => panic!("{e}"),
    };
    let spec = FrameSpec::still(SIZE, SIZE, 0);
    let img = npr_runner::render_frame(gpu(), &c.program(), scene, &spec).unwrap_or_else(|e| panic!("{e}"));
    (0..SIZE * SIZE).map(|i| img.texel(i % SIZE, i / SIZE)).collect()
}

#[test]
fn warp_field_rolls_with_a_rolled_camera_on_the_gpu() {
    let level = roll_scene("level", [0.0, 1.0, 0.0]);
    // Rolled 90°: up := −right, so right' = up and up' = −right (a square image maps pixel to pixel).
    let pose = level.camera.pose(0.0);
    let right = pose.right();
    let rolled = roll_scene("rolled", [-right.x as f64, -right.y as f64, -right.z as f64]);
    let a = render_style(WARP_FIELD, &level);
    let b = render_style(WARP_FIELD, &rolled);
    let n = SIZE as usize;
    let (mut worst, mut count, mut border) = (0.0f64, 0, 0.0f64);
    let mut errors = Vec::new();
    for j in 0..n {
        for i in 0..n {
            // The rolled image's pixel that sees the same ray: i' = n−1−j, j' = i.
            let (w, w_rolled) = (a[j * n + i], b[i * n + (n - 1 - j)]);
            if w[3] == 0.0 || w_rolled[3] == 0.0 {
                continue; // background (alpha 0) in either
            }
            // Screen vectors rotate as (x, y) → (−y, x) with the image.
            let e = ((w_rolled[0] + w[1]) as f64).hypot((w_rolled[1] - w[0]) as f64);
            if i == 0 || j == 0 || i == n - 1 || j == n - 1 {
                // The outermost ring, where the plane's triangles cross the eye
                // plane, is asserted too (`screen_uv` comes from the pixel centre),
                // and also reported on its own.
                border = border.max(e);
            }
            errors.push(e);
            worst = worst.max(e);
            count += 1;
        }
    }
    // The raw noise (zw, remapped to [−1, 1]) does not rotate: without
    // compensation the field would not follow the roll.
    let raw_shift = (0..n * n)
        .filter(|k| a[*k][3] != 0.0)
        .map(|k| {
            let (i, j) = (k % n, k / n);
            let (w, w_rolled) = (a[k], b[i * n + (n - 1 - j)]);
            (((w_rolled[2] + w[3]) as f64).hypot((w_rolled[3] - w[2]) as f64)) * 8.0
        })
        .fold(0.0f64, f64::max);
    errors.sort_by(f64::total_cmp);
    let p99 = errors.get(errors.len() * 99 / 100).copied().unwrap_or(0.0);
    println!("GPU camera roll 90°: {count} px, |W_rolled − R·W| max {worst:.2e} px, 99th percentile {p99:.2e} px (border ring max {border:.2e} px); uncompensated raw field would be off by up to {raw_shift:.2} px");
    assert!(count > 1500, "{count}");
    assert!(worst < 1e-3, "max {worst} px");
    assert!(raw_shift > 1.0, "{raw_shift}");
}
