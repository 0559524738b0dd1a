//! Analytic meshes: sphere, cube, torus, plane, cylinder; and the animated
//! ocean grid of [`super::ocean`] (the one primitive whose geometry depends
//! on time: see [`Primitive::is_time_varying`]).
//!
//! All are centred on the origin with exact (analytic) normals, UVs in
//! [0, 1] with v = 0 at the image top, and analytic tangents with the
//! convention of [`Mesh::tangents`] (w = +1: no primitive mirrors its UVs).
//! Triangles wind counter-clockwise seen from outside. Seams and hard edges
//! duplicate vertices, so every attribute is exact per vertex.
//!
//! Counts are clamped into their valid range (segments 3..=4096, rings
//! 2..=4096, subdivisions 1..=4096) so no call panics or allocates without
//! bound; the scene parser reports out-of-range values as errors before
//! calling these. Sizes are used as given.

use super::geometry::orthonormal_tangent;
use super::mesh::Mesh;
use super::ocean::{self, Ocean};
use glam::{DVec3, Vec3};
use std::f64::consts::{PI, TAU};

/// The most segments (or rings, sides, subdivisions) one primitive may have.
pub const MAX_SEGMENTS: u32 = 4096;

/// The primitive kinds, as written in a scene's `primitive = { kind = ... }`.
pub const KINDS: &[&str] = &["sphere", "cube", "torus", "plane", "cylinder", "ocean"];

/// A primitive with its parameters, as declared in a scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Primitive {
    Sphere {
        radius: f32,
        segments: u32,
        rings: u32,
    },
    Cube {
        size: f32,
    },
    Torus {
        major: f32,
        minor: f32,
        segments: u32,
        sides: u32,
    },
    Plane {
        size: f32,
        subdivisions: u32,
    },
    Cylinder {
        radius: f32,
        height: f32,
        segments: u32,
    },
    /// Age of Sail §6.1's periodic ocean tiles; see [`super::ocean`].
    Ocean(Ocean),
}

impl Primitive {
    /// How many triangles [`Primitive::build`] makes (after clamping counts),
    /// computed without building, so limits can be checked first.
    pub fn triangle_count(&self) -> u64 {
        match *self {
            Primitive::Sphere { segments, rings, .. } => {
                2 * u64::from(segment_count(segments)) * (u64::from(ring_count(rings)) - 1)
            }
            Primitive::Cube { .. } => 12,
            Primitive::Torus { segments, sides, .. } => {
                2 * u64::from(segment_count(segments)) * u64::from(segment_count(sides))
            }
            Primitive::Plane { subdivisions, .. } => 2 * u64::from(subdivision_count(subdivisions)).pow(2),
            Primitive::Cylinder { segments, .. } => 4 * u64::from(segment_count(segments)),
            Primitive::Ocean(o) => 2 * o.sanitized().grid_cells().pow(2),
        }
    }

    /// Whether the geometry changes with time, so a renderer must rebuild it
    /// per frame with [`Primitive::build_at`] (only the ocean).
    pub fn is_time_varying(&self) -> bool {
        matches!(self, Primitive::Ocean(_))
    }

    /// The geometry at `time_s` seconds. Same vertex count and indices at
    /// every time; equal to [`Primitive::build`] for static primitives.
    pub fn build_at(&self, time_s: f64) -> Mesh {
        match self {
            Primitive::Ocean(o) => ocean::ocean_mesh(o, time_s),
            _ => self.build(),
        }
    }

    /// The geometry (at time 0 for a time-varying primitive).
    pub fn build(&self) -> Mesh {
        match *self {
            Primitive::Sphere {
                radius,
                segments,
                rings,
            } => sphere(radius, segments, rings),
            Primitive::Cube { size } => cube(size),
            Primitive::Torus {
                major,
                minor,
                segments,
                sides,
            } => torus(major, minor, segments, sides),
            Primitive::Plane { size, subdivisions } => plane(size, subdivisions),
            Primitive::Cylinder {
                radius,
                height,
                segments,
            } => cylinder(radius, height, segments),
            Primitive::Ocean(o) => ocean::ocean_mesh(&o, 0.0),
        }
    }

