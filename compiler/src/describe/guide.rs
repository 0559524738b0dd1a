//! The reference's answers to what an artist asks first: what a colour is
//! and what arithmetic does to its alpha, what each texture source holds,
//! every pass setting, how units convert, and "how do I" recipes. Every
//! style shown here compiles without a diagnostic
//! (`tests/general/reference_docs.rs`).

/// (rule as written, what it means) for arithmetic on colours; the rules
/// are `compiler/src/front/typecheck/color.rs`'s.
pub const COLOUR_RULES: &[(&str, &str)] = &[
    ("`c * k`, `k * c`, `c / k`", "`vec4(c.rgb * k, c.a)`: a number scales the light, the coverage stays (`base * lambert(normal, light.dir)` is opaque where `base` is)"),
    ("`c + k`, `c - k`, `k - c`, `c % k`", "`vec4(c.rgb + k, c.a)` and so on: the number acts on the light only"),
    ("`a + b`, `a - b` of two colours", "`vec4(a.rgb ± b.rgb, max(a.a, b.a))`: light added or taken where either covers"),
    ("`a * b`, `a / b` of two colours", "per component: a filter (tint), and two opaque colours give an opaque one"),
    ("a colour and a `vec4(...)`", "per component, as written: you wrote that vector's alpha. W0201 warns when it is not 1 for `*` `/` (0 for `+` `-`)"),
    ("`mix`, `min`, `max`, `clamp`, `if`", "per component, alpha included: `mix` of two opaque colours is opaque; `min(c, 0.5)` caps the alpha too, write `vec4(min(c.rgb, vec3(0.5)), c.a)`"),
];

/// What counts as a colour, in words.
pub const WHAT_IS_A_COLOUR: &str = "A colour is a `vec4` of straight (not premultiplied) alpha: light in `.rgb`, coverage in `.a`, each 0..1 in an 8-bit target. Colours are: colour literals (`#rgb`, `#rrggbb`, `#rrggbbaa`; alpha 1 unless written), `color` params, image and art-map textures read as values, reads of `rgba8unorm` and `rgba8unorm_srgb` targets, operators whose result is a colour, and the arithmetic, `mix`, `min`, `max`, `clamp` and `if` of colours. `vec4(...)`, noise textures and float targets are plain vectors: arithmetic on them acts on all four components. The PNG `npr render` writes keeps the output's alpha: an output with alpha 0 is transparent there.";

/// (source as written, its settings, what each texel holds).
pub const TEXTURE_SOURCES: &[(&str, &str, &str)] = &[
    (
        "image(\"file.png\", srgb)",
        "`srgb` (8-bit colour images: decoded to linear) or `linear` (data: normals, masks, noise)",
        "A colour: the file's rgba in 0..1 (alpha 1 where the file has none); EXR files hold floats as written.",
    ),
    (
        "noise(size: 256, octaves: 4, seed: 0, kind: gradient, channels: 1, frequency: 4)",
        "`size` 1..4096 texels (default 256), `octaves` 1..12 (4), `seed` (0), `kind: gradient` (Perlin) or `value` (default `value`), `channels` 1..4 (1), `frequency` 1..256 lattice cells across at the first octave (4)",
        "Tileable noise in 0..1 (mean about 0.5). One channel: the same value in r, g and b; n channels: n independent noises in r, g, b, a; channels not made are 0, alpha 1. Not a colour: arithmetic acts on all four components.",
    ),
    (
        "halftone_table(edge: 0.1)",
        "`edge` 0..0.5, `correction` (on)",
        "The halftone screen's tone-correction table (Breslav et al. 2007 §3.5): pass it to `halftone(...)`; it is not read as a value.",
    ),
    (
        "input(depth)",
        "the kind: `color, linear` or `color, display`, `depth`, `normal, world` or `normal, view`, `id`, `motion` or `image, FORMAT`",
        "An image the host gives each frame, converted at load to the kind's one convention: depth in r (metres along the view axis, 0 where nothing was hit), unit normals in rgb, ids in r, motion in rg (px), colour as said.",
    ),
    (
        "artmap(image(\"file.png\"), filter: \"filter.npr\", levels: auto)",
        "`filter`: a filter style (or `filter(\"f.npr\", arg: value)`), `levels: auto` or a count",
        "A colour: the image's mip chain, each level made by the filter (Klein et al. 2000 §4.2), read by `sample_artmap(...)`.",
    ),
];

