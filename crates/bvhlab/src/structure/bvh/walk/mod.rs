//! The walks of a built [`Bvh`](super::Bvh): every query it answers, each in the file named
//! for it. The table in the [module documentation](super) says which call runs which walk.
//!
//! - `ray.rs`: first hit, any hit and all hits, observed (the walk the lab steps through).
//! - `nearest.rs`: the k nearest, observed, by branch and bound.
//! - `range.rs`, `collide.rs`: the range query and the collision of two trees, observed.
//! - `fast_ray.rs`, `fast_nearest.rs`: the plain first hit and closest point, walks of their
//!   own without the observed walks' bookkeeping, giving the same answers bit for bit.
//! - `lecture.rs`: the slides' recursive `intersect` and `minDistance`, literally.
//! - `stack.rs`: the fixed-size stack the observed walks share.

mod collide;
pub(super) mod fast_nearest;
mod fast_ray;
mod lecture;
mod nearest;
mod range;
mod ray;
pub(super) mod stack;
