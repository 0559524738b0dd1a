//! Explanations of the command-line codes (E05xx): usage, values, outputs,
//! compiled directories, the device, benchmarks and serving.

use super::{Example, Explanation, EXAMPLE};

const GREY: &str = "style \"Case\"\npass p: render(scene) {\n  out c: rgba8unorm = #808080\n}\noutput p.c\n";

const SCENE: &[(&str, &str)] = &[(
    "scene.toml",
    "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\n\n[[object]]\nname = \"ball\"\nprimitive = { kind = \"sphere\", radius = 0.5, segments = 8, rings = 4 }\n",
)];

pub(super) const ALL: &[Explanation] = &[
    Explanation {
        code: "E0501",
        meaning: "The command line does not parse: an unknown command or flag, a missing \
            argument, or a value of the wrong form. The message is clap's; `npr help COMMAND` \
            lists a command's arguments.",
        wrong: Example {
            style: GREY,
            files: SCENE,
            commands: &[&["check", "case.npr", "--sceen", "scene.toml"]],
            ..EXAMPLE
        },
        fixed: Example {
            style: GREY,
            files: SCENE,
            commands: &[&["check", "case.npr", "--scene", "scene.toml"]],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0502",
        meaning: "A command-line value of the right form but outside what it may be: `--fps 0`, \
            a `--time` that is not finite, `--eye 1` for a mono camera, a `--set` value outside \
            its parameter's range, or `npr explain` of a code that does not exist. The message \
            says what is allowed.",
        wrong: Example {
            style: GREY,
            files: SCENE,
            commands: &[&["render", "case.npr", "--scene", "scene.toml", "-o", "out.png", "--size", "16x16", "--fps", "0"]],
            ..EXAMPLE
        },
        fixed: Example {
            style: GREY,
            files: SCENE,
            commands: &[&["render", "case.npr", "--scene", "scene.toml", "-o", "out.png", "--size", "16x16", "--fps", "24"]],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0503",
        meaning: "An output (an image, a compiled directory, a dump, a benchmark's `--plot`) \
            cannot be written: its directory does not exist or is not writable, its extension is \
            not one npr writes (`.png`/`.exr` images, `.svg` plots), or `npr compile -o` names a \
            file, not a directory. A `--plot` path is checked before the benchmark runs. Outputs \
            are written atomically, so nothing half-written is left behind.",
        wrong: Example {
            style: GREY,
            commands: &[&["compile", "case.npr", "-o", "case.npr"]],
            ..EXAMPLE
        },
        fixed: Example {
            style: GREY,
            commands: &[&["compile", "case.npr", "-o", "compiled"]],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0504",
        meaning: "`npr render --compiled DIR` runs a directory written by `npr compile -o DIR`. \
            Its manifest.json is validated first (every index, size and offset the runner \
            relies on), since a file on disk may have been edited or come from another version; \
            the message names the bad field.",
        wrong: Example {
            style: GREY,
            files: SCENE,
            commands: &[&["render", "--compiled", "case.npr", "--scene", "scene.toml", "-o", "out.png", "--size", "16x16"]],
            ..EXAMPLE
        },
        fixed: Example {
            style: GREY,
            files: SCENE,
            commands: &[
                &["compile", "case.npr", "-o", "compiled"],
                &["render", "--compiled", "compiled", "--scene", "scene.toml", "-o", "out.png", "--size", "16x16"],
            ],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0505",
        meaning: "Rendering needs a GPU adapter: a Vulkan driver, or a GL one. On a machine \
            without a GPU a software driver works (Mesa's lavapipe for Vulkan or llvmpipe for \
            GL, e.g. `apt install mesa-vulkan-drivers`); the help names what to install. \
            `npr check` and `npr compile` need no device.",
        wrong: Example {
            style: GREY,
            files: SCENE,
            commands: &[&["render", "case.npr", "--scene", "scene.toml", "-o", "out.png", "--size", "16x16"]],
            not_runnable: Some("it needs a machine without any Vulkan or GL driver, and the machines the tests run on have a software one"),
            ..EXAMPLE
        },
        fixed: Example {
            style: GREY,
            files: SCENE,
            commands: &[&["compile", "case.npr", "-o", "compiled"]],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0506",
        meaning: "A benchmark cannot run on what it was given: a style file that does not exist \
            or does not compile, a style the benchmark does not support, or sizes the device \
            cannot allocate. The note carries the cause.",
        wrong: Example {
            style: GREY,
            commands: &[&["bench", "compile", "styles/case.npr", "--iterations", "1"]],
            ..EXAMPLE
        },
        fixed: Example {
            style: GREY,
            commands: &[&["bench", "compile", "case.npr", "--iterations", "1"]],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0507",
        meaning: "`npr studio` cannot bind its address (the port is taken by another program, \
            or `--host` is not an address of this machine), or `npr watch` / `npr studio` \
            cannot watch the files (on Linux, inotify watches may be exhausted). `--port 0` \
            picks any free port.",
        wrong: Example {
            style: GREY,
            files: SCENE,
            commands: &[&["studio", "case.npr", "--scene", "scene.toml", "--host", "192.0.2.1"]],
            ..EXAMPLE
        },
        fixed: Example {
            style: GREY,
            files: SCENE,
            commands: &[&["studio", "case.npr", "--scene", "scene.toml", "--host", "127.0.0.1", "--port", "0"]],
            serves: true,
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0508",
        meaning: "The GPU ran out of memory while npr built the renderer or ran a frame: the \
            image size, the number and formats of targets, history and art-map levels all take \
            device memory. Every allocation runs inside a wgpu out-of-memory error scope, so \
            this is reported, never a crash; the message says what was being done. Render \
            smaller (`--size`), use narrower formats, or close what else holds the GPU.",
        wrong: Example {
            style: GREY,
            files: SCENE,
            commands: &[&["render", "case.npr", "--scene", "scene.toml", "-o", "out.png", "--size", "16384x16384"]],
            not_runnable: Some("whether a size runs out of memory depends on the device; tests/gpu/gpu_errors.rs provokes it under an address-space limit"),
            ..EXAMPLE
        },
        fixed: Example {
            style: GREY,
            files: SCENE,
            commands: &[&["render", "case.npr", "--scene", "scene.toml", "-o", "out.png", "--size", "16x16"]],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0509",
        meaning: "The GPU device was lost while npr used it: the driver was reset (a hang, an \
            update, a laptop switching GPUs) or the device was destroyed. wgpu reports the loss \
            to a callback npr installs, and the error that followed is reported as this code, \
            not as a crash. Run the command again; a new device is created. If it recurs, the \
            driver's log says why.",
        wrong: Example {
            style: GREY,
            files: SCENE,
            commands: &[&["render", "case.npr", "--scene", "scene.toml", "-o", "out.png", "--size", "16x16"]],
            not_runnable: Some("it needs the driver to reset during the run; tests/gpu/gpu_errors.rs destroys the device to provoke it"),
            ..EXAMPLE
        },
        fixed: Example {
            style: GREY,
            files: SCENE,
            commands: &[&["render", "case.npr", "--scene", "scene.toml", "-o", "out.png", "--size", "16x16"]],
            ..EXAMPLE
        },
    },
];
