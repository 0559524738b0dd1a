//! Stability sweeps: a style rendered with each parameter across its
//! declared range (`points.rs`) on its own tests' scenes and on the hard
//! scenes npr ships (`cases.rs`), every combination checked for NaN or Inf
//! in any target, a blank output where the defaults are not blank, and
//! errors. Each finding comes with its smallest reproduction: one
//! `npr render` command line with the fewest `--set` values that show it
//! (a pair is reported only where neither of its values does alone, a
//! covering-array row is reduced to the pair in it that shows the same, a
//! combination only where the defaults do not fail the same way) on the
//! cheapest case where it shows.
//!
//! Each combination is compiled as `npr render --set` compiles it (values
//! folded as constants, where division by a constant zero happens), under
//! the naive schedule so that every declared target is stored and read
//! back as floats.

pub mod cases;
pub mod covering;
pub mod points;

use super::checks;
use super::frames::{self, Frames};
use super::outcome::{Failure, Outcome, Run, Settings, Status};
use cases::Case;
use npr_abi::manifest::{ParamBinding, ParamManifest};
use npr_abi::param_value::{type_value, ParamShape, ValueKind};
use npr_compiler::ir::SettingOrigin;
use npr_compiler::{CompileError, CompileOptions};
use npr_diag::codes;
use npr_diag::paths::PathChoice;
use npr_diag::{Diagnostic, SourceMap};
use npr_runner::scene::Scene;
use points::Combination;
use std::path::Path;
use std::time::Instant;

/// What a sweep found, and what it covered.
pub struct SweepResult {
    pub failures: Vec<Failure>,
    /// e.g. "9 combinations × 11 cases; not swept (no range): `gamma`".
    pub summary: String,
}

/// Why a sweep could not start: a case's scene or the style at its
/// defaults is bad input (or npr failed), with the sources to show it.
pub struct Stopped {
    pub diagnostics: Vec<Diagnostic>,
    pub sources: SourceMap,
}

/// What one combination did on one case.
#[derive(Debug, Clone, PartialEq)]
enum Probe {
    Rendered {
        /// One line per target holding NaN or Inf.
        non_finite: Vec<String>,
        /// The one colour of an output that has only one.
        blank: Option<[u8; 4]>,
    },
    /// A diagnostic's headline (`E0203: ...`) or a device error.
    Error(String),
}

