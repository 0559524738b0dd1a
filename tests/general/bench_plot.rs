//! `npr bench … --plot PATH.svg` end to end: small real runs write an SVG
//! that parses as XML, with a marker for every measured variant and every
//! name in its key; bad paths are refused before anything is measured.

use crate::common;

use common::cli::{npr, stderr};
use std::path::{Path, PathBuf};

fn scratch(name: &str) -> PathBuf {
    common::cli::scratch("bench_plot", name)
}

/// The SVG at `path`, parsed: (point markers, every text).
fn svg(path: &Path) -> (usize, Vec<String>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let doc = roxmltree::Document::parse(&text).unwrap_or_else(|e| panic!("{} is not XML: {e}", path.display()));
    let circles = doc.descendants().filter(|n| n.tag_name().name() == "circle").count();
    let texts = doc
        .descendants()
        .filter(|n| n.tag_name().name() == "text")
        .map(|n| n.text().unwrap_or("").trim().to_string())
        .collect();
    (circles, texts)
}

/// Only `expected` is left in `dir`: the temporary the SVG was written to
/// before its rename is gone.
fn only_file(dir: &Path, expected: &str) {
    let names: Vec<String> = std::fs::read_dir(dir)
        .expect("scratch dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, [expected], "{}", dir.display());
}

#[test]
fn bench_ops_plots_every_modelled_variant_against_each_error() {
    let dir = scratch("ops");
    let out = dir.join("ops.svg");
    let o = npr(&[
        "bench",
        "ops",
        "--size",
        "16x16",
        "--frames",
        "1",
        "--plot",
        out.to_str().expect("utf-8 path"),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    only_file(&dir, "ops.svg");
    let (circles, texts) = svg(&out);
    let variants = npr_lab::bench_ops::variants();
    let modelled: Vec<&str> = variants.iter().filter(|v| v.model.is_some()).map(|v| v.name).collect();
    // One point per modelled variant on each of the three error charts.
    assert_eq!(circles, 3 * modelled.len(), "{texts:?}");
    for (i, name) in modelled.iter().enumerate() {
        let line = format!("{}  {name}", i + 1);
        assert!(texts.contains(&line), "no key line {line:?}: {texts:?}");
    }
    // The one variant without an error model is named as not drawn.
    let unmodelled = variants.iter().find(|v| v.model.is_none()).expect("one");
    assert!(
        texts
            .iter()
            .any(|t| t.starts_with("not drawn") && t.ends_with(unmodelled.name)),
        "{texts:?}"
    );
}

#[test]
fn bench_lines_plots_cost_against_edges_and_against_error() {
    let dir = scratch("lines");
    let out = dir.join("lines.svg");
    let o = npr(&[
        "bench",
        "lines",
        "--segments",
        "8,16",
        "--size",
        "48",
        "--frames",
        "1",
        "--plot",
        out.to_str().expect("utf-8 path"),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    only_file(&dir, "lines.svg");
    let (circles, texts) = svg(&out);
    // Two charts against edges (3 series × 2 sizes each) and the three
    // methods on each of the two error charts. The strip build is a
    // difference of two timings, which a loaded machine can make ≤ 0: such
    // a point is left off its log axis, and the chart's title counts it.
    let left_out: usize = texts
        .iter()
        .filter_map(|t| {
            t.split_once(" (")?
                .1
                .split_once(" point(s) not drawn")?
                .0
                .parse::<usize>()
                .ok()
        })
        .sum();
    assert!(left_out <= 2, "only the two strip builds may be left out: {texts:?}");
    assert_eq!(circles + left_out, 2 * 3 * 2 + 2 * 3, "{texts:?}");
    for name in [
        "strips against mesh edges",
        "silhouette classification against mesh edges",
        "mesh edges, log",
        "CPU (EdgeMesh::silhouettes, f64)",
        "compute pass + read-back",
    ] {
        // A title may go on with how many points were left out.
        assert!(texts.iter().any(|t| t.starts_with(name)), "{name:?} missing: {texts:?}");
    }
    for method in ["lines, straight", "lines, wavy", "LSA full"] {
        assert!(
            texts
                .iter()
                .any(|t| t.contains(method) && t.starts_with(char::is_numeric)),
            "{method:?} not in the key: {texts:?}"
        );
    }
}

#[test]
fn a_bad_plot_path_is_refused_before_the_benchmark_runs() {
    let dir = scratch("bad");
    let missing = dir.join("no/such/dir/plot.svg");
    let not_svg = dir.join("plot.png");
    for (path, says) in [(&missing, "does not exist"), (&not_svg, "a plot is an SVG file")] {
        let started = std::time::Instant::now();
        let o = npr(&["bench", "contours", "--plot", path.to_str().expect("utf-8 path")]);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        let err = stderr(&o);
        assert!(err.contains("error[E0503]") && err.contains(says), "{err}");
        // Refused up front: the default contour bench takes minutes.
        assert!(started.elapsed().as_secs() < 20, "took {:?}", started.elapsed());
        assert!(
            o.stdout.is_empty(),
            "it measured: {}",
            String::from_utf8_lossy(&o.stdout)
        );
    }
    // Nothing was created on the way.
    assert!(!dir.join("no").exists());
}
