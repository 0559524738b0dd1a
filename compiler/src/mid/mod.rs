//! The middle: what the typed IR needs of a scene and its parameters. The
//! pass DAG and its order, pruning to what the output depends on, parameter
//! overrides, specialization (folding what cannot change) with constant
//! evaluation, and the checks that need folded values (constant domains,
//! tags a known scene lacks, value ranges and WGSL's undefined cases).

pub mod const_domains;
pub mod consteval;
pub mod dag;
pub mod overrides;
pub mod prune;
pub mod ranges;
pub mod scene_tags;
pub mod specialize;
