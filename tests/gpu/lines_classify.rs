//! Silhouette classification in a compute pass (`npr_lab::silhouettes_gpu`,
//! Klein et al. 2000 §5: the edges whose faces differ in facing from the
//! eye) gives the CPU's edges (`EdgeMesh::silhouettes`, f64) on a cube, two
//! spheres and fandisk, from eyes all around each mesh and from eyes in the
//! plane of a cube's faces (edge-on faces, which both call back-facing:
//! the plane and the eye are exact in f32, so n·eye + d is exactly 0).
//!
//! The compute pass tests n·eye + d > 0 in f32, the CPU n·(eye − corner) > 0
//! in f64, so they could only disagree on a face within f32 rounding of
//! edge-on (|n·(eye − corner)| ≲ 1e-6 of the distances). The test requires
//! every disagreement to be such a tie, and measures none on these eyes.

use glam::DVec3;
use npr_lab::silhouettes_gpu::GpuSilhouettes;
use npr_runner::lines::edges::EdgeMesh;

use crate::common;
use common::{gpu, root};

/// A face is a tie when its facing margin is below this share of the
/// eye's distance to its corner plus the corner's distance to the origin.
const TIE: f64 = 1e-6;

fn mesh(object: &str) -> EdgeMesh {
    let text = format!("[camera]\nposition = [0.0, 0.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\n\n[[object]]\n{object}\n");
    let mut sources = npr_diag::SourceMap::new();
    let file = sources.add("scene.toml", text.clone());
    let scene = npr_runner::scene::parse_scene(&text, file, root())
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));
    EdgeMesh::new(&scene.objects[0].mesh)
}

/// `count` eyes on a Fibonacci sphere around `centre`, at 1.5 to 4 times
/// `radius`.
fn eyes_around(centre: DVec3, radius: f64, count: u32) -> Vec<DVec3> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..count)
        .map(|k| {
            let y = 1.0 - 2.0 * (f64::from(k) + 0.5) / f64::from(count);
            let r = (1.0 - y * y).sqrt();
            let a = golden * f64::from(k);
            let distance = radius * (1.5 + 2.5 * f64::from(k % 5) / 4.0);
            centre + DVec3::new(r * a.cos(), y, r * a.sin()) * distance
        })
        .collect()
}

/// The facing margin of face `f` from `eye`, relative to the sizes
/// involved (see [`TIE`]).
fn margin(mesh: &EdgeMesh, f: u32, eye: DVec3) -> f64 {
    let corner = mesh.positions[mesh.faces[f as usize][0] as usize];
    mesh.normals[f as usize].dot(eye - corner).abs() / ((eye - corner).length() + corner.length())
}

/// How many edges the two classify differently over `eyes`; every such
/// edge must be a tie.
fn compare(name: &str, mesh: &EdgeMesh, eyes: &[DVec3]) -> usize {
    let classifier = GpuSilhouettes::new(gpu(), mesh).unwrap_or_else(|e| panic!("{e:?}"));
    let mut disagreements = 0;
    for eye in eyes {
        let cpu = mesh.silhouettes(*eye);
        let on_gpu = classifier.classify(gpu(), *eye).unwrap_or_else(|e| panic!("{e:?}"));
        assert!(!cpu.is_empty(), "{name} from {eye}: a closed mesh has a silhouette");
        if cpu == on_gpu {
            continue;
        }
        let only_one: Vec<u32> = cpu
            .iter()
            .filter(|e| on_gpu.binary_search(e).is_err())
            .chain(on_gpu.iter().filter(|e| cpu.binary_search(e).is_err()))
            .copied()
            .collect();
        for e in &only_one {
            let faces = &mesh.edges[*e as usize].faces;
            let tie = faces
                .iter()
                .map(|f| margin(mesh, *f, *eye))
                .fold(f64::INFINITY, f64::min);
            assert!(
                tie <= TIE,
                "{name} from {eye}: edge {e} differs and its nearest face is {tie:e} from edge-on"
            );
        }
        disagreements += only_one.len();
    }
    eprintln!(
        "{name}: {} edges, {} eyes, {disagreements} edges classified differently (all ties)",
        mesh.edges.len(),
        eyes.len()
    );
    disagreements
}

#[test]
fn the_compute_pass_finds_the_cpus_silhouette_edges() {
    let cube = mesh("primitive = { kind = \"cube\", size = 2.0 }");
    let mut cube_eyes = eyes_around(DVec3::ZERO, 1.8, 48);
    // Eyes in the planes x = 1 and y = −1 (and both): edge-on faces.
    cube_eyes.extend([
        DVec3::new(1.0, 0.3, 4.0),
        DVec3::new(1.0, -1.0, 4.0),
        DVec3::new(-2.5, -1.0, 0.5),
    ]);
    // Those eyes do see faces exactly edge-on.
    let edge_on = cube_eyes[48..]
        .iter()
        .map(|eye| {
            (0..cube.faces.len() as u32)
                .filter(|f| margin(&cube, *f, *eye) == 0.0)
                .count()
        })
        .collect::<Vec<_>>();
    assert!(edge_on.iter().all(|n| *n >= 2), "edge-on faces per eye: {edge_on:?}");
    let mut total = compare("cube", &cube, &cube_eyes);
    for segments in [64, 256] {
        let sphere = mesh(&format!(
            "primitive = {{ kind = \"sphere\", radius = 1.0, segments = {segments}, rings = {} }}",
            segments / 2
        ));
        total += compare(
            &format!("sphere {segments}"),
            &sphere,
            &eyes_around(DVec3::ZERO, 1.0, 48),
        );
    }
    // Fandisk in its file's own coordinates (x 0..4.8, y 12.6..17.9, z −2.7..0).
    let fandisk = mesh("mesh = \"examples/models/fandisk.obj\"\ncrease_angle = 30.0");
    total += compare(
        "fandisk",
        &fandisk,
        &eyes_around(DVec3::new(2.4, 15.25, -1.35), 3.6, 48),
    );
    assert_eq!(total, 0, "no eye here is within f32 rounding of a face's plane");
}
