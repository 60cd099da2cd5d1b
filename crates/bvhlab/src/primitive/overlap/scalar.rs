//! The two number types the separating-axis tests are written for: [`Filtered`], plain `f64`
//! that also carries a bound on its rounding error, and [`Exact`](super::expansion::Exact),
//! exact sums of `f64` values. The tests are generic over [`Scalar`], so each formula is
//! written once and evaluated fast first, exactly only where the fast value cannot decide.

use std::cmp::Ordering;

use glam::Vec3;

/// What the separating-axis formulas need of a number: ring operations on values built from
/// `f32` inputs, and a sign that is either certain or admitted to be unknown.
pub(super) trait Scalar: Clone {
    /// The exact value of an `f32` input.
    fn from_f32(x: f32) -> Self;
    /// `self + other`.
    fn add(&self, other: &Self) -> Self;
    /// `self - other`.
    fn sub(&self, other: &Self) -> Self;
    /// `self · other`.
    fn mul(&self, other: &Self) -> Self;
    /// `-self`.
    fn neg(&self) -> Self;
    /// `|self|`, or `None` when the sign of `self` is unknown.
    fn abs(&self) -> Option<Self> {
        Some(match self.sign()? {
            Ordering::Less => self.neg(),
            _ => self.clone(),
        })
    }
    /// The sign of the exact value, or `None` when rounding makes it unknown.
    fn sign(&self) -> Option<Ordering>;
}

/// Bound on the relative rounding error of a [`Filtered`] value: `2^-46`, that is 128 units
/// of `f64` roundoff (`2^-53`), enough for any chain of up to 60 operations; the formulas here
/// chain at most about 12.
const RELATIVE_ERROR: f64 = 1.0 / (1u64 << 46) as f64;

/// A value computed in plain `f64` together with its magnitude: the same formula evaluated on
/// the absolute values of the inputs with every subtraction turned into an addition.
///
/// The classic static-filter bound (Higham, "Accuracy and Stability of Numerical Algorithms",
/// §3.1; used by Shewchuk's and CGAL's filtered predicates) says that a formula of `d`
/// chained `+`, `-`, `×` on exact inputs is off by at most `γ_d · magnitude` with
/// `γ_d = d u / (1 - d u)`. So the sign is certain when `|value|` exceeds that bound, and a
/// zero magnitude means every input term was zero, hence an exact zero. Magnitudes never
/// underflow here (every non-zero input is at least `2^-149` and a formula multiplies at most
/// four of them), and a value that underflows costs at most `2^-1074`, which the absolute
/// term of the bound covers.
#[derive(Clone, Copy, Debug)]
pub(super) struct Filtered {
    value: f64,
    magnitude: f64,
}

impl Scalar for Filtered {
    #[inline]
    fn from_f32(x: f32) -> Self {
        let value = f64::from(x);
        Self {
            value,
            magnitude: value.abs(),
        }
    }
    #[inline]
    fn add(&self, other: &Self) -> Self {
        Self {
            value: self.value + other.value,
            magnitude: self.magnitude + other.magnitude,
        }
    }
    #[inline]
    fn sub(&self, other: &Self) -> Self {
        Self {
            value: self.value - other.value,
            magnitude: self.magnitude + other.magnitude,
        }
    }
    #[inline]
    fn mul(&self, other: &Self) -> Self {
        Self {
            value: self.value * other.value,
            magnitude: self.magnitude * other.magnitude,
        }
    }
    #[inline]
    fn neg(&self) -> Self {
        Self {
            value: -self.value,
            magnitude: self.magnitude,
        }
    }
    #[inline]
    fn abs(&self) -> Option<Self> {
        // |x̃| is as close to |x| as x̃ is to x, so the magnitude bounds it just the same.
        Some(Self {
            value: self.value.abs(),
            magnitude: self.magnitude,
        })
    }
    #[inline]
    fn sign(&self) -> Option<Ordering> {
        if self.magnitude == 0.0 {
            return Some(Ordering::Equal);
        }
        let bound = self.magnitude * RELATIVE_ERROR + f64::MIN_POSITIVE;
        if self.value > bound {
            Some(Ordering::Greater)
        } else if self.value < -bound {
            Some(Ordering::Less)
        } else {
            None
        }
    }
}

