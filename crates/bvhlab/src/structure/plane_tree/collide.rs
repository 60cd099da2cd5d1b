//! Collision between two plane trees: every pair of overlapping primitives.
//!
//! Simultaneous descent (Gottschalk, Lin and Manocha, "`OBBTree`", SIGGRAPH 1996, §5, for
//! hierarchies of any volume): a pair of nodes whose boxes overlap is split by descending the
//! node with the larger box (or the one that is not a leaf); two leaves test their primitives
//! pair by pair. Both trees list a straddling primitive in several leaves, so the same pair of
//! primitives can meet in several leaf pairs: it is tested once.
//!
//! Events: [`Event::NodePairTest`] for each pair of nodes taken from the stack (pairs whose
//! boxes miss go no further), [`Event::PairTest`] for each pair of primitives tested (a pair
//! met again in another leaf pair is skipped silently).

use std::collections::HashSet;

use super::{PlaneNode, PlaneTree, PointOfTree, ROOT, node_id};
use crate::Primitive;
use crate::structure::{Event, Observer, QueryCost, Traced};
use crate::volume::{Aabb, BoundingVolume};

/// A node of each tree, each with its box.
type NodePair<V> = ((u32, Aabb<V>), (u32, Aabb<V>));

/// Every overlapping pair `(a, b)`, `a` from `first`, `b` from `second`, ascending.
pub(crate) fn collide<T: PlaneTree, O: Observer<PointOfTree<T>>>(
    first: &T,
    second: &T,
    observer: &mut O,
) -> Traced<Vec<(usize, usize)>> {
    let mut cost = QueryCost::default();
    let mut pairs = Vec::new();
    let (Some(root_a), Some(root_b)) = (first.root_bound(), second.root_bound()) else {
        return Traced {
            answer: pairs,
            cost,
        };
    };
    let (prims_a, prims_b) = (first.prims(), second.prims());
    let mut tested: HashSet<(u32, u32)> = HashSet::new();
    let mut stack: Vec<NodePair<PointOfTree<T>>> = vec![((ROOT, root_a), (ROOT, root_b))];
    while let Some(((a, box_a), (b, box_b))) = stack.pop() {
        cost.bound_tests += 1;
        let overlap = box_a.overlaps(&box_b);
        observer.on(Event::NodePairTest {
            a: node_id(a),
            b: node_id(b),
            overlap,
        });
        if !overlap {
            continue;
        }
        cost.nodes_visited += 1;
        match (first.node(a), second.node(b)) {
            (PlaneNode::Leaf(list_a), PlaneNode::Leaf(list_b)) => {
                for &i in list_a {
                    for &j in list_b {
                        if !tested.insert((i, j)) {
                            continue;
                        }
                        cost.prim_tests += 1;
                        let overlap = prims_a[i as usize].intersects(&prims_b[j as usize]);
                        observer.on(Event::PairTest {
                            a: i,
                            b: j,
                            overlap,
                        });
                        if overlap {
                            pairs.push((i as usize, j as usize));
                        }
                    }
                }
            }
            (PlaneNode::Inner(children), PlaneNode::Leaf(_)) => {
                let bounds = first.child_bounds(a, &box_a);
                for side in [1, 0] {
                    stack.push(((children[side], bounds[side]), (b, box_b)));
                }
            }
            (PlaneNode::Leaf(_), PlaneNode::Inner(children)) => {
                let bounds = second.child_bounds(b, &box_b);
                for side in [1, 0] {
                    stack.push(((a, box_a), (children[side], bounds[side])));
                }
            }
            (PlaneNode::Inner(children_a), PlaneNode::Inner(children_b)) => {
                // Descend the larger box: its children are the likelier to separate.
                if box_a.boundary_measure() >= box_b.boundary_measure() {
                    let bounds = first.child_bounds(a, &box_a);
                    for side in [1, 0] {
                        stack.push(((children_a[side], bounds[side]), (b, box_b)));
                    }
                } else {
                    let bounds = second.child_bounds(b, &box_b);
                    for side in [1, 0] {
                        stack.push(((a, box_a), (children_b[side], bounds[side])));
                    }
                }
            }
        }
    }
    pairs.sort_unstable();
    Traced {
        answer: pairs,
        cost,
    }
}
