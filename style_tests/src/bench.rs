//! `npr test --bench`: for each test that declares `variants`, each
//! variant's frame cost (a ratio to a passthrough, `budget.rs`) against its
//! FLIP difference from the test's reference variant, as a table in the
//! style of docs/PERFORMANCE.md's operator tables and, with `--plot`, as
//! a speed-against-error SVG (`bench::plot`). A benchmark: it reports,
//! and fails only on bad input or an internal error.

use super::declare::{TestDecl, TestFile, When};
use super::frames::Frames;
use super::run;
use npr_compiler::{CompileError, CompileOptions};
use npr_diag::paths::PathChoice;
use npr_diag::{Diagnostic, SourceMap};
use npr_lab::plot::{Chart, ChartKind, Figure, Point};
use npr_runner::schedule::FrameRequest;
use npr_runner::{FrameSpec, Gpu};
use std::fmt::Write;

/// One variant of one test, measured.
#[derive(Debug, Clone)]
pub struct Row {
    /// `style.npr::test`.
    pub id: String,
    pub variant: String,
    pub reference: bool,
    pub cost: super::budget::FrameCost,
    pub flip_mean: f64,
    pub flip_p99: f64,
}

/// Why a test could not be measured, with the sources its diagnostics point into.
pub struct Stopped {
    pub diagnostics: Vec<Diagnostic>,
    pub sources: SourceMap,
    pub internal: bool,
}

/// Measure every variant of `test` (which has some).
pub fn measure(file: &TestFile, test: &TestDecl, gpu: &Gpu) -> Result<Vec<Row>, Stopped> {
    let mut sources = file.sources.clone();
    let stop = |diagnostics: Vec<Diagnostic>, sources: &SourceMap, internal: bool| Stopped {
        diagnostics,
        sources: sources.clone(),
        internal,
    };
    let policy = PathChoice::default()
        .policy(&file.style, Some(&test.scene.value))
        .map_err(|d| stop(vec![d], &sources, false))?;
    let scene = npr_runner::scene::load_scene_in(&test.scene.value, &mut sources, Some(&policy))
        .map_err(|d| stop(d, &sources, false))?;
    let request = match test.when {
        When::At { time_s } => FrameRequest::At { time_s },
        When::Range { start, end } => FrameRequest::Range { start, end },
    };
    let mut measured: Vec<(String, super::budget::FrameCost, image::RgbaImage)> = Vec::new();
    for variant in &test.variants {
        let mut sets = test.sets.clone();
        for (n, v) in &variant.sets {
            sets.retain(|(m, _)| m.value != n.value);
            sets.push((n.clone(), v.clone()));
        }
        let opts = CompileOptions {
            scene: Some(scene.summary(&test.scene.value.display().to_string())),
            paths: Some(policy.clone()),
            settings: run::param_settings(&sets, &sources),
            ..Default::default()
        };
        let program = match npr_compiler::compile_file(&file.style, &mut sources, &opts) {
            Ok(c) => c.program(),
            Err(CompileError::User(d)) => return Err(stop(d, &sources, false)),
            Err(CompileError::Internal(e)) => return Err(stop(vec![e.to_diagnostic()], &sources, true)),
        };
        let frames = npr_runner::schedule::schedule(request, test.fps, program.manifest.is_path_dependent());
        let render = || -> Result<_, npr_runner::RunError> {
            let rendered = Frames {
                size: test.size,
                eye: test.eye.value,
                frames: &frames,
            }
            .render(gpu, &program, &scene, false)?;
            let last = frames.iter().rev().find(|f| f.write).copied();
            let output = rendered.outputs.last().map(|(_, img)| img.to_rgba8());
            let (Some(last), Some(output)) = (last, output) else {
                return Err(npr_runner::RunError::Internal("the test wrote no frame".into()));
            };
            let spec = FrameSpec {
                width: test.size.0,
                height: test.size.1,
                time_s: last.time_s,
                frame: last.frame,
                eye: test.eye.value,
            };
            Ok((super::budget::measure(gpu, &program, &scene, &spec)?, output))
        };
        let (cost, output) = gpu.watch.check(render()).map_err(|e| {
            let internal = !e.is_user_error();
            stop(e.diagnostics(), &sources, internal)
        })?;
        measured.push((variant.name.value.clone(), cost, output));
    }
    let reference = measured[test.reference].2.clone();
    let id = run::id(file, test);
    Ok(measured
        .into_iter()
        .enumerate()
        .map(|(i, (variant, cost, output))| {
            let (errors, _) = npr_lab::harness::flip_error_map(&output, &reference);
            let flip_mean = errors.iter().map(|e| f64::from(*e)).sum::<f64>() / errors.len().max(1) as f64;
            Row {
                id: id.clone(),
                variant,
                reference: i == test.reference,
                cost,
                flip_mean,
                flip_p99: f64::from(npr_lab::harness::percentile(&errors, 99.0)),
            }
        })
        .collect())
}

/// The rows as a Markdown table, one block per test.
pub fn table(rows: &[Row]) -> String {
    let mut s = String::new();
    let mut ids: Vec<&str> = rows.iter().map(|r| r.id.as_str()).collect();
    ids.dedup();
    for id in ids {
        let _ = writeln!(s, "{id}\n");
        let _ = writeln!(
            s,
            "| variant | frame vs passthrough (×) | frame ms | passthrough ms | FLIP mean | FLIP p99 |"
        );
        let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|");
        for r in rows.iter().filter(|r| r.id == id) {
            let name = if r.reference {
                format!("{} (reference)", r.variant)
            } else {
                r.variant.clone()
            };
            let _ = writeln!(
                s,
                "| {name} | {:.2} | {:.3} | {:.3} | {:.4} | {:.4} |",
                r.cost.ratio(),
                r.cost.style_ms,
                r.cost.passthrough_ms,
                r.flip_mean,
                r.flip_p99
            );
        }
        s.push('\n');
    }
    s
}

/// One speed-against-error chart per test: FLIP mean against the cost ratio.
pub fn figure(rows: &[Row], subtitle: &str) -> Figure {
    let mut fig = Figure::new("npr test --bench: variants, cost against FLIP", subtitle);
    let mut ids: Vec<&str> = rows.iter().map(|r| r.id.as_str()).collect();
    ids.dedup();
    for id in ids {
        let mut chart = Chart::new(
            ChartKind::SpeedError,
            id,
            "FLIP mean against the reference variant",
            "frame vs passthrough (×)",
        );
        for r in rows.iter().filter(|r| r.id == id) {
            let key = Some(fig.key(&format!("{id}: {}", r.variant)));
            chart
                .series("variants")
                .points
                .push(Point::new(r.flip_mean, r.cost.ratio(), key));
        }
        fig.charts.push(chart);
    }
    fig.notes.push(format!(
        "each cost: the fastest of {} frames, alternating with a passthrough, wall clock",
        super::budget::FRAMES
    ));
    fig
}
