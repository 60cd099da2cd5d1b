//! Gaussian elimination with partial pivoting for the small systems of the sphere fits.

/// Solves `a x = b` for an `n x n` system (`n <= 3`) stored in the leading part of `a` and `b`.
///
/// Returns `None` when the matrix is singular to working precision: the caller then knows the
/// points it came from are affinely dependent (collinear or coplanar boundary points).
pub fn solve(mut a: [[f64; 3]; 3], mut b: [f64; 3], n: usize) -> Option<[f64; 3]> {
    let scale = a
        .iter()
        .take(n)
        .flat_map(|row| row.iter().take(n))
        .fold(0.0f64, |m, x| m.max(x.abs()));
    if scale == 0.0 {
        return (n == 0).then_some([0.0; 3]);
    }
    for col in 0..n {
        let pivot = (col..n).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[pivot][col].abs() <= scale * 1e-12 {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        let (top, below) = a.split_at_mut(col + 1);
        let pivot_row = &top[col];
        for (offset, row) in below.iter_mut().take(n - col - 1).enumerate() {
            let f = row[col] / pivot_row[col];
            for (x, p) in row[col..n].iter_mut().zip(&pivot_row[col..n]) {
                *x -= f * p;
            }
            b[col + 1 + offset] -= f * b[col];
        }
    }
    let mut x = [0.0; 3];
    for row in (0..n).rev() {
        let tail: f64 = (row + 1..n).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - tail) / a[row][row];
    }
    Some(x)
}
