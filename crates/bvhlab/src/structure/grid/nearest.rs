//! The k nearest primitives in the grid: start in the query point's cell and search outward,
//! ring by ring.
//!
//! Ring `ρ` is the shell of cells whose index differs from the start cell's by exactly `ρ`
//! along some axis (Chebyshev distance `ρ`). Every cell of ring `ρ` lies at least `ρ - 1`
//! cell widths from the start cell, so at least `√(d_G² + ((ρ - 1) w)²)` from the query point,
//! where `w` is the narrowest cell width and `d_G` the point's distance to the grid box (for a
//! point outside, the start cell is the one nearest to it, which holds the point's projection
//! `p` onto the box, and `|q - x|² >= |q - p|² + |p - x|²` for every `x` in the box). Rings
//! are searched while that bound is below the k-th best distance so far; within a ring, a
//! cell is searched only when its own box is nearer than the k-th best (branch and bound).
//! This is the lecture's distance query ("descend to the cell of the query point, then search
//! outward, pruning cells whose distance exceeds the best found so far") on a uniform grid:
//! cell coordinates do the descending, and no priority queue or visited set is needed.

use super::layout::{CellCoords, Grid, cells_in};
use super::probe::NearestProbe;
use super::tolerance::{box_distance, box_max_abs, max_abs, may_be_nearer};
use crate::structure::{Event, Nearest, NodeId, Observer, PruneAt, PruneReason, Traced};
use crate::{Primitive, Vector};

impl<P: Primitive> Grid<P> {
    /// The `k` nearest primitives to `point`, nearest first.
    pub(super) fn search_nearest<O: Observer<P::Point>>(
        &self,
        point: P::Point,
        k: usize,
        observer: &mut O,
    ) -> Traced<Vec<Nearest<P::Point>>> {
        let mut probe = NearestProbe::new(&self.prims, point, k);
        if !point.is_finite() || k == 0 {
            return probe.finish();
        }
        for &i in &self.unplaced {
            probe.test(i, observer);
        }
        if self.cell_count() == 0 {
            return probe.finish();
        }
        let dim = P::Point::DIM;
        let scale = max_abs(point).max(box_max_abs(&self.bounds));
        let mut start: CellCoords = [0; 3];
        for (i, c) in start.iter_mut().enumerate().take(dim) {
            *c = self.locate(i, f64::from(point.coord(i)));
        }
        let outside = box_distance(&self.bounds, point);
        let width = self.narrowest_cell() * (1.0 - 1e-6);
        let last_ring = (0..dim)
            .map(|i| start[i].max(self.dims[i] - 1 - start[i]))
            .max()
            .unwrap_or(0);
        for ring in 0..=last_ring {
            let gap = if ring > 1 {
                f64::from(ring - 1) * width
            } else {
                0.0
            };
            let ring_bound = outside.hypot(gap);
            if !may_be_nearer(ring_bound, probe.bound(), scale) {
                break;
            }
            let clip = self.reach(point, probe.bound(), scale);
            Self::for_each_in_ring(start, ring, clip, |coords| {
                self.search_cell(coords, point, scale, &mut probe, observer);
            });
        }
        probe.finish()
    }

    /// Searches one cell of a ring: an empty one is only entered; a non-empty one is measured
    /// and then searched or pruned.
    fn search_cell<O: Observer<P::Point>>(
        &self,
        coords: CellCoords,
        point: P::Point,
        scale: f64,
        probe: &mut NearestProbe<'_, P>,
        observer: &mut O,
    ) {
        let cell = self.cell_index(coords);
        let node = NodeId(cell as u32);
        let prims = self.cell_primitives(cell);
        if !prims.is_empty() {
            let distance = box_distance(&self.cell_box(coords), point);
            probe.cost.bound_tests += 1;
            observer.on(Event::DistanceBoundTest {
                node,
                distance: distance as f32,
            });
            let best = probe.bound();
            if !may_be_nearer(distance, best, scale) {
                observer.on(Event::Prune {
                    node,
                    reason: PruneReason::NoNearer {
                        distance: distance as f32,
                        best,
                    },
                    at: PruneAt::Test,
                });
                return;
            }
        }
        probe.cost.nodes_visited += 1;
        observer.on(Event::EnterNode { node, depth: 0 });
        for &i in prims {
            probe.test(i, observer);
        }
    }

    /// The narrowest cell width over the axes with more than one cell (`inf` when every axis
    /// has one cell: then there is no second ring).
    fn narrowest_cell(&self) -> f64 {
        (0..P::Point::DIM)
            .filter(|&i| self.dims[i] > 1)
            .flat_map(|i| {
                self.planes[i]
                    .windows(2)
                    .map(|w| f64::from(w[1]) - f64::from(w[0]))
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// The range of cells that may lie within `bound` of `point`: those the box
    /// `point ± bound` (grown by the rounding tolerance) touches. All cells while `bound` is
    /// infinite.
    fn reach(&self, point: P::Point, bound: f32, scale: f64) -> (CellCoords, CellCoords) {
        let all = ([0; 3], self.dims.map(|n| n - 1));
        let bound = f64::from(bound);
        if !bound.is_finite() {
            return all;
        }
        let grow = bound + 1e-5 * bound + 1e-6 * scale + 1e-22;
        let (mut lo, mut hi) = all;
        for i in 0..P::Point::DIM {
            let x = f64::from(point.coord(i));
            let (from, to) = ((x - grow) as f32, (x + grow) as f32);
            lo[i] = self.first_cell_reaching(i, from.max(self.planes[i][0]));
            hi[i] = self.last_cell_reaching(i, to.min(self.planes[i][self.dims[i] as usize]));
        }
        (lo, hi)
    }

    /// Calls `f` once for every cell of ring `ring` around `start` inside `clip` (an
    /// inclusive coordinate range within the grid): for each axis `a` and side, the cells
    /// `ring` away along `a`, strictly less than `ring` away along the axes before `a`, and
    /// up to `ring` away along the axes after it.
    pub(super) fn for_each_in_ring(
        start: CellCoords,
        ring: u32,
        (clip_lo, clip_hi): (CellCoords, CellCoords),
        mut f: impl FnMut(CellCoords),
    ) {
        if ring == 0 {
            f(start);
            return;
        }
        let dim = P::Point::DIM;
        let ring = i64::from(ring);
        for a in 0..dim {
            for side in [-1, 1] {
                let at = i64::from(start[a]) + side * ring;
                if at < i64::from(clip_lo[a]) || at > i64::from(clip_hi[a]) {
                    continue;
                }
                let (mut lo, mut hi) = ([0u32; 3], [0u32; 3]);
                let mut empty = false;
                for i in 0..dim {
                    let reach = match i.cmp(&a) {
                        std::cmp::Ordering::Less => ring - 1,
                        std::cmp::Ordering::Equal => 0,
                        std::cmp::Ordering::Greater => ring,
                    };
                    let centre = if i == a { at } else { i64::from(start[i]) };
                    let from = (centre - reach).max(i64::from(clip_lo[i]));
                    let to = (centre + reach).min(i64::from(clip_hi[i]));
                    empty |= from > to;
                    (lo[i], hi[i]) = (from as u32, to as u32);
                }
                if empty {
                    continue;
                }
                cells_in((lo, hi)).for_each(&mut f);
            }
        }
    }
}
