//! Reading a style's test file, `<style>.tests.toml` beside `<style>.npr`:
//! an optional `[defaults]` table and one `[[test]]` table per test.
//!
//! ```toml
//! [defaults]
//! size = "192x192"
//! per_pixel = { max = 2, outliers = 0.005 }
//!
//! [[test]]
//! name = "spot"
//! scene = "scenes/spot.toml"
//! set = { bands = 5 }
//! golden = "golden/toon_spot.png"
//! flip = { mean = 0.01, p99 = 0.3 }
//! sweep = true        # also sweep every parameter's range on this scene
//! # frames = "0..12" and flicker = 0.02: the mean change between frames
//! # coherence = { flicker = 0.02, sliding = 0.3, popping = 0.1 }: the same,
//! #   warped by the scene's motion (a moving camera too), and more
//! budget = 40         # the frame at most 40× a passthrough, timed in the run
//! variants = { fast = { samples = 4 }, exact = { samples = 64 } }
//! reference = "exact" # `npr test --bench`: each variant's cost against its FLIP
//! ```
//!
//! The file is read from toml's spanned tree with the scene reader's field
//! helpers (`npr_runner::scene::toml_fields`), so every problem in it is an
//! E0407 that points at the key or value, all of them reported at once.
//! `set` values are kept as the text `--set` would take: they are typed
//! against the compiled style's parameters when the test runs. The values
//! inside fields (`set`, `variants`, `flip`, `per_pixel`, `coherence`)
//! are `values.rs`. Just over 600 lines: the declared test's types and the
//! one reading of `[defaults]` merged into each `[[test]]`; the next field
//! should move the types into their own module.

mod values;

use npr_diag::{codes, Diagnostic, FileId, SourceMap, Span};
use npr_runner::scene::toml_fields::{At, Fields, Report};
use std::path::{Path, PathBuf};
use toml::de::DeTable;
use values::{coherence_bound, flip_bound, per_pixel_bound, set_entries, variants};

/// The file name suffix that makes a TOML file a style's tests.
pub const SUFFIX: &str = ".tests.toml";

/// The image size of a test that gives none: small, since tests render on
/// a software rasterizer.
const DEFAULT_SIZE: (u32, u32) = (256, 256);

/// One `<style>.tests.toml`, read and checked.
#[derive(Debug, Clone)]
pub struct TestFile {
    /// `<style>.npr` beside it.
    pub style: PathBuf,
    /// The file's text alone (its `FileId` is the one every span of its
    /// tests carries): each test's diagnostics render against a copy.
    pub sources: SourceMap,
    pub tests: Vec<TestDecl>,
}

/// One `[[test]]`, with the `[defaults]` filled in.
#[derive(Debug, Clone)]
pub struct TestDecl {
    pub name: At<String>,
    pub scene: At<PathBuf>,
    pub size: (u32, u32),
    pub when: When,
    pub fps: f64,
    pub eye: At<u32>,
    /// `set = { name = value }`: each name and its value as `--set` text.
    pub sets: Vec<(At<String>, At<String>)>,
    pub golden: Option<Golden>,
    pub may_be_blank: bool,
    /// `sweep = true`: also sweep every parameter's range on this test's
    /// scene, size and frames (`sweep/`).
    pub sweep: bool,
    /// `flicker = 0.02`: over `frames`, with a still camera, the mean
    /// absolute change of the output between consecutive frames (channels
    /// in 0..1) stays at or under this.
    pub flicker: Option<At<f64>>,
    /// `coherence = { … }`: over `frames`, bounds on the temporal coherence
    /// measures against the scene's exact motion (`coherence.rs`).
    pub coherence: Option<At<CoherenceBound>>,
    /// `budget = 40`: the frame costs at most this many times a
    /// passthrough measured in the same run (`budget.rs`).
    pub budget: Option<At<f64>>,
    /// `variants = { fast = { samples = 4 }, exact = { samples = 64 } }`:
    /// parameter sets over the test's own, compared by `npr test --bench`.
    pub variants: Vec<Variant>,
    /// Which variant the others' FLIP is against (`reference = "exact"`;
    /// the first by default): an index into `variants`.
    pub reference: usize,
}

/// One named parameter set of a test, over the test's `set`.
#[derive(Debug, Clone)]
pub struct Variant {
    pub name: At<String>,
    pub sets: Vec<(At<String>, At<String>)>,
}

/// Which frame (or frames) a test renders.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum When {
    /// `time = t` (seconds) or `frame = n` (at `fps`).
    At { time_s: f64 },
    /// `frames = "A..B"`: every frame is checked, the last one compared with the golden.
    Range { start: u32, end: u32 },
}

