//! The studio's render thread: it owns the device, the renderer and the
//! file watcher, takes [`Job`]s (a file changed, a control moved, the time or
//! eye changed, "write into the file"), and publishes each result to the
//! [`Hub`].
//!
//! - A file change rebuilds: scene + compile (with `--keep-params`, the
//!   `--set`s and the controls' values) + a new `Renderer`, through the same
//!   `npr_runner::Renderer` as `npr render`.
//! - A control change types the value by the `--set` rules against the
//!   running manifest (`npr_abi::param_value::type_value`), writes
//!   it into the renderer's manifest (a uniform) and renders again without
//!   recompiling. A rebuild passes the controls' values as written, after
//!   the `--set`s, so the compiler types them against the edited style.
//! - A failed build keeps the last good frame and publishes the
//!   diagnostics; a render error likewise. A panic is caught, reported, and
//!   the device and renderer are made again; the thread never ends while the
//!   server runs.

use super::hub::{FrameImages, Hub};
use super::orbit::Orbit;
use super::state;
use crate::build::{self, Built, Inputs};
use crate::guard;
use crate::watcher::FileWatcher;
use npr_abi::manifest::ParamBinding;
use npr_abi::param_value::{format_literal, type_value, ParamShape};
use npr_abi::ParamOverride;
use npr_compiler::ir::SettingOrigin;
use npr_diag::SourceMap;
use npr_runner::schedule::FrameRequest;
use npr_runner::{FrameSpec, Gpu, Renderer, RunError};
use serde_json::{json, Value};
use std::path::PathBuf;
use std::sync::mpsc::{Receiver, Sender};
use std::time::Instant;

pub enum Job {
    /// Watched files changed (or the first build).
    Rebuild(Vec<PathBuf>),
    /// A control: the parameter's value as the language writes it.
    SetParam { name: String, literal: String },
    /// Forget a control's value: back to the file's default.
    ResetParam(String),
    /// The time scrubber, the eye toggle and the orbit camera
    /// (`Some(None)`: back to the scene's camera).
    SetView {
        time: Option<f64>,
        eye: Option<u32>,
        orbit: Option<Option<Orbit>>,
    },
    /// Panic inside the render thread (only with `NPR_STUDIO_DEBUG=1`), to
    /// show that a panic is reported and the server keeps serving.
    Panic,
    /// Write the control's current value into the `.npr` file as its default.
    WriteParam(String),
}

/// What every render uses that is not in the style.
#[derive(Debug, Clone, Copy)]
pub struct View {
    pub size: (u32, u32),
    pub time: f64,
    pub fps: f64,
    pub eye: u32,
    /// The page's orbit/zoom camera, overriding the scene's.
    pub orbit: Option<Orbit>,
}

/// A build that rendered, with the renderer made for it.
struct Session {
    built: Built,
    renderer: Renderer,
    timer: Option<npr_runner::pass_timer::PassTimer>,
}

/// A control moved away from the file's default.
struct Control {
    /// The value as the page sent it: what a rebuild types again, as a `--set`.
    literal: String,
    /// The value typed against the running style: what the uniforms and the page show.
    typed: ParamOverride,
}

/// The thread's own state across builds and device restarts.
struct Studio {
    inputs: Inputs,
    view: View,
    hub: Hub,
    /// The controls' values, applied on every rebuild after the `--set`s.
    controls: Vec<Control>,
    frame_id: u64,
    /// The last good frame's description (kept while the style is broken).
    frame: Value,
    params: Value,
    diagnostics: Value,
    param_error: Value,
    notice: Value,
    compile_ms: f64,
    /// What the last good build depended on, watched while a build fails.
    last_good_files: Vec<PathBuf>,
    stereo: bool,
}

