//! The lab's large mesh: a UV sphere pushed in and out by a sum of random plane waves, so it
//! has a million triangles of uneven size and no symmetry for a structure to exploit, and is
//! made in a fraction of a second (a few sines per vertex).

use bvhlab::Mesh;
use bvhlab::glam::Vec3;

use super::random::Random;
use super::uv_sphere::sphere_grid;

/// How many waves displace the sphere.
const WAVES: usize = 8;

/// A UV sphere of `segments` meridians and `bands` bands (as [`uv_sphere`](super::uv_sphere))
/// whose radius in direction `d` is `1 + Σ aₖ sin(fₖ d·uₖ + φₖ)`, over eight waves with random
/// directions `uₖ`, frequencies `fₖ` from 2 to 12, phases `φₖ` and amplitudes `aₖ` falling
/// from 0.08, all from `seed`. The radius stays between 0.6 and 1.4, so the surface stays
/// closed and never crosses the centre.
pub fn lumpy_sphere(segments: u32, bands: u32, seed: u64) -> Mesh {
    let mut random = Random::new(seed);
    let waves: Vec<(Vec3, f32, f32, f32)> = (0..WAVES)
        .map(|k| {
            let direction = random.direction();
            let frequency = random.range(2.0, 12.0);
            let phase = random.range(0.0, std::f32::consts::TAU);
            (direction, frequency, phase, 0.08 / (1.0 + 0.5 * k as f32))
        })
        .collect();
    let (positions, indices) = sphere_grid(segments, bands, |d| {
        let bump: f32 = waves
            .iter()
            .map(|&(u, f, phase, a)| a * (f * d.dot(u) + phase).sin())
            .sum();
        d * (1.0 + bump)
    });
    super::indexed(positions, indices)
}
