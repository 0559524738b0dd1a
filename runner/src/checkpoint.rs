//! Checkpoint files: a renderer's state between two frames of a sequence
//! ([`crate::exec::RendererState`]), with what it was made for, so a chunk
//! of a path-dependent style's sequence can start at its first frame
//! instead of replaying every frame before it.
//!
//! Layout: the magic `NPRCKPT\0`, the format version (u32 LE), the header's
//! length (u64 LE), the header (JSON: [`Identity`], the frame, the state's
//! scalars and the list of blocks), the blocks' bytes one after the other,
//! and the BLAKE3 hash of everything before it (32 bytes). A file whose
//! hash does not match (truncated, corrupted) is E0513; one made for
//! another style, scene, size, frame rate or npr version is E0512, naming
//! what differs. Written atomically (`output::write_atomic`): a chunk that
//! fails leaves no partial checkpoint.

use crate::exec::{RendererState, StateBlock, StateKind};
use crate::scene::Scene;
use npr_diag::{codes, Diagnostic};
use serde::{Deserialize, Serialize};
use std::path::Path;

const MAGIC: &[u8; 8] = b"NPRCKPT\0";
/// Changes with the layout of the file or of [`RendererState`].
pub const FORMAT_VERSION: u32 = 1;

/// What a checkpoint was made for: a render may start from it only when
/// all of these are its own.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Identity {
    /// The version of the program that wrote it (`npr --version`).
    pub npr_version: String,
    /// [`style_hash`] of the compiled style (its `--set` values included).
    pub style: String,
    /// [`scene_hash`] of the scene.
    pub scene: String,
    pub width: u32,
    pub height: u32,
    pub fps: f64,
}

/// A checkpoint: the renderer's state after frames `0..frame`, ready to
/// render `frame`.
#[derive(Debug, Clone, PartialEq)]
pub struct Checkpoint {
    pub identity: Identity,
    pub frame: u32,
    pub state: RendererState,
}

#[derive(Serialize, Deserialize)]
struct BlockHeader {
    texture: bool,
    owner: u32,
    index: u32,
    copy: u32,
    len: u64,
}

#[derive(Serialize, Deserialize)]
struct Header {
    identity: Identity,
    frame: u32,
    frames_begun: u64,
    motion: [Option<crate::exec::FrameTransforms>; 2],
    blocks: Vec<BlockHeader>,
}

/// The hash of a compiled style: its manifest and every shader.
pub fn style_hash(program: &crate::StyleProgram) -> String {
    let mut h = blake3::Hasher::new();
    h.update(&serde_json::to_vec(&program.manifest).unwrap_or_default());
    for (name, wgsl) in &program.shaders {
        h.update(name.as_bytes());
        h.update(&[0]);
        h.update(wgsl.as_bytes());
        h.update(&[0]);
    }
    h.finalize().to_hex().to_string()
}

/// The hash of what a scene renders with: objects (meshes, transforms,
/// tags, params, image bindings as written), camera, lights, background.
/// Where things were written (spans) and absolute paths are left out, so
/// the same scene checked out elsewhere, or loaded after other files, has
/// the same hash.
pub fn scene_hash(scene: &Scene) -> String {
    let mut s = scene.clone();
    for o in &mut s.objects {
        o.param_spans.clear();
        o.mesh_span = npr_diag::Span::default();
        for t in o.textures.values_mut() {
            t.span = npr_diag::Span::default();
            t.resolved = std::path::PathBuf::new();
        }
    }
    blake3::hash(format!("{s:?}").as_bytes()).to_hex().to_string()
}

