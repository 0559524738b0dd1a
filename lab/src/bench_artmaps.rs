//! `npr bench artmaps`: what art-maps and rip-maps (Klein et al. 2000 §4.2)
//! cost. Two tables, both taken in one run:
//! - **build**: per filter style and source size, the box-filtered mip
//!   chain on the CPU, the filter run on each level on the GPU (per level
//!   and in all), and the rip-map atlas (every 2^-i × 2^-j level filtered);
//!   the cache is bypassed, so every figure is a real build;
//! - **sampling**: frame time of the same scene read through a plain
//!   mipped image, an art-map (trilinear), `sample_biased` and
//!   `sample_ripmap`, against a pass that samples nothing.

use crate::bench::{time_interleaved, wait_idle};
use npr_runner::artmap::{mip_chain, ripmap_atlas, FilterRunner, Level};
use npr_runner::{Gpu, RunError, StyleProgram};
use std::time::Instant;

/// One filter on one square source size.
#[derive(Debug, Clone)]
pub struct BuildRow {
    pub filter: String,
    pub size: u32,
    pub levels: u32,
    /// The mip chain, on the CPU.
    pub mip_ms: f64,
    /// The filter on each level, largest first.
    pub level_ms: Vec<f64>,
    /// Every level of the rip-map filtered and packed.
    pub rip_levels: u32,
    pub rip_ms: f64,
}

/// A deterministic source image: smooth value noise with some detail, so
/// that filters which threshold or blur see varied tones (their cost does
/// not depend on the content, but a constant image would hide a bug).
pub fn source(size: u32) -> Level {
    let hash = |x: u32, y: u32| {
        let mut h = x.wrapping_mul(0x9e37_79b1) ^ y.wrapping_mul(0x85eb_ca77);
        h ^= h >> 15;
        h = h.wrapping_mul(0x2c1b_3c6d);
        h ^= h >> 12;
        (h & 0xffff) as f32 / 65535.0
    };
    let pixels = (0..size * size)
        .map(|i| {
            let (x, y) = (i % size, i / size);
            let coarse = hash(x / 16, y / 16);
            let fine = hash(x, y);
            let v = 0.8 * coarse + 0.2 * fine;
            [v, 0.9 * v, 0.8 * v, 1.0]
        })
        .collect();
    Level {
        width: size,
        height: size,
        pixels,
    }
}

/// The build table: each filter program on each size.
pub fn build_rows(
    gpu: &Gpu,
    filters: &[(String, StyleProgram)],
    sizes: &[u32],
    mut progress: impl FnMut(&str),
) -> Result<Vec<BuildRow>, RunError> {
    let mut rows = Vec::new();
    for (name, program) in filters {
        for &size in sizes {
            progress(&format!("building {name} at {size}²"));
            let base = source(size);
            let t = Instant::now();
            let chain = mip_chain(base.clone(), u32::MAX);
            let mip_ms = t.elapsed().as_secs_f64() * 1e3;
            // One filter renderer for the chain, as `artmap::build` runs it:
            // level 0 pays for the pipelines, the others only rebind.
            let mut runner = FilterRunner::new(&gpu.device, &gpu.queue, program);
            let mut level_ms = Vec::with_capacity(chain.len());
            for (index, level) in chain.iter().enumerate() {
                let t = Instant::now();
                runner.filter(level, index as u32)?;
                wait_idle(gpu)?;
                level_ms.push(t.elapsed().as_secs_f64() * 1e3);
            }
            let rip_levels = npr_abi::RipmapAtlas {
                width: size,
                height: size,
            }
            .level_count();
            let t = Instant::now();
            ripmap_atlas(&gpu.device, &gpu.queue, program, base)?;
            wait_idle(gpu)?;
            let rip_ms = t.elapsed().as_secs_f64() * 1e3;
            rows.push(BuildRow {
                filter: name.clone(),
                size,
                levels: chain.len() as u32,
                mip_ms,
                level_ms,
                rip_levels,
                rip_ms,
            });
        }
    }
    Ok(rows)
}

pub fn build_table(rows: &[BuildRow]) -> String {
    let mut out = String::from(
        "| filter | source | levels | mip chain (CPU) ms | level 0 ms | smallest level ms | all levels ms | rip-map levels | rip-map ms | rip ÷ art-map |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for r in rows {
        let total: f64 = r.level_ms.iter().sum();
        let first = r.level_ms.first().copied().unwrap_or(f64::NAN);
        let last = r.level_ms.last().copied().unwrap_or(f64::NAN);
        out += &format!(
            "| {} | {}² | {} | {:.1} | {:.1} | {:.1} | {:.1} | {} | {:.1} | {:.1}× |\n",
            r.filter,
            r.size,
            r.levels,
            r.mip_ms,
            first,
            last,
            total,
            r.rip_levels,
            r.rip_ms,
            r.rip_ms / (r.mip_ms + total)
        );
    }
    out
}

