//! Primitives that structures are built over: segments in 2D, triangles in 3D, and points in
//! both (point clouds, for nearest-neighbour queries).
//!
//! Each pairing has its own file: [`segment`] holds ray-segment and point-segment,
//! [`triangle`] the watertight ray-triangle test and point-triangle, [`point`] points as
//! primitives, and [`overlap`] the exact primitive-box and primitive-primitive tests that
//! grids, range queries and collision queries need.

pub mod overlap;
pub mod point;
pub mod segment;
pub mod triangle;

pub use segment::Segment2;
pub use triangle::Triangle3;

use std::fmt::Debug;

use crate::volume::Aabb;
use crate::{Ray, Vector};

/// What a spatial structure needs of the things it stores: bounds, a centre to sort by, a ray
/// test, a closest-point query and exact overlap tests. Builders only look at
/// [`bounds`](Primitive::bounds) and [`centroid`](Primitive::centroid).
pub trait Primitive: Copy + Debug + PartialEq + Send + Sync + 'static {
    /// The vector type of the space the primitive lives in.
    type Point: Vector;

    /// The tightest axis-aligned box around the primitive.
    fn bounds(&self) -> Aabb<Self::Point>;
    /// The centre used to sort primitives while building a hierarchy (the vertex average).
    fn centroid(&self) -> Self::Point;
    /// The smallest `t >= 0` at which the ray touches the primitive, if any.
    fn ray_hit(&self, ray: &Ray<Self::Point>) -> Option<f32>;
    /// The point of the primitive nearest to `point`.
    fn closest_point(&self, point: Self::Point) -> Self::Point;
    /// Euclidean distance from `point` to the primitive.
    fn distance(&self, point: Self::Point) -> f32 {
        (self.closest_point(point) - point).length()
    }
    /// Length (a segment), area (a triangle), 0 (a point).
    fn measure(&self) -> f32;
    /// A normal, not normalised, of length 2 × area for a triangle and the segment's length
    /// for a segment (zero for a point). For facets of a convex hull it points outward: a
    /// triangle is seen counter-clockwise from where its normal points, and a segment's normal
    /// points to the right of `a → b` (so a counter-clockwise polygon's normals point out).
    fn normal(&self) -> Self::Point;
    /// The vertices (2 for a segment, 3 for a triangle, 1 for a point).
    fn vertices(&self) -> impl Iterator<Item = Self::Point>;
    /// Whether the primitive and the closed box share at least one point (exact, not just a
    /// bounds test): a grid lists a primitive in exactly the cells it touches.
    fn intersects_aabb(&self, aabb: &Aabb<Self::Point>) -> bool;
    /// Whether two primitives share at least one point (touching counts): the leaf test of
    /// the collision query.
    fn intersects(&self, other: &Self) -> bool;
}
