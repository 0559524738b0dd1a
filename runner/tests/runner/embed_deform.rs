//! A host's own deforming mesh (`StyleRuntime::update_mesh`): its vertices
//! are written over the mesh's GPU buffers in place, the history goes on,
//! and everything made from the vertices follows (compute passes over
//! vertices, `lines` passes, the light camera of shadow passes).
//!
//! Two references, neither using the new path:
//! - the ocean of Age of Sail §6.1 as a host's own mesh, deformed each
//!   frame into the primitive's geometry at the frame's time, against a
//!   `Renderer` (what `npr render` drives) drawing the same ocean as a
//!   time-varying primitive, the same frames in the same order (its
//!   vertices rewritten by `update_time_varying`): a style with history
//!   (`afterimage`, `previous(...)`), one with a compute pass over vertices
//!   (`object_centroids`) and one with `lines` (`wavy_lines`);
//! - a sphere the host squashes and shears, casting a shadow on a ground
//!   (Age of Sail's light-view depth pass, whose light camera is fitted to
//!   the casters' bounds) and under `wavy_lines`, against a `Renderer`
//!   built afresh for each frame with the deformed mesh made by
//!   `Mesh::from_parts` (these styles keep no history).
//!
//! Every comparison is byte for byte (the same vertices reach the same
//! shaders). On a difference the runtime's image, the reference's and
//! their difference (×8) are written under
//! `$CARGO_TARGET_TMPDIR/embed-deform/`. The frames after the first create
//! no GPU object (`npr_runner::gpu_count`) and no scene change; bad updates
//! are coded errors (E0601, E0603) that leave the mesh as it was.
//!
//! One file past ~600 lines on purpose: every test drives the same frame
//! helpers and references (`render`, `present`, `squash`, the ocean), which
//! a split would have to move into `common/`, where the other embed tests'
//! binaries would carry them unused.

#![allow(clippy::disallowed_methods)]

use crate::common;
use common::{compile, gpu, host_target, read_host, render_frame, write_mismatch};

use glam::{Mat4, Vec3};
use npr_runner::embed::{Deformed, EmbedError, Frame, Instance, Lights, MeshHandle, StyleRuntime, Target};
use npr_runner::gpu_count::created_on_this_thread;
use npr_runner::readback::TargetImage;
use npr_runner::scene::ocean::Ocean;
use npr_runner::scene::patches::PatchSpec;
use npr_runner::scene::{primitives, Camera, Mesh, Object, Primitive, Scene};
use npr_runner::{FrameSpec, Renderer};
use std::collections::BTreeMap;

use std::sync::Arc;

const WIDTH: u32 = 96;
const HEIGHT: u32 = 72;

/// The frames' times, in order (frame indices 0, 1, ...).
const TIMES: [f64; 4] = [0.0, 0.5, 1.25, 2.0];

/// A small sea (the allocation test's): quick on a software rasterizer.
fn ocean() -> Primitive {
    Primitive::Ocean(Ocean {
        cells: 16,
        tiles: 3,
        modes: 8,
        ring: 400.0,
        ..Ocean::default()
    })
}

fn object(name: &str, mesh: Arc<Mesh>, model: Mat4, tags: &[&str], time_varying: Option<Primitive>) -> Object {
    Object {
        name: name.into(),
        mesh,
        model,
        tags: tags.iter().map(|t| t.to_string()).collect(),
        params: BTreeMap::new(),
        param_spans: BTreeMap::new(),
        textures: BTreeMap::new(),
        mesh_span: npr_diag::Span::default(),
        time_varying,
        casts_shadows: true,
        spin: Vec3::ZERO,
        blend: None,
        patch: None,
        animation: None,
        pose: None,
        material: None,
    }
}

/// Frame `k` of the runtime presented into `texture`, submitted.
fn render(
    runtime: &mut StyleRuntime,
    scene: &Scene,
    objects: &[Instance],
    (k, time_s): (usize, f64),
    texture: &wgpu::Texture,
) {
    let lights = Lights {
        key: scene.light,
        more: scene.more_lights,
    };
    let frame = Frame {
        camera: &scene.camera,
        objects,
        lights: &lights,
        time_s,
        frame_index: k as u32,
        eye: 0,
    };
    render_frame(runtime, &frame, Target::View(&texture.create_view(&Default::default())))
        .unwrap_or_else(|e| panic!("frame {k}: {:?}", e.diagnostics()));
}

