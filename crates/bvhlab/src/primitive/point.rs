//! Points as primitives: a point cloud is a slice of `Vec2` or `Vec3`, and every structure
//! answers nearest-neighbour queries over it (`KdTree::build(&points)` is the textbook tree,
//! `Bvh4::build(&points)` the fastest here; `crates/bvhlab/examples/point_cloud_knn.rs`
//! asks both for the k nearest and for ranges).

use crate::volume::Aabb;
use crate::{Primitive, Ray, Vector};

impl<V: Vector> Primitive for V {
    type Point = V;

    fn bounds(&self) -> Aabb<V> {
        Aabb::new(*self, *self)
    }
    fn centroid(&self) -> V {
        *self
    }
    /// A ray hits a point only when it passes exactly through it: `t` is where the ray comes
    /// closest, and the hit counts when the point is there (to the last bit of `f32`).
    fn ray_hit(&self, ray: &Ray<V>) -> Option<f32> {
        let d = ray.dir();
        let t = (*self - ray.origin()).dot(d) / d.length_squared();
        (t >= 0.0 && ray.at(t) == *self).then_some(t)
    }
    fn project_point(&self, _point: V) -> V {
        *self
    }
    fn measure(&self) -> f32 {
        0.0
    }
    fn normal(&self) -> V {
        V::ZERO
    }
    fn vertices(&self) -> impl Iterator<Item = V> {
        std::iter::once(*self)
    }
    fn intersects_aabb(&self, aabb: &Aabb<V>) -> bool {
        crate::BoundingVolume::contains(aabb, *self)
    }
    fn intersects(&self, other: &Self) -> bool {
        self == other
    }
}
