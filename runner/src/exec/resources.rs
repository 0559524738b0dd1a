//! Everything that depends on the output size, built once per size and
//! rebuilt only when it changes: the physical textures (one set per eye
//! slot; aliased targets share one; a history texture has a second copy), a
//! depth texture per pass size for the passes that need one, a depth
//! texture of its own per eye slot for each pass with `depth: keep` (never
//! shared, so it lives through the frame: to its last tester and beyond),
//! a depth texture per eye slot for each host `input(depth)` a pass tests
//! against (`host_depth.rs` draws it each frame),
//! and per frame parity, eye slot and pass its attachment views and group 0.
//!
//! History textures (`previous(...)` reads): frames alternate between parity
//! 0 and parity 1. A frame of parity 0 writes the first copy and binds the
//! second to previous-frame reads; parity 1 the other way round. Both copies
//! start as zero (wgpu zero-initialises textures), which is what
//! `previous(...)` reads on the first frame after the renderer is built or
//! resized.

use super::sized::{scaled_size, texture_2d, wgpu_format, Physical, SizedPass, SizedResources};
use super::Renderer;
use crate::gpu_count::CreateView;
use npr_abi::manifest::{DepthMode, PassKindManifest};
use std::collections::BTreeMap;

impl Renderer {
    /// Make the size-dependent resources for `width`×`height` unless they
    /// exist; out of memory (E0508) leaves the renderer without any, so a
    /// later call at a smaller size starts afresh.
    pub(super) fn ensure_size(&mut self, width: u32, height: u32) -> Result<(), crate::RunError> {
        if self
            .sized
            .as_ref()
            .is_some_and(|s| s.width == width && s.height == height)
        {
            return Ok(());
        }
        // A target at a scale above 1 may pass what this adapter allows
        // even when `--size` does not.
        let max = self.device.limits().max_texture_dimension_2d;
        for t in &self.manifest.targets {
            let (w, h) = scaled_size(width, height, t.scale);
            if w > max || h > max {
                return Err(crate::RunError::Limit(format!(
                    "target `{}` would be {w}x{h} at --size {width}x{height} (scale {}), over this GPU \
                     adapter's 2D texture limit of {max}",
                    t.name, t.scale
                )));
            }
        }
        // Free the old size's textures before making the new ones.
        self.sized = None;
        let device = self.device.clone();
        crate::gpu_error::scoped(
            &device,
            || format!("making the targets of a {width}x{height} image"),
            || self.make_sized(width, height),
        )
        .inspect_err(|_| self.sized = None)?;
        self.generation = super::next_generation();
        Ok(())
    }

