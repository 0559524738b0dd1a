//! Art-maps are built once (Klein et al. 2000 §6: "relegating expensive NPR
//! filtering to a preprocess"): kept in memory for the process and on disk
//! between runs, under a content hash of everything the levels depend on —
//! the source file's bytes, its colour space, the compiled filter (its
//! manifest and WGSL, so a changed filter or filter parameter default
//! misses), the level count and this format's version.
//!
//! The disk cache is `$NPR_CACHE_DIR`, else `$XDG_CACHE_HOME/npr`, else
//! `$HOME/.cache/npr`, in `artmaps/<hash>.levels`; with none of them set the
//! art-map is cached in memory only, and the build says so. Files are
//! written atomically, and one that does not parse is rebuilt (and
//! overwritten), never trusted.

use crate::image_level::Level;
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, OnceLock};

/// Bumped whenever the build or the file layout changes, so that old
/// entries miss.
const FORMAT_VERSION: u32 = 1;
const MAGIC: &[u8; 8] = b"nprartm\0";
/// Art-maps kept in memory; the oldest goes first (a studio session that
/// edits a filter many times must not grow without bound).
const MEMORY_ENTRIES: usize = 16;

pub type Key = [u8; 32];

/// Where a build's levels came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Origin {
    /// Filtered now, and stored on disk (or in memory only, without a cache directory).
    Built { on_disk: bool },
    /// This process built or read it before.
    Memory,
    /// Read from the disk cache.
    Disk,
}

pub fn key(source_bytes: &[u8], srgb: bool, filter_json: &[u8], levels: u32, rip: bool) -> Key {
    let mut h = blake3::Hasher::new();
    h.update(&FORMAT_VERSION.to_le_bytes());
    h.update(&(source_bytes.len() as u64).to_le_bytes());
    h.update(source_bytes);
    h.update(&[srgb as u8]);
    h.update(&(filter_json.len() as u64).to_le_bytes());
    h.update(filter_json);
    h.update(&levels.to_le_bytes());
    h.update(&[rip as u8]);
    *h.finalize().as_bytes()
}

fn hex(key: &Key) -> String {
    key.iter().map(|b| format!("{b:02x}")).collect()
}

/// The disk cache directory, if the environment names one.
pub fn cache_dir() -> Option<PathBuf> {
    let from = |var: &str| std::env::var_os(var).filter(|v| !v.is_empty()).map(PathBuf::from);
    from("NPR_CACHE_DIR")
        .or_else(|| from("XDG_CACHE_HOME").map(|d| d.join("npr")))
        .or_else(|| from("HOME").map(|d| d.join(".cache").join("npr")))
}

fn file_path(key: &Key) -> Option<PathBuf> {
    cache_dir().map(|d| d.join("artmaps").join(format!("{}.levels", hex(key))))
}

struct Memory {
    entries: HashMap<Key, Arc<Vec<Level>>>,
    order: Vec<Key>,
}

fn memory() -> &'static Mutex<Memory> {
    static M: OnceLock<Mutex<Memory>> = OnceLock::new();
    M.get_or_init(|| {
        Mutex::new(Memory {
            entries: HashMap::new(),
            order: Vec::new(),
        })
    })
}

/// The levels under `key`, from memory or disk.
pub fn get(key: &Key) -> Option<(Arc<Vec<Level>>, Origin)> {
    if let Some(levels) = memory().lock().ok()?.entries.get(key) {
        return Some((levels.clone(), Origin::Memory));
    }
    let bytes = std::fs::read(file_path(key)?).ok()?;
    let levels = Arc::new(decode(&bytes)?);
    remember(*key, levels.clone());
    Some((levels, Origin::Disk))
}

/// Keep `levels` under `key`; whether they reached the disk.
pub fn put(key: &Key, levels: Arc<Vec<Level>>) -> bool {
    let on_disk = file_path(key).is_some_and(|p| crate::output::write_atomic(&p, &encode(&levels)).is_ok());
    remember(*key, levels);
    on_disk
}

