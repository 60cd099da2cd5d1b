//! The 4-wide copy of a built AABB tree, [`Bvh4`]: the fastest unobserved first hits and
//! closest points, bit for bit the binary tree's answers.
//!
//! - `layout.rs`: [`Bvh4`] and its 128-byte [`Bvh4Node`], and the collapse of a binary tree.
//! - `ray.rs`: [`Bvh4::ray_first_hit`], four slab tests at once.
//! - `nearest.rs`: [`Bvh4::closest_point`], four distance bounds at once.
//! - `stack.rs`: the stack both walks share, sized per tree.
//! - `refit.rs`: [`Bvh4::refit`] after the primitives moved, and the SAH cost it reports.
//! - `validate.rs`: [`Bvh4::validate`], the invariants (every box inside its parent's).

mod layout;
mod nearest;
mod ray;
mod refit;
mod stack;
mod validate;

pub use layout::{Bvh4, Bvh4Node, WIDTH};
