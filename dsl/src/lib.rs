//! The `.npr` style language: grammar, parser and AST with spans, and the
//! `npr explain` texts. Diagnostics, spans and limits are the `diag` crate's.
//!
//! The public API is independent of pest: [`parse`] turns text into an
//! [`ast::Ast`] plus a list of [`Diagnostic`]s. Parsing recovers at top-level
//! item boundaries, so one run reports several syntax errors.

pub mod ast;
pub mod explain;
mod grammar;
mod nesting;
mod parser;
mod syntax_error;

use npr_diag::{Diagnostic, FileId};

/// Parse one `.npr` source file. Spans refer to `file`.
///
/// Always returns an AST (possibly partial) and every diagnostic found.
pub fn parse(file: FileId, source: &str) -> (ast::Ast, Vec<Diagnostic>) {
    parser::parse(file, source)
}
