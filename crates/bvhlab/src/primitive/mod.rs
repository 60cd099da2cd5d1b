//! Primitives that structures are built over: segments in 2D, triangles in 3D.
//!
//! Each pairing has its own file: [`segment`] holds ray-segment and point-segment,
//! [`triangle`] holds the watertight ray-triangle test and point-triangle.

pub mod segment;
pub mod triangle;

pub use segment::Segment2;
pub use triangle::Triangle3;

use crate::volume::Aabb;
use crate::{Ray, Vector};

/// What a spatial structure needs of the things it stores: bounds, a centre to sort by, a ray
/// test and a closest-point query. Builders only look at [`bounds`](Primitive::bounds) and
/// [`centroid`](Primitive::centroid).
pub trait Primitive<V: Vector> {
    /// The tightest axis-aligned box around the primitive.
    fn bounds(&self) -> Aabb<V>;
    /// The centre used to sort primitives while building a hierarchy (the vertex average).
    fn centroid(&self) -> V;
    /// The smallest `t >= 0` at which the ray touches the primitive, if any.
    fn ray_hit(&self, ray: &Ray<V>) -> Option<f32>;
    /// The point of the primitive nearest to `point`.
    fn closest_point(&self, point: V) -> V;
    /// Euclidean distance from `point` to the primitive.
    fn distance(&self, point: V) -> f32 {
        (self.closest_point(point) - point).length()
    }
    /// Length (a segment) or area (a triangle).
    fn measure(&self) -> f32;
    /// A normal, not normalised, of length 2 × area for a triangle and the segment's length
    /// for a segment. For facets of a convex hull it points outward: a triangle is seen
    /// counter-clockwise from where its normal points, and a segment's normal points to the
    /// right of `a → b` (so a counter-clockwise polygon's normals point out).
    fn normal(&self) -> V;
    /// The vertices (2 for a segment, 3 for a triangle).
    fn vertices(&self) -> impl Iterator<Item = V>;
}
