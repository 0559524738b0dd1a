//! One build of a watched style: load the scene, compile the style for it
//! (with the `--set`s and the studio's controls), and list every file the
//! result depends on, whether the build succeeded or not, so that a fix to
//! any of them triggers the next build.
//!
//! Nothing here prints: `npr watch` prints the diagnostics, `npr studio`
//! sends them to the page.

use npr_compiler::{CompileError, CompileOptions, Compiled};
use npr_diag::{Diagnostic, SourceMap};
use npr_runner::scene::Scene;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What a build reads: given once on the command line.
#[derive(Debug, Clone)]
pub struct Inputs {
    pub style: PathBuf,
    pub scene: PathBuf,
    pub sets: Vec<String>,
    /// Compile with `--keep-params` (the studio, so sliders need no recompile).
    pub keep_params: bool,
    /// `--root` and `--allow-path`.
    pub paths: npr_diag::paths::PathChoice,
    /// `--schedule`, or the command's default.
    pub schedule: npr_compiler::schedule::Schedule,
}

pub struct Built {
    pub compiled: Compiled,
    pub scene: Scene,
    pub sources: SourceMap,
    /// Wall time of scene load + compile (with the `--set` typing).
    pub compile_ms: f64,
}

impl Built {
    /// Every warning of this build, as `npr render` prints them: the
    /// compiler's, then the scene's bindings the style does not read (W0401).
    pub fn warnings(&self) -> Vec<Diagnostic> {
        let mut all = self.compiled.warnings.clone();
        all.extend(npr_runner::scene_warnings(&self.compiled.manifest, &self.scene));
        all
    }
}

pub struct Failed {
    pub diagnostics: Vec<Diagnostic>,
    pub sources: SourceMap,
}

/// Build once. `controls` (the studio's values, `name=value` as a `--set`
/// writes them) apply after the `--set`s, so a control wins over the
/// command line; they are typed against the style as it is now, so a value
/// that an edit of the file made wrong is a diagnostic like a `--set`'s.
pub fn build(inputs: &Inputs, controls: &[String]) -> Result<Built, Failed> {
    let start = Instant::now();
    let mut sources = SourceMap::new();
    let paths = match inputs.paths.policy(&inputs.style, Some(&inputs.scene)) {
        Ok(p) => p,
        Err(d) => {
            return Err(Failed {
                diagnostics: vec![d],
                sources,
            })
        }
    };
    let scene = match npr_runner::scene::load_scene_in(&inputs.scene, &mut sources, Some(&paths)) {
        Ok(s) => s,
        Err(diagnostics) => return Err(Failed { diagnostics, sources }),
    };
    let opts = CompileOptions {
        keep_params: inputs.keep_params,
        scene: Some(scene.summary(&inputs.scene.display().to_string())),
        paths: Some(paths),
        schedule: inputs.schedule,
        ..Default::default()
    };
    let sets: Vec<String> = inputs.sets.iter().chain(controls).cloned().collect();
    match npr_compiler::set_values::compile_with_sets(&inputs.style, &sets, &mut sources, &opts) {
        Ok(compiled) => Ok(Built {
            compiled,
            scene,
            sources,
            compile_ms: start.elapsed().as_secs_f64() * 1e3,
        }),
        Err(CompileError::User(diagnostics)) => Err(Failed { diagnostics, sources }),
        Err(CompileError::Internal(e)) => Err(Failed {
            diagnostics: vec![e.to_diagnostic()],
            sources,
        }),
    }
}

/// Every file a build read or will read: the style, the scene, what the
/// style `use`s, and, when it got that far, the textures and meshes named.
pub fn dependencies(inputs: &Inputs, sources: &SourceMap, built: Option<&Built>) -> Vec<PathBuf> {
    let mut files = vec![inputs.style.clone(), inputs.scene.clone()];
    files.extend(
        sources
            .files()
            .iter()
            .map(|f| PathBuf::from(&f.name))
            .filter(|p| p.is_file()),
    );
    if let Some(b) = built {
        for t in &b.compiled.manifest.textures {
            if let npr_abi::manifest::TextureSourceManifest::Image { resolved, .. } = &t.source {
                files.push(PathBuf::from(resolved));
            }
        }
        for o in &b.scene.objects {
            files.extend(o.textures.values().map(|t| t.resolved.clone()));
            let mesh = Path::new(&o.mesh.source);
            if mesh.is_file() {
                files.push(mesh.to_path_buf());
            }
        }
    }
    files
}
