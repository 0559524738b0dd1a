// Camera-roll compensation (Age of Sail §4.3): express a warp vector (e.g. the
// rg of a noise texture remapped to [−1, 1]) in the frame of the screen-space
// gradient of u: out = vec.x·ê + vec.y·ê⊥ with ê = ∇u/|∇u|, ê⊥ = (−ê.y, ê.x).
// When the camera rolls, ∇u rolls with the image and so does the warp field,
// so warped edges keep their shape. ∇u = 0 leaves the vector unchanged.
fn npr_roll_compensate(w: vec2<f32>, grad_u: vec2<f32>) -> vec2<f32> {
    let l = length(grad_u);
    if (!(l > 1e-30) || l > 1e30) {
        // Zero, NaN or infinite ∇u: no frame to rotate into.
        return w;
    }
    let e = grad_u / l;
    return w.x * e + w.y * vec2<f32>(-e.y, e.x);
}
