//! Bounding volumes: simple shapes that enclose other geometry (lecture §2).
//!
//! One file per volume, each generic over the dimension: [`Aabb`], [`Sphere`] (its three fits
//! in [`sphere_fit`]), [`Obb`] (the separating-axis test in [`obb_sat`]), and [`ConvexHull`]
//! (built by [`hull_build2`] and [`hull_build3`]). [`tightness`] compares them on one point set.

pub mod aabb;
pub mod hull;
pub mod hull_build2;
pub mod hull_build3;
pub mod obb;
pub mod obb_sat;
pub mod sphere;
pub mod sphere_fit;
pub mod tightness;

pub use aabb::{Aabb, SlabTest};
pub use hull::ConvexHull;
pub use obb::{Obb, PcaFit};
pub use obb_sat::{AxisSource, AxisTest, SeparatingAxis};
pub use sphere::Sphere;
pub use tightness::{FitKind, FitReport};

use std::borrow::Cow;
use std::fmt::Debug;

use crate::error::{GeometryError, check_finite};
use crate::queries::{PointQuery, RayCast};
use crate::{Ray, Vector};

/// The queries every bounding volume answers, in 2D and 3D.
///
/// Where the ray first meets a volume and its nearest point to a point are the questions
/// every primitive and structure answers too: [`RayCast`] and [`PointQuery`], which every
/// volume implements. This trait adds what only volumes answer: the whole interval a ray
/// spends inside, containment, overlap, merging and measures.
///
/// Volumes are closed sets: a point on the boundary is contained, and a ray that only touches
/// the boundary hits. The empty volume (fitted to no points) contains nothing, is missed by
/// every ray and is infinitely far from every point.
///
/// The plain queries take the query point as given; a point with a NaN or infinite coordinate
/// then yields `false`, `None` or NaN. The `checked_` variants reject such a point with a
/// [`GeometryError`] instead (rays are checked when they are made, see [`Ray::new`]).
pub trait BoundingVolume: Clone + Debug + RayCast<Self::Point> + PointQuery<Self::Point> {
    /// The vector type: [`Vec2`](glam::Vec2) or [`Vec3`](glam::Vec3).
    type Point: Vector;

    /// The interval `[t_enter, t_exit]` of `t >= 0` for which the ray is inside the volume, or
    /// `None` when the ray misses. `t_enter = 0` when the origin is inside; a ray that only
    /// touches the boundary gives `t_enter == t_exit`.
    fn ray_interval(&self, ray: &Ray<Self::Point>) -> Option<(f32, f32)>;

    /// Whether `point` lies in the volume, boundary included.
    fn contains(&self, point: Self::Point) -> bool;

    /// Whether two volumes of this kind share at least one point (touching counts).
    fn overlaps(&self, other: &Self) -> bool;

    /// A volume of this kind that contains both (for building hierarchies bottom-up).
    #[must_use]
    fn merge(&self, other: &Self) -> Self;

    /// Area in 2D, volume in 3D.
    fn measure(&self) -> f32;

    /// Perimeter in 2D, surface area in 3D: the quantity the surface area heuristic weighs.
    fn boundary_measure(&self) -> f32;

    /// Whether this is the empty volume.
    fn is_empty(&self) -> bool;

    /// The axis-aligned box around this volume.
    fn aabb(&self) -> Aabb<Self::Point>;

    /// [`contains`](Self::contains), rejecting a non-finite query point.
    ///
    /// # Errors
    /// [`GeometryError::NonFinite`] when a coordinate of `point` is NaN or infinite.
    fn checked_contains(&self, point: Self::Point) -> Result<bool, GeometryError> {
        check_finite(|| "query point".into(), point).map(|p| self.contains(p))
    }
}

/// The finite points of a fit's input. The lenient fits (`from_points`, `centroid_fit`, ...)
/// skip NaN and infinite points rather than let one poison the whole volume; the `try_`
/// fits use [`checked_points`] to report them instead.
pub(crate) fn finite_points<V: Vector>(points: &[V]) -> Cow<'_, [V]> {
    if points.iter().all(|p| p.is_finite()) {
        Cow::Borrowed(points)
    } else {
        Cow::Owned(points.iter().copied().filter(|p| p.is_finite()).collect())
    }
}

/// Checks a fit's input: non-empty, every coordinate finite.
///
/// # Errors
/// [`GeometryError::Empty`] for no points; [`GeometryError::NonFinite`] naming the first bad
/// point by its index.
pub(crate) fn checked_points<V: Vector>(points: &[V]) -> Result<&[V], GeometryError> {
    if points.is_empty() {
        return Err(GeometryError::Empty { what: "point set" });
    }
    for (i, &p) in points.iter().enumerate() {
        check_finite(|| format!("point {i}"), p)?;
    }
    Ok(points)
}
