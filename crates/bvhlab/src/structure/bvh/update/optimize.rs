//! Improving an AABB tree in place: take out the nodes that cost most for what they hold
//! and put their children back where the SAH cost rises least.
//!
//! Bittner, Hapala and Havran, "Fast Insertion-Based Optimization of Bounding Volume
//! Hierarchies" (Computer Graphics Forum 32(1), 2013). Each pass ranks the inner nodes by
//! their inefficiency, the product of three of the paper's measures for a node `N` with
//! children `L` and `R`:
//!
//! - `A(N)`, its area (big nodes are visited often),
//! - `A(N) / min(A(L), A(R))` (a child much smaller than its parent wastes the test),
//! - `A(N) / ((A(L) + A(R)) / 2)` (children that together cover little of the parent).
//!
//! For a batch of the worst, one at a time: the node is cut out together with its parent
//! (its sibling takes the parent's place), and its two children are inserted again, each
//! at the place found by the insertion's branch-and-bound search (`search.rs`). The search
//! may put a child back where it was, or elsewhere when that is cheaper.
//!
//! A single reinsertion is greedy and can raise the total cost (the second child's best
//! place is chosen after the first's, and the old place may no longer be on offer). So the
//! tree is copied before each reinsertion, which is kept only when the whole tree's SAH
//! cost fell: the cost falls step by step and never ends higher than it started.

use std::collections::HashSet;

use super::search::{Item, Place};
use crate::structure::bvh::Bvh;
use crate::volume::{Aabb, BoundingVolume};
use crate::{Primitive, Vector};

/// The share of inner nodes each pass takes out and reinserts (at least one).
const BATCH_DIVISOR: usize = 50;

/// What [`Bvh::optimize_by_reinsertion`] did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OptimizeReport {
    /// The SAH cost before ([`Stats::sah_cost`](crate::structure::Stats::sah_cost)).
    pub sah_before: Option<f32>,
    /// The SAH cost after: never above `sah_before`.
    pub sah_after: Option<f32>,
    /// The passes run that lowered the cost.
    pub passes: usize,
    /// The reinsertions kept (each lowered the cost).
    pub reinserted: usize,
}

/// Identifies a node across edits of the arrays (which renumber nodes): the input indices
/// of its first and last primitive in leaf order. Each node holds a different run of
/// slots, so at most one node matches.
type NodeKey = (u32, u32);

