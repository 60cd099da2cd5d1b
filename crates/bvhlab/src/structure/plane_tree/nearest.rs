//! k nearest primitives on a plane tree, by branch and bound.
//!
//! Depth first, the child on the query point's side of the plane first (the lecture's "descend
//! to the cell of the query point, then search outward"; Friedman, Bentley and Finkel, "An
//! Algorithm for Finding Best Matches in Logarithmic Expected Time", 1977). A subtree is pruned
//! when the distance from the point to its box (a k-d cell, or the box of a BSP node's
//! primitives) exceeds the k-th best distance so far: every primitive point under it is at
//! least that far. Equal distances are not pruned, because an equally near primitive with a
//! lower index would still win, and the distances are compared with a rounding margin.
//!
//! Events: [`Event::DistanceBoundTest`] of the root box; for each subtree taken from the stack,
//! `Prune { NoNearer, at: Pop }` when its box is now too far, else [`Event::EnterNode`]; at an
//! inner node a `DistanceBoundTest` per child (near side first), then [`Event::ChildQueued`]
//! (rank 0 is visited first, keyed by the box distance) or `Prune { NoNearer, at: Test }`; in a
//! leaf
//! [`Event::PrimitiveTest`] with the distance (`AlreadyTested` for a mailboxed primitive) and
//! [`Event::NewBest`] with the primitive's distance when it enters the k nearest.

use super::{PlaneNode, PlaneTree, PointOfTree, ROOT, SLACK, magnitude, node_id};
use crate::PointQuery;
use crate::primitive::contract;
use crate::structure::{
    Event, Mailbox, Nearest, NearestSet, Observer, PrimitiveResult, PruneAt, PruneReason,
    QueryCost, Traced,
};
use crate::volume::Aabb;
use crate::{Primitive, Vector};

/// A subtree waiting on the stack, with its box and the distance to it.
struct Pending<V: Vector> {
    node: u32,
    depth: u32,
    bound: Aabb<V>,
    distance: f32,
}

/// The `k` primitives nearest to `point`, sorted by `(distance, index)`.
pub(crate) fn k_nearest<T: PlaneTree, O: Observer<PointOfTree<T>>>(
    tree: &T,
    point: PointOfTree<T>,
    k: usize,
    observer: &mut O,
) -> Traced<Vec<Nearest<PointOfTree<T>>>> {
    let mut cost = QueryCost::default();
    let root = tree.root_bound().filter(|_| k > 0 && point.is_finite());
    let Some(root) = root else {
        return Traced {
            answer: Vec::new(),
            cost,
        };
    };
    // Distances to boxes and to primitives are rounded relative to the coordinates involved;
    // a box is pruned only when it is farther than the best by more than that.
    let margin = SLACK * (magnitude(point) + magnitude(root.min).max(magnitude(root.max)));
    let prims = tree.prims();
    let mut nearest = NearestSet::new(k);
    let mut mailbox = Mailbox::new();
    cost.bound_tests += 1;
    let distance = root.distance(point);
    observer.on(Event::DistanceBoundTest {
        node: node_id(ROOT),
        distance,
    });
    let mut stack = vec![Pending {
        node: ROOT,
        depth: 0,
        bound: root,
        distance,
    }];
    while let Some(next) = stack.pop() {
        let best = nearest.bound();
        if next.distance - margin > best {
            observer.on(Event::Prune {
                node: node_id(next.node),
                reason: PruneReason::NoNearer {
                    distance: next.distance,
                    best,
                },
                at: PruneAt::Pop,
            });
            continue;
        }
        observer.on(Event::EnterNode {
            node: node_id(next.node),
            depth: next.depth,
        });
        cost.nodes_visited += 1;
        match tree.node(next.node) {
            PlaneNode::Leaf(list) => {
                test_leaf(
                    prims,
                    list,
                    point,
                    &mut nearest,
                    &mut mailbox,
                    &mut cost,
                    observer,
                );
            }
            PlaneNode::Inner(children) => {
                let bounds = tree.child_bounds(next.node, &next.bound);
                let near = tree.side_of(next.node, point);
                let mut queued: [Option<Pending<_>>; 2] = [None, None];
                let mut rank = 0;
                for (slot, side) in [near, 1 - near].into_iter().enumerate() {
                    cost.bound_tests += 1;
                    let distance = bounds[side].distance(point);
                    observer.on(Event::DistanceBoundTest {
                        node: node_id(children[side]),
                        distance,
                    });
                    let best = nearest.bound();
                    if distance - margin > best {
                        observer.on(Event::Prune {
                            node: node_id(children[side]),
                            reason: PruneReason::NoNearer { distance, best },
                            at: PruneAt::Test,
                        });
                        continue;
                    }
                    observer.on(Event::ChildQueued {
                        parent: node_id(next.node),
                        child: node_id(children[side]),
                        key: distance,
                        rank,
                    });
                    rank += 1;
                    queued[slot] = Some(Pending {
                        node: children[side],
                        depth: next.depth + 1,
                        bound: bounds[side],
                        distance,
                    });
                }
                // The near child is popped first.
                stack.extend(queued.into_iter().rev().flatten());
            }
        }
    }
    Traced {
        answer: nearest.into_vec(),
        cost,
    }
}

/// Offers every primitive of a leaf not tested yet to the nearest set.
fn test_leaf<P: Primitive, O: Observer<P::Point>>(
    prims: &[P],
    list: &[u32],
    point: P::Point,
    nearest: &mut NearestSet<P::Point>,
    mailbox: &mut Mailbox,
    cost: &mut QueryCost,
    observer: &mut O,
) {
    for &prim in list {
        if !mailbox.admit(prim, observer) {
            continue;
        }
        cost.prim_tests += 1;
        let q = contract::project_point(&prims[prim as usize], point);
        let d = (q - point).length();
        observer.on(Event::PrimitiveTest {
            prim,
            result: PrimitiveResult::Distance(d),
        });
        if nearest.offer(prim as usize, q, d) {
            observer.on(Event::NewBest { prim, value: d });
        }
    }
}
