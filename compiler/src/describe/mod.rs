//! Markdown descriptions of what the language offers, from the metadata
//! alone: stdlib operators (signature, parameters with type, unit, default
//! and range, doc, reference, specializations), builtins, pass kinds, units
//! and target formats. `npr doc` writes them as the reference and `npr lsp`
//! shows them on hover, so both say the same thing.

pub mod builtins;
pub mod guide;
pub mod language;

use npr_stdlib::{Default, Operator, Param, Ty, Unit};

/// A type as a style writes it.
pub fn ty_name(ty: Ty) -> String {
    match ty {
        Ty::Float => "float".into(),
        Ty::Int => "int".into(),
        Ty::Bool => "bool".into(),
        Ty::Vec2 => "vec2".into(),
        Ty::Vec3 => "vec3".into(),
        Ty::Vec4 => "vec4".into(),
        Ty::Color => "color".into(),
        Ty::Texture => "texture".into(),
        Ty::SampledTexture => "texture (sampled)".into(),
        Ty::Enum(variants) => format!("enum({})", variants.join(", ")),
    }
}

/// A unit's symbol, or "" for a plain number.
pub fn unit_symbol(unit: Unit) -> &'static str {
    match unit {
        Unit::None => "",
        other => other.name(),
    }
}

/// A number as the style would write it (no trailing `.0` on integers).
pub fn number(x: f64) -> String {
    if x.fract() == 0.0 && x.abs() < 1e15 {
        format!("{}", x as i64)
    } else {
        format!("{x}")
    }
}

fn with_unit(x: f64, unit: Unit) -> String {
    format!("{}{}", number(x), unit_symbol(unit))
}

/// A parameter's default, or `required`.
pub fn default_text(p: &Param) -> String {
    match p.default {
        Default::Required => "required".into(),
        Default::Number(x) => with_unit(x, p.unit),
        Default::Builtin(b) => format!("`{b}`"),
        Default::Variant(v) => v.to_string(),
    }
}

/// `lo..hi` with units, or "" when the parameter has no range.
pub fn range_text(p: &Param) -> String {
    p.range
        .map(|(lo, hi)| format!("{}..{}", with_unit(lo, p.unit), with_unit(hi, p.unit)))
        .unwrap_or_default()
}

/// `name(x: float, steps: int = 3 in 1..16) -> float`.
pub fn signature(op: &Operator) -> String {
    let params: Vec<String> = op
        .params
        .iter()
        .map(|p| {
            let mut s = format!("{}: {}", p.name, ty_name(p.ty));
            if p.unit != Unit::None {
                s.push_str(&format!(" [{}]", unit_symbol(p.unit)));
            }
            if p.default != Default::Required {
                s.push_str(&format!(" = {}", default_text(p).trim_matches('`')));
            }
            let range = range_text(p);
            if !range.is_empty() {
                s.push_str(&format!(" in {range}"));
            }
            s
        })
        .collect();
    format!("{}({}) -> {}", op.name, params.join(", "), ty_name(op.returns))
}

/// What an operator reads of each texture argument, in words, from its
/// declared footprints (`npr_stdlib::Footprint`): what decides fusion and a
/// tile's apron. Every operator runs in any pass kind that can call it.
pub fn reads_text(op: &Operator) -> String {
    let reads: Vec<String> = op
        .footprints
        .iter()
        .map(|(param, f)| match f {
            npr_stdlib::Footprint::Around {
                uv,
                radius: npr_stdlib::Radius::Texels(0),
            } => format!("`{param}` at the texel under `{uv}` only"),
            npr_stdlib::Footprint::Around {
                uv,
                radius: npr_stdlib::Radius::Texels(r),
            } => format!("`{param}` within {r} texel(s) of `{uv}`"),
            npr_stdlib::Footprint::Around {
                uv,
                radius: npr_stdlib::Radius::Scaled { param: by, k, max },
            } => format!("`{param}` within ⌈{k}·`{by}`⌉ texels of `{uv}` (at most {max})"),
            npr_stdlib::Footprint::Anywhere => format!("`{param}` anywhere (at a computed coordinate)"),
        })
        .collect();
    if reads.is_empty() {
        "no texture".into()
    } else {
        reads.join("; ")
    }
}

/// An operator's specializations as sentences.
pub fn specializations(op: &Operator) -> Vec<String> {
    op.specializations
        .iter()
        .map(|s| {
            format!(
                "`{}: {}` compiles to `{}` (the parameter is dropped)",
                s.param,
                number(s.value),
                s.use_operator
            )
        })
        .collect()
}

/// One parameter as a Markdown table row: name, type, unit, default, range, doc.
pub fn param_row(p: &Param) -> String {
    let unit = match p.unit {
        Unit::None => "—".to_string(),
        u => u.name().to_string(),
    };
    let range = range_text(p);
    format!(
        "| `{}` | {} | {} | {} | {} | {} |",
        p.name,
        ty_name(p.ty),
        unit,
        default_text(p),
        if range.is_empty() { "—".into() } else { range },
        p.doc.replace('|', "\\|")
    )
}

/// An operator in Markdown; `heading` is the `#`s of its title.
pub fn operator_markdown(op: &Operator, heading: &str) -> String {
    let mut out = format!(
        "{heading} `{}`\n\n```npr\n{}\n```\n\n{}\n\n",
        op.name,
        signature(op),
        op.doc
    );
    out.push_str(&format!("- **Source:** {}\n", op.reference));
    out.push_str(&format!("- **Reads:** {}\n", reads_text(op)));
    for s in specializations(op) {
        out.push_str(&format!("- **Specialization:** {s}\n"));
    }
    out.push('\n');
    if !op.params.is_empty() {
        out.push_str("| parameter | type | unit | default | range | doc |\n|---|---|---|---|---|---|\n");
        for p in op.params {
            out.push_str(&param_row(p));
            out.push('\n');
        }
        out.push('\n');
    }
    out
}
