//! A virtual X display for the tests of `npr view`: Xvfb started on a
//! free display number (and stopped with the test), and a screenshot of
//! a process's window taken through the X server (`GetImage`, as `xwd`
//! does), not read back from npr's own textures.
//!
//! Input is typed and dragged through XTEST, as a user's would arrive.
//! A missing Xvfb fails the test with the package to install.

use std::process::{Child, Command, Stdio};
use std::time::Duration;
use x11rb::connection::Connection;
use x11rb::protocol::xproto::{AtomEnum, ConnectionExt, ImageFormat, InputFocus, Window};
use x11rb::protocol::xtest::ConnectionExt as _;
use x11rb::rust_connection::RustConnection;

pub struct Xvfb {
    child: Child,
    /// `:N`, for `DISPLAY`.
    pub display: String,
}

impl Xvfb {
    /// Xvfb on a display number it picks itself (`-displayfd`: no race
    /// between tests starting at once), a 24-bit screen of 1024×768.
    pub fn start() -> Xvfb {
        let found = Command::new("Xvfb")
            .arg("-help")
            .stderr(Stdio::null())
            .stdout(Stdio::null())
            .status();
        assert!(
            found.is_ok(),
            "the npr view tests need Xvfb, a virtual X display: install it with \
             `sudo apt-get install -y xvfb x11-utils` (or ./setup.sh --tests)"
        );
        let mut child = Command::new("Xvfb")
            .args(["-displayfd", "1", "-screen", "0", "1024x768x24", "-nolisten", "tcp"])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("start Xvfb");
        // Xvfb writes the display's number once it accepts connections.
        let out = child.stdout.take().expect("Xvfb's stdout");
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut line = String::new();
            let _ = std::io::BufRead::read_line(&mut std::io::BufReader::new(out), &mut line);
            let _ = tx.send(line);
        });
        let line = rx.recv_timeout(Duration::from_secs(30)).unwrap_or_default();
        let Ok(n) = line.trim().parse::<u32>() else {
            let _ = child.kill();
            let _ = child.wait();
            panic!("Xvfb did not report a display number (it printed {line:?})");
        };
        Xvfb {
            child,
            display: format!(":{n}"),
        }
    }

    /// The pixels of the top-level window of process `pid` (its
    /// `_NET_WM_PID`), `width`×`height` from its top left corner.
    pub fn screenshot(&self, pid: u32, width: u32, height: u32) -> image::RgbaImage {
        let (conn, screen) = RustConnection::connect(Some(&self.display)).expect("connect to Xvfb");
        let root = conn.setup().roots[screen].clone();
        let window = window_of(&conn, root.root, pid)
            .unwrap_or_else(|| panic!("no window of process {pid} on {}", self.display));
        let reply = conn
            .get_image(ImageFormat::Z_PIXMAP, window, 0, 0, width as u16, height as u16, !0)
            .expect("GetImage request")
            .reply()
            .expect("GetImage reply");
        let visual = root
            .allowed_depths
            .iter()
            .flat_map(|d| d.visuals.iter())
            .find(|v| v.visual_id == reply.visual || v.visual_id == root.root_visual)
            .expect("the window's visual");
        let bytes_per_pixel = reply.data.len() / (width as usize * height as usize);
        assert_eq!(bytes_per_pixel, 4, "expected a 32-bit-per-pixel image (24-bit screen)");
        let channel = |pixel: u32, mask: u32| ((pixel & mask) >> mask.trailing_zeros()) as u8;
        image::RgbaImage::from_fn(width, height, |x, y| {
            let i = 4 * (y as usize * width as usize + x as usize);
            let pixel = u32::from_le_bytes([reply.data[i], reply.data[i + 1], reply.data[i + 2], reply.data[i + 3]]);
            image::Rgba([
                channel(pixel, visual.red_mask),
                channel(pixel, visual.green_mask),
                channel(pixel, visual.blue_mask),
                255,
            ])
        })
    }
}

impl Xvfb {
    /// The title of the window of `pid` (its `_NET_WM_NAME`, UTF-8).
    pub fn title(&self, pid: u32) -> String {
        let (conn, screen) = RustConnection::connect(Some(&self.display)).expect("connect to Xvfb");
        let root = conn.setup().roots[screen].root;
        let window = window_of(&conn, root, pid).unwrap_or_else(|| panic!("no window of process {pid}"));
        let atom = |name: &[u8]| {
            conn.intern_atom(false, name)
                .expect("atom")
                .reply()
                .expect("atom reply")
                .atom
        };
        let (name, utf8) = (atom(b"_NET_WM_NAME"), atom(b"UTF8_STRING"));
        let reply = conn
            .get_property(false, window, name, utf8, 0, 1024)
            .expect("title")
            .reply()
            .expect("title reply");
        String::from_utf8_lossy(&reply.value).into_owned()
    }
}

