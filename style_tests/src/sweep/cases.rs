//! Where a stability sweep renders: the hard scenes npr ships
//! (`hard_scenes/` in this package, built into the library and written out beside
//! the run's images so that a reproduction line names a file that exists),
//! and the scenes of the style's own tests, each at a small size.

use crate::declare::When;
use npr_runner::schedule::FrameRequest;
use std::path::{Path, PathBuf};

/// The size a sweep renders a style's own scenes at, and most hard
/// scenes: small, since every combination is rendered on a software
/// rasterizer.
pub const SWEEP_SIZE: (u32, u32) = (32, 32);

/// One scene, size, frame range and eye that every combination is rendered at.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// What the report calls it: a hard scene's name or the test's.
    pub label: String,
    pub scene: PathBuf,
    pub size: (u32, u32),
    pub request: FrameRequest,
    pub fps: f64,
    pub eye: u32,
    /// Whether one colour is a finding here: not where the picture may
    /// rightly be one colour (a speck far away, an image of 1 or 21 pixels,
    /// one small triangle).
    pub check_blank: bool,
}

impl Case {
    /// A declared test's own scene, size, frames and eye.
    pub fn of_test(test: &crate::declare::TestDecl) -> Case {
        Case {
            label: test.name.value.clone(),
            scene: test.scene.value.clone(),
            size: test.size,
            request: match test.when {
                When::At { time_s } => FrameRequest::At { time_s },
                When::Range { start, end } => FrameRequest::Range { start, end },
            },
            fps: test.fps,
            eye: test.eye.value,
            check_blank: !test.may_be_blank,
        }
    }

    /// A test's case at the sweep's small size, for `--sweep`.
    pub fn of_test_small(test: &crate::declare::TestDecl) -> Case {
        Case {
            size: (SWEEP_SIZE.0.min(test.size.0), SWEEP_SIZE.1.min(test.size.1)),
            ..Case::of_test(test)
        }
    }

    /// Pixels times frames: the cheaper of two cases is the smaller reproduction.
    pub fn cost(&self) -> u64 {
        let frames = match self.request {
            FrameRequest::At { .. } => 1,
            FrameRequest::Range { start, end } => u64::from(end.saturating_sub(start)).max(1),
        };
        u64::from(self.size.0) * u64::from(self.size.1) * frames
    }

    /// The `npr render` arguments after the style that render this case.
    pub fn render_args(&self) -> Vec<String> {
        let mut args = vec![
            "--scene".to_string(),
            self.scene.display().to_string(),
            "--size".into(),
            format!("{}x{}", self.size.0, self.size.1),
        ];
        match self.request {
            FrameRequest::At { time_s } if time_s != 0.0 => args.extend(["--time".into(), format!("{time_s}")]),
            FrameRequest::At { .. } => {}
            FrameRequest::Range { start, end } => args.extend(["--frames".into(), format!("{start}..{end}")]),
        }
        if self.fps != npr_runner::FrameSpec::DEFAULT_FPS {
            args.extend(["--fps".into(), format!("{}", self.fps)]);
        }
        if self.eye != 0 {
            args.extend(["--eye".into(), self.eye.to_string()]);
        }
        args
    }
}

/// The hard scenes' files, as shipped in `hard_scenes/`.
const HARD_FILES: &[(&str, &str)] = &[
    ("grazing.toml", include_str!("../../hard_scenes/grazing.toml")),
    ("near_plane.toml", include_str!("../../hard_scenes/near_plane.toml")),
    ("tiny_far.toml", include_str!("../../hard_scenes/tiny_far.toml")),
    ("degenerate.toml", include_str!("../../hard_scenes/degenerate.toml")),
    ("degenerate.obj", include_str!("../../hard_scenes/degenerate.obj")),
    ("camera_cut.toml", include_str!("../../hard_scenes/camera_cut.toml")),
    ("small.toml", include_str!("../../hard_scenes/small.toml")),
    ("stereo.toml", include_str!("../../hard_scenes/stereo.toml")),
    ("walking.toml", include_str!("../../hard_scenes/walking.toml")),
];

/// The binary files the hard scenes name, written beside them: the
/// Blender-made walker of `walking.toml`, a copy of
/// `examples/models/walker.glb` kept in this package so that it publishes
/// whole (`tests/general/packaging.rs` checks the two are the same bytes).
const HARD_MESHES: &[(&str, &[u8])] = &[("walker.glb", include_bytes!("../../hard_scenes/walker.glb"))];

/// Write the hard scenes into `dir` (each file atomically).
pub fn write_hard_scenes(dir: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    for (name, text) in HARD_FILES {
        npr_runner::output::write_atomic(&dir.join(name), text.as_bytes())?;
    }
    for (name, bytes) in HARD_MESHES {
        npr_runner::output::write_atomic(&dir.join(name), bytes)?;
    }
    Ok(())
}

/// The hard cases, their scenes in `dir` (written by [`write_hard_scenes`]).
pub fn hard_cases(dir: &Path) -> Vec<Case> {
    let case = |label: &str, file: &str, size: (u32, u32), request: FrameRequest, eye: u32| Case {
        label: label.to_string(),
        scene: dir.join(file),
        size,
        request,
        fps: npr_runner::FrameSpec::DEFAULT_FPS,
        eye,
        check_blank: !matches!(label, "tiny_far" | "degenerate" | "1x1" | "3x7"),
    };
    let still = FrameRequest::At { time_s: 0.0 };
    vec![
        case("grazing", "grazing.toml", SWEEP_SIZE, still, 0),
        case("near_plane", "near_plane.toml", SWEEP_SIZE, still, 0),
        case("tiny_far", "tiny_far.toml", SWEEP_SIZE, still, 0),
        case("degenerate", "degenerate.toml", SWEEP_SIZE, still, 0),
        case(
            "camera_cut",
            "camera_cut.toml",
            SWEEP_SIZE,
            FrameRequest::Range { start: 0, end: 3 },
            0,
        ),
        case("1x1", "small.toml", (1, 1), still, 0),
        case("3x7", "small.toml", (3, 7), still, 0),
        case("stereo_left", "stereo.toml", SWEEP_SIZE, still, 0),
        case("stereo_right", "stereo.toml", SWEEP_SIZE, still, 1),
        // Mid-stride (0.3 s): the GPU deformation and the CPU pose of
        // lines and light views, in one frame.
        case(
            "walking",
            "walking.toml",
            SWEEP_SIZE,
            FrameRequest::At { time_s: 0.3 },
            0,
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_hard_scene_is_shipped_and_named_by_a_case() {
        let dir = Path::new("hard_scenes");
        for (name, text) in HARD_FILES {
            let on_disk = std::fs::read_to_string(dir.join(name)).expect("shipped file");
            assert_eq!(&on_disk, text);
        }
        for case in hard_cases(dir) {
            assert!(case.scene.is_file(), "{}", case.scene.display());
        }
    }

    /// The hard scenes as a sweep writes them load, the walker with the
    /// mesh written beside it, playing its clip.
    #[test]
    fn the_written_hard_scenes_load_with_their_meshes() {
        let dir = std::env::temp_dir().join(format!("npr-hard-scenes-{}", std::process::id()));
        write_hard_scenes(&dir).expect("write the hard scenes");
        let mut sources = npr_diag::SourceMap::new();
        let scene = npr_runner::scene::load_scene(&dir.join("walking.toml"), &mut sources)
            .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));
        assert!(scene.objects[0].animation.is_some(), "the walker plays its clip");
        std::fs::remove_dir_all(&dir).expect("remove the scratch folder");
    }
}
