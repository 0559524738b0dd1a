//! Quantitative invisibility (decision 0063) against truth computed another
//! way: on boxes and an open quad, the closed form (a ray crosses an open
//! quad once where it passes its plane inside it, and a closed convex box
//! twice where it passes through its inside, once when it ends on the
//! box's far side); on a torus, a brute-force ray cast against every
//! triangle in f64 with no hierarchy. Each line the runner cuts into runs
//! of one QI is sampled densely; the length-weighted precision and recall
//! of its visible and hidden labels are at least 0.95, and a set of
//! `hidden(1)` draws lines behind exactly one surface.

use glam::{DMat4, DVec3};
use npr_abi::lines::{EdgeTypes, LineVisibility};
use npr_runner::lines::edges::EdgeMesh;
use npr_runner::lines::sets::{select, SetInput, SetSurface};
use npr_runner::lines::visibility::Occluders;
use npr_runner::scene::primitives::{cube, torus};
use npr_runner::scene::Mesh;

use super::lines_edge_types::STYLE;

/// An axis-aligned box by its corners.
#[derive(Clone, Copy)]
struct Box3 {
    lo: DVec3,
    hi: DVec3,
}

impl Box3 {
    /// The box as a placed unit cube (`cube(2.0)` spans −1..1).
    fn model(&self) -> DMat4 {
        DMat4::from_translation((self.lo + self.hi) * 0.5) * DMat4::from_scale((self.hi - self.lo) * 0.5)
    }

    /// Surfaces the open segment eye → p (p on or off the box) crosses: the
    /// slab test's entry and exit parameters in (0, 1).
    fn crossings(&self, eye: DVec3, p: DVec3) -> u32 {
        let d = p - eye;
        let (mut near, mut far) = (f64::NEG_INFINITY, f64::INFINITY);
        for axis in 0..3 {
            if d[axis].abs() < 1e-15 {
                if eye[axis] < self.lo[axis] || eye[axis] > self.hi[axis] {
                    return 0;
                }
                continue;
            }
            let (a, b) = (
                (self.lo[axis] - eye[axis]) / d[axis],
                (self.hi[axis] - eye[axis]) / d[axis],
            );
            near = near.max(a.min(b));
            far = far.min(a.max(b));
        }
        if near >= far {
            return 0; // missed, or only grazed along an edge
        }
        let eps = 1e-9;
        u32::from(near > eps && near < 1.0 - eps) + u32::from(far > eps && far < 1.0 - eps)
    }
}

/// An open quad in the plane z = `z`, x and y in the given ranges.
struct Quad {
    z: f64,
    x: (f64, f64),
    y: (f64, f64),
}

impl Quad {
    fn mesh(&self) -> Mesh {
        let (z, x, y) = (self.z as f32, self.x, self.y);
        let (x0, x1, y0, y1) = (x.0 as f32, x.1 as f32, y.0 as f32, y.1 as f32);
        Mesh::from_parts(
            vec![[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]],
            None,
            None,
            None,
            vec![0, 1, 2, 0, 2, 3],
            "quad".into(),
        )
    }

    fn crossings(&self, eye: DVec3, p: DVec3) -> u32 {
        let t = (self.z - eye.z) / (p.z - eye.z);
        if !(1e-9..1.0 - 1e-9).contains(&t) {
            return 0;
        }
        let at = eye + (p - eye) * t;
        u32::from(at.x > self.x.0 && at.x < self.x.1 && at.y > self.y.0 && at.y < self.y.1)
    }
}

/// Length-weighted agreement of the runner's labels with the truth: for
/// each class, (true positive, labelled, truly in the class) lengths.
#[derive(Default, Debug)]
struct Confusion {
    both: f64,
    labelled: f64,
    truth: f64,
}

impl Confusion {
    fn add(&mut self, length: f64, labelled: bool, truth: bool) {
        if labelled && truth {
            self.both += length;
        }
        if labelled {
            self.labelled += length;
        }
        if truth {
            self.truth += length;
        }
    }

    fn precision(&self) -> f64 {
        self.both / self.labelled
    }

    fn recall(&self) -> f64 {
        self.both / self.truth
    }
}

