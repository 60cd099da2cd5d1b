//! Exact orientation predicates for `f32` points: which side of a line (2D) or plane (3D) a
//! point is on, decided without rounding error.
//!
//! Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
//! Predicates", Discrete & Computational Geometry 18, 1997. The determinant is first computed
//! in plain `f64` with a bound on its rounding error; only when it is smaller than the bound
//! (the points are nearly collinear or coplanar) is it evaluated again exactly, as a sum of
//! exactly computed products that Shewchuk's expansion arithmetic adds without loss.
//!
//! Exactness needs products that neither underflow nor overflow `f64`, which holds for any
//! finite `f32` input (at most three factors of at most 2 × 3.4e38, at least 2⁻¹⁴⁹).

use glam::{DVec3, Vec2};

use crate::math::exact::{sign_of_sum, two_product, two_sum};

/// Half a unit in the last place of 1.0: the relative rounding error of one `f64` operation.
const EPS: f64 = f64::EPSILON / 2.0;

/// A value with the exact sign of `(b − a) × (c − a)`: positive when `a, b, c` turn left
/// (counter-clockwise), negative when they turn right, zero when collinear.
pub(in crate::volume) fn orient2d(a: Vec2, b: Vec2, c: Vec2) -> f64 {
    let (da, db, dc) = (a.as_dvec2(), b.as_dvec2(), c.as_dvec2());
    let left = (db.x - da.x) * (dc.y - da.y);
    let right = (db.y - da.y) * (dc.x - da.x);
    let det = left - right;
    if det.abs() > (3.0 + 16.0 * EPS) * EPS * (left.abs() + right.abs()) {
        return det;
    }
    // Differences of f32 values need not be exact in f64, but products of two f32 values are
    // (24 + 24 bits < 53), and expanded the determinant is a sum of six such products.
    let m = |x: f32, y: f32| f64::from(x) * f64::from(y);
    sign_of_sum([
        m(b.x, c.y),
        -m(b.x, a.y),
        -m(a.x, c.y),
        -m(b.y, c.x),
        m(b.y, a.x),
        m(a.y, c.x),
    ])
}

/// A value with the exact sign of `((b − a) × (c − a)) · (d − a)`: positive when `d` is above
/// the plane of `a, b, c`, on the side from which they run counter-clockwise. The coordinates
/// must be `f32` values (converted to `f64`).
pub(in crate::volume) fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    // Shewchuk's orient3d with `d` as the pivot computes det[a − d, b − d, c − d], which is
    // the negative of ours.
    let (ad, bd, cd) = (a - d, b - d, c - d);
    let (bc, ca, ab) = (
        bd.x * cd.y - bd.y * cd.x,
        cd.x * ad.y - cd.y * ad.x,
        ad.x * bd.y - ad.y * bd.x,
    );
    let det = ad.z * bc + bd.z * ca + cd.z * ab;
    let permanent = ((bd.x * cd.y).abs() + (bd.y * cd.x).abs()) * ad.z.abs()
        + ((cd.x * ad.y).abs() + (cd.y * ad.x).abs()) * bd.z.abs()
        + ((ad.x * bd.y).abs() + (ad.y * bd.x).abs()) * cd.z.abs();
    if det.abs() > (7.0 + 56.0 * EPS) * EPS * permanent {
        return -det;
    }
    if permanent == 0.0 {
        // Every product is zero (they cannot underflow for f32 input): so is the determinant,
        // as when d is one of the corners.
        return 0.0;
    }
    -exact_det3([a, b, c].map(|p| exact_difference(p, d)))
}

/// `(b − a) × (c − a)`, each coordinate within a few units in its last place, however thin
/// the triangle: the normal of a sliver still points the right way.
///
/// The differences are kept as exact pairs and each coordinate, a 2 × 2 determinant
/// `x y − z w`, is evaluated by Kahan's algorithm with a fused multiply-add (analysed by
/// Jeannerod, Louvet and Muller, "Further analysis of Kahan's algorithm for the accurate
/// computation of 2 × 2 determinants", Mathematics of Computation 82, 2013), plus the
/// first-order terms of the pairs' low parts.
pub(in crate::volume) fn accurate_cross(a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (d, e) = (exact_difference(b, a), exact_difference(c, a));
    let det = |i: usize, j: usize| {
        let ([x, x_low], [y, y_low]) = (d[i], e[j]);
        let ([z, z_low], [w, w_low]) = (d[j], e[i]);
        let zw = z * w;
        let zw_error = z.mul_add(w, -zw);
        let high = x.mul_add(y, -zw) - zw_error;
        high + (x_low * y + x * y_low - z_low * w - z * w_low)
    };
    DVec3::new(det(1, 2), det(2, 0), det(0, 1))
}