/// [`render`], checking that a frame after the first creates no GPU
/// object, and the host's texture read back.
fn present(
    runtime: &mut StyleRuntime,
    scene: &Scene,
    objects: &[Instance],
    (k, time_s): (usize, f64),
    texture: &wgpu::Texture,
) -> TargetImage {
    let before = created_on_this_thread();
    render(runtime, scene, objects, (k, time_s), texture);
    let after = created_on_this_thread();
    assert!(
        k == 0 || after == before,
        "frame {k} after update_mesh created GPU objects: {before:?} → {after:?}"
    );
    read_host(texture)
}

fn spec((k, time_s): (usize, f64)) -> FrameSpec {
    FrameSpec {
        width: WIDTH,
        height: HEIGHT,
        time_s,
        frame: k as u32,
        eye: 0,
    }
}

/// The runtime kept one renderer and one scene over the frames.
fn assert_no_rebuild(runtime: &StyleRuntime, name: &str) {
    assert_eq!(runtime.builds(), 1, "{name}: the runtime rebuilt its renderer");
    assert_eq!(
        runtime.scene_changes(),
        0,
        "{name}: update_mesh made a scene change (the history restarted)"
    );
}

/// Per frame: (the runtime's image, the reference's), with the ocean as
/// the host's own mesh deformed to the primitive's geometry at each
/// frame's time, twice (two instances of one handle, which share its
/// buffers), against a `Renderer` drawing two time-varying oceans.
fn ocean_frames(style: &str) -> Vec<(TargetImage, TargetImage)> {
    let program = compile(style);
    let sea = ocean();
    let far = Mat4::from_translation(Vec3::new(6.0, -1.0, 30.0));
    let mut scene = Scene::empty();
    scene.camera = Camera::looking_at(Vec3::new(0.0, 6.0, 0.0), Vec3::new(0.0, 1.0, 40.0));
    scene.objects = vec![
        object("sea", Arc::new(sea.build()), Mat4::IDENTITY, &[], Some(sea)),
        object("far sea", Arc::new(sea.build()), far, &[], Some(sea)),
    ];
    let mut renderer = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");

    let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, program).expect("runtime");
    // The host's own mesh: nothing tells the runtime it moves.
    let water = runtime.add_mesh(sea.build());
    let objects = [Instance::new(water, Mat4::IDENTITY), Instance::new(water, far)];
    let texture = host_target(WIDTH, HEIGHT, wgpu::TextureFormat::Rgba8Unorm, &[]);
    let mut frames = Vec::new();
    for (k, &time_s) in TIMES.iter().enumerate() {
        if k > 0 {
            let waves = sea.build_at(time_s);
            let tangents = waves.tangents.as_deref().expect("the ocean has tangents");
            runtime
                .update_mesh(
                    water,
                    Deformed::positions(&waves.positions)
                        .with_normals(&waves.normals)
                        .with_tangents(tangents),
                )
                .unwrap_or_else(|e| panic!("update at frame {k}: {:?}", e.diagnostics()));
        }
        let hosted = present(&mut runtime, &scene, &objects, (k, time_s), &texture);
        renderer.render(&scene, &spec((k, time_s))).expect("render");
        frames.push((hosted, renderer.read_output().expect("read back the output")));
    }
    assert_no_rebuild(&runtime, style);
    frames
}

/// The host's deformation of the sphere at `time_s`: squashed, bulging
/// and sheared, so its bounds (and the light camera fitted to them) change.
fn squash(rest: &[[f32; 3]], time_s: f64) -> Vec<[f32; 3]> {
    let t = time_s as f32;
    rest.iter()
        .map(|&[x, y, z]| {
            let bulge = 1.0 + 0.3 * (3.0 * y + 2.0 * t).sin() * (t * 0.8).min(1.0);
            [x * bulge + 0.4 * t * y, y * (1.0 - 0.2 * t), z * bulge]
        })
        .collect()
}

