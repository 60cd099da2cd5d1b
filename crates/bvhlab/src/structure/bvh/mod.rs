//! Bounding volume hierarchies (lecture §3): sphere trees, AABB trees and OBB trees, one
//! implementation generic over the node volume.
//!
//! A [`Bvh<B, P>`] is a binary tree over primitives `P` whose nodes hold a bounding volume
//! `B` around everything below them. The topology is built top-down from the primitives'
//! boxes and centres alone ([`SplitMethod`]: the lecture's median splits or the binned
//! surface area heuristic); each node's volume is then fitted to that node's primitives:
//!
//! | alias | `B` | node volume | node size (3D) |
//! | --- | --- | --- | --- |
//! | [`AabbTree<P>`] | [`Aabb`] | union of the primitives' boxes | 32 bytes |
//! | [`SphereTree<P>`] | [`Sphere`] | Ritter's (or Welzl's) sphere of their vertices | 24 bytes |
//! | [`ObbTree<P>`] | [`Obb`] | PCA box of their vertices | 68 bytes |
//!
//! Each volume is grown by [`SLACK`] (a millionth) of its coordinates so that the rounding of
//! the node tests can never refuse what a primitive test accepts ([`volume`] explains why).
//!
//! ```
//! use bvhlab::glam::Vec3;
//! use bvhlab::prelude::*;
//! use bvhlab::structure::bvh::{BvhOptions, SphereTree, SplitMethod};
//!
//! let floor = Triangle3::new(Vec3::ZERO, Vec3::X * 4.0, Vec3::Y * 4.0);
//! let roof = Triangle3::new(Vec3::Z, Vec3::Z + Vec3::X * 4.0, Vec3::Z + Vec3::Y * 4.0);
//! let options = BvhOptions::with_method(SplitMethod::SpatialMedian);
//! let tree = SphereTree::<Triangle3>::build_with(&[floor, roof], &options);
//! tree.validate()?;
//!
//! let down = Ray3::new(Vec3::new(1.0, 1.0, 3.0), -Vec3::Z)?;
//! let hit = tree.ray_first_hit(&down, f32::INFINITY).expect("the roof is below");
//! assert_eq!((hit.prim, hit.t), (1, 2.0));
//! let nearest = tree.closest_point(Vec3::new(1.0, 1.0, 0.25)).expect("two triangles");
//! assert_eq!((nearest.prim, nearest.distance), (0, 0.25));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Every query of [`SpatialIndex`] is answered exactly as [`BruteForce`](super::BruteForce)
//! answers it (a primitive with a NaN or infinite coordinate is left out of the tree and never
//! reported), and reports its steps to an [`Observer`] (every structure's event order is
//! written as a grammar in [`observe`](super::observe#the-order-of-events)):
//!
//! - **Build** ([`Bvh::build_observed`]): per node, depth-first and first child first,
//!   `BuildNode` (its index in [`Bvh::nodes`], parent, depth, size), then `BuildSplit`
//!   (axis-aligned plane, sizes of both sides, SAH cost for SAH splits) or `BuildLeaf`. An
//!   observer that [wants them](Observer::wants_splits) also gets each node's
//!   [`SplitRecord`] with its SAH cost curve ([`Observer::on_split`]).
//! - **Ray first hit / any hit / all hits**: `RayBoundTest` of the root, then for each node
//!   popped from the stack either `Prune(BeyondBestHit, at Pop)` (the best hit, or `t_max`,
//!   has meanwhile moved before its entry) or `EnterNode`; at an inner node `RayBoundTest` of
//!   both children, `Prune(RayMissed | BeyondBestHit, at Test)` for a child refused, and
//!   `ChildQueued` for the others, nearer entry first (`rank` 0); at a leaf one
//!   `PrimitiveTest` per primitive and `NewBest` when the best hit improves (first hit
//!   only). An any-hit query that finds a hit reports `Prune(AlreadyHit, at Stop)` for every
//!   node still waiting.
//! - **k nearest**: the same walk with `DistanceBoundTest` instead of `RayBoundTest`,
//!   `Prune(NoNearer)` instead of `BeyondBestHit`, children queued nearer first,
//!   `PrimitiveTest(Distance)` per primitive and `NewBest` (with its distance) when one
//!   enters the k best.
//! - **Range**: `Prune(NoOverlap, at Test)` for the root or a child whose volume misses the
//!   region, `ChildQueued` (key 0, first child first) for the others, `EnterNode` when
//!   popped, `PrimitiveTest(Overlap | NoOverlap)` per primitive of a leaf.
//! - **Collision**: `NodePairTest` per pair of nodes popped (the roots first; of an
//!   overlapping pair, the larger node's children are paired with the other node, first
//!   child first), `PairTest` per primitive pair of two overlapping leaves.
//!
//! Every query returns its [`QueryCost`](super::QueryCost): `EnterNode`s (overlapping node
//! pairs) as nodes visited, bound tests (node pair tests), and primitive (pair) tests.
//!
//! Beside these, the slides' own recursive queries, literally, for the lab to compare:
//! [`Bvh::lecture_intersect_observed`] (left child then right, no pruning by the best hit),
//! [`Bvh::lecture_min_distance_observed`] (every node, no bounding volume tested) and
//! [`Bvh::lecture_min_distance_pruned_observed`] (pruned, still left then right). They give
//! the same answers as the real traversals and report the same kinds of events.
//!
//! ## Where the code lives
//!
//! One subfolder per job, as parry splits its BVH by phase:
//!
//! - [`layout`]: the tree and its node ([`Bvh`], [`BvhNode`]), their statistics
//!   (`layout/stats.rs`), and the flat node and triangle arrays that the app's GPU heat map
//!   reads ([`layout::gpu`], mirrored by WGSL in the app).
//! - [`volume`]: what a node volume answers ([`NodeVolume`], [`PreparedRay`],
//!   [`PreparedRange`]), one file per volume (`aabb.rs` with the slab test, `sphere.rs`,
//!   `obb.rs`), and the node fits of a build run in slices (`fit_sliced/`).
//! - `build/`: the options ([`BvhOptions`], `options.rs`), the lecture's median splits
//!   (`median.rs`), the binned SAH (`sah.rs`), the builder whose node work runs in resumable
//!   stages (`mod.rs`, `node_stages.rs`), the one-go box-tree build (`fast.rs`,
//!   `fast_bins.rs`), the build in slices ([`BvhBuild`], `job.rs`) and the split log
//!   ([`SplitRecord`], `split_log.rs`).
//! - `walk/`: the queries, one file per job (`ray.rs`, `nearest.rs`, `range.rs`,
//!   `collide.rs`), the unobserved first hit and closest point (`fast_ray.rs`,
//!   `fast_nearest.rs`), the slides' recursions (`lecture.rs`) and the stack (`stack.rs`).
//! - `wide/`: [`Bvh4`], the 4-wide copy of an AABB tree (`layout.rs`), with its own
//!   first-hit and closest-point walks (`ray.rs`, `nearest.rs`) and stack (`stack.rs`).
//! - `refit.rs`: [`Bvh::refit`] after the primitives moved (Wald, Boulos and Shirley 2007),
//!   its [`RefitReport`] and [`Bvh::needs_rebuild`]; [`Bvh4::refit`] is in `wide/refit.rs`.
//! - `update/`: an AABB tree's [`Bvh::insert`], [`Bvh::remove`] and [`Bvh::replace`]
//!   without a rebuild (`mod.rs`), the branch-and-bound search for the cheapest place
//!   (`search.rs`, Bittner, Hapala and Havran 2013), the edits of the depth-first arrays
//!   (`splice.rs`), the tree rotations after an insert (`rotate.rs`, Catto 2019) and
//!   [`Bvh::optimize_by_reinsertion`] (`optimize.rs`). What each update
//!   costs beside the other structures' is in [`update`](super::update).
//! - `validate.rs` (the invariants) and `tests.rs` (unit tests that need private fields).
//!
//! ## Which walk each call runs
//!
//! | call | runs |
//! | --- | --- |
//! | [`ray_first_hit_observed`](SpatialIndex::ray_first_hit_observed) | `walk/ray.rs` (`first_hit`) |
//! | [`ray_first_hit`](RayCast::ray_first_hit) | `walk/fast_ray.rs`, a walk of its own |
//! | [`ray_any_hit_observed`](SpatialIndex::ray_any_hit_observed) | `walk/ray.rs` (`any_hit`) |
//! | [`ray_any_hit`](RayCast::ray_any_hit) | `walk/fast_ray.rs`, the first-hit walk stopping at the first hit |
//! | [`ray_all_hits_observed`](SpatialIndex::ray_all_hits_observed), [`ray_all_hits`](SpatialQuery::ray_all_hits) | `walk/ray.rs` (`all_hits`) |
//! | [`closest_point`](PointQuery::closest_point), [`checked_closest_point`](PointQuery::checked_closest_point) | `walk/fast_nearest.rs`, a walk of its own |
//! | [`k_nearest_observed`](SpatialIndex::k_nearest_observed), [`k_nearest`](SpatialQuery::k_nearest) (for every `k`, 1 too) | `walk/nearest.rs` |
//! | [`range_observed`](SpatialIndex::range_observed), [`range`](SpatialQuery::range) | `walk/range.rs` |
//! | [`collide_observed`](SpatialIndex::collide_observed), [`collide`](SpatialIndex::collide) | `walk/collide.rs` |
//! | [`lecture_intersect_observed`](Bvh::lecture_intersect_observed), [`lecture_intersect`](Bvh::lecture_intersect) | `walk/lecture.rs` (`Intersect`) |
//! | [`lecture_min_distance_observed`](Bvh::lecture_min_distance_observed), [`lecture_min_distance_pruned_observed`](Bvh::lecture_min_distance_pruned_observed) and their plain forms | `walk/lecture.rs` (`MinDistance`) |
//! | [`Bvh4::ray_first_hit`] | `wide/ray.rs` |
//! | [`Bvh4::closest_point`] | `wide/nearest.rs` |
//! | [`stats`](SpatialIndex::stats), [`Bvh::depths`] | `layout/stats.rs` |
//! | [`validate`](SpatialIndex::validate) | `validate.rs` |
//! | [`Bvh::refit`], [`Bvh::needs_rebuild`] | `refit.rs` |
//! | [`Bvh4::refit`], [`Bvh4::needs_rebuild`], [`Bvh4::validate`] | `wide/refit.rs`, `wide/validate.rs` |
//! | [`Bvh::insert`], [`Bvh::remove`], [`Bvh::replace`] (AABB trees) | `update/mod.rs`, placing with `update/search.rs`, editing with `update/splice.rs`, rotating with `update/rotate.rs` |
//! | [`Bvh::optimize_by_reinsertion`] (AABB trees) | `update/optimize.rs` |
//! | [`Bvh::build`], [`Bvh::build_with`]: an AABB tree with [`SplitMethod::BinnedSah`] | `build/fast.rs`, in one go |
//! | `Bvh::build_parallel`, `Bvh::build_with_parallel` (the `parallel` feature): an AABB tree with [`SplitMethod::BinnedSah`] | `build/parallel.rs`, on every core, the same tree; any other tree as [`Bvh::build_with`] |
//! | [`Bvh::build`], [`Bvh::build_with`]: any other tree; [`Bvh::build_observed`] | `build/mod.rs` and `node_stages.rs`, the resumable builder run to the end |
//! | [`BvhBuild::step`], [`BvhBuild::finish`] | the same builder, a budget at a time (`build/job.rs`) |
//! | [`Bvh4::build`], [`Bvh4::build_with`] | with the binned SAH `build/fast.rs`, then the collapse of `wide/layout.rs`; otherwise [`Bvh::build_with`] and [`Bvh4::from_bvh`] |
//! | [`Bvh4::from_bvh`] | `wide/layout.rs` (the collapse) |
//!
//! Every plain form not named above is its `_observed` form with the no-op observer `()`
//! (the defaults of [`SpatialIndex`]): the observer costs nothing there (`()`'s
//! [`Observer::on`] is empty and always inlined), but the walk still keeps what its reports
//! would need and counts its [`QueryCost`](super::QueryCost). Three plain forms do not: the
//! plain [`ray_first_hit`](RayCast::ray_first_hit), [`ray_any_hit`](RayCast::ray_any_hit)
//! and [`closest_point`](PointQuery::closest_point), which nobody watches, take walks of their
//! own that skip what only the lab needs (each waiting node's depth, the counters, the order
//! of reports, the k-best set): the nearer child is visited next without touching the stack,
//! and only the farther waits. They answer exactly what the observed walks answer, bit for
//! bit (the same node and primitive tests, and pruning that never skips a node the observed
//! walk visits); the lab steps through the observed ones.
//!
//! For the fastest answers, [`Bvh4::from_bvh`] collapses a built AABB tree into a 4-wide copy
//! (four children's boxes per node, tested at once) that answers the same first hits and
//! closest points, bit for bit; the binary tree stays what the lab steps through.

