//! The `.npr` style language: grammar, AST with spans, and diagnostics.
//!
//! The public API is independent of pest: [`parse`] turns text into an
//! [`ast::Ast`] plus a list of [`Diagnostic`]s. Parsing recovers at top-level
//! item boundaries, so one run reports several syntax errors.

pub mod ast;
pub mod diagnostic;
pub mod explain;
pub mod limits;
mod nesting;
pub mod panics;
mod parser;
pub mod paths;
pub mod span;
mod syntax_error;
pub mod text;

pub use diagnostic::{codes, Diagnostic, Label, Severity};
pub use span::{FileId, SourceMap, Span};

/// Parse one `.npr` source file. Spans refer to `file`.
///
/// Always returns an AST (possibly partial) and every diagnostic found.
pub fn parse(file: FileId, source: &str) -> (ast::Ast, Vec<Diagnostic>) {
    parser::parse(file, source)
}
