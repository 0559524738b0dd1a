//! Running one declared test: its scene loaded, its style compiled for the
//! scene with its `set` values (typed exactly as `npr render --set`), its
//! frames rendered as `npr render` renders them, and then the checks of
//! `checks.rs` on what came back. Bad input (a parameter that does not
//! exist, a golden of another size) stops the test with diagnostics;
//! a check that does not hold is a [`Failure`].

use super::checks;
use super::declare::{Golden, TestDecl, TestFile, When};
use super::frames::{non_finite_failures, Frames};
use super::outcome::{Failure, Outcome, Run, Settings, Status};
use npr_compiler::ir::{ParamSetting, SettingOrigin};
use npr_compiler::{CompileError, CompileOptions, Compiled};
use npr_diag::paths::PathChoice;
use npr_diag::{codes, Diagnostic, SourceMap, Span};
use npr_runner::scene::toml_fields::At;
use npr_runner::schedule::FrameRequest;
use npr_runner::{FrameSpec, RunError, TargetImage};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Why a test stopped before its checks: bad input, or an internal error.
enum Stop {
    Invalid(Vec<Diagnostic>),
    Internal(Vec<Diagnostic>),
}

impl From<RunError> for Stop {
    fn from(e: RunError) -> Stop {
        if e.is_user_error() {
            Stop::Invalid(e.diagnostics())
        } else {
            Stop::Internal(e.diagnostics())
        }
    }
}

/// What the checks found, and the warnings met on the way.
struct Checked {
    failures: Vec<Failure>,
    warnings: Vec<Diagnostic>,
    blessed: Option<PathBuf>,
    note: Option<String>,
}

pub fn id(file: &TestFile, test: &TestDecl) -> String {
    format!("{}::{}", file.style.display(), test.name.value)
}

/// Run `test` of `file`.
pub fn run(file: &TestFile, test: &TestDecl, settings: &Settings) -> Run {
    let started = Instant::now();
    let mut sources = file.sources.clone();
    let result = execute(file, test, settings, &mut sources);
    let (status, failures, diagnostics, blessed, note) = match result {
        Ok(c) if c.failures.is_empty() => (Status::Passed, Vec::new(), c.warnings, c.blessed, c.note),
        Ok(c) => (Status::Failed, c.failures, c.warnings, c.blessed, c.note),
        Err(Stop::Invalid(d)) => (Status::Invalid, Vec::new(), d, None, None),
        Err(Stop::Internal(d)) => (Status::Internal, Vec::new(), d, None, None),
    };
    let messages = diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| npr_diag::diagnostic::render(std::slice::from_ref(d), &sources, false))
        .collect();
    Run {
        outcome: Outcome {
            id: id(file, test),
            style: file.style.clone(),
            name: test.name.value.clone(),
            status,
            seconds: started.elapsed().as_secs_f64(),
            failures,
            messages,
            blessed,
            note,
        },
        diagnostics,
        sources,
    }
}

