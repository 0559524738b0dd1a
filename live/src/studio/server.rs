//! The studio's HTTP side (tiny_http; docs/decisions/0026 says why): the page
//! and its script and style (embedded in the binary, no build step, nothing
//! fetched from elsewhere), the event stream, the frame images, and the
//! control endpoints that hand jobs to the render thread.
//!
//! | route | what |
//! |---|---|
//! | `GET /` , `/studio.js`, `/studio.css` | the page |
//! | `GET /events` | server-sent events: one `state` event per publish, the current state first |
//! | `GET /state` | the current state as JSON |
//! | `GET /frame/{id}/{target}.png` | a target (by name, `shade.color`, or index) of frame `id`, one of the last few, as `npr render` writes it |
//! | `GET /frame/{id}/{target}.f32` | its RGBA texels as little-endian f32 (exposure, readout) |
//! | `POST /param` `{"name", "literal"}` | set a control (typed like `--set`) |
//! | `POST /param/reset`, `/param/write` `{"name"}` | back to the file's value; write the value into the file |
//! | `POST /view` `{"time"?, "eye"?}` | the time scrubber and the eye toggle |

use super::hub::Hub;
use super::orbit::Orbit;
use super::render_thread::Job;
use serde_json::Value;
use std::io::{Read, Write};
use std::sync::mpsc::{RecvTimeoutError, Sender};
use std::time::Duration;
use tiny_http::{Header, Method, Request, Response, StatusCode};

const PAGE: &str = include_str!("page.html");
const SCRIPT: &str = include_str!("studio.js");
const STYLE: &str = include_str!("studio.css");

/// The largest request body taken (a control's value is a few bytes).
const MAX_BODY: u64 = 64 * 1024;

/// How often an idle event stream sends a comment, so a closed page is noticed.
const KEEPALIVE: Duration = Duration::from_secs(10);

/// Serve until the process ends; each request on its own thread (event
/// streams stay open).
pub fn serve(server: tiny_http::Server, hub: Hub, jobs: Sender<Job>) {
    for request in server.incoming_requests() {
        let hub = hub.clone();
        let jobs = jobs.clone();
        std::thread::spawn(move || handle(request, &hub, &jobs));
    }
}

fn header(name: &str, value: &str) -> Header {
    Header::from_bytes(name.as_bytes(), value.as_bytes()).expect("static header names and values are valid")
}

fn respond(request: Request, status: u16, content_type: &str, body: Vec<u8>) {
    let response = Response::from_data(body)
        .with_status_code(StatusCode(status))
        .with_header(header("Content-Type", content_type))
        .with_header(header("Cache-Control", "no-store"));
    // The page may have gone away; nothing to do about it.
    let _ = request.respond(response);
}

fn text(request: Request, status: u16, message: &str) {
    respond(
        request,
        status,
        "text/plain; charset=utf-8",
        message.as_bytes().to_vec(),
    );
}

fn handle(mut request: Request, hub: &Hub, jobs: &Sender<Job>) {
    let url = request.url().split('?').next().unwrap_or("").to_string();
    match (request.method().clone(), url.as_str()) {
        (Method::Get, "/") => respond(request, 200, "text/html; charset=utf-8", PAGE.into()),
        (Method::Get, "/studio.js") => respond(request, 200, "text/javascript; charset=utf-8", SCRIPT.into()),
        (Method::Get, "/studio.css") => respond(request, 200, "text/css; charset=utf-8", STYLE.into()),
        (Method::Get, "/state") => respond(request, 200, "application/json", hub.state().to_string().into_bytes()),
        (Method::Get, "/events") => events(request, hub),
        (Method::Get, path) if path.starts_with("/frame/") => frame(request, hub, &path["/frame/".len()..]),
        // Only for tests of the panic path: the render thread panics.
        (Method::Post, "/debug/panic") if std::env::var_os("NPR_STUDIO_DEBUG").is_some_and(|v| v == "1") => {
            if jobs.send(Job::Panic).is_err() {
                return text(request, 503, "the render thread has stopped");
            }
            respond(request, 202, "application/json", b"{}".to_vec());
        }
        (Method::Post, "/param" | "/param/reset" | "/param/write" | "/view") => {
            let body = match read_json(&mut request) {
                Ok(v) => v,
                Err(e) => return text(request, 400, &e),
            };
            let name = body["name"].as_str().map(str::to_string);
            let job =
                match (url.as_str(), name) {
                    ("/param", Some(name)) => match body["literal"].as_str() {
                        Some(l) => Job::SetParam {
                            name,
                            literal: l.to_string(),
                        },
                        None => return text(request, 400, "expected {\"name\": ..., \"literal\": \"...\"}"),
                    },
                    ("/param/reset", Some(name)) => Job::ResetParam(name),
                    ("/param/write", Some(name)) => Job::WriteParam(name),
                    ("/view", _) => Job::SetView {
                        time: body["time"].as_f64(),
                        eye: body["eye"].as_u64().map(|e| e as u32),
                        orbit: match body.get("orbit") {
                            None => None,
                            Some(Value::Null) => Some(None),
                            Some(o) => match Orbit::from_json(o) {
                                Some(o) => Some(Some(o)),
                                None => return text(
                                    request,
                                    400,
                                    "expected \"orbit\": {\"yaw\": deg, \"pitch\": deg, \"zoom\": factor > 0} or null",
                                ),
                            },
                        },
                    },
                    _ => return text(request, 400, "expected {\"name\": ...}"),
                };
            if jobs.send(job).is_err() {
                return text(request, 503, "the render thread has stopped");
            }
            respond(request, 202, "application/json", b"{}".to_vec());
        }
        _ => text(request, 404, "not found"),
    }
}

