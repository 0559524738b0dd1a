//! Helpers shared by the integration tests in `tests/`: one headless GPU per
//! test binary (failing, never skipping, when there is none) and the
//! repository root.

// Each test binary uses its own subset of these.
#![allow(dead_code)]

use runner::Gpu;
use std::path::Path;
use std::sync::OnceLock;

/// The headless device of this test binary.
pub fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Gpu> = OnceLock::new();
    GPU.get_or_init(|| {
        Gpu::headless().unwrap_or_else(|e| {
            panic!("this test needs a GPU adapter: {e} (install one with ./setup.sh: mesa-vulkan-drivers)")
        })
    })
}

/// The repository root (where `examples/` and `tests/` are).
pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}
