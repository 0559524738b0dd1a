//! Which tests a run of `npr test PATH...` runs: the test files found under
//! the paths, then `--filter` and `--shard i/n` over the tests' ids.
//!
//! A shard is every n-th test of the filtered tests sorted by id, so the n
//! shards of one filter partition its tests exactly, on any machine, in any
//! order the paths were given.

use super::declare::{self, SUFFIX};
use npr_diag::{codes, Diagnostic};
use std::path::{Path, PathBuf};

/// The test files under the paths given, and the styles that have none.
#[derive(Debug, Default)]
pub struct Found {
    pub test_files: Vec<PathBuf>,
    pub untested: Vec<PathBuf>,
    /// The untested styles named on the command line (not found in a
    /// directory, where libraries and art-map filters are too): what
    /// `--sweep` sweeps besides the styles with tests.
    pub named_untested: Vec<PathBuf>,
}

/// Walk `paths`: a directory for every `*.tests.toml` in it (and every
/// `.npr` without one), a style for its test file, a test file itself.
/// E0502 for a path that does not exist or is neither.
pub fn find(paths: &[PathBuf]) -> Result<Found, Diagnostic> {
    let mut found = Found::default();
    for path in paths {
        if path.is_dir() {
            walk(path, &mut found).map_err(|e| bad_path(path, &format!("cannot read the directory: {e}")))?;
        } else if path.to_string_lossy().ends_with(SUFFIX) && path.is_file() {
            found.test_files.push(path.clone());
        } else if path.extension().is_some_and(|e| e == "npr") && path.is_file() {
            let tests = declare::tests_of(path);
            if tests.is_file() {
                found.test_files.push(tests);
            } else {
                found.untested.push(path.clone());
                found.named_untested.push(path.clone());
            }
        } else if path.exists() {
            return Err(bad_path(
                path,
                "it is neither a style (.npr), a test file (.tests.toml) nor a directory",
            ));
        } else {
            return Err(bad_path(path, "no such file or directory"));
        }
    }
    found.test_files.sort();
    found.test_files.dedup();
    found.untested.sort();
    found.untested.dedup();
    found.named_untested.sort();
    found.named_untested.dedup();
    Ok(found)
}

fn bad_path(path: &Path, why: &str) -> Diagnostic {
    Diagnostic::error(codes::BAD_ARGUMENT_VALUE, format!("npr test {}: {why}", path.display()))
        .with_help("give styles, their `<style>.tests.toml` files, or directories holding them")
}

/// Every test file and untested style under `dir`, skipping hidden
/// directories and `target` (build and test output).
fn walk(dir: &Path, found: &mut Found) -> std::io::Result<()> {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)?
        .map(|e| e.map(|e| e.path()))
        .collect::<Result<_, _>>()?;
    entries.sort();
    for path in entries {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        if path.is_dir() {
            if !name.starts_with('.') && name != "target" {
                walk(&path, found)?;
            }
        } else if name.ends_with(SUFFIX) {
            found.test_files.push(path);
        } else if name.ends_with(".npr") && !declare::tests_of(&path).is_file() {
            found.untested.push(path);
        }
    }
    Ok(())
}

/// `--shard i/n`: shard i (from 1) of n.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

/// Read `--shard i/n`; E0502 unless 1 ≤ i ≤ n.
pub fn parse_shard(text: &str) -> Result<Shard, Diagnostic> {
    let bad = |why: &str| {
        Diagnostic::error(codes::BAD_ARGUMENT_VALUE, format!("--shard {text}: {why}"))
            .with_help("`--shard i/n` runs the i-th of n shards, i from 1 to n, e.g. `--shard 2/4`")
    };
    let (i, n) = text.split_once('/').ok_or_else(|| bad("expected i/n"))?;
    let (Ok(index), Ok(count)) = (i.trim().parse::<usize>(), n.trim().parse::<usize>()) else {
        return Err(bad("i and n must be whole numbers"));
    };
    if count == 0 {
        return Err(bad("there must be at least one shard"));
    }
    if index == 0 || index > count {
        return Err(bad(&format!("shard {index} does not exist: shards are 1 to {count}")));
    }
    Ok(Shard { index, count })
}

/// The indices into `ids` that a run keeps: those containing `filter`,
/// then, sorted by id, every `count`-th from the shard's own.
pub fn select(ids: &[String], filter: Option<&str>, shard: Option<Shard>) -> Vec<usize> {
    let mut kept: Vec<usize> = (0..ids.len())
        .filter(|&i| filter.is_none_or(|f| ids[i].contains(f)))
        .collect();
    kept.sort_by(|&a, &b| ids[a].cmp(&ids[b]));
    match shard {
        None => kept,
        Some(s) => kept
            .into_iter()
            .enumerate()
            .filter(|(rank, _)| rank % s.count == s.index - 1)
            .map(|(_, i)| i)
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_partition_the_filtered_tests() {
        let ids: Vec<String> = ["b::x", "a::y", "c::z", "a::x", "d::w"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        let mut all: Vec<usize> = (1..=3)
            .flat_map(|index| select(&ids, None, Some(Shard { index, count: 3 })))
            .collect();
        all.sort();
        assert_eq!(all, vec![0, 1, 2, 3, 4]);
        assert_eq!(select(&ids, Some("::x"), None), vec![3, 0]);
        assert_eq!(select(&ids, Some("::x"), Some(Shard { index: 2, count: 2 })), vec![0]);
    }

    #[test]
    fn a_shard_outside_its_count_is_refused() {
        assert_eq!(parse_shard("2/4").ok(), Some(Shard { index: 2, count: 4 }));
        for bad in ["5/4", "0/4", "1/0", "x/4", "3"] {
            assert_eq!(parse_shard(bad).unwrap_err().code, codes::BAD_ARGUMENT_VALUE, "{bad}");
        }
    }
}
