//! Axis-aligned bounding boxes and the slab test (lecture §2, "Axis-aligned bounding box").

use super::{BoundingVolume, checked_points, finite_points};
use crate::error::GeometryError;
use crate::queries::{PointQuery, RayCast, volume_hit, volume_nearest};
use crate::{Hit, Nearest};
use crate::{Ray, Vector};

/// An axis-aligned box `[min, max]`, closed, in 2D ([`Aabb2`](crate::Aabb2)) or 3D
/// ([`Aabb3`](crate::Aabb3)).
///
/// The empty box has `min = +inf` and `max = -inf` in every coordinate, so that it is the
/// identity of [`merge`](BoundingVolume::merge) and growing it by a point gives that point.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb<V: Vector> {
    /// The corner with the smallest coordinates (`x_min`, `y_min`, `z_min`).
    pub min: V,
    /// The corner with the largest coordinates.
    pub max: V,
}

/// The slab test of a ray against a box, axis by axis, as the lecture draws it.
///
/// For each axis `i`, `[t_near[i], t_far[i]]` is where the ray is between the two planes of
/// that slab (the entry and exit ends swapped when the direction component is negative). A
/// ray parallel to a slab (`d_i = ±0`) is inside it for all `t` (`[-inf, +inf]`) or never
/// (`[+inf, -inf]`) depending on where its origin lies; deciding this from the origin, rather
/// than from `(x_min - x_e) · inf`, avoids the `0 · inf = NaN` of an origin exactly on a slab
/// plane (the lecture's "when does this fail?").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlabTest<V: Vector> {
    /// Per axis, the `t` at which the ray enters the slab.
    pub t_near: V,
    /// Per axis, the `t` at which the ray leaves the slab.
    pub t_far: V,
}

impl<V: Vector> SlabTest<V> {
    /// `max_i t_near[i]`: the last slab entry.
    #[inline]
    pub fn t_enter(&self) -> f32 {
        self.t_near.max_element()
    }

    /// `min_i t_far[i]`: the first slab exit.
    #[inline]
    pub fn t_exit(&self) -> f32 {
        self.t_far.min_element()
    }

    /// The lecture's test: the ray misses when `max(t_near) > min(t_far)`, or when the whole
    /// overlap lies behind the origin. Otherwise the interval, clamped to `t >= 0`.
    #[inline]
    pub fn interval(&self) -> Option<(f32, f32)> {
        let enter = self.t_enter().max(0.0);
        let exit = self.t_exit();
        (enter <= exit).then_some((enter, exit))
    }
}

impl<V: Vector> Aabb<V> {
    /// The empty box.
    pub const EMPTY: Self = Self {
        min: V::INFINITY,
        max: V::NEG_INFINITY,
    };

    /// The box with the given corners. A box with `min > max` on some axis is empty.
    pub const fn new(min: V, max: V) -> Self {
        Self { min, max }
    }

    /// The lecture's fit: `x_min = min_i v_x^i`, `x_max = max_i v_x^i`, and likewise for `y`
    /// (and `z`). Points with NaN or infinite coordinates are skipped; no points give
    /// [`Aabb::EMPTY`]. Use [`Aabb::try_from_points`] to be told about such input instead.
    #[inline]
    pub fn from_points(points: &[V]) -> Self {
        finite_points(points)
            .iter()
            .fold(Self::EMPTY, |b, &p| b.grown(p))
    }

    /// [`Aabb::from_points`], refusing empty or non-finite input.
    ///
    /// # Errors
    /// [`GeometryError::Empty`] or [`GeometryError::NonFinite`] (naming the point).
    #[inline]
    pub fn try_from_points(points: &[V]) -> Result<Self, GeometryError> {
        checked_points(points).map(Self::from_points)
    }

    /// The box grown to contain `p`.
    #[must_use]
    #[inline]
    pub fn grown(&self, p: V) -> Self {
        Self::new(self.min.min(p), self.max.max(p))
    }

    /// The centre `(min + max) / 2`.
    #[inline]
    pub fn center(&self) -> V {
        (self.min + self.max) * 0.5
    }

    /// The side lengths `max - min` (zero for an empty box).
    #[inline]
    pub fn size(&self) -> V {
        if self.is_empty() {
            V::ZERO
        } else {
            self.max - self.min
        }
    }

