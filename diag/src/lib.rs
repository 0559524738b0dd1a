//! npr's diagnostics, the one vocabulary the compiler, the runtime and the
//! CLI report problems in: [`Diagnostic`] with its error [`codes`], spans
//! into a [`SourceMap`] (style files, scene files, `--set` arguments), the
//! terminal and JSON renderings, the [`limits`] on every input, the
//! [`paths`] policy for files a style or scene may read and the [`files`]
//! they are read from (the disk, or memory in the web build), UTF-8 text
//! loading, and the catcher of panics npr expects from its dependencies.
//!
//! It holds no parser: the runtime (`runner`), which reports scene and
//! device errors in the same form, depends on this crate and not on `dsl`
//! or pest.

pub mod diagnostic;
pub mod exit;
pub mod files;
pub mod limits;
pub mod panics;
pub mod paths;
pub mod printer;
pub mod sizes;
pub mod span;
pub mod text;
pub mod writes;

pub use diagnostic::{codes, Diagnostic, Label, Severity};
pub use span::{FileId, SourceMap, Span};
