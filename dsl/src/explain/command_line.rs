//! Explanations of the command-line codes (E05xx): usage, values, outputs,
//! compiled directories, the device, benchmarks and serving.

use super::{Example, Explanation, EXAMPLE};

const GREY: &str = "style \"Case\"\npass p: render(scene) {\n  out c: rgba8unorm = #808080\n}\noutput p.c\n";

/// A path-dependent style: each frame over the fading previous one.
const TRAIL: &str =
    "style \"Case\"\npass p: image() {\n  out c: rgba8unorm = mix(#808080, previous(p.c), 0.5)\n}\noutput p.c\n";

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
    Explanation {
        code: "E0510",
        meaning: "A pass needs a WebGPU feature, or a limit above WebGPU's default, that the \
            device (or its adapter) does not have. WebGPU guarantees its defaults on every \
            device; anything past them must be asked for when the device is made: a tiled pass \
            with five outputs needs five storage textures per shader stage (the default is four), \
            a pass with five rgba32float outputs 80 bytes of colour attachments per sample (the \
            default is 32). The compiler writes each pass's needs into the manifest \
            (`device_needs`, WebGPU's names; `npr compile --report` lists them), `npr render` \
            asks the adapter for exactly those, and a host that makes its own device must ask \
            for them too. Change the pass to need less (fewer outputs, or narrower formats), or \
            run it on an adapter that has more.",
        wrong: Example {
            style: FIVE_TILED_OUTPUTS,
            files: SCENE,
            commands: &[&["render", "case.npr", "--scene", "scene.toml", "-o", "out.png", "--size", "16x16"]],
            not_runnable: Some("lavapipe allows more storage textures than WebGPU's default, so the style renders here; tests/gpu/device_needs.rs renders it on a device with WebGPU's defaults"),
            ..EXAMPLE
        },
        fixed: Example {
            style: FOUR_TILED_OUTPUTS,
            files: SCENE,
            commands: &[&["render", "case.npr", "--scene", "scene.toml", "-o", "out.png", "--size", "16x16"]],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0511",
        meaning: "`-o NAME.mp4` and `-o NAME.webm` are encoded by the system's ffmpeg (H.264 \
            with libx264, VP9 with libvpx-vp9), fed the frames on a pipe as they render. It is \
            looked for before anything is compiled or rendered, so a long render never fails at \
            its end: `ffmpeg` on the PATH, or the program `NPR_FFMPEG` names. Install it \
            (Debian/Ubuntu: `apt install ffmpeg`), or write a `.gif`, which npr encodes itself.",
        wrong: Example {
            style: GREY,
            files: SCENE,
            commands: &[&["render", "case.npr", "--scene", "scene.toml", "-o", "clip.mp4", "--frames", "0..2", "--size", "16x16"]],
            not_runnable: Some("it needs a machine without ffmpeg, and the tests' machines have it; tests/error_codes/ runs it with NPR_FFMPEG naming no program"),
            ..EXAMPLE
        },
        fixed: Example {
            style: GREY,
            files: SCENE,
            commands: &[&["render", "case.npr", "--scene", "scene.toml", "-o", "clip.gif", "--frames", "0..2", "--size", "16x16"]],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0512",
        meaning: "`npr render --checkpoints DIR` starts a path-dependent style's chunk (one that \
            reads `previous(...)` or keeps `state`) from the state the frames before it left, \
            saved in DIR by the chunk before it. A checkpoint holds that state for one render \
            only: the compiled style (with its `--set` values), the scene, `--size`, `--fps` \
            and the npr that wrote it. One made for anything else would give other frames than \
            a single run, so it is refused, naming what differs; npr never replaces it by a \
            replay silently. Render with what wrote it, or give each render its own directory.",
        wrong: Example {
            style: TRAIL,
            files: SCENE,
            commands: &[
                &["render", "case.npr", "--scene", "scene.toml", "--size", "16x16", "--frames", "0-1", "--checkpoints", "ck"],
                &["render", "case.npr", "--scene", "scene.toml", "--size", "24x24", "--frames", "2-3", "--checkpoints", "ck"],
            ],
            ..EXAMPLE
        },
        fixed: Example {
            style: TRAIL,
            files: SCENE,
            commands: &[
                &["render", "case.npr", "--scene", "scene.toml", "--size", "16x16", "--frames", "0-1", "--checkpoints", "ck"],
                &["render", "case.npr", "--scene", "scene.toml", "--size", "16x16", "--frames", "2-3", "--checkpoints", "ck"],
            ],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0513",
        meaning: "A file in the `--checkpoints` directory named as a checkpoint \
            (`frame_NNNNNN.nprstate`) is not a whole one: truncated (a copy cut short), \
            corrupted, or not a checkpoint at all. Every checkpoint ends with a BLAKE3 hash of \
            its contents, checked before anything in it is used. npr writes checkpoints \
            atomically, so a chunk that failed leaves none; delete the file and render the \
            chunk before it again.",
        wrong: Example {
            style: TRAIL,
            files: &[SCENE[0], ("ck/frame_000002.nprstate", "not a checkpoint")],
            commands: &[&["render", "case.npr", "--scene", "scene.toml", "--size", "16x16", "--frames", "2-3", "--checkpoints", "ck"]],
            ..EXAMPLE
        },
        fixed: Example {
            style: TRAIL,
            files: SCENE,
            commands: &[&["render", "case.npr", "--scene", "scene.toml", "--size", "16x16", "--frames", "2-3", "--checkpoints", "ck"]],
            ..EXAMPLE
        },
    },
];

/// A tiled pass writing five live outputs: five storage textures in its
/// compute stage, one past WebGPU's default (E0510 on a default device).
const FIVE_TILED_OUTPUTS: &str = "style \"Case\"\npass g: render(scene) {\n  out c: rgba16float = vec4(normal, 1.0)\n}\npass b: image(g) {\n  schedule: tiled\n  let v = gaussian(g.c, sigma: 1px, axis: x)\n  out o1: rgba8unorm = v\n  out o2: rgba8unorm = v * 0.5\n  out o3: rgba16float = v\n  out o4: r32float = v.r\n  out o5: rgba32float = v\n}\npass f: image(b) {\n  out c: rgba8unorm = (b.o1 + b.o2 + b.o3 + vec4(vec3(b.o4), 0.0) + b.o5) * 0.2\n}\noutput f.c\n";

/// [`FIVE_TILED_OUTPUTS`] with four: within every device's defaults.
const FOUR_TILED_OUTPUTS: &str = "style \"Case\"\npass g: render(scene) {\n  out c: rgba16float = vec4(normal, 1.0)\n}\npass b: image(g) {\n  schedule: tiled\n  let v = gaussian(g.c, sigma: 1px, axis: x)\n  out o1: rgba8unorm = v\n  out o2: rgba8unorm = v * 0.5\n  out o3: rgba16float = v\n  out o4: r32float = v.r\n}\npass f: image(b) {\n  out c: rgba8unorm = (b.o1 + b.o2 + b.o3 + vec4(vec3(b.o4), 0.0)) * 0.25\n}\noutput f.c\n";
