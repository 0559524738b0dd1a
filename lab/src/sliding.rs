//! The sliding ("shower-door") measure of dynamic 2D patterns (Breslav et
//! al. 2007 §4 and Fig. 4): at every pixel an object covers, how far, in px
//! per frame, the pattern point drawn there moved from where the surface
//! point under it moved. A pattern fixed to the screen does not move at all,
//! so it slides by the surface's whole motion; a texture fixed to the object
//! moves with the surface point and slides by 0 by construction (but its
//! marks are not 2D: they shrink, stretch and foreshorten with the surface,
//! which is what dynamic patterns avoid); a dynamic pattern moves by the
//! object's best 2D similarity, so it slides by what a similarity cannot
//! follow (perspective, depth differences across the object, rotation out
//! of the image plane).
//!
//! Measured on the GPU with the tracker itself (`examples/lib/dynamic_pattern.npr`)
//! and [`MEASURE`]: a pass over objects keeps the previous frame's pattern
//! frame, and a render pass maps each pixel q through this frame's pattern
//! coordinates back to where the pattern point was (o′ + x·u′ + y·v′), and
//! compares that with where the surface point was (`project_previous` of its
//! position: in these motions the objects stand still and the camera moves).
//! Means are over covered pixels and frames 1….

use crate::bench::wait_idle;
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Gpu, RunError, StyleProgram};
use std::time::Instant;

/// Keeps last frame's pattern frame per object, and draws each pixel's
/// sliding: x, the dynamic pattern's; y, a screen-fixed pattern's; z, 1.
pub const MEASURE: &str = r#"
/// Per object: the pattern frame of this frame (`*_now`) and the last (`*_before`).
pass frames: compute(objects) {
  state o_now: vec2 = vec2(0.0, 0.0)
  state u_now: vec2 = vec2(1.0, 0.0)
  state v_now: vec2 = vec2(0.0, 1.0)
  state o_before: vec2 = vec2(0.0, 0.0)
  state u_before: vec2 = vec2(1.0, 0.0)
  state v_before: vec2 = vec2(0.0, 1.0)
  o_before = o_now
  u_before = u_now
  v_before = v_now
  o_now = pattern.o
  u_now = pattern.u
  v_now = pattern.v
}

pass slide: render(scene) {
  let q = frag_coord / 1px
  // Where the pattern point drawn at q was one frame ago (§3.3's frame).
  let at = pattern_uv(frames.o_now, frames.u_now, frames.v_now)
  let pattern_before = frames.o_before + frames.u_before * at.x + frames.v_before * at.y
  // Where the surface point at q was (the objects stand still: only the
  // camera moves, so the point was where the last camera saw it).
  let surface_before = project_previous(position).xy * (resolution / 1px)
  out error: rgba32float = vec4(distance(pattern_before, surface_before), distance(q, surface_before), 1.0, 0.0)
}

output slide.error
"#;

/// The tracker with `samples` per object and `weighting`, and [`MEASURE`].
pub fn style(tracker: &str, samples: u32, weighting: &str) -> String {
    format!(
        "{}\n{MEASURE}",
        tracker
            .replace("count: 400", &format!("count: {samples}"))
            .replace("= area\n", &format!("= {weighting}\n"))
    )
}

/// One camera or object motion of the comparison.
pub struct Motion {
    pub name: &'static str,
    /// The scene, as TOML, at 24 fps over [`FRAMES`] frames.
    pub scene: &'static str,
}

/// Frames measured per motion (1 s).
pub const FRAMES: u32 = 24;
/// Image size.
pub const SIZE: (u32, u32) = (192, 144);

const COW: &str = r#"
[[object]]
mesh = "../models/cow.obj"
scale = 0.25
translate = [0.0, 0.9, 0.0]
rotate = [0.0, 30.0, 0.0]
"#;