/// Per frame: (the runtime's image, the reference's), a deforming sphere
/// tagged `caster` over a still ground, normals and tangents made by the
/// runtime, against a `Renderer` made for each frame with the sphere's
/// mesh from `Mesh::from_parts` of the same positions. With `frozen_clock`
/// every frame is at t = 0 (only the mesh changes: nothing else would make
/// a `lines` pass build its strips anew).
fn squashed_frames(style: &str, frozen_clock: bool) -> Vec<(TargetImage, TargetImage)> {
    let program = compile(style);
    let rest = primitives::sphere(0.8, 32, 16);
    let ground = Arc::new(primitives::plane(6.0, 4));
    let lifted = Mat4::from_translation(Vec3::new(0.0, 0.9, 0.0));
    let mut scene = Scene::empty();
    scene.camera = Camera::looking_at(Vec3::new(0.5, 2.5, 4.0), Vec3::new(0.0, 0.6, 0.0));

    let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, program.clone()).expect("runtime");
    let ball = runtime.add_mesh(rest.clone());
    let floor = runtime.add_shared_mesh(ground.clone());
    let objects = [
        Instance::new(ball, lifted).with_tag("caster"),
        Instance::new(floor, Mat4::IDENTITY),
    ];
    let texture = host_target(WIDTH, HEIGHT, wgpu::TextureFormat::Rgba8Unorm, &[]);
    let mut frames = Vec::new();
    for (k, &time_s) in TIMES.iter().enumerate() {
        let positions = squash(&rest.positions, time_s);
        if k > 0 {
            runtime
                .update_mesh(ball, Deformed::positions(&positions))
                .unwrap_or_else(|e| panic!("update at frame {k}: {:?}", e.diagnostics()));
        }
        let deformed = if k == 0 {
            rest.clone()
        } else {
            Mesh::from_parts(
                positions,
                None,
                rest.uvs.clone(),
                None,
                rest.indices.clone(),
                "deformed sphere".into(),
            )
        };
        scene.objects = vec![
            object("ball", Arc::new(deformed), lifted, &["caster"], None),
            object("ground", ground.clone(), Mat4::IDENTITY, &[], None),
        ];
        let at = (k, if frozen_clock { 0.0 } else { time_s });
        let hosted = present(&mut runtime, &scene, &objects, at, &texture);
        let mut fresh = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
        fresh.render(&scene, &spec(at)).expect("render");
        frames.push((hosted, fresh.read_output().expect("read back the output")));
    }
    assert_no_rebuild(&runtime, style);
    frames
}

/// Every frame equals its reference byte for byte, and the images move
/// (a deformation the frames did not show would prove nothing).
fn assert_equal(frames: &[(TargetImage, TargetImage)], name: &str) {
    assert_frames_equal(frames, name);
    let last = &frames.last().expect("frames").1;
    let changed = frames[0]
        .1
        .bytes
        .chunks(4)
        .zip(last.bytes.chunks(4))
        .filter(|(a, b)| a != b)
        .count();
    assert!(
        changed > 50,
        "{name}: the deformation barely shows ({changed} pixels changed)"
    );
}

