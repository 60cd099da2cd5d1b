//! Helpers shared by the BVH tests: primitives that can be generated and mapped, rays and
//! points that hit the hard cases, and the check of every query against brute force.
#![allow(
    dead_code,
    unused_imports,
    reason = "each test file uses a different part of this module"
)]

pub mod checks;
pub mod rays;
pub mod scenes;

pub use checks::{
    Budget, Checked, TreeBits, assert_counts, check_collide, check_ray, check_scene, check_tree,
    tree_bits,
};
pub use rays::{plausible_hit, points_for, rays_for};

use bvhlab::Aabb;
use bvhlab::glam::{DVec3, Vec2, Vec3};
use bvhlab::prelude::*;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A shared mesh's triangles (`../shared/data/meshes` beside the repository), or `None`
/// with a message when that folder is absent (the tests then skip the mesh).
pub fn shared_mesh(name: &str) -> Option<Vec<Triangle3>> {
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/meshes")
        .join(name);
    let Ok(bytes) = std::fs::read(&path) else {
        eprintln!("skipping {name}: {} is absent", path.display());
        return None;
    };
    let mesh = Mesh::from_obj(&bytes).unwrap_or_else(|e| panic!("{name} loads: {e}"));
    Some(mesh.triangles().to_vec())
}

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

/// A primitive the tests can generate at random and move vertex by vertex.
pub trait TestPrim: Primitive {
    /// A small random primitive near a point in `[-extent, extent]^DIM`.
    fn random(rng: &mut ChaCha8Rng, extent: f32) -> Self;
    /// The primitive with every vertex mapped.
    #[must_use]
    fn map(&self, f: impl Fn(Self::Point) -> Self::Point) -> Self;
}

impl TestPrim for Segment2 {
    fn random(rng: &mut ChaCha8Rng, extent: f32) -> Self {
        let a: Vec2 = random_vector(rng, extent);
        Segment2::new(a, a + random_vector::<Vec2>(rng, 0.15 * extent))
    }
    fn map(&self, f: impl Fn(Vec2) -> Vec2) -> Self {
        Segment2::new(f(self.a), f(self.b))
    }
}

impl TestPrim for Triangle3 {
    fn random(rng: &mut ChaCha8Rng, extent: f32) -> Self {
        let a: Vec3 = random_vector(rng, extent);
        let b = a + random_vector::<Vec3>(rng, 0.15 * extent);
        Triangle3::new(a, b, a + random_vector::<Vec3>(rng, 0.15 * extent))
    }
    fn map(&self, f: impl Fn(Vec3) -> Vec3) -> Self {
        Triangle3::new(f(self.a), f(self.b), f(self.c))
    }
}

impl TestPrim for Vec2 {
    fn random(rng: &mut ChaCha8Rng, extent: f32) -> Self {
        random_vector(rng, extent)
    }
    fn map(&self, f: impl Fn(Vec2) -> Vec2) -> Self {
        f(*self)
    }
}

impl TestPrim for Vec3 {
    fn random(rng: &mut ChaCha8Rng, extent: f32) -> Self {
        random_vector(rng, extent)
    }
    fn map(&self, f: impl Fn(Vec3) -> Vec3) -> Self {
        f(*self)
    }
}

/// The box around the scene and a length scale for it (at least a tiny positive number).
pub fn scene_box<P: Primitive>(prims: &[P]) -> (Aabb<P::Point>, f32) {
    let bounds = prims
        .iter()
        .filter(|p| p.vertices().all(Vector::is_finite))
        .fold(Aabb::EMPTY, |b, p| b.merge(&p.bounds()));
    if bounds.is_empty() {
        return (Aabb::new(P::Point::splat(-1.0), P::Point::splat(1.0)), 1.0);
    }
    let size = bounds.size().max_element();
    (
        bounds,
        size.max(bounds.center().abs().max_element() * 1e-6)
            .max(1e-30),
    )
}
