//! No import cycle among the compiler's modules (issue 31): each file is a
//! module, and a module that names a path into another (`crate::…`,
//! `super::…`, `self::…`, or a child module by name, in a `use` or in code)
//! depends on it, unless it is one of its own descendants: a parent
//! declaring its children (`mod x;`), re-exporting their items (`pub use
//! x::…`) or calling into them makes no cycle with them. Children reaching
//! into each other both ways, or into a module that reaches back into
//! them, do. Test modules (`#[cfg(test)]` to the end of the file) are
//! left out. The reading of Rust is lexical, which is enough for the
//! compiler's own sources: a misread path is a false cycle here, never a
//! missed one that matters.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

type Module = Vec<String>;

#[test]
fn no_module_depends_on_itself_through_others() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = BTreeMap::new();
    collect(&src, &src, &mut files);
    let modules: BTreeSet<Module> = files.keys().cloned().collect();
    assert!(
        modules.len() > 40,
        "{} modules found under {}",
        modules.len(),
        src.display()
    );
    let mut edges: BTreeMap<Module, BTreeSet<Module>> = BTreeMap::new();
    for (module, text) in &files {
        let code = without_comments_and_strings(text);
        let code = code.split("#[cfg(test)]").next().unwrap_or("");
        for path in paths(code) {
            let Some(target) = resolve(module, &path, &modules) else {
                continue;
            };
            if !target.starts_with(module) {
                edges.entry(module.clone()).or_default().insert(target);
            }
        }
    }
    let cycles: Vec<String> = strongly_connected(&modules, &edges)
        .into_iter()
        .filter(|c| c.len() > 1)
        .map(|c| c.iter().map(|m| m.join("::")).collect::<Vec<_>>().join(", "))
        .collect();
    assert!(
        cycles.is_empty(),
        "import cycles among compiler modules:\n{}",
        cycles.join("\n")
    );
}

/// Every `.rs` file under `dir`, by module path (`mod.rs` and `lib.rs` name
/// their directory's module).
fn collect(root: &Path, dir: &Path, files: &mut BTreeMap<Module, String>) {
    for entry in std::fs::read_dir(dir).expect("read src").flatten() {
        let path = entry.path();
        if path.is_dir() {
            collect(root, &path, files);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let rel = path.strip_prefix(root).expect("under src").with_extension("");
            let mut module: Module = rel.iter().map(|p| p.to_string_lossy().into_owned()).collect();
            if matches!(module.last().map(String::as_str), Some("mod" | "lib")) {
                module.pop();
            }
            files.insert(module, std::fs::read_to_string(&path).expect("read file"));
        }
    }
}

/// `text` with comments removed and string and char literals emptied (a
/// lifetime `'a` is kept).
fn without_comments_and_strings(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < b.len() {
        match (b[i], b.get(i + 1)) {
            (b'/', Some(b'/')) => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
            }
            (b'/', Some(b'*')) => {
                i += 2;
                while i + 1 < b.len() && !(b[i] == b'*' && b[i + 1] == b'/') {
                    i += 1;
                }
                i += 2;
            }
            (b'"', _) => {
                i += 1;
                while i < b.len() && b[i] != b'"' {
                    i += if b[i] == b'\\' { 2 } else { 1 };
                }
                i += 1;
                out.push_str("\"\"");
            }
            (b'\'', _) if b.get(i + 2) == Some(&b'\'') || b.get(i + 1) == Some(&b'\\') => {
                i += 1;
                while i < b.len() && b[i] != b'\'' {
                    i += if b[i] == b'\\' { 2 } else { 1 };
                }
                i += 1;
            }
            _ => {
                let len = text[i..].chars().next().map_or(1, char::len_utf8);
                out.push_str(&text[i..i + len]);
                i += len;
            }
        }
    }
    out
}

/// The paths `code` names: those of its `use` items (groups expanded) and
/// the `a::b` paths in its code.
fn paths(code: &str) -> Vec<Vec<String>> {
    let mut found = Vec::new();
    let mut rest = String::new();
    let mut at = 0;
    while let Some(k) = find_word(&code[at..], "use").map(|k| at + k) {
        let Some(end) = code[k..].find(';').map(|e| k + e) else {
            break;
        };
        rest.push_str(&code[at..k]);
        found.extend(expand(&code[k + 3..end]));
        at = end + 1;
    }
    rest.push_str(&code[at..]);
    let b = rest.as_bytes();
    let ident = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    let mut i = 0;
    while i < b.len() {
        if ident(b[i]) && (i == 0 || !(ident(b[i - 1]) || b[i - 1] == b':')) {
            let start = i;
            while i < b.len() && (ident(b[i]) || (b[i] == b':' && b.get(i + 1) == Some(&b':'))) {
                i += if b[i] == b':' { 2 } else { 1 };
            }
            let path: Vec<String> = rest[start..i]
                .split("::")
                .filter(|s| !s.is_empty())
                .map(String::from)
                .collect();
            if path.len() > 1 {
                found.push(path);
            }
        } else {
            i += 1;
        }
    }
    found
}

