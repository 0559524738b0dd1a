//! `npr bench contours`: cost and accuracy of the contour methods — LSA
//! base, LSA with each extension on and off, LSA full, Sobel on depth and
//! Roberts normal+depth — per resolution (a benchmark, never a test).
//!
//! Cost: every variant shares one G-buffer pass (world positions and
//! normals in rgba32float, linear depth, encoded view normals, and the
//! packed LSA layout: view positions in rgba16float and octahedral view
//! normals in rg16float; the final pass reads all six so none is pruned). A passthrough image pass (one
//! texel of each target) costs t_pass = (T(five chained passthrough
//! passes) − T(one)) / 4 ([`CHAINED_PASSTHROUGHS`]); the G-buffer alone
//! T_gb = T(one) − t_pass. A method's image
//! stage is T − T_gb, stated in ms, relative to t_pass, and as pixel
//! throughput. Each time is the fastest of `frames` frames, the frames
//! interleaved across variants and sizes, so machine load affects every
//! variant and size alike and a frame slowed by another process does not
//! count.
//!
//! The first two programs must be the passthrough variants of
//! [`variants`], compiled as declared (`npr bench contours` compiles every
//! variant `naive`, and each method also `auto` where fusion changes its
//! passes, as a row of its own).
//!
//! Accuracy: precision and recall within 1 px against the analytic ground
//! truth of [`crate::contours::builtin_scenes`], at each resolution; the
//! table gives the minimum over the scenes.
//!
//! Linearity: over the sizes measured, per method, the least-squares line
//! of the image stage against the pixel count (its slope in ns per pixel)
//! and the log–log exponent ([`slopes`], [`crate::fit`]).

use crate::bench::wait_idle;
use crate::contours::{accuracy, builtin_scenes, ink_mask, Accuracy};
use npr_runner::{FrameSpec, Gpu, RunError, StyleProgram};

/// The shared G-buffer. `vpos` and `oct` are the packed LSA layout (view
/// positions in rgba16float, octahedral view normals in rg16float, 12 bytes
/// a pixel against the 32 of `pos` and `nrm`); every variant writes both
/// layouts, so the G-buffer cost subtracted from each is the same.
const GBUFFER: &str = "style \"bench contours\"\npass gbuffer: render(scene) {\n  out pos: rgba32float = vec4(position.world, 1.0)\n  out nrm: rgba32float = vec4(normal.world, 1.0)\n  out depth: r32float = depth\n  out enc: rgba16float = vec4(normal.view * 0.5 + 0.5, 1.0)\n  out vpos: rgba16float = vec4(position.view, 1.0)\n  out oct: rg16float = oct_encode(normal.view)\n}\n";

/// Reads every G-buffer target at zero weight, so all variants keep the same G-buffer.
const KEEP: &str =
    "0.0 * (gbuffer.pos.x + gbuffer.nrm.x + gbuffer.depth + gbuffer.enc.x + gbuffer.vpos.x + gbuffer.oct.x)";

/// LSA passes: error (the operator call), line density, ink.
fn lsa_passes(call: &str, density: Option<f64>) -> String {
    let (thin, src) = match density {
        Some(s) => (
            format!("pass thin: image(error) {{\n  out e: rgba16float = lsa_density(error.e, strength: {s:?})\n}}\n"),
            "thin",
        ),
        None => (String::new(), "error"),
    };
    format!(
        "pass error: image(gbuffer) {{\n  out e: rgba16float = {call}\n}}\n{thin}pass ink: image({src}, gbuffer) {{\n  let e = {src}.e\n  let line = max(max(e.x, e.y), max(e.z, e.w))\n  out c: rgba8unorm = mix(vec4(1.0), vec4(0.0, 0.0, 0.0, 1.0), line) + {KEEP}\n}}\noutput ink.c\n"
    )
}

/// How many passthrough passes the second variant chains: t_pass is the
/// difference of the two variants' frames over `CHAINED_PASSTHROUGHS − 1`,
/// so the noise of two frame times is divided by 4, not by 1 (with two
/// chained passes, one passthrough at 512² is about 0.4–0.9 ms beside
/// frame times that move by that much under load).
pub const CHAINED_PASSTHROUGHS: usize = 5;

