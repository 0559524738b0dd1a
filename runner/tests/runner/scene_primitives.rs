//! Analytic primitives against their closed forms: normals, UVs, tangent
//! frames, winding, index ranges and triangle counts.

use glam::Vec3;
use npr_runner::scene::primitives::{self, Primitive};
use npr_runner::scene::Mesh;

const TOLERANCE: f32 = 1e-5;

fn v3(a: [f32; 3]) -> Vec3 {
    Vec3::from_array(a)
}

/// Invariants every primitive must satisfy.
fn check_common(mesh: &Mesh) {
    let vertex_count = mesh.positions.len();
    assert_eq!(mesh.normals.len(), vertex_count, "{}", mesh.source);
    assert_eq!(mesh.indices.len() % 3, 0);
    assert!(
        mesh.indices.iter().all(|&i| (i as usize) < vertex_count),
        "{}: index out of range",
        mesh.source
    );
    assert!(mesh.validate().is_ok());

    for n in &mesh.normals {
        assert!(
            (v3(*n).length() - 1.0).abs() < TOLERANCE,
            "{}: normal {n:?} not unit",
            mesh.source
        );
    }
    let uvs = mesh.uvs.as_ref().expect("primitives have UVs");
    assert_eq!(uvs.len(), vertex_count);
    for uv in uvs {
        assert!(
            uv.iter().all(|c| (0.0..=1.0).contains(c)),
            "{}: uv {uv:?} outside [0,1]",
            mesh.source
        );
    }
    let tangents = mesh.tangents.as_ref().expect("primitives have tangents");
    assert_eq!(tangents.len(), vertex_count);
    for (t, n) in tangents.iter().zip(&mesh.normals) {
        let t3 = Vec3::new(t[0], t[1], t[2]);
        assert!(
            (t3.length() - 1.0).abs() < TOLERANCE,
            "{}: tangent {t:?} not unit",
            mesh.source
        );
        assert!(
            t3.dot(v3(*n)).abs() < TOLERANCE,
            "{}: tangent {t:?} not orthogonal to {n:?}",
            mesh.source
        );
        // No primitive mirrors its UVs.
        assert_eq!(t[3], 1.0, "{}: handedness", mesh.source);
    }

    // Counter-clockwise seen from outside: each face normal agrees with its
    // vertex normals. No degenerate triangles either.
    for triangle in mesh.indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| v3(mesh.positions[triangle[k] as usize]));
        let face = (b - a).cross(c - a);
        assert!(face.length() > 0.0, "{}: degenerate triangle {triangle:?}", mesh.source);
        let vertex_normals: Vec3 = triangle.iter().map(|&i| v3(mesh.normals[i as usize])).sum();
        assert!(
            face.dot(vertex_normals) > 0.0,
            "{}: triangle {triangle:?} winds inwards",
            mesh.source
        );
    }
}

/// The analytic tangent frame must match the one derived from the UVs
/// (same direction, same handedness) wherever the derivation is well
/// defined: this pins the tangent convention to the UV layout.
fn check_tangents_match_uv_derivatives(mesh: &Mesh, well_defined: impl Fn(Vec3) -> bool) {
    let derived = Mesh::from_parts(
        mesh.positions.clone(),
        Some(mesh.normals.clone()),
        mesh.uvs.clone(),
        None,
        mesh.indices.clone(),
        mesh.source.clone(),
    );
    let (analytic, derived) = (
        mesh.tangents.as_ref().expect("analytic"),
        derived.tangents.expect("derived"),
    );
    let mut compared = 0;
    for (vertex, (a, d)) in analytic.iter().zip(&derived).enumerate() {
        if !well_defined(v3(mesh.positions[vertex])) {
            continue;
        }
        compared += 1;
        let cos = Vec3::new(a[0], a[1], a[2]).dot(Vec3::new(d[0], d[1], d[2]));
        assert!(
            cos > 0.99,
            "{}: vertex {vertex}: analytic {a:?} vs derived {d:?}",
            mesh.source
        );
        assert_eq!(a[3], d[3], "{}: vertex {vertex}: handedness", mesh.source);
    }
    assert!(compared > 0);
}

#[test]
fn sphere_normals_are_position_over_radius() {
    let radius = 2.5;
    let (segments, rings) = (48, 24);
    let mesh = primitives::sphere(radius, segments, rings);
    check_common(&mesh);
    assert_eq!(mesh.triangle_count(), 2 * 48 * 23);
    assert_eq!(mesh.vertex_count(), 49 * 25);
    for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
        let p = v3(*p);
        assert!((p.length() - radius).abs() < 1e-5 * radius);
        assert!((p / radius - v3(*n)).length() < 1e-5, "normal {n:?} at {p:?}");
    }
    check_tangents_match_uv_derivatives(&mesh, |p| p.y.abs() < 0.9 * radius);
}

#[test]
fn sphere_uvs_run_from_the_north_pole_down() {
    let mesh = primitives::sphere(1.0, 8, 4);
    let uvs = mesh.uvs.as_ref().expect("uvs");
    for (p, uv) in mesh.positions.iter().zip(uvs) {
        let polar = (p[1].clamp(-1.0, 1.0)).acos();
        assert!((uv[1] - polar / std::f32::consts::PI).abs() < 1e-5);
    }
}