/// The ways a combination fails on a case, each with its message.
fn problems(probe: &Probe, baseline: &Probe) -> Vec<(&'static str, String)> {
    match probe {
        Probe::Error(e) => vec![("error", e.clone())],
        Probe::Rendered { non_finite, blank } => {
            let mut found: Vec<(&'static str, String)> = non_finite.iter().map(|m| ("finite", m.clone())).collect();
            // Blank only where the defaults are not: a speck 400 m away
            // may rightly leave one colour.
            let baseline_blank = matches!(baseline, Probe::Rendered { blank: Some(_), .. });
            if let (Some([r, g, b, a]), false) = (blank, baseline_blank) {
                found.push((
                    "blank",
                    format!("the output is one colour, #{r:02x}{g:02x}{b:02x}{a:02x}, where the defaults are not"),
                ));
            }
            found
        }
    }
}

/// One combination's problems over the cases.
struct Finding {
    combination: Combination,
    /// (case index, check, message), in case order.
    seen: Vec<(usize, &'static str, String)>,
}

/// Sweep `style` over `cases`.
pub fn sweep(style: &Path, cases: &[Case], settings: &Settings) -> Result<SweepResult, Stopped> {
    let loaded = load_cases(style, cases)?;
    let declared = params(style, &loaded)?;
    let shapes: Vec<ParamShape> = declared.iter().map(ParamShape::of_manifest).collect();
    // A kept uniform takes a new value without a new compile or pipeline,
    // as in the studio: those combinations render with one renderer.
    let uniform: Vec<&str> = declared
        .iter()
        .filter(|p| p.binding == ParamBinding::Uniform && !p.default_percent_of_height)
        .map(|p| p.name.as_str())
        .collect();
    let kept = |c: &Combination| c.iter().all(|(n, _)| uniform.contains(&n.as_str()));
    let axes: Vec<points::Axis> = shapes.iter().filter_map(points::axis).collect();
    let unswept: Vec<String> = shapes
        .iter()
        .filter(|p| !p.per_object && !axes.iter().any(|a| a.name == p.name))
        .map(|p| format!("`{}`", p.name))
        .collect();
    let combinations = points::combinations(&axes);
    // Per case, per combination: the problems' checks (for the pairs' minimality).
    let mut failed: Vec<Vec<Vec<&'static str>>> = vec![vec![Vec::new(); combinations.len()]; cases.len()];
    let mut findings: Vec<Finding> = Vec::new();
    for (ci, (case, scene, base_sources)) in loaded.iter().enumerate() {
        let mut uniforms = Uniforms::new(style, case, scene, base_sources);
        let mut run = |combination: &Combination| {
            if kept(combination) {
                uniforms.probe(combination, &shapes, scene, settings)
            } else {
                probe(style, case, scene, base_sources, combination, settings)
            }
        };
        let baseline = run(&Vec::new());
        // A colour may be the background's: one colour is then the true
        // picture (black ink on black), not a finding.
        let checks_of = |result: &Probe, combination: &Combination| {
            let mut found = problems(result, &baseline);
            let sets_colour = combination
                .iter()
                .any(|(n, _)| shapes.iter().any(|s| &s.name == n && s.kind == ValueKind::Colour));
            if !case.check_blank || sets_colour {
                found.retain(|(check, _)| *check != "blank");
            }
            found
        };
        for (k, combination) in combinations.iter().enumerate() {
            let result = if k == 0 { baseline.clone() } else { run(combination) };
            let mut found = checks_of(&result, combination);
            for (check, _) in &found {
                failed[ci][k].push(check);
            }
            if k > 0 {
                // What the defaults already fail on this case is their finding.
                found.retain(|(check, _)| !failed[ci][0].contains(check));
            }
            if combination.len() > 1 {
                // A pair shows nothing new where one of its values alone fails the same way.
                found.retain(|(check, _)| {
                    !combination.iter().any(|single| {
                        combinations
                            .iter()
                            .position(|c| c.len() == 1 && c[0] == *single)
                            .is_some_and(|s| failed[ci][s].contains(check))
                    })
                });
            }
            if found.is_empty() {
                continue;
            }
            // A covering row sets many params: reduce it to the first pair
            // of them that shows the same check alone (its singles were
            // ruled out above), else keep the whole row.
            let mut shown = combination.clone();
            if combination.len() > 2 {
                let pairs = (0..combination.len())
                    .flat_map(|a| (a + 1..combination.len()).map(move |b| (a, b)))
                    .collect::<Vec<_>>();
                for (a, b) in pairs {
                    let pair = vec![combination[a].clone(), combination[b].clone()];
                    let checks = checks_of(&run(&pair), &pair);
                    let same = |c: &&str| checks.iter().any(|(d, _)| d == c);
                    if found.iter().any(|(c, _)| same(c)) {
                        found.retain(|(c, _)| same(c));
                        shown = pair;
                        break;
                    }
                }
            }
            let finding = match findings.iter_mut().position(|f| f.combination == shown) {
                Some(i) => &mut findings[i],
                None => {
                    findings.push(Finding {
                        combination: shown.clone(),
                        seen: Vec::new(),
                    });
                    findings.last_mut().expect("just pushed")
                }
            };
            finding
                .seen
                .extend(found.into_iter().map(|(check, message)| (ci, check, message)));
        }
    }
    let failures = findings
        .iter()
        .map(|f| report(style, cases, f, kept(&f.combination)))
        .collect();
    let mut summary = format!(
        "swept {} combination(s) of {} parameter(s) on {} case(s)",
        combinations.len(),
        axes.len(),
        cases.len()
    );
    let (covered, pairs) = points::pairs_covered(&axes);
    if pairs > 0 {
        summary.push_str(&format!(
            "; {covered} of {pairs} pairs of parameter ends covered by {} combination(s)",
            combinations.iter().filter(|c| c.len() >= 2).count()
        ));
    }
    if !unswept.is_empty() {
        summary.push_str(&format!("; not swept (no declared range): {}", unswept.join(", ")));
    }
    Ok(SweepResult { failures, summary })
}

/// Each case's scene, loaded once (a bad scene is bad input).
fn load_cases<'c>(style: &Path, cases: &'c [Case]) -> Result<Vec<(&'c Case, Scene, SourceMap)>, Stopped> {
    cases
        .iter()
        .map(|case| {
            let mut sources = SourceMap::new();
            let loaded = PathChoice::default()
                .policy(style, Some(&case.scene))
                .map_err(|d| vec![d])
                .and_then(|policy| npr_runner::scene::load_scene_in(&case.scene, &mut sources, Some(&policy)));
            match loaded {
                Ok(scene) => Ok((case, scene, sources)),
                Err(diagnostics) => Err(Stopped { diagnostics, sources }),
            }
        })
        .collect()
}

/// The style's parameters, from a compile that keeps them all (so none is
/// folded away before the sweep sees it) on the first case that compiles.
fn params(style: &Path, loaded: &[(&Case, Scene, SourceMap)]) -> Result<Vec<ParamManifest>, Stopped> {
    let mut first_error = None;
    for (case, scene, base) in loaded {
        let mut sources = base.clone();
        let opts = CompileOptions {
            keep_params: true,
            ..options(style, case, scene, Vec::new())
        };
        match npr_compiler::compile_file(style, &mut sources, &opts) {
            Ok(c) => {
                return Ok(c
                    .manifest
                    .params
                    .iter()
                    .filter(|p| p.binding != ParamBinding::Removed)
                    .cloned()
                    .collect())
            }
            Err(CompileError::User(diagnostics)) => {
                first_error = first_error.or(Some(Stopped { diagnostics, sources }));
            }
            Err(CompileError::Internal(e)) => {
                return Err(Stopped {
                    diagnostics: vec![e.to_diagnostic()],
                    sources,
                })
            }
        }
    }
    Err(first_error.unwrap_or(Stopped {
        diagnostics: Vec::new(),
        sources: SourceMap::new(),
    }))
}

fn options(style: &Path, case: &Case, scene: &Scene, settings: Vec<npr_compiler::ir::ParamSetting>) -> CompileOptions {
    CompileOptions {
        scene: Some(scene.summary(&case.scene.display().to_string())),
        paths: PathChoice::default().policy(style, Some(&case.scene)).ok(),
        settings,
        schedule: npr_compiler::schedule::Schedule::Naive,
        ..Default::default()
    }
}

/// The `--sweep` of `style` over `cases`, as one outcome named `@sweep`.
pub fn run_sweep(style: &Path, cases: &[Case], settings: &Settings) -> Run {
    let started = Instant::now();
    let (status, failures, diagnostics, note, sources) = match sweep(style, cases, settings) {
        Ok(r) if r.failures.is_empty() => (
            Status::Passed,
            Vec::new(),
            Vec::new(),
            Some(r.summary),
            SourceMap::new(),
        ),
        Ok(r) => (
            Status::Failed,
            r.failures,
            Vec::new(),
            Some(r.summary),
            SourceMap::new(),
        ),
        Err(s) => {
            let internal = s.diagnostics.iter().any(|d| d.code == codes::INTERNAL);
            let status = if internal { Status::Internal } else { Status::Invalid };
            (status, Vec::new(), s.diagnostics, None, s.sources)
        }
    };
    let messages = diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| npr_diag::diagnostic::render(std::slice::from_ref(d), &sources, false))
        .collect();
    Run {
        outcome: Outcome {
            id: sweep_id(style),
            style: style.to_path_buf(),
            name: SWEEP_NAME.into(),
            status,
            seconds: started.elapsed().as_secs_f64(),
            failures,
            messages,
            blessed: None,
            note,
        },
        diagnostics,
        sources,
    }
}

