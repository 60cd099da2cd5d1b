//! The range query on the 2^D tree: the primitives in a range (descend into the cells the
//! region overlaps).

use super::layout::{Orthtree, child_box_at, split_point};
use crate::Primitive;
use crate::structure::grid::probe::{prim_id, test_range};
use crate::structure::grid::tolerance::{box_max_abs, is_prunable_range, range_may_touch};
use crate::structure::{
    Event, Mailbox, NodeId, Observer, PruneAt, PruneReason, QueryCost, RangeShape, Traced,
};

impl<P: Primitive> Orthtree<P> {
    /// The primitives that share a point with the region, ascending. A region that is not a
    /// finite box or ball is answered by testing every primitive, as brute force does.
    pub(super) fn search_range<O: Observer<P::Point>>(
        &self,
        shape: &RangeShape<P::Point>,
        observer: &mut O,
    ) -> Traced<Vec<usize>> {
        let mut cost = QueryCost::default();
        let mut found = Vec::new();
        if !is_prunable_range(shape) {
            for (i, prim) in self.prims.iter().enumerate() {
                test_range((prim_id(i), prim), shape, &mut cost, &mut found, observer);
            }
            return Traced {
                answer: found,
                cost,
            };
        }
        let mut mailbox = Mailbox::new();
        let mut stack = Vec::new();
        if !self.nodes.is_empty() {
            stack.push((0u32, self.root, 0u32));
        }
        while let Some((node, bounds, depth)) = stack.pop() {
            let id = NodeId(node);
            cost.bound_tests += 1;
            if !range_may_touch(shape, &bounds, box_max_abs(&self.root)) {
                observer.on(Event::Prune {
                    node: id,
                    reason: PruneReason::NoOverlap,
                    at: PruneAt::Pop,
                });
                continue;
            }
            cost.nodes_visited += 1;
            observer.on(Event::EnterNode { node: id, depth });
            if let Some(children) = self.children(id) {
                let mid = split_point(&bounds);
                for (k, child) in children.enumerate().rev() {
                    stack.push((child, child_box_at(&bounds, mid, k), depth + 1));
                }
                continue;
            }
            for &i in self.leaf_primitives(id) {
                if mailbox.admit(i, observer) {
                    let prim = (i, &self.prims[i as usize]);
                    test_range(prim, shape, &mut cost, &mut found, observer);
                }
            }
        }
        found.sort_unstable();
        Traced {
            answer: found,
            cost,
        }
    }
}
