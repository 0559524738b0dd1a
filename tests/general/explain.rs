//! `npr explain`: every code of `npr_diag::codes::ALL` has an explanation whose
//! two examples are run through the `npr` binary, as a user would run them:
//! the wrong one must give exactly its code (an error exits 1, a warning
//! 0), the fixed one no diagnostic at all. An example that cannot run here
//! is listed in [`NOT_RUNNABLE`] with its reason; nothing else is skipped.

use npr_dsl::explain::{Example, Explanation, STYLE_FILE};
use std::collections::BTreeSet;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::Duration;

/// The examples the tests cannot run (code, which one), each with its
/// reason in the explanation's `not_runnable`. The host codes' examples
/// are Rust calls of `npr_runner::embed`: tests/error_codes/host.rs makes each
/// mistake, and the runtime's own example renders the fixed way.
const NOT_RUNNABLE: &[(&str, &str)] = &[
    ("E0505", "wrong"),
    ("E0508", "wrong"),
    ("E0509", "wrong"),
    ("E0510", "wrong"),
    ("E0511", "wrong"),
    ("E0601", "wrong"),
    ("E0601", "fixed"),
    ("E0602", "wrong"),
    ("E0602", "fixed"),
    ("E0603", "wrong"),
    ("E0603", "fixed"),
    ("E0604", "wrong"),
    ("E0604", "fixed"),
    ("E0605", "wrong"),
    ("E0605", "fixed"),
    ("E0606", "wrong"),
    ("E0606", "fixed"),
    ("E0607", "wrong"),
    ("E0607", "fixed"),
    ("E0608", "wrong"),
    ("E0608", "fixed"),
    ("E0609", "wrong"),
    ("E0609", "fixed"),
    ("E0612", "wrong"),
    ("E0612", "fixed"),
    ("E0613", "wrong"),
    ("E0613", "fixed"),
    ("E0614", "wrong"),
    ("E0614", "fixed"),
    ("E0615", "wrong"),
    ("E0615", "fixed"),
    ("E0616", "wrong"),
    ("E0616", "fixed"),
];

fn npr(dir: &Path, args: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_npr"));
    c.args(args)
        .args(["--message-format", "json"])
        .current_dir(dir)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir());
    c
}

/// An empty directory holding the example's files.
fn write_example(code: &str, which: &str, example: &Example) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("explain")
        .join(code)
        .join(which);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("example dir");
    if !example.style.is_empty() {
        std::fs::write(dir.join(STYLE_FILE), example.style_bytes()).expect("write style");
    }
    for (name, text) in example.files {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().expect("a parent")).expect("dir");
        std::fs::write(path, text).expect("write file");
    }
    dir
}

/// The codes of the JSON diagnostics a command printed.
fn codes_printed(o: &Output) -> BTreeSet<String> {
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .chain(String::from_utf8_lossy(&o.stderr).lines())
        .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
        .filter_map(|v| v.get("code").and_then(|c| c.as_str()).map(str::to_string))
        .collect()
}

