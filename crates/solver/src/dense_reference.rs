//! Dense, independent reference solutions of the KKT system
//!
//! ```text
//! [ K   Jᵀ ] [ x ]   [ a ]
//! [ J   0  ] [ y ] = [ b ]
//! ```
//!
//! Built on nalgebra only (no faer), for tests and benchmarks of
//! [`crate::kkt`]. [`solve_dense_pivoted`] uses a full-pivoting LU of the
//! true KKT matrix plus two steps of iterative refinement, and returns `None`
//! (never NaN) when the matrix is numerically singular.
//! [`solve_dense_least_squares`] gives the minimum-norm least-squares solution
//! through an SVD, which is the natural reference for singular systems (e.g.
//! duplicated constraint rows: `x` unique, the multipliers of the duplicates
//! split equally).

use nalgebra::{DMatrix, DVector};

/// Assembles the dense true KKT matrix, or `None` for inconsistent sizes or
/// non-finite input.
pub fn kkt_matrix(n: usize, m: usize, k: &DMatrix<f64>, j: &DMatrix<f64>) -> Option<DMatrix<f64>> {
    if k.nrows() != n || k.ncols() != n || j.nrows() != m || j.ncols() != n {
        return None;
    }
    if k.iter().chain(j.iter()).any(|v| !v.is_finite()) {
        return None;
    }
    let nn = n + m;
    let mut a = DMatrix::<f64>::zeros(nn, nn);
    a.view_mut((0, 0), (n, n)).copy_from(k);
    a.view_mut((n, 0), (m, n)).copy_from(j);
    a.view_mut((0, n), (n, m)).copy_from(&j.transpose());
    Some(a)
}

/// Symmetric equilibration `s` (powers of two, so exact) with
/// `max_j |s_i a_ij s_j| ≈ 1` for every non-zero row; zero rows keep `s_i = 1`.
pub fn equilibrate(a: &DMatrix<f64>) -> Vec<f64> {
    let nn = a.nrows();
    let mut s = vec![1.0f64; nn];
    for _ in 0..30 {
        let mut changed = false;
        let row_max: Vec<f64> =
            (0..nn).map(|i| (0..nn).fold(0.0f64, |acc, j| acc.max((s[i] * a[(i, j)] * s[j]).abs()))).collect();
        for i in 0..nn {
            if row_max[i] > 0.0 {
                if !(0.5..=2.0).contains(&row_max[i]) {
                    changed = true;
                }
                s[i] /= row_max[i].sqrt();
            }
        }
        if !changed {
            break;
        }
    }
    s.iter().map(|v| v.log2().round().exp2()).collect()
}

/// Solves the KKT system with a full-pivoting LU of the symmetrically
/// equilibrated true KKT matrix ([`equilibrate`]; without it a stiffness ratio
/// of 1e8 makes the raw KKT matrix condition number ≈ 1e16) and two refinement
/// steps. `k` is n×n (used as given, both triangles), `j` is m×n,
/// `rhs = [a; b]`. Returns `[x; y]`, or `None` if the sizes are inconsistent,
/// an input is not finite, the equilibrated matrix is numerically singular
/// (smallest pivot `≤ 10·(n+m)·ε_mach ×` largest), or the result is not finite.
pub fn solve_dense_pivoted(n: usize, m: usize, k: &DMatrix<f64>, j: &DMatrix<f64>, rhs: &[f64]) -> Option<Vec<f64>> {
    let a0 = kkt_matrix(n, m, k, j)?;
    let nn = n + m;
    if rhs.len() != nn || rhs.iter().any(|v| !v.is_finite()) {
        return None;
    }
    if nn == 0 {
        return Some(Vec::new());
    }
    let s = equilibrate(&a0);
    let a = DMatrix::from_fn(nn, nn, |i, j| s[i] * a0[(i, j)] * s[j]);
    let lu = a.clone().full_piv_lu();
    let u = lu.u();
    let diag: Vec<f64> = (0..nn).map(|i| u[(i, i)].abs()).collect();
    let dmax = diag.iter().cloned().fold(0.0, f64::max);
    let dmin = diag.iter().cloned().fold(f64::INFINITY, f64::min);
    if dmax.is_nan() || dmax <= 0.0 || dmin <= 10.0 * nn as f64 * f64::EPSILON * dmax {
        return None;
    }
    let b = DVector::from_fn(nn, |i, _| s[i] * rhs[i]);
    let mut x = lu.solve(&b)?;
    for _ in 0..2 {
        let r = &b - &a * &x;
        let dx = lu.solve(&r)?;
        x += dx;
    }
    let out: Vec<f64> = x.iter().zip(&s).map(|(v, si)| v * si).collect();
    if out.iter().any(|v| !v.is_finite()) {
        return None;
    }
    Some(out)
}

/// Minimum-norm least-squares solution of the KKT system via SVD; singular
/// values below `rcond × σ_max` are treated as zero. `None` for inconsistent
/// sizes, non-finite input or output.
pub fn solve_dense_least_squares(
    n: usize,
    m: usize,
    k: &DMatrix<f64>,
    j: &DMatrix<f64>,
    rhs: &[f64],
    rcond: f64,
) -> Option<Vec<f64>> {
    let a = kkt_matrix(n, m, k, j)?;
    let nn = n + m;
    if rhs.len() != nn || rhs.iter().any(|v| !v.is_finite()) || !(rcond.is_finite() && rcond >= 0.0) {
        return None;
    }
    if nn == 0 {
        return Some(Vec::new());
    }
    let svd = a.svd(true, true);
    let smax = svd.singular_values.iter().cloned().fold(0.0, f64::max);
    let b = DVector::from_column_slice(rhs);
    let x = svd.solve(&b, rcond * smax).ok()?;
    if x.iter().any(|v| !v.is_finite()) {
        return None;
    }
    Some(x.as_slice().to_vec())
}
