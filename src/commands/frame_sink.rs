//! Where `npr render` puts each written frame, chosen by `-o`'s extension
//! and `--layers`: an image per frame (`.png`, `.exr`), every target as a
//! layer of one EXR per frame (`--layers`), or one video of the sequence
//! (`.mp4`, `.webm`, `.gif`; `video.rs`).
//!
//! [`check`] refuses a bad combination or a bad `{frame}` pattern (E0502) or an extension npr does not
//! write (E0503) before anything is compiled or rendered, and a video
//! whose encoder is missing (E0511), so a
//! long render never fails at its end for an output it could not write.

use crate::frame_pattern::FramePattern;
use npr_diag::exit::EXIT_USER;
use npr_diag::writes::cannot_write;
use npr_diag::{codes, Diagnostic};
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Renderer, RunError};
use std::path::{Path, PathBuf};

/// What `-o` names.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum OutputKind {
    Image,
    Layers,
    Video(crate::video::Container),
}

fn extension(out: &Path) -> String {
    out.extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default()
}

/// The kind of output `out` is, or why it cannot be one.
pub(crate) fn check(out: &Path, layers: bool, sequence: bool) -> Result<OutputKind, Diagnostic> {
    FramePattern::parse_path(out).map_err(|e| {
        Diagnostic::error(codes::BAD_ARGUMENT_VALUE, format!("-o: {e}")).with_help(crate::frame_pattern::FORMS)
    })?;
    let ext = extension(out);
    if let Some(container) = crate::video::Container::from_extension(&ext) {
        if layers {
            return Err(Diagnostic::error(
                codes::BAD_ARGUMENT_VALUE,
                format!("--layers writes EXR files, not {}", out.display()),
            )
            .with_help("give -o NAME.exr (with --frames, one EXR per frame: NAME_{frame}.exr)"));
        }
        if !sequence {
            return Err(Diagnostic::error(
                codes::BAD_ARGUMENT_VALUE,
                format!("{} is a video, which needs --frames", out.display()),
            )
            .with_help("give the frames to encode, e.g. --frames 0..48; for one frame write a .png"));
        }
        crate::video::check_encoder(container)?;
        return Ok(OutputKind::Video(container));
    }
    match (ext.as_str(), layers) {
        ("exr", true) => Ok(OutputKind::Layers),
        (_, true) => Err(Diagnostic::error(
            codes::BAD_ARGUMENT_VALUE,
            format!("--layers writes one EXR of every target, not {}", out.display()),
        )
        .with_help("give -o NAME.exr")),
        ("png" | "exr" | "", false) => Ok(OutputKind::Image),
        (other, false) => Err(crate::printer::unsupported_image(out, other)),
    }
}

/// [`check`] for `npr render`: the diagnostic printed, the exit code returned.
pub(crate) fn check_or_exit(
    out: Option<&Path>,
    layers: bool,
    sequence: bool,
    printer: &npr_diag::printer::Printer,
) -> Result<Option<OutputKind>, i32> {
    match out.map(|o| check(o, layers, sequence)) {
        None => Ok(None),
        Some(Ok(kind)) => Ok(Some(kind)),
        Some(Err(d)) => {
            printer.fail(d);
            Err(EXIT_USER)
        }
    }
}

/// The file frame `frame` of a sequence is written to: each `{frame}` or
/// `{frame:0N}` in `out` replaced by the frame number (`crate::frame_pattern`),
/// or, without one, `_NNNN` appended to its stem.
pub(crate) fn frame_path(out: &Path, frame: u32) -> PathBuf {
    if let Some(pattern) = FramePattern::parse_path(out).ok().filter(FramePattern::has_frame) {
        return pattern.path(frame);
    }
    let stem = out
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "frame".into());
    let ext = out
        .extension()
        .map(|e| e.to_string_lossy().into_owned())
        .unwrap_or_else(|| "png".into());
    out.with_file_name(format!("{stem}_{frame:04}.{ext}"))
}

/// An open output: frames go in one by one, [`FrameSink::finish`] completes it.
pub(crate) enum FrameSink {
    Image { out: PathBuf, sequence: bool },
    Layers { out: PathBuf, sequence: bool },
    Video(crate::video::VideoWriter),
}

fn io(e: std::io::Error, p: &Path) -> RunError {
    RunError::User(vec![cannot_write(p, e)])
}

impl FrameSink {
    /// Open `out` as `kind` for frames of `width`×`height` at `fps`
    /// (a video starts its encoder here, writing to a temporary file).
    pub(crate) fn open(
        out: &Path,
        kind: OutputKind,
        sequence: bool,
        (width, height): (u32, u32),
        fps: f64,
    ) -> Result<Self, RunError> {
        Ok(match kind {
            OutputKind::Image => FrameSink::Image {
                out: out.to_path_buf(),
                sequence,
            },
            OutputKind::Layers => FrameSink::Layers {
                out: out.to_path_buf(),
                sequence,
            },
            OutputKind::Video(container) => FrameSink::Video(
                crate::video::VideoWriter::start(out, container, width, height, fps).map_err(|e| io(e, out))?,
            ),
        })
    }

    /// Write the frame `r` has just rendered; returns what to report for a
    /// single image (its path and size), nothing for a sequence.
    pub(crate) fn frame(
        &mut self,
        r: &mut Renderer,
        scene: &Scene,
        spec: &FrameSpec,
    ) -> Result<Option<(PathBuf, u32, u32)>, RunError> {
        match self {
            FrameSink::Image { out, sequence } => {
                let path = if *sequence {
                    frame_path(out, spec.frame)
                } else {
                    out.clone()
                };
                let img = r.read_output()?;
                npr_runner::output::write_target(&img, &path).map_err(|e| io(e, &path))?;
                Ok((!*sequence).then_some((path, img.width, img.height)))
            }
            FrameSink::Layers { out, sequence } => {
                let path = if *sequence {
                    frame_path(out, spec.frame)
                } else {
                    out.clone()
                };
                let images = r.read_all_targets(scene, spec)?;
                npr_runner::exr_layers::write_layers(&images, &path).map_err(|e| io(e, &path))?;
                Ok((!*sequence).then_some((path, spec.width, spec.height)))
            }
            FrameSink::Video(video) => {
                let img = r.read_output()?;
                video.push(&img).map_err(|e| io(e, video.path()))?;
                Ok(None)
            }
        }
    }

    /// Complete the output: a video's encoder is flushed and the file renamed
    /// into place (until then it does not exist under its name).
    pub(crate) fn finish(self) -> Result<(), RunError> {
        match self {
            FrameSink::Video(video) => {
                let path = video.path().to_path_buf();
                let frames = video.finish().map_err(|e| io(e, &path))?;
                eprintln!("wrote {} ({frames} frames)", path.display());
                Ok(())
            }
            FrameSink::Image { .. } | FrameSink::Layers { .. } => Ok(()),
        }
    }
}