    /// The description stored in [`Mesh::source`], e.g. `sphere(radius=1, segments=64, rings=32)`.
    pub fn description(&self) -> String {
        match *self {
            Primitive::Sphere {
                radius,
                segments,
                rings,
            } => {
                format!("sphere(radius={radius}, segments={segments}, rings={rings})")
            }
            Primitive::Cube { size } => format!("cube(size={size})"),
            Primitive::Torus {
                major,
                minor,
                segments,
                sides,
            } => {
                format!("torus(major={major}, minor={minor}, segments={segments}, sides={sides})")
            }
            Primitive::Plane { size, subdivisions } => {
                format!("plane(size={size}, subdivisions={subdivisions})")
            }
            Primitive::Cylinder {
                radius,
                height,
                segments,
            } => {
                format!("cylinder(radius={radius}, height={height}, segments={segments})")
            }
            Primitive::Ocean(o) => ocean::description(&o),
        }
    }
}

/// A UV sphere around the Y axis: `segments` around, `rings` from pole to
/// pole. u runs around from +X, v from the north pole (+Y, v = 0) to the
/// south pole. The degenerate triangles at the poles are left out, so there
/// are `2 · segments · (rings - 1)` triangles.
pub fn sphere(radius: f32, segments: u32, rings: u32) -> Mesh {
    let (segments, rings) = (segment_count(segments), ring_count(rings));
    let mut builder = Builder::default();
    for ring in 0..=rings {
        let v = f64::from(ring) / f64::from(rings);
        let polar = PI * v;
        for segment in 0..=segments {
            let u = f64::from(segment) / f64::from(segments);
            let azimuth = TAU * u;
            let normal = DVec3::new(polar.sin() * azimuth.cos(), polar.cos(), -polar.sin() * azimuth.sin());
            // d(position)/du; unlike the polar derivative it does not vanish
            // at the poles, so pole vertices get a proper tangent too.
            let along_u = DVec3::new(-azimuth.sin(), 0.0, -azimuth.cos());
            let towards_north = DVec3::new(-polar.cos() * azimuth.cos(), polar.sin(), polar.cos() * azimuth.sin());
            builder.vertex(normal * f64::from(radius), normal, [u, v], along_u, towards_north);
        }
    }
    let row = segments + 1;
    for ring in 0..rings {
        for segment in 0..segments {
            let top_left = ring * row + segment;
            let [a, b, c, d] = [top_left, top_left + row, top_left + row + 1, top_left + 1];
            if ring != 0 {
                builder.triangle(a, c, d);
            }
            if ring != rings - 1 {
                builder.triangle(a, b, c);
            }
        }
    }
    builder.finish(
        Primitive::Sphere {
            radius,
            segments,
            rings,
        }
        .description(),
    )
}

/// An axis-aligned cube with edge length `size`: 24 vertices (4 per face, so
/// normals are exactly the face axes) and 12 triangles. Each face's UVs span
/// the whole [0, 1] square.
pub fn cube(size: f32) -> Mesh {
    let half = f64::from(size) / 2.0;
    // (outward normal, image right, image top) per face; right × top = normal.
    let faces = [
        (DVec3::X, DVec3::NEG_Z, DVec3::Y),
        (DVec3::NEG_X, DVec3::Z, DVec3::Y),
        (DVec3::Y, DVec3::X, DVec3::NEG_Z),
        (DVec3::NEG_Y, DVec3::X, DVec3::Z),
        (DVec3::Z, DVec3::X, DVec3::Y),
        (DVec3::NEG_Z, DVec3::NEG_X, DVec3::Y),
    ];
    let mut builder = Builder::default();
    for (normal, right, top) in faces {
        let first = builder.next_index();
        // Corners in the order top-left, bottom-left, bottom-right, top-right.
        for (x, y) in [(-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0), (1.0, 1.0)] {
            let position = (normal + right * x + top * y) * half;
            let uv = [(x + 1.0) / 2.0, (1.0 - y) / 2.0];
            builder.vertex(position, normal, uv, right, top);
        }
        builder.quad(first, first + 1, first + 2, first + 3);
    }
    builder.finish(Primitive::Cube { size }.description())
}