/// (option, values) after a texture declaration: `texture t = ... { wrap: repeat }`.
pub const TEXTURE_OPTIONS: &[(&str, &str)] = &[
    ("wrap", "`repeat` (the default for noise) or `clamp`"),
    ("filter", "`linear` or `nearest`"),
    ("mips", "`on` or `off` (an art-map always has mips)"),
];

/// (setting as written, the passes that take it, what it does).
pub const PASS_SETTINGS: &[(&str, &str, &str)] = &[
    ("clear: #rrggbb", "render, image, lines", "The colour every output starts from before the pass draws (default `#00000000`, transparent black); a number `k` is `(k, k, k, 1)`."),
    ("depth: keep", "render", "Keep this pass's depth buffer so later render and lines passes can test against it."),
    ("depth: test(pass, bias: 1px)", "render, lines", "Test against the depth `pass` kept, without writing it; `bias` in px (slope-scaled) or in depth units (a plain number) lets a surface pass its own depth. `pass` may instead be an `input(depth)` texture: the host's depth, drawn each frame through the camera's projection, hides npr's own lines or surfaces behind the host's (the pass at scale 1, through the camera: E0320; any other name: E0319)."),
    ("out name: format = value { blend: over }", "render, image, lines", "How an output combines with what the target holds: `replace` (default), `over` (straight-alpha Porter-Duff over), `add`, `multiply`. 32-bit float formats cannot blend (E0307)."),
    ("schedule: naive | auto | tiled | recompute", "image", "Force how this pass runs whatever `--schedule` says: `naive` as written, `tiled` as compute over workgroup tiles, `recompute` in its reader's tiles, `auto` leaves it to `--schedule`."),
    ("scale 1/2", "image, render (after the kind)", "The pass's image size relative to the output, in (0, 4]."),
    ("view(light)", "render (after the kind)", "Draw from the scene's light instead of the camera (a shadow map; `position.light`)."),
    ("vertex { inflate: 2px, shadow_warp: w }", "render", "Vertex modifiers: push each vertex out along its screen-space normal by a width (outlines by inflated back faces), warp a light-view pass."),
    ("silhouettes, creases, width, amplitude, wavelength, phase, taper", "lines", "The strips' shape: `silhouettes: true`, `creases: 40deg` or `off`, `width: 3px`, `amplitude: 1px`, `wavelength: 40px`, `phase`, `taper`."),
    ("set name { edges: silhouette, width: 3px, color: ink }", "lines", "A line set (decision 0056): `edges:` a union of edge types joined by a vertical bar, from `silhouette`, `border`, `crease(35deg)`, `material_boundary`, `intersection`, `marked` (edges the mesh file marks: glTF `_NPR_EDGE_MARK`, decision 0063); `tag: name` narrows the pass's objects; `priority: n` (higher first, ties in the order written: an edge two sets select is drawn once, by the higher, unless their visibilities are disjoint); `visibility: visible`, `hidden`, `hidden(n)` or `all` (by quantitative invisibility, the surfaces in front counted per piece of line; without it the pass's depth test hides; decision 0063); `dash: 6px` or `dash: dashes(6px, 4px)` (along the screen arc length); `color:`, which `line.color` reads in the pass's outputs (`line.set` is the set's index); and the shape settings, the pass's where unset. With sets, the pass's `silhouettes:`/`creases:` are refused (E0317)."),
    ("count: n, seed: n", "compute(samples)", "How many stratified surface samples per object, and their seed."),
];

