// Per-edge silhouette classification (Klein et al. 2000 §5: silhouettes are
// the edges whose front and back faces differ from the current eye), one
// invocation per 32 edges, writing one bit per edge. The same test as
// `EdgeMesh::is_front` in f32: a face is front when n·eye + d > 0, with
// the plane (n, d = −n·corner) computed in f64 on the CPU and rounded.
// No atomics: every invocation owns its output word.

struct Params {
    // xyz: the eye in object space; w unused.
    eye: vec4<f32>,
    // x: edges, y: words (ceil(edges / 32)), z: words per dispatch row.
    counts: vec4<u32>,
}

@group(0) @binding(0) var<uniform> params: Params;
// One plane per face: xyz the unit normal, w = −n·corner.
@group(0) @binding(1) var<storage, read> planes: array<vec4<f32>>;
// The two faces of each edge; 0xffffffff in x for an edge that has not
// exactly two (boundary, non-manifold): never a silhouette.
@group(0) @binding(2) var<storage, read> edge_faces: array<vec2<u32>>;
@group(0) @binding(3) var<storage, read_write> flags: array<u32>;

const NO_FACE: u32 = 0xffffffffu;

fn front(f: u32) -> bool {
    let p = planes[f];
    return dot(p.xyz, params.eye.xyz) + p.w > 0.0;
}

@compute @workgroup_size(64)
fn classify(@builtin(global_invocation_id) id: vec3<u32>) {
    let word = id.y * params.counts.z + id.x;
    if (word >= params.counts.y) {
        return;
    }
    var bits = 0u;
    let first = word * 32u;
    let last = min(first + 32u, params.counts.x);
    for (var e = first; e < last; e = e + 1u) {
        let fg = edge_faces[e];
        if (fg.x != NO_FACE && front(fg.x) != front(fg.y)) {
            bits = bits | (1u << (e - first));
        }
    }
    flags[word] = bits;
}
