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
//! * [`KktFactor`] — the sparse quasi-definite LDLᵀ with scaling,
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
//!
//! One KKT solver over small engines, as a direct solver owns regularization and refinement over its
//! factorizations: [`KktSolver`] ([`solver`]) keeps the true system of the last factorization
//! ([`system`]: its values, row sizes and residual), checks what it is given, solves, refines against the
//! true matrix ([`refinement`], with its backward error) and counts; an engine ([`KktEngine`]) only
//! factorizes the values its own way and applies the inverse. The engines are [`QuasiDefiniteLdlt`]
//! ([`sparse_ldlt`], by stage: symbolic, numeric, solve) and [`PivotedLu`] ([`dense_lu`]), both scaling by
//! [`scaling`] (Ruiz equilibration rounded to powers of two) over [`pattern`] (the fixed sparsity,
//! checked and ordered); [`KktFactor`] and [`DenseLu`] are the solvers of the two, and [`auto`] picks one.
//! A third engine is one file: a type implementing [`KktEngine`], whose [`KktSolver`] is then a
//! [`KktBackend`]. This module holds the vocabulary they share: options, reports, counters, errors, the
//! values of one system and the interface.

pub mod auto;
pub mod dense_lu;
pub mod pattern;
pub mod refinement;
pub mod scaling;
pub mod solver;
pub mod sparse_ldlt;
pub mod system;

pub use auto::{AutoKkt, BackendChoice, DENSE_MAX_ORDER};
pub use dense_lu::{DenseLu, LuFactors, PivotedLu};
pub use pattern::KktPattern;
pub use solver::{KktEngine, KktSolver};
pub use sparse_ldlt::{KktFactor, KktSymbolic, QuasiDefiniteLdlt};
pub use system::KktSystem;

/// Which faer LDLᵀ kernel to use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FactorKind {
    /// faer decides from the flop count per factor entry (default).
    #[default]
    Auto,
    /// Column-by-column (cheaper for very sparse factors, e.g. one corner).
    Simplicial,
    /// Dense supernodes (faster when the factor has dense blocks).
    Supernodal,
}

/// Tuning parameters of [`KktFactor`]. All thresholds are dimensionless: they
/// apply to the Ruiz-scaled system, where the largest entry of every row is 1.
#[derive(Clone, Debug, PartialEq)]
pub struct KktOptions {
    /// Augmented-Lagrangian penalty ρ in scaled units. `None` (default):
    /// automatic, `max_k K̂_kk / max_i ‖Ĵ_i‖²` clamped to [1e-8, 1e8] (≈ 0.1…1
    /// after scaling); `1/max_i ‖Ĵ_i‖²` when `K̂ = 0`.
    pub rho: Option<f64>,
    /// Quasi-definite regularization ε: the (2,2) block is `−(ε/ρ)I` in scaled
    /// units. Default 1e-10 (see the module docs for the measurement).
    pub epsilon: f64,
    /// Maximum number of iterative-refinement steps per solve (default 3;
    /// 1–2 are used on well-posed systems).
    pub max_refinement: usize,
    /// Refinement stops once the componentwise backward error is at or below
    /// this (default `2·ε_mach`).
    pub refinement_tol: f64,
    /// Maximum number of Ruiz equilibration sweeps (default 20, stops early
    /// once every row maximum is within [0.5, 2]; 0 disables scaling).
    pub scaling_iterations: usize,
    /// Dynamic regularization threshold: a pivot with `|d| ≤ pivot_threshold`
    /// (with signed regularization: on the wrong side of `±pivot_threshold`) is
    /// replaced. Must stay below `ε/ρ` so that redundant constraint rows keep
    /// their `≈ −2ε/ρ` pivot. Default 1e-13.
    pub pivot_threshold: f64,
    /// Replacement magnitude of a regularized pivot (default 1e-8). Dynamic
    /// regularization is off when this or `pivot_threshold` is 0; an exactly
    /// zero pivot is then reported as [`FactorError::Singular`].
    pub pivot_delta: f64,
    /// Relative pivot size below which a body dof / constraint row is reported
    /// as suspect in [`FactorReport`] (default 1e-8; for constraint rows this is
    /// a relative orthogonal component of ≈ 1e-4).
    pub suspect_tol: f64,
    /// faer kernel selection (default [`FactorKind::Auto`]).
    pub kind: FactorKind,
    /// Pass `dynamic_regularization_signs` (+1 body, −1 constraint) to faer.
    /// Default `false`: it overwrites legitimate negative body pivots (K
    /// indefinite on the constraint manifold) by `+pivot_delta`, see the
    /// module docs.
    pub signed_regularization: bool,
}