/// (conversion, how) between units.
pub const UNIT_CONVERSIONS: &[(&str, &str)] = &[
    ("px → plain number", "divide by one pixel: `width / 1px` (a unit divided by itself is a plain number)."),
    ("plain number → px", "multiply by one pixel: `k * 1px`, or write the literal with its unit (`3px`)."),
    ("% → px", "`50%` is half the image height, in px, at run time; `resolution.y` is the pass's height in px."),
    ("mm → m", "at compile time: `20mm` is `0.02m` (a param declared `m` takes either)."),
    ("m → px at a surface point", "`size / depth * camera.focal.y * resolution.y * 0.5`: a world length `size` seen at view distance `depth` (both m) spans that many px (`camera.focal.y` is the projection's P₁₁). That is a perspective camera's; through an orthographic one (`camera.orthographic` is 1) leave out the division by `depth`: P₁₁ is then 2 / the view height."),
    ("px → m at a surface point", "the inverse: `w / (camera.focal.y * resolution.y * 0.5) * depth` (orthographic: without `* depth`)."),
    ("deg → radians", "operators take `deg` and receive radians; `45deg` is π/4 in the shader."),
    ("s and Hz", "`time * 2Hz` is a plain number (cycles); `1 / 2Hz` is `0.5s`."),
];

/// A "how do I" recipe: the question, the answer, and a style that does
/// it (compiled by the reference's test).
pub struct Recipe {
    pub question: &'static str,
    pub answer: &'static str,
    pub style: &'static str,
}

pub const RECIPES: &[Recipe] = &[
    Recipe {
        question: "Thicker ink lines",
        answer: "`normal_depth_edges` and `sobel` find edges one pixel wide in an image pass. For lines of a chosen width, draw the silhouettes and creases as strips with a `lines` pass (`width`, and `amplitude`/`wavelength` for a hand-drawn wobble), tested against the shading's kept depth, and multiply it in; or inflate back faces in a second render pass (`vertex { inflate: 3px }`, see `examples/overlay_lines.npr`).",
        style: "style \"Thick lines\"\nparam ink: color = #1c1a22\n\npass shade: render(scene) {\n  out color: rgba8unorm = #f4efe4 * half_lambert(normal, light.dir)\n  depth: keep\n  clear: #ffffff\n}\n\npass ink_layer: lines(scene) {\n  silhouettes: true\n  creases: 40deg\n  width: 4px\n  depth: test(shade, bias: 1px)\n  out ink: rgba8unorm = vec4(ink.rgb, 1.0 - smoothstep(0.6, 1.0, abs(line.across))) { blend: over }\n  clear: #ffffff\n}\n\npass final: image(shade, ink_layer) {\n  out color: rgba8unorm = shade.color * ink_layer.ink\n}\n\noutput final.color\n",
    },
    Recipe {
        question: "A paper texture",
        answer: "Declare a texture (an image of paper, or generated noise), read it at `screen_uv` in an image pass (a texture read as a value is sampled there) and multiply the shading by it. A noise texture is data, not a colour: take one channel (`.r`) and scale the paper colour by it.",
        style: "style \"Paper\"\ntexture grain = noise(size: 256, octaves: 5, seed: 7, kind: gradient) { wrap: repeat, filter: linear }\n\npass shade: render(scene) {\n  out color: rgba8unorm = #e07a3a * half_lambert(normal, light.dir)\n  clear: #ffffff\n}\n\npass final: image(shade) {\n  let paper = #f4efe4 * mix(0.85, 1.0, grain.r)\n  out color: rgba8unorm = shade.color * paper\n}\n\noutput final.color\n",
    },
    Recipe {
        question: "A cast shadow",
        answer: "Render the scene's depth from the light (`view(light)`, `position.light.z` into an `r32float` target, cleared to white), then in the camera's pass `shadow(depth.d, bias: ..., warp: ...)` is 0 in shadow and 1 in light. For soft, rounded shadow shapes, blur and threshold the light term (`examples/rounded_shadows.npr`).",
        style: "style \"Shadow\"\nparam lit: color = #f2c894\nparam dark: color = #4a3b6b\n\npass depth: render(scene) view(light) {\n  out d: r32float = position.light.z\n  clear: #ffffff\n}\n\npass shade: render(scene) {\n  let light_term = lambert(normal, light.dir) * shadow(depth.d, bias: 0.01, warp: 0.0)\n  out color: rgba8unorm = mix(dark, lit, light_term)\n  clear: #ffffff\n}\n\noutput shade.color\n",
    },
    Recipe {
        question: "Read the previous frame",
        answer: "`previous(pass.target)` is the target as the previous frame left it (transparent black on the first frame); a pass may read its own target so. `npr render --time t` replays the frames from 0 at `--fps`, so a frame looks the same alone as in a sequence (`examples/afterimage.npr`).",
        style: "style \"Trails\"\nparam persistence: float = 0.8 in 0..0.99\n\npass shade: render(scene) {\n  out color: rgba8unorm = #e07a3a * toon(half_lambert(normal, light.dir), steps: 3)\n  clear: #101018\n}\n\npass final: image(shade) {\n  out color: rgba8unorm = mix(shade.color, previous(final.color), persistence)\n}\n\noutput final.color\n",
    },
];

