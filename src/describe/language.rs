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
        "A fullscreen pass that reads the targets of the passes it lists, at its own resolution scale (`scale 1/2`).",
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
pub fn format_text(f: abi::Format) -> String {
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
pub fn formats() -> impl Iterator<Item = (&'static str, abi::Format)> {
    abi::Format::ALL.iter().copied()
}
