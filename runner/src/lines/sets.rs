//! The line sets of a `lines` pass (decision 0056): each set selects its
//! surfaces (the pass's objects, narrowed by the set's tag) and a union of
//! edge types, and draws them in its own style. An edge two sets select is
//! drawn once, by the set listed first (the manifest lists sets highest
//! priority first), so two sets never stack two strips with different
//! phases on one edge (issue 35 item 8, now between sets).
//!
//! Edge identity: a mesh edge is (surface, edge index), the surface being
//! its index in the pass's surfaces (the same object selected by two sets
//! is the same surface, whatever its place in each set); an intersection segment is its two end points'
//! bits, which are computed from the same triangles by the same arithmetic
//! in every set that finds them, so equal bit for bit.
//!
//! Sets with visibilities (decision 0063) own an edge per range of QI: a
//! visible and a hidden set both take an edge, and each draws its pieces;
//! a set whose QIs overlap those of a set before it that took the edge does
//! not.
//!
//! Within a set, as in a pass without sets, the silhouettes are chained
//! first (a silhouette loop keeps one phase all round it) and the set's
//! other mesh edges are chained together after them; the intersection lines
//! are chained on their own.
//!
//! A set with a `visibility:` keeps only the pieces of its lines with the
//! quantitative invisibility it asks for (`visibility.rs`, decision 0063)
//! and may draw them dashed (`strip::build_dashed`).

use std::collections::{HashMap, HashSet};

use glam::{DMat4, DVec2, DVec3};
use npr_abi::lines::{EdgeTypes, LineVisibility, QiRange};

use super::edges::EdgeMesh;
use super::intersections::{intersection_segments, weld_and_chain, PlacedMesh};
use super::strip::{self, LineStyle, Strips};
use super::viewpoint::Viewpoint;
use super::visibility::Occluders;

/// A surface's identity across sets: its index among the pass's surfaces.
pub type SurfaceKey = usize;

/// One surface a set draws: its edge mesh, placement and identity.
pub struct SetSurface<'a> {
    pub edges: &'a EdgeMesh,
    pub model: DMat4,
    pub key: SurfaceKey,
}

/// One set, ready to build: its surfaces, edge types and style.
pub struct SetInput<'a> {
    pub surfaces: Vec<SetSurface<'a>>,
    pub edges: EdgeTypes,
    pub style: LineStyle,
    /// Which lines by quantitative invisibility (decision 0063); `None`
    /// draws all and leaves hiding to the pass's depth test.
    pub visibility: Option<LineVisibility>,
    /// Dashes `(on, off)` in px along the screen arc length.
    pub dash: Option<[f64; 2]>,
}

/// World-space polylines (closed or not).
pub type Polylines = Vec<(Vec<DVec3>, bool)>;

