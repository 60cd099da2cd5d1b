//! Covariance matrices and their eigenvectors, for principal component analysis.
//!
//! The cyclic Jacobi method (Golub and Van Loan, "Matrix Computations", 4th ed., §8.5) is used
//! because it is simple, unconditionally stable for symmetric matrices, and always returns an
//! orthonormal set of eigenvectors, also for repeated eigenvalues, which PCA boxes of
//! symmetric point sets (a square, a cube) produce.

/// The covariance matrix `(1/n) Σ (p - mean)(p - mean)ᵀ` of a point set; zero for no points.
///
/// Two passes (mean first, then centred products) avoid the cancellation of the one-pass
/// formula `E[ppᵀ] - mean meanᵀ` for points far from the origin.
#[must_use]
pub fn covariance<const N: usize>(points: impl Iterator<Item = [f64; N]> + Clone) -> [[f64; N]; N] {
    let mean = mean(points.clone());
    let mut cov = [[0.0; N]; N];
    let mut count = 0usize;
    for p in points {
        let d: [f64; N] = std::array::from_fn(|i| p[i] - mean[i]);
        for (row, di) in cov.iter_mut().zip(d) {
            for (x, dj) in row.iter_mut().zip(d) {
                *x += di * dj;
            }
        }
        count += 1;
    }
    if count > 0 {
        for x in cov.iter_mut().flatten() {
            *x /= count as f64;
        }
    }
    cov
}

/// What principal component analysis of a point set gives, in `f64`: see
/// [`principal_components`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipalComponents<const N: usize> {
    /// The centroid `(1/n) Σ p`.
    pub mean: [f64; N],
    /// The covariance matrix, as from [`covariance`].
    pub covariance: [[f64; N]; N],
    /// The variances along the principal axes (the eigenvalues), largest first, never negative.
    pub variances: [f64; N],
    /// The principal axes (unit eigenvectors), in the order of `variances`.
    pub axes: [[f64; N]; N],
}

/// The centroid `(1/n) Σ p`; zero for no points.
#[must_use]
pub fn mean<const N: usize>(points: impl Iterator<Item = [f64; N]>) -> [f64; N] {
    let mut sum = [0.0; N];
    let mut count = 0usize;
    for p in points {
        for (s, x) in sum.iter_mut().zip(p) {
            *s += x;
        }
        count += 1;
    }
    if count > 0 {
        for s in &mut sum {
            *s /= count as f64;
        }
    }
    sum
}

/// Principal component analysis: centroid, covariance, and its eigen-decomposition.
///
/// This is the lecture's OBB recipe up to the extents ("find the directions of maximum and
/// minimum variance: the eigenvectors of the covariance matrix"). Rounding can make a zero
/// eigenvalue come out as `-1e-20`; variances are clamped at zero since that is what they are.
#[must_use]
pub fn principal_components<const N: usize>(
    points: impl Iterator<Item = [f64; N]> + Clone,
) -> PrincipalComponents<N> {
    let covariance = covariance(points.clone());
    let (variances, axes) = symmetric_eigen(covariance);
    PrincipalComponents {
        mean: mean(points),
        covariance,
        variances: variances.map(|v| v.max(0.0)),
        axes,
    }
}

/// Unit eigenvectors of a symmetric matrix, ordered by decreasing eigenvalue.
///
/// The result is always an orthonormal set, including for zero and repeated eigenvalues
/// (any orthonormal basis of the eigenspace is then returned).
#[must_use]
pub fn symmetric_eigenvectors<const N: usize>(matrix: [[f64; N]; N]) -> [[f64; N]; N] {
    symmetric_eigen(matrix).1
}

