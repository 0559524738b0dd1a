//! Live authoring: what `npr watch` and `npr studio` share.
//!
//! - `watcher.rs`: the debounced directory watcher and its file set;
//! - `build.rs`: one build (scene + compile with `--set`s and the controls)
//!   and the files it depends on;
//! - `guard.rs`: running a step so that a panic becomes a report.

pub mod build;
pub mod guard;
pub mod watcher;
