//! The host codes (E06xx) and the parameter codes a host's
//! `StyleRuntime::set_param` gives: mistakes of an application embedding a
//! style (`npr_runner::embed`), as error values, rendered.

use super::{check, check_case, style, SIMPLE_PASS};
use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use npr_runner::embed::{Deformed, EmbedError, Frame, Instance, Lights, SkinPose, Skinning, StyleRuntime, Target};
use npr_runner::inputs::{ColorEncoding, DepthConvention, SourceConvention};
use npr_runner::scene::{primitives, Camera};
use std::path::Path;
use std::sync::OnceLock;

fn gpu() -> &'static npr_runner::Gpu {
    static GPU: OnceLock<npr_runner::Gpu> = OnceLock::new();
    GPU.get_or_init(|| {
        npr_runner::Gpu::headless().unwrap_or_else(|e| {
            panic!("these cases need a GPU adapter (Mesa's lavapipe: apt-get install mesa-vulkan-drivers): {e}")
        })
    })
}

/// A runtime of `text`, compiled with its params kept.
fn runtime(text: &str) -> StyleRuntime {
    let mut sources = SourceMap::new();
    let options = CompileOptions {
        keep_params: true,
        ..Default::default()
    };
    let compiled = npr_compiler::compile_source("case.npr", text, Path::new("."), &mut sources, &options)
        .unwrap_or_else(|e| panic!("{e:?}"));
    StyleRuntime::new(&gpu().device, &gpu().queue, compiled.program()).unwrap_or_else(|e| panic!("{e}"))
}

fn rendered(e: EmbedError) -> (Vec<npr_diag::Diagnostic>, String) {
    let d = e.diagnostics();
    let r = npr_diag::diagnostic::render(&d, &SourceMap::new(), false);
    (d, r)
}

