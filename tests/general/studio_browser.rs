//! `npr studio` in a real browser: Debian's Chromium, headless, driven over
//! the DevTools protocol (a WebSocket, `tungstenite`) against the real
//! server. It checks that
//! 1. the page's canvas shows the rendered image: its pixels equal
//!    `npr render --keep-params` within 1/255 (8-bit output: exact in practice);
//! 2. moving a slider changes the image (to `--set` of the slider's value);
//! 3. a broken save shows the diagnostic with its line and column while the
//!    last image stays;
//! 4. fixing it brings a new image;
//! 5. clicking a pass thumbnail shows that target.
//!
//! A failing step saves a screenshot into `target/tmp/studio-browser/`.
//! Chromium missing is a failure with the install command, never a skip
//! (`common::chromium`).

use crate::common;

use common::chromium::Browser;
use common::http;
use common::live::{save_by_rename, start_studio};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The studio's page in a headless Chromium (`common::chromium`), and
/// where a failing step saves its screenshot.
struct Page {
    browser: Browser,
    shots: PathBuf,
}

impl std::ops::Deref for Page {
    type Target = Browser;
    fn deref(&self) -> &Browser {
        &self.browser
    }
}

impl std::ops::DerefMut for Page {
    fn deref_mut(&mut self) -> &mut Browser {
        &mut self.browser
    }
}

impl Page {
    fn launch(profile: &Path, shots: PathBuf) -> Page {
        Page {
            browser: Browser::launch(profile, &["--disable-gpu", "--disable-quic"], common::live::HANG),
            shots,
        }
    }

    /// Wait until `expr` is truthy in the page (the page updates on server events).
    fn wait_until(&mut self, what: &str, expr: &str) {
        let deadline = Instant::now() + common::live::HANG;
        // Before the page has loaded, `document.body` is null: not yet.
        let probe = format!("(() => {{ try {{ return !!({expr}); }} catch (e) {{ return false; }} }})()");
        while !self.eval(&probe).as_bool().unwrap_or(false) {
            assert!(Instant::now() < deadline, "the page never showed {what}");
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// The canvas's RGBA bytes.
    fn canvas(&mut self) -> Vec<u8> {
        let v = self.eval(
            "(() => { const c = document.getElementById('view'); \
             return Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data); })()",
        );
        v.as_array()
            .expect("pixel array")
            .iter()
            .map(|x| x.as_u64().expect("byte") as u8)
            .collect()
    }

    fn shown_frame(&mut self) -> u64 {
        self.eval("Number(document.body.dataset.shownFrame || 0)")
            .as_u64()
            .unwrap_or(0)
    }

    /// Run a step; if it fails, save a screenshot named after it first.
    fn step(&mut self, name: &str, f: impl FnOnce(&mut Page)) {
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| f(self)));
        if let Err(e) = result {
            let shot = self.call("Page.captureScreenshot", json!({"format": "png"}));
            if let Some(b64) = shot["data"].as_str() {
                let path = self.shots.join(format!("{name}.png"));
                std::fs::write(&path, base64_decode(b64)).expect("write screenshot");
                eprintln!("step `{name}` failed; screenshot: {}", path.display());
            }
            std::panic::resume_unwind(e);
        }
    }
}

/// Standard base64 (DevTools' screenshot encoding).
fn base64_decode(s: &str) -> Vec<u8> {
    let val = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        _ => 63,
    };
    let clean: Vec<u8> = s.bytes().filter(|c| *c != b'=' && !c.is_ascii_whitespace()).collect();
    let mut out = Vec::with_capacity(clean.len() * 3 / 4);
    for chunk in clean.chunks(4) {
        let n = chunk
            .iter()
            .enumerate()
            .fold(0u32, |n, (i, c)| n | (val(*c) as u32) << (18 - 6 * i));
        out.extend_from_slice(&n.to_be_bytes()[1..chunk.len()]);
    }
    out
}

/// [`common::live::reference_render`] decoded to RGBA bytes.
fn reference(style: &Path, sets: &[&str], out: &Path) -> Vec<u8> {
    let png = common::live::reference_render(style, sets, out);
    image::load_from_memory(&png)
        .expect("decode reference")
        .to_rgba8()
        .into_raw()
}

/// The golden tolerance of 8-bit images: 1/255 per channel.
fn assert_close(actual: &[u8], expected: &[u8], what: &str) {
    assert_eq!(actual.len(), expected.len(), "{what}: sizes differ");
    let worst = actual
        .iter()
        .zip(expected)
        .map(|(a, b)| a.abs_diff(*b))
        .max()
        .unwrap_or(0);
    assert!(worst <= 1, "{what}: a channel differs by {worst}/255");
}

