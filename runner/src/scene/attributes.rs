//! Checking that every object's mesh has the vertex attributes a style reads
//! (E0403), with a help line that says how to fix it.

use super::mesh::Attribute;
use super::Scene;
use npr_diag::{codes, Diagnostic};
use std::path::Path;

impl Scene {
    /// One E0403 per object whose mesh lacks any of `required`, pointing at
    /// where its mesh or primitive was declared. `why` is a clause naming
    /// the need, e.g. "the style `toon` reads `uv`"; it opens the message.
    ///
    /// Positions and normals are always present (normals are computed when
    /// a file has none), and tangents are derived whenever there are UVs, so
    /// in practice only UV-less meshes fail.
    pub fn check_attributes(&self, required: &[Attribute], why: &str) -> Vec<Diagnostic> {
        self.objects
            .iter()
            .filter_map(|object| {
                let missing: Vec<Attribute> = required.iter().copied().filter(|a| !object.mesh.has(*a)).collect();
                if missing.is_empty() {
                    return None;
                }
                let names: Vec<&str> = missing.iter().map(|a| a.plural_name()).collect();
                let names = names.join(" or ");
                let mesh_name = short_name(&object.mesh.source);
                let with_uvs = self
                    .objects
                    .iter()
                    .find(|other| missing.iter().all(|a| other.mesh.has(*a)))
                    .map(|other| short_name(&other.mesh.source));
                let fix = "use a primitive, a mesh with `vt` lines (or TEXCOORD_0 in glTF), or a style that does not read `uv`";
                let help = match with_uvs {
                    Some(good) => format!("{good} has {names}; {mesh_name} does not: {fix}"),
                    None => format!("{mesh_name} has no {names}: {fix}"),
                };
                let mut diagnostic =
                    Diagnostic::error(codes::MISSING_ATTRIBUTE, format!("{why}, but object `{}` has no {names}", object.name))
                        .with_primary(object.mesh_span, format!("{mesh_name} has no {names}"))
                        .with_help(help);
                if missing.contains(&Attribute::Tangent) {
                    diagnostic = diagnostic.with_note("tangents are derived from UVs, so a mesh without UVs has neither");
                }
                Some(diagnostic)
            })
            .collect()
    }
}

/// The file name of a mesh path (`cow.obj`), or a primitive's description.
fn short_name(source: &str) -> String {
    if source.ends_with(')') {
        return source.to_string();
    }
    Path::new(source)
        .file_name()
        .map_or_else(|| source.to_string(), |name| name.to_string_lossy().into_owned())
}
