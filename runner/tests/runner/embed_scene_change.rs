//! A scene change (issue 32: "objects can be added and removed between
//! frames") keeps the style's GPU resources: after frames of two objects,
//! adding an object of a registered mesh, adding one of a newly registered
//! mesh, removing one and changing a tag each make, in the frame that
//! follows, no shader module, pipeline, layout or sampler, and no texture
//! (no style texture, art-map or per-object image again, and no target:
//! the size did not change), counted by `npr_runner::gpu_count`. And that
//! frame, and the one after it, are what they must be: for a style without
//! history, the first two frames of a new runtime given the same objects,
//! byte for byte; for a style with history textures, which a scene change
//! keeps (docs/decisions/0046), the frames of a runtime that never changed
//! its scene, holding every object from frame 0 and keeping those not in
//! the scene out of the view, byte for byte (and not a new runtime's: the
//! trails stay). Over Age of Sail (per-object images, tagged shadow
//! casters), an art-map style with a lines pass, a compute style and a
//! history style. `embed_history_across_scene.rs` checks the history in
//! detail (compute state, ids, despawns).

#![allow(clippy::disallowed_methods)]

use crate::common;
use common::{compile, examples, gpu, host_target, render_frame, write_mismatch};

use npr_runner::embed::{Frame, Instance, Lights, MeshHandle, StyleRuntime, Target};
use npr_runner::gpu_count::{created_on_this_thread, GpuCreations};
use npr_runner::scene::{primitives, Camera, Mesh};

const SIZE: (u32, u32) = (64, 48);

/// The meshes a test draws, registered in this order by every runtime.
fn meshes() -> Vec<Mesh> {
    vec![
        primitives::sphere(0.6, 24, 12),
        primitives::cube(0.8),
        primitives::torus(0.5, 0.2, 24, 12),
    ]
}

/// One object of the host's scene: which of [`meshes`], its tags, and
/// the per-object image it binds (param, file under examples/), and who
/// it is (`key`, unique in a test: the reference runtime's identity).
#[derive(Clone)]
struct Object {
    key: usize,
    mesh: usize,
    tags: Vec<&'static str>,
    image: Option<(&'static str, &'static str)>,
}

/// The objects as instances of `handles` at frame `k` (they move).
fn instances(handles: &[MeshHandle], objects: &[Object], k: u32) -> Vec<Instance> {
    objects
        .iter()
        .enumerate()
        .map(|(i, o)| {
            let x = i as f32 * 1.2 - 1.2 + 0.05 * k as f32;
            let mut instance = Instance::new(
                handles[o.mesh],
                glam::Mat4::from_translation(glam::Vec3::new(x, 0.0, 0.0))
                    * glam::Mat4::from_rotation_y(0.1 * k as f32),
            );
            for t in &o.tags {
                instance = instance.with_tag(t);
            }
            if let Some((param, file)) = o.image {
                instance = instance.with_image(param, examples().join(file));
            }
            instance
        })
        .collect()
}

struct Host {
    runtime: StyleRuntime,
    handles: Vec<MeshHandle>,
    target: wgpu::Texture,
    other_size: wgpu::Texture,
}

fn texture(width: u32, height: u32) -> wgpu::Texture {
    host_target(width, height, wgpu::TextureFormat::Rgba8Unorm, &[])
}

