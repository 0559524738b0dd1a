//! `npr view`'s window: winit's `ApplicationHandler`, which turns input
//! into camera, clock and parameter changes, rebuilds on a save, and draws
//! a frame each time the window may (at the display's rate, or as fast as
//! frames render with `--no-vsync`).
//!
//! Lines a test or script can wait for (stderr): `view: build N shown`
//! once build N's first frame is presented, `view: build N failed` after a
//! bad save (the last good frame stays); with `--frames N`, the mean frame
//! time on stdout before it exits.

use super::camera::{Control, Held};
use super::clock::{Clock, FrameTimes};
use super::keys::{self, Action, Motion};
use super::params::Stepper;
use super::style::Loaded;
use super::surface::WindowGpu;
use super::ViewEvent;
use crate::build::{self, Inputs};
use crate::guard;
use crate::watcher::FileWatcher;
use npr_diag::exit::{EXIT_INTERNAL, EXIT_OK, EXIT_USER};
use npr_diag::printer::Printer;
use npr_diag::{Diagnostic, SourceMap};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::dpi::{PhysicalPosition, PhysicalSize};
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::ActiveEventLoop;
use winit::keyboard::PhysicalKey;
use winit::window::{Window, WindowId};

/// How often the title's frame time is refreshed.
const TITLE_EVERY: Duration = Duration::from_millis(250);

pub struct App<'p> {
    pub printer: &'p Printer,
    pub inputs: Inputs,
    /// The size of one eye's image at start.
    pub eye_size: (u32, u32),
    pub vsync: bool,
    /// `--frames N`: exit after N frames with their mean frame time.
    pub frames: Option<u32>,
    pub clock: Clock,
    pub watcher: FileWatcher,
    /// The process's exit code, once the loop ends.
    pub exit: i32,

    window: Option<Arc<Window>>,
    gpu: Option<WindowGpu>,
    /// What is shown, and a new build waiting for its first frame.
    shown: Option<Loaded>,
    pending: Option<(u64, Loaded)>,
    /// The build number of `shown`, and whether its first frame was reported.
    shown_build: u64,
    reported: bool,
    builds: u64,
    /// The files of the last good build, watched again after a bad one.
    last_good: Vec<PathBuf>,
    control: Control,
    held: Held,
    stepper: Stepper,
    cursor: Option<PhysicalPosition<f64>>,
    left: bool,
    right: bool,
    last_frame: Option<Instant>,
    times: FrameTimes,
    frames_drawn: u32,
    title_at: Option<Instant>,
    /// The last render error printed, so a failing frame is reported once.
    last_error: Option<String>,
}

