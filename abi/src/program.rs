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
        let manifest: Manifest = serde_json::from_str(&text).map_err(|e| LoadError::Json { message: e.to_string() })?;
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
