//! Explanations of the file and scene codes (E04xx, W04xx): textures,
//! meshes, attributes, limits, scene files and style test files.

use super::{Example, Explanation, EXAMPLE};

/// A scene of one sphere; the examples that need a scene add to it.
macro_rules! sphere_scene {
    ($extra:literal) => {
        concat!(
            "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\n\n[light]\ndirection = [0.0, 1.0, 0.0]\n\n",
            "[[object]]\nname = \"ball\"\nprimitive = { kind = \"sphere\", radius = 0.5, segments = 8, rings = 4 }\n",
            $extra
        )
    };
}

/// A scene of one mesh file, `tri.obj`.
const TRIANGLE_SCENE: &str = "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\n\n[light]\ndirection = [0.0, 1.0, 0.0]\n\n[[object]]\nname = \"tri\"\nmesh = \"tri.obj\"\n";

/// A scene of one glTF file, `tri.gltf`.
const GLTF_TRIANGLE_SCENE: &str = "[camera]\nposition = [0.5, 0.5, 3.0]\ntarget = [0.5, 0.5, 0.0]\nfov = 40.0\n\n[light]\ndirection = [0.0, 1.0, 0.0]\n\n[[object]]\nname = \"tri\"\nmesh = \"tri.gltf\"\n";

/// A one-triangle glTF file whose material has a base colour texture:
/// `$source` is the texture's image index, `$image` the image's URI
/// (`png`: a 1×1 PNG).
macro_rules! textured_triangle {
    ($source:literal, png) => {
        textured_triangle!(
            $source,
            "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR4nGM4UaHxHwAF3AJoiJKY8QAAAABJRU5ErkJggg=="
        )
    };
    ($source:literal, $image:literal) => {
        concat!(
            r#"{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],"#,
            r#""meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"material":0}]}],"#,
            r#""materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],"#,
            r#""textures":[{"source":"#,
            $source,
            r#"}],"images":[{"uri":""#,
            $image,
            r#""}],"buffers":[{"byteLength":60,"uri":"data:application/octet-stream;base64,"#,
            r#"AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/"}],"#,
            r#""bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":24}],"#,
            r#""accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},"#,
            r#"{"bufferView":1,"componentType":5126,"count":3,"type":"VEC2"}]}"#
        )
    };
}

/// Render `case.npr` on `scene.toml`, small.
const RENDER: &[&[&str]] = &[&[
    "render",
    "case.npr",
    "--scene",
    "scene.toml",
    "-o",
    "out.png",
    "--size",
    "16x16",
]];

/// Run the tests of `case.npr` (its `case.tests.toml`).
const TEST: &[&[&str]] = &[&["test", "case.npr"]];

/// One test of `case.npr` against a golden that is not there until blessed.
const GOLDEN_TEST: &str = "[[test]]\nname = \"grey\"\nscene = \"scene.toml\"\nsize = \"16x16\"\ngolden = \"golden/grey.png\"\nper_pixel = { max = 1, outliers = 0.0 }\n";

const GREY: &str = "style \"Case\"\npass p: render(scene) {\n  out c: rgba8unorm = #808080\n}\noutput p.c\n";

