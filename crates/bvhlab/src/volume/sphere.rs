//! Bounding spheres (circles in 2D) and the ray-sphere quadratic (lecture §2, "Bounding sphere").
//!
//! The fits live in [`super::sphere_fit`].

use crate::queries::{PointQuery, RayCast, volume_hit, volume_nearest};
use crate::{Hit, Nearest};
use glam::DVec3;

use super::{Aabb, BoundingVolume};
use crate::{Ray, Vector};

/// A closed ball `|p - center| <= radius`: a sphere in 3D ([`Sphere3`](crate::Sphere3)), a
/// circle in 2D ([`Sphere2`](crate::Sphere2)).
///
/// A negative radius is the empty sphere ([`Sphere::EMPTY`], fitted to no points).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere<V: Vector> {
    /// The centre `c`.
    pub center: V,
    /// The radius `r`.
    pub radius: f32,
}

/// The lecture's quadratic `a t² + b t + c = 0` for a ray against a sphere, with the sphere
/// translated to the origin: `a = dᵀd`, `b = 2 eᵀd`, `c = eᵀe - r²` (e is the ray origin
/// relative to the centre, d the ray direction). Computed in `f64`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayQuadratic {
    /// `dᵀd`.
    pub a: f64,
    /// `2 eᵀd`.
    pub b: f64,
    /// `eᵀe - r²`.
    pub c: f64,
}

impl RayQuadratic {
    /// The discriminant `b² - 4ac`: negative when the ray's line misses the sphere.
    pub fn discriminant(&self) -> f64 {
        self.b * self.b - 4.0 * self.a * self.c
    }

    /// Both roots `t0 <= t1` of the quadratic, or `None` when the discriminant is negative.
    ///
    /// Uses the cancellation-free form `q = -(b + sign(b) √disc) / 2`, `t = q/a` and `c/q`
    /// (Press et al., "Numerical Recipes", §5.6), because the textbook `(-b ± √disc) / 2a`
    /// loses all precision in one root when `b² ≫ 4ac`, i.e. for a far-away sphere.
    pub fn roots(&self) -> Option<(f64, f64)> {
        let disc = self.discriminant();
        if disc < 0.0 {
            return None;
        }
        let q = -0.5 * (self.b + self.b.signum() * disc.sqrt());
        let (r0, r1) = if q == 0.0 {
            // b = 0 and disc = 0: the double root t = 0 (the ray starts on a tangent point).
            (0.0, 0.0)
        } else {
            (q / self.a, self.c / q)
        };
        Some((r0.min(r1), r0.max(r1)))
    }
}

impl<V: Vector> Sphere<V> {
    /// The empty sphere: contains nothing, missed by every ray.
    pub const EMPTY: Self = Self {
        center: V::ZERO,
        radius: f32::NEG_INFINITY,
    };

    /// The sphere with the given centre and radius.
    pub const fn new(center: V, radius: f32) -> Self {
        Self { center, radius }
    }

    /// The coefficients of the lecture's ray-sphere quadratic for this ray.
    pub fn ray_quadratic(&self, ray: &Ray<V>) -> RayQuadratic {
        let e: DVec3 = (ray.origin() - self.center).to_dvec3();
        let d: DVec3 = ray.dir().to_dvec3();
        let r = f64::from(self.radius);
        RayQuadratic {
            a: d.dot(d),
            b: 2.0 * e.dot(d),
            c: e.dot(e) - r * r,
        }
    }

    /// `|point - center|`, in `f64`: exact enough that containment never depends on `f32`
    /// overflow (coordinates beyond ~1e19 overflow `f32` squares) or rounding.
    pub fn center_distance(&self, point: V) -> f64 {
        (point.to_dvec3() - self.center.to_dvec3()).length()
    }

    /// The smallest sphere containing this sphere and `point`.
    #[must_use]
    pub fn grown(&self, point: V) -> Self {
        self.merge(&Self::new(point, 0.0))
    }
}

