//! `.npr` files as Bevy assets: [`NprStyleLoader`] compiles a style with
//! npr's compiler (its parameters kept as uniforms, so [`crate::NprParams`]
//! can change every one) into an [`NprStyleAsset`]. A style that does not
//! compile is logged as npr prints it (`error[E0001]: ...`, then
//! `file:line:col` and the source line) and the load fails; on a hot
//! reload Bevy then keeps the asset it had, so a broken save keeps the
//! last style that compiled.

use bevy::asset::io::Reader;
use bevy::asset::{AssetLoader, LoadContext};
use bevy::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

/// A compiled style. Each load (and reload) gets a new
/// [`NprStyleAsset::revision`]: the render world rebuilds a camera's
/// runtime when it changes.
#[derive(Asset, TypePath, Clone, Debug)]
pub struct NprStyleAsset {
    program: Arc<runner::StyleProgram>,
    revision: u64,
}

impl NprStyleAsset {
    /// The compiled style (manifest and WGSL).
    pub fn program(&self) -> &Arc<runner::StyleProgram> {
        &self.program
    }

    /// Distinct for every successful load of any style.
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// The style's name (its `style "..."` line).
    pub fn name(&self) -> &str {
        &self.program.manifest.style
    }
}

/// Why a `.npr` asset did not load: the codes of its diagnostics, and
/// their text as logged (npr's rendering: code, message, `file:line:col`,
/// the source line).
#[derive(Debug)]
pub struct NprLoadError {
    pub path: PathBuf,
    pub codes: Vec<&'static str>,
    pub rendered: String,
}

impl std::fmt::Display for NprLoadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the style {} did not compile ({}); the camera keeps its last style that compiled",
            self.path.display(),
            self.codes.join(", ")
        )
    }
}

impl std::error::Error for NprLoadError {}

/// Compiles `.npr` files. `root` is the asset folder on disk: a style's
/// `use`s and `image("...")`s are read relative to its own file, as `npr
/// render` reads them.
#[derive(TypePath)]
pub struct NprStyleLoader {
    pub root: PathBuf,
}

static REVISIONS: AtomicU64 = AtomicU64::new(1);

impl NprStyleLoader {
    /// Compile `bytes`, the text of the style at `path` (relative to the
    /// asset root). Diagnostics (errors and warnings) go to Bevy's log.
    pub fn compile(&self, path: &Path, bytes: Vec<u8>) -> Result<NprStyleAsset, NprLoadError> {
        let file = self.root.join(path);
        let name = file.display().to_string();
        let dir = file.parent().map(Path::to_path_buf).unwrap_or_default();
        let mut sources = diag::SourceMap::new();
        let fail = |diags: &[diag::Diagnostic], sources: &diag::SourceMap| {
            let rendered = diag::diagnostic::render(diags, sources, false);
            error!("{rendered}");
            NprLoadError {
                path: file.clone(),
                codes: diags.iter().map(|d| d.code).collect(),
                rendered,
            }
        };
        let text = match diag::text::add_utf8(&mut sources, &name, bytes) {
            Ok((_, text)) => text,
            Err(d) => return Err(fail(&[d], &sources)),
        };
        // `add_utf8` only checked the text: the compiler adds the file itself.
        let mut sources = diag::SourceMap::new();
        let options = compiler::CompileOptions {
            keep_params: true,
            ..Default::default()
        };
        match compiler::compile_source(&name, &text, &dir, &mut sources, &options) {
            Ok(compiled) => {
                if !compiled.warnings.is_empty() {
                    warn!("{}", diag::diagnostic::render(&compiled.warnings, &sources, false));
                }
                Ok(NprStyleAsset {
                    program: Arc::new(compiled.program()),
                    revision: REVISIONS.fetch_add(1, Ordering::Relaxed),
                })
            }
            Err(compiler::CompileError::User(diags)) => Err(fail(&diags, &sources)),
            Err(compiler::CompileError::Internal(e)) => Err(fail(&[e.to_diagnostic()], &sources)),
        }
    }
}

impl AssetLoader for NprStyleLoader {
    type Asset = NprStyleAsset;
    type Settings = ();
    type Error = NprLoadError;

    async fn load(
        &self,
        reader: &mut dyn Reader,
        _settings: &(),
        load_context: &mut LoadContext<'_>,
    ) -> Result<NprStyleAsset, NprLoadError> {
        let path = load_context.path().path().to_path_buf();
        let mut bytes = Vec::new();
        if let Err(e) = reader.read_to_end(&mut bytes).await {
            let d = diag::Diagnostic::error(
                diag::codes::BAD_USE,
                format!("cannot read the style {}: {e}", path.display()),
            );
            let rendered = diag::diagnostic::render(&[d], &diag::SourceMap::new(), false);
            error!("{rendered}");
            return Err(NprLoadError {
                path,
                codes: vec![diag::codes::BAD_USE],
                rendered,
            });
        }
        self.compile(&path, bytes)
    }

    fn extensions(&self) -> &[&str] {
        &["npr"]
    }
}
