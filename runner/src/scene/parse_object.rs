//! `[[object]]` in a scene: the mesh or primitive, the transform, tags,
//! shadows and per-object parameter bindings.

use super::gltf_material::MeshMaterial;
use super::mesh::Mesh;
use super::mesh_file::{load_mesh_file_parts, MeshLoadError};
use super::parse_patches::PatchRequest;
use super::parse_primitive::parse_primitive;
use super::primitives::Primitive;
use super::rig::Rig;
use super::toml_fields::{describe, expect_numbers, parse_hex_color, At, Fields, Report};
use super::{Object, ObjectAnimation, TextureBinding};
use glam::{Mat4, Quat, Vec3};
use npr_diag::{Diagnostic, Span};
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use toml::de::DeValue;

/// Meshes already loaded while reading one scene: objects naming the same
/// file or the same primitive share one [`Mesh`].
#[derive(Default)]
pub struct MeshCache {
    files: HashMap<PathBuf, Result<LoadedFile, MeshLoadError>>,
    primitives: HashMap<String, Arc<Mesh>>,
}

/// A mesh file's rest mesh and, for a glTF file that has them, its skins,
/// morph targets and clips, and its material.
type LoadedFile = (Arc<Mesh>, Option<Arc<Rig>>, Option<Arc<MeshMaterial>>);

/// What [`read_mesh`] found: the mesh, where it was declared, a name for
/// an object without one, the primitive when its geometry depends on
/// time, a glTF file's rig and material.
type ReadMesh = (
    Arc<Mesh>,
    Span,
    String,
    Option<Primitive>,
    Option<Arc<Rig>>,
    Option<Arc<MeshMaterial>>,
);

/// An object as read, with what duplicate-name checking needs.
pub struct ObjectDecl {
    pub object: Object,
    /// `patches = ...` and `blend_rings`: expanded into one object per
    /// patch after naming.
    pub patches: Option<PatchRequest>,
    /// Where the name was written; `None` when it was derived.
    pub name_span: Option<Span>,
}

/// Reads one `[[object]]`. `None` after reporting what is wrong; every field
/// is still checked, so one object can yield several diagnostics.
pub fn parse_object(
    mut fields: Fields,
    base_dir: &Path,
    cache: &mut MeshCache,
    report: &mut Report,
) -> Option<ObjectDecl> {
    let errors_before = report.diagnostics.len();
    let explicit_name = fields.string("name", report);
    if let Some(name) = &explicit_name {
        if name.value.trim().is_empty() {
            report.bad_scene(
                name.span,
                "an object name cannot be empty",
                "empty name",
                "write e.g. `name = \"spot\"`, or leave `name` out to use the mesh's name",
            );
        }
        fields.set_context(format!("object `{}`", name.value));
    }
    let mesh = read_mesh(&mut fields, base_dir, cache, report);
    let crease = read_crease_angle(&mut fields, report);
    let model = read_transform(&mut fields, report);
    let tags = read_tags(&mut fields, report);
    let casts_shadows = fields.boolean("casts_shadows", report).is_none_or(|flag| flag.value);
    let spin = fields.vec3("spin", report).map_or(Vec3::ZERO, |s| s.value);
    let (params, param_spans, textures) = read_params(&mut fields, base_dir, report);
    let patches = super::parse_patches::read_request(&mut fields, report);
    let playing = read_animation(&mut fields, report);
    fields.finish(report);
    if report.diagnostics.len() > errors_before {
        return None;
    }
    let (mut mesh, mesh_span, derived_name, time_varying, rig, material) = mesh?;
    let animation = match playing {
        Some(playing) => Some(playing.bind(rig.as_ref(), mesh_span, report)?),
        None => None,
    };
    if let Some(deg) = crease {
        if time_varying.is_some() || animation.is_some() {
            report.bad_scene(
                mesh_span,
                "`crease_angle` cannot be used with an animated primitive or a clip",
                "rebuilt every frame",
                "remove `crease_angle` from this object",
            );
            return None;
        }
        mesh = Arc::new(mesh.with_crease_normals(deg));
    }
    let name_span = explicit_name.as_ref().map(|name| name.span);
    Some(ObjectDecl {
        object: Object {
            name: explicit_name.map_or(derived_name, |name| name.value),
            mesh,
            model: model?,
            tags,
            params,
            param_spans,
            textures,
            mesh_span,
            casts_shadows,
            time_varying,
            spin,
            blend: None,
            patch: None,
            animation,
            pose: None,
            material,
        },
        name_span,
        patches,
    })
}

