//! Oriented bounding boxes fitted by principal component analysis (lecture §2, "Object-oriented
//! bounding box"). The overlap test, the separating-axis theorem, is in
//! [`obb_sat`](super::obb_sat).
//!
//! Every query works in the box's own frame, where the box is the axis-aligned box
//! `[-half_extents, half_extents]`: [`Obb::to_local`] moves a point there, and the ray and
//! distance queries then reuse what [`Aabb`] does (Ericson, "Real-Time Collision Detection",
//! §4.4 and §5.1.4).

use super::{Aabb, BoundingVolume, SlabTest, checked_points, finite_points};
use crate::error::GeometryError;
use crate::queries::{PointQuery, RayCast, volume_hit, volume_nearest};
use crate::{Hit, Nearest};
use crate::{Ray, Vector};

/// An oriented box, closed, in 2D ([`Obb2`](crate::Obb2)) or 3D ([`Obb3`](crate::Obb3)): the
/// points `center + Σ_i s_i axes[i]` with `|s_i| <= half_extents[i]`.
///
/// `axes` must be orthonormal (right-handed in 3D); the fits and [`Obb::from_aabb`] make it so.
/// The empty box has negative (`-inf`) half extents: it contains nothing, and merging with it
/// gives the other box.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Obb<V: Vector> {
    /// The centre of the box.
    pub center: V,
    /// The box's own axes: unit vectors, pairwise orthogonal, right-handed in 3D.
    pub axes: V::Axes,
    /// Half the side length along each of `axes`, in the same order.
    pub half_extents: V,
}

/// What the PCA fit computed on its way to the box, for the lab to show next to it.
///
/// These are the steps of the lecture's method: the centroid, the covariance matrix of the
/// points, and its eigenvectors (the box's axes) with their eigenvalues, which are the
/// variances of the points along those axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PcaFit<V: Vector> {
    /// The centroid `c = (1/n) Σ v_i` (not the box centre: that is re-placed at the middle of
    /// the extents).
    pub mean: V,
    /// The covariance matrix `(1/n) Σ (v_i - c)(v_i - c)ᵀ`, symmetric, one row per vector.
    pub covariance: V::Axes,
    /// The principal axes, by decreasing variance: the box's [`Obb::axes`].
    pub axes: V::Axes,
    /// The variance of the points along each principal axis (the covariance's eigenvalues),
    /// largest first; never negative.
    pub variances: V,
}

impl<V: Vector> Obb<V> {
    /// The box with the given centre, orthonormal axes and half extents, taken as given.
    pub const fn new(center: V, axes: V::Axes, half_extents: V) -> Self {
        Self {
            center,
            axes,
            half_extents,
        }
    }

    /// The empty box: identity axes, `-inf` half extents.
    #[must_use]
    pub fn empty() -> Self {
        Self::new(V::ZERO, V::identity_axes(), V::NEG_INFINITY)
    }

    /// The lecture's PCA fit; see [`Obb::pca_fit_detailed`]. Points with NaN or infinite
    /// coordinates are skipped; no points give the empty box. Use [`Obb::try_pca_fit`] to be
    /// told about such input instead.
    #[must_use]
    pub fn pca_fit(points: &[V]) -> Self {
        Self::pca_fit_detailed(points).0
    }

    /// [`Obb::pca_fit`], refusing empty or non-finite input.
    ///
    /// # Errors
    /// [`GeometryError::Empty`] or [`GeometryError::NonFinite`] (naming the point).
    pub fn try_pca_fit(points: &[V]) -> Result<Self, GeometryError> {
        checked_points(points).map(Self::pca_fit)
    }

