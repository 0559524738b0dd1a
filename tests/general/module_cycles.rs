//! No import cycle among the modules of any crate in the workspace (issue
//! 46): every library and binary that `cargo metadata` lists, read with
//! `syn` from its root by following `mod` declarations.
//!
//! A module depends on another when it names a path into it (`crate::…`,
//! `super::…`, `self::…`, or a child module by name), in a `use`, in code,
//! or inside a macro's tokens, unless the other is one of its own
//! descendants: a parent declaring its children, re-exporting their items
//! or calling into them makes no cycle with them. Children reaching into
//! each other both ways, or into a module that reaches back into them, do.
//! Items under `#[cfg(test)]` are left out.
//!
//! A path through a parent's re-export (`crate::exec::Thing` where `exec`
//! only re-exports it) counts as a dependency on the parent, so a cycle
//! hidden behind a facade is not seen: the check errs towards missing
//! such a cycle, never towards reporting a false one from a real import.

use crate::common::cargo::cargo_stdout;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use syn::visit::Visit;

type Module = Vec<String>;

/// Cycles that exist today and are known, by crate and the modules in
/// them (none since issue 46 broke the last ones; a cycle that must be
/// accepted for a while goes here, with the issue that will break it).
/// The test fails when one of them is gone too, so the list stays true.
const KNOWN_CYCLES: &[(&str, &[&str])] = &[];

#[test]
fn no_module_of_any_crate_depends_on_itself_through_others() {
    let mut found: Vec<(String, Vec<String>)> = Vec::new();
    let mut crates = 0;
    for (name, root) in crate_roots() {
        crates += 1;
        let modules = read_modules(&root);
        assert!(
            !modules.is_empty(),
            "crate {name}: nothing read from {}",
            root.display()
        );
        for cycle in cycles(&modules) {
            found.push((name.clone(), cycle));
        }
    }
    assert!(crates >= 9, "only {crates} crates found by cargo metadata");
    let known: BTreeSet<(String, Vec<String>)> = KNOWN_CYCLES
        .iter()
        .map(|(name, mods)| (name.to_string(), mods.iter().map(|m| m.to_string()).collect()))
        .collect();
    let new: Vec<String> = found
        .iter()
        .filter(|c| !known.contains(*c))
        .map(|(name, mods)| format!("{name}: {}", mods.join(", ")))
        .collect();
    assert!(
        new.is_empty(),
        "import cycles among the modules of a crate (break each: move what both sides need into a module \
         that imports neither):\n{}",
        new.join("\n")
    );
    let found: BTreeSet<_> = found.into_iter().collect();
    let gone: Vec<String> = known
        .iter()
        .filter(|c| !found.contains(*c))
        .map(|(name, mods)| format!("{name}: {}", mods.join(", ")))
        .collect();
    assert!(
        gone.is_empty(),
        "these known cycles are broken now: remove them from KNOWN_CYCLES\n{}",
        gone.join("\n")
    );
}

/// A cycle between two modules is found, and one through a parent's child
/// is not: the reading of paths the test relies on.
#[test]
fn the_reading_finds_a_cycle_and_spares_a_parent() {
    let modules: BTreeMap<Module, Vec<Vec<String>>> = [
        (vec![], vec![path("a::f"), path("b::g")]),
        (vec!["a".into()], vec![path("crate::b::g"), path("super::c")]),
        (vec!["b".into()], vec![path("crate::a::f")]),
        (vec!["c".into()], vec![path("crate::d")]),
    ]
    .into_iter()
    .collect();
    let graph: BTreeMap<Module, BTreeSet<Module>> = modules
        .iter()
        .map(|(m, paths)| {
            let known: BTreeSet<Module> = modules.keys().cloned().collect();
            let targets = paths
                .iter()
                .filter_map(|p| resolve(m, p, &known))
                .filter(|t| !t.starts_with(m))
                .collect();
            (m.clone(), targets)
        })
        .collect();
    let components: Vec<Vec<Module>> = strongly_connected(&graph).into_iter().filter(|c| c.len() > 1).collect();
    assert_eq!(components.len(), 1, "{components:?}");
    let mut cycle = components[0].clone();
    cycle.sort();
    assert_eq!(cycle, vec![vec!["a".to_string()], vec!["b".to_string()]]);
}