/// `p − q` per coordinate as an exact pair `(rounded, error)`.
fn exact_difference(p: DVec3, q: DVec3) -> [[f64; 2]; 3] {
    [0, 1, 2].map(|i| {
        let (diff, error) = two_sum(p[i], -q[i]);
        [diff, error]
    })
}

/// The sign of the 3 × 3 determinant whose rows are `rows`, each entry an exact pair: the
/// six terms of the Leibniz formula, each a product of three pairs, expanded into exact
/// products of three floats (four floats each) and summed exactly.
fn exact_det3(rows: [[[f64; 2]; 3]; 3]) -> f64 {
    const PERMUTATIONS: [([usize; 3], f64); 6] = [
        ([0, 1, 2], 1.0),
        ([1, 2, 0], 1.0),
        ([2, 0, 1], 1.0),
        ([0, 2, 1], -1.0),
        ([2, 1, 0], -1.0),
        ([1, 0, 2], -1.0),
    ];
    let mut terms = Vec::with_capacity(192);
    for ([i, j, k], sign) in PERMUTATIONS {
        for &x in &rows[0][i] {
            for &y in &rows[1][j] {
                for &z in &rows[2][k] {
                    if x != 0.0 && y != 0.0 && z != 0.0 {
                        let (p, e) = two_product(sign * x, y);
                        let (pz, pz_error) = two_product(p, z);
                        let (ez, ez_error) = two_product(e, z);
                        terms.extend([pz, pz_error, ez, ez_error]);
                    }
                }
            }
        }
    }
    sign_of_sum(terms)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orient2d_sees_through_cancellation() {
        // Collinear in exact arithmetic, but b − a and c − a are not exact in f64.
        let a = Vec2::new(1.0e-30, 1.0e-30);
        let (b, c) = (Vec2::new(1.0, 1.0), Vec2::new(3.0, 3.0));
        assert_eq!(orient2d(a, b, c), 0.0);
        let up = Vec2::new(3.0, f32::from_bits(3.0f32.to_bits() + 1));
        assert!(orient2d(a, b, up) > 0.0);
        assert!(orient2d(a, b, Vec2::new(3.0, 2.999_999_8)) < 0.0);
    }

    #[test]
    fn orient3d_signs_and_exact_zeros() {
        let [a, b, c] = [DVec3::ZERO, DVec3::X, DVec3::Y];
        assert!(orient3d(a, b, c, DVec3::Z) > 0.0);
        assert!(orient3d(a, c, b, DVec3::Z) < 0.0);
        // The plane z = x + y through a point with a tiny x: the differences round in f64.
        let tiny = f64::from(1.0e-30f32);
        let [a, b, c] = [
            DVec3::new(tiny, 0.0, tiny),
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(3.0, 5.0, 8.0),
        ];
        assert_eq!(orient3d(a, b, c, DVec3::new(7.0, 1.0, 8.0)), 0.0);
        let up = DVec3::new(7.0, 1.0, f64::from(f32::from_bits(8.0f32.to_bits() + 1)));
        let high = DVec3::new(7.0, 1.0, 9.0);
        assert!(orient3d(a, b, c, up) != 0.0);
        assert_eq!(
            orient3d(a, b, c, up).signum(),
            orient3d(a, b, c, high).signum()
        );
    }

    #[test]
    fn accurate_cross_of_a_sliver() {
        // The apex is one f32 step off the line through a and b, far from the origin.
        let (a, b) = (DVec3::splat(1000.0), DVec3::new(1002.0, 1001.0, 1000.0));
        let y = f64::from(f32::from_bits(1000.5f32.to_bits() + 1));
        let apex = DVec3::new(1001.0, y, 1000.0);
        let exact_z = 2.0 * (y - 1000.0) - 1.0;
        assert_eq!(accurate_cross(a, b, apex), DVec3::new(0.0, 0.0, exact_z));
    }
}
