//! Per-object state read from the [`Scene`] every frame: the object uniform
//! blocks (model matrix, normal matrix, per-object params) written into the
//! one dynamic-offset object buffer, and the world bounds the light camera
//! is fitted to. The scene's structure (objects, meshes, tags, bound images)
//! is fixed when the renderer is built; only these values may change.
//!
//! Both are kept between frames, because a host's frame is mostly these
//! (`npr bench host`, docs/PERFORMANCE.md): the blocks' bytes are rewritten
//! in place (in the frame's staging bytes, `upload.rs`), and each object's
//! world box is recomputed only when its transform or mesh changed since
//! the box was made.

use crate::scene::{union_bounds, Mesh, Scene, EMPTY_BOUNDS};
use crate::{animation, RunError};
use abi::manifest::*;
use abi::ObjectHead;
use glam::{Mat4, Vec3};
use std::sync::Arc;

/// Every object's uniform block at its dynamic offset (`stride` apart, zero
/// padded), written over `bytes` (`stride` × objects long): the [`ObjectHead`]
/// (`model`, the normal matrix — inverse transpose of `model`, or the
/// identity where `model` is singular — the previous frame's `model`, and
/// the ids: index, index + 1, vertex count), then the per-object param
/// slots. Bindings with the wrong number of components or out of range
/// (E0405, E0401) come back as `RunError::User`.
pub(super) fn write_object_blocks(
    manifest: &Manifest,
    scene: &Scene,
    stride: u64,
    (previous_models, vertex_counts): (&[Mat4], &[usize]),
    bytes: &mut [u8],
) -> Result<(), RunError> {
    let stride = stride as usize;
    // Padding past the params is never written, so it stays zero.
    let params_at = OBJECT_PARAMS_OFFSET as usize;
    let params_end = (manifest.object_uniform_size as usize).clamp(params_at, stride);
    let mut diags = Vec::new();
    for (index, (block, o)) in bytes.chunks_exact_mut(stride).zip(&scene.objects).enumerate() {
        let normal_matrix = o.model.inverse().transpose();
        let normal_matrix = if normal_matrix.is_finite() {
            normal_matrix
        } else {
            Mat4::IDENTITY
        };
        let head = ObjectHead {
            model: o.model.to_cols_array_2d(),
            normal_matrix: normal_matrix.to_cols_array_2d(),
            previous_model: previous_models.get(index).unwrap_or(&o.model).to_cols_array_2d(),
            ids: [
                index as u32,
                index as u32 + 1,
                vertex_counts.get(index).map_or(0, |n| *n as u32),
                0,
            ],
        };
        block[..params_at].copy_from_slice(bytemuck::bytes_of(&head));
        animation::write_object_params(manifest, o, &mut block[params_at..params_end], &mut diags);
    }
    if !diags.is_empty() {
        return Err(RunError::User(diags));
    }
    Ok(())
}

/// World bounds for the light camera of a frame (`scene::light_view_proj`):
/// what the whole scene spans (its depth range) and what the light-view
/// passes draw, the shadow casters (its x, y extent). Kept from frame to
/// frame: per object its [`crate::scene::Object::world_bounds`] and what
/// they were computed from, so a frame transforms the vertices of the
/// objects that moved only. The unions are folded over the objects in
/// order, as [`Scene::bounds_of`] folds them, so they are the bounds
/// computed from scratch, bit for bit (a unit test compares them).
pub(super) struct LightBounds {
    /// Per object: whether a light-view pass draws it.
    drawn: Vec<bool>,
    /// Per object: its world box and the model and mesh it is of.
    boxes: Vec<ObjectBox>,
    /// The whole scene's box.
    pub scene: (Vec3, Vec3),
    /// The shadow casters' box (the scene's when no object is drawn).
    pub casters: (Vec3, Vec3),
}

struct ObjectBox {
    model: Mat4,
    mesh: Arc<Mesh>,
    bounds: (Vec3, Vec3),
}

impl LightBounds {
    /// The bounds of `scene`, whose objects' tags decide which the
    /// light-view passes of `manifest` draw (fixed for the renderer's life).
    pub fn new(manifest: &Manifest, scene: &Scene) -> LightBounds {
        // Objects any light-view pass draws; all of them when such a pass has no tag.
        let tags: Vec<Option<&String>> = manifest
            .passes
            .iter()
            .filter_map(|p| match &p.kind {
                PassKindManifest::Render {
                    tag, light_view: true, ..
                } => Some(tag.as_ref()),
                _ => None,
            })
            .collect();
        let mut bounds = LightBounds {
            drawn: scene
                .objects
                .iter()
                .map(|o| tags.iter().any(|t| t.is_none_or(|t| o.tags.contains(t))))
                .collect(),
            boxes: scene
                .objects
                .iter()
                .map(|o| ObjectBox {
                    model: o.model,
                    mesh: o.mesh.clone(),
                    bounds: o.world_bounds(),
                })
                .collect(),
            scene: EMPTY_BOUNDS,
            casters: EMPTY_BOUNDS,
        };
        bounds.unite();
        bounds
    }

    /// Bring the bounds to `scene` (the objects the renderer was built
    /// for, posed for this frame): only moved objects' boxes are made anew.
    pub fn update(&mut self, scene: &Scene) {
        let mut changed = false;
        for (b, o) in self.boxes.iter_mut().zip(&scene.objects) {
            if b.model != o.model || !Arc::ptr_eq(&b.mesh, &o.mesh) {
                b.model = o.model;
                if !Arc::ptr_eq(&b.mesh, &o.mesh) {
                    b.mesh = o.mesh.clone();
                }
                b.bounds = o.world_bounds();
                changed = true;
            }
        }
        if changed {
            self.unite();
        }
    }

