//! `npr studio` over real HTTP: the binary serves on an ephemeral port; the
//! test fetches the page, subscribes to the event stream, moves a control,
//! edits, breaks, deletes and fixes a temp copy of a style on disk, and
//! checks each `state` event and frame image. Images are compared byte for
//! byte with `npr render --keep-params` of the same values: the studio
//! renders through the same runner.

use crate::common;

use common::http::{self, Events};
use common::live::{save_by_rename, start_studio as start};
use serde_json::{json, Value};

fn frame_id(s: &Value) -> u64 {
    s["frame"]["id"].as_u64().unwrap_or(0)
}

fn errors(s: &Value) -> Vec<&Value> {
    s["diagnostics"]
        .as_array()
        .map(|d| d.iter().filter(|d| d["severity"] == "error").collect())
        .unwrap_or_default()
}

fn output_png(addr: &str, s: &Value) -> Vec<u8> {
    let path = format!("/frame/{}/{}.png", frame_id(s), s["frame"]["output"]);
    let r = http::get(addr, &path);
    assert_eq!(r.status, 200, "{path}: {}", r.text());
    assert_eq!(r.content_type, "image/png");
    r.body
}

fn param<'a>(s: &'a Value, name: &str) -> &'a Value {
    s["params"]
        .as_array()
        .and_then(|p| p.iter().find(|p| p["name"] == name))
        .unwrap_or_else(|| panic!("no control `{name}` in {}", s["params"]))
}

#[test]
fn the_page_the_stream_controls_and_saves_over_real_http() {
    let dir = common::live::scratch("studio", "cycle");
    let style = dir.join("toon.npr");
    let original = std::fs::read_to_string("examples/toon.npr").expect("toon.npr");
    std::fs::write(&style, &original).expect("copy");
    let (mut studio, addr) = start(&style);

    // The page: one document, its script and style from this server only.
    let page = http::get(&addr, "/");
    assert_eq!(page.status, 200);
    let html = page.text();
    assert!(
        html.contains("<canvas id=\"view\"") && html.contains("src=\"/studio.js\""),
        "{html}"
    );
    for asset in ["/studio.js", "/studio.css"] {
        let r = http::get(&addr, asset);
        assert_eq!(r.status, 200, "{asset}");
        assert!(
            !r.text().contains("http://") && !r.text().contains("https://"),
            "{asset} fetches nothing from elsewhere"
        );
    }
    assert!(!html.contains("https://"), "the page fetches nothing from elsewhere");
    assert_eq!(http::get(&addr, "/nothing").status, 404);

    // The first frame, as `npr render --keep-params` renders it.
    let mut events = Events::open(&addr);
    let first = events.until("a first frame", |s| frame_id(s) > 0);
    assert!(errors(&first).is_empty(), "{}", first["diagnostics"]);
    assert_eq!(
        output_png(&addr, &first),
        common::live::reference_render(&style, &[], &dir.join("ref0.png"))
    );
    // Controls from the manifest: not the per-object `tint`.
    assert_eq!(param(&first, "bands")["control"], "int");
    assert_eq!(param(&first, "bands")["range_written"], json!([1.0, 8.0]));
    assert_eq!(param(&first, "base")["control"], "color");
    assert_eq!(param(&first, "base")["literal"], "#e07a3a");
    assert_eq!(param(&first, "bands")["doc"], "Number of shading bands.");
    assert!(first["params"]
        .as_array()
        .expect("params")
        .iter()
        .all(|p| p["name"] != "tint"));
    // Every target of the frame has a thumbnail image.
    let targets = first["frame"]["targets"].as_array().expect("targets").len();
    for t in 0..targets {
        assert_eq!(
            http::get(&addr, &format!("/frame/{}/{t}.png", frame_id(&first))).status,
            200
        );
        let raw = http::get(&addr, &format!("/frame/{}/{t}.f32", frame_id(&first)));
        assert_eq!(raw.body.len(), 64 * 64 * 16, "RGBA f32 texels");
    }

    // A control: a uniform changes and the frame is rendered again.
    assert_eq!(
        http::post(&addr, "/param", &json!({"name": "bands", "literal": "5"})).status,
        202
    );
    let moved = events.until("bands = 5", |s| {
        frame_id(s) > frame_id(&first) && param(s, "bands")["literal"] == "5"
    });
    assert_eq!(
        output_png(&addr, &moved),
        common::live::reference_render(&style, &["bands=5"], &dir.join("ref5.png"))
    );
    // A value outside the range is refused with its code, and nothing renders.
    http::post(&addr, "/param", &json!({"name": "bands", "literal": "99"}));
    let refused = events.until("a refused value", |s| !s["param_error"].is_null());
    assert_eq!(refused["param_error"]["code"], "E0203");
    assert_eq!(frame_id(&refused), frame_id(&moved));

    // A save on disk: a new frame event, keeping the control's value.
    let edited = original.replace("param base: color = #e07a3a", "param base: color = #3080ff");
    save_by_rename(&style, &edited);
    let saved = events.until("the saved colour", |s| {
        param(s, "base")["literal"] == "#3080ff" && frame_id(s) > frame_id(&moved)
    });
    assert_eq!(
        output_png(&addr, &saved),
        common::live::reference_render(&style, &["bands=5"], &dir.join("ref_saved.png"))
    );

    // A broken save: diagnostics with line and column; the last image stays.
    save_by_rename(&style, &edited.replace("output shade.color", "output shade.colour"));
    let broken = events.until("diagnostics", |s| !errors(s).is_empty());
    let d = errors(&broken)[0];
    assert!(d["code"].as_str().expect("code").starts_with('E'), "{d}");
    let label = &d["labels"][0];
    assert!(label["file"].as_str().expect("file").ends_with("toon.npr"), "{d}");
    assert_eq!(label["line"], 23, "{d}");
    assert!(label["column"].as_u64().expect("column") > 0);
    assert!(
        d["rendered"]
            .as_str()
            .expect("rendered")
            .contains("output shade.colour"),
        "{d}"
    );
    assert_eq!(
        frame_id(&broken),
        frame_id(&saved),
        "a broken style keeps the last frame"
    );
    assert_eq!(
        http::get(&addr, &format!("/frame/{}/0.png", frame_id(&saved))).status,
        200
    );

    // Fixing it clears them and renders again.
    save_by_rename(&style, &edited);
    let fixed = events.until("a fixed frame", |s| {
        errors(s).is_empty() && frame_id(s) > frame_id(&saved)
    });
    assert_eq!(output_png(&addr, &fixed), output_png(&addr, &fixed));

    // Deleted while watched: reported, and the studio recovers when it returns.
    std::fs::remove_file(&style).expect("delete");
    let gone = events.until("the missing file", |s| !errors(s).is_empty());
    assert_eq!(frame_id(&gone), frame_id(&fixed));
    std::fs::write(&style, &edited).expect("restore");
    events.until("recovery", |s| errors(s).is_empty() && frame_id(s) > frame_id(&fixed));

    // "Write into the file": only the default's text changes.
    http::post(&addr, "/param/write", &json!({"name": "bands"}));
    events.until("the written notice", |s| {
        s["notice"].as_str().is_some_and(|n| n.starts_with("wrote"))
    });
    let written = std::fs::read_to_string(&style).expect("style");
    assert_eq!(
        written,
        edited.replace("param bands: int = 3 in 1..8", "param bands: int = 5 in 1..8")
    );
    assert!(
        studio.child.try_wait().expect("status").is_none(),
        "the server keeps serving"
    );
}

