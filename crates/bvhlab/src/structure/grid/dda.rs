//! Walking a ray through the grid cell by cell: the 3D-DDA of Amanatides and Woo ("A Fast
//! Voxel Traversal Algorithm for Ray Tracing", Eurographics 1987), written once for any
//! dimension, made conservative.
//!
//! The classic walk keeps, per axis, the `t` at which the ray crosses the next cell boundary
//! and steps along the axis whose crossing comes first. Here those crossings are recomputed
//! from the boundary values in `f64` at each step (no accumulated `t_delta` drift), and the
//! walk never skips a cell the exact ray could touch:
//!
//! - **Near corners.** When the next crossings of several axes lie within the rounding
//!   tolerance of each other, the ray passes (nearly) through an edge or corner of the cell,
//!   and the order of the crossings cannot be trusted. Every cell the ray could pass through
//!   there is visited: all cells reached by stepping a non-empty proper subset of those axes,
//!   then the walk steps all of them at once.
//! - **Along boundaries.** A ray with a zero direction component that runs on (or within the
//!   tolerance of) a cell boundary plane lies in the cells on both sides; both are visited,
//!   for the whole walk. A component so small that the ray moves less than the tolerance
//!   along that axis while it crosses the grid counts as zero: such a ray may leave a flat
//!   grid's single layer at once, in exact arithmetic, and still hit what lies in it (hits
//!   are only as exact as `f32` coordinates).
//! - **At the entry.** The entry point is computed, so it may round into the next cell across
//!   a boundary it actually reaches a moment later; when it lies within the tolerance of the
//!   boundary behind it, the walk starts one cell further back.
//! - **Outside the grid.** The ray is first clipped to the grid's box, grown by the
//!   tolerance, and the entry cell is clamped to the grid.
//! - **A tolerance as wide as a cell.** All of the above looks one cell to each side, which
//!   is enough while the tolerance is narrower than a cell. It is not for a ray from very far
//!   away (the tolerance grows with the origin's magnitude: from 1e6 cell widths away it is a
//!   cell wide), where a "tie" can span several cells and stepping the tied axes at once
//!   skipped the cells between. Such a ray visits every cell its tolerance band touches,
//!   sorted by where it enters them (`Grid::walk_wide`).

use std::ops::ControlFlow;

use super::layout::{CellCoords, Grid};
use super::tolerance::{RayTolerance, ray_box_interval};
use crate::{Primitive, Ray, Vector};

/// One cell of the walk and where the ray is inside it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct CellVisit {
    /// The cell's linear index.
    pub cell: u32,
    /// Its coordinates.
    pub coords: CellCoords,
    /// Where the ray enters it.
    pub t_enter: f64,
    /// Where the ray leaves it.
    pub t_exit: f64,
}

/// The per-axis state of the walk (axes beyond the dimension stay at cell 0, never step).
#[derive(Clone, Copy, Debug, Default)]
struct Axis {
    /// The current cell along this axis.
    cell: i64,
    /// `+1`, `-1` or `0` (the ray is parallel to this axis' boundaries).
    step: i64,
    /// Where the ray crosses into the next cell along this axis (`inf` when parallel).
    t_next: f64,
    /// For a parallel axis: offsets (`-1`, `+1`) of neighbouring cells whose shared boundary
    /// the ray runs along, visited together with every cell of the walk.
    beside: [i64; 2],
    beside_len: usize,
}