/// Bounds on the temporal coherence measures; each is checked when given.
#[derive(Debug, Clone, PartialEq)]
pub struct CoherenceBound {
    /// Motion-compensated flicker: the mean change of a channel (0..1).
    pub flicker: Option<f64>,
    /// Pattern sliding against the surface, px per frame.
    pub sliding: Option<f64>,
    /// The share of marks that appear or vanish per frame (0..1).
    pub popping: Option<f64>,
    pub marks: Marks,
}

/// Which pixels are marks (strokes, dots, foam shapes) for popping.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marks {
    /// Darker than mid grey (ink on paper).
    Dark,
    /// Lighter than mid grey (foam, highlights).
    Light,
}

/// `golden = "file.png"` and the tolerance it is compared with.
#[derive(Debug, Clone)]
pub struct Golden {
    pub path: At<PathBuf>,
    pub flip: Option<FlipBound>,
    pub per_pixel: Option<PerPixelBound>,
}

/// `flip = { mean = .., p95 = .., p99 = .. }`: bounds on the FLIP error map.
#[derive(Debug, Clone, PartialEq)]
pub struct FlipBound {
    pub mean: Option<f64>,
    /// (percentile, bound): the error that `percentile` % of pixels stay under.
    pub percentiles: Vec<(f64, f64)>,
}

/// `per_pixel = { max = 2, outliers = 0.005 }`: every channel within `max`
/// levels of 255, except a share `outliers` of the pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PerPixelBound {
    pub max: u8,
    pub outliers: f64,
}

/// The percentile keys `flip` takes.
const PERCENTILES: [(&str, f64); 4] = [("p50", 50.0), ("p90", 90.0), ("p95", 95.0), ("p99", 99.0)];

/// `time`, `frame` or `frames` as written: a frame becomes a time once
/// `fps` is known.
#[derive(Debug, Clone, Copy)]
enum WhenDecl {
    Time(f64),
    Frame(u32),
    Frames(u32, u32),
}

/// What a `[[test]]` or `[defaults]` table says, before the two are merged.
#[derive(Debug, Clone, Default)]
struct Partial {
    scene: Option<At<String>>,
    size: Option<(u32, u32)>,
    when: Option<WhenDecl>,
    fps: Option<f64>,
    eye: Option<At<u32>>,
    sets: Vec<(At<String>, At<String>)>,
    flip: Option<FlipBound>,
    per_pixel: Option<PerPixelBound>,
    may_be_blank: Option<bool>,
    sweep: Option<bool>,
    flicker: Option<At<f64>>,
    coherence: Option<At<CoherenceBound>>,
    budget: Option<At<f64>>,
}

/// The style a test file is for: `x.tests.toml` → `x.npr`.
pub fn style_of(test_file: &Path) -> Option<PathBuf> {
    let name = test_file.file_name()?.to_str()?;
    let stem = name.strip_suffix(SUFFIX)?;
    Some(test_file.with_file_name(format!("{stem}.npr")))
}

/// The test file of a style: `x.npr` → `x.tests.toml`.
pub fn tests_of(style: &Path) -> PathBuf {
    let stem = style
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    style.with_file_name(format!("{stem}{SUFFIX}"))
}

/// Read and check `path`; every problem found is returned at once, with
/// the sources to render them against.
pub fn read(path: &Path) -> Result<TestFile, (Vec<Diagnostic>, SourceMap)> {
    let mut sources = SourceMap::new();
    let bytes = match read_bounded(path) {
        Ok(b) => b,
        Err(why) => {
            let d = Diagnostic::error(
                codes::BAD_TEST_FILE,
                format!("cannot read test file {}: {why}", path.display()),
            )
            .with_help("a style's tests are in `<style>.tests.toml` beside it");
            return Err((vec![d], sources));
        }
    };
    let (file, text) = match npr_diag::text::add_utf8(&mut sources, &path.display().to_string(), bytes) {
        Ok(read) => read,
        Err(d) => return Err((vec![d], sources)),
    };
    check(path, file, &text, sources)
}

/// [`read`] of a text already in memory (the language server's buffer).
pub fn read_text(path: &Path, text: &str) -> Result<TestFile, (Vec<Diagnostic>, SourceMap)> {
    let mut sources = SourceMap::new();
    let file = sources.add(path.display().to_string(), text.to_string());
    check(path, file, text, sources)
}