/// Every labelled run's segments, sampled at `per_segment` midpoints each:
/// (sample length, runner's QI, true QI).
fn labelled_samples(
    runs: &[(Vec<DVec3>, bool, u32)],
    truth: &impl Fn(DVec3) -> u32,
    per_segment: usize,
) -> Vec<(f64, u32, u32)> {
    let mut out = Vec::new();
    for (points, closed, qi) in runs {
        let mut pairs: Vec<(DVec3, DVec3)> = points.windows(2).map(|w| (w[0], w[1])).collect();
        if *closed {
            pairs.push((points[points.len() - 1], points[0]));
        }
        for (a, b) in pairs {
            let step = (b - a).length() / per_segment as f64;
            for k in 0..per_segment {
                let p = a + (b - a) * ((k as f64 + 0.5) / per_segment as f64);
                out.push((step, *qi, truth(p)));
            }
        }
    }
    out
}

/// The scene: a long closed bar at the back, an open quad in front of its
/// middle and a closed box in front of its right part, seen from above and
/// to the right of the axis.
struct Scene {
    eye: DVec3,
    bar: Box3,
    block: Box3,
    quad: Quad,
}

fn scene() -> Scene {
    Scene {
        eye: DVec3::new(0.6, 2.0, 10.0),
        bar: Box3 {
            lo: DVec3::new(-4.0, -0.5, -4.0),
            hi: DVec3::new(4.0, 0.5, -3.0),
        },
        block: Box3 {
            lo: DVec3::new(2.0, -1.0, -0.3),
            hi: DVec3::new(2.6, 1.5, 0.3),
        },
        quad: Quad {
            z: 0.0,
            x: (-1.0, 1.0),
            y: (-1.0, 1.5),
        },
    }
}

impl Scene {
    fn truth(&self, p: DVec3) -> u32 {
        self.bar.crossings(self.eye, p) + self.block.crossings(self.eye, p) + self.quad.crossings(self.eye, p)
    }
}

#[test]
fn qi_of_a_bars_edges_behind_a_quad_and_a_box_matches_the_closed_form() {
    let s = scene();
    let (unit, quad) = (EdgeMesh::new(&cube(2.0)), EdgeMesh::new(&s.quad.mesh()));
    let occluders = Occluders::new([
        (&unit, s.bar.model()),
        (&unit, s.block.model()),
        (&quad, DMat4::IDENTITY),
    ]);
    // The bar's 12 sides, one polyline each, in world space.
    let model = s.bar.model();
    let creases = unit.creases_over(40.0);
    assert_eq!(creases.len(), 12);
    let mut samples = Vec::new();
    for &e in &creases {
        let edge = &unit.edges[e as usize];
        let line = [
            model.transform_point3(unit.positions[edge.a as usize]),
            model.transform_point3(unit.positions[edge.b as usize]),
        ];
        let runs = occluders.runs(&line, false, s.eye);
        // The runs cover the side from end to end, in order.
        assert_eq!(runs[0].0[0], line[0]);
        assert_eq!(*runs.last().unwrap().0.last().unwrap(), line[1]);
        samples.extend(labelled_samples(&runs, &|p| s.truth(p), 400));
    }
    let (mut visible, mut hidden, mut behind_one) = (Confusion::default(), Confusion::default(), Confusion::default());
    for &(length, qi, truth) in &samples {
        visible.add(length, qi == 0, truth == 0);
        hidden.add(length, qi >= 1, truth >= 1);
        behind_one.add(length, qi == 1, truth == 1);
    }
    // The scene has every case: lines in view, behind one surface (the
    // quad, or the bar's own front) and behind more (the box: two).
    let qis: std::collections::BTreeSet<u32> = samples.iter().map(|s| s.2).collect();
    assert!(
        qis.contains(&0) && qis.contains(&1) && qis.contains(&2) && qis.contains(&3),
        "{qis:?}"
    );
    for (name, c) in [("visible", &visible), ("hidden", &hidden), ("QI 1", &behind_one)] {
        eprintln!("{name}: precision {:.5}, recall {:.5}", c.precision(), c.recall());
        assert!(c.precision() >= 0.95 && c.recall() >= 0.95, "{name}: {c:?}");
    }
    // The boundaries are bisected: far better than the 0.95 asked.
    assert!(visible.precision() > 0.999 && visible.recall() > 0.999, "{visible:?}");
}

