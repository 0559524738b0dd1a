//! `npr studio`: live authoring in the browser.
//!
//! - `server.rs`: the HTTP routes (tiny_http) and the event stream;
//! - `hub.rs`: the state and frame shared by the render and HTTP threads;
//! - `render_thread.rs`: builds, renders and publishes, never ending on an error;
//! - `state.rs`: the page's JSON (controls, diagnostics);
//! - `write_back.rs`: "write into the file";
//! - `malloc.rs`: one malloc arena, so resident memory stays flat across edits;
//! - `page.html`, `studio.js`, `studio.css`: the page, embedded with `include_str!`.

mod hub;
mod malloc;
pub mod orbit;
mod render_thread;
mod server;
pub mod state;
pub mod write_back;

use crate::build::Inputs;
use npr_diag::exit::EXIT_INTERNAL;
use npr_diag::printer::Printer;
use npr_diag::{codes, Diagnostic};
use std::io::Write;
use std::net::{IpAddr, SocketAddr};

pub struct StudioArgs {
    pub inputs: Inputs,
    pub size: (u32, u32),
    pub time: f64,
    pub fps: f64,
    pub eye: u32,
    pub host: String,
    pub port: u16,
}

/// Bind, print the address, and serve until interrupted.
pub fn run(args: StudioArgs, printer: &Printer) -> i32 {
    malloc::single_arena();
    if let Err(d) =
        npr_diag::sizes::check_size(args.size).and_then(|()| npr_diag::sizes::check_time(args.time, args.fps))
    {
        return printer.fail(d);
    }
    let ip: IpAddr = match args.host.parse() {
        Ok(ip) => ip,
        Err(_) => {
            return printer.fail(
                Diagnostic::error(
                    codes::BAD_ARGUMENT_VALUE,
                    format!("--host {}: not an IP address", args.host),
                )
                .with_help("give an address such as 127.0.0.1 (the default), ::1, or 0.0.0.0 for every interface"),
            )
        }
    };
    if !ip.is_loopback() {
        eprintln!(
            "warning: --host {ip}: the studio is reachable from other machines; it has no authentication, and anyone who reaches it can read the style and rewrite parameter defaults in it"
        );
    }
    let addr = SocketAddr::new(ip, args.port);
    let server = match tiny_http::Server::http(addr) {
        Ok(s) => s,
        Err(e) => return printer.fail(cannot_bind(addr, e.as_ref())),
    };
    let bound = server.server_addr().to_ip().unwrap_or(addr);
    let url = match bound.ip() {
        IpAddr::V6(ip) => format!("http://[{ip}]:{}/", bound.port()),
        IpAddr::V4(ip) => format!("http://{ip}:{}/", bound.port()),
    };
    println!("npr studio: {url}");
    let _ = std::io::stdout().flush();
    let hub = hub::Hub::default();
    let (jobs, job_rx) = std::sync::mpsc::channel();
    let view = render_thread::View {
        size: args.size,
        time: args.time,
        fps: args.fps,
        eye: args.eye,
        orbit: None,
    };
    let render_hub = hub.clone();
    let watcher_jobs = jobs.clone();
    let inputs = args.inputs;
    let spawned = std::thread::Builder::new()
        .name("npr studio render".into())
        .spawn(move || render_thread::run(inputs, view, render_hub, job_rx, watcher_jobs));
    if let Err(e) = spawned {
        return printer.fail(Diagnostic::error(
            codes::INTERNAL,
            format!("cannot start the render thread: {e}"),
        ));
    }
    server::serve(server, hub, jobs);
    EXIT_INTERNAL
}

/// The address cannot be bound: E0507, with a hint for the usual cause.
fn cannot_bind(addr: SocketAddr, e: &(dyn std::error::Error + 'static)) -> Diagnostic {
    let in_use = e
        .downcast_ref::<std::io::Error>()
        .is_some_and(|io| io.kind() == std::io::ErrorKind::AddrInUse);
    let d = Diagnostic::error(codes::CANNOT_SERVE, format!("cannot serve on {addr}: {e}"));
    if in_use {
        d.with_help(format!(
            "port {} is in use (another studio?): pick another with --port, or --port 0 for any free one",
            addr.port()
        ))
    } else {
        d.with_help("check --host: it must be an address of this machine")
    }
}
