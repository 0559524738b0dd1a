//! `--frames` and `--chunk` of `npr render`, as render farms write them.
//!
//! `--frames` takes `A..B` (B exclusive, npr's own form), `A-B` (inclusive,
//! as Flamenco, Open Job Description and OpenCue hand a task its range) or a
//! single frame `N`. `--chunk I/N` (I from 0, as Kubernetes' indexed jobs
//! and `SLURM_ARRAY_TASK_ID` with `--array=0-(N-1)` number tasks) takes the
//! I-th of N contiguous chunks of the `--frames` range, chunk sizes
//! differing by at most one frame, so N tasks cover the range exactly once.
//!
//! Each argument is added to the [`SourceMap`] as a file named after its
//! flag, as `--set` does, so a bad range is an E0502 pointing into the
//! argument itself (`10-5`: at the end that comes first).

use npr_diag::{codes, Diagnostic, SourceMap, Span};

/// A half-open frame range `start..end`, never empty.
pub type Frames = (u32, u32);

/// What is wrong with an argument, before it has a file in the source map.
struct Bad {
    message: String,
    at: std::ops::Range<usize>,
    label: &'static str,
    help: &'static str,
}

fn bad(message: String, at: std::ops::Range<usize>, label: &'static str, help: &'static str) -> Bad {
    Bad {
        message,
        at,
        label,
        help,
    }
}

const FORMS: &str = "write A..B (B exclusive), A-B (B inclusive) or one frame N, e.g. 0..48, 0-47 or 12";

/// A frame number at `text[at]` (surrounding spaces allowed).
fn number(text: &str, at: std::ops::Range<usize>) -> Result<u32, Bad> {
    let part = &text[at.clone()];
    part.trim().parse().map_err(|_| {
        bad(
            format!("`{part}` is not a frame number"),
            at,
            "expected a whole number from 0",
            FORMS,
        )
    })
}

/// `--frames` without its source file: the range, or what is wrong where.
fn parse_frames_text(text: &str) -> Result<Frames, Bad> {
    let whole = 0..text.len();
    if let Some(i) = text.find("..") {
        let (a, b) = (number(text, 0..i)?, number(text, i + 2..text.len())?);
        if b <= a {
            return Err(bad(
                format!("the frame range {text} is empty: the end is exclusive, so it must be after the start"),
                whole,
                "empty range",
                "for the frames A to B inclusive write A-B, or A..B+1",
            ));
        }
        return Ok((a, b));
    }
    // `A-B`: a `-` after the first digit (a leading `-` is a negative number).
    if let Some(i) = text.char_indices().skip(1).find(|&(_, c)| c == '-').map(|(i, _)| i) {
        let (a, b) = (number(text, 0..i)?, number(text, i + 1..text.len())?);
        if b < a {
            return Err(bad(
                format!("the frame range {text} ends before it starts"),
                whole,
                "the last frame is before the first",
                "A-B renders frames A to B inclusive, so B must be at least A",
            ));
        }
        let end = b.checked_add(1).ok_or_else(|| {
            bad(
                format!("frame {b} is past the last frame number"),
                i + 1..text.len(),
                "too large",
                "frames are numbered below 4294967295",
            )
        })?;
        return Ok((a, end));
    }
    let n = number(text, whole.clone())?;
    let end = n.checked_add(1).ok_or_else(|| {
        bad(
            format!("frame {n} is past the last frame number"),
            whole,
            "too large",
            FORMS,
        )
    })?;
    Ok((n, end))
}