    /// The scene's and the casters' boxes from the objects' boxes.
    fn unite(&mut self) {
        let boxes = || self.boxes.iter().map(|b| b.bounds);
        self.scene = boxes().fold(EMPTY_BOUNDS, union_bounds);
        let drawn = boxes()
            .zip(&self.drawn)
            .filter(|(_, d)| **d)
            .map(|(b, _)| b)
            .fold(EMPTY_BOUNDS, union_bounds);
        self.casters = if drawn.0.is_finite() { drawn } else { self.scene };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{primitives, Camera, Object};
    use std::collections::BTreeMap;

    fn object(name: &str, mesh: &Arc<Mesh>, model: Mat4, tags: &[&str]) -> Object {
        Object {
            name: name.into(),
            mesh: mesh.clone(),
            model,
            tags: tags.iter().map(|t| t.to_string()).collect(),
            params: BTreeMap::new(),
            param_spans: BTreeMap::new(),
            textures: BTreeMap::new(),
            mesh_span: diag::Span::default(),
            time_varying: None,
            casts_shadows: true,
            spin: Vec3::ZERO,
            blend: None,
            patch: None,
        }
    }

    /// A manifest with one light-view pass drawing `tag`.
    fn manifest(tag: Option<&str>) -> Manifest {
        let source = match tag {
            Some(t) => format!(
                "style \"B\"\npass d: render({t}) view(light) {{\n  out c: rgba8unorm = vec4(1.0)\n}}\noutput d.c\n"
            ),
            None => {
                "style \"B\"\npass d: render(scene) view(light) {\n  out c: rgba8unorm = vec4(1.0)\n}\noutput d.c\n"
                    .to_string()
            }
        };
        let mut sources = diag::SourceMap::new();
        compiler::compile_source(
            "b.npr",
            &source,
            std::path::Path::new("."),
            &mut sources,
            &Default::default(),
        )
        .map_err(|e| format!("{e:?}"))
        .unwrap()
        .program()
        .manifest
    }

    /// The bounds as the renderer computed them before they were kept:
    /// every kept object's vertices through `Mat4::transform_point3`, one
    /// running min and max over all of them.
    fn flat_bounds(scene: &Scene, keep: impl Fn(&Object) -> bool) -> (Vec3, Vec3) {
        let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for o in scene.objects.iter().filter(|o| keep(o)) {
            for p in &o.mesh.positions {
                let w = o.model.transform_point3(Vec3::from(*p));
                if w.is_finite() {
                    lo = lo.min(w);
                    hi = hi.max(w);
                }
            }
        }
        (lo, hi)
    }

    /// Kept bounds equal the bounds computed from the whole scene, and the
    /// running min and max of every transformed vertex (`==`: equal values;
    /// only a zero's sign could differ, which no camera built from them
    /// tells apart), after objects move, one at a time and all at once, and
    /// after a mesh is swapped.
    #[test]
    fn kept_bounds_are_the_bounds_from_scratch() {
        let sphere = Arc::new(primitives::sphere(1.0, 16, 8));
        let cube = Arc::new(primitives::cube(2.0));
        for tag in [Some("caster"), None, Some("nothing")] {
            let manifest = manifest(tag);
            let mut scene = Scene::empty();
            scene.camera = Camera::looking_at(Vec3::Z, Vec3::ZERO);
            for i in 0..5 {
                let mesh = if i % 2 == 0 { &sphere } else { &cube };
                let tags: &[&str] = if i % 3 == 0 { &["caster"] } else { &[] };
                let model = Mat4::from_translation(Vec3::new(i as f32 * 1.7 - 3.0, 0.3 * i as f32, -0.5));
                scene.objects.push(object(&format!("o{i}"), mesh, model, tags));
            }
            let mut kept = LightBounds::new(&manifest, &scene);
            let check = |kept: &LightBounds, scene: &Scene, when: &str| {
                let fresh = LightBounds::new(&manifest, scene);
                assert_eq!(kept.scene, scene.bounds(), "{tag:?} {when}: scene");
                assert_eq!(kept.scene, fresh.scene, "{tag:?} {when}: scene");
                assert_eq!(kept.casters, fresh.casters, "{tag:?} {when}: casters");
                let drawn = scene.bounds_of(|o| tag.is_none_or(|t| o.has_tag(t)));
                let casters = if drawn.0.is_finite() { drawn } else { scene.bounds() };
                assert_eq!(kept.casters, casters, "{tag:?} {when}: casters");
                assert_eq!(kept.scene, flat_bounds(scene, |_| true), "{tag:?} {when}: scene, flat");
                let flat = flat_bounds(scene, |o| tag.is_none_or(|t| o.has_tag(t)));
                let flat = if flat.0.is_finite() {
                    flat
                } else {
                    flat_bounds(scene, |_| true)
                };
                assert_eq!(kept.casters, flat, "{tag:?} {when}: casters, flat");
            };
            check(&kept, &scene, "built");
            for frame in 1..4 {
                let turn = Mat4::from_rotation_y(0.37 * frame as f32) * Mat4::from_scale(Vec3::splat(1.1));
                scene.objects[frame].model *= turn;
                kept.update(&scene);
                check(&kept, &scene, &format!("object {frame} moved"));
            }
            for o in &mut scene.objects {
                o.model = Mat4::from_rotation_x(0.2) * o.model;
            }
            kept.update(&scene);
            check(&kept, &scene, "all moved");
            scene.objects[0].mesh = cube.clone();
            kept.update(&scene);
            check(&kept, &scene, "a mesh swapped");
        }
    }
}
