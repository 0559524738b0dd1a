//! `npr test PATH...`: find the test files, read them all (any mistake in
//! one is reported with the others and stops the run before rendering),
//! add a sweep per style with `--sweep`, select by `--filter` and
//! `--shard`, run each test with a progress bar, and report. Exit 0 when every test passes, 1 when one fails or has bad
//! input, 2 when npr itself failed.

use crate::cli::TestArgs;
use crate::printer::headless_gpu;
use npr_diag::exit::{EXIT_INTERNAL, EXIT_OK, EXIT_USER};
use npr_diag::printer::Printer;
use npr_diag::writes::cannot_write;
use npr_diag::{codes, Diagnostic};
use npr_test::bench;
use npr_test::declare::{self, TestDecl, TestFile};
use npr_test::outcome::{Settings, Status};
use npr_test::report::{self, ReportFormat, RunReport};
use npr_test::run;
use npr_test::select;
use npr_test::sweep;
use npr_test::sweep::cases::{self, Case};
use std::time::Instant;

/// One line of the run: a declared test, or a style's sweep over its cases.
enum Job<'a> {
    Test(&'a TestFile, &'a TestDecl),
    Sweep(&'a std::path::Path, Vec<Case>),
}

pub fn run(args: TestArgs, printer: &Printer) -> i32 {
    let started = Instant::now();
    let shard = match args.shard.as_deref().map(select::parse_shard).transpose() {
        Ok(s) => s,
        Err(d) => return printer.fail(d),
    };
    let found = match select::find(&args.paths) {
        Ok(f) => f,
        Err(d) => return printer.fail(d),
    };
    let mut files: Vec<TestFile> = Vec::new();
    let mut bad_input = false;
    for path in &found.test_files {
        match declare::read(path) {
            Ok(f) => files.push(f),
            Err((diags, sources)) => {
                printer.diagnostics(&diags, &sources);
                bad_input = true;
            }
        }
    }
    if bad_input {
        return EXIT_USER;
    }
    let mut jobs: Vec<Job> = files
        .iter()
        .flat_map(|f| f.tests.iter().map(move |t| Job::Test(f, t)))
        .collect();
    let hard_dir = args.out.join("hard_scenes");
    if args.sweep {
        let mut styles: Vec<&std::path::Path> = files.iter().map(|f| f.style.as_path()).collect();
        styles.extend(found.named_untested.iter().map(|p| p.as_path()));
        for style in styles {
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
            cases.extend(cases::hard_cases(&hard_dir));
            jobs.push(Job::Sweep(style, cases));
        }
    }
    let ids: Vec<String> = jobs
        .iter()
        .map(|j| match j {
            Job::Test(f, t) => run::id(f, t),
            Job::Sweep(style, _) => sweep::sweep_id(style),
        })
        .collect();
    if let Some(filter) = &args.filter {
        if !ids.iter().any(|id| id.contains(filter.as_str())) {
            return printer.fail(
                Diagnostic::error(
                    codes::BAD_ARGUMENT_VALUE,
                    format!("--filter {filter}: no test's id contains it"),
                )
                .with_help(format!(
                    "the ids are `style.npr::name` (and `style.npr::@sweep` with --sweep); there are {} test(s)",
                    ids.len()
                )),
            );
        }
    }
    let selected = select::select(&ids, args.filter.as_deref(), shard);
    if selected.iter().any(|&i| matches!(jobs[i], Job::Sweep(..))) {
        if let Err(e) = cases::write_hard_scenes(&hard_dir) {
            return printer.fail(cannot_write(&hard_dir, e));
        }
    }
    if args.bench {
        return bench(&args, &jobs, &selected, printer);
    }
    let gpu = if selected.is_empty() {
        None
    } else {
        match headless_gpu(printer) {
            Ok(g) => Some(g),
            Err(code) => return code,
        }
    };
    let bar = indicatif::ProgressBar::new(selected.len() as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} tests {elapsed_precise} {wide_msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let mut outcomes = Vec::with_capacity(selected.len());
    // A style's warnings would repeat for each of its tests: each once.
    let mut warned = std::collections::HashSet::new();
    if let Some(gpu) = &gpu {
        let settings = Settings {
            gpu,
            out_dir: &args.out,
            bless: args.bless,
        };
        for &i in &selected {
            bar.set_message(ids[i].clone());
            let result = match &jobs[i] {
                Job::Test(file, test) => run::run(file, test, &settings),
                Job::Sweep(style, cases) => sweep::run_sweep(style, cases, &settings),
            };
            let fresh: Vec<Diagnostic> = result
                .diagnostics
                .iter()
                .filter(|d| {
                    d.is_error()
                        || warned.insert(npr_diag::diagnostic::render(
                            std::slice::from_ref(*d),
                            &result.sources,
                            false,
                        ))
                })
                .cloned()
                .collect();
            bar.suspend(|| {
                printer.diagnostics(&fresh, &result.sources);
                eprintln!("{}", report::line(&result.outcome));
            });
            outcomes.push(result.outcome);
            bar.inc(1);
        }
    }
    bar.finish_and_clear();
    let run_report = RunReport {
        outcomes: &outcomes,
        seconds: started.elapsed().as_secs_f64(),
        untested: &found.untested,
        not_selected: jobs.len() - selected.len(),
    };
    let text = match args.format {
        ReportFormat::Human => report::human(&run_report),
        ReportFormat::Json => report::json(&run_report),
        ReportFormat::Junit => report::junit(&run_report),
    };
    match &args.report {
        Some(path) => {
            if let Err(e) = npr_runner::output::write_atomic(path, text.as_bytes()) {
                return printer.fail(cannot_write(path, e));
            }
            if args.format != ReportFormat::Human {
                eprint!("{}", report::human(&run_report));
            }
        }
        None => print!("{text}"),
    }
    if outcomes.iter().any(|o| o.status == Status::Internal) {
        EXIT_INTERNAL
    } else if outcomes.iter().any(|o| o.status != Status::Passed) {
        EXIT_USER
    } else {
        EXIT_OK
    }
}

/// `--bench`: measure the selected tests that declare variants; print the
/// table (and draw it with `--plot`). Exit 1 on bad input, 2 on npr's.
fn bench(args: &TestArgs, jobs: &[Job], selected: &[usize], printer: &Printer) -> i32 {
    if let Some(plot) = &args.plot {
        if let Err(d) = npr_lab::plot::check_path(plot) {
            return printer.fail(d);
        }
    }
    let tests: Vec<(&TestFile, &TestDecl)> = selected
        .iter()
        .filter_map(|&i| match jobs[i] {
            Job::Test(f, t) if !t.variants.is_empty() => Some((f, t)),
            _ => None,
        })
        .collect();
    if tests.is_empty() {
        return printer.fail(
            Diagnostic::error(codes::BAD_ARGUMENT_VALUE, "--bench: no selected test declares `variants`")
                .with_help("give a test `variants = { fast = { .. }, exact = { .. } }` (and `reference = \"exact\"`) in its `.tests.toml`"),
        );
    }
    let gpu = match headless_gpu(printer) {
        Ok(g) => g,
        Err(code) => return code,
    };
    let mut rows = Vec::new();
    for (file, test) in tests {
        eprintln!("measuring {} ({} variants)", run::id(file, test), test.variants.len());
        match bench::measure(file, test, &gpu) {
            Ok(r) => rows.extend(r),
            Err(stopped) => {
                printer.diagnostics(&stopped.diagnostics, &stopped.sources);
                return if stopped.internal { EXIT_INTERNAL } else { EXIT_USER };
            }
        }
    }
    print!("{}", bench::table(&rows));
    if let Some(plot) = &args.plot {
        let subtitle = format!("{}, one run", gpu.adapter_info.name);
        if let Err(code) = crate::bench::write_plot(&bench::figure(&rows, &subtitle), plot, printer) {
            return code;
        }
    }
    EXIT_OK
}
