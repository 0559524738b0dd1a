//! `npr render`'s host inputs (issue 47): `--input NAME=FILE` per input,
//! `--inputs FILE.exr` for all of them from one multi-layer EXR (Blender's
//! layer names understood, `--map NAME=LAYER` for others), read and
//! converted to the language's conventions (`npr_runner::inputs`). A file
//! with a `{frame}` pattern (`crate::frame_pattern`, the one `-o` uses) is
//! a sequence, read frame by frame as `--frames` renders them.
//!
//! Every problem names the input and the file: E0420 for one that cannot
//! be used, E0421 for a missing frame, E0422 for a frame of another size
//! than its sequence's first. Missing frames and sizes are found from the
//! files' headers before the first frame renders; a frame's other problems
//! before that frame renders, so no output is written from inputs that did
//! not all load.

use crate::frame_pattern::FramePattern;
use npr_abi::manifest::{Manifest, TextureSourceManifest};
use npr_abi::InputKind;
use npr_diag::diagnostic::did_you_mean;
use npr_diag::{codes, Diagnostic};
use npr_runner::inputs::{self, files, HostInputs};
use npr_runner::scene::Camera;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The inputs as the command line gives them.
pub(crate) struct InputArgs<'a> {
    pub input: &'a [String],
    pub inputs: Option<&'a Path>,
    pub map: &'a [String],
}

impl InputArgs<'_> {
    pub fn any(&self) -> bool {
        !self.input.is_empty() || self.inputs.is_some()
    }
}

/// The style's inputs: (name, kind), in declaration order.
pub(crate) fn declared(m: &Manifest) -> Vec<(String, InputKind)> {
    m.textures
        .iter()
        .filter_map(|t| match &t.source {
            TextureSourceManifest::Input(spec) => Some((t.name.clone(), spec.kind)),
            _ => None,
        })
        .collect()
}

fn bad(message: String, help: String) -> Diagnostic {
    Diagnostic::error(codes::BAD_INPUT, message).with_help(help)
}

/// `NAME=VALUE` pairs of a repeated flag, each NAME an input of the style.
fn pairs(flag: &str, given: &[String], names: &[&str]) -> Result<BTreeMap<String, String>, Diagnostic> {
    let mut out = BTreeMap::new();
    for g in given {
        let Some((name, value)) = g.split_once('=').filter(|(n, v)| !n.is_empty() && !v.is_empty()) else {
            return Err(
                Diagnostic::error(codes::BAD_ARGUMENT_VALUE, format!("`--{flag} {g}` is not NAME=VALUE"))
                    .with_help(format!("write e.g. `--{flag} color=beauty.png`")),
            );
        };
        if !names.contains(&name) {
            let help = match did_you_mean(name, names.iter().copied()) {
                Some(s) => format!("did you mean `{s}`?"),
                None if names.is_empty() => "the style declares no `input(...)` texture".to_string(),
                None => format!("the style's inputs are: {}", names.join(", ")),
            };
            return Err(bad(format!("`--{flag} {g}`: the style has no input `{name}`"), help));
        }
        if out.insert(name.to_string(), value.to_string()).is_some() {
            return Err(bad(
                format!("input `{name}` is given twice by `--{flag}`"),
                "give each input once".into(),
            ));
        }
    }
    Ok(out)
}

/// Where one input comes from: its own file, or a layer of the
/// `--inputs` EXR; either a `{frame}` pattern or one file for all frames.
enum Origin {
    File(FramePattern),
    Layer(String),
    /// Not given (E0420 when read).
    Missing,
}

/// Every frame's inputs of a render: read once when no file names a
/// `{frame}`, else for each frame as it comes. Every problem is found
/// before the frame it concerns is rendered: a missing frame or one of
/// another size ([`InputFrames::check_frames`]) before the first.
pub(crate) struct InputFrames {
    declared: Vec<(String, InputKind, Origin)>,
    /// `--inputs`, when given.
    exr: Option<FramePattern>,
    /// The scene's camera (normals turn between spaces by its pose at
    /// each frame's time).
    camera: Option<Camera>,
    /// The frame the inputs were first read for, and what was read.
    first_frame: u32,
    first: HostInputs,
    /// Per input, the file its first frame was read from.
    first_files: BTreeMap<String, PathBuf>,
}

/// A `{frame}` pattern given to `flag` (`--input NAME`, `--inputs`): E0502 when bad.
fn pattern(flag: &str, text: &str) -> Result<FramePattern, Diagnostic> {
    FramePattern::parse(text).map_err(|e| {
        Diagnostic::error(codes::BAD_ARGUMENT_VALUE, format!("{flag}: {e}")).with_help(crate::frame_pattern::FORMS)
    })
}

impl InputFrames {
    /// No inputs (a style that takes none).
    pub fn none() -> InputFrames {
        InputFrames {
            declared: Vec::new(),
            exr: None,
            camera: None,
            first_frame: 0,
            first: HostInputs::new(),
            first_files: BTreeMap::new(),
        }
    }

