// e_plane of the LSA contours (eq. 6), shared by the operators that enable
// the planarity extension. The arc extrema of |N·d| over the great-circle
// arc between two unit normals have closed forms:
// - min: 0 if N·d changes sign along the arc (N_a·d and N_b·d differ in
//   sign), else min(|N_a·d|, |N_b·d|) — |N·d| is a sinusoid over an arc
//   shorter than π, concave between its zeros, so its minimum is at an end;
// - max: |d projected onto the arc's plane| if the direction of that
//   projection (or its opposite) lies on the arc, else the larger end value.
//
// Which offsets: as printed, eq. 6 takes both from q, which makes a step
// between parallel planes give the ratio 1 and no line (contradicting
// Fig. 3 and the text after eq. 6). Following the authors' public code, the
// numerator uses the checked texel q and the denominator the control texel
// q̌ that fixes S(p, q): on one plane the denominator is ~0 (ε remains) and
// any offset of q along the normal makes e_plane grow rapidly.

fn npr_lsa_plane__arc_min(d: vec3<f32>, na: vec3<f32>, nb: vec3<f32>) -> f32 {
    let da = dot(d, na);
    let db = dot(d, nb);
    return select(min(abs(da), abs(db)), 0.0, da * db <= 0.0);
}

fn npr_lsa_plane__arc_max(d: vec3<f32>, na: vec3<f32>, nb: vec3<f32>) -> f32 {
    let ends = max(abs(dot(d, na)), abs(dot(d, nb)));
    let axis = cross(na, nb);
    let s = length(axis);
    if (s < 1e-6) {
        return ends;
    }
    let w = axis / s;
    let dp = d - w * dot(d, w);
    // The projection's direction is on the arc from na to nb (turning about
    // w) when it is past na and before nb; its opposite when both fail.
    let x = dot(cross(na, dp), w);
    let y = dot(cross(dp, nb), w);
    let on_arc = (x >= 0.0 && y >= 0.0) || (x <= 0.0 && y <= 0.0);
    return select(ends, max(ends, length(dp)), on_arc);
}

// Eq. 6's denominator for control c: the arc maximum of |ΔP·N| from N_p to
// N_c, with the offset scaled by sc (1 for a one-step control, 0.5 for the
// doubled offsets of eq. 8). It depends on the control alone, so each
// operator computes it once per control and reuses it for every check.
fn npr_lsa_plane__den(c: npr_lsa_core__Texel, p: npr_lsa_core__Texel, sc: f32) -> f32 {
    return npr_lsa_plane__arc_max((c.p - p.p) * sc, p.n, c.n);
}

// Eq. 6's numerator for check q: the arc minimum of |ΔP·N| from N_p to N_q,
// the offset scaled by sq as for `den`. It depends on the check alone.
fn npr_lsa_plane__num(q: npr_lsa_core__Texel, p: npr_lsa_core__Texel, sq: f32) -> f32 {
    return npr_lsa_plane__arc_min((q.p - p.p) * sq, p.n, q.n);
}

// Eq. 6's terms of two texels on opposite sides of p, `back` = p − k·m and
// `ahead` = p + k·m, with offsets scaled by `scale` (1 for k = 1, 0.5 for
// the two-step texels of eq. 8): each texel's denominator, for when it is
// the control, and numerator, for when it is the check, computed once;
// all 0 when the planarity extension is off.
struct npr_lsa_plane__Pair {
    den_back: f32,
    den_ahead: f32,
    num_back: f32,
    num_ahead: f32,
}

fn npr_lsa_plane__pair(back: npr_lsa_core__Texel, ahead: npr_lsa_core__Texel, p: npr_lsa_core__Texel, scale: f32, plane: bool) -> npr_lsa_plane__Pair {
    var t = npr_lsa_plane__Pair(0.0, 0.0, 0.0, 0.0);
    if (plane) {
        t.den_back = npr_lsa_plane__den(back, p, scale);
        t.den_ahead = npr_lsa_plane__den(ahead, p, scale);
        t.num_back = npr_lsa_plane__num(back, p, scale);
        t.num_ahead = npr_lsa_plane__num(ahead, p, scale);
    }
    return t;
}

// e_plane (eq. 6) from its numerator and denominator, with k: [50, 150] →
// [0, 1], clamped; 0 when the planarity extension is off (eq. 7's e_sum is
// then e_curv alone).
fn npr_lsa_plane__term(plane: bool, num: f32, den: f32) -> f32 {
    return select(0.0, clamp((num / (den + 1e-5) - 50.0) / 100.0, 0.0, 1.0), plane);
}