    /// The lecture's PCA fit, with the intermediate results the lab shows.
    ///
    /// The centroid `c` and the covariance matrix of the points give the axes: its
    /// eigenvectors, largest variance first ([`Vector::principal_axes`]). The extents are the
    /// minimum and maximum of the points projected on each axis, and the centre is re-placed at
    /// the middle of them (it is not `c` in general).
    ///
    /// Every fitted point is contained, exactly: after the centre is placed, each half extent
    /// is recomputed as `max |axes[i] · (p - center)|`, the very `f32` expression that
    /// [`contains`](BoundingVolume::contains) evaluates, so rounding cannot leave a point out.
    /// Degenerate sets (one point, a segment, a plane) give zero extents along the missing
    /// directions; symmetric sets (a square, a cube) have repeated variances and then any
    /// orthonormal frame of the eigenspace is used.
    ///
    /// Non-finite points are skipped as in [`Obb::pca_fit`].
    ///
    /// ```
    /// use bvhlab::glam::Vec2;
    /// use bvhlab::prelude::*;
    ///
    /// let points = [Vec2::new(0.0, 0.0), Vec2::new(4.0, 2.0), Vec2::new(2.5, 0.5)];
    /// let (obb, pca) = Obb2::pca_fit_detailed(&points);
    /// assert!(points.iter().all(|&p| obb.contains(p)));
    /// assert!(pca.variances.x >= pca.variances.y);
    /// assert_eq!(pca.axes, obb.axes);
    /// ```
    #[must_use]
    pub fn pca_fit_detailed(points: &[V]) -> (Self, PcaFit<V>) {
        let points = finite_points(points);
        let pca = V::principal_axes(&points);
        (Self::fit_in_frame(&points, pca.mean, pca.axes), pca)
    }

    /// The tightest box with the given orthonormal `axes` around the points (skipping
    /// non-finite ones; empty for none), with the same exact containment as the PCA fit.
    ///
    /// This lets the lab compare the PCA axes with axes the user turns by hand.
    #[must_use]
    pub fn fit_with_axes(points: &[V], axes: V::Axes) -> Self {
        let points = finite_points(points);
        let reference = points.first().copied().unwrap_or(V::ZERO);
        Self::fit_in_frame(&points, reference, axes)
    }

    /// The box with identity axes that covers `aabb` (empty for the empty box); contains
    /// every corner of `aabb`.
    #[must_use]
    pub fn from_aabb(aabb: &Aabb<V>) -> Self {
        if aabb.is_empty() {
            Self::empty()
        } else {
            // The two extreme corners fix every half extent of an axis-aligned frame.
            Self::fit_in_frame(&[aabb.min, aabb.max], aabb.min, V::identity_axes())
        }
    }

    /// Projects finite `points` on `axes` (relative to `reference`, which keeps the
    /// differences small), centres the box between the extremes, then takes each half extent
    /// as the largest `|axes[i] · (p - center)|`, the formula of `contains`.
    fn fit_in_frame(points: &[V], reference: V, axes: V::Axes) -> Self {
        if points.is_empty() {
            return Self::new(V::ZERO, axes, V::NEG_INFINITY);
        }
        let frame = Self::new(reference, axes, V::ZERO);
        let (lo, hi) = points
            .iter()
            .map(|&p| frame.to_local(p))
            .fold((V::INFINITY, V::NEG_INFINITY), |(lo, hi), l| {
                (lo.min(l), hi.max(l))
            });
        // Halving before adding cannot overflow.
        let center = frame.to_world(lo * 0.5 + hi * 0.5);
        let mut obb = Self::new(center, axes, V::ZERO);
        obb.half_extents = points
            .iter()
            .fold(V::ZERO, |h, &p| h.max(obb.to_local(p).abs()));
        obb
    }

    /// Axis `i` of the box.
    fn axis(&self, i: usize) -> V {
        self.axes.as_ref()[i]
    }

    /// Coordinates of `p` in the box's frame: `axes[i] · (p - center)`. The box is
    /// `[-half_extents, half_extents]` there.
    #[must_use]
    pub fn to_local(&self, p: V) -> V {
        self.rotate_to_local(p - self.center)
    }

    /// The world point with box-frame coordinates `local`: `center + Σ_i local[i] axes[i]`.
    #[must_use]
    pub fn to_world(&self, local: V) -> V {
        (0..V::DIM).fold(self.center, |p, i| p + self.axis(i) * local.coord(i))
    }

    /// A direction in the box's frame (rotation only, no translation).
    fn rotate_to_local(&self, d: V) -> V {
        let mut local = V::ZERO;
        for i in 0..V::DIM {
            local.set_coord(i, self.axis(i).dot(d));
        }
        local
    }

