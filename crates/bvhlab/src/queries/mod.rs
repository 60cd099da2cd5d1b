//! One trait per question, answered alike by a bounding volume, a primitive and a structure
//! (as parry's `RayCast` and `PointQuery` are).
//!
//! - [`RayCast`]: where does a ray first meet this, and does it meet it at all
//!   ([`ray_first_hit`](RayCast::ray_first_hit), [`ray_any_hit`](RayCast::ray_any_hit)).
//! - [`PointQuery`]: which point of this is nearest to a point, and how far
//!   ([`closest_point`](PointQuery::closest_point), [`distance`](PointQuery::distance)).
//!
//! The answer types are the structures' ([`Hit`], [`Nearest`]), so a box, a triangle and a
//! tree of a million triangles answer the same call in the same words. A single volume or
//! primitive names itself as primitive 0. Queries that only structures answer (all hits,
//! the k nearest, range, collision, and the observed walks the lab plays back) stay on
//! [`SpatialIndex`](crate::SpatialIndex), which requires both traits; [`Bvh4`](crate::Bvh4)
//! implements the two traits (and the rest as methods of its own).
//!
//! ```
//! use bvhlab::glam::Vec3;
//! use bvhlab::prelude::*;
//!
//! let tri = Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::Y);
//! let ray = Ray3::new(Vec3::new(0.25, 0.25, 1.0), -Vec3::Z)?;
//! let tree = AabbTree3::build(&[tri]);
//! let bounds = tri.bounds();
//! // The same call on a box, a triangle and a tree.
//! assert_eq!(bounds.ray_first_hit(&ray, f32::INFINITY).map(|h| h.t), Some(1.0));
//! assert_eq!(tri.ray_first_hit(&ray, f32::INFINITY).map(|h| h.t), Some(1.0));
//! assert_eq!(tree.ray_first_hit(&ray, f32::INFINITY).map(|h| h.t), Some(1.0));
//! let p = Vec3::new(2.0, 0.0, 0.0);
//! assert_eq!(tri.distance(p), 1.0);
//! assert_eq!(tree.closest_point(p).map(|n| n.point), Some(Vec3::X));
//! # Ok::<(), bvhlab::GeometryError>(())
//! ```

mod batch;
#[cfg(feature = "parallel")]
mod threads;

#[cfg(feature = "parallel")]
pub use threads::with_threads;

use crate::error::{GeometryError, check_finite};
use crate::{Hit, Nearest, Primitive, Ray, Vector};

/// Where a ray meets the thing: its first hit within `[0, t_max]`, or whether it meets it at
/// all.
///
/// A ray that starts inside a closed volume meets it at `t = 0`; a ray that only touches the
/// boundary meets it. `t` is in units of the ray's direction, so `ray.at(hit.t)` is the hit
/// point. A hit on a structure names the primitive by its index in the slice the structure
/// was built from, with its coordinates on it ([`Hit::u`], [`Hit::v`]); a volume or a lone
/// primitive is primitive 0.
pub trait RayCast<V: Vector> {
    /// The first hit along the ray with `0 <= t <= t_max` (ties in `t` go to the lower
    /// primitive index), or `None`.
    fn ray_first_hit(&self, ray: &Ray<V>, t_max: f32) -> Option<Hit>;

    /// Some hit with `0 <= t <= t_max`, not necessarily the first: for occlusion (shadow
    /// rays), where any hit answers the question and a walk may stop at the first it finds.
    #[inline]
    fn ray_any_hit(&self, ray: &Ray<V>, t_max: f32) -> Option<Hit> {
        self.ray_first_hit(ray, t_max)
    }

    /// Whether the ray meets the thing with `0 <= t <= t_max`.
    #[inline]
    fn intersects_ray(&self, ray: &Ray<V>, t_max: f32) -> bool {
        self.ray_any_hit(ray, t_max).is_some()
    }

    /// [`ray_first_hit`](Self::ray_first_hit) of each ray, in the rays' order: the same
    /// answers as one call per ray. With the `parallel` feature the rays are split across
    /// threads (rayon's work stealing), one per core or as many as
    /// `queries::with_threads` (the `parallel` feature) or a rayon pool's `install` gives.
    fn ray_first_hits(&self, rays: &[Ray<V>], t_max: f32) -> Vec<Option<Hit>>
    where
        Self: Sync,
    {
        batch::in_order(rays, |ray| self.ray_first_hit(ray, t_max))
    }