/// `CHAINED_PASSTHROUGHS` passthrough passes, each reading the previous
/// one's target and every G-buffer target at its pixel.
fn chained_passthroughs() -> String {
    let mut text =
        format!("pass copy1: image(gbuffer) {{\n  out c: rgba8unorm = vec4(gbuffer.pos.w * 0.0) + {KEEP}\n}}\n");
    for k in 2..CHAINED_PASSTHROUGHS {
        text.push_str(&format!(
            "pass copy{k}: image(copy{}, gbuffer) {{\n  out c: rgba8unorm = copy{}.c + {KEEP}\n}}\n",
            k - 1,
            k - 1
        ));
    }
    let last = CHAINED_PASSTHROUGHS - 1;
    text.push_str(&format!(
        "pass ink: image(copy{last}, gbuffer) {{\n  out c: rgba8unorm = copy{last}.c + {KEEP}\n}}\noutput ink.c\n"
    ));
    text
}

fn single_pass(line: &str) -> String {
    format!(
        "pass ink: image(gbuffer) {{\n  let line = {line}\n  out c: rgba8unorm = mix(vec4(1.0), vec4(0.0, 0.0, 0.0, 1.0), line) + {KEEP}\n}}\noutput ink.c\n"
    )
}

/// (name, style text, measured for accuracy).
pub fn variants() -> Vec<(&'static str, String, bool)> {
    let g = |rest: String| format!("{GBUFFER}{rest}");
    let lsa = |plane: bool, aa: bool| format!("lsa(gbuffer.pos, gbuffer.nrm, plane: {plane}, aa: {aa})");
    let packed = |plane: bool, aa: bool| {
        format!("lsa(gbuffer.vpos, gbuffer.oct, plane: {plane}, aa: {aa}, normal_encoding: octahedral)")
    };
    vec![
        (
            "passthrough",
            g(single_pass(&format!("gbuffer.pos.w * 0.0 + {KEEP}"))),
            false,
        ),
        ("passthrough x5", g(chained_passthroughs()), false),
        (
            "LSA base (e_curv, density 0.5)",
            g(lsa_passes(&lsa(false, false), Some(0.5))),
            true,
        ),
        (
            "LSA + plane (eqs. 6-7)",
            g(lsa_passes(&lsa(true, false), Some(1.0))),
            true,
        ),
        ("LSA + aa (eq. 8)", g(lsa_passes(&lsa(false, true), Some(1.0))), true),
        (
            "LSA full, no density filter",
            g(lsa_passes(&lsa(true, true), None)),
            true,
        ),
        (
            "LSA full (plane + aa, density 1)",
            g(lsa_passes(&lsa(true, true), Some(1.0))),
            true,
        ),
        (
            "LSA base, packed G-buffer (view rgba16float + octahedral normals)",
            g(lsa_passes(&packed(false, false), Some(0.5))),
            true,
        ),
        (
            "LSA full, packed G-buffer (view rgba16float + octahedral normals)",
            g(lsa_passes(&packed(true, true), Some(1.0))),
            true,
        ),
        (
            "Sobel on depth (0.05 m/px)",
            g(single_pass("threshold(sobel(gbuffer.depth), lo: 0.05, hi: 0.05)")),
            true,
        ),
        (
            "normal+depth (Roberts)",
            g(single_pass(
                "normal_depth_edges(gbuffer.enc, gbuffer.depth, depth_threshold: 50mm, normal_threshold: 0.4)",
            )),
            true,
        ),
    ]
}

/// The least t_pass (seconds) the ratios divide by: the one-pass and the
/// chained passthrough frames can come out equal or reversed under load,
/// and t_pass is then this floor, not a measurement.
pub const T_PASS_FLOOR_S: f64 = 1e-9;