/// Per set (in the order given, highest priority first), the world-space
/// polylines it draws from the eye at `eye_position`: each edge in exactly
/// one set, the first that selects it.
///
/// A set with a visibility keeps the pieces of its lines whose quantitative
/// invisibility it shows ([`super::visibility`]), counted against every surface
/// some set of the pass draws; the edges it selects are its own whether or
/// not a piece is drawn (an edge is owned, then cut by visibility).
pub fn select(sets: &[SetInput<'_>], eye_position: impl Into<Viewpoint>) -> Vec<Polylines> {
    let eye_position = eye_position.into();
    let occluders = sets.iter().any(|s| s.visibility.is_some()).then(|| {
        let mut seen: HashSet<SurfaceKey> = HashSet::new();
        Occluders::new(
            sets.iter()
                .flat_map(|s| &s.surfaces)
                .filter(|s| seen.insert(s.key))
                .map(|s| (s.edges, s.model)),
        )
    });
    let selected = select_edges(sets, eye_position);
    selected
        .into_iter()
        .zip(sets)
        .map(|(polylines, set)| match (set.visibility, &occluders) {
            (Some(shown), Some(occluders)) => visible_pieces(&polylines, occluders, eye_position, shown),
            _ => polylines,
        })
        .collect()
}

/// The pieces of `polylines` whose QI `shown` takes; neighbouring pieces of
/// two QIs it takes stay one line (the arc length runs on).
fn visible_pieces(polylines: &Polylines, occluders: &Occluders, eye: Viewpoint, shown: LineVisibility) -> Polylines {
    let mut out: Polylines = Vec::new();
    for (points, closed) in polylines {
        let runs = occluders.runs(points, *closed, eye);
        let mut joining = false;
        for (run, run_closed, qi) in runs {
            if !LineVisibility::shows(Some(shown), qi) {
                joining = false;
                continue;
            }
            match out.last_mut() {
                Some((line, false)) if joining && line.last() == run.first() => line.extend(run.into_iter().skip(1)),
                _ => out.push((run, run_closed)),
            }
            joining = true;
        }
    }
    out
}

/// Per set, the polylines of the edges it owns (the first set that selects
/// an edge owns it), before visibility.
fn select_edges(sets: &[SetInput<'_>], eye_position: Viewpoint) -> Vec<Polylines> {
    let mut taken_edges: HashMap<(SurfaceKey, u32), Vec<QiRange>> = HashMap::new();
    let mut taken_segments: HashMap<[u64; 6], Vec<QiRange>> = HashMap::new();
    sets.iter()
        .map(|set| {
            let range = LineVisibility::qi_range(set.visibility);
            let mut polylines: Polylines = Vec::new();
            for surface in &set.surfaces {
                let mesh = surface.edges;
                let world = |vertices: &[u32], closed: bool| -> (Vec<DVec3>, bool) {
                    let points = vertices
                        .iter()
                        .map(|&v| surface.model.transform_point3(mesh.positions[v as usize]));
                    (points.collect(), closed)
                };
                let local_eye = eye_position.transformed(surface.model.inverse());
                let mut claim = |indices: Vec<u32>| -> Vec<u32> {
                    indices
                        .into_iter()
                        .filter(|&e| claim_for(taken_edges.entry((surface.key, e)).or_default(), range))
                        .collect()
                };
                if set.edges.silhouette && local_eye.is_finite() {
                    let silhouettes = claim(mesh.silhouettes(local_eye));
                    polylines.extend(mesh.chain(&silhouettes).iter().map(|l| world(&l.vertices, l.closed)));
                }
                let mut others: Vec<u32> = Vec::new();
                if set.edges.border {
                    others.extend(mesh.borders());
                }
                if let Some(threshold) = set.edges.crease_deg {
                    others.extend(mesh.creases_over(threshold));
                }
                if set.edges.material_boundary {
                    others.extend(mesh.part_boundaries());
                }
                if set.edges.marked {
                    others.extend(mesh.marked());
                }
                others.sort_unstable();
                others.dedup();
                let others = claim(others);
                polylines.extend(mesh.chain(&others).iter().map(|l| world(&l.vertices, l.closed)));
            }
            if set.edges.intersection {
                let placed: Vec<PlacedMesh<'_>> = set
                    .surfaces
                    .iter()
                    .map(|s| PlacedMesh {
                        edges: s.edges,
                        model: s.model,
                    })
                    .collect();
                let (segments, tolerance) = intersection_segments(&placed);
                let mine: Vec<(DVec3, DVec3)> = segments
                    .into_iter()
                    .filter(|&(a, b)| claim_for(taken_segments.entry(segment_key(a, b)).or_default(), range))
                    .collect();
                polylines.extend(weld_and_chain(&mine, tolerance));
            }
            polylines
        })
        .collect()
}

/// Claims an edge for a set showing QIs `range`, unless a set before it
/// took the edge for QIs that overlap: sets of disjoint visibilities (a
/// visible and a hidden set) both draw an edge, each its own pieces.
fn claim_for(claims: &mut Vec<QiRange>, range: QiRange) -> bool {
    if claims.iter().any(|c| c.0 <= range.1 && range.0 <= c.1) {
        return false;
    }
    claims.push(range);
    true
}

/// A segment's identity whichever way round it was found.
fn segment_key(a: DVec3, b: DVec3) -> [u64; 6] {
    let (a, b) = (a.to_array().map(f64::to_bits), b.to_array().map(f64::to_bits));
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    [lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]]
}

/// The strips of every set from one eye, each vertex marked with its set's
/// index (`LineVertex::line.w`, which the shader's `line.color` reads).
pub fn build(sets: &[SetInput<'_>], eye_position: impl Into<Viewpoint>, view_proj: DMat4, size: DVec2) -> Strips {
    let mut strips = Strips::default();
    for (index, (set, polylines)) in sets.iter().zip(select(sets, eye_position)).enumerate() {
        let mut built = match set.dash {
            Some(dash) => strip::build_dashed(&polylines, view_proj, size, &set.style, dash),
            None => strip::build(&polylines, view_proj, size, &set.style),
        };
        if set.visibility.is_some() {
            // Visibility is decided here, exactly: the pass's depth test
            // must not hide a hidden line again, so these strips sit at the
            // near plane, where every depth test passes.
            for v in &mut built.vertices {
                v.depth = 0.0;
                v.inv_w = 0.0;
            }
        }
        strips.append(built, index as u32);
    }
    strips
}
