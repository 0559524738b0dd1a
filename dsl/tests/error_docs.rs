//! `docs/ERRORS.md` holds the table of `npr_diag::codes::ALL`, verbatim between
//! its `<!-- codes -->` markers, so every code the tools print is listed.
//! `UPDATE_ERRORS_DOC=1 cargo test -p npr-dsl --test error_docs` rewrites it.

use std::path::Path;

#[test]
fn the_docs_table_is_the_code_table() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/ERRORS.md");
    let doc = std::fs::read_to_string(&path).expect("docs/ERRORS.md");
    let (start, end) = ("<!-- codes -->\n", "<!-- /codes -->");
    let from = doc.find(start).expect("start marker") + start.len();
    let to = doc.find(end).expect("end marker");
    let table = npr_diag::codes::markdown_table();
    if std::env::var_os("UPDATE_ERRORS_DOC").is_some() {
        let updated = format!("{}{table}{}", &doc[..from], &doc[to..]);
        std::fs::write(&path, updated).expect("write docs/ERRORS.md");
        return;
    }
    assert_eq!(
        &doc[from..to],
        table,
        "docs/ERRORS.md differs from npr_diag::codes::ALL; run with UPDATE_ERRORS_DOC=1"
    );
}
