//! A compiled style in one file (`.nprb`): the manifest, the WGSL of every
//! pass and the bytes of every image file the manifest names, so that a
//! shipped program (a game, a web page) carries a style without the
//! compiler and without the files it was compiled from.
//!
//! Layout (little-endian), versioned apart from the manifest so that the
//! container and its contents can change independently:
//!
//! ```text
//! magic        8 bytes   b"NPRBNDL\0"
//! version      u32       BUNDLE_VERSION
//! entries      u32       count, at most MAX_ENTRIES
//! per entry:   u32 name length, name (UTF-8), u64 data length, data
//! ```
//!
//! Entry names: `manifest.json`, then one `<shader file>` per shader (the
//! names the manifest's passes give), then `file:<resolved path>` per image
//! file, keyed by the `resolved` path the manifest holds (that is what the
//! runtime looks them up by). Reading checks every length against the
//! bytes left before allocating, refuses duplicate or unknown entries, and
//! validates the program as [`StyleProgram::load_dir`] does.

use crate::manifest::{Manifest, TextureSourceManifest};
use crate::program::{LoadError, StyleProgram};
use std::collections::BTreeMap;

/// The first bytes of every bundle.
pub const BUNDLE_MAGIC: &[u8; 8] = b"NPRBNDL\0";
/// The container's layout version; another is refused.
pub const BUNDLE_VERSION: u32 = 1;
/// The most entries a bundle may hold (a manifest, its shaders, its files).
pub const MAX_ENTRIES: u32 = 4096;
/// The longest entry name, in bytes.
pub const MAX_NAME_BYTES: u32 = 4096;

const MANIFEST_ENTRY: &str = "manifest.json";
const FILE_PREFIX: &str = "file:";

/// The image files `manifest` names (resolved paths, each once, in order).
pub fn image_files(manifest: &Manifest) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for t in &manifest.textures {
        let resolved = match &t.source {
            TextureSourceManifest::Image { resolved, .. } => resolved,
            TextureSourceManifest::Artmap(spec) => &spec.resolved,
            _ => continue,
        };
        if !out.contains(resolved) {
            out.push(resolved.clone());
        }
    }
    out
}

impl StyleProgram {
    /// This program as one bundle. Every image file the manifest names is
    /// embedded: from [`StyleProgram::files`] when the program holds it,
    /// else as `read` returns it (the compiler's output names files on disk).
    pub fn to_bundle(&self, read: impl Fn(&str) -> std::io::Result<Vec<u8>>) -> Result<Vec<u8>, LoadError> {
        self.validate()?;
        let manifest =
            serde_json::to_string_pretty(&self.manifest).map_err(|e| LoadError::Json { message: e.to_string() })?;
        let mut entries: Vec<(String, Vec<u8>)> = vec![(MANIFEST_ENTRY.to_string(), manifest.into_bytes())];
        for (name, wgsl) in &self.shaders {
            entries.push((name.clone(), wgsl.clone().into_bytes()));
        }
        for resolved in image_files(&self.manifest) {
            let bytes = match self.files.get(&resolved) {
                Some(b) => b.clone(),
                None => read(&resolved).map_err(|e| LoadError::Io {
                    path: resolved.clone().into(),
                    message: e.to_string(),
                })?,
            };
            entries.push((format!("{FILE_PREFIX}{resolved}"), bytes));
        }
        let mut out = Vec::new();
        out.extend_from_slice(BUNDLE_MAGIC);
        out.extend_from_slice(&BUNDLE_VERSION.to_le_bytes());
        out.extend_from_slice(&(entries.len() as u32).to_le_bytes());
        for (name, data) in entries {
            out.extend_from_slice(&(name.len() as u32).to_le_bytes());
            out.extend_from_slice(name.as_bytes());
            out.extend_from_slice(&(data.len() as u64).to_le_bytes());
            out.extend_from_slice(&data);
        }
        Ok(out)
    }

