//! Source files as text: styles, `use`d styles and scenes are UTF-8.
//!
//! A file that is not is still added to the [`SourceMap`] (decoded lossily,
//! so the bytes before the first bad one are exactly as written), so that
//! its error points at the line and column of that byte like any other.

use crate::{codes, Diagnostic, FileId, SourceMap, Span};

/// `bytes` as text, added to `sources` as `name`; E0007 at the first byte
/// that is not UTF-8, with the file still added so the error renders.
pub fn add_utf8(sources: &mut SourceMap, name: &str, bytes: Vec<u8>) -> Result<(FileId, String), Diagnostic> {
    match String::from_utf8(bytes) {
        Ok(text) => Ok((sources.add(name, text.clone()), text)),
        Err(e) => {
            let at = e.utf8_error().valid_up_to();
            let bytes = e.as_bytes();
            // A sequence cut off by the end of the file has no error length.
            let bad_len = e.utf8_error().error_len().unwrap_or(bytes.len() - at);
            let help = encoding_hint(bytes);
            let shown: Vec<String> = bytes[at..at + bad_len].iter().map(|b| format!("0x{b:02x}")).collect();
            // The lossy text keeps the valid prefix byte for byte, so `at`
            // is the bad byte's offset in it too; U+FFFD takes 3 bytes.
            let lossy = String::from_utf8_lossy(bytes).into_owned();
            let file = sources.add(name, lossy);
            Err(Diagnostic::error(codes::NOT_UTF8, "the file is not valid UTF-8 text")
                .with_primary(
                    Span::new(file, at, at + '\u{fffd}'.len_utf8()),
                    format!("byte {} here", shown.join(" ")),
                )
                .with_help(help))
        }
    }
}

/// What the file probably is, from its first bytes.
fn encoding_hint(bytes: &[u8]) -> String {
    let utf16 = bytes.starts_with(&[0xff, 0xfe]) || bytes.starts_with(&[0xfe, 0xff]);
    if utf16 {
        "the file starts like UTF-16 text; save it as UTF-8".into()
    } else {
        "npr reads style and scene files as UTF-8; save the file as UTF-8 (a byte like this one is often Latin-1 or Windows-1252 text)".into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_span_is_at_the_first_bad_byte() {
        let mut sources = SourceMap::new();
        let mut bytes = b"style \"S\"\nparam caf".to_vec();
        bytes.push(0xe9); // Latin-1 é
        bytes.extend_from_slice(b": float = 1.0\n");
        let d = add_utf8(&mut sources, "s.npr", bytes).expect_err("not UTF-8");
        let span = d.primary_span().expect("a span");
        assert_eq!(sources.line_col(span.file, span.start), (2, 10));
        assert!(d.labels[0].message.contains("0xe9"), "{:?}", d.labels);
    }

    #[test]
    fn utf16_is_named() {
        let mut sources = SourceMap::new();
        let d = add_utf8(&mut sources, "s.npr", vec![0xff, 0xfe, b's', 0]).expect_err("not UTF-8");
        assert!(d.help.as_deref().unwrap_or("").contains("UTF-16"), "{d:?}");
    }

    #[test]
    fn utf8_text_is_added_as_is() {
        let mut sources = SourceMap::new();
        let (file, text) = add_utf8(&mut sources, "s.npr", "style \"Café\"\n".as_bytes().to_vec()).expect("UTF-8");
        assert_eq!(text, "style \"Café\"\n");
        assert_eq!(sources.get(file).map(|f| f.text.as_str()), Some(text.as_str()));
    }
}
