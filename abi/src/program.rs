//! A compiled style as the runner sees it: the manifest plus WGSL per pass,
//! either straight from the compiler (`npr_compiler::Compiled::program`) or read
//! back from `npr compile -o DIR` ([`StyleProgram::load_dir`], validated).

use crate::manifest::Manifest;
use crate::validate::Invalid;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

#[derive(Debug, Clone)]
pub struct StyleProgram {
    pub manifest: Manifest,
    /// WGSL source by shader file name (`<pass>.wgsl`).
    pub shaders: BTreeMap<String, String>,
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
}

impl std::fmt::Display for LoadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LoadError::Io { path, message } => write!(f, "cannot read {}: {message}", path.display()),
            LoadError::Json { message } => write!(f, "bad manifest.json: {message}"),
            LoadError::Invalid(e) => write!(f, "bad manifest.json: {e}"),
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
        let program = StyleProgram { manifest, shaders };
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
