//! naga validation of every emitted module. A failure is a compiler bug, not
//! a user error: it is reported as an internal error naming the pass and the
//! `.npr` span that produced the code.

use naga::valid::{Capabilities, ValidationFlags, Validator};

/// Parse and validate WGSL with naga; `Err` holds naga's rendered message.
pub fn validate_wgsl(name: &str, wgsl: &str) -> Result<naga::Module, String> {
    let module = naga::front::wgsl::parse_str(wgsl).map_err(|e| e.emit_to_string_with_path(wgsl, name))?;
    Validator::new(ValidationFlags::all(), Capabilities::default())
        .validate(&module)
        .map_err(|e| e.emit_to_string_with_path(wgsl, name))?;
    Ok(module)
}
