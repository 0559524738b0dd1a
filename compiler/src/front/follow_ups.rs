//! Errors that follow from a syntax error are not reported.
//!
//! A declaration that does not parse is left out of the AST (the parser
//! reports it and records its name in `Ast::broken`), so every use of its
//! name would be "unknown", and a broken `output` line would be "no
//! output". Those messages say nothing the syntax error did not: with a
//! syntax error in the run, they are dropped. Every other error of the
//! declarations that did parse is still reported.

use npr_diag::{codes, Diagnostic, SourceMap};

/// Drop from `diags` the errors that a syntax error in the same run
/// explains: unknown names that are names of `broken` declarations, and a
/// missing `output`.
pub fn suppress(diags: &mut Vec<Diagnostic>, broken: &[String], sources: &SourceMap) {
    if !diags.iter().any(|d| d.code == codes::SYNTAX) {
        return;
    }
    diags.retain(|d| match d.code {
        codes::UNKNOWN_NAME => !d
            .primary_span()
            .is_some_and(|s| broken.iter().any(|b| b == sources.snippet(s))),
        codes::NO_OUTPUT => false,
        _ => true,
    });
}