mod build;
pub mod layout;
mod refit;
mod update;
mod validate;
pub mod volume;
mod walk;
mod wide;

#[cfg(test)]
mod tests;

pub use build::job::{BuildPhase, BuildProgress, BvhBuild};
pub use build::options::{BvhOptions, MAX_DEPTH, SphereFit, SplitMethod};
pub use build::split_log::SplitRecord;
pub use layout::{Bvh, BvhNode};
pub use refit::{RefitError, RefitReport};
pub use update::OptimizeReport;
pub use volume::{NodeVolume, PreparedRange, PreparedRay, SLACK, TINY};
pub use wide::{Bvh4, Bvh4Node, WIDTH};

use super::{
    Hit, Nearest, Observer, PointOf, RangeShape, SpatialIndex, SpatialQuery, Stats, Traced,
    ValidationError,
};
use crate::structure::query::{placed, placed_all_traced, placed_traced};
use crate::volume::{Aabb, Obb, Sphere};
use crate::{PointQuery, Primitive, Ray, RayCast};

/// An AABB tree: a [`Bvh`] whose nodes are axis-aligned boxes, over any primitive `P` (also
/// `bvhlab::AabbTree`, and in the prelude). `AabbTree3` and `AabbTree2` are its forms over
/// triangles and 2D segments: the same type, shorter to write.
pub type AabbTree<P> = Bvh<Aabb<<P as Primitive>::Point>, P>;
/// A sphere tree: a [`Bvh`] whose nodes are spheres (circles in 2D), over any primitive `P`
/// (`SphereTree3` is `SphereTree<Triangle3>`).
pub type SphereTree<P> = Bvh<Sphere<<P as Primitive>::Point>, P>;
/// An OBB tree: a [`Bvh`] whose nodes are oriented boxes, over any primitive `P`
/// (`ObbTree3` is `ObbTree<Triangle3>`).
pub type ObbTree<P> = Bvh<Obb<<P as Primitive>::Point>, P>;

