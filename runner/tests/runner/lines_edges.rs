//! Edge extraction against exact truth: the cube's 12 right-angle creases
//! and its silhouette hexagon, the cylinder's rims, the sphere's silhouette
//! against the analytic circle, and degenerate input.

use glam::DVec3;
use npr_runner::lines::edges::*;
use npr_runner::scene::primitives::{cube, cylinder, sphere};
use npr_runner::scene::Mesh;
use std::collections::HashMap;

/// Vertex degrees of the graph made by `edges`.
fn degrees(mesh: &EdgeMesh, edges: &[u32]) -> HashMap<u32, usize> {
    let mut degree = HashMap::new();
    for &e in edges {
        let edge = &mesh.edges[e as usize];
        *degree.entry(edge.a).or_insert(0) += 1;
        *degree.entry(edge.b).or_insert(0) += 1;
    }
    degree
}

#[test]
fn cube_has_twelve_right_angle_creases_in_twelve_chains() {
    let mesh = EdgeMesh::new(&cube(2.0));
    assert_eq!(mesh.positions.len(), 8, "24 split vertices weld to 8 corners");
    assert_eq!(mesh.faces.len(), 12);
    assert_eq!(mesh.edges.len(), 18, "12 sides + 6 face diagonals");
    let creases = mesh.creases(40.0);
    assert_eq!(creases.len(), 12);
    for &(e, kind) in &creases {
        assert_eq!(kind, EdgeKind::Crease);
        let edge = &mesh.edges[e as usize];
        let angle = mesh.dihedral_deg(edge).unwrap();
        assert!((angle - 90.0).abs() < 1e-9, "dihedral {angle}");
        let length = (mesh.positions[edge.a as usize] - mesh.positions[edge.b as usize]).length();
        assert!((length - 2.0).abs() < 1e-12, "a crease is a cube side, length {length}");
    }
    // The diagonals are coplanar: exactly 0°.
    let flat: Vec<f64> = mesh
        .edges
        .iter()
        .filter_map(|e| mesh.dihedral_deg(e))
        .filter(|a| *a < 45.0)
        .collect();
    assert_eq!(flat.len(), 6);
    assert!(flat.iter().all(|a| a.abs() < 1e-9));
    // Three creases meet at every corner, so no chain runs through one.
    let indices: Vec<u32> = creases.iter().map(|c| c.0).collect();
    let lines = mesh.chain(&indices);
    assert_eq!(lines.len(), 12);
    assert!(lines.iter().all(|l| l.vertices.len() == 2 && !l.closed));
    // A threshold over 90° leaves none.
    assert!(mesh.creases(90.5).is_empty());
}

#[test]
fn cube_silhouette_is_a_closed_hexagon() {
    let mesh = EdgeMesh::new(&cube(2.0));
    // Seen from the (+,+,+) octant, +X, +Y and +Z face the eye; the
    // silhouette is the six sides between those and the other three.
    let eye = DVec3::new(3.0, 2.5, 4.0);
    let silhouette = mesh.silhouettes(eye);
    assert_eq!(silhouette.len(), 6);
    for &e in &silhouette {
        let edge = &mesh.edges[e as usize];
        let [f, g] = edge.faces[..] else { panic!("two faces") };
        assert_ne!(mesh.is_front(f, eye), mesh.is_front(g, eye));
        let (p, q) = (mesh.positions[edge.a as usize], mesh.positions[edge.b as usize]);
        // Neither the nearest corner (1,1,1) nor the farthest (-1,-1,-1).
        for c in [p, q] {
            assert!(c != DVec3::ONE && c != -DVec3::ONE, "{c}");
        }
    }
    let lines = mesh.chain(&silhouette);
    assert_eq!(lines.len(), 1);
    assert!(lines[0].closed);
    assert_eq!(lines[0].vertices.len(), 6);
}

