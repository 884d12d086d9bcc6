//! Reusable sparse factorization of the quasi-static KKT (saddle-point) system
//!
//! ```text
//! [ K   Jᵀ ] [ x ]   [ a ]
//! [ J   0  ] [ y ] = [ b ]
//! ```
//!
//! `K` (n×n, symmetric) is the tangent stiffness, `J` (m×n) the constraint
//! Jacobian, `y` the constraint multipliers (the sign convention is the one of
//! the block matrix above: the constraint force on the bodies is `-Jᵀy` moved
//! to the right-hand side, i.e. `K x = a - Jᵀ y`). The sparsity patterns are
//! fixed for a whole load sweep while the values change at every step, so the
//! work is split faer-style into [`KktFactor::analyze`] (once: pattern, ordering,
//! elimination tree, slot maps, every workspace) and
//! [`KktFactor::factorize`] / [`KktFactor::solve_in_place`] (per step, no
//! allocation except for the `suspect_*` lists of a [`FactorReport`], which stay
//! empty — and unallocated — on healthy systems).
//!
//! # Why this formulation
//!
//! Measured on such systems with faer 0.24 by the project's prototype:
//!
//! * the sparse intranodal Bunch–Kaufman (`factorize_numeric_intranode_lblt`)
//!   returns NaN on these KKT matrices;
//! * plain sparse LDLᵀ hits an exactly zero pivot in the constraint block;
//! * LDLᵀ with dynamic regularization alone runs, but loses the multipliers `y`
//!   from a stiffness ratio of about 1e4;
//! * sparse and dense LU return all-NaN *silently* on singular systems (a pure
//!   mechanism, a redundant joint).
//!
//! What holds up is the quasi-definite augmented-Lagrangian form
//!
//! ```text
//! [ K + ρJᵀJ   Jᵀ      ] [x]   [ a + ρJᵀb ]
//! [ J          −(ε/ρ)I ] [y] = [ b        ]
//! ```
//!
//! Its first block row equals the original one whenever `Jx = b`, and the
//! `−(ε/ρ)I` block makes the matrix quasi-definite (`K + ρJᵀJ` positive definite
//! for any ρ above a threshold whenever the constrained system is stable, the
//! (2,2) block negative definite), so an LDLᵀ factorization without pivoting
//! exists for *every* symmetric permutation and can reuse one symbolic analysis.
//! The `ε` perturbation and all rounding are then removed by iterative refinement
//! against the *true* KKT matrix (original `K`, `J`, zero (2,2) block).
//!
//! # Method, step by step
//!
//! 1. **Scaling.** A symmetric Ruiz equilibration `S = diag(s)` of the true KKT
//!    matrix (every row's largest entry driven to 1), rounded to powers of two so
//!    that scaling is exact. Scaled quantities carry a hat:
//!    `K̂ = S_x K S_x`, `Ĵ = S_y J S_x`; `x = S_x x̂`, `y = S_y ŷ`. This makes a
//!    1e8 stiffness ratio and unit-scale constraint rows comparable before any
//!    pivot is taken. The (2,2) block is zero and does not take part. Each
//!    factorization starts from the last one's scaling, so that a load path's
//!    slowly changing values take one confirming sweep.
//! 2. **Penalty.** `ρ = max_k K̂_kk / max_i ‖Ĵ_i‖²` (both in scaled units; `ρ`
//!    falls back to `1/max‖Ĵ_i‖²` for `K = 0`), overridable by
//!    [`KktOptions::rho`]. `ε` ([`KktOptions::epsilon`]) is dimensionless: the
//!    (2,2) block is `−(ε/ρ)I` in scaled units.
//! 3. **Ordering.** AMD on the pattern of `K + JᵀJ` (body block only); every
//!    constraint row is then inserted directly after the last of the body
//!    coordinates it touches, so its pivot is the well-sized Schur complement
//!    `−ε/ρ − Ĵ_i (…)⁻¹ Ĵ_iᵀ` (≈ `−1/ρ`), never a bare `−ε/ρ` (except for a
//!    redundant row, which is exactly how redundancy is detected). The
//!    permutation is applied by this module (faer sees `SymmetricOrdering::
//!    Identity` on an already permuted matrix), so values are scattered straight
//!    into faer's input through precomputed slot maps.
//! 4. **Factorization.** faer's simplicial or supernodal LDLᵀ (faer picks by flop
//!    ratio unless [`KktOptions::kind`] forces one), called directly at the
//!    kernel level (`simplicial::factorize_simplicial_numeric_ldlt` /
//!    `supernodal::factorize_supernodal_numeric_ldlt`) so that the pivots `D`
//!    can be read back. Dynamic regularization is the safety net for tiny
//!    pivots: a pivot with `|d| ≤ pivot_threshold` becomes `±pivot_delta` (its
//!    own sign; `+` for an exact zero), scaled units. Regularized pivots are
//!    counted by this module (faer 0.24's dense kernel, used by the supernodal
//!    path, only counts the `+1`-sign corrections).
//!
//!    *Signs.* faer's `dynamic_regularization_signs` (+1 body rows, −1
//!    constraint rows) is available as [`KktOptions::signed_regularization`]
//!    but is OFF by default: with it, faer replaces every body pivot `≤
//!    threshold` — including a genuinely negative one — by `+δ`. A negative body
//!    pivot is legitimate whenever `K` is indefinite on the constraint manifold
//!    (an unstable equilibrium, past a limit point; geometric stiffness), and
//!    overwriting it by a tiny `+δ` destroys the factor. Measured on random
//!    `K = SPD − shift·I` systems (tests, `indefinite_stiffness_on_the_
//!    constraint_manifold`): with signs every such case ended in `Singular` or a
//!    non-finite solution, without signs all were solved to ≈ 1e-15. Without
//!    indefiniteness both modes give identical results.
//! 5. **Solve.** `[x̂; ŷ] = LDLᵀ \ T S [a; b]`, with `T` the augmented-Lagrangian
//!    right-hand-side map `[a; b] ↦ [a + ρĴᵀb; b]`, then iterative refinement:
//!    `r = [a; b] − KKT·[x; y]` with the original values, correction by the same
//!    map, until the componentwise (Oettli–Prager) backward error
//!    `ω = max_i |r_i| / (|KKT|·|z| + |rhs|)_i` is below
//!    [`KktOptions::refinement_tol`] (2·ε_mach), stops improving by at least a
//!    factor 2, or [`KktOptions::max_refinement`] steps were made. A step that
//!    does not reduce `ω` is discarded. A row whose terms all sit at rounding level (a constraint row
//!    met by unknowns that are exactly 0 and came out `1e-20`) would read `ω = 1` whatever the
//!    solution; it is measured normwise instead. (A normwise criterion was tried first:
//!    it declared convergence after one step while the forward error was still
//!    1e-10 at stiffness ratio 1e12; the componentwise one does not.)
//!
//! # What the tests hold (`tests/kkt_factor.rs`), and why ε is 1e-10
//!
//! * Stiffness ratios 1…1e8, constraints on the soft, the stiff or both kinds
//!   of coordinates: `x` and `y` agree with the dense equilibrated full-pivot LU
//!   reference to 1.6e-15 relative, in one or two refinement steps.
//! * `ε` ([`KktOptions::epsilon`]) trades refinement against the redundancy
//!   test: a larger `ε` leaves more for refinement to remove, a smaller one
//!   shrinks the gap between the
//!   pivot of a redundant row (`≈ −2ε/ρ`) and rounding noise and lets rounding
//!   decide how a duplicated row's multiplier is split.
//!
//! Its times are `cargo xtask bench`'s (`--only scaling`).
//!
//! # Diagnostics
//!
//! After each factorization the pivots `D` (scaled units) are inspected:
//! * a body dof whose pivot has `|d| ≤ suspect_tol ×` its diagonal in
//!   `K̂ + ρĴᵀĴ` (or was regularized) is a direction that nothing restrains
//!   (zero stiffness and no constraint; a floating sub-assembly). Because every
//!   row is first scaled to unit size, a dof is judged on its own scale: any
//!   nonzero stiffness counts as a restraint, however small;
//! * other negative body pivots are counted in
//!   [`FactorReport::negative_body_pivots`] (the inertia: unstable directions);
//! * a constraint row whose pivot satisfies `|d|·ρ ≤ ε + suspect_tol` (or was
//!   regularized) is (numerically) linearly dependent on rows eliminated before
//!   it: a redundant joint. Its multiplier is then not unique; the factorization
//!   returns the one that the `ε` regularization selects (the multipliers of a
//!   set of duplicated rows share the load) while `x` and `Jx = b` stay exact.
//!
//! Both lists are in the ORIGINAL numbering. Which member of a dependent set is
//! flagged depends on the elimination order; [`redundant_rows`](crate::redundancy::redundant_rows) gives the
//! order-independent answer "rows dependent on earlier rows".

