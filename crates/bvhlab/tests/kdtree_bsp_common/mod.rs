//! Scenes shared by the k-d tree and BSP tree tests: random and degenerate primitive sets in
//! 2D and 3D, and the real meshes. The checks against brute force are in `check.rs`.
#![allow(
    dead_code,
    reason = "the k-d tree and the BSP tests use different parts of this module"
)]

pub mod check;

use std::path::PathBuf;

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::{Mesh, Vector};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A point uniformly in `[-extent, extent]^DIM`.
pub fn random_vector<V: Vector>(rng: &mut ChaCha8Rng, extent: f32) -> V {
    let mut v = V::ZERO;
    for i in 0..V::DIM {
        v.set_coord(i, rng.random_range(-extent..=extent));
    }
    v
}

/// A point with integer coordinates in `[-n, n]` (lots of shared coordinates: split ties).
pub fn lattice_vector<V: Vector>(rng: &mut ChaCha8Rng, n: i32) -> V {
    let mut v = V::ZERO;
    for i in 0..V::DIM {
        v.set_coord(i, rng.random_range(-n..=n) as f32);
    }
    v
}

/// A primitive the tests can make at random, from a few points.
pub trait Sample: Primitive {
    /// A primitive with its vertices near `at`, within `size`.
    fn near(rng: &mut ChaCha8Rng, at: Self::Point, size: f32) -> Self;
    /// A primitive from vertices picked by `vertex`.
    fn from_vertices(vertex: impl FnMut() -> Self::Point) -> Self;
    /// The primitive with every vertex mapped.
    #[must_use]
    fn map(&self, f: impl Fn(Self::Point) -> Self::Point) -> Self;
}

impl Sample for Segment2 {
    fn near(rng: &mut ChaCha8Rng, at: Vec2, size: f32) -> Self {
        Segment2::new(at, at + random_vector::<Vec2>(rng, size))
    }
    fn from_vertices(mut vertex: impl FnMut() -> Vec2) -> Self {
        Segment2::new(vertex(), vertex())
    }
    fn map(&self, f: impl Fn(Vec2) -> Vec2) -> Self {
        Segment2::new(f(self.a), f(self.b))
    }
}

impl Sample for Triangle3 {
    fn near(rng: &mut ChaCha8Rng, at: Vec3, size: f32) -> Self {
        let b = at + random_vector::<Vec3>(rng, size);
        Triangle3::new(at, b, at + random_vector::<Vec3>(rng, size))
    }
    fn from_vertices(mut vertex: impl FnMut() -> Vec3) -> Self {
        Triangle3::new(vertex(), vertex(), vertex())
    }
    fn map(&self, f: impl Fn(Vec3) -> Vec3) -> Self {
        Triangle3::new(f(self.a), f(self.b), f(self.c))
    }
}

impl Sample for Vec2 {
    fn near(_: &mut ChaCha8Rng, at: Vec2, _: f32) -> Self {
        at
    }
    fn from_vertices(mut vertex: impl FnMut() -> Vec2) -> Self {
        vertex()
    }
    fn map(&self, f: impl Fn(Vec2) -> Vec2) -> Self {
        f(*self)
    }
}

impl Sample for Vec3 {
    fn near(_: &mut ChaCha8Rng, at: Vec3, _: f32) -> Self {
        at
    }
    fn from_vertices(mut vertex: impl FnMut() -> Vec3) -> Self {
        vertex()
    }
    fn map(&self, f: impl Fn(Vec3) -> Vec3) -> Self {
        f(*self)
    }
}

/// Named scenes of primitives `P`, random and degenerate, from `seed`.
pub fn scenes<P: Sample>(seed: u64) -> Vec<(&'static str, Vec<P>)> {
    let mut r = rng(seed);
    let random: Vec<P> = (0..300)
        .map(|_| {
            let at = random_vector(&mut r, 10.0);
            P::near(&mut r, at, 1.5)
        })
        .collect();
    let long: Vec<P> = (0..80)
        .map(|_| {
            let at = random_vector(&mut r, 10.0);
            P::near(&mut r, at, 10.0)
        })
        .collect();
    let lattice: Vec<P> = (0..250)
        .map(|_| P::from_vertices(|| lattice_vector(&mut r, 6)))
        .collect();
    let mut duplicates: Vec<P> = random[..40].to_vec();
    duplicates.extend_from_slice(&random[..40]);
    duplicates.extend(std::iter::repeat_n(random[0], 30));
    // Everything in the plane (line, in 2D) `x_last = 0`: a split plane of its own.
    let last = P::Point::DIM - 1;
    let flat: Vec<P> = random
        .iter()
        .take(150)
        .map(|p| {
            p.map(|mut v| {
                v.set_coord(last, 0.0);
                v
            })
        })
        .collect();
    let scale = |s: f32| -> Vec<P> { random.iter().take(100).map(|p| p.map(|v| v * s)).collect() };
    let collapsed: Vec<P> = random
        .iter()
        .take(60)
        .map(|p| P::from_vertices(|| p.centroid()))
        .collect();
    vec![
        ("random", random.clone()),
        ("long", long),
        ("lattice", lattice),
        ("duplicates", duplicates),
        ("flat", flat),
        ("huge", scale(1.0e30)),
        ("tiny", scale(1.0e-30)),
        ("collapsed", collapsed),
        ("one", random[..1].to_vec()),
        ("none", Vec::new()),
    ]
}

/// A height field of `n × n` quads, two triangles each: shared edges and vertices everywhere,
/// many vertices on common coordinates.
pub fn height_field(n: usize, rng: &mut ChaCha8Rng) -> Vec<Triangle3> {
    let heights: Vec<f32> = (0..(n + 1) * (n + 1))
        .map(|_| rng.random_range(-0.5f32..0.5))
        .collect();
    let vertex = |i: usize, j: usize| Vec3::new(i as f32, heights[i * (n + 1) + j], j as f32);
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..n {
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

/// A closed polyline of `n` segments on a circle: shared end points everywhere.
pub fn polygon(n: usize, radius: f32) -> Vec<Segment2> {
    let at = |i: usize| Vec2::from_angle(std::f32::consts::TAU * i as f32 / n as f32) * radius;
    (0..n).map(|i| Segment2::new(at(i), at(i + 1))).collect()
}

/// The triangles of a mesh from the shared data folder, or `None` (with a message) when the
/// folder is absent.
pub fn load_mesh(name: &str) -> Option<Vec<Triangle3>> {
    let path: PathBuf = [
        env!("CARGO_MANIFEST_DIR"),
        "..",
        "..",
        "..",
        "shared",
        "data",
    ]
    .iter()
    .collect::<PathBuf>()
    .join("meshes")
    .join(name);
    let Ok(bytes) = std::fs::read(&path) else {
        eprintln!("skipping {name}: {} is not there", path.display());
        return None;
    };
    let mesh = Mesh::from_obj(&bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
    Some(mesh.triangles().to_vec())
}
