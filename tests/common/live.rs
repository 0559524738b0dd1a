//! Driving a long-running `npr` (watch, studio) from a test: the child's
//! output read line by line on a thread, and waits for a line that fail
//! with everything the child printed when it never comes. The deadline is a
//! hang guard, not a measurement: nothing asserts how fast a line came.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{channel, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

/// How long a test waits for the child before failing (a hang, not a speed check).
pub const HANG: Duration = Duration::from_secs(120);

pub struct Live {
    pub child: Child,
    lines: Receiver<String>,
    /// Everything read so far, for failure messages.
    pub seen: Vec<String>,
}

impl Live {
    /// Start `npr args` in the repository root with stdout and stderr captured.
    pub fn start(args: &[&str]) -> Live {
        Live::start_with_env(args, &[])
    }

    /// [`Live::start`] with extra environment variables.
    pub fn start_with_env(args: &[&str], envs: &[(&str, &str)]) -> Live {
        let mut child = Command::new(env!("CARGO_BIN_EXE_npr"))
            .args(args)
            .envs(envs.iter().copied())
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .env("XDG_RUNTIME_DIR", std::env::temp_dir())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("start npr");
        let (tx, lines) = channel();
        let out = child.stdout.take().expect("stdout");
        let err = child.stderr.take().expect("stderr");
        let tx2 = tx.clone();
        std::thread::spawn(move || {
            BufReader::new(out)
                .lines()
                .map_while(Result::ok)
                .for_each(|l| drop(tx.send(l)))
        });
        std::thread::spawn(move || {
            BufReader::new(err)
                .lines()
                .map_while(Result::ok)
                .for_each(|l| drop(tx2.send(l)))
        });
        Live {
            child,
            lines,
            seen: Vec::new(),
        }
    }

    /// Wait for a line containing `needle`; the lines read on the way.
    pub fn wait_for(&mut self, needle: &str) -> Vec<String> {
        let deadline = Instant::now() + HANG;
        let mut read = Vec::new();
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.lines.recv_timeout(left) {
                Ok(line) => {
                    self.seen.push(line.clone());
                    let hit = line.contains(needle);
                    read.push(line);
                    if hit {
                        return read;
                    }
                }
                Err(RecvTimeoutError::Timeout) | Err(RecvTimeoutError::Disconnected) => {
                    let status = self.child.try_wait().ok().flatten();
                    panic!(
                        "npr never printed `{needle}` (exit status: {status:?}); it printed:\n{}",
                        self.seen.join("\n")
                    );
                }
            }
        }
    }
}

impl Drop for Live {
    fn drop(&mut self) {
        // Our own child, by its handle.
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Save `text` as an editor that saves by rename does: a temporary file in
/// the same directory, renamed over `path`.
pub fn save_by_rename(path: &Path, text: &str) {
    let tmp = path.with_extension("npr.tmp~");
    std::fs::write(&tmp, text).expect("write temp file");
    std::fs::rename(&tmp, path).expect("rename over the file");
}

/// Start `npr studio` on `style` (64×64, spot.toml, any free port); the
/// child and its address (`127.0.0.1:PORT`).
pub fn start_studio(style: &Path) -> (Live, String) {
    start_studio_with_env(style, &[])
}

/// [`start_studio`] with extra environment variables.
pub fn start_studio_with_env(style: &Path, envs: &[(&str, &str)]) -> (Live, String) {
    let mut studio = Live::start_with_env(
        &[
            "studio",
            style.to_str().expect("utf-8"),
            "--scene",
            "examples/scenes/spot.toml",
            "--size",
            "64x64",
            "--port",
            "0",
        ],
        envs,
    );
    let line = studio.wait_for("npr studio: http://").pop().expect("address line");
    let addr = line
        .split("http://")
        .nth(1)
        .expect("url")
        .trim_end_matches('/')
        .to_string();
    (studio, addr)
}

/// A fresh scratch directory `<target tmp>/<group>/<name>`.
pub fn scratch(group: &str, name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(group).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// `npr render --keep-params` of `style` with `sets` on `spot.toml` at
/// 64×64 into `out`: the reference a studio frame must equal. Returns the
/// PNG file's bytes.
pub fn reference_render(style: &Path, sets: &[&str], out: &Path) -> Vec<u8> {
    let mut args = vec![
        "render".to_string(),
        style.display().to_string(),
        "--scene".into(),
        "examples/scenes/spot.toml".into(),
        "--size".into(),
        "64x64".into(),
        "--keep-params".into(),
        "-o".into(),
        out.display().to_string(),
    ];
    for s in sets {
        args.push("--set".into());
        args.push(s.to_string());
    }
    let o = Command::new(env!("CARGO_BIN_EXE_npr"))
        .args(&args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("npr render");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::read(out).expect("reference image")
}
