//! `docs/LIMITS.md` holds the table of `npr_diag::limits::ALL`, verbatim between
//! its `<!-- limits -->` markers, so the documented limits are the enforced
//! ones. `UPDATE_LIMITS_DOC=1 cargo test -p npr-dsl --test limits` rewrites it.

use std::path::Path;

#[test]
fn the_docs_table_is_the_limits_module() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/LIMITS.md");
    let doc = std::fs::read_to_string(&path).expect("docs/LIMITS.md");
    let (start, end) = ("<!-- limits -->\n", "<!-- /limits -->");
    let from = doc.find(start).expect("start marker") + start.len();
    let to = doc.find(end).expect("end marker");
    let table = npr_diag::limits::markdown_table();
    if std::env::var_os("UPDATE_LIMITS_DOC").is_some() {
        let updated = format!("{}{table}{}", &doc[..from], &doc[to..]);
        std::fs::write(&path, updated).expect("write docs/LIMITS.md");
        return;
    }
    assert_eq!(
        &doc[from..to],
        table,
        "docs/LIMITS.md differs from npr_diag::limits::ALL; run with UPDATE_LIMITS_DOC=1"
    );
}

#[test]
fn every_limit_has_a_known_code() {
    for l in npr_diag::limits::ALL {
        assert!(
            npr_diag::codes::ALL.iter().any(|(c, _)| *c == l.code),
            "{} has code {}, which is not in npr_diag::codes::ALL",
            l.name,
            l.code
        );
    }
}
