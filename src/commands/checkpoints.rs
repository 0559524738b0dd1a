//! `npr render --checkpoints DIR`: a path-dependent style's sequence in
//! chunks, each starting from the state the frames before it left
//! (`npr_runner::checkpoint`) instead of replaying them.
//!
//! `DIR/frame_NNNNNN.nprstate` holds the renderer's state ready to render
//! frame NNNNNN. A render of `--frames A..B` starts from the checkpoint of
//! the latest frame at or before A in DIR (replaying only from there; from
//! 0 when there is none), and writes the checkpoint of frame B when it
//! ends, so the next chunk (B..C) starts there; `--checkpoint-every K`
//! also writes one at every multiple of K it passes, so one pass over the
//! sequence (without `-o`) prepares every chunk's start for chunks that
//! then run in parallel. A checkpoint for another render, or a damaged
//! one, is refused (E0512, E0513), never silently replaced by a replay.

use npr_runner::checkpoint::{self, Checkpoint, Identity};
use npr_runner::schedule::ScheduledFrame;
use npr_runner::{Renderer, RunError, StyleProgram};
use std::path::{Path, PathBuf};

/// The checkpoints of one render.
pub(crate) struct Checkpoints {
    dir: PathBuf,
    identity: Identity,
    /// Also save at every multiple of this many frames.
    every: Option<u32>,
    /// The frame after the last one requested: always saved.
    end: u32,
}

/// Where the checkpoint of `frame` is in `dir`.
pub(crate) fn path_of(dir: &Path, frame: u32) -> PathBuf {
    dir.join(format!("frame_{frame:06}.nprstate"))
}

/// The frame a file in a checkpoint directory is for.
fn frame_of(name: &str) -> Option<u32> {
    name.strip_prefix("frame_")?.strip_suffix(".nprstate")?.parse().ok()
}

impl Checkpoints {
    pub(crate) fn new(
        dir: &Path,
        program: &StyleProgram,
        scene: &npr_runner::scene::Scene,
        (width, height): (u32, u32),
        fps: f64,
        every: Option<u32>,
        end: u32,
    ) -> Self {
        Checkpoints {
            dir: dir.to_path_buf(),
            identity: Identity {
                npr_version: env!("CARGO_PKG_VERSION").to_string(),
                style: checkpoint::style_hash(program),
                scene: checkpoint::scene_hash(scene),
                width,
                height,
                fps,
            },
            every,
            end,
        }
    }

    /// Restore `r` from the latest checkpoint at or before `start` in the
    /// directory, if any; the frame it is ready to render (0 without one).
    pub(crate) fn resume(&self, r: &mut Renderer, start: u32) -> Result<u32, RunError> {
        let latest = std::fs::read_dir(&self.dir)
            .into_iter()
            .flatten()
            .flatten()
            .filter_map(|e| frame_of(&e.file_name().to_string_lossy()))
            .filter(|f| *f <= start && *f > 0)
            .max();
        let Some(frame) = latest else {
            if start > 0 {
                eprintln!(
                    "note: no checkpoint at or before frame {start} in {}, so the frames before it are replayed",
                    self.dir.display()
                );
            }
            return Ok(0);
        };
        let path = path_of(&self.dir, frame);
        let c = checkpoint::read(&path, &self.identity).map_err(|d| RunError::User(vec![d]))?;
        if c.frame != frame {
            return Err(RunError::User(vec![npr_diag::Diagnostic::error(
                npr_diag::codes::BAD_CHECKPOINT,
                format!("checkpoint {} is of frame {}, not {frame}", path.display(), c.frame),
            )
            .with_help("a checkpoint's name says its frame: do not rename them")]));
        }
        r.restore_state(&c.state)?;
        eprintln!("note: starting from checkpoint {} (frame {frame})", path.display());
        Ok(frame)
    }

    /// After `scheduled` was rendered: save the checkpoint of the next
    /// frame when it is the end of the request or a multiple of `every`.
    pub(crate) fn after(&self, r: &Renderer, scheduled: &ScheduledFrame) -> Result<(), RunError> {
        let next = scheduled.frame + 1;
        if next != self.end && self.every.is_none_or(|k| !next.is_multiple_of(k)) {
            return Ok(());
        }
        let c = Checkpoint {
            identity: self.identity.clone(),
            frame: next,
            state: r.save_state()?,
        };
        let path = path_of(&self.dir, next);
        checkpoint::write(&path, &c).map_err(|e| RunError::User(vec![npr_diag::writes::cannot_write(&path, e)]))
    }
}