impl<P: Primitive> Grid<P> {
    /// Calls `visit` for every cell the ray passes through (or passes within the rounding
    /// tolerance of), in the order the ray reaches them, until `visit` breaks or the ray
    /// leaves the grid.
    pub(super) fn walk_ray(
        &self,
        ray: &Ray<P::Point>,
        tol: &RayTolerance,
        mut visit: impl FnMut(CellVisit) -> ControlFlow<()>,
    ) {
        let dim = P::Point::DIM;
        if self.cell_count() == 0 {
            return;
        }
        let Some((t_start, t_end)) = ray_box_interval(ray, &self.bounds, tol.len) else {
            return;
        };
        if self.tolerance_spans_a_cell(tol) {
            self.walk_wide(ray, tol, visit);
            return;
        }
        let mut axes = [Axis::default(); 3];
        for (i, axis) in axes.iter_mut().enumerate().take(dim) {
            *axis = self.start_axis(ray, i, (t_start, t_end), tol);
        }
        let axes_beside = axes.iter().any(|a| a.beside_len > 0);
        let mut t_enter = t_start;
        loop {
            let t_min = axes[..dim]
                .iter()
                .map(|a| a.t_next)
                .fold(f64::INFINITY, f64::min);
            let coords = Self::coords_of(&axes);
            if self
                .visit_beside(
                    &axes,
                    axes_beside,
                    coords,
                    (t_enter, t_min.max(t_enter)),
                    &mut visit,
                )
                .is_break()
                || !t_min.is_finite()
            {
                return;
            }
            // The axes whose crossings (nearly) tie with the first one.
            let ties: u32 = (0..dim)
                .filter(|&i| axes[i].t_next <= t_min + tol.t)
                .fold(0, |m, i| m | 1 << i);
            if ties.count_ones() > 1 {
                let mut subset = (ties - 1) & ties;
                while subset != 0 {
                    if let Some(c) = self.stepped(&axes, subset) {
                        let cell_box = self.cell_box(c);
                        let span = ray_box_interval(ray, &cell_box, 0.0).unwrap_or((t_min, t_min));
                        if self
                            .visit_beside(&axes, axes_beside, c, span, &mut visit)
                            .is_break()
                        {
                            return;
                        }
                    }
                    subset = (subset - 1) & ties;
                }
            }
            for (i, axis) in axes.iter_mut().enumerate().take(dim) {
                if ties >> i & 1 == 1 {
                    axis.cell += axis.step;
                    if axis.cell < 0 || axis.cell >= i64::from(self.dims[i]) {
                        return;
                    }
                    axis.t_next = self.crossing(ray, i, axis.cell, axis.step);
                }
            }
            t_enter = t_min;
        }
    }

    /// Whether the rounding tolerance is half a cell wide or more along an axis with several
    /// cells: then the one-cell look-around of the walk is not enough.
    fn tolerance_spans_a_cell(&self, tol: &RayTolerance) -> bool {
        (0..P::Point::DIM).any(|i| {
            let n = self.dims[i] as usize;
            n > 1 && (0..n).any(|k| self.plane(i, k + 1) - self.plane(i, k) <= 2.0 * tol.len)
        })
    }

    /// Every cell whose box, grown by the tolerance, the ray passes through, in the order the
    /// ray enters them (ties by index): the walk for a tolerance as wide as a cell. It tests
    /// every cell, so it is kept for those rays alone.
    fn walk_wide(
        &self,
        ray: &Ray<P::Point>,
        tol: &RayTolerance,
        mut visit: impl FnMut(CellVisit) -> ControlFlow<()>,
    ) {
        let mut cells = Vec::new();
        for z in 0..self.dims[2] {
            for y in 0..self.dims[1] {
                for x in 0..self.dims[0] {
                    let coords = [x, y, z];
                    let cell_box = self.cell_box(coords);
                    if let Some((t_enter, t_exit)) = ray_box_interval(ray, &cell_box, tol.len) {
                        cells.push(CellVisit {
                            cell: self.cell_index(coords) as u32,
                            coords,
                            t_enter,
                            t_exit,
                        });
                    }
                }
            }
        }
        cells.sort_by(|a, b| a.t_enter.total_cmp(&b.t_enter).then(a.cell.cmp(&b.cell)));
        for cell in cells {
            if visit(cell).is_break() {
                return;
            }
        }
    }

