//! The lane tests of the [`Bvh4`](super::Bvh4) range walk: which of a node's four boxes may
//! share a point with the region, and which lie wholly inside it.
//!
//! A lane that may share a point is entered (its primitives tested one by one); a lane wholly
//! inside is taken whole, every primitive below it without a test. Both tests are
//! conservative the way each needs: the first may keep a box that holds no answer, never
//! drop one that does (it grows the region as the binary tree's walk does); the second may
//! call a box that lies inside "not inside", never the reverse (it shrinks a ball by more
//! than any rounding of the primitives' own tests, see [`inside_squared`]).

use super::layout::{Bvh4Node, WIDTH};
use super::nearest::bound_lanes;
use crate::Vector;
use crate::structure::RangeShape;
use crate::structure::bvh::volume::{GROW, PreparedRange};
use crate::structure::bvh::walk::fast_nearest::reach_squared;
use crate::volume::BoundingVolume;

/// How a node's lanes are tested against the region.
#[derive(Clone, Copy, Debug)]
pub(super) enum LaneTest {
    /// The box's lower and upper corners, per axis.
    Box([f32; 3], [f32; 3]),
    /// The ball's centre, the squared reach of its grown radius (a lane nearer than that
    /// may hold an answer) and the squared inner reach (a lane whose farthest corner is
    /// nearer than that holds only answers).
    Ball {
        center: [f32; 3],
        reach_sq: f32,
        inside_sq: f32,
    },
}

/// Of a node's used lanes: those that may share a point with the region (`touch`), and of
/// those, the ones wholly inside it (`inside`), as bit sets.
#[derive(Clone, Copy, Debug)]
pub(super) struct LaneMasks {
    pub touch: u32,
    pub inside: u32,
}

impl LaneTest {
    /// The test of `shape`, or `None` when it holds nothing (an empty box, a negative or
    /// NaN radius).
    pub(super) fn new<V: Vector>(shape: &RangeShape<V>) -> Option<Self> {
        match shape {
            RangeShape::Box(b) if !b.is_empty() => Some(Self::Box(coords(b.min), coords(b.max))),
            RangeShape::Ball(s) if !s.is_empty() => {
                let prepared = PreparedRange::new(shape);
                let grown = prepared.grown_radius().unwrap_or(s.radius);
                Some(Self::Ball {
                    center: coords(s.center),
                    reach_sq: reach_squared(grown),
                    inside_sq: inside_squared(s.radius, prepared.slack),
                })
            }
            _ => None,
        }
    }

    /// The lanes of `node` that touch the region and those inside it.
    #[inline]
    pub(super) fn lanes<const DIM: usize>(&self, node: &Bvh4Node) -> LaneMasks {
        match self {
            Self::Box(lo, hi) => box_lanes::<DIM>(node, lo, hi),
            Self::Ball {
                center,
                reach_sq,
                inside_sq,
            } => {
                let touch = bound_lanes::<DIM>(node, center, *reach_sq).1;
                let inside = touch & farthest_within::<DIM>(node, center, *inside_sq);
                LaneMasks { touch, inside }
            }
        }
    }
}

/// The used lanes whose boxes overlap the closed box `lo..=hi` (which is not empty), the
/// binary tree's `Aabb::overlaps` lane by lane; and those whose boxes lie inside it on
/// every axis. The comparisons are exact, and a lane's box holds its primitives' bounds
/// (`validate` checks it), so every primitive of an inside lane lies in the region and its
/// exact [`intersects_aabb`](crate::Primitive::intersects_aabb) says so.
#[inline]
fn box_lanes<const DIM: usize>(node: &Bvh4Node, lo: &[f32; 3], hi: &[f32; 3]) -> LaneMasks {
    let mut overlap = [true; WIDTH];
    let mut inside = [true; WIDTH];
    for axis in 0..DIM {
        let (min, max) = (&node.planes[0][axis], &node.planes[1][axis]);
        for lane in 0..WIDTH {
            overlap[lane] &= min[lane] <= hi[axis] && lo[axis] <= max[lane];
            inside[lane] &= lo[axis] <= min[lane] && max[lane] <= hi[axis];
        }
    }
    let mut masks = LaneMasks {
        touch: 0,
        inside: 0,
    };
    for lane in 0..WIDTH {
        // An unused lane holds the empty box, which overlaps nothing.
        let used = node.planes[0][0][lane] <= node.planes[1][0][lane];
        masks.touch |= u32::from(overlap[lane] && used) << lane;
        masks.inside |= u32::from(overlap[lane] && inside[lane] && used) << lane;
    }
    masks
}

