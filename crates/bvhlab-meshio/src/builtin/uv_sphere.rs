//! The UV sphere: vertices on circles of latitude (bands) and meridians (segments), joined by
//! quads split in two, and by fans of triangles at the poles.

use bvhlab::Mesh;
use bvhlab::glam::Vec3;

/// The unit sphere with `segments` meridians and `bands` bands of latitude (at least 3 and 2):
/// `2 · segments · (bands − 1)` triangles, closed, wound counter-clockwise from outside.
pub fn uv_sphere(segments: u32, bands: u32) -> Mesh {
    let (positions, indices) = sphere_grid(segments, bands, |direction| direction);
    super::indexed(positions, indices)
}

/// The vertices and triangles of a UV sphere whose vertex in unit direction `d` is placed at
/// `place(d)`: the unit sphere for the identity, a displaced one otherwise.
///
/// Vertex 0 is the north pole (+y), then `bands − 1` rings of `segments` vertices from north
/// to south, then the south pole.
pub(super) fn sphere_grid(
    segments: u32,
    bands: u32,
    place: impl Fn(Vec3) -> Vec3,
) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let (segments, bands) = (segments.max(3), bands.max(2));
    let rings = bands - 1;
    let mut positions = Vec::with_capacity((2 + rings * segments) as usize);
    positions.push(place(Vec3::Y));
    let angles: Vec<(f32, f32)> = (0..segments)
        .map(|i| (std::f32::consts::TAU * i as f32 / segments as f32).sin_cos())
        .collect();
    for j in 1..bands {
        let (sin_phi, cos_phi) = (std::f32::consts::PI * j as f32 / bands as f32).sin_cos();
        for &(sin_theta, cos_theta) in &angles {
            let direction = Vec3::new(sin_phi * cos_theta, cos_phi, sin_phi * sin_theta);
            positions.push(place(direction));
        }
    }
    let south = positions.len() as u32;
    positions.push(place(Vec3::NEG_Y));

    let ring = |j: u32, i: u32| 1 + j * segments + i % segments;
    let mut indices = Vec::with_capacity((2 * segments * rings) as usize);
    for i in 0..segments {
        indices.push([0, ring(0, i + 1), ring(0, i)]);
    }
    for j in 0..rings - 1 {
        for i in 0..segments {
            // The quad (j, i)–(j, i+1)–(j+1, i+1)–(j+1, i): going along i, then down j, turns
            // counter-clockwise seen from outside.
            let (a, b) = (ring(j, i), ring(j, i + 1));
            let (c, d) = (ring(j + 1, i), ring(j + 1, i + 1));
            indices.push([a, b, c]);
            indices.push([b, d, c]);
        }
    }
    for i in 0..segments {
        indices.push([ring(rings - 1, i), ring(rings - 1, i + 1), south]);
    }
    (positions, indices)
}
