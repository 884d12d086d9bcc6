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

use crate::kkt::pattern::{amd_order, build_csc, transpose_pattern, validate, KktPattern};
use crate::kkt::refinement::{backward_error, Factored, Refinement};
use crate::kkt::scaling::equilibrate;
use crate::kkt::{
    alloc_err, check_values, max_abs, try_vec, Accuracy, FactorCounters, FactorError, FactorKind, FactorReport,
    KktBackend, KktOptions, KktValues, SolveReport,
};
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::ldlt::factor::{LdltError, LdltRegularization};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, simplicial, supernodal, CholeskySymbolicParams, LdltRef, SymbolicCholesky,
    SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par, Side, Spec};
use std::sync::Arc;

/// The symbolic analysis of one KKT pattern (see the module docs for the method): the pattern of
/// `K + ρJᵀJ`, the ordering, the elimination tree, the slot maps of every value, the workspace sizes. It
/// depends on the pattern and the options only, never on values, and does not change once made: one
/// `Arc<KktSymbolic>` serves any number of numeric factors ([`KktFactor::from_symbolic`]), as the
/// threads of a batch over one model's variants need.
pub struct KktSymbolic {
    n: usize,
    m: usize,
    options: KktOptions,
    // Original pattern.
    k_col_ptr: Vec<usize>,
    k_row_idx: Vec<usize>,
    j_col_ptr: Vec<usize>,
    j_row_idx: Vec<usize>,
    // Slot in the factor input of every entry of J (CSC order). J's pattern is kept by columns only.
    j_slot: Vec<usize>,
    // Pattern of the body block of K + ρJᵀJ (upper, original numbering), `None` when it is K's own (J
    // adds no entry to K's pattern, as in every assembly's, where each joint couples its two bodies in
    // K), and the slots of its entries.
    pb_pattern: Option<(Vec<usize>, Vec<usize>)>,
    pb_slot: Vec<usize>,
    cdiag_slot: Vec<usize>,
    // Permutation: perm[p] = original index eliminated at step p.
    perm: Vec<usize>,
    // Signs for faer's signed regularization (+1 body, −1 constraint, factor order); empty unless
    // `options.signed_regularization`.
    signs: Vec<i8>,
    // faer structures.
    a_pattern: Option<SymbolicSparseColMat<usize>>,
    symbolic: Option<SymbolicCholesky<usize>>,
    // What a numeric factor allocates: its kernels' scratch, the factor input's and the factor's entries.
    req: StackReq,
    a_nnz: usize,
    l_len: usize,
}

impl std::fmt::Debug for KktSymbolic {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("KktSymbolic")
            .field("n", &self.n)
            .field("m", &self.m)
            .field("factor_input_nnz", &self.a_nnz)
            .field("factor_nnz", &self.l_len)
            .finish_non_exhaustive()
    }
}

/// Reusable KKT factorization (see the module docs for the method): the numeric factor of a shared
/// symbolic analysis ([`KktSymbolic`]) with its own values, scaling and workspaces.
pub struct KktFactor {
    sym: Arc<KktSymbolic>,
    n: usize,
    m: usize,
    options: KktOptions,
    a_val: Vec<f64>,
    l_val: Vec<f64>,
    mem: MemBuffer,
    // Numeric workspaces. The scaled `K̂` is not kept: each of its entries is formed where it is used, by
    // the same product. Row maxima of the scaling and the pivots are not kept either: the first use
    // `tmp` (a solve workspace, free during a factorization), the second are read from the factor.
    scale: Vec<f64>,
    /// Largest entry of each row of the true KKT, original units (for the backward error).
    row_norm: Vec<f64>,
    k_val: Vec<f64>,
    j_val: Vec<f64>,
    // Ĵ in J's order, kept although the factor input holds it too: every solve reads it in sequence, and
    // reading it from the input through `j_slot` made a 10 000-body chain's solve 1.45× slower.
    j_hat: Vec<f64>,
    rho: f64,
    // Solve workspaces.
    z: Vec<f64>,
    rhs0: Vec<f64>,
    tmp: Vec<f64>,
    refinement: Refinement,
    factorized: bool,
    counters: FactorCounters,
}