impl Default for KktOptions {
    fn default() -> Self {
        Self {
            rho: None,
            epsilon: 1e-10,
            max_refinement: 3,
            refinement_tol: 2.0 * f64::EPSILON,
            scaling_iterations: 20,
            pivot_threshold: 1e-13,
            pivot_delta: 1e-8,
            suspect_tol: 1e-8,
            kind: FactorKind::Auto,
            signed_regularization: false,
        }
    }
}

/// Outcome of one numeric factorization. Pivot magnitudes are in scaled units.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FactorReport {
    /// Pivots replaced by dynamic regularization (both blocks).
    pub regularized_pivots: usize,
    /// Penalty ρ actually used (scaled units).
    pub rho: f64,
    /// Number of negative body pivots (not regularized). In exact arithmetic
    /// this is the number of negative eigenvalues of `K` on the constraint
    /// manifold `{Jx = 0}`: 0 for a stable equilibrium, > 0 past a limit or
    /// bifurcation point.
    pub negative_body_pivots: usize,
    /// Smallest |pivot| among body coordinates (0 if `n = 0`).
    pub min_body_pivot: f64,
    /// Largest |pivot| among body coordinates (0 if `n = 0`).
    pub max_body_pivot: f64,
    /// Smallest |pivot| among constraint rows (0 if `m = 0`).
    pub min_constraint_pivot: f64,
    /// Largest |pivot| among constraint rows (0 if `m = 0`).
    pub max_constraint_pivot: f64,
    /// Body coordinates (original numbering, ascending) whose pivot was tiny
    /// relative to their scale: directions nothing restrains (or unstable ones).
    pub suspect_body_dofs: Vec<usize>,
    /// Constraint rows (original numbering, ascending) whose pivot was ≈ −ε/ρ:
    /// redundant constraints.
    pub suspect_constraint_rows: Vec<usize>,
}

/// Outcome of one solve (residuals of the TRUE KKT system, original units).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SolveReport {
    /// Refinement steps performed (a final step that was discarded because it
    /// did not improve the residual is included).
    pub refinement_steps: usize,
    /// `‖K x + Jᵀ y − a‖∞`.
    pub residual_x: f64,
    /// `‖J x − b‖∞`.
    pub residual_y: f64,
    /// Componentwise (Oettli–Prager) backward error of the final `[x; y]`,
    /// `max_i |r_i| / (|KKT|·|[x; y]| + |[a; b]|)_i`, invariant under scaling; a row whose terms are
    /// all at rounding level is measured normwise (see `kkt_backend::backward_error`).
    pub backward_error: f64,
    /// Whether `backward_error ≤ refinement_tol`.
    pub converged: bool,
    /// Whether the residuals and the backward error were measured. A solve for a Newton increment
    /// (`Accuracy::Increment` of a dense backend) skips the measurement; its report then reads 0 and
    /// `converged: false`.
    pub measured: bool,
}

/// Work counters, cumulative over the lifetime of a [`KktFactor`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FactorCounters {
    /// Symbolic analyses (one per [`KktFactor::analyze`]).
    pub symbolic_analyses: u64,
    /// Successful numeric factorizations.
    pub numeric_factorizations: u64,
    /// Successful solves.
    pub solves: u64,
    /// Iterative-refinement steps over all solves.
    pub refinement_steps: u64,
}