/// A point eye and a direction eye see from where they should, and a
/// translation moves the first but not the second.
#[test]
fn a_viewpoint_is_a_point_or_a_direction() {
    use glam::{DMat4, DVec4};
    use npr_runner::lines::viewpoint::Viewpoint;
    let p = DVec3::new(1.0, 2.0, 3.0);
    assert_eq!(Viewpoint::from(DVec3::ZERO).towards_from(p), -p);
    assert_eq!(Viewpoint::direction(DVec3::Z).towards_from(p), DVec3::Z);
    let shift = DMat4::from_translation(DVec3::X);
    assert_eq!(
        Viewpoint::from(DVec3::ZERO).transformed(shift).0,
        DVec4::new(1.0, 0.0, 0.0, 1.0)
    );
    assert_eq!(Viewpoint::direction(DVec3::Z).transformed(shift).0, DVec4::Z);
}

/// An orthographic camera sees every face along one direction (decision
/// 0062), so a face's facing does not depend on where it is. From (3, 0.3,
/// 0.3) a perspective eye sees only the +X face of the cube [−1, 1]³ (the
/// eye is below the +Y and +Z planes): its silhouette is that face's square.
/// An orthographic camera there looking at the origin sees +X, +Y and +Z
/// (each normal has a positive dot with the direction towards it): the
/// hexagon, the same wherever the cube is moved.
#[test]
fn an_orthographic_cube_silhouette_is_the_hexagon_wherever_the_cube_is() {
    use npr_runner::lines::viewpoint::Viewpoint;
    use npr_runner::scene::Camera;
    let mesh = EdgeMesh::new(&cube(2.0));
    let position = glam::Vec3::new(3.0, 0.3, 0.3);
    let mut camera = Camera::looking_at(position, glam::Vec3::ZERO);
    let perspective = Viewpoint(camera.pose(0.0).homogeneous_eye(0).as_dvec4());
    let square = mesh.silhouettes(perspective);
    assert_eq!(square.len(), 4);
    for &e in &square {
        let edge = &mesh.edges[e as usize];
        let (p, q) = (mesh.positions[edge.a as usize], mesh.positions[edge.b as usize]);
        assert!(p.x == 1.0 && q.x == 1.0, "an edge of the +X face: {p} {q}");
    }
    camera.ortho_height_m = Some(3.0);
    let eye = Viewpoint(camera.pose(0.0).homogeneous_eye(0).as_dvec4());
    assert_eq!(eye.0.w, 0.0, "the orthographic eye is at infinity");
    for shift in [DVec3::ZERO, DVec3::new(0.0, 40.0, -25.0), DVec3::new(-60.0, 0.0, 0.0)] {
        // The cube moved by `shift`: the eye in its own space.
        let local = eye.transformed(glam::DMat4::from_translation(-shift));
        let hexagon = mesh.silhouettes(local);
        assert_eq!(hexagon.len(), 6, "cube at {shift}");
        for &e in &hexagon {
            let edge = &mesh.edges[e as usize];
            let [f, g] = edge.faces[..] else { panic!("two faces") };
            let towards = local.0.truncate();
            let (nf, ng) = (
                mesh.normals[f as usize].dot(towards),
                mesh.normals[g as usize].dot(towards),
            );
            assert!(
                (nf > 0.0) != (ng > 0.0),
                "one face towards the camera's direction: {nf} {ng}"
            );
            let (p, q) = (mesh.positions[edge.a as usize], mesh.positions[edge.b as usize]);
            for c in [p, q] {
                assert!(c != DVec3::ONE && c != -DVec3::ONE, "{c}");
            }
        }
        let lines = mesh.chain(&hexagon);
        assert!(lines.len() == 1 && lines[0].closed && lines[0].vertices.len() == 6);
    }
}