#[test]
fn sets_by_visibility_split_the_lines_and_hidden_1_is_behind_exactly_one_surface() {
    let s = scene();
    let (unit, quad) = (EdgeMesh::new(&cube(2.0)), EdgeMesh::new(&s.quad.mesh()));
    let set = |visibility: Option<LineVisibility>| SetInput {
        surfaces: vec![
            SetSurface {
                edges: &unit,
                model: s.bar.model(),
                key: 0,
            },
            SetSurface {
                edges: &unit,
                model: s.block.model(),
                key: 1,
            },
            SetSurface {
                edges: &quad,
                model: DMat4::IDENTITY,
                key: 2,
            },
        ],
        edges: EdgeTypes {
            crease_deg: Some(40.0),
            border: true,
            ..EdgeTypes::default()
        },
        style: STYLE,
        visibility,
        dash: None,
    };
    let length = |polylines: &[(Vec<DVec3>, bool)]| -> f64 {
        polylines
            .iter()
            .map(|(p, closed)| {
                let open: f64 = p.windows(2).map(|w| (w[1] - w[0]).length()).sum();
                open + if *closed { (p[0] - p[p.len() - 1]).length() } else { 0.0 }
            })
            .sum()
    };
    let measure = |visibility| length(&select(&[set(visibility)], s.eye)[0]);
    let all = measure(None);
    let (visible, hidden, every) = (
        measure(Some(LineVisibility::Visible)),
        measure(Some(LineVisibility::Hidden)),
        measure(Some(LineVisibility::All)),
    );
    // 24 box sides (bar: 8 × 2 + 2 × 1 × 4 ... summed) and the quad's rim.
    assert!((every - all).abs() < 1e-9, "{every} {all}");
    assert!(
        (visible + hidden - all).abs() < 1e-6 * all,
        "{visible} + {hidden} != {all}"
    );
    assert!(visible > 0.2 * all && hidden > 0.2 * all, "{visible} {hidden} of {all}");
    // hidden(1): every sampled point of it is behind exactly one surface
    // by the closed form (at 0.95 of its length at least).
    let behind_one = &select(&[set(Some(LineVisibility::Behind(1)))], s.eye)[0];
    let mut c = Confusion::default();
    for (points, closed) in behind_one {
        let runs = [(points.clone(), *closed, 1)];
        for (length, _, truth) in labelled_samples(&runs, &|p| s.truth(p), 50) {
            c.add(length, true, truth == 1);
        }
    }
    assert!(c.labelled > 0.05 * all, "hidden(1) draws something: {c:?}");
    assert!(c.precision() >= 0.95, "{c:?}");
    // What it leaves out of the hidden lines is behind two or more.
    let behind_more = hidden - c.labelled;
    assert!(behind_more > 0.0, "the box hides some lines twice");
}

#[test]
fn qi_of_a_torus_silhouette_matches_a_brute_force_ray_cast() {
    let mesh = EdgeMesh::new(&torus(1.0, 0.35, 48, 24));
    let model = DMat4::from_rotation_x(0.5);
    let eye = DVec3::new(0.3, 0.8, 4.0);
    let occluders = Occluders::new([(&mesh, model)]);
    let triangles: Vec<[DVec3; 3]> = mesh
        .faces
        .iter()
        .map(|f| f.map(|v| model.transform_point3(mesh.positions[v as usize])))
        .collect();
    // Every triangle, no hierarchy: Möller–Trumbore with the same
    // exclusion of the point's own faces (parameter within 1e-7 of 1).
    let brute = |p: DVec3| -> u32 {
        let d = p - eye;
        let mut hits: Vec<f64> = triangles
            .iter()
            .filter_map(|t| {
                let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
                let q = d.cross(e2);
                let det = e1.dot(q);
                if det.abs() < 1e-14 {
                    return None;
                }
                let s = eye - t[0];
                let u = s.dot(q) / det;
                let r = s.cross(e1);
                let v = d.dot(r) / det;
                let at = e2.dot(r) / det;
                (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && at > 0.0 && at < 1.0 - 1e-7).then_some(at)
            })
            .collect();
        hits.sort_by(f64::total_cmp);
        hits.dedup_by(|a, b| (*a - *b).abs() < 1e-10);
        hits.len() as u32
    };
    let local_eye = model.inverse().transform_point3(eye);
    let silhouettes = mesh.silhouettes(local_eye);
    let mut samples = Vec::new();
    for chain in mesh.chain(&silhouettes) {
        let points: Vec<DVec3> = chain
            .vertices
            .iter()
            .map(|&v| model.transform_point3(mesh.positions[v as usize]))
            .collect();
        let runs = occluders.runs(&points, chain.closed, eye);
        samples.extend(labelled_samples(&runs, &brute, 8));
    }
    let (mut visible, mut hidden) = (Confusion::default(), Confusion::default());
    for &(length, qi, truth) in &samples {
        visible.add(length, qi == 0, truth == 0);
        hidden.add(length, qi >= 1, truth >= 1);
    }
    assert!(
        hidden.truth > 0.1 * (hidden.truth + visible.truth),
        "the torus hides part of its own silhouette"
    );
    for (name, c) in [("visible", &visible), ("hidden", &hidden)] {
        eprintln!("torus {name}: precision {:.5}, recall {:.5}", c.precision(), c.recall());
        assert!(c.precision() >= 0.95 && c.recall() >= 0.95, "{name}: {c:?}");
    }
}