/// The name of a style's sweep: not a test name (`@` is not allowed in
/// one), so it never meets a declared test's id.
pub const SWEEP_NAME: &str = "@sweep";

pub fn sweep_id(style: &Path) -> String {
    format!("{}::{SWEEP_NAME}", style.display())
}

/// Compile `style` with `combination` as `npr render --set` does, render
/// `case`, and look at every target.
fn probe(
    style: &Path,
    case: &Case,
    scene: &Scene,
    base: &SourceMap,
    combination: &Combination,
    settings: &Settings,
) -> Probe {
    let mut sources = base.clone();
    let sets: Vec<String> = combination.iter().map(|(n, v)| format!("{n}={v}")).collect();
    let given = npr_compiler::set_values::settings(&sets, &mut sources);
    let compiled = match npr_compiler::compile_file(style, &mut sources, &options(style, case, scene, given)) {
        Ok(c) => c,
        Err(CompileError::User(d)) => return Probe::Error(headline(&d)),
        Err(CompileError::Internal(e)) => return Probe::Error(headline(&[e.to_diagnostic()])),
    };
    let program = compiled.program();
    let path_dependent = program.manifest.is_path_dependent();
    let frames = npr_runner::schedule::schedule(case.request, case.fps, path_dependent);
    let frames = Frames {
        size: case.size,
        eye: case.eye,
        frames: &frames,
    };
    let gpu = settings.gpu;
    observe(&program, gpu.watch.check(frames.render(gpu, &program, scene, true)))
}

