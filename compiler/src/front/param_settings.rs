//! Parameter settings: new defaults given from outside a style's text.
//! `--set name=value` on the command line (the studio's controls are
//! `--set` values too), and the arguments of `filter("hatching.npr",
//! spacing: 8)` in a host style's art-map (Klein et al. 2000 §4.2), which
//! are new defaults for the filter style's params.
//!
//! Each is a name and a `Literal` with their spans, read where the text
//! is (the CLI reads `--set` text, resolve reads a filter's arguments from
//! the host's AST). [`type_settings`] types them all against the params
//! the style declares, in the one compile, after typecheck: the name (E0101
//! with "did you mean"), a per-object param (E0502), then the value
//! (`param_values::type_value`: E0201 type, E0202 unit, E0203 range),
//! each diagnostic pointing at the setting. `mid::overrides::apply` then
//! writes the values in as defaults.

use crate::front::param_values::{shape_of_ir, type_value};
use crate::ir::{Ir, ParamSetting, SettingOrigin};
use npr_abi::ParamOverride;
use npr_diag::diagnostic::did_you_mean;
use npr_diag::{codes, Diagnostic, SourceMap};

/// Type every setting against the params of `ir` (after typecheck): the
/// overrides to apply, a later setting of a name replacing an earlier one,
/// or every mistake at once.
pub fn type_settings(
    ir: &Ir,
    settings: &[ParamSetting],
    sources: &SourceMap,
) -> Result<Vec<ParamOverride>, Vec<Diagnostic>> {
    let mut overrides: Vec<ParamOverride> = Vec::new();
    let mut diags = Vec::new();
    for s in settings {
        let Some(param) = ir.params.iter().find(|p| p.name == s.name) else {
            diags.push(unknown_name(ir, s));
            continue;
        };
        let text = sources.snippet(s.value_span).trim();
        match type_value(&shape_of_ir(ir, param), &s.value, text, &s.origin) {
            Ok(o) => {
                // A later `--set` of the same name wins, as in most CLIs
                // (a filter's argument cannot repeat: resolve refuses it).
                overrides.retain(|x| x.name != o.name);
                overrides.push(o);
            }
            Err(r) => diags.push(
                Diagnostic::error(r.code, format!("{}: {}", s.origin.subject(&s.name), r.message))
                    .with_primary(s.value_span, r.label)
                    .with_help(r.help),
            ),
        }
    }
    if diags.is_empty() {
        Ok(overrides)
    } else {
        Err(diags)
    }
}

fn unknown_name(ir: &Ir, s: &ParamSetting) -> Diagnostic {
    let name = &s.name;
    let owner = s.origin.owner();
    // Per-object params are left out: a setting cannot change them. (A
    // texture a scene binds per object is a texture, not a param.)
    let settable: Vec<&str> = ir
        .params
        .iter()
        .filter(|p| !p.per_object)
        .map(|p| p.name.as_str())
        .collect();
    let d = Diagnostic::error(
        codes::UNKNOWN_NAME,
        format!("{}: the {owner} has no parameter `{name}`", s.origin.subject(name)),
    )
    .with_primary(s.name_span, "no parameter of this name");
    match did_you_mean(name, settable.iter().copied()) {
        Some(close) => d.with_help(format!("did you mean `{close}`?")),
        None if settable.is_empty() => d.with_help(match s.origin {
            SettingOrigin::CommandLine | SettingOrigin::TestFile | SettingOrigin::Host => {
                "this style declares no parameter that --set can change"
            }
            SettingOrigin::FilterArgument { .. } => "this filter declares no parameter that an argument can set",
        }),
        None => d.with_help(format!("its parameters are: {}", settable.join(", "))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::param_values::{ParamShape, ValueKind};
    use crate::ir::Literal;
    use npr_diag::Span;

    #[test]
    fn a_colour_is_typed_by_the_declared_type_that_the_manifest_keeps() {
        // Named without `.npr`: nothing can find the style's text again to
        // learn which params are colours; the IR and the manifest say so.
        let text = "style \"c\"\nparam base: color = #e07a3a\n\
                    pass p: render(scene) {\n  out c: rgba8unorm = base\n}\noutput p.c\n";
        let mut sources = SourceMap::new();
        let file = sources.add("--set", "base=#3080ff");
        let setting = ParamSetting {
            name: "base".into(),
            name_span: Span::new(file, 0, 4),
            value: Literal::Colour([48.0 / 255.0, 128.0 / 255.0, 1.0, 1.0]),
            value_span: Span::new(file, 5, 12),
            origin: SettingOrigin::CommandLine,
        };
        let opts = crate::CompileOptions {
            settings: vec![setting],
            ..Default::default()
        };
        let compiled = crate::compile_source("colour", text, std::path::Path::new("."), &mut sources, &opts)
            .unwrap_or_else(|e| panic!("{e:?}"));
        let base = &compiled.manifest.params[0];
        assert_eq!(base.ty, "color");
        assert_eq!(base.default, vec![48.0 / 255.0, 128.0 / 255.0, 1.0, 1.0]);
        // The manifest alone tells the studio how to read a control's value.
        assert_eq!(ParamShape::of_manifest(base).kind, ValueKind::Colour);
    }
}