fn execute(file: &TestFile, test: &TestDecl, settings: &Settings, sources: &mut SourceMap) -> Result<Checked, Stop> {
    let gpu = settings.gpu;
    let scene_path = &test.scene.value;
    let policy = PathChoice::default()
        .policy(&file.style, Some(scene_path))
        .map_err(|d| Stop::Invalid(vec![d]))?;
    let scene = npr_runner::scene::load_scene_in(scene_path, sources, Some(&policy)).map_err(Stop::Invalid)?;
    if test.eye.value == 1 && !scene.camera.is_stereo() {
        return Err(Stop::Invalid(vec![Diagnostic::error(
            codes::BAD_TEST_FILE,
            format!(
                "test `{}` renders eye 1, but its scene's camera is mono",
                test.name.value
            ),
        )
        .with_primary(test.eye.span, "eye 1 of a mono camera")
        .with_help("give the scene's [camera] an `ipd` to make it stereo, or test eye 0")]));
    }
    if let (Some(bound), true) = (&test.flicker, scene.camera.keys().len() > 1) {
        return Err(Stop::Invalid(vec![Diagnostic::error(
            codes::BAD_TEST_FILE,
            format!(
                "test `{}` bounds flicker, but its scene's camera moves",
                test.name.value
            ),
        )
        .with_primary(bound.span, "measured with a still camera")
        .with_help(
            "flicker is the change a still view should not have: test it on a scene without `[[camera.keys]]`",
        )]));
    }
    let opts = CompileOptions {
        scene: Some(scene.summary(&scene_path.display().to_string())),
        paths: Some(policy),
        ..Default::default()
    };
    let opts = CompileOptions {
        settings: param_settings(&test.sets, sources),
        ..opts
    };
    let compiled = compile(&file.style, sources, &opts)?;
    let texture_errors = crate::texture_files::texture_file_errors(&compiled, npr_runner::texture_file::Depth::Header);
    if !texture_errors.is_empty() {
        return Err(Stop::Invalid(texture_errors));
    }
    let program = compiled.program();
    let mut warnings = compiled.warnings.clone();
    warnings.extend(npr_runner::scene_warnings(&program.manifest, &scene));
    let request = match test.when {
        When::At { time_s } => FrameRequest::At { time_s },
        When::Range { start, end } => FrameRequest::Range { start, end },
    };
    let path_dependent = program.manifest.is_path_dependent();
    let count = npr_runner::schedule::frame_count(request, test.fps, path_dependent);
    npr_diag::sizes::check_frame_count(count as usize)
        .map_err(|d| Stop::Invalid(vec![d.with_primary(test.name.span, "this test")]))?;
    let frames = npr_runner::schedule::schedule(request, test.fps, path_dependent);
    let frame = Frames {
        size: test.size,
        eye: test.eye.value,
        frames: &frames,
    };

    let checked = (|| -> Result<Checked, RunError> {
        let first_run = frame.render(gpu, &program, &scene, true)?;
        let mut failures = non_finite_failures(&program, &first_run.non_finite);
        // A fused target is not stored under the auto schedule: the naive
        // one stores every declared target, so each is read back there.
        if compiled
            .report
            .entries
            .iter()
            .any(|e| matches!(e.action, "fused" | "recomputed"))
        {
            let naive = CompileOptions {
                schedule: npr_compiler::schedule::Schedule::Naive,
                ..opts.clone()
            };
            let naive = npr_compiler::compile_file(&file.style, sources, &naive)
                .map_err(|e| RunError::Internal(format!("the style compiled under auto but not naive: {e:?}")))?
                .program();
            let stored: Vec<&str> = program.manifest.targets.iter().map(|t| t.name.as_str()).collect();
            let mut found = frame.render(gpu, &naive, &scene, true)?.non_finite;
            found.retain(|f| !stored.contains(&naive.manifest.targets[f.target].name.as_str()));
            failures.extend(non_finite_failures(&naive, &found));
        }
        let second_run = frame.render(gpu, &program, &scene, false)?;
        failures.extend(determinism_failures(&first_run.outputs, &second_run.outputs));
        if !test.may_be_blank {
            failures.extend(blank_failures(&first_run.outputs));
        }
        if let Some(bound) = &test.flicker {
            failures.extend(flicker_failures(&first_run.outputs, bound.value));
        }
        let mut notes = Vec::new();
        if let Some(bound) = &test.coherence {
            let measured = super::motion::measure(gpu, &scene, &frame, &first_run.outputs, &opts, bound.value.marks)?;
            let (found, said) = super::motion::failures(&measured, &bound.value);
            failures.extend(found);
            notes.push(said);
        }
        let last = first_run.outputs.last().map(|(_, img)| img.to_rgba8());
        let (golden_failures, blessed) = match (&test.golden, last) {
            (Some(golden), Some(actual)) => golden_check(file, test, golden, &actual, failures.is_empty(), settings)?,
            _ => (Vec::new(), None),
        };
        failures.extend(golden_failures);
        if let (Some(bound), Some(last)) = (&test.budget, frames.iter().rev().find(|f| f.write)) {
            let spec = FrameSpec {
                width: test.size.0,
                height: test.size.1,
                time_s: last.time_s,
                frame: last.frame,
                eye: test.eye.value,
            };
            let cost = super::budget::measure(gpu, &program, &scene, &spec)?;
            let said = format!(
                "the frame costs {:.2}× a passthrough ({:.3} ms against {:.3} ms, fastest of {})",
                cost.ratio(),
                cost.style_ms,
                cost.passthrough_ms,
                super::budget::FRAMES
            );
            if cost.ratio() > bound.value {
                failures.push(Failure {
                    check: "budget",
                    message: format!("{said}; the budget is {}×", bound.value),
                    files: Vec::new(),
                    reproduce: None,
                });
            }
            notes.push(said);
        }
        Ok(Checked {
            failures,
            warnings,
            blessed,
            note: (!notes.is_empty()).then(|| notes.join("; ")),
        })
    })();
    let mut checked = gpu
        .watch
        .check(checked)
        .map_err(|e| e.at_texture_spans(&compiled.texture_spans))?;
    if test.sweep {
        let case = super::sweep::cases::Case::of_test(test);
        match super::sweep::sweep(&file.style, std::slice::from_ref(&case), settings) {
            Ok(r) => {
                checked.failures.extend(r.failures);
                checked.note = Some(r.summary);
            }
            // Its spans point into the sweep's own sources: the messages alone.
            Err(s) => {
                return Err(Stop::Invalid(
                    s.diagnostics
                        .iter()
                        .map(|d| Diagnostic::error(d.code, d.message.clone()))
                        .collect(),
                ))
            }
        }
    }
    Ok(checked)
}