#[test]
fn the_page_shows_the_image_follows_a_slider_shows_and_clears_errors_and_switches_targets() {
    let dir = common::live::scratch("studio-browser", "run");
    let style = dir.join("sobel_outline.npr");
    let original = std::fs::read_to_string("examples/sobel_outline.npr").expect("style");
    std::fs::write(&style, &original).expect("copy");
    let (_studio, addr) = start_studio(&style);
    let mut b = Page::launch(&dir.join("profile"), dir.clone());
    b.call("Page.enable", json!({}));
    b.call("Page.navigate", json!({"url": format!("http://{addr}/")}));

    let mut first = Vec::new();
    b.step("1_image", |b| {
        b.wait_until("a frame", "document.body.dataset.shownFrame");
        first = b.canvas();
        assert_close(
            &first,
            &reference(&style, &[], &dir.join("ref0.png")),
            "the first frame",
        );
    });

    let mut moved = Vec::new();
    b.step("2_slider", |b| {
        let before = b.shown_frame();
        b.wait_until(
            "the threshold slider",
            "document.querySelector('.param[data-name=threshold] input[type=range]')",
        );
        b.eval(
            "(() => { const i = document.querySelector('.param[data-name=threshold] .input'); \
             i.value = 0.005; i.dispatchEvent(new Event('input')); })()",
        );
        b.wait_until(
            "the slider's frame",
            &format!("Number(document.body.dataset.shownFrame) > {before}"),
        );
        moved = b.canvas();
        assert_ne!(moved, first, "moving the slider changes the image");
        assert_close(
            &moved,
            &reference(&style, &["threshold=0.005"], &dir.join("ref1.png")),
            "the slider's frame",
        );
    });

    b.step("3_broken", |b| {
        let before = b.shown_frame();
        save_by_rename(
            &style,
            &original.replace("output ink_lines.color", "output ink_lines.colour"),
        );
        b.wait_until("a diagnostic", "document.querySelector('#diagnostics .diag.error')");
        let text = b
            .eval("document.getElementById('diagnostics').innerText")
            .as_str()
            .unwrap_or("")
            .to_string();
        assert!(text.contains("sobel_outline.npr:21:"), "line and column shown: {text}");
        assert!(
            text.contains("output ink_lines.colour"),
            "the source line shown: {text}"
        );
        assert_eq!(b.shown_frame(), before, "the last image stays");
        assert_eq!(b.canvas(), moved, "the last image stays");
    });

    b.step("4_fixed", |b| {
        let before = b.shown_frame();
        save_by_rename(&style, &original);
        b.wait_until(
            "the fixed frame",
            &format!(
                "!document.querySelector('#diagnostics .diag.error') && Number(document.body.dataset.shownFrame) > {before}"
            ),
        );
        // The slider's value survives the save.
        assert_close(
            &b.canvas(),
            &reference(&style, &["threshold=0.005"], &dir.join("ref2.png")),
            "the fixed frame",
        );
    });

    b.step("5_thumbnail", |b| {
        let state: Value = serde_json::from_slice(&http::get(&addr, "/state").body).expect("state");
        let frame = state["frame"]["id"].as_u64().expect("frame id");
        let targets = state["frame"]["targets"].as_array().expect("targets").clone();
        let output = state["frame"]["output"].as_u64().expect("output");
        let other = targets
            .iter()
            .find(|t| t["index"].as_u64() != Some(output))
            .expect("a target besides the output");
        let index = other["index"].as_u64().expect("index");
        b.eval(&format!(
            "document.querySelector('.thumb[data-index=\"{index}\"]').click()"
        ));
        b.wait_until(
            "the clicked target",
            &format!("document.body.dataset.shownTarget === '{index}'"),
        );
        // The large view shows that target's texels as `npr render` writes a
        // one-channel float target: grey, clamped to [0, 1].
        let raw = http::get(&addr, &format!("/frame/{frame}/{index}.f32")).body;
        let expected: Vec<u8> = raw
            .chunks(16)
            .flat_map(|t| {
                let r = f32::from_le_bytes([t[0], t[1], t[2], t[3]]);
                let g = (r.clamp(0.0, 1.0) * 255.0).round() as u8;
                [g, g, g, 255]
            })
            .collect();
        assert_close(&b.canvas(), &expected, &format!("target {}", other["name"]));
        let name = b.eval("document.getElementById('target-name').textContent");
        assert!(
            name.as_str()
                .unwrap_or("")
                .contains(other["name"].as_str().unwrap_or("?")),
            "{name}"
        );
    });

    b.step("6_orbit", |b| {
        let before = b.canvas();
        let frame = b.shown_frame();
        let rect = b.eval(
            "(() => { const r = document.getElementById('view').getBoundingClientRect(); \
             return [r.left + r.width / 2, r.top + r.height / 2]; })()",
        );
        let (x, y) = (rect[0].as_f64().expect("x"), rect[1].as_f64().expect("y"));
        // A real drag: press on the image, move 80 px right and 30 px down, release.
        let mouse = |b: &mut Page, kind: &str, x: f64, y: f64| {
            b.call(
                "Input.dispatchMouseEvent",
                json!({"type": kind, "x": x, "y": y, "button": "left", "buttons": 1, "clickCount": 1}),
            );
        };
        mouse(b, "mousePressed", x, y);
        mouse(b, "mouseMoved", x + 40.0, y + 15.0);
        mouse(b, "mouseMoved", x + 80.0, y + 30.0);
        mouse(b, "mouseReleased", x + 80.0, y + 30.0);
        b.wait_until(
            "an orbited frame",
            &format!(
                "Number(document.body.dataset.shownFrame) > {frame} && state.view.orbit && state.view.orbit.yaw === -40 \
                 && Number(document.body.dataset.shownFrame) === state.frame.id"
            ),
        );
        let orbited = b.canvas();
        let changed = before.chunks(4).zip(orbited.chunks(4)).filter(|(p, q)| p != q).count();
        assert!(changed * 20 > before.len() / 4, "the drag changed only {changed} pixels");
        let state: Value = serde_json::from_slice(&http::get(&addr, "/state").body).expect("state");
        assert!(state["view"]["orbit"]["yaw"].as_f64().is_some_and(|y| y < 0.0), "{}", state["view"]);
        // Reset to the scene's camera: the image from before the drag.
        let frame = b.shown_frame();
        b.eval("document.getElementById('camera-reset').click()");
        b.wait_until(
            "the scene camera again",
            &format!(
                "Number(document.body.dataset.shownFrame) > {frame} && state.view.orbit === null \
                 && Number(document.body.dataset.shownFrame) === state.frame.id"
            ),
        );
        assert_close(&b.canvas(), &before, "the scene camera after reset");
    });
}

