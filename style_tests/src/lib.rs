//! npr style tests: a style's tests, declared beside it in
//! `<style>.tests.toml` and run the way `npr render` renders, so a style
//! author tests a style without writing Rust, npr tests its own examples
//! the same way, and a Rust program can run them too. The `npr test`
//! command (package `npr-cli`) only parses arguments, prints and exits.
//!
//! - [`declare`]: the test file, read with spanned diagnostics (E0407);
//! - [`select`]: test files under the paths given, `--filter`, `--shard`;
//! - [`plan`]: a run's jobs (tests and sweeps), selected and run in order,
//!   each result handed to the caller;
//! - [`run`]: one test compiled, rendered and checked;
//! - [`outcome`]: what a test reports (status, failures), shared by
//!   [`run`] and [`sweep`]; `frames.rs`: rendering a test's frames;
//! - [`coherence`]: temporal coherence against exact motion (flicker
//!   after warping, pattern sliding, popping); `motion.rs`: the scene's
//!   motion from a probe render, and the `coherence` bounds checked;
//! - [`checks`]: the checks on its images (finite, not blank,
//!   deterministic, flicker, golden);
//! - [`budget`]: a frame's cost as a ratio to a passthrough;
//! - [`bench`](mod@bench): `--bench`, each variant's cost against its FLIP;
//! - [`report`]: the lines, the summary, JSON and JUnit XML;
//! - [`sweep`]: stability sweeps over every parameter's range, on the
//!   style's scenes and the hard scenes npr ships (`--sweep`, `sweep = true`);
//! - [`texture_files`]: a compiled style's texture files opened the way the
//!   runner will, refusals pointing at the style's `image("…")`.
//!
//! # Example
//!
//! Run every test of one style's test file and say which failed:
//!
//! ```no_run
//! use npr_test::outcome::{Settings, Status};
//! use npr_test::{declare, run};
//! use std::path::Path;
//!
//! let Ok(file) = declare::read(Path::new("examples/toon.tests.toml")) else {
//!     panic!("the test file has errors (declare::read returns them with their sources)");
//! };
//! let gpu = npr_runner::Gpu::headless().expect("a GPU adapter (lavapipe will do)");
//! let out_dir = Path::new("target/npr-test-output");
//! let settings = Settings { gpu: &gpu, out_dir, bless: false };
//! for test in &file.tests {
//!     let result = run::run(&file, test, &settings);
//!     if result.outcome.status == Status::Failed {
//!         eprintln!("{} failed: {:?}", result.outcome.id, result.outcome.failures);
//!     }
//! }
//! ```

pub mod bench;
pub mod budget;
pub mod checks;
pub mod coherence;
pub mod declare;
mod frames;
mod motion;
pub mod outcome;
pub mod plan;
pub mod report;
pub mod run;
pub mod select;
pub mod sweep;
pub mod texture_files;