    /// [`ray_any_hit`](Self::ray_any_hit) of each ray, in order (shadow rays); parallel as
    /// [`ray_first_hits`](Self::ray_first_hits).
    fn ray_any_hits(&self, rays: &[Ray<V>], t_max: f32) -> Vec<Option<Hit>>
    where
        Self: Sync,
    {
        batch::in_order(rays, |ray| self.ray_any_hit(ray, t_max))
    }
}

/// The point of the thing nearest to a query point, and its distance.
///
/// A point inside a closed volume is its own closest point, at distance 0. Something empty
/// (the empty volume, a structure over no primitives) has no closest point and is infinitely
/// far. The plain queries take the point as given (a NaN coordinate gives `None` or NaN); the
/// `checked_` forms refuse a NaN or infinite one with a [`GeometryError`].
pub trait PointQuery<V: Vector> {
    /// The nearest point, which primitive it lies on (0 for a volume or a lone primitive) and
    /// its distance; ties go to the lower primitive index. `None` when there is nothing.
    fn closest_point(&self, point: V) -> Option<Nearest<V>>;

    /// The Euclidean distance to the nearest point: 0 inside a volume, `+inf` when there is
    /// nothing.
    #[inline]
    fn distance(&self, point: V) -> f32 {
        self.closest_point(point)
            .map_or(f32::INFINITY, |nearest| nearest.distance)
    }

    /// [`closest_point`](Self::closest_point) of each point, in order: the same answers as
    /// one call per point. A large batch is answered in Morton order of the points, so that
    /// neighbours find the tree's nodes in the cache, and the answers are put back in order;
    /// with the `parallel` feature, split across threads.
    fn closest_points(&self, points: &[V]) -> Vec<Option<Nearest<V>>>
    where
        Self: Sync,
    {
        batch::by_location(points, |&point| self.closest_point(point))
    }

    /// [`closest_point`](Self::closest_point), refusing a non-finite query point.
    ///
    /// # Errors
    /// [`GeometryError::NonFinite`] when a coordinate of `point` is NaN or infinite.
    #[inline]
    fn checked_closest_point(&self, point: V) -> Result<Option<Nearest<V>>, GeometryError> {
        check_finite(|| "query point".into(), point).map(|p| self.closest_point(p))
    }

    /// [`distance`](Self::distance), refusing a non-finite query point.
    ///
    /// # Errors
    /// [`GeometryError::NonFinite`] when a coordinate of `point` is NaN or infinite.
    #[inline]
    fn checked_distance(&self, point: V) -> Result<f32, GeometryError> {
        check_finite(|| "query point".into(), point).map(|p| self.distance(p))
    }
}

/// A primitive answers from the two methods it implements: [`Primitive::ray_hit`] (with
/// [`Primitive::hit_coordinates`]) and [`Primitive::project_point`].
impl<P: Primitive> RayCast<P::Point> for P {
    #[inline]
    fn ray_first_hit(&self, ray: &Ray<P::Point>, t_max: f32) -> Option<Hit> {
        let t = self.ray_hit(ray).filter(|&t| t <= t_max)?;
        Some(Hit::on(0, t, self, ray))
    }
}

impl<P: Primitive> PointQuery<P::Point> for P {
    #[inline]
    fn closest_point(&self, point: P::Point) -> Option<Nearest<P::Point>> {
        let nearest = self.project_point(point);
        Some(Nearest {
            prim: 0,
            point: nearest,
            distance: (nearest - point).length(),
        })
    }
}

/// The answer of a volume that meets the ray over `interval`, as a hit on "primitive 0".
#[inline]
pub(crate) fn volume_hit(interval: Option<(f32, f32)>, t_max: f32) -> Option<Hit> {
    let (t_enter, _) = interval.filter(|&(t, _)| t <= t_max)?;
    Some(Hit {
        prim: 0,
        t: t_enter,
        u: 0.0,
        v: 0.0,
    })
}

/// The answer of a volume whose nearest point to `point` is `nearest`.
#[inline]
pub(crate) fn volume_nearest<V: Vector>(point: V, nearest: Option<V>) -> Option<Nearest<V>> {
    nearest.map(|q| Nearest {
        prim: 0,
        point: q,
        distance: (q - point).length(),
    })
}
