//! `Manifest::validate` for compute passes: no target written, value
//! types that are slot types, an element stage and attributes only in the
//! vertex domain.

use super::*;

impl Manifest {
    /// A compute pass writes no target; its value types are slot types;
    /// only the vertex domain has an element stage and attributes.
    pub(super) fn validate_compute(&self, field: &str, p: &PassManifest) -> Result<(), Invalid> {
        let PassKindManifest::Compute {
            domain,
            attributes,
            values,
            elements_entry,
            pixels_of,
            samples,
            ..
        } = &p.kind
        else {
            return Ok(());
        };
        if !p.outputs.is_empty() {
            return bad(
                format!("{field}.outputs"),
                format!("compute pass `{}` writes targets", p.name),
            );
        }
        if values.is_empty() || values.len() > MAX_VALUE_SLOTS {
            return bad(
                format!("{field}.kind.values"),
                format!(
                    "compute pass `{}` has {} values; 1..={MAX_VALUE_SLOTS} are allowed",
                    p.name,
                    values.len()
                ),
            );
        }
        for (k, v) in values.iter().enumerate() {
            if !["float", "vec2", "vec3", "vec4"].contains(&v.ty.as_str()) {
                return bad(
                    format!("{field}.kind.values[{k}].ty"),
                    format!("`{}` is not a value type", v.ty),
                );
            }
            let reduces = matches!(v.kind, ValueKind::Reduce(_));
            if reduces != domain.has_elements() {
                return bad(
                    format!("{field}.kind.values[{k}].kind"),
                    format!("value `{}` does not belong to a pass over {}", v.name, domain.name()),
                );
            }
        }
        if elements_entry.is_some() != domain.has_elements() {
            return bad(
                format!("{field}.kind.elements_entry"),
                "exactly the passes over vertices or pixels have an element stage",
            );
        }
        if !domain.on_meshes() && !attributes.is_empty() {
            return bad(
                format!("{field}.kind.attributes"),
                format!("a pass over {} reads no vertex attributes", domain.name()),
            );
        }
        if let Some(k) = attributes.iter().position(|a| *a == Attribute::PatchWeight) {
            return bad(
                format!("{field}.kind.attributes[{k}]"),
                "a compute pass reads no patch weights (render passes only, §3.6)",
            );
        }
        match (domain, pixels_of) {
            (ComputeDomain::Pixels, Some(t)) => match self.targets.get(*t) {
                Some(target) if target.format == Format::R32float => {}
                Some(target) => {
                    return bad(
                        format!("{field}.kind.pixels_of"),
                        format!("ID target `{}` is {}, not r32float", target.name, target.format.name()),
                    )
                }
                None => {
                    return bad(
                        format!("{field}.kind.pixels_of"),
                        format!("target {t} does not exist ({} targets)", self.targets.len()),
                    )
                }
            },
            (ComputeDomain::Pixels, None) => {
                return bad(
                    format!("{field}.kind.pixels_of"),
                    "a pass over pixels names its ID target",
                )
            }
            (_, Some(_)) => {
                return bad(
                    format!("{field}.kind.pixels_of"),
                    "only a pass over pixels has an ID target",
                )
            }
            (_, None) => {}
        }
        match (domain, samples) {
            (ComputeDomain::Samples, Some(spec)) if (1..=MAX_SAMPLES_PER_OBJECT).contains(&spec.count) => {}
            (ComputeDomain::Samples, Some(spec)) => {
                return bad(
                    format!("{field}.kind.samples.count"),
                    format!(
                        "{} samples per object; 1..={MAX_SAMPLES_PER_OBJECT} are allowed",
                        spec.count
                    ),
                )
            }
            (ComputeDomain::Samples, None) => {
                return bad(format!("{field}.kind.samples"), "a pass over samples says how many")
            }
            (_, Some(_)) => return bad(format!("{field}.kind.samples"), "only a pass over samples has samples"),
            (_, None) => {}
        }
        Ok(())
    }
}
