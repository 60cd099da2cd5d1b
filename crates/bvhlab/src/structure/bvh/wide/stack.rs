//! The stack of the [`Bvh4`](super::Bvh4) walks: children waiting to be visited, with the key
//! (ray entry `t` or squared distance bound) that decides whether they still need to be.
//!
//! The stack lives in a fixed-size array on the call stack, which is zeroed on every query:
//! its size is chosen per tree from the wide tree's depth ([`SHALLOW_DEPTH`] and
//! [`MIDDLE_DEPTH`] levels fit in shorter arrays, deeper trees get one for
//! [`MAX_DEPTH`]), since the longest (2.3 KB) would be zeroed on every ray,
//! a coherent one taking only about 250 cycles. The middle size is for the largest meshes:
//! the 2M-triangle sphere of the peer comparison has 17 wide levels, and zeroing the longest
//! stack cost its primary rays 5% and its diffuse rays 5-8% (measured against this tier).
//!
//! [`MAX_DEPTH`]: crate::structure::bvh::MAX_DEPTH

use super::layout::{Bvh4Node, WIDTH};

/// Wide trees at most this deep (in wide levels) take the walks with the short stack.
pub(super) const SHALLOW_DEPTH: usize = 16;

/// Wide trees deeper than [`SHALLOW_DEPTH`] and at most this deep take the middle stack.
pub(super) const MIDDLE_DEPTH: usize = 24;

/// The stack size for a wide tree of `depth` levels: each node visited leaves at most
/// `WIDTH - 1` children waiting, and only the nodes on the path to the current one have
/// children still waiting.
pub(super) const fn capacity(depth: usize) -> usize {
    (WIDTH - 1) * depth + 1
}

/// A child waiting on the stack, or being visited: its wide node (`count == 0`) or its leaf's
/// primitives (`child..child + count`), and its key.
#[derive(Clone, Copy, Debug)]
pub(super) struct Lane {
    pub child: u32,
    pub count: u32,
    pub key: f32,
}

impl Lane {
    /// The root node, to start from.
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
/// the least key. The others are pushed onto `stack[*len..]` so that the nearest of them is
/// popped first (ties in lane order, which only changes the order of work, never the
/// answer).
#[expect(
    clippy::inline_always,
    reason = "the hot step of the walk: left out of line it costs a call per node (measured)"
)]
#[inline(always)]
pub(super) fn visit_nearest<const CAP: usize>(
    node: &Bvh4Node,
    mask: u32,
    keys: &[f32; WIDTH],
    stack: &mut [Lane; CAP],
    len: &mut usize,
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
        stack[*len] = far;
        *len += 1;
        return near;
    }
    // Insertion by descending key into the top of the stack.
    let base = *len;
    let mut bits = mask;
    while bits != 0 {
        let lane = bits.trailing_zeros() as usize;
        bits &= bits - 1;
        let new = Lane::of(node, lane, keys[lane]);
        let mut at = *len;
        while at > base && stack[at - 1].key < new.key {
            stack[at] = stack[at - 1];
            at -= 1;
        }
        stack[at] = new;
        *len += 1;
    }
    *len -= 1;
    stack[*len]
}
