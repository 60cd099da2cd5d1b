//! Building a grid: choose the resolution, list each primitive in every cell it touches, and
//! pack the lists into one array in cell order.

use super::layout::{CellList, Grid, GridOptions};
use super::probe::{finite_bounds, prim_id};
use super::resolution::{choose_resolution, planes};
use crate::structure::{Event, NodeId, Observer};
use crate::{Primitive, Vector};

impl<P: Primitive> Grid<P> {
    /// A grid with the default options ([`GridOptions::default`]).
    pub fn build(prims: &[P]) -> Self {
        Self::build_with(prims, &GridOptions::default())
    }

    /// A grid with the given options; see [`GridOptions`] for how the resolution is chosen.
    pub fn build_with(prims: &[P], options: &GridOptions) -> Self {
        Self::build_observed(prims, options, &mut ())
    }

    /// Builds the grid, reporting a [`Event::BuildLeaf`] for every non-empty cell (in
    /// linear-index order, with the number of primitives it lists).
    ///
    /// Each primitive goes to every cell its bounding box touches when that is a single cell
    /// (it then lies inside it); otherwise to those of them it shares a point with, decided by
    /// the exact [`Primitive::intersects_aabb`], so a triangle crossing a cell's corner is not
    /// listed in the cells its box merely covers. The (cell, primitive) pairs are then sorted
    /// into cell order by a counting sort, which keeps each list ascending. `O(n + cells +
    /// references)` besides the exact tests. Primitives with a NaN or infinite coordinate are
    /// left out ([`Primitive::has_finite_coordinates`]).
    pub fn build_observed<O: Observer<P::Point>>(
        prims: &[P],
        options: &GridOptions,
        observer: &mut O,
    ) -> Self {
        let (bounds, placed) = finite_bounds(prims);
        let dims = choose_resolution(&bounds, placed, options);
        let mut grid = Self {
            prims: prims.to_vec(),
            bounds,
            dims,
            planes: std::array::from_fn(|i| {
                if i < P::Point::DIM && dims[i] > 0 {
                    planes(bounds.min.coord(i), bounds.max.coord(i), dims[i])
                } else {
                    Vec::new()
                }
            }),
            cell_lists: Vec::new(),
            cell_prims: Vec::new(),
            spare: 0,
            unplaced: Vec::new(),
            options: *options,
        };
        if grid.cell_count() == 0 {
            return grid;
        }

        // Every (cell, primitive) pair, in primitive order.
        let mut pairs: Vec<(u32, u32)> = Vec::with_capacity(placed + placed / 2);
        let mut cells = Vec::new();
        for (i, prim) in prims.iter().enumerate() {
            if prim.has_finite_coordinates() {
                grid.cells_of(prim, &mut cells);
                pairs.extend(cells.iter().map(|&c| (c, prim_id(i))));
            }
        }

        // Counting sort by cell: stable, so each cell's list stays ascending.
        let cell_count = grid.cell_count();
        let mut start = vec![0u32; cell_count + 1];
        for &(c, _) in &pairs {
            start[c as usize + 1] += 1;
        }
        for c in 0..cell_count {
            start[c + 1] += start[c];
        }
        let mut next = start.clone();
        let mut lists = vec![0u32; pairs.len()];
        for &(c, i) in &pairs {
            lists[next[c as usize] as usize] = i;
            next[c as usize] += 1;
        }
        grid.cell_lists = start
            .windows(2)
            .map(|w| CellList {
                start: w[0],
                len: w[1] - w[0],
                room: w[1] - w[0],
            })
            .collect();
        grid.cell_prims = lists;

        for c in 0..cell_count {
            let count = grid.cell_lists[c].len;
            if count > 0 {
                observer.on(Event::BuildLeaf {
                    node: NodeId(c as u32),
                    prims: count,
                });
            }
        }
        grid
    }
}
