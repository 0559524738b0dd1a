//! The arguments of `filter("hatching.npr", spacing: 8)` in an art-map
//! (Klein et al. 2000 §4.2): new defaults for the filter style's params,
//! checked against the params the filter declares, as `--set` values are
//! against a style's: the name (E0101, did you mean), the number of
//! components (E0201), the unit (E0202; a plain number fits any), the
//! declared range (E0203) and, for an enum param, the variant named
//! (`mode: soft`; E0201 with did you mean), each pointing at the argument
//! in the host style.

use crate::ir::FilterArg;
use crate::mid::overrides::ParamOverride;
use abi::manifest::{ParamBinding, ParamManifest};
use diag::diagnostic::did_you_mean;
use diag::{codes, Diagnostic};
use stdlib::Unit;

/// The overrides `args` make of the filter `filter_name`'s `params`, or
/// every argument that does not fit.
pub fn overrides(
    args: &[FilterArg],
    params: &[ParamManifest],
    filter_name: &str,
) -> Result<Vec<ParamOverride>, Vec<Diagnostic>> {
    let settable: Vec<&ParamManifest> = params
        .iter()
        .filter(|p| p.binding != ParamBinding::PerObject && p.ty != "texture")
        .collect();
    let mut diags = Vec::new();
    let mut out = Vec::new();
    for a in args {
        let Some(p) = settable.iter().find(|p| p.name == a.name) else {
            let names: Vec<&str> = settable.iter().map(|p| p.name.as_str()).collect();
            let mut d = Diagnostic::error(
                codes::UNKNOWN_NAME,
                format!("filter `{filter_name}` has no param `{}`", a.name),
            )
            .with_primary(a.span, "not a param of the filter");
            d = match did_you_mean(&a.name, names.iter().copied()) {
                Some(s) => d.with_help(format!("did you mean `{s}`?")),
                None if names.is_empty() => d.with_help(format!("`{filter_name}` declares no params")),
                None => d.with_help(format!("its params are: {}", names.join(", "))),
            };
            diags.push(d);
            continue;
        };
        if !p.enum_variants.is_empty() {
            match choice(a, p, filter_name) {
                Ok(index) => out.push(ParamOverride {
                    name: a.name.clone(),
                    value: vec![index as f64],
                    percent_of_height: false,
                }),
                Err(d) => diags.push(d),
            }
            continue;
        }
        if let Some(name) = &a.choice {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!("`{}` of filter `{filter_name}` is {}", a.name, p.ty),
                )
                .with_primary(a.span, format!("`{name}` is a name, not a value"))
                .with_help("give a constant such as `8`, `2px` or `#ff0000`"),
            );
            continue;
        }
        if a.value.len() != p.components as usize {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!("`{}` of filter `{filter_name}` is {}", a.name, p.ty),
                )
                .with_primary(
                    a.span,
                    format!("this has {} component(s), not {}", a.value.len(), p.components),
                ),
            );
            continue;
        }
        if a.unit != Unit::None && a.unit.name() != p.unit {
            let wanted = if p.unit == Unit::None.name() {
                p.unit.clone()
            } else {
                format!("in {}", p.unit)
            };
            diags.push(
                Diagnostic::error(
                    codes::UNIT_MISMATCH,
                    format!("`{}` of filter `{filter_name}` is {wanted}", a.name),
                )
                .with_primary(a.span, format!("this is in {}", a.unit.name()))
                .with_help("write the value in the param's unit, or as a plain number"),
            );
            continue;
        }
        if let Some((lo, hi)) = p.range {
            if let Some(v) = a.value.iter().find(|v| !(lo..=hi).contains(*v)) {
                diags.push(
                    Diagnostic::error(codes::OUT_OF_RANGE, format!("`{}` out of the filter's range", a.name))
                        .with_primary(a.span, format!("{v} is outside {lo}..{hi}")),
                );
                continue;
            }
        }
        out.push(ParamOverride {
            name: a.name.clone(),
            value: a.value.clone(),
            percent_of_height: false,
        });
    }
    if diags.is_empty() {
        Ok(out)
    } else {
        Err(diags)
    }
}

/// The variant index `a` chooses of the enum param `p`, as `--set` types an
/// enum (`src/set_params.rs`): a name among the variants, E0201 otherwise,
/// with the nearest variant when one is close.
fn choice(a: &FilterArg, p: &ParamManifest, filter_name: &str) -> Result<usize, Diagnostic> {
    let variants = p.enum_variants.join(" | ");
    let Some(name) = &a.choice else {
        return Err(Diagnostic::error(
            codes::TYPE_MISMATCH,
            format!("`{}` of filter `{filter_name}` is a choice of names", a.name),
        )
        .with_primary(a.span, format!("expected one of {variants}"))
        .with_help(format!(
            "write the variant's name, e.g. `{}: {}`",
            a.name, p.enum_variants[0]
        )));
    };
    p.enum_variants.iter().position(|v| v == name).ok_or_else(|| {
        let help = match did_you_mean(name, p.enum_variants.iter().map(String::as_str)) {
            Some(close) => format!("did you mean `{close}`?"),
            None => format!("one of: {}", p.enum_variants.join(", ")),
        };
        Diagnostic::error(
            codes::TYPE_MISMATCH,
            format!("`{name}` is not a variant of `{}` in filter `{filter_name}`", a.name),
        )
        .with_primary(a.span, format!("expected one of {variants}"))
        .with_help(help)
    })
}
