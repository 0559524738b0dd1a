// The anti-aliasing term of the LSA contours (eq. 8), shared by the operators
// that enable it.

// e_aa (eq. 8) from the remapped terms a, b, c; a < 0 or b < 0 marks a term
// whose far texel lies outside the image (it then takes no part).
fn npr_lsa_aa__mix(a: f32, b: f32, c: f32) -> f32 {
    let aa = select(a, c, a < 0.0);
    let bb = select(b, c, b < 0.0);
    let m = min(aa, bb);
    return select(c, 0.5 * (m + c), m < c);
}