fn read_json(request: &mut Request) -> Result<Value, String> {
    let mut body = String::new();
    request
        .as_reader()
        .take(MAX_BODY)
        .read_to_string(&mut body)
        .map_err(|e| format!("cannot read the request: {e}"))?;
    serde_json::from_str(&body).map_err(|e| format!("the request is not JSON: {e}"))
}

/// `/frame/{id}/{target}.png` or `.f32`: a target by name or index, of one
/// of the last [`super::hub::FRAME_RING`] frames.
fn frame(request: Request, hub: &Hub, rest: &str) {
    let parsed = rest.split_once('/').and_then(|(id, file)| {
        let (target, ext) = file.rsplit_once('.')?;
        Some((id.parse::<u64>().ok()?, target.to_string(), ext.to_string()))
    });
    let Some((id, target, ext)) = parsed else {
        return text(
            request,
            404,
            &format!("`/frame/{rest}` is no frame image: ask for /frame/{{id}}/{{target}}.png or .f32, the target by name (`shade.color`) or index"),
        );
    };
    let frame = match hub.frame_by_id(id) {
        Ok(f) => f,
        Err(kept) => {
            let kept: Vec<String> = kept.iter().map(u64::to_string).collect();
            return text(
                request,
                404,
                &format!(
                    "frame {id} is no longer kept: the studio keeps the last {} frames ({})",
                    super::hub::FRAME_RING,
                    kept.join(", ")
                ),
            );
        }
    };
    let Some(index) = frame.target_index(&target) else {
        return text(
            request,
            404,
            &format!(
                "frame {id} has no target `{target}`: its targets are {}",
                frame.target_names().join(", ")
            ),
        );
    };
    let bytes = match ext.as_str() {
        "png" => frame.png(index).map(|b| b.map(|b| (b, "image/png"))),
        "f32" => frame.f32(index).map(|b| Ok((b, "application/octet-stream"))),
        _ => None,
    };
    match bytes {
        Some(Ok((b, ty))) => respond(request, 200, ty, b.to_vec()),
        Some(Err(e)) => text(
            request,
            500,
            &format!("cannot encode target `{target}` of frame {id}: {e}"),
        ),
        None => text(
            request,
            404,
            &format!("`.{ext}` is not served: ask for `{target}.png` or `{target}.f32`"),
        ),
    }
}

/// A server-sent event stream: written by hand on the raw connection, since
/// it never ends (tiny_http's responses have a body of known end).
fn events(request: Request, hub: &Hub) {
    let rx = hub.subscribe();
    let mut w = request.into_writer();
    let head = "HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\nCache-Control: no-store\r\nConnection: keep-alive\r\n\r\n";
    if w.write_all(head.as_bytes()).and_then(|()| w.flush()).is_err() {
        return;
    }
    loop {
        let chunk = match rx.recv_timeout(KEEPALIVE) {
            Ok(event) => event,
            Err(RecvTimeoutError::Timeout) => ": keepalive\n\n".to_string(),
            Err(RecvTimeoutError::Disconnected) => return,
        };
        if w.write_all(chunk.as_bytes()).and_then(|()| w.flush()).is_err() {
            // The page closed the stream; its sender is dropped at the next publish.
            return;
        }
    }
}
