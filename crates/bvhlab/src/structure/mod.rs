//! Spatial data structures (lecture §3) and the one query interface they all answer.
//!
//! Every structure answers [`RayCast`] (ray first hit, any hit) and [`PointQuery`] (closest
//! point, distance), as volumes and primitives do, and [`SpatialQuery`] (all hits, k nearest,
//! range): code that takes any structure, the fast [`Bvh4`](bvh::Bvh4) included, is written
//! against these. Every structure but [`Bvh4`](bvh::Bvh4) also answers [`SpatialIndex`]:
//! each query in an `_observed` form that reports every step to an [`Observer`] and returns
//! its [`QueryCost`], collision, statistics and validation. [`BruteForce`] answers the same
//! queries by testing every primitive: it is the reference the tests compare against and the
//! baseline the lab shows beside each structure.
//!
//! ## Where each structure lives
//!
//! One folder per structure, and one file name per job across them (a folder where a job
//! has several files):
//!
//! | structure | layout | build | ray | nearest | range, collide | validate |
//! | --- | --- | --- | --- | --- | --- | --- |
//! | [`Bvh`] ([`bvh`]) | `layout/` | `build/` | `walk/ray.rs`, `walk/fast_ray.rs` | `walk/nearest.rs`, `walk/fast_nearest.rs` | `walk/range.rs`, `walk/collide.rs` | `validate.rs` |
//! | [`KdTree`] ([`kdtree`]) | `layout.rs` | `build/` | `plane_tree/ray.rs` | `plane_tree/nearest.rs` | `plane_tree/range.rs`, `collide.rs` | `validate.rs` |
//! | [`BspTree`] ([`bsp`]) | `layout.rs`, `plane.rs` | `build.rs`, `splitter.rs` | `plane_tree/ray.rs` | `plane_tree/nearest.rs` | `plane_tree/range.rs`, `collide.rs` | `validate.rs` |
//! | [`Grid`] ([`grid`]) | `layout.rs` | `build.rs`, `resolution.rs` | `ray.rs` over `dda.rs` | `nearest.rs` | `range.rs`, `collide.rs` | `validate.rs` |
//! | quadtree, octree: [`Orthtree`] ([`quadtree`]) | `layout.rs` | `build.rs` | `ray.rs` | `nearest.rs` | `range.rs`, `collide.rs` | `validate.rs` |
//! | [`BruteForce`] | `brute_force.rs` | | | | | |
//!
//! The k-d tree and the BSP tree share their walks in [`plane_tree`] (a k-d tree is a BSP tree
//! with axis-aligned planes); the grid and the quadtree share their rounding tolerances and
//! per-query bookkeeping (`grid/tolerance.rs`, `grid/probe.rs`). Beside the structures:
//! [`observe`] (the events), [`query`] (answers and their cost), [`outline`] (what the lab
//! draws), [`stats`], [`mailbox`], and [`update`]: what inserting, removing and moving a
//! primitive does to indices, and what it costs in each structure.

pub mod brute_force;
pub mod bsp;
pub mod bvh;
pub mod grid;
mod index_sort;
pub mod kdtree;
pub mod mailbox;
pub mod observe;
pub mod outline;
pub mod plane_tree;
#[doc(alias = "octree", alias = "orthtree")]
pub mod quadtree;
pub mod query;
pub mod spatial_query;
pub mod stats;
pub mod update;

pub use brute_force::BruteForce;
pub use bsp::{BspOptions, BspTree};
pub use bvh::{Bvh, BvhOptions, SplitMethod};
pub use grid::{Grid, GridOptions};
pub use kdtree::{KdTree, KdTreeOptions};
pub use mailbox::Mailbox;
pub use observe::{Event, NodeId, Observer, PrimitiveResult, PruneAt, PruneReason, Recorder};
pub use outline::{NodeOutline, NodeShape, Outline, SplitPlane};
pub use quadtree::{Orthtree, OrthtreeOptions};
pub use query::{Hit, HitTracker, Nearest, NearestSet, QueryCost, RangeShape, Traced};
pub use spatial_query::SpatialQuery;
pub use stats::{Stats, ValidationError};
pub use update::{Removed, UpdateError};

#[cfg(doc)]
use crate::queries::{PointQuery, RayCast};
use crate::{Primitive, Ray};

