//! The grid's invariants and numbers.

use crate::structure::check_primitives_contract;
use std::cmp::Ordering;

use super::layout::Grid;
use crate::structure::{Stats, ValidationError};
use crate::{Primitive, Vector};

/// Up to this many (cell, primitive) pairs, validation tests every primitive against every
/// cell, independently of the build's candidate ranges.
const EXHAUSTIVE_PAIRS: usize = 50_000;

fn fail(message: String) -> Result<(), ValidationError> {
    Err(ValidationError::new(message))
}

impl<P: Primitive> Grid<P> {
    /// Cells, non-empty cells, the histogram of list lengths over all cells (bucket 0 counts
    /// the empty cells), references (cell entries plus the unplaced primitives, which every
    /// query tests), memory. A grid has no depth and no SAH cost.
    pub(super) fn grid_stats(&self) -> Stats {
        let cells = self.cell_count();
        let sizes = (0..cells).map(|c| self.cell_primitives(c).len());
        Stats {
            nodes: cells,
            leaves: sizes.clone().filter(|&n| n > 0).count(),
            max_depth: 0,
            leaf_sizes: Stats::leaf_size_histogram(sizes),
            primitives: self.prims.len(),
            references: self.listed() + self.unplaced.len(),
            memory_bytes: self.memory_bytes(),
            sah_cost: None,
        }
    }

    /// Checks the layout (planes, cell lists apart from each other, sorted lists), that the
    /// unplaced primitives are exactly the finite ones that do not fit in the grid's box
    /// (moved out by an update; one with a NaN or infinite coordinate is in no list at all),
    /// and that every primitive is listed
    /// in exactly the cells it shares a point with: against every cell on moderate inputs,
    /// else against the cells its box touches.
    pub(super) fn check(&self) -> Result<(), ValidationError> {
        self.check_shape()?;
        self.check_layout()?;
        check_primitives_contract(&self.prims)?;
        if self.unplaced.windows(2).any(|w| w[0] >= w[1]) {
            return fail("the unplaced list is not ascending".into());
        }
        for (i, prim) in self.prims.iter().enumerate() {
            let listed = self.unplaced.binary_search(&(i as u32)).is_ok();
            if self.belongs_unplaced(prim) != listed {
                let why = if !prim.has_finite_coordinates() {
                    "has a NaN or infinite coordinate but is listed as unplaced"
                } else if self.fits(prim) {
                    "fits in the grid box but is listed as unplaced"
                } else {
                    "sticks out of the grid box but is not listed as unplaced"
                };
                return fail(format!("primitive {i} {why}"));
            }
        }
        if self
            .unplaced
            .last()
            .is_some_and(|&i| i as usize >= self.prims.len())
        {
            return fail("the unplaced list names a primitive out of range".into());
        }
        let placed = self.prims.iter().filter(|prim| self.fits(prim)).count();
        if self.cell_count().saturating_mul(placed) <= EXHAUSTIVE_PAIRS {
            self.check_every_cell()
        } else {
            self.check_candidate_cells()
        }
    }

    /// What the other checks take for granted, and a grid loaded from a file may break: the
    /// cell count fits in a `usize` (every method multiplies the resolution out), a grid with
    /// cells has a finite box, and one without has no resolution at all.
    fn check_shape(&self) -> Result<(), ValidationError> {
        let cells = self
            .dims
            .iter()
            .try_fold(1usize, |product, &n| product.checked_mul(n as usize));
        match cells {
            None => fail(format!("the resolution {:?} has too many cells", self.dims)),
            Some(0) if self.dims != [0; 3] => {
                fail(format!("the resolution {:?} has an empty axis", self.dims))
            }
            Some(n) if n > 0 && !(self.bounds.min.is_finite() && self.bounds.max.is_finite()) => {
                fail(format!("the grid box {:?} is not finite", self.bounds))
            }
            _ => Ok(()),
        }
    }

