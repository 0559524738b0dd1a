//! The front end: from `.npr` text to a typed IR. Loading (the root file,
//! its `use`s and the art-maps' filter styles, each under the paths
//! policy), resolving names into the IR, typechecking with units, and the
//! checks that need types (filters, rip-map uses, `lines` settings), and
//! the typing of parameter settings (`--set`, a filter's arguments).
//! Everything here reports user errors as diagnostics with spans.

pub mod filter_checks;
pub mod follow_ups;
pub mod line_settings;
pub mod load;
pub mod load_filters;
pub mod param_settings;
pub mod param_values;
pub mod paths;
pub mod resolve;
pub mod texture_spans;
pub mod texture_uses;
pub mod typecheck;