impl std::fmt::Debug for KktFactor {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (kind, l_nnz) = match self.sym.symbolic.as_ref().map(|s| s.raw()) {
            Some(SymbolicCholeskyRaw::Simplicial(s)) => ("simplicial", s.len_val()),
            Some(SymbolicCholeskyRaw::Supernodal(s)) => ("supernodal", s.len_val()),
            None => ("empty", 0),
        };
        f.debug_struct("KktFactor")
            .field("n", &self.n)
            .field("m", &self.m)
            .field("options", &self.options)
            .field("factor_kind", &kind)
            .field("factor_input_nnz", &self.a_val.len())
            .field("factor_nnz", &l_nnz)
            .field("factorized", &self.factorized)
            .field("counters", &self.counters)
            .finish_non_exhaustive()
    }
}

/// Visits the pivots `D` in factor order, `(step, pivot)`, read out of faer's LDLᵀ storage.
fn for_each_pivot(symbolic: &SymbolicCholesky<usize>, l_val: &[f64], mut visit: impl FnMut(usize, f64)) {
    match symbolic.raw() {
        SymbolicCholeskyRaw::Simplicial(s) => {
            let cp = s.col_ptr();
            for k in 0..s.nrows() {
                visit(k, l_val[cp[k]]);
            }
        }
        SymbolicCholeskyRaw::Supernodal(s) => {
            let f = supernodal::SupernodalLdltRef::new(s, l_val);
            for si in 0..s.n_supernodes() {
                let sn = f.supernode(si);
                let start = sn.start();
                let v = sn.val();
                for j in 0..v.ncols() {
                    visit(start + j, v[(j, j)]);
                }
            }
        }
    }
}

