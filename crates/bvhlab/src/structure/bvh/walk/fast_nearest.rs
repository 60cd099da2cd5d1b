//! The unobserved closest point: the k-nearest walk of `nearest.rs` for `k = 1`,
//! without the bookkeeping that only the lab needs.
//!
//! The observed walk keeps the k best in a [`NearestSet`](crate::structure::NearestSet) (a
//! vector, allocated per query), each waiting node's depth, and counts every test. For one
//! nearest primitive the best so far is a single value in registers, the nearer child is
//! visited next without touching the stack, and only the farther one waits.
//!
//! Nodes are compared by their squared bound ([`NodeVolume::distance_bound_squared`]), which
//! saves a square root per node test.
//!
//! The answer is the observed walk's, bit for bit: the same primitive distance, a pruning
//! rule that skips no node the observed walk visits (it skips a node when its bound exceeds
//! the best distance times [`GROW`] plus the query's slack; here the squares are compared
//! with room for their rounding, so a node on the edge may be visited in vain), and the best
//! is the least `(distance, index)` over every primitive not pruned, whatever the order they
//! are met in.

use crate::primitive::contract;
use crate::structure::Nearest;
use crate::structure::bvh::volume::{GROW, NodeVolume, query_slack};
use crate::structure::bvh::{Bvh, MAX_DEPTH};
use crate::{Primitive, Vector};

/// One waiting sibling per level, plus room for the root.
const CAPACITY: usize = MAX_DEPTH + 2;

impl<B, P> Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// The primitive nearest to `point` (ties by index), none for a non-finite point: what
    /// `k_nearest_impl(point, 1, &mut ())` answers, found faster.
    pub(in crate::structure::bvh) fn closest_point_fast(
        &self,
        point: P::Point,
    ) -> Option<Nearest<P::Point>> {
        if self.nodes.is_empty() || !point.is_finite() {
            return None;
        }
        // The primitives' distances are rounded at the query point's scale.
        let slack = query_slack(point);
        let mut best = Best::NONE;
        // The square of what a node's bound may be and still hold something as near as the
        // best, with room for rounding (`reach_squared`).
        let mut reach_sq = f32::INFINITY;
        // Written as the observed walk's rule, `bound > reach` prunes, so that a NaN bound
        // is kept as it is there.
        #[expect(clippy::neg_cmp_op_on_partial_ord, reason = "NaN must not prune")]
        let bound = |node: u32, reach_sq: f32| {
            let squared = self.nodes[node as usize]
                .volume
                .distance_bound_squared(point);
            (!(squared > reach_sq)).then_some(squared)
        };
        bound(0, reach_sq)?;
        let mut stack = [(0u32, 0.0f32); CAPACITY];
        let mut len = 0;
        let mut current = 0u32;
        loop {
            let node = &self.nodes[current as usize];
            if node.is_leaf() {
                let range = node.leaf_range();
                let leaf = self.leaf_prims[range.clone()].iter().copied();
                if best.test_leaf(leaf.zip(self.leaf_ids[range].iter().copied()), point) {
                    reach_sq = reach_squared(best.distance * GROW + slack);
                }
            } else {
                let (first, second) = (current + 1, node.start);
                match (bound(first, reach_sq), bound(second, reach_sq)) {
                    (Some(d_first), Some(d_second)) => {
                        // (Squared distances: the same order.)
                        // Nearer first; a tie keeps the first child first.
                        let (near, far, d_far) = if d_second < d_first {
                            (second, first, d_first)
                        } else {
                            (first, second, d_second)
                        };
                        stack[len] = (far, d_far);
                        len += 1;
                        current = near;
                        continue;
                    }
                    (Some(_), None) => {
                        current = first;
                        continue;
                    }
                    (None, Some(_)) => {
                        current = second;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            // Pop the next waiting node the best has not moved in front of.
            loop {
                if len == 0 {
                    return best.into_nearest();
                }
                len -= 1;
                let (node, squared) = stack[len];
                #[expect(clippy::neg_cmp_op_on_partial_ord, reason = "NaN must not prune")]
                if !(squared > reach_sq) {
                    current = node;
                    break;
                }
            }
        }
    }
}

/// The largest squared node bound that must still be visited when the observed walk visits
/// a node whose bound `d` is at most `reach`.
///
/// `d` is the square root of a sum `x` rounded to nearest, so `d <= reach` gives
/// `x <= reach² (1 + 2^-23)`; `reach * reach` is itself rounded (relative `2^-24`, or an
/// absolute half subnormal when it underflows), and the factor and the subnormals added
/// cover both with room (see [`NodeVolume::distance_bound_squared`]). Visiting a few
/// nodes more than the observed walk cannot change the answer; visiting fewer could.
#[inline]
pub(in crate::structure::bvh) fn reach_squared(reach: f32) -> f32 {
    reach * reach * (1.0 + 4e-6) + 4.0 * f32::from_bits(1)
}

/// The best primitive so far, in registers rather than in an `Option`: none yet is the
/// distance `+inf` with the index `usize::MAX`, which every primitive whose distance is not
/// NaN beats (one at distance `+inf` by its lower index, as input indices are `u32`), just
/// as every such primitive replaces `None` in the observed walk; a NaN distance never wins.
/// The binary and the 4-wide fast walks share it.
pub(in crate::structure::bvh) struct Best<V: Vector> {
    pub(in crate::structure::bvh) prim: usize,
    pub(in crate::structure::bvh) point: V,
    pub(in crate::structure::bvh) distance: f32,
}

impl<V: Vector> Best<V> {
    pub(in crate::structure::bvh) const NONE: Self = Self {
        prim: usize::MAX,
        point: V::ZERO,
        distance: f32::INFINITY,
    };

    /// Tests the primitives of one leaf (each with its input index) with the observed
    /// walk's rule, the least `(distance, index)` wins; whether the best changed.
    #[inline]
    pub(in crate::structure::bvh) fn test_leaf<P: Primitive<Point = V>>(
        &mut self,
        leaf: impl Iterator<Item = (P, u32)>,
        point: V,
    ) -> bool {
        let mut changed = false;
        for (prim, id) in leaf {
            changed |= self.test(&prim, id, point);
        }
        changed
    }

    /// Tests one primitive (`id` its input index) by the same rule; whether it became the
    /// best.
    #[inline]
    pub(in crate::structure::bvh) fn test<P: Primitive<Point = V>>(
        &mut self,
        prim: &P,
        id: u32,
        point: V,
    ) -> bool {
        let q = contract::project_point(prim, point);
        let distance = (q - point).length();
        let id = id as usize;
        let better = distance < self.distance || (distance == self.distance && id < self.prim);
        if better {
            *self = Self {
                prim: id,
                point: q,
                distance,
            };
        }
        better
    }

    /// The answer: none when no primitive had a distance that is not NaN.
    pub(in crate::structure::bvh) fn into_nearest(self) -> Option<Nearest<V>> {
        (self.prim != usize::MAX).then_some(Nearest {
            prim: self.prim,
            point: self.point,
            distance: self.distance,
        })
    }
}