mod numeric;
mod solve;
mod symbolic;

pub use symbolic::KktSymbolic;

use crate::kkt::solver::{KktEngine, KktSolver};
use crate::kkt::system::KktSystem;
use crate::kkt::{
    alloc_err, try_vec, Accuracy, FactorCounters, FactorError, FactorReport, KktBackend, KktOptions, KktPattern,
    KktValues, SolveReport,
};
use faer::dyn_stack::MemBuffer;
use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;
use std::sync::Arc;

/// Reusable KKT factorization (see the module docs for the method): the [`KktSolver`] of a
/// [`QuasiDefiniteLdlt`].
pub type KktFactor = KktSolver<QuasiDefiniteLdlt>;

/// The engine of [`KktFactor`]: the numeric factor of a shared symbolic analysis ([`KktSymbolic`]) with its
/// own scaling, penalty and workspaces.
pub struct QuasiDefiniteLdlt {
    sym: Arc<KktSymbolic>,
    n: usize,
    m: usize,
    a_val: Vec<f64>,
    l_val: Vec<f64>,
    mem: MemBuffer,
    // Numeric workspaces. The scaled `K̂` is not kept: each of its entries is formed where it is used, by
    // the same product. Row maxima of the scaling and the pivots are not kept either: the first use
    // `tmp` (a solve workspace, free during a factorization), the second are read from the factor.
    scale: Vec<f64>,
    // Ĵ in J's order, kept although the factor input holds it too: every solve reads it in sequence, and
    // reading it from the input through `j_slot` costs a long chain's solve about half as much again.
    j_hat: Vec<f64>,
    rho: f64,
    tmp: Vec<f64>,
}