/// A torus around the Y axis: the tube's centre circle has radius `major`,
/// the tube radius `minor`. u runs around the Y axis (`segments`), v around
/// the tube (`sides`), starting on the outer equator and going down first.
pub fn torus(major: f32, minor: f32, segments: u32, sides: u32) -> Mesh {
    let (segments, sides) = (segment_count(segments), segment_count(sides));
    let (major_r, minor_r) = (f64::from(major), f64::from(minor));
    let mut builder = Builder::default();
    for side in 0..=sides {
        let v = f64::from(side) / f64::from(sides);
        let tube_angle = TAU * v;
        for segment in 0..=segments {
            let u = f64::from(segment) / f64::from(segments);
            let azimuth = TAU * u;
            let outwards = DVec3::new(azimuth.cos(), 0.0, -azimuth.sin());
            let normal = outwards * tube_angle.cos() - DVec3::Y * tube_angle.sin();
            let position = outwards * major_r + normal * minor_r;
            let along_u = DVec3::new(-azimuth.sin(), 0.0, -azimuth.cos());
            let towards_image_top = outwards * tube_angle.sin() + DVec3::Y * tube_angle.cos();
            builder.vertex(position, normal, [u, v], along_u, towards_image_top);
        }
    }
    builder.grid(sides, segments);
    builder.finish(
        Primitive::Torus {
            major,
            minor,
            segments,
            sides,
        }
        .description(),
    )
}

/// A square in the XZ plane facing +Y, `subdivisions` cells along each side.
/// u runs along +X, v along +Z.
pub fn plane(size: f32, subdivisions: u32) -> Mesh {
    let cells = subdivision_count(subdivisions);
    let size = f64::from(size);
    let mut builder = Builder::default();
    for row in 0..=cells {
        let v = f64::from(row) / f64::from(cells);
        for column in 0..=cells {
            let u = f64::from(column) / f64::from(cells);
            let position = DVec3::new((u - 0.5) * size, 0.0, (v - 0.5) * size);
            builder.vertex(position, DVec3::Y, [u, v], DVec3::X, DVec3::NEG_Z);
        }
    }
    builder.grid(cells, cells);
    builder.finish(
        Primitive::Plane {
            size: size as f32,
            subdivisions: cells,
        }
        .description(),
    )
}