/// Every frame equals its reference byte for byte.
fn assert_frames_equal(frames: &[(TargetImage, TargetImage)], name: &str) {
    let mut failures = Vec::new();
    for (k, (hosted, reference)) in frames.iter().enumerate() {
        if hosted.bytes != reference.bytes {
            let max = hosted
                .bytes
                .iter()
                .zip(&reference.bytes)
                .map(|(a, b)| a.abs_diff(*b))
                .max();
            let pixels = hosted
                .bytes
                .chunks(4)
                .zip(reference.bytes.chunks(4))
                .filter(|(a, b)| a != b)
                .count();
            let at = format!("{name}_frame{k}");
            let dir = write_mismatch("embed-deform", &at, hosted, reference);
            failures.push(format!(
                "frame {k}: {pixels} pixels differ, by up to {max:?}/255 (images: {}/{at}_*.png)",
                dir.display()
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{name}: the deformed mesh's frames differ from the reference:\n{}",
        failures.join("\n")
    );
}

/// A style with history (`previous(...)`): the deformed frames go on from
/// the frames before, as the renderer's time-varying ocean does (a scene
/// change would restart the history and differ from frame 1 on).
#[test]
fn a_history_style_follows_the_deformed_mesh() {
    assert_equal(&ocean_frames("afterimage.npr"), "afterimage_ocean");
}

/// A compute pass over vertices (each object's projected vertices reduced
/// on the GPU to its screen centroid and extent, which place its dots):
/// its copy of the members' vertices follows the deformation. (On the
/// ocean the dots do not move: the sphere's shear moves them.)
#[test]
fn a_compute_pass_over_vertices_follows_the_deformed_mesh() {
    assert_equal(&squashed_frames("object_centroids.npr", false), "centroids_squash");
}

/// A `lines` pass finds its edges on the deformed mesh.
#[test]
fn lines_follow_the_deformed_ocean() {
    assert_equal(&ocean_frames("wavy_lines.npr"), "lines_ocean");
}

/// Age of Sail's shadow: the light camera is fitted to the deformed
/// caster's bounds, and normals and tangents made by the runtime equal
/// those of a mesh made from the same positions.
#[test]
fn shadows_follow_the_deformed_mesh() {
    assert_equal(&squashed_frames("age_of_sail.npr", false), "shadow_squash");
}

/// Lines on a mesh whose silhouette the deformation changes, the clock
/// stopped: the strips are built anew for the deformed mesh alone (the
/// waves' phase follows the time, which would rebuild them anyway).
#[test]
fn lines_follow_the_deformed_sphere() {
    assert_equal(&squashed_frames("wavy_lines.npr", true), "lines_squash");
}

fn expect_code(result: Result<(), EmbedError>, code: &str, what: &str) -> EmbedError {
    let e = result.expect_err(what);
    assert_eq!(e.code(), code, "{what}: {e}");
    let rendered = npr_diag::diagnostic::render(&e.diagnostics(), &npr_diag::SourceMap::new(), false);
    assert!(rendered.contains(&format!("error[{code}]")), "{what}: {rendered}");
    e
}

/// Mistakes are values with a code, never a panic, and leave the mesh as
/// it was: a removed handle (E0601); vertices that do not fit the mesh, a
/// number that is not finite, tangents for a mesh without them, the handle
/// of an animated primitive or of a patch (E0603).
#[test]
fn bad_updates_are_coded_errors_that_change_nothing() {
    let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, compile("toon.npr")).expect("runtime");
    let ball = runtime.add_mesh(primitives::sphere(1.0, 8, 4));
    let before = runtime.mesh(ball).expect("mesh").clone();
    let n = before.vertex_count();
    let positions = before.positions.clone();
    let normals = before.normals.clone();
    let tangents = before.tangents.clone().expect("a sphere has tangents");

    expect_code(
        runtime.update_mesh(ball, Deformed::positions(&positions[1..])),
        "E0603",
        "one position too few",
    );
    let more: Vec<[f32; 3]> = positions.iter().chain(&positions[..1]).copied().collect();
    expect_code(
        runtime.update_mesh(ball, Deformed::positions(&more)),
        "E0603",
        "one position too many",
    );
    expect_code(
        runtime.update_mesh(ball, Deformed::positions(&positions).with_normals(&normals[..n - 1])),
        "E0603",
        "normals too few",
    );
    expect_code(
        runtime.update_mesh(ball, Deformed::positions(&positions).with_tangents(&tangents[..n - 1])),
        "E0603",
        "tangents too few",
    );
    let mut nan = positions.clone();
    nan[3][1] = f32::NAN;
    let e = expect_code(
        runtime.update_mesh(ball, Deformed::positions(&nan)),
        "E0603",
        "a NaN position",
    );
    assert!(e.to_string().contains("vertex 3"), "the message names the vertex: {e}");
    let mut infinite = normals.clone();
    infinite[0][2] = f32::INFINITY;
    expect_code(
        runtime.update_mesh(ball, Deformed::positions(&positions).with_normals(&infinite)),
        "E0603",
        "an infinite normal",
    );
    let mut bad_tangent = tangents.clone();
    bad_tangent[1][3] = f32::NAN;
    expect_code(
        runtime.update_mesh(ball, Deformed::positions(&positions).with_tangents(&bad_tangent)),
        "E0603",
        "a NaN tangent",
    );
    assert!(
        Arc::ptr_eq(runtime.mesh(ball).expect("mesh"), &before),
        "a refused update changed the mesh"
    );

    // A mesh without UVs has no tangents to replace.
    let bare = runtime.add_mesh(Mesh::from_parts(
        positions.clone(),
        None,
        None,
        None,
        before.indices.clone(),
        "bare".into(),
    ));
    expect_code(
        runtime.update_mesh(bare, Deformed::positions(&positions).with_tangents(&tangents)),
        "E0603",
        "tangents for a mesh without UVs",
    );

    // The runtime makes these vertices itself.
    let sea = runtime.add_primitive(ocean());
    let waves = runtime.mesh(sea).expect("sea").positions.clone();
    expect_code(
        runtime.update_mesh(sea, Deformed::positions(&waves)),
        "E0603",
        "an animated primitive",
    );
    let patches = runtime
        .add_patches(Arc::new(primitives::sphere(1.0, 16, 8)), PatchSpec::Split(2), 1)
        .expect("patches");
    let patch_positions = runtime.mesh(patches[0]).expect("patch").positions.clone();
    expect_code(
        runtime.update_mesh(patches[0], Deformed::positions(&patch_positions)),
        "E0603",
        "a patch",
    );

    runtime.remove_mesh(ball).expect("remove");
    expect_code(
        runtime.update_mesh(ball, Deformed::positions(&positions)),
        "E0601",
        "a removed mesh",
    );

    // A good update is taken, with normals and tangents made from it.
    let bare_before = runtime.mesh(bare).expect("bare").clone();
    let stretched: Vec<[f32; 3]> = positions.iter().map(|p| [p[0] * 2.0, p[1], p[2]]).collect();
    runtime
        .update_mesh(bare, Deformed::positions(&stretched))
        .expect("a good update");
    let after = runtime.mesh(bare).expect("bare");
    assert_eq!(after.positions, stretched);
    assert_eq!(after.indices, bare_before.indices);
    assert_ne!(
        after.normals, bare_before.normals,
        "the normals follow the new positions"
    );
}

/// Frames after `update_mesh` create no GPU object (buffer, texture, bind
/// group, pipeline, ...): counted over a render style, a compute pass over
/// vertices, a `lines` pass, a history target and Age of Sail's shadow,
/// with two instances of the deformed mesh and a still one.
#[test]
fn frames_after_update_mesh_create_no_gpu_object() {
    for style in [
        "toon.npr",
        "object_centroids.npr",
        "wavy_lines.npr",
        "afterimage.npr",
        "age_of_sail.npr",
    ] {
        let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, compile(style)).expect("runtime");
        let rest = primitives::sphere(0.6, 24, 12);
        let ball: MeshHandle = runtime.add_mesh(rest.clone());
        let cube = runtime.add_mesh(primitives::cube(0.8));
        let objects = [
            Instance::new(ball, Mat4::from_translation(Vec3::new(-0.8, 0.0, 0.0))).with_tag("caster"),
            Instance::new(ball, Mat4::from_translation(Vec3::new(0.8, 0.0, 0.0))),
            Instance::new(cube, Mat4::from_translation(Vec3::new(0.0, -0.9, 0.0))),
        ];
        let mut scene = Scene::empty();
        scene.camera = Camera::looking_at(Vec3::new(0.0, 1.0, 4.0), Vec3::ZERO);
        let texture = host_target(WIDTH, HEIGHT, wgpu::TextureFormat::Rgba8Unorm, &[]);
        render(&mut runtime, &scene, &objects, (0, 0.0), &texture);
        gpu().device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
        let first = created_on_this_thread();
        for (k, &time_s) in TIMES.iter().enumerate().skip(1) {
            let positions = squash(&rest.positions, time_s);
            runtime
                .update_mesh(ball, Deformed::positions(&positions))
                .expect("update");
            render(&mut runtime, &scene, &objects, (k, time_s), &texture);
            // The host waits for each frame (a swapchain paces it): the
            // uniforms' staging buffer is back for the next one. Frames in
            // flight are the staging ring's: embed_frames_in_flight.rs.
            gpu().device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
        }
        let after = created_on_this_thread();
        assert_eq!(
            after, first,
            "{style}: deformed frames created GPU objects: {first:?} → {after:?}"
        );
        assert_no_rebuild(&runtime, style);
    }
}

/// A mesh whose vertices change every frame is a new content for a
/// `lines` pass's cache each frame: the edge meshes no eye draws any more
/// are dropped, so the cache stays bounded (it grew by one per frame).
#[test]
fn a_deforming_mesh_does_not_pile_up_edge_meshes() {
    use npr_runner::lines::cache::{EdgeSelection, LineObject, LinesCache};
    use npr_runner::lines::strip::LineStyle;
    let rest = primitives::sphere(0.8, 16, 8);
    let mut cache = LinesCache::default();
    let style = LineStyle {
        width_px: 2.0,
        amplitude_px: 0.0,
        wavelength_px: 16.0,
        phase: 0.0,
        taper: 0.0,
    };
    let selection = EdgeSelection {
        silhouettes: true,
        crease_deg: Some(40.0),
    };
    let view_proj = Camera::looking_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO)
        .pose(0.0)
        .projection(1.0)
        .as_dmat4()
        * Camera::looking_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO)
            .pose(0.0)
            .view(0)
            .as_dmat4();
    for frame in 0..60 {
        let mut mesh = rest.clone();
        for p in &mut mesh.positions {
            p[0] *= 1.0 + 0.01 * frame as f32;
        }
        let objects = [LineObject {
            mesh: &mesh,
            model: glam::DMat4::IDENTITY,
        }];
        cache.strips(
            0,
            &objects,
            glam::DVec3::new(0.0, 0.0, 4.0),
            view_proj,
            glam::DVec2::new(64.0, 64.0),
            &style,
            selection,
        );
    }
    assert_eq!(cache.mesh_builds, 60, "each deformed mesh is a new edge mesh");
    assert!(
        cache.edge_meshes() <= 10,
        "the cache kept {} edge meshes of one deforming mesh",
        cache.edge_meshes()
    );
}

