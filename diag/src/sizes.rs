//! Image sizes (`512x512`), frame ranges (`0..48`), times and frame rates
//! as a user writes them, on a command line or in a test file, read and checked against
//! [`crate::limits`]: one reading for the CLI's arguments and `npr-test`'s
//! declarations. A syntax error is a plain message (the CLI's usage error,
//! E0501, or the test file's E0407 around it); a value past a limit is E0404.

use crate::codes;
use crate::limits::{MAX_FRAMES, MAX_OUTPUT_SIZE};
use crate::Diagnostic;

/// `--size WIDTHxHEIGHT`.
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or("expected WIDTHxHEIGHT, e.g. 512x512")?;
    let w: u32 = w.trim().parse().map_err(|_| format!("bad width `{w}`"))?;
    let h: u32 = h.trim().parse().map_err(|_| format!("bad height `{h}`"))?;
    if w == 0 || h == 0 {
        return Err("width and height must be at least 1".into());
    }
    Ok((w, h))
}

/// `--frames A..B` (B exclusive, after A).
pub fn parse_frames(s: &str) -> Result<(u32, u32), String> {
    let (a, b) = s.split_once("..").ok_or("expected A..B, e.g. 0..48")?;
    let a: u32 = a.trim().parse().map_err(|_| format!("bad frame `{a}`"))?;
    let b: u32 = b.trim().parse().map_err(|_| format!("bad frame `{b}`"))?;
    if b <= a {
        return Err(format!(
            "empty frame range {a}..{b}: the end is exclusive, so it must be after the start"
        ));
    }
    Ok((a, b))
}

/// An image size (`--size`, or one of `bench contours --sizes`) under the limit.
pub fn check_size((w, h): (u32, u32)) -> Result<(), Diagnostic> {
    if w > MAX_OUTPUT_SIZE || h > MAX_OUTPUT_SIZE {
        return Err(Diagnostic::error(
            codes::LIMIT_EXCEEDED,
            format!("--size {w}x{h} is larger than {MAX_OUTPUT_SIZE}x{MAX_OUTPUT_SIZE}"),
        )
        .with_help(format!(
            "an image is at most {MAX_OUTPUT_SIZE} pixels wide and tall (the 2D texture limit)"
        )));
    }
    Ok(())
}

/// How many frames a render will run: `--frames A..B`, or for a
/// path-dependent style at `--time t`, the replay of frames 0..=t·fps.
pub fn check_frame_count(frames: usize) -> Result<(), Diagnostic> {
    if frames > MAX_FRAMES as usize {
        return Err(Diagnostic::error(
            codes::LIMIT_EXCEEDED,
            format!("this render would run {frames} frames, more than the limit of {MAX_FRAMES}"),
        )
        .with_help(
            "render a shorter --frames range; a style that reads `previous(...)` or keeps `state` replays from frame 0",
        ));
    }
    Ok(())
}

/// `--fps` and `--time` (of `npr render`, `watch`, `view` and `studio`):
/// E0502 for a frame rate that is not above 0 or a time that is not finite.
pub fn check_time(time: f64, fps: f64) -> Result<(), Diagnostic> {
    let bad_value = |message: String, help: &str| Diagnostic::error(codes::BAD_ARGUMENT_VALUE, message).with_help(help);
    if !(fps.is_finite() && fps > 0.0) {
        return Err(bad_value(
            format!("--fps {fps}: the frame rate must be a number above 0"),
            "frame n is at time n / fps; 24 is the default",
        ));
    }
    if !time.is_finite() {
        return Err(bad_value(
            format!("--time {time}: the time must be a finite number of seconds"),
            "times before 0 are allowed and clamp to frame 0",
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_and_frame_counts_past_the_limits_are_refused_with_a_code() {
        assert_eq!(check_size((16385, 1)).unwrap_err().code, codes::LIMIT_EXCEEDED);
        assert!(check_size((16384, 16384)).is_ok());
        assert!(check_frame_count(MAX_FRAMES as usize).is_ok());
        assert_eq!(
            check_frame_count(MAX_FRAMES as usize + 1).unwrap_err().code,
            codes::LIMIT_EXCEEDED
        );
    }

    #[test]
    fn sizes_and_frame_ranges_are_read_as_written() {
        assert_eq!(parse_size("512x256"), Ok((512, 256)));
        assert_eq!(parse_size(" 4 X 3 "), Ok((4, 3)));
        assert!(parse_size("0x4").is_err() && parse_size("512").is_err() && parse_size("ax4").is_err());
        assert!(parse_frames("5..2").is_err() && parse_frames("3..3").is_err());
        assert_eq!(check_time(0.0, 0.0).unwrap_err().code, codes::BAD_ARGUMENT_VALUE);
        assert_eq!(check_time(0.0, -24.0).unwrap_err().code, codes::BAD_ARGUMENT_VALUE);
        assert_eq!(check_time(f64::NAN, 24.0).unwrap_err().code, codes::BAD_ARGUMENT_VALUE);
        assert_eq!(
            check_time(f64::INFINITY, 24.0).unwrap_err().code,
            codes::BAD_ARGUMENT_VALUE
        );
        assert!(check_time(-1.0, 24.0).is_ok());
        assert_eq!(parse_frames("0..1"), Ok((0, 1)));
    }
}
