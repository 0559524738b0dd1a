//! `npr bench ops`: each MetaTexture variant's cost against a plain texture
//! sample pass at the same resolution, next to its error from
//! `npr_stdlib::metrics` (a benchmark, never a test).
//!
//! Cost: one style per variant, the same render pass over the scene with
//! only the texture read changed, so the ratio isolates the operator. Frames
//! are timed round robin over all variants (render + GPU wait each), so a
//! change of machine load hits every variant alike; the fastest frame is
//! reported (the least disturbed by other work on a shared CPU).
//!
//! Error, on the analytic ground plane of `npr_stdlib::metrics` (1–1000 m,
//! elevations 90°–2°, azimuths 0°/35°, w = 32 px): scale = mean
//! |log₂(screen-space period / target)| of the blend-weighted taps; anisotropy
//! = mean |angle between the texture's screen-space axes − 90°|; contrast =
//! |σ_M/σ_T − 1| measured with the f64 reference on a white-noise example.

use npr_stdlib::metrics::{self, Variant};

/// One variant: the name, `let`s before the read, the read expression, and
/// the metrics model (`None`: not modelled on the plane).
pub struct OpsVariant {
    pub name: &'static str,
    pub lets: &'static str,
    pub read: &'static str,
    pub model: Option<Variant>,
}

/// The bench style; `LETS` and `READ` are substituted per variant.
pub const OPS_STYLE: &str = "style \"bench\"\ntexture grain = noise(size: 128, octaves: 4, seed: 3, kind: gradient) { wrap: repeat, mips: on }\npass p: render(scene) {\nLETS  out c: rgba8unorm = READ\n}\noutput p.c\n";

const SMOOTH: &str = "  let g = uv_gradients(density: vec2(8.0, 8.0))\n";
const PAPER: &str = "  let g = uv_gradients(density: vec2(8.0, 8.0), mode: paper)\n";

fn v(skew: i64) -> Variant {
    Variant::new(32.0, skew)
}

pub fn variants() -> Vec<OpsVariant> {
    let smooth = |skew| Variant {
        smooth: true,
        ..v(skew)
    };
    vec![
        OpsVariant {
            name: "plain texture sample (baseline)",
            lets: "",
            read: "sample(grain, uv * 8.0)",
            model: Some(Variant { plain: true, ..v(0) }),
        },
        OpsVariant {
            name: "4-tap, derivative gradients",
            lets: "",
            read: "metatexture(grain, uv * 8.0, width: 48px, skew: 0)",
            model: Some(v(0)),
        },
        OpsVariant {
            name: "4-tap, smooth vertex gradients ([T_s B_s]⁻¹)",
            lets: SMOOTH,
            read: "metatexture_grad(grain, uv * 8.0, g.xy, g.zw, width: 48px, skew: 0)",
            // Exact on the plane: the same model as derivatives.
            model: Some(v(0)),
        },
        OpsVariant {
            name: "4-tap, smooth vertex gradients (eqs. 9–10 as printed)",
            lets: PAPER,
            read: "metatexture_grad(grain, uv * 8.0, g.xy, g.zw, width: 48px, skew: 0)",
            model: Some(smooth(0)),
        },
        OpsVariant {
            name: "4-tap + contrast ÷√c",
            lets: "",
            read: "metatexture(grain, uv * 8.0, width: 48px, skew: 0, contrast: variance)",
            model: Some(Variant { contrast: 2, ..v(0) }),
        },
        OpsVariant {
            name: "4-tap + contrast × c (printed)",
            lets: "",
            read: "metatexture(grain, uv * 8.0, width: 48px, skew: 0, contrast: printed)",
            model: Some(Variant { contrast: 1, ..v(0) }),
        },
        OpsVariant {
            name: "4-tap + radial α (eq. 11)",
            lets: "",
            read: "metatexture(grain, uv * 8.0, width: 48px * radial_alpha(), skew: 0)",
            model: Some(Variant { radial: true, ..v(0) }),
        },
        OpsVariant {
            name: "8-tap skew n = 1",
            lets: "",
            read: "metatexture(grain, uv * 8.0, width: 48px, skew: 1)",
            model: Some(v(1)),
        },
        OpsVariant {
            name: "8-tap skew n = 2",
            lets: "",
            read: "metatexture(grain, uv * 8.0, width: 48px, skew: 2)",
            model: Some(v(2)),
        },
        OpsVariant {
            name: "8-tap skew n = 3",
            lets: "",
            read: "metatexture(grain, uv * 8.0, width: 48px, skew: 3)",
            model: Some(v(3)),
        },
        OpsVariant {
            name: "8-tap skew n = 4",
            lets: "",
            read: "metatexture(grain, uv * 8.0, width: 48px, skew: 4)",
            model: Some(v(4)),
        },
        OpsVariant {
            name: "8-tap skew n = 4, smooth vertex gradients ([T_s B_s]⁻¹)",
            lets: SMOOTH,
            read: "metatexture_grad(grain, uv * 8.0, g.xy, g.zw, width: 48px, skew: 4)",
            model: Some(v(4)),
        },
        OpsVariant {
            name: "8-tap skew n = 4, smooth vertex gradients (eqs. 9–10 as printed)",
            lets: PAPER,
            read: "metatexture_grad(grain, uv * 8.0, g.xy, g.zw, width: 48px, skew: 4)",
            model: Some(smooth(4)),
        },
        OpsVariant {
            name: "8-tap n = 4 + contrast ÷√c + radial α",
            lets: "",
            read: "metatexture(grain, uv * 8.0, width: 48px * radial_alpha(), skew: 4, contrast: variance)",
            model: Some(Variant {
                contrast: 2,
                radial: true,
                ..v(4)
            }),
        },
        OpsVariant {
            name: "4-tap + contour orientation (§3.5), smooth gradients",
            lets: SMOOTH,
            read: "metatexture_contour_grad(grain, uv * 8.0, g.xy, g.zw, width: 48px, skew: 0)",
            model: None,
        },
    ]
}