/// The bytes of a checkpoint file.
pub fn encode(c: &Checkpoint) -> Vec<u8> {
    let header = Header {
        identity: c.identity.clone(),
        frame: c.frame,
        frames_begun: c.state.frames_begun,
        motion: c.state.motion.clone(),
        blocks: c
            .state
            .blocks
            .iter()
            .map(|b| BlockHeader {
                texture: b.kind == StateKind::Texture,
                owner: b.owner,
                index: b.index,
                copy: b.copy,
                len: b.bytes.len() as u64,
            })
            .collect(),
    };
    // Serializing plain data cannot fail.
    let header = serde_json::to_vec(&header).unwrap_or_default();
    let mut out = Vec::new();
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    out.extend_from_slice(&(header.len() as u64).to_le_bytes());
    out.extend_from_slice(&header);
    for b in &c.state.blocks {
        out.extend_from_slice(&b.bytes);
    }
    let hash = blake3::hash(&out);
    out.extend_from_slice(hash.as_bytes());
    out
}

/// Write `c` to `path` atomically.
pub fn write(path: &Path, c: &Checkpoint) -> std::io::Result<()> {
    crate::output::write_atomic(path, &encode(c))
}

fn corrupt(path: &Path, why: impl std::fmt::Display) -> Diagnostic {
    Diagnostic::error(
        codes::BAD_CHECKPOINT,
        format!("checkpoint {} is unusable: {why}", path.display()),
    )
    .with_help("delete it and render the chunk before it again (with --checkpoints) to write a new one")
}

/// Parse a checkpoint file's bytes (E0513 when they are not one, whole).
pub fn decode(bytes: &[u8], path: &Path) -> Result<Checkpoint, Diagnostic> {
    let fixed = MAGIC.len() + 4 + 8;
    if bytes.len() < fixed + 32 || &bytes[..MAGIC.len()] != MAGIC {
        return Err(corrupt(path, "it is not an npr checkpoint, or is truncated"));
    }
    let (body, hash) = bytes.split_at(bytes.len() - 32);
    if blake3::hash(body).as_bytes() != hash {
        return Err(corrupt(path, "its checksum does not match (truncated or corrupted)"));
    }
    let version = u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]);
    if version != FORMAT_VERSION {
        return Err(corrupt(
            path,
            format!("it is in checkpoint format {version}; this npr reads format {FORMAT_VERSION}"),
        ));
    }
    let mut len = [0u8; 8];
    len.copy_from_slice(&bytes[12..20]);
    let header_len = usize::try_from(u64::from_le_bytes(len)).unwrap_or(usize::MAX);
    let header_bytes = body
        .get(fixed..fixed.saturating_add(header_len))
        .ok_or_else(|| corrupt(path, "its header is cut short"))?;
    let header: Header =
        serde_json::from_slice(header_bytes).map_err(|e| corrupt(path, format!("its header does not parse: {e}")))?;
    let mut at = fixed + header_len;
    let mut blocks = Vec::with_capacity(header.blocks.len());
    for b in &header.blocks {
        let end = usize::try_from(b.len).ok().and_then(|n| at.checked_add(n));
        let data = end
            .and_then(|end| body.get(at..end))
            .ok_or_else(|| corrupt(path, "a state block is cut short"))?;
        at += data.len();
        blocks.push(StateBlock {
            kind: if b.texture {
                StateKind::Texture
            } else {
                StateKind::Buffer
            },
            owner: b.owner,
            index: b.index,
            copy: b.copy,
            bytes: data.to_vec(),
        });
    }
    if at != body.len() {
        return Err(corrupt(path, "it has bytes past its last block"));
    }
    Ok(Checkpoint {
        state: RendererState {
            width: header.identity.width,
            height: header.identity.height,
            frames_begun: header.frames_begun,
            motion: header.motion,
            blocks,
        },
        identity: header.identity,
        frame: header.frame,
    })
}

fn short(hash: &str) -> &str {
    hash.get(..12).unwrap_or(hash)
}

