//! `npr bench studio`: what the studio adds to a frame, end to end over
//! its real HTTP server and event stream, against `npr render`'s own frame
//! time in the same run, and the memory it holds across edits.
//!
//! - **`npr render` frame**: in this process, the style compiled as `npr
//!   render` compiles it, `Renderer::render` + read-back of the output, the
//!   median of `--frames`.
//! - **slider → image**: `POST /param` (alternating two values) until the
//!   page's event stream has the new frame and its output PNG is fetched;
//!   overhead = that − the `npr render` frame.
//! - **save → image**: the style saved by rename (a comment changed) until
//!   the rebuilt frame's PNG is fetched; overhead = that − the build's
//!   compile time (the studio's own figure) − the `npr render` frame. It
//!   includes the file watcher's debounce (`npr_live::watcher::QUIET`).
//! - **memory**: the studio's resident memory and wgpu's allocated GPU
//!   memory (the frame's `memory`), after edits 10, 100, 250, 500 and 750
//!   and after all `--edits` (alternating slider moves and saves), so a
//!   steady growth shows apart from the first edits' warm-up.
//!
//! The studio is a child `npr studio` process on a free port; the style is
//! edited as a temporary copy beside the original (so relative paths hold),
//! removed at the end.

use super::http_client::{request, Events};
use npr_diag::exit::{EXIT_INTERNAL, EXIT_OK};
use npr_diag::printer::Printer;
use npr_diag::{codes, Diagnostic, SourceMap};
use npr_runner::{FrameSpec, Renderer};
use serde_json::{json, Value};
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Instant;

pub struct StudioBench<'a> {
    pub style: &'a Path,
    pub scene: &'a Path,
    pub size: (u32, u32),
    pub frames: u32,
    pub edits: u32,
    pub param: &'a str,
    pub values: (&'a str, &'a str),
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    if v.is_empty() {
        f64::NAN
    } else {
        v[v.len() / 2]
    }
}

fn frame_id(s: &Value) -> u64 {
    s["frame"]["id"].as_u64().unwrap_or(0)
}

/// The child studio, killed when dropped; the temporary style removed.
struct Studio {
    child: Child,
    addr: String,
    copy: PathBuf,
}

impl Drop for Studio {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
        let _ = std::fs::remove_file(&self.copy);
    }
}

