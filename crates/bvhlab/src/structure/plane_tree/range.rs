//! Range queries on a plane tree: every primitive that shares a point with a box or a ball.
//!
//! Descend into every child whose box (k-d cell, or the box of a BSP node's primitives)
//! overlaps the region; in the leaves, test each primitive exactly, once (a [`Mailbox`]
//! skips the copies of a primitive listed in several leaves).
//!
//! Events: `Prune { NoOverlap, at: Test }` when the region misses the root box;
//! [`Event::EnterNode`] per visited node; per child [`Event::ChildQueued`] (key 0, below child
//! first) or `Prune { NoOverlap, at: Test }`; in a leaf [`Event::PrimitiveTest`] (`Overlap`, `NoOverlap`, or
//! `AlreadyTested`).

use super::{PlaneNode, PlaneTree, PointOfTree, ROOT, SLACK, magnitude, node_id};
use crate::PointQuery;
use crate::Vector;
use crate::structure::{
    Event, Mailbox, Observer, PrimitiveResult, PruneAt, PruneReason, QueryCost, RangeShape, Traced,
};
use crate::volume::{Aabb, BoundingVolume};

/// Whether the region may share a point with the box. Exact for a box region; for a ball the
/// box distance is compared with a rounding margin, so that a primitive brute force finds at
/// distance exactly `radius` is never pruned.
fn may_overlap<V: Vector>(shape: &RangeShape<V>, bound: &Aabb<V>, margin: f32) -> bool {
    match shape {
        RangeShape::Box(_) => shape.overlaps_aabb(bound),
        RangeShape::Ball(ball) => {
            !ball.is_empty()
                && !bound.is_empty()
                && bound.distance(ball.center) - margin <= ball.radius
        }
    }
}

/// The indices of the primitives that share a point with the region, ascending.
pub(crate) fn range<T: PlaneTree, O: Observer<PointOfTree<T>>>(
    tree: &T,
    shape: &RangeShape<PointOfTree<T>>,
    observer: &mut O,
) -> Traced<Vec<usize>> {
    let mut cost = QueryCost::default();
    let mut found = Vec::new();
    let Some(root) = tree.root_bound() else {
        return Traced {
            answer: found,
            cost,
        };
    };
    let margin = match shape {
        RangeShape::Box(_) => 0.0,
        RangeShape::Ball(ball) => {
            SLACK * (magnitude(ball.center) + magnitude(root.min).max(magnitude(root.max)))
        }
    };
    cost.bound_tests += 1;
    if !may_overlap(shape, &root, margin) {
        observer.on(Event::Prune {
            node: node_id(ROOT),
            reason: PruneReason::NoOverlap,
            at: PruneAt::Test,
        });
        return Traced {
            answer: found,
            cost,
        };
    }
    let prims = tree.prims();
    let mut mailbox = Mailbox::new();
    let mut stack = vec![(ROOT, 0u32, root)];
    while let Some((node, depth, bound)) = stack.pop() {
        observer.on(Event::EnterNode {
            node: node_id(node),
            depth,
        });
        cost.nodes_visited += 1;
        match tree.node(node) {
            PlaneNode::Leaf(list) => {
                for &prim in list {
                    if !mailbox.admit(prim, observer) {
                        continue;
                    }
                    cost.prim_tests += 1;
                    let overlap = shape.overlaps_primitive(&prims[prim as usize]);
                    observer.on(Event::PrimitiveTest {
                        prim,
                        result: if overlap {
                            PrimitiveResult::Overlap
                        } else {
                            PrimitiveResult::NoOverlap
                        },
                    });
                    if overlap {
                        found.push(prim as usize);
                    }
                }
            }
            PlaneNode::Inner(children) => {
                let bounds = tree.child_bounds(node, &bound);
                let mut rank = 0;
                let mut queued = [None, None];
                for side in 0..2 {
                    cost.bound_tests += 1;
                    if !may_overlap(shape, &bounds[side], margin) {
                        observer.on(Event::Prune {
                            node: node_id(children[side]),
                            reason: PruneReason::NoOverlap,
                            at: PruneAt::Test,
                        });
                        continue;
                    }
                    observer.on(Event::ChildQueued {
                        parent: node_id(node),
                        child: node_id(children[side]),
                        key: 0.0,
                        rank,
                    });
                    rank += 1;
                    queued[side] = Some((children[side], depth + 1, bounds[side]));
                }
                stack.extend(queued.into_iter().rev().flatten());
            }
        }
    }
    found.sort_unstable();
    Traced {
        answer: found,
        cost,
    }
}