impl std::fmt::Debug for QuasiDefiniteLdlt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (kind, l_nnz) = match self.sym.symbolic.as_ref().map(|s| s.raw()) {
            Some(SymbolicCholeskyRaw::Simplicial(s)) => ("simplicial", s.len_val()),
            Some(SymbolicCholeskyRaw::Supernodal(s)) => ("supernodal", s.len_val()),
            None => ("empty", 0),
        };
        f.debug_struct("QuasiDefiniteLdlt")
            .field("n", &self.n)
            .field("m", &self.m)
            .field("factor_kind", &kind)
            .field("factor_input_nnz", &self.a_val.len())
            .field("factor_nnz", &l_nnz)
            .finish_non_exhaustive()
    }
}

impl KktFactor {
    /// Symbolic analysis once ([`KktSymbolic::analyze`]) and a numeric factor of it
    /// ([`KktFactor::from_symbolic`]).
    pub fn analyze(pattern: &KktPattern, options: KktOptions) -> Result<Self, FactorError> {
        Self::with_analyses(KktSymbolic::analyze(pattern, options)?, 1)
    }

    /// A numeric factor of a symbolic analysis, which it shares: every workspace sized and allocated here,
    /// none later. Its counters start at zero (the analysis was counted by whoever made it).
    pub fn from_symbolic(sym: Arc<KktSymbolic>) -> Result<Self, FactorError> {
        Self::with_analyses(sym, 0)
    }

