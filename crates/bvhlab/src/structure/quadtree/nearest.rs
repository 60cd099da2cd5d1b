//! The k nearest primitives in the 2^D tree: the lecture's distance query on a quadtree.
//!
//! "Descend to the cell of the query point, then search outward, pruning cells whose distance
//! exceeds the best found so far": done best-first (Hjaltason and Samet, "Distance browsing in
//! spatial databases", ACM TODS 1999). A priority queue holds cells by the distance from the
//! query point to their boxes; the root's children are queued, the nearest one (distance 0
//! when it holds the point) is expanded next, and so on down to the leaf holding the point,
//! whose primitives give the first bound. The search then takes cells in order of distance
//! and stops at the first that is no nearer than the k-th best distance so far.

use std::collections::BinaryHeap;

use super::layout::{Orthtree, child_box_at, child_count, split_point};
use crate::structure::grid::probe::{NearestProbe, Queued};
use crate::structure::grid::tolerance::{box_distance, box_max_abs, max_abs, may_be_nearer};
use crate::structure::{Event, Nearest, NodeId, Observer, PruneAt, PruneReason, Traced};
use crate::volume::Aabb;
use crate::{Primitive, Vector};

impl<P: Primitive> Orthtree<P> {
    pub(super) fn search_nearest<O: Observer<P::Point>>(
        &self,
        point: P::Point,
        k: usize,
        observer: &mut O,
    ) -> Traced<Vec<Nearest<P::Point>>> {
        let mut probe = NearestProbe::new(&self.prims, point, k);
        if !point.is_finite() || k == 0 {
            return probe.finish();
        }
        if self.nodes.is_empty() {
            return probe.finish();
        }
        let scale = max_abs(point).max(box_max_abs(&self.root));
        let mut queue: BinaryHeap<Queued<(Aabb<P::Point>, u32)>> = BinaryHeap::new();
        let distance = box_distance(&self.root, point);
        probe.cost.bound_tests += 1;
        observer.on(Event::DistanceBoundTest {
            node: NodeId(0),
            distance: distance as f32,
        });
        queue.push(Queued {
            key: distance,
            tie: 0,
            item: (self.root, 0),
        });
        while let Some(Queued {
            key: distance,
            tie: node,
            item: (bounds, depth),
        }) = queue.pop()
        {
            let best = probe.bound();
            if !may_be_nearer(distance, best, scale) {
                // Every cell still queued is at least this far: the search is over.
                observer.on(Event::Prune {
                    node: NodeId(node),
                    reason: PruneReason::NoNearer {
                        distance: distance as f32,
                        best,
                    },
                    at: PruneAt::Pop,
                });
                break;
            }
            probe.cost.nodes_visited += 1;
            observer.on(Event::EnterNode {
                node: NodeId(node),
                depth,
            });
            let Some(children) = self.children(NodeId(node)) else {
                for &i in self.leaf_primitives(NodeId(node)) {
                    probe.test(i, observer);
                }
                continue;
            };
            // Measure the children and queue them nearest first.
            let mut order = [(0.0f64, 0usize); 8];
            let n = child_count::<P::Point>();
            let mid = split_point(&bounds);
            for (k, slot) in order.iter_mut().enumerate().take(n) {
                let d = box_distance(&child_box_at(&bounds, mid, k), point);
                probe.cost.bound_tests += 1;
                observer.on(Event::DistanceBoundTest {
                    node: NodeId(children.start + k as u32),
                    distance: d as f32,
                });
                *slot = (d, k);
            }
            let order = &mut order[..n];
            order.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            let mut rank = 0;
            for &(d, k) in order.iter() {
                let child = children.start + k as u32;
                if self.is_empty_leaf(child) {
                    continue;
                }
                let best = probe.bound();
                if may_be_nearer(d, best, scale) {
                    observer.on(Event::ChildQueued {
                        parent: NodeId(node),
                        child: NodeId(child),
                        key: d as f32,
                        rank,
                    });
                    rank += 1;
                    queue.push(Queued {
                        key: d,
                        tie: child,
                        item: (child_box_at(&bounds, mid, k), depth + 1),
                    });
                } else {
                    observer.on(Event::Prune {
                        node: NodeId(child),
                        reason: PruneReason::NoNearer {
                            distance: d as f32,
                            best,
                        },
                        at: PruneAt::Test,
                    });
                }
            }
        }
        probe.finish()
    }
}
