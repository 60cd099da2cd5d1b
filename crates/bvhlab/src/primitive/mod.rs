//! Primitives that structures are built over: segments in 2D, triangles in 3D, and points in
//! both (point clouds, for nearest-neighbour queries).
//!
//! [`contract`] checks the part of the [`Primitive`] contract that can be checked cheaply.
//! Each pairing has its own file: [`segment`] holds ray-segment and point-segment,
//! [`triangle`] the watertight ray-triangle test and point-triangle, [`point`] points as
//! primitives, and [`overlap`] the exact primitive-box and primitive-primitive tests that
//! grids, range queries and collision queries need.

pub mod contract;
pub mod overlap;
pub mod point;
pub mod segment;
pub mod triangle;

pub use contract::{check_bounds_hold, check_enclosed_by_vertices};
pub use segment::Segment2;
pub use triangle::Triangle3;

use std::fmt::Debug;

use crate::volume::Aabb;
use crate::{Ray, Vector};

/// What a spatial structure needs of the things it stores: bounds, a centre to sort by, a ray
/// test, a closest-point query and exact overlap tests.
///
/// Implemented for [`Segment2`], [`Triangle3`] and points (`Vec2`, `Vec3`); implement it for
/// your own primitive (spheres, capsules, ...) and every structure indexes it. Builders look
/// only at [`bounds`](Primitive::bounds) and [`centroid`](Primitive::centroid), except the
/// sphere and OBB trees, which fit their nodes to the [`vertices`](Primitive::vertices); the
/// queries trust each method's answer. So every structure answers exactly as
/// [`BruteForce`](crate::BruteForce) only if the methods keep this contract, where "the
/// primitive" is the closed set of points it covers:
///
/// 1. **Enclosed by its vertices.** The primitive lies inside the convex hull of
///    [`vertices`](Primitive::vertices) (for a segment or triangle it *is* that hull). A ball
///    must return points whose hull holds the ball (e.g. the corners of its box), not its
///    centre: the sphere and OBB trees would fit their nodes around the centre alone and
///    miss the ball's hits and nearest points. In particular [`bounds`](Primitive::bounds)
///    lies inside the box of the vertices; `validate()` of every BVH checks this
///    ([`check_enclosed_by_vertices`], which you can call on your own primitives).
/// 2. **Bounded by [`bounds`](Primitive::bounds).** Every point of the primitive, so every
///    hit point, closest point and overlap, lies in its box (grids, k-d trees, BSP trees,
///    octrees and AABB trees cull by it). [`check_bounds_hold`] probes this, and every
///    structure's `validate()` runs it; debug builds also check every hit point and
///    projected point a query meets, and stop with a message naming the primitive.
/// 3. **Tests agree with the geometry.** [`ray_hit`](Primitive::ray_hit) gives the least
///    `t >= 0` whose `ray.at(t)` is on the primitive; [`project_point`](Primitive::project_point)
///    a point of the primitive, no farther from the query than any other;
///    [`intersects_aabb`](Primitive::intersects_aabb)
///    and [`intersects`](Primitive::intersects) are exact (touching counts) and symmetric
///    where that applies. Rounding is allowed (a few units in the last place of the
///    coordinates: the structures grow their volumes by [`SLACK`](crate::structure::bvh::SLACK)
///    of them), a wrong answer is not.
/// 4. **Deterministic and pure.** The same primitive and query give the same answer every
///    time (structures compare answers with brute force and with each other bit for bit).
///
/// A primitive with a NaN or infinite coordinate ([`is_finite`](Primitive::has_finite_coordinates) is
/// false) is not geometry a query can answer with: every structure leaves it out and no query
/// reports it, [`BruteForce`](crate::BruteForce) included. The other methods need not handle
/// one.
///
/// You implement [`ray_hit`](Primitive::ray_hit) and [`project_point`](Primitive::project_point);
/// every primitive then answers the same questions as volumes and structures, through
/// [`RayCast`](crate::RayCast) (`ray_first_hit`, with [`hit_coordinates`](Primitive::hit_coordinates))
/// and [`PointQuery`](crate::PointQuery) (`closest_point`, `distance`).
///
/// # Implementing it for your own primitive
///
/// 1. Derive `Clone, Copy, Debug, PartialEq` and pick [`Point`](Primitive::Point) (`Vec2`
///    or `Vec3`). Write the required methods; [`hit_coordinates`](Primitive::hit_coordinates)
///    has a default (`[0, 0]`) that a primitive with its own surface coordinates (a ball's
///    longitude and latitude, say) replaces.
/// 2. Call [`check_enclosed_by_vertices`] and [`check_bounds_hold`] on a few of your
///    primitives: they catch vertices that do not enclose the primitive (contract 1) and
///    bounds too small for it (contract 2) before a tree misses them.
/// 3. Build any structure over a slice of them, call `validate()`, and compare a few answers
///    with [`BruteForce`](crate::BruteForce)'s, which tests every primitive: a difference means
///    a method breaks the contract (often a [`bounds`](Primitive::bounds) too small for
///    contract 2, or a [`ray_hit`](Primitive::ray_hit) that takes the ray's direction to be
///    of unit length: it need not be, and `t` is in units of it).
///
/// `crates/bvhlab/examples/custom_primitive.rs` does all three for balls, and the crate
/// documentation's "Start here" has a condensed version.
pub trait Primitive: Copy + Debug + PartialEq + Send + Sync + 'static {
    /// The vector type of the space the primitive lives in.
    type Point: Vector;

    /// The tightest axis-aligned box around the primitive: it must hold every point of it
    /// (contract 2) and lie inside the box of its [`vertices`](Self::vertices) (contract 1).
    fn bounds(&self) -> Aabb<Self::Point>;
    /// The centre used to sort primitives while building a hierarchy (the vertex average).
    /// Any point inside [`bounds`](Self::bounds) keeps the answers exact; one near the
    /// middle of the primitive makes better trees.
    fn centroid(&self) -> Self::Point;
    /// The smallest `t >= 0` at which the ray touches the primitive, if any (`t` in units of
    /// the ray's direction, so `ray.at(t)` is on the primitive). `None` for a ray that misses.
    fn ray_hit(&self, ray: &Ray<Self::Point>) -> Option<f32>;
    /// Where on the primitive a hit at `t` lies, for [`Hit::u`](crate::Hit::u) and
    /// [`Hit::v`](crate::Hit::v): for a triangle the barycentric coordinates of Möller and
    /// Trumbore, `ray.at(t) = (1 - u - v) a + u b + v c`; for a segment `u` is the parameter
    /// along it (`a + u (b - a)`) and `v = 0`; for a point both are 0 (the default). Called
    /// only with a `t` that [`ray_hit`](Self::ray_hit) returned for this ray, once per
    /// reported hit; it must be finite.
    fn hit_coordinates(&self, ray: &Ray<Self::Point>, t: f32) -> [f32; 2] {
        let _ = (ray, t);
        [0.0, 0.0]
    }
    /// The point of the primitive nearest to `point` (on the primitive, no farther than any
    /// other of its points): the projection of `point` onto the primitive. Callers ask
    /// [`PointQuery::closest_point`](crate::PointQuery::closest_point) and
    /// [`PointQuery::distance`](crate::PointQuery::distance), which every primitive answers
    /// from this.
    fn project_point(&self, point: Self::Point) -> Self::Point;
    /// Length (a segment), area (a triangle), 0 (a point). Reported, never used to prune.
    fn measure(&self) -> f32;
    /// A normal, not normalised, of length 2 × area for a triangle and the segment's length
    /// for a segment (zero for a point). For facets of a convex hull it points outward: a
    /// triangle is seen counter-clockwise from where its normal points, and a segment's normal
    /// points to the right of `a → b` (so a counter-clockwise polygon's normals point out).
    /// Reported, and used by the BSP tree's autopartition (a zero normal gives no plane
    /// through the primitive, which is then split by others).
    fn normal(&self) -> Self::Point;
    /// The vertices (2 for a segment, 3 for a triangle, 1 for a point): points whose convex
    /// hull holds the whole primitive (contract 1). The sphere and OBB trees fit their nodes
    /// to these, and every BVH leaves out a primitive with a non-finite one.
    fn vertices(&self) -> impl Iterator<Item = Self::Point>;
    /// Whether the primitive and the closed box share at least one point (exact, not just a
    /// bounds test): a grid lists a primitive in exactly the cells it touches.
    fn intersects_aabb(&self, aabb: &Aabb<Self::Point>) -> bool;
    /// Whether two primitives share at least one point (touching counts): the leaf test of
    /// the collision query. Symmetric.
    fn intersects(&self, other: &Self) -> bool;

    /// Whether every coordinate of the primitive is a finite number: all its
    /// [`vertices`](Self::vertices) and both corners of its [`bounds`](Self::bounds).
    ///
    /// The one rule for the others, everywhere in the crate: a primitive with a NaN or
    /// infinite coordinate is never an answer. Every structure leaves it out when it builds,
    /// refits, updates or loads (it is in no node, cell or list, and `validate()` refuses a
    /// tree that stores one), and [`BruteForce`](crate::BruteForce) skips it, so that every
    /// structure still answers as brute force does. A point at infinity is at an infinite
    /// distance from every query and a segment to infinity has no end to report; rather than
    /// answer with such numbers, no query answers with them at all. The provided body is the
    /// rule; there is no reason to replace it.
    fn has_finite_coordinates(&self) -> bool {
        let b = self.bounds();
        b.min.is_finite() && b.max.is_finite() && self.vertices().all(Vector::is_finite)
    }
}