    /// The axis along which the box is longest (the lecture's split axis).
    #[inline]
    pub fn longest_axis(&self) -> usize {
        let size = self.size();
        (0..V::DIM)
            .max_by(|&i, &j| size.coord(i).total_cmp(&size.coord(j)))
            .unwrap_or(0)
    }

    /// The corners, `2^DIM` of them, in binary order (bit `i` set: `max` on axis `i`).
    #[inline]
    pub fn corners(&self) -> impl Iterator<Item = V> + '_ {
        (0..1usize << V::DIM).map(move |bits| {
            let mut corner = self.min;
            for i in (0..V::DIM).filter(|i| bits >> i & 1 == 1) {
                corner.set_coord(i, self.max.coord(i));
            }
            corner
        })
    }

    /// The slab test, axis by axis, for drawing and stepping; see [`SlabTest`].
    #[inline]
    pub fn slab_test(&self, ray: &Ray<V>) -> SlabTest<V> {
        let (origin, inv_dir, dir) = (ray.origin(), ray.inv_dir(), ray.dir());
        let mut t_near = V::ZERO;
        let mut t_far = V::ZERO;
        for i in 0..V::DIM {
            let (o, lo, hi) = (origin.coord(i), self.min.coord(i), self.max.coord(i));
            let (near, far) = if dir.coord(i) == 0.0 {
                if lo <= o && o <= hi {
                    (f32::NEG_INFINITY, f32::INFINITY)
                } else {
                    (f32::INFINITY, f32::NEG_INFINITY)
                }
            } else {
                let inv = inv_dir.coord(i);
                let (t0, t1) = ((lo - o) * inv, (hi - o) * inv);
                if inv < 0.0 { (t1, t0) } else { (t0, t1) }
            };
            t_near.set_coord(i, near);
            t_far.set_coord(i, far);
        }
        SlabTest { t_near, t_far }
    }
}

impl<V: Vector> Default for Aabb<V> {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl<V: Vector> BoundingVolume for Aabb<V> {
    type Point = V;

    #[inline]
    fn ray_interval(&self, ray: &Ray<V>) -> Option<(f32, f32)> {
        self.slab_test(ray).interval()
    }

    #[inline]
    fn contains(&self, point: V) -> bool {
        (0..V::DIM)
            .all(|i| self.min.coord(i) <= point.coord(i) && point.coord(i) <= self.max.coord(i))
    }

    #[inline]
    fn overlaps(&self, other: &Self) -> bool {
        (0..V::DIM).all(|i| {
            self.min.coord(i) <= other.max.coord(i) && other.min.coord(i) <= self.max.coord(i)
        }) && !self.is_empty()
            && !other.is_empty()
    }

    #[inline]
    fn merge(&self, other: &Self) -> Self {
        Self::new(self.min.min(other.min), self.max.max(other.max))
    }

    #[inline]
    fn measure(&self) -> f32 {
        V::box_measure(self.size())
    }

    #[inline]
    fn boundary_measure(&self) -> f32 {
        V::box_boundary_measure(self.size())
    }

    #[inline]
    fn is_empty(&self) -> bool {
        (0..V::DIM).any(|i| self.min.coord(i) > self.max.coord(i))
    }

    #[inline]
    fn aabb(&self) -> Self {
        *self
    }
}

impl<V: Vector> Aabb<V> {
    #[inline]
    pub(crate) fn nearest_point(&self, point: V) -> Option<V> {
        (!self.is_empty()).then(|| point.max(self.min).min(self.max))
    }
}

impl<V: Vector> RayCast<V> for Aabb<V> {
    /// Where the ray enters ([`BoundingVolume::ray_interval`]): `t = 0` from inside.
    #[inline]
    fn ray_first_hit(&self, ray: &Ray<V>, t_max: f32) -> Option<Hit> {
        volume_hit(self.ray_interval(ray), t_max)
    }
}

impl<V: Vector> PointQuery<V> for Aabb<V> {
    #[inline]
    fn closest_point(&self, point: V) -> Option<Nearest<V>> {
        volume_nearest(point, self.nearest_point(point))
    }
}
