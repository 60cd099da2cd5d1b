//! The uniform grid (lecture §3, "Uniform spatial subdivision"), in 2D and 3D.
//!
//! - [`layout`]: the [`Grid`] and its [`GridOptions`]; the cell lists in one array.
//! - [`resolution`]: how many cells (Cleary and Wyvill's rule), and where their boundaries lie.
//! - [`build`]: each primitive listed in exactly the cells it touches.
//! - [`ray`]: first hit, any hit, all hits, with mailboxing, over the cells that [`dda`]
//!   walks.
//! - [`dda`]: the conservative cell walk along a ray (Amanatides and Woo's 3D-DDA).
//! - [`nearest`]: k nearest, searching outward from the query point's cell.
//! - [`range`]: the primitives in a range.
//! - [`collide`]: grid-against-grid collision.
//! - [`update`]: [`Grid::insert`], [`Grid::remove`] and [`Grid::replace`], which edit only
//!   the cells a primitive covered and now covers; the box and cells stay as built, and a
//!   primitive outside the box is kept in the unplaced list that every query tests.
//! - [`validate`]: invariants and statistics.
//! - `tolerance` and `probe` (crate-private): the rounding tolerances and the per-query
//!   bookkeeping that the grid and the quadtree/octree ([`super::quadtree`]) share.
//!
//! Query events (their order is written as a grammar in
//! [`observe`](crate::structure::observe#the-order-of-events)): ray queries report
//! [`Event::CellEnter`] for each cell walked (with its coordinates and `[t_enter, t_exit]`),
//! [`Event::PrimitiveTest`] (including `AlreadyTested` for mailboxed primitives),
//! [`Event::HitBeyondRegion`] for a hit beyond the current cell, [`Event::NewBest`] (first
//! hit) and a final [`Event::Prune`] (`BeyondBestHit`, at `Stop`) for the cell at which the
//! walk stops. The k-nearest query reports [`Event::DistanceBoundTest`] for each cell it
//! measures, [`Event::EnterNode`] for each cell it searches, `Prune(NoNearer, at Test)` for
//! cells it drops. Range reports `EnterNode` per cell and `Prune(NoOverlap, at Test)` for
//! cells a ball misses; collision reports [`Event::NodePairTest`] for each pair of non-empty
//! overlapping cells and [`Event::PairTest`] per primitive pair. Cells are named by their
//! linear index ([`Grid::cell_index`]).
//!
//! [`Event::CellEnter`]: crate::Event::CellEnter
//! [`Event::PrimitiveTest`]: crate::Event::PrimitiveTest
//! [`Event::HitBeyondRegion`]: crate::Event::HitBeyondRegion
//! [`Event::NewBest`]: crate::Event::NewBest
//! [`Event::Prune`]: crate::Event::Prune
//! [`Event::DistanceBoundTest`]: crate::Event::DistanceBoundTest
//! [`Event::EnterNode`]: crate::Event::EnterNode
//! [`Event::NodePairTest`]: crate::Event::NodePairTest
//! [`Event::PairTest`]: crate::Event::PairTest

pub mod build;
pub mod collide;
pub mod dda;
pub mod layout;
pub mod nearest;
pub(crate) mod probe;
pub mod range;
pub mod ray;
pub mod resolution;
pub(crate) mod tolerance;
pub mod update;
pub mod validate;

#[cfg(test)]
mod tests;

pub use layout::{CellCoords, Grid, GridOptions};

use super::{
    Hit, Nearest, Observer, PointOf, RangeShape, SpatialIndex, Stats, Traced, ValidationError,
};
use crate::structure::query::{placed_all_traced, placed_traced};
use crate::{Primitive, Ray};

impl<P: Primitive> SpatialIndex for Grid<P> {
    type Prim = P;

    /// [`Grid::build`]: the default resolution.
    fn build(prims: &[P]) -> Self {
        Grid::build(prims)
    }

    fn primitives(&self) -> &[P] {
        &self.prims
    }

    fn ray_first_hit_observed<O: Observer<PointOf<Self>>>(
        &self,
        ray: &Ray<PointOf<Self>>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>> {
        placed_traced(self.walk_first_hit(ray, t_max, observer), &self.prims, ray)
    }

    fn ray_any_hit_observed<O: Observer<PointOf<Self>>>(
        &self,
        ray: &Ray<PointOf<Self>>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>> {
        placed_traced(self.walk_any_hit(ray, t_max, observer), &self.prims, ray)
    }

    fn ray_all_hits_observed<O: Observer<PointOf<Self>>>(
        &self,
        ray: &Ray<PointOf<Self>>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Vec<Hit>> {
        placed_all_traced(self.walk_all_hits(ray, t_max, observer), &self.prims, ray)
    }

    fn k_nearest_observed<O: Observer<PointOf<Self>>>(
        &self,
        point: PointOf<Self>,
        k: usize,
        observer: &mut O,
    ) -> Traced<Vec<Nearest<PointOf<Self>>>> {
        self.search_nearest(point, k, observer)
    }

    fn range_observed<O: Observer<PointOf<Self>>>(
        &self,
        shape: &RangeShape<PointOf<Self>>,
        observer: &mut O,
    ) -> Traced<Vec<usize>> {
        self.search_range(shape, observer)
    }

    fn collide_observed<O: Observer<PointOf<Self>>>(
        &self,
        other: &Self,
        observer: &mut O,
    ) -> Traced<Vec<(usize, usize)>> {
        self.search_collisions(other, observer)
    }

    fn stats(&self) -> Stats {
        self.grid_stats()
    }

    fn validate(&self) -> Result<(), ValidationError> {
        self.check()
    }
}