fn compile(style: &Path, sources: &mut SourceMap, opts: &CompileOptions) -> Result<Compiled, Stop> {
    npr_compiler::compile_file(style, sources, opts).map_err(|e| match e {
        CompileError::User(d) => Stop::Invalid(d),
        CompileError::Internal(e) => Stop::Internal(vec![e.to_diagnostic()]),
    })
}

/// The test's `set` values as settings the compiler types as it types
/// `npr render --set` (`npr_compiler::front::param_settings`), each error
/// pointing at the value in the test file.
pub fn param_settings(sets: &[(At<String>, At<String>)], sources: &SourceMap) -> Vec<ParamSetting> {
    sets.iter()
        .map(|(name, value)| {
            // A TOML string's span holds its quotes; messages quote the text inside.
            let mut value_span = value.span;
            let raw = sources.snippet(value_span);
            if raw.len() >= 2 && raw.starts_with('"') && raw.ends_with('"') {
                value_span = Span::new(
                    value_span.file,
                    value_span.start as usize + 1,
                    value_span.end as usize - 1,
                );
            }
            ParamSetting {
                name: name.value.clone(),
                name_span: name.span,
                value: npr_abi::param_literal::read_literal(value.value.trim()),
                value_span,
                origin: SettingOrigin::TestFile,
            }
        })
        .collect()
}

fn determinism_failures(first: &[(u32, TargetImage)], second: &[(u32, TargetImage)]) -> Vec<Failure> {
    first
        .iter()
        .zip(second)
        .filter_map(|((frame, a), (_, b))| {
            let at = checks::first_difference(&a.bytes, &b.bytes)?;
            let texel = at / a.format.bytes_per_pixel().max(1) as usize;
            let (x, y) = (texel % a.width.max(1) as usize, texel / a.width.max(1) as usize);
            Some(Failure {
                check: "deterministic",
                message: format!("frame {frame}: a second render differs from the first, first at pixel ({x}, {y})"),
                files: Vec::new(),
                reproduce: None,
            })
        })
        .take(1)
        .collect()
}

pub(super) fn blank_failures(outputs: &[(u32, TargetImage)]) -> Vec<Failure> {
    outputs
        .iter()
        .filter_map(|(frame, img)| {
            let [r, g, b, a] = checks::single_colour(&img.to_rgba8())?;
            Some(Failure {
                check: "blank",
                message: format!(
                    "frame {frame}: the output is one colour, #{r:02x}{g:02x}{b:02x}{a:02x}; say `may_be_blank = true` if it may be"
                ),
                files: Vec::new(),
                reproduce: None,
            })
        })
        .take(1)
        .collect()
}