/// The page's value of the `shading` gradient (`--set` text).
const SHADING: &str = "state.params.find((p) => p.name === 'shading').literal";

impl Page {
    /// Wait for a frame after `before` that shows `shading` other than
    /// `old`, and return that value.
    fn next_shading(&mut self, what: &str, before: u64, old: &str) -> String {
        self.wait_until(
            what,
            &format!(
                "Number(document.body.dataset.shownFrame) > {before} && Number(document.body.dataset.shownFrame) === state.frame.id \
                 && {SHADING} !== {old:?}"
            ),
        );
        self.eval(SHADING).as_str().expect("literal").to_string()
    }

    /// The centre of the `i`th stop handle and the strip's left edge and width, in page pixels.
    fn stop_geometry(&mut self, i: usize) -> (f64, f64, f64, f64) {
        let v = self.eval(&format!(
            "(() => {{ const g = document.querySelector('.param[data-name=shading] .gradient'); \
             const h = g.querySelector('.stop[data-i=\"{i}\"]').getBoundingClientRect(); \
             const s = g.querySelector('.strip').getBoundingClientRect(); \
             return [h.left + h.width / 2, h.top + h.height / 2, s.left, s.width]; }})()"
        ));
        let n = |k: usize| v[k].as_f64().expect("number");
        (n(0), n(1), n(2), n(3))
    }

    fn mouse(&mut self, kind: &str, x: f64, y: f64) {
        self.call(
            "Input.dispatchMouseEvent",
            json!({"type": kind, "x": x, "y": y, "button": "left", "buttons": 1, "clickCount": 1}),
        );
    }
}