/// A 3-vector of [`Scalar`]s: the points, edges and axes of the tests. 2D input is lifted to
/// the plane `z = 0`, so one set of formulas serves both dimensions.
#[derive(Clone, Debug)]
pub(super) struct V3<T>(pub [T; 3]);

impl<T: Scalar> V3<T> {
    /// The exact value of a 3D input point.
    pub fn from_vec3(p: Vec3) -> Self {
        Self([T::from_f32(p.x), T::from_f32(p.y), T::from_f32(p.z)])
    }

    /// `self - other`.
    pub fn sub(&self, other: &Self) -> Self {
        let [a, b, c] = &self.0;
        let [x, y, z] = &other.0;
        Self([a.sub(x), b.sub(y), c.sub(z)])
    }

    /// `self + other`.
    pub fn add(&self, other: &Self) -> Self {
        let [a, b, c] = &self.0;
        let [x, y, z] = &other.0;
        Self([a.add(x), b.add(y), c.add(z)])
    }

    /// `self · other`.
    pub fn dot(&self, other: &Self) -> T {
        let [a, b, c] = &self.0;
        let [x, y, z] = &other.0;
        a.mul(x).add(&b.mul(y)).add(&c.mul(z))
    }

    /// `self × other`.
    pub fn cross(&self, other: &Self) -> Self {
        let [a, b, c] = &self.0;
        let [x, y, z] = &other.0;
        Self([
            b.mul(z).sub(&c.mul(y)),
            c.mul(x).sub(&a.mul(z)),
            a.mul(y).sub(&b.mul(x)),
        ])
    }

    /// `self × u_k`, with `u_k` the unit vector of coordinate axis `k`: a permutation of two
    /// coordinates with one sign change, so no rounding at all.
    pub fn cross_unit(&self, k: usize) -> Self {
        let zero = T::from_f32(0.0);
        let [a, b, c] = &self.0;
        Self(match k {
            0 => [zero, c.clone(), b.neg()],
            1 => [c.neg(), zero, a.clone()],
            _ => [b.clone(), a.neg(), zero],
        })
    }

    /// Whether every coordinate is exactly zero (`None`: cannot tell).
    pub fn is_zero(&self) -> Option<bool> {
        let mut unknown = false;
        for x in &self.0 {
            match x.sign() {
                Some(Ordering::Equal) => {}
                Some(_) => return Some(false),
                None => unknown = true,
            }
        }
        (!unknown).then_some(true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn filtered_sign_is_certain_far_from_zero_and_admits_doubt_near_it() {
        let one = Filtered::from_f32(1.0);
        let third = Filtered::from_f32(1.0 / 3.0);
        assert_eq!(one.sub(&third).sign(), Some(Ordering::Greater));
        // (1 + 1e-30) − 1 is 1e-30 in exact arithmetic but 0 in f64: the filter must not
        // claim a sign.
        let tiny = Filtered::from_f32(1.0e-30);
        assert_eq!(one.add(&tiny).sub(&one).sign(), None);
        assert_eq!(one.add(&tiny).sub(&one).sub(&tiny).sign(), None);
        // Exact zeros from zero inputs are certain.
        let zero = Filtered::from_f32(0.0);
        assert_eq!(zero.mul(&third).sign(), Some(Ordering::Equal));
    }

    #[test]
    fn cross_unit_matches_cross() {
        let v = V3::<Filtered>::from_vec3(Vec3::new(1.0, 2.0, 3.0));
        for k in 0..3 {
            let u = V3::<Filtered>::from_vec3(Vec3::AXES[k]);
            let (a, b) = (v.cross_unit(k), v.cross(&u));
            for i in 0..3 {
                assert_eq!(a.0[i].value, b.0[i].value);
            }
        }
    }
}
