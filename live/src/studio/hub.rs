//! The studio's shared state between the render thread and the HTTP
//! threads: the latest state (as JSON, what the page shows), the last
//! [`FRAME_RING`] frames' images, and the event-stream subscribers.
//!
//! The render thread publishes; every publish pushes one `state` event to
//! every subscriber. A subscriber gets the current state as soon as it
//! subscribes, so a page opened after a render (or after a failed compile)
//! shows it at once.

use serde_json::Value;
use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::{Arc, Mutex, MutexGuard, OnceLock};

/// How many of the latest frames stay readable at `/frame/{id}/...`: a
/// page (or a script) told of frame `id` can still fetch its targets after
/// a few newer frames, as when a slider moves while its thumbnails load.
/// Four frames of targets stay small next to the renderer's own textures;
/// the studio benchmark's memory across edits measures the whole.
pub const FRAME_RING: usize = 4;

/// One rendered frame's targets, served at `/frame/{id}/{target}.png` and
/// `.f32`, the target by name (`shade.color`) or index. The texels are kept as read back, and each file is encoded the
/// first time it is asked for (then kept with the frame): encoding every
/// target of every frame before publishing it cost more than rendering it
/// (docs/PERFORMANCE.md), and the page asks only for the thumbnails and the
/// target it shows, while slider moves replace frames faster than that.
pub struct FrameImages {
    pub id: u64,
    targets: Vec<Encoded>,
}

struct Encoded {
    image: npr_runner::TargetImage,
    /// PNG bytes as `npr render` writes them; or why they could not be made.
    png: OnceLock<Result<Vec<u8>, String>>,
    /// RGBA f32 texels, row-major, little-endian.
    f32: OnceLock<Vec<u8>>,
}

impl FrameImages {
    pub fn new(id: u64, images: Vec<npr_runner::TargetImage>) -> FrameImages {
        let targets = images
            .into_iter()
            .map(|image| Encoded {
                image,
                png: OnceLock::new(),
                f32: OnceLock::new(),
            })
            .collect();
        FrameImages { id, targets }
    }

    /// The index of the target named `name` (`shade.color`), or `name`
    /// read as an index.
    pub fn target_index(&self, name: &str) -> Option<usize> {
        self.targets
            .iter()
            .position(|t| t.image.name == name)
            .or_else(|| name.parse::<usize>().ok().filter(|i| *i < self.targets.len()))
    }

    /// The names of the targets, in index order.
    pub fn target_names(&self) -> Vec<&str> {
        self.targets.iter().map(|t| t.image.name.as_str()).collect()
    }

    /// Target `index` as PNG (encoded on first use; a second request waits
    /// for the first's encoding instead of doing it again).
    pub fn png(&self, index: usize) -> Option<Result<&[u8], &str>> {
        let t = self.targets.get(index)?;
        let png = t
            .png
            .get_or_init(|| npr_runner::output::encode_png(&t.image).map_err(|e| e.to_string()));
        Some(png.as_deref().map_err(String::as_str))
    }

    /// Target `index` as RGBA f32 texels.
    pub fn f32(&self, index: usize) -> Option<&[u8]> {
        let t = self.targets.get(index)?;
        Some(t.f32.get_or_init(|| {
            let texels = t.image.to_rgba_f32();
            let mut bytes = Vec::with_capacity(texels.len() * 16);
            for v in texels.iter().flatten() {
                bytes.extend_from_slice(&v.to_le_bytes());
            }
            bytes
        }))
    }
}

#[derive(Default)]
struct Inner {
    /// The state the page renders; `seq` increases with every publish.
    state: Value,
    seq: u64,
    /// The latest frames, oldest first, at most [`FRAME_RING`].
    frames: std::collections::VecDeque<Arc<FrameImages>>,
    subscribers: Vec<Sender<String>>,
}

#[derive(Clone, Default)]
pub struct Hub {
    inner: Arc<Mutex<Inner>>,
}

impl Hub {
    fn lock(&self) -> MutexGuard<'_, Inner> {
        // A panic while holding the lock left valid data (every write is a
        // whole assignment); keep serving.
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Replace the state (and the frame, when a new one was rendered) and
    /// push it to every subscriber.
    pub fn publish(&self, mut state: Value, frame: Option<FrameImages>) {
        let mut inner = self.lock();
        inner.seq += 1;
        state["seq"] = inner.seq.into();
        if let Some(f) = frame {
            if inner.frames.len() == FRAME_RING {
                inner.frames.pop_front();
            }
            inner.frames.push_back(Arc::new(f));
        }
        let event = sse_event("state", &state.to_string());
        inner.state = state;
        inner.subscribers.retain(|s| s.send(event.clone()).is_ok());
    }

    pub fn state(&self) -> Value {
        self.lock().state.clone()
    }

    /// Frame `id`, if it is one of the last [`FRAME_RING`]; else the ids kept.
    pub fn frame_by_id(&self, id: u64) -> Result<Arc<FrameImages>, Vec<u64>> {
        let inner = self.lock();
        inner
            .frames
            .iter()
            .find(|f| f.id == id)
            .cloned()
            .ok_or_else(|| inner.frames.iter().map(|f| f.id).collect())
    }

    /// A new subscriber: the current state first, then every publish.
    pub fn subscribe(&self) -> Receiver<String> {
        let (tx, rx) = channel();
        let mut inner = self.lock();
        if !inner.state.is_null() {
            let _ = tx.send(sse_event("state", &inner.state.to_string()));
        }
        inner.subscribers.push(tx);
        rx
    }
}

/// One server-sent event (`data` is one line of JSON, so one `data:` field).
fn sse_event(name: &str, data: &str) -> String {
    format!("event: {name}\ndata: {data}\n\n")
}
