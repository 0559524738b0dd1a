//! `npr studio` over real HTTP and SSE: the orbit/zoom camera overrides the
//! scene's and "reset to the scene's camera" brings back the same image;
//! a panic forced in the render thread is reported on the page, and the
//! server keeps serving (the device and renderer are made again).

use crate::common;

use common::http::{self, Events};
use common::live::{scratch, start_studio_with_env};
use serde_json::{json, Value};

fn frame_id(s: &Value) -> u64 {
    s["frame"]["id"].as_u64().unwrap_or(0)
}

fn output_png(addr: &str, s: &Value) -> Vec<u8> {
    let path = format!("/frame/{}/{}.png", frame_id(s), s["frame"]["output"]);
    let r = http::get(addr, &path);
    assert_eq!(r.status, 200, "{path}: {}", r.text());
    r.body
}

fn decoded(png: &[u8]) -> image::RgbaImage {
    image::load_from_memory(png).expect("a PNG").to_rgba8()
}

fn style_copy(name: &str) -> std::path::PathBuf {
    let dir = scratch("studio-camera", name);
    let style = dir.join("toon.npr");
    std::fs::copy(common::root().join("examples/toon.npr"), &style).expect("copy toon");
    style
}

#[test]
fn the_orbit_camera_overrides_the_scene_camera_and_reset_restores_it() {
    let style = style_copy("orbit");
    let (_studio, addr) = start_studio_with_env(&style, &[]);
    let mut events = Events::open(&addr);
    let first = events.until("a first frame", |s| frame_id(s) > 0);
    assert!(first["view"]["orbit"].is_null(), "{}", first["view"]);
    let scene_image = output_png(&addr, &first);

    // Turn 60° round and come nearer.
    let orbit = json!({"yaw": 60.0, "pitch": 20.0, "zoom": 0.8});
    assert_eq!(http::post(&addr, "/view", &json!({ "orbit": orbit })).status, 202);
    let turned = events.until("the orbited frame", |s| {
        frame_id(s) > frame_id(&first) && s["view"]["orbit"]["yaw"] == 60.0
    });
    let orbited = output_png(&addr, &turned);
    let (a, b) = (decoded(&scene_image), decoded(&orbited));
    let changed = a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count();
    assert!(
        changed * 10 > (a.width() * a.height()) as usize,
        "the orbit changed only {changed} of {} pixels",
        a.width() * a.height()
    );

    // A bad orbit is refused, and changes nothing.
    assert_eq!(
        http::post(
            &addr,
            "/view",
            &json!({"orbit": {"yaw": 1.0, "pitch": 0.0, "zoom": -1.0}})
        )
        .status,
        400
    );

    // Back to the scene's camera: the very image of the first frame.
    assert_eq!(http::post(&addr, "/view", &json!({ "orbit": null })).status, 202);
    let reset = events.until("the scene camera again", |s| {
        frame_id(s) > frame_id(&turned) && s["view"]["orbit"].is_null()
    });
    assert_eq!(output_png(&addr, &reset), scene_image, "reset is the scene's camera");
}

#[test]
fn a_panic_in_the_render_thread_is_reported_and_the_server_keeps_serving() {
    let style = style_copy("panic");
    // Without NPR_STUDIO_DEBUG the route does not exist.
    {
        let (_studio, addr) = start_studio_with_env(&style, &[]);
        assert_eq!(http::post(&addr, "/debug/panic", &json!({})).status, 404);
    }
    let (mut studio, addr) = start_studio_with_env(&style, &[("NPR_STUDIO_DEBUG", "1")]);
    let mut events = Events::open(&addr);
    let first = events.until("a first frame", |s| frame_id(s) > 0);
    let before = output_png(&addr, &first);
    assert_eq!(http::post(&addr, "/debug/panic", &json!({})).status, 202);
    let reported = events.until("the panic on the page", |s| {
        s["diagnostics"]
            .as_array()
            .is_some_and(|d| d.iter().any(|d| d["code"] == "E9001" && d["stage"] == "panic"))
    });
    let text = reported["diagnostics"].to_string();
    assert!(
        text.contains("the render thread panicked: forced by POST /debug/panic"),
        "{text}"
    );
    // The last good image is still served.
    assert_eq!(http::get(&addr, "/").status, 200);
    assert_eq!(output_png(&addr, &reported), before);
    // The thread made its device again and rebuilt: a control renders a new frame.
    assert_eq!(
        http::post(&addr, "/param", &json!({"name": "bands", "literal": "5"})).status,
        202
    );
    let after = events.until("a frame with bands = 5 after the panic", |s| {
        frame_id(s) > frame_id(&first)
            && s["diagnostics"]
                .as_array()
                .is_some_and(|d| d.iter().all(|d| d["severity"] != "error"))
            && s["params"]
                .as_array()
                .is_some_and(|p| p.iter().any(|p| p["name"] == "bands" && p["literal"] == "5"))
    });
    assert_ne!(output_png(&addr, &after), before, "bands = 5 shows");
    assert!(
        studio.child.try_wait().expect("child status").is_none(),
        "the studio is still running"
    );
}
