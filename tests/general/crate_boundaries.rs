//! The crate boundaries ARCHITECTURE.md promises, read from `cargo metadata`
//! (the resolved graph, normal dependencies only, followed transitively):
//! an application that embeds the runtime (`npr-runner`) links no compiler, no
//! stdlib, no parser and no pest; the contract crates (`abi`, `diag`) depend
//! on none of npr's own crates but each other; the compiler does not depend
//! on the runtime. A forbidden edge that comes back fails here, naming the
//! path by which it came.

use crate::common::cargo::cargo_stdout;
use serde_json::Value;
use std::collections::{BTreeMap, BTreeSet, VecDeque};
use std::sync::OnceLock;

/// The host's target triple (`rustc -vV`): the graph is resolved for the
/// platform this runs on, whose packages the build has already fetched.
fn host_triple() -> String {
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let out = std::process::Command::new(rustc)
        .arg("-vV")
        .output()
        .expect("run rustc -vV");
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    text.lines()
        .find_map(|l| l.strip_prefix("host: "))
        .unwrap_or_else(|| panic!("no `host:` line in rustc -vV:\n{text}"))
        .to_string()
}

/// Package name → the names of its normal (non-dev, non-build) dependencies,
/// read once per test binary.
fn normal_dependency_graph() -> &'static BTreeMap<String, Vec<String>> {
    static GRAPH: OnceLock<BTreeMap<String, Vec<String>>> = OnceLock::new();
    GRAPH.get_or_init(read_graph)
}

fn read_graph() -> BTreeMap<String, Vec<String>> {
    let host = host_triple();
    let out = cargo_stdout(&[
        "metadata",
        "--format-version",
        "1",
        "--offline",
        "--filter-platform",
        &host,
    ]);
    let meta: Value = serde_json::from_str(&out).expect("cargo metadata's JSON");
    let name_of: BTreeMap<&str, &str> = meta["packages"]
        .as_array()
        .expect("packages")
        .iter()
        .map(|p| (p["id"].as_str().expect("id"), p["name"].as_str().expect("name")))
        .collect();
    let mut graph = BTreeMap::new();
    for node in meta["resolve"]["nodes"].as_array().expect("resolve.nodes") {
        let from = name_of[node["id"].as_str().expect("id")].to_string();
        let deps = node["deps"]
            .as_array()
            .expect("deps")
            .iter()
            .filter(|d| {
                d["dep_kinds"]
                    .as_array()
                    .expect("dep_kinds")
                    .iter()
                    .any(|k| k["kind"].is_null())
            })
            .map(|d| name_of[d["pkg"].as_str().expect("pkg")].to_string())
            .collect();
        graph.insert(from, deps);
    }
    graph
}

/// The dependency path from `from` to `to`, if `to` is reachable.
fn path(graph: &BTreeMap<String, Vec<String>>, from: &str, to: &str) -> Option<Vec<String>> {
    let mut came_from: BTreeMap<&str, &str> = BTreeMap::new();
    let mut seen = BTreeSet::from([from]);
    let mut queue = VecDeque::from([from]);
    while let Some(at) = queue.pop_front() {
        if at == to {
            let mut p = vec![to.to_string()];
            let mut cur = to;
            while let Some(prev) = came_from.get(cur) {
                p.push(prev.to_string());
                cur = prev;
            }
            p.reverse();
            return Some(p);
        }
        for next in graph.get(at).into_iter().flatten() {
            if seen.insert(next) {
                came_from.insert(next, at);
                queue.push_back(next);
            }
        }
    }
    None
}

fn assert_no_edge(graph: &BTreeMap<String, Vec<String>>, from: &str, forbidden: &[&str]) {
    assert!(graph.contains_key(from), "`{from}` is not in the workspace's graph");
    // A forbidden name that is no package (a crate renamed) would pass unseen.
    for to in forbidden {
        assert!(graph.contains_key(*to), "`{to}` is not in the workspace's graph");
    }
    let found: Vec<String> = forbidden
        .iter()
        .filter_map(|to| path(graph, from, to))
        .map(|p| p.join(" → "))
        .collect();
    assert!(
        found.is_empty(),
        "`{from}` must not depend on {forbidden:?}, but does through:\n  {}",
        found.join("\n  ")
    );
}

