//! Running cargo itself from a test (the workspace's metadata, package
//! lists, dependency trees): the cargo that runs the tests, in the
//! repository root, its output checked.

use std::process::Command;

/// `cargo ARGS` in the repository root, run to completion; its stdout, or a
/// panic with its stderr.
pub fn cargo_stdout(args: &[&str]) -> String {
    let out = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap_or_else(|e| panic!("run cargo {}: {e}", args.join(" ")));
    assert!(
        out.status.success(),
        "cargo {} failed: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}
