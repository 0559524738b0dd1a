//! The stdlib and language reference `npr doc` writes: Markdown pages from
//! the metadata (`pages.rs`), with each operator's demo image (`images.rs`)
//! and its committed benchmark figures (`figures.rs`), and the same pages as
//! a static HTML site (`html.rs`). `docs/reference/` is this output, checked by
//! `tests/general/reference_docs.rs`.

pub mod figures;
mod html;
pub mod images;
mod pages;

/// Every file of the reference: (file name, contents).
pub fn files(figures: &figures::Figures) -> Vec<(String, String)> {
    let pages = pages::all(figures);
    let mut out: Vec<(String, String)> = pages
        .iter()
        .map(|p| (format!("{}.md", p.stem), p.markdown.clone()))
        .collect();
    for p in &pages {
        out.push((format!("{}.html", p.stem), html::page(p, &pages)));
    }
    out.push(("style.css".into(), html::CSS.into()));
    out
}

/// One page: its file stem, its title and its Markdown.
pub struct Page {
    pub stem: &'static str,
    pub title: &'static str,
    pub markdown: String,
}