/// One row of the report.
#[derive(Debug, Clone)]
pub struct Row {
    pub name: String,
    pub size: u32,
    pub frame_s: f64,
    /// Frame time minus the G-buffer's.
    pub image_stage_s: f64,
    /// Image-stage cost over one passthrough pass's; `None` when either
    /// was not measurable in this run (two passthrough frames equal or
    /// reversed under load, or an image stage at or below 0: tiny sizes).
    pub vs_passthrough: Option<f64>,
    /// Over the analytic scenes except `parallel_planes`: the minimum
    /// precision and the minimum recall; then the recall on
    /// `parallel_planes` (the step e_curv and Sobel cannot see).
    pub accuracy: Option<(f64, f64, f64)>,
}

/// Per size, its frame spec and a renderer per variant.
type SizeRenderers = Vec<(FrameSpec, Vec<npr_runner::Renderer>)>;

/// The fastest of `frames` frames per variant and size, `[size][variant]`,
/// frames interleaved across variants and sizes (render + GPU wait; one
/// warm-up frame each): a change of load falls on every size alike, so it
/// does not tilt the fit of cost against pixels ([`slopes`]). Every
/// (variant, size) keeps its own renderer and targets meanwhile: about
/// 70 bytes a pixel per variant, some 2 GB for 28 variants at 1024².
/// The renderers are returned with their frame specs, `[size]`, for the
/// accuracy renders to reuse (a new renderer compiles every pipeline
/// again, which is most of the cost at small sizes).
fn min_frame_times(
    gpu: &Gpu,
    programs: &[(String, StyleProgram, bool)],
    scene: &npr_runner::scene::Scene,
    sizes: &[u32],
    frames: u32,
) -> Result<(Vec<Vec<f64>>, SizeRenderers), RunError> {
    let wait = || wait_idle(gpu);
    let mut renderers = Vec::new();
    for &size in sizes {
        let spec = FrameSpec::still(size, size, 0);
        let mut row = Vec::new();
        for (_, p, _) in programs {
            let mut r = npr_runner::Renderer::new(&gpu.device, &gpu.queue, p, scene)?;
            r.render(scene, &spec)?;
            wait()?;
            row.push(r);
        }
        renderers.push((spec, row));
    }
    let mut best = vec![vec![f64::INFINITY; programs.len()]; sizes.len()];
    for _ in 0..frames.max(1) {
        for ((spec, row), best) in renderers.iter_mut().zip(best.iter_mut()) {
            for (r, best) in row.iter_mut().zip(best.iter_mut()) {
                let t = std::time::Instant::now();
                r.render(scene, spec)?;
                wait()?;
                *best = best.min(t.elapsed().as_secs_f64());
            }
        }
    }
    Ok((best, renderers))
}

/// The timing scene: a coarse sphere before a plane that covers every
/// pixel. Screen-space cost depends on how many pixels, not on what they
/// show; coarse meshes keep the (CPU-rasterized) G-buffer cheap next to it.
pub fn timing_scene(sources: &mut npr_diag::SourceMap) -> Result<npr_runner::scene::Scene, RunError> {
    let text = "[camera]\nposition = [0.0, 0.3, 4.0]\ntarget = [0.0, 0.0, 0.0]\n\n[[object]]\nprimitive = { kind = \"plane\", size = 40.0 }\nrotate = [90.0, 0.0, 0.0]\n\n[[object]]\nprimitive = { kind = \"sphere\", radius = 0.7, segments = 32, rings = 16 }\ntranslate = [0.2, 0.0, 0.9]\n";
    let file = sources.add("timing.toml", text);
    npr_runner::scene::parse_scene(text, file, std::path::Path::new(".")).map_err(RunError::User)
}

