//! Inserting, removing and moving primitives in a built grid (issue 20, "Moving geometry"):
//! only the cells a primitive covered and now covers are edited.
//!
//! The grid's box and cells are fixed at build time, so a primitive's cells depend on it
//! alone (`cells_of` in `layout.rs`, the build's own rule): an update takes the primitive
//! out of the cells it left and lists it in those it reached, each list edited in place and
//! kept ascending. Every cell list has room to grow (`start`, `len`, `room`); a list that
//! outgrows its room moves to the end of the list array with twice the room (a dynamic
//! array's doubling), and when the spare entries (room left, rooms left behind) outnumber
//! the listed entries and the cells together, all lists are packed again as a build packs
//! them, in O(cells + entries) paid for by the updates that made the spare ones. So an
//! update costs O(cells it covered + cells it covers), times their lists' lengths,
//! amortised, beside the exact primitive-cell tests (as in the build); nothing else is
//! touched.
//!
//! A primitive that does not lie inside the grid's box (it moved out, or was inserted
//! outside) goes to the unplaced list, which every query tests before walking the cells
//! ([`Grid::unplaced`]). Queries stay exact, and pay one test per such primitive: when many
//! wander out, rebuild the grid. A primitive given a NaN or infinite coordinate leaves its
//! cells and goes nowhere: no query answers with it ([`Primitive::has_finite_coordinates`]).

use super::layout::{CellList, Grid};
use crate::Primitive;
use crate::structure::update::{Removed, UpdateError, check_index};

/// The smallest room a list gets when it moves.
const MIN_ROOM: u32 = 4;

