//! `--set name=value` on the command line: clap's check of its shape, and
//! the one-shot commands' compile with the settings
//! (`npr_compiler::set_values`, which reads and types them), diagnostics
//! printed.

use npr_compiler::set_values::compile_with_sets;
use npr_compiler::{CompileOptions, Compiled};
use npr_diag::printer::Printer;
use npr_diag::SourceMap;
use std::path::Path;

/// `npr_compiler::set_values::compile_with_sets` for the one-shot commands: diagnostics printed, the
/// error is the exit code.
pub(crate) fn compile(
    style: &Path,
    sets: &[String],
    sources: &mut SourceMap,
    opts: &CompileOptions,
    printer: &Printer,
) -> Result<Compiled, i32> {
    let result = compile_with_sets(style, sets, sources, opts);
    crate::printer::report_compile(result, sources, printer)
}

/// clap's value parser: `name=value` with a name, else a usage error (E0501).
pub fn parse_set_arg(s: &str) -> Result<String, String> {
    match s.split_once('=') {
        Some((name, _)) if !name.trim().is_empty() => Ok(s.to_string()),
        _ => Err("expected NAME=VALUE, e.g. --set bands=5 or --set base=#3080ff".into()),
    }
}

#[cfg(test)]
mod tests {
    use npr_abi::manifest::{ParamBinding, ParamManifest};
    use npr_abi::param_literal::read_literal;
    use npr_abi::param_value::{format_literal, type_value, ParamShape};
    use npr_abi::ParamOverride;
    use npr_compiler::ir::{Literal, SettingOrigin};
    use npr_diag::codes;

    fn param(ty: &str, unit: &str, default: Vec<f64>, range: Option<(f64, f64)>) -> ParamShape {
        ParamShape::of_manifest(&ParamManifest {
            name: "p".into(),
            doc: String::new(),
            ty: ty.into(),
            unit: unit.into(),
            components: default.len() as u32,
            default,
            default_percent_of_height: false,
            range,
            enum_variants: Vec::new(),
            keyframes: Vec::new(),
            interpolation: "linear".into(),
            binding: ParamBinding::Folded,
            offset: None,
        })
    }

    /// `text` typed as a `--set` value of `p`.
    fn parse_value(p: &ParamShape, text: &str) -> Result<ParamOverride, &'static str> {
        type_value(p, &read_literal(text), text, &SettingOrigin::CommandLine).map_err(|r| r.code)
    }

    #[test]
    fn values_are_read_in_canonical_units() {
        let deg = param("deg", "deg", vec![0.0], None);
        let v = parse_value(&deg, "90deg").expect("deg").value[0];
        assert!((v - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        let m = param("m", "m", vec![1.0], None);
        assert_eq!(parse_value(&m, "50mm").expect("mm").value, vec![0.05]);
        let px = param("px", "px", vec![2.0], Some((0.0, 16.0)));
        assert!(parse_value(&px, "50%").expect("%").percent_of_height);
        assert_eq!(parse_value(&px, "16px").expect("px").value, vec![16.0]);
        assert_eq!(parse_value(&px, "17px").unwrap_err(), codes::OUT_OF_RANGE);
        assert_eq!(parse_value(&px, "2").unwrap_err(), codes::UNIT_MISMATCH);
        assert_eq!(parse_value(&px, "2m").unwrap_err(), codes::UNIT_MISMATCH);
        let int = param("int", "a plain number", vec![3.0], Some((1.0, 8.0)));
        assert_eq!(parse_value(&int, "2.5").unwrap_err(), codes::TYPE_MISMATCH);
        assert_eq!(parse_value(&int, "1e1").unwrap_err(), codes::TYPE_MISMATCH);
        let f = param("float", "a plain number", vec![0.5], None);
        assert_eq!(parse_value(&f, "1e-3").expect("exponent").value, vec![1e-3]);
        assert_eq!(parse_value(&f, "x").unwrap_err(), codes::TYPE_MISMATCH);
    }

    #[test]
    fn the_text_is_read_before_the_parameter_is_known() {
        assert_eq!(read_literal("#ff0000"), Literal::Colour([1.0, 0.0, 0.0, 1.0]));
        assert_eq!(read_literal("#12"), Literal::Unreadable);
        assert_eq!(read_literal("0.2..0.6"), Literal::Range(0.2, 0.6));
        assert_eq!(read_literal("0.2..x"), Literal::Unreadable);
        assert_eq!(read_literal("cubic"), Literal::Name("cubic".into()));
        assert_eq!(read_literal("false"), Literal::Bool(false));
        assert_eq!(read_literal("inf"), Literal::Name("inf".into()));
        assert_eq!(read_literal("-"), Literal::Unreadable);
        assert_eq!(
            read_literal("1, 0.5"),
            Literal::Numbers {
                values: vec![1.0, 0.5],
                suffix: String::new(),
                whole: false
            }
        );
        assert_eq!(read_literal("1px, 2"), Literal::Unreadable);
        assert_eq!(read_literal("3"), Literal::number(3.0, "", true));
        assert_eq!(read_literal("2km"), Literal::number(2.0, "km", true));
    }

    #[test]
    fn every_literal_written_reads_back_to_its_value() {
        let mut e = param("enum(a|b)", "a plain number", vec![1.0], None);
        e.variants = vec!["a".into(), "b".into()];
        let cases = [
            (param("float", "a plain number", vec![0.25], None), vec![0.1]),
            (param("int", "a plain number", vec![3.0], None), vec![7.0]),
            (param("bool", "a plain number", vec![1.0], None), vec![0.0]),
            (param("px", "px", vec![2.0], None), vec![3.5]),
            (param("deg", "deg", vec![0.5], None), vec![30f64.to_radians()]),
            (
                param("color", "a plain number", vec![1.0, 0.5, 0.0, 1.0], None),
                vec![48.0 / 255.0, 128.0 / 255.0, 1.0, 1.0],
            ),
            (param("range", "a plain number", vec![0.2, 0.6], None), vec![0.1, 0.9]),
            (
                param("vec3", "a plain number", vec![0.0; 3], None),
                vec![1.0, -2.5, 0.125],
            ),
            (e, vec![0.0]),
        ];
        for (p, v) in cases {
            let text = format_literal(&p, &v).expect("formattable");
            let back = parse_value(&p, &text)
                .unwrap_or_else(|e| panic!("{} `{text}`: {e:?}", p.ty))
                .value;
            assert_eq!(back.len(), v.len(), "{} `{text}`", p.ty);
            for (a, b) in back.iter().zip(&v) {
                assert!((a - b).abs() < 1e-12, "{} `{text}`: {a} vs {b}", p.ty);
            }
        }
    }
}