/// The vector type a structure works in.
pub type PointOf<S> = <<S as SpatialIndex>::Prim as Primitive>::Point;

/// The queries every spatial structure answers, exactly, each observed step by step: what
/// the lab steps through.
///
/// The first hit, any hit and the closest point are the questions volumes and primitives
/// answer too: [`RayCast`] and [`PointQuery`]; all hits, the k nearest and range are
/// [`SpatialQuery`]'s. Every structure implements all three (the macro
/// `queries_by_observed_walks!` answers them by the observed walks with no observer; the
/// [`Bvh`] has faster unobserved first-hit and closest-point walks of its own). This trait
/// adds each query observed step by step, collision, and the structure's statistics and
/// invariants.
///
/// Primitives are named by their index in the slice the structure was built from. Answers
/// are deterministic and equal to [`BruteForce`]'s: hits at equal `t` and neighbours at equal
/// distance are ordered by index. A query point with a NaN or infinite coordinate gets no
/// answer (`None` or empty); the `checked_` forms report it as an error instead. A primitive
/// with a NaN or infinite coordinate is never an answer, from any structure or from brute
/// force ([`Primitive::has_finite_coordinates`]): it keeps its index, and nothing else sees it.
pub trait SpatialIndex: SpatialQuery<PointOf<Self>> {
    /// What the structure stores.
    type Prim: Primitive;

    /// Builds the structure over `prims` with its default options. An empty slice gives an
    /// empty structure whose queries find nothing.
    fn build(prims: &[Self::Prim]) -> Self
    where
        Self: Sized;

    /// The primitives, in input order.
    fn primitives(&self) -> &[Self::Prim];