#[test]
fn a_style_broken_at_start_still_opens_the_page_with_its_diagnostics() {
    let dir = common::live::scratch("studio", "broken-start");
    let style = dir.join("broken.npr");
    std::fs::write(
        &style,
        "style \"Broken\"\nparam x: float = 1 in 0..2\noutput nothing.color\n",
    )
    .expect("write");
    let (_studio, addr) = start(&style);
    assert_eq!(http::get(&addr, "/").status, 200);
    let mut events = Events::open(&addr);
    let s = events.until("diagnostics", |s| !errors(s).is_empty());
    assert!(s["frame"].is_null(), "nothing rendered yet");
    assert_eq!(errors(&s)[0]["labels"][0]["line"], 3);
}

#[test]
fn a_texture_is_watched_and_an_unreadable_one_is_reported_while_serving() {
    let dir = common::live::scratch("studio", "texture");
    let grad = dir.join("grad.png");
    let write_grad = |flip: bool| {
        let img = image::RgbaImage::from_fn(8, 8, |x, _| {
            let v = (x * 32) as u8;
            image::Rgba([if flip { 255 - v } else { v }, 64, 128, 255])
        });
        img.save(&grad).expect("write texture");
    };
    write_grad(false);
    let style = dir.join("tex.npr");
    std::fs::write(
        &style,
        "style \"T\"\ntexture grad = image(\"grad.png\", linear)\npass p: image() {\n  out c: rgba8unorm = grad\n}\noutput p.c\n",
    )
    .expect("style");
    let (studio, addr) = start(&style);
    let mut events = Events::open(&addr);
    let first = events.until("a first frame", |s| frame_id(s) > 0);
    let first_png = output_png(&addr, &first);

    // A new texture on disk is a new frame.
    write_grad(true);
    let changed = events.until("the new texture", |s| frame_id(s) > frame_id(&first));
    assert_ne!(output_png(&addr, &changed), first_png);

    // An unreadable one is reported with its code; the last frame stays.
    std::fs::write(&grad, b"not a png").expect("corrupt texture");
    let broken = events.until("the unreadable texture", |s| !errors(s).is_empty());
    assert_eq!(errors(&broken)[0]["code"], "E0401", "{}", broken["diagnostics"]);
    assert_eq!(frame_id(&broken), frame_id(&changed));
    assert_eq!(http::get(&addr, "/").status, 200, "the server keeps serving");

    write_grad(false);
    let back = events.until("recovery", |s| errors(s).is_empty() && frame_id(s) > frame_id(&changed));
    assert_eq!(output_png(&addr, &back), first_png);
    drop(studio);
}

