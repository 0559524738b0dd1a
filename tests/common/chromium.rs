//! A headless Chromium (Debian's `chromium`) with one page, driven over
//! the DevTools protocol (a WebSocket, `tungstenite`, flat sessions):
//! `tests/general/studio_browser.rs` drives the studio's page with it, and
//! `tests/general/webgpu_portability.rs` Chromium's own WebGPU (Dawn and
//! its WGSL compiler, Tint, on the SwiftShader adapter). Chromium missing
//! is a failure with the install command, never a skip.

use serde_json::{json, Value};
use std::net::TcpStream;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicU32, Ordering};
use std::time::{Duration, Instant};
use tungstenite::{stream::MaybeTlsStream, Message, WebSocket};

pub const CHROMIUM: &str = "/usr/bin/chromium";

/// The flags every launch has: headless, as root, no first-run or
/// background work, DevTools on a free port.
const COMMON_FLAGS: &[&str] = &[
    "--headless=new",
    "--no-sandbox",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--remote-debugging-port=0",
];

/// The flags that give a page WebGPU on Chromium's own software adapter
/// (SwiftShader): no GPU, no download.
pub const WEBGPU_FLAGS: &[&str] = &[
    "--enable-unsafe-webgpu",
    "--use-webgpu-adapter=swiftshader",
    "--disable-gpu-sandbox",
];

/// A headless Chromium and its one page.
pub struct Browser {
    child: Child,
    ws: WebSocket<MaybeTlsStream<TcpStream>>,
    next_id: u64,
    /// The page's session (flat mode); `None` while talking to the browser.
    session: Option<String>,
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Browser {
    /// Start Chromium with `flags` besides the common ones, its profile in
    /// `profile` (a fresh directory), and attach to a new blank page. A
    /// DevTools reply that takes longer than `patience` fails the test
    /// instead of hanging it.
    pub fn launch(profile: &Path, flags: &[&str], patience: Duration) -> Browser {
        assert!(
            Path::new(CHROMIUM).exists(),
            "this test needs Chromium at {CHROMIUM}: install it with `sudo apt-get install -y chromium` (`./setup.sh --tests` does)"
        );
        // A directory of its own per launch: a browser restarted after a
        // crash must not read the port file its predecessor (or that one's
        // surviving child processes) left in a shared profile.
        static LAUNCHES: AtomicU32 = AtomicU32::new(0);
        let profile = &profile.join(format!("launch-{}", LAUNCHES.fetch_add(1, Ordering::Relaxed)));
        let _ = std::fs::remove_dir_all(profile);
        std::fs::create_dir_all(profile).expect("chromium profile directory");
        let port_file = profile.join("DevToolsActivePort");
        let child = Command::new(CHROMIUM)
            .args(COMMON_FLAGS)
            .args(flags)
            .arg(format!("--user-data-dir={}", profile.display()))
            .arg("about:blank")
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("start chromium");
        // Chromium writes the port it chose and its browser socket's path
        // into the profile.
        let deadline = Instant::now() + super::live::HANG;
        let (port, path) = loop {
            let text = std::fs::read_to_string(&port_file).unwrap_or_default();
            let mut lines = text.lines();
            if let (Some(port), Some(path)) = (lines.next(), lines.next()) {
                break (port.to_string(), path.to_string());
            }
            assert!(Instant::now() < deadline, "chromium never opened its DevTools port");
            std::thread::sleep(Duration::from_millis(50));
        };
        let url = format!("ws://127.0.0.1:{port}{path}");
        // The port file can be written a moment before the socket accepts.
        let ws = loop {
            match tungstenite::connect(url.as_str()) {
                Ok((ws, _)) => break ws,
                Err(e) if Instant::now() >= deadline => panic!("connect to chromium's DevTools socket {url}: {e}"),
                Err(_) => std::thread::sleep(Duration::from_millis(100)),
            }
        };
        if let MaybeTlsStream::Plain(tcp) = ws.get_ref() {
            tcp.set_read_timeout(Some(patience)).expect("a read timeout");
        }
        let mut b = Browser {
            child,
            ws,
            next_id: 0,
            session: None,
        };
        // One page, attached in flat mode: its commands carry the session id.
        let target = b.call("Target.createTarget", json!({"url": "about:blank"}));
        let attached = b.call(
            "Target.attachToTarget",
            json!({"targetId": target["targetId"], "flatten": true}),
        );
        b.session = attached["sessionId"].as_str().map(str::to_string);
        assert!(b.session.is_some(), "no DevTools session: {attached}");
        b
    }

    /// One DevTools command (to the page once attached); its result (events before it are skipped).
    pub fn call(&mut self, method: &str, params: Value) -> Value {
        self.next_id += 1;
        let id = self.next_id;
        let mut msg = json!({"id": id, "method": method, "params": params});
        if let Some(s) = &self.session {
            msg["sessionId"] = json!(s);
        }
        let msg = msg.to_string();
        self.ws.send(Message::text(msg)).expect("send DevTools command");
        loop {
            let reply = self
                .ws
                .read()
                .unwrap_or_else(|e| panic!("no DevTools reply to {method} (timed out or closed): {e}"));
            let Message::Text(text) = reply else { continue };
            let v: Value = serde_json::from_str(text.as_str()).expect("DevTools JSON");
            if v["id"] == id {
                assert!(v["error"].is_null(), "{method}: {}", v["error"]);
                return v["result"].clone();
            }
        }
    }

    /// Evaluate JavaScript in the page (promises awaited); its value.
    pub fn eval(&mut self, expr: &str) -> Value {
        let r = self.call(
            "Runtime.evaluate",
            json!({"expression": expr, "returnByValue": true, "awaitPromise": true}),
        );
        assert!(
            r["exceptionDetails"].is_null(),
            "{}: {}",
            expr.chars().take(300).collect::<String>(),
            r["exceptionDetails"]
        );
        r["result"]["value"].clone()
    }
}