impl Host {
    /// A runtime of `example` with the first `registered` of [`meshes`].
    fn new(example: &str, registered: usize) -> Host {
        let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, compile(example)).expect("runtime");
        let handles = meshes()
            .into_iter()
            .take(registered)
            .map(|m| runtime.add_mesh(m))
            .collect();
        Host {
            runtime,
            handles,
            target: texture(SIZE.0, SIZE.1),
            other_size: texture(SIZE.0 + 16, SIZE.1 + 12),
        }
    }

    /// Render frame `k` of `objects` (at the other size with `resized`),
    /// submit and wait; what it created on the GPU.
    fn frame(&mut self, objects: &[Object], k: u32, resized: bool) -> GpuCreations {
        let instances = instances(&self.handles, objects, k);
        self.frame_of(&instances, k, resized)
    }

    /// [`Host::frame`] of instances made by the caller.
    fn frame_of(&mut self, instances: &[Instance], k: u32, resized: bool) -> GpuCreations {
        let camera = Camera::looking_at(glam::Vec3::new(0.3, 1.2, 4.0), glam::Vec3::ZERO);
        let lights = Lights::default();
        let frame = Frame {
            camera: &camera,
            objects: instances,
            lights: &lights,
            time_s: f64::from(k) / 24.0,
            frame_index: k,
            eye: 0,
        };
        let view = if resized { &self.other_size } else { &self.target }.create_view(&Default::default());
        let before = created_on_this_thread();
        render_frame(&mut self.runtime, &frame, Target::View(&view))
            .unwrap_or_else(|e| panic!("frame {k}: {:?}", e.diagnostics()));
        let after = created_on_this_thread();
        gpu().device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
        minus(after, before)
    }

    fn output(&self) -> npr_runner::TargetImage {
        let manifest = self.runtime.manifest();
        let name = manifest.targets[manifest.output].name.clone();
        self.runtime.read_target(&name).expect("read the output")
    }
}

fn minus(a: GpuCreations, b: GpuCreations) -> GpuCreations {
    GpuCreations {
        buffers: a.buffers - b.buffers,
        textures: a.textures - b.textures,
        texture_views: a.texture_views - b.texture_views,
        samplers: a.samplers - b.samplers,
        bind_groups: a.bind_groups - b.bind_groups,
        layouts: a.layouts - b.layouts,
        pipelines: a.pipelines - b.pipelines,
        shader_modules: a.shader_modules - b.shader_modules,
        render_bundles: a.render_bundles - b.render_bundles,
    }
}

/// Where the reference runtime keeps an object that is not in the scene:
/// far to the side, out of the view.
const AWAY: glam::Vec3 = glam::Vec3::new(1000.0, 0.0, 0.0);

/// The reference's instances: every object of `all` (in its order, meshes
/// of `handles`), each as `placed` (the host's instances of `objects`)
/// places it, or away when it is not in `objects`.
fn reference_instances(
    handles: &[MeshHandle],
    all: &[Object],
    objects: &[Object],
    placed: &[Instance],
) -> Vec<Instance> {
    all.iter()
        .map(|u| match objects.iter().position(|o| o.key == u.key) {
            // Its own tags, which never change: the reference's scene
            // never changes (a history style reads no tag here).
            Some(i) => Instance {
                mesh: handles[u.mesh],
                tags: u.tags.iter().map(|t| t.to_string()).collect(),
                ..placed[i].clone()
            },
            None => Instance::new(handles[u.mesh], glam::Mat4::from_translation(AWAY)),
        })
        .collect()
}