#[test]
fn cube_faces_are_axis_aligned() {
    let size = 3.0;
    let mesh = primitives::cube(size);
    check_common(&mesh);
    assert_eq!(mesh.triangle_count(), 12);
    assert_eq!(mesh.vertex_count(), 24);
    for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
        // Exactly one axis, ±1, and the vertex lies on that face's plane.
        let axis = n.iter().position(|c| c.abs() == 1.0).expect("axis-aligned normal");
        assert_eq!(n.iter().filter(|c| **c == 0.0).count(), 2, "{n:?}");
        assert!((p[axis] - n[axis] * size / 2.0).abs() < 1e-6);
        assert!(p.iter().all(|c| c.abs() <= size / 2.0 + 1e-6));
    }
    // Every face's UVs cover the whole square.
    let uvs = mesh.uvs.as_ref().expect("uvs");
    for face in uvs.chunks_exact(4) {
        let mut corners: Vec<[u8; 2]> = face.iter().map(|uv| [uv[0] as u8, uv[1] as u8]).collect();
        corners.sort();
        assert_eq!(corners, vec![[0, 0], [0, 1], [1, 0], [1, 1]]);
    }
    check_tangents_match_uv_derivatives(&mesh, |_| true);
}

#[test]
fn torus_normals_point_away_from_the_tube_centre() {
    let (major, minor) = (1.5, 0.4);
    let mesh = primitives::torus(major, minor, 40, 20);
    check_common(&mesh);
    assert_eq!(mesh.triangle_count(), 2 * 40 * 20);
    for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
        let p = v3(*p);
        let ring_centre = Vec3::new(p.x, 0.0, p.z).normalize() * major;
        let expected = (p - ring_centre) / minor;
        assert!((expected.length() - 1.0).abs() < 1e-5, "{p:?} is not on the tube");
        assert!((expected - v3(*n)).length() < 1e-5, "normal {n:?} at {p:?}");
    }
    check_tangents_match_uv_derivatives(&mesh, |_| true);
}

#[test]
fn plane_faces_up_with_a_regular_grid() {
    let mesh = primitives::plane(4.0, 8);
    check_common(&mesh);
    assert_eq!(mesh.triangle_count(), 2 * 8 * 8);
    assert_eq!(mesh.vertex_count(), 9 * 9);
    assert!(mesh.normals.iter().all(|n| *n == [0.0, 1.0, 0.0]));
    assert!(mesh
        .positions
        .iter()
        .all(|p| p[1] == 0.0 && p[0].abs() <= 2.0 && p[2].abs() <= 2.0));
    assert_eq!(mesh.bounds(), Some(([-2.0, 0.0, -2.0], [2.0, 0.0, 2.0])));
    check_tangents_match_uv_derivatives(&mesh, |_| true);
}

#[test]
fn cylinder_has_radial_sides_and_flat_caps() {
    let (radius, height) = (0.75, 2.0);
    let mesh = primitives::cylinder(radius, height, 32);
    check_common(&mesh);
    assert_eq!(mesh.triangle_count(), 4 * 32);
    for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
        let p = v3(*p);
        if n[1] == 0.0 {
            let radial = Vec3::new(p.x, 0.0, p.z) / radius;
            assert!((radial - v3(*n)).length() < 1e-5, "side normal {n:?} at {p:?}");
        } else {
            assert_eq!(n[1].abs(), 1.0);
            assert!(
                (p.y - n[1] * height / 2.0).abs() < 1e-6,
                "cap vertex {p:?} off its plane"
            );
        }
    }
    check_tangents_match_uv_derivatives(&mesh, |_| true);
}

#[test]
fn predicted_triangle_counts_match_built_meshes() {
    let shapes = [
        Primitive::Sphere {
            radius: 1.0,
            segments: 7,
            rings: 5,
        },
        Primitive::Cube { size: 1.0 },
        Primitive::Torus {
            major: 1.0,
            minor: 0.3,
            segments: 9,
            sides: 4,
        },
        Primitive::Plane {
            size: 1.0,
            subdivisions: 3,
        },
        Primitive::Cylinder {
            radius: 1.0,
            height: 1.0,
            segments: 5,
        },
        // Clamped counts: the prediction must clamp the same way.
        Primitive::Sphere {
            radius: 1.0,
            segments: 0,
            rings: 0,
        },
        Primitive::Plane {
            size: 1.0,
            subdivisions: 0,
        },
    ];
    for shape in shapes {
        let mesh = shape.build();
        assert_eq!(
            mesh.triangle_count() as u64,
            shape.triangle_count(),
            "{}",
            shape.description()
        );
        check_common(&mesh);
    }
}

#[test]
fn descriptions_name_the_kind_and_parameters() {
    assert_eq!(
        primitives::sphere(1.0, 64, 32).source,
        "sphere(radius=1, segments=64, rings=32)"
    );
    assert_eq!(primitives::cube(0.5).source, "cube(size=0.5)");
}

#[test]
fn the_winding_check_catches_inward_triangles() {
    // Negative control for `check_common`: the same sphere with every
    // triangle reversed must fail it.
    let mut mesh = primitives::sphere(1.0, 8, 4);
    for triangle in mesh.indices.chunks_exact_mut(3) {
        triangle.swap(1, 2);
    }
    let outcome = std::panic::catch_unwind(|| check_common(&mesh));
    assert!(outcome.is_err());
}
