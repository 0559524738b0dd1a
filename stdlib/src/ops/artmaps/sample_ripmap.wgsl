// A read of a rip-map (Klein et al. 2000 §4.2, Fig. 7–8): "a cascading
// series of pre-filtered, off-angle images of the texture", here every
// level (i, j) of the source's width halved i times and its height j
// times, side by side in one atlas of 2W × 2H texels (npr_abi::RipmapAtlas).
// Hardware has no rip-maps, so the level of each axis is chosen here from
// the screen derivatives of that axis alone, log2 of the larger of
// |du/dx|, |du/dy| in level-0 texels (and the same for v), and the four
// levels around (lod_u, lod_v) are blended bilinearly: an oblique surface
// gets a level squashed along its foreshortened axis only, so its strokes
// keep their aspect ratio. uv repeats; bilinear taps stay half a texel
// inside each level's rectangle (a half-texel seam where uv wraps).

fn npr_ripmap_levels(size: u32) -> u32 {
    return 32u - countLeadingZeros(max(size, 1u));
}

// Texels before level k along an axis of `size` texels at level 0.
fn npr_ripmap_offset(size: u32, k: u32) -> u32 {
    var o = 0u;
    for (var l = 0u; l < k; l = l + 1u) {
        o = o + max(size >> l, 1u);
    }
    return o;
}

fn npr_ripmap_tap(tex: texture_2d<f32>, samp: sampler, uv: vec2<f32>, base: vec2<u32>, level: vec2<u32>) -> vec4<f32> {
    let atlas = vec2<f32>(textureDimensions(tex));
    let size = vec2<f32>(f32(max(base.x >> level.x, 1u)), f32(max(base.y >> level.y, 1u)));
    let origin = vec2<f32>(f32(npr_ripmap_offset(base.x, level.x)), f32(npr_ripmap_offset(base.y, level.y)));
    let local = clamp(fract(uv) * size, vec2<f32>(0.5), size - vec2<f32>(0.5));
    return textureSampleLevel(tex, samp, (origin + local) / atlas, 0.0);
}

fn npr_sample_ripmap(tex: texture_2d<f32>, samp: sampler, uv: vec2<f32>) -> vec4<f32> {
    let base = textureDimensions(tex) / 2u;
    let dx = dpdx(uv);
    let dy = dpdy(uv);
    let footprint = vec2<f32>(max(abs(dx.x), abs(dy.x)) * f32(base.x), max(abs(dx.y), abs(dy.y)) * f32(base.y));
    let top = vec2<f32>(f32(npr_ripmap_levels(base.x) - 1u), f32(npr_ripmap_levels(base.y) - 1u));
    let lod = clamp(log2(max(footprint, vec2<f32>(1e-12))), vec2<f32>(0.0), top);
    let l0 = vec2<u32>(floor(lod));
    let l1 = min(l0 + vec2<u32>(1u), vec2<u32>(top));
    let t = lod - floor(lod);
    let a = mix(npr_ripmap_tap(tex, samp, uv, base, l0), npr_ripmap_tap(tex, samp, uv, base, vec2<u32>(l1.x, l0.y)), t.x);
    let b = mix(npr_ripmap_tap(tex, samp, uv, base, vec2<u32>(l0.x, l1.y)), npr_ripmap_tap(tex, samp, uv, base, l1), t.x);
    return mix(a, b, t.y);
}