/// `Renderer` (what `npr render` and the runtime drive) takes an object's
/// deformed copy of its mesh in place, and refuses (E0405, the renderer
/// left as it was) one that does not fit its buffers or objects sharing
/// one mesh's buffers given different meshes.
#[test]
fn the_renderer_refuses_a_mesh_that_does_not_fit() {
    let program = compile("toon.npr");
    let rest = Arc::new(primitives::sphere(0.6, 16, 8));
    let mut scene = Scene::empty();
    scene.camera = Camera::looking_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO);
    let left = Mat4::from_translation(Vec3::new(-0.7, 0.0, 0.0));
    let right = Mat4::from_translation(Vec3::new(0.7, 0.0, 0.0));
    scene.objects = vec![
        object("left", rest.clone(), left, &[], None),
        object("right", rest.clone(), right, &[], None),
    ];
    let mut renderer = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    renderer.render(&scene, &spec((0, 0.0))).expect("frame 0");
    let still = renderer.read_output().expect("output");

    let squashed = Arc::new(Mesh::from_parts(
        squash(&rest.positions, TIMES[3]),
        None,
        rest.uvs.clone(),
        None,
        rest.indices.clone(),
        "squashed".into(),
    ));
    let refused = |renderer: &mut Renderer, scene: &Scene, what: &str| {
        let e = renderer.render(scene, &spec((1, 0.0))).expect_err(what);
        assert_eq!(e.diagnostics()[0].code, "E0405", "{what}: {e:?}");
    };
    // One of two objects sharing the sphere's buffers: the other would
    // draw the squashed vertices too.
    let mut apart = scene.clone();
    apart.objects[0].mesh = squashed.clone();
    refused(&mut renderer, &apart, "objects of one mesh given different meshes");
    // Another vertex count.
    let mut other = scene.clone();
    let finer = Arc::new(primitives::sphere(0.6, 24, 12));
    other.objects[0].mesh = finer.clone();
    other.objects[1].mesh = finer;
    refused(&mut renderer, &other, "another vertex count");
    // Other triangles.
    let mut flipped = (*squashed).clone();
    flipped.indices.swap(0, 1);
    let flipped = Arc::new(flipped);
    let mut turned = scene.clone();
    turned.objects[0].mesh = flipped.clone();
    turned.objects[1].mesh = flipped;
    refused(&mut renderer, &turned, "other triangles");
    // Nothing changed: the still sphere renders as before.
    renderer.render(&scene, &spec((0, 0.0))).expect("the still sphere");
    assert_eq!(
        renderer.read_output().expect("output").bytes,
        still.bytes,
        "a refused mesh changed the renderer"
    );

    // Both objects given the squashed copy: written in place, as a renderer
    // built with it draws.
    let mut deformed = scene.clone();
    deformed.objects[0].mesh = squashed.clone();
    deformed.objects[1].mesh = squashed;
    renderer.render(&deformed, &spec((0, 0.0))).expect("the deformed copy");
    let mut fresh = Renderer::new(&gpu().device, &gpu().queue, &program, &deformed).expect("renderer");
    fresh.render(&deformed, &spec((0, 0.0))).expect("fresh");
    let (hosted, reference) = (
        renderer.read_output().expect("output"),
        fresh.read_output().expect("output"),
    );
    assert_ne!(hosted.bytes, still.bytes, "the squash does not show");
    assert_frames_equal(&[(hosted, reference)], "renderer_squash");
}