/// Eigenvalues and unit eigenvectors of a symmetric matrix, by decreasing eigenvalue: the
/// cyclic Jacobi method. `vectors[i]` belongs to `values[i]`; the vectors are orthonormal, also
/// for zero and repeated eigenvalues.
#[must_use]
pub fn symmetric_eigen<const N: usize>(matrix: [[f64; N]; N]) -> ([f64; N], [[f64; N]; N]) {
    let mut a = matrix;
    // Columns of `v` accumulate the rotations: v[k][i] is component k of eigenvector i.
    let mut v = [[0.0; N]; N];
    for (i, row) in v.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    let scale: f64 = a.iter().flatten().map(|x| x * x).sum::<f64>().sqrt();
    // Cyclic sweeps converge quadratically; 50 sweeps is far beyond what 3x3 ever needs.
    for _sweep in 0..50 {
        let off: f64 = (0..N)
            .flat_map(|i| (0..N).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i][j] * a[i][j])
            .sum();
        if off <= (f64::EPSILON * scale).powi(2) || off == 0.0 {
            break;
        }
        for p in 0..N {
            for q in p + 1..N {
                if a[p][q] == 0.0 {
                    continue;
                }
                // Rotation angle that zeroes a[p][q] (Golub & Van Loan, Algorithm 8.5.1).
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                // a <- Jᵀ a J: first the columns p and q, then the rows p and q.
                for row in a.iter_mut().chain(v.iter_mut()) {
                    let (kp, kq) = (row[p], row[q]);
                    row[p] = c * kp - s * kq;
                    row[q] = s * kp + c * kq;
                }
                let (row_p, row_q) = (a[p], a[q]);
                a[p] = std::array::from_fn(|k| c * row_p[k] - s * row_q[k]);
                a[q] = std::array::from_fn(|k| s * row_p[k] + c * row_q[k]);
            }
        }
    }
    let mut order: [usize; N] = std::array::from_fn(|i| i);
    order.sort_by(|&i, &j| a[j][j].total_cmp(&a[i][i]));
    (
        order.map(|i| a[i][i]),
        order.map(|i| std::array::from_fn(|k| v[k][i])),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mul<const N: usize>(m: &[[f64; N]; N], x: &[f64; N]) -> [f64; N] {
        std::array::from_fn(|i| (0..N).map(|j| m[i][j] * x[j]).sum())
    }

    #[test]
    fn eigenvectors_satisfy_the_eigen_equation_and_are_orthonormal() {
        let m = [[4.0, 1.0, -2.0], [1.0, 2.0, 0.5], [-2.0, 0.5, 3.0]];
        let vs = symmetric_eigenvectors(m);
        let mut previous = f64::INFINITY;
        for v in &vs {
            let mv = mul(&m, v);
            let lambda: f64 = (0..3).map(|i| mv[i] * v[i]).sum();
            assert!(lambda <= previous + 1e-12, "eigenvalues must decrease");
            previous = lambda;
            for i in 0..3 {
                assert!((mv[i] - lambda * v[i]).abs() < 1e-10);
            }
        }
        for i in 0..3 {
            for j in 0..3 {
                let d: f64 = (0..3).map(|k| vs[i][k] * vs[j][k]).sum();
                assert!((d - f64::from(u8::from(i == j))).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn repeated_and_zero_eigenvalues_still_give_an_orthonormal_basis() {
        for m in [
            [[0.0; 3]; 3],
            [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        ] {
            let vs = symmetric_eigenvectors(m);
            for i in 0..3 {
                for j in 0..3 {
                    let d: f64 = (0..3).map(|k| vs[i][k] * vs[j][k]).sum();
                    assert!((d - f64::from(u8::from(i == j))).abs() < 1e-12);
                }
            }
        }
    }

    #[test]
    fn eigenvalues_belong_to_their_eigenvectors() {
        let m = [[2.0, -1.0], [-1.0, 2.0]];
        let (values, vectors) = symmetric_eigen(m);
        assert!((values[0] - 3.0).abs() < 1e-12 && (values[1] - 1.0).abs() < 1e-12);
        for (lambda, v) in values.iter().zip(&vectors) {
            let mv = mul(&m, v);
            assert!((0..2).all(|i| (mv[i] - lambda * v[i]).abs() < 1e-12));
        }
    }

    #[test]
    fn principal_components_of_points_on_a_line() {
        // Points t (3, 4) + (1, 1) for t = -1, 0, 1: variance 25 · 2/3 along (3, 4)/5.
        let points = [-1.0, 0.0, 1.0].map(|t| [1.0 + 3.0 * t, 1.0 + 4.0 * t]);
        let pca = principal_components(points.into_iter());
        assert_eq!(pca.mean, [1.0, 1.0]);
        assert!((pca.variances[0] - 50.0 / 3.0).abs() < 1e-12);
        assert!(
            (0.0..1e-12).contains(&pca.variances[1]),
            "clamped, never negative"
        );
        let along = pca.axes[0][0] * 0.6 + pca.axes[0][1] * 0.8;
        assert!((along.abs() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn covariance_of_a_centred_segment() {
        let cov = covariance([[-1.0, 0.0], [1.0, 0.0]].into_iter());
        assert_eq!(cov, [[1.0, 0.0], [0.0, 0.0]]);
    }
}
