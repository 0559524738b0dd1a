//! After the first frame, a frame of a `StyleRuntime` creates no GPU object
//! (buffer, texture, view, sampler, bind group, layout, pipeline, shader,
//! render bundle)
//! unless the size, the style or the set of objects changes: counted by
//! `npr_runner::gpu_count`, through which the runner makes every one (its
//! `clippy.toml` refuses the uncounted wgpu calls). The frames move the
//! objects and the camera, change per-object and style params and advance
//! the time; then an object is added (the scene-level resources made
//! anew, allowed; `embed_scene_change.rs` counts that frame) and the frames
//! after it are counted again, then the size changes. Over examples with a
//! render and image passes, a compute pass, a lines pass, a history
//! (previous-frame) target and Age of Sail's seven passes; the animated
//! ocean, whose vertex buffers every frame rewrites in place; styles over a
//! host's inputs, one of them with lines tested against the host's depth.

#![allow(clippy::disallowed_methods)]

mod common;
use common::{compile, gpu, host_target, read_host, render_frame};

use npr_runner::embed::{Frame, Instance, Lights, MeshHandle, StyleRuntime, Target};
use npr_runner::gpu_count::created_on_this_thread;
use npr_runner::scene::ocean::Ocean;
use npr_runner::scene::{primitives, Camera, Primitive};
use std::path::Path;

fn target(width: u32, height: u32) -> wgpu::Texture {
    host_target(width, height, wgpu::TextureFormat::Bgra8Unorm, &[])
}

/// A per-object param the frames change, and its components.
type Param = Option<(&'static str, usize)>;

/// The host's objects at frame `k`: they move, and a per-object param changes.
fn objects(meshes: &[MeshHandle], k: u32, tags: &[&str], param: Param) -> Vec<Instance> {
    meshes
        .iter()
        .enumerate()
        .map(|(i, &mesh)| {
            let x = i as f32 * 1.5 - 0.75 + 0.05 * k as f32;
            let mut o = Instance::new(
                mesh,
                glam::Mat4::from_translation(glam::Vec3::new(x, 0.0, 0.0))
                    * glam::Mat4::from_rotation_y(0.1 * k as f32),
            );
            for t in tags {
                o = o.with_tag(t);
            }
            if let Some((p, components)) = param {
                o = o.with_param(p, &vec![0.5 + 0.05 * f64::from(k); components]);
            }
            o
        })
        .collect()
}

/// Render frame `k` of `instances` at `view`'s size, submit, and wait.
fn frame(runtime: &mut StyleRuntime, instances: &[Instance], k: u32, view: &wgpu::TextureView) {
    let camera = Camera::looking_at(
        glam::Vec3::new(0.2 * (k as f32 * 0.1).sin(), 1.0, 4.0),
        glam::Vec3::ZERO,
    );
    let lights = Lights::default();
    let frame = Frame {
        camera: &camera,
        objects: instances,
        lights: &lights,
        time_s: f64::from(k) / 24.0,
        frame_index: k,
        eye: 0,
    };
    render_frame(runtime, &frame, Target::View(view)).unwrap_or_else(|e| panic!("frame {k}: {:?}", e.diagnostics()));
    gpu().device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
}

/// Frames `from..to` create nothing once frame `from - 1` was rendered.
fn steady(
    runtime: &mut StyleRuntime,
    meshes: &[MeshHandle],
    tags: &[&str],
    param: Param,
    frames: std::ops::Range<u32>,
    view: &wgpu::TextureView,
    what: &str,
) {
    let before = created_on_this_thread();
    let builds = runtime.builds();
    for k in frames {
        frame(runtime, &objects(meshes, k, tags, param), k, view);
    }
    let after = created_on_this_thread();
    assert_eq!(
        after, before,
        "{what}: frames created GPU objects: {before:?} → {after:?}"
    );
    assert_eq!(runtime.builds(), builds, "{what}: frames rebuilt the scene");
}

/// The whole sequence for one example.
fn check(example: &str, tags: &[&str], object_param: Param, style_param: Option<(&str, &str)>) {
    let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, compile(example)).expect("runtime");
    let sphere = runtime.add_mesh(primitives::sphere(0.6, 24, 12));
    let cube = runtime.add_mesh(primitives::cube(0.8));
    let texture = target(64, 48);
    let view = texture.create_view(&Default::default());
    let mut meshes = vec![sphere, cube];
    frame(&mut runtime, &objects(&meshes, 0, tags, object_param), 0, &view);
    let first = created_on_this_thread();
    assert!(
        first.pipelines > 0,
        "{example}: the first frame built no pipeline: {first:?}"
    );
    steady(&mut runtime, &meshes, tags, object_param, 1..6, &view, example);
    if let Some((name, value)) = style_param {
        runtime
            .set_param(name, value)
            .unwrap_or_else(|e| panic!("{:?}", e.diagnostics()));
        steady(
            &mut runtime,
            &meshes,
            tags,
            object_param,
            6..8,
            &view,
            &format!("{example} after set_param"),
        );
    }
    // A third object: scene-level resources are made anew, then steady again.
    meshes.push(sphere);
    frame(&mut runtime, &objects(&meshes, 8, tags, object_param), 8, &view);
    steady(
        &mut runtime,
        &meshes,
        tags,
        object_param,
        9..12,
        &view,
        &format!("{example} with an object added"),
    );
    // And removed again.
    meshes.pop();
    frame(&mut runtime, &objects(&meshes, 12, tags, object_param), 12, &view);
    steady(
        &mut runtime,
        &meshes,
        tags,
        object_param,
        13..15,
        &view,
        &format!("{example} with the object removed"),
    );
    // A new size: the targets are made anew, then steady again.
    let bigger = target(80, 60);
    let bigger_view = bigger.create_view(&Default::default());
    frame(
        &mut runtime,
        &objects(&meshes, 15, tags, object_param),
        15,
        &bigger_view,
    );
    steady(
        &mut runtime,
        &meshes,
        tags,
        object_param,
        16..19,
        &bigger_view,
        &format!("{example} at a new size"),
    );
}

