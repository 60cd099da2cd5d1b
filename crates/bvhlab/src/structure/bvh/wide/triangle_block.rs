//! Four triangles side by side, and the four-lane test that proves which of them a ray
//! misses.
//!
//! A [`Bvh4`](super::Bvh4) over triangles keeps its leaves' triangles in blocks of four, one
//! array per corner and axis (structure of arrays, 144 bytes), so that the first step of the
//! watertight test (Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection", JCGT
//! 2(1), 2013) runs on four triangles at once, as Embree's and tinybvh's leaves do.
//!
//! The four-lane step moves and shears the corners exactly as
//! [`Triangle3::ray_hit`] does (the same subtractions and multiplies in `f32`, so the same
//! values bit for bit), then takes the three edge values in `f32`. Rounding is monotonic, so
//! an `f32` edge value that is not zero and not NaN has the sign of the exact value, which
//! is the sign the scalar test's `f64` value has: a lane with one negative and one positive
//! edge value is a proven miss, as the scalar test would find. Every other lane (a hit, an
//! edge value rounded to zero, an overflow) goes to the unchanged scalar test, on the
//! triangle read back from the block, so every answer is the scalar test's, bit for bit.
//!
//! Measured on the bunny and the dragon (issue 33, first hits over 307,210 rays of four
//! kinds): with a tree that costs leaves by blocks
//! ([`BvhOptions::for_triangle_blocks`](crate::structure::bvh::BvhOptions::for_triangle_blocks)),
//! 1.01-1.49x as fast as one triangle at a time on the default tree. Written as a loop over
//! the lanes the compiler left the step half scalar; glam's four-lane type made the gain.

use arrayvec::ArrayVec;
use glam::{Vec3, Vec4};

use crate::structure::bvh::volume::SLACK;
use crate::{Ray3, Triangle3};

/// Triangles per block.
pub(super) const BLOCK: usize = 4;

/// Four triangles in structure-of-arrays form: `corners[k][axis][lane]` is coordinate `axis`
/// of corner `k` (a, b, c) of the lane's triangle. A lane past a leaf's last triangle holds
/// NaN corners and is never read: a leaf's count says how many lanes it uses. Two blocks are
/// equal when their coordinates are, bit for bit (so the NaN of a lane left unused is equal
/// to itself, and trees built twice compare equal).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct TriangleBlock {
    corners: [[[f32; BLOCK]; 3]; 3],
}

impl TriangleBlock {
    /// A block of four unused lanes.
    pub(super) const UNUSED: Self = Self {
        corners: [[[f32::NAN; BLOCK]; 3]; 3],
    };

    /// The triangle in `lane`.
    #[inline]
    pub(super) fn triangle(&self, lane: usize) -> Triangle3 {
        let corner = |k: usize| {
            let c = &self.corners[k];
            Vec3::new(c[0][lane], c[1][lane], c[2][lane])
        };
        Triangle3::new(corner(0), corner(1), corner(2))
    }

    /// Puts `triangle` in `lane`.
    pub(super) fn set(&mut self, lane: usize, triangle: &Triangle3) {
        for (k, corner) in [triangle.a, triangle.b, triangle.c].into_iter().enumerate() {
            for axis in 0..3 {
                self.corners[k][axis][lane] = corner[axis];
            }
        }
    }

    /// A bit set for each of the first `used` lanes whose triangle the ray may hit: the
    /// lanes left clear are proven misses (the module's first section says why).
    #[expect(
        clippy::inline_always,
        reason = "the leaf test of the ray walks: out of line it costs a call per block"
    )]
    #[inline(always)]
    pub(super) fn may_hit(&self, ray: &Ray3, used: usize) -> u32 {
        let ([kx, ky, kz], [sx, sy]) = ray.shear().axes_and_shear();
        let origin = ray.origin();
        let (ox, oy, oz) = (
            Vec4::splat(origin[kx]),
            Vec4::splat(origin[ky]),
            Vec4::splat(origin[kz]),
        );
        let (sx, sy) = (Vec4::splat(sx), Vec4::splat(sy));
        let sheared = |k: usize| {
            let c = &self.corners[k];
            let z = Vec4::from_array(c[kz]) - oz;
            (
                (Vec4::from_array(c[kx]) - ox) - sx * z,
                (Vec4::from_array(c[ky]) - oy) - sy * z,
            )
        };
        let ((ax, ay), (bx, by), (cx, cy)) = (sheared(0), sheared(1), sheared(2));
        // The scalar test's edge values, in its order: u = edge(c, b), v = edge(a, c),
        // w = edge(b, a).
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        let negative = u.cmplt(Vec4::ZERO) | v.cmplt(Vec4::ZERO) | w.cmplt(Vec4::ZERO);
        let positive = u.cmpgt(Vec4::ZERO) | v.cmpgt(Vec4::ZERO) | w.cmpgt(Vec4::ZERO);
        let missed = (negative & positive).bitmask();
        !missed & lanes_below(used)
    }
}

impl PartialEq for TriangleBlock {
    fn eq(&self, other: &Self) -> bool {
        let bits = |block: &Self| {
            let coords = block.corners.as_flattened().as_flattened();
            coords
                .iter()
                .map(|c| c.to_bits())
                .collect::<ArrayVec<u32, 36>>()
        };
        bits(self) == bits(other)
    }
}

impl TriangleBlock {
    /// A bit set for each of the first `used` lanes whose triangle may lie within reach of
    /// `point`: the squared distance bound of the triangle's box, fitted as a leaf's box is
    /// fitted ([`NodeVolume::fit`]: its bounds grown by their slack), is not beyond
    /// `reach_sq`. The closest-point walks prune a wide node's lanes by this very rule
    /// (`bound_lanes`), so a lane left clear holds nothing a walk could take: as if each
    /// triangle were a leaf lane of its own, the answers stay brute force's.
    ///
    /// [`NodeVolume::fit`]: crate::structure::bvh::NodeVolume::fit
    #[inline]
    pub(super) fn near_lanes(&self, point: &[f32; 3], reach_sq: f32, used: usize) -> u32 {
        let mut low = [Vec4::ZERO; 3];
        let mut high = [Vec4::ZERO; 3];
        for axis in 0..3 {
            let [a, b, c] = self.corners.map(|corner| Vec4::from_array(corner[axis]));
            low[axis] = a.min(b).min(c);
            high[axis] = a.max(b).max(c);
        }
        // The fit's growth, lane by lane: `SLACK` times the larger magnitude of the box's
        // corners, plus the smallest normal.
        let magnitude = |v: &[Vec4; 3]| v[0].abs().max(v[1].abs()).max(v[2].abs());
        let grow = Vec4::splat(SLACK) * magnitude(&low).max(magnitude(&high))
            + Vec4::splat(f32::MIN_POSITIVE);
        let mut squared = Vec4::ZERO;
        for axis in 0..3 {
            let p = Vec4::splat(point[axis]);
            let clamped = p.max(low[axis] - grow).min(high[axis] + grow);
            let offset = clamped - p;
            squared += offset * offset;
        }
        // NaN must not prune (`!(sq > reach)`), as in `bound_lanes`.
        !squared.cmpgt(Vec4::splat(reach_sq)).bitmask() & lanes_below(used)
    }
}

/// The bits of lanes `0..used` (all four from 4 on).
#[inline]
fn lanes_below(used: usize) -> u32 {
    (1u32 << used.min(BLOCK)) - 1
}
