//! Collision of two trees: the lecture's simultaneous descent.
//!
//! Two nodes, one of each tree, are tested against each other; if their volumes are
//! disjoint nothing below them can touch. Otherwise the larger of the two (by surface area,
//! perimeter in 2D) is opened and each of its children paired with the other node, until two
//! leaves meet and their primitives are tested pair by pair (Gottschalk, Lin and Manocha,
//! "`OBBTree`", SIGGRAPH 1996, §5: "descend the larger").

use crate::Primitive;
use crate::structure::bvh::Bvh;
use crate::structure::bvh::volume::NodeVolume;
use crate::structure::{Event, NodeId, Observer, QueryCost, Traced};

impl<B, P> Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// Every pair `(a, b)` of a primitive of `self` and one of `other` that share a point,
    /// ascending.
    ///
    /// Events, in order: a `NodePairTest` for each pair of nodes popped (the roots first);
    /// for two overlapping leaves a `PairTest` per primitive pair. A node pair's children
    /// pairs are tested first child first. The cost counts node pairs tested as bound tests,
    /// overlapping node pairs as nodes visited, and primitive pairs as primitive tests.
    pub(in crate::structure::bvh) fn collide_impl<O: Observer<P::Point>>(
        &self,
        other: &Self,
        observer: &mut O,
    ) -> Traced<Vec<(usize, usize)>> {
        let mut cost = QueryCost::default();
        let mut pairs = Vec::new();
        let mut stack: Vec<(u32, u32)> = Vec::new();
        if !self.nodes.is_empty() && !other.nodes.is_empty() {
            stack.push((0, 0));
        }
        while let Some((a, b)) = stack.pop() {
            let (node_a, node_b) = (&self.nodes[a as usize], &other.nodes[b as usize]);
            let overlap = node_a.volume.overlaps_node(&node_b.volume);
            cost.bound_tests += 1;
            observer.on(Event::NodePairTest {
                a: NodeId(a),
                b: NodeId(b),
                overlap,
            });
            if !overlap {
                continue;
            }
            cost.nodes_visited += 1;
            let open_a = match (node_a.is_leaf(), node_b.is_leaf()) {
                (true, true) => {
                    self.leaf_pairs(other, a, b, observer, &mut cost, &mut pairs);
                    continue;
                }
                (false, true) => true,
                (true, false) => false,
                (false, false) => {
                    node_a.volume.boundary_measure() >= node_b.volume.boundary_measure()
                }
            };
            // Pushed second child first, so that the first child's pair is popped first.
            if open_a {
                stack.extend([(node_a.start, b), (a + 1, b)]);
            } else {
                stack.extend([(a, node_b.start), (a, b + 1)]);
            }
        }
        pairs.sort_unstable();
        Traced {
            answer: pairs,
            cost,
        }
    }

    /// Tests every primitive of leaf `a` against every primitive of `other`'s leaf `b`.
    fn leaf_pairs<O: Observer<P::Point>>(
        &self,
        other: &Self,
        a: u32,
        b: u32,
        observer: &mut O,
        cost: &mut QueryCost,
        pairs: &mut Vec<(usize, usize)>,
    ) {
        let (range_a, range_b) = (
            self.nodes[a as usize].leaf_range(),
            other.nodes[b as usize].leaf_range(),
        );
        let ids_b = &other.leaf_ids[range_b.clone()];
        for (pa, &ia) in self.leaf_prims[range_a.clone()]
            .iter()
            .zip(&self.leaf_ids[range_a])
        {
            for (pb, &ib) in other.leaf_prims[range_b.clone()].iter().zip(ids_b) {
                let overlap = pa.intersects(pb);
                cost.prim_tests += 1;
                observer.on(Event::PairTest {
                    a: ia,
                    b: ib,
                    overlap,
                });
                if overlap {
                    pairs.push((ia as usize, ib as usize));
                }
            }
        }
    }
}
