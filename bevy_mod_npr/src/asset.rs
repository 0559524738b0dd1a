//! A compiled style as a Bevy asset ([`NprStyleAsset`]), its load error,
//! and the loader of precompiled `.nprb` bundles ([`NprBundleLoader`],
//! `npr compile -o STYLE.nprb`), which needs only npr's runtime. The
//! loader that compiles `.npr` files is `source_loader.rs` (the `compiler`
//! feature).

use bevy::asset::io::Reader;
use bevy::asset::{AssetLoader, LoadContext};
use bevy::prelude::*;
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

/// A compiled style. Each load (and reload) gets a new
/// [`NprStyleAsset::revision`]: the render world rebuilds a camera's
/// runtime when it changes.
#[derive(Asset, TypePath, Clone, Debug)]
pub struct NprStyleAsset {
    program: Arc<npr_runner::StyleProgram>,
    revision: u64,
    /// The files besides the style's own that it read (absolute paths).
    read: Vec<PathBuf>,
}

static REVISIONS: AtomicU64 = AtomicU64::new(1);

impl NprStyleAsset {
    /// An asset of a compiled style the program made or loaded itself
    /// (`npr_runner::StyleProgram::from_bundle`, `load_dir`, or the
    /// compiler), to add to `Assets<NprStyleAsset>`.
    pub fn from_program(program: npr_runner::StyleProgram) -> NprStyleAsset {
        NprStyleAsset::new(program, Vec::new())
    }

    pub(crate) fn new(program: npr_runner::StyleProgram, read: Vec<PathBuf>) -> NprStyleAsset {
        NprStyleAsset {
            program: Arc::new(program),
            revision: REVISIONS.fetch_add(1, Ordering::Relaxed),
            read,
        }
    }

    /// The compiled style (manifest and WGSL).
    pub fn program(&self) -> &Arc<npr_runner::StyleProgram> {
        &self.program
    }

    /// Distinct for every successful load of any style.
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// The files the style read besides its own, as absolute paths: its
    /// `use`d modules and filter styles (every file of the compilation)
    /// and the images its `image("...")`s name. The loader makes those
    /// inside the asset folder dependencies of the asset.
    pub fn files_read(&self) -> &[PathBuf] {
        &self.read
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

impl NprLoadError {
    /// The error of `diags`, logged as npr prints them.
    pub(crate) fn logged(path: PathBuf, diags: &[npr_diag::Diagnostic], sources: &npr_diag::SourceMap) -> NprLoadError {
        let rendered = npr_diag::diagnostic::render(diags, sources, false);
        error!("{rendered}");
        NprLoadError {
            path,
            codes: diags.iter().map(|d| d.code).collect(),
            rendered,
        }
    }
}

/// Loads `.nprb` files, written by `npr compile STYLE -o STYLE.nprb`: the
/// manifest, WGSL and image files of a compiled style, validated as the
/// runtime reads them. A bundle that does not load is E0507, logged.
#[derive(TypePath, Default)]
pub struct NprBundleLoader;

impl NprBundleLoader {
    /// The asset of a bundle's `bytes` (the file at `path`, for messages).
    pub fn load_bytes(&self, path: &std::path::Path, bytes: &[u8]) -> Result<NprStyleAsset, NprLoadError> {
        npr_runner::StyleProgram::from_bundle(bytes)
            .map(NprStyleAsset::from_program)
            .map_err(|e| {
                let d = npr_diag::Diagnostic::error(npr_diag::codes::BAD_COMPILED_DIR, format!("{}: {e}", path.display()))
                    .with_help("compile the style again with `npr compile STYLE -o STYLE.nprb` of the npr release this program uses");
                NprLoadError::logged(path.to_path_buf(), &[d], &npr_diag::SourceMap::new())
            })
    }
}

/// Reads an asset's bytes; a read error is `BAD_USE`, naming the file.
pub(crate) async fn read_all(reader: &mut dyn Reader, path: &std::path::Path) -> Result<Vec<u8>, NprLoadError> {
    let mut bytes = Vec::new();
    if let Err(e) = reader.read_to_end(&mut bytes).await {
        let d = npr_diag::Diagnostic::error(
            npr_diag::codes::BAD_USE,
            format!("cannot read the style {}: {e}", path.display()),
        );
        return Err(NprLoadError::logged(
            path.to_path_buf(),
            &[d],
            &npr_diag::SourceMap::new(),
        ));
    }
    Ok(bytes)
}

impl AssetLoader for NprBundleLoader {
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
        self.load_bytes(&path, &bytes)
    }

    fn extensions(&self) -> &[&str] {
        &["nprb"]
    }
}
