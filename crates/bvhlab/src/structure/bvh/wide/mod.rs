//! The 4-wide copy of a built AABB tree, [`Bvh4`]: the fastest unobserved queries, each
//! answering as the binary tree does.
//!
//! - `layout.rs`: [`Bvh4`] and its 128-byte [`Bvh4Node`], and the collapse of a binary tree.
//! - `leaves.rs`: the leaves' primitives in leaf order: triangles in blocks of four, any other
//!   primitive one per slot.
//! - `triangle_block.rs`: four triangles side by side, and the four-lane step of the
//!   watertight test that proves which of them a ray misses.
//! - `collapse_parallel.rs`: the same collapse on every core (the `parallel` feature).
//! - `ray.rs`: [`Bvh4::ray_first_hit`], four slab tests at once.
//! - `any_all_hits.rs`: [`Bvh4::ray_any_hit`] and [`Bvh4::ray_all_hits`], the walk whose
//!   limit stays `t_max`.
//! - `nearest.rs`: [`Bvh4::closest_point`], four distance bounds at once.
//! - `k_nearest.rs`: [`Bvh4::k_nearest`], the same walk keeping the k best.
//! - `range.rs`: [`Bvh4::range`], [`Bvh4::range_count`] and [`Bvh4::range_for_each`],
//!   boxes and balls, one walk that takes lanes wholly inside the region whole.
//! - `range_lanes.rs`: the range walk's lane tests (may touch the region, lies inside it).
//! - `stack.rs`: the stack the nearest-first walks share, sized per tree.
//! - `refit.rs`: [`Bvh4::refit`] after the primitives moved, and the SAH cost it reports.
//! - `update.rs`: [`Bvh4::insert`] and [`Bvh4::remove`], without a rebuild.
//! - `validate.rs`: [`Bvh4::validate`], the invariants (every box inside its parent's).
//!
//! The wide tree answers what its callers ask most, without the lab's events: it implements
//! [`RayCast`](crate::RayCast), [`PointQuery`](crate::PointQuery) and
//! [`SpatialQuery`](crate::SpatialQuery), the traits code that takes any structure is written
//! against (`query_traits.rs`), but not [`SpatialIndex`](crate::structure::SpatialIndex),
//! whose `_observed` forms report every node by its index and whose event grammar is written
//! for binary nodes (a wide node's leaf lanes are no nodes at all), and it keeps no copy of
//! the primitives in input order (only those it leaves out, for [`Bvh4::remove`]). Its queries are also inherent methods with the traits'
//! names and answers; the lab steps through the binary tree.

mod any_all_hits;
#[cfg(feature = "parallel")]
mod collapse_parallel;
mod k_nearest;
mod layout;
mod leaves;
mod nearest;
mod query_traits;
mod range;
mod range_lanes;
mod ray;
mod refit;
mod stack;
mod triangle_block;
mod update;
mod validate;

pub use layout::{Bvh4, Bvh4Node, WIDTH};