/// The whole sequence for one example: `change_tag` is the tag the fourth
/// change gives the first object; `image` the per-object image the second
/// object binds, if the style has such a param.
fn check(
    example: &str,
    base_tags: &[&'static str],
    change_tag: &'static str,
    image: Option<(&'static str, &'static str)>,
) {
    let mut host = Host::new(example, 2);
    let history = compile(example).manifest.is_path_dependent();
    let object = |key: usize, mesh: usize, image| Object {
        key,
        mesh,
        tags: base_tags.to_vec(),
        image,
    };
    let mut objects = vec![object(0, 0, None), object(1, 1, image)];
    // Every object the test will show, in the order they first come: a
    // style with history is compared with a runtime that holds them all
    // from frame 0 (those not in the scene out of the view).
    let all = vec![
        object(0, 0, None),
        object(1, 1, image),
        object(2, 0, None),
        object(3, 2, None),
    ];
    let mut reference = history.then(|| Host::new(example, 3));
    let frame = |host: &mut Host, reference: &mut Option<Host>, objects: &[Object], k: u32, resized: bool| {
        let placed = instances(&host.handles, objects, k);
        if let Some(reference) = reference {
            let others = reference_instances(&reference.handles, &all, objects, &placed);
            reference.frame_of(&others, k, resized);
        }
        host.frame_of(&placed, k, resized)
    };
    let first = frame(&mut host, &mut reference, &objects, 0, false);
    assert!(
        first.pipelines > 0 && first.shader_modules > 0,
        "{example}: the first frame built nothing: {first:?}"
    );
    frame(&mut host, &mut reference, &objects, 1, true);
    // Back at the test's size: what a frame making only the size-level
    // resources (targets, depth, their views and groups) creates.
    let resize = frame(&mut host, &mut reference, &objects, 2, false);
    assert_eq!(
        (resize.pipelines, resize.shader_modules, resize.layouts),
        (0, 0, 0),
        "{example}: a resize made pipelines: {resize:?}"
    );
    assert!(resize.textures > 0, "{example}: a resize made no target: {resize:?}");
    // Five frames before the first change, two between the others: the
    // changes come after an odd number of frames, where a parity
    // started over would show.
    frame(&mut host, &mut reference, &objects, 3, false);
    frame(&mut host, &mut reference, &objects, 4, false);

    let mut k = 5;
    for change in [
        "an object of a registered mesh added",
        "an object of a new mesh added",
        "an object removed",
        "a tag changed",
    ] {
        match change {
            "an object of a registered mesh added" => objects.push(all[2].clone()),
            "an object of a new mesh added" => {
                let handle = host.runtime.add_mesh(meshes().swap_remove(2));
                host.handles.push(handle);
                objects.push(all[3].clone());
            }
            "an object removed" => {
                objects.remove(0);
            }
            _ => objects[0].tags.push(change_tag),
        }
        let what = format!("{example}, {change}");
        let changes_before = host.runtime.scene_changes();
        let made = frame(&mut host, &mut reference, &objects, k, false);
        assert_eq!(
            host.runtime.scene_changes(),
            changes_before + 1,
            "{what}: no scene change seen"
        );
        assert_eq!(host.runtime.builds(), 1, "{what}: the runtime built the style again");
        assert_eq!(
            (
                made.shader_modules,
                made.pipelines,
                made.layouts,
                made.samplers,
                made.textures
            ),
            (0, 0, 0, 0, 0),
            "{what}: the frame made style-level objects (shader modules, pipelines, layouts, samplers) \
             or textures (a style texture, an art-map, a per-object image or a target again): {made:?}"
        );
        // The same objects in a new runtime: its first two frames.
        let mut fresh = Host::new(example, 3);
        for step in 0..2 {
            if step == 1 {
                frame(&mut host, &mut reference, &objects, k + 1, false);
            }
            let fresh_made = fresh.frame(&objects, k + step, false);
            if step == 0 {
                // What the change frame did not make again, a new runtime does.
                let style_textures = !fresh.runtime.manifest().textures.is_empty();
                assert!(
                    fresh_made.pipelines > 0 && (!style_textures || fresh_made.textures > made.textures),
                    "{what}: a new runtime's first frame made no more than the change's: {fresh_made:?}"
                );
            }
            let changed = host.output();
            let name = format!(
                "{}-{}-{step}",
                example.trim_end_matches(".npr"),
                change.replace(' ', "-")
            );
            let (expected, against) = match &reference {
                // The history goes on: the trails stay, as in a runtime
                // whose scene never changed, and the frame is not a new
                // runtime's (whose history is empty).
                Some(reference) => {
                    assert_ne!(
                        changed.bytes,
                        fresh.output().bytes,
                        "{what}: frame {step} after the change is a new runtime's: the history was not kept"
                    );
                    (reference.output(), "the reference's (all objects from frame 0)")
                }
                None => (fresh.output(), "a new runtime's"),
            };
            if changed.bytes != expected.bytes {
                let dir = write_mismatch("embed-scene-change", &name, &changed, &expected);
                panic!(
                    "{what}: frame {step} after the change differs from {against} (images in {})",
                    dir.display()
                );
            }
        }
        k += 2;
    }
}

#[test]
fn age_of_sail_keeps_its_pipelines_and_images_across_scene_changes() {
    check(
        "age_of_sail.npr",
        &[],
        "caster",
        Some(("lit_map", "textures/paint_spot_lit.png")),
    );
}

#[test]
fn an_artmap_style_keeps_its_artmaps_across_scene_changes() {
    check("artmap_gallery.npr", &[], "pillar", None);
}

#[test]
fn a_compute_style_keeps_its_pipelines_across_scene_changes() {
    check("object_centroids.npr", &[], "extra", None);
}

#[test]
fn a_history_style_keeps_its_history_across_scene_changes() {
    check("afterimage.npr", &[], "extra", None);
}
