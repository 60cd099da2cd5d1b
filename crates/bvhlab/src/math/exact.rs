//! Exact sums and products of `f64` values: Shewchuk's floating-point expansions.
//!
//! J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
//! Predicates", Discrete & Computational Geometry 18, 1997. A number is held exactly as a sum
//! of `f64` components that do not overlap bit-wise, sorted by increasing magnitude, so its
//! sign is the sign of its largest component. The convex-hull predicates and the exact
//! overlap tests decide their rare near-zero cases here.

/// The exact sum of `terms` as an expansion: non-overlapping, non-zero components of
/// increasing magnitude (empty for zero). Shewchuk's grow-expansion with zero elimination,
/// one term at a time.
pub(crate) fn exact_sum(terms: impl IntoIterator<Item = f64>) -> Vec<f64> {
    let mut components: Vec<f64> = Vec::new();
    for term in terms {
        let mut q = term;
        let mut kept = 0;
        for k in 0..components.len() {
            let (sum, error) = two_sum(q, components[k]);
            if error != 0.0 {
                components[kept] = error;
                kept += 1;
            }
            q = sum;
        }
        components.truncate(kept);
        if q != 0.0 {
            components.push(q);
        }
    }
    components
}

/// A value with the exact sign of `Σ terms` (its largest expansion component, or 0).
pub(crate) fn sign_of_sum(terms: impl IntoIterator<Item = f64>) -> f64 {
    exact_sum(terms).last().copied().unwrap_or(0.0)
}

/// Knuth's two-sum: `a + b = sum + error` exactly, for any finite `f64` values.
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let sum = a + b;
    let b_virtual = sum - a;
    let a_virtual = sum - b_virtual;
    (sum, (a - a_virtual) + (b - b_virtual))
}

/// `a · b = product + error` exactly (when the error does not underflow): the error is what a
/// fused multiply-add leaves of `a · b − product`.
pub(crate) fn two_product(a: f64, b: f64) -> (f64, f64) {
    let product = a * b;
    (product, a.mul_add(b, -product))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_that_cancel_are_exact() {
        assert_eq!(sign_of_sum([1.0e30, 1.0e-30, -1.0e30, -1.0e-30]), 0.0);
        assert!(sign_of_sum([1.0e30, 1.0e-30, -1.0e30]) > 0.0);
        assert_eq!(exact_sum([0.5, 0.25]), vec![0.75]);
        let (p, e) = two_product(1.0 + f64::EPSILON, 1.0 - f64::EPSILON);
        assert_eq!(sign_of_sum([p, e, -1.0]), -(f64::EPSILON * f64::EPSILON));
    }
}