impl<B, P> Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// Builds the tree with the default options (binned SAH, leaves of at most 4).
    pub fn build(prims: &[P]) -> Self {
        Self::build_with(prims, &BvhOptions::default())
    }

    /// Builds the tree with the given options.
    pub fn build_with(prims: &[P], options: &BvhOptions) -> Self {
        // The same tree either way; a box tree's SAH build has a faster path.
        if !B::NEEDS_VERTICES && options.method == SplitMethod::BinnedSah {
            return build::build_sah_boxes(prims, options);
        }
        build::build(prims, options, &mut ())
    }

    /// [`build`](Self::build) on every core (the `parallel` feature): the same tree, bit
    /// for bit.
    #[cfg(feature = "parallel")]
    pub fn build_parallel(prims: &[P]) -> Self {
        Self::build_with_parallel(prims, &BvhOptions::default())
    }

    /// [`build_with`](Self::build_with) on every core (the `parallel` feature): the same
    /// tree, bit for bit (nodes, boxes, leaf order), so a tree built either way answers
    /// every query alike. The binned-SAH build of a box tree runs in parallel (`build/parallel.rs`:
    /// the two children of a large node are built at once, and the steps that read every
    /// primitive near the root are split across threads); every other tree is built as
    /// [`build_with`](Self::build_with) builds it, on one thread.
    #[cfg(feature = "parallel")]
    pub fn build_with_parallel(prims: &[P], options: &BvhOptions) -> Self {
        if !B::NEEDS_VERTICES && options.method == SplitMethod::BinnedSah {
            return build::build_sah_boxes_parallel(prims, options);
        }
        Self::build_with(prims, options)
    }

    /// Builds the tree, reporting each node to `observer` (`BuildNode` when a node is made,
    /// then `BuildSplit` with the plane and, for the SAH, its cost, or `BuildLeaf`; nodes
    /// depth-first, first child first), and, to an observer that
    /// [wants them](Observer::wants_splits), every split decision with its SAH cost curve
    /// ([`Observer::on_split`]).
    pub fn build_observed<O: Observer<P::Point>>(
        prims: &[P],
        options: &BvhOptions,
        observer: &mut O,
    ) -> Self {
        build::build(prims, options, observer)
    }
}