#[test]
fn toon_frames_allocate_nothing() {
    check("toon.npr", &[], Some(("tint", 4)), Some(("bands", "5")));
}

#[test]
fn a_compute_style_allocates_nothing_per_frame() {
    check("object_centroids.npr", &[], None, None);
}

#[test]
fn a_lines_style_allocates_nothing_per_frame() {
    check("wavy_lines.npr", &[], None, None);
}

#[test]
fn a_history_style_allocates_nothing_per_frame() {
    check("afterimage.npr", &[], None, Some(("persistence", "0.5")));
}

#[test]
fn age_of_sail_allocates_nothing_per_frame() {
    check("age_of_sail.npr", &[], Some(("breakup", 1)), Some(("warp_px", "6px")));
}

/// A host's own animated ocean (`add_primitive`, Age of Sail §6.1): each
/// frame rebuilds its vertices at the frame's time and writes them over
/// its vertex buffers in place, creating nothing.
#[test]
fn an_animated_ocean_allocates_nothing_per_frame() {
    let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, compile("ocean.npr")).expect("runtime");
    let ocean = Ocean {
        cells: 16,
        tiles: 3,
        modes: 8,
        ring: 400.0,
        ..Ocean::default()
    };
    let sea = runtime.add_primitive(Primitive::Ocean(ocean));
    let instances = [Instance::new(sea, glam::Mat4::IDENTITY)];
    let texture = target(64, 48);
    let view = texture.create_view(&Default::default());
    frame(&mut runtime, &instances, 0, &view);
    let before = created_on_this_thread();
    assert!(before.pipelines > 0, "the first frame built no pipeline: {before:?}");
    for k in 1..8 {
        frame(&mut runtime, &instances, k, &view);
    }
    let after = created_on_this_thread();
    assert_eq!(
        after, before,
        "the ocean's frames created GPU objects: {before:?} → {after:?}"
    );
    assert_eq!(runtime.builds(), 1, "the ocean's frames rebuilt the scene");
}

/// A TOML scene is the same structure: its objects become instances
/// (shared meshes registered once), and the runtime renders it as
/// `Renderer` does, pixel for pixel.
#[test]
fn a_toml_scene_renders_through_the_runtime_as_through_the_renderer() {
    toml_scene_through_the_runtime("toon.npr", "spheres.toml");
}

/// Age of Sail on its scene: every object binds its own painted `lit_map`
/// and `shadow_map`, which instances carry (without them the runtime drew
/// the style's default images, unlike `npr render`).
#[test]
fn per_object_images_render_through_the_runtime_as_through_the_renderer() {
    toml_scene_through_the_runtime("age_of_sail.npr", "age_of_sail.toml");
}

/// The walker's glTF material (its base colour texture and factor,
/// decision 0058) reaches the runtime's instances through `add_scene`, as
/// it reaches `npr render`'s objects: `age_of_sail.npr` tints its paint by
/// `base_color_map × base_color`, and the two frames are equal byte for byte.
#[test]
fn gltf_materials_render_through_the_runtime_as_through_the_renderer() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/scenes/walker.toml");
    let scene = npr_runner::scene::load_scene(&path, &mut npr_diag::SourceMap::new()).expect("scene");
    let material = scene.objects[0].material.as_ref().expect("the walker has a material");
    assert!(material.base_color_map.is_some(), "the walker's material has a texture");
    toml_scene_through_the_runtime("age_of_sail.npr", "walker.toml");
}

