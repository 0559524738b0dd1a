//! The surfaces a `lines` pass finds feature edges on, from the scene's
//! objects. An object divided into patches (Breslav et al. 2007 §3.6) is one
//! surface: its patches are objects of their own for every per-object pass,
//! but their seams are where the k-means split (or the file's parts) cut a
//! smooth surface, not creases of it. Found patch by patch, every seam edge
//! would have one face in each patch's mesh and be drawn as a boundary
//! (Klein et al. 2000 §5 draws creases "at the intersections of
//! non-coplanar polygons"; a boundary is always drawn), and a silhouette
//! running across a seam would lose the edge on it. So the patches of one
//! object are drawn as the object's whole mesh ([`PatchOf::whole`]), once:
//! a seam edge is then a crease exactly when its dihedral angle says so,
//! and chains (and the sine's phase along them) run on across seams.
//!
//! The whole mesh stands for its patches only when the pass draws every
//! one of them with one model matrix, as a scene's patches always are (they
//! share their object's transform, tags and spin). A program that moves one
//! patch apart makes separate surfaces: each patch is then drawn on its
//! own, seams as boundaries, since they are the edges of pieces apart.

use std::collections::{HashMap, HashSet};

use super::cache::LineObject;
use crate::scene::patches::PatchOf;
use crate::scene::{Mesh, Object};

/// Per drawn object (with its mesh at this frame's time), the surfaces to
/// find edges on, in the objects' order: a patched object's whole mesh in
/// the place of its first patch.
pub fn line_objects<'a>(drawn: &[(&'a Object, &'a Mesh)]) -> Vec<LineObject<'a>> {
    // Per patched object: how many of its patches are drawn, and whether
    // they all have the first one's model.
    let mut groups: HashMap<&str, (u32, glam::Mat4, bool)> = HashMap::new();
    for (object, _) in drawn {
        if let Some(patch) = &object.patch {
            let group = groups.entry(patch.source.as_str()).or_insert((0, object.model, true));
            group.0 += 1;
            group.2 &= group.1 == object.model;
        }
    }
    let is_whole = |patch: &PatchOf| {
        let (drawn, _, same_model) = groups[patch.source.as_str()];
        drawn == patch.count && same_model
    };
    let mut emitted: HashSet<&str> = HashSet::new();
    let mut out = Vec::with_capacity(drawn.len());
    for &(object, mesh) in drawn {
        let model = object.model.as_dmat4();
        match &object.patch {
            Some(patch) if is_whole(patch) => {
                if emitted.insert(patch.source.as_str()) {
                    out.push(LineObject {
                        mesh: patch.whole.as_ref(),
                        model,
                    });
                }
            }
            _ => out.push(LineObject { mesh, model }),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lines::edges::{EdgeKind, EdgeMesh};
    use crate::scene::Scene;

    fn scene(object: &str) -> Scene {
        let text = format!("[camera]\nposition = [0.0, 3.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\n\n[[object]]\n{object}\n");
        let mut sources = npr_diag::SourceMap::new();
        let file = sources.add("patched.toml", text.clone());
        crate::scene::parse_scene(&text, file, std::path::Path::new("."))
            .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
    }

    /// Boundary and crease edges (at 40°) over the surfaces `line_objects`
    /// gives for every object of `scene`.
    fn feature_edges(scene: &Scene) -> (usize, usize, usize) {
        let drawn: Vec<(&Object, &Mesh)> = scene.objects.iter().map(|o| (o, o.mesh.as_ref())).collect();
        let surfaces = line_objects(&drawn);
        let mut counts = (surfaces.len(), 0, 0);
        for s in &surfaces {
            for (_, kind) in EdgeMesh::new(s.mesh).creases(40.0) {
                match kind {
                    EdgeKind::Boundary => counts.1 += 1,
                    _ => counts.2 += 1,
                }
            }
        }
        counts
    }

    /// An 8 × 8 plane in 3 patches: its boundary is its rim, 4 × 8 edges,
    /// and nothing else, as without patches; each patch alone would add
    /// every seam edge twice, once per side.
    #[test]
    fn a_patched_planes_only_boundary_is_its_rim() {
        let plane = "primitive = { kind = \"plane\", size = 2.0, subdivisions = 8 }";
        let patched = scene(&format!("{plane}\npatches = 3\n"));
        assert_eq!(patched.objects.len(), 3);
        assert_eq!(feature_edges(&scene(plane)), (1, 32, 0));
        assert_eq!(feature_edges(&patched), (1, 32, 0));
        let per_patch: usize = patched
            .objects
            .iter()
            .map(|o| EdgeMesh::new(&o.mesh).creases(40.0).len())
            .sum();
        // 60 here: the seams between the three patches are 14 edges long.
        assert!(per_patch >= 32 + 2 * 8, "patch by patch: {per_patch} boundary edges");
    }

    /// A smooth sphere (64 × 32, 5.6° between neighbouring faces) in 5
    /// patches has no feature edge at 40°, and a silhouette on a seam is
    /// found: the whole mesh's edges are the unpatched sphere's.
    #[test]
    fn a_patched_sphere_has_no_seam_edges_and_the_spheres_silhouette() {
        let sphere = "primitive = { kind = \"sphere\", radius = 1.0, segments = 64, rings = 32 }";
        let (plain, patched) = (scene(sphere), scene(&format!("{sphere}\npatches = 5\n")));
        assert_eq!(feature_edges(&patched), (1, 0, 0));
        let drawn: Vec<(&Object, &Mesh)> = patched.objects.iter().map(|o| (o, o.mesh.as_ref())).collect();
        let surfaces = line_objects(&drawn);
        let eye = glam::DVec3::new(0.3, 2.0, 3.0);
        let whole = EdgeMesh::new(surfaces[0].mesh);
        let alone = EdgeMesh::new(&plain.objects[0].mesh);
        assert_eq!(whole.silhouettes(eye).len(), alone.silhouettes(eye).len());
        assert_eq!(whole.edges.len(), alone.edges.len());
    }

    /// A patch moved apart is a surface of its own, its seams boundaries:
    /// the plane's two halves (k-means of a symmetric grid splits it down
    /// the middle) have the rim and the 8 seam edges on each side.
    #[test]
    fn a_patch_moved_apart_is_drawn_alone() {
        let plane = "primitive = { kind = \"plane\", size = 2.0, subdivisions = 8 }\npatches = 2\n";
        let mut moved = scene(plane);
        moved.objects[1].model = glam::Mat4::from_translation(glam::Vec3::new(0.0, 1.0, 0.0)) * moved.objects[1].model;
        let (surfaces, boundaries, creases) = feature_edges(&moved);
        assert_eq!((surfaces, boundaries, creases), (2, 32 + 2 * 8, 0));
    }
}