impl KktSymbolic {
    /// Symbolic analysis once: pattern of K+ρJᵀJ, ordering, elimination tree, slot maps, and the sizes
    /// of every workspace a numeric factor needs.
    pub fn analyze(pattern: &KktPattern, options: KktOptions) -> Result<Arc<Self>, FactorError> {
        validate(pattern, &options)?;
        let (n, m) = (pattern.n, pattern.m);
        let nn = n.checked_add(m).ok_or(FactorError::OutOfMemory)?;
        // Probed as every factor will be, so that a size too large is refused here.
        drop(try_vec(nn, 1.0f64)?);
        let k_nnz = pattern.k_row_idx.len();
        let j_nnz = pattern.j_row_idx.len();

        // J by rows, for the pattern of JᵀJ and the ordering only.
        let (jr_ptr, jr_col, jr_src) = transpose_pattern(m, n, &pattern.j_col_ptr, &pattern.j_row_idx);
        drop(jr_src);

        // Upper pattern of K + JᵀJ, column by column.
        let mut pb_ptr = Vec::with_capacity(n + 1);
        pb_ptr.push(0usize);
        let mut pb_row: Vec<usize> = Vec::with_capacity(k_nnz + j_nnz);
        let mut mark = vec![usize::MAX; n];
        for c in 0..n {
            let start = pb_row.len();
            for &r in &pattern.k_row_idx[pattern.k_col_ptr[c]..pattern.k_col_ptr[c + 1]] {
                mark[r] = c;
                pb_row.push(r);
            }
            for &i in &pattern.j_row_idx[pattern.j_col_ptr[c]..pattern.j_col_ptr[c + 1]] {
                for &r in &jr_col[jr_ptr[i]..jr_ptr[i + 1]] {
                    if r <= c && mark[r] != c {
                        mark[r] = c;
                        pb_row.push(r);
                    }
                }
            }
            pb_row[start..].sort_unstable();
            pb_ptr.push(pb_row.len());
        }
        drop(mark);

        // Ordering: AMD on the body block, constraints after their last dof.
        let (bperm, bperm_inv) = amd_order(n, &pb_ptr, &pb_row)?;
        let mut key = vec![n; m];
        for (i, k) in key.iter_mut().enumerate() {
            for &c in &jr_col[jr_ptr[i]..jr_ptr[i + 1]] {
                let p = bperm_inv[c];
                *k = if *k == n { p } else { (*k).max(p) };
            }
        }
        drop((jr_ptr, jr_col, bperm_inv));
        let mut bucket_ptr = vec![0usize; n + 2];
        for &k in &key {
            bucket_ptr[k + 1] += 1;
        }
        for p in 0..=n {
            bucket_ptr[p + 1] += bucket_ptr[p];
        }
        let mut bucket = vec![0usize; m];
        {
            let mut next = bucket_ptr.clone();
            for (i, &k) in key.iter().enumerate() {
                bucket[next[k]] = i;
                next[k] += 1;
            }
        }
        let mut perm = Vec::with_capacity(nn);
        for p in 0..=n {
            if p < n {
                perm.push(bperm[p]);
            }
            for &i in &bucket[bucket_ptr[p]..bucket_ptr[p + 1]] {
                perm.push(n + i);
            }
        }
        drop((bperm, key, bucket_ptr, bucket));
        let mut perm_inv = vec![0usize; nn];
        for (p, &o) in perm.iter().enumerate() {
            perm_inv[o] = p;
        }
        let signs: Vec<i8> = if options.signed_regularization {
            perm.iter().map(|&o| if o < n { 1 } else { -1 }).collect()
        } else {
            Vec::new()
        };

        // Entries of the augmented matrix (upper), listed in original numbering: body block, then J block in
        // J's CSC order, then the constraint diagonal; stored at once in permuted numbering.
        let pb_nnz = pb_row.len();
        let mut entries: Vec<(usize, usize)> = Vec::with_capacity(pb_nnz + j_nnz + m);
        let mut push = |r: usize, c: usize| {
            let (a, b) = (perm_inv[r], perm_inv[c]);
            entries.push((a.min(b), a.max(b)));
        };
        for c in 0..n {
            for &r in &pb_row[pb_ptr[c]..pb_ptr[c + 1]] {
                push(r, c);
            }
        }
        for c in 0..n {
            for &i in &pattern.j_row_idx[pattern.j_col_ptr[c]..pattern.j_col_ptr[c + 1]] {
                push(c, n + i);
            }
        }
        for i in 0..m {
            push(n + i, n + i);
        }
        drop(perm_inv);
        let a_nnz = entries.len();
        // J adds nothing to K's pattern in every assembly's KKT: the body block is then read through K's.
        let pb_pattern = if pb_ptr == pattern.k_col_ptr && pb_row == pattern.k_row_idx {
            None
        } else {
            pb_row.shrink_to_fit();
            Some((pb_ptr, pb_row))
        };
        let (mut a_ptr, mut a_row, mut slot) = build_csc(nn, &entries);

        let mut symbolic = None;
        let mut a_pattern = None;
        let mut l_len = 0;
        let mut req = StackReq::EMPTY;
        if nn > 0 {
            let upper = SymbolicSparseColMat::<usize>::new_checked(nn, nn, a_ptr, None, a_row);
            let params = CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: match options.kind {
                    FactorKind::Auto => SupernodalThreshold::AUTO,
                    FactorKind::Simplicial => SupernodalThreshold::FORCE_SIMPLICIAL,
                    FactorKind::Supernodal => SupernodalThreshold::FORCE_SUPERNODAL,
                },
                ..CholeskySymbolicParams::default()
            };
            let sym = factorize_symbolic_cholesky(upper.as_ref(), Side::Upper, SymmetricOrdering::Identity, params)
                .map_err(|e| FactorError::Analysis(format!("{e:?}")))?;
            let pat = match sym.raw() {
                SymbolicCholeskyRaw::Simplicial(_) => {
                    req = simplicial::factorize_simplicial_numeric_ldlt_scratch::<usize, f64>(nn);
                    upper
                }
                SymbolicCholeskyRaw::Supernodal(s) => {
                    req = supernodal::factorize_supernodal_numeric_ldlt_scratch::<usize, f64>(
                        s,
                        Par::Seq,
                        Spec::default(),
                    );
                    // The supernodal kernel reads the lower triangle.
                    for e in entries.iter_mut() {
                        *e = (e.1, e.0);
                    }
                    (a_ptr, a_row, slot) = build_csc(nn, &entries);
                    SymbolicSparseColMat::<usize>::new_checked(nn, nn, a_ptr, None, a_row)
                }
            };
            req = StackReq::any_of(&[req, sym.solve_in_place_scratch::<f64>(1, Par::Seq)]);
            l_len = sym.len_val();
            symbolic = Some(sym);
            a_pattern = Some(pat);
        }
        drop(entries);
        let cdiag_slot = slot.split_off(pb_nnz + j_nnz);
        let j_slot = slot.split_off(pb_nnz);
        let mut pb_slot = slot;
        pb_slot.shrink_to_fit();

