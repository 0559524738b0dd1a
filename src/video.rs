//! `npr render -o NAME.mp4|.webm|.gif --frames …`: one video of the frames.
//!
//! MP4 (H.264) and WebM (VP9) go through the system's `ffmpeg` (Debian's
//! `ffmpeg` package), fed raw RGBA frames on a pipe as they render: ffmpeg
//! is the maintained encoder every platform packages, and writing an H.264
//! or VP9 encoder is out of the question. Settings, chosen for a
//! preview that plays everywhere: yuv420p (what browsers and players
//! decode; odd sizes are padded by one black row or column, since 4:2:0
//! needs even ones), constant quality (x264 `-crf 18 -preset medium`, the
//! visually lossless end of its scale; VP9 `-crf 30 -b:v 0`, its
//! constant-quality mode). Alpha is dropped: neither container's common
//! profile has it.
//!
//! GIF is written by the `gif` crate (the encoder the `image` crate wraps),
//! not ffmpeg: a README preview then needs no system package, frames stream
//! to the file as they render, and the bytes are deterministic. Each frame
//! gets its own 256-colour palette (NeuQuant); GIF counts delays in
//! hundredths of a second, so the frame delay is 100/fps rounded (24 fps
//! plays at 25). Alpha is dropped here too (made opaque): GIF's one-bit
//! transparency would punch holes where a frame is translucent.
//!
//! Nothing half-written: the video is written to a hidden temporary file
//! beside the output and renamed into place by [`VideoWriter::finish`]; an
//! error, or a writer dropped unfinished, stops the encoder and removes the
//! temporary. A missing `ffmpeg` (or one without the encoder) is E0511,
//! found by [`check_encoder`] before anything renders.

use npr_diag::{codes, Diagnostic};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};

/// A video container npr writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Container {
    Mp4,
    Webm,
    Gif,
}

impl Container {
    pub fn from_extension(ext: &str) -> Option<Container> {
        match ext {
            "mp4" => Some(Container::Mp4),
            "webm" => Some(Container::Webm),
            "gif" => Some(Container::Gif),
            _ => None,
        }
    }

