//! What running a style test reports: its status, the checks that did not
//! hold, and the settings every test of a run shares. Shared by a declared
//! test (`run.rs`) and a sweep (`sweep/`), which import it and not each
//! other.

use npr_diag::{Diagnostic, SourceMap};
use npr_runner::Gpu;
use std::path::{Path, PathBuf};

/// How a test ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    Passed,
    /// A check did not hold.
    Failed,
    /// Its input is wrong (diagnostics with codes): exit 1 like a failure.
    Invalid,
    /// npr or the device failed: exit 2.
    Internal,
}

/// A check that did not hold.
#[derive(Debug, Clone)]
pub struct Failure {
    /// `golden`, `finite`, `blank` or `deterministic`.
    pub check: &'static str,
    pub message: String,
    /// The images written to look at it (actual, diff, FLIP map).
    pub files: Vec<PathBuf>,
    /// A sweep's finding: the one `npr render` command line that shows it.
    pub reproduce: Option<String>,
}

/// What one test did.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// `<style>::<name>`: what `--filter` matches and `--shard` sorts.
    pub id: String,
    pub style: PathBuf,
    pub name: String,
    pub status: Status,
    pub seconds: f64,
    pub failures: Vec<Failure>,
    /// Its diagnostics as plain text, for the JSON and JUnit reports.
    pub messages: Vec<String>,
    /// The golden written by `--bless`.
    pub blessed: Option<PathBuf>,
    /// What a sweep covered, for its line.
    pub note: Option<String>,
}

/// What every test of a run shares.
pub struct Settings<'a> {
    pub gpu: &'a Gpu,
    /// Where a failing test's images go (`<out>/<style>/<test>.*.png`).
    pub out_dir: &'a Path,
    pub bless: bool,
}

/// An outcome, and the diagnostics to print with the sources they point into.
pub struct Run {
    pub outcome: Outcome,
    pub diagnostics: Vec<Diagnostic>,
    pub sources: SourceMap,
}