fn toml_scene_through_the_runtime(style: &str, scene_file: &str) {
    let program = compile(style);
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../examples/scenes")
        .join(scene_file);
    let scene = npr_runner::scene::load_scene(&path, &mut npr_diag::SourceMap::new()).expect("scene");
    let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, program.clone()).expect("runtime");
    let instances = runtime.add_scene(&scene);
    assert_eq!(instances.len(), scene.objects.len());
    let lights = Lights {
        key: scene.light,
        more: scene.more_lights,
    };
    let frame = Frame {
        camera: &scene.camera,
        objects: &instances,
        lights: &lights,
        time_s: 0.0,
        frame_index: 0,
        eye: 0,
    };
    let texture = host_target(64, 48, wgpu::TextureFormat::Rgba8Unorm, &[]);
    render_frame(
        &mut runtime,
        &frame,
        Target::View(&texture.create_view(&Default::default())),
    )
    .unwrap_or_else(|e| panic!("{:?}", e.diagnostics()));
    let presented = read_host(&texture);
    let direct =
        npr_runner::render_frame(gpu(), &program, &scene, &npr_runner::FrameSpec::still(64, 48, 0)).expect("render");
    assert_eq!(direct.format, npr_abi::Format::Rgba8unorm);
    assert_eq!(
        presented.bytes, direct.bytes,
        "the host's view differs from npr render's output"
    );
}

/// A view of a host texture of `format` at `size`, which a style may read
/// as an input.
fn host_view(format: wgpu::TextureFormat, (width, height): (u32, u32)) -> wgpu::TextureView {
    gpu()
        .device
        .create_texture(&wgpu::TextureDescriptor {
            label: Some("host image"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        })
        .create_view(&Default::default())
}

/// Frames `frames` at `size` over new host images of `formats`, which
/// `give` hands to the runtime again before each frame, with `instances(k)`
/// drawn: the first frame makes what the size needs, the others create no
/// GPU object.
fn steady_over_inputs(
    runtime: &mut StyleRuntime,
    formats: &[wgpu::TextureFormat],
    give: &dyn Fn(&mut StyleRuntime, &[wgpu::TextureView]),
    instances: &dyn Fn(u32) -> Vec<Instance>,
    frames: std::ops::Range<u32>,
    size: (u32, u32),
    what: &str,
) {
    let inputs: Vec<wgpu::TextureView> = formats.iter().map(|&f| host_view(f, size)).collect();
    let texture = target(size.0, size.1);
    let view = texture.create_view(&Default::default());
    give(runtime, &inputs);
    frame(runtime, &instances(frames.start), frames.start, &view);
    let before = created_on_this_thread();
    for k in frames.start + 1..frames.end {
        give(runtime, &inputs);
        frame(runtime, &instances(k), k, &view);
    }
    let after = created_on_this_thread();
    assert_eq!(
        after, before,
        "{what}: frames created GPU objects: {before:?} → {after:?}"
    );
}

/// A style over a host's G-buffer (`examples/post/ink_over.npr`): each frame
/// the host gives its colour, reverse-Z depth and world normals again (the
/// same views) and the camera moves, so the normals' conversion into view
/// space changes every frame; converting them creates nothing. A new size
/// (new views, a new target) makes the input textures anew, then steady again.
#[test]
fn a_style_over_host_inputs_allocates_nothing_per_frame() {
    use npr_runner::inputs::{ColorEncoding, DepthConvention, NormalConvention, SourceConvention};
    let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, compile("post/ink_over.npr")).expect("runtime");
    let formats = [
        wgpu::TextureFormat::Rgba16Float,
        wgpu::TextureFormat::Depth32Float,
        wgpu::TextureFormat::Rgba16Float,
    ];
    let give = |runtime: &mut StyleRuntime, views: &[wgpu::TextureView]| {
        let [colour, depth, normal] = views else {
            panic!("three host images")
        };
        runtime
            .set_input("color_in", colour, SourceConvention::Color(ColorEncoding::Linear))
            .expect("colour");
        runtime
            .set_input(
                "depth_in",
                depth,
                SourceConvention::Depth(DepthConvention::ReverseZ { near: 0.1 }),
            )
            .expect("depth");
        runtime
            .set_input("normal_in", normal, SourceConvention::Normal(NormalConvention::World))
            .expect("normal");
    };
    let no_objects = |_| Vec::new();
    let what = "ink over inputs";
    steady_over_inputs(&mut runtime, &formats, &give, &no_objects, 0..6, (64, 48), what);
    let what = "ink over inputs at a new size";
    steady_over_inputs(&mut runtime, &formats, &give, &no_objects, 6..10, (80, 60), what);
    assert_eq!(runtime.builds(), 1, "the frames rebuilt the style");
}

