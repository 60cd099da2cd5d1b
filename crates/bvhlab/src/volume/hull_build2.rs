//! PLACEHOLDER: monotone chain.
use glam::Vec2;
use super::ConvexHull;
/// PLACEHOLDER.
pub fn monotone_chain(points: &[Vec2]) -> ConvexHull<Vec2> { super::hull::placeholder(points) }
