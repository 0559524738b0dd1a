//! `Style.setParam` without a GPU: the rule every host API follows
//! (`npr_abi::host_param`: a value written as `--set` takes it, typed
//! against the compiled style's manifest; an unknown name E0101, a wrong
//! type, unit or range E0201-E0203, a parameter folded into the shaders or
//! bound per object E0502), made the parameter's constant in the style's
//! manifest, which a runtime reads.

use npr_abi::host_param::{type_host_setting, JS_API};
use npr_abi::manifest::ParamManifest;
use npr_diag::Diagnostic;

/// Set `name` to `value` in `params`; on a refusal nothing changes.
pub fn set_param(params: &mut [ParamManifest], name: &str, value: &str) -> Result<(), Diagnostic> {
    let (index, typed) = type_host_setting(params, name, value, &JS_API)
        .map_err(|r| Diagnostic::error(r.code, r.message).with_help(r.help))?;
    params[index].set_constant(&typed);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compile::{compile, Request};
    use npr_diag::codes;

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
