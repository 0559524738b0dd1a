//! What a host gives every frame: a [`Frame`] (camera, objects, lights,
//! time) and a [`Target`] (the texture views to render into).

use super::{MeshHandle, SkinPose};
use crate::scene::gltf_material::MeshMaterial;
use crate::scene::{Camera, Light, ObjectAnimation, TextureBinding};
use glam::Mat4;
use std::collections::BTreeMap;
use std::sync::Arc;

/// One object of the host's scene this frame: a registered mesh placed by
/// `transform`. A scene built in code is made of these; a TOML scene's
/// objects are the same (`StyleRuntime::add_scene`). What the mesh draws
/// beyond its vertices comes with its handle: an animated primitive's
/// vertices at the frame's time (`StyleRuntime::add_primitive`, the
/// ocean), a patch's blended n-ring (`StyleRuntime::add_patches`).
#[derive(Debug, Clone, PartialEq)]
pub struct Instance {
    pub mesh: MeshHandle,
    /// Object-to-world.
    pub transform: Mat4,
    /// For `render(scene, tag: ...)`, `lines(tag)` and `compute(objects, tag)` passes.
    pub tags: Vec<String>,
    /// Values of the style's `object param`s: 1 component for a number or
    /// boolean (1 or 0), N for a vector, 4 for a colour (linear 0..1, as
    /// the style's colour literals). An object that leaves a param out gets
    /// its declared default.
    pub params: BTreeMap<String, Vec<f64>>,
    /// Whether `view(light)` passes (shadow maps) draw it.
    pub casts_shadows: bool,
    /// Its own images for the style's per-object `texture` params (Age of
    /// Sail's `lit_map`, `shadow_map`), as a scene's `params` binds them;
    /// a param left out gets the image the style declares. Images are
    /// scene-level resources: changing them rebuilds the scene's resources.
    pub images: BTreeMap<String, TextureBinding>,
    /// Who this object is from frame to frame (a game's entity id), so a
    /// frame whose objects came or went keeps this one's compute state and
    /// previous transform wherever it is in the list
    /// (docs/decisions/0046). Without one, an object continues the
    /// previous frame's object at its position in the list that had none.
    pub id: Option<u64>,
    /// Its pose this frame, for an instance of a skinned or morphing mesh
    /// (`StyleRuntime::add_skinned_mesh`): its joint matrices and morph
    /// weights, which the GPU deforms the mesh by (as a scene file's clip).
    /// `None`: the mesh as registered (its bind pose). Having a pose or not
    /// is a change of the scene; the pose's values change freely.
    pub pose: Option<SkinPose>,
    /// A clip of its mesh's glTF file playing at the frame's `time_s`, as
    /// a scene file's `animation = { clip, speed, loop, offset }` plays it
    /// (`StyleRuntime::add_scene` sets it from the scene): the GPU deforms
    /// the mesh (its rest pose) by the clip's pose at that time, and the
    /// CPU the same pose for lines and light bounds. Having one or not is
    /// a change of the scene; its clip, speed and offset change freely.
    pub animation: Option<ObjectAnimation>,
    /// The material of its mesh's glTF file, as a scene's object carries
    /// it (`StyleRuntime::add_scene` sets it from the scene): per-object
    /// `base_color`, `metallic`, `roughness`, `emissive` and the texture
    /// `base_color_map` for styles that read them (decision 0058). Its
    /// image is a scene-level resource: another material (another `Arc`)
    /// is a change of the scene.
    pub material: Option<Arc<MeshMaterial>>,
}

impl Instance {
    /// `mesh` at `transform`, no tags, no per-object params, casting shadows.
    pub fn new(mesh: MeshHandle, transform: Mat4) -> Instance {
        Instance {
            mesh,
            transform,
            tags: Vec::new(),
            params: BTreeMap::new(),
            casts_shadows: true,
            images: BTreeMap::new(),
            id: None,
            pose: None,
            animation: None,
            material: None,
        }
    }

    /// With `pose` ([`Instance::pose`]).
    pub fn with_pose(mut self, pose: SkinPose) -> Instance {
        self.pose = Some(pose);
        self
    }