fn remember(key: Key, levels: Arc<Vec<Level>>) {
    let Ok(mut m) = memory().lock() else { return };
    if m.entries.insert(key, levels).is_none() {
        m.order.push(key);
    }
    while m.order.len() > MEMORY_ENTRIES {
        let oldest = m.order.remove(0);
        m.entries.remove(&oldest);
    }
}

/// Forget what this process holds in memory (tests of the disk cache).
pub fn clear_memory() {
    if let Ok(mut m) = memory().lock() {
        m.entries.clear();
        m.order.clear();
    }
}

/// Magic, version, level count, then per level its width, height and
/// RGBA f32 texels, little-endian.
fn encode(levels: &[Level]) -> Vec<u8> {
    let mut out = Vec::new();
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    out.extend_from_slice(&(levels.len() as u32).to_le_bytes());
    for l in levels {
        out.extend_from_slice(&l.width.to_le_bytes());
        out.extend_from_slice(&l.height.to_le_bytes());
        for p in &l.pixels {
            for c in p {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
    }
    out
}

fn decode(bytes: &[u8]) -> Option<Vec<Level>> {
    let mut at = 0usize;
    let mut take = |n: usize| -> Option<&[u8]> {
        let s = bytes.get(at..at.checked_add(n)?)?;
        at += n;
        Some(s)
    };
    if take(8)? != MAGIC {
        return None;
    }
    let u32_at = |s: &[u8]| u32::from_le_bytes([s[0], s[1], s[2], s[3]]);
    if u32_at(take(4)?) != FORMAT_VERSION {
        return None;
    }
    let count = u32_at(take(4)?);
    if count == 0 || count > npr_abi::ArtmapSpec::MAX_LEVELS {
        // A rip-map is one atlas level; a mip chain at most MAX_LEVELS.
        return None;
    }
    let mut levels = Vec::new();
    for _ in 0..count {
        let width = u32_at(take(4)?);
        let height = u32_at(take(4)?);
        let texels = (width as usize).checked_mul(height as usize)?;
        if width == 0
            || height == 0
            || width > npr_diag::limits::MAX_TEXTURE_SIZE
            || height > npr_diag::limits::MAX_TEXTURE_SIZE
        {
            return None;
        }
        let raw = take(texels.checked_mul(16)?)?;
        let pixels = raw
            .chunks_exact(16)
            .map(|t| std::array::from_fn(|c| f32::from_le_bytes([t[4 * c], t[4 * c + 1], t[4 * c + 2], t[4 * c + 3]])))
            .collect();
        levels.push(Level { width, height, pixels });
    }
    (at == bytes.len()).then_some(levels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_survive_the_file_format_and_damage_is_refused() {
        let levels = vec![
            Level {
                width: 2,
                height: 1,
                pixels: vec![[0.25, 0.5, 1.0, 1.0], [0.0, -1.5, 3.0e-8, 0.5]],
            },
            Level {
                width: 1,
                height: 1,
                pixels: vec![[0.125, 0.25, 0.5, 1.0]],
            },
        ];
        let bytes = encode(&levels);
        assert_eq!(decode(&bytes), Some(levels));
        assert_eq!(decode(&bytes[..bytes.len() - 1]), None, "a truncated file");
        let mut longer = bytes.clone();
        longer.push(0);
        assert_eq!(decode(&longer), None, "trailing bytes");
        let mut wrong = bytes.clone();
        wrong[0] ^= 1;
        assert_eq!(decode(&wrong), None, "bad magic");
    }

    #[test]
    fn the_key_changes_with_every_input() {
        let base = key(b"png", true, b"{filter}", 9, false);
        assert_ne!(base, key(b"pnG", true, b"{filter}", 9, false));
        assert_ne!(base, key(b"png", false, b"{filter}", 9, false));
        assert_ne!(base, key(b"png", true, b"{filteR}", 9, false));
        assert_ne!(base, key(b"png", true, b"{filter}", 8, false));
        assert_ne!(base, key(b"png", true, b"{filter}", 9, true));
        assert_eq!(base, key(b"png", true, b"{filter}", 9, false));
    }
}
