//! Splitting planes (lines in 2D): which side a primitive lies on, where a ray crosses.
//!
//! The arithmetic is `f64`: a product of two `f32` values is exact in `f64`, so signed distances
//! of `f32` points to an `f32` plane lose only the rounding of a few additions, far below the
//! tolerance used here. Classification is conservative: a primitive goes to every side that it
//! may reach within the tolerance, so no query can miss it.

use crate::structure::plane_tree::{Crossing, SLACK};
use crate::{Primitive, Ray, Vector};

/// The tolerance of a signed distance, relative to the magnitudes summed to compute it: a few
/// units in the last place of `f32`, so that a primitive's own supporting plane (stored in
/// `f32`) still counts it as lying in the plane.
const IN_PLANE: f64 = 4.0 * f32::EPSILON as f64;

/// The rounding of `f64` sums of a few exact products, relative to their magnitudes.
const F64_ROUNDING: f64 = 1e-12;

/// The plane `normal · x = offset`; "below" is `normal · x < offset`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Plane<V: Vector> {
    /// Unit normal.
    pub normal: V,
    /// Offset along the normal.
    pub offset: f32,
}

/// Which sides of a plane a primitive reaches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Sides {
    /// It has a point on or below the plane.
    pub below: bool,
    /// It has a point on or above the plane.
    pub above: bool,
}

impl<V: Vector> Plane<V> {
    /// The plane through `point` with normal `direction` (normalised here); `None` when the
    /// direction is zero or not finite, or the offset is not finite.
    pub(crate) fn through(point: V, direction: V) -> Option<Self> {
        let d = direction.to_dvec3();
        let length = d.length();
        if !(length > 0.0 && length.is_finite()) {
            return None;
        }
        let normal = V::from_dvec3(d / length);
        let offset = normal.to_dvec3().dot(point.to_dvec3()) as f32;
        (normal.is_finite() && offset.is_finite() && normal != V::ZERO)
            .then_some(Self { normal, offset })
    }

    /// The signed distance `normal · p - offset` and the magnitude of its terms.
    fn signed(&self, p: V) -> (f64, f64) {
        let (n, p) = (self.normal.to_dvec3(), p.to_dvec3());
        let terms = n * p;
        let offset = f64::from(self.offset);
        (
            terms.x + terms.y + terms.z - offset,
            terms.abs().element_sum() + offset.abs(),
        )
    }

    /// The sides a convex primitive reaches: below when some vertex is on or below the plane
    /// (within the tolerance), above likewise. A primitive in the plane reaches both; every
    /// primitive reaches at least one.
    pub(crate) fn sides<P: Primitive<Point = V>>(&self, prim: &P) -> Sides {
        let mut sides = Sides {
            below: false,
            above: false,
        };
        for v in prim.vertices() {
            let (d, scale) = self.signed(v);
            let tol = IN_PLANE * scale;
            sides.below |= d <= tol;
            sides.above |= d >= -tol;
        }
        if !sides.below && !sides.above {
            // Only NaN distances get here; the builders skip such primitives.
            sides = Sides {
                below: true,
                above: true,
            };
        }
        sides
    }

    /// The sides the primitive certainly reaches: those with a vertex farther from the plane
    /// than a generous tolerance (what a validator may demand).
    pub(crate) fn certain_sides<P: Primitive<Point = V>>(&self, prim: &P) -> Sides {
        let mut sides = Sides {
            below: false,
            above: false,
        };
        for v in prim.vertices() {
            let (d, scale) = self.signed(v);
            let tol = 1e3 * IN_PLANE * scale;
            sides.below |= d < -tol;
            sides.above |= d > tol;
        }
        sides
    }

    /// The side a point is on: 0 below, 1 above (on the plane counts as above).
    pub(crate) fn side_of(&self, p: V) -> usize {
        usize::from(self.signed(p).0 >= 0.0)
    }

    /// Where the ray crosses the plane, `t = -(n · o - c) / (n · d)`, with its error margin: the
    /// `f64` rounding, plus [`SLACK`] relative to the terms for the primitives' own `f32`
    /// rounding. A ray (numerically) parallel to the plane stays on the side of its origin, or
    /// in the plane (both sides) when its origin is within the tolerance.
    pub(crate) fn crossing(&self, ray: &Ray<V>) -> Crossing {
        let (dist, scale_o) = self.signed(ray.origin());
        let n = self.normal.to_dvec3();
        let terms = n * ray.dir().to_dvec3();
        let denom = terms.x + terms.y + terms.z;
        let scale_d = terms.abs().element_sum();
        if denom == 0.0 {
            let tol = IN_PLANE * scale_o;
            return Crossing::Parallel {
                below: dist <= tol,
                above: dist >= -tol,
            };
        }
        let t = -dist / denom;
        let err = (F64_ROUNDING * (scale_o + t.abs() * scale_d)
            + f64::from(SLACK) * (scale_o + t.abs() * scale_d))
            / denom.abs();
        if t.is_nan() || err.is_nan() {
            return Crossing::Parallel {
                below: true,
                above: true,
            };
        }
        Crossing::At {
            t: t as f32,
            err: err as f32,
            below_first: denom > 0.0,
        }
    }
}