fn check(path: &Path, file: FileId, text: &str, sources: SourceMap) -> Result<TestFile, (Vec<Diagnostic>, SourceMap)> {
    let style = style_of(path).unwrap_or_else(|| path.with_extension("npr"));
    let mut report = Report {
        file,
        code: codes::BAD_TEST_FILE,
        diagnostics: Vec::new(),
        paths: None,
    };
    if !style.is_file() {
        report.bad_scene(
            Span::new(file, 0, 0),
            format!(
                "{} has no style beside it: {} does not exist",
                path.display(),
                style.display()
            ),
            "the tests of this file are for that style",
            "name the test file after its style: `toon.tests.toml` tests `toon.npr`",
        );
    }
    let tests = parse(text, file, path.parent().unwrap_or(Path::new(".")), &mut report);
    if report.has_errors() {
        let mut diagnostics = report.diagnostics;
        diagnostics.sort_by_key(|d| d.primary_span().map_or(0, |s| s.start));
        return Err((diagnostics, sources));
    }
    Ok(TestFile { style, sources, tests })
}

/// A test file is small: read at most a scene file's limit, so a path to
/// `/dev/zero` is refused rather than read for ever.
fn read_bounded(path: &Path) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let limit = npr_diag::limits::MAX_SCENE_BYTES;
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(limit as u64 + 1).read_to_end(&mut bytes))
        .map_err(|e| e.to_string())?;
    if bytes.len() > limit {
        return Err(format!("it is larger than {limit} bytes"));
    }
    Ok(bytes)
}

fn parse(text: &str, file: FileId, dir: &Path, report: &mut Report) -> Vec<TestDecl> {
    let document = match DeTable::parse(text) {
        Ok(d) => d,
        Err(err) => {
            let range = err.span().unwrap_or(0..0);
            report.push(
                Diagnostic::error(
                    codes::BAD_TEST_FILE,
                    format!("malformed test file: {}", err.message().trim()),
                )
                .with_primary(
                    Span::new(file, range.start.min(text.len()), range.end.min(text.len())),
                    "TOML syntax error",
                )
                .with_help("a test file is TOML (https://toml.io): `[[test]]` tables, see `npr explain E0407`"),
            );
            return Vec::new();
        }
    };
    let mut root = Fields::new(document.get_ref(), Span::new(file, 0, 0), "the test file");
    let defaults = root
        .table("defaults", "[defaults]", report)
        .map(|fields| partial(fields, dir, report))
        .unwrap_or_default();
    let tables = root.tables("test", |i| format!("test #{}", i + 1), report);
    if tables.is_empty() && root.span_of("test", report).is_none() {
        report.bad_scene(
            root.header(),
            "the test file declares no test",
            "no `[[test]]` table",
            "add a `[[test]]` table with `name` and `scene`",
        );
    }
    let mut tests: Vec<TestDecl> = Vec::new();
    for mut fields in tables {
        let name = test_name(&mut fields, report);
        if let Some(n) = &name {
            fields.set_context(format!("test `{}`", n.value));
        }
        let golden = fields.string("golden", report);
        let (variants, reference) = variants(&mut fields, report);
        let own = partial_fields(&mut fields, dir, report);
        let header = fields.header();
        fields.finish(report);
        let Some(name) = name else { continue };
        if let Some(first) = tests.iter().find(|t| t.name.value == name.value) {
            report.push(
                Diagnostic::error(codes::BAD_TEST_FILE, format!("two tests are named `{}`", name.value))
                    .with_primary(name.span, "a second test of this name")
                    .with_secondary(first.name.span, "the first")
                    .with_help("give each test its own name: it names its images and its line in reports"),
            );
            continue;
        }
        if let Some(mut t) = merge(name, own, &defaults, golden, dir, header, report) {
            t.variants = variants;
            t.reference = reference;
            tests.push(t);
        }
    }
    root.finish(report);
    tests
}

/// `name`: required, and safe as a file name (it names the test's images).
fn test_name(fields: &mut Fields, report: &mut Report) -> Option<At<String>> {
    let Some(name) = fields.string("name", report) else {
        if fields.span_of("name", report).is_none() {
            fields.missing("name", "name = \"spot\"", report);
        }
        return None;
    };
    let ok = !name.value.is_empty()
        && name
            .value
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'));
    if !ok {
        report.bad_scene(
            name.span,
            format!("`{}` is not a test name", name.value),
            "letters, digits, `_`, `-` and `.` only",
            "a test's name names its images on disk, e.g. `name = \"spot_bands_5\"`",
        );
        return None;
    }
    Some(name)
}