    /// The program a bundle holds, validated; its image files are in
    /// [`StyleProgram::files`], and only there: the runtime reads no disk
    /// for them.
    pub fn from_bundle(bytes: &[u8]) -> Result<StyleProgram, LoadError> {
        let mut r = Cursor { bytes, at: 0 };
        if r.take(8, "magic")? != BUNDLE_MAGIC {
            return Err(bad(
                "magic",
                "not an npr bundle (it does not start with NPRBNDL)".into(),
            ));
        }
        let version = r.u32("version")?;
        if version != BUNDLE_VERSION {
            return Err(bad(
                "version",
                format!(
                    "bundle version {version}; this runtime reads version {BUNDLE_VERSION}: compile the style again"
                ),
            ));
        }
        let count = r.u32("entries")?;
        if count > MAX_ENTRIES {
            return Err(bad(
                "entries",
                format!("{count} entries, more than the limit of {MAX_ENTRIES}"),
            ));
        }
        let mut manifest_text = None;
        let mut shaders = BTreeMap::new();
        let mut files = BTreeMap::new();
        for i in 0..count {
            let field = format!("entries[{i}]");
            let name_len = r.u32(&field)?;
            if name_len > MAX_NAME_BYTES {
                return Err(bad(
                    &field,
                    format!("a name of {name_len} bytes, more than {MAX_NAME_BYTES}"),
                ));
            }
            let name = std::str::from_utf8(r.take(name_len as u64, &field)?)
                .map_err(|_| bad(&field, "a name that is not UTF-8".into()))?
                .to_string();
            let data_len = r.u64(&field)?;
            let data = r.take(data_len, &field)?.to_vec();
            let text =
                |data: Vec<u8>| String::from_utf8(data).map_err(|_| bad(&field, format!("`{name}` is not UTF-8")));
            let fresh = if name == MANIFEST_ENTRY {
                manifest_text.replace(text(data)?).is_none()
            } else if let Some(path) = name.strip_prefix(FILE_PREFIX) {
                files.insert(path.to_string(), data).is_none()
            } else if name.ends_with(".wgsl") {
                shaders.insert(name.clone(), text(data)?).is_none()
            } else {
                return Err(bad(&field, format!("unknown entry `{name}`")));
            };
            if !fresh {
                return Err(bad(&field, format!("`{name}` twice")));
            }
        }
        if r.at != bytes.len() {
            return Err(bad(
                "entries",
                format!("{} bytes after the last entry", bytes.len() - r.at),
            ));
        }
        let text = manifest_text.ok_or_else(|| bad("entries", "no manifest.json".into()))?;
        let manifest = crate::program::parse_manifest(&text)?;
        manifest.validate()?;
        for resolved in image_files(&manifest) {
            if !files.contains_key(&resolved) {
                return Err(bad(
                    "entries",
                    format!("the image file `{resolved}` the manifest names is not in the bundle"),
                ));
            }
        }
        let program = StyleProgram {
            manifest,
            shaders,
            files,
        };
        program.validate()?;
        Ok(program)
    }
}

fn bad(field: &str, message: String) -> LoadError {
    LoadError::Bundle {
        field: format!("bundle.{field}"),
        message,
    }
}

/// Reads the container, every length checked against what is left.
struct Cursor<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Cursor<'a> {
    fn take(&mut self, n: u64, field: &str) -> Result<&'a [u8], LoadError> {
        let left = (self.bytes.len() - self.at) as u64;
        if n > left {
            return Err(bad(field, format!("truncated: {n} bytes wanted, {left} left")));
        }
        let out = &self.bytes[self.at..self.at + n as usize];
        self.at += n as usize;
        Ok(out)
    }

    fn u32(&mut self, field: &str) -> Result<u32, LoadError> {
        let b = self.take(4, field)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    fn u64(&mut self, field: &str) -> Result<u64, LoadError> {
        let b = self.take(8, field)?;
        Ok(u64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]))
    }
}
