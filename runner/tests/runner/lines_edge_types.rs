//! The edge types of line sets (decision 0056) against closed-form truth on
//! meshes built here: borders of an open box and a plane, creases alone,
//! material (part) boundaries, intersection lines between two objects and
//! within one, and the priority rule that draws an edge once, by the first
//! set that selects it.

use glam::{DMat4, DVec3};
use npr_abi::lines::EdgeTypes;
use npr_runner::lines::edges::EdgeMesh;
use npr_runner::lines::intersections::{intersection_lines, triangle_pair_segment, PlacedMesh};
use npr_runner::lines::sets::{select, SetInput, SetSurface};
use npr_runner::lines::strip::LineStyle;
use npr_runner::scene::primitives::{cube, plane, sphere};
use npr_runner::scene::Mesh;

/// The mesh with only the triangles `keep` accepts (by their corners).
fn keep_triangles(mesh: &Mesh, keep: impl Fn([[f32; 3]; 3]) -> bool) -> Mesh {
    let indices: Vec<u32> = mesh
        .indices
        .chunks_exact(3)
        .filter(|t| keep([0, 1, 2].map(|k| mesh.positions[t[k] as usize])))
        .flatten()
        .copied()
        .collect();
    Mesh::from_parts(mesh.positions.clone(), None, None, None, indices, "kept".into())
}

/// A box of side 2 without its lid (+Y face).
fn open_box() -> Mesh {
    keep_triangles(&cube(2.0), |t| !t.iter().all(|p| p[1] == 1.0))
}

/// The end points of edge `e`.
fn ends(mesh: &EdgeMesh, e: u32) -> (DVec3, DVec3) {
    let edge = &mesh.edges[e as usize];
    (mesh.positions[edge.a as usize], mesh.positions[edge.b as usize])
}

fn length(mesh: &EdgeMesh, edges: &[u32]) -> f64 {
    edges
        .iter()
        .map(|&e| ends(mesh, e))
        .map(|(a, b)| (a - b).length())
        .sum()
}

/// A quad from four corners, two triangles, counter-clockwise.
fn quad(corners: [[f32; 3]; 4]) -> Mesh {
    Mesh::from_parts(
        corners.to_vec(),
        None,
        None,
        None,
        vec![0, 1, 2, 0, 2, 3],
        "quad".into(),
    )
}

#[test]
fn an_open_boxs_border_is_its_rim_and_its_creases_are_the_other_eight_sides() {
    let mesh = EdgeMesh::new(&open_box());
    let borders = mesh.borders();
    assert_eq!(borders.len(), 4);
    for &e in &borders {
        let (a, b) = ends(&mesh, e);
        assert_eq!((a.y, b.y), (1.0, 1.0), "a border is on the rim");
        assert!(((a - b).length() - 2.0).abs() < 1e-12);
    }
    let rim = mesh.chain(&borders);
    assert_eq!(rim.len(), 1);
    assert!(rim[0].closed && rim[0].vertices.len() == 4);
    // Creases alone: the 4 upright and 4 bottom sides at 90°, not the rim.
    let creases = mesh.creases_over(40.0);
    assert_eq!(creases.len(), 8);
    for &e in &creases {
        let (a, b) = ends(&mesh, e);
        let upright = a.x == b.x && a.z == b.z && a.x.abs() == 1.0 && a.z.abs() == 1.0;
        let bottom = a.y == -1.0 && b.y == -1.0;
        assert!(upright || bottom, "{a} {b}");
        assert!((mesh.dihedral_deg(&mesh.edges[e as usize]).unwrap() - 90.0).abs() < 1e-9);
    }
    assert!(mesh.creases_over(90.5).is_empty());
    assert!(borders.iter().all(|b| !creases.contains(b)));
    assert!(mesh.part_boundaries().is_empty(), "one part");
}

#[test]
fn a_planes_border_is_its_square_outline() {
    let mesh = EdgeMesh::new(&plane(2.0, 4));
    let borders = mesh.borders();
    assert_eq!(borders.len(), 16);
    assert!((length(&mesh, &borders) - 8.0).abs() < 1e-12);
    for &e in &borders {
        let (a, b) = ends(&mesh, e);
        let on_side = (a.x.abs() == 1.0 && a.x == b.x) || (a.z.abs() == 1.0 && a.z == b.z);
        assert!(on_side, "{a} {b}");
    }
    assert!(mesh.creases_over(1.0).is_empty());
    let closed: usize = mesh.chain(&borders).iter().filter(|l| l.closed).count();
    assert_eq!(closed, 1);
}