/// One case compiled once with every parameter kept as a uniform, and
/// its renderer (made again per render for a style that reads earlier
/// frames, whose history must start empty).
struct Uniforms {
    compiled: Result<(npr_abi::StyleProgram, bool), String>,
    renderer: Option<npr_runner::Renderer>,
    case: Case,
}

impl Uniforms {
    fn new(style: &Path, case: &Case, scene: &Scene, base: &SourceMap) -> Uniforms {
        let mut sources = base.clone();
        let opts = CompileOptions {
            keep_params: true,
            ..options(style, case, scene, Vec::new())
        };
        let compiled = match npr_compiler::compile_file(style, &mut sources, &opts) {
            Ok(c) => {
                let program = c.program();
                let path_dependent = program.manifest.is_path_dependent();
                Ok((program, path_dependent))
            }
            Err(CompileError::User(d)) => Err(headline(&d)),
            Err(CompileError::Internal(e)) => Err(headline(&[e.to_diagnostic()])),
        };
        Uniforms {
            compiled,
            renderer: None,
            case: case.clone(),
        }
    }

    fn probe(
        &mut self,
        combination: &Combination,
        shapes: &[ParamShape],
        scene: &Scene,
        settings: &Settings<'_>,
    ) -> Probe {
        let (program, path_dependent) = match &self.compiled {
            Ok(c) => c,
            Err(e) => return Probe::Error(e.clone()),
        };
        let gpu = settings.gpu;
        if self.renderer.is_none() || *path_dependent {
            match gpu
                .watch
                .check(npr_runner::Renderer::new(&gpu.device, &gpu.queue, program, scene))
            {
                Ok(r) => self.renderer = Some(r),
                Err(e) => return Probe::Error(headline(&e.diagnostics())),
            }
        }
        let Some(r) = self.renderer.as_mut() else {
            return Probe::Error("no renderer".into());
        };
        let defaults = r.manifest().params.clone();
        for (name, text) in combination {
            let Some(shape) = shapes.iter().find(|s| &s.name == name) else {
                continue;
            };
            let literal = npr_abi::param_literal::read_literal(text);
            match type_value(shape, &literal, text, &SettingOrigin::CommandLine) {
                Ok(o) => {
                    if let Some(p) = r.params_mut().iter_mut().find(|p| &p.name == name) {
                        p.set_constant(&o);
                    }
                }
                Err(refusal) => {
                    *r.params_mut() = defaults;
                    return Probe::Error(format!("{}: {}", refusal.code, refusal.message));
                }
            }
        }
        let frames = npr_runner::schedule::schedule(self.case.request, self.case.fps, *path_dependent);
        let frames = Frames {
            size: self.case.size,
            eye: self.case.eye,
            frames: &frames,
        };
        let rendered = gpu.watch.check(frames.render_with(r, scene, true));
        *r.params_mut() = defaults;
        observe(program, rendered)
    }
}

/// What a render showed: its non-finite targets and whether it is blank.
fn observe(program: &npr_abi::StyleProgram, rendered: Result<frames::Rendered, npr_runner::RunError>) -> Probe {
    match rendered {
        Ok(rendered) => Probe::Rendered {
            non_finite: frames::non_finite_failures(program, &rendered.non_finite)
                .into_iter()
                .map(|f| f.message)
                .collect(),
            blank: rendered
                .outputs
                .last()
                .and_then(|(_, img)| checks::single_colour(&img.to_rgba8())),
        },
        Err(e) => Probe::Error(headline(&e.diagnostics())),
    }
}

