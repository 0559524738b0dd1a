//! Explanations of the type codes (E02xx): types, units, ranges, constants
//! and the types of per-object values.

use super::{Example, Explanation, EXAMPLE};

pub(super) const ALL: &[Explanation] = &[
    Explanation {
        code: "E0201",
        meaning: "A value of one type where another is needed: a `vec3` passed to an operator \
            parameter that takes a `float`, a `bool` in arithmetic, a vector of the wrong size. \
            Scalars widen to vectors only where the reference says so; take a component \
            (`.x`, `.r`) or build the vector (`vec4(v, 1.0)`) yourself.",
        wrong: Example {
            style: "style \"Case\"\npass p: render(scene) {\n  out c: r8unorm = toon(normal, steps: 3)\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass p: render(scene) {\n  out c: r8unorm = toon(lambert(normal, light.dir), steps: 3)\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0202",
        meaning: "Units are checked at compile time. `px` (screen pixels), `%` (of the image), \
            `m` and `mm` (world lengths), `s`, `Hz` and `deg` cannot be added to or compared with \
            each other, and a parameter declared with a unit takes a value in that unit. A \
            world length and a pixel width differ by the camera's projection: convert \
            explicitly, or declare both in the unit the operator takes (the reference lists \
            each parameter's unit).",
        wrong: Example {
            style: "style \"Case\"\nparam width: px = 2px\nparam reach: m = 1m\npass p: render(scene) {\n  vertex { inflate: width + reach }\n  out c: rgba8unorm = vec4(1.0)\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nparam width: px = 2px\nparam reach: px = 1px\npass p: render(scene) {\n  vertex { inflate: width + reach }\n  out c: rgba8unorm = vec4(1.0)\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0203",
        meaning: "A parameter declared `in a..b` must have its default, its keyframes and every \
            `--set` value inside the range, and the range must not be empty. Literal arguments \
            of operators are checked against the operator's own ranges (the reference lists \
            them), as are the settings of generated textures.",
        wrong: Example {
            style: "style \"Case\"\nparam bands: int = 12 in 1..8\npass p: render(scene) {\n  out c: r8unorm = toon(lambert(normal, light.dir), steps: bands)\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nparam bands: int = 4 in 1..8\npass p: render(scene) {\n  out c: r8unorm = toon(lambert(normal, light.dir), steps: bands)\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0204",
        meaning: "Some expressions are fixed when the style is compiled: parameter defaults, the \
            bounds of ranges, keyframes, pass scales and texture settings. They may use literals \
            and arithmetic on them, but no builtin (`time`, `normal`) and no other parameter: a \
            parameter can be changed with `--set` or in the studio, so a default computed from \
            it would render differently with `--keep-params`.",
        wrong: Example {
            style: "style \"Case\"\nparam a: float = 0.5 in 0..time\npass p: image() {\n  out c: r8unorm = a\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nparam a: float = 0.5 in 0..1\npass p: image() {\n  out c: r8unorm = a * fract(time)\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0206",
        meaning: "A `gradient` param is a colour ramp: `gradient(stop(position, colour), ...)` \
            with at least one stop, positions from 0 to 1 written in order (two stops may share \
            a position: a hard edge), each colour a literal, and `mode: constant` for bands \
            instead of blends. `ramp(g, t)` reads its colour at `t`.",
        wrong: Example {
            style: "style \"Case\"\nparam g: gradient = gradient(stop(0.6, #2a1f4a), stop(0.2, #ffe0b0))\npass p: render(scene) {\n  out c: rgba8unorm = ramp(g, lambert(normal, light.dir))\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nparam g: gradient = gradient(stop(0.2, #2a1f4a), stop(0.6, #ffe0b0))\npass p: render(scene) {\n  out c: rgba8unorm = ramp(g, lambert(normal, light.dir))\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "W0201",
        meaning: "A colour is light (`.rgb`) and coverage (`.a`, straight alpha). A number \
            applied to a colour changes its light and keeps its coverage, as in compositing \
            tools: `base * lambert(normal, light.dir)` darkens `base` and stays opaque, and two \
            colours added or subtracted keep the larger alpha. A plain `vec4(...)` is not a \
            colour: a colour times `vec4(k)` multiplies the alpha by `k` too, so the dark side \
            of an opaque object comes out transparent in the PNG. Multiply by the number \
            itself, or write the vector's alpha as 1 (0 when adding). The language reference's \
            \"Colours and alpha\" lists every rule.",
        wrong: Example {
            style: "style \"Case\"\nparam base: color = #e07a3a\npass p: render(scene) {\n  out c: rgba8unorm = base * vec4(lambert(normal, light.dir))\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nparam base: color = #e07a3a\npass p: render(scene) {\n  out c: rgba8unorm = base * lambert(normal, light.dir)\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0205",
        meaning: "A compute pass makes per-object values: `reduce` (a sum over the object's \
            vertices, samples or pixels), `out` and `state`. They are stored as floats in a \
            buffer, so their type is `float`, `vec2`, `vec3` or `vec4`; a `bool` or an `int` \
            cannot be summed. Sum `step(edge, x)` (0 or 1) to count.",
        wrong: Example {
            style: "style \"Case\"\npass sums: compute(vertices) {\n  reduce lit: float = sum(normal.y > 0.0)\n}\npass shade: render(scene) {\n  out c: r32float = sums.lit\n}\noutput shade.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass sums: compute(vertices) {\n  reduce lit: float = sum(step(0.0, normal.y))\n}\npass shade: render(scene) {\n  out c: r32float = sums.lit\n}\noutput shade.c\n",
            ..EXAMPLE
        },
    },
];