/// The object's mesh (from `mesh` or `primitive`), where it was declared,
/// a name for objects without one (the file stem or primitive kind), the
/// primitive again when its geometry depends on time, and a glTF file's
/// rig and material.
fn read_mesh(fields: &mut Fields, base_dir: &Path, cache: &mut MeshCache, report: &mut Report) -> Option<ReadMesh> {
    let file = fields.string("mesh", report);
    let primitive_span = fields.span_of("primitive", report);
    let primitive = fields.table("primitive", "the primitive", report);
    match (file, primitive_span) {
        (Some(file), Some(primitive_span)) => {
            report.push(
                Diagnostic::error(
                    npr_diag::codes::BAD_SCENE,
                    format!("{} has both `mesh` and `primitive`", fields.context()),
                )
                .with_primary(primitive_span, "second shape")
                .with_secondary(file.span, "first shape")
                .with_help("an object has one shape: remove `mesh` or `primitive`"),
            );
            None
        }
        (Some(file), None) => {
            let path = base_dir.join(&file.value);
            if !report.path_allowed(file.span, &file.value, &path) {
                return None;
            }
            let loaded = cache.files.entry(path.clone()).or_insert_with(|| {
                load_mesh_file_parts(&path).map(|l| (Arc::new(l.mesh), l.rig.map(Arc::new), l.material.map(Arc::new)))
            });
            match loaded {
                Ok((mesh, rig, material)) => {
                    let stem = Path::new(&file.value)
                        .file_stem()
                        .map_or("mesh".into(), |s| s.to_string_lossy().into_owned());
                    Some((Arc::clone(mesh), file.span, stem, None, rig.clone(), material.clone()))
                }
                Err(err) => {
                    report.push(
                        Diagnostic::error(err.code, err.message.clone())
                            .with_primary(file.span, "this mesh")
                            .with_help(err.help.clone()),
                    );
                    None
                }
            }
        }
        (None, Some(span)) => {
            let primitive = parse_primitive(primitive?, report)?;
            let description = primitive.description();
            let kind = description.split('(').next().unwrap_or("primitive").to_string();
            let mesh = cache
                .primitives
                .entry(description)
                .or_insert_with(|| Arc::new(primitive.build()));
            let time_varying = primitive.is_time_varying().then_some(primitive);
            Some((Arc::clone(mesh), span, kind, time_varying, None, None))
        }
        (None, None) => {
            // A `mesh` of the wrong type was already reported.
            if fields.span_of("mesh", report).is_none() {
                report.bad_scene(
                    fields.header(),
                    format!("{} has neither `mesh` nor `primitive`", fields.context()),
                    "no shape",
                    "add `mesh = \"model.obj\"` or `primitive = { kind = \"sphere\" }`",
                );
            }
            None
        }
    }
}

/// `animation = { clip = "walk", speed = 1.0, loop = true, offset = 0.0 }`
/// as written, before the clip is looked up in the mesh's file.
struct Playing {
    clip: super::toml_fields::At<String>,
    speed: f64,
    looping: bool,
    offset: f64,
    span: Span,
}

fn read_animation(fields: &mut Fields, report: &mut Report) -> Option<Playing> {
    let span = fields.span_of("animation", report)?;
    let mut table = fields.table("animation", "`animation`", report)?;
    let clip = table.string("clip", report);
    let speed = table.number("speed", report).map_or(1.0, |s| s.value);
    let looping = table.boolean("loop", report).is_none_or(|l| l.value);
    let offset = table.number("offset", report).map_or(0.0, |o| o.value);
    table.finish(report);
    let Some(clip) = clip else {
        report.bad_scene(
            span,
            "`animation` has no `clip`",
            "which clip?",
            "write `animation = { clip = \"walk\" }` with the name of one of the file's animations",
        );
        return None;
    };
    Some(Playing {
        clip,
        speed,
        looping,
        offset,
        span,
    })
}