pub(super) const ALL: &[Explanation] = &[
    Explanation {
        code: "E0401",
        meaning: "A texture declared `image(\"path\", srgb)` is read from a file when the style is \
            checked, compiled or rendered. The path is relative to the style file. The file must \
            exist and be an image npr reads (PNG or EXR), within the texture size limit; the \
            error points at the path in the style.",
        wrong: Example {
            style: "style \"Case\"\ntexture paper = image(\"paper.png\", srgb)\npass p: render(scene) {\n  out c: rgba8unorm = paper\n}\noutput p.c\n",
            commands: &[
                &["texgen", "-o", "textures/paper.png", "--size", "16"],
                &["check", "case.npr"],
            ],
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\ntexture paper = image(\"textures/paper.png\", srgb)\npass p: render(scene) {\n  out c: rgba8unorm = paper\n}\noutput p.c\n",
            commands: &[
                &["texgen", "-o", "textures/paper.png", "--size", "16"],
                &["check", "case.npr"],
            ],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0402",
        meaning: "A scene object's `mesh = \"file\"` (OBJ or glTF, relative to the scene file) \
            cannot be read: it is missing, or it does not parse (a face that names no vertex, a \
            number that is not one). The message carries the reader's own error. A glTF file's \
            skin, morph targets or animations that cannot be used are E0402 too, naming the glTF \
            path (`/meshes/0/primitives/0/attributes/WEIGHTS_0`): skin weights that do not sum to \
            1 within 0.01, a joint past the skin's, a sampler whose accessor cannot be read or \
            holds the wrong number of values.",
        wrong: Example {
            style: GREY,
            files: &[("scene.toml", TRIANGLE_SCENE), ("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 three\n")],
            commands: RENDER,
            ..EXAMPLE
        },
        fixed: Example {
            style: GREY,
            files: &[("scene.toml", TRIANGLE_SCENE), ("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")],
            commands: RENDER,
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0403",
        meaning: "A style that reads `uv` (or tangents, which come from UVs) needs every object \
            it draws to have texture coordinates. Primitives have them; a mesh file has them \
            when it has `vt` lines (OBJ) or `TEXCOORD_0` (glTF). Export the mesh with UVs, or \
            shade without them.",
        wrong: Example {
            style: "style \"Case\"\npass p: render(scene) {\n  out c: rgba8unorm = vec4(uv, 0.0, 1.0)\n}\noutput p.c\n",
            files: &[("scene.toml", TRIANGLE_SCENE), ("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")],
            commands: RENDER,
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass p: render(scene) {\n  out c: rgba8unorm = vec4(uv, 0.0, 1.0)\n}\noutput p.c\n",
            files: &[
                ("scene.toml", TRIANGLE_SCENE),
                ("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n"),
            ],
            commands: RENDER,
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0404",
        meaning: "Inputs are bounded so that no file or command can exhaust memory or the stack: \
            the size of a style file, nesting, the number of parameters, passes and targets, \
            texture and output sizes, mesh triangles and frames. docs/LIMITS.md lists every \
            limit with its value; the message names the one passed.",
        wrong: Example {
            style: "style \"Case\"\ntexture n = noise(size: 100000)\npass p: image() {\n  out c: rgba8unorm = n\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\ntexture n = noise(size: 256)\npass p: image() {\n  out c: rgba8unorm = n\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0405",
        meaning: "A scene file is TOML with a `[camera]`, an optional `[light]` and `[[object]]` \
            tables. This code is a file that is not TOML, or a field of the wrong type, a \
            missing one, or one npr does not know; the label points into the scene file.",
        wrong: Example {
            style: GREY,
            files: &[("scene.toml", "[camera\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\n")],
            commands: RENDER,
            ..EXAMPLE
        },
        fixed: Example {
            style: GREY,
            files: &[("scene.toml", "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\n")],
            commands: RENDER,
            ..EXAMPLE
        },
    },
    Explanation {
        code: "W0401",
        meaning: "A warning: an object in the scene binds `params = { name = value }` for a name \
            the style does not read per object (an `object param`). The value would be ignored, \
            so the name is probably misspelt, or the style's parameter is style-wide (the same \
            for every object, set with `--set`).",
        wrong: Example {
            style: "style \"Case\"\nobject param tint: color = #ffffff\npass p: render(scene) {\n  out c: rgba8unorm = tint\n}\noutput p.c\n",
            files: &[("scene.toml", sphere_scene!("params = { tnit = \"#ff0000\" }\n"))],
            commands: RENDER,
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nobject param tint: color = #ffffff\npass p: render(scene) {\n  out c: rgba8unorm = tint\n}\noutput p.c\n",
            files: &[("scene.toml", sphere_scene!("params = { tint = \"#ff0000\" }\n"))],
            commands: RENDER,
            ..EXAMPLE
        },
    },
    Explanation {
        code: "W0402",
        meaning: "A warning: a `render(tag)` or `compute(domain, tag)` pass draws only the \
            objects with that tag, and no object of the scene has it. The pass draws nothing \
            (its targets stay at their clear value). The message lists the scene's tags.",
        wrong: Example {
            style: "style \"Case\"\npass ground: render(gorund) {\n  out c: rgba8unorm = #808080\n}\noutput ground.c\n",
            files: &[("scene.toml", sphere_scene!("tags = [\"ground\"]\n"))],
            commands: RENDER,
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass ground: render(ground) {\n  out c: rgba8unorm = #808080\n}\noutput ground.c\n",
            files: &[("scene.toml", sphere_scene!("tags = [\"ground\"]\n"))],
            commands: RENDER,
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0406",
        meaning: "npr reads only files inside the root: by default the deepest directory that \
            holds the style and the scene, or `--root DIR`. A path in a style (`use`, \
            `image(\"…\")`, an art-map's filter) or in a scene (`mesh`, per-object images) that \
            is absolute, climbs out of the root with `..`, or follows a symbolic link out of it \
            is refused before it is read, at the path as written. `--allow-path DIR` admits a \
            directory outside the root. docs/PATHS.md gives the rules and why: a project should \
            render the same from any directory, and a style from someone else should not read \
            what is outside it.",
        wrong: Example {
            style: "style \"Case\"\ntexture paper = image(\"../paper.png\", srgb)\npass p: render(scene) {\n  out c: rgba8unorm = paper\n}\noutput p.c\n",
            commands: &[&["check", "case.npr"]],
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\ntexture paper = image(\"textures/paper.png\", srgb)\npass p: render(scene) {\n  out c: rgba8unorm = paper\n}\noutput p.c\n",
            commands: &[
                &["texgen", "-o", "textures/paper.png", "--size", "16"],
                &["check", "case.npr"],
            ],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0407",
        meaning: "`npr test` reads a style's tests from `<style>.tests.toml` beside it: an optional \
            `[defaults]` table and one `[[test]]` table per test, with `name`, `scene`, `size`, \
            `time`, `frame` or `frames`, `eye`, `set`, `golden` with its `flip` or `per_pixel` \
            tolerance, `may_be_blank`, `sweep`, `flicker`, `budget`, and `variants` with their \
            `reference`. This code is a file that is not \
            TOML, a field npr does not know, one missing or of the wrong type, a value outside its \
            domain, two tests of one name, a scene that does not exist, or `flicker` on a single \
            frame or a moving camera; the label points into the test file.",
        wrong: Example {
            style: GREY,
            files: &[
                ("scene.toml", sphere_scene!("")),
                ("case.tests.toml", "[[test]]\nname = \"grey\"\nsceen = \"scene.toml\"\nsize = \"16x16\"\n"),
            ],
            commands: TEST,
            ..EXAMPLE
        },
        fixed: Example {
            style: GREY,
            files: &[
                ("scene.toml", sphere_scene!("")),
                ("case.tests.toml", "[[test]]\nname = \"grey\"\nscene = \"scene.toml\"\nsize = \"16x16\"\n"),
            ],
            commands: TEST,
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0408",
        meaning: "A test with `golden = \"file.png\"` compares its image with that file. The file \
            must exist, be a PNG npr can read, and have the size the test renders. A new test has \
            no golden yet: `npr test --bless` renders it and writes the golden (only then, and \
            only for tests whose other checks pass); look at it before you commit it.",
        wrong: Example {
            style: GREY,
            files: &[("scene.toml", sphere_scene!("")), ("case.tests.toml", GOLDEN_TEST)],
            commands: TEST,
            ..EXAMPLE
        },
        fixed: Example {
            style: GREY,
            files: &[("scene.toml", sphere_scene!("")), ("case.tests.toml", GOLDEN_TEST)],
            commands: &[&["test", "case.npr", "--bless"], &["test", "case.npr"]],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0409",
        meaning: "A glTF file's material names a texture, a texture names an image or a sampler, \
            that the file does not have: an index past the end of its list. The message gives \
            the file and the glTF path of the index (`/textures/0/source`). npr reads the \
            material of the file's first triangle primitive that has one, and gives styles its \
            values and base colour texture (`base_color`, `metallic`, `roughness`, `emissive`, \
            `base_color_map`; the scene-file reference). Re-export the file, or fix the index.",
        wrong: Example {
            style: GREY,
            files: &[
                ("scene.toml", GLTF_TRIANGLE_SCENE),
                ("tri.gltf", textured_triangle!("3", png)),
            ],
            commands: RENDER,
            ..EXAMPLE
        },
        fixed: Example {
            style: GREY,
            files: &[
                ("scene.toml", GLTF_TRIANGLE_SCENE),
                ("tri.gltf", textured_triangle!("0", png)),
            ],
            commands: RENDER,
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0410",
        meaning: "A glTF file's material has a base colour image that npr cannot use: its bytes \
            are not a PNG that decodes (a JPEG, a truncated or corrupt file), or they cannot be \
            read (a buffer view outside its buffer, an image file that is missing or outside the \
            glTF file's folder). The message gives the file and the image's glTF path \
            (`/images/0`). Images are checked when the file loads, whether or not a style reads \
            them. Re-export the textures as PNG (Blender's glTF exporter: Images › PNG).",
        wrong: Example {
            style: GREY,
            files: &[
                ("scene.toml", GLTF_TRIANGLE_SCENE),
                ("tri.gltf", textured_triangle!("0", "data:image/png;base64,bm90IGEgcG5n")),
            ],
            commands: RENDER,
            ..EXAMPLE
        },
        fixed: Example {
            style: GREY,
            files: &[
                ("scene.toml", GLTF_TRIANGLE_SCENE),
                ("tri.gltf", textured_triangle!("0", png)),
            ],
            commands: RENDER,
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0420",
        meaning: "A style that declares `texture NAME = input(kind, ...)` runs over images its host \
            gives: `npr render STYLE --input NAME=FILE` (a PNG or EXR per input) or `--inputs \
            FILE.exr` (every input from one multi-layer EXR, found by Blender's layer names or \
            `--map NAME=LAYER`). Each input must be given, be an image npr reads, have the \
            layer and channels its kind needs, be the size of the other inputs (and of \
            `--size`, when given), and hold values its kind allows: a finite depth, in front of \
            the camera. The message names the input and the file; nothing is rendered or \
            written until every input is good.",
        wrong: Example {
            style: INPUT_STYLE,
            commands: &[&["render", "case.npr", "--input", "beauty=beauty.png", "-o", "out.png"]],
            ..EXAMPLE
        },
        fixed: Example {
            style: INPUT_STYLE,
            files: &[("scene.toml", sphere_scene!("")), ("make.npr", GREY_MADE)],
            commands: &[
                &["render", "make.npr", "--scene", "scene.toml", "--size", "16x16", "-o", "beauty.png"],
                &["render", "case.npr", "--input", "beauty=beauty.png", "-o", "out.png"],
            ],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0421",
        meaning: "A host input given with a `{frame}` pattern (`--input NAME='beauty/{frame}.png'`, \
            `--inputs 'shots/{frame:04}.exr'`; `{frame}` is the frame number in 4 digits, \
            `{frame:0N}` in N, as `-o` writes them) is a sequence: each frame rendered reads \
            its own file. Every frame asked for with `--frames` (and, for a style that reads \
            `previous(...)` or keeps `state`, every frame it replays from 0 or from its \
            checkpoint) must have its file. The message names the input, the first missing \
            file and how many frames are missing; they are looked for before the first frame \
            renders, so nothing is written.",
        wrong: Example {
            style: INPUT_STYLE,
            files: &[("scene.toml", sphere_scene!("")), ("make.npr", GREY_MADE)],
            commands: &[
                MAKE_TWO_FRAMES,
                &["render", "case.npr", "--input", "beauty=b_{frame}.png", "--frames", "0..3", "-o", "out_{frame}.png"],
            ],
            ..EXAMPLE
        },
        fixed: Example {
            style: INPUT_STYLE,
            files: &[("scene.toml", sphere_scene!("")), ("make.npr", GREY_MADE)],
            commands: &[
                MAKE_TWO_FRAMES,
                &["render", "case.npr", "--input", "beauty=b_{frame}.png", "--frames", "0..2", "-o", "out_{frame}.png"],
            ],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0422",
        meaning: "Every frame of a host input sequence (a `{frame}` pattern in `--input` or \
            `--inputs`) is the size of the sequence's first frame: a style over inputs renders \
            at their size, and its targets and history keep one size through a sequence. The \
            sizes are read from the files' headers before the first frame renders, so nothing \
            is written; re-render the odd frame at the sequence's size.",
        wrong: Example {
            style: INPUT_STYLE,
            files: &[("scene.toml", sphere_scene!("")), ("make.npr", GREY_MADE)],
            commands: &[
                &["render", "make.npr", "--scene", "scene.toml", "--size", "16x16", "--frames", "0..1", "-o", "b_{frame}.png"],
                &["render", "make.npr", "--scene", "scene.toml", "--size", "16x8", "--frames", "1..2", "-o", "b_{frame}.png"],
                &["render", "case.npr", "--input", "beauty=b_{frame}.png", "--frames", "0..2", "-o", "out_{frame}.png"],
            ],
            ..EXAMPLE
        },
        fixed: Example {
            style: INPUT_STYLE,
            files: &[("scene.toml", sphere_scene!("")), ("make.npr", GREY_MADE)],
            commands: &[
                MAKE_TWO_FRAMES,
                &["render", "case.npr", "--input", "beauty=b_{frame}.png", "--frames", "0..2", "-o", "out_{frame}.png"],
            ],
            ..EXAMPLE
        },
    },
];

/// Frames 0 and 1 of a grey sphere, the beauty sequence of the E0421 and
/// E0422 examples.
const MAKE_TWO_FRAMES: &[&str] = &[
    "render",
    "make.npr",
    "--scene",
    "scene.toml",
    "--size",
    "16x16",
    "--frames",
    "0..2",
    "-o",
    "b_{frame}.png",
];

/// A style over one host input, its colour, halved.
const INPUT_STYLE: &str = "style \"Case\"\ntexture beauty = input(color, display)\npass p: image() {\n  out c: rgba8unorm = vec4(beauty.rgb * 0.5, 1.0)\n}\noutput p.c\n";

/// A grey sphere: the beauty image the fixed E0420 example renders first.
const GREY_MADE: &str =
    "style \"Make\"\npass p: render(scene) {\n  out c: rgba8unorm = vec4(0.5, 0.5, 0.5, 1.0)\n}\noutput p.c\n";