fn describe(args: &[&str], o: &Output) -> String {
    format!(
        "`npr {}` exited {:?}\nstdout:\n{}\nstderr:\n{}",
        args.join(" "),
        o.status.code(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// Run every command of `example` but the last, which must succeed; return
/// the last one's output.
fn run_example(dir: &Path, example: &Example) -> Result<(Vec<&'static str>, Output), String> {
    let commands = example.command_lines();
    let (last, before) = commands.split_last().expect("at least one command");
    for args in before {
        let o = npr(dir, args).output().expect("run npr");
        if !o.status.success() {
            return Err(format!("a setup command failed: {}", describe(args, &o)));
        }
    }
    let o = npr(dir, last).output().expect("run npr");
    Ok((last.to_vec(), o))
}

fn check_wrong(e: &Explanation) -> Result<(), String> {
    let dir = write_example(e.code, "wrong", &e.wrong);
    let (args, o) = run_example(&dir, &e.wrong)?;
    let codes = codes_printed(&o);
    let want_exit = if e.code.starts_with('W') { 0 } else { 1 };
    if codes != BTreeSet::from([e.code.to_string()]) || o.status.code() != Some(want_exit) {
        return Err(format!(
            "{}: the wrong example must give exactly {} (exit {want_exit}), gave {codes:?}: {}",
            e.code,
            e.code,
            describe(&args, &o)
        ));
    }
    Ok(())
}

fn check_fixed(e: &Explanation) -> Result<(), String> {
    let dir = write_example(e.code, "fixed", &e.fixed);
    if e.fixed.serves {
        return check_serves(&dir, e);
    }
    let (args, o) = run_example(&dir, &e.fixed)?;
    let codes = codes_printed(&o);
    if !codes.is_empty() || !o.status.success() {
        return Err(format!(
            "{}: the fixed example must give no diagnostic and exit 0, gave {codes:?}: {}",
            e.code,
            describe(&args, &o)
        ));
    }
    Ok(())
}

/// A server example is fixed when it prints its address; it is stopped then.
fn check_serves(dir: &Path, e: &Explanation) -> Result<(), String> {
    let commands = e.fixed.command_lines();
    let args = commands.last().expect("a command");
    let mut child = npr(dir, args)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("start npr");
    let stdout = child.stdout.take().expect("stdout");
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    let mut seen = Vec::new();
    // A hang guard, not a measurement.
    let deadline = std::time::Instant::now() + Duration::from_secs(120);
    let served = loop {
        let left = deadline.saturating_duration_since(std::time::Instant::now());
        match rx.recv_timeout(left) {
            Ok(line) if line.starts_with("npr studio: http://") => break true,
            Ok(line) => seen.push(line),
            Err(_) => break false,
        }
    };
    let _ = child.kill();
    let _ = child.wait();
    if served {
        Ok(())
    } else {
        Err(format!(
            "{}: the fixed example never started serving; it printed:\n{}",
            e.code,
            seen.join("\n")
        ))
    }
}

#[test]
fn every_code_has_one_explanation() {
    let explained: Vec<&str> = npr_dsl::explain::all().map(|e| e.code).collect();
    let unique: BTreeSet<&str> = explained.iter().copied().collect();
    assert_eq!(unique.len(), explained.len(), "a code explained twice: {explained:?}");
    let codes: BTreeSet<&str> = npr_diag::codes::ALL.iter().map(|(c, _)| *c).collect();
    assert_eq!(unique, codes, "explanations and npr_diag::codes::ALL differ");
    for e in npr_dsl::explain::all() {
        assert!(
            e.meaning.split_whitespace().count() >= 20,
            "{}: explain it at length",
            e.code
        );
    }
}

#[test]
fn every_wrong_example_gives_its_code_and_every_fixed_one_compiles() {
    let mut failures = Vec::new();
    let mut not_run = Vec::new();
    for e in npr_dsl::explain::all() {
        for (which, example, check) in [
            ("wrong", &e.wrong, check_wrong as fn(&Explanation) -> Result<(), String>),
            ("fixed", &e.fixed, check_fixed),
        ] {
            if example.not_runnable.is_some() {
                not_run.push((e.code, which));
                continue;
            }
            if let Err(f) = check(e) {
                failures.push(f);
            }
        }
    }
    assert_eq!(not_run, NOT_RUNNABLE, "examples not run");
    assert!(
        failures.is_empty(),
        "{} failing example(s):\n\n{}",
        failures.len(),
        failures.join("\n\n")
    );
}

#[test]
fn npr_explain_prints_the_explanation() {
    let o = npr(Path::new(env!("CARGO_MANIFEST_DIR")), &["explain", "E0202"])
        .output()
        .expect("run npr");
    assert!(o.status.success(), "{}", describe(&["explain", "E0202"], &o));
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(text.starts_with("E0202: unit mismatch\n"), "{text}");
    assert!(text.contains("Wrong:") && text.contains("Fixed:"), "{text}");
    insta::assert_snapshot!("explain_E0202", text);
    // Every code, in any letter case.
    for (code, _) in npr_diag::codes::ALL {
        let lower = code.to_ascii_lowercase();
        let o = npr(Path::new(env!("CARGO_MANIFEST_DIR")), &["explain", &lower])
            .output()
            .expect("run npr");
        assert!(o.status.success(), "{}", describe(&["explain", &lower], &o));
        assert!(String::from_utf8_lossy(&o.stdout).starts_with(&format!("{code}: ")));
    }
}

#[test]
fn an_unknown_code_gives_e0502_with_the_nearest_codes() {
    let o = Command::new(env!("CARGO_BIN_EXE_npr"))
        .args(["explain", "E9999"])
        .output()
        .expect("run npr");
    assert_eq!(o.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        stderr.contains("error[E0502]: `E9999` is not an npr error code"),
        "{stderr}"
    );
    assert!(
        stderr.contains("E0615 (a host's skin does not fit its mesh)"),
        "{stderr}"
    );
    insta::assert_snapshot!("explain_unknown_code", stderr);
    let o = npr(Path::new("."), &["explain", "E0z02"]).output().expect("run npr");
    assert_eq!(codes_printed(&o), BTreeSet::from(["E0502".to_string()]));
    assert!(String::from_utf8_lossy(&o.stdout).contains("E0202 (unit mismatch)"));
}

#[test]
fn explain_finds_a_code_by_its_number_or_by_words_of_its_title() {
    let o = npr(Path::new("."), &["explain", "202"]).output().expect("run npr");
    assert!(o.status.success(), "{}", describe(&["explain", "202"], &o));
    assert!(String::from_utf8_lossy(&o.stdout).starts_with("E0202: unit mismatch\n"));
    for (words, want) in [
        ("units", "E0202 (unit mismatch)"),
        ("cannot write", "E0503 (cannot write an output)"),
        ("colour alpha", "W0201 (colour arithmetic that changes alpha (warning))"),
    ] {
        let o = npr(Path::new("."), &["explain", words]).output().expect("run npr");
        assert_eq!(o.status.code(), Some(1));
        // `--message-format json`: the diagnostic is on stdout.
        let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
        assert!(
            stdout.contains(&format!("codes about `{words}`: {want}")),
            "{words}: {stdout}"
        );
    }
}