    /// The first hit along the ray with `0 <= t <= t_max`, reporting each step.
    fn ray_first_hit_observed<O: Observer<PointOf<Self>>>(
        &self,
        ray: &Ray<PointOf<Self>>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>>;

    /// Some hit with `0 <= t <= t_max`, not necessarily the first (occlusion, shadow rays):
    /// stops at the first one found.
    fn ray_any_hit_observed<O: Observer<PointOf<Self>>>(
        &self,
        ray: &Ray<PointOf<Self>>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>>;

    /// Every primitive the ray hits with `0 <= t <= t_max`, once each (at its first `t`),
    /// sorted by `t`, then index.
    fn ray_all_hits_observed<O: Observer<PointOf<Self>>>(
        &self,
        ray: &Ray<PointOf<Self>>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Vec<Hit>>;

    /// The `k` primitives nearest to `point`, nearest first, by branch and bound.
    fn k_nearest_observed<O: Observer<PointOf<Self>>>(
        &self,
        point: PointOf<Self>,
        k: usize,
        observer: &mut O,
    ) -> Traced<Vec<Nearest<PointOf<Self>>>>;

    /// The primitives that share a point with the region, by index, ascending.
    fn range_observed<O: Observer<PointOf<Self>>>(
        &self,
        shape: &RangeShape<PointOf<Self>>,
        observer: &mut O,
    ) -> Traced<Vec<usize>>;

    /// Every pair `(a, b)` of a primitive of `self` and a primitive of `other` that share a
    /// point, ascending: the lecture's collision query, structure against structure.
    fn collide_observed<O: Observer<PointOf<Self>>>(
        &self,
        other: &Self,
        observer: &mut O,
    ) -> Traced<Vec<(usize, usize)>>;

    /// Node count, depth, leaf sizes, memory, duplicated references, SAH cost.
    fn stats(&self) -> Stats;

    /// Checks the structure's invariants: topology, every child inside its parent's bounds,
    /// every primitive reachable where it must be.
    ///
    /// # Errors
    /// A [`ValidationError`] saying what is wrong.
    fn validate(&self) -> Result<(), ValidationError>;

    /// Every overlapping pair between `self` and `other`, ascending.
    #[inline]
    fn collide(&self, other: &Self) -> Vec<(usize, usize)> {
        self.collide_observed(other, &mut ()).answer
    }
}

/// Implements [`RayCast`], [`PointQuery`] and [`SpatialQuery`] for a structure generic over
/// its primitive (`MyTree<P>`) through its [`SpatialIndex`] observed walks with the no-op
/// observer `()` (whose calls compile away): how every structure here but the [`Bvh`]
/// (whose first hit and closest point have walks of their own) answers them, and
/// what a structure of your own can use once it implements [`SpatialIndex`]:
/// `bvhlab::queries_by_observed_walks!(MyTree);`.
#[macro_export]
macro_rules! queries_by_observed_walks {
    ($structure:ident) => {
        impl<P: $crate::Primitive> $crate::RayCast<P::Point> for $structure<P> {
            #[inline]
            fn ray_first_hit(
                &self,
                ray: &$crate::Ray<P::Point>,
                t_max: f32,
            ) -> Option<$crate::Hit> {
                $crate::SpatialIndex::ray_first_hit_observed(self, ray, t_max, &mut ()).answer
            }

            #[inline]
            fn ray_any_hit(&self, ray: &$crate::Ray<P::Point>, t_max: f32) -> Option<$crate::Hit> {
                $crate::SpatialIndex::ray_any_hit_observed(self, ray, t_max, &mut ()).answer
            }
        }

        impl<P: $crate::Primitive> $crate::PointQuery<P::Point> for $structure<P> {
            #[inline]
            fn closest_point(&self, point: P::Point) -> Option<$crate::Nearest<P::Point>> {
                $crate::SpatialIndex::k_nearest_observed(self, point, 1, &mut ())
                    .answer
                    .into_iter()
                    .next()
            }
        }

        impl<P: $crate::Primitive> $crate::SpatialQuery<P::Point> for $structure<P> {
            #[inline]
            fn ray_all_hits(&self, ray: &$crate::Ray<P::Point>, t_max: f32) -> Vec<$crate::Hit> {
                $crate::SpatialIndex::ray_all_hits_observed(self, ray, t_max, &mut ()).answer
            }

            #[inline]
            fn k_nearest(&self, point: P::Point, k: usize) -> Vec<$crate::Nearest<P::Point>> {
                $crate::SpatialIndex::k_nearest_observed(self, point, k, &mut ()).answer
            }

            #[inline]
            fn range(&self, shape: &$crate::RangeShape<P::Point>) -> Vec<usize> {
                $crate::SpatialIndex::range_observed(self, shape, &mut ()).answer
            }
        }
    };
}

queries_by_observed_walks!(BruteForce);
queries_by_observed_walks!(KdTree);
queries_by_observed_walks!(BspTree);
queries_by_observed_walks!(Grid);
queries_by_observed_walks!(Orthtree);

/// The rounding the [`Primitive`](crate::Primitive) contract allows a primitive's own tests:
/// a few units in the last place of its coordinates, [`SLACK`](bvh::SLACK) of the largest
/// plus [`TINY`](bvh::TINY). Validation does not ask a structure to store a primitive where
/// it reaches only by that much.
pub(crate) fn contract_rounding<P: Primitive>(prim: &P) -> f32 {
    use crate::Vector as _;
    let bounds = prim.bounds();
    let magnitude = (0..P::Point::DIM)
        .map(|axis| {
            bounds
                .min
                .coord(axis)
                .abs()
                .max(bounds.max.coord(axis).abs())
        })
        .fold(0.0, f32::max);
    magnitude * bvh::SLACK + bvh::TINY
}

/// The [`Primitive`](crate::Primitive) contract's checks that `validate()` of every structure
/// runs on each primitive it indexes (`index` is its input index, for the message): its
/// vertices enclose it ([`check_enclosed_by_vertices`](crate::primitive::check_enclosed_by_vertices))
/// and its bounds hold what its own queries give
/// ([`check_bounds_hold`](crate::primitive::check_bounds_hold)). A primitive with a
/// non-finite coordinate passes both (it is in no structure).
pub(crate) fn check_primitive_contract<P: Primitive>(
    index: usize,
    prim: &P,
) -> Result<(), ValidationError> {
    crate::primitive::check_enclosed_by_vertices(prim)
        .and_then(|()| crate::primitive::check_bounds_hold(prim))
        .map_err(|why| {
            ValidationError::new(format!(
                "primitive {index} breaks the Primitive contract: {why}"
            ))
        })
}

/// [`check_primitive_contract`] for every primitive of a structure, in input order.
pub(crate) fn check_primitives_contract<P: Primitive>(prims: &[P]) -> Result<(), ValidationError> {
    prims
        .iter()
        .enumerate()
        .try_for_each(|(i, prim)| check_primitive_contract(i, prim))
}
