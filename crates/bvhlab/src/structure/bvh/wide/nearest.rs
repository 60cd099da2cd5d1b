//! The closest point in a [`Bvh4`]: the squared distance bound of four boxes at once, then
//! the boxes that may hold something nearer than the best, nearest first.
//!
//! The four-lane bound is the box's
//! [`distance_bound_squared`] over fixed-size
//! arrays, one lane per child (clamp the point into the box, sum the squared offsets in axis
//! order), which the compiler turns into vector instructions.
//!
//! A node's leaf lanes are tested where the node is met, before its inner lanes are
//! ordered and pushed: a leaf lane on the stack would cost a push, a pop and a branch on
//! its kind, and a better best found in it prunes the node's inner lanes before they are
//! pushed. Only inner nodes wait on the stack. On the peer workload (1M random points
//! around ogre.obj) this is about 4% faster than pushing leaf lanes; the walk then meets 47
//! wide nodes and 53 triangles per query, and most of its time goes to cache misses on them
//! and to mispredicted branches, not to the triangle test.
//!
//! The answer is the binary walks' (fast and observed), bit for bit: the same primitive
//! distance, the same pruning rule as the binary fast walk (a child is skipped when its
//! squared bound exceeds the square of the best distance times [`GROW`] plus the query's
//! slack, with room for rounding), and the best is the least `(distance, index)` over every
//! primitive not pruned, whatever the order they are met in.
//!
//! Where the triangle tests go (issue 33, 100,000 of the peer workload's points, counted in
//! the walk): on the tree of four-triangle blocks the walk projects 81, 55 and 50 triangles
//! a query onto the bunny, the dragon and the ogre, and only 8, 9 and 7 of them become the
//! best; `perf` puts a third of the time (ogre) in the projection. Tried and not kept:
//! - taking a leaf's triangles nearest box first: 2-7% fewer projections;
//! - skipping a triangle whose plane (in `f64`) is farther than the reach: 3-8 fewer a
//!   query;
//! - a four-lane `f32` lower bound per block, the plane's distance with the distance outside
//!   the farthest edge line, each lowered by a margin far above its rounding (used only on
//!   well-shaped triangles): it spared 17-38 projections a query, and the walk was
//!   1.00-1.04x as fast (one core, old and new binaries alternately three times, medians):
//!   the projections it spared saved about what computing it cost.
//!
//! Sparing most of the rest would need the exact distance of four triangles at once
//! (corners included); the walk itself, whose samples sit on the loads of nodes and blocks,
//! takes the other two thirds.
//!
//! [`distance_bound_squared`]: crate::structure::bvh::NodeVolume::distance_bound_squared

use super::layout::{Bvh4, Bvh4Node, WIDTH};
use super::stack::{LaneStack, visit_nearest};
use crate::structure::Nearest;
use crate::structure::bvh::volume::{GROW, query_slack};
use crate::structure::bvh::walk::fast_nearest::{Best, reach_squared};
use crate::{Primitive, Vector};

/// The squared distance bounds of the four children's boxes, and a bit set for each lane
/// that is used and whose bound is not beyond `reach_sq` (a NaN bound is kept, as the
/// binary walk keeps it; an unused lane's empty box has `min > max`).
#[expect(
    clippy::inline_always,
    reason = "the hot step of the walk: left out of line it costs a call per node (measured)"
)]
#[inline(always)]
pub(super) fn bound_lanes<const DIM: usize>(
    node: &Bvh4Node,
    point: &[f32; 3],
    reach_sq: f32,
) -> ([f32; WIDTH], u32) {
    let mut squared = [0.0f32; WIDTH];
    for (axis, &p) in point.iter().enumerate().take(DIM) {
        for (lane, sq) in squared.iter_mut().enumerate() {
            // The clamp as comparisons, not `f32::max`/`min`: no operand is NaN (the point
            // is finite, the planes finite or infinite), so the value is theirs, and each
            // is one instruction (`maxps`/`minps`; SIMD128's `pmax`/`pmin`), where WebAssembly
            // has no NaN-ignoring minimum and calls `fminf`/`fmaxf` (a third of its time).
            let (lo, hi) = (node.planes[0][axis][lane], node.planes[1][axis][lane]);
            let clamped = if p < lo { lo } else { p };
            let clamped = if clamped > hi { hi } else { clamped };
            let offset = clamped - p;
            *sq += offset * offset;
        }
    }
    let mut mask = 0;
    for (lane, &sq) in squared.iter().enumerate() {
        #[expect(clippy::neg_cmp_op_on_partial_ord, reason = "NaN must not prune")]
        let kept = !(sq > reach_sq) && node.planes[0][0][lane] <= node.planes[1][0][lane];
        mask |= u32::from(kept) << lane;
    }
    (squared, mask)
}

