//! Building an art-map (Klein et al. 2000 §4.2): "we simply filter the
//! photorealistic images as in normal mip-mapping, but then apply an NPR
//! filter to each level independently". The source image's mip chain is
//! box-filtered in linear light, as `mips: on` textures are; then the
//! filter style runs once per level on the GPU ([`Renderer::new_filter`],
//! its image passes at the level's size, `frame` = the level's index), and
//! its output is that level of the art-map. A rip-map filters every
//! 2^-i × 2^-j level the same way and packs them into one atlas. Levels are cached
//! (`artmap_cache`): a second build of the same inputs filters nothing.

use crate::artmap_cache::{self, Origin};
pub use crate::image_level::{halve_axis, mip_chain, Level};
use crate::{FrameSpec, Renderer, RunError};
use npr_abi::ArtmapSpec;
use std::sync::Arc;

/// What building one art-map did, for the caller to report.
#[derive(Debug, Clone, PartialEq)]
pub struct ArtmapBuild {
    pub texture: String,
    pub levels: u32,
    pub origin: Origin,
    /// Wall time of the build (cache lookup included).
    pub ms: f64,
}

/// A rip-map (§4.2, Fig. 7–8): every level (i, j) of the source halved i
/// times along x and j times along y, each filtered (`frame` = i + 16 j),
/// packed into one atlas as [`npr_abi::RipmapAtlas`] lays it out.
pub fn ripmap_atlas(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    program: &npr_abi::StyleProgram,
    base: Level,
) -> Result<Level, RunError> {
    let layout = npr_abi::RipmapAtlas {
        width: base.width,
        height: base.height,
    };
    let (aw, ah) = layout.atlas_size();
    if aw > npr_diag::limits::MAX_TEXTURE_SIZE || ah > npr_diag::limits::MAX_TEXTURE_SIZE {
        return Err(RunError::User(vec![npr_diag::Diagnostic::error(
            npr_diag::codes::LIMIT_EXCEEDED,
            format!(
                "a rip-map of a {}x{} image needs a {aw}x{ah} atlas, over the {} texel limit",
                base.width,
                base.height,
                npr_diag::limits::MAX_TEXTURE_SIZE
            ),
        )
        .with_help(
            "a rip-map's atlas is twice the image's size on each axis: use an image of at most 8192 texels a side",
        )]));
    }
    let mut atlas = vec![[0.0f32; 4]; (aw * ah) as usize];
    let mut runner = FilterRunner::new(device, queue, program);
    let columns = npr_abi::RipmapAtlas::levels(base.width);
    let rows = npr_abi::RipmapAtlas::levels(base.height);
    let mut row_start = base;
    for j in 0..rows {
        let mut level = row_start.clone();
        for i in 0..columns {
            let filtered = runner.filter(&level, i + 16 * j)?;
            let (ox, oy) = layout.offset(i, j);
            for y in 0..filtered.height {
                let dst = ((oy + y) * aw + ox) as usize;
                let src = (y * filtered.width) as usize;
                atlas[dst..dst + filtered.width as usize]
                    .copy_from_slice(&filtered.pixels[src..src + filtered.width as usize]);
            }
            if i + 1 < columns {
                level = halve_axis(&level, 0);
            }
        }
        if j + 1 < rows {
            row_start = halve_axis(&row_start, 1);
        }
    }
    Ok(Level {
        width: aw,
        height: ah,
        pixels: atlas,
    })
}

