//! The world bounds the light camera of a frame is fitted to
//! (`scene::light_view_proj`): the whole scene's box (its depth range) and
//! the shadow casters' (its x, y extent), kept from frame to frame.
//!
//! A host's objects move every frame, and transforming every vertex of
//! every object was most of a host's frame (docs/PERFORMANCE.md, "host
//! path"). So: an object's box is made anew only when its transform or
//! mesh changed; and the vertices are transformed once per mesh and
//! linear part (rotation and scale), not once per object: a point's world
//! coordinate is `w + a`, `a` its linear image, and rounding is monotonic,
//! so the largest `w + a` over the vertices is `w + (the largest a)`,
//! exactly. Objects turning together, or only translating, share that
//! work. The boxes are the ones computed from every transformed vertex,
//! equal in value (a unit test compares them).

use crate::scene::{union_bounds, Mesh, Object, Scene, EMPTY_BOUNDS};
use glam::{Mat4, Vec3, Vec4};
use npr_abi::manifest::*;
use rustc_hash::FxHashMap;
use std::sync::Arc;

/// World bounds for the light camera of a frame: per object its box and
/// what it was computed from, and the unions, folded over the objects in
/// order as [`Scene::bounds_of`] folds them.
pub(super) struct LightBounds {
    /// Per object: whether a light-view pass draws it.
    drawn: Vec<bool>,
    /// Per object: its world box and the model and mesh it is of.
    boxes: Vec<ObjectBox>,
    /// The whole scene's box.
    pub scene: (Vec3, Vec3),
    /// The shadow casters' box (the scene's when no object is drawn).
    pub casters: (Vec3, Vec3),
    /// Per mesh and linear part: the box of the vertices' linear images.
    linear: LinearBoxes,
    /// The last light camera and the bits of the light direction it was
    /// made for, kept while neither it nor the boxes change.
    light_camera: Option<([u32; 3], Mat4)>,
}

/// A mesh (by address; the entry holds it, so the address stays its own)
/// and the bits of a model's first three columns.
type LinearKey = (usize, [u32; 12]);

/// The linear boxes by mesh and linear part, hashed with rustc-hash
/// (every moved object looks its key up every frame), and the last key
/// looked up with its box: objects in a row that share both (a crowd
/// turning together, objects that are only moved) skip the hash.
#[derive(Default)]
struct LinearBoxes {
    map: FxHashMap<LinearKey, LinearBox>,
    /// Valid while `map` holds its key (whose entry keeps the mesh's
    /// address its own): [`LinearBoxes::clear`] forgets it too.
    last: Option<(LinearKey, Option<(Vec4, Vec4)>)>,
}

impl LinearBoxes {
    /// The box of `mesh`'s vertices' images under `m`'s linear part
    /// ([`linear_box`]), computed once per key.
    fn get(&mut self, mesh: &Arc<Mesh>, m: &Mat4) -> Option<(Vec4, Vec4)> {
        let mut bits = [0u32; 12];
        for (b, v) in bits.iter_mut().zip(m.to_cols_array()) {
            *b = v.to_bits();
        }
        let key = (Arc::as_ptr(mesh) as usize, bits);
        if let Some((last, bounds)) = self.last {
            if last == key {
                return bounds;
            }
        }
        let bounds = self
            .map
            .entry(key)
            .or_insert_with(|| LinearBox {
                _mesh: mesh.clone(),
                bounds: linear_box(mesh, m),
            })
            .bounds;
        self.last = Some((key, bounds));
        bounds
    }

    fn clear(&mut self) {
        self.map.clear();
        self.last = None;
    }
}

