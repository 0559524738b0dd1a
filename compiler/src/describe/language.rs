//! The parts of the language that are not operators or builtins: pass
//! kinds, units and target formats, each with what it is for.

/// (kind as written, what it does).
pub const PASS_KINDS: &[(&str, &str)] = &[
    (
        "render(scene)",
        "Draws the scene's geometry (or only the objects with a tag: `render(caster)`), with vertex modifiers (`vertex { inflate: 2px }`), a view (`view(light)`), a depth mode (`depth: keep`, `depth: test(pass, bias: 1px)`) and typed outputs.",
    ),
    (
        "image(a, b)",
        "A fullscreen pass that reads the targets of the passes it lists, at its own resolution scale (`scale 1/2`). `schedule: naive`, `schedule: tiled` or `schedule: auto` in its body forces how it runs (never fused, or as compute over workgroup tiles) whatever `--schedule` says, or leaves it to `--schedule`.",
    ),
    (
        "compute(vertices)",
        "Per-object values over each object's vertices: `reduce name: type = sum(value)` and `out` (optionally `compute(vertices, tag)`).",
    ),
    (
        "compute(samples)",
        "The same over stratified surface samples of each object (Breslav et al. 2007 §3.1); `sample.spacing` is their spacing.",
    ),
    (
        "compute(pixels, ids.id)",
        "The same over the pixels of an ID target (`r32float`, written with `object.id`): each pixel counts for its object.",
    ),
    (
        "compute(objects)",
        "Once per object: `out` values and `state` kept from frame to frame (`state s: vec2 = first` then `s = next`).",
    ),
    (
        "lines(scene)",
        "Wavy strips along the visible silhouettes and creases of the objects (or those with a tag: `lines(rocks)`; Klein et al. 2000 §5): `silhouettes: true`, `creases: 40deg` or `creases: off`, `width`, `amplitude`, `wavelength` (px), `phase`, `taper`, each a sum of numbers, params and `time`; `depth: test(pass, bias: 1px)` hides edges behind a kept depth. Fragments have `line.s` (arc length, px) and `line.across` (-1..1). Line sets (`set outline { edges: silhouette, width: 3px, color: ink }`) draw several edge types (silhouette, border, crease(angle), material_boundary, intersection, marked, joined in a set's `edges:` by a vertical bar), each in its own style, every edge once by priority; `line.color` is the drawing set's colour.",
    ),
];

/// (suffix, what it measures).
pub const UNITS: &[(&str, &str)] = &[
    ("px", "screen pixels"),
    ("%", "a percentage of the image height; converts to px at run time"),
    ("m", "metres, world lengths"),
    ("mm", "millimetres; converts to m at compile time"),
    ("s", "seconds"),
    ("Hz", "hertz"),
    ("deg", "degrees; passed to operators in radians"),
];

/// A target format's properties in words.
pub fn format_text(f: npr_abi::Format) -> String {
    format!(
        "{} channel(s), {} bytes per pixel{}{}",
        f.channels(),
        f.bytes_per_pixel(),
        if f.is_filterable() {
            ", filterable"
        } else {
            ", not filterable"
        },
        if f.is_blendable() {
            ", blendable"
        } else {
            ", not blendable"
        },
    )
}

/// Every target format, by name.
pub fn formats() -> impl Iterator<Item = (&'static str, npr_abi::Format)> {
    npr_abi::Format::ALL.iter().copied()
}

/// What an intrinsic function does (an exhaustive match on
/// `crate::ir::Intrinsic`, so a new one is described before it builds).
pub fn intrinsic_doc(i: crate::ir::Intrinsic) -> String {
    use crate::ir::Intrinsic::*;
    match i {
        Construct(n) => format!("`vec{n}(...)`: a {n}-vector from scalars and vectors (components in order), or one scalar in every component."),
        Map(name) => format!("WGSL `{name}`, per component; the result has the argument's type."),
        Map2(name) => format!("WGSL `{name}` of two arguments of one type, per component."),
        Map3(name) => format!("WGSL `{name}` of three arguments, per component."),
        Length => "WGSL `length`: the length of a vector.".into(),
        Dot => "WGSL `dot`: the dot product of two vectors of one size.".into(),
        Distance => "WGSL `distance`: the distance between two points.".into(),
        Normalize => "WGSL `normalize`: the unit vector in a vector's direction.".into(),
        Cross => "WGSL `cross`: the cross product of two `vec3`s.".into(),
        Project => "`project(p)`: a world point → (screen u, screen v, NDC depth) in this eye.".into(),
        ProjectOtherEye => "`project_other_eye(p)`: the same in the other eye of a stereo frame.".into(),
        ProjectPrevious => "`project_previous(p)`: the same with the previous frame's camera.".into(),
        Ramp(_) => "`ramp(g, t)` of a gradient kept live (`--keep-params`): its colour at `t`, read from the style uniform block.".into(),
    }
}

/// Calls the compiler treats specially (not operators, not intrinsics):
/// (name, as written, what it does).
pub const SPECIAL_CALLS: &[(&str, &str, &str)] = &[
    ("previous", "previous(pass.target)", "The target as it was at the end of the previous frame (black on the first frame); no dependency, so a pass may read its own target."),
    ("other_eye", "other_eye(pass.target)", "The target of the other eye of a stereo frame (LSA §4.2); makes the style stereo."),
    ("scene_has", "scene_has(tag)", "Whether an object of the scene has the tag: a constant when the scene is known at compile time, else `true`."),
    ("sum", "reduce name: type = sum(value)", "In a compute pass over elements: the sum of `value` over each object's vertices, samples or pixels (also `min`, `max`)."),
    ("image", "texture t = image(\"path.png\", srgb)", "A texture read from a PNG or EXR file (`srgb` or `linear`), relative to the style."),
    ("noise", "texture t = noise(size: 256, octaves: 4, seed: 1, kind: gradient)", "A tileable noise texture made by npr's generator (the one `npr texgen` writes)."),
    ("halftone_table", "texture t = halftone_table(edge: 0.1)", "The halftone screen's tone-correction table (Breslav et al. 2007 §3.5), for `halftone(...)`."),
    ("input", "texture t = input(depth)", "An image the host gives each frame (`npr render --input`/`--inputs`), of a kind that fixes its convention: `color, linear` or `color, display`, `depth` (metres along the view axis, 0 = nothing), `normal, world` or `normal, view`, `id`, `motion`, `image, FORMAT`."),
    ("ramp", "ramp(g, t)", "The colour of the `gradient` param `g` at `t` in 0..1: between two stops their mix (or, with `mode: constant`, the last stop's colour at or before `t`)."),
    ("gradient", "param g: gradient = gradient(stop(0.0, #000000), stop(1.0, #ffffff))", "A colour ramp: stops of position (0..1, in order) and colour, `mode: linear` (default) or `constant`; read with `ramp(g, t)`. A constant, folded into the shader; `--set g=\"0:#000000, 1:#ffffff\"` replaces its stops."),
    ("test", "depth: test(pass, bias: 1px)", "A render pass's depth test against the kept depth buffer of another pass."),
];