/// The gradient editor of `examples/toon_ramp.npr` (kept live, a uniform):
/// recolour a stop, drag one along the strip, add one; each re-renders to
/// what `npr render --keep-params --set shading=...` of the page's value
/// renders (within 1/255), and `write` puts the stops into the file as the
/// language writes them, which renders the same image with no `--set`.
#[test]
fn the_page_edits_a_gradient_and_writes_its_stops_into_the_file() {
    let dir = common::live::scratch("studio-browser", "gradient");
    let style = dir.join("toon_ramp.npr");
    let original = std::fs::read_to_string("examples/toon_ramp.npr").expect("style");
    std::fs::write(&style, &original).expect("copy");
    let (_studio, addr) = start_studio(&style);
    let mut b = Page::launch(&dir.join("profile"), dir.clone());
    b.call("Page.enable", json!({}));
    b.call("Page.navigate", json!({"url": format!("http://{addr}/")}));
    let set = |literal: &str| format!("shading={literal}");

    let (mut image, mut literal) = (Vec::new(), String::new());
    b.step("g1_strip", |b| {
        b.wait_until(
            "the gradient's six stops and a frame",
            "document.querySelectorAll('.param[data-name=shading] .gradient .stop').length === 6 \
             && document.body.dataset.shownFrame",
        );
        literal = b.eval(SHADING).as_str().expect("literal").to_string();
        assert_eq!(
            literal,
            "0:#2a1f4a, 0.35:#5a3a6a, 0.5:#8a4a5a, 0.5:#e07a3a, 0.85:#f2b36a, 1:#fff0d0"
        );
        image = b.canvas();
        assert_close(&image, &reference(&style, &[], &dir.join("g0.png")), "the first frame");
    });

    // Each edit: a new frame, other than the last, equal to `--set` of the page's value.
    let mut check = |b: &mut Page, name: &str, new: &str| {
        let now = b.canvas();
        assert_ne!(now, image, "{name} changes the image");
        assert_close(
            &now,
            &reference(&style, &[&set(new)], &dir.join(format!("{name}.png"))),
            name,
        );
        image = now;
    };

    b.step("g2_recolour", |b| {
        let before = b.shown_frame();
        let (x, y, _, _) = b.stop_geometry(0);
        b.mouse("mousePressed", x, y);
        b.mouse("mouseReleased", x, y);
        b.eval(
            "(() => { const c = document.querySelector('.param[data-name=shading] .stop-colour'); \
             c.value = '#00ff00'; c.dispatchEvent(new Event('input')); })()",
        );
        let new = b.next_shading("the recoloured stop's frame", before, &literal);
        assert_eq!(new, literal.replacen("#2a1f4a", "#00ff00", 1));
        check(b, "recoloured", &new);
        literal = new;
    });

    b.step("g3_move", |b| {
        let before = b.shown_frame();
        // Drag the stop at 0.35 to 0.2 of the strip's width.
        let (x, y, left, width) = b.stop_geometry(1);
        let to = left + 0.2 * width;
        b.mouse("mousePressed", x, y);
        b.mouse("mouseMoved", (x + to) / 2.0, y);
        b.mouse("mouseMoved", to, y);
        b.mouse("mouseReleased", to, y);
        let new = b.next_shading("the moved stop's frame", before, &literal);
        let moved: f64 = new
            .split(", ")
            .nth(1)
            .and_then(|s| s.split(':').next())
            .expect("a stop")
            .parse()
            .expect("a position");
        assert!((moved - 0.2).abs() < 0.01, "the stop moved to {moved}, not 0.2: {new}");
        check(b, "moved", &new);
        literal = new;
    });

    b.step("g4_add", |b| {
        let before = b.shown_frame();
        b.eval("document.querySelector('.param[data-name=shading] .add-stop').click()");
        let new = b.next_shading("the added stop's frame", before, &literal);
        assert_eq!(new.split(", ").count(), 7, "a seventh stop: {new}");
        check(b, "added", &new);
        literal = new;
    });

    b.step("g5_bad", |b| {
        // A value out of order is refused with its code, and the image stays.
        let frame = b.shown_frame();
        let bad = http::post(
            &addr,
            "/param",
            &json!({"name": "shading", "literal": "0.8:#000000, 0.2:#ffffff"}),
        );
        assert!(bad.status < 500, "{}", bad.status);
        b.wait_until(
            "the refusal",
            "document.querySelector('.param[data-name=shading] .error').textContent.includes('E0206')",
        );
        assert_eq!(b.shown_frame(), frame, "a refused value renders nothing");
    });

    b.step("g6_write", |b| {
        let before = b.shown_frame();
        b.eval("document.querySelector('.param[data-name=shading] button[title^=\"write\"]').click()");
        let npr_abi::param_literal::Literal::Stops(stops) = npr_abi::param_literal::read_literal(&literal) else {
            panic!("the page's value is no stops: {literal}")
        };
        let declared = npr_abi::gradient::declaration_text(&stops, false);
        let start = original.find("gradient(stop").expect("the default");
        let end = start + original[start..].find('\n').expect("end of line");
        let expected = format!("{}{declared}{}", &original[..start], &original[end..]);
        let deadline = Instant::now() + common::live::HANG;
        while std::fs::read_to_string(&style).ok().as_deref() != Some(expected.as_str()) {
            assert!(
                Instant::now() < deadline,
                "the file never had the stops; it has:\n{}",
                std::fs::read_to_string(&style).unwrap_or_default()
            );
            std::thread::sleep(Duration::from_millis(50));
        }
        b.wait_until(
            "the written file's frame",
            &format!(
                "!document.querySelector('#diagnostics .diag.error') && Number(document.body.dataset.shownFrame) > {before} \
                 && Number(document.body.dataset.shownFrame) === state.frame.id && !state.params.find((p) => p.name === 'shading').overridden"
            ),
        );
        assert_eq!(b.eval(SHADING).as_str(), Some(literal.as_str()), "the file's value is the page's");
        assert_close(&b.canvas(), &reference(&style, &[], &dir.join("written.png")), "the written file");
        assert_close(&b.canvas(), &image, "the written file renders the edited image");
    });
}
