//! `npr bench compile`: compile time, in two measurements.
//!
//! - In process: our front end and code generation against naga's parse +
//!   validate of the WGSL we emit, from the stage timings of the same
//!   compilations (median of `--iterations`).
//! - `--cold`: a whole `npr compile STYLE -o DIR --time-passes` process, as a
//!   user runs it (process start, file reads, writes of the outputs),
//!   spawned from this binary; the wall time's median over `--runs`, and
//!   naga's share of it taken from the child's own `validate` stage time.

use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// One row per style: front end + codegen against naga, in process.
pub fn in_process(styles: &[PathBuf], iterations: u32) -> Result<String, String> {
    let mut out = String::from(
        "| style | npr front end + codegen (ms) | naga parse+validate of output (ms) | ratio |\n|---|---:|---:|---:|\n",
    );
    for style in styles {
        let mut ours = Vec::new();
        let mut naga_time = Vec::new();
        for _ in 0..iterations.max(1) {
            let mut sources = SourceMap::new();
            let c =
                npr_compiler::compile_file(style, &mut sources, &CompileOptions::default()).map_err(|e| match e {
                    npr_compiler::CompileError::User(d) => npr_diag::diagnostic::render(&d, &sources, false),
                    npr_compiler::CompileError::Internal(e) => e.to_string(),
                })?;
            let total: f64 = c.timings.iter().map(|(_, d)| d.as_secs_f64()).sum();
            let validate = stage_seconds(&c.timings, "validate");
            ours.push(total - validate);
            naga_time.push(validate);
        }
        let (o, n) = (median(&mut ours), median(&mut naga_time));
        out.push_str(&format!(
            "| {} | {:.3} | {:.3} | {:.2}x |\n",
            style.display(),
            o * 1e3,
            n * 1e3,
            o / n.max(1e-12)
        ));
    }
    Ok(out)
}

fn stage_seconds(timings: &[(&'static str, std::time::Duration)], stage: &str) -> f64 {
    timings
        .iter()
        .filter(|(s, _)| *s == stage)
        .map(|(_, d)| d.as_secs_f64())
        .sum()
}

/// The `validate` line of `npr compile --time-passes` output, in ms.
fn validate_ms(stdout: &str) -> Option<f64> {
    stdout.lines().find_map(|l| {
        let rest = l.strip_prefix("validate")?;
        rest.trim().strip_suffix("ms")?.trim().parse().ok()
    })
}

/// One row per style: whole `npr compile` processes, wall time.
pub fn cold(styles: &[PathBuf], runs: u32) -> Result<String, String> {
    let exe = std::env::current_exe().map_err(|e| format!("cannot find the npr binary: {e}"))?;
    let scratch = std::env::temp_dir().join(format!("npr-bench-compile-{}", std::process::id()));
    let mut out = String::from(
        "| style | `npr compile` wall, median (ms) | min (ms) | naga validate in it (ms) | naga share |\n|---|---:|---:|---:|---:|\n",
    );
    for style in styles {
        let mut walls = Vec::new();
        let mut nagas = Vec::new();
        for run in 0..runs.max(1) {
            let dir = scratch.join(format!("run{run}"));
            let (wall, stdout) = spawn_compile(&exe, style, &dir)?;
            walls.push(wall);
            nagas.push(validate_ms(&stdout).ok_or_else(|| format!("no `validate` time in:\n{stdout}"))? / 1e3);
        }
        let min = walls.iter().copied().fold(f64::INFINITY, f64::min);
        let (w, n) = (median(&mut walls), median(&mut nagas));
        out.push_str(&format!(
            "| {} | {:.2} | {:.2} | {:.2} | {:.0}% |\n",
            style.display(),
            w * 1e3,
            min * 1e3,
            n * 1e3,
            100.0 * n / w.max(1e-12)
        ));
    }
    let _ = std::fs::remove_dir_all(&scratch);
    Ok(out)
}

fn spawn_compile(exe: &Path, style: &Path, dir: &Path) -> Result<(f64, String), String> {
    let start = Instant::now();
    let output = Command::new(exe)
        .arg("compile")
        .arg(style)
        .arg("-o")
        .arg(dir)
        .arg("--time-passes")
        .output()
        .map_err(|e| format!("cannot run {}: {e}", exe.display()))?;
    let wall = start.elapsed().as_secs_f64();
    if !output.status.success() {
        return Err(format!(
            "`npr compile {}` failed:\n{}",
            style.display(),
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    Ok((wall, String::from_utf8_lossy(&output.stdout).into_owned()))
}

#[cfg(test)]
mod tests {
    #[test]
    fn reads_the_validate_stage_of_time_passes() {
        let out = "parse                        0.100 ms\nvalidate                     1.250 ms\ntotal    2.000 ms\n";
        assert_eq!(super::validate_ms(out), Some(1.25));
        assert_eq!(super::validate_ms("total 1 ms"), None);
    }
}