    /// With the identity `id` ([`Instance::id`]).
    pub fn with_id(mut self, id: u64) -> Instance {
        self.id = Some(id);
        self
    }

    /// With `tag` added.
    pub fn with_tag(mut self, tag: &str) -> Instance {
        self.tags.push(tag.to_string());
        self
    }

    /// With the per-object param `name` set to `value`.
    pub fn with_param(mut self, name: &str, value: &[f64]) -> Instance {
        self.params.insert(name.to_string(), value.to_vec());
        self
    }

    /// With the per-object texture param `name` bound to the image file
    /// at `path` (PNG or EXR; its colour space the param's default image's).
    pub fn with_image(mut self, name: &str, path: impl Into<std::path::PathBuf>) -> Instance {
        let resolved = path.into();
        self.images.insert(
            name.to_string(),
            TextureBinding {
                path: resolved.display().to_string(),
                resolved,
                srgb: None,
                span: npr_diag::Span::default(),
            },
        );
        self
    }
}

/// The directional lights: `light` is the key light (`light.dir` …),
/// `more` are `light2` … `light4` (absent ones are zero in the style).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Lights {
    pub key: Light,
    pub more: [Option<Light>; 3],
}

/// Everything that changes from frame to frame.
#[derive(Debug, Clone, Copy)]
pub struct Frame<'a> {
    /// A camera with `ipd_m` is a stereo pair: a stereo style renders both
    /// eyes. Keyframes, if any, are played at `time_s`.
    pub camera: &'a Camera,
    /// Every object drawn this frame. Objects may come and go between
    /// frames; a frame whose objects have the same meshes, tags,
    /// images and shadow flags as the previous one (in the same order) allocates
    /// nothing on the GPU.
    pub objects: &'a [Instance],
    pub lights: &'a Lights,
    /// Seconds: the style's `time`, its keyframed params, the camera's keys.
    pub time_s: f64,
    /// The style's `frame` (a counter the host advances).
    pub frame_index: u32,
    /// Which eye a mono style renders with a stereo camera (0 left, 1 right).
    pub eye: u32,
}

/// Where the style's output goes: texture views of the host (a swapchain
/// image's view, an offscreen texture), which the runtime draws into at
/// their size. Each view's texture must be 2D with one mip level and one
/// layer, have `RENDER_ATTACHMENT` usage and a colour format with float or
/// normalized channels. [`Target::View`], [`Target::Eyes`] and
/// [`Target::SideBySide`] get the style's output as is, like `npr
/// render`'s PNG, so their textures must not be sRGB (make the view with
/// the non-sRGB twin of an sRGB surface format, listed in the surface
/// configuration's `view_formats`); [`Target::LinearView`] is for a host
/// that keeps linear light in its textures (an sRGB view, Bevy's view
/// targets).
#[derive(Debug, Clone, Copy)]
pub enum Target<'a> {
    /// The output of a mono style, or of the frame's `eye` of a stereo one.
    View(&'a wgpu::TextureView),
    /// Both eyes of a stereo style, each into its own view (same size).
    Eyes {
        left: &'a wgpu::TextureView,
        right: &'a wgpu::TextureView,
    },
    /// Both eyes of a stereo style side by side, each in one half of the
    /// view (its width must be even).
    SideBySide(&'a wgpu::TextureView),
    /// The output of a mono style (or of the frame's `eye`), into a view
    /// whose host reads its texels as linear light: an sRGB view, whose
    /// hardware encoding turns them back into the output's values, or a
    /// float or unorm texture that the host encodes for display later
    /// (Bevy's view targets, HDR or not). The present pass decodes the
    /// output with the sRGB transfer function (alpha as is), so the host's
    /// display shows what `npr render` writes. `format` is the view's
    /// format, which wgpu cannot tell from a view: its texture's format or
    /// that format's sRGB twin (listed in the texture's `view_formats`).
    LinearView {
        view: &'a wgpu::TextureView,
        format: wgpu::TextureFormat,
    },
}
