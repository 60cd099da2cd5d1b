//! Seeded random numbers for the generated meshes: `ChaCha8` (Bernstein, "`ChaCha`, a variant
//! of Salsa20", 2008), whose output for a seed is fixed by its specification, so a seed gives the
//! same mesh on every platform and with every version of this crate.

use bvhlab::glam::Vec3;
use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{Rng, SeedableRng};

/// A seeded stream of uniform numbers.
pub(super) struct Random(ChaCha8Rng);

impl Random {
    pub(super) fn new(seed: u64) -> Self {
        Self(ChaCha8Rng::seed_from_u64(seed))
    }

    /// Uniform in `[0, 1)`, from the top 24 bits (all an `f32` holds).
    pub(super) fn unit(&mut self) -> f32 {
        (self.0.next_u32() >> 8) as f32 / (1u32 << 24) as f32
    }

    /// Uniform in `[lo, hi)`.
    pub(super) fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform on the unit sphere (Archimedes: height and angle uniform).
    pub(super) fn direction(&mut self) -> Vec3 {
        let z = self.range(-1.0, 1.0);
        let (sin, cos) = (std::f32::consts::TAU * self.unit()).sin_cos();
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * cos, r * sin, z)
    }
}
