//! `npr explain CODE`: the long explanation of an error or warning code
//! (`npr_dsl::explain`), or E0502 with the nearest codes for one that does not
//! exist.

use npr_diag::exit::EXIT_OK;
use npr_diag::printer::Printer;
use npr_diag::{codes, Diagnostic};

pub fn run(code: &str, printer: &Printer) -> i32 {
    let numbered = npr_dsl::explain::by_number(code);
    let found = npr_dsl::explain::lookup(code).or_else(|| match numbered.as_slice() {
        [one] => npr_dsl::explain::lookup(one),
        _ => None,
    });
    match found {
        Some(e) => {
            print!("{}", npr_dsl::explain::render(e));
            EXIT_OK
        }
        None => printer.fail(unknown_code(code)),
    }
}

/// E0502: `code` is no code of npr's; the help names the codes whose
/// titles share its words, or else those of its number, or else the
/// nearest in number and spelling.
fn unknown_code(code: &str) -> Diagnostic {
    let listed = |codes: Vec<&str>| -> String {
        codes
            .into_iter()
            .map(|c| format!("{c} ({})", npr_dsl::explain::summary(c).unwrap_or("")))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let words = npr_dsl::explain::by_words(code, 4);
    let numbered = npr_dsl::explain::by_number(code);
    let help = if !words.is_empty() {
        format!("codes about `{}`: {}", code.trim(), listed(words))
    } else if !numbered.is_empty() {
        format!("codes numbered {}: {}", code.trim(), listed(numbered))
    } else {
        format!("the nearest codes are {}", listed(npr_dsl::explain::nearest(code, 3)))
    };
    Diagnostic::error(
        codes::BAD_ARGUMENT_VALUE,
        format!("`{code}` is not an npr error code"),
    )
    .with_help(help)
    .with_note("`npr explain` takes a code (E0202), its number (202) or words of its title (unit); docs/ERRORS.md lists every code")
}