fn path(text: &str) -> Vec<String> {
    text.split("::").map(String::from).collect()
}

/// Each workspace package's library and binaries: a name and the root file.
fn crate_roots() -> Vec<(String, PathBuf)> {
    let metadata: serde_json::Value =
        serde_json::from_str(&cargo_stdout(&["metadata", "--no-deps", "--format-version", "1"]))
            .expect("metadata JSON");
    let mut roots = Vec::new();
    for package in metadata["packages"].as_array().expect("packages") {
        let package_name = package["name"].as_str().expect("package name");
        for target in package["targets"].as_array().expect("targets") {
            let kinds: Vec<&str> = target["kind"]
                .as_array()
                .expect("kind")
                .iter()
                .filter_map(|k| k.as_str())
                .collect();
            if kinds.iter().any(|k| matches!(*k, "lib" | "rlib" | "cdylib" | "bin")) {
                let name = format!("{package_name} ({})", target["name"].as_str().unwrap_or("?"));
                roots.push((name, PathBuf::from(target["src_path"].as_str().expect("src_path"))));
            }
        }
    }
    roots
}

/// Every module of the crate rooted at `root`, by module path, with the
/// paths its code names. Follows `mod x;` declarations (`x.rs` or
/// `x/mod.rs`), leaving out `#[cfg(test)]` ones; an inline `mod x { … }`
/// belongs to its file's module.
fn read_modules(root: &Path) -> BTreeMap<Module, Vec<Vec<String>>> {
    let mut modules = BTreeMap::new();
    let dir = root.parent().expect("root's folder").to_path_buf();
    let mut pending = vec![(Module::new(), root.to_path_buf(), dir)];
    while let Some((module, file, children_dir)) = pending.pop() {
        let text = std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("read {}: {e}", file.display()));
        let parsed = syn::parse_file(&text).unwrap_or_else(|e| panic!("parse {}: {e}", file.display()));
        let mut reader = PathReader::default();
        for item in &parsed.items {
            if is_test_only(item) {
                continue;
            }
            if let syn::Item::Mod(m) = item {
                if m.content.is_none() {
                    let name = m.ident.to_string();
                    let flat = children_dir.join(format!("{name}.rs"));
                    let nested = children_dir.join(&name).join("mod.rs");
                    let (child_file, grandchildren) = if flat.exists() {
                        (flat, children_dir.join(&name))
                    } else if nested.exists() {
                        (nested, children_dir.join(&name))
                    } else {
                        panic!(
                            "module {name} of {}: neither {} nor {}",
                            file.display(),
                            flat.display(),
                            nested.display()
                        )
                    };
                    let mut child = module.clone();
                    child.push(name);
                    pending.push((child, child_file, grandchildren));
                    continue;
                }
            }
            reader.visit_item(item);
        }
        modules.insert(module, reader.paths);
    }
    modules
}

/// Is the item compiled only for tests (`#[cfg(test)]`)?
fn is_test_only(item: &syn::Item) -> bool {
    let attrs = match item {
        syn::Item::Mod(m) => &m.attrs,
        syn::Item::Fn(f) => &f.attrs,
        syn::Item::Use(u) => &u.attrs,
        syn::Item::Impl(i) => &i.attrs,
        _ => return false,
    };
    attrs
        .iter()
        .any(|a| a.path().is_ident("cfg") && a.parse_args::<syn::Meta>().is_ok_and(|m| m.path().is_ident("test")))
}

/// The paths a module's items name: `use` trees expanded, paths in code,
/// and `a::b` runs of tokens inside macro calls.
#[derive(Default)]
struct PathReader {
    paths: Vec<Vec<String>>,
}