#[test]
fn cylinder_rims_are_two_closed_creases() {
    let segments = 32;
    let mesh = EdgeMesh::new(&cylinder(1.0, 2.0, segments));
    // 2 rings of `segments` + 2 cap centres after welding the seam and the caps.
    assert_eq!(mesh.positions.len(), 2 * segments as usize + 2);
    let creases = mesh.creases(40.0);
    assert_eq!(creases.len(), 2 * segments as usize);
    for &(e, _) in &creases {
        let edge = &mesh.edges[e as usize];
        assert!((mesh.dihedral_deg(edge).unwrap() - 90.0).abs() < 1e-5);
        let (p, q) = (mesh.positions[edge.a as usize], mesh.positions[edge.b as usize]);
        assert!(p.y.abs() == 1.0 && p.y == q.y, "on a rim: {p} {q}");
    }
    // The side's vertical edges bend by exactly 360°/segments.
    let side = mesh
        .edges
        .iter()
        .filter(|e| mesh.positions[e.a as usize].y != mesh.positions[e.b as usize].y)
        .filter(|e| mesh.positions[e.a as usize].x == mesh.positions[e.b as usize].x)
        .filter_map(|e| mesh.dihedral_deg(e))
        .collect::<Vec<_>>();
    assert_eq!(side.len(), segments as usize);
    for angle in side {
        assert!((angle - 360.0 / f64::from(segments)).abs() < 1e-4, "{angle}");
    }
    let indices: Vec<u32> = creases.iter().map(|c| c.0).collect();
    let lines = mesh.chain(&indices);
    assert_eq!(lines.len(), 2);
    assert!(lines.iter().all(|l| l.closed && l.vertices.len() == segments as usize));
    // From above on the axis only the top cap faces the eye: the silhouette
    // is the top rim, one loop.
    let silhouette = mesh.silhouettes(DVec3::new(0.0, 10.0, 0.0));
    assert_eq!(silhouette.len(), segments as usize);
    let lines = mesh.chain(&silhouette);
    assert_eq!(lines.len(), 1);
    assert!(lines[0].closed);
    assert!(lines[0].vertices.iter().all(|&v| mesh.positions[v as usize].y == 1.0));
}

#[test]
fn sphere_has_no_creases_and_its_silhouette_is_the_analytic_circle() {
    let (segments, rings) = (64, 32);
    let mesh = EdgeMesh::new(&sphere(1.0, segments, rings));
    assert!(mesh.creases(20.0).is_empty(), "a smooth sphere has no creases");
    let longest = mesh
        .edges
        .iter()
        .map(|e| (mesh.positions[e.a as usize] - mesh.positions[e.b as usize]).length())
        .fold(0.0, f64::max);
    for (direction, distance) in [
        (DVec3::Z, 4.0),
        (DVec3::new(1.0, 2.0, 3.0).normalize(), 5.0),
        (DVec3::Y, 3.0),
    ] {
        let eye = direction * distance;
        let silhouette = mesh.silhouettes(eye);
        assert!(!silhouette.is_empty());
        // A closed mesh's silhouette graph has even degree everywhere.
        assert!(degrees(&mesh, &silhouette).values().all(|d| d % 2 == 0));
        // Truth: the cone from the eye touches the unit sphere on the circle
        // p·d̂ = 1/distance. Each silhouette vertex is a corner of a front
        // and a back face, so within one edge length of it.
        let plane = 1.0 / distance;
        let mut worst: f64 = 0.0;
        let (u, v) = (direction.any_orthonormal_pair().0, direction.any_orthonormal_pair().1);
        let mut bins = [false; 36];
        for line in mesh.chain(&silhouette) {
            assert!(line.closed, "the sphere's silhouette closes");
            for &vertex in &line.vertices {
                let p = mesh.positions[vertex as usize];
                worst = worst.max((p.dot(direction) - plane).abs());
                let angle = p.dot(v).atan2(p.dot(u)).to_degrees() + 180.0;
                bins[((angle / 10.0) as usize).min(35)] = true;
            }
        }
        assert!(
            worst <= longest,
            "{worst} from the silhouette plane, longest edge {longest}"
        );
        assert!(bins.iter().all(|&b| b), "the silhouette goes all the way round");
    }
}

