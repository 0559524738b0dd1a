//! The executor of `lines` passes (Klein et al. 2000, §5). Per frame and eye
//! slot, [`LinesPassExec::prepare`] evaluates the pass's shape settings at
//! the frame's time, asks the pass's [`LinesCache`] for the strips of the
//! objects it draws (rebuilt only when the view, an object, a mesh, the
//! size or the shape changed) and uploads their vertices, biased towards
//! the eye, into that slot's buffers (a pass with line sets builds each
//! set's strips, every vertex carrying its set's index: decision 0056) (grown, never shrunk). `encode` then
//! draws them with the compiled shader into the pass's targets. With a
//! depth test the shader reads the kept depth as group 1
//! (`npr_abi::lines::LINE_DEPTH_WGSL`) and tests each vertex's edge point; the
//! pipeline has no depth attachment.

use super::bind;
use super::common::{self, Timestamps};
use super::sized::SizedPass;
use crate::gpu_count::Create;
use crate::lines::cache::{EdgeSelection, LinesCache, SetRequest};
use crate::lines::draw::{vertices, DepthBias};
use crate::lines::objects::line_objects;
use crate::lines::strip::LineStyle;
use crate::lines::viewpoint::Viewpoint;
use crate::RunError;
use glam::{DMat4, DVec2};
use npr_abi::lines::{
    LineEdges, LineSet, LineShape, LineVertex, LINE_VERTEX_ATTRIBUTES, MAX_LINE_WIDTH_PX, MAX_TAPER, MIN_WAVELENGTH_PX,
};
use npr_abi::manifest::*;

/// One eye slot's strips on the GPU.
struct SlotGeometry {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
}

pub(super) struct LinesPassExec {
    name: String,
    clear: wgpu::Color,
    tag: Option<String>,
    edges: LineEdges,
    shape: LineShape,
    /// The line sets, highest priority first; with any, they replace
    /// `edges` and `shape`.
    sets: Vec<LineSet>,
    /// `Some` with a depth test: the view-space bias in px.
    depth_test: Option<f64>,
    pipeline: wgpu::RenderPipeline,
    pub(super) layout0: wgpu::BindGroupLayout,
    /// Group 1 with a depth test: the kept depth, read by the vertex shader.
    depth_layout: Option<wgpu::BindGroupLayout>,
    cache: LinesCache,
    slots: Vec<Option<SlotGeometry>>,
}

/// What [`LinesPassExec::prepare`] needs of one eye slot.
pub(super) struct LinesEye {
    pub slot: usize,
    /// The eye index the cache keys the strips by (0 mono/left, 1 right).
    pub eye: u32,
    /// The eye's homogeneous position: (position, 1), or (−forward, 0)
    /// for an orthographic camera (`lines::viewpoint`).
    pub position: Viewpoint,
    pub view_proj: DMat4,
    /// P₁₁ of the projection (px per view depth, in NDC units).
    pub focal_y: f64,
}

/// The frame's values every lines pass reads.
pub(super) struct LinesFrame<'a> {
    pub manifest: &'a Manifest,
    pub scene: &'a crate::scene::Scene,
    /// The meshes as they are at this frame's time (time-varying ones rebuilt).
    pub meshes: &'a [std::sync::Arc<crate::scene::Mesh>],
    pub time_s: f64,
    pub width: u32,
    pub height: u32,
}