fn texture(format: wgpu::TextureFormat) -> wgpu::Texture {
    gpu().device.create_texture(&wgpu::TextureDescriptor {
        label: None,
        size: wgpu::Extent3d {
            width: 16,
            height: 16,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        view_formats: &[],
    })
}

/// Render one frame of `objects` into `view`.
fn render(runtime: &mut StyleRuntime, objects: &[Instance], view: &wgpu::TextureView) -> Result<(), EmbedError> {
    let camera = Camera::looking_at(glam::Vec3::new(0.0, 0.0, 3.0), glam::Vec3::ZERO);
    render_with(runtime, objects, view, &camera)
}

/// Render one frame of `objects` into `view`, seen by `camera`.
fn render_with(
    runtime: &mut StyleRuntime,
    objects: &[Instance],
    view: &wgpu::TextureView,
    camera: &Camera,
) -> Result<(), EmbedError> {
    let lights = Lights::default();
    let frame = Frame {
        camera,
        objects,
        lights: &lights,
        time_s: 0.0,
        frame_index: 0,
        eye: 0,
    };
    let mut encoder = gpu().device.create_command_encoder(&Default::default());
    let result = runtime.render(&mut encoder, &frame, Target::View(view));
    gpu().queue.submit([encoder.finish()]);
    result
}

#[test]
fn e0601_a_mesh_used_after_it_was_removed() {
    let mut rt = runtime(&style(SIMPLE_PASS));
    let ball = rt.add_mesh(primitives::sphere(0.5, 8, 4));
    rt.remove_mesh(ball).expect("remove");
    // A new mesh may take the slot: the old handle still names nothing.
    let _cube = rt.add_mesh(primitives::cube(1.0));
    let target = texture(wgpu::TextureFormat::Rgba8Unorm);
    let e = render(
        &mut rt,
        &[Instance::new(ball, glam::Mat4::IDENTITY)],
        &target.create_view(&Default::default()),
    )
    .expect_err("a removed mesh");
    assert!(matches!(e, EmbedError::UnknownMesh(_)), "{e:?}");
    check("E0601", rendered(e));
}

#[test]
fn e0602_a_texture_view_of_the_wrong_format() {
    let mut rt = runtime(&style(SIMPLE_PASS));
    let ball = rt.add_mesh(primitives::sphere(0.5, 8, 4));
    let objects = [Instance::new(ball, glam::Mat4::IDENTITY)];
    let srgb = texture(wgpu::TextureFormat::Rgba8UnormSrgb);
    let e = render(&mut rt, &objects, &srgb.create_view(&Default::default())).expect_err("an sRGB view");
    check("E0602", rendered(e));
    let depth = texture(wgpu::TextureFormat::Depth32Float);
    let e = render(&mut rt, &objects, &depth.create_view(&Default::default())).expect_err("a depth view");
    check_case("E0602", "E0602_depth", rendered(e));
    // A mono style has no second eye for a side-by-side view.
    let plain = texture(wgpu::TextureFormat::Rgba8Unorm);
    let view = plain.create_view(&Default::default());
    let camera = Camera::looking_at(glam::Vec3::new(0.0, 0.0, 3.0), glam::Vec3::ZERO);
    let lights = Lights::default();
    let frame = Frame {
        camera: &camera,
        objects: &objects,
        lights: &lights,
        time_s: 0.0,
        frame_index: 0,
        eye: 0,
    };
    let mut encoder = gpu().device.create_command_encoder(&Default::default());
    let e = rt
        .render(&mut encoder, &frame, Target::SideBySide(&view))
        .expect_err("side by side of a mono style");
    check_case("E0602", "E0602_side_by_side", rendered(e));
}

#[test]
fn e0603_deformed_vertices_that_do_not_fit_the_mesh() {
    let mut rt = runtime(&style(SIMPLE_PASS));
    let ball = rt.add_mesh(primitives::sphere(0.5, 8, 4));
    let positions = rt.mesh(ball).expect("the mesh").positions.clone();
    // One vertex short: another mesh, not a deformation of this one.
    let e = rt
        .update_mesh(ball, Deformed::positions(&positions[1..]))
        .expect_err("too few positions");
    assert!(matches!(e, EmbedError::MeshUpdate(_)), "{e:?}");
    check("E0603", rendered(e));
}

#[test]
fn set_param_mistakes_are_the_codes_of_set() {
    let text = style(
        "param bands: int = 3 in 1..8\nparam width: px = 2px in 0px..16px\n\
         pass p: render(scene) {\n  out color: rgba8unorm = vec4(toon(lambert(normal, light.dir), steps: bands), width / 16px, 0.0, 1.0)\n}\noutput p.color\n",
    );
    let mut rt = runtime(&text);
    rt.set_param("bands", "5").expect("a good value");
    rt.set_param("width", "50%").expect("a % of the height");
    check_case(
        "E0101",
        "E0101_set_param",
        rendered(rt.set_param("bnads", "5").expect_err("no such param")),
    );
    check_case(
        "E0201",
        "E0201_set_param",
        rendered(rt.set_param("bands", "2.5").expect_err("not an int")),
    );
    check_case(
        "E0202",
        "E0202_set_param",
        rendered(rt.set_param("width", "2m").expect_err("not px")),
    );
    check_case(
        "E0203",
        "E0203_set_param",
        rendered(rt.set_param("bands", "9").expect_err("out of range")),
    );
}

/// A style over a colour and a depth input.
const INPUTS: &str = "texture c = input(color, linear)\ntexture z = input(depth)\n\
    pass p: image() {\n  out o: rgba8unorm = vec4(c.rgb * z.r, 1.0)\n}\noutput p.o\n";

/// A host's image of `size`, `format`, sampled by the style.
fn host_image(format: wgpu::TextureFormat, (width, height): (u32, u32)) -> wgpu::Texture {
    gpu().device.create_texture(&wgpu::TextureDescriptor {
        label: None,
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
}

const LINEAR: SourceConvention = SourceConvention::Color(ColorEncoding::Linear);
const DISTANCE: SourceConvention = SourceConvention::Depth(DepthConvention::CYCLES);

#[test]
fn e0604_an_input_the_style_does_not_have() {
    let mut rt = runtime(&style(INPUTS));
    let colour = host_image(wgpu::TextureFormat::Rgba16Float, (16, 16));
    let e = rt
        .set_input("colour", &colour.create_view(&Default::default()), LINEAR)
        .expect_err("no such input");
    let (d, r) = rendered(e);
    assert!(
        r.contains("did you mean `c`?") || r.contains("the style's inputs are: c, z"),
        "{r}"
    );
    check("E0604", (d, r));
}

#[test]
fn e0605_a_view_or_convention_the_input_cannot_be_read_from() {
    let mut rt = runtime(&style(INPUTS));
    // A depth image described as colour.
    let depth = host_image(wgpu::TextureFormat::R32Float, (16, 16));
    let e = rt
        .set_input("z", &depth.create_view(&Default::default()), LINEAR)
        .expect_err("colour convention for depth");
    check("E0605", rendered(e));
    // An integer format, which the GPU does not read as floats.
    let ids = host_image(wgpu::TextureFormat::R32Uint, (16, 16));
    let e = rt
        .set_input("z", &ids.create_view(&Default::default()), DISTANCE)
        .expect_err("an integer format");
    check_case("E0605", "E0605_integer_format", rendered(e));
    // An sRGB texture said to hold sRGB values: the GPU decodes it when read.
    let srgb = host_image(wgpu::TextureFormat::Rgba8UnormSrgb, (16, 16));
    let e = rt
        .set_input(
            "c",
            &srgb.create_view(&Default::default()),
            SourceConvention::Color(ColorEncoding::Srgb),
        )
        .expect_err("sRGB twice");
    check_case("E0605", "E0605_srgb", rendered(e));
}

#[test]
fn e0606_inputs_of_another_size_than_the_target() {
    let mut rt = runtime(&style(INPUTS));
    let colour = host_image(wgpu::TextureFormat::Rgba16Float, (16, 16));
    let depth = host_image(wgpu::TextureFormat::R32Float, (8, 8));
    rt.set_input("c", &colour.create_view(&Default::default()), LINEAR)
        .expect("colour");
    rt.set_input("z", &depth.create_view(&Default::default()), DISTANCE)
        .expect("depth");
    let target = texture(wgpu::TextureFormat::Rgba8Unorm);
    let e = render(&mut rt, &[], &target.create_view(&Default::default())).expect_err("8x8 depth, 16x16 target");
    let (d, r) = rendered(e);
    assert!(r.contains("`z`") && r.contains("8x8") && r.contains("16x16"), "{r}");
    check("E0606", (d, r));
}

#[test]
fn e0607_an_input_the_host_did_not_give() {
    let mut rt = runtime(&style(INPUTS));
    let colour = host_image(wgpu::TextureFormat::Rgba16Float, (16, 16));
    rt.set_input("c", &colour.create_view(&Default::default()), LINEAR)
        .expect("colour");
    let target = texture(wgpu::TextureFormat::Rgba8Unorm);
    let e = render(&mut rt, &[], &target.create_view(&Default::default())).expect_err("no depth given");
    check("E0607", rendered(e));
}

/// A box of two joints (its lower half follows joint 0, its upper joint 1)
/// and, with `targets`, as many morph targets lifting it.
fn skinned_box(targets: usize) -> (npr_runner::scene::Mesh, Skinning) {
    let cube = primitives::cube(0.8);
    let joints = cube
        .positions
        .iter()
        .map(|p| if p[1] > 0.0 { [1, 0, 0, 0] } else { [0; 4] })
        .collect();
    let weights = vec![[1.0, 0.0, 0.0, 0.0]; cube.vertex_count()];
    let lift = npr_runner::scene::rig::MorphTarget {
        positions: vec![[0.0, 0.2, 0.0]; cube.vertex_count()],
        normals: None,
        tangents: None,
    };
    let skinning = Skinning {
        joint_count: 2,
        joints,
        weights,
        morph_targets: vec![lift; targets],
    };
    (cube, skinning)
}

/// Render one frame of `pose` on a skinned box (two joints, `targets` morph targets).
fn render_pose(targets: usize, pose: SkinPose) -> EmbedError {
    let mut rt = runtime(&style(SIMPLE_PASS));
    let (mesh, skinning) = skinned_box(targets);
    let boxed = rt.add_skinned_mesh(mesh, skinning).expect("a good skin");
    let target = texture(wgpu::TextureFormat::Rgba8Unorm);
    let view = target.create_view(&Default::default());
    // The bind pose renders: the mistakes below are the pose's.
    let good = [Instance::new(boxed, glam::Mat4::IDENTITY).with_pose(SkinPose::bind(2, targets))];
    render(&mut rt, &good, &view).expect("the bind pose");
    render(
        &mut rt,
        &[Instance::new(boxed, glam::Mat4::IDENTITY).with_pose(pose)],
        &view,
    )
    .expect_err("a bad pose")
}

#[test]
fn e0612_a_pose_of_other_joints_than_the_skin() {
    let e = render_pose(0, SkinPose::bind(3, 0));
    assert!(matches!(e, EmbedError::Skin(_)), "{e:?}");
    check("E0612", rendered(e));
    // A pose for a mesh registered without a skin.
    let mut rt = runtime(&style(SIMPLE_PASS));
    let ball = rt.add_mesh(primitives::sphere(0.5, 8, 4));
    let target = texture(wgpu::TextureFormat::Rgba8Unorm);
    let e = render(
        &mut rt,
        &[Instance::new(ball, glam::Mat4::IDENTITY)
            .with_id(7)
            .with_pose(SkinPose::bind(2, 0))],
        &target.create_view(&Default::default()),
    )
    .expect_err("a pose for a rigid mesh");
    check_case("E0612", "E0612_no_skin", rendered(e));
}

#[test]
fn e0613_a_pose_that_is_not_finite() {
    let mut pose = SkinPose::bind(2, 1);
    pose.joints[1] = glam::Mat4::from_scale(glam::Vec3::ZERO).inverse();
    let e = render_pose(1, pose);
    check("E0613", rendered(e));
    let mut pose = SkinPose::bind(2, 1);
    pose.morph_weights[0] = f32::NAN;
    check_case("E0613", "E0613_weight", rendered(render_pose(1, pose)));
}

#[test]
fn e0614_morph_weights_of_other_targets_than_the_mesh() {
    let e = render_pose(2, SkinPose::bind(2, 1));
    check("E0614", rendered(e));
}

#[test]
fn e0615_a_skin_that_does_not_fit_its_mesh() {
    let mut rt = runtime(&style(SIMPLE_PASS));
    let (mesh, mut skinning) = skinned_box(0);
    skinning.weights[0] = [0.0; 4];
    let e = rt
        .add_skinned_mesh(mesh.clone(), skinning)
        .expect_err("weights summing to 0");
    assert!(matches!(e, EmbedError::Skin(_)), "{e:?}");
    check("E0615", rendered(e));
    let (_, mut skinning) = skinned_box(0);
    skinning.joints[3] = [2, 0, 0, 0];
    check_case(
        "E0615",
        "E0615_joint",
        rendered(
            rt.add_skinned_mesh(mesh.clone(), skinning)
                .expect_err("a joint past the skin's"),
        ),
    );
    let (_, mut skinning) = skinned_box(1);
    skinning.morph_targets[0].positions.pop();
    check_case(
        "E0615",
        "E0615_morph",
        rendered(rt.add_skinned_mesh(mesh, skinning).expect_err("a short morph target")),
    );
    assert_eq!(rt.mesh_count(), 0, "a refused skin registers nothing");
}

#[test]
fn e0616_a_camera_whose_projection_cannot_be_drawn_with() {
    let mut rt = runtime(&style(SIMPLE_PASS));
    let target = texture(wgpu::TextureFormat::Rgba8Unorm);
    let view = target.create_view(&Default::default());
    let mut camera = Camera::looking_at(glam::Vec3::new(0.0, 0.0, 3.0), glam::Vec3::ZERO);
    camera.near = 0.0;
    let (d, r) = rendered(render_with(&mut rt, &[], &view, &camera).expect_err("a zero near plane"));
    assert!(r.contains("near plane is at 0 m"), "{r}");
    check("E0616", (d, r));
    // A field of view of 0 or π: no perspective projection (`camera.focal`
    // would be infinite or 0), and the frame is refused, not drawn.
    for fov in [0.0, std::f32::consts::PI, f32::NAN] {
        let mut camera = Camera::looking_at(glam::Vec3::new(0.0, 0.0, 3.0), glam::Vec3::ZERO);
        camera.fov_y_rad = fov;
        let e = render_with(&mut rt, &[], &view, &camera).expect_err("no perspective");
        assert_eq!(e.code(), "E0616", "fov {fov}: {e}");
    }
    // An orthographic camera (decision 0062) needs a positive height, a
    // finite far plane and no stereo eyes; its field of view is unused.
    for (height, far, ipd) in [(0.0, 50.0, None), (2.0, f32::INFINITY, None), (2.0, 50.0, Some(0.06))] {
        let mut camera = Camera::looking_at(glam::Vec3::new(0.0, 0.0, 3.0), glam::Vec3::ZERO);
        (camera.ortho_height_m, camera.far, camera.ipd_m, camera.fov_y_rad) = (Some(height), far, ipd, 0.0);
        let e = render_with(&mut rt, &[], &view, &camera).expect_err("a bad orthographic camera");
        assert_eq!(e.code(), "E0616", "height {height}, far {far}, ipd {ipd:?}: {e}");
    }
    let mut camera = Camera::looking_at(glam::Vec3::new(0.0, 0.0, 3.0), glam::Vec3::ZERO);
    (camera.ortho_height_m, camera.fov_y_rad) = (Some(2.0), 0.0);
    render_with(&mut rt, &[], &view, &camera).expect("a good orthographic camera draws");
    render(&mut rt, &[], &view).expect("a good camera after the refused ones draws");
}