/// Where `word` starts in `s` as a whole word.
fn find_word(s: &str, word: &str) -> Option<usize> {
    let ident = |c: Option<char>| c.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_');
    s.match_indices(word)
        .map(|(k, _)| k)
        .find(|k| !ident(s[..*k].chars().next_back()) && !ident(s[k + word.len()..].chars().next()))
}

/// The paths of a `use` tree, `a::{b, c::{d as e}}` as `a::b`, `a::c::d`.
fn expand(tree: &str) -> Vec<Vec<String>> {
    let tree = tree.trim();
    let Some(open) = tree.find('{') else {
        let path = tree.split(" as ").next().unwrap_or("");
        return vec![path
            .split("::")
            .map(|s| s.trim().to_string())
            .filter(|s| !s.is_empty())
            .collect()];
    };
    let head: Vec<String> = tree[..open]
        .split("::")
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .collect();
    let inner = &tree[open + 1..tree.rfind('}').unwrap_or(tree.len())];
    let (mut items, mut depth, mut current) = (Vec::new(), 0, String::new());
    for c in inner.chars() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                items.push(std::mem::take(&mut current));
                continue;
            }
            _ => {}
        }
        current.push(c);
    }
    items.push(current);
    items
        .iter()
        .filter(|i| !i.trim().is_empty())
        .flat_map(|i| expand(i))
        .map(|tail| head.iter().cloned().chain(tail).collect())
        .collect()
}

/// The module `path` (named in `from`) leads into, if it is one of
/// `modules`: the longest module prefix of where it points.
fn resolve(from: &Module, path: &[String], modules: &BTreeSet<Module>) -> Option<Module> {
    let mut segs = path.iter().map(String::as_str).peekable();
    let mut base: Module = match segs.peek().copied() {
        Some("crate") => {
            segs.next();
            Vec::new()
        }
        Some("super" | "self") => {
            let mut base = from.clone();
            while let Some(s @ ("super" | "self")) = segs.peek().copied() {
                if s == "super" {
                    base.pop();
                }
                segs.next();
            }
            base
        }
        // A relative path into a child module (`fuse::fuse_pointwise`).
        Some(first) if modules.contains(&from.iter().cloned().chain([first.to_string()]).collect::<Module>()) => {
            from.clone()
        }
        _ => return None,
    };
    base.extend(segs.map(String::from));
    (1..=base.len())
        .rev()
        .map(|k| base[..k].to_vec())
        .find(|m| modules.contains(m))
}

/// The strongly connected components of the graph (Tarjan).
fn strongly_connected(nodes: &BTreeSet<Module>, edges: &BTreeMap<Module, BTreeSet<Module>>) -> Vec<Vec<Module>> {
    struct State<'a> {
        edges: &'a BTreeMap<Module, BTreeSet<Module>>,
        index: BTreeMap<Module, usize>,
        low: BTreeMap<Module, usize>,
        stack: Vec<Module>,
        on_stack: BTreeSet<Module>,
        components: Vec<Vec<Module>>,
    }
    fn visit(v: &Module, s: &mut State) {
        let n = s.index.len();
        s.index.insert(v.clone(), n);
        s.low.insert(v.clone(), n);
        s.stack.push(v.clone());
        s.on_stack.insert(v.clone());
        for w in s.edges.get(v).into_iter().flatten() {
            if !s.index.contains_key(w) {
                visit(w, s);
                let low = s.low[v].min(s.low[w]);
                s.low.insert(v.clone(), low);
            } else if s.on_stack.contains(w) {
                let low = s.low[v].min(s.index[w]);
                s.low.insert(v.clone(), low);
            }
        }
        if s.low[v] == s.index[v] {
            let mut component = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on_stack.remove(&w);
                let done = w == *v;
                component.push(w);
                if done {
                    break;
                }
            }
            s.components.push(component);
        }
    }
    let mut s = State {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        components: Vec::new(),
    };
    for v in nodes {
        if !s.index.contains_key(v) {
            visit(v, &mut s);
        }
    }
    s.components
}
