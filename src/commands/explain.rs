//! `npr explain CODE`: the long explanation of an error or warning code
//! (`dsl::explain`), or E0502 with the nearest codes for one that does not
//! exist.

use crate::cli::EXIT_OK;
use crate::printer::Printer;
use diag::{codes, Diagnostic};

pub fn run(code: &str, printer: &Printer) -> i32 {
    match dsl::explain::lookup(code) {
        Some(e) => {
            print!("{}", dsl::explain::render(e));
            EXIT_OK
        }
        None => printer.fail(unknown_code(code)),
    }
}

/// E0502: `code` is no code of npr's; the help names the nearest ones.
fn unknown_code(code: &str) -> Diagnostic {
    let near: Vec<String> = dsl::explain::nearest(code, 3)
        .into_iter()
        .map(|c| format!("{c} ({})", dsl::explain::summary(c).unwrap_or("")))
        .collect();
    Diagnostic::error(codes::BAD_ARGUMENT_VALUE, format!("`{code}` is not an npr error code"))
        .with_help(format!("the nearest codes are {}", near.join(", ")))
        .with_note("docs/ERRORS.md lists every code")
}
