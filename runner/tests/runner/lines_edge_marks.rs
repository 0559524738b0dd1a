//! Edges marked in a mesh's file (Freestyle's edge marks, decision 0063)
//! against the marks Blender wrote: `examples/models/marked_box.glb`, made
//! by `tests/data/blender/make_marked.py`, which also lists the marked
//! edges' end points (`marked_box_marks.json`, read back from Blender's
//! Freestyle marks). Exact: the same edges, no more.

use std::path::PathBuf;

use glam::{DMat4, DVec3};
use npr_abi::lines::EdgeTypes;
use npr_runner::lines::edges::EdgeMesh;
use npr_runner::lines::sets::{select, SetInput, SetSurface};
use npr_runner::lines::strip::LineStyle;
use npr_runner::scene::load_mesh_file;
use npr_runner::scene::primitives::cube;

fn models() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples/models")
}

/// An unordered edge as its end points in µm (the asset's corners are
/// whole and half units, exact in f32).
fn key(a: DVec3, b: DVec3) -> [i64; 6] {
    let (a, b) = (
        (a * 1e6).round().as_i64vec3().to_array(),
        (b * 1e6).round().as_i64vec3().to_array(),
    );
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    [lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]]
}

/// The marked edges Blender lists for the asset.
fn blender_marks() -> Vec<[i64; 6]> {
    let text = std::fs::read_to_string(models().join("marked_box_marks.json")).expect("marked_box_marks.json");
    let json: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    let point = |p: &serde_json::Value| {
        let c: Vec<f64> = p.as_array().unwrap().iter().map(|c| c.as_f64().unwrap()).collect();
        DVec3::new(c[0], c[1], c[2])
    };
    let mut marks: Vec<[i64; 6]> = json["marked_edges"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| key(point(&e[0]), point(&e[1])))
        .collect();
    marks.sort_unstable();
    marks
}

#[test]
fn the_marked_edges_are_the_ones_blender_marked() {
    let mesh = load_mesh_file(&models().join("marked_box.glb")).expect("marked_box.glb loads");
    assert!(mesh.edge_marks.is_some(), "the file's `_NPR_EDGE_MARK` was read");
    let edges = EdgeMesh::new(&mesh);
    let mut marked: Vec<[i64; 6]> = edges
        .marked()
        .iter()
        .map(|&e| {
            let edge = &edges.edges[e as usize];
            key(edges.positions[edge.a as usize], edges.positions[edge.b as usize])
        })
        .collect();
    marked.sort_unstable();
    let truth = blender_marks();
    assert_eq!(truth.len(), 10, "the asset marks 10 edges");
    assert_eq!(marked, truth);
    // Closed form: the top face's rim (y = 1, |x| = 1 or |z| = 1) and the
    // line across it at x = 0, ten edges of length 1.
    for &e in &edges.marked() {
        let edge = &edges.edges[e as usize];
        let (a, b) = (edges.positions[edge.a as usize], edges.positions[edge.b as usize]);
        assert_eq!((a.y, b.y), (1.0, 1.0), "{a} {b} is on the top");
        assert!((a.x == b.x && (a.x.abs() == 1.0 || a.x == 0.0)) || (a.z == b.z && a.z.abs() == 1.0));
        assert!(((a - b).length() - 1.0).abs() < 1e-12);
    }
    // The diagonals of the triangulation and the other sides: unmarked.
    assert_eq!(edges.edges.len() - edges.marked().len(), edges.edges.len() - 10);
    let chains = edges.chain(&edges.marked());
    let vertices: usize = chains.iter().map(|c| c.vertices.len()).sum();
    assert!(vertices >= 9, "the rim and the cross line chain through their vertices");
}

#[test]
fn a_set_of_marked_edges_draws_them_and_a_mesh_without_marks_has_none() {
    let mesh = EdgeMesh::new(&load_mesh_file(&models().join("marked_box.glb")).expect("loads"));
    let style = LineStyle {
        width_px: 2.0,
        amplitude_px: 0.0,
        wavelength_px: 24.0,
        phase: 0.0,
        taper: 0.0,
    };
    let set = |edges: EdgeTypes| SetInput {
        surfaces: vec![SetSurface {
            edges: &mesh,
            model: DMat4::from_translation(DVec3::new(0.0, 0.0, -5.0)),
            key: 0,
        }],
        edges,
        style,
        visibility: None,
        dash: None,
    };
    let marked = EdgeTypes {
        marked: true,
        ..EdgeTypes::default()
    };
    let crease = EdgeTypes {
        crease_deg: Some(40.0),
        ..EdgeTypes::default()
    };
    let drawn = select(&[set(marked), set(crease)], DVec3::new(0.0, 4.0, 5.0));
    let segments = |polylines: &[(Vec<DVec3>, bool)]| -> usize {
        polylines
            .iter()
            .map(|(p, closed)| p.len() - 1 + usize::from(*closed))
            .sum()
    };
    assert_eq!(segments(&drawn[0]), 10);
    // The cube's 12 sides, cut in two: 24 crease edges, 4 of them (the top
    // rim's four... eight halves) drawn by the marked set first.
    assert_eq!(segments(&drawn[1]), 24 - 8);
    assert!(EdgeMesh::new(&cube(2.0)).marked().is_empty());
}
