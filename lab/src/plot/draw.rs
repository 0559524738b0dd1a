//! Draws a [`Figure`] with plotters' SVG backend: a header, the charts one
//! above the other, then the numbered key and the notes.
//!
//! Every point is a `<circle>` and nothing else is (legend swatches are
//! rectangles), which the tests count on. Labels of points that land
//! within a few pixels of each other are merged into one ("2,3,5"), since
//! variants of equal error and cost would otherwise print over each other.

use super::axis::{self, Scale};
use super::{Chart, ChartKind, Figure};
use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::sync::OnceLock;

const WIDTH: u32 = 960;
const HEADER: u32 = 56;
const CHART: u32 = 440;
const LINE: u32 = 17;

/// Text is measured with this font (plotters' `ab_glyph` feature needs one
/// registered; the SVG itself only names `sans-serif`). DejaVu Sans,
/// unmodified, under its own licence: `lab/assets/fonts/LICENSE-DejaVu`.
static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
const FAMILY: &str = "sans-serif";

fn register_font() -> Result<(), String> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            plotters::style::register_font(FAMILY, FontStyle::Normal, FONT)
                .map_err(|_| "the vendored font does not parse".to_string())
        })
        .clone()
}

/// Tableau 10: distinct in colour and in lightness, so series stay apart
/// in print too.
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// A legend names the series when there are a few; with more, a cost
/// against size chart labels each line's last point with its key number.
const MAX_LEGEND: usize = 8;

fn err<E: std::fmt::Debug>(e: E) -> String {
    format!("{e:?}")
}

pub(super) fn svg(figure: &Figure) -> Result<String, String> {
    register_font()?;
    let text_lines = (figure.key.len() + figure.notes.len()) as u32;
    let height = HEADER + CHART * figure.charts.len() as u32 + LINE * text_lines + 24;
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (WIDTH, height)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let (header, rest) = root.split_vertically(HEADER);
        header
            .draw_text(
                &figure.title,
                &(FAMILY, 20).into_font().style(FontStyle::Bold).color(&BLACK),
                (12, 8),
            )
            .map_err(err)?;
        header
            .draw_text(&figure.subtitle, &(FAMILY, 13).into_font().color(&BLACK), (12, 34))
            .map_err(err)?;
        let (charts, footer) = rest.split_vertically(CHART * figure.charts.len() as u32);
        for (area, chart) in charts
            .split_evenly((figure.charts.len().max(1), 1))
            .iter()
            .zip(&figure.charts)
        {
            draw_chart(area, chart)?;
        }
        let style = (FAMILY, 13).into_font().color(&BLACK);
        let lines = figure
            .key
            .iter()
            .enumerate()
            .map(|(i, name)| format!("{:>2}  {name}", i + 1))
            .chain(figure.notes.iter().cloned());
        for (i, line) in lines.enumerate() {
            footer
                .draw_text(&line, &style, (16, 8 + LINE as i32 * i as i32))
                .map_err(err)?;
        }
        root.present().map_err(err)?;
    }
    Ok(out)
}

/// One chart: its scales from its kind and values, then the points.
fn draw_chart<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, chart: &Chart) -> Result<(), String> {
    let xs: Vec<f64> = chart.series.iter().flat_map(|s| s.points.iter().map(|p| p.x)).collect();
    let ys: Vec<f64> = chart.series.iter().flat_map(|s| s.points.iter().map(|p| p.y)).collect();
    let (sx, sy) = match chart.kind {
        ChartKind::SpeedError => (axis::auto_scale(&xs), axis::auto_scale(&ys)),
        ChartKind::CostSize => (Scale::Log, Scale::Log),
    };
    let left_out = xs
        .iter()
        .zip(&ys)
        .filter(|(x, y)| !axis::drawable(**x, sx) || !axis::drawable(**y, sy))
        .count();
    let caption = if left_out > 0 {
        format!(
            "{} ({left_out} point(s) not drawn: ≤ 0 on a log axis, or not finite)",
            chart.title
        )
    } else {
        chart.title.clone()
    };
    let (x0, x1) = axis::range(&xs, sx);
    let (y0, y1) = axis::range(&ys, sy);
    let linear = |a: f64, b: f64| RangedCoordf64::from(a..b);
    let log = |a: f64, b: f64| LogCoord::from((a..b).log_scale());
    let scales = Scales { x: sx, y: sy };
    match (sx, sy) {
        (Scale::Linear, Scale::Linear) => draw_in(area, chart, &caption, scales, linear(x0, x1), linear(y0, y1)),
        (Scale::Log, Scale::Linear) => draw_in(area, chart, &caption, scales, log(x0, x1), linear(y0, y1)),
        (Scale::Linear, Scale::Log) => draw_in(area, chart, &caption, scales, linear(x0, x1), log(y0, y1)),
        (Scale::Log, Scale::Log) => draw_in(area, chart, &caption, scales, log(x0, x1), log(y0, y1)),
    }
}

