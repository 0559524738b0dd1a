//! The integration tests that open a wgpu device in this process (one
//! per binary, `common::gpu`): rendering, compute, goldens, the runner's
//! API. One binary instead of one per file, so the suite links once.

#[path = "../common/mod.rs"]
mod common;

mod age_of_sail_pipeline;
mod artmap_cache;
mod artmaps;
mod artmaps_hard_cases;
mod bench_overhead;
mod blend_depth;
mod blender_scene;
mod blender_sequence;
mod checkpoints;
mod colour_alpha;
mod compute;
mod compute_pixels;
mod compute_samples;
mod device_needs;
mod dynamic_patterns;
mod embed_inputs;
mod gltf_materials;
mod golden_images;
mod gpu_errors;
mod gradient_ramp;
mod halftone_tone;
mod history;
mod host_builtins;
mod host_inputs;
mod input_sequences;
mod lines_classify;
mod lines_over;
mod lines_pass;
mod lines_sets;
mod lsa_gbuffer_precision;
mod lsa_stereo;
mod manifest_mutation;
mod object_textures;
mod ocean_look;
mod patch_blend;
mod patch_blend_styles;
mod pattern_styles;
mod post_examples;
mod runner_api;
mod schedule_equivalence;
mod screen_uv;
mod sequence_outputs;
mod sliding;
mod stereo_passes;
mod walker_styles;
