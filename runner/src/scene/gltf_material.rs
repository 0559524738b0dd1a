//! A glTF file's material, as the per-object values and texture a style
//! reads under fixed names (issue 48, decision 0058).
//!
//! An object drawn from a glTF file gives each style that declares them:
//! `object param base_color: color` (the base colour factor, as stored:
//! linear), `metallic: float`, `roughness: float`, `emissive: color`
//! (the emissive factor, alpha 1), and `object param base_color_map:
//! texture`, the base colour texture's image. A value the scene binds
//! under the same name wins; a name the style does not declare is not
//! read. The material is the one of the file's first triangle primitive
//! that names one, in document order: npr draws one object with one set
//! of per-object values, and most characters have one material.
//!
//! Images are decoded when the file loads, so that a broken one is an
//! error at the scene's `mesh = "…"` (E0410, with the file and the glTF
//! path) rather than at the first style that reads it; an index out of
//! range in a material, texture or image is E0409 with its path.

use super::mesh_error::MeshLoadError;
use gltf::buffer::Data as BufferData;
use gltf::mesh::Mode;
use npr_diag::codes;
use std::path::{Component, Path};
use std::sync::Arc;

/// The names styles read a material under (docs: the scene reference).
pub const BASE_COLOR: &str = "base_color";
pub const METALLIC: &str = "metallic";
pub const ROUGHNESS: &str = "roughness";
pub const EMISSIVE: &str = "emissive";
pub const BASE_COLOR_MAP: &str = "base_color_map";

/// One glTF material's values for styles.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshMaterial {
    /// `/materials/N`, for messages.
    pub path: String,
    /// `pbrMetallicRoughness.baseColorFactor` (linear RGBA).
    pub base_color: [f32; 4],
    pub metallic: f32,
    pub roughness: f32,
    /// `emissiveFactor` (linear RGB).
    pub emissive: [f32; 3],
    /// The base colour texture's image, when the material has one.
    pub base_color_map: Option<MaterialImage>,
}

/// An image of a glTF file, kept encoded (the texture loader decodes it
/// as it decodes a scene's image files).
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialImage {
    /// `<file>#/images/N`: the image's name in messages and the key of
    /// its GPU texture (two objects of one file share it).
    pub key: String,
    /// A file name whose extension says the format (`image.png`).
    pub format_hint: &'static str,
    pub bytes: Arc<Vec<u8>>,
}

impl MeshMaterial {
    /// The value of per-object param `name`, if the material gives one:
    /// its components and how many there are (no allocation: it is read
    /// every frame).
    pub fn value(&self, name: &str) -> Option<([f64; 4], usize)> {
        let [r, g, b, a] = self.base_color.map(f64::from);
        let [er, eg, eb] = self.emissive.map(f64::from);
        match name {
            BASE_COLOR => Some(([r, g, b, a], 4)),
            METALLIC => Some(([f64::from(self.metallic), 0.0, 0.0, 0.0], 1)),
            ROUGHNESS => Some(([f64::from(self.roughness), 0.0, 0.0, 0.0], 1)),
            EMISSIVE => Some(([er, eg, eb, 1.0], 4)),
            _ => None,
        }
    }
}

fn material_error(code: &'static str, source: &str, path: &str, what: impl std::fmt::Display) -> MeshLoadError {
    let help = if code == codes::BAD_MATERIAL_REFERENCE {
        "re-export the file (Blender: File › Export › glTF 2.0), or fix the index; \
         the Khronos glTF validator lists every bad one"
    } else {
        "re-export the file with its textures as PNG (Blender: File › Export › glTF 2.0, Images: PNG), \
         or check it with the Khronos glTF validator"
    };
    MeshLoadError {
        code,
        message: format!("glTF file `{source}`, at `{path}`: {what}"),
        help: help.into(),
    }
}

/// E0409 for a glTF validation error in a material, texture, image or
/// sampler (an index out of range), with its path as a JSON pointer;
/// `None` for any other validation error (E0402 then, as before).
pub fn validation_error(error: &gltf::Error, source: &str) -> Option<MeshLoadError> {
    let gltf::Error::Validation(errors) = error else {
        return None;
    };
    let (path, what) = errors.iter().find(|(path, _)| {
        let p = path.to_string();
        ["materials", "textures", "images", "samplers"]
            .iter()
            .any(|root| p.starts_with(root))
    })?;
    Some(material_error(
        codes::BAD_MATERIAL_REFERENCE,
        source,
        &json_pointer(&path.to_string()),
        what,
    ))
}

/// `materials[0].pbrMetallicRoughness.baseColorTexture.index` as
/// `/materials/0/pbrMetallicRoughness/baseColorTexture/index`.
fn json_pointer(path: &str) -> String {
    let mut out = String::new();
    for piece in path.split('.') {
        for part in piece.split('[') {
            out.push('/');
            out.push_str(part.trim_end_matches(']'));
        }
    }
    out
}

/// The material of the file's first triangle primitive that names one.
pub fn read_material(
    document: &gltf::Document,
    buffers: &[BufferData],
    base_dir: &Path,
    source: &str,
) -> Result<Option<MeshMaterial>, MeshLoadError> {
    let Some(material) = document
        .meshes()
        .flat_map(|m| m.primitives().collect::<Vec<_>>())
        .filter(|p| p.mode() == Mode::Triangles)
        .find_map(|p| p.material().index().map(|_| p.material()))
    else {
        return Ok(None);
    };
    let index = material.index().unwrap_or(0);
    let pbr = material.pbr_metallic_roughness();
    let base_color_map = match pbr.base_color_texture() {
        None => None,
        Some(info) => {
            let image = info.texture().source();
            Some(read_image(&image, buffers, base_dir, source)?)
        }
    };
    let emissive = material.emissive_factor();
    Ok(Some(MeshMaterial {
        path: format!("/materials/{index}"),
        base_color: pbr.base_color_factor(),
        metallic: pbr.metallic_factor(),
        roughness: pbr.roughness_factor(),
        emissive,
        base_color_map,
    }))
}