impl<'p> App<'p> {
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        printer: &'p Printer,
        inputs: Inputs,
        eye_size: (u32, u32),
        vsync: bool,
        frames: Option<u32>,
        clock: Clock,
        watcher: FileWatcher,
    ) -> App<'p> {
        App {
            printer,
            inputs,
            eye_size,
            vsync,
            frames,
            clock,
            watcher,
            exit: EXIT_OK,
            window: None,
            gpu: None,
            shown: None,
            pending: None,
            shown_build: 0,
            reported: false,
            builds: 0,
            last_good: Vec::new(),
            control: Control::Scene,
            held: Held::default(),
            stepper: Stepper::default(),
            cursor: None,
            left: false,
            right: false,
            last_frame: None,
            times: FrameTimes::default(),
            frames_drawn: 0,
            title_at: None,
            last_error: None,
        }
    }

    fn print(&self, diagnostics: &[Diagnostic], sources: &SourceMap) {
        self.printer.diagnostics(diagnostics, sources);
    }

    /// Build the style again after a save; a bad build is reported and
    /// the last good frame stays.
    fn rebuild(&mut self) {
        let built = self.build();
        self.apply(built);
    }

    /// One build, a panic in it reported as E9001.
    fn build(&self) -> Result<build::Built, build::Failed> {
        guard::catch(|| build::build(&self.inputs, &[])).unwrap_or_else(|panic| {
            Err(build::Failed {
                diagnostics: vec![guard::panic_diagnostic(&panic)],
                sources: SourceMap::new(),
            })
        })
    }

    /// Take a build: a good one waits in `pending` for its first frame, a
    /// bad one is reported; then watch the files it read.
    fn apply(&mut self, built: Result<build::Built, build::Failed>) {
        let Some(gpu) = self.gpu.as_ref() else { return };
        self.builds += 1;
        let n = self.builds;
        let files = match built {
            Err(failed) => {
                self.print(&failed.diagnostics, &failed.sources);
                eprintln!("view: build {n} failed; kept the last good frame; fix the error and save");
                let mut files = build::dependencies(&self.inputs, &failed.sources, None);
                files.extend(self.last_good.iter().cloned());
                files
            }
            Ok(built) => {
                self.print(&built.compiled.warnings, &built.sources);
                let files = build::dependencies(&self.inputs, &built.sources, Some(&built));
                match Loaded::new(built, &gpu.device, &gpu.queue) {
                    Ok(loaded) => {
                        self.last_good = files.clone();
                        self.pending = Some((n, loaded));
                    }
                    Err(failed) => {
                        self.print(&failed.diagnostics, &failed.sources);
                        eprintln!("view: build {n} failed; kept the last good frame; fix the error and save");
                    }
                }
                files
            }
        };
        self.watcher.set_files(files);
    }

    /// The window's size for a style (both eyes side by side when stereo).
    fn window_size(&self, stereo: bool) -> PhysicalSize<u32> {
        let (w, h) = self.eye_size;
        PhysicalSize::new(if stereo { 2 * w } else { w }, h)
    }

    /// Make the pending build the shown one if its first frame renders;
    /// then render the shown one. `false` when nothing was recorded.
    fn record(&mut self, encoder: &mut wgpu::CommandEncoder, view: &wgpu::TextureView) -> bool {
        let time_s = self.clock.time_s;
        let frame = self.clock.frame();
        if let Some((n, mut candidate)) = self.pending.take() {
            let camera = self.control.camera(&candidate.scene.camera, time_s);
            let mut stepper = Stepper::new(&candidate.runtime.manifest().params);
            let carried = stepper.carry_over(&self.stepper);
            let set = carried
                .iter()
                .try_for_each(|(name, value)| candidate.set_param(name, value));
            match set.and_then(|()| candidate.render(encoder, view, &camera, time_s, frame)) {
                Ok(()) => {
                    let resized = self.shown.as_ref().is_none_or(|s| s.stereo != candidate.stereo);
                    if resized {
                        if let Some(w) = &self.window {
                            let _ = w.request_inner_size(self.window_size(candidate.stereo));
                        }
                    }
                    self.shown = Some(candidate);
                    self.stepper = stepper;
                    self.shown_build = n;
                    self.reported = false;
                    self.last_error = None;
                    return true;
                }
                Err(failed) => {
                    self.print(&failed.diagnostics, &failed.sources);
                    eprintln!("view: build {n} failed; kept the last good frame; fix the error and save");
                }
            }
        }
        let Some(shown) = self.shown.as_mut() else { return false };
        let camera = self.control.camera(&shown.scene.camera, time_s);
        match shown.render(encoder, view, &camera, time_s, frame) {
            Ok(()) => {
                self.last_error = None;
                true
            }
            Err(failed) => {
                let text = npr_diag::diagnostic::render(&failed.diagnostics, &failed.sources, false);
                if self.last_error.as_deref() != Some(&text) {
                    self.print(&failed.diagnostics, &failed.sources);
                    self.last_error = Some(text);
                }
                false
            }
        }
    }

    /// Draw one frame and present it.
    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let now = Instant::now();
        let dt = self.last_frame.map_or(Duration::ZERO, |t| now - t);
        self.last_frame = Some(now);
        self.clock.tick(dt);
        if let Control::Fly(f) = &mut self.control {
            f.advance(self.held, dt.as_secs_f64());
        }
        let Some(gpu) = self.gpu.as_mut() else { return };
        if let Some(size) = self.window.as_ref().map(|w| w.inner_size()) {
            gpu.resize(size.width, size.height);
        }
        let Some((image, view)) = gpu.next_image() else {
            self.request_redraw();
            return;
        };
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("npr view frame"),
        });
        if !self.record(&mut encoder, &view) {
            clear(&mut encoder, &view);
        }
        let Some(gpu) = self.gpu.as_ref() else { return };
        gpu.queue.submit([encoder.finish()]);
        gpu.queue.present(image);
        if let Some(lost) = gpu.watch.lost() {
            self.printer.diagnostics(
                &[Diagnostic::error(
                    npr_diag::codes::DEVICE_LOST,
                    format!("the GPU device was lost: {lost}"),
                )],
                &SourceMap::new(),
            );
            self.exit = EXIT_INTERNAL;
            event_loop.exit();
            return;
        }
        let size = gpu.size();
        if self.shown.is_some() && !self.reported {
            self.reported = true;
            let (w, h) = size;
            let gpu = self.gpu.as_ref().map_or(String::new(), |g| g.adapter.clone());
            eprintln!("view: build {} shown ({w}x{h}, {gpu})", self.shown_build);
        }
        // The first frame builds the style's resources: not a frame time.
        if self.frames_drawn > 0 {
            self.times.record(dt);
        }
        self.frames_drawn += 1;
        self.update_title(now);
        if let Some(n) = self.frames {
            if self.frames_drawn >= n.saturating_add(1) {
                let (mean, count) = self.times.mean_ms();
                let (w, h) = size;
                println!(
                    "view: {count} frames at {w}x{h}: mean frame time {mean:.3} ms ({:.1} fps), {}",
                    1e3 / mean.max(1e-9),
                    if self.vsync {
                        "at the display's rate"
                    } else {
                        "no vsync"
                    }
                );
                event_loop.exit();
                return;
            }
        }
        self.request_redraw();
    }

    fn request_redraw(&self) {
        if let Some(w) = &self.window {
            w.request_redraw();
        }
    }

    fn update_title(&mut self, now: Instant) {
        if self.title_at.is_some_and(|t| now - t < TITLE_EVERY) {
            return;
        }
        self.title_at = Some(now);
        let Some(w) = &self.window else { return };
        let ms = self.times.recent_mean_ms();
        let mut title = format!(
            "npr view — {} — {ms:.1} ms ({:.0} fps) — t = {:.2} s{} — {}",
            self.inputs.style.display(),
            if ms > 0.0 { 1e3 / ms } else { 0.0 },
            self.clock.time_s,
            if self.clock.paused { " (paused)" } else { "" },
            self.control.name()
        );
        if let Some(p) = self.stepper.describe() {
            title.push_str(&format!(" — {p}"));
        }
        w.set_title(&title);
    }

    fn key(&mut self, action: Action, pressed: bool, event_loop: &ActiveEventLoop) {
        if let Action::Move(m) = action {
            let h = &mut self.held;
            match m {
                Motion::Forward => h.forward = pressed,
                Motion::Back => h.back = pressed,
                Motion::Left => h.left = pressed,
                Motion::Right => h.right = pressed,
                Motion::Up => h.up = pressed,
                Motion::Down => h.down = pressed,
                Motion::Fast => h.fast = pressed,
            }
            if pressed && m != Motion::Fast && !matches!(self.control, Control::Fly(_)) {
                self.take_over(|c, cam, t| {
                    c.fly(cam, t);
                });
            }
            return;
        }
        if !pressed {
            return;
        }
        match action {
            Action::TogglePause => self.clock.paused = !self.clock.paused,
            Action::StepTime(n) => self.clock.step(n),
            Action::SwitchCamera => self.take_over(|c, cam, t| {
                if matches!(c, Control::Fly(_)) {
                    c.orbit(cam, t);
                } else {
                    c.fly(cam, t);
                }
            }),
            Action::SceneCamera => self.control = Control::Scene,
            Action::ChooseParam(d) => {
                self.stepper.choose(d);
                self.say_param();
            }
            Action::StepParam(d) => {
                if let Some((name, value)) = self.stepper.step(d) {
                    if let Some(shown) = self.shown.as_mut() {
                        if let Err(failed) = shown.set_param(&name, &value) {
                            self.print(&failed.diagnostics, &failed.sources);
                        }
                    }
                    self.say_param();
                }
            }
            Action::Quit => event_loop.exit(),
            Action::Move(_) => {}
        }
        self.title_at = None;
    }

    fn say_param(&self) {
        match self.stepper.describe() {
            Some(p) => eprintln!("view: {p}"),
            None => eprintln!("view: the style has no parameter the keys can step (compiled in, or not a number)"),
        }
    }

    /// Change the camera control, given the scene camera and the time.
    fn take_over(&mut self, change: impl FnOnce(&mut Control, &npr_runner::scene::Camera, f64)) {
        if let Some(shown) = &self.shown {
            change(&mut self.control, &shown.scene.camera, self.clock.time_s);
        }
    }

    fn mouse_moved(&mut self, to: PhysicalPosition<f64>) {
        let from = self.cursor.replace(to);
        let Some(from) = from else { return };
        let (dx, dy) = (to.x - from.x, to.y - from.y);
        if !(self.left || self.right) {
            return;
        }
        let height = self.gpu.as_ref().map_or(1.0, |g| f64::from(g.size().1));
        let (left, right) = (self.left, self.right);
        self.take_over(|c, cam, t| {
            let fov = f64::from(cam.fov_y_rad);
            if let Control::Fly(f) = c {
                if left {
                    f.look(dx, dy);
                }
                return;
            }
            let o = c.orbit(cam, t);
            if left {
                o.drag(dx, dy);
            } else if right {
                o.pan(dx, dy, height, fov);
            }
        });
    }
}

