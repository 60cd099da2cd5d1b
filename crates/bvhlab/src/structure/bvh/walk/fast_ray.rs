//! The unobserved ray first hit and any hit: the same walk as `ray.rs`, without the
//! bookkeeping that only the lab needs.
//!
//! The observed walk (`ray.rs`) keeps, per waiting node, its depth for `EnterNode`,
//! counts every test for [`QueryCost`](crate::structure::QueryCost) and pushes both
//! children before popping the nearer again, so that every step can be reported in the order
//! the lab plays it back. A caller that only wants the answer pays for none of that here:
//! the nearer child is visited next without touching the stack, only the farther one waits
//! (node index and entry `t`, 8 bytes), and nothing is counted.
//!
//! The answer is the observed walk's, bit for bit: both use the same node test
//! ([`NodeVolume::ray_entry`], or [`NodeVolume::ray_enter`], which gives the same entry `t`
//! with wider instructions), the same primitive test and the same pruning rule (a node
//! is skipped only when the ray enters it beyond the best hit times [`GROW`]), and the best
//! hit is the least `(t, index)` over every primitive not pruned, whatever the order they
//! are met in ([`HitTracker`]).
//!
//! The any-hit walk is the same walk stopping at the first primitive hit within `t_max`.
//! The observed any-hit walk visits nodes in the same order (nearer entry first, the first
//! child on a tie) with the same constant limit `t_max`, and tests a leaf's primitives in
//! leaf order, so both stop at the same primitive: the same answer, bit for bit.

use crate::primitive::contract;
use crate::structure::bvh::volume::{GROW, NodeVolume, PreparedRay};
use crate::structure::bvh::{Bvh, MAX_DEPTH};
use crate::structure::{Hit, HitTracker};
use crate::{Primitive, Ray};

/// One waiting sibling per level, plus room for the root.
const CAPACITY: usize = MAX_DEPTH + 2;

impl<B, P> Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// The first hit with `0 <= t <= t_max` (none for a NaN `t_max`): what
    /// `first_hit(ray, t_max, &mut ())` answers, found faster.
    pub(in crate::structure::bvh) fn first_hit_fast(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
    ) -> Option<Hit> {
        self.walk_fast::<false>(ray, t_max)
    }

    /// Some hit with `0 <= t <= t_max` (none for a NaN `t_max`): what
    /// `any_hit(ray, t_max, &mut ())` answers, found faster.
    pub(in crate::structure::bvh) fn any_hit_fast(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
    ) -> Option<Hit> {
        self.walk_fast::<true>(ray, t_max)
    }

    /// The walk; `ANY` stops at the first hit met instead of keeping the nearest.
    #[inline]
    fn walk_fast<const ANY: bool>(&self, ray: &Ray<P::Point>, t_max: f32) -> Option<Hit> {
        if self.nodes.is_empty() || t_max.is_nan() {
            return None;
        }
        let prepared = PreparedRay::new(ray);
        let mut best = HitTracker::new(t_max);
        // `best.limit()`, kept in a local so that the hot loop reads a register.
        let mut limit = t_max;
        let enters = |node: u32, limit: f32| {
            self.nodes[node as usize]
                .volume
                .ray_enter(&prepared)
                .filter(|&t_enter| t_enter <= limit * GROW)
        };
        enters(0, limit)?;
        let mut stack = [(0u32, 0.0f32); CAPACITY];
        let mut len = 0;
        let mut current = 0u32;
        loop {
            let node = &self.nodes[current as usize];
            if node.is_leaf() {
                let range = node.leaf_range();
                if ANY {
                    let leaf = self.leaf_prims[range.clone()].iter();
                    for (prim, &id) in leaf.zip(&self.leaf_ids[range.clone()]) {
                        if let Some(t) = contract::ray_hit(prim, ray).filter(|&t| t <= t_max) {
                            return Some(Hit::unplaced(id as usize, t));
                        }
                    }
                } else if best.offer_leaf(
                    &self.leaf_prims[range.clone()],
                    &self.leaf_ids[range],
                    ray,
                ) {
                    limit = best.limit();
                }
            } else {
                let (first, second) = (current + 1, node.start);
                match (enters(first, limit), enters(second, limit)) {
                    (Some(t_first), Some(t_second)) => {
                        // Nearer entry first; a tie keeps the first child first.
                        let (near, far, t_far) = if t_second < t_first {
                            (second, first, t_first)
                        } else {
                            (first, second, t_second)
                        };
                        stack[len] = (far, t_far);
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
            // Pop the next waiting node the best hit has not moved in front of.
            loop {
                if len == 0 {
                    return best.best();
                }
                len -= 1;
                let (node, t_enter) = stack[len];
                if t_enter <= limit * GROW {
                    current = node;
                    break;
                }
            }
        }
    }
}