    /// The inputs `args` give for the style of `m`, read for `first_frame`
    /// (at `time_s`): the renderer is built with them.
    pub fn new(
        m: &Manifest,
        args: &InputArgs,
        camera: Option<&Camera>,
        first_frame: u32,
        time_s: f64,
    ) -> Result<InputFrames, Diagnostic> {
        let declared = declared(m);
        let names: Vec<&str> = declared.iter().map(|(n, _)| n.as_str()).collect();
        let single = pairs("input", args.input, &names)?;
        let map = pairs("map", args.map, &names)?;
        if declared.is_empty() && args.any() {
            return Err(bad(
                format!("style \"{}\" takes no inputs", m.style),
                "remove --input/--inputs, or declare them: `texture color = input(color, linear)`".into(),
            ));
        }
        let exr = args
            .inputs
            .map(|p| pattern("--inputs", &p.to_string_lossy()))
            .transpose()?;
        let mut sources = Vec::new();
        for (name, kind) in declared {
            let from = if let Some(f) = single.get(&name) {
                Origin::File(pattern(&format!("--input {name}"), f)?)
            } else if exr.is_some() {
                let layer = map
                    .get(&name)
                    .cloned()
                    .or_else(|| files::blender_layer(kind).map(String::from))
                    .unwrap_or_else(|| name.clone());
                Origin::Layer(layer)
            } else {
                // Said when its turn comes to be read, in declaration order.
                Origin::Missing
            };
            sources.push((name, kind, from));
        }
        let mut frames = InputFrames {
            declared: sources,
            exr,
            camera: camera.cloned(),
            first_frame,
            first: HostInputs::new(),
            first_files: BTreeMap::new(),
        };
        let (first, files) = frames.read(first_frame, time_s, true)?;
        frames.first = first;
        frames.first_files = files;
        Ok(frames)
    }

    /// The inputs of the first frame read.
    pub fn first(&self) -> &HostInputs {
        &self.first
    }

    /// Whether a file names a `{frame}`: each frame has its own inputs.
    pub fn is_sequence(&self) -> bool {
        self.exr.as_ref().is_some_and(FramePattern::has_frame)
            || self
                .declared
                .iter()
                .any(|(_, _, f)| matches!(f, Origin::File(p) if p.has_frame()))
    }

    /// Before the first frame is rendered: every file of every frame in
    /// `frames` exists (E0421, listing the missing ones) and has the size
    /// of its input's first frame (E0422), by their headers.
    pub fn check_frames(&self, frames: &[u32]) -> Result<(), Diagnostic> {
        for (name, _, _) in &self.declared {
            let Some(pattern) = self.pattern_of(name).filter(|p| p.has_frame()) else {
                continue;
            };
            let missing: Vec<u32> = frames.iter().copied().filter(|f| !pattern.path(*f).is_file()).collect();
            if let Some(first) = missing.first() {
                return Err(missing_frame(name, pattern, *first, &missing, frames));
            }
            let Some((want, first_file)) = self
                .first
                .get(name)
                .map(|l| (l.raw.width, l.raw.height))
                .zip(self.first_files.get(name))
            else {
                continue;
            };
            for &frame in frames.iter().filter(|f| **f != self.first_frame) {
                let path = pattern.path(frame);
                let size = files::header_size(name, &path)?;
                if size != want {
                    return Err(frame_of_another_size(
                        name,
                        (path.as_path(), frame, size),
                        (first_file.as_path(), self.first_frame, want),
                    ));
                }
            }
        }
        Ok(())
    }

    /// The inputs of `frame` (at `time_s`), when they differ from those of
    /// the frame before: `None` for inputs that are one file for all frames
    /// and for the first frame, which the renderer was built with.
    pub fn frame(&self, frame: u32, time_s: f64) -> Result<Option<HostInputs>, Diagnostic> {
        if !self.is_sequence() || frame == self.first_frame {
            return Ok(None);
        }
        self.read(frame, time_s, false).map(|(inputs, _)| Some(inputs))
    }

    /// The file pattern input `name` is read from.
    fn pattern_of(&self, name: &str) -> Option<&FramePattern> {
        match self.declared.iter().find(|(n, _, _)| n == name).map(|(_, _, f)| f)? {
            Origin::File(p) => Some(p),
            Origin::Layer(_) => self.exr.as_ref(),
            Origin::Missing => None,
        }
    }