    /// ffmpeg's encoder and its arguments, and the muxer; none for GIF.
    fn ffmpeg(self) -> Option<(&'static str, &'static [&'static str], &'static str)> {
        match self {
            Container::Mp4 => Some((
                "libx264",
                &["-preset", "medium", "-crf", "18", "-movflags", "+faststart"],
                "mp4",
            )),
            Container::Webm => Some(("libvpx-vp9", &["-crf", "30", "-b:v", "0", "-row-mt", "1"], "webm")),
            Container::Gif => None,
        }
    }
}

/// The ffmpeg program: `NPR_FFMPEG` when set (a build of one's own), else
/// `ffmpeg` on the PATH.
fn ffmpeg_program() -> std::ffi::OsString {
    std::env::var_os("NPR_FFMPEG").unwrap_or_else(|| "ffmpeg".into())
}

const INSTALL_HELP: &str =
    "install ffmpeg (Debian/Ubuntu: `apt install ffmpeg`; macOS: `brew install ffmpeg`), or write a .gif, which needs no ffmpeg";

/// E0511 unless `container`'s encoder can run: ffmpeg is found and lists
/// the encoder. Checked before anything is compiled or rendered.
pub fn check_encoder(container: Container) -> Result<(), Diagnostic> {
    let Some((encoder, _, _)) = container.ffmpeg() else {
        return Ok(());
    };
    let program = ffmpeg_program();
    let listed = Command::new(&program)
        .args(["-hide_banner", "-encoders"])
        .stdin(Stdio::null())
        .stderr(Stdio::null())
        .output();
    let missing = |why: String| {
        Diagnostic::error(codes::NO_VIDEO_ENCODER, why)
            .with_note(format!(
                "npr encodes .mp4 and .webm with the system's ffmpeg ({encoder}), found as `{}`",
                program.to_string_lossy()
            ))
            .with_help(INSTALL_HELP)
    };
    match listed {
        Err(e) => Err(missing(format!(
            "cannot run `{}` to encode the video: {e}",
            program.to_string_lossy()
        ))),
        Ok(o) if !String::from_utf8_lossy(&o.stdout).contains(&format!(" {encoder} ")) => Err(missing(format!(
            "`{}` has no {encoder} encoder",
            program.to_string_lossy()
        ))),
        Ok(_) => Ok(()),
    }
}

/// A GIF side: at most 65535 pixels.
fn gif_side(n: u32) -> std::io::Result<u16> {
    u16::try_from(n).map_err(|_| std::io::Error::other(format!("a GIF is at most 65535 pixels wide and tall, not {n}")))
}

/// The temporary a video is written under: hidden, beside `out`, with its
/// extension (so a crash leaves a recognisable `.NAME.tmp-PID.mp4`).
fn temp_path(out: &Path) -> PathBuf {
    let dir = out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = out
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    dir.join(format!(".{name}.tmp-{}", std::process::id()))
}

enum Encoder {
    Ffmpeg {
        child: Child,
        stdin: Option<ChildStdin>,
        /// ffmpeg's stderr, read on a thread so it never blocks on a full pipe.
        log: Option<std::thread::JoinHandle<String>>,
    },
    Gif(Box<gif::Encoder<std::io::BufWriter<std::fs::File>>>),
}

/// A video being written: [`VideoWriter::push`] each frame, then
/// [`VideoWriter::finish`]. Dropped unfinished, it leaves nothing.
pub struct VideoWriter {
    out: PathBuf,
    temp: PathBuf,
    size: (u32, u32),
    frames: u64,
    /// Hundredths of a second per frame.
    gif_delay: u16,
    encoder: Option<Encoder>,
}

impl VideoWriter {
    /// Start writing `out` (frames of `width`×`height` at `fps`).
    pub fn start(out: &Path, container: Container, width: u32, height: u32, fps: f64) -> std::io::Result<Self> {
        let temp = temp_path(out);
        if let Some(dir) = temp.parent() {
            std::fs::create_dir_all(dir)?;
        }
        let encoder = match container.ffmpeg() {
            Some((encoder, settings, muxer)) => {
                let mut child = Command::new(ffmpeg_program())
                    .args([
                        "-hide_banner",
                        "-loglevel",
                        "error",
                        "-y",
                        "-f",
                        "rawvideo",
                        "-pix_fmt",
                        "rgba",
                    ])
                    .args([
                        "-s",
                        &format!("{width}x{height}"),
                        "-framerate",
                        &fps.to_string(),
                        "-i",
                        "-",
                    ])
                    .args([
                        "-vf",
                        "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                        "-pix_fmt",
                        "yuv420p",
                        "-c:v",
                        encoder,
                    ])
                    .args(settings)
                    .args(["-f", muxer])
                    .arg(&temp)
                    .stdin(Stdio::piped())
                    .stdout(Stdio::null())
                    .stderr(Stdio::piped())
                    .spawn()?;
                let stdin = child.stdin.take();
                let log = child.stderr.take().map(|mut e| {
                    std::thread::spawn(move || {
                        let mut s = String::new();
                        let _ = std::io::Read::read_to_string(&mut e, &mut s);
                        s
                    })
                });
                Encoder::Ffmpeg { child, stdin, log }
            }
            None => {
                let (w, h) = (gif_side(width)?, gif_side(height)?);
                let file = std::io::BufWriter::new(std::fs::File::create(&temp)?);
                let mut gif = gif::Encoder::new(file, w, h, &[]).map_err(std::io::Error::other)?;
                gif.set_repeat(gif::Repeat::Infinite).map_err(std::io::Error::other)?;
                Encoder::Gif(Box::new(gif))
            }
        };
        let centis = (100.0 / fps).round().clamp(1.0, f64::from(u16::MAX)) as u16;
        Ok(VideoWriter {
            out: out.to_path_buf(),
            temp,
            size: (width, height),
            frames: 0,
            gif_delay: centis,
            encoder: Some(encoder),
        })
    }

