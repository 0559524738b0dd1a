//! What the fuzzers share: how many cases a run makes. CI runs the default;
//! a soak run sets `NPR_FUZZ_CASES` (and `NPR_FUZZ_FIRST` for the seeded
//! generator; docs/FUZZING.md has the command and the last result).

/// `NPR_FUZZ_CASES` when set (a positive number), else `default`.
pub fn cases(default: u32) -> u32 {
    match std::env::var("NPR_FUZZ_CASES") {
        Ok(v) => v
            .trim()
            .parse()
            .ok()
            .filter(|n| *n > 0)
            .unwrap_or_else(|| panic!("NPR_FUZZ_CASES={v:?} is not a positive number")),
        Err(_) => default,
    }
}

/// `NPR_FUZZ_FIRST` when set, else 0: the first seed of a generator that
/// names its cases by seed (`fuzz_generated`), so a soak can go on where
/// the last one stopped instead of repeating its cases.
pub fn first_case() -> u64 {
    match std::env::var("NPR_FUZZ_FIRST") {
        Ok(v) => v
            .trim()
            .parse()
            .unwrap_or_else(|_| panic!("NPR_FUZZ_FIRST={v:?} is not a number")),
        Err(_) => 0,
    }
}

/// Every file under `dir` (recursively) whose extension is `ext`, sorted.
pub fn files_with_extension(dir: &std::path::Path, ext: &str) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display())) {
            let p = entry.expect("readable directory entry").path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == ext) {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}
