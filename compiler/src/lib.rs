//! The npr compiler: `.npr` source to validated WGSL plus a manifest.
//!
//! See [`pipeline`] for the order of the stages. User errors come back as
//! [`npr_diag::Diagnostic`]s ([`CompileError::User`]); a bug in the compiler, such
//! as emitted WGSL that naga rejects, is a separate [`InternalError`].
//!
//! What it produces is defined in the `abi` crate (the manifest types, the
//! frame block, [`npr_abi::StyleProgram`] via [`Compiled::program`]); the compiler
//! does not depend on the runner, nor the runner on it.

pub mod back;
pub mod describe;
pub mod dump;
pub mod front;
pub mod ir;
pub mod mid;
pub mod pipeline;
pub mod report;
pub mod schedule;
pub mod set_values;

/// The loading stage alone, for tools that need a style's declarations
/// without compiling it (the language server): the document and every
/// file it `use`s, parsed with recovery.
pub use front::load::{load_source, Loaded};

use npr_abi::SceneSummary;
use npr_diag::{Diagnostic, SourceMap, Span};
use std::path::Path;

#[derive(Debug, Clone, Default)]
pub struct CompileOptions {
    /// Keep every live parameter as a uniform (for live tweaking) instead of folding it.
    pub keep_params: bool,
    /// Record a dump of the IR after each stage.
    pub dump_ir: bool,
    /// The scene the style will run on, when known: `scene_has(tag)` folds to
    /// a constant, so passes only an absent tag needs are pruned. `None` keeps
    /// everything (`scene_has` is conservatively `true`).
    pub scene: Option<SceneSummary>,
    /// New defaults for parameters (`--set`, the studio's controls, a
    /// filter's arguments), as written: typed against the params after
    /// typecheck (`front::param_settings`) and applied there, so they fold
    /// like written defaults. Their spans are in the caller's `SourceMap`.
    pub settings: Vec<ir::ParamSetting>,
    /// Which files the style may read (`use`, `image("…")`): `None` reads
    /// any path (library use); the `npr` commands always give one
    /// (`npr_diag::paths`, docs/PATHS.md).
    pub paths: Option<npr_diag::paths::PathPolicy>,
    /// Where the files the style names are read from: the disk by default;
    /// in memory (`npr_diag::files::MemoryFiles`, with
    /// `PathPolicy::in_memory`) where there is no file system, as in the
    /// WebAssembly build (decision 0052).
    pub files: npr_diag::files::Files,
    /// How the passes run (`--schedule`): `Auto` fuses pointwise image
    /// chains; `Naive` keeps every declared pass and target.
    pub schedule: schedule::Schedule,
    /// Tests only: every workgroup tile is this many texels narrower than
    /// the operators' footprints say, so reads fall outside it and the
    /// tiled pass takes the path a wrong footprint would (the workgroup
    /// runs again, reading the targets themselves; `emit/tiled`). The
    /// image must not change.
    #[doc(hidden)]
    pub tile_apron_deficit: u32,
}

#[derive(Debug, Clone)]
pub struct Compiled {
    pub manifest: npr_abi::Manifest,
    /// (file name, WGSL) per live pass, in execution order.
    pub shaders: Vec<(String, String)>,
    pub report: report::Report,
    pub warnings: Vec<Diagnostic>,
    /// Per manifest texture: where the style names its file (the path in
    /// `image("…")`), for errors found when the runner opens it.
    pub texture_spans: Vec<Span>,
    pub timings: Vec<(&'static str, std::time::Duration)>,
    pub dumps: Vec<(&'static str, String)>,
    /// Each live target's proved value range (`mid/ranges`, issue 49).
    pub ranges: Vec<mid::ranges::TargetRange>,
}

impl Compiled {
    pub fn shader(&self, file: &str) -> Option<&str> {
        self.shaders.iter().find(|(f, _)| f == file).map(|(_, s)| s.as_str())
    }

    /// The manifest and shaders as the runner takes them.
    pub fn program(&self) -> npr_abi::StyleProgram {
        npr_abi::StyleProgram {
            manifest: self.manifest.clone(),
            shaders: self.shaders.iter().cloned().collect(),
            files: Default::default(),
        }
    }

    /// Each live target's proved range as text (`mid/ranges/text.rs`):
    /// what `npr check --ranges` and `npr compile --report` print.
    pub fn ranges_text(&self, sources: &npr_diag::SourceMap) -> String {
        mid::ranges::text::render(&self.ranges, sources)
    }
}

/// A bug in npr. Reported with the `.npr` span that produced the bad code.
#[derive(Debug, Clone, thiserror::Error)]
#[error("internal compiler error: {message}\n{detail}")]
pub struct InternalError {
    pub message: String,
    pub detail: String,
    pub span: Option<Span>,
    pub wgsl: Option<String>,
}

impl InternalError {
    /// As a diagnostic pointing at the `.npr` source (code E9001).
    pub fn to_diagnostic(&self) -> Diagnostic {
        let mut d = Diagnostic::error(
            npr_diag::codes::INTERNAL,
            format!("internal compiler error: {}", self.message),
        )
        .with_note(self.detail.clone())
        .with_help("this is a bug in npr, not in your style; please report it with this .npr file");
        if let Some(s) = self.span {
            let label = if self.wgsl.is_some() {
                "the code generated for this failed validation"
            } else {
                "the compiler reached an impossible state here"
            };
            d = d.with_primary(s, label);
        }
        d
    }
}

#[derive(Debug, Clone)]
pub enum CompileError {
    User(Vec<Diagnostic>),
    Internal(InternalError),
}

/// Compile a `.npr` file (and what it `use`s). Files read are added to `sources`.
pub fn compile_file(path: &Path, sources: &mut SourceMap, opts: &CompileOptions) -> Result<Compiled, CompileError> {
    let mut diags = Vec::new();
    let Some(loaded) = front::load::load_file_from(opts.files.source(), path, sources, opts.paths.as_ref(), &mut diags)
    else {
        return Err(CompileError::User(diags));
    };
    pipeline::run(loaded, sources, &path.display().to_string(), opts, diags)
}

/// Compile source text; relative paths (textures, `use`) resolve against `dir`.
pub fn compile_source(
    name: &str,
    text: &str,
    dir: &Path,
    sources: &mut SourceMap,
    opts: &CompileOptions,
) -> Result<Compiled, CompileError> {
    let mut diags = Vec::new();
    let loaded = front::load::load_source_from(
        opts.files.source(),
        name,
        text,
        dir,
        sources,
        opts.paths.as_ref(),
        &mut diags,
    );
    pipeline::run(loaded, sources, name, opts, diags)
}
