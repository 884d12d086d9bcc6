//! Iterative refinement against the true KKT system, and the backward error it is judged by: one
//! loop for every backend, each supplying how it applies its factorization and its residual.

use crate::kkt::max_abs;

/// The componentwise (Oettli–Prager) backward error of a solution `z` of `A z = b`, from its residual
/// `r = b − A z`, the row sums `den = |A|·|z| + |b|` and each row's largest entry `row_norm_i = ‖A_i‖∞`:
/// `max_i |r_i| / den_i`.
///
/// A row whose terms are all at rounding level against the row's size — a constraint row satisfied by
/// unknowns that came out `1e-20` where they are exactly 0, say — has `|r_i| ≈ den_i` whatever the
/// solution's quality, and would make the measure 1. Such a row (`den_i` below `1000·size·ε` times
/// `‖A_i‖∞‖z‖∞ + |b_i|`) is measured normwise instead, against `den_i + ‖A_i‖∞‖z‖∞` (Arioli, Demmel and
/// Duff's two-category backward error).
pub(crate) fn backward_error(r: &[f64], den: &[f64], row_norm: &[f64], rhs: &[f64], z: &[f64]) -> f64 {
    let size = r.len() as f64;
    let z_norm = max_abs(z);
    let mut omega = 0.0f64;
    for i in 0..r.len() {
        if r[i] == 0.0 {
            continue;
        }
        let normwise = row_norm[i] * z_norm;
        let tiny = 1000.0 * size * f64::EPSILON * (normwise + rhs[i].abs());
        let d = if den[i] > tiny { den[i] } else { den[i] + normwise };
        let q = r[i].abs() / d;
        omega = if q.is_nan() { f64::INFINITY } else { omega.max(q) };
    }
    omega
}

#[cfg(test)]
mod tests {
    use super::backward_error;

    /// The stiff-case table read `ω = 1.0, not converged` on every row: a driver row `z_k = 0` met by
    /// `z_k = 1e-20` has `|r| = |A|·|z|` exactly, and counted as a total failure.
    #[test]
    fn a_row_met_to_rounding_level_does_not_read_as_a_backward_error_of_one() {
        // Row 0: one entry, a·z_k with z_k = 1e-20 where 0 was asked. Row 1: an ordinary row with a
        // residual of 1e-12 against terms of size 1.
        let (a, z_k): (f64, f64) = (3.0, 1e-20);
        let r = [-a * z_k, 1e-12];
        let den = [a * z_k, 1.0];
        let row_norm = [a, 1.0];
        let rhs = [0.0, 0.5];
        let z = [z_k, 1.0];
        // Componentwise alone: max(1, 1e-12) = 1.
        assert_eq!(r[0].abs() / den[0], 1.0);
        let omega = backward_error(&r, &den, &row_norm, &rhs, &z);
        // Row 0 is measured normwise, 3e-20 / (3e-20 + 3) = 1e-20; row 1 stays componentwise, 1e-12.
        assert!((omega - 1e-12).abs() <= 1e-12 * f64::EPSILON * 4.0, "{omega:e}");
        // A row at rounding level with a real residual is not hidden: r = 1e-3 against |A|·|z| = 3e-20.
        let omega = backward_error(&[1e-3, 0.0], &den, &row_norm, &rhs, &z);
        assert!((omega - 1e-3 / (a * z_k + a)).abs() < 1e-18, "{omega:e}");
    }
}
