//! Explanations of the host codes (E06xx): mistakes of an application that
//! embeds a style with `runner::embed::StyleRuntime`. They come from Rust
//! calls, not from `npr` commands, so the examples show the style a host
//! loads and say where the host's mistake is tested.

use super::{Example, Explanation, EXAMPLE};

const GREY: &str = "style \"Case\"\npass p: render(scene) {\n  out c: rgba8unorm = #808080\n}\noutput p.c\n";

pub(super) const ALL: &[Explanation] = &[
    Explanation {
        code: "E0601",
        meaning: "A host application gave the runtime a mesh handle it does not hold: the mesh \
            was removed with `StyleRuntime::remove_mesh` (a handle is never reused for another \
            mesh: each slot has a generation), or the handle came from another runtime. \
            Register the mesh with `add_mesh` and use the handle it returns for as long as \
            instances draw it; remove it only after the last frame that draws it.",
        wrong: Example {
            style: GREY,
            not_runnable: Some(
                "a host's Rust call, not an `npr` command: tests/error_codes/host.rs removes a mesh \
                 and renders an instance of it",
            ),
            ..EXAMPLE
        },
        fixed: Example { style: GREY, ..EXAMPLE },
    },
    Explanation {
        code: "E0602",
        meaning: "A host application gave `StyleRuntime::render` a texture view it cannot draw \
            the style's output into. The view's texture must be 2D with one layer and one mip \
            level, have `RENDER_ATTACHMENT` usage, a colour format with float or normalized \
            channels that is not sRGB (the style's output is written as `npr render` writes \
            its PNG; view an sRGB surface through its non-sRGB twin, listed in `view_formats`), \
            and a size from 1 to the largest image on a side. `Target::Eyes` and \
            `Target::SideBySide` need a stereo style; the two eyes' views must be the same \
            size, and a side-by-side view an even width.",
        wrong: Example {
            style: GREY,
            not_runnable: Some(
                "a host's Rust call, not an `npr` command: tests/error_codes/host.rs renders into \
                 an sRGB view",
            ),
            ..EXAMPLE
        },
        fixed: Example { style: GREY, ..EXAMPLE },
    },
];