/// npr's own lines hidden behind a host's depth (`examples/post/lines_over.npr`,
/// `depth: test(depth_in)`, decision 0057): each frame the host gives its
/// colour and depth again, the objects and the camera move, and the
/// host-depth draw turns the depth input into a depth buffer through the
/// frame's projection, creating nothing. A new size makes the input
/// textures and that depth buffer anew, then steady again.
#[test]
fn lines_tested_against_a_host_depth_allocate_nothing_per_frame() {
    use npr_runner::inputs::{ColorEncoding, DepthConvention, SourceConvention};
    let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, compile("post/lines_over.npr")).expect("runtime");
    let meshes = [
        runtime.add_mesh(primitives::sphere(0.6, 24, 12)),
        runtime.add_mesh(primitives::cube(0.8)),
    ];
    let formats = [wgpu::TextureFormat::Rgba8Unorm, wgpu::TextureFormat::Depth32Float];
    let give = |runtime: &mut StyleRuntime, views: &[wgpu::TextureView]| {
        let [colour, depth] = views else {
            panic!("two host images")
        };
        runtime
            .set_input("color_in", colour, SourceConvention::Color(ColorEncoding::Srgb))
            .expect("colour");
        runtime
            .set_input(
                "depth_in",
                depth,
                SourceConvention::Depth(DepthConvention::ReverseZ { near: 0.1 }),
            )
            .expect("depth");
    };
    let moving = |k| objects(&meshes, k, &[], None);
    let what = "lines over a host's depth";
    steady_over_inputs(&mut runtime, &formats, &give, &moving, 0..6, (64, 48), what);
    let what = "lines over a host's depth at a new size";
    steady_over_inputs(&mut runtime, &formats, &give, &moving, 6..10, (80, 60), what);
    assert_eq!(runtime.builds(), 1, "the frames rebuilt the style");
}

/// A host's skinned mesh (`add_skinned_mesh`) drawn as three instances
/// with poses of their own, new every frame (joint matrices and a morph
/// weight): the poses are written over buffers made with the scene, and
/// the GPU stage deforms each instance into its own vertex buffers,
/// creating nothing. Over a plain style and a `lines` style (whose edges
/// the CPU makes from the same poses each frame).
#[test]
fn posed_skinned_instances_allocate_nothing_per_frame() {
    use npr_runner::embed::{SkinPose, Skinning};
    for example in ["toon.npr", "wavy_lines.npr"] {
        let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, compile(example)).expect("runtime");
        // A tall box, its upper half bound to joint 1, its lower to joint 0.
        let body = primitives::cube(0.6);
        let joints = body
            .positions
            .iter()
            .map(|p| if p[1] > 0.0 { [1, 0, 0, 0] } else { [0; 4] })
            .collect();
        let stretch = npr_runner::scene::rig::MorphTarget {
            positions: body.positions.iter().map(|p| [p[0] * 0.3, 0.0, p[2] * 0.3]).collect(),
            normals: None,
            tangents: None,
        };
        let skinning = Skinning {
            joint_count: 2,
            weights: vec![[1.0, 0.0, 0.0, 0.0]; body.vertex_count()],
            joints,
            morph_targets: vec![stretch],
        };
        let handle = runtime.add_skinned_mesh(body, skinning).expect("a good skin");
        let mut instances: Vec<Instance> = (0..3)
            .map(|i| {
                Instance::new(handle, glam::Mat4::from_translation(glam::Vec3::X * (i as f32 - 1.0)))
                    .with_pose(SkinPose::bind(2, 1))
            })
            .collect();
        let pose = |instances: &mut [Instance], k: u32| {
            for (i, instance) in instances.iter_mut().enumerate() {
                let pose = instance.pose.as_mut().expect("posed");
                let angle = 0.2 * k as f32 + i as f32;
                pose.joints[1] = glam::Mat4::from_rotation_z(0.5 * angle.sin());
                pose.morph_weights[0] = 0.5 + 0.5 * angle.cos();
            }
        };
        let texture = target(64, 48);
        let view = texture.create_view(&Default::default());
        pose(&mut instances, 0);
        frame(&mut runtime, &instances, 0, &view);
        let before = created_on_this_thread();
        for k in 1..8 {
            pose(&mut instances, k);
            frame(&mut runtime, &instances, k, &view);
        }
        let after = created_on_this_thread();
        assert_eq!(
            after, before,
            "{example}: frames of new poses created GPU objects: {before:?} → {after:?}"
        );
        assert_eq!(runtime.builds(), 1, "{example}: the posed frames rebuilt the scene");
        assert_eq!(runtime.scene_changes(), 0, "{example}: a new pose is no scene change");
    }
}
