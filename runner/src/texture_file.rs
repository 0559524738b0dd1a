//! Image files named by a style's textures: opened header first, so that
//! `npr check` reports what `npr render` would (not an image, too large,
//! unreadable) without decoding, and so that render refuses an image past
//! `MAX_TEXTURE_SIZE` before allocating its pixels.
//!
//! Both go through `header`, the one definition of what a readable
//! texture file is; [`TextureFileError::to_diagnostic`] is the one wording.

use image::ImageReader;
use npr_abi::manifest::{Manifest, TextureSourceManifest};
use npr_diag::limits::MAX_TEXTURE_SIZE;
use npr_diag::{codes, Diagnostic};
use std::io::BufReader;
use std::path::Path;

/// Why a texture file cannot be used.
#[derive(Debug)]
pub enum TextureFileError {
    /// It cannot be opened or read (missing, a directory, no permission).
    Unreadable(std::io::Error),
    /// It is not an image of a format npr reads (PNG, EXR), or it is corrupt.
    NotAnImage(image::ImageError),
    /// Wider or taller than [`MAX_TEXTURE_SIZE`].
    TooLarge { width: u32, height: u32 },
}

type Reader = ImageReader<BufReader<std::fs::File>>;

/// The file's reader, its format guessed from its content (then its
/// extension), and its size, checked against the limit.
fn header(path: &Path) -> Result<(Reader, (u32, u32)), TextureFileError> {
    header_of(|| ImageReader::open(path)?.with_guessed_format())
}

/// [`header`] of a reader `open` makes (twice: the size consumes one).
fn header_of<R: std::io::BufRead + std::io::Seek>(
    open: impl Fn() -> std::io::Result<ImageReader<R>>,
) -> Result<(ImageReader<R>, (u32, u32)), TextureFileError> {
    let reader = open().map_err(TextureFileError::Unreadable)?;
    // `into_dimensions` consumes a reader: read the header with a second one.
    let (width, height) = open()
        .map_err(TextureFileError::Unreadable)?
        .into_dimensions()
        .map_err(|e| match e {
            image::ImageError::IoError(io) => TextureFileError::Unreadable(io),
            other => TextureFileError::NotAnImage(other),
        })?;
    if width > MAX_TEXTURE_SIZE || height > MAX_TEXTURE_SIZE {
        return Err(TextureFileError::TooLarge { width, height });
    }
    Ok((reader, (width, height)))
}

/// The file's size, from its header alone.
pub fn probe(path: &Path) -> Result<(u32, u32), TextureFileError> {
    header(path).map(|(_, size)| size)
}

/// The decoded image, after [`probe`]'s checks.
pub fn read(path: &Path) -> Result<image::DynamicImage, TextureFileError> {
    let (reader, _) = header(path)?;
    decode(reader)
}

/// [`read`] of a file's bytes held in memory (read once, or a bundle's
/// image files). As from disk, the format is guessed from the content,
/// then from `name`'s extension: a corrupt `x.png` is then refused by the
/// PNG decoder with its reason, not as "format could not be determined".
pub fn read_bytes(bytes: &[u8], name: &Path) -> Result<image::DynamicImage, TextureFileError> {
    let by_extension = image::ImageFormat::from_path(name).ok();
    let (reader, _) = header_of(|| {
        let mut reader = ImageReader::new(std::io::Cursor::new(bytes));
        if let Some(format) = by_extension {
            reader.set_format(format);
        }
        reader.with_guessed_format()
    })?;
    decode(reader)
}

fn decode<R: std::io::BufRead + std::io::Seek>(
    reader: ImageReader<R>,
) -> Result<image::DynamicImage, TextureFileError> {
    reader.decode().map_err(|e| match e {
        image::ImageError::IoError(io) => TextureFileError::Unreadable(io),
        other => TextureFileError::NotAnImage(other),
    })
}

impl TextureFileError {
    /// The diagnostic for texture `name`, whose file the style wrote as
    /// `path`: E0401, or E0404 past the size limit. No label: the caller
    /// knows where the file was named (the `image("…")` in the style, or a
    /// binding in the scene).
    pub fn to_diagnostic(&self, name: &str, path: &str) -> Diagnostic {
        match self {
            TextureFileError::Unreadable(e) => Diagnostic::error(
                codes::MISSING_TEXTURE,
                format!("cannot read texture `{name}` ({path}): {e}"),
            )
            .with_help("check that the file exists and is readable; paths are relative to the file that names them"),
            TextureFileError::NotAnImage(e) => Diagnostic::error(
                codes::MISSING_TEXTURE,
                format!("texture `{name}` ({path}) is not an image npr can read: {e}"),
            )
            .with_help("use a PNG or EXR file"),
            TextureFileError::TooLarge { width, height } => Diagnostic::error(
                codes::LIMIT_EXCEEDED,
                format!("texture `{name}` ({path}) is {width}x{height}, over the {MAX_TEXTURE_SIZE}-texel limit"),
            )
            .with_help(format!(
                "downscale the image to at most {MAX_TEXTURE_SIZE}x{MAX_TEXTURE_SIZE} (docs/LIMITS.md)"
            )),
        }
    }
}

/// How far [`check_files`] opens each file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Depth {
    /// The header ([`probe`]): size and format. Enough before a render,
    /// whose own decode reports corrupt data at the same place; and cheap
    /// enough for the language server on every edit.
    Header,
    /// The whole decode ([`read`]): `npr check`, which must refuse what
    /// render would, corrupt data past a good header included.
    Decode,
}

/// Every image file `manifest`'s textures name, opened to `depth`:
/// (texture index, diagnostic) for each one that render would refuse.
pub fn check_files(manifest: &Manifest, depth: Depth) -> Vec<(usize, Diagnostic)> {
    manifest
        .textures
        .iter()
        .enumerate()
        .filter_map(|(i, t)| {
            // Only image and art-map sources read a file; the others are generated.
            let (path, resolved) = match &t.source {
                TextureSourceManifest::Image { path, resolved, .. } => (path, resolved),
                TextureSourceManifest::Artmap(spec) => (&spec.path, &spec.resolved),
                _ => return None,
            };
            let opened = match depth {
                Depth::Header => probe(Path::new(resolved)).map(|_| ()),
                Depth::Decode => read(Path::new(resolved)).map(|_| ()),
            };
            opened.err().map(|e| (i, e.to_diagnostic(&t.name, path)))
        })
        .collect()
}
