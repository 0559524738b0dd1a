//! The integration tests that need no device of their own: the compiler's
//! snapshots, the CLI (which may render in its own process), the language
//! server, the studio, the fuzzers and the docs. One binary instead of one
//! per file, so the suite links once.

#[path = "../common/mod.rs"]
mod common;

mod bench_plot;
mod bundles;
mod cli;
mod cli_usage;
mod crate_boundaries;
mod determinism;
mod embed_example;
mod examples_compile;
mod explain;
mod flamenco;
mod fuzz_compiler;
mod fuzz_generated;
mod fuzz_scenes;
mod limits;
mod lines_fandisk;
mod lsa_contours;
mod lsa_packed_gbuffer;
mod lsp;
mod module_cycles;
mod openjd;
mod packaging;
mod paths;
mod range_warnings;
mod reference_docs;
mod set_params;
mod studio_browser;
mod studio_camera;
mod studio_server;
mod style_sweeps;
mod style_tests;
mod style_tests_examples;
mod view;
mod vscode_extension;
mod watch;
mod web_package;
mod webgpu_portability;