#[test]
fn a_material_boundary_is_where_the_parts_meet() {
    // A 2 × 2 plane of 4 × 4 cells, part 1 where x > 0: the boundary is the
    // line x = 0 across it, 4 edges, length 2.
    let flat = plane(2.0, 4);
    let parts: Vec<u32> = flat
        .indices
        .chunks_exact(3)
        .map(|t| {
            let x: f32 = t.iter().map(|&v| flat.positions[v as usize][0]).sum();
            u32::from(x > 0.0)
        })
        .collect();
    let mesh = EdgeMesh::new(&flat.with_parts(parts));
    let boundary = mesh.part_boundaries();
    assert_eq!(boundary.len(), 4);
    assert!((length(&mesh, &boundary) - 2.0).abs() < 1e-12);
    for &e in &boundary {
        let (a, b) = ends(&mesh, e);
        assert_eq!((a.x, b.x), (0.0, 0.0));
    }
    // A cube with a part per face: its boundaries are its 12 sides.
    let cube_mesh = cube(2.0);
    let per_face: Vec<u32> = (0..cube_mesh.triangle_count() as u32).map(|t| t / 2).collect();
    let mesh = EdgeMesh::new(&cube_mesh.with_parts(per_face));
    let mut boundary = mesh.part_boundaries();
    let mut creases = mesh.creases_over(40.0);
    boundary.sort_unstable();
    creases.sort_unstable();
    assert_eq!(boundary.len(), 12);
    assert_eq!(boundary, creases);
}

/// Quad A in z = 0 (x, y in −1..1) and quad B in x = 0 (y in −0.5..0.5,
/// z in −1..1) meet along x = z = 0, y in −0.5..0.5.
fn crossing_quads() -> (Mesh, Mesh) {
    (
        quad([[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]]),
        quad([[0.0, -0.5, -1.0], [0.0, -0.5, 1.0], [0.0, 0.5, 1.0], [0.0, 0.5, -1.0]]),
    )
}

#[test]
fn two_crossing_quads_meet_along_one_segment() {
    let (a, b) = crossing_quads();
    let (a, b) = (EdgeMesh::new(&a), EdgeMesh::new(&b));
    // B placed 0.25 up: the segment is y in −0.25..0.75.
    let lift = DMat4::from_translation(DVec3::new(0.0, 0.25, 0.0));
    let lines = intersection_lines(&[
        PlacedMesh {
            edges: &a,
            model: DMat4::IDENTITY,
        },
        PlacedMesh { edges: &b, model: lift },
    ]);
    assert_eq!(lines.len(), 1, "{lines:?}");
    let (points, closed) = &lines[0];
    assert!(!closed);
    let total: f64 = points.windows(2).map(|w| (w[1] - w[0]).length()).sum();
    assert!((total - 1.0).abs() < 1e-12, "length {total}");
    for p in points {
        assert!(p.x.abs() < 1e-12 && p.z.abs() < 1e-12, "{p}");
    }
    let (lo, hi) = (
        points.first().unwrap().y.min(points.last().unwrap().y),
        points.first().unwrap().y.max(points.last().unwrap().y),
    );
    assert!((lo + 0.25).abs() < 1e-12 && (hi - 0.75).abs() < 1e-12, "{lo}..{hi}");
    // Moved apart, they do not meet.
    let apart = DMat4::from_translation(DVec3::new(0.0, 0.0, 3.0));
    assert!(intersection_lines(&[
        PlacedMesh {
            edges: &a,
            model: DMat4::IDENTITY
        },
        PlacedMesh {
            edges: &b,
            model: apart
        },
    ])
    .is_empty());
}

#[test]
fn one_mesh_through_itself_is_a_self_intersection_and_closed_meshes_have_none() {
    let (a, b) = crossing_quads();
    let mut indices = a.indices.clone();
    indices.extend(b.indices.iter().map(|i| i + 4));
    let mut positions = a.positions.clone();
    positions.extend(&b.positions);
    let both = EdgeMesh::new(&Mesh::from_parts(positions, None, None, None, indices, "both".into()));
    let lines = intersection_lines(&[PlacedMesh {
        edges: &both,
        model: DMat4::IDENTITY,
    }]);
    assert_eq!(lines.len(), 1);
    let total: f64 = lines[0].0.windows(2).map(|w| (w[1] - w[0]).length()).sum();
    assert!((total - 1.0).abs() < 1e-12, "length {total}");
    // Neighbouring faces share an edge or a corner: no line.
    for mesh in [cube(2.0), sphere(1.0, 32, 16)] {
        let edges = EdgeMesh::new(&mesh);
        let placed = [PlacedMesh {
            edges: &edges,
            model: DMat4::IDENTITY,
        }];
        assert!(intersection_lines(&placed).is_empty(), "{}", mesh.source);
    }
}