/// Measures every variant at every size (square images).
pub fn run(
    gpu: &Gpu,
    programs: &[(String, StyleProgram, bool)],
    sizes: &[u32],
    frames: u32,
    mut progress: impl FnMut(&str),
) -> Result<Vec<Row>, RunError> {
    let scenes = builtin_scenes();
    let mut sources = npr_diag::SourceMap::new();
    let loaded: Vec<_> = scenes
        .iter()
        .map(|s| s.scene(&mut sources).map_err(RunError::User))
        .collect::<Result<_, _>>()?;
    let timing_scene = timing_scene(&mut sources)?;
    let mut rows = Vec::new();
    progress("timing every size, frames interleaved");
    let (bests, mut renderers) = min_frame_times(gpu, programs, &timing_scene, sizes, frames)?;
    for ((&size, best), (spec, size_renderers)) in sizes.iter().zip(&bests).zip(&mut renderers) {
        let t_chain = (best[1] - best[0]) / (CHAINED_PASSTHROUGHS - 1) as f64;
        let measured_pass = t_chain > T_PASS_FLOOR_S;
        let t_pass = t_chain.max(T_PASS_FLOOR_S);
        let gbuffer = best[0] - t_pass;
        for (i, ((name, _, measure), renderer)) in programs.iter().zip(size_renderers.iter_mut()).enumerate() {
            let accuracy = if *measure {
                progress(&format!("accuracy of {name} at {size}x{size}"));
                let (mut min_p, mut min_r, mut planes_r) = (1.0f64, 1.0f64, 1.0f64);
                for (s, scene) in scenes.iter().zip(&loaded) {
                    // The timing renderer, given the analytic scene: the
                    // same image a new renderer would draw (the contour
                    // styles keep no history), without compiling again.
                    renderer.set_scene(scene)?;
                    renderer.render(scene, spec)?;
                    let img = renderer.read_output()?;
                    let a: Accuracy = accuracy(&ink_mask(&img, 0.5), &s.truth(size, size), 1);
                    if s.name == "parallel_planes" {
                        planes_r = a.recall;
                    } else {
                        min_p = min_p.min(a.precision);
                        min_r = min_r.min(a.recall);
                    }
                }
                Some((min_p, min_r, planes_r))
            } else {
                None
            };
            let image_stage_s = best[i] - gbuffer;
            rows.push(Row {
                name: name.clone(),
                size,
                frame_s: best[i],
                image_stage_s,
                vs_passthrough: (measured_pass && image_stage_s > 0.0).then(|| image_stage_s / t_pass),
                accuracy,
            });
        }
    }
    Ok(rows)
}

/// The report as a Markdown table.
pub fn table(rows: &[Row]) -> String {
    let mut s = String::from(
        "| size | method | ms/frame | image stage (ms) | × passthrough | Mpx/s | min precision | min recall | recall, parallel planes |\n|---:|---|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for r in rows {
        let px = f64::from(r.size) * f64::from(r.size);
        let (p, rc, planes) = match r.accuracy {
            Some((p, rc, planes)) => (format!("{p:.3}"), format!("{rc:.3}"), format!("{planes:.3}")),
            None => ("–".into(), "–".into(), "–".into()),
        };
        // At or below t_pass's floor (a passthrough whose t_pass was not
        // measured, or a method no slower than the G-buffer estimate) the
        // image stage is no measurement: its throughput would be absurd.
        let measured = r.image_stage_s > T_PASS_FLOOR_S;
        let stage = if measured {
            format!("{:.3}", r.image_stage_s * 1e3)
        } else {
            "–".into()
        };
        let throughput = if measured {
            format!("{:.1}", px / r.image_stage_s / 1e6)
        } else {
            "–".into()
        };
        s.push_str(&format!(
            "| {0}² | {1} | {2:.3} | {3} | {4} | {5} | {6} | {7} | {8} |\n",
            r.size,
            r.name,
            r.frame_s * 1e3,
            stage,
            r.vs_passthrough.map_or("–".into(), |v| format!("{v:.2}x")),
            throughput,
            p,
            rc,
            planes
        ));
    }
    s
}

/// One method's image stage against its pixel count over the sizes
/// measured (issue 14: "cost linear in pixels from 128² to 1024², with the
/// slope reported").
#[derive(Debug, Clone)]
pub struct Slope {
    pub name: String,
    /// The sizes whose image stage was measured (above t_pass's floor);
    /// the others are left out of both fits.
    pub sizes: Vec<u32>,
    /// Image stage (s) = intercept + slope · pixels.
    pub line: Option<crate::fit::Line>,
    /// Image stage = c · pixels^exponent: 1 is linear with no fixed cost.
    pub power: Option<crate::fit::PowerLaw>,
}

