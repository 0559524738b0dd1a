//! `--set name=value`: parameter values a user gives outside the style (a
//! command line, a test file's `set`, a studio control), as settings the
//! compiler types against the style's params in its one compile
//! ([`crate::CompileOptions::settings`]): an unknown name with "did you
//! mean" (E0101), a value of the wrong type (E0201) or unit (E0202),
//! outside the declared range (E0203), or a per-object parameter, which a
//! single value cannot set (E0502), each pointing into the `--set` text.
//!
//! The value's text is read by the ABI's reader
//! (`npr_abi::param_literal::read_literal`), the one a host's
//! `StyleRuntime::set_param` uses too.

use crate::ir::{ParamSetting, SettingOrigin};
use crate::{CompileError, CompileOptions, Compiled};
use npr_abi::param_literal::read_literal;
use npr_diag::{SourceMap, Span};
use std::path::Path;

/// Every `name=value` as a setting, its text added to `sources` as a file
/// named `--set`, so that the compiler's diagnostics point into it.
pub fn settings(sets: &[String], sources: &mut SourceMap) -> Vec<ParamSetting> {
    sets.iter()
        .map(|arg| {
            let file = sources.add("--set", arg.clone());
            let (name, value) = arg.split_once('=').unwrap_or((arg.as_str(), ""));
            ParamSetting {
                name: name.trim().to_string(),
                name_span: Span::new(file, 0, name.len()),
                value: read_literal(value.trim()),
                value_span: Span::new(file, name.len() + 1, arg.len()),
                origin: SettingOrigin::CommandLine,
            }
        })
        .collect()
}

/// Compile `style` once, with `sets` (`name=value`, in order: a later one
/// of a name wins) typed against its params.
pub fn compile_with_sets(
    style: &Path,
    sets: &[String],
    sources: &mut SourceMap,
    opts: &CompileOptions,
) -> Result<Compiled, CompileError> {
    let opts = CompileOptions {
        settings: settings(sets, sources),
        ..opts.clone()
    };
    crate::compile_file(style, sources, &opts)
}