/// The art-map's levels for `spec`, its source already decoded to linear
/// `base` from the file's `source_bytes`.
pub fn build(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    name: &str,
    spec: &ArtmapSpec,
    source_bytes: &[u8],
    base: Level,
) -> Result<(Arc<Vec<Level>>, ArtmapBuild), RunError> {
    let start = std::time::Instant::now();
    let count = if spec.rip {
        npr_abi::RipmapAtlas {
            width: base.width,
            height: base.height,
        }
        .level_count()
    } else {
        spec.level_count(base.width, base.height)
    };
    let filter_json = serde_json::to_vec(&spec.filter)
        .map_err(|e| RunError::Internal(format!("art-map `{name}`: the filter does not serialize: {e}")))?;
    let key = artmap_cache::key(source_bytes, spec.srgb, &filter_json, count, spec.rip);
    let report = |origin| ArtmapBuild {
        texture: name.to_string(),
        levels: count,
        origin,
        ms: start.elapsed().as_secs_f64() * 1e3,
    };
    if let Some((levels, origin)) = artmap_cache::get(&key) {
        return Ok((levels.clone(), report(origin)));
    }
    let program = spec.filter.program();
    let filtered = if spec.rip {
        vec![ripmap_atlas(device, queue, &program, base)?]
    } else {
        let mut runner = FilterRunner::new(device, queue, &program);
        let mut filtered = Vec::with_capacity(count as usize);
        for (index, level) in mip_chain(base, count).into_iter().enumerate() {
            filtered.push(runner.filter(&level, index as u32)?);
        }
        filtered
    };
    let levels = Arc::new(filtered);
    let on_disk = artmap_cache::put(&key, levels.clone());
    Ok((levels, report(Origin::Built { on_disk })))
}

/// Runs a filter style on level after level with one renderer: its
/// pipelines are built once, for the first level, and each further level
/// only replaces the filter's input (`Renderer::set_filter_input`).
pub struct FilterRunner<'d> {
    device: &'d wgpu::Device,
    queue: &'d wgpu::Queue,
    program: &'d npr_abi::StyleProgram,
    renderer: Option<Renderer>,
}

impl<'d> FilterRunner<'d> {
    pub fn new(
        device: &'d wgpu::Device,
        queue: &'d wgpu::Queue,
        program: &'d npr_abi::StyleProgram,
    ) -> FilterRunner<'d> {
        FilterRunner {
            device,
            queue,
            program,
            renderer: None,
        }
    }

    /// The filter's output on `level` (`frame` = `index`).
    pub fn filter(&mut self, level: &Level, index: u32) -> Result<Level, RunError> {
        let r = match self.renderer.as_mut() {
            Some(r) => {
                r.set_filter_input(level)?;
                r
            }
            None => self
                .renderer
                .insert(Renderer::new_filter(self.device, self.queue, self.program, level)?),
        };
        filtered_output(r, level, index)
    }
}

/// Run the filter on one level with a renderer of its own (what
/// [`FilterRunner`] does for a whole chain): its output target, read back,
/// is the filtered level (same size).
pub fn filter_level(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    program: &npr_abi::StyleProgram,
    level: &Level,
    index: u32,
) -> Result<Level, RunError> {
    FilterRunner::new(device, queue, program).filter(level, index)
}

fn filtered_output(r: &mut Renderer, level: &Level, index: u32) -> Result<Level, RunError> {
    let scene = crate::scene::Scene::empty();
    r.render(
        &scene,
        &FrameSpec {
            width: level.width,
            height: level.height,
            time_s: 0.0,
            frame: index,
            eye: 0,
        },
    )?;
    let out = r.read_output()?;
    if (out.width, out.height) != (level.width, level.height) {
        return Err(RunError::User(vec![npr_diag::Diagnostic::error(
            npr_diag::codes::BAD_FILTER,
            format!(
                "the filter's output is {}x{}, not the level's {}x{}",
                out.width, out.height, level.width, level.height
            ),
        )
        .with_help("an art-map filter's output pass must run at scale 1")]));
    }
    let pixels = (0..out.height)
        .flat_map(|y| (0..out.width).map(move |x| (x, y)))
        .map(|(x, y)| out.texel(x, y))
        .collect();
    Ok(Level {
        width: out.width,
        height: out.height,
        pixels,
    })
}
