//! Explanations of the name codes (E01xx): unknown names, operators,
//! arguments, types and formats.

use super::{Example, Explanation, EXAMPLE};

pub(super) const ALL: &[Explanation] = &[
    Explanation {
        code: "E0101",
        meaning: "A name that is not declared where it is read: not a parameter, texture, pass or \
            `let` of this file or a `use`d one, and not a builtin of the pass kind (`normal`, \
            `uv`, `light.dir`, `screen_uv`, `time`...). When a declared name is close, the help \
            says \"did you mean\". `npr doc` lists the builtins.",
        wrong: Example {
            style: "style \"Case\"\nparam bands: int = 3 in 1..8\npass p: render(scene) {\n  out c: r8unorm = toon(half_lambert(normal, light.dir), steps: bnads)\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nparam bands: int = 3 in 1..8\npass p: render(scene) {\n  out c: r8unorm = toon(half_lambert(normal, light.dir), steps: bands)\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0102",
        meaning: "A call to a function that is neither a stdlib operator (`lambert`, `toon`, \
            `metatexture`...) nor an intrinsic (`mix`, `dot`, `vec4`, `previous`...). The help \
            suggests the closest operator; `npr doc` writes the reference of all of them.",
        wrong: Example {
            style: "style \"Case\"\npass p: render(scene) {\n  out c: r8unorm = lambrt(normal, light.dir)\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass p: render(scene) {\n  out c: r8unorm = lambert(normal, light.dir)\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0103",
        meaning: "An argument that does not fit the call: a named argument the operator has no \
            parameter for, one given twice, a required one missing, or a setting (a blend mode, a \
            texture option, `previous(...)` of something that is not a target) that does not \
            exist. Operator parameters are named in the reference (`npr doc`); positional \
            arguments come first, then named ones.",
        wrong: Example {
            style: "style \"Case\"\npass p: render(scene) {\n  out c: r8unorm = toon(lambert(normal, light.dir), stesp: 3)\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass p: render(scene) {\n  out c: r8unorm = toon(lambert(normal, light.dir), steps: 3)\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0104",
        meaning: "A type, texture format, field or swizzle that does not exist: a parameter type \
            other than `float`, `int`, `bool`, `vec2`..`vec4`, `color`, a unit (`px`, `m`, `s`, \
            `deg`...) or an enum; a target format other than the WGSL storage formats npr \
            supports (`r8unorm`, `rgba8unorm`, `rgba16float`, `r32float`...); a field a value \
            does not have; or a swizzle that mixes `xyzw` with `rgba`.",
        wrong: Example {
            style: "style \"Case\"\npass p: render(scene) {\n  out c: rgba8unrom = vec4(normal * 0.5 + 0.5, 1.0)\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass p: render(scene) {\n  out c: rgba8unorm = vec4(normal * 0.5 + 0.5, 1.0)\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
];
