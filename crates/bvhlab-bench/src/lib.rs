//! Benchmark scenes for bvh-lab: procedural meshes with fixed parameters (and seeds), the
//! shared real meshes when present, and camera rays; [`workload`] puts them together into the
//! inputs of the comparison with peer libraries (issue 7), natively and in WebAssembly.

pub mod rng;
pub mod scenes;
pub mod workload;

use std::path::PathBuf;

use rng::SplitMix64;

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::{Ray3, Segment2, Triangle3};

/// A torus of `2 · rings · sides` triangles around the z axis.
pub fn torus(major: f32, minor: f32, rings: usize, sides: usize) -> Vec<Triangle3> {
    let vertex = |i: usize, j: usize| {
        let u = std::f32::consts::TAU * (i % rings) as f32 / rings as f32;
        let v = std::f32::consts::TAU * (j % sides) as f32 / sides as f32;
        let r = major + minor * v.cos();
        Vec3::new(r * u.cos(), r * u.sin(), minor * v.sin())
    };
    let mut tris = Vec::with_capacity(2 * rings * sides);
    for i in 0..rings {
        for j in 0..sides {
            let (a, b, c, d) = (
                vertex(i, j),
                vertex(i + 1, j),
                vertex(i + 1, j + 1),
                vertex(i, j + 1),
            );
            tris.push(Triangle3::new(a, b, c));
            tris.push(Triangle3::new(a, c, d));
        }
    }
    tris
}

/// A torus with about `n` triangles.
pub fn torus_with(n: usize) -> Vec<Triangle3> {
    let sides = ((n as f32 / 8.0).sqrt() as usize).max(3);
    let rings = (n / (2 * sides)).max(3);
    torus(1.0, 0.3, rings, sides)
}

/// `n` random segments in the unit square, from a fixed-seed generator (2D scenes).
pub fn random_segments(n: usize, seed: u64) -> Vec<Segment2> {
    let mut rng = SplitMix64::new(seed);
    let mut next = move || rng.next_f32();
    let length = 2.0 / (n as f32).sqrt();
    (0..n)
        .map(|_| {
            let a = Vec2::new(next(), next());
            Segment2::new(a, a + (Vec2::new(next(), next()) - 0.5) * length)
        })
        .collect()
}

/// Primary rays of a pinhole camera at `eye` looking at `target`, `width × height` of them.
pub fn camera_rays(eye: Vec3, target: Vec3, width: usize, height: usize) -> Vec<Ray3> {
    let forward = (target - eye).normalize();
    let right = forward.cross(Vec3::Z).normalize_or(Vec3::X);
    let up = right.cross(forward);
    let mut rays = Vec::with_capacity(width * height);
    for y in 0..height {
        for x in 0..width {
            let u = (x as f32 + 0.5) / width as f32 * 2.0 - 1.0;
            let v = (y as f32 + 0.5) / height as f32 * 2.0 - 1.0;
            let dir = forward + right * (u * 0.6) + up * (v * 0.6 * height as f32 / width as f32);
            if let Ok(ray) = Ray3::new(eye, dir) {
                rays.push(ray);
            }
        }
    }
    rays
}

/// `../shared/data/meshes/NAME` beside the repository, if present.
pub fn shared_mesh(name: &str) -> Option<PathBuf> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/meshes")
        .join(name);
    path.is_file().then_some(path)
}
