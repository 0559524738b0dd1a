//! What each benchmark plots: its rows (the ones its tables print) turned
//! into a [`Figure`]. Every number here is a column of the printed table,
//! or, where said, a mean or difference of printed columns.
//!
//! | bench | speed against error | cost against size (log–log) |
//! |---|---|---|
//! | `ops` | × plain sample against each of the three errors | (one size) |
//! | `contours` | image stage ms against 1 − min precision and against 1 − min recall (planes included), a series per size | image stage ms against pixels, per method (with ≥ 2 sizes) |
//! | `patterns` | tracking ms against the rel. error of z, a series per object count; sliding variants: frame ms against the mean sliding | tracking ms against samples drawn, per object count |
//! | `artmaps` | (no error measured) | art-map and rip-map build ms against source pixels, per filter |
//! | `lines` | ms over the base pass against 1 − min precision and 1 − min recall | strip build and frames, and CPU against compute classification, against mesh edges |

use super::{Chart, ChartKind, Figure, Point};
use crate::{bench_artmaps, bench_contours, bench_lines, bench_ops, bench_patterns, sliding};

/// Whether `xs` holds two different sizes: a cost-against-size chart of
/// one size would be a column of dots.
fn several(xs: impl IntoIterator<Item = f64>) -> bool {
    let mut xs = xs.into_iter();
    let Some(first) = xs.next() else { return false };
    xs.any(|x| x != first)
}

fn plural(n: usize, one: &str) -> String {
    if n == 1 {
        format!("{n} {one}")
    } else {
        format!("{n} {one}s")
    }
}

/// `npr bench ops`: cost against each of the three error models.
pub fn ops(rows: &[bench_ops::Row], subtitle: &str) -> Figure {
    let mut fig = Figure::new("npr bench ops: MetaTexture variants, speed against error", subtitle);
    let y = "cost vs plain sample (×)";
    let mut charts = [
        Chart::new(
            ChartKind::SpeedError,
            "cost against scale error",
            "scale error (mean |log₂ period/target|)",
            y,
        ),
        Chart::new(
            ChartKind::SpeedError,
            "cost against anisotropy",
            "anisotropy (mean |axis angle − 90°|, °)",
            y,
        ),
        Chart::new(
            ChartKind::SpeedError,
            "cost against contrast error",
            "contrast error |σ_M/σ_T − 1|",
            y,
        ),
    ];
    for r in rows {
        let Some((scale, aniso, contrast)) = r.errors else {
            fig.notes
                .push(format!("not drawn (no error model on the plane): {}", r.name));
            continue;
        };
        let key = Some(fig.key(r.name));
        for (chart, x) in charts.iter_mut().zip([scale, aniso, contrast]) {
            chart.series("variants").points.push(Point::new(x, r.vs_plain, key));
        }
    }
    fig.charts.extend(charts);
    fig
}

/// Two speed-against-error charts from precision and recall: false lines
/// (1 − precision) and missed lines (1 − recall).
fn accuracy_charts(what: &str, y: &str, recall_note: &str) -> [Chart; 2] {
    [
        Chart::new(
            ChartKind::SpeedError,
            &format!("{what} against false lines"),
            "1 − min precision",
            y,
        ),
        Chart::new(
            ChartKind::SpeedError,
            &format!("{what} against missed lines"),
            &format!("1 − min recall{recall_note}"),
            y,
        ),
    ]
}

/// `npr bench contours`: the image stage against both errors per size,
/// and against the pixel count per method.
pub fn contours(rows: &[bench_contours::Row], subtitle: &str) -> Figure {
    let mut fig = Figure::new("npr bench contours: contour methods, cost against accuracy", subtitle);
    let y = "image stage (ms)";
    let mut charts = accuracy_charts("image stage", y, " (parallel planes included)");
    let mut by_size = Chart::new(ChartKind::CostSize, "image stage against pixel count", "pixels", y);
    for r in rows {
        let key = fig.key(&r.name);
        // A passthrough's image stage is t_pass; at its floor it was not
        // measured (the table's 0.000), and not drawn.
        let stage_ms = if r.image_stage_s > bench_contours::T_PASS_FLOOR_S {
            r.image_stage_s * 1e3
        } else {
            f64::NAN
        };
        if let Some((precision, recall, planes)) = r.accuracy {
            let series = format!("{}²", r.size);
            charts[0]
                .series(&series)
                .points
                .push(Point::new(1.0 - precision, stage_ms, Some(key)));
            charts[1]
                .series(&series)
                .points
                .push(Point::new(1.0 - recall.min(planes), stage_ms, Some(key)));
        }
        let px = f64::from(r.size) * f64::from(r.size);
        by_size.series(&r.name).points.push(Point::new(px, stage_ms, None));
    }
    label_line_ends(&mut fig, &mut by_size);
    fig.charts.extend(charts);
    if several(rows.iter().map(|r| f64::from(r.size))) {
        fig.charts.push(by_size);
    }
    fig.notes.push(
        "image stage = frame − G-buffer (the table's column; not drawn where ≤ 0, or at t_pass's floor); \
         errors over the analytic scenes, within 1 px"
            .into(),
    );
    fig
}

