//! Test support shared by bvh-lab's tests: seeded random scenes, degenerate point sets,
//! independent reference answers (dense sampling, brute force) and the shared data folder.
//!
//! Everything here is generic over [`Vector`], so each check is written once and run in 2D
//! and 3D.

pub mod conformance;
pub mod scenes;

use std::path::PathBuf;

use bvhlab::glam::DVec3;
use bvhlab::prelude::*;
use bvhlab::{Ray, Vector};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A deterministic random generator: the same seed gives the same scene on every machine.
pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A point uniformly in `[-extent, extent]^DIM`.
pub fn random_vector<V: Vector>(rng: &mut ChaCha8Rng, extent: f32) -> V {
    let e = f64::from(extent);
    V::from_dvec3(DVec3::new(
        rng.random_range(-e..=e),
        rng.random_range(-e..=e),
        rng.random_range(-e..=e),
    ))
}

/// A unit direction, uniformly distributed.
pub fn random_direction<V: Vector>(rng: &mut ChaCha8Rng) -> V {
    loop {
        let v: V = random_vector(rng, 1.0);
        let len = v.length();
        if len > 0.1 && len <= 1.0 {
            return v / len;
        }
    }
}

/// A ray from a point in `[-extent, extent]^DIM` in a random direction of random length.
///
/// # Panics
/// Never for a finite `extent`: the direction is non-zero by construction.
pub fn random_ray<V: Vector>(rng: &mut ChaCha8Rng, extent: f32) -> Ray<V> {
    let dir = random_direction::<V>(rng) * rng.random_range(0.25f32..4.0);
    Ray::new(random_vector(rng, extent), dir).expect("random rays are finite and non-zero")
}

/// `n` points in a box of half-size `extent` around a random centre.
pub fn random_cloud<V: Vector>(rng: &mut ChaCha8Rng, n: usize, extent: f32) -> Vec<V> {
    let centre: V = random_vector(rng, extent);
    (0..n)
        .map(|_| centre + random_vector::<V>(rng, extent))
        .collect()
}

/// Point sets that break naive fits: one point, one point repeated, collinear points (with
/// repeats), points on a coordinate plane (3D) or line, a square's (cube's) corners whose
/// covariance has repeated eigenvalues, and points far from the origin.
pub fn degenerate_sets<V: Vector>(rng: &mut ChaCha8Rng) -> Vec<Vec<V>> {
    let p: V = random_vector(rng, 10.0);
    let dir: V = random_direction(rng);
    let line: Vec<V> = (0..12)
        .map(|i| p + dir * (((i * 7) % 5) as f32 * 0.75))
        .collect();
    let mut flat: Vec<V> = (0..20).map(|_| random_vector::<V>(rng, 3.0)).collect();
    for q in &mut flat {
        q.set_coord(V::DIM - 1, 1.5);
    }
    let unit_corners: Vec<V> = bvhlab::Aabb::new(V::splat(-1.0), V::splat(1.0))
        .corners()
        .collect();
    let far: Vec<V> = (0..20)
        .map(|_| V::splat(1.0e4) + random_vector::<V>(rng, 1.0))
        .collect();
    vec![vec![p], vec![p; 5], line, flat, unit_corners, far]
}

/// Checks `interval` (a volume's `ray_interval` answer) against `contains` sampled densely
/// along the ray: inside the interval every sample must be contained, and outside it no
/// sample may be, except within `slack` (in `t`) of the interval's ends where rounding decides.
///
/// # Panics
/// When the two disagree, with the sample that shows it.
pub fn assert_interval_matches_sampling<V: Vector>(
    ray: &Ray<V>,
    interval: Option<(f32, f32)>,
    contains: impl Fn(V) -> bool,
    t_max: f32,
    slack: f32,
) {
    const SAMPLES: usize = 2000;
    for k in 0..=SAMPLES {
        let t = t_max * k as f32 / SAMPLES as f32;
        let inside = contains(ray.at(t));
        let predicted = interval.is_some_and(|(a, b)| a <= t && t <= b);
        let near_end =
            interval.is_some_and(|(a, b)| (t - a).abs() <= slack || (t - b).abs() <= slack);
        assert!(
            inside == predicted || near_end,
            "ray {ray:?}: at t = {t} contains() says {inside} but the interval {interval:?} says {predicted}"
        );
    }
}

/// `../shared/data/meshes` beside the repository, if it is there. Tests that need the real
/// meshes skip with a message when it is absent.
pub fn mesh_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/data/meshes");
    dir.is_dir().then_some(dir)
}

/// A closed triangle mesh: a UV sphere with `rings` x `segments` quads split in two, whose
/// triangles share their vertices exactly (the same `f32` values), as a real mesh does.
pub fn closed_sphere_mesh(radius: f32, rings: usize, segments: usize) -> Vec<Triangle3> {
    use bvhlab::glam::Vec3;
    let vertex = |ring: usize, seg: usize| {
        if ring == 0 {
            return Vec3::new(0.0, 0.0, radius);
        }
        if ring == rings {
            return Vec3::new(0.0, 0.0, -radius);
        }
        let theta = std::f32::consts::PI * ring as f32 / rings as f32;
        let phi = std::f32::consts::TAU * (seg % segments) as f32 / segments as f32;
        Vec3::new(
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        ) * radius
    };
    let mut tris = Vec::new();
    for ring in 0..rings {
        for seg in 0..segments {
            let (a, b) = (vertex(ring, seg), vertex(ring, seg + 1));
            let (c, d) = (vertex(ring + 1, seg), vertex(ring + 1, seg + 1));
            if ring != 0 {
                tris.push(Triangle3::new(a, c, b));
            }
            if ring + 1 != rings {
                tris.push(Triangle3::new(b, c, d));
            }
        }
    }
    tris
}
