//! npr lab: what an application embedding the runner does not need, but the
//! tests, the benchmarks and the CLI's `npr bench` do.
//!
//! - [`harness`]: golden-image comparison (per-pixel bound or FLIP), with the
//!   actual and diff images written on failure.
//! - [`contours`]: analytic contour ground truth (f64 ray casting) and
//!   precision/recall of a rendered line mask.
//! - [`bench`](mod@bench): frame overhead against the runner's own passes, frame time
//!   and per-pass GPU time.
//!   (`npr bench passes`, `npr studio`).
//! - [`bench_overhead`]: `npr bench overhead`, the runner against an
//!   independent hand-written wgpu program drawing the same WGSL passes.
//! - [`bench_host`]: `npr bench host`, a host's CPU time per frame through
//!   `npr_runner::embed` against a minimal wgpu program.
//! - [`bench_contours`]: `npr bench contours`, contour methods' cost and accuracy.
//! - [`fit`]: least-squares line and log–log power law of a cost against a size.
//! - [`bench_lines`]: `npr bench lines`, lines passes' cost against edges and against LSA contours.
//! - [`silhouettes_gpu`]: silhouette classification in a compute pass, timed
//!   against the CPU's by `npr bench lines` (not used by the renderer).
//! - [`bench_ops`]: `npr bench ops`, the MetaTexture variants and their error models.
//! - [`plot`]: the benchmarks' figures as SVG (`--plot`).
//! - [`bench_patterns`]: `npr bench patterns`, the pattern tracker's cost and its error against f64.
//! - [`bench_styles`]: `npr bench styles`, whole styles' frame cost against a baseline style.
//! - [`patterns_f64`]: the dynamic 2D pattern tracker in f64 (tests, `npr bench patterns`).
//! - [`bench_reduce`], [`bench_reduce_pixels`]: `npr bench reduce` and
//!   `npr bench pixels`, compute passes' reductions over vertices and over
//!   the pixels of an ID image.

pub mod bench;
pub mod bench_artmaps;
pub mod bench_contours;
pub mod bench_host;
pub mod bench_lines;
pub mod bench_ops;
pub mod bench_overhead;
pub mod bench_patterns;
pub mod bench_reduce;
pub mod bench_reduce_pixels;
pub mod bench_styles;
pub mod contours;
pub mod fit;
pub mod harness;
pub mod patterns_f64;
pub mod plot;
pub mod silhouettes_gpu;
pub mod sliding;
pub mod thread_cpu;
