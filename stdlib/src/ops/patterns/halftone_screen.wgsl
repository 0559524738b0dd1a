// The procedural dot screen of Breslav et al. 2007's halftones (§3.4), as
// jot-lib draws it (nprdata/glsl/haftone_tx.fp, `halftone`): a height in
// [0.1, 0.9] at each point uv of the pattern, the mean over both axes of
// 0.5 + 0.4·cos(2πx). Ink covers the points whose height is below the
// threshold, so a dot grows from each cell's corner as the tone darkens.
// `blend` in [0, 1] mixes the heights of this screen and of the screen at
// half the period (§3.4), so that over an LOD transition each dot morphs
// into four instead of fading out. `fract` first keeps f32 precision far
// from the pattern's origin.
fn npr_halftone_screen(uv: vec2<f32>, blend: f32) -> f32 {
    let turn = 6.2831853;
    let coarse = 0.5 + 0.4 * cos(fract(uv) * turn);
    let fine = 0.5 + 0.4 * cos(fract(uv * 2.0) * turn);
    let h = mix(coarse, fine, clamp(blend, 0.0, 1.0));
    return 0.5 * (h.x + h.y);
}