/// A closed cylinder along the Y axis from -height/2 to +height/2. The side
/// has u around (as the sphere) and v from top to bottom; each cap is a fan
/// with its own vertices (normals ±Y) and UVs mapping the disc into [0, 1]².
pub fn cylinder(radius: f32, height: f32, segments: u32) -> Mesh {
    let segments = segment_count(segments);
    let (r, half) = (f64::from(radius), f64::from(height) / 2.0);
    let mut builder = Builder::default();
    for (v, y) in [(0.0, half), (1.0, -half)] {
        for segment in 0..=segments {
            let u = f64::from(segment) / f64::from(segments);
            let azimuth = TAU * u;
            let outwards = DVec3::new(azimuth.cos(), 0.0, -azimuth.sin());
            let along_u = DVec3::new(-azimuth.sin(), 0.0, -azimuth.cos());
            builder.vertex(outwards * r + DVec3::Y * y, outwards, [u, v], along_u, DVec3::Y);
        }
    }
    builder.grid(1, segments);
    // Caps, seen from outside: the top with image top towards -Z, the bottom
    // with image top towards +Z (as the cube's ±Y faces).
    for (normal, image_top) in [(DVec3::Y, DVec3::NEG_Z), (DVec3::NEG_Y, DVec3::Z)] {
        let centre = builder.next_index();
        builder.vertex(normal * half, normal, [0.5, 0.5], DVec3::X, image_top);
        for segment in 0..segments {
            let azimuth = TAU * f64::from(segment) / f64::from(segments);
            let offset = DVec3::new(azimuth.cos(), 0.0, -azimuth.sin());
            // v grows towards the bottom of the image, i.e. against image_top.
            let uv = [0.5 + offset.x / 2.0, 0.5 - offset.dot(image_top) / 2.0];
            builder.vertex(normal * half + offset * r, normal, uv, DVec3::X, image_top);
        }
        for segment in 0..segments {
            let here = centre + 1 + segment;
            let next = centre + 1 + (segment + 1) % segments;
            // Increasing azimuth turns counter-clockwise seen from +Y.
            if normal.y > 0.0 {
                builder.triangle(centre, here, next);
            } else {
                builder.triangle(centre, next, here);
            }
        }
    }
    builder.finish(
        Primitive::Cylinder {
            radius,
            height,
            segments,
        }
        .description(),
    )
}

fn segment_count(requested: u32) -> u32 {
    requested.clamp(3, MAX_SEGMENTS)
}

fn ring_count(requested: u32) -> u32 {
    requested.clamp(2, MAX_SEGMENTS)
}

fn subdivision_count(requested: u32) -> u32 {
    requested.clamp(1, MAX_SEGMENTS)
}

/// Accumulates vertices in f64 (so trigonometry is exact to f32 precision)
/// and converts once at the end.
#[derive(Default)]
struct Builder {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    uvs: Vec<[f32; 2]>,
    tangents: Vec<[f32; 4]>,
    indices: Vec<u32>,
}

impl Builder {
    fn next_index(&self) -> u32 {
        self.positions.len() as u32
    }

    /// `along_u` and `towards_image_top` need not be unit or orthogonal to
    /// the normal: the tangent frame is orthonormalized here.
    fn vertex(&mut self, position: DVec3, normal: DVec3, uv: [f64; 2], along_u: DVec3, towards_image_top: DVec3) {
        let normal = normal.normalize_or(DVec3::Y);
        self.positions.push(position.as_vec3().to_array());
        self.normals.push(normal.as_vec3().to_array());
        self.uvs.push([uv[0] as f32, uv[1] as f32]);
        let to_f32 = |v: DVec3| -> Vec3 { v.as_vec3() };
        self.tangents.push(orthonormal_tangent(
            to_f32(normal),
            to_f32(along_u),
            to_f32(towards_image_top),
        ));
    }

    fn triangle(&mut self, a: u32, b: u32, c: u32) {
        self.indices.extend([a, b, c]);
    }

    /// Two triangles for corners given counter-clockwise from the top-left.
    fn quad(&mut self, top_left: u32, bottom_left: u32, bottom_right: u32, top_right: u32) {
        self.triangle(top_left, bottom_left, bottom_right);
        self.triangle(top_left, bottom_right, top_right);
    }

    /// Quads over a `(rows + 1) × (columns + 1)` vertex grid laid out row by
    /// row, where rows run down the image and columns to its right.
    fn grid(&mut self, rows: u32, columns: u32) {
        let first = self.next_index() - (rows + 1) * (columns + 1);
        let stride = columns + 1;
        for row in 0..rows {
            for column in 0..columns {
                let top_left = first + row * stride + column;
                self.quad(top_left, top_left + stride, top_left + stride + 1, top_left + 1);
            }
        }
    }

    fn finish(self, source: String) -> Mesh {
        Mesh {
            positions: self.positions,
            normals: self.normals,
            uvs: Some(self.uvs),
            tangents: Some(self.tangents),
            indices: self.indices,
            source,
            parts: None,
            edge_marks: None,
        }
    }
}