        Ok(Arc::new(KktSymbolic {
            n,
            m,
            options,
            k_col_ptr: pattern.k_col_ptr.clone(),
            k_row_idx: pattern.k_row_idx.clone(),
            j_col_ptr: pattern.j_col_ptr.clone(),
            j_row_idx: pattern.j_row_idx.clone(),
            j_slot,
            pb_pattern,
            pb_slot,
            cdiag_slot,
            perm,
            signs,
            a_pattern,
            symbolic,
            req,
            a_nnz,
            l_len,
        }))
    }
}

impl KktFactor {
    /// Symbolic analysis once ([`KktSymbolic::analyze`]) and a numeric factor of it
    /// ([`KktFactor::from_symbolic`]).
    pub fn analyze(pattern: &KktPattern, options: KktOptions) -> Result<Self, FactorError> {
        let mut factor = Self::from_symbolic(KktSymbolic::analyze(pattern, options)?)?;
        factor.counters.symbolic_analyses = 1;
        Ok(factor)
    }

    /// A numeric factor of a symbolic analysis, which it shares: every workspace sized and allocated here,
    /// none later. Its counters start at zero (the analysis was counted by whoever made it).
    pub fn from_symbolic(sym: Arc<KktSymbolic>) -> Result<Self, FactorError> {
        let (n, m) = (sym.n, sym.m);
        let nn = n + m;
        let scale = try_vec(nn, 1.0f64)?;
        let mem = MemBuffer::try_new(sym.req).map_err(alloc_err)?;
        Ok(Self {
            n,
            m,
            options: sym.options.clone(),
            a_val: vec![0.0; sym.a_nnz],
            l_val: vec![0.0; sym.l_len],
            mem,
            scale,
            row_norm: vec![0.0; nn],
            k_val: vec![0.0; sym.k_row_idx.len()],
            j_val: vec![0.0; sym.j_row_idx.len()],
            j_hat: vec![0.0; sym.j_row_idx.len()],
            rho: 1.0,
            z: vec![0.0; nn],
            rhs0: vec![0.0; nn],
            tmp: vec![0.0; nn],
            refinement: Refinement::new(nn),
            factorized: false,
            counters: FactorCounters::default(),
            sym,
        })
    }

    /// The symbolic analysis this factor is of, to share with more factors.
    pub fn symbolic(&self) -> &Arc<KktSymbolic> {
        &self.sym
    }

    /// Number of body coordinates `n`.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Number of constraint rows `m`.
    pub fn m(&self) -> usize {
        self.m
    }

    /// Options given to [`KktFactor::analyze`].
    pub fn options(&self) -> &KktOptions {
        &self.options
    }

    /// Symmetric scaling `s` of the last factorization (`x = s_x ∘ x̂`, length
    /// `n + m`, powers of two).
    pub fn scaling(&self) -> &[f64] {
        &self.scale
    }

    /// Number of stored entries of the LDLᵀ factor.
    pub fn factor_nnz(&self) -> usize {
        self.l_val.len()
    }

    /// Work counters.
    pub fn counters(&self) -> FactorCounters {
        self.counters
    }

