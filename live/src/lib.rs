//! npr live authoring: a style rebuilt on every save of it, of what it
//! `use`s, of its scene and of the files they name, and shown as it is
//! edited, in a window (`npr view`) or in a browser (`npr studio`). A bad
//! save reports its diagnostics and keeps the last good build; a panic in
//! a build is reported as E9001 and never ends the session.
//!
//! - [`watcher`]: the debounced directory watcher and its file set;
//! - [`build`]: one build (scene + compile with `--set`s and the controls)
//!   and the files it depends on;
//! - [`guard`]: running a step so that a panic becomes a report;
//! - [`view`]: the window, driven through `npr_runner::embed` like any host;
//! - [`studio`]: the browser studio's HTTP server and render thread.
//!
//! `npr watch` (package `npr-cli`) renders to a file on every save with
//! the same [`build`] and [`watcher`].
//!
//! # Example
//!
//! A window on a style that follows every save (what `npr view` does):
//!
//! ```no_run
//! use npr_diag::printer::{MessageFormat, Printer};
//! use npr_live::build::Inputs;
//! use npr_live::view::{run, ViewOptions};
//!
//! let options = ViewOptions {
//!     inputs: Inputs {
//!         style: "examples/toon.npr".into(),
//!         scene: "examples/scenes/spot.toml".into(),
//!         sets: vec!["bands=4".into()],
//!         keep_params: true,
//!         paths: Default::default(),
//!         schedule: npr_compiler::schedule::Schedule::Auto,
//!     },
//!     size: (512, 512),
//!     time: 0.0,
//!     paused: false,
//!     fps: 24.0,
//!     frames: None,
//!     vsync: true,
//! };
//! std::process::exit(run(options, &Printer::new(MessageFormat::Human)));
//! ```

pub mod build;
pub mod guard;
pub mod studio;
pub mod view;
pub mod watcher;