    /// The file being written (its final name).
    pub fn path(&self) -> &Path {
        &self.out
    }

    /// Encode the next frame (the style's output).
    pub fn push(&mut self, img: &npr_runner::TargetImage) -> std::io::Result<()> {
        if (img.width, img.height) != self.size {
            return Err(std::io::Error::other(format!(
                "a {}x{} frame in a {}x{} video",
                img.width, img.height, self.size.0, self.size.1
            )));
        }
        let mut rgba = img.to_rgba8().into_raw();
        // Alpha is dropped, as the video codecs' common profiles do: GIF's
        // one-bit transparency would punch holes where a frame is translucent.
        rgba.chunks_exact_mut(4).for_each(|px| px[3] = 255);
        match self.encoder.as_mut() {
            Some(Encoder::Ffmpeg { stdin: Some(stdin), .. }) => {
                if let Err(e) = stdin.write_all(&rgba) {
                    // ffmpeg stopped: its log says why better than the broken pipe.
                    let log = self.stop();
                    return Err(std::io::Error::other(format!("ffmpeg stopped ({e}): {}", log.trim())));
                }
            }
            Some(Encoder::Gif(gif)) => {
                let (w, h) = (gif_side(self.size.0)?, gif_side(self.size.1)?);
                // Speed 10 of 1..=30: NeuQuant's default trade of palette quality for time.
                let mut frame = gif::Frame::from_rgba_speed(w, h, &mut rgba, 10);
                frame.delay = self.gif_delay;
                gif.write_frame(&frame).map_err(std::io::Error::other)?;
            }
            _ => return Err(std::io::Error::other("the video encoder has stopped")),
        }
        self.frames += 1;
        Ok(())
    }

    /// Stop the encoder without completing the file; its log, if any.
    fn stop(&mut self) -> String {
        let log = match self.encoder.take() {
            Some(Encoder::Ffmpeg { mut child, stdin, log }) => {
                drop(stdin);
                let _ = child.kill();
                let _ = child.wait();
                log.and_then(|l| l.join().ok()).unwrap_or_default()
            }
            Some(Encoder::Gif(_)) | None => String::new(),
        };
        let _ = std::fs::remove_file(&self.temp);
        log
    }

    /// Complete the video and rename it into place; the number of frames.
    pub fn finish(mut self) -> std::io::Result<u64> {
        let written = match self.encoder.take() {
            Some(Encoder::Ffmpeg { mut child, stdin, log }) => {
                drop(stdin); // end of input: ffmpeg flushes and exits
                let status = child.wait()?;
                let log = log.and_then(|l| l.join().ok()).unwrap_or_default();
                if status.success() {
                    Ok(())
                } else {
                    Err(std::io::Error::other(format!(
                        "ffmpeg failed ({status}): {}",
                        log.trim()
                    )))
                }
            }
            Some(Encoder::Gif(gif)) => gif
                .into_inner()
                .map_err(std::io::Error::other)
                .and_then(|w| w.into_inner().map_err(|e| e.into_error()))
                .and_then(|f| f.sync_all()),
            None => Err(std::io::Error::other("the video encoder has stopped")),
        };
        let renamed = written
            .and_then(|()| std::fs::File::open(&self.temp).and_then(|f| f.sync_all()))
            .and_then(|()| std::fs::rename(&self.temp, &self.out));
        if let Err(e) = renamed {
            let _ = std::fs::remove_file(&self.temp);
            return Err(e);
        }
        Ok(self.frames)
    }
}

impl Drop for VideoWriter {
    /// A writer dropped unfinished (an error mid-sequence) leaves no file.
    fn drop(&mut self) {
        if self.encoder.is_some() {
            self.stop();
        }
    }
}