/// XTEST's event types (`xproto`'s event numbers).
const KEY_PRESS: u8 = 2;
const KEY_RELEASE: u8 = 3;
const BUTTON_PRESS: u8 = 4;
const BUTTON_RELEASE: u8 = 5;
const MOTION: u8 = 6;

impl Xvfb {
    fn input(&self, pid: u32, events: &[(u8, u8, i16, i16)]) {
        let (conn, screen) = RustConnection::connect(Some(&self.display)).expect("connect to Xvfb");
        let root = conn.setup().roots[screen].root;
        let window = window_of(&conn, root, pid).unwrap_or_else(|| panic!("no window of process {pid}"));
        // Window coordinates to the root's.
        let at = conn
            .translate_coordinates(window, root, 0, 0)
            .expect("translate")
            .reply()
            .expect("translate reply");
        // No window manager gives the window the keyboard focus: give it.
        conn.set_input_focus(InputFocus::PARENT, window, x11rb::CURRENT_TIME)
            .expect("focus")
            .check()
            .expect("focus the window");
        for &(kind, detail, x, y) in events {
            conn.xtest_fake_input(kind, detail, 0, root, at.dst_x + x, at.dst_y + y, 0)
                .expect("fake input");
            // A round trip: the event is processed before the next one.
            conn.get_input_focus().expect("sync").reply().expect("sync reply");
            std::thread::sleep(Duration::from_millis(30));
        }
    }

    /// Hold the key of X keysym `keysym` (e.g. `0x77` for w) down for
    /// `hold`, with the pointer and the focus on the window of `pid`.
    pub fn key(&self, pid: u32, keysym: u32, hold: Duration) {
        let (conn, _) = RustConnection::connect(Some(&self.display)).expect("connect to Xvfb");
        let setup = conn.setup();
        let (min, max) = (setup.min_keycode, setup.max_keycode);
        let map = conn
            .get_keyboard_mapping(min, max - min + 1)
            .expect("keyboard mapping")
            .reply()
            .expect("keyboard mapping reply");
        let per = map.keysyms_per_keycode as usize;
        let index = map
            .keysyms
            .iter()
            .position(|k| *k == keysym)
            .unwrap_or_else(|| panic!("no key types keysym {keysym:#x}"));
        let code = min + (index / per) as u8;
        self.input(pid, &[(MOTION, 0, 10, 10), (KEY_PRESS, code, 10, 10)]);
        std::thread::sleep(hold);
        self.input(pid, &[(KEY_RELEASE, code, 10, 10)]);
    }

    /// Drag with mouse button `button` (1 left, 3 right) from `from` to
    /// `to` in the window of `pid`, in a few moves.
    pub fn drag(&self, pid: u32, button: u8, from: (i16, i16), to: (i16, i16)) {
        let mut events = vec![(MOTION, 0, from.0, from.1), (BUTTON_PRESS, button, from.0, from.1)];
        for k in 1..=4 {
            let x = from.0 + (to.0 - from.0) * k / 4;
            let y = from.1 + (to.1 - from.1) * k / 4;
            events.push((MOTION, 0, x, y));
        }
        events.push((BUTTON_RELEASE, button, to.0, to.1));
        self.input(pid, &events);
    }
}

/// The window under `parent` (depth first) whose `_NET_WM_PID` is `pid`.
fn window_of(conn: &RustConnection, parent: Window, pid: u32) -> Option<Window> {
    let atom = conn.intern_atom(false, b"_NET_WM_PID").ok()?.reply().ok()?.atom;
    let tree = conn.query_tree(parent).ok()?.reply().ok()?;
    for w in tree.children {
        let prop = conn
            .get_property(false, w, atom, AtomEnum::CARDINAL, 0, 1)
            .ok()?
            .reply()
            .ok()?;
        if prop.value32().and_then(|mut v| v.next()) == Some(pid) {
            return Some(w);
        }
        if let Some(found) = window_of(conn, w, pid) {
            return Some(found);
        }
    }
    None
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        // Our own child, by its handle.
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