/// Two handles of one shared mesh (`add_shared_mesh` of one `Arc` twice)
/// are one mesh, drawn from the same GPU buffers: deforming one deforms
/// both, as a renderer given the deformed mesh for both draws.
#[test]
fn handles_of_one_shared_mesh_deform_together() {
    let program = compile("toon.npr");
    let rest = Arc::new(primitives::sphere(0.6, 16, 8));
    let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, program.clone()).expect("runtime");
    let first = runtime.add_shared_mesh(rest.clone());
    let second = runtime.add_shared_mesh(rest.clone());
    let left = Mat4::from_translation(Vec3::new(-0.7, 0.0, 0.0));
    let right = Mat4::from_translation(Vec3::new(0.7, 0.0, 0.0));
    let objects = [Instance::new(first, left), Instance::new(second, right)];
    let mut scene = Scene::empty();
    scene.camera = Camera::looking_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO);
    let texture = host_target(WIDTH, HEIGHT, wgpu::TextureFormat::Rgba8Unorm, &[]);
    present(&mut runtime, &scene, &objects, (0, 0.0), &texture);
    let positions = squash(&rest.positions, TIMES[3]);
    runtime
        .update_mesh(first, Deformed::positions(&positions))
        .expect("update");
    assert!(
        Arc::ptr_eq(
            runtime.mesh(first).expect("first"),
            runtime.mesh(second).expect("second")
        ),
        "the two handles of one mesh were deformed apart"
    );
    assert_eq!(runtime.mesh(second).expect("second").positions, positions);
    let hosted = present(&mut runtime, &scene, &objects, (1, 0.0), &texture);
    assert_no_rebuild(&runtime, "shared mesh");
    let squashed = Arc::new(Mesh::from_parts(
        positions,
        None,
        rest.uvs.clone(),
        None,
        rest.indices.clone(),
        "squashed".into(),
    ));
    scene.objects = vec![
        object("left", squashed.clone(), left, &[], None),
        object("right", squashed, right, &[], None),
    ];
    let mut fresh = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    fresh.render(&scene, &spec((1, 0.0))).expect("render");
    assert_frames_equal(&[(hosted, fresh.read_output().expect("output"))], "shared_squash");
}