#[test]
fn the_studio_shows_the_warnings_npr_render_prints() {
    let dir = common::live::scratch("studio", "warnings");
    let style = dir.join("plain.npr");
    // Reads no per-object param, while spot.toml binds `tint`: W0401.
    std::fs::write(
        &style,
        "style \"Plain\"\nparam base: color = #e07a3a\npass p: render(scene) {\n  out c: rgba8unorm = base * vec4(lambert(normal, light.dir))\n}\noutput p.c\n",
    )
    .expect("write");
    let rendered = common::cli::npr(&[
        "render",
        style.to_str().expect("utf-8"),
        "--scene",
        "examples/scenes/spot.toml",
        "--size",
        "32x32",
        "-o",
        dir.join("plain.png").to_str().expect("utf-8"),
    ]);
    let printed = common::cli::stderr(&rendered);
    assert_eq!(rendered.status.code(), Some(0), "{printed}");
    let (_studio, addr) = start(&style);
    let mut events = Events::open(&addr);
    let s = events.until("a frame", |s| !s["frame"].is_null());
    let shown: Vec<(String, String)> = s["diagnostics"]
        .as_array()
        .expect("diagnostics")
        .iter()
        .map(|d| {
            (
                d["code"].as_str().unwrap_or("").to_string(),
                d["message"].as_str().unwrap_or("").to_string(),
            )
        })
        .collect();
    let codes: Vec<&str> = shown.iter().map(|(c, _)| c.as_str()).collect();
    assert_eq!(codes, ["W0201", "W0401"], "{shown:?}");
    for (code, message) in &shown {
        assert!(
            printed.contains(&format!("warning[{code}]: {message}")),
            "the studio shows {code} `{message}`, npr render printed:\n{printed}"
        );
    }
}

#[test]
fn frames_are_read_by_target_name_and_the_last_few_stay_readable() {
    let dir = common::live::scratch("studio", "ring");
    let style = dir.join("toon.npr");
    std::fs::copy("examples/toon.npr", &style).expect("copy");
    let (_studio, addr) = start(&style);
    let mut events = Events::open(&addr);
    let first = events.until("a frame", |s| !s["frame"].is_null());
    let id = frame_id(&first);
    let by_index = http::get(&addr, &format!("/frame/{id}/0.png"));
    let by_name = http::get(&addr, &format!("/frame/{id}/shade.color.png"));
    assert_eq!(by_name.status, 200, "{}", by_name.text());
    assert_eq!(by_name.body, by_index.body, "the name and the index are one target");
    let unknown = http::get(&addr, &format!("/frame/{id}/shade.colour.png"));
    assert_eq!(unknown.status, 404);
    assert!(
        unknown.text().contains("its targets are shade.color"),
        "{}",
        unknown.text()
    );
    // Newer frames: the first stays readable while it is among the last 4.
    let mut last = id;
    for (i, bands) in ["2", "3", "4", "5", "6"].into_iter().enumerate() {
        assert_eq!(
            http::post(&addr, "/param", &json!({"name": "bands", "literal": bands})).status,
            202
        );
        let s = events.until("a newer frame", |s| {
            frame_id(s) > last && param(s, "bands")["literal"] == bands
        });
        last = frame_id(&s);
        let old = http::get(&addr, &format!("/frame/{id}/shade.color.png"));
        if i < 3 {
            assert_eq!(old.status, 200, "after {} newer frame(s): {}", i + 1, old.text());
            assert_eq!(old.body, by_index.body, "frame {id} is still its own image");
        } else {
            assert_eq!(old.status, 404, "after {} newer frames", i + 1);
            assert!(old.text().contains("no longer kept"), "{}", old.text());
        }
    }
}

