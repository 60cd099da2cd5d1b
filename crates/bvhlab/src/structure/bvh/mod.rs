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
//! let tree = SphereTree::<Triangle3>::with_options(&[floor, roof], &options);
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
//!   (axis-aligned plane, sizes of both sides, SAH cost for SAH splits) or `BuildLeaf`. The
//!   returned [`SplitRecord`]s keep each SAH cost curve.
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
//! The folder follows parry's split by phase: [`tree`] (layout), `build` with
//! `split_median` and `split_sah` (construction, whose decisions [`SplitRecord`] keeps),
//! [`volume`] with `node_aabb`, `node_sphere` and `node_obb` (what a node volume answers,
//! conservatively), `traverse_ray`, `traverse_nearest`, `traverse_range` and
//! `traverse_collide` (queries), `fast_ray` and `fast_nearest` (the unobserved first hit and
//! closest point), `lecture` (the slides' recursions), `stats` and `validate`, and `tests`.
//!
//! The plain [`ray_first_hit`](SpatialIndex::ray_first_hit) and
//! [`closest_point`](SpatialIndex::closest_point), which nobody watches, take walks of their
//! own that skip what only the lab needs (depths, counters, the order of reports): the
//! nearer child is visited next without touching the stack, and only the farther waits.
//! They answer exactly what the observed walks answer, bit for bit (the same node and
//! primitive tests, and pruning that never skips a node the observed walk visits); the lab
//! steps through the observed ones.
//!
//! For the fastest answers, [`Bvh4::from_bvh`] collapses a built AABB tree into a 4-wide copy
//! (`wide_tree`: four children's boxes per node, tested at once in `wide_ray` and
//! `wide_nearest`, with the stack of `wide_stack`) that answers the same first hits and
//! closest points, bit for bit; the binary tree stays what the lab steps through.

mod build;
mod build_job;
mod build_log;
mod fast_nearest;
mod fast_ray;
mod fit_sliced;
mod fit_sliced_obb;
mod fit_sliced_sphere;
mod lecture;
mod node_aabb;
mod node_obb;
mod node_sphere;
mod options;
mod split_median;
mod split_sah;
mod stack;
mod stats;
mod traverse_collide;
mod traverse_nearest;
mod traverse_range;
mod traverse_ray;
pub mod tree;
mod validate;
pub mod volume;
mod wide_nearest;
mod wide_ray;
mod wide_stack;
mod wide_tree;

#[cfg(test)]
mod tests;

pub use build_job::{BuildPhase, BuildProgress, BvhBuild};
pub use build_log::SplitRecord;
pub use options::{BvhOptions, MAX_DEPTH, SphereFit, SplitMethod};
pub use tree::{Bvh, BvhNode};
pub use volume::{NodeVolume, PreparedRange, PreparedRay, SLACK, TINY};
pub use wide_tree::{Bvh4, Bvh4Node, WIDTH};

use super::{
    Hit, Nearest, Observer, PointOf, RangeShape, SpatialIndex, Stats, Traced, ValidationError,
};
use crate::volume::{Aabb, Obb, Sphere};
use crate::{Primitive, Ray};

/// An AABB tree: a [`Bvh`] whose nodes are axis-aligned boxes.
pub type AabbTree<P> = Bvh<Aabb<<P as Primitive>::Point>, P>;
/// A sphere tree: a [`Bvh`] whose nodes are spheres (circles in 2D).
pub type SphereTree<P> = Bvh<Sphere<<P as Primitive>::Point>, P>;
/// An OBB tree: a [`Bvh`] whose nodes are oriented boxes.
pub type ObbTree<P> = Bvh<Obb<<P as Primitive>::Point>, P>;

impl<B, P> Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// Builds the tree with the default options (binned SAH, leaves of at most 4).
    pub fn build(prims: &[P]) -> Self {
        Self::with_options(prims, &BvhOptions::default())
    }

    /// Builds the tree with the given options.
    pub fn with_options(prims: &[P], options: &BvhOptions) -> Self {
        // The same tree either way; a box tree's SAH build has a faster path.
        if !B::NEEDS_VERTICES && options.method == SplitMethod::BinnedSah {
            return build::build_sah_boxes(prims, options);
        }
        build::build(prims, options, &mut (), None)
    }

    /// Builds the tree, reporting each node to `observer` (`BuildNode` when a node is made,
    /// then `BuildSplit` with the plane and, for the SAH, its cost, or `BuildLeaf`; nodes
    /// depth-first, first child first), and returns every split decision with its SAH cost
    /// curve.
    pub fn build_observed<O: Observer<P::Point>>(
        prims: &[P],
        options: &BvhOptions,
        observer: &mut O,
    ) -> (Self, Vec<SplitRecord>) {
        let mut log = Vec::new();
        let bvh = build::build(prims, options, observer, Some(&mut log));
        (bvh, log)
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
        self.first_hit(ray, t_max, observer)
    }

    /// The unobserved walk (`fast_ray`): the observed one's answer, without its bookkeeping.
    #[inline]
    fn ray_first_hit(&self, ray: &Ray<PointOf<Self>>, t_max: f32) -> Option<Hit> {
        self.first_hit_fast(ray, t_max)
    }

    /// The unobserved walk (`fast_nearest`): the observed one's answer, without its
    /// bookkeeping.
    #[inline]
    fn closest_point(&self, point: PointOf<Self>) -> Option<Nearest<PointOf<Self>>> {
        self.closest_point_fast(point)
    }

    fn ray_any_hit_observed<O: Observer<PointOf<Self>>>(
        &self,
        ray: &Ray<PointOf<Self>>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>> {
        self.any_hit(ray, t_max, observer)
    }

    fn ray_all_hits_observed<O: Observer<PointOf<Self>>>(
        &self,
        ray: &Ray<PointOf<Self>>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Vec<Hit>> {
        self.all_hits(ray, t_max, observer)
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
