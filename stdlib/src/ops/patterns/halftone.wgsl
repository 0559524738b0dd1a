// A tone-corrected halftone (Breslav et al. 2007 §3.5): the paper's share
// at uv (1 = paper, 0 = ink) for the wanted tone (1 = white), on the screen
// `npr_halftone_screen(uv, blend)` with soft dot edges of half-width `edge`:
// paper = smoothstep(−edge, edge, t − h). The threshold t is not the tone
// itself: it is looked up in `table`, a `halftone_table(...)` texture that
// the runner builds at load by tabulating the mean paper share R(t, blend)
// that this very screen and edge produce over a cell and inverting it, so
// that the mean over a cell is the wanted tone at every LOD blend.
//
// The table is 256 × 17 texels: row j < 16 holds R⁻¹(i/255) at blend j/15,
// and texel (0, 16) holds the edge the table was built with, which is read
// here, so the shader and the table cannot disagree on it (jot-lib's table
// assumes ±0.1 where its shader draws ±0.2; see docs/PERFORMANCE.md).
fn npr_halftone(table: texture_2d<f32>, uv: vec2<f32>, tone: f32, blend: f32) -> f32 {
    let b = clamp(blend, 0.0, 1.0);
    let edge = textureLoad(table, vec2<i32>(0, 16), 0).r;
    // Bilinear interpolation of the table at (tone·255, b·15), by hand so
    // that it is exact and needs no sampler.
    let at = vec2<f32>(clamp(tone, 0.0, 1.0) * 255.0, b * 15.0);
    let lo = vec2<i32>(floor(at));
    let hi = min(lo + vec2<i32>(1), vec2<i32>(255, 15));
    let f = at - floor(at);
    let t00 = textureLoad(table, lo, 0).r;
    let t10 = textureLoad(table, vec2<i32>(hi.x, lo.y), 0).r;
    let t01 = textureLoad(table, vec2<i32>(lo.x, hi.y), 0).r;
    let t11 = textureLoad(table, hi, 0).r;
    let threshold = mix(mix(t00, t10, f.x), mix(t01, t11, f.x), f.y);
    return smoothstep(-edge, edge, threshold - npr_halftone_screen(uv, b));
}
