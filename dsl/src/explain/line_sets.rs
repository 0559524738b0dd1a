//! The explanations of line sets' codes, E0313–E0318 (decision 0056) and
//! E0323 (decision 0063).

use super::{Example, Explanation, EXAMPLE};

/// A fill with a kept depth, then a lines pass whose sets are `$SETS`.
macro_rules! sets_case {
    ($sets:literal) => {
        concat!(
            "style \"Case\"\npass shade: render(scene) {\n  out color: rgba8unorm = #808080\n  depth: keep\n}\n",
            "pass ink: lines(scene) {\n",
            $sets,
            "\n  depth: test(shade, bias: 1px)\n  out ink: rgba8unorm = line.color { blend: over }\n  clear: #ffffff\n}\noutput ink.ink\n"
        )
    };
}

pub(super) const ALL: &[Explanation] = &[
    Explanation {
        code: "E0313",
        meaning: "A line set's `edges:` is a union of edge types joined by `|`: `silhouette` (edges \
            between a face turned to the eye and one turned away), `border` (edges of one face: an \
            open mesh's rim), `crease(angle)` (edges whose two faces turn by more than the angle), \
            `material_boundary` (edges between faces of different parts of the mesh: OBJ `o`/`g`, \
            glTF primitives), `intersection` (where two surfaces, or one and itself, pass \
            through each other) and `marked` (edges the mesh's file marks: a glTF file's \
            `_NPR_EDGE_MARK` face-corner attribute). Another name, an argument to a type other than `crease`, or a \
            value that is not a union is this error.",
        wrong: Example {
            style: sets_case!("  set outline { edges: silhouette | bordr }"),
            ..EXAMPLE
        },
        fixed: Example {
            style: sets_case!("  set outline { edges: silhouette | border }"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0314",
        meaning: "`crease(angle)` selects the edges whose two faces turn by more than `angle`, a \
            dihedral angle written in `deg` between 0deg (every edge of two faces) and 180deg \
            (none). A crease without an angle, with a number without `deg`, or outside 0..180deg \
            is this error.",
        wrong: Example {
            style: sets_case!("  set detail { edges: crease(0.5) }"),
            ..EXAMPLE
        },
        fixed: Example {
            style: sets_case!("  set detail { edges: crease(30deg) }"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0315",
        meaning: "An edge two line sets select is drawn once, by the set of higher priority \
            (`priority: n`, 0 when unset; among equals, the one written first). A set that has no \
            `edges:`, or whose every edge type a set before it takes over the same objects (no \
            `tag:`, or the same tag; a lower crease angle takes every edge a higher one does), \
            would draw nothing. Give it a higher priority, or edge types or a tag the other set \
            does not take.",
        wrong: Example {
            style: sets_case!(
                "  set all { edges: silhouette | crease(30deg), priority: 1 }\n  set detail { edges: crease(45deg) }"
            ),
            ..EXAMPLE
        },
        fixed: Example {
            style: sets_case!(
                "  set all { edges: silhouette | crease(30deg) }\n  set detail { edges: crease(45deg), priority: 1 }"
            ),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0316",
        meaning: "The line sets of one pass are named so that messages and the manifest can tell \
            them apart: two sets of one pass cannot share a name.",
        wrong: Example {
            style: sets_case!("  set outline { edges: silhouette }\n  set outline { edges: border }"),
            ..EXAMPLE
        },
        fixed: Example {
            style: sets_case!("  set outline { edges: silhouette }\n  set rim { edges: border }"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0317",
        meaning: "Line sets belong to `lines` passes. A `set` block in another pass, the \
            pass-level `silhouettes:` or `creases:` beside sets (a pass with sets draws what its \
            sets select), a setting a set does not have (a set takes `edges`, `tag`, \
            `visibility`, `priority`, `color` and the shape settings `width`, `amplitude`, \
            `wavelength`, `phase`, `taper`), or `line.color` / `line.set` in a pass without sets \
            is this error.",
        wrong: Example {
            style: sets_case!("  set outline { edges: silhouette, colour: #ff0000 }"),
            ..EXAMPLE
        },
        fixed: Example {
            style: sets_case!("  set outline { edges: silhouette, color: #ff0000 }"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0318",
        meaning: "A line set's `visibility:` picks its lines by quantitative invisibility, the \
            number of surfaces between the eye and the line, counted per piece of line \
            (decision 0063): `visible` (none), `hidden` (one or more), `hidden(n)` (exactly n, \
            a whole number from 1) or `all`. Without `visibility:` a set draws every line it \
            selects and the pass's `depth: test(pass)` hides what is behind. Another name, or \
            `hidden` with anything but one whole number from 1, is this error.",
        wrong: Example {
            style: sets_case!("  set hidden { edges: silhouette, visibility: hiden }"),
            ..EXAMPLE
        },
        fixed: Example {
            style: sets_case!("  set hidden { edges: silhouette, visibility: hidden }"),
            ..EXAMPLE
        },
    },
    Explanation {
        code: "E0323",
        meaning: "A line set's `dash:` draws its lines dashed along the screen arc length: \
            `dash: 6px` draws 6px and leaves 6px out, `dash: dashes(6px, 4px)` draws 6px and \
            leaves 4px out (decision 0063). Lengths are in px and over 0; anything else is this \
            error.",
        wrong: Example {
            style: sets_case!("  set hidden { edges: silhouette, visibility: hidden, dash: 6 }"),
            ..EXAMPLE
        },
        fixed: Example {
            style: sets_case!("  set hidden { edges: silhouette, visibility: hidden, dash: dashes(6px, 4px) }"),
            ..EXAMPLE
        },
    },
];