impl<P: Primitive> Grid<P> {
    /// Adds a primitive and returns its index, the old length of
    /// [`primitives`](crate::SpatialIndex::primitives); no other index changes. It is listed
    /// in the cells it touches, or, outside the grid's box, in [`unplaced`](Self::unplaced).
    ///
    /// ```
    /// use bvhlab::glam::Vec2;
    /// use bvhlab::prelude::*;
    ///
    /// let mut grid = Grid2::build(&[Segment2::new(Vec2::ZERO, Vec2::new(4.0, 4.0))]);
    /// let inside = grid.insert(Segment2::new(Vec2::new(0.0, 4.0), Vec2::new(4.0, 0.0)));
    /// let outside = grid.insert(Segment2::new(Vec2::new(9.0, 0.0), Vec2::new(9.0, 4.0)));
    /// assert_eq!((inside, outside), (1, 2));
    /// assert_eq!(grid.unplaced(), &[2]);
    /// grid.validate()?;
    /// let ray = Ray2::new(Vec2::new(-1.0, 1.0), Vec2::X)?;
    /// let hits = grid.ray_all_hits(&ray, f32::INFINITY);
    /// assert_eq!(hits.iter().map(|h| h.prim).collect::<Vec<_>>(), [0, 1, 2]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn insert(&mut self, prim: P) -> usize {
        let index = self.prims.len();
        self.prims.push(prim);
        self.place(index);
        index
    }

    /// Removes primitive `index` and returns it. The last primitive takes its index (a
    /// swap-remove): [`Removed::moved_from`] says which one moved, and no other index
    /// changes. The removed primitive leaves its cells, and the moved one is renamed in its
    /// own cells (each list stays ascending).
    ///
    /// # Errors
    /// [`UpdateError::NoSuchPrimitive`] when `index` is out of range; the grid is unchanged.
    pub fn remove(&mut self, index: usize) -> Result<Removed<P>, UpdateError> {
        check_index(index, self.prims.len())?;
        self.unplace(index);
        let last = self.prims.len() - 1;
        if index != last {
            self.unplace(last);
        }
        let prim = self.prims.swap_remove(index);
        if index == last {
            return Ok(Removed {
                prim,
                moved_from: None,
            });
        }
        self.place(index);
        Ok(Removed {
            prim,
            moved_from: Some(last),
        })
    }

    /// Moves (or reshapes) primitive `index` to `prim` and returns what it was; every index
    /// stays. It leaves the cells it no longer touches and joins those it now touches; the
    /// cells it touches before and after are not edited.
    ///
    /// # Errors
    /// [`UpdateError::NoSuchPrimitive`] when `index` is out of range; the grid is unchanged.
    pub fn replace(&mut self, index: usize, prim: P) -> Result<P, UpdateError> {
        check_index(index, self.prims.len())?;
        let (mut before, mut after) = (Vec::new(), Vec::new());
        self.cells_if_fits(&self.prims[index], &mut before);
        self.cells_if_fits(&prim, &mut after);
        let id = index as u32;
        // Both lists ascend: walk them together, leaving cells only in `before` and
        // joining cells only in `after`.
        let (mut i, mut j) = (0, 0);
        while i < before.len() || j < after.len() {
            match (before.get(i), after.get(j)) {
                (Some(&b), Some(&a)) if b == a => (i, j) = (i + 1, j + 1),
                (Some(&b), a) if a.is_none_or(|&a| b < a) => {
                    self.leave(b as usize, id);
                    i += 1;
                }
                (_, Some(&a)) => {
                    self.join(a as usize, id);
                    j += 1;
                }
                (_, None) => unreachable!("the loop runs while one list has cells"),
            }
        }
        match (
            self.belongs_unplaced(&self.prims[index]),
            self.belongs_unplaced(&prim),
        ) {
            (false, true) => insert_sorted(&mut self.unplaced, id),
            (true, false) => remove_sorted(&mut self.unplaced, id),
            _ => {}
        }
        Ok(std::mem::replace(&mut self.prims[index], prim))
    }

    /// The cells `prim` is listed in (its candidate cells refined by the exact test), or
    /// none when it does not fit in the grid's box; returns whether it fits.
    fn cells_if_fits(&self, prim: &P, out: &mut Vec<u32>) -> bool {
        out.clear();
        let fits = self.fits(prim);
        if fits {
            self.cells_of(prim, out);
        }
        fits
    }

    /// Lists primitive `index` (already in `prims`) in its cells, or as unplaced (or
    /// nowhere, when it is not finite).
    fn place(&mut self, index: usize) {
        let mut cells = Vec::new();
        if self.cells_if_fits(&self.prims[index], &mut cells) {
            for c in cells {
                self.join(c as usize, index as u32);
            }
        } else if self.belongs_unplaced(&self.prims[index]) {
            insert_sorted(&mut self.unplaced, index as u32);
        }
    }

    /// Takes primitive `index` out of its cells, or out of the unplaced list.
    fn unplace(&mut self, index: usize) {
        let mut cells = Vec::new();
        if self.cells_if_fits(&self.prims[index], &mut cells) {
            for c in cells {
                self.leave(c as usize, index as u32);
            }
        } else if self.belongs_unplaced(&self.prims[index]) {
            remove_sorted(&mut self.unplaced, index as u32);
        }
    }

    /// Adds `id` to a cell's list, keeping it ascending; a full list first moves to the end
    /// of the array with twice the room.
    fn join(&mut self, cell: usize, id: u32) {
        let mut list = self.cell_lists[cell];
        if list.len == list.room {
            // The old room is left behind, all spare; the new one is spare but for the list.
            let room = (2 * list.room).max(MIN_ROOM);
            let start = self.cell_prims.len();
            self.cell_prims.extend_from_within(list.range());
            self.cell_prims.resize(start + room as usize, 0);
            self.spare += room as usize;
            list = CellList {
                start: start as u32,
                len: list.len,
                room,
            };
        }
        let entries = &mut self.cell_prims[list.start as usize..(list.start + list.room) as usize];
        let at = entries[..list.len as usize].partition_point(|&p| p < id);
        entries[at..=list.len as usize].rotate_right(1);
        entries[at] = id;
        list.len += 1;
        self.spare -= 1;
        self.cell_lists[cell] = list;
        if 2 * self.spare > self.cell_prims.len() + self.cell_lists.len() {
            self.compact();
        }
    }

    /// Takes `id` out of a cell's list (it must be there).
    fn leave(&mut self, cell: usize, id: u32) {
        let list = &mut self.cell_lists[cell];
        let entries = &mut self.cell_prims[list.range()];
        let at = entries
            .binary_search(&id)
            .expect("a primitive leaves only cells that list it");
        entries[at..].rotate_left(1);
        list.len -= 1;
        self.spare += 1;
        if 2 * self.spare > self.cell_prims.len() + self.cell_lists.len() {
            self.compact();
        }
    }

    /// Packs the lists again in cell order with no room to spare, as a build does.
    fn compact(&mut self) {
        let mut packed = Vec::with_capacity(self.cell_prims.len() - self.spare);
        for list in &mut self.cell_lists {
            let start = packed.len() as u32;
            packed.extend_from_slice(&self.cell_prims[list.range()]);
            *list = CellList {
                start,
                len: list.len,
                room: list.len,
            };
        }
        self.cell_prims = packed;
        self.spare = 0;
    }
}

fn insert_sorted(list: &mut Vec<u32>, id: u32) {
    let at = list.partition_point(|&p| p < id);
    list.insert(at, id);
}

fn remove_sorted(list: &mut Vec<u32>, id: u32) {
    if let Ok(at) = list.binary_search(&id) {
        list.remove(at);
    }
}
