//! [`Bvh4`] answers the questions every volume, primitive and structure answers
//! ([`RayCast`], [`PointQuery`]) and those every structure answers ([`SpatialQuery`]) with
//! its own walks, so code written against the traits takes the fast tree as it takes any
//! other.

use super::Bvh4;
use crate::{Hit, Nearest, PointQuery, Primitive, RangeShape, Ray, RayCast, SpatialQuery};

impl<P: Primitive> RayCast<P::Point> for Bvh4<P> {
    #[inline]
    fn ray_first_hit(&self, ray: &Ray<P::Point>, t_max: f32) -> Option<Hit> {
        // The inherent method (inherent methods come before trait methods in a path).
        Bvh4::ray_first_hit(self, ray, t_max)
    }

    #[inline]
    fn ray_any_hit(&self, ray: &Ray<P::Point>, t_max: f32) -> Option<Hit> {
        Bvh4::ray_any_hit(self, ray, t_max)
    }
}

impl<P: Primitive> PointQuery<P::Point> for Bvh4<P> {
    #[inline]
    fn closest_point(&self, point: P::Point) -> Option<Nearest<P::Point>> {
        Bvh4::closest_point(self, point)
    }
}

impl<P: Primitive> SpatialQuery<P::Point> for Bvh4<P> {
    #[inline]
    fn ray_all_hits(&self, ray: &Ray<P::Point>, t_max: f32) -> Vec<Hit> {
        Bvh4::ray_all_hits(self, ray, t_max)
    }

    #[inline]
    fn k_nearest(&self, point: P::Point, k: usize) -> Vec<Nearest<P::Point>> {
        Bvh4::k_nearest(self, point, k)
    }

    #[inline]
    fn range(&self, shape: &RangeShape<P::Point>) -> Vec<usize> {
        Bvh4::range(self, shape)
    }
}
