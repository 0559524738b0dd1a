//! End to end through the `npr` binary: exit codes, JSON diagnostics,
//! compile output, rendering to PNG/EXR, `--dump-passes`, and `--frames`.

use crate::common;

use common::cli::{npr, stderr};
use std::path::{Path, PathBuf};

fn scratch(name: &str) -> PathBuf {
    common::cli::scratch("cli", name)
}

#[test]
fn check_accepts_every_example() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut checked = 0;
    for entry in std::fs::read_dir(&dir).expect("examples") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "npr") {
            let name = format!("examples/{}", path.file_name().expect("name").to_string_lossy());
            let o = npr(&["check", &name]);
            assert_eq!(o.status.code(), Some(0), "{name}: {}", stderr(&o));
            checked += 1;
        }
    }
    assert!(checked >= 10, "only {checked} examples found");
}

#[test]
fn user_errors_exit_1_with_a_rendered_diagnostic() {
    let dir = scratch("bad");
    let file = dir.join("bad.npr");
    std::fs::write(&file, "style \"Bad\"\nparam w: px = 2m\n").expect("write");
    let o = npr(&["check", file.to_str().expect("utf-8 path")]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(err.contains("error[E0202]") && err.contains("bad.npr:2:15"), "{err}");
}

#[test]
fn json_diagnostics_are_machine_readable() {
    let dir = scratch("json");
    let file = dir.join("bad.npr");
    std::fs::write(
        &file,
        "style \"Bad\"\npass p: render(scene) {\n  out c: r8unorm = lambrt(normal, light.dir)\n}\noutput p.c\n",
    )
    .expect("write");
    let o = npr(&["check", file.to_str().expect("utf-8 path"), "--message-format", "json"]);
    assert_eq!(o.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&o.stdout);
    let first: serde_json::Value = serde_json::from_str(stdout.lines().next().expect("a line")).expect("json");
    assert_eq!(first["code"], "E0102");
    assert_eq!(first["labels"][0]["line"], 3);
    assert_eq!(first["labels"][0]["column"], 20);
    assert!(first["help"].as_str().unwrap_or("").contains("lambert"));
}

#[test]
fn compile_writes_wgsl_manifest_and_report() {
    let dir = scratch("compile");
    let o = npr(&[
        "compile",
        "examples/outline.npr",
        "-o",
        dir.to_str().expect("path"),
        "--report",
        "--time-passes",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains(&format!("{:<14} pass `sobel_debug`", "removed")),
        "{stdout}"
    );
    assert!(stdout.contains("validate"), "stage timings printed: {stdout}");
    // The report ends with the proved ranges, the very text of `npr check
    // --ranges` (issue 49), and so does report.txt.
    let check = npr(&["check", "--ranges", "examples/outline.npr"]);
    let ranges = String::from_utf8_lossy(&check.stdout);
    assert!(
        ranges.starts_with("value ranges") && ranges.contains("finite for all declared params"),
        "{ranges}"
    );
    assert!(stdout.contains(ranges.as_ref()), "{stdout}");
    let written = std::fs::read_to_string(dir.join("report.txt")).expect("report.txt");
    assert!(written.ends_with(ranges.as_ref()), "{written}");
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("manifest.json")).expect("manifest")).expect("json");
    let passes: Vec<&str> = manifest["passes"]
        .as_array()
        .expect("passes")
        .iter()
        .map(|p| p["name"].as_str().unwrap_or(""))
        .collect();
    assert_eq!(passes, ["gbuffer", "ink_lines"]);
    for p in passes {
        let wgsl = std::fs::read_to_string(dir.join(format!("{p}.wgsl"))).expect("wgsl");
        assert!(wgsl.contains("outline.npr:"), "WGSL maps back to .npr lines");
    }
    // No temp files left behind by the atomic writes.
    assert!(std::fs::read_dir(&dir).expect("dir").all(|e| !e
        .expect("entry")
        .file_name()
        .to_string_lossy()
        .contains(".tmp-")));
}