/// `--chunk I/N` of `frames`, without its source file.
fn chunk_text(text: &str, (start, end): Frames) -> Result<Frames, Bad> {
    let slash = text.find('/').ok_or_else(|| {
        bad(
            format!("`{text}` is not a chunk"),
            0..text.len(),
            "expected I/N",
            "--chunk I/N renders the I-th (from 0) of N equal parts of --frames, e.g. --chunk 0/4",
        )
    })?;
    let count_at = slash + 1..text.len();
    let (index, count) = (number(text, 0..slash)?, number(text, count_at.clone())?);
    if count == 0 {
        return Err(bad(
            "a range cannot be split into 0 chunks".into(),
            count_at,
            "expected 1 or more",
            "--chunk I/N splits --frames into N chunks",
        ));
    }
    if index >= count {
        return Err(bad(
            format!(
                "chunk {index} of {count} does not exist: chunks are numbered 0 to {}",
                count - 1
            ),
            0..slash,
            "past the last chunk",
            "chunks count from 0, as Kubernetes indexed jobs and Slurm arrays (--array=0-(N-1)) number tasks",
        ));
    }
    let len = u64::from(end - start);
    if u64::from(count) > len {
        return Err(bad(
            format!("{count} chunks of {len} frame(s) would leave some chunks empty"),
            count_at,
            "more chunks than frames",
            "give at most as many chunks as --frames has frames",
        ));
    }
    // Chunk i is [start + ⌊i·len/N⌋, start + ⌊(i+1)·len/N⌋): contiguous,
    // covering the range once, sizes differing by at most one.
    let at = |i: u32| start + (u64::from(i) * len / u64::from(count)) as u32;
    Ok((at(index), at(index + 1)))
}

/// The diagnostic of `bad`, its argument added to `sources` as `flag`.
fn diagnostic(flag: &str, text: &str, b: Bad, sources: &mut SourceMap) -> Diagnostic {
    let file = sources.add(flag, text.to_string());
    Diagnostic::error(codes::BAD_ARGUMENT_VALUE, format!("{flag} {text}: {}", b.message))
        .with_primary(Span::new(file, b.at.start, b.at.end), b.label)
        .with_help(b.help)
}

/// The frames `npr render` writes: `--frames`, narrowed by `--chunk`
/// (which needs `--frames`, the whole range it splits).
pub fn resolve(
    frames: Option<&str>,
    chunk: Option<&str>,
    sources: &mut SourceMap,
) -> Result<Option<Frames>, Diagnostic> {
    let range = match frames {
        Some(text) => Some(parse_frames_text(text).map_err(|b| diagnostic("--frames", text, b, sources))?),
        None => None,
    };
    match (range, chunk) {
        (range, None) => Ok(range),
        (Some(range), Some(text)) => chunk_text(text, range)
            .map(Some)
            .map_err(|b| diagnostic("--chunk", text, b, sources)),
        (None, Some(text)) => Err(Diagnostic::error(
            codes::BAD_ARGUMENT_VALUE,
            format!("--chunk {text} needs --frames: the whole range it is a chunk of"),
        )
        .with_help("give the whole sequence too, e.g. --frames 0-479 --chunk 2/10")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frames(s: &str) -> Option<Frames> {
        parse_frames_text(s).ok()
    }

    #[test]
    fn the_three_forms_of_a_range() {
        assert_eq!(frames("0..48"), Some((0, 48)));
        assert_eq!(frames("96-191"), Some((96, 192)));
        assert_eq!(frames(" 3 - 3 "), Some((3, 4)));
        assert_eq!(frames("12"), Some((12, 13)));
        for bad in ["10-5", "5..5", "5..2", "-3", "a-b", "", "1..", "4294967295"] {
            assert_eq!(frames(bad), None, "{bad}");
        }
    }

    #[test]
    fn chunks_cover_the_range_once_in_order() {
        for (range, n) in [((0, 480), 10), ((7, 17), 3), ((0, 5), 5), ((100, 101), 1)] {
            let chunks: Vec<Frames> = (0..n)
                .map(|i| chunk_text(&format!("{i}/{n}"), range).ok().expect("a chunk"))
                .collect();
            assert_eq!(chunks.first().map(|c| c.0), Some(range.0));
            assert_eq!(chunks.last().map(|c| c.1), Some(range.1));
            for pair in chunks.windows(2) {
                assert_eq!(pair[0].1, pair[1].0, "{chunks:?}");
            }
            let sizes: Vec<u32> = chunks.iter().map(|c| c.1 - c.0).collect();
            let (min, max) = (sizes.iter().min(), sizes.iter().max());
            assert!(max.zip(min).is_some_and(|(a, b)| a - b <= 1), "{sizes:?}");
        }
        for bad in ["3/2", "2/2", "0/0", "1", "a/2", "0/6"] {
            assert!(chunk_text(bad, (0, 5)).is_err(), "{bad}");
        }
    }
}
