// Roberts-cross edges on normals and linear depth (the "Honks" outline
// method): normals are stored encoded as n·0.5 + 0.5 in rgb, depth in r.
// 1 where either diagonal difference exceeds its threshold, else 0.
fn npr_normal_depth_edges(normals: texture_2d<f32>, depth: texture_2d<f32>, uv: vec2<f32>, depth_threshold: f32, normal_threshold: f32) -> f32 {
    let nd = vec2<i32>(textureDimensions(normals));
    let dd = vec2<i32>(textureDimensions(depth));
    let pn = clamp(vec2<i32>(floor(uv * vec2<f32>(nd))), vec2<i32>(0), nd - vec2<i32>(1));
    let pd = clamp(vec2<i32>(floor(uv * vec2<f32>(dd))), vec2<i32>(0), dd - vec2<i32>(1));
    let n0 = textureLoad(normals, pn, 0).rgb * 2.0 - 1.0;
    let n1 = textureLoad(normals, min(pn + vec2<i32>(1, 1), nd - vec2<i32>(1)), 0).rgb * 2.0 - 1.0;
    let n2 = textureLoad(normals, min(pn + vec2<i32>(1, 0), nd - vec2<i32>(1)), 0).rgb * 2.0 - 1.0;
    let n3 = textureLoad(normals, min(pn + vec2<i32>(0, 1), nd - vec2<i32>(1)), 0).rgb * 2.0 - 1.0;
    let d0 = textureLoad(depth, pd, 0).r;
    let d1 = textureLoad(depth, min(pd + vec2<i32>(1, 1), dd - vec2<i32>(1)), 0).r;
    let d2 = textureLoad(depth, min(pd + vec2<i32>(1, 0), dd - vec2<i32>(1)), 0).r;
    let d3 = textureLoad(depth, min(pd + vec2<i32>(0, 1), dd - vec2<i32>(1)), 0).r;
    let dn = sqrt(dot(n1 - n0, n1 - n0) + dot(n3 - n2, n3 - n2));
    let ddep = sqrt((d1 - d0) * (d1 - d0) + (d3 - d2) * (d3 - d2));
    return select(0.0, 1.0, dn > normal_threshold || ddep > depth_threshold);
}
