//! `npr bench … --plot PATH.svg` and `npr test --bench --plot`: the benchmarks' figures drawn as SVG with
//! plotters, from the same rows the command prints (no second measurement).
//!
//! One model for every benchmark: a [`Figure`] is a stack of [`Chart`]s
//! and a numbered key; a chart is either speed against error (one point
//! per variant, each labelled with its key number) or cost against size
//! (one line per method, log–log). `figures.rs` fills it per benchmark,
//! `draw.rs` draws it, `axis.rs` decides the axes. Text is measured with
//! the vendored DejaVu Sans (plotters' `ab_glyph` feature), so nothing
//! asks the system for fonts; the SVG names `sans-serif` and the viewer
//! renders it.

mod axis;
mod draw;
pub mod figures;

use npr_diag::{codes, Diagnostic};
use std::path::Path;

/// Everything one `--plot` file shows.
#[derive(Debug, Clone, Default)]
pub struct Figure {
    pub title: String,
    /// The device and how the figures were taken.
    pub subtitle: String,
    pub charts: Vec<Chart>,
    /// Names behind the key numbers the points are labelled with (1-based
    /// on the figure, 0-based in [`Point::key`]).
    pub key: Vec<String>,
    /// Lines under the key: what is not drawn and why.
    pub notes: Vec<String>,
}

impl Figure {
    pub fn new(title: impl Into<String>, subtitle: impl Into<String>) -> Self {
        Figure {
            title: title.into(),
            subtitle: subtitle.into(),
            ..Default::default()
        }
    }

    /// The key index of `name`, added on first use, so a variant measured
    /// at several sizes has one number.
    pub fn key(&mut self, name: &str) -> usize {
        match self.key.iter().position(|k| k == name) {
            Some(i) => i,
            None => {
                self.key.push(name.to_string());
                self.key.len() - 1
            }
        }
    }
}

/// The two kinds of chart.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ChartKind {
    /// x: an error the benchmark reports, y: a cost; each axis linear or
    /// logarithmic by `axis::auto_scale`; points only.
    SpeedError,
    /// x: a size (pixels, edges, samples), y: a cost; log–log, each series
    /// a line through its points in the order given.
    CostSize,
}

#[derive(Debug, Clone)]
pub struct Chart {
    pub kind: ChartKind,
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
}

impl Chart {
    pub fn new(kind: ChartKind, title: &str, x_label: &str, y_label: &str) -> Self {
        Chart {
            kind,
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
        }
    }

    /// The series named `name`, added on first use.
    pub fn series(&mut self, name: &str) -> &mut Series {
        let i = match self.series.iter().position(|s| s.name == name) {
            Some(i) => i,
            None => {
                self.series.push(Series {
                    name: name.into(),
                    points: Vec::new(),
                });
                self.series.len() - 1
            }
        };
        &mut self.series[i]
    }
}

/// A group of points drawn in one colour: a size in a speed-against-error
/// chart, a method in a cost-against-size chart.
#[derive(Debug, Clone)]
pub struct Series {
    pub name: String,
    pub points: Vec<Point>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    pub x: f64,
    pub y: f64,
    /// The key entry written next to the point, if any.
    pub key: Option<usize>,
}

impl Point {
    pub fn new(x: f64, y: f64, key: Option<usize>) -> Self {
        Point { x, y, key }
    }
}

/// The figure as SVG text.
pub fn render_svg(figure: &Figure) -> Result<String, String> {
    draw::svg(figure)
}

/// Refuses a `--plot` path before the benchmark runs (minutes may pass
/// before it would be written): it must end in `.svg`, and its directory
/// must exist (the atomic writer would create it, and a typo would then
/// leave a new directory behind). E0503, as for any output.
pub fn check_path(path: &Path) -> Result<(), Diagnostic> {
    let is_svg = path
        .extension()
        .is_some_and(|e| e.to_string_lossy().eq_ignore_ascii_case("svg"));
    if !is_svg {
        return Err(Diagnostic::error(
            codes::CANNOT_WRITE,
            format!("cannot write plot {}: a plot is an SVG file", path.display()),
        )
        .with_help("name the file `….svg`"));
    }
    if path.is_dir() {
        return Err(Diagnostic::error(
            codes::CANNOT_WRITE,
            format!("cannot write plot {}: it is a directory", path.display()),
        )
        .with_help("name a file in it, e.g. `plot.svg`"));
    }
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !dir.is_dir() {
        return Err(Diagnostic::error(
            codes::CANNOT_WRITE,
            format!(
                "cannot write plot {}: directory {} does not exist",
                path.display(),
                dir.display()
            ),
        )
        .with_help("create the directory first, or name a file in an existing one"));
    }
    Ok(())
}

/// Draws `figure` and writes it to `path` atomically (temp file, fsync,
/// rename: `npr_runner::output::write_atomic`). A figure that cannot be
/// drawn is npr's fault (E9001, `codes::INTERNAL`); a path that cannot be
/// written is E0503.
pub fn write(figure: &Figure, path: &Path) -> Result<(), Diagnostic> {
    // Drawing numbers the bench produced cannot fail on the user's input.
    let svg = render_svg(figure)
        .map_err(|e| Diagnostic::error(codes::INTERNAL, format!("the plot could not be drawn: {e}")))?;
    npr_runner::output::write_atomic(path, svg.as_bytes()).map_err(|e| npr_diag::writes::cannot_write(path, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plot_path_must_be_an_svg_in_an_existing_directory() {
        let dir = std::env::temp_dir().join(format!("npr-plot-path-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        assert!(check_path(&dir.join("a.svg")).is_ok());
        assert!(check_path(&dir.join("a.SVG")).is_ok());
        for (bad, says) in [
            (dir.join("a.png"), "a plot is an SVG file"),
            (dir.join("a"), "a plot is an SVG file"),
            (dir.join("missing/a.svg"), "does not exist"),
        ] {
            let e = check_path(&bad).expect_err("refused");
            assert_eq!(e.code, codes::CANNOT_WRITE);
            assert!(e.message.contains(says), "{bad:?}: {}", e.message);
        }
        let as_dir = dir.join("d.svg");
        std::fs::create_dir_all(&as_dir).expect("dir named .svg");
        assert!(check_path(&as_dir)
            .expect_err("a directory")
            .message
            .contains("is a directory"));
        // A bare file name is in the working directory, which exists.
        assert!(check_path(Path::new("plot.svg")).is_ok());
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_name_keeps_its_key_number() {
        let mut f = Figure::new("t", "s");
        assert_eq!((f.key("a"), f.key("b"), f.key("a")), (0, 1, 0));
        let mut c = Chart::new(ChartKind::CostSize, "c", "x", "y");
        c.series("one").points.push(Point::new(1.0, 1.0, None));
        c.series("one").points.push(Point::new(2.0, 2.0, None));
        c.series("two");
        assert_eq!(c.series.len(), 2);
        assert_eq!(c.series[0].points.len(), 2);
    }
}