fn start(b: &StudioBench, copy: &Path) -> Result<Studio, String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let size = format!("{}x{}", b.size.0, b.size.1);
    let mut child = Command::new(exe)
        .arg("studio")
        .arg(copy)
        .arg("--scene")
        .arg(b.scene)
        .args(["--size", &size, "--port", "0"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .map_err(|e| format!("cannot start npr studio: {e}"))?;
    let out = child.stdout.take().ok_or("no stdout")?;
    let mut lines = BufReader::new(out).lines();
    let addr = loop {
        match lines.next() {
            Some(Ok(l)) if l.contains("http://") => {
                break l
                    .split("http://")
                    .nth(1)
                    .unwrap_or("")
                    .trim_end_matches('/')
                    .to_string()
            }
            Some(Ok(_)) => continue,
            _ => return Err("npr studio exited before printing its address".into()),
        }
    };
    // Keep draining its stdout so it never blocks on a full pipe.
    std::thread::spawn(move || lines.for_each(drop));
    Ok(Studio {
        child,
        addr,
        copy: copy.to_path_buf(),
    })
}

/// The output PNG of state `s`, fetched as the page fetches it.
fn fetch_output(addr: &str, s: &Value) -> Result<(), String> {
    let path = format!("/frame/{}/{}.png", frame_id(s), s["frame"]["output"]);
    match request(addr, "GET", &path, "")? {
        (200, body) if !body.is_empty() => Ok(()),
        (status, _) => Err(format!("GET {path}: {status}")),
    }
}

/// `npr render`'s frame time (ms): render + read-back of the output.
fn render_frame_ms(b: &StudioBench, printer: &Printer) -> Result<f64, i32> {
    let mut sources = SourceMap::new();
    let (scene, compiled, gpu) = super::scene_style_gpu(b.style, b.scene, &mut sources, printer)?;
    let program = compiled.program();
    let fail = |e: npr_runner::RunError| {
        printer.diagnostics(&e.diagnostics(), &sources);
        EXIT_INTERNAL
    };
    let mut r = Renderer::new(&gpu.device, &gpu.queue, &program, &scene).map_err(fail)?;
    let spec = FrameSpec {
        width: b.size.0,
        height: b.size.1,
        time_s: 0.0,
        frame: 0,
        eye: 0,
    };
    let mut times = Vec::new();
    for i in 0..b.frames + 3 {
        let t = Instant::now();
        r.render(&scene, &spec).map_err(fail)?;
        r.read_output().map_err(fail)?;
        if i >= 3 {
            times.push(t.elapsed().as_secs_f64() * 1e3);
        }
    }
    Ok(median(&mut times))
}

struct Edit {
    total_ms: f64,
    /// The studio's compile time for a save, 0 for a slider.
    compile_ms: f64,
    /// The studio's own render + read-back of every target (its thumbnails).
    studio_render_ms: f64,
    memory: Value,
}

fn slider(studio: &Studio, events: &mut Events, b: &StudioBench, k: u32, last: u64) -> Result<(Edit, u64), String> {
    let value = if k.is_multiple_of(2) { b.values.1 } else { b.values.0 };
    let t = Instant::now();
    let body = json!({"name": b.param, "literal": value}).to_string();
    match request(&studio.addr, "POST", "/param", &body)? {
        (202, _) => {}
        (status, body) => return Err(format!("POST /param: {status} {}", String::from_utf8_lossy(&body))),
    }
    let s = events.until(|s| {
        frame_id(s) > last
            && s["params"]
                .as_array()
                .is_some_and(|p| p.iter().any(|p| p["name"] == b.param && p["literal"] == value))
            || !s["param_error"].is_null()
    })?;
    if !s["param_error"].is_null() {
        return Err(format!("--param {}: {}", b.param, s["param_error"]["message"]));
    }
    fetch_output(&studio.addr, &s)?;
    let edit = Edit {
        total_ms: t.elapsed().as_secs_f64() * 1e3,
        compile_ms: 0.0,
        studio_render_ms: s["frame"]["render_ms"].as_f64().unwrap_or(f64::NAN),
        memory: s["frame"]["memory"].clone(),
    };
    Ok((edit, frame_id(&s)))
}

fn save(studio: &Studio, events: &mut Events, text: &str, k: u32, last: u64) -> Result<(Edit, u64), String> {
    let tmp = studio.copy.with_extension("npr.saving");
    std::fs::write(&tmp, format!("{text}\n// npr bench studio: save {k}\n")).map_err(|e| e.to_string())?;
    let t = Instant::now();
    std::fs::rename(&tmp, &studio.copy).map_err(|e| e.to_string())?;
    let s = events.until(|s| frame_id(s) > last)?;
    fetch_output(&studio.addr, &s)?;
    let edit = Edit {
        total_ms: t.elapsed().as_secs_f64() * 1e3,
        compile_ms: s["frame"]["compile_ms"].as_f64().unwrap_or(f64::NAN),
        studio_render_ms: s["frame"]["render_ms"].as_f64().unwrap_or(f64::NAN),
        memory: s["frame"]["memory"].clone(),
    };
    Ok((edit, frame_id(&s)))
}

fn mib(memory: &Value, key: &str, scale: f64) -> String {
    memory[key]
        .as_f64()
        .map_or("n/a".into(), |v| format!("{:.1}", v * scale / (1024.0 * 1024.0)))
}

pub fn run(b: &StudioBench, printer: &Printer) -> i32 {
    let frame_ms = match render_frame_ms(b, printer) {
        Ok(ms) => ms,
        Err(code) => return code,
    };
    let text = match std::fs::read_to_string(b.style) {
        Ok(t) => t,
        Err(e) => {
            return printer.fail(Diagnostic::error(
                codes::BENCH_UNSUPPORTED,
                format!("{}: {e}", b.style.display()),
            ))
        }
    };
    let dir = b.style.parent().unwrap_or(Path::new("."));
    let copy = dir.join(format!(".npr-bench-studio-{}.npr", std::process::id()));
    if let Err(e) = std::fs::write(&copy, &text) {
        return printer.fail(Diagnostic::error(
            codes::BENCH_UNSUPPORTED,
            format!("{}: {e}", copy.display()),
        ));
    }
    match measure(b, &copy, &text, frame_ms) {
        Ok(()) => EXIT_OK,
        Err(e) => {
            printer.fail(Diagnostic::error(codes::BENCH_UNSUPPORTED, "the studio benchmark could not run").with_note(e))
        }
    }
}

fn measure(b: &StudioBench, copy: &Path, text: &str, frame_ms: f64) -> Result<(), String> {
    let studio = start(b, copy).inspect_err(|_| drop(std::fs::remove_file(copy)))?;
    let mut events = Events::open(&studio.addr)?;
    let first = events.until(|s| frame_id(s) > 0 || !s["diagnostics"].as_array().is_none_or(|d| d.is_empty()))?;
    if frame_id(&first) == 0 {
        return Err(format!(
            "the style does not render in the studio: {}",
            first["diagnostics"]
        ));
    }
    let mut last = frame_id(&first);
    let (mut sliders, mut saves) = (Vec::new(), Vec::new());
    let mut memory_after: Vec<(u32, Value)> = vec![(0, first["frame"]["memory"].clone())];
    for k in 1..=b.edits.max(2) {
        let (edit, id) = if !k.is_multiple_of(2) {
            slider(&studio, &mut events, b, k, last)?
        } else {
            save(&studio, &mut events, text, k, last)?
        };
        last = id;
        if [10, 100, 250, 500, 750].contains(&k) || k == b.edits.max(2) {
            memory_after.push((k, edit.memory.clone()));
        }
        if !k.is_multiple_of(2) {
            sliders.push(edit);
        } else {
            saves.push(edit);
        }
    }
    let mut slider_total: Vec<f64> = sliders.iter().map(|e| e.total_ms).collect();
    let mut save_total: Vec<f64> = saves.iter().map(|e| e.total_ms).collect();
    let mut save_compile: Vec<f64> = saves.iter().map(|e| e.compile_ms).collect();
    let mut save_overhead: Vec<f64> = saves.iter().map(|e| e.total_ms - e.compile_ms - frame_ms).collect();
    let (slider_ms, save_ms) = (median(&mut slider_total), median(&mut save_total));
    let compile_ms = median(&mut save_compile);
    let mut slider_render: Vec<f64> = sliders.iter().map(|e| e.studio_render_ms).collect();
    let mut save_render: Vec<f64> = saves.iter().map(|e| e.studio_render_ms).collect();
    println!(
        "npr bench studio: {} on {}, {}x{}, {} edits ({} slider moves of `{}`, {} saves), medians",
        b.style.display(),
        b.scene.display(),
        b.size.0,
        b.size.1,
        b.edits.max(2),
        sliders.len(),
        b.param,
        saves.len()
    );
    println!();
    println!(
        "| step | to new image, ms | compile, ms | npr render frame, ms | overhead, ms | target | of which: studio render + read-back of every target, ms |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    println!(
        "| slider → image | {slider_ms:.1} | — | {frame_ms:.1} | {:.1} | ≤ 15 | {:.1} |",
        slider_ms - frame_ms,
        median(&mut slider_render)
    );
    println!(
        "| save → image | {save_ms:.1} | {compile_ms:.1} | {frame_ms:.1} | {:.1} | ≤ 30 | {:.1} |",
        median(&mut save_overhead),
        median(&mut save_render)
    );
    println!();
    println!("| after edit | studio RSS, MiB | GPU allocated, MiB | GPU reserved, MiB |");
    println!("|---:|---:|---:|---:|");
    for (k, m) in &memory_after {
        println!(
            "| {k} | {} | {} | {} |",
            mib(m, "rss_kib", 1024.0),
            mib(m, "gpu_allocated_bytes", 1.0),
            mib(m, "gpu_reserved_bytes", 1.0)
        );
    }
    Ok(())
}
