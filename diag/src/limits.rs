//! Every limit npr enforces on its input, in one table, each with the error
//! code it is reported with.
//!
//! The limits are on purpose: past them npr refuses the input with a user
//! error (exit 1) instead of running out of stack, memory or time. Each one
//! is far above what a real style, scene or command line needs. The table in
//! `docs/LIMITS.md` is checked against [`ALL`] by a test (`dsl/tests/limits.rs`),
//! so the documentation cannot drift from the code.

use crate::codes;

/// Largest style file (a root file or one it `use`s), in bytes.
pub const MAX_SOURCE_BYTES: usize = 1 << 20;
/// Largest scene file (TOML), in bytes: geometry goes in mesh files.
pub const MAX_SCENE_BYTES: usize = 1 << 20;
/// Deepest nesting of brackets, blocks and `if`s: `(`, `{`, a call's
/// argument list and an `if` each open a level. The parser checks it on the
/// raw text before parsing, so the recursive-descent parser never goes
/// deeper than this.
pub const MAX_NESTING: usize = 64;
/// Deepest expression tree: every operator of a chain such as
/// `a + b + c` is a level (it is `(a + b) + c`), as are calls, fields and
/// brackets. Bounds the recursion of every compiler stage.
pub const MAX_EXPR_DEPTH: usize = 256;
/// Most parameters (style and object) in one style, `use`d files included.
pub const MAX_PARAMS: usize = 1024;
/// Most passes in one style.
pub const MAX_PASSES: usize = 64;
/// Most outputs (targets) of one pass: WebGPU's colour attachment limit.
pub const MAX_TARGETS_PER_PASS: usize = 8;
/// Widest and tallest texture file, in texels (wgpu's 2D texture limit).
pub const MAX_TEXTURE_SIZE: u32 = 16384;
/// Widest and tallest rendered image (`--size`), in pixels: its targets are
/// 2D textures too.
pub const MAX_OUTPUT_SIZE: u32 = 16384;
/// Most triangles of one mesh (a file or a primitive): past this a scene
/// takes minutes on the software rasterizer and gigabytes of memory.
pub const MAX_TRIANGLES: usize = 2_000_000;
/// Most joints of one glTF skin: a GPU skinning stage's joint matrices
/// fit one 16 KiB uniform array (256 × 64 bytes); characters use tens to
/// about two hundred.
pub const MAX_JOINTS: usize = 256;
/// Most frames one `npr render` renders (`--frames A..B`, or the frames a
/// path-dependent style replays for `--time`): 69 minutes at 24 fps.
pub const MAX_FRAMES: u32 = 100_000;

/// One limit: what it bounds, its value, and the code it is reported with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limit {
    /// The constant's name in this module.
    pub name: &'static str,
    /// What is limited, as the documentation says it.
    pub what: &'static str,
    pub value: u64,
    pub unit: &'static str,
    pub code: &'static str,
}

/// Every limit, in the order `docs/LIMITS.md` lists them.
pub const ALL: &[Limit] = &[
    Limit {
        name: "MAX_SOURCE_BYTES",
        what: "size of one style file",
        value: MAX_SOURCE_BYTES as u64,
        unit: "bytes",
        code: codes::LIMIT_EXCEEDED,
    },
    Limit {
        name: "MAX_SCENE_BYTES",
        what: "size of one scene file",
        value: MAX_SCENE_BYTES as u64,
        unit: "bytes",
        code: codes::LIMIT_EXCEEDED,
    },
    Limit {
        name: "MAX_NESTING",
        what: "nesting of brackets, blocks, calls and `if`s",
        value: MAX_NESTING as u64,
        unit: "levels",
        code: codes::NESTED_TOO_DEEP,
    },
    Limit {
        name: "MAX_EXPR_DEPTH",
        what: "depth of an expression (each operator of a chain is a level)",
        value: MAX_EXPR_DEPTH as u64,
        unit: "levels",
        code: codes::EXPRESSION_TOO_DEEP,
    },
    Limit {
        name: "MAX_PARAMS",
        what: "parameters in one style",
        value: MAX_PARAMS as u64,
        unit: "params",
        code: codes::LIMIT_EXCEEDED,
    },
    Limit {
        name: "MAX_PASSES",
        what: "passes in one style",
        value: MAX_PASSES as u64,
        unit: "passes",
        code: codes::LIMIT_EXCEEDED,
    },
    Limit {
        name: "MAX_TARGETS_PER_PASS",
        what: "outputs (targets) of one pass",
        value: MAX_TARGETS_PER_PASS as u64,
        unit: "targets",
        code: codes::LIMIT_EXCEEDED,
    },
    Limit {
        name: "MAX_TEXTURE_SIZE",
        what: "width and height of a texture file",
        value: MAX_TEXTURE_SIZE as u64,
        unit: "texels",
        code: codes::LIMIT_EXCEEDED,
    },
    Limit {
        name: "MAX_TRIANGLES",
        what: "triangles of one mesh",
        value: MAX_TRIANGLES as u64,
        unit: "triangles",
        code: codes::LIMIT_EXCEEDED,
    },
    Limit {
        name: "MAX_JOINTS",
        what: "joints of one glTF skin",
        value: MAX_JOINTS as u64,
        unit: "joints",
        code: codes::LIMIT_EXCEEDED,
    },
    Limit {
        name: "MAX_FRAMES",
        what: "frames one `npr render` renders or replays",
        value: MAX_FRAMES as u64,
        unit: "frames",
        code: codes::LIMIT_EXCEEDED,
    },
    Limit {
        name: "MAX_OUTPUT_SIZE",
        what: "width and height of the rendered image (`--size`)",
        value: MAX_OUTPUT_SIZE as u64,
        unit: "pixels",
        code: codes::LIMIT_EXCEEDED,
    },
];

/// The table as Markdown, exactly as `docs/LIMITS.md` holds it between its
/// `<!-- limits -->` markers.
pub fn markdown_table() -> String {
    let mut s = String::from("| limit | value | code | constant |\n|---|---:|---|---|\n");
    for l in ALL {
        s.push_str(&format!(
            "| {} | {} {} | {} | `npr_diag::limits::{}` |\n",
            l.what, l.value, l.unit, l.code, l.name
        ));
    }
    s
}
