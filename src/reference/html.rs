//! The reference as a static HTML site: each Markdown page converted with
//! pulldown-cmark (links to `.md` pages pointed at their `.html`), inside a
//! page with a navigation bar and one shared stylesheet. No scripts, no
//! external fetches.

use super::Page;
use pulldown_cmark::{html, CowStr, Event, Options, Parser, Tag};

pub const CSS: &str = "body { font-family: system-ui, sans-serif; max-width: 60rem; margin: 2rem auto; padding: 0 1rem; line-height: 1.5; color: #222; }
nav { border-bottom: 1px solid #ccc; padding-bottom: 0.5rem; margin-bottom: 1rem; }
nav a { margin-right: 1rem; }
code, pre { font-family: ui-monospace, monospace; background: #f4f4f4; }
pre { padding: 0.6rem; overflow-x: auto; }
table { border-collapse: collapse; margin: 0.5rem 0; }
th, td { border: 1px solid #ccc; padding: 0.2rem 0.5rem; text-align: left; vertical-align: top; }
";

pub fn page(p: &Page, all: &[Page]) -> String {
    let parser = Parser::new_ext(&p.markdown, Options::ENABLE_TABLES).map(|event| match event {
        Event::Start(Tag::Link {
            link_type,
            dest_url,
            title,
            id,
        }) => Event::Start(Tag::Link {
            link_type,
            dest_url: html_link(dest_url),
            title,
            id,
        }),
        other => other,
    });
    let mut body = String::new();
    html::push_html(&mut body, parser);
    let nav: Vec<String> = all
        .iter()
        .map(|q| format!("<a href=\"{}.html\">{}</a>", q.stem, q.title))
        .collect();
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>npr reference: {}</title>\n<link rel=\"stylesheet\" href=\"style.css\">\n</head>\n<body>\n<nav>{}</nav>\n{body}</body>\n</html>\n",
        p.title,
        nav.join("")
    )
}

/// `operators.md#toon` → `operators.html#toon`; other links unchanged.
fn html_link(dest: CowStr<'_>) -> CowStr<'_> {
    let (file, anchor) = dest.split_once('#').map_or((&*dest, None), |(f, a)| (f, Some(a)));
    match file.strip_suffix(".md") {
        Some(stem) if !stem.contains('/') && !stem.contains(':') => {
            let mut s = format!("{stem}.html");
            if let Some(a) = anchor {
                s.push('#');
                s.push_str(a);
            }
            CowStr::from(s)
        }
        _ => dest,
    }
}