/// The largest change between consecutive frames, if over `bound`.
fn flicker_failures(outputs: &[(u32, TargetImage)], bound: f64) -> Vec<Failure> {
    let images: Vec<(u32, image::RgbaImage)> = outputs.iter().map(|(f, img)| (*f, img.to_rgba8())).collect();
    let worst = images
        .windows(2)
        .map(|pair| (pair[1].0, checks::frame_change(&pair[0].1, &pair[1].1)))
        .max_by(|a, b| a.1.total_cmp(&b.1));
    match worst {
        Some((frame, change)) if change > bound => vec![Failure {
            check: "flicker",
            message: format!(
                "frame {frame} changes from the one before by a mean of {change:.5} per channel (allowed {bound})"
            ),
            files: Vec::new(),
            reproduce: None,
        }],
        _ => Vec::new(),
    }
}

/// Compare with the golden, or write it with `--bless` when every other
/// check held (a golden is never an image that failed them).
fn golden_check(
    file: &TestFile,
    test: &TestDecl,
    golden: &Golden,
    actual: &image::RgbaImage,
    others_passed: bool,
    settings: &Settings,
) -> Result<(Vec<Failure>, Option<PathBuf>), RunError> {
    let path = &golden.path.value;
    let bad_golden = |message: String, label: &str| {
        RunError::User(vec![Diagnostic::error(codes::BAD_GOLDEN, message)
            .with_primary(golden.path.span, label.to_string())
            .with_help(
                "`npr test --bless` writes the golden from the current render; look at it before committing it",
            )])
    };
    if settings.bless {
        if !others_passed {
            return Ok((Vec::new(), None));
        }
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(|e| RunError::User(vec![npr_diag::writes::cannot_write(dir, e)]))?;
        }
        npr_runner::output::write_png8(actual, path)
            .map_err(|e| RunError::User(vec![npr_diag::writes::cannot_write(path, e)]))?;
        return Ok((Vec::new(), Some(path.clone())));
    }
    if !path.exists() {
        return Err(bad_golden(
            format!("golden {} does not exist", path.display()),
            "no such file",
        ));
    }
    let expected = match image::open(path) {
        Ok(img) => img.to_rgba8(),
        Err(e) => {
            return Err(bad_golden(
                format!("golden {} is not an image npr reads: {e}", path.display()),
                "not a PNG",
            ))
        }
    };
    if expected.dimensions() != actual.dimensions() {
        let (w, h) = expected.dimensions();
        return Err(bad_golden(
            format!(
                "golden {} is {w}x{h}, but test `{}` renders {}x{}",
                path.display(),
                test.name.value,
                actual.width(),
                actual.height()
            ),
            "another size",
        ));
    }
    let verdict = checks::compare(actual, &expected, golden);
    if verdict.passed {
        return Ok((Vec::new(), None));
    }
    let stem = file
        .style
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let dir = settings.out_dir.join(stem);
    let name = &test.name.value;
    let mut images = vec![
        (dir.join(format!("{name}.actual.png")), actual.clone()),
        (dir.join(format!("{name}.diff.png")), verdict.diff),
    ];
    if let Some(flip) = verdict.flip_picture {
        images.push((dir.join(format!("{name}.flip.png")), flip));
    }
    std::fs::create_dir_all(&dir).map_err(|e| RunError::User(vec![npr_diag::writes::cannot_write(&dir, e)]))?;
    for (p, img) in &images {
        npr_runner::output::write_png8(img, p)
            .map_err(|e| RunError::User(vec![npr_diag::writes::cannot_write(p, e)]))?;
    }
    Ok((
        vec![Failure {
            check: "golden",
            message: format!("differs from {}: {}", path.display(), verdict.lines.join("; ")),
            files: images.into_iter().map(|(p, _)| p).collect(),
            reproduce: None,
        }],
        None,
    ))
}