/// The key numbers written next to points that land within 8 px of
/// `pixel`, at the first of them.
struct Label {
    pixel: (i32, i32),
    point: (f64, f64),
    keys: Vec<usize>,
    color: RGBColor,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Corner {
    UpperLeft,
    UpperRight,
    LowerLeft,
    LowerRight,
}

/// The corner of the plotting area (x in `xs`, y in `ys`, pixels, y down)
/// with the fewest `occupied` pixels in its 40% × 40% box, the first of
/// `preferred` on a tie: where the legend hides least.
fn emptiest_corner(
    occupied: &[(i32, i32)],
    (xs, ys): (std::ops::Range<i32>, std::ops::Range<i32>),
    preferred: [Corner; 4],
) -> Corner {
    let (w, h) = ((xs.end - xs.start) * 2 / 5, (ys.end - ys.start) * 2 / 5);
    let inside = |c: Corner, (x, y): (i32, i32)| {
        let left = x < xs.start + w;
        let right = x > xs.end - w;
        let top = y < ys.start + h;
        let bottom = y > ys.end - h;
        match c {
            Corner::UpperLeft => left && top,
            Corner::UpperRight => right && top,
            Corner::LowerLeft => left && bottom,
            Corner::LowerRight => right && bottom,
        }
    };
    let count = |c: Corner| occupied.iter().filter(|p| inside(c, **p)).count();
    // `min_by_key` keeps the first of equal counts: the preferred one.
    preferred.into_iter().min_by_key(|c| count(*c)).unwrap_or(preferred[0])
}

#[derive(Clone, Copy)]
struct Scales {
    x: Scale,
    y: Scale,
}

fn draw_in<DB, X, Y>(
    area: &DrawingArea<DB, Shift>,
    chart: &Chart,
    caption: &str,
    scales: Scales,
    x: X,
    y: Y,
) -> Result<(), String>
where
    DB: DrawingBackend,
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let scale_name = |s: Scale| if s == Scale::Log { ", log" } else { "" };
    let mut ctx = ChartBuilder::on(area)
        .caption(caption, (FAMILY, 16))
        .margin(12)
        // Room for the key numbers of points at the right edge.
        .margin_right(72)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(x, y)
        .map_err(err)?;
    let tick = |s: Scale| match s {
        Scale::Linear => |v: &f64| axis::tick(*v),
        Scale::Log => |v: &f64| axis::log_tick(*v),
    };
    let (x_tick, y_tick) = (tick(scales.x), tick(scales.y));
    ctx.configure_mesh()
        .x_desc(format!("{}{}", chart.x_label, scale_name(scales.x)))
        .y_desc(format!("{}{}", chart.y_label, scale_name(scales.y)))
        .x_label_formatter(&x_tick)
        .y_label_formatter(&y_tick)
        .label_style((FAMILY, 12))
        .axis_desc_style((FAMILY, 13))
        // No minor grid: on a log axis it packs into grey bands near each decade.
        .light_line_style(TRANSPARENT)
        .bold_line_style(RGBColor(210, 210, 210))
        .draw()
        .map_err(err)?;
    let legend = (2..=MAX_LEGEND).contains(&chart.series.len());
    let on_axes = |p: &&super::Point| axis::drawable(p.x, scales.x) && axis::drawable(p.y, scales.y);
    let mut labels: Vec<Label> = Vec::new();
    // Where markers and lines are, in pixels, for the legend's corner.
    let mut occupied: Vec<(i32, i32)> = Vec::new();
    for (i, series) in chart.series.iter().enumerate() {
        let color = PALETTE[i % PALETTE.len()];
        let points: Vec<(f64, f64)> = series.points.iter().filter(on_axes).map(|p| (p.x, p.y)).collect();
        let pixels: Vec<(i32, i32)> = points.iter().map(|p| ctx.backend_coord(p)).collect();
        occupied.extend(&pixels);
        if chart.kind == ChartKind::CostSize {
            for w in pixels.windows(2) {
                occupied
                    .extend((1..8).map(|k| (w[0].0 + (w[1].0 - w[0].0) * k / 8, w[0].1 + (w[1].1 - w[0].1) * k / 8)));
            }
        }
        if chart.kind == ChartKind::CostSize && points.len() > 1 {
            ctx.draw_series(LineSeries::new(points.iter().copied(), color.stroke_width(2)))
                .map_err(err)?;
        }
        let drawn = ctx
            .draw_series(points.iter().map(|p| Circle::new(*p, 4, color.filled())))
            .map_err(err)?;
        if legend {
            drawn
                .label(series.name.clone())
                .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 14, y + 5)], color.filled()));
        }
        for p in series.points.iter().filter(on_axes) {
            let Some(key) = p.key else { continue };
            let at = ctx.backend_coord(&(p.x, p.y));
            match labels
                .iter_mut()
                .find(|l| (l.pixel.0 - at.0).abs() <= 8 && (l.pixel.1 - at.1).abs() <= 8)
            {
                Some(l) => l.keys.push(key),
                None => labels.push(Label {
                    pixel: at,
                    point: (p.x, p.y),
                    keys: vec![key],
                    color,
                }),
            }
        }
    }
    // In the colour of the (first) point's series: told apart from the
    // black tick labels by eye, and by the tests.
    for mut l in labels {
        l.keys.sort_unstable();
        l.keys.dedup();
        let text = l.keys.iter().map(|k| (k + 1).to_string()).collect::<Vec<_>>().join(",");
        let style = (FAMILY, 12).into_font().color(&l.color);
        ctx.draw_series(std::iter::once(
            EmptyElement::at(l.point) + Text::new(text, (6, -16), style),
        ))
        .map_err(err)?;
    }
    if legend {
        let (xs, ys) = ctx.plotting_area().get_pixel_range();
        let preferred = match chart.kind {
            // The costly, inaccurate corner is the one most often empty.
            ChartKind::SpeedError => [
                Corner::UpperRight,
                Corner::UpperLeft,
                Corner::LowerRight,
                Corner::LowerLeft,
            ],
            // Lines rise to the right: the upper left is most often free.
            ChartKind::CostSize => [
                Corner::UpperLeft,
                Corner::LowerRight,
                Corner::UpperRight,
                Corner::LowerLeft,
            ],
        };
        let position = match emptiest_corner(&occupied, (xs, ys), preferred) {
            Corner::UpperLeft => SeriesLabelPosition::UpperLeft,
            Corner::UpperRight => SeriesLabelPosition::UpperRight,
            Corner::LowerLeft => SeriesLabelPosition::LowerLeft,
            Corner::LowerRight => SeriesLabelPosition::LowerRight,
        };
        ctx.configure_series_labels()
            .position(position)
            .label_font((FAMILY, 12))
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(160, 160, 160))
            .draw()
            .map_err(err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::{Chart, ChartKind, Figure, Point};
    use super::svg;

    /// The SVG parsed as XML.
    struct Parsed {
        /// Point markers.
        circles: usize,
        /// Every text.
        texts: Vec<String>,
        /// The texts next to points (in a series' colour, not black).
        labels: Vec<String>,
    }

    fn parsed(figure: &Figure) -> Parsed {
        let text = svg(figure).expect("drawn");
        let doc = roxmltree::Document::parse(&text).unwrap_or_else(|e| panic!("not XML: {e}\n{text}"));
        let named = |name: &'static str| doc.descendants().filter(move |n| n.tag_name().name() == name);
        let content = |n: roxmltree::Node| n.text().unwrap_or("").trim().to_string();
        Parsed {
            circles: named("circle").count(),
            texts: named("text").map(content).collect(),
            labels: named("text")
                .filter(|n| n.attribute("fill") != Some("#000000"))
                .map(content)
                .collect(),
        }
    }

    fn speed_error() -> Figure {
        let mut fig = Figure::new("Title <&>", "device");
        let mut chart = Chart::new(ChartKind::SpeedError, "cost against error", "error", "ms");
        for (name, series, x, y) in [
            ("fast & rough", "64²", 0.4, 1.0),
            ("slow <exact>", "64²", 0.01, 8.0),
            ("middle", "128²", 0.1, 3.0),
        ] {
            let key = Some(fig.key(name));
            chart.series(series).points.push(Point::new(x, y, key));
        }
        fig.charts.push(chart);
        fig
    }

    #[test]
    fn one_marker_and_one_label_per_point_and_every_name_in_the_key() {
        let Parsed { circles, texts, labels } = parsed(&speed_error());
        assert_eq!(circles, 3, "{texts:?}");
        assert_eq!(labels, ["1", "2", "3"]);
        for line in ["1  fast & rough", "2  slow <exact>", "3  middle"] {
            assert!(texts.iter().any(|t| t == line), "{line}: {texts:?}");
        }
        // Two series: a legend names them; the title survives escaping.
        for name in ["64²", "128²", "Title <&>", "cost against error"] {
            assert!(texts.iter().any(|t| t == name), "{name}: {texts:?}");
        }
        // Error spans 40×: a log axis, and the axis says so.
        assert!(texts.iter().any(|t| t == "error, log"), "{texts:?}");
        assert!(texts.iter().any(|t| t == "ms"), "8× in cost stays linear: {texts:?}");
    }

    #[test]
    fn points_on_the_same_spot_share_one_label() {
        let mut fig = Figure::new("t", "s");
        let mut chart = Chart::new(ChartKind::SpeedError, "c", "error", "ms");
        for name in ["a", "b"] {
            let key = Some(fig.key(name));
            chart.series("all").points.push(Point::new(0.3, 2.0, key));
        }
        let key = Some(fig.key("c"));
        chart.series("all").points.push(Point::new(0.9, 5.0, key));
        fig.charts.push(chart);
        let Parsed { circles, texts, labels } = parsed(&fig);
        assert_eq!(circles, 3);
        assert_eq!(labels, ["1,2", "3"]);
        // One series: no legend.
        assert!(!texts.iter().any(|t| t == "all"), "{texts:?}");
    }

    #[test]
    fn a_cost_of_zero_is_left_off_a_log_chart_and_counted() {
        let mut fig = Figure::new("t", "s");
        let mut chart = Chart::new(ChartKind::CostSize, "cost against pixels", "pixels", "ms");
        for (px, ms) in [(4096.0, 0.0), (16384.0, 2.0), (65536.0, 9.0)] {
            chart.series("method").points.push(Point::new(px, ms, None));
        }
        chart.series("other").points.push(Point::new(65536.0, f64::NAN, None));
        fig.charts.push(chart);
        let Parsed { circles, texts, labels } = parsed(&fig);
        assert_eq!(circles, 2, "{texts:?}");
        assert!(labels.is_empty(), "no key on these points: {labels:?}");
        assert!(
            texts
                .iter()
                .any(|t| t.starts_with("cost against pixels (2 point(s) not drawn")),
            "{texts:?}"
        );
        assert!(texts.iter().any(|t| t == "pixels, log") && texts.iter().any(|t| t == "ms, log"));
    }

    #[test]
    fn the_legend_goes_to_the_emptiest_corner() {
        use super::{emptiest_corner, Corner::*};
        let area = (0..100, 0..100);
        let order = [UpperRight, UpperLeft, LowerRight, LowerLeft];
        // Nothing anywhere: the first preferred.
        assert_eq!(emptiest_corner(&[], area.clone(), order), UpperRight);
        // Upper right taken (y grows downward): the next free one.
        assert_eq!(emptiest_corner(&[(90, 5)], area.clone(), order), UpperLeft);
        // Every corner taken, the lower left least.
        let taken = [(90, 5), (90, 6), (5, 5), (5, 6), (95, 95), (96, 95), (5, 95)];
        assert_eq!(emptiest_corner(&taken, area, order), LowerLeft);
    }

    #[test]
    fn degenerate_figures_still_draw() {
        // One point, a figure of equal points, a chart with nothing drawable,
        // and a figure with no chart at all.
        let mut fig = Figure::new("t", "s");
        let mut one = Chart::new(ChartKind::SpeedError, "one", "error", "ms");
        one.series("s").points.push(Point::new(0.0, 0.0, Some(0)));
        fig.key("only");
        let mut equal = Chart::new(ChartKind::CostSize, "equal", "px", "ms");
        for _ in 0..3 {
            equal.series("s").points.push(Point::new(100.0, 1.0, None));
        }
        let mut none = Chart::new(ChartKind::CostSize, "none", "px", "ms");
        none.series("s").points.push(Point::new(0.0, -1.0, None));
        fig.charts.extend([one, equal, none]);
        let Parsed { circles, labels, .. } = parsed(&fig);
        assert_eq!(circles, 4);
        assert_eq!(labels, ["1"]);
        let mut empty = Figure::new("t", "s");
        empty.notes.push("nothing measured".into());
        let Parsed { circles, texts, .. } = parsed(&empty);
        assert_eq!(circles, 0);
        assert!(texts.iter().any(|t| t == "nothing measured"));
    }
}
