//! The region quadtree (2D) and octree (3D): one implementation with 2^D children per cell
//! (lecture §3, "Non-uniform axis-aligned spatial subdivision"). The type is [`Orthtree`]
//! ("orthant tree", the name for every dimension); [`Quadtree2`](crate::Quadtree2) and
//! [`Octree3`](crate::Octree3) are its 2D and 3D aliases, and this folder serves both.
//!
//! - [`layout`]: the [`Orthtree`], its [`OrthtreeOptions`], 8-byte nodes, child boxes.
//! - [`build`]: top-down splitting, each primitive sent to every child it touches.
//! - [`ray`]: ray first hit, any hit, all hits, front to back with mailboxing.
//! - [`nearest`]: k nearest (the lecture's distance query), best-first from the query
//!   point's cell outward.
//! - [`range`]: the primitives in a range.
//! - [`collide`]: tree-against-tree collision by simultaneous descent.
//! - [`validate`]: invariants and statistics.
//!
//! The rounding tolerances and the per-query bookkeeping (mailbox, probes) are the grid's
//! (`grid/tolerance.rs`, `grid/probe.rs`), which both space partitions share.
//!
//! Query events (their order is written as a grammar in
//! [`observe`](crate::structure::observe#the-order-of-events)): ray queries report
//! [`Event::RayBoundTest`] per cell tested (with `Prune(RayMissed, at Test)` on a miss),
//! [`Event::ChildQueued`] for the children met in order of entry `t`, [`Event::EnterNode`],
//! [`Event::PrimitiveTest`] (including `AlreadyTested`), [`Event::HitBeyondRegion`] for a hit
//! beyond the current leaf, [`Event::NewBest`] (first hit) and `Prune(BeyondBestHit, at Pop)`
//! for the cells skipped once a nearer hit is known. The k-nearest query reports
//! [`Event::DistanceBoundTest`] per cell, `ChildQueued` (nearest first) or
//! `Prune(NoNearer, at Test)` per child, `EnterNode` per cell taken from the queue (the first
//! one no nearer than the best is `Prune(NoNearer, at Pop)`, and ends the search); range
//! reports `EnterNode` or `Prune(NoOverlap, at Pop)` per cell popped; collision reports
//! [`Event::NodePairTest`] and [`Event::PairTest`]. Nodes are named by their index (the root
//! is 0).
//!
//! [`Event::RayBoundTest`]: crate::Event::RayBoundTest
//! [`Event::ChildQueued`]: crate::Event::ChildQueued
//! [`Event::EnterNode`]: crate::Event::EnterNode
//! [`Event::PrimitiveTest`]: crate::Event::PrimitiveTest
//! [`Event::HitBeyondRegion`]: crate::Event::HitBeyondRegion
//! [`Event::NewBest`]: crate::Event::NewBest
//! [`Event::DistanceBoundTest`]: crate::Event::DistanceBoundTest
//! [`Event::NodePairTest`]: crate::Event::NodePairTest
//! [`Event::PairTest`]: crate::Event::PairTest

pub mod build;
pub mod collide;
pub mod layout;
pub mod nearest;
pub mod range;
pub mod ray;
pub mod validate;

#[cfg(test)]
mod tests;

pub use layout::{MAX_DEPTH, Orthtree, OrthtreeCell, OrthtreeOptions};

use super::{
    Hit, Nearest, Observer, PointOf, RangeShape, SpatialIndex, Stats, Traced, ValidationError,
};
use crate::structure::query::{placed_all_traced, placed_traced};
use crate::{Primitive, Ray};

impl<P: Primitive> SpatialIndex for Orthtree<P> {
    type Prim = P;

    /// [`Orthtree::build`]: the default options.
    fn build(prims: &[P]) -> Self {
        Orthtree::build(prims)
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
        self.tree_stats()
    }

    fn validate(&self) -> Result<(), ValidationError> {
        self.check()
    }
}