impl Playing {
    /// The clip looked up in the object's file (E0405 at the clip's name
    /// when there is no such clip, or no file with clips).
    fn bind(self, rig: Option<&Arc<Rig>>, mesh_span: Span, report: &mut Report) -> Option<ObjectAnimation> {
        let Some(rig) = rig.filter(|r| !r.clips.is_empty()) else {
            report.push(
                Diagnostic::error(
                    npr_diag::codes::BAD_SCENE,
                    format!("`animation` plays clip `{}`, but the object's mesh has no animations", self.clip.value),
                )
                .with_primary(self.span, "no clip to play")
                .with_secondary(mesh_span, "this mesh has none")
                .with_help("clips come from a glTF file's `animations`; remove `animation`, or export the mesh with its actions"),
            );
            return None;
        };
        let Some(clip) = rig.clip_index(&self.clip.value) else {
            let names: Vec<&str> = rig.clips.iter().map(|c| c.name.as_str()).collect();
            report.push(
                Diagnostic::error(
                    npr_diag::codes::BAD_SCENE,
                    format!("the mesh has no clip `{}`", self.clip.value),
                )
                .with_primary(self.clip.span, "no such clip")
                .with_secondary(mesh_span, "in this file")
                .with_help(format!("the file's clips are {}", super::toml_fields::list(&names))),
            );
            return None;
        };
        if !(self.speed.is_finite() && self.offset.is_finite()) {
            report.bad_scene(
                self.span,
                "`speed` and `offset` must be finite",
                "not finite",
                "write e.g. `speed = 1.0, offset = 0.0`",
            );
            return None;
        }
        Some(ObjectAnimation {
            rig: rig.clone(),
            clip,
            speed: self.speed,
            looping: self.looping,
            offset: self.offset,
        })
    }
}

/// `crease_angle`: degrees in (0, 180]; `None` when absent or invalid
/// (the latter reported).
fn read_crease_angle(fields: &mut Fields, report: &mut Report) -> Option<f32> {
    let angle = fields.number("crease_angle", report)?;
    if !(angle.value > 0.0 && angle.value <= 180.0) {
        report.bad_scene(
            angle.span,
            "`crease_angle` must be in (0, 180] degrees",
            "out of range",
            "write e.g. `crease_angle = 30.0`: faces meeting at a sharper angle get separate normals",
        );
        return None;
    }
    Some(angle.value as f32)
}

/// `translate`, `rotate` (degrees; Y, then X, then Z) and `scale`, composed
/// as translate · rotate · scale.
fn read_transform(fields: &mut Fields, report: &mut Report) -> Option<Mat4> {
    let translate = fields.vec3("translate", report).map_or(Vec3::ZERO, |t| t.value);
    let rotate = fields.vec3("rotate", report).map_or(Vec3::ZERO, |r| r.value);
    let scale = match fields.number_or_vec3("scale", report) {
        Some(scale) if scale.value.cmple(Vec3::ZERO).any() => {
            report.bad_scene(
                scale.span,
                "`scale` must be positive",
                "must be > 0",
                "write e.g. `scale = 1.0` or `scale = [1.0, 2.0, 1.0]`; mirror a mesh in a modelling tool instead",
            );
            return None;
        }
        Some(scale) => scale.value,
        None => Vec3::ONE,
    };
    let rotate = rotate * (std::f32::consts::PI / 180.0);
    // Quaternion products apply right to left: Y first, then X, then Z.
    let rotation = Quat::from_rotation_z(rotate.z) * Quat::from_rotation_x(rotate.x) * Quat::from_rotation_y(rotate.y);
    Some(Mat4::from_scale_rotation_translation(scale, rotation, translate))
}

fn read_tags(fields: &mut Fields, report: &mut Report) -> Vec<String> {
    let tags = fields.strings("tags", report).unwrap_or_default();
    let mut unique: Vec<String> = Vec::new();
    for tag in tags {
        if tag.value.trim().is_empty() {
            report.bad_scene(
                tag.span,
                "a tag cannot be empty",
                "empty tag",
                "write e.g. `tags = [\"caster\"]`",
            );
        } else if !unique.contains(&tag.value) {
            unique.push(tag.value);
        }
    }
    unique
}

/// The `params` table: each binding is a number, a boolean (1 or 0), an
/// array of 1 to 4 numbers, a colour string `"#rrggbb"` (4 components), or
/// an image for an `object param t: texture`: a path string (in the colour
/// space the style declares for the param's default) or a table
/// `{ image = "path.png", srgb = false }` that says which. Paths are relative to the
/// scene file; whether the name is a texture param is checked against the
/// style when the renderer is built (`textures::load_object_textures`).
#[allow(clippy::type_complexity)]
fn read_params(
    fields: &mut Fields,
    base_dir: &Path,
    report: &mut Report,
) -> (
    BTreeMap<String, Vec<f64>>,
    BTreeMap<String, Span>,
    BTreeMap<String, TextureBinding>,
) {
    let mut params = BTreeMap::new();
    let mut spans = BTreeMap::new();
    let mut textures = BTreeMap::new();
    let Some(mut table) = fields.table("params", "`params`", report) else {
        return (params, spans, textures);
    };
    for (name, value) in table.entries(report) {
        if !is_identifier(&name.value) {
            report.bad_scene(
                name.span,
                format!("`{}` is not a parameter name", name.value),
                "not an identifier",
                "parameter names are letters, digits and `_`, not starting with a digit, as in the style",
            );
            continue;
        }
        if let Some(binding) = texture_value(&name, value, base_dir, report) {
            if let Some(binding) = binding {
                spans.insert(name.value.clone(), binding.span);
                textures.insert(name.value, binding);
            }
            continue;
        }
        if let Some(components) = param_value(&name, value, report) {
            spans.insert(name.value.clone(), components.span);
            params.insert(name.value, components.value);
        }
    }
    table.finish(report);
    (params, spans, textures)
}