/// Errors of the KKT factorization. Every variant names the offending index.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FactorError {
    /// A CSC array is malformed.
    #[error(
        "invalid {matrix} pattern at column {col}: {reason}; pass CSC arrays with a column pointer \
         of length n + 1 starting at 0, non-decreasing, ending at the number of stored entries, and \
         strictly increasing in-range row indices within each column"
    )]
    InvalidPattern {
        /// `"K"` or `"J"`.
        matrix: &'static str,
        /// Offending column (or the pointer index for pointer errors).
        col: usize,
        /// What is wrong.
        reason: String,
    },
    /// The diagonal entry of `K` in column `col` is not stored.
    #[error(
        "K has no stored diagonal entry in column {col}; store every diagonal entry of K \
         (an explicit 0.0 for a structurally zero one) in the upper-triangle pattern"
    )]
    MissingDiagonal {
        /// Column of `K` lacking its diagonal.
        col: usize,
    },
    /// An array has the wrong length.
    #[error(
        "{what} has length {got} but {expected} was expected; values must be aligned with the row \
         index arrays given to analyze(), and the right-hand side must have length n + m"
    )]
    PatternMismatch {
        /// Name of the array.
        what: &'static str,
        /// Required length.
        expected: usize,
        /// Length received.
        got: usize,
    },
    /// A value is NaN or infinite.
    #[error(
        "{what}[{index}] is not finite; every stiffness, Jacobian and right-hand-side value must \
         be finite (check the element that produced this entry)"
    )]
    NonFinite {
        /// Name of the array.
        what: &'static str,
        /// Index into that array.
        index: usize,
    },
    /// An option is out of range.
    #[error("option {name} is invalid: {reason}")]
    InvalidOption {
        /// Option name.
        name: &'static str,
        /// Why.
        reason: &'static str,
    },
    /// The factorization met a zero or non-finite pivot it could not regularize.
    #[error(
        "the equations are singular at {kind} {index}: a part is free to move where nothing holds it, or a \
         joint repeats another; check the model's degrees of freedom and redundant joints, and add the \
         missing mount or remove the repeated joint"
    )]
    Singular {
        /// `"body coordinate"` or `"constraint row"`.
        kind: &'static str,
        /// Index within that block, original numbering.
        index: usize,
    },
    /// [`KktFactor::solve_in_place`] was called without a valid factorization.
    #[error("a solve was asked for before the equations were factorized for the current values")]
    NotFactorized,
    /// The computed solution is not finite (the right-hand side was left unchanged).
    #[error(
        "the solution is not finite (unknown {index}): the equations are numerically singular — a part \
         is held by next to nothing or a joint nearly repeats another; check the model's degrees of \
         freedom and redundant joints"
    )]
    NonFiniteSolution {
        /// First non-finite index in `[x; y]`.
        index: usize,
    },
    /// faer's symbolic analysis failed (index overflow / allocation).
    #[error("symbolic analysis failed in faer: {0}")]
    Analysis(String),
    /// A workspace could not be allocated.
    #[error("out of memory while allocating factorization workspace")]
    OutOfMemory,
}

/// The values of one KKT system, each aligned with its row-index array of the [`KktPattern`]
/// (`k` and `k_skew` with `k_row_idx`, `j` with `j_row_idx`).
///
/// [`KktPattern`]: crate::kkt::pattern::KktPattern
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

pub(crate) fn check_values(what: &'static str, values: &[f64], expected: usize) -> Result<(), FactorError> {
    if values.len() != expected {
        return Err(FactorError::PatternMismatch { what, expected, got: values.len() });
    }
    if let Some(index) = values.iter().position(|v| !v.is_finite()) {
        return Err(FactorError::NonFinite { what, index });
    }
    Ok(())
}

pub(crate) fn check_options(o: &KktOptions) -> Result<(), FactorError> {
    let bad = |name, reason| Err(FactorError::InvalidOption { name, reason });
    if let Some(rho) = o.rho {
        if !(rho.is_finite() && rho > 0.0) {
            return bad("rho", "must be finite and > 0");
        }
    }
    if !(o.epsilon.is_finite() && o.epsilon > 0.0) {
        return bad("epsilon", "must be finite and > 0");
    }
    if !(o.refinement_tol.is_finite() && o.refinement_tol >= 0.0) {
        return bad("refinement_tol", "must be finite and >= 0");
    }
    if !(o.pivot_threshold.is_finite() && o.pivot_threshold >= 0.0) {
        return bad("pivot_threshold", "must be finite and >= 0");
    }
    if !(o.pivot_delta.is_finite() && o.pivot_delta >= 0.0) {
        return bad("pivot_delta", "must be finite and >= 0");
    }
    if !(o.suspect_tol.is_finite() && o.suspect_tol >= 0.0) {
        return bad("suspect_tol", "must be finite and >= 0");
    }
    Ok(())
}

pub(crate) fn alloc_err(_: impl std::fmt::Debug) -> FactorError {
    FactorError::OutOfMemory
}

/// Fallible `vec![value; len]`: huge dimensions (e.g. a large `m` with an
/// empty Jacobian pattern) give [`FactorError::OutOfMemory`] instead of an
/// abort. Every dimension-sized buffer is first probed with this.
pub(crate) fn try_vec<T: Clone>(len: usize, value: T) -> Result<Vec<T>, FactorError> {
    // Leave head-room for the several buffers of this size that follow.
    if len > (isize::MAX as usize) / 64 {
        return Err(FactorError::OutOfMemory);
    }
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(alloc_err)?;
    v.resize(len, value);
    Ok(v)
}

/// `‖v‖∞`, 0 for an empty slice.
pub(crate) fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |acc, x| acc.max(x.abs()))
}
