//! `.npr` files as Bevy assets (the `compiler` feature): [`NprStyleLoader`]
//! compiles a style with npr's compiler (its parameters kept as uniforms,
//! so [`crate::NprParams`] can change every one) into an [`NprStyleAsset`].
//! A style that does not compile is logged as npr prints it
//! (`error[E0001]: ...`, then `file:line:col` and the source line) and the
//! load fails; on a hot reload Bevy then keeps the asset it had, so a
//! broken save keeps the last style that compiled.
//!
//! The files a style reads besides its own (`use`d modules, filter styles,
//! `image("...")` files) are read again through Bevy's `LoadContext`, which
//! makes them the asset's loader dependencies: with hot reload on, editing
//! one reloads the style. Files outside the asset folder cannot be asset
//! paths; they are logged once per load and not watched.

use crate::asset::{read_all, NprLoadError, NprStyleAsset};
use bevy::asset::io::Reader;
use bevy::asset::{AssetLoader, LoadContext};
use bevy::prelude::*;
use std::path::{Path, PathBuf};

/// Compiles `.npr` files. `root` is the asset folder on disk: a style's
/// `use`s and `image("...")`s are read relative to its own file, as `npr
/// render` reads them.
#[derive(TypePath)]
pub struct NprStyleLoader {
    pub root: PathBuf,
}

impl NprStyleLoader {
    /// Compile `bytes`, the text of the style at `path` (relative to the
    /// asset root). Diagnostics (errors and warnings) go to Bevy's log.
    pub fn compile(&self, path: &Path, bytes: Vec<u8>) -> Result<NprStyleAsset, NprLoadError> {
        let file = self.root.join(path);
        let name = file.display().to_string();
        let dir = file.parent().map(Path::to_path_buf).unwrap_or_default();
        let mut sources = npr_diag::SourceMap::new();
        let fail = |diags: &[npr_diag::Diagnostic], sources: &npr_diag::SourceMap| {
            NprLoadError::logged(file.clone(), diags, sources)
        };
        let text = match npr_diag::text::add_utf8(&mut sources, &name, bytes) {
            Ok((_, text)) => text,
            Err(d) => return Err(fail(&[d], &sources)),
        };
        // `add_utf8` only checked the text: the compiler adds the file itself.
        let mut sources = npr_diag::SourceMap::new();
        let options = npr_compiler::CompileOptions {
            keep_params: true,
            ..Default::default()
        };
        match npr_compiler::compile_source(&name, &text, &dir, &mut sources, &options) {
            Ok(compiled) => {
                if !compiled.warnings.is_empty() {
                    warn!("{}", npr_diag::diagnostic::render(&compiled.warnings, &sources, false));
                }
                let program = compiled.program();
                let read = files_read(&file, &sources, &program);
                Ok(NprStyleAsset::new(program, read))
            }
            Err(npr_compiler::CompileError::User(diags)) => Err(fail(&diags, &sources)),
            Err(npr_compiler::CompileError::Internal(e)) => Err(fail(&[e.to_diagnostic()], &sources)),
        }
    }
}

/// Every file of the compilation but the style's own (`sources` holds each
/// file by the path it was read from) and every `image("...")` file.
fn files_read(style: &Path, sources: &npr_diag::SourceMap, program: &npr_runner::StyleProgram) -> Vec<PathBuf> {
    let own = canonical(style);
    let mut read: Vec<PathBuf> = sources
        .files()
        .iter()
        .map(|f| canonical(Path::new(&f.name)))
        .chain(program.manifest.textures.iter().filter_map(|t| match &t.source {
            npr_abi::manifest::TextureSourceManifest::Image { resolved, .. } => Some(canonical(Path::new(resolved))),
            _ => None,
        }))
        .filter(|p| *p != own && p.is_absolute())
        .collect();
    read.sort();
    read.dedup();
    read
}

fn canonical(path: &Path) -> PathBuf {
    path.canonicalize().unwrap_or_else(|_| path.to_path_buf())
}

impl NprStyleLoader {
    /// Read each file the style read through `load_context`, so that Bevy
    /// records it as a dependency and reloads the style when it changes.
    async fn depend_on_files_read(&self, asset: &NprStyleAsset, load_context: &mut LoadContext<'_>) {
        let root = canonical(&self.root);
        for file in asset.files_read() {
            let Ok(relative) = file.strip_prefix(&root) else {
                info!(
                    "the style {} reads {}, outside the asset folder {}: editing it does not reload the style",
                    load_context.path(),
                    file.display(),
                    root.display()
                );
                continue;
            };
            // Asset paths are written with `/` on every platform.
            let asset_path = relative
                .components()
                .map(|c| c.as_os_str().to_string_lossy())
                .collect::<Vec<_>>()
                .join("/");
            if let Err(e) = load_context.read_asset_bytes(asset_path).await {
                // The compiler read it a moment ago; a file gone since is
                // only not watched (the runtime reports a missing image).
                warn!(
                    "the style {} reads {}, which Bevy cannot read ({e}): editing it does not reload the style",
                    load_context.path(),
                    file.display()
                );
            }
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
        let bytes = read_all(reader, &path).await?;
        let asset = self.compile(&path, bytes)?;
        self.depend_on_files_read(&asset, load_context).await;
        Ok(asset)
    }

    fn extensions(&self) -> &[&str] {
        &["npr"]
    }
}