    fn with_analyses(sym: Arc<KktSymbolic>, analyses: u64) -> Result<Self, FactorError> {
        let (n, m) = (sym.n, sym.m);
        let nn = n + m;
        let scale = try_vec(nn, 1.0f64)?;
        let mem = MemBuffer::try_new(sym.req).map_err(alloc_err)?;
        let engine = QuasiDefiniteLdlt {
            n,
            m,
            a_val: vec![0.0; sym.a_nnz],
            l_val: vec![0.0; sym.l_len],
            mem,
            scale,
            j_hat: vec![0.0; sym.pattern.j_row_idx.len()],
            rho: 1.0,
            tmp: vec![0.0; nn],
            sym: Arc::clone(&sym),
        };
        Ok(KktSolver::new(engine, Arc::clone(&sym.pattern), sym.options.clone(), analyses))
    }

    /// The symbolic analysis this factor is of, to share with more factors.
    pub fn symbolic(&self) -> &Arc<KktSymbolic> {
        &self.engine().sym
    }

    /// Symmetric scaling `s` of the last factorization (`x = s_x ∘ x̂`, length
    /// `n + m`, powers of two).
    pub fn scaling(&self) -> &[f64] {
        &self.engine().scale
    }

    /// Number of stored entries of the LDLᵀ factor.
    pub fn factor_nnz(&self) -> usize {
        self.engine().l_val.len()
    }

    /// Numeric factorization for new values (`k_values` aligned with
    /// `k_row_idx`, `j_values` with `j_row_idx`). No allocation, except for the
    /// suspect lists of the report when there are suspects.
    pub fn factorize(&mut self, k_values: &[f64], j_values: &[f64]) -> Result<FactorReport, FactorError> {
        KktBackend::factorize(self, KktValues { k: k_values, k_skew: None, j: j_values })
    }

    /// Solve for (x, y) in place: `rhs = [a; b]` (length n+m) becomes `[x; y]`; iterative refinement
    /// against the true KKT until the backward error stops improving or `options.max_refinement` steps.
    /// On error `rhs` is left unchanged.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<SolveReport, FactorError> {
        KktBackend::solve_in_place(self, rhs, Accuracy::Refined)
    }

    /// Work counters.
    pub fn counters(&self) -> FactorCounters {
        KktBackend::counters(self)
    }

    /// Forgets the scaling, the factorization and the counters, keeping the analysis and every buffer:
    /// the next factorization is the one a freshly analysed factor would make.
    pub fn reset(&mut self) {
        KktBackend::reset(self)
    }
}

impl KktEngine for QuasiDefiniteLdlt {
    fn name(&self) -> &'static str {
        "sparse LDLᵀ"
    }

    /// The symmetric part only: the solver wraps GMRES around it for the skew part.
    fn solves_skew(&self) -> bool {
        false
    }

    fn factorize(&mut self, system: &KktSystem) -> Result<FactorReport, FactorError> {
        QuasiDefiniteLdlt::factorize(self, system)
    }

    fn apply_inverse(&mut self, src: &[f64], out: &mut [f64]) {
        QuasiDefiniteLdlt::apply_inverse(self, src, out)
    }

    /// Both accuracies refine: the solution of the regularized form is `O(ε)` off the true one until
    /// refined, and on stiff models that costs Newton more iterations than refinement costs solves.
    fn refines(&self, _accuracy: Accuracy) -> bool {
        true
    }

    fn reset(&mut self) {
        self.scale.fill(1.0);
    }
}