    /// The corners, `2^DIM` of them (none for the empty box), in binary order: bit `i` set
    /// means `+half_extents[i]` along `axes[i]`, as [`Aabb::corners`].
    pub fn corners(&self) -> impl Iterator<Item = V> + '_ {
        let count = if self.is_empty() { 0 } else { 1usize << V::DIM };
        (0..count).map(move |bits| {
            let mut local = -self.half_extents;
            for i in (0..V::DIM).filter(|i| bits >> i & 1 == 1) {
                local.set_coord(i, self.half_extents.coord(i));
            }
            self.to_world(local)
        })
    }

    /// The slab test in the box's own frame, for drawing and stepping, or `None` for the empty
    /// box.
    ///
    /// The ray is rotated and translated into the frame, where the box is the axis-aligned
    /// `[-half_extents, half_extents]`, and [`Aabb::slab_test`] does the rest. A rotation
    /// keeps lengths, so `t` is still measured in units of the original `ray.dir()`. Also
    /// `None` in the freak case where the moved ray is not representable (a direction so
    /// small that it rotates to zero, or an origin beyond `f32` range in the frame).
    pub fn slab_test(&self, ray: &Ray<V>) -> Option<SlabTest<V>> {
        if self.is_empty() {
            return None;
        }
        let local = Ray::new(self.to_local(ray.origin()), self.rotate_to_local(ray.dir())).ok()?;
        Some(Aabb::new(-self.half_extents, self.half_extents).slab_test(&local))
    }
}

impl<V: Vector> Default for Obb<V> {
    fn default() -> Self {
        Self::empty()
    }
}

impl<V: Vector> BoundingVolume for Obb<V> {
    type Point = V;

    /// The slab test in the box's frame ([`Obb::slab_test`]). Since the origin's local
    /// coordinates are computed as in [`contains`](Self::contains), `t_enter = 0` exactly when
    /// `contains(ray.origin())`.
    fn ray_interval(&self, ray: &Ray<V>) -> Option<(f32, f32)> {
        match self.slab_test(ray) {
            Some(slabs) => slabs.interval(),
            // A direction that vanishes in the frame does not move the ray: it stays where
            // its origin is.
            None => self.contains(ray.origin()).then_some((0.0, f32::INFINITY)),
        }
    }

    fn contains(&self, point: V) -> bool {
        let local = self.to_local(point);
        (0..V::DIM).all(|i| local.coord(i).abs() <= self.half_extents.coord(i))
    }

    /// The separating-axis test: [`Obb::overlaps`].
    fn overlaps(&self, other: &Self) -> bool {
        Obb::overlaps(self, other)
    }

    /// The PCA fit of both boxes' corners. It contains both boxes, since it contains their
    /// corners and is convex, but is not the smallest such box.
    fn merge(&self, other: &Self) -> Self {
        if other.is_empty() {
            return *self;
        }
        if self.is_empty() {
            return *other;
        }
        let corners: Vec<V> = self.corners().chain(other.corners()).collect();
        Self::pca_fit(&corners)
    }

    fn measure(&self) -> f32 {
        if self.is_empty() {
            0.0
        } else {
            V::box_measure(self.half_extents * 2.0)
        }
    }

    fn boundary_measure(&self) -> f32 {
        if self.is_empty() {
            0.0
        } else {
            V::box_boundary_measure(self.half_extents * 2.0)
        }
    }

    fn is_empty(&self) -> bool {
        (0..V::DIM).any(|i| self.half_extents.coord(i) < 0.0)
    }

    /// The exact axis-aligned box: the box reaches `Σ_i |axes[i]| half_extents[i]` from its
    /// centre along the coordinate axes (Ericson §4.2.6).
    fn aabb(&self) -> Aabb<V> {
        if self.is_empty() {
            return Aabb::EMPTY;
        }
        let reach = (0..V::DIM).fold(V::ZERO, |r, i| {
            r + self.axis(i).abs() * self.half_extents.coord(i)
        });
        Aabb::new(self.center - reach, self.center + reach)
    }
}

impl<V: Vector> Obb<V> {
    /// Clamps the point to `[-half_extents, half_extents]` in the box's frame (Ericson §5.1.4);
    /// a contained point is returned as it is, not moved by the round trip through the frame.
    pub(crate) fn nearest_point(&self, point: V) -> Option<V> {
        if self.is_empty() {
            return None;
        }
        if self.contains(point) {
            return Some(point);
        }
        let h = self.half_extents;
        Some(self.to_world(self.to_local(point).max(-h).min(h)))
    }
}

impl<V: Vector> RayCast<V> for Obb<V> {
    /// Where the ray enters ([`BoundingVolume::ray_interval`]): `t = 0` from inside.
    #[inline]
    fn ray_first_hit(&self, ray: &Ray<V>, t_max: f32) -> Option<Hit> {
        volume_hit(self.ray_interval(ray), t_max)
    }
}

impl<V: Vector> PointQuery<V> for Obb<V> {
    #[inline]
    fn closest_point(&self, point: V) -> Option<Nearest<V>> {
        volume_nearest(point, self.nearest_point(point))
    }
}
