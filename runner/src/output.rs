//! Writing images: 8-bit sRGB PNG for display targets, 16-bit PNG or EXR for
//! float targets, and a contact sheet of every target. Every file is written
//! to a temporary name in the same directory and renamed into place, so a
//! crash never leaves a half-written image.

use crate::readback::TargetImage;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Whether `path` is something other than a regular file or a directory (a
/// device like `/dev/null`, a FIFO, a socket): renaming a temporary over
/// it would replace the device node with a plain file, so it is written in
/// place instead (atomicity means nothing there).
fn is_special(path: &Path) -> bool {
    std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir())
}

/// Write `bytes` to `path` atomically (temp file + rename); a device or FIFO
/// (`-o /dev/null`) is written in place.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    if is_special(path) {
        return std::fs::OpenOptions::new().write(true).open(path)?.write_all(bytes);
    }
    let tmp = temp_path(path)?;
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// The temporary name `path` is written under before its rename: a hidden
/// file beside it (same directory, so the rename is atomic), which is
/// created if missing. The name is unique per call (process id and a
/// counter), so two threads writing the same path never share a temporary.
fn temp_path(path: &Path) -> std::io::Result<PathBuf> {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir)?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    Ok(dir.join(format!(".{name}.tmp-{}-{n}", std::process::id())))
}

/// Write several files atomically, each as [`write_atomic`] does, but with
/// their flushes to disk issued together: every file goes to a temporary
/// name, all are synced in parallel (the filesystem commits them in one
/// journal transaction instead of one per file), then each is renamed into
/// place. On an error no temporary file is left; files renamed before it
/// stay (each is whole).
pub fn write_all_atomic(files: &[(PathBuf, &[u8])]) -> std::io::Result<()> {
    let mut temps: Vec<(PathBuf, &Path)> = Vec::new();
    let result = (|| {
        let mut written = Vec::new();
        for (path, bytes) in files {
            if is_special(path) {
                std::fs::OpenOptions::new().write(true).open(path)?.write_all(bytes)?;
                continue;
            }
            let tmp = temp_path(path)?;
            let mut f = std::fs::File::create(&tmp)?;
            temps.push((tmp, path));
            f.write_all(bytes)?;
            written.push(f);
        }
        std::thread::scope(|scope| {
            let syncs: Vec<_> = written.iter().map(|f| scope.spawn(move || f.sync_all())).collect();
            syncs.into_iter().try_for_each(|s| {
                s.join()
                    .unwrap_or_else(|_| Err(std::io::Error::other("a sync thread panicked")))
            })
        })?;
        for (tmp, path) in &temps {
            std::fs::rename(tmp, path)?;
        }
        Ok(())
    })();
    if result.is_err() {
        for (tmp, _) in &temps {
            let _ = std::fs::remove_file(tmp);
        }
    }
    result
}

fn encode(img: image::DynamicImage, format: image::ImageFormat) -> std::io::Result<Vec<u8>> {
    let mut buf = std::io::Cursor::new(Vec::new());
    img.write_to(&mut buf, format).map_err(std::io::Error::other)?;
    Ok(buf.into_inner())
}

/// A target as PNG bytes, exactly as [`write_target`] writes a `.png`:
/// 8-bit for unorm targets, 16-bit (clamped to [0, 1]) for float targets.
///
/// Every row is filtered with Paeth, not the encoder's default adaptive
/// choice among all five filters per row: on a 512² toon frame that is
/// 0.8 ms instead of 3.0 ms for a file 3% larger (37.7 kB against 36.7 kB;
/// 1% on the Age of Sail golden), and the studio encodes one on every
/// slider move (docs/PERFORMANCE.md). The compression stays the encoder's
/// fast one (fdeflate).
pub fn encode_png(img: &TargetImage) -> std::io::Result<Vec<u8>> {
    use image::ImageEncoder;
    let mut out = Vec::new();
    let encoder = image::codecs::png::PngEncoder::new_with_quality(
        &mut out,
        image::codecs::png::CompressionType::Fast,
        image::codecs::png::FilterType::Paeth,
    );
    let written = if img.is_float() {
        let px: Vec<u16> = img
            .to_rgba_f32()
            .into_iter()
            .flat_map(|p| {
                let p = if img.format.channels() == 1 {
                    [p[0], p[0], p[0], 1.0]
                } else {
                    p
                };
                p.map(|c| (if c.is_finite() { c } else { 0.0 }.clamp(0.0, 1.0) * 65535.0).round() as u16)
            })
            .collect();
        // PNG stores 16-bit samples big-endian; the encoder takes native-endian bytes.
        let bytes: Vec<u8> = px.iter().flat_map(|v| v.to_ne_bytes()).collect();
        encoder.write_image(&bytes, img.width, img.height, image::ExtendedColorType::Rgba16)
    } else {
        let px = img.to_rgba8();
        encoder.write_image(px.as_raw(), img.width, img.height, image::ExtendedColorType::Rgba8)
    };
    written.map_err(std::io::Error::other)?;
    Ok(out)
}

/// Write a target: `.png` (8-bit for unorm targets, 16-bit for float targets)
/// or `.exr` (32-bit float, values unclamped).
/// The image extensions [`write_target`] writes (no extension is PNG).
pub const IMAGE_EXTENSIONS: &[&str] = &["png", "exr"];