#[test]
fn units_stay_as_written_on_the_page_and_in_the_file() {
    let dir = common::live::scratch("studio", "units");
    let style = dir.join("outline.npr");
    std::fs::write(
        &style,
        "style \"Units\"\nparam reach: m = 50mm in 0m..1m\npass p: render(scene) {\n  vertex { inflate: 2px }\n  out c: rgba8unorm = #808080 * step(reach, depth)\n}\noutput p.c\n",
    )
    .expect("write");
    let (_studio, addr) = start(&style);
    let mut events = Events::open(&addr);
    let first = events.until("a frame", |s| !s["frame"].is_null());
    assert_eq!(param(&first, "reach")["literal"], "50mm", "{}", param(&first, "reach"));
    assert_eq!(
        http::post(&addr, "/param", &json!({"name": "reach", "literal": "20mm"})).status,
        202
    );
    let moved = events.until("reach = 20mm", |s| param(s, "reach")["overridden"] == true);
    assert_eq!(param(&moved, "reach")["literal"], "20mm");
    assert_eq!(http::post(&addr, "/param/write", &json!({"name": "reach"})).status, 202);
    events.until("the file's new value", |s| {
        param(s, "reach")["overridden"] == false && param(s, "reach")["literal"] == "20mm"
    });
    let text = std::fs::read_to_string(&style).expect("read back");
    assert!(text.contains("param reach: m = 20mm in 0m..1m"), "{text}");
}

#[test]
fn a_px_parameter_set_in_percent_of_the_height_renders_as_npr_render_sets_it() {
    // A kept uniform moves in place (no recompile); the value typed in `%`
    // must reach the renderer as `%` of the height, not as that many px.
    let dir = common::live::scratch("studio", "percent");
    let style = dir.join("percent.npr");
    std::fs::write(
        &style,
        "style \"Percent\"\nparam w: px = 1px in 0px..50px\npass p: render(scene) {\n  vertex { inflate: w }\n  out c: rgba8unorm = #808080\n}\noutput p.c\n",
    )
    .expect("write");
    let (_studio, addr) = start(&style);
    let mut events = Events::open(&addr);
    let first = events.until("a frame", |s| !s["frame"].is_null());
    assert_eq!(
        http::post(&addr, "/param", &json!({"name": "w", "literal": "10%"})).status,
        202
    );
    let moved = events.until("w = 10%", |s| {
        frame_id(s) > frame_id(&first) && param(s, "w")["literal"] == "10%"
    });
    let percent = common::live::reference_render(&style, &["w=10%"], &dir.join("ref_percent.png"));
    let pixels = common::live::reference_render(&style, &["w=10px"], &dir.join("ref_px.png"));
    assert_ne!(percent, pixels, "the test's style must tell 10% of 64 px from 10 px");
    assert_eq!(output_png(&addr, &moved), percent);
}

#[test]
fn a_path_dependent_style_replays_from_frame_0_after_a_control_moves() {
    // Afterimage mixes in its previous frame: a frame rendered on top of the
    // last one without restarting the history would differ from
    // `npr render`, which starts every frame's replay at frame 0.
    let dir = common::live::scratch("studio", "path_dependent");
    let style = dir.join("afterimage.npr");
    std::fs::copy("examples/afterimage.npr", &style).expect("copy");
    let (studio, addr) = start(&style);
    let mut events = Events::open(&addr);
    let first = events.until("a first frame", |s| frame_id(s) > 0);
    assert!(errors(&first).is_empty(), "{}", first["diagnostics"]);
    assert_eq!(
        output_png(&addr, &first),
        common::live::reference_render(&style, &[], &dir.join("ref.png"))
    );
    for (k, persistence) in ["0.5", "0.9"].into_iter().enumerate() {
        http::post(&addr, "/param", &json!({"name": "persistence", "literal": persistence}));
        let moved = events.until("the moved control's frame", |s| {
            frame_id(s) > frame_id(&first) + k as u64 && param(s, "persistence")["literal"] == persistence
        });
        assert_eq!(
            output_png(&addr, &moved),
            common::live::reference_render(
                &style,
                &[&format!("persistence={persistence}")],
                &dir.join(format!("ref{k}.png"))
            ),
            "persistence = {persistence}: the studio's frame is not npr render's"
        );
    }
    drop(studio);
}
