//! `npr render`'s host inputs (issue 47): `--input NAME=FILE` per input,
//! `--inputs FILE.exr` for all of them from one multi-layer EXR (Blender's
//! layer names understood, `--map NAME=LAYER` for others), read and
//! converted to the language's conventions (`npr_runner::inputs`). Every
//! problem is E0420 naming the input and the file, found before anything
//! is rendered or written.

use npr_abi::manifest::{Manifest, TextureSourceManifest};
use npr_abi::InputKind;
use npr_diag::diagnostic::did_you_mean;
use npr_diag::{codes, Diagnostic};
use npr_runner::inputs::{self, files, HostInputs};
use npr_runner::scene::CameraPose;
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

/// Every input the style declares, read and converted; `camera` turns
/// normals between world and view space.
pub(crate) fn load(m: &Manifest, args: &InputArgs, camera: Option<&CameraPose>) -> Result<HostInputs, Diagnostic> {
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
    let exr = match args.inputs {
        Some(p) => Some((p, files::read_exr(names.first().copied().unwrap_or("?"), p)?)),
        None => None,
    };
    let mut out = HostInputs::new();
    let mut first: Option<(String, PathBuf, (u32, u32))> = None;
    for (name, kind) in declared {
        let (raw, source, file) = if let Some(f) = single.get(&name) {
            let path = PathBuf::from(f);
            let (raw, source) = files::single_file(&name, kind, &path)?;
            (raw, source, path)
        } else if let Some((path, exr)) = &exr {
            let layer = map
                .get(&name)
                .cloned()
                .or_else(|| files::blender_layer(kind).map(String::from))
                .unwrap_or_else(|| name.clone());
            let file = path.display().to_string();
            let raw = files::exr_layer(&name, &file, kind, exr, &layer)?;
            let blender = files::blender_layer(kind).is_some_and(|b| layer == b || layer.ends_with(&format!(".{b}")));
            (raw, files::file_convention(kind, true, blender), path.to_path_buf())
        } else {
            return Err(bad(
                format!("the style reads input `{name}` ({}), which was not given", kind.name()),
                format!("give it: `--input {name}=FILE`, or all inputs from one EXR with `--inputs FILE.exr`"),
            ));
        };
        let shown = file.display().to_string();
        let level = inputs::convert(&name, &shown, kind, source, &raw, camera)?;
        let size = (level.width, level.height);
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
            None => first = Some((name.clone(), file.clone(), size)),
        }
        out.insert(name, level);
    }
    Ok(out)
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
