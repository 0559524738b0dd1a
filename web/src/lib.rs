//! npr in the browser (issue 50): the style compiler built for
//! `wasm32-unknown-unknown` with a typed JavaScript API (wasm-bindgen; the
//! `.d.ts` is generated). `web/build.sh` builds the package into
//! `web/pkg/`; `js/npr.js`, copied beside the generated module, is what a
//! page imports (it turns a trap into an error value and loads the module
//! afresh). Decision 0052 says why it is shaped so.
//!
//! - [`compile`]: the compile itself, plain Rust (tested natively);
//! - [`params`]: `setParam`, typed against the manifest;
//! - [`js`]: the bindings: `Style`, `ShaderModule`, the files and options
//!   objects, errors as `NprError` values, the panic hook.

pub mod compile;
pub mod js;
pub mod params;
