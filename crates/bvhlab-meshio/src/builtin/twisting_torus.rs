//! The twisting torus: a torus with a flattened (elliptic) tube that turns and ripples over
//! time, for refitting a tree every frame. Its vertices are a pure function of the time, so
//! every frame, test and student sees the same triangles at the same moment; its triangles
//! keep their indices (only the positions move), which is what a refit needs.

use std::f64::consts::TAU;

use bvhlab::Mesh;
use bvhlab::glam::Vec3;

/// The tube's half-width across the ring (before it turns) and its half-height.
const TUBE: (f32, f32) = (0.42, 0.14);
/// Radians per second the whole tube turns about its own centre line.
const SPIN: f64 = 0.9;
/// How far (radians) the tube's turn varies around the ring, at most, and how fast that
/// twist swells and ebbs (radians per second).
const TWIST: (f32, f64) = (1.6, 0.7);
/// The ring's ripple: its height (a fraction of the ring's radius 1), waves around the ring,
/// and radians per second it travels.
const RIPPLE: (f32, f32, f64) = (0.12, 3.0, 1.3);

/// The twisting torus `seconds` into its motion, on `rings` steps around the y axis and
/// `sides` around the tube (at least 3 each): `2 · rings · sides` triangles, closed, wound
/// counter-clockwise from outside, the same indices at every time.
///
/// Around the ring (angle `u`) the ring's radius ripples, `1 + 0.12 sin(3u − 1.3 t)`; the
/// tube's section is an ellipse 0.84 wide and 0.28 high, turned about the tube's centre
/// line by `0.9 t + 1.6 sin(u) sin(0.7 t)`: the whole tube spins, and its twist swells and
/// ebbs. At `seconds = 0` it is a flat ring tube.
pub fn twisting_torus(rings: u32, sides: u32, seconds: f64) -> Mesh {
    let (rings, sides) = (rings.max(3), sides.max(3));
    // Phases reduced in f64, so that a page left running for hours keeps its precision.
    let phase = |rate: f64| (rate * seconds).rem_euclid(TAU) as f32;
    let (spin, swell, travel) = (phase(SPIN), phase(TWIST.1).sin(), phase(RIPPLE.2));
    let mut positions = Vec::with_capacity((rings * sides) as usize);
    for i in 0..rings {
        let u = (TAU * f64::from(i) / f64::from(rings)) as f32;
        let (sin_u, cos_u) = u.sin_cos();
        let radius = 1.0 + RIPPLE.0 * (RIPPLE.1 * u - travel).sin();
        let (sin_turn, cos_turn) = (spin + TWIST.0 * sin_u * swell).sin_cos();
        for j in 0..sides {
            let v = (TAU * f64::from(j) / f64::from(sides)) as f32;
            let (sin_v, cos_v) = v.sin_cos();
            // The ellipse's point, turned: `across` points away from the axis, `up` along y.
            let (x, y) = (TUBE.0 * cos_v, TUBE.1 * sin_v);
            let across = x * cos_turn - y * sin_turn;
            let up = x * sin_turn + y * cos_turn;
            let reach = radius + across;
            positions.push(Vec3::new(reach * cos_u, up, reach * sin_u));
        }
    }
    // The torus's triangles: turning the section keeps their orientation.
    super::indexed(positions, super::torus::ring_triangles(rings, sides))
}
