//! Where a new leaf or a cut-out subtree goes: the place that raises the tree's SAH cost
//! least, found by branch and bound.
//!
//! The search of Bittner, Hapala and Havran, "Fast Insertion-Based Optimization of Bounding
//! Volume Hierarchies" (Computer Graphics Forum 32(1), 2013, §4), which `Box2D`'s dynamic tree
//! uses to insert (Catto, "Dynamic Bounding Volume Hierarchies", GDC 2019). Putting `x`
//! beside a node `s` adds a parent around both, of area `A(s ∪ x)`, and every ancestor `a`
//! of `s` grows by `A(a ∪ x) - A(a)`: the *inherited* cost, which only grows on the way
//! down. So below a node whose inherited cost plus `A(x)` (the least any place can add) is
//! already no better than the best place found, nothing can be better, and the search
//! stops there. Nodes are taken cheapest bound first from a priority queue. `A` is the
//! surface area in 3D and the perimeter in 2D, as in [`Stats::sah_cost`].
//!
//! Leaves hold several primitives here, so a single primitive has a second kind of place:
//! into a leaf with room (fewer than `leaf_size`), which turns the leaf's cost
//! `c · A(L)` into `(c + 1) · A(L ∪ x)`. A new leaf beside `s` costs `A(s ∪ x) + A(x)`
//! (the parent and the leaf itself); the two kinds are compared on that one scale, so a
//! primitive inside a leaf's box joins it and one far away gets a leaf of its own.
//!
//! [`Stats::sah_cost`]: crate::structure::Stats::sah_cost

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::structure::bvh::Bvh;
use crate::volume::{Aabb, BoundingVolume};
use crate::{Primitive, Vector};

/// What is being placed.
pub(super) struct Item<V: Vector> {
    /// Its volume (a leaf's box, or a subtree root's).
    pub(super) volume: Aabb<V>,
    /// `Some(k)` for a leaf of `k` primitives, which may join a leaf with room; `None` for
    /// a subtree, which only goes beside a node.
    pub(super) prims: Option<usize>,
    /// Its height (0 for a leaf).
    pub(super) height: usize,
}

/// The places the search may take.
pub(super) struct Limits<'a> {
    /// The deepest any node may end up ([`BvhOptions::max_depth`]).
    ///
    /// [`BvhOptions::max_depth`]: crate::structure::bvh::BvhOptions::max_depth
    pub(super) depth: usize,
    /// Every node's height, to keep the tree within `depth`; `None` to ignore depth.
    pub(super) heights: Option<&'a [usize]>,
    /// The most primitives a leaf may get by joining.
    pub(super) leaf_size: usize,
    /// Whether leaves may grow past `leaf_size` (the fallback when no place keeps the
    /// depth: the build, too, makes leaves of any size at its depth limit).
    pub(super) full_leaves: bool,
}

impl Limits<'_> {
    /// Whether an item of height `height` may go beside `node` (at `depth`): the new parent
    /// pushes `node`'s subtree one level down, and the item hangs one level below the
    /// parent.
    fn allow_beside(&self, node: usize, depth: usize, height: usize) -> bool {
        self.heights
            .is_none_or(|h| depth + 1 + h[node].max(height) <= self.depth)
    }
}

/// A place in the tree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Place {
    /// Beside this node, under a new parent.
    Sibling(usize),
    /// Into this leaf.
    IntoLeaf(usize),
}

/// What the search found: the place, the depth of its node, and how many nodes the search
/// looked at (its cost, which the tests compare with the tree's size).
#[derive(Clone, Copy, Debug)]
pub(super) struct Found {
    pub(super) place: Place,
    pub(super) depth: usize,
    #[cfg_attr(
        not(test),
        expect(dead_code, reason = "only the unit tests read the search's cost")
    )]
    pub(super) visited: usize,
}

/// A node waiting in the queue, with the cost its ancestors would add and the least any
/// place below it can cost.
struct Waiting {
    bound: f64,
    inherited: f64,
    node: usize,
    depth: usize,
}

impl PartialEq for Waiting {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Waiting {}

impl PartialOrd for Waiting {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Waiting {
    /// Reversed, so that the max-heap pops the smallest bound; then the lower node index
    /// (deterministic order among equal bounds).
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .bound
            .total_cmp(&self.bound)
            .then(other.node.cmp(&self.node))
    }
}

/// `A`: the surface area (3D) or perimeter (2D), widened so sums of many do not round.
fn area<V: Vector>(b: &Aabb<V>) -> f64 {
    f64::from(b.boundary_measure())
}

impl<V, P> Bvh<Aabb<V>, P>
where
    V: Vector,
    P: Primitive<Point = V>,
{
    /// The cheapest place for `item` within `limits`; `None` only when `limits` allow no
    /// place. The tree must not be empty.
    pub(super) fn cheapest_place(&self, item: &Item<V>, limits: &Limits<'_>) -> Option<Found> {
        let x = area(&item.volume);
        // What the item itself adds when it gets a place of its own (a leaf: its cost;
        // a subtree keeps its cost wherever it goes, so nothing to compare).
        let own = item.prims.map_or(0.0, |k| k as f64 * x);
        let mut best: Option<(f64, Place, usize)> = None;
        let better = |cost: f64, best: &Option<(f64, Place, usize)>| {
            best.as_ref().is_none_or(|&(b, _, _)| cost < b)
        };
        let mut queue = BinaryHeap::from([Waiting {
            bound: 0.0,
            inherited: 0.0,
            node: 0,
            depth: 0,
        }]);
        let mut visited = 0;
        while let Some(w) = queue.pop() {
            if best.as_ref().is_some_and(|&(b, _, _)| w.bound >= b) {
                break;
            }
            visited += 1;
            let node = &self.nodes[w.node];
            let here = area(&node.volume);
            let joined = area(&node.volume.merge(&item.volume));
            if limits.allow_beside(w.node, w.depth, item.height) {
                let cost = w.inherited + joined + own;
                if better(cost, &best) {
                    best = Some((cost, Place::Sibling(w.node), w.depth));
                }
            }
            if node.is_leaf() {
                if let Some(k) = item.prims {
                    let c = node.count as usize;
                    if c + k <= limits.leaf_size || limits.full_leaves {
                        let cost = w.inherited + (c + k) as f64 * joined - c as f64 * here;
                        if better(cost, &best) {
                            best = Some((cost, Place::IntoLeaf(w.node), w.depth));
                        }
                    }
                }
                continue;
            }
            let inherited = w.inherited + (joined - here);
            let bound = inherited + x;
            if better(bound, &best) {
                for child in [w.node + 1, node.start as usize] {
                    queue.push(Waiting {
                        bound,
                        inherited,
                        node: child,
                        depth: w.depth + 1,
                    });
                }
            }
        }
        best.map(|(_, place, depth)| Found {
            place,
            depth,
            visited,
        })
    }

    /// Every node's height (0 for a leaf): children come after their parent, so a backward
    /// pass sees both first.
    pub(super) fn heights(&self) -> Vec<usize> {
        let mut heights = vec![0; self.nodes.len()];
        for i in (0..self.nodes.len()).rev() {
            let node = &self.nodes[i];
            if !node.is_leaf() {
                heights[i] = 1 + heights[i + 1].max(heights[node.start as usize]);
            }
        }
        heights
    }
}
