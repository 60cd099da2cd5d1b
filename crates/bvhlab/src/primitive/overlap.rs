//! Exact overlap tests: primitive against box, primitive against primitive.
//!
//! INTERIM: bounds-overlap only (conservative); the exact separating-axis versions are being
//! written (issue 3).

use glam::{Vec2, Vec3};

use super::{Primitive, Segment2, Triangle3};
use crate::BoundingVolume;
use crate::volume::Aabb;

/// Whether a segment and a closed box share a point.
pub fn segment2_aabb(s: &Segment2, aabb: &Aabb<Vec2>) -> bool {
    s.bounds().overlaps(aabb)
}

/// Whether two segments share a point.
pub fn segment2_segment2(a: &Segment2, b: &Segment2) -> bool {
    a.bounds().overlaps(&b.bounds())
}

/// Whether a triangle and a closed box share a point.
pub fn triangle3_aabb(t: &Triangle3, aabb: &Aabb<Vec3>) -> bool {
    t.bounds().overlaps(aabb)
}

/// Whether two triangles share a point.
pub fn triangle3_triangle3(a: &Triangle3, b: &Triangle3) -> bool {
    a.bounds().overlaps(&b.bounds())
}