impl LinesPassExec {
    pub fn build(
        device: &wgpu::Device,
        manifest: &Manifest,
        pass: &PassManifest,
        shader: common::PassShader,
    ) -> Result<LinesPassExec, RunError> {
        let PassKindManifest::Lines {
            tag,
            edges,
            shape,
            sets,
            depth,
            ..
        } = &pass.kind
        else {
            return Err(RunError::Internal(format!("pass `{}` is not a lines pass", pass.name)));
        };
        let layout0 = bind::group0_layout(device, pass);
        let attributes = LINE_VERTEX_ATTRIBUTES
            .iter()
            .enumerate()
            .map(|(location, &(offset, components))| {
                let format = match components {
                    1 => wgpu::VertexFormat::Float32,
                    2 => wgpu::VertexFormat::Float32x2,
                    3 => wgpu::VertexFormat::Float32x3,
                    4 => wgpu::VertexFormat::Float32x4,
                    n => return Err(RunError::Internal(format!("a line vertex attribute of {n} components"))),
                };
                Ok(wgpu::VertexAttribute {
                    format,
                    offset,
                    shader_location: location as u32,
                })
            })
            .collect::<Result<Vec<_>, RunError>>()?;
        let buffers = [Some(wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<LineVertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &attributes,
        })];
        let depth_test = match depth {
            DepthMode::Own => None,
            DepthMode::Test { bias_px, .. } | DepthMode::TestInput { bias_px, .. } => Some(*bias_px),
            DepthMode::Keep => return Err(RunError::Internal(format!("lines pass `{}` keeps a depth", pass.name))),
        };
        let depth_layout = depth_test.map(|_| {
            device.make_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(&format!("{} kept depth", pass.name)),
                entries: &[wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::VERTEX,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Depth,
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                }],
            })
        });
        let mut layouts = vec![&layout0];
        layouts.extend(depth_layout.as_ref());
        let pipeline = common::render_pipeline(device, manifest, pass, shader, &layouts, &buffers, None)?;
        Ok(LinesPassExec {
            name: pass.name.clone(),
            clear: common::clear_color(pass),
            tag: tag.clone(),
            edges: *edges,
            shape: shape.clone(),
            sets: sets.clone(),
            depth_test,
            pipeline,
            layout0,
            depth_layout,
            cache: LinesCache::default(),
            slots: Vec::new(),
        })
    }

    /// A new scene: the cached strips and edge meshes go (as a new
    /// renderer's would; the cache is keyed by content, so this bounds its
    /// memory rather than its correctness); the pipeline and the slots'
    /// buffers (grown, never shrunk) stay.
    pub fn set_scene(&mut self) {
        self.cache = LinesCache::default();
    }

    /// Group 1 over the tested pass's kept depth (with a depth test).
    pub fn tested_depth_group(&self, device: &wgpu::Device, kept: &wgpu::TextureView) -> Option<wgpu::BindGroup> {
        let layout = self.depth_layout.as_ref()?;
        Some(device.make_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&format!("{} kept depth", self.name)),
            layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(kept),
            }],
        }))
    }

    /// The strips' shape at the frame's time. Settings animated past the
    /// ranges typecheck enforces on constants are held at their ends.
    fn style(&self, frame: &LinesFrame, shape: &LineShape) -> Result<LineStyle, RunError> {
        let eval = |name: &str, s: &npr_abi::lines::LineScalar| {
            s.eval(frame.time_s, |p| {
                crate::animation::scalar_at(frame.manifest, p, frame.time_s, frame.height)
            })
            .ok_or_else(|| RunError::Internal(format!("lines pass `{}`: `{name}` reads a missing param", self.name)))
        };
        Ok(LineStyle {
            width_px: eval("width", &shape.width)?.clamp(0.0, MAX_LINE_WIDTH_PX),
            amplitude_px: eval("amplitude", &shape.amplitude)?.max(0.0),
            wavelength_px: eval("wavelength", &shape.wavelength)?.max(MIN_WAVELENGTH_PX),
            phase: eval("phase", &shape.phase)?,
            taper: eval("taper", &shape.taper)?.clamp(0.0, MAX_TAPER),
        })
    }

    /// Per line set, its surfaces among the pass's `objects` (the drawn
    /// objects that also have the set's tag, patched ones as their whole
    /// mesh, as `line_objects` gives them) and its style at the frame's time.
    fn set_requests(
        &self,
        frame: &LinesFrame,
        drawn: &[(&crate::scene::Object, &crate::scene::Mesh)],
        objects: &[crate::lines::cache::LineObject<'_>],
    ) -> Result<Vec<SetRequest>, RunError> {
        self.sets
            .iter()
            .map(|set| {
                let mine: Vec<_> = drawn
                    .iter()
                    .filter(|(o, _)| set.tag.as_ref().is_none_or(|t| o.tags.contains(t)))
                    .copied()
                    .collect();
                let surfaces = line_objects(&mine)
                    .iter()
                    .filter_map(|s| {
                        objects
                            .iter()
                            .position(|o| std::ptr::eq(o.mesh, s.mesh) && o.model == s.model)
                    })
                    .collect();
                Ok(SetRequest {
                    surfaces,
                    edges: set.edges,
                    style: self.style(frame, &set.shape)?,
                    visibility: set.visibility,
                    dash: set.dash,
                })
            })
            .collect()
    }

    /// Build (or reuse) the strips of one eye slot and upload them.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        frame: &LinesFrame,
        eye: &LinesEye,
        scale: f64,
    ) -> Result<(), RunError> {
        let drawn: Vec<(&crate::scene::Object, &crate::scene::Mesh)> = frame
            .scene
            .objects
            .iter()
            .zip(frame.meshes)
            .filter(|(o, _)| self.tag.as_ref().is_none_or(|t| o.tags.contains(t)))
            .map(|(o, mesh)| (o, mesh.as_ref()))
            .collect();
        // A patched object's patches are one surface: its whole mesh.
        let objects = line_objects(&drawn);
        let (w, h) = super::sized::scaled_size(frame.width, frame.height, scale);
        let size = DVec2::new(f64::from(w), f64::from(h));
        let strips = if self.sets.is_empty() {
            let style = self.style(frame, &self.shape)?;
            let selection = EdgeSelection {
                silhouettes: self.edges.silhouettes,
                crease_deg: self.edges.crease_deg,
            };
            self.cache
                .strips(eye.eye, &objects, eye.position, eye.view_proj, size, &style, selection)
        } else {
            let requests = self.set_requests(frame, &drawn, &objects)?;
            self.cache
                .set_strips(eye.eye, &objects, &requests, eye.position, eye.view_proj, size)
        };
        // Clip space is linear in homogeneous points, so an orthographic
        // eye's point at infinity pulls along the view axis (w = 0 there).
        let eye_clip_z = (eye.view_proj * eye.position.0).z;
        let bias = DepthBias::view_space_px(self.depth_test.unwrap_or(0.0), eye.focal_y, size.y, eye_clip_z);
        let gpu_vertices = vertices(strips, [size.x, size.y], bias);
        let index_bytes: &[u8] = bytemuck::cast_slice(&strips.indices);
        let vertex_bytes: &[u8] = bytemuck::cast_slice(&gpu_vertices);
        if self.slots.len() <= eye.slot {
            self.slots.resize_with(eye.slot + 1, || None);
        }
        let fits = self.slots[eye.slot].as_ref().is_some_and(|g| {
            g.vertices.size() >= vertex_bytes.len() as u64 && g.indices.size() >= index_bytes.len() as u64
        });
        if !fits {
            // Grown to the next power of two of twice what this frame needs,
            // so a changing view (more silhouettes, longer wavy strips)
            // seldom reallocates: the one GPU allocation a frame after the
            // first may make (`npr_runner::embed` docs).
            let buffer = |label: &str, bytes: usize, usage: wgpu::BufferUsages| {
                device.make_buffer(&wgpu::BufferDescriptor {
                    label: Some(label),
                    size: (2 * bytes.max(16) as u64).next_power_of_two(),
                    usage: usage | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                })
            };
            self.slots[eye.slot] = Some(SlotGeometry {
                vertices: buffer(
                    &format!("{} strip vertices", self.name),
                    vertex_bytes.len(),
                    wgpu::BufferUsages::VERTEX,
                ),
                indices: buffer(
                    &format!("{} strip indices", self.name),
                    index_bytes.len(),
                    wgpu::BufferUsages::INDEX,
                ),
                index_count: 0,
            });
        }
        let geometry = self.slots[eye.slot]
            .as_mut()
            .ok_or_else(|| RunError::Internal("lines slot buffers missing".into()))?;
        if !vertex_bytes.is_empty() {
            queue.write_buffer(&geometry.vertices, 0, vertex_bytes);
            queue.write_buffer(&geometry.indices, 0, index_bytes);
        }
        geometry.index_count = strips.indices.len() as u32;
        Ok(())
    }

    /// How many times the pass's strips were built (tests, `npr bench lines`).
    pub fn rebuilds(&self) -> u64 {
        self.cache.rebuilds
    }

    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        sized: &SizedPass,
        slot: usize,
        timestamps: Option<&Timestamps>,
    ) {
        let mut rp = common::begin_render_pass(encoder, &self.name, self.clear, sized, None, timestamps);
        let Some(Some(geometry)) = self.slots.get(slot) else {
            return;
        };
        if geometry.index_count == 0 {
            return;
        }
        rp.set_pipeline(&self.pipeline);
        rp.set_bind_group(0, &sized.group0, &[]);
        if let Some(group) = &sized.tested_depth {
            rp.set_bind_group(1, group, &[]);
        }
        rp.set_vertex_buffer(0, geometry.vertices.slice(..));
        rp.set_index_buffer(geometry.indices.slice(..), wgpu::IndexFormat::Uint32);
        rp.draw_indexed(0..geometry.index_count, 0, 0..1);
    }
}