/// The lanes whose farthest corner from `point` has a computed squared distance of at most
/// `inside_sq` (an unused lane's empty box gives `-inf` offsets, so `+inf`; a NaN never
/// passes).
///
/// Per axis the farthest plane is at `max(p - lo, hi - p)` (for `lo <= hi` the larger of the
/// two is the absolute offset of the farther plane). Each of the two subtractions, the
/// squares and the sum rounds to nearest, so the computed sum is at least the exact one
/// divided by `(1 + 2^-24)^5`, less a few subnormal steps when it underflows;
/// [`inside_squared`] leaves room for both.
#[inline]
fn farthest_within<const DIM: usize>(node: &Bvh4Node, point: &[f32; 3], inside_sq: f32) -> u32 {
    let mut squared = [0.0f32; WIDTH];
    for (axis, &p) in point.iter().enumerate().take(DIM) {
        for (lane, sq) in squared.iter_mut().enumerate() {
            let below = p - node.planes[0][axis][lane];
            let above = node.planes[1][axis][lane] - p;
            // Comparisons rather than `f32::max`, for the same reason as `bound_lanes`.
            let far = if below > above { below } else { above };
            *sq += far * far;
        }
    }
    let mut mask = 0;
    for (lane, &sq) in squared.iter().enumerate() {
        mask |= u32::from(sq <= inside_sq) << lane;
    }
    mask
}

/// The squared inner reach of a ball of `radius` whose query slack is `slack`
/// ([`PreparedRange::slack`]): a lane box whose farthest corner has a computed squared
/// distance of at most this lies, with every primitive in it, within `radius / GROW - slack`
/// of the centre; `-inf` when that is not positive (radius 0, or tiny).
///
/// Why every such primitive is an answer, that is `prim.distance(center) <= radius` as
/// [`RangeShape::overlaps_primitive`] computes it: the primitive lies in its bounds, which
/// lie in the lane box, so its exact distance is at most the farthest corner's, and the
/// primitive's coordinates are no larger than the ball's box's (which sizes `slack`). Its
/// computed distance exceeds the exact one by a few units in the last place of the distance
/// and of the coordinates at most (the [`Primitive`](crate::Primitive) contract: rounding of
/// a few ulps of the coordinates), far less than the `SLACK` of both taken off here. The
/// relative `4e-6` and the eight subnormal steps cover the rounding of the corner's squared
/// distance ([`farthest_within`]) and of this square. A reach that overflows is held to
/// `f32::MAX`, so a corner whose square overflows is never called inside.
pub(super) fn inside_squared(radius: f32, slack: f32) -> f32 {
    let inner = radius / GROW - slack;
    if inner.is_nan() || inner <= 0.0 {
        return f32::NEG_INFINITY;
    }
    (inner * inner * (1.0 - 4e-6) - 8.0 * f32::from_bits(1)).min(f32::MAX / 2.0)
}

/// A point's coordinates as the lane tests read them (unused axes 0).
pub(super) fn coords<V: Vector>(point: V) -> [f32; 3] {
    let mut c = [0.0; 3];
    for (axis, value) in c.iter_mut().enumerate().take(V::DIM) {
        *value = point.coord(axis);
    }
    c
}
