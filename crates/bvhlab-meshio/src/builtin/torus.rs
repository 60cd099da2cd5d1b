//! The torus: a circle of radius `r` swept around the y axis at distance 1.

use std::f32::consts::TAU;

use bvhlab::Mesh;
use bvhlab::glam::Vec3;

/// The torus around the y axis, with the tube's centre at distance 1 and the tube's radius
/// `tube` (below 1), on `rings` steps around the axis and `sides` around the tube (at least
/// 3 each): `2 · rings · sides` triangles, closed, wound counter-clockwise from outside.
pub fn torus(rings: u32, sides: u32, tube: f32) -> Mesh {
    let (rings, sides) = (rings.max(3), sides.max(3));
    let mut positions = Vec::with_capacity((rings * sides) as usize);
    for i in 0..rings {
        let (sin_u, cos_u) = (TAU * i as f32 / rings as f32).sin_cos();
        for j in 0..sides {
            let (sin_v, cos_v) = (TAU * j as f32 / sides as f32).sin_cos();
            let reach = 1.0 + tube * cos_v;
            positions.push(Vec3::new(reach * cos_u, tube * sin_v, reach * sin_u));
        }
    }
    super::indexed(positions, ring_triangles(rings, sides))
}

/// The triangles of a torus whose vertices are laid out ring by ring (`rings` rings of
/// `sides` vertices each), closed around both circles: two per quad.
pub(super) fn ring_triangles(rings: u32, sides: u32) -> Vec<[u32; 3]> {
    let at = |i: u32, j: u32| (i % rings) * sides + j % sides;
    let mut indices = Vec::with_capacity((2 * rings * sides) as usize);
    for i in 0..rings {
        for j in 0..sides {
            // Around the tube (j) then around the axis (i) turns counter-clockwise from
            // outside.
            let (a, b) = (at(i, j), at(i, j + 1));
            let (c, d) = (at(i + 1, j), at(i + 1, j + 1));
            indices.push([a, b, c]);
            indices.push([b, d, c]);
        }
    }
    indices
}
