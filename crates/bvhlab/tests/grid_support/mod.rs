//! Shared by the grid and quadtree/octree tests: seeded scenes, rays that meet cell boundaries,
//! the comparison of every query against brute force, and a minimal OBJ reader.

#![allow(dead_code, reason = "each test file uses a different part")]

mod check;

pub use check::{check_queries, points_for, rays_for};

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::{Primitive, Segment2, Triangle3, Vector};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A vector with coordinates uniform in `[-scale, scale]`.
pub fn random_vector<V: Vector>(rng: &mut ChaCha8Rng, scale: f32) -> V {
    let mut v = V::ZERO;
    for i in 0..V::DIM {
        v.set_coord(i, rng.random_range(-scale..=scale));
    }
    v
}

/// Applies a function to every vertex.
pub trait Map: Primitive {
    #[must_use]
    fn map(&self, f: impl Fn(Self::Point) -> Self::Point) -> Self;
    /// `n` random primitives of size about `size` in `[-10, 10]^D`.
    fn random(rng: &mut ChaCha8Rng, n: usize, size: f32) -> Vec<Self>;
    /// The scale of the "tiny" scene. 1e-20, except for triangles: at that scale
    /// `Triangle3::ray_hit`'s `f32` products underflow and it reports `t = ±0` for triangles
    /// anywhere on the ray's line, even behind the origin, so brute force's own answers are
    /// wrong there (reported to the lead); 1e-12 is as far as its arithmetic holds.
    const TINY: f32 = 1e-20;
}

impl Map for Segment2 {
    fn map(&self, f: impl Fn(Vec2) -> Vec2) -> Self {
        Segment2::new(f(self.a), f(self.b))
    }
    fn random(rng: &mut ChaCha8Rng, n: usize, size: f32) -> Vec<Self> {
        (0..n)
            .map(|_| {
                let a: Vec2 = random_vector(rng, 10.0);
                Segment2::new(a, a + random_vector::<Vec2>(rng, size))
            })
            .collect()
    }
}

impl Map for Triangle3 {
    const TINY: f32 = 1e-12;
    fn map(&self, f: impl Fn(Vec3) -> Vec3) -> Self {
        Triangle3::new(f(self.a), f(self.b), f(self.c))
    }
    fn random(rng: &mut ChaCha8Rng, n: usize, size: f32) -> Vec<Self> {
        (0..n)
            .map(|_| {
                let a: Vec3 = random_vector(rng, 10.0);
                let b = a + random_vector::<Vec3>(rng, size);
                Triangle3::new(a, b, a + random_vector::<Vec3>(rng, size))
            })
            .collect()
    }
}

impl Map for Vec2 {
    fn map(&self, f: impl Fn(Vec2) -> Vec2) -> Self {
        f(*self)
    }
    fn random(rng: &mut ChaCha8Rng, n: usize, _: f32) -> Vec<Self> {
        (0..n).map(|_| random_vector(rng, 10.0)).collect()
    }
}

impl Map for Vec3 {
    fn map(&self, f: impl Fn(Vec3) -> Vec3) -> Self {
        f(*self)
    }
    fn random(rng: &mut ChaCha8Rng, n: usize, _: f32) -> Vec<Self> {
        (0..n).map(|_| random_vector(rng, 10.0)).collect()
    }
}

/// Named scenes: none, one, a few, many small, long ones spanning many cells, duplicates,
/// flat (last coordinate constant), integer coordinates (they meet cell boundaries and split
/// planes exactly), and the random scene scaled down (`Map::TINY`) and by 1e15 and shifted far away.
pub fn scenes<P: Map>(rng: &mut ChaCha8Rng) -> Vec<(String, Vec<P>)> {
    let many = P::random(rng, 300, 1.5);
    let mut duplicates = P::random(rng, 20, 1.5);
    let copies = duplicates.clone();
    duplicates.extend(copies.iter().copied());
    duplicates.extend(std::iter::repeat_n(copies[0], 15));
    let last = P::Point::DIM - 1;
    let flat = P::random(rng, 150, 3.0)
        .iter()
        .map(|p| {
            p.map(|mut v| {
                v.set_coord(last, 0.5);
                v
            })
        })
        .collect();
    let integer = P::random(rng, 150, 4.0)
        .iter()
        .map(|p| {
            p.map(|mut v| {
                for i in 0..P::Point::DIM {
                    v.set_coord(i, v.coord(i).round());
                }
                v
            })
        })
        .collect();
    let far = P::Point::splat(1e5);
    vec![
        ("empty".into(), Vec::new()),
        ("one".into(), P::random(rng, 1, 1.5)),
        ("a few".into(), P::random(rng, 6, 1.5)),
        ("many".into(), many.clone()),
        ("long".into(), P::random(rng, 60, 12.0)),
        ("duplicates".into(), duplicates),
        ("flat".into(), flat),
        ("integer".into(), integer),
        (
            "tiny".into(),
            many.iter().map(|p| p.map(|v| v * P::TINY)).collect(),
        ),
        (
            "huge".into(),
            many.iter().map(|p| p.map(|v| v * 1e15)).collect(),
        ),
        (
            "far".into(),
            many.iter().map(|p| p.map(|v| v + far)).collect(),
        ),
    ]
}

/// The triangles of an OBJ file (`v` and `f` lines; polygons fanned), or `None` with a
/// message when the shared meshes folder is absent.
pub fn load_mesh(name: &str) -> Option<Vec<Triangle3>> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/meshes")
        .join(name);
    let Ok(text) = std::fs::read_to_string(&path) else {
        eprintln!("skipping: {} not found", path.display());
        return None;
    };
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let c: Vec<f32> = words.take(3).filter_map(|w| w.parse().ok()).collect();
                vertices.push(Vec3::new(c[0], c[1], c[2]));
            }
            Some("f") => {
                let ids: Vec<usize> = words
                    .filter_map(|w| w.split('/').next()?.parse::<usize>().ok())
                    .map(|i| i - 1)
                    .collect();
                for k in 1..ids.len().saturating_sub(1) {
                    triangles.push(Triangle3::new(
                        vertices[ids[0]],
                        vertices[ids[k]],
                        vertices[ids[k + 1]],
                    ));
                }
            }
            _ => {}
        }
    }
    Some(triangles)
}
