//! What the fuzzers share: how many cases a run makes. CI runs the default;
//! a soak run sets `NPR_FUZZ_CASES` (docs/FUZZING.md has the command and
//! the last result).

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