/// Per method, in the order of the rows, the least-squares fits of its
/// image stage against its pixel count.
pub fn slopes(rows: &[Row]) -> Vec<Slope> {
    let mut names: Vec<&str> = Vec::new();
    for r in rows {
        if !names.contains(&r.name.as_str()) {
            names.push(&r.name);
        }
    }
    names
        .into_iter()
        .map(|name| {
            let measured: Vec<&Row> = rows
                .iter()
                .filter(|r| r.name == name && r.image_stage_s > T_PASS_FLOOR_S)
                .collect();
            let points: Vec<(f64, f64)> = measured
                .iter()
                .map(|r| (f64::from(r.size) * f64::from(r.size), r.image_stage_s))
                .collect();
            Slope {
                name: name.to_string(),
                sizes: measured.iter().map(|r| r.size).collect(),
                line: crate::fit::line(&points),
                power: crate::fit::power_law(&points),
            }
        })
        .collect()
}

/// The fits as a Markdown table: the slope in ns per pixel, the intercept
/// (the fixed cost the line puts at zero pixels) and the log–log exponent.
pub fn slope_table(slopes: &[Slope]) -> String {
    let mut s = String::from(
        "| method | sizes fitted | slope (ns/px) | intercept (ms) | log–log exponent |\n|---|---|---:|---:|---:|\n",
    );
    for f in slopes {
        let sizes: Vec<String> = f.sizes.iter().map(|n| format!("{n}²")).collect();
        let (slope, intercept) = match f.line {
            Some(l) => (format!("{:.2}", l.slope * 1e9), format!("{:.3}", l.intercept * 1e3)),
            None => ("–".into(), "–".into()),
        };
        let exponent = f.power.map_or("–".into(), |p| format!("{:.2}", p.exponent));
        s.push_str(&format!(
            "| {} | {} | {slope} | {intercept} | {exponent} |\n",
            f.name,
            sizes.join(", ")
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(name: &str, size: u32, image_stage_s: f64) -> Row {
        Row {
            name: name.into(),
            size,
            frame_s: image_stage_s + 1e-3,
            image_stage_s,
            vs_passthrough: None,
            accuracy: None,
        }
    }

    #[test]
    fn slopes_fit_each_method_over_its_measured_sizes() {
        let mut rows = Vec::new();
        for size in [128, 256, 512, 1024] {
            let px = f64::from(size * size);
            rows.push(row(
                "passthrough",
                size,
                if size == 256 { T_PASS_FLOOR_S } else { 5e-9 * px },
            ));
            rows.push(row("LSA", size, 1e-3 + 50e-9 * px));
        }
        let s = slopes(&rows);
        assert_eq!(s.len(), 2);
        // The floored 256² passthrough is no measurement: left out.
        assert_eq!(s[0].name, "passthrough");
        assert_eq!(s[0].sizes, [128, 512, 1024]);
        let p = s[0].power.expect("a fit");
        assert!((p.exponent - 1.0).abs() < 1e-9, "{p:?}");
        assert_eq!(s[1].sizes, [128, 256, 512, 1024]);
        let l = s[1].line.expect("a fit");
        assert!(
            (l.slope - 50e-9).abs() < 1e-15 && (l.intercept - 1e-3).abs() < 1e-12,
            "{l:?}"
        );
        let table = slope_table(&s);
        assert!(
            table.contains("| LSA | 128², 256², 512², 1024² | 50.00 | 1.000 |"),
            "{table}"
        );
        assert!(
            table.contains("| passthrough | 128², 512², 1024² | 5.00 | 0.000 | 1.00 |"),
            "{table}"
        );
    }

    #[test]
    fn an_image_stage_at_the_floor_is_no_measurement() {
        // 1024² in one run: t_pass not measured, so the passthrough's
        // image stage is the floor, and its Mpx/s was printed as 10⁹.
        let t = table(&[row("passthrough", 1024, T_PASS_FLOOR_S)]);
        assert!(t.contains("| 1024² | passthrough | 1.000 | – | – | – |"), "{t}");
    }

    #[test]
    fn one_size_fits_nothing() {
        let s = slopes(&[row("LSA", 128, 1e-3)]);
        assert!(s[0].line.is_none() && s[0].power.is_none());
        assert!(slope_table(&s).contains("| LSA | 128² | – | – | – |"));
    }
}