#[test]
fn degenerate_faces_and_zero_length_edges_are_dropped() {
    // A quad split in two, plus a sliver with two corners at one point and
    // a collinear face: only the quad's faces survive.
    let positions = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0], // the same point as vertex 2
        [2.0, 0.0, 0.0], // collinear with 0 and 1
    ];
    let indices = vec![0, 1, 2, 0, 2, 3, 1, 2, 4, 0, 1, 5];
    let mesh = EdgeMesh::new(&Mesh::from_parts(positions, None, None, None, indices, "test".into()));
    assert_eq!(mesh.faces.len(), 2);
    assert!(mesh.normals.iter().all(|n| n.is_finite() && (n.z - 1.0).abs() < 1e-12));
    assert_eq!(mesh.edges.len(), 5);
    // The open quad's four sides are boundaries; the diagonal is flat.
    let creases = mesh.creases(30.0);
    assert_eq!(creases.len(), 4);
    assert!(creases.iter().all(|c| c.1 == EdgeKind::Boundary));
    let lines = mesh.chain(&creases.iter().map(|c| c.0).collect::<Vec<_>>());
    assert_eq!(
        lines,
        vec![Polyline {
            vertices: vec![0, 1, 2, 3],
            closed: true
        }]
    );
    // An edge-on eye (in the quad's plane) sees both faces as back faces:
    // no silhouette, no NaN.
    assert!(mesh.silhouettes(DVec3::new(5.0, 0.5, 0.0)).is_empty());
    // chain() on its own drops zero-length edges.
    assert_eq!(
        chain(&[(3, 3), (1, 2)]),
        vec![Polyline {
            vertices: vec![1, 2],
            closed: false
        }]
    );
    assert!(chain(&[(7, 7)]).is_empty());
    // An empty mesh has no edges.
    let empty = EdgeMesh::new(&Mesh::from_parts(vec![], None, None, None, vec![], "empty".into()));
    assert!(empty.edges.is_empty() && empty.silhouettes(DVec3::Z).is_empty());
}

#[test]
fn fandisk_creases_agree_with_a_brute_force_search_and_chain_every_edge_once() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/models/fandisk.obj");
    let source = npr_runner::scene::load_mesh_file(&path).expect("fandisk.obj loads");
    let started = std::time::Instant::now();
    let mesh = EdgeMesh::new(&source);
    let creases = mesh.creases(40.0);
    let built = started.elapsed();
    assert!(!creases.is_empty(), "fandisk is a CAD part with sharp creases");
    // Brute force from the file's own triangles: for each crease, every
    // triangle holding both end points (compared as exact positions), its
    // normal from the f32 corners, and the angle between the two.
    let corner = |v: u32| {
        let p = source.positions[v as usize];
        DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
    };
    for &(e, kind) in &creases {
        let edge = &mesh.edges[e as usize];
        let (a, b) = (mesh.positions[edge.a as usize], mesh.positions[edge.b as usize]);
        let normals: Vec<DVec3> = source
            .indices
            .chunks_exact(3)
            .filter(|t| {
                let c = [corner(t[0]), corner(t[1]), corner(t[2])];
                c.contains(&a) && c.contains(&b)
            })
            .map(|t| {
                (corner(t[1]) - corner(t[0]))
                    .cross(corner(t[2]) - corner(t[0]))
                    .normalize()
            })
            .collect();
        match kind {
            EdgeKind::Crease => {
                assert_eq!(normals.len(), 2);
                let angle = normals[0].dot(normals[1]).clamp(-1.0, 1.0).acos().to_degrees();
                assert!(angle > 40.0 - 1e-6, "a crease of {angle}°");
                assert!((angle - mesh.dihedral_deg(edge).unwrap()).abs() < 1e-6);
            }
            EdgeKind::Boundary => assert_eq!(normals.len(), 1),
            EdgeKind::NonManifold => assert!(normals.len() > 2),
            EdgeKind::Silhouette => unreachable!(),
        }
    }
    // Every crease is in exactly one chain, once.
    let indices: Vec<u32> = creases.iter().map(|c| c.0).collect();
    let lines = mesh.chain(&indices);
    let mut seen = std::collections::HashSet::new();
    for line in &lines {
        let n = line.vertices.len();
        let steps = if line.closed { n } else { n - 1 };
        for k in 0..steps {
            let (p, q) = (line.vertices[k], line.vertices[(k + 1) % n]);
            assert!(seen.insert((p.min(q), p.max(q))), "edge {p}-{q} chained twice");
        }
    }
    assert_eq!(seen.len(), creases.len());
    let silhouette_started = std::time::Instant::now();
    let silhouette = mesh.silhouettes(DVec3::new(30.0, 20.0, 40.0));
    let silhouette_chains = mesh.chain(&silhouette);
    eprintln!(
        "fandisk: {} faces, {} edges, {} creases in {} chains, built in {built:?}; \
         {} silhouette edges in {} chains in {:?}",
        mesh.faces.len(),
        mesh.edges.len(),
        creases.len(),
        lines.len(),
        silhouette.len(),
        silhouette_chains.len(),
        silhouette_started.elapsed()
    );
}
