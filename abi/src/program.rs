//! A compiled style as the runner sees it: the manifest plus WGSL per pass,
//! either straight from the compiler (`npr_compiler::Compiled::program`) or read
//! back from `npr compile -o DIR` ([`StyleProgram::load_dir`], validated)
//! or from one bundle file ([`StyleProgram::from_bundle`], `bundle.rs`).

use crate::manifest::Manifest;
use crate::validate::Invalid;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

#[derive(Debug, Clone)]
pub struct StyleProgram {
    pub manifest: Manifest,
    /// WGSL source by shader file name (`<pass>.wgsl`).
    pub shaders: BTreeMap<String, String>,
    /// The image files the manifest names, by their `resolved` path, when
    /// the program carries them ([`StyleProgram::from_bundle`]); the runtime
    /// then reads them from here and never from disk. Empty for a program
    /// from the compiler or [`StyleProgram::load_dir`], whose files are on
    /// disk.
    pub files: BTreeMap<String, Vec<u8>>,
}

/// Why a compiled directory cannot be run.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum LoadError {
    /// A file could not be read.
    Io { path: PathBuf, message: String },
    /// `manifest.json` is not JSON of the manifest's shape.
    Json { message: String },
    /// A value in the manifest is out of range or inconsistent.
    Invalid(Invalid),
    /// A bundle's container is not one this runtime reads
    /// (`crate::bundle`): `field` names the part, as `bundle.entries[3]`.
    Bundle { field: String, message: String },
}

impl std::fmt::Display for LoadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LoadError::Io { path, message } => write!(f, "cannot read {}: {message}", path.display()),
            LoadError::Json { message } => write!(f, "bad manifest.json: {message}"),
            LoadError::Invalid(e) => write!(f, "bad manifest.json: {e}"),
            LoadError::Bundle { field, message } => write!(f, "bad bundle: `{field}`: {message}"),
        }
    }
}

impl std::error::Error for LoadError {}

/// `manifest.json`'s text as a [`Manifest`]. Its `version` is read first:
/// a manifest of another version is refused by its number (with what to
/// do), not as JSON of an unknown shape, so an older runner given a newer
/// style's manifest says so even when the newer one has fields it cannot
/// parse.
pub fn parse_manifest(text: &str) -> Result<Manifest, LoadError> {
    #[derive(serde::Deserialize)]
    struct VersionOnly {
        version: u32,
    }
    if let Ok(VersionOnly { version }) = serde_json::from_str::<VersionOnly>(text) {
        if version != crate::MANIFEST_VERSION {
            return Err(LoadError::Invalid(crate::validate::Invalid {
                field: "version".into(),
                message: format!(
                    "manifest version {version} is not supported (expected {}); {}",
                    crate::MANIFEST_VERSION,
                    if version > crate::MANIFEST_VERSION {
                        "the style was compiled by a newer npr: update this runner, or recompile the style"
                    } else {
                        "recompile the style"
                    }
                ),
            }));
        }
    }
    serde_json::from_str(text).map_err(|e| LoadError::Json { message: e.to_string() })
}

impl From<Invalid> for LoadError {
    fn from(e: Invalid) -> LoadError {
        LoadError::Invalid(e)
    }
}

impl StyleProgram {
    /// A compiled style at `path`: a directory ([`StyleProgram::load_dir`])
    /// or a bundle file ([`StyleProgram::from_bundle`]).
    pub fn load(path: &Path) -> Result<StyleProgram, LoadError> {
        if path.is_dir() {
            return StyleProgram::load_dir(path);
        }
        let bytes = std::fs::read(path).map_err(|e| LoadError::Io {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        StyleProgram::from_bundle(&bytes)
    }

    /// Read `manifest.json` and the WGSL files beside it; the manifest is
    /// validated ([`StyleProgram::validate`]) before anything else reads it.
    pub fn load_dir(dir: &Path) -> Result<StyleProgram, LoadError> {
        let read = |path: PathBuf| {
            std::fs::read_to_string(&path).map_err(|e| LoadError::Io {
                message: e.to_string(),
                path,
            })
        };
        let text = read(dir.join("manifest.json"))?;
        let manifest = parse_manifest(&text)?;
        // Before the shader names are used as paths.
        manifest.validate()?;
        let mut shaders = BTreeMap::new();
        for p in &manifest.passes {
            if !shaders.contains_key(&p.shader) {
                shaders.insert(p.shader.clone(), read(dir.join(&p.shader))?);
            }
        }
        let program = StyleProgram {
            manifest,
            shaders,
            files: BTreeMap::new(),
        };
        program.validate()?;
        Ok(program)
    }

    /// The manifest's checks ([`Manifest::validate`]), and a shader for every pass.
    pub fn validate(&self) -> Result<(), Invalid> {
        self.manifest.validate()?;
        for (i, p) in self.manifest.passes.iter().enumerate() {
            if !self.shaders.contains_key(&p.shader) {
                return Err(Invalid {
                    field: format!("passes[{i}].shader"),
                    message: format!("no shader `{}` for pass `{}`", p.shader, p.name),
                });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A newer compiler's manifest, with a field this runner cannot parse,
    /// is refused by its version number, saying which side to update.
    #[test]
    fn another_version_is_refused_by_its_number_before_its_shape() {
        let newer = format!(
            "{{\"version\": {}, \"passes\": [{{\"depth\": \"some_future_mode\"}}]}}",
            crate::MANIFEST_VERSION + 1
        );
        let e = parse_manifest(&newer).expect_err("a newer version");
        assert!(matches!(&e, LoadError::Invalid(i) if i.field == "version"), "{e}");
        assert!(e.to_string().contains("newer npr"), "{e}");
        let older = "{\"version\": 8}";
        let e = parse_manifest(older).expect_err("an older version");
        assert!(e.to_string().contains("recompile the style"), "{e}");
        // This version's own shape errors stay JSON errors.
        let bad = format!("{{\"version\": {}}}", crate::MANIFEST_VERSION);
        assert!(matches!(parse_manifest(&bad), Err(LoadError::Json { .. })));
    }
}