/// The elongated object of Fig. 4: a 10 m strip on the ground, seen along
/// its length from 0.6 m up while the camera slides sideways, so that its
/// near end sweeps across the image much faster than its far end; `extra`
/// adds object fields (`patches = 4`: one similarity per quarter, §3.6).
fn elongated(extra: &str) -> String {
    format!(
        "[camera]\nposition = [-0.8, 0.6, 1.0]\ntarget = [-0.8, 0.0, -4.0]\nfov = 50.0\n\
         [[camera.keys]]\ntime = 0.0\nposition = [-0.8, 0.6, 1.0]\ntarget = [-0.8, 0.0, -4.0]\n\
         [[camera.keys]]\ntime = 1.0\nposition = [0.8, 0.6, 1.0]\ntarget = [0.8, 0.0, -4.0]\n\
         [light]\ndirection = [0.4, 1.0, 0.6]\n\
         [[object]]\nprimitive = {{ kind = \"plane\", size = 1.0, subdivisions = 32 }}\nscale = [1.2, 1.0, 10.0]\ntranslate = [0.0, 0.0, -4.5]\n{extra}"
    )
}

/// Pan, zoom (a dolly), roll and orbit around the paper's cow, the orbit
/// again with the cow in 6 patches (§3.6), and the elongated-object worst
/// case of Fig. 4 without and with patches.
pub fn motions() -> Vec<(&'static str, String)> {
    let cam = |keys: &str| {
        format!("[camera]\nposition = [0.0, 1.2, 5.0]\ntarget = [0.0, 0.8, 0.0]\nfov = 40.0\n{keys}\n[light]\ndirection = [0.4, 1.0, 0.6]\n")
    };
    let orbit = "[[camera.keys]]\ntime = 0.0\nposition = [0.0, 1.2, 5.0]\n[[camera.keys]]\ntime = 0.5\nposition = [2.5, 1.2, 4.33]\n[[camera.keys]]\ntime = 1.0\nposition = [4.33, 1.2, 2.5]\n";
    vec![
        (
            "pan",
            cam("[[camera.keys]]\ntime = 0.0\nposition = [-0.6, 1.2, 5.0]\ntarget = [-0.6, 0.8, 0.0]\n[[camera.keys]]\ntime = 1.0\nposition = [0.6, 1.2, 5.0]\ntarget = [0.6, 0.8, 0.0]\n") + COW,
        ),
        (
            "zoom",
            cam("[[camera.keys]]\ntime = 0.0\nposition = [0.0, 1.2, 6.0]\n[[camera.keys]]\ntime = 1.0\nposition = [0.0, 1.1, 3.5]\n") + COW,
        ),
        (
            "roll",
            cam("[[camera.keys]]\ntime = 0.0\nroll = 0.0\n[[camera.keys]]\ntime = 1.0\nroll = 30.0\n") + COW,
        ),
        ("orbit", cam(orbit) + COW),
        ("orbit, 6 patches", cam(orbit) + COW + "patches = 6\n"),
        ("elongated", elongated("")),
        ("elongated, 4 patches", elongated("patches = 4\n")),
    ]
}

/// A tracker variant.
#[derive(Debug, Clone, Copy)]
pub struct Variant {
    pub samples: u32,
    pub weighting: &'static str,
}

/// The variants compared: the paper's weights at three densities, and no weights.
pub const VARIANTS: &[Variant] = &[
    Variant {
        samples: 100,
        weighting: "area",
    },
    Variant {
        samples: 400,
        weighting: "area",
    },
    Variant {
        samples: 1600,
        weighting: "area",
    },
    Variant {
        samples: 400,
        weighting: "unweighted",
    },
];

/// The mean sliding of one run, px per frame over covered pixels.
#[derive(Debug, Clone, Copy)]
pub struct Sliding {
    pub tracked: f64,
    pub screen_fixed: f64,
    /// Median wall ms of a frame (tracker plus the measuring pass).
    pub frame_ms: f64,
}

/// Parses a motion's scene; relative mesh paths resolve against `base`.
pub fn scene(text: &str, base: &std::path::Path) -> Result<Scene, RunError> {
    let mut sources = npr_diag::SourceMap::new();
    let file = sources.add("sliding.toml", text.to_string());
    npr_runner::scene::parse_scene(text, file, base).map_err(RunError::User)
}

