//! `npr view`: a style on a scene in a live window, driven through the
//! runner's embedding API (`npr_runner::embed::StyleRuntime`), rebuilt on every
//! save through `npr watch`'s builder and file watcher (`live/`).
//!
//! - `app.rs`: the winit application: input, rebuilds, frames;
//! - `surface.rs`: the window's surface and device;
//! - `style.rs`: a build as a `StyleRuntime` with the scene's meshes, and
//!   one frame of it;
//! - `camera.rs`: orbit and fly cameras (pure math, tested in f64);
//! - `clock.rs`: the style's time and the frame times;
//! - `params.rs`: stepping a parameter from the keyboard;
//! - `keys.rs`: the key bindings and their help.

mod app;
pub mod camera;
mod clock;
pub mod keys;
mod params;
mod style;
mod surface;

use crate::build::Inputs;
use crate::watcher::FileWatcher;
use npr_diag::exit::EXIT_USER;
use npr_diag::printer::Printer;
use npr_diag::{codes, Diagnostic};
use std::path::PathBuf;

/// What reaches the window's event loop from other threads.
#[derive(Debug)]
pub enum ViewEvent {
    /// Watched files changed (the watcher's thread).
    Changed(Vec<PathBuf>),
}

/// No window can be opened: no display, or the display refused it.
fn no_window(e: String) -> Diagnostic {
    Diagnostic::error(codes::NO_DEVICE, format!("npr view cannot open a window: {e}")).with_help(
        "run it under a display (X11 or Wayland: DISPLAY or WAYLAND_DISPLAY set); without one, \
         `xvfb-run npr view ...` gives a virtual X display (Debian: `apt-get install -y xvfb`); \
         X11 also needs libX11, libxkbcommon-x11 and libXcursor (Debian: `apt-get install -y \
         libx11-xcb1 libxkbcommon-x11-0 libxcursor1`)",
    )
}

/// What `npr view` shows, and how.
pub struct ViewOptions {
    /// The style, its scene and how to build it (`keep_params: true` lets
    /// the keys step parameters without a recompile).
    pub inputs: Inputs,
    /// The window's inner size in pixels.
    pub size: (u32, u32),
    /// The style's time at the first frame, in seconds.
    pub time: f64,
    /// Start with the clock stopped.
    pub paused: bool,
    /// The frame rate that frame numbers and `time` are counted in.
    pub fps: f64,
    /// Close the window after this many frames (tests, screenshots).
    pub frames: Option<u32>,
    /// Present at the display's refresh rate.
    pub vsync: bool,
}

/// Open the window and run until it closes; the exit code
/// (`npr_diag::exit`).
pub fn run(options: ViewOptions, printer: &Printer) -> i32 {
    if let Err(code) = printer
        .check(npr_diag::sizes::check_size(options.size))
        .and_then(|()| printer.check(npr_diag::sizes::check_time(options.time, options.fps)))
    {
        return code;
    }
    let inputs = options.inputs;
    // winit loads the display's libraries (libX11, libxkbcommon-x11, ...)
    // here, and panics where one is missing: a diagnostic too.
    let event_loop =
        match npr_diag::panics::catch(|| winit::event_loop::EventLoop::<ViewEvent>::with_user_event().build()) {
            Ok(Ok(l)) => l,
            Ok(Err(e)) => return printer.fail(no_window(e.to_string())),
            Err(panic) => return printer.fail(no_window(panic)),
        };
    let proxy = event_loop.create_proxy();
    let watcher = match FileWatcher::new(move |files| {
        // The loop is gone only when the window closed.
        let _ = proxy.send_event(ViewEvent::Changed(files));
    }) {
        Ok(w) => w,
        Err(e) => return printer.fail(crate::watcher::cannot_watch(e)),
    };
    eprintln!("{}", keys::help());
    let clock = clock::Clock {
        time_s: options.time,
        paused: options.paused,
        fps: options.fps,
    };
    let mut app = app::App::new(
        printer,
        inputs,
        options.size,
        options.vsync,
        options.frames,
        clock,
        watcher,
    );
    if let Err(e) = event_loop.run_app(&mut app) {
        printer.diagnostics(&[no_window(e.to_string())], &npr_diag::SourceMap::new());
        return EXIT_USER;
    }
    app.exit
}
