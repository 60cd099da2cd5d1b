//! Exact arithmetic on values built from `f32` inputs: Shewchuk's floating-point expansions.
//!
//! Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
//! Predicates", Discrete & Computational Geometry 18, 1997: a number is held exactly as a sum
//! of `f64` components that do not overlap bit-wise, sorted by increasing magnitude, so its
//! sign is the sign of the largest component (the arithmetic is in [`crate::math::exact`]).
//! Only the overlap tests' rare undecided cases come here.
//!
//! Exactness needs every product's rounding error to be representable: the formulas of the
//! overlap tests multiply at most four `f32`-derived factors, so every value and every error
//! term is a multiple of `2^(-149·4)`, far above `f64`'s underflow threshold, and at most
//! `(2 · 3.4e38)^4 · 16`, far below its overflow threshold.

use std::cmp::Ordering;

use super::scalar::Scalar;
use crate::math::exact::{exact_sum, two_product};

/// An exact number: the sum of its components (non-overlapping, increasing magnitude, no
/// zeros).
#[derive(Clone, Debug, Default)]
pub(super) struct Exact(Vec<f64>);

impl Exact {
    fn sum_of(terms: impl IntoIterator<Item = f64>) -> Self {
        Self(exact_sum(terms))
    }
}

impl Scalar for Exact {
    fn from_f32(x: f32) -> Self {
        Self::sum_of([f64::from(x)])
    }
    fn add(&self, other: &Self) -> Self {
        Self::sum_of(self.0.iter().chain(&other.0).copied())
    }
    fn sub(&self, other: &Self) -> Self {
        Self::sum_of(self.0.iter().copied().chain(other.0.iter().map(|x| -x)))
    }
    fn mul(&self, other: &Self) -> Self {
        Self::sum_of(self.0.iter().flat_map(|&x| {
            other.0.iter().flat_map(move |&y| {
                let (product, error) = two_product(x, y);
                [product, error]
            })
        }))
    }
    fn neg(&self) -> Self {
        Self(self.0.iter().map(|x| -x).collect())
    }
    fn sign(&self) -> Option<Ordering> {
        Some(self.0.last().map_or(Ordering::Equal, |x| x.total_cmp(&0.0)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn exact(x: f32) -> Exact {
        Exact::from_f32(x)
    }

    #[test]
    fn sees_the_sign_that_rounding_hides() {
        // 3 · fl(1/3) − 1: fl(1/3) is a little above 1/3 in f32, so the exact value is
        // positive (f64 happens to get this one right too).
        let third = 1.0f32 / 3.0;
        let value = exact(3.0).mul(&exact(third)).sub(&exact(1.0));
        let expected = (3.0 * f64::from(third) - 1.0).total_cmp(&0.0);
        assert_eq!(value.sign(), Some(expected));
        assert_ne!(value.sign(), Some(Ordering::Equal));
        // (1e30 + 1e-30) − 1e30 − 1e-30 = 0 exactly; f64 alone would say −1e-30.
        let (big, tiny) = (exact(1.0e30), exact(1.0e-30));
        let zero = big.add(&tiny).sub(&big).sub(&tiny);
        assert_eq!(zero.sign(), Some(Ordering::Equal));
        let positive = big.add(&tiny).sub(&big);
        assert_eq!(positive.sign(), Some(Ordering::Greater));
        assert_eq!(positive.neg().sign(), Some(Ordering::Less));
    }

    #[test]
    fn products_of_tiny_and_huge_inputs_stay_exact() {
        let (tiny, huge) = (exact(f32::from_bits(1)), exact(f32::MAX));
        let four = tiny.mul(&tiny).mul(&tiny).mul(&tiny);
        assert_eq!(four.sign(), Some(Ordering::Greater));
        let big = huge.mul(&huge).mul(&huge).mul(&huge);
        assert!(big.0.iter().all(|x| x.is_finite()));
        // x² − (x − ε)(x + ε) = ε² exactly, far below the rounding of x².
        let (x, e) = (exact(16_777_215.0), exact(f32::from_bits(1)));
        let diff = x.mul(&x).sub(&x.sub(&e).mul(&x.add(&e)));
        assert_eq!(diff.sign(), Some(Ordering::Greater));
        assert_eq!(diff.sub(&e.mul(&e)).sign(), Some(Ordering::Equal));
    }
}