struct LinearBox {
    _mesh: Arc<Mesh>,
    /// The min and max of `z·p.z + (y·p.y + x·p.x)` over the vertices `p`,
    /// or `None` when some vertex's is not finite (then the object's box
    /// is computed vertex by vertex, as [`Object::world_bounds`] does).
    bounds: Option<(Vec4, Vec4)>,
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
                    bounds: EMPTY_BOUNDS,
                })
                .collect(),
            scene: EMPTY_BOUNDS,
            casters: EMPTY_BOUNDS,
            linear: LinearBoxes::default(),
            light_camera: None,
        };
        for (b, o) in bounds.boxes.iter_mut().zip(&scene.objects) {
            b.bounds = object_box(&mut bounds.linear, o);
        }
        bounds.unite();
        bounds
    }

    /// Bring the bounds to `scene` (the objects the renderer was built
    /// for, posed for this frame): only moved objects' boxes are made anew.
    pub fn update(&mut self, scene: &Scene) {
        // Linear parts of past frames: kept while they are few.
        if self.linear.map.len() > 2 * self.boxes.len() + 16 {
            self.linear.clear();
        }
        let mut changed = false;
        for (b, o) in self.boxes.iter_mut().zip(&scene.objects) {
            if b.model != o.model || !Arc::ptr_eq(&b.mesh, &o.mesh) {
                b.model = o.model;
                if !Arc::ptr_eq(&b.mesh, &o.mesh) {
                    b.mesh = o.mesh.clone();
                }
                b.bounds = object_box(&mut self.linear, o);
                changed = true;
            }
        }
        if changed {
            self.unite();
        }
    }

    /// The light camera for `direction` (`scene::light_view_proj` of the
    /// casters' and the scene's boxes), made anew only when the direction
    /// or the boxes changed since the last call: equal inputs, equal matrix.
    pub fn light_view_proj(&mut self, direction: Vec3) -> Mat4 {
        let bits = [direction.x.to_bits(), direction.y.to_bits(), direction.z.to_bits()];
        match self.light_camera {
            Some((kept, matrix)) if kept == bits => matrix,
            _ => {
                let matrix = crate::scene::light_view_proj(direction, self.casters, self.scene);
                self.light_camera = Some((bits, matrix));
                matrix
            }
        }
    }

    /// The scene's and the casters' boxes from the objects' boxes.
    fn unite(&mut self) {
        self.light_camera = None;
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

/// `o`'s world box: `w + ` its linear box, or vertex by vertex where a
/// linear image or a world coordinate is not finite.
fn object_box(linear: &mut LinearBoxes, o: &Object) -> (Vec3, Vec3) {
    let m = &o.model;
    if let Some((lo, hi)) = linear.get(&o.mesh, m) {
        // `w_axis + a`, the last sum of `Object::world_bounds`.
        let (lo, hi) = ((m.w_axis + lo).truncate(), (m.w_axis + hi).truncate());
        // Every world coordinate lies between these: all finite, none was left out.
        if lo.is_finite() && hi.is_finite() {
            return (lo, hi);
        }
    }
    o.world_bounds()
}

/// The box of `z·p.z + (y·p.y + x·p.x)` over `mesh`'s vertices, with
/// `Object::world_bounds`'s products and sums; `None` when a vertex's is
/// not finite, or there is no vertex.
fn linear_box(mesh: &Mesh, m: &Mat4) -> Option<(Vec4, Vec4)> {
    let (mut lo, mut hi) = (Vec4::INFINITY, Vec4::NEG_INFINITY);
    for p in &mesh.positions {
        let a = m.z_axis * p[2] + (m.y_axis * p[1] + m.x_axis * p[0]);
        if a.is_finite_mask().bitmask() & 0b111 != 0b111 {
            return None;
        }
        lo = lo.min(a);
        hi = hi.max(a);
    }
    (!mesh.positions.is_empty()).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{primitives, Camera};

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
        let mut sources = npr_diag::SourceMap::new();
        npr_compiler::compile_source(
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
                scene.objects.push(Object::plain(&format!("o{i}"), mesh, model, tags));
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
            // Every object turned alike (in a row, the same linear part:
            // the same mesh, objects 0 and 1, or another, 1 and 2).
            let alike = Mat4::from_rotation_z(0.3) * Mat4::from_scale(Vec3::new(1.0, 0.5, 2.0));
            for (i, o) in scene.objects.iter_mut().enumerate() {
                o.model = Mat4::from_translation(Vec3::new(i as f32, -1.0, 0.25 * i as f32)) * alike;
            }
            kept.update(&scene);
            check(&kept, &scene, "all turned alike");
            // Some world coordinates overflow: those vertices are left out.
            scene.objects[1].model =
                Mat4::from_translation(Vec3::new(3.0e38, 0.0, 0.0)) * Mat4::from_scale(Vec3::splat(1.0e38));
            kept.update(&scene);
            check(&kept, &scene, "an object at the edge of f32");
        }
    }
}