impl<B, P> SpatialIndex for Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    type Prim = P;

    fn build(prims: &[P]) -> Self {
        Bvh::build(prims)
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
        placed_traced(self.first_hit(ray, t_max, observer), &self.prims, ray)
    }

    fn ray_any_hit_observed<O: Observer<PointOf<Self>>>(
        &self,
        ray: &Ray<PointOf<Self>>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>> {
        placed_traced(self.any_hit(ray, t_max, observer), &self.prims, ray)
    }

    fn ray_all_hits_observed<O: Observer<PointOf<Self>>>(
        &self,
        ray: &Ray<PointOf<Self>>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Vec<Hit>> {
        placed_all_traced(self.all_hits(ray, t_max, observer), &self.prims, ray)
    }

    fn k_nearest_observed<O: Observer<PointOf<Self>>>(
        &self,
        point: PointOf<Self>,
        k: usize,
        observer: &mut O,
    ) -> Traced<Vec<Nearest<PointOf<Self>>>> {
        self.k_nearest_impl(point, k, observer)
    }

    fn range_observed<O: Observer<PointOf<Self>>>(
        &self,
        shape: &RangeShape<PointOf<Self>>,
        observer: &mut O,
    ) -> Traced<Vec<usize>> {
        self.range_impl(shape, observer)
    }

    fn collide_observed<O: Observer<PointOf<Self>>>(
        &self,
        other: &Self,
        observer: &mut O,
    ) -> Traced<Vec<(usize, usize)>> {
        self.collide_impl(other, observer)
    }

    fn stats(&self) -> Stats {
        self.stats_impl()
    }

    fn validate(&self) -> Result<(), ValidationError> {
        self.validate_impl()
    }
}

impl<B, P> RayCast<P::Point> for Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// The unobserved walk (`walk/fast_ray.rs`): the observed one's answer, without its
    /// bookkeeping.
    #[inline]
    fn ray_first_hit(&self, ray: &Ray<P::Point>, t_max: f32) -> Option<Hit> {
        placed(self.first_hit_fast(ray, t_max), &self.prims, ray)
    }

    /// The unobserved walk (`walk/fast_ray.rs`, stopping at the first hit): the observed
    /// one's answer, without its bookkeeping.
    #[inline]
    fn ray_any_hit(&self, ray: &Ray<P::Point>, t_max: f32) -> Option<Hit> {
        placed(self.any_hit_fast(ray, t_max), &self.prims, ray)
    }
}

/// The observed walks with the no-op observer `()`, whose calls compile away.
impl<B, P> SpatialQuery<P::Point> for Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    #[inline]
    fn ray_all_hits(&self, ray: &Ray<P::Point>, t_max: f32) -> Vec<Hit> {
        self.ray_all_hits_observed(ray, t_max, &mut ()).answer
    }

    #[inline]
    fn k_nearest(&self, point: P::Point, k: usize) -> Vec<Nearest<P::Point>> {
        self.k_nearest_observed(point, k, &mut ()).answer
    }

    #[inline]
    fn range(&self, shape: &RangeShape<P::Point>) -> Vec<usize> {
        self.range_observed(shape, &mut ()).answer
    }
}

impl<B, P> PointQuery<P::Point> for Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// The unobserved walk (`walk/fast_nearest.rs`): the observed one's answer, without its
    /// bookkeeping.
    #[inline]
    fn closest_point(&self, point: P::Point) -> Option<Nearest<P::Point>> {
        self.closest_point_fast(point)
    }
}