    fn make_sized(&mut self, width: u32, height: u32) -> Result<(), crate::RunError> {
        let slots = self.frame_buffers.len();
        let physical = Physical {
            slots: (0..slots).map(|_| self.create_physical(width, height)).collect(),
            second: (0..slots).map(|_| self.create_history_copies(width, height)).collect(),
        };
        let parities = self.parities;
        let mut depth: BTreeMap<(u32, u32), wgpu::Texture> = BTreeMap::new();
        // Kept depths by (eye slot, keeping pass); every parity shares them,
        // as each frame clears and rewrites them before any test reads them.
        let mut kept: BTreeMap<(usize, usize), wgpu::Texture> = BTreeMap::new();
        // The host's depth by (eye slot, input texture), drawn each frame
        // (`host_depth.rs`) and tested like a kept depth.
        let mut host: BTreeMap<(usize, usize), wgpu::Texture> = BTreeMap::new();
        for slot in 0..slots {
            for input in super::host_depth::tested_inputs(&self.manifest) {
                let name = &self.manifest.textures[input].name;
                host.insert(
                    (slot, input),
                    texture_2d(
                        &self.device,
                        &format!("npr host depth `{name}`"),
                        (width, height),
                        wgpu::TextureFormat::Depth32Float,
                        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
                    ),
                );
            }
        }
        let mut passes: Vec<Vec<Vec<SizedPass>>> = Vec::new();
        for parity in 0..parities {
            let mut parity_passes = Vec::new();
            for slot in 0..slots {
                let mut slot_passes = Vec::new();
                for (pi, pass) in self.manifest.passes.iter().enumerate() {
                    let (w, h) = scaled_size(width, height, pass.scale);
                    let view_of_target = |t: usize| {
                        physical
                            .texture(slot, parity, self.manifest.targets[t].physical, false)
                            .make_view(&Default::default())
                    };
                    let color_views: Vec<wgpu::TextureView> = pass.outputs.iter().map(|t| view_of_target(*t)).collect();
                    let depth_texture = |label: &str| {
                        texture_2d(
                            &self.device,
                            label,
                            (w, h),
                            wgpu::TextureFormat::Depth32Float,
                            // Lines passes read a kept depth in their shader.
                            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
                        )
                    };
                    // `Manifest::validate`: a test names an earlier kept pass
                    // of the same size, whose texture is made first.
                    let kept_by = match &pass.kind {
                        PassKindManifest::Render {
                            depth: DepthMode::Keep, ..
                        } => Some(pi),
                        PassKindManifest::Render {
                            depth: DepthMode::Test { pass, .. },
                            ..
                        } => Some(*pass),
                        _ => None,
                    };
                    // `Manifest::validate`: a test of the host's depth is at scale 1.
                    let host_tested = match &pass.kind {
                        PassKindManifest::Render {
                            depth: DepthMode::TestInput { input, .. },
                            ..
                        }
                        | PassKindManifest::Lines {
                            depth: DepthMode::TestInput { input, .. },
                            ..
                        } => host.get(&(slot, *input)),
                        _ => None,
                    };
                    // A render pass loads it as its attachment; a lines
                    // pass reads it (below) and draws with its own.
                    let host_attachment = host_tested.filter(|_| matches!(pass.kind, PassKindManifest::Render { .. }));
                    let depth_view = self.passes[pi].needs_depth().then(|| {
                        match (host_attachment, kept_by) {
                            (Some(h), _) => h,
                            (None, Some(k)) => kept.entry((slot, k)).or_insert_with(|| {
                                depth_texture(&format!("npr kept depth of `{}`", self.manifest.passes[k].name))
                            }),
                            (None, None) => depth.entry((w, h)).or_insert_with(|| depth_texture("npr depth")),
                        }
                        .make_view(&Default::default())
                    });
                    // A lines pass's test reads the kept depth, or the
                    // host's, as a texture (group 1), made above.
                    let tested_depth = match &pass.kind {
                        PassKindManifest::Lines {
                            depth: DepthMode::Test { pass: tested, .. },
                            ..
                        } => {
                            let texture = kept.get(&(slot, *tested)).ok_or_else(|| {
                                crate::RunError::Internal(format!(
                                    "lines pass `{}` tests a depth that no earlier pass kept",
                                    pass.name
                                ))
                            })?;
                            self.passes[pi].tested_depth_group(&self.device, &texture.make_view(&Default::default()))
                        }
                        PassKindManifest::Lines {
                            depth: DepthMode::TestInput { .. },
                            ..
                        } => host_tested.and_then(|texture| {
                            self.passes[pi].tested_depth_group(&self.device, &texture.make_view(&Default::default()))
                        }),
                        _ => None,
                    };
                    let tiled_outputs = self.passes[pi].tiled_outputs(&self.device, &color_views, (w, h));
                    slot_passes.push(SizedPass {
                        tiled_outputs,
                        color_views,
                        depth_view,
                        tested_depth,
                        group0: self.group0(pi, slot, parity, &physical),
                        pixel_workgroups: self.scene_gpu.values[pi]
                            .as_ref()
                            .map_or(0, |b| b.pixel_workgroups(&self.manifest, width, height)),
                        draws: None,
                    });
                }
                parity_passes.push(slot_passes);
            }
            passes.push(parity_passes);
        }
        let host_depths = match &self.host_depth {
            Some(pipeline) => host
                .iter()
                .map(|(&(slot, input), texture)| super::host_depth::HostDepthDraw {
                    view: texture.make_view(&Default::default()),
                    group: pipeline.bind(
                        &self.device,
                        &self.frame_buffers[slot],
                        &self.textures[input].texture.make_view(&Default::default()),
                    ),
                })
                .collect(),
            None => Vec::new(),
        };
        // New textures hold no history: the next frame is frame 0 again,
        // and compute passes' state starts again from its first values.
        self.frames_begun = 0;
        super::values::reset(&self.queue, &self.scene_gpu.values);
        // Rows a scene change left to copy would bring old state back.
        self.carried_rows.lock().unwrap_or_else(|e| e.into_inner()).clear();
        super::values::write_pixel_dispatch(&self.queue, &self.manifest, &self.scene_gpu.values, width, height);
        self.motion = super::frame::Motion::default();
        self.sized = Some(SizedResources {
            width,
            height,
            physical,
            passes,
            host_depths,
            output_slot: 0,
        });
        Ok(())
    }

    /// The second copy of every history texture, by physical index.
    fn create_history_copies(&self, width: u32, height: u32) -> BTreeMap<usize, wgpu::Texture> {
        (0..self.manifest.physical.len())
            .filter(|i| self.manifest.physical[*i].history)
            .map(|i| (i, self.physical_texture(i, width, height)))
            .collect()
    }

    /// One physical texture per `manifest.physical` entry, at `width`×`height` × its scale.
    fn create_physical(&self, width: u32, height: u32) -> Vec<wgpu::Texture> {
        (0..self.manifest.physical.len())
            .map(|i| self.physical_texture(i, width, height))
            .collect()
    }

    /// Physical texture `index` of the manifest at `width`×`height` × its scale.
    fn physical_texture(&self, index: usize, width: u32, height: u32) -> wgpu::Texture {
        let p = &self.manifest.physical[index];
        // A tiled pass writes its outputs as storage textures.
        let stored_by_compute = self.manifest.passes.iter().any(|pass| {
            matches!(pass.kind, PassKindManifest::TiledImage { .. })
                && pass.outputs.iter().any(|t| self.manifest.targets[*t].physical == index)
        });
        let mut usage = if stored_by_compute {
            crate::gpu_error::TARGET_USAGE | wgpu::TextureUsages::STORAGE_BINDING
        } else {
            crate::gpu_error::TARGET_USAGE
        };
        // A history texture is written back from a checkpoint (`state.rs`).
        if p.history {
            usage |= wgpu::TextureUsages::COPY_DST;
        }
        texture_2d(
            &self.device,
            &format!("npr physical #{index}"),
            scaled_size(width, height, p.scale),
            wgpu_format(p.format),
            usage,
        )
    }
}