/// The window's background before the first good build.
fn clear(encoder: &mut wgpu::CommandEncoder, view: &wgpu::TextureView) {
    let _ = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("npr view: no style yet"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view,
            resolve_target: None,
            depth_slice: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                store: wgpu::StoreOp::Store,
            },
        })],
        ..Default::default()
    });
}

impl ApplicationHandler<ViewEvent> for App<'_> {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_some() {
            return;
        }
        // The first build decides the window's width (stereo or not); its
        // GPU part waits for the device.
        let built = self.build();
        let stereo_guess = built.as_ref().is_ok_and(|b| b.compiled.manifest.is_stereo());
        let attributes = Window::default_attributes()
            .with_title("npr view")
            .with_inner_size(self.window_size(stereo_guess))
            .with_resize_increments(PhysicalSize::new(if stereo_guess { 2 } else { 1 }, 1));
        let window = match event_loop.create_window(attributes) {
            Ok(w) => Arc::new(w),
            Err(e) => {
                self.printer
                    .diagnostics(&[super::no_window(e.to_string())], &SourceMap::new());
                self.exit = EXIT_USER;
                event_loop.exit();
                return;
            }
        };
        match WindowGpu::new(window.clone(), event_loop.owned_display_handle(), self.vsync) {
            Ok(gpu) => self.gpu = Some(gpu),
            Err(d) => {
                self.printer.diagnostics(&[d], &SourceMap::new());
                self.exit = EXIT_USER;
                event_loop.exit();
                return;
            }
        }
        self.window = Some(window);
        self.apply(built);
        self.request_redraw();
    }

    fn user_event(&mut self, _: &ActiveEventLoop, event: ViewEvent) {
        match event {
            ViewEvent::Changed(files) => {
                let names: Vec<String> = files.iter().map(|p| p.display().to_string()).collect();
                eprintln!("view: changed: {}", names.join(", "));
                self.rebuild();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::RedrawRequested => self.redraw(event_loop),
            WindowEvent::Resized(size) => {
                if let Some(gpu) = self.gpu.as_mut() {
                    gpu.resize(size.width, size.height);
                }
                self.request_redraw();
            }
            WindowEvent::KeyboardInput { event, .. } => {
                if let PhysicalKey::Code(code) = event.physical_key {
                    if let Some(action) = keys::action(code) {
                        if !event.repeat || matches!(action, Action::StepParam(_) | Action::StepTime(_)) {
                            self.key(action, event.state == ElementState::Pressed, event_loop);
                        }
                    }
                }
            }
            WindowEvent::CursorMoved { position, .. } => self.mouse_moved(position),
            WindowEvent::CursorLeft { .. } => self.cursor = None,
            WindowEvent::MouseInput { state, button, .. } => {
                let down = state == ElementState::Pressed;
                match button {
                    MouseButton::Left => self.left = down,
                    MouseButton::Right | MouseButton::Middle => self.right = down,
                    _ => {}
                }
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let steps = match delta {
                    MouseScrollDelta::LineDelta(_, y) => f64::from(y),
                    MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
                };
                if !matches!(self.control, Control::Fly(_)) {
                    self.take_over(|c, cam, t| c.orbit(cam, t).zoom(steps));
                }
            }
            WindowEvent::Focused(false) => self.held = Held::default(),
            _ => {}
        }
    }
}