#[test]
fn the_runtime_links_no_compiler_stdlib_parser_or_benchmarks() {
    let graph = normal_dependency_graph();
    assert_no_edge(
        graph,
        "npr-runner",
        &[
            "npr-compiler",
            "npr-stdlib",
            "npr-dsl",
            "pest",
            "npr-lab",
            "npr-test",
            "npr-cli",
        ],
    );
    // The path finder finds what is there: the runner does reach wgpu and abi.
    assert!(path(graph, "npr-runner", "wgpu").is_some() && path(graph, "npr-runner", "npr-abi").is_some());
}

#[test]
fn the_contract_crates_depend_on_no_other_npr_crate() {
    let graph = normal_dependency_graph();
    assert_no_edge(
        graph,
        "npr-abi",
        &[
            "npr-diag",
            "npr-dsl",
            "npr-compiler",
            "npr-stdlib",
            "npr-runner",
            "npr-lab",
            "pest",
        ],
    );
    assert_no_edge(
        graph,
        "npr-diag",
        &[
            "npr-abi",
            "npr-dsl",
            "npr-compiler",
            "npr-stdlib",
            "npr-runner",
            "npr-lab",
            "pest",
        ],
    );
}

#[test]
fn the_compiler_does_not_depend_on_the_runtime() {
    let graph = normal_dependency_graph();
    assert_no_edge(graph, "npr-compiler", &["npr-runner", "npr-lab", "npr-test", "wgpu"]);
    assert_no_edge(
        graph,
        "npr-stdlib",
        &["npr-compiler", "npr-runner", "npr-lab", "npr-dsl", "wgpu"],
    );
}

#[test]
fn the_libraries_behind_the_command_line_do_not_depend_on_it() {
    let graph = normal_dependency_graph();
    // The binary is a thin front end: what it runs is in libraries a Rust
    // program can depend on, none of which reaches back into it.
    for library in ["npr-test", "npr-lsp", "npr-live", "npr-lab", "npr-web"] {
        assert_no_edge(graph, library, &["npr-cli"]);
    }
    assert!(
        path(graph, "npr-cli", "npr-test").is_some()
            && path(graph, "npr-cli", "npr-lsp").is_some()
            && path(graph, "npr-cli", "npr-live").is_some()
    );
}

/// The packages `cargo tree` says `package` links with `features`
/// (normal dependencies, this platform), by name.
fn linked(package: &str, features: &[&str]) -> BTreeSet<String> {
    let mut args = vec![
        "tree",
        "-p",
        package,
        "-e",
        "normal",
        "--prefix",
        "none",
        "--format",
        "{p}",
        "--offline",
    ];
    args.extend_from_slice(features);
    cargo_stdout(&args)
        .lines()
        .filter_map(|l| l.split_whitespace().next())
        .map(str::to_string)
        .collect()
}

#[test]
fn a_shipped_bevy_game_links_the_runtime_and_no_compiler() {
    let compiler = ["npr-compiler", "npr-stdlib", "npr-dsl", "pest"];
    let shipped = linked("bevy_mod_npr", &["--no-default-features"]);
    assert!(
        shipped.contains("npr-runner"),
        "the plugin without features has no runtime: {shipped:?}"
    );
    let found: Vec<_> = compiler.iter().filter(|c| shipped.contains(**c)).collect();
    assert!(
        found.is_empty(),
        "bevy_mod_npr without default features links {found:?}"
    );
    // The development build does link it (the check above can fail).
    let development = linked("bevy_mod_npr", &[]);
    assert!(
        development.contains("npr-compiler") && development.contains("pest"),
        "{development:?}"
    );
    // Hot reload is a feature too: Bevy's watcher (notify) only with it.
    assert!(
        !shipped.contains("notify") && development.contains("notify"),
        "file_watcher is not the feature that brings notify"
    );
}
