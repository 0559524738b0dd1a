//! naga validation of every emitted module. A failure is a compiler bug, not
//! a user error: it is reported as an internal error naming the pass and the
//! `.npr` span that produced the code.
//!
//! naga itself can panic on WGSL it should reject or accept (naga 30's
//! constant evaluator has `unreachable!`s: soak case 272687,
//! docs/FUZZING.md). Nothing may panic on any input (ARCHITECTURE.md), so
//! a panic inside naga becomes that same internal error, never an abort.

use naga::valid::{Capabilities, ValidationFlags, Validator};

/// A module naga parsed and validated, with what validation learnt of it
/// (which globals each entry point uses: `back::device_needs`).
pub type ValidModule = (naga::Module, naga::valid::ModuleInfo);

/// Parse and validate WGSL with naga; `Err` holds naga's rendered message
/// (or, if naga panicked, its panic message). The panic is expected
/// (`npr_diag::panics`): `npr` prints the internal error, not Rust's panic line.
pub fn validate_wgsl(name: &str, wgsl: &str) -> Result<ValidModule, String> {
    npr_diag::panics::catch(|| parse_and_validate(name, wgsl))
        .unwrap_or_else(|why| Err(format!("naga panicked on {name}: {why}")))
}

fn parse_and_validate(name: &str, wgsl: &str) -> Result<ValidModule, String> {
    let module = naga::front::wgsl::parse_str(wgsl).map_err(|e| e.emit_to_string_with_path(wgsl, name))?;
    let info = Validator::new(ValidationFlags::all(), Capabilities::default())
        .validate(&module)
        .map_err(|e| e.emit_to_string_with_path(wgsl, name))?;
    Ok((module, info))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The WGSL of soak case 272687 reduced: a constant `select` over a
    /// vector built from a nested vector, which naga 30 evaluates at parse
    /// time and panics on. The emitter no longer writes it
    /// (`emit::uses::needs_runtime_condition`); a panic like it is an
    /// internal error here, not an abort. When a naga upgrade fixes the
    /// bug, the first assertion fails: then keep the test with another
    /// input naga panics on, or drop the workaround.
    #[test]
    fn a_panic_in_naga_is_an_error() {
        let wgsl =
            "fn f() -> vec3<f32> {\n    return select(vec3<f32>(1.0, vec2<f32>(2.0)), vec3<f32>(1.0), 1.0 > 2.0);\n}\n";
        // (naga's panic message is printed to stderr; the hook is global,
        // so it is left alone while other tests run.)
        let raw = std::panic::catch_unwind(|| parse_and_validate("case.wgsl", wgsl));
        assert!(raw.is_err(), "naga 30 panics on this module");
        let e = validate_wgsl("case.wgsl", wgsl).expect_err("an error, not a panic");
        assert!(e.starts_with("naga panicked on case.wgsl: "), "{e}");
    }
}
