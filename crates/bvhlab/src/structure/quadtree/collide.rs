//! Collision on the 2^D tree: the pairs that collide between two trees (descend both at
//! once).

use super::layout::{Orthtree, child_box_at, child_count, split_point};
use crate::structure::grid::probe::PairCollector;
use crate::structure::{Event, NodeId, Observer, Traced};
use crate::volume::Aabb;
use crate::{BoundingVolume, Primitive, Vector};

impl<P: Primitive> Orthtree<P> {
    /// Every pair of a primitive of `self` and one of `other` that share a point, ascending.
    ///
    /// Simultaneous descent of both trees (Gottschalk, Lin and Manocha, "`OBBTree`", 1996,
    /// with cells for volumes): a pair of cells whose boxes overlap ([`Event::NodePairTest`])
    /// is split by descending into the children of the larger cell (or of the one that is not
    /// a leaf); two overlapping leaves test their primitives pairwise, each pair once per
    /// query, a pair whose bounding boxes are apart being rejected without the exact test.
    pub(super) fn search_collisions<O: Observer<P::Point>>(
        &self,
        other: &Self,
        observer: &mut O,
    ) -> Traced<Vec<(usize, usize)>> {
        let mut pairs = PairCollector::default();
        if self.nodes.is_empty() || other.nodes.is_empty() {
            return pairs.finish();
        }
        let mut stack = vec![(0u32, self.root, 0u32, other.root)];
        while let Some((a, a_box, b, b_box)) = stack.pop() {
            pairs.cost.bound_tests += 1;
            let overlap = a_box.overlaps(&b_box);
            observer.on(Event::NodePairTest {
                a: NodeId(a),
                b: NodeId(b),
                overlap,
            });
            if !overlap {
                continue;
            }
            pairs.cost.nodes_visited += 1;
            let (a_children, b_children) = (self.children(NodeId(a)), other.children(NodeId(b)));
            match (a_children, b_children) {
                (None, None) => {
                    for &i in self.leaf_primitives(NodeId(a)) {
                        for &j in other.leaf_primitives(NodeId(b)) {
                            let pa = (i, &self.prims[i as usize]);
                            pairs.test(pa, (j, &other.prims[j as usize]), true, observer);
                        }
                    }
                }
                (Some(children), None) => push_split_a(&mut stack, children, a_box, b, b_box),
                (Some(children), Some(_)) if side(&a_box) >= side(&b_box) => {
                    push_split_a(&mut stack, children, a_box, b, b_box);
                }
                (_, Some(children)) => {
                    let mid = split_point(&b_box);
                    for (k, child) in children.enumerate().rev() {
                        stack.push((a, a_box, child, child_box_at(&b_box, mid, k)));
                    }
                }
            }
        }
        pairs.finish()
    }
}

/// The longest side of a cell, in `f64`.
fn side<V: Vector>(b: &Aabb<V>) -> f64 {
    (0..V::DIM)
        .map(|i| f64::from(b.max.coord(i)) - f64::from(b.min.coord(i)))
        .fold(0.0, f64::max)
}

/// Queues the pairs of `a`'s children with `b`.
fn push_split_a<V: Vector>(
    stack: &mut Vec<(u32, Aabb<V>, u32, Aabb<V>)>,
    children: std::ops::Range<u32>,
    a_box: Aabb<V>,
    b: u32,
    b_box: Aabb<V>,
) {
    debug_assert_eq!(children.len(), child_count::<V>());
    let mid = split_point(&a_box);
    for (k, child) in children.enumerate().rev() {
        stack.push((child, child_box_at(&a_box, mid, k), b, b_box));
    }
}