/// A cost-against-size chart with many lines labels the last point of
/// each with its series' key number instead of a legend.
fn label_line_ends(fig: &mut Figure, chart: &mut Chart) {
    for s in &mut chart.series {
        let key = fig.key(&s.name);
        if let Some(last) = s.points.last_mut() {
            last.key = Some(key);
        }
    }
}

/// `npr bench patterns`: the tracker's cost against its error and its
/// samples, and the sliding of each tracker variant against its frame time.
pub fn patterns(rows: &[bench_patterns::Row], slides: &[sliding::Row], subtitle: &str) -> Figure {
    let mut fig = Figure::new("npr bench patterns: the dynamic 2D pattern tracker", subtitle);
    let y = "tracking (ms)";
    let mut error = Chart::new(
        ChartKind::SpeedError,
        "tracking cost against the error of z (f32 GPU vs f64)",
        "relative error of z",
        y,
    );
    let mut by_samples = Chart::new(
        ChartKind::CostSize,
        "tracking cost against samples drawn",
        "samples drawn",
        y,
    );
    for r in rows {
        let key = Some(fig.key(&format!("{} samples / object", r.samples)));
        let series = plural(r.objects, "object");
        error
            .series(&series)
            .points
            .push(Point::new(r.z_error, r.tracking_ms, key));
        by_samples
            .series(&series)
            .points
            .push(Point::new(r.drawn as f64, r.tracking_ms, None));
    }
    fig.charts.push(error);
    if several(rows.iter().map(|r| r.drawn as f64)) {
        fig.charts.push(by_samples);
    }
    if !slides.is_empty() {
        let mut slide = Chart::new(
            ChartKind::SpeedError,
            "sliding against frame time, per tracker variant",
            "sliding, mean over the motions (px/frame)",
            "frame (ms, median over the motions)",
        );
        for (i, v) in sliding::VARIANTS.iter().enumerate() {
            let mean = slides.iter().map(|r| r.variants[i].tracked).sum::<f64>() / slides.len() as f64;
            let key = Some(fig.key(&format!("dynamic, {} × {}", v.weighting, v.samples)));
            slide
                .series("tracker variants")
                .points
                .push(Point::new(mean, sliding::frame_ms(slides, i), key));
        }
        fig.charts.push(slide);
    }
    fig
}

/// `npr bench artmaps`: build times against the source's pixels.
pub fn artmaps(build: &[bench_artmaps::BuildRow], subtitle: &str) -> Figure {
    let mut fig = Figure::new("npr bench artmaps: art-map and rip-map builds", subtitle);
    let mut by_size = Chart::new(
        ChartKind::CostSize,
        "build time against source pixels (cache bypassed)",
        "source pixels",
        "build (ms)",
    );
    for r in build {
        let px = f64::from(r.size) * f64::from(r.size);
        // The table's "rip ÷ art-map" divides by this sum: the art-map is
        // its mip chain and every level filtered.
        let artmap_ms = r.mip_ms + r.level_ms.iter().sum::<f64>();
        by_size
            .series(&format!("{}, art-map", r.filter))
            .points
            .push(Point::new(px, artmap_ms, None));
        by_size
            .series(&format!("{}, rip-map", r.filter))
            .points
            .push(Point::new(px, r.rip_ms, None));
    }
    if several(build.iter().map(|r| f64::from(r.size))) {
        fig.charts.push(by_size);
    } else {
        fig.notes
            .push("one source size: no cost-against-size chart (give --sizes A,B,…)".into());
    }
    fig.notes.push(
        "this command measures no error (tests/gpu/artmaps.rs asserts the reads' errors), so no speed-against-error chart; \
         the sampling table has one image size"
            .into(),
    );
    fig
}

/// `npr bench lines`: strips and classification against mesh edges, and
/// the methods' cost over their base against both errors.
pub fn lines(
    edges: &[bench_lines::EdgeRow],
    classify: &[bench_lines::ClassifyRow],
    methods: &[bench_lines::MethodRow],
    size: u32,
    subtitle: &str,
) -> Figure {
    let mut fig = Figure::new("npr bench lines: lines passes against edges, and against LSA", subtitle);
    let ms = "ms";
    let mut strips = Chart::new(ChartKind::CostSize, "strips against mesh edges", "mesh edges", ms);
    for r in edges {
        let x = r.mesh_edges as f64;
        for (name, s) in [
            ("strip build (rebuilt − reused prepare)", r.build_s),
            ("frame, strips rebuilt", r.frame_rebuilt_s),
            ("frame, strips reused", r.frame_reused_s),
        ] {
            strips.series(name).points.push(Point::new(x, s * 1e3, None));
        }
    }
    let mut classes = Chart::new(
        ChartKind::CostSize,
        "silhouette classification against mesh edges",
        "mesh edges",
        ms,
    );
    for r in classify {
        let x = r.mesh_edges as f64;
        for (name, s) in [
            ("CPU (EdgeMesh::silhouettes, f64)", r.cpu_s),
            ("compute pass + read-back", r.gpu_s),
            ("read-back alone", r.read_back_s),
        ] {
            classes.series(name).points.push(Point::new(x, s * 1e3, None));
        }
    }
    if several(edges.iter().map(|r| r.mesh_edges as f64)) {
        fig.charts.push(strips);
        fig.charts.push(classes);
    }
    let mut charts = accuracy_charts("cost over the base pass", "over its base pass (ms)", "");
    let series = format!("{size}²");
    for r in methods {
        let key = Some(fig.key(r.name));
        let cost = r.method_s * 1e3;
        charts[0]
            .series(&series)
            .points
            .push(Point::new(1.0 - r.min_precision, cost, key));
        charts[1]
            .series(&series)
            .points
            .push(Point::new(1.0 - r.min_recall, cost, key));
    }
    fig.charts.extend(charts);
    fig
}

