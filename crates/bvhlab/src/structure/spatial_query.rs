//! [`SpatialQuery`]: the questions every structure over many primitives answers, the fast
//! [`Bvh4`](crate::Bvh4) included, without the lab's stepping.

use crate::queries::{PointQuery, RayCast};
use crate::structure::{Hit, Nearest, RangeShape};
use crate::{Ray, Vector};

/// The queries every structure answers, each exactly as [`BruteForce`](crate::BruteForce)
/// does: the first hit, any hit and the closest point ([`RayCast`], [`PointQuery`]), and
/// every hit along a ray, the `k` nearest and a range.
///
/// Write code that takes any structure against this trait: every [`SpatialIndex`](crate::SpatialIndex)
/// implements it, and so does [`Bvh4`](crate::Bvh4), the fastest tree, which has no observed
/// walks and so is not a [`SpatialIndex`](crate::SpatialIndex) (that trait adds what the lab
/// needs: each query step by step, collision, statistics and validation).
///
/// ```
/// use bvhlab::glam::Vec3;
/// use bvhlab::prelude::*;
/// use bvhlab::{KdTree, RangeShape};
///
/// /// How many points lie within 1.5 of the query, by any structure.
/// fn neighbours(index: &impl SpatialQuery<Vec3>, at: Vec3) -> usize {
///     index.range(&RangeShape::Ball(Sphere3::new(at, 1.5))).len()
/// }
///
/// let points: Vec<Vec3> = (0..10).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
/// assert_eq!(neighbours(&Bvh4::build(&points), Vec3::ZERO), 2);
/// assert_eq!(neighbours(&KdTree::build(&points), Vec3::ZERO), 2);
/// ```
pub trait SpatialQuery<V: Vector>: RayCast<V> + PointQuery<V> {
    /// Every primitive the ray hits with `0 <= t <= t_max`, once each (at its first `t`),
    /// sorted by `t`, then index.
    fn ray_all_hits(&self, ray: &Ray<V>, t_max: f32) -> Vec<Hit>;

    /// The `k` primitives nearest to `point`, nearest first (ties by index).
    fn k_nearest(&self, point: V, k: usize) -> Vec<Nearest<V>>;

    /// The primitives that share a point with the region, by index, ascending.
    fn range(&self, shape: &RangeShape<V>) -> Vec<usize>;
}
