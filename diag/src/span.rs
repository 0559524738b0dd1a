//! Source spans and the file table that diagnostics are rendered against.

use serde::Serialize;

/// Index of a file in a [`SourceMap`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Default, PartialOrd, Ord)]
pub struct FileId(pub u32);

/// A byte range in one source file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Default)]
pub struct Span {
    pub file: FileId,
    pub start: u32,
    pub end: u32,
}

impl Span {
    pub fn new(file: FileId, start: usize, end: usize) -> Self {
        Span {
            file,
            start: start as u32,
            end: end as u32,
        }
    }

    /// The smallest span covering both (assumes the same file).
    pub fn to(self, other: Span) -> Span {
        Span {
            file: self.file,
            start: self.start.min(other.start),
            end: self.end.max(other.end),
        }
    }

    pub fn range(self) -> std::ops::Range<usize> {
        self.start as usize..self.end as usize
    }
}

/// The files a compilation read: `.npr` styles, `use`d modules, scene TOML files.
#[derive(Debug, Clone, Default)]
pub struct SourceMap {
    files: Vec<SourceFile>,
}

#[derive(Debug, Clone)]
pub struct SourceFile {
    pub name: String,
    pub text: String,
    /// The byte offset of every line's start, so that [`SourceMap::line_col`]
    /// is a binary search: the emitter asks for the line of every `let`, and
    /// scanning from the file's start each time was quadratic.
    line_starts: Vec<usize>,
}

impl SourceMap {
    pub fn new() -> Self {
        Self::default()
    }

    pub fn add(&mut self, name: impl Into<String>, text: impl Into<String>) -> FileId {
        let text = text.into();
        let line_starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        self.files.push(SourceFile {
            name: name.into(),
            text,
            line_starts,
        });
        FileId(self.files.len() as u32 - 1)
    }

    pub fn get(&self, id: FileId) -> Option<&SourceFile> {
        self.files.get(id.0 as usize)
    }

    pub fn files(&self) -> &[SourceFile] {
        &self.files
    }

    /// 1-based (line, column) of a byte offset, columns counted in chars.
    pub fn line_col(&self, id: FileId, offset: u32) -> (usize, usize) {
        let Some(file) = self.get(id) else {
            return (0, 0);
        };
        let offset = floor_char_boundary(&file.text, (offset as usize).min(file.text.len()));
        // The last line start at or before the offset (the first is 0).
        let line = file.line_starts.partition_point(|&start| start <= offset);
        let start = file.line_starts[line.saturating_sub(1)];
        let col = file.text[start..offset].chars().count() + 1;
        (line, col)
    }

    /// The source text a span covers ("" when out of range).
    pub fn snippet(&self, span: Span) -> &str {
        self.get(span.file).and_then(|f| f.text.get(span.range())).unwrap_or("")
    }
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_col_counts_lines_and_chars() {
        let mut m = SourceMap::new();
        let text = "ab\nçd\n\nx";
        let f = m.add("t", text);
        let naive = |o: usize| {
            let before = &text[..o];
            let line = before.matches('\n').count() + 1;
            let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
            (line, col)
        };
        for o in (0..=text.len()).filter(|o| text.is_char_boundary(*o)) {
            assert_eq!(m.line_col(f, o as u32), naive(o), "offset {o}");
        }
        // Inside a multi-byte char, and past the end.
        assert_eq!(m.line_col(f, 4), (2, 1));
        assert_eq!(m.line_col(f, 1000), naive(text.len()));
    }
}
