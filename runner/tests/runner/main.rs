//! The runner's tests, one module per file, in one test binary: a binary
//! per file linked wgpu and the runner 28 times over (issue 46). Tests
//! that need a process of their own stay apart: `embed_allocations.rs`
//! installs a counting global allocator.
//!
//! Run one file's tests with `cargo test -p npr-runner --test runner
//! <file>::`.

// The tests create wgpu objects as a host would: the runner's clippy.toml
// bans uncounted creation inside the runner, not in its hosts.
#![allow(clippy::disallowed_methods)]

#[path = "../common/mod.rs"]
mod common;
#[path = "../common/skin_reference.rs"]
mod skin_reference;

mod embed_animated;
mod embed_deform;
mod embed_frames_in_flight;
mod embed_history_across_scene;
mod embed_linear_view;
mod embed_params;
mod embed_scene_change;
mod embed_skinned;
mod embed_stereo_targets;
mod gltf_animation_sampler;
mod gltf_characters;
mod gpu_deform;
mod input_motion;
mod lines_edge_marks;
mod lines_edge_types;
mod lines_edges;
mod lines_pixels;
mod lines_strip;
mod lines_visibility;
mod metatexture_contrast;
mod object_motion;
mod ocean_textures;
mod readback_conversions;
mod render_bundles;
mod scene_camera;
mod scene_errors;
mod scene_meshes;
mod scene_ocean;
mod scene_patches;
mod scene_primitives;
mod scene_spin;
mod screen_frame;
mod skinned_render;