pub fn run(inputs: Inputs, view: View, hub: Hub, jobs: Receiver<Job>, job_sender: Sender<Job>) {
    let mut watcher = match FileWatcher::new(move |files| {
        let _ = job_sender.send(Job::Rebuild(files));
    }) {
        Ok(w) => Some(w),
        Err(e) => {
            eprintln!("studio: {e}; files are not watched");
            None
        }
    };
    let mut st = Studio {
        inputs,
        view,
        hub,
        controls: Vec::new(),
        frame_id: 0,
        frame: Value::Null,
        params: json!([]),
        diagnostics: json!([]),
        param_error: Value::Null,
        notice: Value::Null,
        compile_ms: 0.0,
        last_good_files: Vec::new(),
        stereo: false,
    };
    // The outer loop makes the device again after a panic; the inner one
    // serves jobs with it.
    loop {
        let gpu = match Gpu::headless() {
            Ok(g) => g,
            Err(e) => {
                st.diagnostics = state::diagnostics_json(&[e.to_diagnostic()], &SourceMap::new(), "device");
                st.publish(None);
                // Try again when something changes.
                if jobs.recv().is_err() {
                    return;
                }
                continue;
            }
        };
        let mut session: Option<Session> = None;
        let mut pending = Some(Pending::Rebuild);
        loop {
            if let Some(work) = pending.take() {
                let done = guard::catch(|| st.work(work, &gpu, &mut session, watcher.as_mut()));
                if let Err(panic) = done {
                    st.diagnostics =
                        state::diagnostics_json(&[guard::panic_diagnostic(&panic)], &SourceMap::new(), "panic");
                    st.publish(None);
                    break;
                }
                // A lost device (its E0509 is on the page) is made again,
                // and the style rebuilt on it.
                if gpu.watch.lost().is_some() {
                    break;
                }
            }
            let Ok(first) = jobs.recv() else { return };
            // Coalesce: a burst of slider moves renders once, with the last values.
            let mut batch = vec![first];
            while let Ok(more) = jobs.try_recv() {
                batch.push(more);
            }
            pending = batch
                .into_iter()
                .fold(None, |acc, job| Pending::merge(acc, st.take_job(job)));
        }
        drop(session);
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Pending {
    Render,
    Rebuild,
    /// `Job::Panic`: panic where rendering would happen.
    Panic,
}

impl Pending {
    fn merge(a: Option<Pending>, b: Option<Pending>) -> Option<Pending> {
        match (a, b) {
            (Some(Pending::Panic), _) | (_, Some(Pending::Panic)) => Some(Pending::Panic),
            (Some(Pending::Rebuild), _) | (_, Some(Pending::Rebuild)) => Some(Pending::Rebuild),
            (Some(Pending::Render), _) | (_, Some(Pending::Render)) => Some(Pending::Render),
            _ => None,
        }
    }
}

impl Studio {
    fn publish(&self, images: Option<FrameImages>) {
        let state = json!({
            "style": self.inputs.style.display().to_string(),
            "scene": self.inputs.scene.display().to_string(),
            "frame": self.frame,
            "params": self.params,
            "diagnostics": self.diagnostics,
            "param_error": self.param_error,
            "notice": self.notice,
            "view": { "time": self.view.time, "eye": self.view.eye, "fps": self.view.fps,
                      "width": self.view.size.0, "height": self.view.size.1, "stereo": self.stereo,
                      "orbit": self.view.orbit.map(Orbit::to_json) },
        });
        self.hub.publish(state, images);
    }

    /// Take a job's effect on the state; what it needs done next.
    fn take_job(&mut self, job: Job) -> Option<Pending> {
        self.param_error = Value::Null;
        self.notice = Value::Null;
        match job {
            Job::Rebuild(files) => {
                if !files.is_empty() {
                    let names: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
                    eprintln!("studio: changed: {}", names.join(", "));
                }
                Some(Pending::Rebuild)
            }
            Job::SetView { time, eye, orbit } => {
                if let Some(t) = time.filter(|t| t.is_finite()) {
                    self.view.time = t;
                }
                if let Some(o) = orbit {
                    self.view.orbit = o;
                }
                if let Some(e) = eye {
                    if e == 0 || (e == 1 && self.stereo) {
                        self.view.eye = e;
                    }
                }
                Some(Pending::Render)
            }
            Job::ResetParam(name) => {
                self.controls.retain(|c| c.typed.name != name);
                Some(Pending::Rebuild)
            }
            Job::SetParam { name, literal } => self.set_param(&name, &literal),
            Job::Panic => Some(Pending::Panic),
            Job::WriteParam(name) => {
                self.write_param(&name);
                // The watcher sees the write and rebuilds; publish the notice now.
                self.publish(None);
                None
            }
        }
    }

    fn manifest_param(&self, name: &str) -> Option<npr_abi::manifest::ParamManifest> {
        serde_json::from_value::<Vec<state::ParamState>>(self.params.clone())
            .ok()?
            .into_iter()
            .find(|p| p.manifest.name == name)
            .map(|p| p.manifest)
    }

    /// The controls' typed values, for the page and the uniforms.
    fn typed_controls(&self) -> Vec<ParamOverride> {
        self.controls.iter().map(|c| c.typed.clone()).collect()
    }

    /// Each value as the page shows it where it is written with a unit:
    /// the file's default as written (`50mm`), then a control's as typed.
    fn written_literals(&self) -> std::collections::BTreeMap<String, String> {
        let mut written = std::fs::read_to_string(&self.inputs.style)
            .map(|text| super::write_back::unit_defaults_as_written(&text))
            .unwrap_or_default();
        for c in &self.controls {
            written.insert(c.typed.name.clone(), c.literal.clone());
        }
        written
    }

    fn set_param(&mut self, name: &str, literal: &str) -> Option<Pending> {
        let Some(param) = self.manifest_param(name) else {
            self.param_error = json!({ "name": name, "message": format!("the style has no parameter `{name}`") });
            self.publish(None);
            return None;
        };
        let literal = literal.trim();
        let value = npr_abi::param_literal::read_literal(literal);
        match type_value(
            &ParamShape::of_manifest(&param),
            &value,
            literal,
            &SettingOrigin::CommandLine,
        ) {
            Ok(o) => {
                self.controls.retain(|c| c.typed.name != o.name);
                self.controls.push(Control {
                    literal: literal.to_string(),
                    typed: o,
                });
                // A kept uniform changes without a recompile.
                Some(
                    if param.binding == ParamBinding::Uniform && !param.default_percent_of_height {
                        Pending::Render
                    } else {
                        Pending::Rebuild
                    },
                )
            }
            Err(e) => {
                self.param_error = json!({ "name": name, "code": e.code,
                    "message": format!("{}: {}", e.code, e.message), "help": e.help });
                self.publish(None);
                None
            }
        }
    }

    fn write_param(&mut self, name: &str) {
        let Some(o) = self
            .controls
            .iter()
            .find(|c| c.typed.name == name)
            .map(|c| c.typed.clone())
        else {
            self.notice = json!(format!("`{name}` already has the file's value"));
            return;
        };
        let Some(param) = self.manifest_param(name) else { return };
        // The value as it was typed (`20mm` stays `20mm` in the file), which
        // typed against this parameter; else formatted from its value.
        let typed = self
            .controls
            .iter()
            .find(|c| c.typed.name == name)
            .map(|c| c.literal.clone());
        let literal = if param.ty == npr_abi::gradient::GRADIENT_TYPE {
            // A file writes a gradient as the language does,
            // `gradient(stop(0.0, #000000), ...)`, not as `--set` text.
            npr_abi::gradient::unpack(&o.value)
                .map(|(stops, constant)| npr_abi::gradient::declaration_text(&stops, constant))
        } else {
            typed
        };
        let literal = literal.or_else(|| {
            if o.percent_of_height {
                Some(format!("{}%", o.value[0]))
            } else {
                format_literal(&ParamShape::of_manifest(&param), &o.value)
            }
        });
        let Some(literal) = literal else { return };
        match super::write_back::rewrite_default(&self.inputs.style, name, &literal) {
            Ok(()) => {
                self.controls.retain(|c| c.typed.name != name);
                self.notice = json!(format!(
                    "wrote `{name} = {literal}` into {}",
                    self.inputs.style.display()
                ));
            }
            Err(e) => self.notice = json!(format!("cannot write `{name}` into the file: {e}")),
        }
    }

    fn work(&mut self, work: Pending, gpu: &Gpu, session: &mut Option<Session>, watcher: Option<&mut FileWatcher>) {
        if work == Pending::Panic {
            panic!("forced by POST /debug/panic (NPR_STUDIO_DEBUG=1)");
        }
        if work == Pending::Rebuild || session.is_none() {
            let files = self.rebuild(gpu, session);
            if let Some(w) = watcher {
                w.set_files(files);
            }
        } else if let Some(s) = session.as_mut() {
            for c in &self.controls {
                if let Some(p) = s.renderer.params_mut().iter_mut().find(|p| p.name == c.typed.name) {
                    p.set_constant(&c.typed);
                }
            }
            let typed = self.typed_controls();
            let written = self.written_literals();
            if let Some(p) = &mut self.params.as_array_mut() {
                state::set_values(p, &typed, &written);
            }
        }
        if let Some(s) = session.as_mut() {
            self.render(gpu, s);
        } else {
            self.publish(None);
        }
    }

    /// Build and make a renderer; the files to watch.
    fn rebuild(&mut self, gpu: &Gpu, session: &mut Option<Session>) -> Vec<PathBuf> {
        let controls: Vec<String> = self
            .controls
            .iter()
            .map(|c| format!("{}={}", c.typed.name, c.literal))
            .collect();
        let built = match build::build(&self.inputs, &controls) {
            Ok(b) => b,
            Err(failed) => {
                self.diagnostics = state::diagnostics_json(&failed.diagnostics, &failed.sources, "compile");
                let mut files = build::dependencies(&self.inputs, &failed.sources, None);
                files.extend(self.last_good_files.iter().cloned());
                *session = None;
                return files;
            }
        };
        let files = build::dependencies(&self.inputs, &built.sources, Some(&built));
        self.last_good_files = files.clone();
        self.compile_ms = built.compile_ms;
        self.stereo = built.scene.camera.is_stereo();
        if !self.stereo {
            self.view.eye = 0;
        }
        // Drop the old renderer (its pipelines and textures) before making the new one.
        *session = None;
        let program = built.compiled.program();
        let renderer = gpu
            .watch
            .check(Renderer::new(&gpu.device, &gpu.queue, &program, &built.scene))
            .map_err(|e| e.at_texture_spans(&built.compiled.texture_spans));
        match renderer {
            Ok(renderer) => {
                self.params = state::params_json(
                    &built.compiled.manifest.params,
                    &self.typed_controls(),
                    &self.written_literals(),
                );
                self.diagnostics = state::diagnostics_json(&built.warnings(), &built.sources, "compile");
                let timer = npr_runner::pass_timer::PassTimer::new(gpu, renderer.manifest().passes.len());
                *session = Some(Session { built, renderer, timer });
            }
            Err(e) => {
                self.diagnostics = state::diagnostics_json(&e.diagnostics(), &built.sources, "render");
            }
        }
        files
    }

    fn render(&mut self, gpu: &Gpu, s: &mut Session) {
        let start = Instant::now();
        match gpu.watch.check(render_frame(gpu, s, &self.view)) {
            Ok((images, pass_ms)) => {
                let render_ms = start.elapsed().as_secs_f64() * 1e3;
                self.frame_id += 1;
                let manifest = s.renderer.manifest();
                let targets: Vec<Value> = images
                    .iter()
                    .enumerate()
                    .map(|(i, t)| {
                        json!({
                            "index": i, "name": t.name, "format": format!("{:?}", t.format),
                            "float": t.is_float(), "width": t.width, "height": t.height,
                        })
                    })
                    .collect();
                let frame = FrameImages::new(self.frame_id, images);
                self.frame = json!({
                    "id": self.frame_id,
                    "output": manifest.output,
                    "targets": targets,
                    "compile_ms": self.compile_ms,
                    "render_ms": render_ms,
                    "passes": pass_ms.map(|ms| manifest.passes.iter().zip(ms).map(|(p, ms)| json!({"name": p.name, "gpu_ms": ms})).collect::<Vec<_>>()),
                    "device": gpu.describe(),
                    "memory": memory_json(gpu),
                    "time": self.view.time,
                    "eye": self.view.eye,
                });
                // Keep compile warnings; drop an old render error.
                if let Some(d) = self.diagnostics.as_array_mut() {
                    d.retain(|d| d["stage"] == "compile");
                }
                self.publish(Some(frame));
            }
            Err(e) => {
                self.diagnostics = state::diagnostics_json(&e.diagnostics(), &s.built.sources, "render");
                self.publish(None);
            }
        }
    }
}

/// Render the view's frame (replaying history for a path-dependent style
/// with a fresh renderer) and read every target; the per-pass GPU times of
/// the last frame when the adapter has timestamps.
fn render_frame(
    gpu: &Gpu,
    s: &mut Session,
    view: &View,
) -> Result<(Vec<npr_runner::TargetImage>, Option<Vec<f64>>), RunError> {
    let path_dependent = s.renderer.manifest().is_path_dependent();
    if path_dependent && s.renderer.frames_begun() > 0 {
        // History must start from frame 0 again, as `npr render` starts:
        // `restart_history` restarts it (history, compute state, previous
        // transforms) and keeps the pipelines and style textures, which a
        // new renderer would make again for every slider move
        // (docs/decisions/0044, 0046).
        s.renderer.restart_history();
    }
    let schedule = npr_runner::schedule::schedule(FrameRequest::At { time_s: view.time }, view.fps, path_dependent);
    // The page's orbit camera replaces the scene's for every frame.
    let orbited;
    let scene = match view.orbit {
        Some(o) => {
            orbited = o.scene(&s.built.scene, view.time);
            &orbited
        }
        None => &s.built.scene,
    };
    let spec = |time_s: f64, frame: u32| FrameSpec {
        width: view.size.0,
        height: view.size.1,
        time_s,
        frame,
        eye: view.eye,
    };
    let Some((last, replay)) = schedule.split_last() else {
        return Err(RunError::Internal("an empty frame schedule".into()));
    };
    for f in replay {
        s.renderer.render(scene, &spec(f.time_s, f.frame))?;
    }
    let spec = spec(last.time_s, last.frame);
    let times = match &s.timer {
        Some(t) => Some(t.frame(gpu, &mut s.renderer, scene, &spec)?),
        None => {
            s.renderer.render(scene, &spec)?;
            None
        }
    };
    let images = s.renderer.read_all_targets(scene, &spec)?;
    Ok((images, times))
}

/// What the studio holds after this frame: the process's resident memory
/// (`VmRSS`) and the GPU memory wgpu's allocator has (Vulkan; `null`
/// elsewhere), so a leak across rebuilds shows (`npr bench studio`).
fn memory_json(gpu: &Gpu) -> Value {
    let rss_kib = std::fs::read_to_string("/proc/self/status").ok().and_then(|s| {
        s.lines()
            .find_map(|l| l.strip_prefix("VmRSS:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
    });
    let report = gpu.device.generate_allocator_report();
    json!({
        "rss_kib": rss_kib,
        "gpu_allocated_bytes": report.as_ref().map(|r| r.total_allocated_bytes),
        "gpu_reserved_bytes": report.as_ref().map(|r| r.total_reserved_bytes),
    })
}