/// The smallest `f32` that is at least `x`, so that a radius computed in `f64` still covers
/// every point it was measured to.
pub(crate) fn round_up(x: f64) -> f32 {
    let r = x as f32;
    if f64::from(r) < x { r.next_up() } else { r }
}

impl<V: Vector> Default for Sphere<V> {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl<V: Vector> BoundingVolume for Sphere<V> {
    type Point = V;

    /// Solves the lecture's quadratic; the ray is inside between the two roots.
    fn ray_interval(&self, ray: &Ray<V>) -> Option<(f32, f32)> {
        if self.is_empty() {
            return None;
        }
        let (t0, t1) = self.ray_quadratic(ray).roots()?;
        (t1 >= 0.0).then(|| (t0.max(0.0) as f32, t1 as f32))
    }

    fn contains(&self, point: V) -> bool {
        self.center_distance(point) <= f64::from(self.radius)
    }

    fn overlaps(&self, other: &Self) -> bool {
        !self.is_empty()
            && !other.is_empty()
            && self.center_distance(other.center)
                <= f64::from(self.radius) + f64::from(other.radius)
    }

    /// The smallest sphere containing both (exact: it is tangent to both from inside).
    fn merge(&self, other: &Self) -> Self {
        if other.is_empty() {
            return *self;
        }
        if self.is_empty() {
            return *other;
        }
        let (r1, r2) = (f64::from(self.radius), f64::from(other.radius));
        let dist = self.center_distance(other.center);
        if dist + r2 <= r1 {
            return *self;
        }
        if dist + r1 <= r2 {
            return *other;
        }
        let radius = 0.5 * (dist + r1 + r2);
        let (c1, c2) = (self.center.to_dvec3(), other.center.to_dvec3());
        let center = V::from_dvec3(c1 + (c2 - c1) * ((radius - r1) / dist));
        // Rounding the centre to f32 may leave either sphere a hair outside: cover both.
        let probe = Self::new(center, 0.0);
        let radius =
            (probe.center_distance(self.center) + r1).max(probe.center_distance(other.center) + r2);
        Self::new(center, round_up(radius))
    }

    fn measure(&self) -> f32 {
        if self.is_empty() {
            0.0
        } else {
            V::ball_measure(self.radius)
        }
    }

    fn boundary_measure(&self) -> f32 {
        if self.is_empty() {
            0.0
        } else {
            V::ball_boundary_measure(self.radius)
        }
    }

    fn is_empty(&self) -> bool {
        // A NaN radius also counts as empty.
        self.radius.is_nan() || self.radius < 0.0
    }

    fn aabb(&self) -> Aabb<V> {
        if self.is_empty() {
            return Aabb::EMPTY;
        }
        let extent = V::splat(self.radius);
        Aabb::new(self.center - extent, self.center + extent)
    }
}

impl<V: Vector> Sphere<V> {
    pub(crate) fn nearest_point(&self, point: V) -> Option<V> {
        if self.is_empty() {
            return None;
        }
        let offset = point.to_dvec3() - self.center.to_dvec3();
        let dist = offset.length();
        Some(if dist <= f64::from(self.radius) {
            point
        } else {
            V::from_dvec3(self.center.to_dvec3() + offset * (f64::from(self.radius) / dist))
        })
    }
}

impl<V: Vector> RayCast<V> for Sphere<V> {
    /// Where the ray enters ([`BoundingVolume::ray_interval`]): `t = 0` from inside.
    #[inline]
    fn ray_first_hit(&self, ray: &Ray<V>, t_max: f32) -> Option<Hit> {
        volume_hit(self.ray_interval(ray), t_max)
    }
}

impl<V: Vector> PointQuery<V> for Sphere<V> {
    #[inline]
    fn closest_point(&self, point: V) -> Option<Nearest<V>> {
        volume_nearest(point, self.nearest_point(point))
    }

    fn distance(&self, point: V) -> f32 {
        (self.center_distance(point) - f64::from(self.radius)).max(0.0) as f32
    }
}