impl<P: Primitive> Bvh4<P> {
    /// The primitive nearest to `point` (ties by the lower index), none for a non-finite
    /// point: what the binary tree's
    /// [`closest_point`](crate::PointQuery::closest_point) answers, bit for bit.
    pub fn closest_point(&self, point: P::Point) -> Option<Nearest<P::Point>> {
        if self.nodes.is_empty() || !point.is_finite() {
            return None;
        }
        self.closest_walk(point)
    }

    /// The walk.
    fn closest_walk(&self, point: P::Point) -> Option<Nearest<P::Point>> {
        let slack = query_slack(point);
        let mut coords = [0.0; 3];
        for (axis, c) in coords.iter_mut().enumerate().take(P::Point::DIM) {
            *c = point.coord(axis);
        }
        let mut best = Best::<P::Point>::NONE;
        // The square of what a box's bound may be and still hold something as near as the
        // best, with room for rounding (`reach_squared`).
        let mut reach_sq = f32::INFINITY;
        // Inner nodes waiting, with their squared bounds.
        let mut stack = LaneStack::new();
        let mut current = 0u32;
        loop {
            let node = &self.nodes[current as usize];
            let (squared, mask) = if P::Point::DIM == 3 {
                bound_lanes::<3>(node, &coords, reach_sq)
            } else {
                bound_lanes::<2>(node, &coords, reach_sq)
            };
            // Leaf lanes first, in lane order (the order changes only the work, not the
            // answer); one that a better best from the lanes before it has put out of
            // reach is skipped (2-5% on the peer workload's points, bunny and dragon;
            // taking the leaf lanes nearest first instead was no faster).
            let leaves = mask & leaf_lanes(node);
            let mut bits = leaves;
            while bits != 0 {
                let lane = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                if squared[lane] > reach_sq {
                    continue;
                }
                let start = node.child[lane] as usize;
                let range = start..start + node.count[lane] as usize;
                let ids = &self.leaf_ids;
                self.leaf_prims
                    .each_near(range, &coords, &mut reach_sq, |slot, prim| {
                        best.test(prim, ids[slot], point)
                            .then(|| reach_squared(best.distance * GROW + slack))
                    });
            }
            // The inner lanes still in reach of a best the leaves may have improved.
            let inner = (mask & !leaves) & within(&squared, reach_sq);
            if inner != 0 {
                current = visit_nearest(node, inner, &squared, &mut stack).child;
                continue;
            }
            // Pop the next waiting child the best has not moved in front of.
            loop {
                let Some(waiting) = stack.pop() else {
                    return best.into_nearest();
                };
                #[expect(clippy::neg_cmp_op_on_partial_ord, reason = "NaN must not prune")]
                if !(waiting.key > reach_sq) {
                    current = waiting.child;
                    break;
                }
            }
        }
    }
}

/// The lanes of `node` that are leaves, as a bit set.
#[inline]
pub(super) fn leaf_lanes(node: &Bvh4Node) -> u32 {
    let mut mask = 0;
    for (lane, &count) in node.count.iter().enumerate() {
        mask |= u32::from(count > 0) << lane;
    }
    mask
}

/// The lanes whose squared bound is not beyond `reach_sq`, as a bit set (NaN kept).
#[inline]
pub(super) fn within(squared: &[f32; WIDTH], reach_sq: f32) -> u32 {
    let mut mask = 0;
    for (lane, &sq) in squared.iter().enumerate() {
        #[expect(clippy::neg_cmp_op_on_partial_ord, reason = "NaN must not prune")]
        let kept = !(sq > reach_sq);
        mask |= u32::from(kept) << lane;
    }
    mask
}
