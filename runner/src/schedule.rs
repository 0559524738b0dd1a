//! Which frames to render for a request, and which of them to write.
//!
//! A style whose frames depend on earlier frames (history targets,
//! `Manifest::is_path_dependent`) must give the same image for
//! frame `n` whether it is rendered in a sequence or alone, so rendering
//! alone replays frames `0..=n` at the requested rate. Every other style
//! renders only what is asked for.

/// What the user asked for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FrameRequest {
    /// One frame at a time in seconds (`npr render --time t`).
    At { time_s: f64 },
    /// Frames `start..end` (exclusive) at the frame rate (`--frames a..b`).
    Range { start: u32, end: u32 },
}

/// One frame to render.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScheduledFrame {
    pub frame: u32,
    pub time_s: f64,
    /// Whether the request asked for this frame's image (a replayed frame
    /// is rendered for its history only).
    pub write: bool,
}

/// How many frames [`schedule`] renders for `request`, without making the
/// list: a caller checks it against `npr_diag::limits::MAX_FRAMES` first, since
/// `--time 1e9` of a path-dependent style would otherwise allocate and
/// replay billions of frames.
pub fn frame_count(request: FrameRequest, fps: f64, path_dependent: bool) -> u64 {
    match request {
        FrameRequest::At { time_s } => {
            let n = (time_s * fps).round().max(0.0).min(u32::MAX as f64) as u64;
            if path_dependent {
                n + 1
            } else {
                1
            }
        }
        FrameRequest::Range { start, end } => {
            let first = if path_dependent { 0 } else { start };
            u64::from(end.saturating_sub(first))
        }
    }
}

/// The frames to render for `request` at `fps`, in order.
pub fn schedule(request: FrameRequest, fps: f64, path_dependent: bool) -> Vec<ScheduledFrame> {
    let at = |frame: u32, write: bool| ScheduledFrame {
        frame,
        time_s: frame as f64 / fps,
        write,
    };
    match request {
        FrameRequest::At { time_s } => {
            let n = (time_s * fps).round().max(0.0) as u32;
            if path_dependent {
                (0..=n).map(|k| at(k, k == n)).collect()
            } else {
                vec![ScheduledFrame {
                    frame: n,
                    time_s,
                    write: true,
                }]
            }
        }
        FrameRequest::Range { start, end } => {
            let first = if path_dependent { 0 } else { start };
            (first..end).map(|k| at(k, k >= start)).collect()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_independent_frame_renders_alone_at_its_exact_time() {
        let s = schedule(FrameRequest::At { time_s: 2.51 }, 24.0, false);
        assert_eq!(
            s,
            vec![ScheduledFrame {
                frame: 60,
                time_s: 2.51,
                write: true
            }]
        );
    }

    #[test]
    fn frame_count_is_the_schedule_length() {
        for path_dependent in [false, true] {
            for request in [
                FrameRequest::At { time_s: 2.5 },
                FrameRequest::At { time_s: -3.0 },
                FrameRequest::Range { start: 5, end: 9 },
            ] {
                let n = schedule(request, 24.0, path_dependent).len() as u64;
                assert_eq!(frame_count(request, 24.0, path_dependent), n, "{request:?}");
            }
        }
        let huge = FrameRequest::At { time_s: 1e12 };
        assert_eq!(frame_count(huge, 24.0, true), u32::MAX as u64 + 1);
    }

    #[test]
    fn a_path_dependent_frame_replays_from_frame_zero() {
        let s = schedule(FrameRequest::At { time_s: 2.5 }, 24.0, true);
        assert_eq!(s.len(), 61);
        assert_eq!(s.iter().filter(|f| f.write).count(), 1);
        assert_eq!(s.last().map(|f| (f.frame, f.write)), Some((60, true)));
        assert!(s.windows(2).all(|w| w[1].frame == w[0].frame + 1));
        assert_eq!(s[0].time_s, 0.0);
    }

    #[test]
    fn a_path_dependent_range_replays_the_frames_before_it() {
        let s = schedule(FrameRequest::Range { start: 5, end: 8 }, 24.0, true);
        let written: Vec<u32> = s.iter().filter(|f| f.write).map(|f| f.frame).collect();
        assert_eq!(written, [5, 6, 7]);
        assert_eq!(s.len(), 8);
        let plain = schedule(FrameRequest::Range { start: 5, end: 8 }, 24.0, false);
        assert_eq!(plain.iter().map(|f| f.frame).collect::<Vec<_>>(), [5, 6, 7]);
    }

    #[test]
    fn the_same_frame_has_the_same_time_either_way() {
        let alone = schedule(FrameRequest::At { time_s: 8.0 / 24.0 }, 24.0, true);
        let range = schedule(FrameRequest::Range { start: 0, end: 9 }, 24.0, true);
        assert_eq!(
            alone,
            range
                .iter()
                .map(|f| ScheduledFrame {
                    write: f.frame == 8,
                    ..*f
                })
                .collect::<Vec<_>>()
        );
    }
}
