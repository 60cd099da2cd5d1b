//! A cloud of small tetrahedra: many separate closed objects at random places, sizes and
//! turns, whose bounding boxes overlap, as in a scene of many small parts.

use bvhlab::Mesh;
use bvhlab::glam::{Quat, Vec3};

use super::random::Random;

/// `count` regular tetrahedra with centres uniform in `[-1, 1]³`, circumradii between 0.03
/// and 0.12 and random orientations, from `seed`: `4 · count` triangles, each tetrahedron
/// closed and wound counter-clockwise from outside.
pub fn tetrahedra(count: u32, seed: u64) -> Mesh {
    // A regular tetrahedron: alternate corners of a cube, circumradius 1.
    let corners = [
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(1.0, -1.0, -1.0),
        Vec3::new(-1.0, 1.0, -1.0),
        Vec3::new(-1.0, -1.0, 1.0),
    ]
    .map(|c| c / 3f32.sqrt());
    let mut random = Random::new(seed);
    let mut positions = Vec::with_capacity(4 * count as usize);
    let mut indices = Vec::with_capacity(4 * count as usize);
    for k in 0..count {
        let centre = Vec3::new(
            random.range(-1.0, 1.0),
            random.range(-1.0, 1.0),
            random.range(-1.0, 1.0),
        );
        let size = random.range(0.03, 0.12);
        let turn =
            Quat::from_axis_angle(random.direction(), random.range(0.0, std::f32::consts::TAU));
        positions.extend(corners.map(|c| centre + turn * (size * c)));
        let first = 4 * k;
        for apex in 0..4 {
            // The face opposite `apex`, wound so that the apex is behind it.
            let [a, b, c] = [(apex + 1) % 4, (apex + 2) % 4, (apex + 3) % 4];
            let at = |i: u32| corners[i as usize];
            let outward = (at(b) - at(a)).cross(at(c) - at(a)).dot(at(a) - at(apex)) > 0.0;
            let (b, c) = if outward { (b, c) } else { (c, b) };
            indices.push([first + a, first + b, first + c]);
        }
    }
    super::indexed(positions, indices)
}
