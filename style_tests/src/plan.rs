//! A run of style tests as a list of jobs: the test files found under the
//! paths given (every one read before anything renders, so all their
//! mistakes are reported together), a sweep per style when asked, and the
//! jobs `filter` and `shard` select. [`Plan::run`] runs the selected jobs
//! and hands each result to an observer, which is where a front end
//! prints; the plan itself prints nothing.

use crate::declare::{self, TestDecl, TestFile};
use crate::outcome::{Outcome, Run, Settings};
use crate::select::{self, Shard};
use crate::sweep::cases::{self, Case};
use crate::{run, sweep};
use npr_diag::{codes, Diagnostic, SourceMap};
use std::path::{Path, PathBuf};

/// What a run is asked for.
pub struct PlanOptions<'a> {
    /// Styles, test files or directories to search.
    pub paths: &'a [PathBuf],
    /// Add a sweep per style (its tests' scenes and the hard scenes).
    pub sweep: bool,
    /// Keep only the jobs whose id contains this.
    pub filter: Option<&'a str>,
    /// Keep only this shard of the jobs, sorted by id.
    pub shard: Option<Shard>,
    /// Where a run writes (the hard scenes go in `hard_scenes/` inside).
    pub out_dir: &'a Path,
}

/// Why no plan was made: one diagnostic (a bad path, a filter matching
/// nothing), or the test files' own mistakes, each with its sources.
pub enum PlanError {
    Argument(Diagnostic),
    TestFiles(Vec<(Vec<Diagnostic>, SourceMap)>),
}

/// One line of the run: a declared test, or a style's sweep over its cases.
pub enum Job<'a> {
    Test(&'a TestFile, &'a TestDecl),
    Sweep(&'a Path, &'a [Case]),
}

/// The jobs of a run and which of them are selected.
pub struct Plan {
    files: Vec<TestFile>,
    sweeps: Vec<(PathBuf, Vec<Case>)>,
    /// Each job's id (`style.npr::name`, `style.npr::@sweep`): the tests
    /// of every file in order, then the sweeps.
    ids: Vec<String>,
    selected: Vec<usize>,
    /// Styles found without a test file.
    pub untested: Vec<PathBuf>,
    hard_dir: PathBuf,
}

impl Plan {
    /// Finds and reads the test files and lists the jobs.
    pub fn new(options: &PlanOptions) -> Result<Plan, PlanError> {
        let found = select::find(options.paths).map_err(PlanError::Argument)?;
        let mut files = Vec::new();
        let mut bad = Vec::new();
        for path in &found.test_files {
            match declare::read(path) {
                Ok(f) => files.push(f),
                Err(e) => bad.push(e),
            }
        }
        if !bad.is_empty() {
            return Err(PlanError::TestFiles(bad));
        }
        let hard_dir = options.out_dir.join("hard_scenes");
        let mut sweeps = Vec::new();
        if options.sweep {
            let mut styles: Vec<&Path> = files.iter().map(|f| f.style.as_path()).collect();
            styles.extend(found.named_untested.iter().map(PathBuf::as_path));
            for style in styles {
                sweeps.push((style.to_path_buf(), sweep_cases(&files, style, &hard_dir)));
            }
        }
        let ids: Vec<String> = files
            .iter()
            .flat_map(|f| f.tests.iter().map(move |t| run::id(f, t)))
            .chain(sweeps.iter().map(|(style, _)| sweep::sweep_id(style)))
            .collect();
        if let Some(filter) = options.filter {
            if !ids.iter().any(|id| id.contains(filter)) {
                return Err(PlanError::Argument(
                    Diagnostic::error(
                        codes::BAD_ARGUMENT_VALUE,
                        format!("--filter {filter}: no test's id contains it"),
                    )
                    .with_help(format!(
                        "the ids are `style.npr::name` (and `style.npr::@sweep` with --sweep); there are {} test(s)",
                        ids.len()
                    )),
                ));
            }
        }
        let selected = select::select(&ids, options.filter, options.shard);
        Ok(Plan {
            files,
            sweeps,
            ids,
            selected,
            untested: found.untested,
            hard_dir,
        })
    }

    /// Every job, selected or not, in id order of listing.
    fn job(&self, index: usize) -> Job<'_> {
        let mut i = index;
        for f in &self.files {
            if i < f.tests.len() {
                return Job::Test(f, &f.tests[i]);
            }
            i -= f.tests.len();
        }
        let (style, cases) = &self.sweeps[i];
        Job::Sweep(style, cases)
    }

    /// The selected jobs with their ids, in run order.
    pub fn selected(&self) -> impl Iterator<Item = (&str, Job<'_>)> {
        self.selected.iter().map(|&i| (self.ids[i].as_str(), self.job(i)))
    }

    /// How many jobs the filter and shard left out.
    pub fn not_selected(&self) -> usize {
        self.ids.len() - self.selected.len()
    }

    /// Whether anything is selected.
    pub fn is_empty(&self) -> bool {
        self.selected.is_empty()
    }

    /// Writes the hard scenes a selected sweep renders (before the run).
    pub fn write_hard_scenes(&self) -> Result<(), (PathBuf, std::io::Error)> {
        if self.selected().any(|(_, j)| matches!(j, Job::Sweep(..))) {
            cases::write_hard_scenes(&self.hard_dir).map_err(|e| (self.hard_dir.clone(), e))?;
        }
        Ok(())
    }

    /// Runs the selected jobs in order. `starting` gets each job's id
    /// before it runs, `finished` its result; the outcomes are returned.
    pub fn run(
        &self,
        settings: &Settings,
        mut starting: impl FnMut(&str),
        mut finished: impl FnMut(&Run),
    ) -> Vec<Outcome> {
        let mut outcomes = Vec::with_capacity(self.selected.len());
        for (id, job) in self.selected() {
            starting(id);
            let result = match job {
                Job::Test(file, test) => run::run(file, test, settings),
                Job::Sweep(style, cases) => sweep::run_sweep(style, cases, settings),
            };
            finished(&result);
            outcomes.push(result.outcome);
        }
        outcomes
    }
}

/// A style's sweep cases: each distinct (scene, size, frame, eye) of its
/// tests, made small, then the hard scenes.
fn sweep_cases(files: &[TestFile], style: &Path, hard_dir: &Path) -> Vec<Case> {
    let mut cases: Vec<Case> = Vec::new();
    for test in files.iter().filter(|f| f.style == style).flat_map(|f| &f.tests) {
        let case = Case::of_test_small(test);
        if !cases
            .iter()
            .any(|c| (&c.scene, c.size, c.request, c.eye) == (&case.scene, case.size, case.request, case.eye))
        {
            cases.push(case);
        }
    }
    cases.extend(cases::hard_cases(hard_dir));
    cases
}
