//! The stacks of the [`Bvh4`](super::Bvh4) walks: children waiting to be visited.
//!
//! The nearest-first walks (first hit, closest point, k nearest) keep [`Lane`]s, each child
//! with the key (ray entry `t` or squared distance bound) that decides whether it still
//! needs a visit, in a [`LaneStack`]: an [`ArrayVec`] sized for the deepest tree
//! [`validate`](super::Bvh4::validate) accepts, which is not written before it is used, so
//! a query pays only for what it pushes. These walks had kept zeroed arrays in the three
//! sizes below. On the bunny and the dragon (issue 19, the two builds timed alternately six
//! times, best of each), the `ArrayVec` made first hits of primary, shadow and diffuse rays
//! 1.02-1.13x as fast, and left random and overview rays and the closest point within the
//! noise (0.93-1.07x; the unchanged any-hit walk measured 0.97-1.18x in the same runs); and
//! each of these queries needs one walk instead of three.
//!
//! The walks that visit every child in reach in any order (any hit, all hits, range) keep
//! bare node indices in a fixed-size array, zeroed on every query, its size chosen per tree
//! from the wide tree's depth ([`SHALLOW_DEPTH`] and [`MIDDLE_DEPTH`] levels fit in shorter
//! arrays, deeper trees get one for [`MAX_DEPTH`]): a coherent ray takes only about 250
//! cycles, and zeroing the longest array cost the 2M-triangle sphere's rays 5-8%. With four-
//! byte entries the short array zeroes fast, and an `ArrayVec` made the any-hit walk
//! 0.88-0.97x as fast (pushing every inner lane, or visiting the first at once).
//!
//! [`ArrayVec`]: arrayvec::ArrayVec

use arrayvec::ArrayVec;

use super::layout::{Bvh4Node, WIDTH};
use crate::structure::bvh::MAX_DEPTH;

/// Wide trees at most this deep (in wide levels) take the node-index walks' short array.
pub(super) const SHALLOW_DEPTH: usize = 16;

/// Wide trees deeper than [`SHALLOW_DEPTH`] and at most this deep take the middle array.
pub(super) const MIDDLE_DEPTH: usize = 24;

/// The stack size for a wide tree of `depth` levels: each node visited leaves at most
/// `WIDTH - 1` children waiting (the node-index walks push up to `WIDTH` and pop one at
/// once), and only the nodes on the path to the current one have children still waiting.
pub(super) const fn capacity(depth: usize) -> usize {
    (WIDTH - 1) * depth + 1
}

/// The stack of the nearest-first walks, long enough for a valid tree of any depth (at most
/// [`MAX_DEPTH`] wide levels).
pub(super) type LaneStack = ArrayVec<Lane, { capacity(MAX_DEPTH + 1) }>;

/// A child waiting on the stack, or being visited: its wide node (`count == 0`) or its leaf's
/// primitives (`child..child + count`), and its key.
#[derive(Clone, Copy, Debug)]
pub(super) struct Lane {
    pub child: u32,
    pub count: u32,
    pub key: f32,
}

impl Lane {
    /// The root node (a value for what cannot be empty).
    pub const ROOT: Self = Self {
        child: 0,
        count: 0,
        key: 0.0,
    };

    #[inline]
    fn of(node: &Bvh4Node, lane: usize, key: f32) -> Self {
        Self {
            child: node.child[lane],
            count: node.count[lane],
            key,
        }
    }
}

/// The child to visit next among the lanes of `node` set in `mask` (not 0): the one with
/// the least key. The others are pushed onto `stack` so that the nearest of them is
/// popped first (ties in lane order, which only changes the order of work, never the
/// answer).
#[expect(
    clippy::inline_always,
    reason = "the hot step of the walk: left out of line it costs a call per node (measured)"
)]
#[inline(always)]
pub(super) fn visit_nearest(
    node: &Bvh4Node,
    mask: u32,
    keys: &[f32; WIDTH],
    stack: &mut LaneStack,
) -> Lane {
    let first = mask.trailing_zeros() as usize;
    if mask.is_power_of_two() {
        return Lane::of(node, first, keys[first]);
    }
    let rest = mask & (mask - 1);
    if rest.is_power_of_two() {
        // Two lanes, the commonest case: the farther waits (a tie keeps lane order).
        let second = rest.trailing_zeros() as usize;
        let (a, b) = (
            Lane::of(node, first, keys[first]),
            Lane::of(node, second, keys[second]),
        );
        let (near, far) = if b.key < a.key { (b, a) } else { (a, b) };
        stack.push(far);
        return near;
    }
    // Insertion by descending key into the top of the stack.
    let base = stack.len();
    let mut bits = mask;
    while bits != 0 {
        let lane = bits.trailing_zeros() as usize;
        bits &= bits - 1;
        let new = Lane::of(node, lane, keys[lane]);
        let mut at = stack.len();
        stack.push(new);
        while at > base && stack[at - 1].key < new.key {
            stack[at] = stack[at - 1];
            at -= 1;
        }
        stack[at] = new;
    }
    // At least three lanes were pushed, so the pop finds one.
    stack.pop().unwrap_or(Lane::ROOT)
}
