//! Exact overlap tests: primitive against box, primitive against primitive.
//!
//! Grids, octrees and k-d trees list a primitive in every cell it touches, range queries report
//! every primitive that touches the query box, and collision queries every pair that touches:
//! all of them ask "do these two closed sets share a point?". A wrong "no" loses a primitive, a
//! wrong "yes" makes two structures disagree with brute force, so the answer here is exact for
//! any finite `f32` input, touching included:
//!
//! 1. Input with a NaN or infinite coordinate touches nothing (and a box with a NaN or
//!    `min > max` is empty); a box may extend to infinity.
//! 2. The bounds test compares `f32` coordinates, which is exact, and settles the box's (or
//!    the coordinate axes') share of the separating axes.
//! 3. Cheap certain overlaps: a corner of the primitive inside the box, or a shared corner.
//! 4. The remaining separating axes (`simplex_aabb.rs` after Akenine-Möller 2001,
//!    `simplex_simplex.rs` after Gottschalk et al. 1996 and Eberly 2001) are decided in
//!    `f64` with a rigorous bound on the rounding error (a static filter), and, only when the
//!    bound cannot decide, again in exact expansion arithmetic (Shewchuk 1997). A gap of
//!    exactly zero along an axis is touching.
//!
//! Degenerate input is classified exactly (`simplex.rs`): a zero-area triangle is tested as
//! the segment or point it is, with the axes a segment or point needs; never as a triangle
//! whose zero normal would separate nothing. 2D input is lifted to the plane `z = 0`.

mod expansion;
mod sat;
mod scalar;
mod simplex;
mod simplex_aabb;
mod simplex_simplex;

use glam::{Vec2, Vec3};

use self::simplex::Simplex;
use self::simplex_aabb::simplex_aabb;
use self::simplex_simplex::simplex_simplex;
use super::{Primitive, Segment2, Triangle3};
use crate::volume::Aabb;
use crate::{BoundingVolume, Vector};

/// Whether a segment and a closed box share a point (exact; touching counts).
///
/// A zero-length segment is a point. A segment with a non-finite coordinate touches nothing.
pub fn segment2_aabb(s: &Segment2, aabb: &Aabb<Vec2>) -> bool {
    let Some((min, max)) = clipped_box(s, aabb) else {
        return false;
    };
    if aabb.contains(s.a) || aabb.contains(s.b) {
        return true;
    }
    simplex_aabb(&lift_segment(s), lift(min), lift(max), true)
}

/// Whether two segments share a point (exact; touching, overlapping collinear segments and
/// zero-length segments included).
pub fn segment2_segment2(a: &Segment2, b: &Segment2) -> bool {
    if !prefilter(a, b) {
        return false;
    }
    if [a.a, a.b].iter().any(|p| *p == b.a || *p == b.b) {
        return true;
    }
    simplex_simplex(&lift_segment(a), &lift_segment(b))
}

/// Whether a triangle and a closed box share a point (exact; touching counts).
///
/// A zero-area triangle is the segment or point it spans. A triangle with a non-finite
/// coordinate touches nothing.
pub fn triangle3_aabb(t: &Triangle3, aabb: &Aabb<Vec3>) -> bool {
    let Some((min, max)) = clipped_box(t, aabb) else {
        return false;
    };
    if t.vertices().any(|p| aabb.contains(p)) {
        return true;
    }
    simplex_aabb(&Simplex::new([t.a, t.b, t.c]), min, max, false)
}

/// Whether two triangles share a point (exact; touching counts, zero-area triangles are the
/// segments or points they span, and a triangle overlaps itself).
pub fn triangle3_triangle3(a: &Triangle3, b: &Triangle3) -> bool {
    if !prefilter(a, b) {
        return false;
    }
    if a.vertices().any(|p| b.vertices().any(|q| p == q)) {
        return true;
    }
    simplex_simplex(
        &Simplex::new([a.a, a.b, a.c]),
        &Simplex::new([b.a, b.b, b.c]),
    )
}

/// Whether a triangle has zero area (collinear or repeated corners), decided exactly.
pub(crate) fn is_degenerate(t: &Triangle3) -> bool {
    Simplex::new([t.a, t.b, t.c]).dim != simplex::Dim::Triangle
}

/// Both primitives finite and their bounds overlapping (exact `f32` comparisons).
fn prefilter<P: Primitive>(a: &P, b: &P) -> bool {
    a.has_finite_coordinates() && b.has_finite_coordinates() && a.bounds().overlaps(&b.bounds())
}

/// The part of the box inside the primitive's bounds, or `None` when the primitive is not
/// finite, the box is empty or NaN, or they miss. Since the primitive lies inside its bounds,
/// it meets the box exactly where it meets this part, which is finite even for an infinite
/// box, and small, which keeps the rounding of the later tests small.
fn clipped_box<P: Primitive>(prim: &P, aabb: &Aabb<P::Point>) -> Option<(P::Point, P::Point)> {
    let bounds = prim.bounds();
    (prim.has_finite_coordinates() && bounds.overlaps(aabb))
        .then(|| (bounds.min.max(aabb.min), bounds.max.min(aabb.max)))
}

fn lift(p: Vec2) -> Vec3 {
    p.extend(0.0)
}

fn lift_segment(s: &Segment2) -> Simplex {
    Simplex::segment(lift(s.a), lift(s.b))
}