/// The first error's code and message.
fn headline(diagnostics: &[Diagnostic]) -> String {
    diagnostics
        .iter()
        .find(|d| d.is_error())
        .or(diagnostics.first())
        .map_or("an error without a diagnostic".into(), |d| {
            format!("{}: {}", d.code, d.message)
        })
}

/// A value as one shell word.
fn shell_word(text: &str) -> String {
    let plain = !text.is_empty()
        && text.chars().all(|c| {
            c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.' | '/' | '=' | '#' | '%' | ':' | '+' | ',')
        });
    if plain {
        text.to_string()
    } else {
        format!("'{}'", text.replace('\'', r"'\''"))
    }
}

/// The `npr render` command line that shows `combination` on `case`.
/// With `kept`, the parameters are kept as uniforms (`--keep-params`), as
/// the sweep rendered them. The schedule is the naive one the sweep reads
/// every target under.
pub fn reproduction(style: &Path, case: &Case, combination: &Combination, kept: bool) -> String {
    let mut words = vec!["npr".to_string(), "render".into(), style.display().to_string()];
    words.extend(case.render_args());
    words.extend(["--schedule".into(), "naive".into()]);
    if kept {
        words.push("--keep-params".into());
    }
    for (name, value) in combination {
        words.push("--set".into());
        words.push(format!("{name}={value}"));
    }
    words.extend(["-o".into(), "sweep.png".into()]);
    words.iter().map(|w| shell_word(w)).collect::<Vec<_>>().join(" ")
}

/// A finding as a failure: what failed, where, and the cheapest case's command line.
fn report(style: &Path, cases: &[Case], f: &Finding, kept: bool) -> Failure {
    let cheapest = f
        .seen
        .iter()
        .map(|(ci, _, _)| *ci)
        .min_by_key(|&ci| (cases[ci].cost(), ci))
        .unwrap_or(0);
    let mut checks: Vec<&str> = f.seen.iter().map(|(_, c, _)| *c).collect();
    checks.dedup();
    let mut labels: Vec<&str> = f.seen.iter().map(|(ci, _, _)| cases[*ci].label.as_str()).collect();
    labels.dedup();
    let shown = f
        .seen
        .iter()
        .find(|(ci, _, _)| *ci == cheapest)
        .map_or("", |(_, _, m)| m.as_str());
    let set = if f.combination.is_empty() {
        "the defaults".to_string()
    } else {
        f.combination
            .iter()
            .map(|(n, v)| format!("{n}={v}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    Failure {
        check: "sweep",
        message: format!(
            "{set}: {} on {} of {} case(s) ({}); on {}: {shown}",
            checks.join(", "),
            labels.len(),
            cases.len(),
            labels.join(", "),
            cases[cheapest].label
        ),
        files: Vec::new(),
        reproduce: Some(reproduction(style, &cases[cheapest], &f.combination, kept)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use npr_runner::schedule::FrameRequest;

    #[test]
    fn a_reproduction_is_one_command_line_a_shell_reads_back() {
        let case = Case {
            label: "3x7".into(),
            scene: "out/hard scenes/small.toml".into(),
            size: (3, 7),
            request: FrameRequest::Range { start: 0, end: 3 },
            fps: 24.0,
            eye: 1,
            check_blank: false,
        };
        let line = reproduction(
            Path::new("toon.npr"),
            &case,
            &vec![("offset".into(), "1, 0.5".into()), ("base".into(), "#ffffff".into())],
            true,
        );
        assert_eq!(
            line,
            "npr render toon.npr --scene 'out/hard scenes/small.toml' --size 3x7 --frames 0..3 --eye 1 --schedule naive --keep-params --set 'offset=1, 0.5' --set base=#ffffff -o sweep.png"
        );
    }

    #[test]
    fn blank_counts_only_where_the_defaults_are_not_blank() {
        let drawn = Probe::Rendered {
            non_finite: Vec::new(),
            blank: None,
        };
        let flat = Probe::Rendered {
            non_finite: vec!["target `g.v` ...".into()],
            blank: Some([0, 0, 0, 255]),
        };
        let checks = |p: &Probe, b: &Probe| problems(p, b).into_iter().map(|(c, _)| c).collect::<Vec<_>>();
        assert_eq!(checks(&flat, &drawn), ["finite", "blank"]);
        assert_eq!(checks(&flat, &flat), ["finite"]);
        assert_eq!(checks(&Probe::Error("E0203: x".into()), &drawn), ["error"]);
    }
}
