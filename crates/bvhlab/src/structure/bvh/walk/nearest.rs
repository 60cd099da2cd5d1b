//! The k nearest primitives, by branch and bound (lecture §3, "BVH distance query").
//!
//! The slide's `minDistance` recursion with the pruning that makes it fast: a node is skipped
//! when the distance from the query point to its volume is already beyond the k-th best
//! distance so far, and of two children the nearer is visited first, so that a good bound
//! is found early (Roussopoulos, Kelley and Vincent, "Nearest Neighbor Queries", SIGMOD 1995,
//! depth-first with the same ordering). A node at exactly the bound is still visited: a
//! primitive there ties, and ties go to the lower index.

use super::stack::{Entry, Stack};
use crate::primitive::contract;
use crate::structure::bvh::Bvh;
use crate::structure::bvh::volume::{GROW, NodeVolume, query_slack};
use crate::structure::{
    Event, Nearest, NearestSet, NodeId, Observer, PrimitiveResult, PruneAt, PruneReason, QueryCost,
    Traced,
};
use crate::{Primitive, Vector};

/// The query point and the slack its rounding needs.
struct Probe<V> {
    point: V,
    slack: f32,
}

impl<B, P> Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// The `k` nearest primitives to `point`, nearest first (ties by index). None for a
    /// non-finite point or `k = 0`.
    ///
    /// Events, in order: `DistanceBoundTest` for the root and then for both children of each
    /// inner node entered, `Prune(NoNearer, at Test)` for a child beyond the bound,
    /// `ChildQueued` for the others nearer first; when a node is popped,
    /// `Prune(NoNearer, at Pop)` if the bound has meanwhile dropped below its distance, else
    /// `EnterNode`, then at a leaf a `PrimitiveTest` with each primitive's distance and
    /// `NewBest` when it enters the k best.
    pub(in crate::structure::bvh) fn k_nearest_impl<O: Observer<P::Point>>(
        &self,
        point: P::Point,
        k: usize,
        observer: &mut O,
    ) -> Traced<Vec<Nearest<P::Point>>> {
        let mut cost = QueryCost::default();
        if self.nodes.is_empty() || k == 0 || !point.is_finite() {
            return Traced {
                answer: Vec::new(),
                cost,
            };
        }
        let mut best = NearestSet::new(k);
        // The primitives' distances are rounded at the query point's scale.
        let slack = query_slack(point);
        let mut stack = Stack::new();
        let probe = Probe { point, slack };
        let root = self.distance_child(0, 0, &probe, best.bound(), observer, &mut cost);
        stack.push_pair(root, None);
        while let Some(entry) = stack.pop() {
            let bound = best.bound();
            if entry.key > bound * GROW + slack {
                observer.on(Event::Prune {
                    node: NodeId(entry.node),
                    reason: PruneReason::NoNearer {
                        distance: entry.key,
                        best: bound,
                    },
                    at: PruneAt::Pop,
                });
                continue;
            }
            cost.nodes_visited += 1;
            observer.on(Event::EnterNode {
                node: NodeId(entry.node),
                depth: entry.depth,
            });
            let node = &self.nodes[entry.node as usize];
            if node.is_leaf() {
                let range = node.leaf_range();
                cost.prim_tests += range.len() as u64;
                for (prim, &id) in self.leaf_prims[range.clone()]
                    .iter()
                    .zip(&self.leaf_ids[range])
                {
                    let q = contract::project_point(prim, point);
                    let d = (q - point).length();
                    observer.on(Event::PrimitiveTest {
                        prim: id,
                        result: PrimitiveResult::Distance(d),
                    });
                    if best.offer(id as usize, q, d) {
                        observer.on(Event::NewBest { prim: id, value: d });
                    }
                }
                continue;
            }
            let depth = entry.depth + 1;
            let first =
                self.distance_child(entry.node + 1, depth, &probe, bound, observer, &mut cost);
            let second = self.distance_child(node.start, depth, &probe, bound, observer, &mut cost);
            let order = stack.push_pair(first, second);
            for (rank, child) in order.iter().flatten().enumerate() {
                observer.on(Event::ChildQueued {
                    parent: NodeId(entry.node),
                    child: NodeId(child.node),
                    key: child.key,
                    rank: rank as u32,
                });
            }
        }
        Traced {
            answer: best.into_vec(),
            cost,
        }
    }

    /// The distance from `point` to a node's volume; the entry to queue, or `None` when it
    /// is beyond `bound`.
    fn distance_child<O: Observer<P::Point>>(
        &self,
        node: u32,
        depth: u32,
        probe: &Probe<P::Point>,
        bound: f32,
        observer: &mut O,
        cost: &mut QueryCost,
    ) -> Option<Entry> {
        cost.bound_tests += 1;
        let distance = self.nodes[node as usize].volume.distance_bound(probe.point);
        observer.on(Event::DistanceBoundTest {
            node: NodeId(node),
            distance,
        });
        if distance > bound * GROW + probe.slack {
            observer.on(Event::Prune {
                node: NodeId(node),
                reason: PruneReason::NoNearer {
                    distance,
                    best: bound,
                },
                at: PruneAt::Test,
            });
            return None;
        }
        Some(Entry {
            node,
            depth,
            key: distance,
        })
    }
}
