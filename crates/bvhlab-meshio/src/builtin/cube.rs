//! The cube `[-1, 1]³`: 8 corners, 12 triangles, every face and edge on an axis.

use bvhlab::Mesh;
use bvhlab::glam::Vec3;

/// The cube `[-1, 1]³`, two triangles per face, wound counter-clockwise seen from outside.
pub fn cube() -> Mesh {
    // Corner k has x = ±1 by bit 0, y by bit 1, z by bit 2.
    let positions = (0..8)
        .map(|k| Vec3::new(sign(k & 1), sign(k & 2), sign(k & 4)))
        .collect();
    // Each face as a quad, counter-clockwise from outside.
    let quads: [[u32; 4]; 6] = [
        [0, 4, 6, 2], // x = -1
        [1, 3, 7, 5], // x = +1
        [0, 1, 5, 4], // y = -1
        [2, 6, 7, 3], // y = +1
        [0, 2, 3, 1], // z = -1
        [4, 5, 7, 6], // z = +1
    ];
    let indices = quads
        .iter()
        .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
        .collect();
    super::indexed(positions, indices)
}

fn sign(bit: u32) -> f32 {
    if bit == 0 { -1.0 } else { 1.0 }
}
