//! Welding a triangle soup: corners at the same place become one shared vertex.
//!
//! STL stores every triangle with its own three corners, so a closed surface arrives as
//! separate triangles. Merging corners whose coordinates are bit-for-bit equal (with −0 taken
//! as +0) gives back the shared vertices, so the lab's vertex count means what it says and a
//! closed surface is closed again. Nothing is merged that is not exactly equal: welding within
//! a tolerance would change the geometry.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use bvhlab::glam::Vec3;

/// Shared vertices, built one corner at a time.
#[derive(Default)]
pub(crate) struct Welder {
    index: HashMap<[u32; 3], u32, BuildHasherDefault<Mix>>,
    positions: Vec<Vec3>,
}

impl Welder {
    /// The index of the vertex at `p` (finite), adding it if it is new.
    pub(crate) fn vertex(&mut self, p: Vec3) -> u32 {
        // −0 and +0 compare equal but have different bits: weld them.
        let key = (p + Vec3::ZERO).to_array().map(f32::to_bits);
        let next = self.positions.len() as u32;
        let index = *self.index.entry(key).or_insert(next);
        if index == next {
            self.positions.push(p);
        }
        index
    }

    /// The distinct positions, in the order they first came.
    pub(crate) fn into_positions(self) -> Vec<Vec3> {
        self.positions
    }
}

/// A fast hasher for three 32-bit keys (Fibonacci hashing: multiply by 2⁶⁴/φ and rotate),
/// where `HashMap`'s default, built to resist chosen keys, costs several times more. The keys
/// come from one file the student chose, so there is no adversary to resist.
#[derive(Default)]
pub(crate) struct Mix(u64);

impl Hasher for Mix {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }

    fn write_u32(&mut self, word: u32) {
        self.write_u64(u64::from(word));
    }

    fn write_u64(&mut self, word: u64) {
        self.0 = (self.0.rotate_left(26) ^ word).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_corners_share_a_vertex() {
        let mut welder = Welder::default();
        let a = welder.vertex(Vec3::new(1.0, 2.0, 3.0));
        let b = welder.vertex(Vec3::new(1.0, 2.0, 3.5));
        let c = welder.vertex(Vec3::new(1.0, 2.0, 3.0));
        let zero = welder.vertex(Vec3::ZERO);
        let negative_zero = welder.vertex(Vec3::new(-0.0, 0.0, -0.0));
        assert_eq!((a, b, c, zero, negative_zero), (0, 1, 0, 2, 2));
        assert_eq!(welder.into_positions().len(), 3);
    }
}
