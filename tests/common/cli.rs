//! Running the `npr` binary from a test: the command (from the repository
//! root, with a runtime dir so Mesa does not warn), a fresh scratch
//! directory per case, and the stderr of a run as text.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// `npr ARGS` from the repository root, run to completion.
pub fn npr(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_npr"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run npr")
}

/// An empty directory `group/name` under the test target dir.
pub fn scratch(group: &str, name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(group).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}
