//! `Style.setParam` without a GPU: a value written as `--set` takes it,
//! typed against the compiled style's manifest by the ABI's one rule
//! (`npr_abi::param_value::type_value`), and made the parameter's constant
//! in the style's manifest, which a runtime reads. The refusals are those
//! of `npr_runner::embed::StyleRuntime::set_param`: an unknown name E0101,
//! a wrong type, unit or range E0201-E0203, a parameter folded into the
//! shaders or bound per object E0502.

use npr_abi::manifest::{ParamBinding, ParamManifest};
use npr_abi::param_literal::{did_you_mean, read_literal, SettingOrigin};
use npr_abi::param_value::{type_value, ParamShape};
use npr_diag::{codes, Diagnostic};

/// Whether the running style reads `p` from its uniform block.
fn settable(p: &ParamManifest) -> bool {
    p.binding == ParamBinding::Uniform
}

/// Set `name` to `value` in `params`; on a refusal nothing changes.
pub fn set_param(params: &mut [ParamManifest], name: &str, value: &str) -> Result<(), Diagnostic> {
    let Some(index) = params.iter().position(|p| p.name == name) else {
        return Err(unknown_param(name, params));
    };
    let param = &params[index];
    let typed = type_value(
        &ParamShape::of_manifest(param),
        &read_literal(value.trim()),
        value.trim(),
        &SettingOrigin::Host,
    )
    .map_err(|r| {
        Diagnostic::error(r.code, format!("{}: {}", SettingOrigin::Host.subject(name), r.message))
            .with_help(format!("{} ({})", r.help, r.label))
    })?;
    if !settable(param) {
        return Err(Diagnostic::error(
            codes::BAD_ARGUMENT_VALUE,
            format!(
                "setParam(\"{name}\"): `{name}` cannot change at run time: {}",
                if param.binding == ParamBinding::Removed {
                    "nothing the style's output depends on reads it"
                } else {
                    "it was folded into the style's shaders when the style was compiled"
                }
            ),
        )
        .with_help("compile the style with `{ keepParams: true }` to change its parameters at run time"));
    }
    params[index].set_constant(&typed);
    Ok(())
}

/// E0101 for a name the style has no settable parameter of.
fn unknown_param(name: &str, params: &[ParamManifest]) -> Diagnostic {
    let names: Vec<&str> = params.iter().filter(|p| settable(p)).map(|p| p.name.as_str()).collect();
    let d = Diagnostic::error(
        codes::UNKNOWN_NAME,
        format!("setParam(\"{name}\"): the style has no parameter `{name}` that can change at run time"),
    );
    match did_you_mean(name, names.iter().copied()) {
        Some(close) => d.with_help(format!("did you mean `{close}`?")),
        None if names.is_empty() => d.with_help(
            "this style has no run-time parameters: compile it with `{ keepParams: true }` to keep them in a uniform block",
        ),
        None => d.with_help(format!("its parameters are: {}", names.join(", "))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compile::{compile, Request};

    fn params(keep_params: bool) -> Vec<ParamManifest> {
        let source = "style \"S\"\nparam bands: int = 3 in 1..8\nparam unused: float = 1\npass final: image() {\n  let v = toon(0.5, steps: bands)\n  out color: rgba8unorm = vec4(v, v, v, 1.0)\n}\noutput final.color\n";
        let request = Request {
            name: "s.npr".into(),
            source: source.into(),
            files: Vec::new(),
            keep_params,
        };
        compile(&request).expect("compiles").manifest.params
    }

    #[test]
    fn a_value_is_typed_as_set_types_it_and_a_refusal_changes_nothing() {
        let mut p = params(true);
        set_param(&mut p, "bands", "5").expect("in range");
        let bands = |p: &[ParamManifest]| p.iter().find(|p| p.name == "bands").expect("bands").default.clone();
        assert_eq!(bands(&p), vec![5.0]);
        for (value, code) in [
            ("seven", codes::TYPE_MISMATCH),
            ("40", codes::OUT_OF_RANGE),
            ("2px", codes::UNIT_MISMATCH),
        ] {
            let d = set_param(&mut p, "bands", value).expect_err(value);
            assert_eq!(d.code, code, "{value}: {}", d.message);
            assert_eq!(bands(&p), vec![5.0], "{value} changed it");
        }
        let d = set_param(&mut p, "band", "5").expect_err("unknown");
        assert_eq!(
            (d.code, d.help.as_deref()),
            (codes::UNKNOWN_NAME, Some("did you mean `bands`?"))
        );
    }

    #[test]
    fn a_folded_parameter_cannot_change() {
        let mut p = params(false);
        let d = set_param(&mut p, "bands", "5").expect_err("folded");
        assert!(
            d.code == codes::BAD_ARGUMENT_VALUE || d.code == codes::UNKNOWN_NAME,
            "{d:?}"
        );
    }
}