/// What a `gradient` param is and how `ramp` reads it.
pub const GRADIENTS: &str = "`param g: gradient = gradient(stop(position, colour), ...)` declares a colour ramp: stops at positions from 0 to 1, in order, each a colour literal; two stops at one position make a hard edge, and `mode: constant` gives bands (each stop's colour from its position on) instead of blends. `ramp(g, t)` is the colour at `t`: the first stop's colour below it, the last's past it, and between two stops their mix (Blender's Color Ramp, Unity's Gradient). A gradient is a constant folded into the shader (E0206 for no stops, stops out of order, a position outside 0..1); it has at most 16 stops. `--set g=\"0:#000000, 0.5:#ff8800, 1:#ffffff\"` replaces its stops (`position:#colour`, comma-separated; the mode stays as declared). Under `--keep-params` (`npr studio`, `npr view`, a host's `keep_params`) it is a uniform instead, 21 `vec4` slots of the style block that `ramp` reads in the shader, so new stops re-render without a recompile: the studio shows it as a ramp strip whose stops you add, drag, retype and recolour, and `write` puts them back into the file as `gradient(stop(...), ...)`; a host sets it with `set_param(\"g\", \"0:#000000, 1:#ffffff\")` (E0206 for bad stops) (docs/decisions/0040).";

/// A style that uses a gradient (also `examples/toon_ramp.npr`).
pub const GRADIENT_EXAMPLE: &str = "style \"Ramp\"\nparam shading: gradient = gradient(stop(0.0, #2a1f4a), stop(0.5, #8a4a5a), stop(0.5, #e07a3a), stop(1.0, #fff0d0))\nparam bands: gradient = gradient(stop(0.0, #202020), stop(0.4, #808080), stop(0.8, #f0f0f0), mode: constant)\n\npass p: render(scene) {\n  let light_term = half_lambert(normal, light.dir)\n  out color: rgba8unorm = ramp(shading, light_term) * ramp(bands, light_term)\n  clear: #ffffff\n}\n\noutput p.color\n";

/// The colour section's examples: a style that uses each rule.
pub const COLOUR_EXAMPLE: &str = "style \"Colours\"\nparam base: color = #e07a3a\nparam shade: color = #3a2a5a\n\npass p: render(scene) {\n  let lit = lambert(normal, light.dir)\n  // Opaque where `base` is: the number scales the light only.\n  let dark_side = base * lit\n  // Light added where either colour covers; alpha stays 1.\n  let glow = dark_side + shade * 0.2\n  // Tint: two colours multiplied per component.\n  out color: rgba8unorm = glow * #ffeedd\n  clear: #ffffff\n}\n\noutput p.color\n";