    /// Forgets the scaling, the factorization and the counters, keeping the analysis and every buffer:
    /// the next factorization is the one a freshly analysed factor would make.
    pub fn reset(&mut self) {
        self.scale.fill(1.0);
        self.factorized = false;
        self.counters = FactorCounters::default();
    }

    /// Ruiz equilibration of the true KKT matrix into `self.scale`, starting from the last factorization's
    /// scaling (all ones after `analyze`): along a load path the values change little from one
    /// factorization to the next, and one sweep then confirms that every row's largest entry is still
    /// within a factor 2 of 1, where sweeps from ones took several each time. Values that changed by more
    /// are equilibrated from there, sweep by sweep, to the same criterion.
    fn compute_scaling(&mut self) {
        // The analysis's arrays as slices: held in registers across the loops that write this factor's
        // buffers.
        let sym = Arc::clone(&self.sym);
        let k_col_ptr: &[usize] = &sym.k_col_ptr;
        let k_row_idx: &[usize] = &sym.k_row_idx;
        let j_col_ptr: &[usize] = &sym.j_col_ptr;
        let j_row_idx: &[usize] = &sym.j_row_idx;
        let n = self.n;
        let (k, j) = ((&k_col_ptr, &k_row_idx, &self.k_val), (&j_col_ptr, &j_row_idx, &self.j_val));
        equilibrate(&mut self.scale, &mut self.tmp, self.options.scaling_iterations, |s, rm| {
            for c in 0..n {
                for e in k.0[c]..k.0[c + 1] {
                    let r = k.1[e];
                    let v = k.2[e].abs() * s[r] * s[c];
                    rm[r] = rm[r].max(v);
                    rm[c] = rm[c].max(v);
                }
                for e in j.0[c]..j.0[c + 1] {
                    let i = n + j.1[e];
                    let v = j.2[e].abs() * s[i] * s[c];
                    rm[i] = rm[i].max(v);
                    rm[c] = rm[c].max(v);
                }
            }
        });
    }