impl<V, P> Bvh<Aabb<V>, P>
where
    V: Vector,
    P: Primitive<Point = V>,
{
    /// Runs up to `passes` passes of Bittner et al.'s reinsertion (see `update/optimize.rs`)
    /// and reports the SAH cost before and after. Each reinsertion is kept only when it
    /// lowered the whole tree's cost, so the cost never rises; the passes stop at the first
    /// in which no reinsertion helped. A pass takes out about 2% of the inner nodes, and
    /// each costs O(n) (the edits move the arrays, the cost is summed over the tree, and
    /// the tree is copied to go back to).
    ///
    /// Every primitive keeps its index, and every query answers as before (the same
    /// primitives, other leaves).
    pub fn optimize_by_reinsertion(&mut self, passes: usize) -> OptimizeReport {
        let sah_before = self.sah_cost();
        let mut report = OptimizeReport {
            sah_before,
            sah_after: sah_before,
            passes: 0,
            reinserted: 0,
        };
        let Some(mut best) = sah_before else {
            return report; // a flat root: no cost to lower
        };
        let mut saved = self.clone();
        // Nodes whose reinsertion did not help: the next passes take the next worst.
        let mut tried = HashSet::new();
        for _ in 0..passes {
            let batch = self.most_inefficient(&tried);
            if batch.is_empty() {
                break;
            }
            let mut kept = 0;
            for key in batch {
                let Some(node) = self.find_node(key) else {
                    continue; // an earlier reinsertion took it apart
                };
                if node == 0 || self.nodes[node].is_leaf() {
                    continue;
                }
                saved.copy_from(self);
                match self.reinsert_children(node).and_then(|()| self.sah_cost()) {
                    Some(now) if now < best => {
                        best = now;
                        kept += 1;
                    }
                    // Worse, or no place within the depth limit: back to the copy.
                    _ => {
                        std::mem::swap(self, &mut saved);
                        tried.insert(key);
                    }
                }
            }
            report.passes += usize::from(kept > 0);
            report.reinserted += kept;
        }
        report.sah_after = Some(best);
        report
    }

    /// Takes `node` (an inner node, not the root) out with its parent and inserts its two
    /// children again. `None` when a child found no place within the depth limit: the tree
    /// is then incomplete and must be restored.
    fn reinsert_children(&mut self, node: usize) -> Option<()> {
        let (left, right) = self.detach(node).split()?;
        for part in [left, right] {
            let item = Item {
                volume: part.volume(),
                prims: None,
                height: part.height(),
            };
            match self.place(&item)? {
                Place::Sibling(at) => self.attach(part, at),
                Place::IntoLeaf(_) => unreachable!("a subtree only goes beside a node"),
            }
        }
        Some(())
    }

    /// Makes `self` a copy of `other`, reusing `self`'s memory.
    fn copy_from(&mut self, other: &Self) {
        self.prims.clone_from(&other.prims);
        self.nodes.clone_from(&other.nodes);
        self.leaf_prims.clone_from(&other.leaf_prims);
        self.leaf_ids.clone_from(&other.leaf_ids);
        self.options = other.options;
        self.build_sah_cost = other.build_sah_cost;
    }

    /// The keys of the inner nodes (the root and those `tried` excepted) with the highest
    /// inefficiency, worst first.
    fn most_inefficient(&self, tried: &HashSet<NodeKey>) -> Vec<NodeKey> {
        let spans = self.slot_spans();
        let area = |i: usize| f64::from(self.nodes[i].volume.boundary_measure());
        let mut ranked: Vec<(f64, NodeKey)> = (1..self.nodes.len())
            .filter(|&i| !self.nodes[i].is_leaf())
            .map(|i| {
                let (a, l, r) = (area(i), area(i + 1), area(self.nodes[i].start as usize));
                let score = a * (a / l.min(r)) * (a / (0.5 * (l + r)));
                let (start, end) = spans[i];
                (score, (self.leaf_ids[start], self.leaf_ids[end - 1]))
            })
            .filter(|(_, key)| !tried.contains(key))
            .collect();
        ranked.sort_by(|a, b| b.0.total_cmp(&a.0));
        let batch = (ranked.len() / BATCH_DIVISOR).max(1);
        ranked.into_iter().take(batch).map(|(_, key)| key).collect()
    }

    /// Every node's run of leaf slots, from a backward pass (children come after their
    /// parent).
    fn slot_spans(&self) -> Vec<(usize, usize)> {
        let mut spans = vec![(0, 0); self.nodes.len()];
        for i in (0..self.nodes.len()).rev() {
            let node = &self.nodes[i];
            spans[i] = if node.is_leaf() {
                let r = node.leaf_range();
                (r.start, r.end)
            } else {
                (spans[i + 1].0, spans[node.start as usize].1)
            };
        }
        spans
    }

    /// The node whose run of slots starts at primitive `first` and ends at `last`, if
    /// there is one now.
    fn find_node(&self, (first, last): NodeKey) -> Option<usize> {
        let slot = |id: u32| self.leaf_ids.iter().position(|&i| i == id);
        let (start, end) = (slot(first)?, slot(last)? + 1);
        let mut at = 0;
        loop {
            let span = self.slot_span(at);
            if (span.start, span.end) == (start, end) {
                return Some(at);
            }
            if self.nodes[at].is_leaf() {
                return None;
            }
            let second = self.nodes[at].start as usize;
            let split = self.slot_span(second).start;
            at = if end <= split {
                at + 1
            } else if start >= split {
                second
            } else {
                return None;
            };
        }
    }
}
