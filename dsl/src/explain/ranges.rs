//! Explanations of the range analysis's warnings (W0203–W0210, issue 49):
//! operations whose operands the declared ranges let reach a value where
//! WGSL leaves the result undefined.

use super::{Example, Explanation, EXAMPLE};

/// What every one of these warnings means, before its own case.
macro_rules! ranges_meaning {
    ($own:literal) => {
        concat!(
            $own,
            "\n\nThe compiler proves value ranges: from each param's declared range (`in a..b`; a \
            `--set` value is its value), the builtins' ranges (unit normals, `screen_uv` in \
            [0, 1], `time` ≥ 0) and each target's format, it bounds every expression in f32. \
            Where an operand's range reaches the operation's undefined case, WGSL lets each \
            driver return what it likes: lavapipe may give 0 where another GPU gives +inf or \
            NaN, so a style clean on one machine is broken on another. The warning names the \
            operand's range and the params and builtins it comes from; the help gives a safe \
            form that the analysis proves. `docs/RANGES.md` says what the analysis knows. \
            No warning covers a float-to-int conversion: the language has none (an int comes \
            only from an int or enum param or an int builtin)."
        )
    };
}

pub(super) const ALL: &[Explanation] = &[
    Explanation {
        code: "W0203",
        meaning: ranges_meaning!("`log` or `log2` of a value that may be 0 or negative: log(0) is -inf, and the log of a negative number has no value."),
        wrong: Example {
            style: "style \"Case\"\nparam k: float = 0.5 in 0..1\npass p: image() {\n  out c: r32float = log(k * screen_uv.x)\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nparam k: float = 0.5 in 0..1\npass p: image() {\n  out c: r32float = log(max(k * screen_uv.x, 1e-6))\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "W0204",
        meaning: ranges_meaning!("`sqrt` of a value that may be negative."),
        wrong: Example {
            style: "style \"Case\"\nparam k: float = 0.5 in 0..1\npass p: image() {\n  out c: r32float = sqrt(screen_uv.x - k)\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nparam k: float = 0.5 in 0..1\npass p: image() {\n  out c: r32float = sqrt(max(screen_uv.x - k, 0.0))\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "W0205",
        meaning: ranges_meaning!("`pow(x, y)` where x may be negative, or x may be 0 while y may be 0 or negative. WGSL computes pow as exp2(y·log2(x)), undefined there: `pow(f, sharp - 1.0)` with f = 0 past the terminator and `sharp` allowed below 1 is pow(0, negative)."),
        wrong: Example {
            style: "style \"Case\"\nparam sharp: float = 2.0 in 0.5..4\npass p: render(scene) {\n  let f = max(dot(normal, light.dir), 0.0)\n  out c: r32float = pow(f, sharp - 1.0)\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nparam sharp: float = 2.0 in 0.5..4\npass p: render(scene) {\n  let f = max(dot(normal, light.dir), 0.0)\n  out c: r32float = pow(max(f, 1e-6), sharp - 1.0)\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "W0206",
        meaning: ranges_meaning!("A division by a value whose range holds 0: `/`, `%`, or `smoothstep(e0, e1, x)`, which divides by e1 - e0, with edges whose ranges let them meet. Narrow the declared range, divide by `max(d, 1e-6)`, or keep the edges apart: `smoothstep(a, max(b, a + 0.01), x)`."),
        wrong: Example {
            style: "style \"Case\"\nparam k: float = 0.5 in 0..1\npass p: image() {\n  out c: r32float = screen_uv.x / k\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nparam k: float = 0.5 in 0.1..1\npass p: image() {\n  out c: r32float = screen_uv.x / k\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "W0207",
        meaning: ranges_meaning!("`asin` or `acos` of a value that may leave [-1, 1]. The dot product of two unit vectors is one: in f32 it may round to 1.0000001."),
        wrong: Example {
            style: "style \"Case\"\npass p: render(scene) {\n  out c: r32float = acos(dot(normal, light.dir))\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass p: render(scene) {\n  out c: r32float = acos(clamp(dot(normal, light.dir), -1.0, 1.0))\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "W0208",
        meaning: ranges_meaning!("`normalize` of a vector whose range holds the zero vector: 0 / 0 in every component."),
        wrong: Example {
            style: "style \"Case\"\npass p: image() {\n  out c: r32float = normalize(vec2(screen_uv.x - 0.5, screen_uv.y - 0.5)).x\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass p: image() {\n  out c: r32float = normalize(vec2(screen_uv.x + 0.5, screen_uv.y - 0.5)).x\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "W0209",
        meaning: ranges_meaning!("`atan2(y, x)` where both y and x may be 0: the angle of the origin is undefined in WGSL."),
        wrong: Example {
            style: "style \"Case\"\npass p: image() {\n  out c: r32float = atan2(screen_uv.y - 0.5, screen_uv.x - 0.5)\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\npass p: image() {\n  out c: r32float = atan2(screen_uv.y - 0.5, screen_uv.x + 0.5)\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "W0210",
        meaning: ranges_meaning!("A value stored in an f16 target (`r16float`, `rg16float`, `rgba16float`) that may pass 65504, the largest f16: it is stored as infinity. Clamp it, narrow a param's range, or use a 32-bit float format."),
        wrong: Example {
            style: "style \"Case\"\nparam gain: float = 10.0 in 1..100000\npass p: image() {\n  out c: r16float = screen_uv.x * gain\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nparam gain: float = 10.0 in 1..60000\npass p: image() {\n  out c: r16float = screen_uv.x * gain\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
];