    /// Numeric factorization for new values (`k_values` aligned with
    /// `k_row_idx`, `j_values` with `j_row_idx`). No allocation, except for the
    /// suspect lists of the report when there are suspects.
    pub fn factorize(&mut self, k_values: &[f64], j_values: &[f64]) -> Result<FactorReport, FactorError> {
        // The analysis's arrays as slices: held in registers across the loops that write this factor's
        // buffers.
        let sym = Arc::clone(&self.sym);
        let k_col_ptr: &[usize] = &sym.k_col_ptr;
        let k_row_idx: &[usize] = &sym.k_row_idx;
        let j_col_ptr: &[usize] = &sym.j_col_ptr;
        let j_row_idx: &[usize] = &sym.j_row_idx;
        let j_slot: &[usize] = &sym.j_slot;
        let pb_slot: &[usize] = &sym.pb_slot;
        let cdiag_slot: &[usize] = &sym.cdiag_slot;
        let perm: &[usize] = &sym.perm;
        let signs: &[i8] = &sym.signs;
        self.factorized = false;
        check_values("k_values", k_values, k_row_idx.len())?;
        check_values("j_values", j_values, j_row_idx.len())?;
        let (n, m) = (self.n, self.m);
        let nn = n + m;
        self.k_val.copy_from_slice(k_values);
        self.j_val.copy_from_slice(j_values);
        self.row_norm.fill(0.0);
        for c in 0..n {
            for e in k_col_ptr[c]..k_col_ptr[c + 1] {
                let (r, v) = (k_row_idx[e], self.k_val[e].abs());
                self.row_norm[r] = self.row_norm[r].max(v);
                self.row_norm[c] = self.row_norm[c].max(v);
            }
            for e in j_col_ptr[c]..j_col_ptr[c + 1] {
                let (i, v) = (n + j_row_idx[e], self.j_val[e].abs());
                self.row_norm[i] = self.row_norm[i].max(v);
                self.row_norm[c] = self.row_norm[c].max(v);
            }
        }
        self.compute_scaling();

        // Scaled values and ρ. The squared norms of Ĵ's rows are summed in `tmp` column by column, which
        // adds each row's terms in the order of its columns.
        let s = &self.scale;
        let row_sq = &mut self.tmp[..m];
        row_sq.fill(0.0);
        let mut kdiag_max = 0.0f64;
        for c in 0..n {
            for e in k_col_ptr[c]..k_col_ptr[c + 1] {
                let r = k_row_idx[e];
                if r == c {
                    kdiag_max = kdiag_max.max(self.k_val[e] * s[r] * s[c]);
                }
            }
            for e in j_col_ptr[c]..j_col_ptr[c + 1] {
                let i = j_row_idx[e];
                let v = self.j_val[e] * s[n + i] * s[c];
                self.j_hat[e] = v;
                self.a_val[j_slot[e]] = v;
                row_sq[i] += v * v;
            }
        }
        let jrow_max = row_sq.iter().fold(0.0f64, |acc, &sq| acc.max(sq));
        let rho = match self.options.rho {
            Some(r) => r,
            None if jrow_max > 0.0 => {
                let num = if kdiag_max > 0.0 { kdiag_max } else { 1.0 };
                (num / jrow_max).clamp(1e-8, 1e8)
            }
            None => 1.0,
        };
        self.rho = rho;
        let reg22 = -self.options.epsilon / rho;

        // The body block K̂ + ρĴᵀĴ, entry by entry of its pattern: K̂'s entry, then ρ Ĵ_ic Ĵ_ir over the
        // rows i that the columns c and r share, in increasing i (a merge of the two sorted columns of J).
        let (pb_ptr, pb_row): (&[usize], &[usize]) = match &sym.pb_pattern {
            Some((ptr, row)) => (ptr, row),
            None => (k_col_ptr, k_row_idx),
        };
        for c in 0..n {
            let (mut e, k_end) = (k_col_ptr[c], k_col_ptr[c + 1]);
            let jc = j_col_ptr[c]..j_col_ptr[c + 1];
            for t in pb_ptr[c]..pb_ptr[c + 1] {
                let r = pb_row[t];
                let mut acc = 0.0;
                if e < k_end && k_row_idx[e] == r {
                    acc += self.k_val[e] * s[r] * s[c];
                    e += 1;
                }
                let (mut a, mut b, b_end) = (jc.start, j_col_ptr[r], j_col_ptr[r + 1]);
                while a < jc.end && b < b_end {
                    let (ia, ib) = (j_row_idx[a], j_row_idx[b]);
                    if ia == ib {
                        acc += rho * self.j_hat[a] * self.j_hat[b];
                        a += 1;
                        b += 1;
                    } else if ia < ib {
                        a += 1;
                    } else {
                        b += 1;
                    }
                }
                self.a_val[pb_slot[t]] = acc;
            }
        }
        for &sl in cdiag_slot {
            self.a_val[sl] = reg22;
        }

        let mut report = FactorReport { rho, ..FactorReport::default() };
        let (Some(symbolic), Some(a_pattern)) = (self.sym.symbolic.as_ref(), self.sym.a_pattern.as_ref()) else {
            self.factorized = true;
            self.counters.numeric_factorizations += 1;
            return Ok(report);
        };
        let (delta, threshold) = if self.options.pivot_delta > 0.0 && self.options.pivot_threshold > 0.0 {
            (self.options.pivot_delta, self.options.pivot_threshold)
        } else {
            (0.0, 0.0)
        };
        let reg = LdltRegularization {
            dynamic_regularization_signs: if self.options.signed_regularization { Some(signs) } else { None },
            dynamic_regularization_delta: delta,
            dynamic_regularization_epsilon: threshold,
        };
        let a = SparseColMatRef::new(a_pattern.as_ref(), &self.a_val);
        let stack = MemStack::new(&mut self.mem);
        let res = match symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(s) => {
                simplicial::factorize_simplicial_numeric_ldlt(&mut self.l_val, a, reg, s, stack)
            }
            SymbolicCholeskyRaw::Supernodal(s) => supernodal::factorize_supernodal_numeric_ldlt(
                &mut self.l_val,
                a,
                reg,
                s,
                Par::Seq,
                stack,
                Spec::default(),
            ),
        };
        if let Err(LdltError::ZeroPivot { index }) = res {
            // faer's simplicial kernel reports index + 1, the dense one index.
            let p = match symbolic.raw() {
                SymbolicCholeskyRaw::Simplicial(_) => index.saturating_sub(1),
                SymbolicCholeskyRaw::Supernodal(_) => index,
            }
            .min(nn - 1);
            let o = perm[p];
            return Err(if o < n {
                FactorError::Singular { kind: "body coordinate", index: o }
            } else {
                FactorError::Singular { kind: "constraint row", index: o - n }
            });
        }
        // Pivot statistics and suspects.
        let tol = self.options.suspect_tol;
        let eps = self.options.epsilon;
        let (mut bmin, mut bmax, mut cmin, mut cmax) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
        for_each_pivot(symbolic, &self.l_val, |p, d| {
            let o = perm[p];
            let regularized = delta > 0.0 && d.abs() == delta;
            if regularized {
                report.regularized_pivots += 1;
            }
            if o < n {
                bmin = bmin.min(d.abs());
                bmax = bmax.max(d.abs());
                // The diagonal of K̂ + ρĴᵀĴ, the last entry of its column.
                let diag = self.a_val[pb_slot[pb_ptr[o + 1] - 1]];
                let small = d.abs() <= tol * if diag > 0.0 { diag } else { 1.0 };
                if regularized || small {
                    report.suspect_body_dofs.push(o);
                } else if d < 0.0 {
                    report.negative_body_pivots += 1;
                }
            } else {
                cmin = cmin.min(d.abs());
                cmax = cmax.max(d.abs());
                if regularized || d.abs() * rho <= eps + tol {
                    report.suspect_constraint_rows.push(o - n);
                }
            }
        });
        report.min_body_pivot = if n > 0 { bmin } else { 0.0 };
        report.max_body_pivot = bmax;
        report.min_constraint_pivot = if m > 0 { cmin } else { 0.0 };
        report.max_constraint_pivot = cmax;
        report.suspect_body_dofs.sort_unstable();
        report.suspect_constraint_rows.sort_unstable();
        self.factorized = true;
        self.counters.numeric_factorizations += 1;
        Ok(report)
    }

    /// Solve for (x, y) in place: `rhs = [a; b]` (length n+m) becomes `[x; y]`; iterative refinement
    /// against the true KKT (`refinement.rs`, written once for every backend) until the backward error stops improving or
    /// `options.max_refinement` steps. On error `rhs` is left unchanged.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<SolveReport, FactorError> {
        let nn = self.n + self.m;
        if !self.factorized {
            return Err(FactorError::NotFactorized);
        }
        check_values("rhs", rhs, nn)?;
        self.rhs0.copy_from_slice(rhs);
        let mut z = std::mem::take(&mut self.z);
        self.apply_inverse(rhs, &mut z);
        if let Some(index) = z.iter().position(|v| !v.is_finite()) {
            self.z = z;
            return Err(FactorError::NonFiniteSolution { index });
        }
        let mut refinement = std::mem::take(&mut self.refinement);
        let (steps, eta) = refinement.refine(self, &mut z, self.options.max_refinement, self.options.refinement_tol);
        let r = refinement.residual();
        let (residual_x, residual_y) = (max_abs(&r[..self.n]), max_abs(&r[self.n..]));
        self.refinement = refinement;
        rhs.copy_from_slice(&z);
        self.z = z;
        self.counters.solves += 1;
        self.counters.refinement_steps += steps as u64;
        Ok(SolveReport {
            refinement_steps: steps,
            residual_x,
            residual_y,
            backward_error: eta,
            converged: eta <= self.options.refinement_tol,
            measured: true,
        })
    }
}

