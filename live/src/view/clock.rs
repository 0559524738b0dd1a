//! `npr view`'s time and frame timing: the style's clock (running or
//! paused, stepped by frames) and the mean frame time shown in the title
//! and printed by `--frames N`.

use std::time::Duration;

/// The style's time: starts at `--time`, runs with the wall clock unless
/// paused.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clock {
    pub time_s: f64,
    pub paused: bool,
    /// Frames per second of `,` and `.` steps and of the style's `frame`.
    pub fps: f64,
}

impl Clock {
    /// Advance by a frame's wall time `dt` (nothing while paused).
    pub fn tick(&mut self, dt: Duration) {
        if !self.paused {
            self.time_s += dt.as_secs_f64();
        }
    }

    /// The style's `frame` number at this time (at `fps`), as `npr render
    /// --time` gives it.
    pub fn frame(&self) -> u32 {
        (self.time_s * self.fps).round().max(0.0) as u32
    }

    /// Step `frames` frames (may be negative), never before 0.
    pub fn step(&mut self, frames: i32) {
        self.time_s = (self.time_s + f64::from(frames) / self.fps).max(0.0);
    }
}

/// The last frames' durations, for a mean that follows the current rate.
#[derive(Debug, Default)]
pub struct FrameTimes {
    recent: std::collections::VecDeque<Duration>,
    /// Every frame since the first (for `--frames N`'s report).
    total: Duration,
    count: u32,
}

/// How many frames the title's mean is over.
const WINDOW: usize = 30;

impl FrameTimes {
    pub fn record(&mut self, d: Duration) {
        if self.recent.len() == WINDOW {
            self.recent.pop_front();
        }
        self.recent.push_back(d);
        self.total += d;
        self.count += 1;
    }

    /// Mean over the last frames, milliseconds (0 before any).
    pub fn recent_mean_ms(&self) -> f64 {
        if self.recent.is_empty() {
            return 0.0;
        }
        self.recent.iter().map(Duration::as_secs_f64).sum::<f64>() * 1e3 / self.recent.len() as f64
    }

    /// Mean over every frame recorded, milliseconds, and their number.
    pub fn mean_ms(&self) -> (f64, u32) {
        if self.count == 0 {
            return (0.0, 0);
        }
        (self.total.as_secs_f64() * 1e3 / f64::from(self.count), self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_paused_clock_stands_still_and_steps_by_frames() {
        let mut c = Clock {
            time_s: 1.0,
            paused: true,
            fps: 24.0,
        };
        c.tick(Duration::from_millis(500));
        assert_eq!(c.time_s, 1.0);
        assert_eq!(c.frame(), 24);
        c.step(12);
        assert_eq!(c.time_s, 1.5);
        c.step(-100);
        assert_eq!(c.time_s, 0.0);
        c.paused = false;
        c.tick(Duration::from_millis(250));
        assert_eq!(c.time_s, 0.25);
    }

    #[test]
    fn the_recent_mean_follows_the_last_frames() {
        let mut t = FrameTimes::default();
        assert_eq!(t.recent_mean_ms(), 0.0);
        for _ in 0..WINDOW {
            t.record(Duration::from_millis(10));
        }
        for _ in 0..WINDOW {
            t.record(Duration::from_millis(20));
        }
        assert!((t.recent_mean_ms() - 20.0).abs() < 1e-9);
        let (mean, n) = t.mean_ms();
        assert_eq!(n, 2 * WINDOW as u32);
        assert!((mean - 15.0).abs() < 1e-9);
    }
}
