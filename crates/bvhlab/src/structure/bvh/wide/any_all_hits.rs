//! Any hit and all hits in a [`Bvh4`]: the walk whose limit never moves.
//!
//! Both queries take every box the ray enters within `[0, t_max]` (the first hit's walk
//! shrinks its limit to the best hit so far; these cannot), so the order of visits does not
//! matter to the answer and is not paid for: a node's leaf lanes are tested where the node
//! is met, as the closest-point walk tests them (`nearest.rs`), and its inner lanes wait on
//! the stack in lane order, with no key and no sorting. The any-hit walk stops at the first
//! primitive hit within `t_max` (occlusion and shadow rays, where any blocker will do); the
//! all-hits walk keeps every one and sorts them as the binary tree does.
//!
//! The boxes are tested by the first-hit walk's four-lane slab test (`ray.rs`), with the
//! binary walks' rule: a child is skipped only when the ray misses its box or enters it
//! beyond `t_max` times [`GROW`], so no primitive the binary tree would test is skipped,
//! and each primitive is tested as there (`ray_hit`, kept when `t <= t_max`). All hits are
//! therefore the binary tree's, bit for bit. The any hit is *a* hit the binary tree (and
//! brute force) also reports, found whenever they find one; which one it is may differ,
//! since the binary any-hit walk visits nearer boxes first.
//!
//! Visiting nearer boxes first does not pay here: on the shadow rays of the bunny and the
//! dragon (about half of them blocked), sorting the inner lanes by entry `t` made the walk
//! 0.87-0.89x as fast, and a child order per ray octant fixed when the tree is made
//! 0.88-0.96x (nearest or farthest first), against lane order (issue 19). Measured again
//! on the tree of four-triangle blocks (issue 33; one binary, seven alternating runs on one
//! core, medians): the first-hit walk's own nearest-first order, stopping at the first hit
//! within `t_max`, was 0.91-0.99x of this walk on the shadow, diffuse and random rays of
//! the bunny, the dragon and the ogre (16-42% of them blocked), and this walk was 1.06-1.26x
//! as fast as the first hit on the same rays.

use super::layout::{Bvh4, Bvh4Node, WIDTH};
use super::nearest::leaf_lanes;
use super::ray::{LaneRay, enter_lanes};
use super::stack::{MIDDLE_DEPTH, SHALLOW_DEPTH, capacity};
use crate::structure::Hit;
use crate::structure::bvh::MAX_DEPTH;
use crate::structure::bvh::volume::{GROW, PreparedRay};
use crate::structure::query::by_t_then_prim;
use crate::{Primitive, Ray, Vector};

impl<P: Primitive> Bvh4<P> {
    /// Some hit with `0 <= t <= t_max`, not necessarily the first (none for a NaN `t_max`):
    /// the walk stops at the first primitive it finds hit. It finds one exactly when the
    /// binary tree's [`ray_any_hit`](crate::RayCast::ray_any_hit) (and
    /// brute force) does, and the hit is one they also report, with the same `t`, `u` and
    /// `v`; it may be another primitive than theirs.
    pub fn ray_any_hit(&self, ray: &Ray<P::Point>, t_max: f32) -> Option<Hit> {
        if self.nodes.is_empty() || t_max.is_nan() {
            return None;
        }
        let mut none = Vec::new();
        if self.depth <= SHALLOW_DEPTH {
            self.fixed_limit_walk::<{ capacity(SHALLOW_DEPTH) }, true>(ray, t_max, &mut none)
        } else if self.depth <= MIDDLE_DEPTH {
            self.fixed_limit_walk::<{ capacity(MIDDLE_DEPTH) }, true>(ray, t_max, &mut none)
        } else {
            self.fixed_limit_walk::<{ capacity(MAX_DEPTH + 1) }, true>(ray, t_max, &mut none)
        }
    }

    /// Every primitive the ray hits with `0 <= t <= t_max`, once each, sorted by `t`, then
    /// index (none for a NaN `t_max`): what the binary tree's
    /// [`ray_all_hits`](crate::SpatialQuery::ray_all_hits) answers, bit for bit.
    pub fn ray_all_hits(&self, ray: &Ray<P::Point>, t_max: f32) -> Vec<Hit> {
        let mut hits = Vec::new();
        if self.nodes.is_empty() || t_max.is_nan() {
            return hits;
        }
        if self.depth <= SHALLOW_DEPTH {
            self.fixed_limit_walk::<{ capacity(SHALLOW_DEPTH) }, false>(ray, t_max, &mut hits);
        } else if self.depth <= MIDDLE_DEPTH {
            self.fixed_limit_walk::<{ capacity(MIDDLE_DEPTH) }, false>(ray, t_max, &mut hits);
        } else {
            self.fixed_limit_walk::<{ capacity(MAX_DEPTH + 1) }, false>(ray, t_max, &mut hits);
        }
        hits.sort_by(by_t_then_prim);
        hits
    }

    /// The walk, with a stack of `CAP` node indices (a node pushes at most [`WIDTH`] and the
    /// next one is popped at once, so `capacity(depth)` suffices). `ANY` returns the first
    /// hit found; otherwise every hit is pushed onto `hits` and `None` returned.
    fn fixed_limit_walk<const CAP: usize, const ANY: bool>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        hits: &mut Vec<Hit>,
    ) -> Option<Hit> {
        let lanes = LaneRay::new(&PreparedRay::new(ray));
        let limit_grown = t_max * GROW;
        let mut stack = [0u32; CAP];
        let mut len = 0;
        let mut current = 0u32;
        loop {
            let node = &self.nodes[current as usize];
            let (_, mask) = if P::Point::DIM == 3 {
                enter_lanes::<3>(node, &lanes, limit_grown)
            } else {
                enter_lanes::<2>(node, &lanes, limit_grown)
            };
            let leaves = mask & leaf_lanes(node);
            let mut bits = leaves;
            while bits != 0 {
                let lane = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let start = node.child[lane] as usize;
                let slots = start..start + node.count[lane] as usize;
                let mut found = None;
                self.leaf_prims.each_hit(slots, ray, |slot, t| {
                    if t > t_max {
                        return false;
                    }
                    let prim = self.leaf_prims.get(slot);
                    let hit = Hit::on(self.leaf_ids[slot] as usize, t, &prim, ray);
                    if ANY {
                        found = Some(hit);
                        return true;
                    }
                    hits.push(hit);
                    false
                });
                if found.is_some() {
                    return found;
                }
            }
            push_lanes(node, mask & !leaves, &mut stack, &mut len);
            if len == 0 {
                return None;
            }
            len -= 1;
            current = stack[len];
        }
    }
}

/// Pushes the child nodes of the lanes set in `mask` onto `stack[*len..]`, in lane order.
#[inline]
pub(super) fn push_lanes<const CAP: usize>(
    node: &Bvh4Node,
    mask: u32,
    stack: &mut [u32; CAP],
    len: &mut usize,
) {
    let mut bits = mask;
    while bits != 0 {
        let lane = bits.trailing_zeros() as usize;
        bits &= bits - 1;
        debug_assert!(lane < WIDTH);
        stack[*len] = node.child[lane];
        *len += 1;
    }
}