#[test]
fn a_sphere_through_a_plane_meets_it_in_one_closed_circle() {
    // Unit sphere (64 × 32) and a plane at y = 0.3: the circle of radius
    // √(1 − 0.09). The polyhedron lies between the sphere and the sphere
    // scaled by cos(π/32) (the largest angle a face spans from its centre
    // is under π/32 here), which bounds the section's radius.
    let (ball, ground) = (EdgeMesh::new(&sphere(1.0, 64, 32)), EdgeMesh::new(&plane(4.0, 2)));
    let height = 0.3;
    let lines = intersection_lines(&[
        PlacedMesh {
            edges: &ball,
            model: DMat4::IDENTITY,
        },
        PlacedMesh {
            edges: &ground,
            model: DMat4::from_translation(DVec3::new(0.0, height, 0.0)),
        },
    ]);
    assert_eq!(lines.len(), 1);
    let (points, closed) = &lines[0];
    assert!(closed);
    // One point per sphere edge the plane crosses in its band of quads: 64
    // meridian edges and 64 quad diagonals.
    assert_eq!(points.len(), 128);
    let outer = (1.0f64 - height * height).sqrt();
    let near = (std::f64::consts::PI / 32.0).cos();
    let inner = (near * near - height * height).sqrt();
    for p in points {
        assert!((p.y - height).abs() < 1e-7, "{p}");
        let r = (p.x * p.x + p.z * p.z).sqrt();
        assert!(
            r <= outer + 1e-6 && r >= inner - 1e-6,
            "radius {r} outside {inner}..{outer}"
        );
    }
    let mut total: f64 = points.windows(2).map(|w| (w[1] - w[0]).length()).sum();
    total += (points[0] - points[points.len() - 1]).length();
    let tau = std::f64::consts::TAU;
    assert!(
        total <= tau * outer && total >= tau * inner * (std::f64::consts::PI / 64.0).cos(),
        "{total}"
    );
}

#[test]
fn the_triangle_pair_test_meets_a_worked_case_and_refuses_touching_and_coplanar() {
    let t = [
        DVec3::new(-1.0, -1.0, 0.0),
        DVec3::new(2.0, -1.0, 0.0),
        DVec3::new(-1.0, 2.0, 0.0),
    ];
    // Through t's plane from z = −1 to z = 1 at x = 0: u meets z = 0 along
    // y in −1..2 (its corner (0, 2, 0) is on the plane) and t spans y in
    // −1..1 at x = 0 (its long side is x + y = 1), so they meet in −1..1.
    let u = [
        DVec3::new(0.0, -1.0, -1.0),
        DVec3::new(0.0, -1.0, 1.0),
        DVec3::new(0.0, 2.0, 0.0),
    ];
    let (a, b) = triangle_pair_segment(&t, &u, 1e-12).unwrap();
    let (lo, hi) = (a.y.min(b.y), a.y.max(b.y));
    assert!((lo + 1.0).abs() < 1e-12 && (hi - 1.0).abs() < 1e-12, "{a} {b}");
    assert!(a.x.abs() < 1e-12 && a.z.abs() < 1e-12 && b.x.abs() < 1e-12 && b.z.abs() < 1e-12);
    // Touching at a corner only, and coplanar: no line.
    let touching = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, 1.0),
        DVec3::new(1.0, 0.0, 1.0),
    ]
    .map(|p| p + DVec3::new(-1.0, -1.0, 0.0));
    assert!(triangle_pair_segment(&t, &touching, 1e-12).is_none());
    let coplanar = t.map(|p| p * 0.5);
    assert!(triangle_pair_segment(&t, &coplanar, 1e-12).is_none());
}

/// A straight 2 px line: the sets' style in the set tests here and in
/// `lines_visibility`.
pub(crate) const STYLE: LineStyle = LineStyle {
    width_px: 2.0,
    amplitude_px: 0.0,
    wavelength_px: 24.0,
    phase: 0.0,
    taper: 0.0,
};

