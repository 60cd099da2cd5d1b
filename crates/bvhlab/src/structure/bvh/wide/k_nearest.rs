//! The k nearest primitives in a [`Bvh4`]: the closest-point walk of `nearest.rs` with the
//! k best so far in a [`NearestSet`] instead of one best in registers.
//!
//! The same four-lane squared bound ([`bound_lanes`]), the same order (a node's leaf lanes
//! where it is met, its inner lanes nearest first) and the same pruning rule with the k-th
//! best distance in place of the best: a child is skipped when its squared bound exceeds
//! the square of the k-th best distance times [`GROW`] plus the query's slack, with room for
//! rounding ([`reach_squared`]); while fewer than k are known, nothing is skipped. This never
//! skips a node the binary tree's k-nearest walk visits (it compares unsquared distances
//! with the same reach), each primitive's distance is computed as there, and the set keeps
//! the least `(distance, index)` whatever the order they are offered in, so the answer is the
//! binary tree's, bit for bit (Roussopoulos, Kelley and Vincent, "Nearest Neighbor Queries",
//! SIGMOD 1995, for the depth-first branch and bound).

use super::layout::Bvh4;
use super::nearest::{bound_lanes, leaf_lanes, within};
use super::stack::{LaneStack, visit_nearest};
use crate::primitive::contract;
use crate::structure::bvh::volume::{GROW, query_slack};
use crate::structure::bvh::walk::fast_nearest::reach_squared;
use crate::structure::{Nearest, NearestSet};
use crate::{Primitive, Vector};

impl<P: Primitive> Bvh4<P> {
    /// The `k` primitives nearest to `point`, nearest first, ties by the lower index (none
    /// for `k = 0` or a non-finite point; all of them when `k` exceeds the count): what the
    /// binary tree's [`k_nearest`](crate::SpatialQuery::k_nearest) answers, bit
    /// for bit. For `k = 1`, [`closest_point`](Self::closest_point) gives the same answer
    /// faster.
    pub fn k_nearest(&self, point: P::Point, k: usize) -> Vec<Nearest<P::Point>> {
        if self.nodes.is_empty() || k == 0 || !point.is_finite() {
            return Vec::new();
        }
        self.k_nearest_walk(point, k)
    }

    /// The walk.
    fn k_nearest_walk(&self, point: P::Point, k: usize) -> Vec<Nearest<P::Point>> {
        let slack = query_slack(point);
        let mut coords = [0.0; 3];
        for (axis, c) in coords.iter_mut().enumerate().take(P::Point::DIM) {
            *c = point.coord(axis);
        }
        let mut best = NearestSet::new(k);
        // The square of what a box's bound may be and still hold something as near as the
        // k-th best (infinite while fewer than k are known).
        let mut reach_sq = f32::INFINITY;
        let mut stack = LaneStack::new();
        let mut current = 0u32;
        loop {
            let node = &self.nodes[current as usize];
            let (squared, mask) = if P::Point::DIM == 3 {
                bound_lanes::<3>(node, &coords, reach_sq)
            } else {
                bound_lanes::<2>(node, &coords, reach_sq)
            };
            let leaves = mask & leaf_lanes(node);
            let mut bits = leaves;
            while bits != 0 {
                let lane = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let start = node.child[lane] as usize;
                let slots = start..start + node.count[lane] as usize;
                let ids = &self.leaf_ids;
                self.leaf_prims
                    .each_near(slots, &coords, &mut reach_sq, |slot, prim| {
                        let q = contract::project_point(prim, point);
                        let distance = (q - point).length();
                        best.offer(ids[slot] as usize, q, distance)
                            .then(|| reach_squared(best.bound() * GROW + slack))
                    });
            }
            let inner = (mask & !leaves) & within(&squared, reach_sq);
            if inner != 0 {
                current = visit_nearest(node, inner, &squared, &mut stack).child;
                continue;
            }
            // Pop the next waiting child the k-th best has not moved in front of.
            loop {
                let Some(waiting) = stack.pop() else {
                    return best.into_vec();
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