/// `schedule:` in a pass through the binary: the report says the pass was
/// forced and where, whatever `--schedule` says; a `schedule: tiled` the
/// tiler refuses exits 1 with E0311 at the setting.
#[test]
fn compile_report_says_which_passes_the_style_forced() {
    let dir = scratch("schedule-setting");
    let style = dir.join("forced.npr");
    let text = |setting: &str| {
        format!(
            "style \"Forced\"\npass g: render(scene) {{\n  out d: r32float = depth\n}}\npass edges: image(g) {{\n  {setting}\n  out e: rgba16float = vec4(sobel(g.d, screen_uv), 0.0, 0.0, 1.0)\n}}\npass ink: image(edges) {{\n  out c: rgba8unorm = edges.e\n}}\noutput ink.c\n"
        )
    };
    std::fs::write(&style, text("schedule: naive")).expect("write");
    let out = dir.join("out");
    let (style_arg, out_arg) = (style.to_str().expect("path"), out.to_str().expect("path"));
    let o = npr(&["compile", style_arg, "-o", out_arg, "--report", "--schedule", "tiled"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains(&format!(
            "{:<14} {:<36} forced by `schedule: naive` at line 6",
            "not tiled", "pass `edges`"
        )),
        "{stdout}"
    );
    // Sobel on depth into r16float, which compute cannot store.
    std::fs::write(
        &style,
        "style \"Forced\"\npass g: render(scene) {\n  out d: r32float = depth\n}\npass edges: image(g) {\n  schedule: tiled\n  out e: r16float = sobel(g.d, screen_uv)\n}\noutput edges.e\n",
    )
    .expect("write");
    let o = npr(&["compile", style_arg, "-o", out_arg, "--schedule", "naive"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(err.contains("error[E0311]") && err.contains("forced.npr:6:3"), "{err}");
}

/// `schedule: recompute` wins even under the naive schedule `--dump-passes`
/// uses, so that pass has no target to dump: the dump says so, and holds
/// every other target.
#[test]
fn dump_passes_says_which_pass_is_recomputed_and_not_stored() {
    let dir = scratch("dump-recompute");
    let text = std::fs::read_to_string("examples/lsa_contours.npr")
        .expect("style")
        .replace(
            "pass error: image(gbuffer) {\n",
            "pass error: image(gbuffer) {\n  schedule: recompute\n",
        );
    assert!(text.contains("schedule: recompute"), "the error pass moved");
    let style = dir.join("recomputed.npr");
    std::fs::write(&style, text).expect("write");
    let o = npr(&[
        "render",
        style.to_str().expect("path"),
        "--scene",
        "examples/scenes/spheres.toml",
        "--allow-path",
        "examples",
        "-o",
        dir.join("out.png").to_str().expect("path"),
        "--size",
        "32x24",
        "--dump-passes",
        dir.join("passes").to_str().expect("path"),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains(
            "note: pass `error` is not stored, so --dump-passes has no image of it: forced by `schedule: recompute`"
        ),
        "{err}"
    );
    let index = std::fs::read_to_string(dir.join("passes/contact_sheet.txt")).expect("index");
    assert!(!index.contains("error.e"), "{index}");
    assert!(index.contains("thin.e") && index.contains("gbuffer.pos"), "{index}");
}

#[test]
fn render_writes_png_and_exr_and_dumps_passes() {
    let dir = scratch("render");
    let png = dir.join("toon.png");
    let o = npr(&[
        "render",
        "examples/rounded_shadows.npr",
        "--scene",
        "examples/scenes/spot.toml",
        "-o",
        png.to_str().expect("path"),
        "--size",
        "96x64",
        "--dump-passes",
        dir.join("passes").to_str().expect("path"),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let img = image::open(&png).expect("png");
    assert_eq!((img.width(), img.height()), (96, 64));
    let index = std::fs::read_to_string(dir.join("passes/contact_sheet.txt")).expect("index");
    assert_eq!(index.lines().count(), 6, "every target is dumped: {index}");
    assert!(index.contains("blur_x.r 48x32 r16float"), "{index}");
    assert!(dir.join("passes/contact_sheet.png").exists());
    // The half-resolution float blur dumps as a 16-bit PNG.
    let blur = image::open(dir.join("passes/04_blur_y.r.png")).expect("dump");
    assert!(
        matches!(blur, image::DynamicImage::ImageRgba16(_)),
        "{:?}",
        blur.color()
    );

    let exr = dir.join("toon.exr");
    let o = npr(&[
        "render",
        "examples/toon.npr",
        "--scene",
        "examples/scenes/spot.toml",
        "-o",
        exr.to_str().expect("path"),
        "--size",
        "32x32",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let e = image::open(&exr).expect("exr");
    assert_eq!((e.width(), e.height()), (32, 32));
}

#[test]
fn render_without_an_output_writes_the_styles_png_here_and_says_so() {
    let dir = scratch("no-out");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
        .arg("render")
        .arg(root.join("examples/toon.npr"))
        .arg("--scene")
        .arg(root.join("examples/scenes/spheres.toml"))
        .args(["--size", "32x32"])
        .current_dir(&dir)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run npr");
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(
        err.contains("wrote toon.png (32x32")
            && err.contains("note: no `-o` given: wrote toon.png in the current directory"),
        "{err}"
    );
    let img = image::open(dir.join("toon.png")).expect("toon.png written in the current directory");
    assert_eq!((img.width(), img.height()), (32, 32));
}

#[test]
fn frames_render_an_animation() {
    let dir = scratch("frames");
    let out = dir.join("f_{frame}.png");
    let o = npr(&[
        "render",
        "examples/toon.npr",
        "--scene",
        "examples/scenes/spot.toml",
        "-o",
        out.to_str().expect("path"),
        "--size",
        "32x32",
        "--frames",
        "0..3",
        "--fps",
        "1",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let frames: Vec<image::RgbaImage> = (0..3)
        .map(|f| {
            image::open(dir.join(format!("f_{f:04}.png")))
                .expect("frame")
                .to_rgba8()
        })
        .collect();
    // The rim light is animated from 0.1 (0 s) to 0.5 (4 s): frames differ.
    assert_ne!(frames[0], frames[2]);
}

#[test]
fn too_large_an_image_is_a_user_error() {
    let o = npr(&[
        "render",
        "examples/toon.npr",
        "--scene",
        "examples/scenes/spot.toml",
        "-o",
        "/dev/null",
        "--size",
        "20000x16",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("E0404"), "{}", stderr(&o));
}

#[test]
fn lsa_styles_render_an_analytic_scene_from_the_cli() {
    let dir = scratch("lsa");
    for style in ["lsa_contours", "lsa_base", "sobel_outline"] {
        let out = dir.join(format!("{style}.png"));
        let o = npr(&[
            "render",
            &format!("examples/{style}.npr"),
            "--scene",
            "tests/data/contours/cube.toml",
            "-o",
            out.to_str().expect("utf-8 path"),
            "--size",
            "48x32",
        ]);
        assert_eq!(o.status.code(), Some(0), "{style}: {}", stderr(&o));
        let img = image::open(&out).expect("png").to_rgba8();
        assert_eq!(img.dimensions(), (48, 32));
        // Ink on paper: some pixels are lines, most are paper.
        let dark = img.pixels().filter(|p| p.0[0] < 128).count();
        assert!(dark > 10 && dark < 48 * 32 / 2, "{style}: {dark} line pixels");
    }
}

#[test]
fn bench_host_times_npr_against_both_baselines() {
    // A smoke run at a tiny size: the table's shape and that all three
    // programs ran (a wgpu validation error in a baseline aborts the run),
    // not timings.
    let o = npr(&["bench", "host", "--objects", "1,3", "--frames", "1", "--size", "16"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    for objects in ["1", "3"] {
        let row = stdout
            .lines()
            .find(|l| l.starts_with(&format!("| {objects} |")))
            .unwrap_or_else(|| panic!("no row for {objects} objects:\n{stdout}"));
        let cells: Vec<&str> = row.split('|').map(str::trim).filter(|c| !c.is_empty()).collect();
        assert_eq!(cells.len(), 6, "{row}");
        // npr's, the minimal program's and the pass-shaped program's µs.
        for us in &cells[1..4] {
            assert!(us.parse::<f64>().is_ok_and(|v| v > 0.0), "{row}");
        }
        // Each ratio is `a (b)`: of the medians, and the median per frame.
        for ratio in &cells[4..6] {
            let (of_medians, per_frame) = ratio.split_once(' ').unwrap_or_else(|| panic!("{row}"));
            assert!(of_medians.parse::<f64>().is_ok_and(|v| v > 0.0), "{row}");
            assert!(
                per_frame.trim_matches(['(', ')']).parse::<f64>().is_ok_and(|v| v > 0.0),
                "{row}"
            );
        }
    }
    assert!(stdout.contains("a frame after adding an 11th object"), "{stdout}");
    // A style with compute passes: the pass-shaped program dispatches for them.
    let o = npr(&[
        "bench",
        "host",
        "--style",
        "examples/object_centroids.npr",
        "--objects",
        "2",
        "--frames",
        "1",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = npr(&["bench", "host", "--objects", "1", "--block", "0"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--block 0: each program runs at least one frame per turn"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn bench_contours_reports_every_variant_with_accuracy() {
    // A smoke run at tiny sizes: the tables' shape, not their timings.
    let o = npr(&["bench", "contours", "--sizes", "16,24", "--frames", "1"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    let rows: Vec<&str> = stdout.lines().filter(|l| l.starts_with("| 24²")).collect();
    // Every variant, plus an `auto` row for each method the schedule fuses
    // (the LSA styles fuse their ink pass), a `tiled` row for each method
    // `--schedule tiled` tiles (LSA, Sobel, normal+depth).
    let declared = npr_lab::bench_contours::variants().len();
    let auto = rows.iter().filter(|r| r.contains("[auto: ")).count();
    let tiled = rows.iter().filter(|r| r.contains("[tiled: ")).count();
    // And a `recompute` row for each method whose error pass `--schedule
    // recompute` computes in the density filter's tiles (the LSA methods).
    let recompute = rows.iter().filter(|r| r.contains("[recompute: ")).count();
    assert_eq!(rows.len(), declared + auto + tiled + recompute, "{stdout}");
    assert!(recompute >= 2, "LSA base and full recompute: {stdout}");
    assert!(auto >= 1, "no method was fused: {stdout}");
    assert!(tiled >= 3, "LSA, Sobel and normal+depth tile: {stdout}");
    let full = rows
        .iter()
        .find(|r| r.contains("LSA full (plane + aa"))
        .expect("LSA full row");
    // Columns: ..., min precision, min recall, recall on parallel planes.
    let cells: Vec<&str> = full.split('|').map(str::trim).filter(|c| !c.is_empty()).collect();
    let recall_planes: f64 = cells[cells.len() - 1].parse().expect("a number");
    assert!(recall_planes > 0.5, "{full}");
    // Then one fit per method: the sizes it fits, slope, intercept,
    // exponent. At these sizes an image stage is often within noise of
    // the G-buffer's (a size left out, a fit of one point is "–"): only
    // the shape is checked.
    let fits = stdout
        .split_once("| method | sizes fitted | slope (ns/px) | intercept (ms) | log–log exponent |")
        .map(|(_, t)| t)
        .expect("the slope table");
    let fit_rows: Vec<&str> = fits
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("|---"))
        .collect();
    assert_eq!(fit_rows.len(), rows.len(), "{stdout}");
    let lsa_full = fit_rows
        .iter()
        .find(|r| r.starts_with("| LSA full (plane + aa, density 1) |"))
        .expect("LSA full's fit");
    // "", method, sizes, slope, intercept, exponent, "".
    let cells: Vec<&str> = lsa_full.split('|').map(str::trim).collect();
    assert_eq!(cells.len(), 7, "{lsa_full}");
    assert!(["16², 24²", "16²", "24²", ""].contains(&cells[2]), "{lsa_full}");
    let o = npr(&["bench", "contours", "--sizes", "0"]);
    assert_eq!(o.status.code(), Some(1), "size 0 is a user error");
}

#[test]
fn bench_passes_compares_schedules_in_one_run() {
    // A smoke run at a tiny size: what each schedule changed, and the ratio
    // column against the first schedule, not timings.
    let o = npr(&[
        "bench",
        "passes",
        "examples/lsa_contours.npr",
        "--scene",
        "examples/scenes/orbit.toml",
        "--size",
        "32x32",
        "--frames",
        "1",
        "--schedule",
        "naive,auto,tiled",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    let row = |schedule: &str| -> Vec<String> {
        let line = stdout
            .lines()
            .find(|l| l.starts_with(&format!("| {schedule} | ")))
            .unwrap_or_else(|| panic!("no summary row for {schedule}: {stdout}"));
        line.split('|')
            .map(|c| c.trim().to_string())
            .filter(|c| !c.is_empty())
            .collect()
    };
    // LSA: error, density, ink passes on a G-buffer; `auto` fuses the ink
    // pass, `tiled` also tiles the error and density passes.
    assert_eq!(row("naive")[1..3], ["0 fused, 0 tiled", "4"], "{stdout}");
    assert_eq!(row("naive")[4], "1.00", "{stdout}");
    assert_eq!(row("auto")[1..3], ["1 fused, 0 tiled", "3"], "{stdout}");
    assert_eq!(row("tiled")[1..3], ["1 fused, 2 tiled", "3"], "{stdout}");
    let o = npr(&[
        "bench",
        "passes",
        "examples/toon.npr",
        "--scene",
        "examples/scenes/spot.toml",
        "--schedule",
        "fast",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("error[E0501]: invalid value 'fast'"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn bench_artmaps_reports_every_filter_and_every_read() {
    // A smoke run at a tiny size: the tables' shape and that the figures
    // are real (positive, finite), not their values.
    let o = npr(&["bench", "artmaps", "--sizes", "8", "--size", "32x32", "--frames", "1"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    let builds: Vec<&str> = stdout.lines().filter(|l| l.contains("| 8² |")).collect();
    assert_eq!(builds.len(), 3, "one row per shipped filter:\n{stdout}");
    for row in &builds {
        let cells: Vec<&str> = row.split('|').map(str::trim).filter(|c| !c.is_empty()).collect();
        // 8² has 4 mip levels and 4 × 4 rip-map levels.
        assert_eq!((cells[2], cells[7]), ("4", "16"), "{row}");
        let rip_ms: f64 = cells[8].parse().expect("a number");
        assert!(rip_ms.is_finite() && rip_ms > 0.0, "{row}");
    }
    for v in &npr_lab::bench_artmaps::SAMPLE_VARIANTS {
        let row = stdout
            .lines()
            .find(|l| l.starts_with(&format!("| {} |", v.name)))
            .unwrap_or_else(|| panic!("no row for {}:\n{stdout}", v.name));
        let ms: f64 = row.split('|').nth(2).expect("ms").trim().parse().expect("a number");
        assert!(ms.is_finite() && ms > 0.0, "{row}");
    }
    let o = npr(&["bench", "artmaps", "--sizes", "0"]);
    assert_eq!(o.status.code(), Some(1), "size 0 is a user error");
}

#[test]
fn bench_lines_reports_edges_and_the_methods() {
    // A smoke run at a tiny size: the tables' shape, real figures, and the
    // straight lines exact on the analytic scenes (their accuracy does not
    // depend on timing).
    let o = npr(&["bench", "lines", "--segments", "8,16", "--size", "64", "--frames", "1"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    for segments in ["8", "16"] {
        let row = stdout
            .lines()
            .find(|l| l.starts_with(&format!("| {segments} |")))
            .unwrap_or_else(|| panic!("no row for {segments} segments:\n{stdout}"));
        let cells: Vec<&str> = row.split('|').map(str::trim).filter(|c| !c.is_empty()).collect();
        let frame_ms: f64 = cells[6].parse().expect("a number");
        assert!(frame_ms.is_finite() && frame_ms > 0.0, "{row}");
    }
    assert!(stdout.contains("R² ="), "the linear fit is printed:\n{stdout}");
    // The CPU against the compute classification: both timed, same edges.
    let classify = stdout
        .split("silhouette classification")
        .nth(1)
        .unwrap_or_else(|| panic!("no classification table:\n{stdout}"));
    for segments in ["8", "16"] {
        let row = classify
            .lines()
            .find(|l| l.starts_with(&format!("| {segments} |")))
            .unwrap_or_else(|| panic!("no classification row for {segments} segments:\n{stdout}"));
        let cells: Vec<&str> = row.split('|').map(str::trim).filter(|c| !c.is_empty()).collect();
        for column in [3, 4, 5] {
            let ms: f64 = cells[column].parse().expect("a number");
            assert!(ms.is_finite() && ms >= 0.0, "{row}");
        }
        assert_eq!(cells.last(), Some(&"yes"), "the compute pass found other edges: {row}");
    }
    let straight = stdout
        .lines()
        .find(|l| l.starts_with("| lines, straight"))
        .unwrap_or_else(|| panic!("no straight-lines row:\n{stdout}"));
    let cells: Vec<&str> = straight.split('|').map(str::trim).filter(|c| !c.is_empty()).collect();
    let (precision, recall): (f64, f64) = (cells[3].parse().expect("p"), cells[4].parse().expect("r"));
    assert!(precision >= 0.95 && recall >= 0.95, "{straight}");
    assert!(stdout.lines().any(|l| l.starts_with("| LSA full")), "{stdout}");
    let o = npr(&["bench", "lines", "--segments", "2"]);
    assert_eq!(o.status.code(), Some(1), "2 segments is a user error");
}

/// Decoded RGBA bytes of a PNG.
fn rgba(path: &Path) -> Vec<u8> {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8()
        .into_raw()
}

#[test]
fn the_ocean_loops_seamlessly_over_its_period() {
    // Age of Sail §6.1: "a clip lasting 20 seconds, whose first and last
    // frames match seamlessly". At 0.1 fps frames 0, 1, 2 are t = 0, 10 and
    // 20 s, rendered by one renderer that rewrites the ocean's vertices per
    // frame. The geometry, the live texture (0.5 Hz: 10 cycles) and the
    // keyframed overlay/saturation all have period 20 s.
    let dir = scratch("ocean_loop");
    let out = dir.join("ocean_{frame}.png");
    let o = npr(&[
        "render",
        "examples/ocean.npr",
        "--scene",
        "examples/scenes/ocean.toml",
        "-o",
        out.to_str().expect("utf-8 path"),
        "--size",
        "96x96",
        "--frames",
        "0..3",
        "--fps",
        "0.1",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let [first, middle, last] = [0, 1, 2].map(|f| rgba(&dir.join(format!("ocean_{f:04}.png"))));
    let differing = |a: &[u8], b: &[u8]| {
        let max = a.iter().zip(b).map(|(x, y)| x.abs_diff(*y)).max().unwrap_or(0);
        let pixels = a.chunks(4).zip(b.chunks(4)).filter(|(p, q)| p != q).count();
        (max, pixels)
    };
    // t = 20 s against t = 0: the time in the shader is an f32 and the
    // live texture's phase reaches 2π·10, so a pixel may round differently;
    // nothing else may change.
    let (max, pixels) = differing(&first, &last);
    assert!(
        max <= 1 && pixels * 1000 <= first.len() / 4,
        "t = 20 s vs 0 s: max {max}/255, {pixels} pixels differ"
    );
    // Half a period in, the sea has moved: the comparison can fail.
    let (max, pixels) = differing(&first, &middle);
    assert!(
        max > 40 && pixels * 2 > first.len() / 4,
        "t = 10 s vs 0 s: max {max}, {pixels} pixels differ"
    );
}

#[test]
fn shipped_noise_textures_are_what_texgen_writes() {
    // The commands documented in examples/textures/SOURCES.md.
    let dir = scratch("texgen");
    for (file, args) in [
        (
            "warp_noise.png",
            &["--size", "256", "--octaves", "4", "--channels", "2", "--seed", "11"][..],
        ),
        (
            "breakup.png",
            &[
                "--size",
                "128",
                "--octaves",
                "3",
                "--channels",
                "1",
                "--seed",
                "5",
                "--frequency",
                "8",
                "--kind",
                "value",
            ][..],
        ),
    ] {
        let out = dir.join(file);
        let mut cmd = vec!["texgen", "-o", out.to_str().expect("utf-8 path")];
        cmd.extend_from_slice(args);
        let o = npr(&cmd);
        assert_eq!(o.status.code(), Some(0), "{file}: {}", stderr(&o));
        let fresh = image::open(&out).expect("written").to_rgba16();
        let shipped = image::open(
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("examples/textures")
                .join(file),
        )
        .expect("shipped")
        .to_rgba16();
        assert_eq!(fresh.dimensions(), shipped.dimensions(), "{file}");
        assert!(
            fresh.as_raw() == shipped.as_raw(),
            "{file}: texgen no longer reproduces the shipped texture"
        );
    }
    // Bad arguments are user errors, with nothing written.
    let bad = dir.join("bad.png");
    let o = npr(&["texgen", "-o", bad.to_str().expect("utf-8 path"), "--channels", "7"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("channels"), "{}", stderr(&o));
    assert!(!bad.exists());
}

#[test]
fn texgen_paint_writes_the_checked_in_age_of_sail_paint_map() {
    let out = scratch("texgen-paint").join("spot_lit.png");
    let o = npr(&[
        "texgen",
        "-o",
        out.to_str().expect("utf-8 path"),
        "--kind",
        "paint",
        "--color",
        "#e9c48a",
        "--size",
        "64",
        "--seed",
        "3",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let written = image::open(&out).expect("written png").to_rgba8();
    let checked_in = image::open(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/textures/paint_spot_lit.png"))
        .expect("checked-in png")
        .to_rgba8();
    assert!(
        written == checked_in,
        "npr texgen --kind paint differs from examples/textures/paint_spot_lit.png"
    );
    // A paint map needs its base colour.
    let o = npr(&["texgen", "-o", out.to_str().expect("utf-8 path"), "--kind", "paint"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("--color"), "{}", stderr(&o));
}

#[test]
fn render_compiled_runs_a_compiled_dir_and_rejects_a_bad_one() {
    let dir = scratch("compiled");
    let build = dir.join("toon");
    let o = npr(&["compile", "examples/toon.npr", "-o", build.to_str().expect("utf-8")]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let png = dir.join("toon.png");
    let o = npr(&[
        "render",
        "--compiled",
        build.to_str().expect("utf-8"),
        "--scene",
        "examples/scenes/spot.toml",
        "--size",
        "32x32",
        "-o",
        png.to_str().expect("utf-8"),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(png.exists());
    // An out-of-range index: exit 1 with the field named, no panic.
    let manifest = std::fs::read_to_string(build.join("manifest.json")).expect("manifest");
    let mut json: serde_json::Value = serde_json::from_str(&manifest).expect("json");
    json["output"] = serde_json::Value::from(42);
    std::fs::write(build.join("manifest.json"), json.to_string()).expect("write");
    let o = npr(&[
        "render",
        "--compiled",
        build.to_str().expect("utf-8"),
        "--scene",
        "examples/scenes/spot.toml",
        "-o",
        png.to_str().expect("utf-8"),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("`output`"), "{}", stderr(&o));
    // Not a compiled directory at all.
    let o = npr(&[
        "render",
        "--compiled",
        dir.join("nothing").to_str().expect("utf-8"),
        "--scene",
        "examples/scenes/spot.toml",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    // Neither a directory nor a bundle: the path, and both things it could be.
    let text = stderr(&o);
    assert!(
        text.contains("error[E0504]") && text.contains("nothing: cannot read"),
        "{text}"
    );
    assert!(text.contains("npr compile -o DIR") && text.contains(".nprb"), "{text}");
}

/// An installed npr outside the repository: `npr doc` writes the committed
/// reference, and the benchmarks whose defaults name `examples/` run, from
/// the files built into the binary.
#[test]
fn doc_and_bench_work_from_any_directory() {
    let dir = scratch("elsewhere");
    let run = |args: &[&str]| {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
            .args(args)
            .current_dir(&dir)
            .env("XDG_RUNTIME_DIR", std::env::temp_dir())
            .output()
            .expect("run npr");
        assert_eq!(o.status.code(), Some(0), "npr {args:?}: {}", stderr(&o));
    };
    run(&["doc", "-o", "ref"]);
    let committed = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/reference");
    for entry in std::fs::read_dir(&committed).expect("docs/reference") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "md" || e == "html" || e == "css") {
            let name = path.file_name().expect("name");
            let written = std::fs::read_to_string(dir.join("ref").join(name)).expect("written page");
            assert!(
                written == std::fs::read_to_string(&path).expect("committed page"),
                "{} differs from the one npr doc wrote outside the repository",
                path.display()
            );
        }
    }
    run(&["bench", "ops", "--size", "16x16", "--frames", "1"]);
    run(&["bench", "overhead", "--size", "16x16", "--frames", "2", "--warmup", "1"]);
    run(&["bench", "artmaps", "--sizes", "16", "--size", "16x16", "--frames", "1"]);
    run(&[
        "bench",
        "styles",
        "examples/toon.npr",
        "--scene",
        "examples/scenes/spot.toml",
        "--size",
        "16x16",
        "--frames",
        "1",
    ]);
}