/// Renders [`FRAMES`] + 1 frames of `scene` with `program` (a [`style`])
/// and averages the sliding images of frames 1…[`FRAMES`].
pub fn measure(gpu: &Gpu, program: &StyleProgram, scene: &Scene) -> Result<Sliding, RunError> {
    let mut renderer = npr_runner::Renderer::new(&gpu.device, &gpu.queue, program, scene)?;
    let (mut tracked, mut fixed, mut covered) = (0.0f64, 0.0f64, 0.0f64);
    let mut times = Vec::new();
    for k in 0..=FRAMES {
        let spec = FrameSpec {
            frame: k,
            time_s: k as f64 / FRAMES as f64,
            ..FrameSpec::still(SIZE.0, SIZE.1, 0)
        };
        let started = Instant::now();
        renderer.render(scene, &spec)?;
        wait_idle(gpu)?;
        times.push(started.elapsed().as_secs_f64());
        if k == 0 {
            continue;
        }
        let image = renderer.read_output()?;
        for p in image.to_rgba_f32() {
            if p[2] > 0.5 && p[0].is_finite() && p[1].is_finite() {
                tracked += p[0] as f64;
                fixed += p[1] as f64;
                covered += 1.0;
            }
        }
    }
    if covered == 0.0 {
        return Err(RunError::Internal("the sliding measure saw no covered pixel".into()));
    }
    Ok(Sliding {
        tracked: tracked / covered,
        screen_fixed: fixed / covered,
        frame_ms: crate::bench_reduce::median(times) * 1e3,
    })
}

/// One motion's row: the sliding of each of [`VARIANTS`], in order.
pub struct Row {
    pub motion: &'static str,
    pub screen_fixed: f64,
    pub variants: Vec<Sliding>,
}

/// Measures every motion with every variant. `scenes_dir` is
/// `examples/scenes`, against which the cow's mesh path resolves.
pub fn run(
    gpu: &Gpu,
    tracker: &str,
    compile: impl Fn(&str) -> Result<StyleProgram, RunError>,
    scenes_dir: &std::path::Path,
    progress: impl Fn(&str),
) -> Result<Vec<Row>, RunError> {
    let programs = VARIANTS
        .iter()
        .map(|v| compile(&style(tracker, v.samples, v.weighting)))
        .collect::<Result<Vec<_>, _>>()?;
    let mut rows = Vec::new();
    for (motion, text) in motions() {
        let scene = scene(&text, scenes_dir)?;
        let mut variants = Vec::new();
        for (v, program) in VARIANTS.iter().zip(&programs) {
            let s = measure(gpu, program, &scene)?;
            progress(&format!(
                "{motion}: {} samples, {}: {:.3} px/frame (screen-fixed {:.3})",
                v.samples, v.weighting, s.tracked, s.screen_fixed
            ));
            variants.push(s);
        }
        rows.push(Row {
            motion,
            // The same camera path and coverage in every variant.
            screen_fixed: variants[0].screen_fixed,
            variants,
        });
    }
    Ok(rows)
}

/// The rows as a Markdown table: px/frame per placement, and the frame cost.
pub fn table(rows: &[Row]) -> String {
    let mut s = String::from("| motion | screen-fixed | object-fixed |");
    for v in VARIANTS {
        s += &format!(" dynamic, {} × {} |", v.weighting, v.samples);
    }
    s += "\n|---|---:|---:|";
    s += &"---:|".repeat(VARIANTS.len());
    s += "\n";
    for r in rows {
        s += &format!("| {} | {:.3} | 0 |", r.motion, r.screen_fixed);
        for v in &r.variants {
            s += &format!(
                " {:.3} ({:.0}%) |",
                v.tracked,
                100.0 * v.tracked / r.screen_fixed.max(1e-12)
            );
        }
        s += "\n";
    }
    s += "| frame ms (median, tracker + measure) | | |";
    for i in 0..VARIANTS.len() {
        s += &format!(" {:.2} |", frame_ms(rows, i));
    }
    s + "\n"
}

/// The frame ms of variant `i` the table prints: the median over the motions.
pub fn frame_ms(rows: &[Row], i: usize) -> f64 {
    crate::bench_reduce::median(rows.iter().map(|r| r.variants[i].frame_ms).collect())
}
