//! Collision on the grid: the pairs that collide between two grids. It visits only the
//! cells of the other grid that a cell overlaps; a pair listed in several of them is tested
//! once.

use super::layout::{Grid, cells_in};
use super::probe::PairCollector;
use crate::structure::{Event, NodeId, Observer, Traced};
use crate::{BoundingVolume, Primitive};

impl<P: Primitive> Grid<P> {
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
