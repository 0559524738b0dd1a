// Distance compensation of the warp intensity (Age of Sail §4.4, eq. 26):
// ρ' = ρ / (1 + d²), with d in units of `falloff` (1 m reproduces the paper).
fn npr_distance_attenuate(rho: f32, d: f32, falloff: f32) -> f32 {
    let x = abs(d) / max(falloff, 1e-6);
    // x² overflows to +inf past ~1.8e19: ρ/inf = 0, the right limit.
    return rho / (1.0 + x * x);
}