fn partial(mut fields: Fields, dir: &Path, report: &mut Report) -> Partial {
    let p = partial_fields(&mut fields, dir, report);
    fields.finish(report);
    p
}

/// The fields `[defaults]` and `[[test]]` share.
fn partial_fields(fields: &mut Fields, dir: &Path, report: &mut Report) -> Partial {
    let mut p = Partial {
        scene: fields.string("scene", report),
        ..Partial::default()
    };
    if let Some(scene) = &p.scene {
        let path = dir.join(&scene.value);
        if !path.is_file() {
            report.bad_scene(
                scene.span,
                format!("scene file {} does not exist", path.display()),
                "no such file",
                "a test's scene is a path relative to the test file",
            );
        }
    }
    if let Some(size) = fields.string("size", report) {
        match npr_diag::sizes::parse_size(&size.value) {
            Ok(s) if npr_diag::sizes::check_size(s).is_ok() => p.size = Some(s),
            Ok(_) => report.bad_scene(
                size.span,
                format!("size `{}` is larger than the limit", size.value),
                "too large",
                format!("an image is at most {0}x{0}", npr_diag::limits::MAX_OUTPUT_SIZE),
            ),
            Err(why) => report.bad_scene(
                size.span,
                format!("bad size `{}`: {why}", size.value),
                "expected WIDTHxHEIGHT",
                "write e.g. `size = \"192x192\"`",
            ),
        }
    }
    p.when = when(fields, report);
    if let Some(fps) = fields.number("fps", report) {
        if fps.value > 0.0 {
            p.fps = Some(fps.value);
        } else {
            report.bad_scene(
                fps.span,
                "`fps` must be above 0",
                "not a frame rate",
                "24 is the default",
            );
        }
    }
    if let Some(eye) = fields.integer("eye", report) {
        match u32::try_from(eye.value) {
            Ok(e @ (0 | 1)) => {
                p.eye = Some(At {
                    value: e,
                    span: eye.span,
                })
            }
            _ => report.bad_scene(
                eye.span,
                format!("eye {} does not exist", eye.value),
                "expected 0 or 1",
                "eyes are 0 (left, or mono) and 1 (right, stereo cameras)",
            ),
        }
    }
    if let Some(set) = fields.table("set", "`set`", report) {
        p.sets = set_entries(set, report);
    }
    if let Some(flip) = fields.table("flip", "`flip`", report) {
        p.flip = flip_bound(flip, report);
    }
    if let Some(per_pixel) = fields.table("per_pixel", "`per_pixel`", report) {
        p.per_pixel = per_pixel_bound(per_pixel, report);
    }
    p.may_be_blank = fields.boolean("may_be_blank", report).map(|b| b.value);
    p.sweep = fields.boolean("sweep", report).map(|b| b.value);
    if let Some(f) = fields.number("flicker", report) {
        if (0.0..=1.0).contains(&f.value) {
            p.flicker = Some(f);
        } else {
            report.bad_scene(
                f.span,
                format!("`flicker` must be from 0 to 1, not {}", f.value),
                "outside 0..1",
                "`flicker` bounds the mean change of a channel (0..1) from one frame to the next",
            );
        }
    }
    if let Some(c) = fields.table("coherence", "`coherence`", report) {
        p.coherence = coherence_bound(c, report);
    }
    if let Some(b) = fields.number("budget", report) {
        if b.value > 0.0 && b.value.is_finite() {
            p.budget = Some(b);
        } else {
            report.bad_scene(
                b.span,
                format!("`budget` must be above 0, not {}", b.value),
                "not a ratio",
                "`budget = 40`: the frame costs at most 40 times a passthrough pass",
            );
        }
    }
    p
}

