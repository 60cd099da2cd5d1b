//! PLACEHOLDER: quickhull.
use glam::Vec3;
use super::ConvexHull;
/// PLACEHOLDER.
pub fn quickhull(points: &[Vec3]) -> ConvexHull<Vec3> { super::hull::placeholder(points) }