/// The segments (unordered end pairs, rounded to 1e-9) a set draws.
fn segments(polylines: &[(Vec<DVec3>, bool)]) -> Vec<[i64; 6]> {
    let key = |p: DVec3| (p * 1e9).round().as_i64vec3();
    let mut out = Vec::new();
    for (points, closed) in polylines {
        let mut pairs: Vec<(DVec3, DVec3)> = points.windows(2).map(|w| (w[0], w[1])).collect();
        if *closed {
            pairs.push((points[points.len() - 1], points[0]));
        }
        for (a, b) in pairs {
            let (a, b) = (key(a).to_array(), key(b).to_array());
            let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
            out.push([lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]]);
        }
    }
    out.sort_unstable();
    out
}

#[test]
fn an_edge_in_two_sets_is_drawn_once_by_the_first() {
    let mesh = EdgeMesh::new(&cube(2.0));
    let eye = DVec3::new(3.0, 2.5, 4.0);
    let set = |edges: EdgeTypes| SetInput {
        surfaces: vec![SetSurface {
            edges: &mesh,
            model: DMat4::IDENTITY,
            key: 0,
        }],
        edges,
        style: STYLE,
        visibility: None,
        dash: None,
    };
    let silhouette = EdgeTypes {
        silhouette: true,
        ..EdgeTypes::default()
    };
    let crease = EdgeTypes {
        crease_deg: Some(40.0),
        ..EdgeTypes::default()
    };
    // Silhouettes first: the 6 sides of the hexagon, then the other 6.
    let drawn = select(&[set(silhouette), set(crease)], eye);
    let (first, second) = (segments(&drawn[0]), segments(&drawn[1]));
    assert_eq!((first.len(), second.len()), (6, 6));
    assert!(first.iter().all(|s| !second.contains(s)), "an edge in both sets");
    // Creases first: every silhouette of a cube is a crease, so the
    // silhouette set draws nothing.
    let drawn = select(&[set(crease), set(silhouette)], eye);
    assert_eq!((segments(&drawn[0]).len(), segments(&drawn[1]).len()), (12, 0));
    // The same object under two keys is two surfaces: both draw it.
    let twice = [
        set(crease),
        SetInput {
            surfaces: vec![SetSurface {
                edges: &mesh,
                model: DMat4::IDENTITY,
                key: 1,
            }],
            edges: crease,
            style: STYLE,
            visibility: None,
            dash: None,
        },
    ];
    let drawn = select(&twice, eye);
    assert_eq!(segments(&drawn[1]).len(), 12);
}

#[test]
fn an_intersection_in_two_sets_is_drawn_once_by_the_first() {
    let (a, b) = crossing_quads();
    let (a, b) = (EdgeMesh::new(&a), EdgeMesh::new(&b));
    let surfaces = || {
        vec![
            SetSurface {
                edges: &a,
                model: DMat4::IDENTITY,
                key: 0,
            },
            SetSurface {
                edges: &b,
                model: DMat4::IDENTITY,
                key: 1,
            },
        ]
    };
    let intersection = EdgeTypes {
        intersection: true,
        ..EdgeTypes::default()
    };
    let border_and_intersection = EdgeTypes {
        border: true,
        intersection: true,
        ..EdgeTypes::default()
    };
    let sets = [
        SetInput {
            surfaces: surfaces(),
            edges: intersection,
            style: STYLE,
            visibility: None,
            dash: None,
        },
        SetInput {
            surfaces: surfaces(),
            edges: border_and_intersection,
            style: STYLE,
            visibility: None,
            dash: None,
        },
    ];
    let eye = DVec3::new(0.5, 1.0, 5.0);
    let drawn = select(&sets, eye);
    let first: f64 = drawn[0]
        .iter()
        .map(|(p, _)| p.windows(2).map(|w| (w[1] - w[0]).length()).sum::<f64>())
        .sum();
    assert!((first - 1.0).abs() < 1e-12);
    // The second set draws the two quads' borders (8 sides) and no
    // intersection: 2·4 + 2·2 + 2·1 of outline, and nothing at x = z = 0
    // inside the quads.
    let second = segments(&drawn[1]);
    assert_eq!(second.len(), 8);
    let outline: f64 = drawn[1]
        .iter()
        .map(|(p, c)| {
            let mut l: f64 = p.windows(2).map(|w| (w[1] - w[0]).length()).sum();
            if *c {
                l += (p[0] - p[p.len() - 1]).length();
            }
            l
        })
        .sum();
    assert!((outline - (8.0 + 4.0 + 2.0)).abs() < 1e-12, "{outline}");
}
