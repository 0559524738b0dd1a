//! `npr test`: a style's tests, declared beside it in `<style>.tests.toml`
//! and run the way `npr render` renders, so a style author tests a style
//! without writing Rust (and npr tests its own examples the same way).
//!
//! - `declare/`: the test file, read with spanned diagnostics (E0407);
//! - `select.rs`: test files under the paths given, `--filter`, `--shard`;
//! - `run.rs`: one test compiled, rendered and checked;
//! - `outcome.rs`: what a test reports (status, failures), shared by
//!   `run.rs` and `sweep/`; `frames.rs`: rendering a test's frames;
//! - `coherence.rs`: temporal coherence against exact motion (flicker
//!   after warping, pattern sliding, popping); `motion.rs`: the scene's
//!   motion from a probe render, and the `coherence` bounds checked;
//! - `checks.rs`: the checks on its images (finite, not blank,
//!   deterministic, flicker, golden);
//! - `budget.rs`: a frame's cost as a ratio to a passthrough;
//! - `bench.rs`: `--bench`, each variant's cost against its FLIP;
//! - `report.rs`: the lines, the summary, JSON and JUnit XML;
//! - `sweep/`: stability sweeps over every parameter's range, on the
//!   style's scenes and the hard scenes npr ships (`--sweep`, `sweep = true`).
//!
//! The command itself is `commands/test.rs`.

pub mod bench;
pub mod budget;
pub mod checks;
pub mod coherence;
pub mod declare;
mod frames;
mod motion;
pub mod outcome;
pub mod report;
pub mod run;
pub mod select;
pub mod sweep;
