//! Range queries: every primitive that shares a point with a box or a ball.
//!
//! Depth first: a node whose volume misses the region is pruned with everything below it;
//! leaves test their primitives exactly.

use super::stack::{Entry, Stack};
use crate::Primitive;
use crate::structure::bvh::Bvh;
use crate::structure::bvh::volume::{NodeVolume, PreparedRange};
use crate::structure::{
    Event, NodeId, Observer, PrimitiveResult, PruneAt, PruneReason, QueryCost, RangeShape, Traced,
};

impl<B, P> Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// The primitives that share a point with `shape`, ascending.
    ///
    /// Events, in order: for the root and then for both children of each inner node entered,
    /// `Prune(NoOverlap, at Test)` when the volume misses the region, else `ChildQueued` (key
    /// 0, first child first); `EnterNode` when a node is popped, then at a leaf a `PrimitiveTest`
    /// (`Overlap` or `NoOverlap`) per primitive.
    pub(in crate::structure::bvh) fn range_impl<O: Observer<P::Point>>(
        &self,
        shape: &RangeShape<P::Point>,
        observer: &mut O,
    ) -> Traced<Vec<usize>> {
        let mut cost = QueryCost::default();
        let mut found = Vec::new();
        if self.nodes.is_empty() {
            return Traced {
                answer: found,
                cost,
            };
        }
        let range = PreparedRange::new(shape);
        let mut stack = Stack::new();
        let root = self.overlap_child(0, 0, &range, observer, &mut cost);
        stack.push_pair(root, None);
        while let Some(entry) = stack.pop() {
            cost.nodes_visited += 1;
            observer.on(Event::EnterNode {
                node: NodeId(entry.node),
                depth: entry.depth,
            });
            let node = &self.nodes[entry.node as usize];
            if node.is_leaf() {
                let leaf = node.leaf_range();
                cost.prim_tests += leaf.len() as u64;
                for (prim, &id) in self.leaf_prims[leaf.clone()]
                    .iter()
                    .zip(&self.leaf_ids[leaf])
                {
                    let overlap = shape.overlaps_primitive(prim);
                    observer.on(Event::PrimitiveTest {
                        prim: id,
                        result: if overlap {
                            PrimitiveResult::Overlap
                        } else {
                            PrimitiveResult::NoOverlap
                        },
                    });
                    if overlap {
                        found.push(id as usize);
                    }
                }
                continue;
            }
            let depth = entry.depth + 1;
            let first = self.overlap_child(entry.node + 1, depth, &range, observer, &mut cost);
            let second = self.overlap_child(node.start, depth, &range, observer, &mut cost);
            let order = stack.push_pair(first, second);
            for (rank, child) in order.iter().flatten().enumerate() {
                observer.on(Event::ChildQueued {
                    parent: NodeId(entry.node),
                    child: NodeId(child.node),
                    key: 0.0,
                    rank: rank as u32,
                });
            }
        }
        found.sort_unstable();
        Traced {
            answer: found,
            cost,
        }
    }

    /// Tests a node's volume against the region; the entry to queue, or `None`.
    fn overlap_child<O: Observer<P::Point>>(
        &self,
        node: u32,
        depth: u32,
        range: &PreparedRange<P::Point>,
        observer: &mut O,
        cost: &mut QueryCost,
    ) -> Option<Entry> {
        cost.bound_tests += 1;
        if self.nodes[node as usize].volume.overlaps_range(range) {
            return Some(Entry {
                node,
                depth,
                key: 0.0,
            });
        }
        observer.on(Event::Prune {
            node: NodeId(node),
            reason: PruneReason::NoOverlap,
            at: PruneAt::Test,
        });
        None
    }
}