/// An image binding, if `value` is one: a string naming a file with an
/// extension (not `#...`), or a table. `Some(None)` when it is one but is malformed (reported).
fn texture_value(
    name: &At<String>,
    value: &toml::Spanned<DeValue>,
    base_dir: &Path,
    report: &mut Report,
) -> Option<Option<TextureBinding>> {
    let span = report.span(value.span());
    let (path, srgb) = match value.get_ref() {
        // A file name has an extension; `"red"` stays a (bad) colour.
        DeValue::String(text) if !text.starts_with('#') && Path::new(&**text).extension().is_some() => {
            (text.to_string(), None)
        }
        DeValue::Table(table) => {
            let mut fields = Fields::new(table, span, format!("texture binding `{}`", name.value));
            let image = fields.string("image", report);
            let srgb = fields.boolean("srgb", report).map(|flag| flag.value);
            fields.finish(report);
            let Some(image) = image else {
                if table.get("image").is_some() {
                    // Present but not a string: already reported.
                    return Some(None);
                }
                report.bad_scene(
                    span,
                    format!("texture binding `{}` has no `image`", name.value),
                    "expected `{ image = \"file.png\" }`",
                    "write `{ image = \"textures/lit.png\", srgb = true }`, or just the path as a string",
                );
                return Some(None);
            };
            (image.value, srgb)
        }
        _ => return None,
    };
    let resolved = base_dir.join(&path);
    if !report.path_allowed(span, &path, &resolved) {
        return Some(None);
    }
    if !resolved.is_file() {
        report.diagnostics.push(
            Diagnostic::error(
                npr_diag::codes::MISSING_TEXTURE,
                format!("texture file `{path}` for `{}` not found", name.value),
            )
            .with_primary(span, format!("looked for {}", resolved.display()))
            .with_help("image paths in a scene are relative to the scene file; a colour is written `\"#rrggbb\"`"),
        );
        return Some(None);
    }
    Some(Some(TextureBinding {
        path,
        resolved,
        srgb,
        span,
    }))
}

fn param_value(name: &At<String>, value: &toml::Spanned<DeValue>, report: &mut Report) -> Option<At<Vec<f64>>> {
    let span = report.span(value.span());
    let help = "a parameter binding is a number, a boolean, `[x, y]` to `[x, y, z, w]`, a colour `\"#rrggbb\"`, or an image file `\"file.png\"` for a texture param";
    let components = match value.get_ref() {
        DeValue::Integer(_) | DeValue::Float(_) => {
            super::toml_fields::expect_number(value, &name.value, report).map(|n| vec![n.value])?
        }
        DeValue::Boolean(flag) => vec![if *flag { 1.0 } else { 0.0 }],
        DeValue::String(text) => match parse_hex_color(text) {
            Some(color) => color,
            None => {
                report.bad_scene(
                    span,
                    format!("`{}` is not a colour", name.value),
                    "expected `#rrggbb` or `#rrggbbaa`",
                    help,
                );
                return None;
            }
        },
        DeValue::Array(_) => {
            let numbers = expect_numbers(value, &name.value, report)?;
            if !(1..=4).contains(&numbers.value.len()) {
                report.bad_scene(
                    span,
                    format!("`{}` has {} components", name.value, numbers.value.len()),
                    "expected 1 to 4 numbers",
                    help,
                );
                return None;
            }
            numbers.value
        }
        other => {
            report.bad_scene(
                span,
                format!("`{}` cannot be {}", name.value, describe(other)),
                "not a parameter value",
                help,
            );
            return None;
        }
    };
    Some(At {
        value: components,
        span,
    })
}

fn is_identifier(name: &str) -> bool {
    let mut chars = name.chars();
    chars
        .next()
        .is_some_and(|first| first.is_ascii_alphabetic() || first == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}