    /// Every input of `frame`, read and converted (all of them when `all`,
    /// else only those whose files name the frame; the others are the
    /// first frame's), and the file each was read from.
    fn read(&self, frame: u32, time_s: f64, all: bool) -> Result<(HostInputs, BTreeMap<String, PathBuf>), Diagnostic> {
        let pose = self.camera.as_ref().map(|c| c.pose(time_s));
        let mut out = HostInputs::new();
        let mut read_from = BTreeMap::new();
        let mut exr: Option<(PathBuf, files::ExrChannels)> = None;
        let mut first: Option<(String, PathBuf, (u32, u32))> = None;
        for (name, kind, from) in &self.declared {
            let Some(pattern) = self.pattern_of(name) else {
                return Err(bad(
                    format!("the style reads input `{name}` ({}), which was not given", kind.name()),
                    format!("give it: `--input {name}=FILE`, or all inputs from one EXR with `--inputs FILE.exr`"),
                ));
            };
            if !all && !pattern.has_frame() {
                let level = self
                    .first
                    .get(name)
                    .cloned()
                    .ok_or_else(|| bad(format!("input `{name}` was not read"), "this is a bug in npr".into()))?;
                out.insert(name.clone(), level);
                continue;
            }
            let path = pattern.path(frame);
            if pattern.has_frame() && !path.is_file() {
                return Err(missing_frame(name, pattern, frame, &[frame], &[frame]));
            }
            let (raw, source, unorm) = match from {
                Origin::File(_) | Origin::Missing => files::single_file(name, *kind, &path)?,
                Origin::Layer(layer) => {
                    if exr.as_ref().is_none_or(|(p, _)| *p != path) {
                        exr = Some((path.clone(), files::read_exr(name, &path)?));
                    }
                    let channels = &exr.as_ref().expect("read above").1;
                    let raw = files::exr_layer(name, &path.display().to_string(), *kind, channels, layer)?;
                    let blender =
                        files::blender_layer(*kind).is_some_and(|b| layer == b || layer.ends_with(&format!(".{b}")));
                    (raw, files::file_convention(*kind, true, blender), false)
                }
            };
            let shown = path.display().to_string();
            let level = inputs::prepare(name, &shown, *kind, source, raw, pose.as_ref(), unorm)?;
            let size = (level.raw.width, level.raw.height);
            // A sequence's frame against its first (E0422), then against
            // the frame's other inputs (E0420).
            if let Some((first_level, first_file)) = self.first.get(name).zip(self.first_files.get(name)) {
                let want = (first_level.raw.width, first_level.raw.height);
                if size != want {
                    return Err(frame_of_another_size(
                        name,
                        (path.as_path(), frame, size),
                        (first_file.as_path(), self.first_frame, want),
                    ));
                }
            }
            match &first {
                Some((other, other_file, s)) if *s != size => {
                    return Err(bad(
                        format!(
                            "input `{name}` ({shown}) is {}x{}, but input `{other}` ({}) is {}x{}",
                            size.0,
                            size.1,
                            other_file.display(),
                            s.0,
                            s.1
                        ),
                        "every input of a frame is one size: the frame's".into(),
                    ));
                }
                Some(_) => {}
                None => first = Some((name.clone(), path.clone(), size)),
            }
            out.insert(name.clone(), level);
            read_from.insert(name.clone(), path);
        }
        Ok((out, read_from))
    }
}

/// E0421: frame `frame` of input `name`'s sequence has no file; `missing`
/// are all the missing frames of those asked for, `asked`.
fn missing_frame(name: &str, pattern: &FramePattern, frame: u32, missing: &[u32], asked: &[u32]) -> Diagnostic {
    let mut message = format!(
        "input `{name}`: frame {frame}'s file {} does not exist",
        pattern.path(frame).display()
    );
    if missing.len() > 1 {
        let shown: Vec<String> = missing.iter().take(8).map(u32::to_string).collect();
        let more = if missing.len() > 8 { ", …" } else { "" };
        message.push_str(&format!(
            " ({} of the {} frames are missing: {}{more})",
            missing.len(),
            asked.len(),
            shown.join(", ")
        ));
    }
    Diagnostic::error(codes::INPUT_FRAME_MISSING, message).with_help(format!(
        "render the missing frames of `{}`, or ask for frames the sequence has with --frames \
         (a style that reads `previous(...)` replays from frame 0)",
        pattern.text()
    ))
}

/// E0422: input `name`'s file of frame `at.1` is `at.2` in size, and its
/// first frame's `first.2`.
fn frame_of_another_size(name: &str, at: (&Path, u32, (u32, u32)), first: (&Path, u32, (u32, u32))) -> Diagnostic {
    Diagnostic::error(
        codes::INPUT_FRAME_SIZE,
        format!(
            "input `{name}`: frame {} ({}) is {}x{}, but frame {} ({}), the sequence's first, is {}x{}",
            at.1,
            at.0.display(),
            at.2 .0,
            at.2 .1,
            first.1,
            first.0.display(),
            first.2 .0,
            first.2 .1
        ),
    )
    .with_help("every frame of an input sequence is one size, the frame's: re-render the frame at the sequence's size")
}

/// The frame's size: the inputs', which `--size`, when given, must equal.
pub(crate) fn frame_size(inputs: &HostInputs, size: Option<(u32, u32)>) -> Result<(u32, u32), Diagnostic> {
    match (inputs::size(inputs), size) {
        (Some(s), Some(asked)) if s != asked => Err(bad(
            format!(
                "--size {}x{} differs from the inputs' size, {}x{}",
                asked.0, asked.1, s.0, s.1
            ),
            "leave --size out: a style over inputs renders at their size".into(),
        )),
        (Some(s), _) => Ok(s),
        (None, s) => Ok(s.unwrap_or(DEFAULT_SIZE)),
    }
}

/// `--size` when neither it nor inputs give one.
pub(crate) const DEFAULT_SIZE: (u32, u32) = (512, 512);