#[cfg(test)]
mod tests {
    use super::*;

    fn contour_row(name: &str, size: u32, stage_ms: f64, accuracy: Option<(f64, f64, f64)>) -> bench_contours::Row {
        bench_contours::Row {
            name: name.into(),
            size,
            frame_s: stage_ms * 2e-3,
            image_stage_s: stage_ms * 1e-3,
            vs_passthrough: Some(1.0),
            accuracy,
        }
    }

    #[test]
    fn contours_plot_the_printed_columns() {
        let rows = [
            contour_row("passthrough", 64, 0.1, None),
            contour_row("LSA full", 64, 2.0, Some((0.9, 1.0, 0.5))),
            contour_row("passthrough", 128, 0.3, None),
            contour_row("LSA full", 128, 7.0, Some((0.95, 1.0, 1.0))),
        ];
        let fig = contours(&rows, "test");
        assert_eq!(fig.key, ["passthrough", "LSA full"]);
        assert_eq!(fig.charts.len(), 3, "two error charts and one against pixels");
        // False lines: 1 − precision, one series per size, only measured rows.
        let false_lines = &fig.charts[0];
        assert_eq!(false_lines.series.len(), 2);
        assert_eq!(false_lines.series[0].name, "64²");
        let p = false_lines.series[0].points[0];
        assert!(
            (p.x - 0.1).abs() < 1e-12 && (p.y - 2.0).abs() < 1e-12 && p.key == Some(1),
            "{p:?}"
        );
        // Missed lines: the worse of the two recalls.
        assert!((fig.charts[1].series[0].points[0].x - 0.5).abs() < 1e-12);
        // Against pixels: one line per method, its end labelled.
        let by_size = &fig.charts[2];
        assert_eq!(by_size.kind, ChartKind::CostSize);
        let lsa = &by_size.series[1];
        assert_eq!(lsa.points.iter().map(|p| p.x).collect::<Vec<_>>(), [4096.0, 16384.0]);
        assert_eq!(lsa.points.iter().map(|p| p.key).collect::<Vec<_>>(), [None, Some(1)]);
        // t_pass at its floor is not a measurement: left out (NaN).
        let floor = [
            contour_row("passthrough", 64, 1e-6, None),
            contour_row("passthrough", 128, 0.3, None),
        ];
        assert!(contours(&floor, "test").charts[2].series[0].points[0].y.is_nan());
        // One size: no chart against pixels.
        assert_eq!(contours(&rows[..2], "test").charts.len(), 2);
    }

    #[test]
    fn ops_notes_the_variants_without_an_error_model() {
        let rows = [
            bench_ops::Row {
                name: "plain",
                frame_s: 1e-3,
                vs_plain: 1.0,
                errors: Some((4.8, 22.8, 0.0)),
            },
            bench_ops::Row {
                name: "contour",
                frame_s: 4e-3,
                vs_plain: 4.0,
                errors: None,
            },
        ];
        let fig = ops(&rows, "test");
        assert_eq!(fig.charts.len(), 3);
        assert_eq!(fig.key, ["plain"]);
        assert!(fig.notes.iter().any(|n| n.contains("contour")), "{:?}", fig.notes);
        let xs: Vec<f64> = fig.charts.iter().map(|c| c.series[0].points[0].x).collect();
        assert_eq!(xs, [4.8, 22.8, 0.0]);
    }

    #[test]
    fn artmaps_sum_the_mip_chain_and_the_levels() {
        let row = |size, rip_ms| bench_artmaps::BuildRow {
            filter: "hatching".into(),
            size,
            levels: 2,
            mip_ms: 1.0,
            level_ms: vec![2.0, 3.0],
            rip_levels: 4,
            rip_ms,
        };
        let fig = artmaps(&[row(8, 10.0), row(16, 20.0)], "test");
        let chart = &fig.charts[0];
        assert_eq!(chart.series[0].name, "hatching, art-map");
        assert_eq!(chart.series[0].points[1], Point::new(256.0, 6.0, None));
        assert_eq!(chart.series[1].points[1], Point::new(256.0, 20.0, None));
        assert!(artmaps(&[row(8, 10.0)], "test").charts.is_empty());
    }
}