impl Factored for KktFactor {
    /// `out = M⁻¹ T S r` mapped back by `S` (one application of the
    /// regularized inverse to a residual in original units).
    fn apply_inverse(&mut self, src: &[f64], t: &mut [f64]) {
        // The analysis's arrays as slices: held in registers across the loops that write this factor's
        // buffers.
        let sym = Arc::clone(&self.sym);
        let j_col_ptr: &[usize] = &sym.j_col_ptr;
        let j_row_idx: &[usize] = &sym.j_row_idx;
        let perm: &[usize] = &sym.perm;
        let (n, nn) = (self.n, self.n + self.m);
        for i in 0..nn {
            t[i] = self.scale[i] * src[i];
        }
        for c in 0..n {
            let mut acc = 0.0;
            for e in j_col_ptr[c]..j_col_ptr[c + 1] {
                acc += self.j_hat[e] * t[n + j_row_idx[e]];
            }
            t[c] += self.rho * acc;
        }
        for (p, &o) in perm.iter().enumerate() {
            self.tmp[p] = t[o];
        }
        if let Some(symbolic) = self.sym.symbolic.as_ref() {
            let f = LdltRef::new(symbolic, &self.l_val);
            let stack = MemStack::new(&mut self.mem);
            f.solve_in_place_with_conj(
                Conj::No,
                MatMut::from_column_major_slice_mut(&mut self.tmp, nn, 1),
                Par::Seq,
                stack,
            );
        }
        for (p, &o) in perm.iter().enumerate() {
            t[o] = self.tmp[p] * self.scale[o];
        }
    }

