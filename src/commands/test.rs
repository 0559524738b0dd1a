//! `npr test PATH...`: the run's jobs come from `npr_test::plan` (the test
//! files, sweeps with `--sweep`, `--filter`, `--shard`); this command
//! shows a progress bar, prints each result and a style's warnings once,
//! and writes the report. Exit 0 when every test passes, 1 when one fails
//! or has bad input, 2 when npr itself failed.

use crate::cli::TestArgs;
use crate::printer::headless_gpu;
use npr_diag::exit::{EXIT_INTERNAL, EXIT_OK, EXIT_USER};
use npr_diag::printer::Printer;
use npr_diag::writes::cannot_write;
use npr_diag::{codes, Diagnostic};
use npr_test::bench;
use npr_test::declare::{TestDecl, TestFile};
use npr_test::outcome::{Settings, Status};
use npr_test::plan::{Job, Plan, PlanError, PlanOptions};
use npr_test::report::{self, ReportFormat, RunReport};
use npr_test::run;
use npr_test::select;
use std::time::Instant;

pub fn run(args: TestArgs, printer: &Printer) -> i32 {
    let started = Instant::now();
    let shard = match args.shard.as_deref().map(select::parse_shard).transpose() {
        Ok(s) => s,
        Err(d) => return printer.fail(d),
    };
    let plan = match Plan::new(&PlanOptions {
        paths: &args.paths,
        sweep: args.sweep,
        filter: args.filter.as_deref(),
        shard,
        out_dir: &args.out,
    }) {
        Ok(p) => p,
        Err(PlanError::Argument(d)) => return printer.fail(d),
        Err(PlanError::TestFiles(bad)) => {
            for (diags, sources) in &bad {
                printer.diagnostics(diags, sources);
            }
            return EXIT_USER;
        }
    };
    if let Err((dir, e)) = plan.write_hard_scenes() {
        return printer.fail(cannot_write(&dir, e));
    }
    if args.bench {
        return bench(&args, &plan, printer);
    }
    let gpu = if plan.is_empty() {
        None
    } else {
        match headless_gpu(printer) {
            Ok(g) => Some(g),
            Err(code) => return code,
        }
    };
    let bar = indicatif::ProgressBar::new(plan.selected().count() as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} tests {elapsed_precise} {wide_msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    // A style's warnings would repeat for each of its tests: each once.
    let mut warned = std::collections::HashSet::new();
    let outcomes = match &gpu {
        Some(gpu) => {
            let settings = Settings {
                gpu,
                out_dir: &args.out,
                bless: args.bless,
            };
            plan.run(
                &settings,
                |id| bar.set_message(id.to_string()),
                |result| {
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
                    bar.inc(1);
                },
            )
        }
        None => Vec::new(),
    };
    bar.finish_and_clear();
    let run_report = RunReport {
        outcomes: &outcomes,
        seconds: started.elapsed().as_secs_f64(),
        untested: &plan.untested,
        not_selected: plan.not_selected(),
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
fn bench(args: &TestArgs, plan: &Plan, printer: &Printer) -> i32 {
    if let Some(plot) = &args.plot {
        if let Err(d) = npr_lab::plot::check_path(plot) {
            return printer.fail(d);
        }
    }
    let tests: Vec<(&TestFile, &TestDecl)> = plan
        .selected()
        .filter_map(|(_, job)| match job {
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