/// One way of reading the texture in the sampling table.
pub struct SampleVariant {
    pub name: &'static str,
    /// The texture declaration and the expression of the pass's colour.
    pub texture: &'static str,
    pub color: &'static str,
}

/// The gallery's wall texture as a hatched art-map, read two ways below.
const HATCHED_WALL: &str =
    "texture t = artmap(image(\"textures/gallery_wall.png\", srgb), filter: \"filters/hatching.npr\") { wrap: repeat }";

/// The variants, the first being the baseline that samples nothing. Paths
/// are relative to `examples/` (the gallery's wall texture and the
/// hatching filter).
pub const SAMPLE_VARIANTS: [SampleVariant; 5] = [
    SampleVariant {
        name: "no texture (baseline)",
        texture: "",
        color: "vec4(uv, 0.5, 1.0)",
    },
    SampleVariant {
        name: "image, mips: on (trilinear)",
        texture: "texture t = image(\"textures/gallery_wall.png\", srgb) { mips: on, wrap: repeat }",
        color: "sample(t, uv * 4.0)",
    },
    SampleVariant {
        name: "art-map, trilinear",
        texture: HATCHED_WALL,
        color: "sample(t, uv * 4.0)",
    },
    SampleVariant {
        name: "art-map, sample_biased(+1)",
        texture: HATCHED_WALL,
        color: "sample_biased(t, uv * 4.0, 1.0)",
    },
    SampleVariant {
        name: "rip-map, sample_ripmap",
        texture: "texture t = ripmap(image(\"textures/gallery_wall.png\", srgb), filter: \"filters/hatching.npr\")",
        color: "sample_ripmap(t, uv * 4.0)",
    },
];

/// The style text of a variant: one render pass over the scene.
pub fn sample_style(v: &SampleVariant) -> String {
    format!(
        "style \"bench artmaps: {}\"\n{}\npass p: render(scene) {{\n  out c: rgba8unorm = {}\n}}\noutput p.c\n",
        v.name, v.texture, v.color
    )
}

#[derive(Debug, Clone)]
pub struct SampleRow {
    pub name: &'static str,
    pub ms: f64,
    /// Over the baseline's frame.
    pub ratio: f64,
}

/// Frame times of `programs` (in [`SAMPLE_VARIANTS`] order), interleaved.
pub fn sample_rows(
    gpu: &Gpu,
    programs: &[StyleProgram],
    scene: &npr_runner::scene::Scene,
    size: (u32, u32),
    frames: u32,
) -> Result<Vec<SampleRow>, RunError> {
    let refs: Vec<&StyleProgram> = programs.iter().collect();
    let times = time_interleaved(gpu, &refs, scene, size, frames)?;
    let base = times[0];
    Ok(SAMPLE_VARIANTS
        .iter()
        .zip(&times)
        .map(|(v, t)| SampleRow {
            name: v.name,
            ms: t * 1e3,
            ratio: t / base,
        })
        .collect())
}

pub fn sample_table(rows: &[SampleRow]) -> String {
    let mut out = String::from("| read | frame ms | × baseline |\n|---|---:|---:|\n");
    for r in rows {
        out += &format!("| {} | {:.3} | {:.2}× |\n", r.name, r.ms, r.ratio);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_source_is_deterministic_and_varied() {
        let a = source(64);
        assert_eq!(a, source(64));
        let tones: Vec<f32> = a.pixels.iter().map(|p| p[0]).collect();
        let (lo, hi) = tones
            .iter()
            .fold((f32::MAX, f32::MIN), |(lo, hi), v| (lo.min(*v), hi.max(*v)));
        assert!(hi - lo > 0.5, "tones span only {lo}..{hi}");
        assert!(tones.iter().all(|v| (0.0..=1.0).contains(v)));
    }

    #[test]
    fn every_variant_but_the_baseline_reads_its_texture() {
        for v in &SAMPLE_VARIANTS[1..] {
            assert!(v.color.contains("(t, "), "{}", v.name);
        }
        assert!(SAMPLE_VARIANTS[0].texture.is_empty());
    }
}
