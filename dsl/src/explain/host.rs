//! Explanations of the host codes (E06xx): mistakes of an application that
//! embeds a style with `npr_runner::embed::StyleRuntime`, or draws one over
//! a Bevy camera's frame with `bevy_mod_npr` (E0608, E0609). They come from Rust
//! calls, not from `npr` commands, so the examples are the host's code,
//! and each says where the mistake is tested.

use super::{Example, Explanation, EXAMPLE};

pub(super) const ALL: &[Explanation] = &[
    Explanation {
        code: "E0601",
        meaning: "A host application gave the runtime a mesh handle it does not hold: the mesh \
            was removed with `StyleRuntime::remove_mesh` (a handle is never reused for another \
            mesh: each slot has a generation), or the handle came from another runtime. \
            Register the mesh with `add_mesh` and use the handle it returns for as long as \
            instances draw it; remove it only after the last frame that draws it.",
        wrong: Example {
            host_rust: Some(
                "let sphere = runtime.add_mesh(primitives::sphere(1.0, 32, 16));\n\
                 runtime.remove_mesh(sphere)?;\n\
                 let objects = [Instance::new(sphere, Mat4::IDENTITY)];\n\
                 let frame = Frame { camera: &camera, objects: &objects, lights: &lights, time_s: 0.0, frame_index: 0, eye: 0 };\n\
                 runtime.render(&mut encoder, &frame, Target::View(&view))?; // E0601\n",
            ),
            not_runnable: Some("tests/error_codes/host.rs removes a mesh and renders an instance of it"),
            ..EXAMPLE
        },
        fixed: Example {
            host_rust: Some(
                "let sphere = runtime.add_mesh(primitives::sphere(1.0, 32, 16));\n\
                 let objects = [Instance::new(sphere, Mat4::IDENTITY)];\n\
                 let frame = Frame { camera: &camera, objects: &objects, lights: &lights, time_s: 0.0, frame_index: 0, eye: 0 };\n\
                 runtime.render(&mut encoder, &frame, Target::View(&view))?;\n\
                 // ...after the last frame that draws the sphere:\n\
                 runtime.remove_mesh(sphere)?;\n",
            ),
            not_runnable: Some("runner/src/embed/mod.rs's example renders a registered mesh"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0602",
        meaning: "A host application gave `StyleRuntime::render` a texture view it cannot draw \
            the style's output into. The view's texture must be 2D with one layer and one mip \
            level, have `RENDER_ATTACHMENT` usage, a colour format with float or normalized \
            channels that is not sRGB (the style's output is display-ready, written as `npr \
            render` writes its PNG, and an sRGB texture would encode it again; the texture's \
            format is checked, since wgpu does not tell a view's, so configure a window's \
            surface with a non-sRGB format), and a size from 1 to the largest image on a side. \
            `Target::Eyes` and `Target::SideBySide` need a stereo style; the two eyes' views \
            must be the same size, and a side-by-side view an even width.",
        wrong: Example {
            host_rust: Some(
                "// The surface's preferred format, here Bgra8UnormSrgb:\n\
                 config.format = caps.formats[0];\n\
                 surface.configure(&device, &config);\n\
                 let view = surface.get_current_texture()?.texture.create_view(&Default::default());\n\
                 runtime.render(&mut encoder, &frame, Target::View(&view))?; // E0602\n",
            ),
            not_runnable: Some("tests/error_codes/host.rs renders into an sRGB view"),
            ..EXAMPLE
        },
        fixed: Example {
            host_rust: Some(
                "// A format without sRGB encoding (Bgra8Unorm, Rgba8Unorm, ...):\n\
                 config.format = caps.formats.iter().copied().find(|f| !f.is_srgb()).ok_or(\"no linear format\")?;\n\
                 surface.configure(&device, &config);\n\
                 let view = surface.get_current_texture()?.texture.create_view(&Default::default());\n\
                 runtime.render(&mut encoder, &frame, Target::View(&view))?;\n",
            ),
            not_runnable: Some("examples/embed.rs renders into a window's surface this way"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0603",
        meaning: "A host application gave `StyleRuntime::update_mesh` vertices that cannot be \
            written over the registered mesh. A deformation (skinning on the CPU, cloth, a \
            morph) moves the mesh's vertices and keeps its triangles: it must give one \
            position (and, if it gives them, one normal and one tangent) per vertex of the \
            mesh, in its order, every number finite, and tangents only for a mesh that has \
            them (one with UVs). The handle of an animated primitive (`add_primitive`, whose \
            vertices the runtime makes at each frame's time) or of a patch (`add_patches`, \
            whose n-ring and blending weights are made from the whole mesh) cannot be \
            deformed. A mesh with other vertices or triangles is another mesh: register it \
            with `add_mesh` and draw its handle, a scene change that restarts the history.",
        wrong: Example {
            host_rust: Some(
                "let ball = runtime.add_mesh(primitives::sphere(1.0, 32, 16));\n\
                 // The host's mesh at a finer level of detail: more vertices.\n\
                 let finer = primitives::sphere(1.0, 64, 32);\n\
                 runtime.update_mesh(ball, Deformed::positions(&finer.positions))?; // E0603\n",
            ),
            not_runnable: Some("runner/tests/embed_deform.rs gives too few and too many positions, and non-finite ones"),
            ..EXAMPLE
        },
        fixed: Example {
            host_rust: Some(
                "let ball = runtime.add_mesh(primitives::sphere(1.0, 32, 16));\n\
                 // The host's skinning: one new position per vertex of the mesh.\n\
                 let rest = runtime.mesh(ball)?.positions.clone();\n\
                 let squashed: Vec<[f32; 3]> = rest.iter().map(|p| [p[0], p[1] * 0.5, p[2]]).collect();\n\
                 runtime.update_mesh(ball, Deformed::positions(&squashed))?;\n",
            ),
            not_runnable: Some("runner/src/embed/mod.rs's example of update_mesh deforms a registered mesh"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0604",
        meaning: "A host application called `StyleRuntime::set_input` with a name the style does \
            not declare. A style's inputs are its `texture NAME = input(kind, ...)` declarations \
            (`StyleRuntime::manifest().textures`, those whose source is an input); give each \
            by that name.",
        wrong: Example {
            host_rust: Some(
                "// The style declares `texture color_in = input(color, display)`.\n\
                 runtime.set_input(\"color\", &color_view, SourceConvention::Color(ColorEncoding::Linear))?; // E0604\n",
            ),
            not_runnable: Some("tests/error_codes/host.rs gives an input the style does not have"),
            ..EXAMPLE
        },
        fixed: Example {
            host_rust: Some(
                "runtime.set_input(\"color_in\", &color_view, SourceConvention::Color(ColorEncoding::Linear))?;\n",
            ),
            not_runnable: Some("runner/examples/host_gbuffer.rs gives ink_over.npr its three inputs"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0605",
        meaning: "A host application gave `StyleRuntime::set_input` a texture view, or a \
            convention, that the input cannot be read from. The view's texture must be 2D with \
            one layer, one mip level and one sample, have `TEXTURE_BINDING` usage and a format \
            the GPU reads as floats (float, normalized or depth; not an integer format, not a \
            depth format with stencil). The convention must be of the input's kind: \
            `SourceConvention::Color` for a colour input, `Depth` for depth, `Normal` for \
            normals, `Motion` for motion vectors, `AsIs` for any. An sRGB texture is decoded by the GPU when it is read, so \
            its colour is `ColorEncoding::Linear`. Normals turned between world and view space \
            use the frame's camera.",
        wrong: Example {
            host_rust: Some(
                "// A depth input described as colour:\n\
                 runtime.set_input(\"depth_in\", &depth_view, SourceConvention::Color(ColorEncoding::Linear))?; // E0605\n",
            ),
            not_runnable: Some("tests/error_codes/host.rs gives a wrong convention, an integer format and sRGB twice"),
            ..EXAMPLE
        },
        fixed: Example {
            host_rust: Some(
                "// Bevy's and most games' depth: infinite reverse-Z with the camera's near plane.\n\
                 runtime.set_input(\"depth_in\", &depth_view, SourceConvention::Depth(DepthConvention::ReverseZ { near: 0.1 }))?;\n",
            ),
            not_runnable: Some("runner/examples/host_gbuffer.rs gives a reverse-Z Depth32Float view"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0606",
        meaning: "A style over inputs renders at their size: every input a host gives with \
            `StyleRuntime::set_input` must be the size of the target it renders into (per eye). \
            A host that resizes its window gives the new G-buffer's views and renders into \
            the new target in the same frame.",
        wrong: Example {
            host_rust: Some(
                "// A half-resolution depth buffer under a full-resolution frame:\n\
                 runtime.set_input(\"depth_in\", &half_depth_view, depth)?;\n\
                 runtime.render(&mut encoder, &frame, Target::View(&view))?; // E0606\n",
            ),
            not_runnable: Some("tests/error_codes/host.rs gives an 8x8 input to a 16x16 target"),
            ..EXAMPLE
        },
        fixed: Example {
            host_rust: Some(
                "runtime.set_input(\"depth_in\", &full_depth_view, depth)?;\n\
                 runtime.render(&mut encoder, &frame, Target::View(&view))?;\n",
            ),
            not_runnable: Some("tests/gpu/embed_inputs.rs renders over inputs of the target's size"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0607",
        meaning: "A host application rendered a style that reads an input it has not given. Give \
            every `input(...)` texture of the style with `StyleRuntime::set_input` before the \
            first frame; a view given once is read every frame until another is given.",
        wrong: Example {
            host_rust: Some(
                "runtime.set_input(\"color_in\", &color_view, colour)?;\n\
                 runtime.render(&mut encoder, &frame, Target::View(&view))?; // E0607: depth_in, normal_in\n",
            ),
            not_runnable: Some("tests/error_codes/host.rs renders without one of two inputs"),
            ..EXAMPLE
        },
        fixed: Example {
            host_rust: Some(
                "runtime.set_input(\"color_in\", &color_view, colour)?;\n\
                 runtime.set_input(\"depth_in\", &depth_view, depth)?;\n\
                 runtime.set_input(\"normal_in\", &normal_view, normals)?;\n\
                 runtime.render(&mut encoder, &frame, Target::View(&view))?;\n",
            ),
            not_runnable: Some("runner/examples/host_gbuffer.rs gives every input before its frame"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0608",
        meaning: "A Bevy camera is drawn by a style that reads an input the camera does not \
            produce. bevy_mod_npr gives a style over Bevy's frame the camera's image as `color`, \
            `DepthPrepass`'s texture as `depth`, `NormalPrepass`'s as `normal` and \
            `MotionVectorPrepass`'s as `motion`; Bevy renders no `id` or free-form image. The \
            camera shows what Bevy drew, and the problem is logged once, until the component \
            is added: the style then draws from the next frame on, without a restart.",
        wrong: Example {
            host_rust: Some(
                "// ink_over.npr reads `depth_in` and `normal_in`:\n\
                 let style = NprStyle(assets.load(\"ink_over.npr\"));\n\
                 commands.spawn((Camera3d::default(), Msaa::Off, DepthPrepass, style)); // E0608: no NormalPrepass\n",
            ),
            not_runnable: Some("bevy_mod_npr/tests/headless/post.rs removes NormalPrepass from an inked camera"),
            ..EXAMPLE
        },
        fixed: Example {
            host_rust: Some(
                "let style = NprStyle(assets.load(\"ink_over.npr\"));\n\
                 commands.spawn((Camera3d::default(), Msaa::Off, DepthPrepass, NormalPrepass, style));\n",
            ),
            not_runnable: Some("bevy_mod_npr/tests/headless/post.rs inks Bevy's PBR frame"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0609",
        meaning: "A Bevy camera is drawn by a style over Bevy's frame, and the camera is set up \
            so that the style cannot read it: with MSAA on, Bevy's prepass textures hold several \
            samples per pixel, which an input is not read from; with a viewport, the camera \
            draws a part of a target that a style over inputs would draw whole. Give the camera \
            `Msaa::Off` (the style smooths its own lines) and its own render target. The camera \
            shows what Bevy drew until then.",
        wrong: Example {
            host_rust: Some(
                "// Bevy's default is 4 samples per pixel:\n\
                 let style = NprStyle(assets.load(\"ink_over.npr\"));\n\
                 commands.spawn((Camera3d::default(), DepthPrepass, NormalPrepass, style)); // E0609\n",
            ),
            not_runnable: Some("bevy_mod_npr/tests/headless/post.rs turns MSAA on under an inked camera"),
            ..EXAMPLE
        },
        fixed: Example {
            host_rust: Some(
                "let style = NprStyle(assets.load(\"ink_over.npr\"));\n\
                 commands.spawn((Camera3d::default(), Msaa::Off, DepthPrepass, NormalPrepass, style));\n",
            ),
            not_runnable: Some("bevy_mod_npr/tests/headless/post.rs inks Bevy's PBR frame"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0612",
        meaning: "A host application gave an instance a pose whose joint matrices do not fit its \
            mesh: a skinned mesh (`StyleRuntime::add_skinned_mesh`) takes one matrix per joint of \
            its `Skinning`, in the order its joint indices name them, and a mesh registered \
            with `add_mesh` takes no pose. In Bevy, a `SkinnedMesh` whose joint entities are \
            gone, or that names another number of joints than its inverse bindposes or its \
            mesh's joint indices, gets this code and is drawn unskinned.",
        wrong: Example {
            host_rust: Some(
                "let arm = runtime.add_skinned_mesh(mesh, Skinning { joint_count: 2, joints, weights, morph_targets: vec![] })?;\n\
                 let pose = SkinPose::bind(3, 0); // three joints for a skin of two\n\
                 let objects = [Instance::new(arm, Mat4::IDENTITY).with_pose(pose)];\n\
                 runtime.render(&mut encoder, &frame, Target::View(&view))?; // E0612\n",
            ),
            not_runnable: Some("tests/error_codes/host.rs gives a pose of three joints to a skin of two"),
            ..EXAMPLE
        },
        fixed: Example {
            host_rust: Some(
                "let pose = SkinPose::bind(2, 0); // one matrix per joint of the skin\n\
                 let objects = [Instance::new(arm, Mat4::IDENTITY).with_pose(pose)];\n\
                 runtime.render(&mut encoder, &frame, Target::View(&view))?;\n",
            ),
            not_runnable: Some("runner/tests/runner/embed_skinned.rs poses the Blender-made arms this way"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0613",
        meaning: "A host application gave an instance a pose with a joint matrix or a morph \
            weight that is not a finite number (NaN or infinite): the deformed vertices would \
            be nowhere. Such a pose usually comes from inverting a matrix with a scale of zero, \
            or from weights read before they were written.",
        wrong: Example {
            host_rust: Some(
                "let mut pose = SkinPose::bind(2, 0);\n\
                 pose.joints[1] = Mat4::from_scale(Vec3::ZERO).inverse(); // not finite\n\
                 runtime.render(&mut encoder, &frame, Target::View(&view))?; // E0613\n",
            ),
            not_runnable: Some("tests/error_codes/host.rs gives a joint matrix of NaN"),
            ..EXAMPLE
        },
        fixed: Example {
            host_rust: Some(
                "let mut pose = SkinPose::bind(2, 0);\n\
                 pose.joints[1] = Mat4::from_translation(Vec3::Y * 0.5);\n\
                 runtime.render(&mut encoder, &frame, Target::View(&view))?;\n",
            ),
            not_runnable: Some("runner/src/embed/mod.rs's example of add_skinned_mesh poses a box this way"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0614",
        meaning: "A host application gave an instance a pose with another number of morph \
            weights than its mesh has morph targets: one weight per target of the mesh's \
            `Skinning`, in its order (none for a mesh without targets).",
        wrong: Example {
            host_rust: Some(
                "// The face has two morph targets.\n\
                 let pose = SkinPose { joints: vec![], morph_weights: vec![0.5] };\n\
                 runtime.render(&mut encoder, &frame, Target::View(&view))?; // E0614\n",
            ),
            not_runnable: Some("tests/error_codes/host.rs gives one weight for two targets"),
            ..EXAMPLE
        },
        fixed: Example {
            host_rust: Some(
                "let pose = SkinPose { joints: vec![], morph_weights: vec![0.5, 0.0] };\n\
                 runtime.render(&mut encoder, &frame, Target::View(&view))?;\n",
            ),
            not_runnable: Some("runner/tests/runner/embed_skinned.rs gives the blob's two weights each frame"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0615",
        meaning: "A host application registered a skinned or morphing mesh \
            (`StyleRuntime::add_skinned_mesh`) with a `Skinning` that does not fit it: joint \
            indices and weights must be one set of 4 per vertex, the weights finite, not \
            negative and summing to 1 (within 0.01; they are renormalised), every weighted \
            joint index below `joint_count`, at most 256 joints (the glTF reader's limit), and \
            each morph target one finite delta per vertex. A mesh with neither joints nor \
            morph targets is registered with `add_mesh`.",
        wrong: Example {
            host_rust: Some(
                "// Vertex 0 is bound to nothing: its weights sum to 0.\n\
                 weights[0] = [0.0; 4];\n\
                 runtime.add_skinned_mesh(mesh, Skinning { joint_count: 2, joints, weights, morph_targets: vec![] })?; // E0615\n",
            ),
            not_runnable: Some("tests/error_codes/host.rs registers weights summing to 0 and a joint past the skin's"),
            ..EXAMPLE
        },
        fixed: Example {
            host_rust: Some(
                "weights[0] = [1.0, 0.0, 0.0, 0.0];\n\
                 runtime.add_skinned_mesh(mesh, Skinning { joint_count: 2, joints, weights, morph_targets: vec![] })?;\n",
            ),
            not_runnable: Some("runner/src/embed/mod.rs's example of add_skinned_mesh registers a skinned box"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0616",
        meaning: "A host application rendered a frame whose camera has a projection npr cannot \
            draw with. A perspective `Frame::camera` has its vertical field of view \
            `fov_y_rad` in (0, π), its `near` plane at a positive distance and its `far` plane \
            beyond it (`f32::INFINITY` is allowed), and a stereo camera's `ipd_m` is a finite \
            distance, 0 or more. An orthographic one (`ortho_height_m = Some(h)`, decision \
            0062) has a positive finite height h, a finite `far` beyond `near`, and no `ipd_m`. \
            Scene files are held to the same rules (E0405). The compiler counts on them: \
            `camera.near` and `camera.focal` are positive, so a style may divide by them.",
        wrong: Example {
            host_rust: Some(
                "let mut camera = Camera::looking_at(Vec3::new(0.0, 1.0, 4.0), Vec3::ZERO);\n\
                 camera.near = 0.0; // E0616 at the next render\n",
            ),
            not_runnable: Some("tests/error_codes/host.rs renders with a zero near plane and a zero field of view"),
            ..EXAMPLE
        },
        fixed: Example {
            host_rust: Some(
                "let mut camera = Camera::looking_at(Vec3::new(0.0, 1.0, 4.0), Vec3::ZERO);\n\
                 camera.near = 0.05;\n",
            ),
            not_runnable: Some("examples/embed.rs renders with a checked camera every frame"),
            ..EXAMPLE
        },
    },
];