/// `time`, `frame` or `frames`: at most one of them.
fn when(fields: &mut Fields, report: &mut Report) -> Option<WhenDecl> {
    let time = fields.number("time", report);
    let frame = fields.integer("frame", report);
    let frames = fields.string("frames", report);
    let given: Vec<Span> = [
        time.as_ref().map(|t| t.span),
        frame.as_ref().map(|f| f.span),
        frames.as_ref().map(|f| f.span),
    ]
    .into_iter()
    .flatten()
    .collect();
    if given.len() > 1 {
        report.bad_scene(
            given[1],
            "a test renders at one `time`, one `frame` or over `frames`, not several",
            "a second one",
            "keep one of `time`, `frame` and `frames`",
        );
        return None;
    }
    if let Some(t) = time {
        return Some(WhenDecl::Time(t.value));
    }
    if let Some(f) = frame {
        if f.value < 0 || f.value > i64::from(npr_diag::limits::MAX_FRAMES) {
            report.bad_scene(
                f.span,
                format!("frame {} is outside 0..{}", f.value, npr_diag::limits::MAX_FRAMES),
                "no such frame",
                "frames count from 0",
            );
            return None;
        }
        return Some(WhenDecl::Frame(f.value as u32));
    }
    let f = frames?;
    match npr_diag::sizes::parse_frames(&f.value) {
        Ok((start, end)) if end - start <= npr_diag::limits::MAX_FRAMES => Some(WhenDecl::Frames(start, end)),
        Ok(_) => {
            report.bad_scene(
                f.span,
                format!("`{}` is more than {} frames", f.value, npr_diag::limits::MAX_FRAMES),
                "too many frames",
                "test a shorter range",
            );
            None
        }
        Err(why) => {
            report.bad_scene(
                f.span,
                format!("bad frame range `{}`: {why}", f.value),
                "expected \"A..B\"",
                "write e.g. `frames = \"0..24\"` (the end is exclusive)",
            );
            None
        }
    }
}

/// A test's own fields over the defaults; `None` when something required is missing.
fn merge(
    name: At<String>,
    own: Partial,
    defaults: &Partial,
    golden: Option<At<String>>,
    dir: &Path,
    header: Span,
    report: &mut Report,
) -> Option<TestDecl> {
    let Some(scene) = own.scene.or_else(|| defaults.scene.clone()) else {
        report.bad_scene(
            header,
            format!("test `{}` has no `scene`", name.value),
            "`scene` is required here",
            "add `scene = \"scenes/spot.toml\"` (relative to the test file), or give one in `[defaults]`",
        );
        return None;
    };
    let fps = own.fps.or(defaults.fps).unwrap_or(npr_runner::FrameSpec::DEFAULT_FPS);
    let when = match own.when.or(defaults.when) {
        None => When::At { time_s: 0.0 },
        Some(WhenDecl::Time(time_s)) => When::At { time_s },
        Some(WhenDecl::Frame(n)) => When::At {
            time_s: f64::from(n) / fps,
        },
        Some(WhenDecl::Frames(start, end)) => When::Range { start, end },
    };
    let flicker = own.flicker.or_else(|| defaults.flicker.clone());
    if let (Some(f), When::At { .. }) = (&flicker, when) {
        report.bad_scene(
            f.span,
            format!("test `{}` bounds flicker but renders one frame", name.value),
            "flicker is measured between frames",
            "give the test a range, e.g. `frames = \"0..12\"`, with a still camera",
        );
        return None;
    }
    let coherence = own.coherence.or_else(|| defaults.coherence.clone());
    if let (Some(c), When::At { .. }) = (&coherence, when) {
        report.bad_scene(
            c.span,
            format!("test `{}` bounds coherence but renders one frame", name.value),
            "coherence is measured between frames",
            "give the test a range, e.g. `frames = \"0..12\"`",
        );
        return None;
    }
    let flip = own.flip.or_else(|| defaults.flip.clone());
    let per_pixel = own.per_pixel.or(defaults.per_pixel);
    let golden = match golden {
        Some(g) => {
            if flip.is_none() && per_pixel.is_none() {
                report.bad_scene(g.span, format!("test `{}` has a golden but no tolerance", name.value), "compared how?", "add `flip = { mean = 0.01 }` or `per_pixel = { max = 2, outliers = 0.005 }` (here or in `[defaults]`)");
                return None;
            }
            Some(Golden {
                path: At {
                    value: dir.join(&g.value),
                    span: g.span,
                },
                flip,
                per_pixel,
            })
        }
        None => None,
    };
    let mut sets = defaults.sets.clone();
    for (n, v) in own.sets {
        sets.retain(|(m, _)| m.value != n.value);
        sets.push((n, v));
    }
    Some(TestDecl {
        scene: At {
            value: dir.join(&scene.value),
            span: scene.span,
        },
        size: own.size.or(defaults.size).unwrap_or(DEFAULT_SIZE),
        when,
        fps,
        eye: own.eye.or_else(|| defaults.eye.clone()).unwrap_or(At {
            value: 0,
            span: name.span,
        }),
        sets,
        golden,
        may_be_blank: own.may_be_blank.or(defaults.may_be_blank).unwrap_or(false),
        sweep: own.sweep.or(defaults.sweep).unwrap_or(false),
        flicker,
        coherence,
        budget: own.budget.or_else(|| defaults.budget.clone()),
        variants: Vec::new(),
        reference: 0,
        name,
    })
}