    fn check_layout(&self) -> Result<(), ValidationError> {
        let cells = self.cell_count();
        let dim = P::Point::DIM;
        if self.dims[dim..].iter().any(|&n| n != 1 && cells > 0) {
            return fail(format!("unused axes must have one cell: {:?}", self.dims));
        }
        self.check_cell_lists(cells)?;
        if cells == 0 {
            return Ok(());
        }
        for i in 0..dim {
            let planes = &self.planes[i];
            if planes.len() != self.dims[i] as usize + 1
                || planes.first() != Some(&self.bounds.min.coord(i))
                || planes.last() != Some(&self.bounds.max.coord(i))
                || planes
                    .windows(2)
                    .any(|w| w[0].partial_cmp(&w[1]).is_none_or(Ordering::is_gt))
            {
                return fail(format!("the planes of axis {i} do not tile the grid box"));
            }
        }
        for c in 0..cells {
            let list = self.cell_primitives(c);
            if list.windows(2).any(|w| w[0] >= w[1])
                || list.iter().any(|&i| i as usize >= self.prims.len())
            {
                return fail(format!("cell {c}: list not ascending or out of range"));
            }
        }
        Ok(())
    }

    /// One list place per cell, each inside the list array with its length within its room,
    /// no two rooms sharing an entry, and the entries that hold no list entry counted as
    /// spare.
    fn check_cell_lists(&self, cells: usize) -> Result<(), ValidationError> {
        if self.cell_lists.len() != cells {
            return fail(format!(
                "{} cell lists for {cells} cells",
                self.cell_lists.len()
            ));
        }
        let mut owner = vec![u32::MAX; self.cell_prims.len()];
        for (c, list) in self.cell_lists.iter().enumerate() {
            let end = list.start as usize + list.room as usize;
            if list.len > list.room || end > owner.len() {
                return fail(format!("cell {c}: its list {list:?} overruns its room"));
            }
            for (slot, o) in owner[list.start as usize..end].iter_mut().enumerate() {
                if *o != u32::MAX {
                    return fail(format!(
                        "cells {o} and {c} share list entry {}",
                        list.start as usize + slot
                    ));
                }
                *o = c as u32;
            }
        }
        let spare = self.cell_prims.len() - self.listed();
        if spare != self.spare {
            return fail(format!(
                "{spare} entries of the list array are spare, {} counted",
                self.spare
            ));
        }
        Ok(())
    }

    /// Every placed primitive against every cell: listed exactly where it touches (or, should
    /// the exact test refuse every cell, in all the cells its box touches; see `cells_of`).
    fn check_every_cell(&self) -> Result<(), ValidationError> {
        let mut expected = vec![Vec::new(); self.cell_count()];
        let boxes: Vec<_> = (0..self.cell_count())
            .map(|c| self.cell_box(self.cell_coords(c)))
            .collect();
        for (i, prim) in self.prims.iter().enumerate() {
            if !self.fits(prim) {
                continue;
            }
            let mut touched = (0..boxes.len())
                .filter(|&c| prim.intersects_aabb(&boxes[c]))
                .peekable();
            if touched.peek().is_none() {
                let mut fallback = Vec::new();
                self.cells_of(prim, &mut fallback);
                for &c in &fallback {
                    expected[c as usize].push(i as u32);
                }
            } else {
                for c in touched {
                    expected[c].push(i as u32);
                }
            }
        }
        for (c, want) in expected.iter().enumerate() {
            if want.as_slice() != self.cell_primitives(c) {
                return fail(format!(
                    "cell {c} {:?} lists {:?}, but these touch it: {want:?}",
                    self.cell_coords(c),
                    self.cell_primitives(c)
                ));
            }
        }
        Ok(())
    }

    /// Every placed primitive against the cells its box touches.
    fn check_candidate_cells(&self) -> Result<(), ValidationError> {
        let mut cells = Vec::new();
        let mut total = 0;
        for (i, prim) in self.prims.iter().enumerate() {
            if !self.fits(prim) {
                continue;
            }
            self.cells_of(prim, &mut cells);
            total += cells.len();
            for &c in &cells {
                let listed = self.cell_primitives(c as usize).binary_search(&(i as u32));
                if listed.is_err() {
                    return fail(format!("primitive {i} touches cell {c} but is not listed"));
                }
                if !prim.intersects_aabb(&self.cell_box(self.cell_coords(c as usize))) {
                    return fail(format!(
                        "cell {c} lists primitive {i}, which does not touch it"
                    ));
                }
            }
        }
        if total != self.listed() {
            return fail(format!(
                "{} references, but the primitives touch {total} cells",
                self.listed()
            ));
        }
        Ok(())
    }
}
