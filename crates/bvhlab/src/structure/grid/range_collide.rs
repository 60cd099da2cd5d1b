//! Region queries on the grid: the primitives in a range, and the pairs that collide between
//! two grids. Both visit only the cells that the region (or the other grid's cell) overlaps;
//! a primitive listed in several of them is tested once.

use super::layout::{Grid, cells_in};
use super::probe::{PairCollector, prim_id, test_range};
use super::tolerance::{box_max_abs, is_prunable_range, range_box, range_may_touch};
use crate::structure::{
    Event, Mailbox, NodeId, Observer, PruneAt, PruneReason, QueryCost, RangeShape, Traced,
};
use crate::{BoundingVolume, Primitive};

impl<P: Primitive> Grid<P> {
    /// The primitives that share a point with the region, ascending.
    ///
    /// The cells in the index range of the region's box are visited in linear order; for a
    /// ball, those its box covers but the ball misses are pruned. A region that is not a
    /// finite box or ball (NaN, infinite, inverted) is answered by testing every primitive.
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
        for &i in &self.unplaced {
            test_range(
                (i, &self.prims[i as usize]),
                shape,
                &mut cost,
                &mut found,
                observer,
            );
        }
        let mut mailbox = Mailbox::new();
        if let Some(range) = self.cell_range(&range_box(shape, box_max_abs(&self.bounds))) {
            for coords in cells_in(range) {
                let cell = self.cell_index(coords);
                let node = NodeId(cell as u32);
                if matches!(shape, RangeShape::Ball(_)) {
                    cost.bound_tests += 1;
                    if !range_may_touch(shape, &self.cell_box(coords), box_max_abs(&self.bounds)) {
                        observer.on(Event::Prune {
                            node,
                            reason: PruneReason::NoOverlap,
                            at: PruneAt::Test,
                        });
                        continue;
                    }
                }
                cost.nodes_visited += 1;
                observer.on(Event::EnterNode { node, depth: 0 });
                for &i in self.cell_primitives(cell) {
                    if mailbox.admit(i, observer) {
                        let prim = (i, &self.prims[i as usize]);
                        test_range(prim, shape, &mut cost, &mut found, observer);
                    }
                }
            }
        }
        found.sort_unstable();
        Traced {
            answer: found,
            cost,
        }
    }

    /// Every pair of a primitive of `self` and one of `other` that share a point, ascending.
    ///
    /// For each non-empty cell of `self`, the non-empty cells of `other` whose boxes overlap
    /// it ([`Event::NodePairTest`]); their primitives are tested pairwise, each pair once, a
    /// pair whose bounding boxes are apart being rejected without the exact test. Two
    /// primitives that share a point `x` are both listed in cells that contain `x`, and those
    /// cells overlap, so no pair is missed whatever the two resolutions.
    pub(super) fn search_collisions<O: Observer<P::Point>>(
        &self,
        other: &Self,
        observer: &mut O,
    ) -> Traced<Vec<(usize, usize)>> {
        let mut pairs = PairCollector::default();
        pairs.test_unplaced(
            (&self.prims, &self.unplaced),
            (&other.prims, &other.unplaced),
            observer,
        );
        for cell in 0..self.cell_count() {
            let mine = self.cell_primitives(cell);
            if mine.is_empty() {
                continue;
            }
            let cell_box = self.cell_box(self.cell_coords(cell));
            pairs.cost.nodes_visited += 1;
            let Some(range) = other.cell_range(&cell_box) else {
                continue;
            };
            for coords in cells_in(range) {
                let theirs_index = other.cell_index(coords);
                let theirs = other.cell_primitives(theirs_index);
                if theirs.is_empty() {
                    continue;
                }
                pairs.cost.bound_tests += 1;
                let overlap = cell_box.overlaps(&other.cell_box(coords));
                observer.on(Event::NodePairTest {
                    a: NodeId(cell as u32),
                    b: NodeId(theirs_index as u32),
                    overlap,
                });
                if !overlap {
                    continue;
                }
                for &a in mine {
                    for &b in theirs {
                        let pa = (a, &self.prims[a as usize]);
                        pairs.test(pa, (b, &other.prims[b as usize]), true, observer);
                    }
                }
            }
        }
        pairs.finish()
    }
}