/// The style text of a variant.
pub fn style(v: &OpsVariant) -> String {
    OPS_STYLE.replace("LETS", v.lets).replace("READ", v.read)
}

/// (scale, anisotropy in degrees, contrast error) of a modelled variant.
pub fn errors(model: &Variant) -> (f64, f64, f64) {
    let samples = metrics::standard_plane_set(64, 4);
    let e = metrics::variant_error(&samples, model);
    let contrast = if model.plain {
        0.0
    } else {
        (metrics::contrast_ratio(&metrics::noise_texture(64, 5), &samples, model) - 1.0).abs()
    };
    (e.scale, e.anisotropy_deg, contrast)
}

/// One variant's row of the table.
#[derive(Debug, Clone)]
pub struct Row {
    pub name: &'static str,
    pub frame_s: f64,
    /// Frame time over the plain sample's (the first variant).
    pub vs_plain: f64,
    /// (scale, anisotropy in degrees, contrast error) from [`errors`];
    /// `None` for a variant the plane does not model.
    pub errors: Option<(f64, f64, f64)>,
}

/// The rows of `variants` from their fastest frame times (same order,
/// the plain sample first).
pub fn rows(variants: &[OpsVariant], best: &[f64]) -> Vec<Row> {
    variants
        .iter()
        .zip(best)
        .map(|(v, t)| Row {
            name: v.name,
            frame_s: *t,
            vs_plain: t / best[0],
            errors: v.model.as_ref().map(errors),
        })
        .collect()
}

/// The rows as a Markdown table.
pub fn table(rows: &[Row]) -> String {
    let mut s = String::from(
        "| variant | ms/frame | cost vs plain sample | scale error | anisotropy | contrast error |\n|---|---:|---:|---:|---:|---:|\n",
    );
    for r in rows {
        let errors = match r.errors {
            Some((scale, aniso, contrast)) => format!("{scale:.3} | {aniso:.1}° | {contrast:.3}"),
            None => "— | — | —".to_string(),
        };
        s += &format!(
            "| {} | {:.3} | {:.2}x | {errors} |\n",
            r.name,
            r.frame_s * 1e3,
            r.vs_plain
        );
    }
    s
}
