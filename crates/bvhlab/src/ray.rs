//! Rays `p(t) = e + t d`, validated once at construction.

use crate::Vector;
use crate::error::{GeometryError, check_finite};
use crate::primitive::triangle::RayShear;

/// A ray `p(t) = origin + t · dir` for `t >= 0`, in 2D ([`Ray2`](crate::Ray2)) or 3D
/// ([`Ray3`](crate::Ray3)).
///
/// The direction need not have unit length: `t` is measured in units of `dir`, exactly as in
/// the lecture's `p(t) = e + t (s - e)`, where `t = 1` is the point `s`. Construction rejects
/// non-finite coordinates and a zero or subnormal direction, so every query can trust its
/// ray.
///
/// Construction also precomputes what the watertight triangle test needs of the direction
/// (the permutation and shear of Woop, Benthin and Wald), so that a 3D query does that once
/// per ray, not once per triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray<V: Vector> {
    origin: V,
    dir: V,
    inv_dir: V,
    shear: RayShear,
}

impl<V: Vector> Ray<V> {
    /// A ray from `origin` along `dir`.
    ///
    /// # Errors
    /// [`GeometryError::NonFinite`] when a coordinate is NaN or infinite;
    /// [`GeometryError::ZeroDirection`] when `dir` is zero (`-0.0` counts as zero);
    /// [`GeometryError::TinyDirection`] when every component of `dir` is subnormal (below
    /// [`f32::MIN_POSITIVE`] in magnitude), like `1e-40`: its inverse overflows and `t`
    /// along it overflows for any hit at an ordinary distance, so such a ray would never hit
    /// anything. One subnormal component beside a normal one is fine (it acts as zero in the
    /// slab test, as it should). Any direction reaches only what lies within `f32::MAX`
    /// units of it (`t` is measured in them): with a direction of length 1e-30, nothing
    /// beyond 3.4e8; normalise tiny directions if you need farther hits.
    pub fn new(origin: V, dir: V) -> Result<Self, GeometryError> {
        check_finite(|| "ray origin".into(), origin)?;
        check_finite(|| "ray direction".into(), dir)?;
        if dir == V::ZERO {
            return Err(GeometryError::ZeroDirection);
        }
        if dir.abs().max_element() < f32::MIN_POSITIVE {
            return Err(GeometryError::TinyDirection {
                value: format!("{dir:?}"),
            });
        }
        // 1/±0 = ±inf is what the slab test wants; the zero components are handled there.
        let mut inv_dir = V::ZERO;
        for i in 0..V::DIM {
            inv_dir.set_coord(i, 1.0 / dir.coord(i));
        }
        let shear = if V::DIM == 3 {
            RayShear::of(dir.to_dvec3().as_vec3())
        } else {
            RayShear::default()
        };
        Ok(Self {
            origin,
            dir,
            inv_dir,
            shear,
        })
    }

    /// The ray through `from` and `to`, with `t = 1` at `to` (the lecture's `e` and `s`).
    ///
    /// # Errors
    /// As [`Ray::new`]; `from == to` gives [`GeometryError::ZeroDirection`], two points closer
    /// than about 1e-38 in every coordinate [`GeometryError::TinyDirection`].
    pub fn through(from: V, to: V) -> Result<Self, GeometryError> {
        check_finite(|| "ray end point".into(), to)?;
        Self::new(from, to - from)
    }

    /// The origin `e`.
    pub fn origin(&self) -> V {
        self.origin
    }

    /// The direction `d` (not normalised).
    pub fn dir(&self) -> V {
        self.dir
    }

    /// Component-wise `1 / d`, with `±inf` where a component of `d` is `±0`.
    pub fn inv_dir(&self) -> V {
        self.inv_dir
    }

    /// The watertight triangle test's setup for this direction (3D; unused in 2D).
    #[inline]
    pub(crate) fn shear(&self) -> &RayShear {
        &self.shear
    }

    /// The point `e + t d`.
    pub fn at(&self, t: f32) -> V {
        self.origin + self.dir * t
    }
}
