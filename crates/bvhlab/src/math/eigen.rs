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
pub fn covariance<const N: usize>(
    points: impl Iterator<Item = [f64; N]> + Clone,
) -> [[f64; N]; N] {
    let mut mean = [0.0; N];
    let mut count = 0usize;
    for p in points.clone() {
        for (m, x) in mean.iter_mut().zip(p) {
            *m += x;
        }
        count += 1;
    }
    let mut cov = [[0.0; N]; N];
    if count == 0 {
        return cov;
    }
    for m in &mut mean {
        *m /= count as f64;
    }
    for p in points {
        for i in 0..N {
            for j in 0..N {
                cov[i][j] += (p[i] - mean[i]) * (p[j] - mean[j]);
            }
        }
    }
    for row in &mut cov {
        for x in row.iter_mut() {
            *x /= count as f64;
        }
    }
    cov
}

/// Unit eigenvectors of a symmetric matrix, ordered by decreasing eigenvalue.
///
/// The result is always an orthonormal set, including for zero and repeated eigenvalues
/// (any orthonormal basis of the eigenspace is then returned).
pub fn symmetric_eigenvectors<const N: usize>(matrix: [[f64; N]; N]) -> [[f64; N]; N] {
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
                for k in 0..N {
                    let (akp, akq) = (a[k][p], a[k][q]);
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for k in 0..N {
                    let (apk, aqk) = (a[p][k], a[q][k]);
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for row in &mut v {
                    let (vkp, vkq) = (row[p], row[q]);
                    row[p] = c * vkp - s * vkq;
                    row[q] = s * vkp + c * vkq;
                }
            }
        }
    }
    let mut order: [usize; N] = std::array::from_fn(|i| i);
    order.sort_by(|&i, &j| a[j][j].total_cmp(&a[i][i]));
    order.map(|i| std::array::from_fn(|k| v[k][i]))
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
        for m in [[[0.0; 3]; 3], [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]] {
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
    fn covariance_of_a_centred_segment() {
        let cov = covariance([[-1.0, 0.0], [1.0, 0.0]].into_iter());
        assert_eq!(cov, [[1.0, 0.0], [0.0, 0.0]]);
    }
}