pub fn write_target(img: &TargetImage, path: &Path) -> std::io::Result<()> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    let bytes = match ext.as_str() {
        "exr" => {
            let px: Vec<f32> = img.to_rgba_f32().into_iter().flatten().collect();
            let buf = image::Rgba32FImage::from_raw(img.width, img.height, px)
                .ok_or_else(|| std::io::Error::other("bad image size"))?;
            encode(image::DynamicImage::ImageRgba32F(buf), image::ImageFormat::OpenExr)?
        }
        "png" | "" => encode_png(img)?,
        other => {
            return Err(std::io::Error::other(format!(
                "unsupported image extension `.{other}`: use .png or .exr"
            )))
        }
    };
    write_atomic(path, &bytes)
}

pub fn write_png8(img: &image::RgbaImage, path: &Path) -> std::io::Result<()> {
    write_atomic(
        path,
        &encode(image::DynamicImage::ImageRgba8(img.clone()), image::ImageFormat::Png)?,
    )
}

/// Lay out thumbnails of every target in a grid (row-major, in the order
/// given), each scaled to `cell` px wide. Returns the sheet and the names in
/// cell order (written beside it as `contact_sheet.txt`).
pub fn contact_sheet(images: &[TargetImage], cell: u32) -> image::RgbaImage {
    let cols = (images.len() as f64).sqrt().ceil().max(1.0) as u32;
    let rows = (images.len() as u32).div_ceil(cols).max(1);
    let aspect = images.first().map(|i| i.height as f64 / i.width as f64).unwrap_or(1.0);
    let cell_h = ((cell as f64 * aspect).round() as u32).max(1);
    let gap = 4;
    let mut sheet = image::RgbaImage::from_pixel(
        cols * (cell + gap) + gap,
        rows * (cell_h + gap) + gap,
        image::Rgba([40, 40, 40, 255]),
    );
    for (i, img) in images.iter().enumerate() {
        let thumb = image::imageops::resize(&img.to_rgba8(), cell, cell_h, image::imageops::FilterType::Triangle);
        let (cx, cy) = (i as u32 % cols, i as u32 / cols);
        image::imageops::overlay(
            &mut sheet,
            &thumb,
            (gap + cx * (cell + gap)) as i64,
            (gap + cy * (cell_h + gap)) as i64,
        );
    }
    sheet
}

/// Write every target as `<dir>/<NN>_<pass>.<target>.png` plus `contact_sheet.png`
/// and `contact_sheet.txt` (the grid order). Returns the files written.
pub fn dump_targets(images: &[TargetImage], dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    let mut index = String::new();
    for (i, img) in images.iter().enumerate() {
        let path = dir.join(format!("{i:02}_{}.png", img.name));
        write_target(img, &path)?;
        index.push_str(&format!(
            "{i:02} {} {}x{} {}\n",
            img.name,
            img.width,
            img.height,
            img.format.name()
        ));
        written.push(path);
    }
    let sheet = contact_sheet(images, 256);
    let sheet_path = dir.join("contact_sheet.png");
    write_png8(&sheet, &sheet_path)?;
    written.push(sheet_path);
    let idx = dir.join("contact_sheet.txt");
    write_atomic(&idx, index.as_bytes())?;
    written.push(idx);
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("npr-output-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("scratch");
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .expect("dir")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn several_files_are_written_whole_and_no_temporary_is_left() {
        let dir = scratch("all");
        std::fs::write(dir.join("a.wgsl"), b"old").expect("old file");
        let files = [
            (dir.join("a.wgsl"), &b"new a"[..]),
            (dir.join("sub/b.json"), &b"{}"[..]),
        ];
        write_all_atomic(&files).expect("written");
        assert_eq!(std::fs::read(dir.join("a.wgsl")).expect("a"), b"new a");
        assert_eq!(std::fs::read(dir.join("sub/b.json")).expect("b"), b"{}");
        assert_eq!(names(&dir), ["a.wgsl", "sub"]);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_failing_write_removes_its_temporaries_and_keeps_the_old_files() {
        let dir = scratch("fail");
        std::fs::write(dir.join("a.wgsl"), b"old").expect("old file");
        // `blocker` is a file, so `blocker/c.txt` cannot be created.
        std::fs::write(dir.join("blocker"), b"").expect("blocker");
        let files = [
            (dir.join("a.wgsl"), &b"new"[..]),
            (dir.join("blocker/c.txt"), &b"c"[..]),
        ];
        assert!(write_all_atomic(&files).is_err());
        assert_eq!(
            std::fs::read(dir.join("a.wgsl")).expect("a"),
            b"old",
            "nothing renamed before the error"
        );
        assert_eq!(names(&dir), ["a.wgsl", "blocker"], "no temporary file left");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_fifo_is_written_in_place_not_replaced() {
        // `-o /dev/null` once replaced /dev/null with a plain file (as root).
        // A FIFO stands in for a device here.
        let dir = std::env::temp_dir().join(format!("npr-output-fifo-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("dir");
        let fifo = dir.join("pipe");
        let _ = std::fs::remove_file(&fifo);
        let made = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .expect("mkfifo runs");
        assert!(made.success(), "mkfifo failed");
        let reader = {
            let fifo = fifo.clone();
            std::thread::spawn(move || std::fs::read(fifo).expect("read the fifo"))
        };
        write_atomic(&fifo, b"image bytes").expect("write");
        // Checked before joining: a replaced FIFO never gets a writer, and
        // the reader would wait for ever.
        use std::os::unix::fs::FileTypeExt;
        assert!(
            std::fs::metadata(&fifo).expect("still there").file_type().is_fifo(),
            "replaced by a plain file"
        );
        assert_eq!(reader.join().expect("reader"), b"image bytes");
        std::fs::remove_dir_all(&dir).expect("clean up");
    }
}