    /// The walk's state along axis `i`, for the ray inside the grown grid box over
    /// `[t_start, t_end]`.
    fn start_axis(
        &self,
        ray: &Ray<P::Point>,
        i: usize,
        (t_start, t_end): (f64, f64),
        tol: &RayTolerance,
    ) -> Axis {
        let (o, d) = (
            f64::from(ray.origin().coord(i)),
            f64::from(ray.dir().coord(i)),
        );
        let n = i64::from(self.dims[i]);
        let p = o + t_start * d;
        let mut cell = i64::from(self.locate(i, p));
        // How far the ray moves along this axis inside the grid (NaN for `0 · inf`: parallel).
        let drift = d.abs() * (t_end - t_start);
        let step = if d == 0.0 || drift.is_nan() || drift <= tol.len {
            0
        } else if d > 0.0 {
            1
        } else {
            -1
        };
        // Start one cell back when the entry point may have rounded across the boundary
        // behind it.
        let k = cell as usize;
        if step > 0 && cell > 0 && p - self.plane(i, k) <= tol.len {
            cell -= 1;
        } else if step < 0 && cell < n - 1 && self.plane(i, k + 1) - p <= tol.len {
            cell += 1;
        }
        let mut axis = Axis {
            cell,
            step,
            t_next: f64::INFINITY,
            beside: [0; 2],
            beside_len: 0,
        };
        if step == 0 {
            // The ray stays within `drift` of `p` along this axis.
            let k = cell as usize;
            let reach = tol.len + if drift.is_nan() { 0.0 } else { drift };
            if cell > 0 && (p - self.plane(i, k)).abs() <= reach {
                axis.beside[axis.beside_len] = -1;
                axis.beside_len += 1;
            }
            if cell < n - 1 && (self.plane(i, k + 1) - p).abs() <= reach {
                axis.beside[axis.beside_len] = 1;
                axis.beside_len += 1;
            }
        } else {
            axis.t_next = self.crossing(ray, i, cell, step);
        }
        axis
    }

    /// Where the ray leaves cell `cell` along axis `i`, moving by `step`.
    fn crossing(&self, ray: &Ray<P::Point>, i: usize, cell: i64, step: i64) -> f64 {
        let (o, d) = (
            f64::from(ray.origin().coord(i)),
            f64::from(ray.dir().coord(i)),
        );
        let k = if step > 0 { cell + 1 } else { cell } as usize;
        (self.plane(i, k) - o) / d
    }

    fn coords_of(axes: &[Axis; 3]) -> CellCoords {
        axes.map(|a| a.cell as u32)
    }

    /// The current cell stepped along the axes in `mask`, if still inside the grid.
    fn stepped(&self, axes: &[Axis; 3], mask: u32) -> Option<CellCoords> {
        let mut c = [0; 3];
        for (i, axis) in axes.iter().enumerate() {
            let k = axis.cell + if mask >> i & 1 == 1 { axis.step } else { 0 };
            if k < 0 || k >= i64::from(self.dims[i]) {
                return None;
            }
            c[i] = k as u32;
        }
        Some(c)
    }

    /// Visits cell `c` and, for a ray running along boundaries (`beside`), its neighbours
    /// across them.
    fn visit_beside(
        &self,
        axes: &[Axis; 3],
        beside: bool,
        c: CellCoords,
        (t_enter, t_exit): (f64, f64),
        visit: &mut impl FnMut(CellVisit) -> ControlFlow<()>,
    ) -> ControlFlow<()> {
        let mut one = |coords: CellCoords| {
            visit(CellVisit {
                cell: self.cell_index(coords) as u32,
                coords,
                t_enter,
                t_exit,
            })
        };
        if !beside {
            return one(c);
        }
        // Offsets per axis: 0 first, then the neighbours across the boundaries the ray runs on.
        let offsets = axes.map(|a| {
            let mut o = [0i64; 3];
            o[1..=a.beside_len].copy_from_slice(&a.beside[..a.beside_len]);
            (o, a.beside_len + 1)
        });
        for &dz in &offsets[2].0[..offsets[2].1] {
            for &dy in &offsets[1].0[..offsets[1].1] {
                for &dx in &offsets[0].0[..offsets[0].1] {
                    let shift = |k: u32, by: i64| (i64::from(k) + by) as u32;
                    one([shift(c[0], dx), shift(c[1], dy), shift(c[2], dz)])?;
                }
            }
        }
        ControlFlow::Continue(())
    }
}