#[test]
fn dashes_are_cut_exactly_at_the_pattern_along_the_screen_arc_length() {
    use glam::DVec2;
    use npr_runner::lines::strip::{dash_runs, BackbonePoint};
    // A straight backbone 100 px long, sampled every 1.5 px (as a λ of
    // 24 px samples it), then a bend: s runs on through it.
    let mut backbone: Vec<BackbonePoint> = Vec::new();
    let mut s = 0.0;
    let mut at = DVec2::new(10.0, 10.0);
    for k in 0..=100 {
        let step = if k < 60 {
            DVec2::new(1.5, 0.0)
        } else {
            DVec2::new(0.0, 1.5)
        };
        if k > 0 {
            at += step;
            s += 1.5;
        }
        backbone.push(BackbonePoint {
            base: at,
            normal: DVec2::Y,
            px: at,
            depth: 0.5,
            inv_w: 1.0,
            s,
        });
    }
    let runs = dash_runs(&backbone, [6.0, 4.0]);
    // 150 px: dashes at [10k, 10k + 6) for k = 0..=14.
    assert_eq!(runs.len(), 15);
    for (k, run) in runs.iter().enumerate() {
        let (start, end) = (run[0].s, run[run.len() - 1].s);
        assert!((start - 10.0 * k as f64).abs() < 1e-9, "dash {k} starts at {start}");
        assert!((end - (10.0 * k as f64 + 6.0)).abs() < 1e-9, "dash {k} ends at {end}");
        // The screen length of a dash is its arc length (it bends at 88.5 px).
        let length: f64 = run.windows(2).map(|w| (w[1].px - w[0].px).length()).sum();
        assert!((length - 6.0).abs() < 1e-9, "dash {k} is {length} px");
    }
    assert!(dash_runs(&backbone, [0.0, 4.0]).is_empty());
}

/// An orthographic camera (decision 0062) sees along one direction: a
/// point behind a box counts the box's two faces whatever its distance,
/// and a point just beside the box counts none, where rays to a
/// perspective eye on the box's axis pass through the box (slab test:
/// they enter the front face and leave by the back one).
#[test]
fn an_orthographic_viewpoint_counts_along_its_direction() {
    use npr_runner::lines::viewpoint::Viewpoint;
    let block = Box3 {
        lo: DVec3::new(-1.0, -1.0, -1.0),
        hi: DVec3::new(1.0, 1.0, 1.0),
    };
    let unit = EdgeMesh::new(&cube(2.0));
    let occluders = Occluders::new([(&unit, block.model())]);
    // Looking down −z: the eye lies towards +z.
    let towards_eye = Viewpoint::direction(DVec3::Z);
    let perspective_eye = DVec3::new(0.0, 0.0, 3.0);
    for z in [-1.5, -4.0, -40.0] {
        let behind = DVec3::new(0.95, 0.95, z);
        assert_eq!(occluders.qi(towards_eye, behind), 2, "behind the box at z = {z}");
        let beside = DVec3::new(1.05, 0.0, z);
        assert_eq!(occluders.qi(towards_eye, beside), 0, "beside the box at z = {z}");
        assert_eq!(block.crossings(perspective_eye, beside), 2, "the slab test at z = {z}");
        assert_eq!(
            occluders.qi(perspective_eye, beside),
            2,
            "perspective, beside the box at z = {z}"
        );
    }
}