/// The encoded bytes of `image` (a buffer view, a `data:` URI or a file
/// beside the glTF file), checked to decode.
fn read_image(
    image: &gltf::Image,
    buffers: &[BufferData],
    base_dir: &Path,
    source: &str,
) -> Result<MaterialImage, MeshLoadError> {
    let path = format!("/images/{}", image.index());
    let undecodable = |what: String| material_error(codes::BAD_MATERIAL_IMAGE, source, &path, what);
    let (bytes, mime): (Vec<u8>, Option<String>) = match image.source() {
        gltf::image::Source::View { view, mime_type } => {
            let buffer = buffers
                .get(view.buffer().index())
                .ok_or_else(|| undecodable("its buffer was not loaded".into()))?;
            let bytes = view
                .offset()
                .checked_add(view.length())
                .and_then(|end| buffer.0.get(view.offset()..end))
                .ok_or_else(|| {
                    undecodable(format!(
                        "buffer view {} lies outside its buffer of {} bytes",
                        view.index(),
                        buffer.0.len()
                    ))
                })?;
            (bytes.to_vec(), Some(mime_type.to_string()))
        }
        gltf::image::Source::Uri { uri, mime_type } => match uri.strip_prefix("data:") {
            Some(data) => {
                let (header, payload) = data
                    .split_once(',')
                    .ok_or_else(|| undecodable("a `data:` URI without a comma".into()))?;
                if !header.ends_with(";base64") {
                    return Err(undecodable("a `data:` URI that is not base64".into()));
                }
                let bytes = base64_decode(payload).ok_or_else(|| undecodable("its base64 does not decode".into()))?;
                let mime = header.trim_end_matches(";base64").to_string();
                (bytes, Some(mime_type.map_or(mime, str::to_string)))
            }
            None => {
                // A file beside the glTF file: never absolute, never above it.
                let relative = Path::new(uri);
                if !relative
                    .components()
                    .all(|c| matches!(c, Component::Normal(_) | Component::CurDir))
                {
                    return Err(undecodable(format!(
                        "image file `{uri}` is not inside the glTF file's folder"
                    )));
                }
                let bytes = std::fs::read(base_dir.join(relative))
                    .map_err(|e| undecodable(format!("cannot read image file `{uri}`: {e}")))?;
                (bytes, mime_type.map(str::to_string))
            }
        },
    };
    let format_hint = match mime.as_deref() {
        Some("image/png") | None => "image.png",
        Some(other) => {
            return Err(undecodable(format!(
                "the image is `{other}`; npr reads PNG material images"
            )))
        }
    };
    use crate::texture_file::TextureFileError;
    match crate::texture_file::read_bytes(&bytes, Path::new(format_hint)) {
        Ok(_) => {}
        Err(TextureFileError::TooLarge { width, height }) => {
            return Err(material_error(
                codes::LIMIT_EXCEEDED,
                source,
                &path,
                format!(
                    "the image is {width}x{height}, over the {}-texel limit",
                    npr_diag::limits::MAX_TEXTURE_SIZE
                ),
            ))
        }
        Err(TextureFileError::NotAnImage(e)) => return Err(undecodable(format!("the image does not decode: {e}"))),
        Err(TextureFileError::Unreadable(e)) => return Err(undecodable(format!("the image cannot be read: {e}"))),
    }
    Ok(MaterialImage {
        key: format!("{source}#{path}"),
        format_hint,
        bytes: Arc::new(bytes),
    })
}

/// Standard base64 (RFC 4648, with or without padding); `None` on any
/// other character.
fn base64_decode(text: &str) -> Option<Vec<u8>> {
    let value = |c: u8| -> Option<u32> {
        Some(match c {
            b'A'..=b'Z' => u32::from(c - b'A'),
            b'a'..=b'z' => u32::from(c - b'a') + 26,
            b'0'..=b'9' => u32::from(c - b'0') + 52,
            b'+' => 62,
            b'/' => 63,
            _ => return None,
        })
    };
    let digits = text.trim_end_matches('=').as_bytes();
    let mut out = Vec::with_capacity(digits.len() * 3 / 4);
    for chunk in digits.chunks(4) {
        let mut acc = 0u32;
        for (i, c) in chunk.iter().enumerate() {
            acc |= value(*c)? << (18 - 6 * i);
        }
        let bytes = acc.to_be_bytes();
        match chunk.len() {
            4 => out.extend_from_slice(&bytes[1..4]),
            3 => out.extend_from_slice(&bytes[1..3]),
            2 => out.push(bytes[1]),
            _ => return None,
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_decodes_every_padding() {
        assert_eq!(base64_decode("aGVsbG8=").as_deref(), Some(&b"hello"[..]));
        assert_eq!(base64_decode("aGVsbG8h").as_deref(), Some(&b"hello!"[..]));
        assert_eq!(base64_decode("aGk=").as_deref(), Some(&b"hi"[..]));
        assert_eq!(base64_decode("a"), None);
        assert_eq!(base64_decode("a*bc"), None);
    }

    #[test]
    fn validation_paths_become_json_pointers() {
        assert_eq!(
            json_pointer("materials[0].pbrMetallicRoughness.baseColorTexture.index"),
            "/materials/0/pbrMetallicRoughness/baseColorTexture/index"
        );
    }
}
