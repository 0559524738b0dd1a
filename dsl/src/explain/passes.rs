//! Explanations of the pass codes (E03xx, W0301, W0302): the pass graph, outputs,
//! inputs, compute passes' statements and state, blending, depth and schedules.

use super::{Example, Explanation, EXAMPLE};

pub(super) const ALL: &[Explanation] = &[
    Explanation {
        code: "E0301",
        meaning: "Passes run in an order where every pass comes after the passes whose targets \
            it reads. Two passes that read each other (or a pass that reads its own target) have \
            no such order. A feedback loop goes through the previous frame: \
            `previous(pass.target)` reads what the target held one frame ago and is no \
            dependency.",
        wrong: Example {
            style: "style \"Case\"\npass acc: image() {\n  out c: r8unorm = acc.c * 0.9 + 0.1\n}\noutput acc.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass acc: image() {\n  out c: r8unorm = previous(acc.c) * 0.9 + 0.1\n}\noutput acc.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0302",
        meaning: "A target's format fixes how many channels it has: `r8unorm` one, `rg16float` \
            two, `rgba8unorm` four. The value written must have that many (a `float` for one \
            channel, a `vec4` or `color` for four). Widen a scalar with `vec4(x, x, x, 1.0)` or \
            pick a format with fewer channels.",
        wrong: Example {
            style: "style \"Case\"\npass p: render(scene) {\n  out c: rgba8unorm = lambert(normal, light.dir)\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass p: render(scene) {\n  let l = lambert(normal, light.dir)\n  out c: rgba8unorm = vec4(l, l, l, 1.0)\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0303",
        meaning: "Every style ends with `output pass.target`: the target that is the final image. \
            Only what that target depends on is compiled; a style without one would compile to \
            nothing.",
        wrong: Example {
            style: "style \"Case\"\npass p: render(scene) {\n  out c: rgba8unorm = vec4(1.0)\n}\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass p: render(scene) {\n  out c: rgba8unorm = vec4(1.0)\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0304",
        meaning: "What a pass may read depends on its kind. An `image(a, b)` pass reads only the \
            targets of the passes it lists; a builtin of the geometry (`normal`, `uv`, \
            `position`) exists only where there is geometry (render passes, compute passes over \
            vertices or samples); `screen_uv` only where there are pixels; a per-object texture \
            only in render passes. A depth test runs at its pass's scale. List the pass in the \
            inputs, or move the read to a pass that has it.",
        wrong: Example {
            style: "style \"Case\"\npass g: render(scene) {\n  out n: rgba16float = vec4(normal, 1.0)\n}\npass p: image() {\n  out c: rgba8unorm = g.n\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass g: render(scene) {\n  out n: rgba16float = vec4(normal, 1.0)\n}\npass p: image(g) {\n  out c: rgba8unorm = g.n\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0305",
        meaning: "A compute pass's `state name: type = first` keeps a value per object from frame \
            to frame: it reads `first` on the first frame (and after a reset), and \
            `name = next` sets what it holds for the next frame. A state is read only after its \
            declaration, assigned exactly once, and only states can be assigned.",
        wrong: Example {
            style: "style \"Case\"\npass follow: compute(objects) {\n  state origin: vec2 = vec2(0.0)\n}\npass shade: render(scene) {\n  out c: rg32float = follow.origin\n}\noutput shade.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass follow: compute(objects) {\n  state origin: vec2 = vec2(0.0)\n  origin = origin + vec2(0.01)\n}\npass shade: render(scene) {\n  out c: rg32float = follow.origin\n}\noutput shade.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0306",
        meaning: "Each pass kind has its own statements. `out` writes a target in `render` and \
            `image` passes, and a per-object value in `compute(objects)`; `reduce` exists only in \
            compute passes over elements (`vertices`, `samples`, `pixels`); `state` only in \
            compute passes. Move the statement into a pass of the right kind and read its value \
            as `pass.name`.",
        wrong: Example {
            style: "style \"Case\"\npass shade: render(scene) {\n  reduce n: float = sum(1.0)\n  out c: r32float = 1.0\n}\noutput shade.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass sums: compute(vertices) {\n  reduce n: float = sum(1.0)\n}\npass shade: render(scene) {\n  out c: r32float = sums.n\n}\noutput shade.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "W0301",
        meaning: "A warning: a compute pass whose values no pass that reaches the output reads. \
            It is removed, as every pass the output does not depend on is; the warning is there \
            because a compute pass is usually written to be read. Read its values where they \
            are needed, or delete the pass.",
        wrong: Example {
            style: "style \"Case\"\npass sums: compute(vertices) {\n  reduce n: float = sum(1.0)\n}\npass shade: render(scene) {\n  out c: r32float = 1.0\n}\noutput shade.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass sums: compute(vertices) {\n  reduce n: float = sum(1.0)\n}\npass shade: render(scene) {\n  out c: r32float = 1.0 / sums.n\n}\noutput shade.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "W0302",
        meaning: "A warning: a render pass reads `patch.weight`, so it draws each patch of a \
            patched object over its own faces and the n-ring of faces outside it (Breslav et al. \
            2007 §3.6), where the patches overlap on the same surface. With only the pass's own \
            depth buffer, those copies are not occluded as they should be: a farther surface \
            drawn first stays in the blend, and a ring drawn after its neighbour's faces at the \
            same depth may be rejected. Draw the objects first in a pass that keeps its depth \
            (`depth: keep`, such as an ID pass) and test against it with `depth: test(<pass>)`.",
        wrong: Example {
            style: "style \"Case\"\npass shade: render(scene) {\n  out c: rgba8unorm = vec4(0.2, 0.2, 0.2, pow(patch.weight, 0.5)) { blend: over }\n  clear: #ffffff\n}\noutput shade.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass ids: render(scene) {\n  out id: r32float = object.id\n  depth: keep\n}\npass shade: render(scene) {\n  depth: test(ids)\n  out c: rgba8unorm = vec4(0.2, 0.2, 0.2, pow(patch.weight, 0.5)) { blend: over }\n  clear: #ffffff\n}\noutput shade.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0307",
        meaning: "`{ blend: add }` (or `over`, `multiply`...) on an output blends on the GPU, \
            which cannot blend 32-bit float formats. Use a 16-bit float format \
            (`rgba16float`), or accumulate by reading `previous(...)` without blending.",
        wrong: Example {
            style: "style \"Case\"\npass p: image() {\n  out sum: rgba32float = vec4(0.25) { blend: add }\n}\noutput p.sum\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass p: image() {\n  out sum: rgba16float = vec4(0.25) { blend: add }\n}\noutput p.sum\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0308",
        meaning: "`depth: test(other)` draws a render pass against the depth buffer of pass \
            `other` (lines hidden behind the surface, for example). A pass's depth buffer is \
            dropped after it unless it says `depth: keep`.",
        wrong: Example {
            style: "style \"Case\"\npass gbuffer: render(scene) {\n  out c: rgba8unorm = #808080\n}\npass lines: render(scene) {\n  out ink: rgba8unorm = #000000 { blend: over }\n  depth: test(gbuffer, bias: 1px)\n}\npass final: image(gbuffer, lines) {\n  out color: rgba8unorm = gbuffer.c * lines.ink\n}\noutput final.color\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass gbuffer: render(scene) {\n  out c: rgba8unorm = #808080\n  depth: keep\n}\npass lines: render(scene) {\n  out ink: rgba8unorm = #000000 { blend: over }\n  depth: test(gbuffer, bias: 1px)\n}\npass final: image(gbuffer, lines) {\n  out color: rgba8unorm = gbuffer.c * lines.ink\n}\noutput final.color\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0309",
        meaning: "`compute(pixels, ids.id)` runs over the pixels of an ID target, which says per \
            pixel which object covers it (`object.id`, written by a render pass). IDs must be \
            exact, so the target is `r32float`; a 16-bit or 8-bit format would round them.",
        wrong: Example {
            style: "style \"Case\"\npass ids: render(scene) {\n  out id: r16float = object.id\n}\npass cover: compute(pixels, ids.id) {\n  reduce area: float = sum(1.0)\n}\npass shade: render(scene) {\n  out c: rgba8unorm = vec4(vec3(cover.area / 1000.0), 1.0)\n}\noutput shade.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass ids: render(scene) {\n  out id: r32float = object.id\n}\npass cover: compute(pixels, ids.id) {\n  reduce area: float = sum(1.0)\n}\npass shade: render(scene) {\n  out c: rgba8unorm = vec4(vec3(cover.area / 1000.0), 1.0)\n}\noutput shade.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0310",
        meaning: "An art-map (`artmap(image(\"…\"), filter: \"f.npr\")`, Klein et al. 2000 \
            §4.2) runs its filter style once per mip level of the image, on the GPU, with no \
            scene. So a filter reads exactly one `texture level = filter_input()`, has image \
            passes only, and builds no art-map of its own; in it `frame` is the level index and \
            `resolution` the level's size. The error is in the filter, with a second label at \
            the art-map that names it. A filter given to `npr render` as a style is E0310 too: \
            it has no scene to run on.",
        wrong: Example {
            style: "style \"Case\"\ntexture walls = artmap(image(\"paper.png\", srgb), filter: \"hatch.npr\")\npass p: render(scene) {\n  out c: rgba8unorm = sample(walls, uv)\n}\noutput p.c\n",
            files: &[("hatch.npr", "style \"Hatch\"\ntexture level = filter_input()\npass ink: render(scene) {\n  out c: rgba8unorm = vec4(level.rgb * 0.5, 1.0)\n}\noutput ink.c\n")],
            commands: &[
                &["texgen", "-o", "paper.png", "--size", "16"],
                &["check", "case.npr"],
            ],
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\ntexture walls = artmap(image(\"paper.png\", srgb), filter: \"hatch.npr\")\npass p: render(scene) {\n  out c: rgba8unorm = sample(walls, uv)\n}\noutput p.c\n",
            files: &[("hatch.npr", "style \"Hatch\"\ntexture level = filter_input()\npass ink: image() {\n  out c: rgba8unorm = vec4(level.rgb * 0.5, 1.0)\n}\noutput ink.c\n")],
            commands: &[
                &["texgen", "-o", "paper.png", "--size", "16"],
                &["check", "case.npr"],
            ],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0311",
        meaning: "`schedule: tiled` in an image pass asks that it run as a compute shader over \
            16×16 workgroup tiles, whatever `--schedule` says: each tile loads the targets its \
            operators read around the pixel (with the apron their footprints declare) into \
            workgroup memory once. A pass can run so only if it writes formats a compute shader \
            can store (rgba8unorm, rgba16float, r32float, rg32float, rgba32float), does not \
            blend, takes no screen derivatives (no `sample(...)` of a texture, no operator that \
            calls `dpdx`), reads some target around the pixel with an operator (`sobel`, `lsa`, \
            `gaussian`), and its tiles fit in 16 KiB of workgroup memory. The help line gives the \
            reason for this pass. The compiler does not fall back to a fragment pass: write \
            `schedule: auto` (or no setting) to let it choose, `schedule: naive` to run the pass \
            as written, or change what the pass writes.",
        wrong: Example {
            style: "style \"Case\"\npass g: render(scene) {\n  out d: r32float = depth\n}\npass edges: image(g) {\n  schedule: tiled\n  out e: r16float = sobel(g.d, screen_uv)\n}\noutput edges.e\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass g: render(scene) {\n  out d: r32float = depth\n}\npass edges: image(g) {\n  schedule: tiled\n  out e: rgba16float = vec4(sobel(g.d, screen_uv), 0.0, 0.0, 1.0)\n}\noutput edges.e\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0312",
        meaning: "`schedule: recompute` in an image pass asks that its target not be stored: the \
            one pass that reads it runs over 16×16 workgroup tiles, and each workgroup computes \
            this pass's expression on its tile and the apron its reads need, rounded as the \
            target's format would round it (Halide's `compute_at`). That needs one live target, \
            not the style's output, not blended, not sRGB and not a constant; one reader, an \
            image pass at the same scale, whose own `schedule:` is not set, that reads it this \
            frame (not `previous(...)`, not the other eye's) with operators that load it around \
            the pixel (`sobel`, `lsa_density`, `gaussian`) or as a value at the pixel, and that \
            the tiler accepts with the target in its tile (see E0311); and a pass that takes no \
            screen derivatives, since it runs in compute. The help line gives the reason for \
            this pass. Write `schedule: auto` (or no setting) to let the compiler choose, or \
            `schedule: naive` to store the target.",
        wrong: Example {
            style: "style \"Case\"\npass g: render(scene) {\n  out d: r32float = depth\n}\npass edges: image(g) {\n  schedule: recompute\n  out e: rgba16float = vec4(sobel(g.d, screen_uv), 0.0, 0.0, 1.0)\n}\noutput edges.e\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass g: render(scene) {\n  out d: r32float = depth\n}\npass edges: image(g) {\n  schedule: recompute\n  out e: rgba16float = vec4(sobel(g.d, screen_uv), 0.0, 0.0, 1.0)\n}\npass ink: image(edges) {\n  out c: rgba8unorm = vec4(vec3(sobel(edges.e, screen_uv)), 1.0)\n}\noutput ink.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0319",
        meaning: "`depth: test(name)` draws a render or lines pass against a depth it does not \
            write: `name` is either an earlier pass with `depth: keep`, or a texture declared \
            `input(depth)`, the host's depth (issue 47), which the runner draws through the \
            camera's projection each frame, so that npr's lines over a host's frame are hidden \
            behind the host's surfaces. Any other name (a colour or normal input, a texture from \
            a file, a parameter) has no depth to test against.",
        wrong: Example {
            style: "style \"Case\"\ntexture color_in = input(color, display)\ntexture depth_in = input(depth)\npass ink: lines(scene) {\n  depth: test(color_in, bias: 1px)\n  out ink: rgba8unorm = vec4(0.0, 0.0, 0.0, 1.0) { blend: over }\n  clear: #ffffff\n}\npass final: image(ink) {\n  out color: rgba8unorm = sample(color_in, screen_uv) * ink.ink\n}\noutput final.color\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\ntexture color_in = input(color, display)\ntexture depth_in = input(depth)\npass ink: lines(scene) {\n  depth: test(depth_in, bias: 1px)\n  out ink: rgba8unorm = vec4(0.0, 0.0, 0.0, 1.0) { blend: over }\n  clear: #ffffff\n}\npass final: image(ink) {\n  out color: rgba8unorm = sample(color_in, screen_uv) * ink.ink\n}\noutput final.color\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0320",
        meaning: "The host's depth (`input(depth)`) is the camera's view at the output's size. A \
            pass that tests against it (`depth: test(depth_in)`) renders at scale 1 through the \
            camera: at another scale its depth buffer would not fit, and a `view(light)` pass \
            sees the scene from elsewhere. Test such a pass against an earlier pass of its own \
            scale and view with `depth: keep` instead.",
        wrong: Example {
            style: "style \"Case\"\ntexture color_in = input(color, display)\ntexture depth_in = input(depth)\npass ink: render(scene) scale 1/2 {\n  out c: rgba8unorm = #000000\n  depth: test(depth_in)\n  clear: #ffffff\n}\npass final: image(ink) {\n  out color: rgba8unorm = sample(color_in, screen_uv) * ink.c\n}\noutput final.color\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\ntexture color_in = input(color, display)\ntexture depth_in = input(depth)\npass ink: render(scene) {\n  out c: rgba8unorm = #000000\n  depth: test(depth_in)\n  clear: #ffffff\n}\npass final: image(ink) {\n  out color: rgba8unorm = sample(color_in, screen_uv) * ink.c\n}\noutput final.color\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0321",
        meaning: "In an image pass of a style over a host's frame, npr rebuilds `depth`, \
            `position.view`, `position.world` and `view_dir` from the host's `input(depth)` and \
            the camera, and reads `normal` from `input(normal, ...)`. Texture coordinates cannot \
            be rebuilt: the host's frame does not say how its surfaces are parametrised. Read \
            `screen_uv` instead, or take the host's UVs as an input of their own \
            (`input(image, rg16float)`).",
        wrong: Example {
            style: "style \"Case\"\ntexture c = input(color, linear)\npass p: image() {\n  out c: rgba8unorm = vec4(uv, 0.0, 1.0)\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\ntexture c = input(color, linear)\npass p: image() {\n  out c: rgba8unorm = vec4(screen_uv, 0.0, 1.0)\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
];
