//! Test support shared by bvh-lab's tests: seeded random scenes and the shared data folder.

use std::path::PathBuf;

use bvhlab::glam::{Vec2, Vec3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A deterministic random generator: the same seed gives the same scene on every machine.
pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A point uniformly in `[-extent, extent]^2`.
pub fn vec2_in(rng: &mut ChaCha8Rng, extent: f32) -> Vec2 {
    Vec2::new(rng.random_range(-extent..=extent), rng.random_range(-extent..=extent))
}

/// A point uniformly in `[-extent, extent]^3`.
pub fn vec3_in(rng: &mut ChaCha8Rng, extent: f32) -> Vec3 {
    Vec3::new(
        rng.random_range(-extent..=extent),
        rng.random_range(-extent..=extent),
        rng.random_range(-extent..=extent),
    )
}

/// `../shared/data/meshes` beside the repository, if it is there. Tests that need the real
/// meshes skip with a message when it is absent.
pub fn mesh_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/data/meshes");
    dir.is_dir().then_some(dir)
}