/// E0512 unless `found` is what `expected` needs, naming each difference.
pub fn check_identity(found: &Identity, expected: &Identity, path: &Path) -> Result<(), Diagnostic> {
    let mut differences = Vec::new();
    if found.style != expected.style {
        differences.push(format!(
            "the style: it was made for compiled style {}, this one is {} (another style, or other --set values)",
            short(&found.style),
            short(&expected.style)
        ));
    }
    if found.scene != expected.scene {
        differences.push(format!(
            "the scene: it was made for scene {}, this one is {}",
            short(&found.scene),
            short(&expected.scene)
        ));
    }
    if (found.width, found.height) != (expected.width, expected.height) {
        differences.push(format!(
            "the size: it was made at {}x{}, this render is {}x{}",
            found.width, found.height, expected.width, expected.height
        ));
    }
    if found.fps != expected.fps {
        differences.push(format!(
            "the frame rate: it was made at {} fps, this render is at {}",
            found.fps, expected.fps
        ));
    }
    if found.npr_version != expected.npr_version {
        differences.push(format!(
            "the version: it was written by npr {}, this is npr {}",
            found.npr_version, expected.npr_version
        ));
    }
    let Some(first) = differences.first() else {
        return Ok(());
    };
    let mut d = Diagnostic::error(
        codes::CHECKPOINT_MISMATCH,
        format!("checkpoint {} is for another render: {first}", path.display()),
    );
    for other in &differences[1..] {
        d = d.with_note(format!("also {other}"));
    }
    Err(d.with_help(
        "render with the style, scene, --size, --fps and npr that wrote it, or give --checkpoints a directory of this render's own",
    ))
}

/// Read and check the checkpoint at `path` for a render of `expected`.
pub fn read(path: &Path, expected: &Identity) -> Result<Checkpoint, Diagnostic> {
    let bytes = std::fs::read(path).map_err(|e| corrupt(path, format!("cannot read it: {e}")))?;
    let c = decode(&bytes, path)?;
    check_identity(&c.identity, expected, path)?;
    Ok(c)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Checkpoint {
        Checkpoint {
            identity: Identity {
                npr_version: "0.1.0".into(),
                style: "a".repeat(64),
                scene: "b".repeat(64),
                width: 4,
                height: 2,
                fps: 24.0,
            },
            frame: 7,
            state: RendererState {
                width: 4,
                height: 2,
                frames_begun: 7,
                motion: [Some((vec![[1.0; 16]], vec![[2.0; 16]])), None],
                blocks: vec![
                    StateBlock {
                        kind: StateKind::Texture,
                        owner: 0,
                        index: 3,
                        copy: 1,
                        bytes: (0..32).collect(),
                    },
                    StateBlock {
                        kind: StateKind::Buffer,
                        owner: 2,
                        index: 0,
                        copy: 0,
                        bytes: vec![9; 16],
                    },
                ],
            },
        }
    }

    #[test]
    fn a_checkpoint_reads_back_as_written() {
        let c = sample();
        assert_eq!(decode(&encode(&c), Path::new("c")), Ok(c));
    }

    #[test]
    fn every_truncation_and_every_flipped_byte_is_refused() {
        let bytes = encode(&sample());
        for n in 0..bytes.len() {
            let d = decode(&bytes[..n], Path::new("c")).expect_err("truncated");
            assert_eq!(d.code, codes::BAD_CHECKPOINT);
        }
        for i in 0..bytes.len() {
            let mut b = bytes.clone();
            b[i] ^= 0x10;
            let d = decode(&b, Path::new("c")).expect_err("corrupted");
            assert_eq!(d.code, codes::BAD_CHECKPOINT, "byte {i}");
        }
    }

    #[test]
    fn each_difference_of_identity_is_named() {
        let a = sample().identity;
        assert!(check_identity(&a, &a, Path::new("c")).is_ok());
        let mut b = a.clone();
        b.width = 8;
        b.fps = 30.0;
        let d = check_identity(&a, &b, Path::new("c")).expect_err("differs");
        assert_eq!(d.code, codes::CHECKPOINT_MISMATCH);
        assert!(
            d.message.contains("4x2") && d.notes.iter().any(|n| n.contains("30")),
            "{d:?}"
        );
    }
}
