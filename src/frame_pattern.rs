//! `{frame}` patterns in file names: the one parser of `npr render`'s
//! sequences, for what it writes (`-o 'out/{frame:04}.png'`) and what it
//! reads (`--input color='beauty/{frame}.png'`, `--inputs
//! 'shots/{frame:04}.exr'`).
//!
//! `{frame}` is the frame number zero-padded to 4 digits (what `-o` has
//! always written); `{frame:0N}` pads it to N digits (1 to 9), as Rust's
//! and Python's format strings write it, so a renderer's `0001.exr` and
//! `1.exr` are both named. A number wider than its padding is written in
//! full. Any other `{frame…}` is refused; other braces are text.

use std::path::{Path, PathBuf};

/// The padding `{frame}` has.
const DEFAULT_DIGITS: usize = 4;

/// One piece of a pattern.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Piece {
    Text(String),
    /// The frame number, zero-padded to this many digits.
    Frame {
        digits: usize,
    },
}

/// A file name with `{frame}` in it, parsed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FramePattern {
    text: String,
    pieces: Vec<Piece>,
}

/// How to write a frame number, for the messages of a bad pattern.
pub const FORMS: &str =
    "write {frame} (the frame number in 4 digits, 0001) or {frame:0N} (in N digits, e.g. {frame:06})";

impl FramePattern {
    /// `text` parsed; the message says what is wrong with a bad `{frame…}`.
    pub fn parse(text: &str) -> Result<FramePattern, String> {
        let mut pieces = Vec::new();
        let mut rest = text;
        while let Some(at) = rest.find("{frame") {
            if at > 0 {
                pieces.push(Piece::Text(rest[..at].to_string()));
            }
            let after = &rest[at + "{frame".len()..];
            let Some(close) = after.find('}') else {
                return Err(format!("`{text}`: `{{frame` is not closed"));
            };
            let spec = &after[..close];
            let digits = match spec {
                "" => DEFAULT_DIGITS,
                _ => spec
                    .strip_prefix(":0")
                    .filter(|n| n.len() == 1)
                    .and_then(|n| n.parse::<usize>().ok())
                    .filter(|n| *n >= 1)
                    .ok_or_else(|| format!("`{text}`: `{{frame{spec}}}` is not a frame number's format"))?,
            };
            pieces.push(Piece::Frame { digits });
            rest = &after[close + 1..];
        }
        if !rest.is_empty() {
            pieces.push(Piece::Text(rest.to_string()));
        }
        Ok(FramePattern {
            text: text.to_string(),
            pieces,
        })
    }

    /// [`FramePattern::parse`] of a path (not UTF-8: lossily).
    pub fn parse_path(path: &Path) -> Result<FramePattern, String> {
        Self::parse(&path.to_string_lossy())
    }

    /// The pattern as written.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// Whether the pattern names a frame (else it is one file for all).
    pub fn has_frame(&self) -> bool {
        self.pieces.iter().any(|p| matches!(p, Piece::Frame { .. }))
    }

    /// The file of frame `frame`.
    pub fn path(&self, frame: u32) -> PathBuf {
        let mut s = String::new();
        for p in &self.pieces {
            match p {
                Piece::Text(t) => s.push_str(t),
                Piece::Frame { digits } => s.push_str(&format!("{frame:0digits$}")),
            }
        }
        PathBuf::from(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(pattern: &str, frame: u32) -> String {
        FramePattern::parse(pattern).unwrap().path(frame).display().to_string()
    }

    #[test]
    fn frame_is_four_digits_and_a_width_pads_to_it() {
        assert_eq!(at("out/{frame}.png", 7), "out/0007.png");
        assert_eq!(at("shots/{frame:04}.exr", 12), "shots/0012.exr");
        assert_eq!(at("b_{frame:01}.png", 12), "b_12.png");
        assert_eq!(at("b_{frame:06}.png", 3), "b_000003.png");
        // Wider than the padding: in full.
        assert_eq!(at("{frame:02}", 12345), "12345");
    }

    #[test]
    fn every_occurrence_is_replaced_and_other_braces_are_text() {
        assert_eq!(at("{frame}/{x}_{frame:02}.exr", 5), "0005/{x}_05.exr");
        let plain = FramePattern::parse("beauty.png").unwrap();
        assert!(!plain.has_frame());
        assert_eq!(plain.path(9), PathBuf::from("beauty.png"));
    }

    #[test]
    fn a_bad_frame_format_is_refused() {
        for bad in [
            "{frame:4}",
            "{frame:x}",
            "{frame:00}",
            "{frame:010}",
            "{frames}",
            "a{frame",
        ] {
            assert!(FramePattern::parse(bad).is_err(), "{bad}");
        }
    }
}
