//! Explanations of the syntax codes (E00xx): the text does not parse, its
//! header, names, `use`s, its nesting and depth limits, and its encoding.

use super::{Encoding, Example, Explanation, EXAMPLE};

pub(super) const ALL: &[Explanation] = &[
    Explanation {
        code: "E0001",
        meaning: "The text does not match the grammar of `.npr`. The message lists the tokens \
            npr expected at the furthest point it reached, and the caret is on the token it \
            could not use (or just after the last one, when a line ends too early).

            Parsing recovers at the next top-level item (`param`, `texture`, `pass`, `output`, \
            `use`), so one run reports every broken declaration; names declared by a broken one \
            are not reported again as unknown.",
        wrong: Example {
            style: "style \"Case\"\nparam x: float = (1.0 +\npass p: image() {\n  out c: r8unorm = x\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nparam x: float = (1.0 + 0.5)\npass p: image() {\n  out c: r8unorm = x\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0002",
        meaning: "A style file starts with exactly one header, `style \"Name\"`, before any \
            declaration. The name is shown by `npr check` and the studio. A file that is only \
            `use`d by others needs one too.",
        wrong: Example {
            style: "pass p: image() {\n  out c: r8unorm = 0.5\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Grey\"\npass p: image() {\n  out c: r8unorm = 0.5\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0003",
        meaning: "Parameters, textures, passes and the `let`s and outputs inside one pass share \
            a namespace each; a name may be declared once. Names from `use`d files count too. \
            Rename one of the two declarations (the label points at both).",
        wrong: Example {
            style: "style \"Case\"\nparam gain: float = 1.0\nparam gain: float = 2.0\npass p: image() {\n  out c: r8unorm = gain * 0.25\n}\noutput p.c\n",
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nparam gain: float = 1.0\nparam bias: float = 2.0\npass p: image() {\n  out c: r8unorm = gain * 0.25 + bias * 0.1\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0004",
        meaning: "`use \"file.npr\"` brings another style file's parameters, textures and passes \
            into this one. The path is relative to the file that says `use`. The file must \
            exist and be readable, and `use`s may not form a cycle (a file that, through its \
            own `use`s, uses itself). Here the library `use`s the style that uses it.",
        wrong: Example {
            style: "style \"Case\"\nuse \"lib/common.npr\"\npass p: image() {\n  out c: r8unorm = shared_grey\n}\noutput p.c\n",
            files: &[("lib/common.npr", "style \"Common\"\nuse \"../case.npr\"\nparam shared_grey: float = 0.5\n")],
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nuse \"lib/common.npr\"\npass p: image() {\n  out c: r8unorm = shared_grey\n}\noutput p.c\n",
            files: &[("lib/common.npr", "style \"Common\"\nparam shared_grey: float = 0.5\n")],
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0005",
        meaning: "Brackets, blocks, calls and `if`s may be nested at most 64 levels deep \
            (`npr_diag::limits::MAX_NESTING`, docs/LIMITS.md). The limit is checked on the raw text \
            before parsing, so no input can overflow the parser's stack. Name the inner parts \
            with `let` instead of nesting them.",
        wrong: Example {
            style: "style \"Case\"\nparam x: float = …1.0…\npass p: image() {\n  out c: r8unorm = x\n}\noutput p.c\n",
            repeat: &[("(", 70), (")", 70)],
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nparam x: float = (1.0)\npass p: image() {\n  out c: r8unorm = x\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0006",
        meaning: "An expression tree may be at most 256 levels deep \
            (`npr_diag::limits::MAX_EXPR_DEPTH`, docs/LIMITS.md). A long chain of binary operators \
            counts as deep: `a + b + c` is `(a + b) + c`. Split the chain with `let`s, or \
            write it with a multiplication or a call.",
        wrong: Example {
            style: "style \"Case\"\nparam x: float = 0.001\npass p: image() {\n  out c: r8unorm = x…\n}\noutput p.c\n",
            repeat: &[(" + x", 300)],
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\nparam x: float = 0.001\npass p: image() {\n  out c: r8unorm = x * 301.0\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0007",
        meaning: "Style and scene files are UTF-8 text. A file saved in another encoding (Latin-1, \
            Windows-1252, UTF-16) is refused at its first byte that is not UTF-8, with that \
            byte's line and column; doc comments with accents are the usual cause. Save the \
            file as UTF-8 in your editor.",
        wrong: Example {
            style: "style \"Case\"\n/// Café au lait.\nparam tint: color = #c8a070\npass p: image() {\n  out c: rgba8unorm = tint\n}\noutput p.c\n",
            encoding: Encoding::Latin1,
            ..EXAMPLE
        },
        fixed: Example {
            style: "style \"Case\"\n/// Café au lait.\nparam tint: color = #c8a070\npass p: image() {\n  out c: rgba8unorm = tint\n}\noutput p.c\n",
            ..EXAMPLE
        },
    },
];
