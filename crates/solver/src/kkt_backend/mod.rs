//! Interchangeable factorizations of the KKT (saddle-point) system behind one interface.
//!
//! ```text
//! [ K + S   Jᵀ ] [ x ]   [ a ]
//! [ J       0  ] [ y ] = [ b ]
//! ```
//!
//! `K` is the symmetric part of the tangent stiffness, `S` its skew part (world-fixed loads, preloads
//! turning with their lever arms, an element away from its own equilibrium), `J` the constraint
//! Jacobian. The [`StaticSolver`](crate::StaticSolver) assembles values into one fixed pattern
//! ([`KktPattern`]) and hands them to a [`KktBackend`]:
//!
//! * [`KktFactor`](crate::kkt_factor::KktFactor) — the sparse quasi-definite LDLᵀ with scaling,
//!   dynamic regularization and refinement ([`sparse_ldlt`]). It factorizes the symmetric part only; the
//!   solver wraps GMRES around it for `S`. Its cost grows with the factor's fill, not with the order
//!   cubed: the choice for a whole vehicle or a long chain.
//! * [`DenseLu`] — an equilibrated LU with partial pivoting of the whole non-symmetric matrix, `S`
//!   included ([`dense_lu`]): no GMRES, no augmented-Lagrangian regularization, one refinement only when
//!   the measured backward error asks for it. Its cost grows as the order cubed, and on the small systems
//!   of a suspension corner or an axle it beats the sparse path's bookkeeping.
//! * [`AutoKkt`] ([`auto`]) — picks one of the two by the order `n + m` ([`DENSE_MAX_ORDER`], the
//!   measured crossover), and falls back to the sparse LDLᵀ for a factorization the dense LU finds
//!   singular (the sparse path regularizes and names the suspects).
//!
//! Every backend's solution is checked against the dense pivoted reference in `tests/kkt_backend.rs`.

pub mod auto;
pub mod dense_lu;
pub mod sparse_ldlt;

pub use auto::{AutoKkt, BackendChoice, DENSE_MAX_ORDER};
pub use dense_lu::DenseLu;

use crate::kkt_factor::{max_abs, FactorCounters, FactorError, FactorReport, SolveReport};

/// The values of one KKT system, each aligned with its row-index array of the [`KktPattern`]
/// (`k` and `k_skew` with `k_row_idx`, `j` with `j_row_idx`).
///
/// [`KktPattern`]: crate::kkt_factor::KktPattern
#[derive(Debug, Clone, Copy)]
pub struct KktValues<'a> {
    /// Upper triangle of the symmetric part `K` (diagonal included).
    pub k: &'a [f64],
    /// Skew part above the diagonal: entry `(r, c)`, `r < c`, of `S = ½(K_full − K_fullᵀ)`, so that the
    /// full tangent holds `K + S` at `(r, c)` and `K − S` at `(c, r)`. `None` when the tangent is
    /// symmetric.
    pub k_skew: Option<&'a [f64]>,
    /// `J`.
    pub j: &'a [f64],
}

/// How accurate a solve must be.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Accuracy {
    /// To the backend's refinement tolerance, measured: a compliance, a path tangent, a joint force.
    Refined,
    /// One application of the factorization, the backward error not measured: a Newton increment,
    /// whose error the next iteration's residual sees and corrects.
    Increment,
}

/// One factorization of the KKT system of a fixed pattern: numeric factorization per set of values, then
/// any number of solves.
pub trait KktBackend: std::fmt::Debug + Send {
    /// What it is, for reports ("dense LU", "sparse LDLᵀ").
    fn name(&self) -> &'static str;

    /// Whether [`KktBackend::factorize`] takes the skew part into the factorization, so that a solve
    /// solves the non-symmetric system directly. When `false` the caller must account for `S` itself
    /// (the solver's GMRES).
    fn solves_skew(&self) -> bool;

    /// Numeric factorization of new values.
    fn factorize(&mut self, values: KktValues<'_>) -> Result<FactorReport, FactorError>;

    /// Solves in place with the last factorization: `rhs = [a; b]` becomes `[x; y]`.
    fn solve_in_place(&mut self, rhs: &mut [f64], accuracy: Accuracy) -> Result<SolveReport, FactorError>;

    /// Work counters since construction or the last [`KktBackend::reset`].
    fn counters(&self) -> FactorCounters;

    /// Forgets what the values left — the scaling, the factorization, the counters — and keeps the
    /// analysis and the buffers: the backend then factorizes another set of values of the same pattern
    /// exactly as a freshly analysed one would.
    fn reset(&mut self);
}

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
