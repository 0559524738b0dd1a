//! Byte offsets ↔ LSP positions. LSP counts columns in UTF-16 code units;
//! npr's spans are byte offsets into UTF-8 text, so `é` is two bytes but one
//! column and `𝒩` four bytes but two columns.

use lsp_types::{Position, Range};

/// The start of every line of one text, for converting both ways.
pub struct LineIndex<'t> {
    text: &'t str,
    starts: Vec<usize>,
}

impl<'t> LineIndex<'t> {
    pub fn new(text: &'t str) -> Self {
        let starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        LineIndex { text, starts }
    }

    /// The position of byte `offset` (clamped to the text, and to a
    /// character boundary before it).
    pub fn position(&self, offset: usize) -> Position {
        let mut offset = offset.min(self.text.len());
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        let line = self.starts.partition_point(|&s| s <= offset) - 1;
        let start = self.starts[line];
        let column: usize = self.text[start..offset].chars().map(char::len_utf16).sum();
        Position::new(line as u32, column as u32)
    }

    pub fn range(&self, start: usize, end: usize) -> Range {
        Range::new(self.position(start), self.position(end))
    }

    /// The byte offset of `pos`; a column past the line's end is its end,
    /// a line past the text's end is the text's end.
    pub fn offset(&self, pos: Position) -> usize {
        let Some(&start) = self.starts.get(pos.line as usize) else {
            return self.text.len();
        };
        let end = self
            .starts
            .get(pos.line as usize + 1)
            .map_or(self.text.len(), |next| next - 1);
        let mut units = 0usize;
        for (i, c) in self.text[start..end].char_indices() {
            if units >= pos.character as usize {
                return start + i;
            }
            units += c.len_utf16();
        }
        end
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_are_utf16_code_units() {
        let text = "ab\n/// Café 𝒩 x\nz";
        let index = LineIndex::new(text);
        let x = text.find(" x").expect("x") + 1;
        // `/// Caf` 7, `é` 1, ` ` 1, `𝒩` 2 (a surrogate pair), ` ` 1.
        assert_eq!(index.position(x), Position::new(1, 12));
        assert_eq!(index.offset(Position::new(1, 12)), x);
        assert_eq!(index.position(text.len()), Position::new(2, 1));
        assert_eq!(index.offset(Position::new(0, 99)), 2, "past the line's end");
        assert_eq!(index.offset(Position::new(9, 0)), text.len(), "past the text's end");
        // Inside a multi-byte character: its start.
        let e = text.find('é').expect("é");
        assert_eq!(index.position(e + 1), index.position(e));
    }
}