impl<'ast> Visit<'ast> for PathReader {
    fn visit_item(&mut self, item: &'ast syn::Item) {
        if !is_test_only(item) {
            syn::visit::visit_item(self, item);
        }
    }

    fn visit_item_use(&mut self, item: &'ast syn::ItemUse) {
        use_paths(&item.tree, &mut Vec::new(), &mut self.paths);
    }

    fn visit_path(&mut self, path: &'ast syn::Path) {
        if path.segments.len() > 1 {
            self.paths
                .push(path.segments.iter().map(|s| s.ident.to_string()).collect());
        }
        syn::visit::visit_path(self, path);
    }

    fn visit_macro(&mut self, mac: &'ast syn::Macro) {
        token_paths(mac.tokens.clone(), &mut self.paths);
        syn::visit::visit_macro(self, mac);
    }
}

/// The paths of a `use` tree, `a::{b, c::{d as e}}` as `a::b`, `a::c::d`.
fn use_paths(tree: &syn::UseTree, prefix: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    match tree {
        syn::UseTree::Path(p) => {
            prefix.push(p.ident.to_string());
            use_paths(&p.tree, prefix, out);
            prefix.pop();
        }
        syn::UseTree::Name(n) => out.push(prefix.iter().cloned().chain([n.ident.to_string()]).collect()),
        syn::UseTree::Rename(r) => out.push(prefix.iter().cloned().chain([r.ident.to_string()]).collect()),
        syn::UseTree::Glob(_) => out.push(prefix.clone()),
        syn::UseTree::Group(g) => {
            for t in &g.items {
                use_paths(t, prefix, out);
            }
        }
    }
}

/// The `a::b::c` runs in a macro's tokens (a macro's body is not parsed
/// as code).
fn token_paths(tokens: proc_macro2::TokenStream, out: &mut Vec<Vec<String>>) {
    fn flush(run: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
        if run.len() > 1 {
            out.push(std::mem::take(run));
        }
        run.clear();
    }
    let mut run: Vec<String> = Vec::new();
    let mut colons = 0;
    for token in tokens {
        match token {
            proc_macro2::TokenTree::Ident(ident) => {
                if colons != 2 && !run.is_empty() {
                    flush(&mut run, out);
                }
                run.push(ident.to_string());
                colons = 0;
            }
            proc_macro2::TokenTree::Punct(p) if p.as_char() == ':' && !run.is_empty() && colons < 2 => colons += 1,
            proc_macro2::TokenTree::Group(g) => {
                flush(&mut run, out);
                colons = 0;
                token_paths(g.stream(), out);
            }
            _ => {
                flush(&mut run, out);
                colons = 0;
            }
        }
    }
    flush(&mut run, out);
}

/// The cycles among `modules`: each as its modules' paths, sorted.
fn cycles(modules: &BTreeMap<Module, Vec<Vec<String>>>) -> Vec<Vec<String>> {
    let known: BTreeSet<Module> = modules.keys().cloned().collect();
    let graph: BTreeMap<Module, BTreeSet<Module>> = modules
        .iter()
        .map(|(module, paths)| {
            let targets = paths
                .iter()
                .filter_map(|p| resolve(module, p, &known))
                .filter(|t| !t.starts_with(module))
                .collect();
            (module.clone(), targets)
        })
        .collect();
    strongly_connected(&graph)
        .into_iter()
        .filter(|c| c.len() > 1)
        .map(|c| {
            let mut names: Vec<String> = c
                .iter()
                .map(|m| {
                    if m.is_empty() {
                        "crate".to_string()
                    } else {
                        m.join("::")
                    }
                })
                .collect();
            names.sort();
            names
        })
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
    (0..=base.len())
        .rev()
        .map(|k| base[..k].to_vec())
        .find(|m| modules.contains(m))
}

/// The strongly connected components of the graph (Tarjan).
fn strongly_connected(edges: &BTreeMap<Module, BTreeSet<Module>>) -> Vec<Vec<Module>> {
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
    for v in edges.keys() {
        if !s.index.contains_key(v) {
            visit(v, &mut s);
        }
    }
    s.components
}
