// Contour fade-out (LSA contours §4.2, Fig. 5–6): a soft dark band on the
// near side of occluding contours, wide enough to cover where the two eyes'
// contours differ, so line art fuses binocularly.
// V_C is the viewpoint in the disc A (centre (V_L+V_R)/2, radius |V_L−V_R|/2,
// orthogonal to the view direction F) closest to seeing P as a contour; it
// lies on A's boundary, against the normal's component in A's plane (first
// order in radius/distance). φ = ∠(V_C − P, N); ᾱ = ∠(V_L − P, V_R − P).
// The fade maps φ linearly from [π/2 − c_start, π/2 − c_end] to [0, 1] with
// c_start = start·ᾱ, c_end = end·ᾱ (the paper's 7/4 and 7/16). With one eye
// (ᾱ = 0) it is a step at the contour, φ ≥ π/2. Fuse with E by `max`.
fn npr_contour_fade(p: vec3<f32>, n: vec3<f32>, eye_left: vec3<f32>, eye_right: vec3<f32>, forward: vec3<f32>, start: f32, end: f32) -> f32 {
    let half_pi = 1.5707963267948966;
    let nl = length(n);
    if (!(nl > 1e-20) || nl > 1e20) {
        return 0.0;
    }
    let nn = n / nl;
    let fl = length(forward);
    let f = select(vec3<f32>(0.0, 0.0, -1.0), forward / fl, fl > 1e-20 && fl < 1e20);
    let centre = 0.5 * (eye_left + eye_right);
    let radius = 0.5 * length(eye_right - eye_left);
    let in_plane = nn - dot(nn, f) * f;
    let ipl = length(in_plane);
    var vc = centre;
    if (ipl > 1e-6) {
        vc = centre - radius * in_plane / ipl;
    }
    let to_view = vc - p;
    let tl = length(to_view);
    if (!(tl > 1e-20)) {
        return 0.0;
    }
    let phi = acos(clamp(dot(to_view / tl, nn), -1.0, 1.0));
    let a = eye_left - p;
    let b = eye_right - p;
    let ab = length(a) * length(b);
    var alpha = 0.0;
    if (ab > 1e-30) {
        alpha = acos(clamp(dot(a, b) / ab, -1.0, 1.0));
    }
    let lo = half_pi - max(start, 0.0) * alpha;
    let hi = half_pi - max(end, 0.0) * alpha;
    if (!(hi - lo > 1e-7)) {
        return select(0.0, 1.0, phi >= half_pi);
    }
    return clamp((phi - lo) / (hi - lo), 0.0, 1.0);
}
