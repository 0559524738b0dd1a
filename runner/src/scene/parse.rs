//! Reading a whole scene file: TOML syntax, then `background`, `[camera]`,
//! `[light]` and every `[[object]]`, collecting all diagnostics.

use super::light::Light;

/// The optional extra lights, in `Scene::more_lights` order.
const MORE_LIGHTS: [(&str, &str); 3] = [("light2", "[light2]"), ("light3", "[light3]"), ("light4", "[light4]")];
use super::parse_camera::{parse_camera, parse_light};
use super::parse_object::{parse_object, MeshCache, ObjectDecl};
use super::toml_fields::{Fields, Report};
use super::Scene;
use npr_diag::{codes, Diagnostic, FileId, Span};
use std::collections::HashMap;
use std::path::Path;
use toml::de::DeTable;

const DEFAULT_BACKGROUND: [f32; 4] = [0.0, 0.0, 0.0, 1.0];

/// See [`super::parse_scene`].
pub fn parse_scene(
    text: &str,
    file: FileId,
    base_dir: &Path,
    paths: Option<&npr_diag::paths::PathPolicy>,
) -> Result<Scene, Vec<Diagnostic>> {
    let document = DeTable::parse(text).map_err(|err| vec![syntax_error(&err, file, text)])?;
    let mut report = Report::for_scene(file, paths.cloned());
    let mut root = Fields::new(document.get_ref(), Span::new(file, 0, 0), "the scene file");

    let background = root
        .color("background", &mut report)
        .map_or(DEFAULT_BACKGROUND, |c| c.value);
    let camera_present = root.span_of("camera", &report).is_some();
    let camera = root
        .table("camera", "[camera]", &mut report)
        .and_then(|fields| parse_camera(fields, &mut report));
    if !camera_present {
        report.bad_scene(
            Span::new(file, 0, 0),
            "the scene file has no [camera]",
            "a [camera] table is required",
            "add a [camera] table with `position` and `target`",
        );
    }
    let light = root
        .table("light", "[light]", &mut report)
        .map_or_else(Light::default, |fields| parse_light(fields, &mut report));
    let more_lights = MORE_LIGHTS.map(|(key, context)| {
        root.table(key, context, &mut report)
            .map(|fields| parse_light(fields, &mut report))
    });

    let mut cache = MeshCache::default();
    let object_tables = root.tables("object", |index| format!("object #{}", index + 1), &mut report);
    let declarations: Vec<ObjectDecl> = object_tables
        .into_iter()
        .filter_map(|fields| parse_object(fields, base_dir, &mut cache, &mut report))
        .collect();
    root.finish(&mut report);
    let objects = super::parse_patches::expand(unique_names(declarations, &mut report), &mut report);
    if !report.has_errors() {
        // (Duplicate explicit names are reported by `unique_names`.)
        patch_names_are_unique(&objects, &mut report);
    }

    if report.has_errors() {
        let mut diagnostics = report.diagnostics;
        // Report in file order, as a reader would fix them.
        diagnostics.sort_by_key(|d| d.primary_span().map_or(0, |span| span.start));
        return Err(diagnostics);
    }
    match camera {
        Some(camera) => Ok(Scene {
            objects,
            camera,
            light,
            more_lights,
            background,
        }),
        // Unreachable: a missing camera is always reported above.
        None => Err(report.diagnostics),
    }
}

fn syntax_error(err: &toml::de::Error, file: FileId, text: &str) -> Diagnostic {
    let range = err.span().unwrap_or(0..0);
    let span = Span::new(file, range.start.min(text.len()), range.end.min(text.len()));
    Diagnostic::error(
        codes::BAD_SCENE,
        format!("malformed scene file: {}", err.message().trim()),
    )
    .with_primary(span, "TOML syntax error")
    .with_help("a scene file is TOML (https://toml.io); see the scene format in the runner docs")
}

/// Explicit names must be unique (styles and renders refer to objects by
/// name); derived names are made unique with a `-2`, `-3`, ... suffix.
/// A patch's name (`cow.2`) must not be another object's.
fn patch_names_are_unique(objects: &[super::Object], report: &mut Report) {
    let mut seen: HashMap<&str, Span> = HashMap::new();
    for o in objects {
        if let Some(first) = seen.insert(&o.name, o.mesh_span) {
            report.push(
                Diagnostic::error(codes::BAD_SCENE, format!("two objects are named `{}`", o.name))
                    .with_primary(o.mesh_span, "a patch of this object has that name")
                    .with_secondary(first, "so does this object")
                    .with_help("rename the object whose name ends in `.<number>`"),
            );
        }
    }
}

#[allow(clippy::type_complexity)]
fn unique_names(
    declarations: Vec<ObjectDecl>,
    report: &mut Report,
) -> Vec<(super::Object, Option<super::parse_patches::PatchRequest>)> {
    let mut explicit: HashMap<String, Span> = HashMap::new();
    for declaration in &declarations {
        let Some(span) = declaration.name_span else {
            continue;
        };
        match explicit.get(&declaration.object.name) {
            Some(first) => report.push(
                Diagnostic::error(
                    codes::BAD_SCENE,
                    format!("two objects are named `{}`", declaration.object.name),
                )
                .with_primary(span, "second object with this name")
                .with_secondary(*first, "first object with this name")
                .with_help("give each object its own `name`"),
            ),
            None => {
                explicit.insert(declaration.object.name.clone(), span);
            }
        }
    }
    let mut taken: Vec<String> = explicit.into_keys().collect();
    declarations
        .into_iter()
        .map(|mut declaration| {
            if declaration.name_span.is_none() {
                let base = declaration.object.name.clone();
                let mut candidate = base.clone();
                let mut suffix = 2;
                while taken.contains(&candidate) {
                    candidate = format!("{base}-{suffix}");
                    suffix += 1;
                }
                taken.push(candidate.clone());
                declaration.object.name = candidate;
            }
            (declaration.object, declaration.patches)
        })
        .collect()
}
