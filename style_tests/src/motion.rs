//! The scene's exact motion for a test's coherence bounds: a probe style
//! that writes each pixel's world position and object, rendered over the
//! test's frames with the test's scene; each point's previous position is
//! its object's previous model matrix applied to the point in the object's
//! frame. The measures of `coherence.rs` are then taken between
//! consecutive written frames of the style's own output.
//!
//! An object playing a clip deforms as well as moves: its points are
//! followed as if rigid (the model matrices only), so the measures on a
//! character include its deformation as sliding.

use super::coherence::{self, Frame, MotionField, PreviousCamera};
use super::declare::{CoherenceBound, Marks};
use super::frames::Frames;
use super::outcome::Failure;
use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use npr_runner::scene::Scene;
use npr_runner::{Gpu, RunError, TargetImage};

/// The probe: per pixel, the surface point's world position and its
/// object's index plus one in `w` (0 on the clear, where nothing is drawn;
/// one target, since the compiler keeps only what the output needs).
const PROBE: &str = r#"style "Motion probe"

pass probe: render(scene) {
  out here: rgba32float = vec4(position, object.index * 1.0 + 1.0)
  clear: #00000000
}

output probe.here
"#;

/// The worst of each measure over the test's consecutive frame pairs.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Measured {
    pub flicker: Option<f64>,
    pub sliding: Option<f64>,
    pub popping: Option<f64>,
    /// Frame pairs measured.
    pub pairs: usize,
}

/// Measure the coherence of `outputs` (the style's written frames) on
/// `scene` over `frames`, with the probe rendered over the same frames.
pub fn measure(
    gpu: &Gpu,
    scene: &Scene,
    frames: &Frames,
    outputs: &[(u32, TargetImage)],
    opts: &CompileOptions,
    marks: Marks,
) -> Result<Measured, RunError> {
    let mut sources = SourceMap::new();
    let probe_options = CompileOptions {
        settings: Vec::new(),
        paths: None,
        ..opts.clone()
    };
    let probe = npr_compiler::compile_source(
        "motion_probe.npr",
        PROBE,
        std::path::Path::new("."),
        &mut sources,
        &probe_options,
    )
    .map_err(|e| RunError::Internal(format!("the motion probe did not compile: {e:?}")))?
    .program();
    let rendered = frames.render_targets(gpu, &probe, scene)?;
    let (width, height) = frames.size;
    let here_index = target_index(&probe, "probe.here")?;
    let positions: Vec<(u32, Vec<[f32; 4]>)> = rendered
        .iter()
        .map(|(frame, targets)| (*frame, targets[here_index].to_rgba_f32()))
        .collect();
    let aspect = width as f32 / height as f32;
    let mut measured = Measured::default();
    let worst = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => Some(a.max(b)),
        (a, b) => a.or(b),
    };
    for pair in outputs.windows(2) {
        let ((then_frame, then_image), (now_frame, now_image)) = (&pair[0], &pair[1]);
        if *now_frame != then_frame + 1 {
            continue;
        }
        let find = |frame: u32| positions.iter().find(|(f, _)| *f == frame);
        let (Some((_, previous_here)), Some((_, here))) = (find(*then_frame), find(*now_frame)) else {
            continue;
        };
        let time_of = |frame: u32| frames.frames.iter().find(|f| f.frame == frame).map(|f| f.time_s);
        let (Some(then_time), Some(now_time)) = (time_of(*then_frame), time_of(*now_frame)) else {
            continue;
        };
        let before = previous_positions(scene, here, now_time, then_time);
        let pose = scene.camera.pose(then_time);
        let view = pose.view(frames.eye);
        let camera = PreviousCamera {
            view_projection: pose.projection(aspect) * view,
            eye: view.inverse().transform_point3(glam::Vec3::ZERO),
            pixel_at_one_metre: 2.0 * (pose.fov_y_rad / 2.0).tan() / height as f32,
        };
        let motion = MotionField::new(width, height, here, &before, previous_here, &camera);
        let (now_rgba, then_rgba) = (now_image.to_rgba8(), then_image.to_rgba8());
        let now = Frame {
            width,
            height,
            rgba: now_rgba.as_raw(),
        };
        let then = Frame {
            width,
            height,
            rgba: then_rgba.as_raw(),
        };
        measured.flicker = worst(measured.flicker, coherence::compensated_change(&now, &then, &motion));
        measured.sliding = worst(measured.sliding, coherence::sliding(&now, &then, &motion));
        let is_mark = |c: [f64; 4]| {
            let luminance = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
            match marks {
                Marks::Dark => luminance < 0.5,
                Marks::Light => luminance > 0.5,
            }
        };
        let popped = coherence::popping(&now, &then, &motion, is_mark);
        measured.popping = worst(measured.popping, (popped.judged > 0).then(|| popped.share()));
        measured.pairs += 1;
    }
    Ok(measured)
}

/// Each drawn point's world position at `then`: its object's model at
/// `then` applied to the point in the object's frame at `now`.
fn previous_positions(scene: &Scene, here: &[[f32; 4]], now: f64, then: f64) -> Vec<[f32; 4]> {
    let moves: Vec<glam::Mat4> = scene
        .objects
        .iter()
        .map(|o| o.model_at(then) * o.model_at(now).inverse())
        .collect();
    here.iter()
        .map(|p| {
            let moved = match moves.get((p[3].round() as usize).wrapping_sub(1)) {
                Some(m) => m.transform_point3(glam::Vec3::new(p[0], p[1], p[2])),
                None => glam::Vec3::new(p[0], p[1], p[2]),
            };
            [moved.x, moved.y, moved.z, p[3]]
        })
        .collect()
}

fn target_index(program: &npr_runner::StyleProgram, name: &str) -> Result<usize, RunError> {
    program
        .manifest
        .targets
        .iter()
        .position(|t| t.name == name)
        .ok_or_else(|| RunError::Internal(format!("the motion probe has no target {name}")))
}

/// The failures of `measured` against `bound`, and the line that reports
/// what was measured.
pub fn failures(measured: &Measured, bound: &CoherenceBound) -> (Vec<Failure>, String) {
    let mut failures = Vec::new();
    let mut said = Vec::new();
    let checks = [
        ("flicker", measured.flicker, bound.flicker),
        ("sliding", measured.sliding, bound.sliding),
        ("popping", measured.popping, bound.popping),
    ];
    for (name, value, limit) in checks {
        let Some(limit) = limit else { continue };
        match value {
            Some(v) => {
                said.push(format!("{name} {v:.4}"));
                if v > limit {
                    failures.push(Failure {
                        check: "coherence",
                        message: format!(
                            "{name} is {v:.4} at worst over {} frame pairs; allowed {limit}",
                            measured.pairs
                        ),
                        files: Vec::new(),
                        reproduce: None,
                    });
                }
            }
            None => failures.push(Failure {
                check: "coherence",
                message: format!(
                    "{name} could not be measured: no pixel of the frames has {}",
                    if name == "sliding" {
                        "a pattern on a surface seen in two frames"
                    } else {
                        "a surface seen in two frames"
                    }
                ),
                files: Vec::new(),
                reproduce: None,
            }),
        }
    }
    (
        failures,
        format!("coherence over {} frame pairs: {}", measured.pairs, said.join(", ")),
    )
}
