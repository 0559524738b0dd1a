// npr's GPU deformation stage (runner/src/exec/deform.rs, decision 0053):
// one invocation per vertex of an object playing a glTF clip writes its
// morphed and skinned position, normal and tangent over the object's
// vertex buffers, which every pass then binds.
//
// The formulas are glTF 2.0's and `scene::rig::Rig::deform`'s, operation
// for operation: morph first (§3.7.2.2, p' = p + Σ_k w_k Δp_k, normals
// and tangents likewise), then linear blend skinning of 4 joints (§3.7.3,
// M = Σ_i w_i · palette[j_i]; an unskinned piece's vertices name its
// node's world matrix with weight 1). Normals go through M's cofactor
// matrix (the inverse transpose up to a positive factor), flipped when M
// mirrors; tangents through M's linear part, their handedness flipped
// likewise; both normalised, zero where the length is zero.

struct RestVertex {
    position: vec4<f32>,
    normal: vec4<f32>,
    tangent: vec4<f32>,
    // Indices into `palette`.
    joints: vec4<u32>,
    weights: vec4<f32>,
    // x: its piece's first morph weight, y: the piece's target count,
    // z: its delta of target 0, w: the deltas' stride (the piece's vertex count).
    morph: vec4<u32>,
}

struct MorphDelta {
    position: vec4<f32>,
    normal: vec4<f32>,
    tangent: vec4<f32>,
}

@group(0) @binding(0) var<storage, read> rest: array<RestVertex>;
@group(0) @binding(1) var<storage, read> deltas: array<MorphDelta>;
// The frame's joint matrices (world · inverseBind) and unskinned nodes' world matrices.
@group(0) @binding(2) var<storage, read> palette: array<mat4x4<f32>>;
@group(0) @binding(3) var<storage, read> morph_weights: array<f32>;
@group(0) @binding(4) var<storage, read_write> out_position: array<f32>;
@group(0) @binding(5) var<storage, read_write> out_normal: array<f32>;
// 16 bytes when the mesh has no tangents: nothing is written then.
@group(0) @binding(6) var<storage, read_write> out_tangent: array<f32>;

fn unit_or_zero(v: vec3<f32>) -> vec3<f32> {
    let len = length(v);
    return select(vec3<f32>(0.0), v / len, len > 0.0);
}

// Workgroups (64 vertices each) are numbered x + y * 65535 past 65535 of them.
@compute @workgroup_size(64)
fn deform(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let v = (group.x + group.y * 65535u) * 64u + lane;
    if (v >= arrayLength(&rest)) {
        return;
    }
    let r = rest[v];
    var p = r.position.xyz;
    var n = r.normal.xyz;
    var t = r.tangent;
    for (var k = 0u; k < r.morph.y; k = k + 1u) {
        let w = morph_weights[r.morph.x + k];
        if (w != 0.0) {
            let d = deltas[r.morph.z + k * r.morph.w];
            p = p + w * d.position.xyz;
            n = n + w * d.normal.xyz;
            t = t + vec4<f32>(w * d.tangent.xyz, 0.0);
        }
    }
    let m = palette[r.joints.x] * r.weights.x + palette[r.joints.y] * r.weights.y
        + palette[r.joints.z] * r.weights.z + palette[r.joints.w] * r.weights.w;
    let q = m * vec4<f32>(p, 1.0);
    out_position[3u * v] = q.x;
    out_position[3u * v + 1u] = q.y;
    out_position[3u * v + 2u] = q.z;
    let l = mat3x3<f32>(m[0].xyz, m[1].xyz, m[2].xyz);
    let mirrors = determinant(l) < 0.0;
    let cofactor = mat3x3<f32>(cross(l[1], l[2]), cross(l[2], l[0]), cross(l[0], l[1]));
    let normal = unit_or_zero(select(1.0, -1.0, mirrors) * (cofactor * n));
    out_normal[3u * v] = normal.x;
    out_normal[3u * v + 1u] = normal.y;
    out_normal[3u * v + 2u] = normal.z;
    if (4u * v + 3u < arrayLength(&out_tangent)) {
        let tangent = unit_or_zero(l * t.xyz);
        out_tangent[4u * v] = tangent.x;
        out_tangent[4u * v + 1u] = tangent.y;
        out_tangent[4u * v + 2u] = tangent.z;
        out_tangent[4u * v + 3u] = select(t.w, -t.w, mirrors);
    }
}