    /// `r = rhs0 − KKT z` with the original values (`den` receives `|KKT|·|z| + |rhs0|`); returns its
    /// backward error ([`backward_error`]: componentwise, rows at rounding level normwise).
    fn residual(&self, z: &[f64], r: &mut [f64], den: &mut [f64]) -> f64 {
        // The analysis's arrays as slices: held in registers across the loops that write this factor's
        // buffers.
        let sym = Arc::clone(&self.sym);
        let k_col_ptr: &[usize] = &sym.k_col_ptr;
        let k_row_idx: &[usize] = &sym.k_row_idx;
        let j_col_ptr: &[usize] = &sym.j_col_ptr;
        let j_row_idx: &[usize] = &sym.j_row_idx;
        let n = self.n;
        r.copy_from_slice(&self.rhs0);
        for (d, b) in den.iter_mut().zip(&self.rhs0) {
            *d = b.abs();
        }
        for c in 0..n {
            let zc = z[c];
            for e in k_col_ptr[c]..k_col_ptr[c + 1] {
                let row = k_row_idx[e];
                let v = self.k_val[e];
                r[row] -= v * zc;
                den[row] += (v * zc).abs();
                if row != c {
                    r[c] -= v * z[row];
                    den[c] += (v * z[row]).abs();
                }
            }
            for e in j_col_ptr[c]..j_col_ptr[c + 1] {
                let i = n + j_row_idx[e];
                let v = self.j_val[e];
                r[c] -= v * z[i];
                den[c] += (v * z[i]).abs();
                r[i] -= v * zc;
                den[i] += (v * zc).abs();
            }
        }
        backward_error(r, den, &self.row_norm, &self.rhs0, z)
    }
}

impl KktBackend for KktFactor {
    fn name(&self) -> &'static str {
        "sparse LDLᵀ"
    }

    fn solves_skew(&self) -> bool {
        false
    }

    fn factorize(&mut self, values: KktValues<'_>) -> Result<FactorReport, FactorError> {
        KktFactor::factorize(self, values.k, values.j)
    }

    /// Both accuracies refine: the solution of the regularized form is `O(ε)` off the true one until
    /// refined, and on stiff models that costs Newton more iterations than refinement costs solves.
    fn solve_in_place(&mut self, rhs: &mut [f64], _accuracy: Accuracy) -> Result<SolveReport, FactorError> {
        KktFactor::solve_in_place(self, rhs)
    }

    fn counters(&self) -> FactorCounters {
        KktFactor::counters(self)
    }

    fn reset(&mut self) {
        KktFactor::reset(self)
    }
}
