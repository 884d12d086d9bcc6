//! The numeric stage, per set of values: the scaling, the augmented quasi-definite matrix and its penalty,
//! faer's LDLᵀ kernel with dynamic regularization, and the pivots read back into the factorization's
//! report (see the module docs for the method).

use super::QuasiDefiniteLdlt;
use crate::kkt::scaling::equilibrate;
use crate::kkt::system::KktSystem;
use crate::kkt::{FactorError, FactorReport};
use faer::dyn_stack::MemStack;
use faer::linalg::cholesky::ldlt::factor::{LdltError, LdltRegularization};
use faer::sparse::linalg::cholesky::{simplicial, supernodal, SymbolicCholesky, SymbolicCholeskyRaw};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Par, Spec};
use std::sync::Arc;

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

impl QuasiDefiniteLdlt {
    /// Ruiz equilibration of the true KKT matrix into `self.scale`, starting from the last factorization's
    /// scaling (all ones after `analyze`): along a load path the values change little from one
    /// factorization to the next, and one sweep then confirms that every row's largest entry is still
    /// within a factor 2 of 1, where sweeps from ones took several each time. Values that changed by more
    /// are equilibrated from there, sweep by sweep, to the same criterion.
    fn compute_scaling(&mut self, system: &KktSystem) {
        // The pattern's arrays as slices: held in registers across the loops that write this factor's
        // buffers.
        let p = system.pattern();
        let (k_col_ptr, k_row_idx, j_col_ptr, j_row_idx) =
            (&p.k_col_ptr[..], &p.k_row_idx[..], &p.j_col_ptr[..], &p.j_row_idx[..]);
        let n = self.n;
        let (k, j) = ((&k_col_ptr, &k_row_idx, system.k()), (&j_col_ptr, &j_row_idx, system.j()));
        equilibrate(&mut self.scale, &mut self.tmp, self.sym.options.scaling_iterations, |s, rm| {
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

    /// Numeric factorization of the values of `system`: scaling, the augmented matrix, faer's kernel and
    /// the pivots' report. No allocation, except for the suspect lists of the report when there are
    /// suspects.
    pub(super) fn factorize(&mut self, system: &KktSystem) -> Result<FactorReport, FactorError> {
        self.compute_scaling(system);
        let rho = self.scale_constraints(system);
        self.fill_augmented(system, rho);
        let sym = Arc::clone(&self.sym);
        let report = FactorReport { rho, ..FactorReport::default() };
        let (Some(symbolic), Some(a_pattern)) = (sym.symbolic.as_ref(), sym.a_pattern.as_ref()) else {
            return Ok(report);
        };
        let delta = self.factor_augmented(symbolic, a_pattern)?;
        Ok(self.pivot_report(symbolic, delta, report))
    }

    /// Ĵ, the scaled constraint Jacobian, into `j_hat` and the factor's input; returns the penalty ρ (the
    /// option's, else `max_k K̂_kk / max_i ‖Ĵ_i‖²` clamped to [1e-8, 1e8], see the module docs). The squared
    /// norms of Ĵ's rows are summed in `tmp` column by column, which adds each row's terms in the order of
    /// its columns.
    fn scale_constraints(&mut self, system: &KktSystem) -> f64 {
        let sym = Arc::clone(&self.sym);
        let p = system.pattern();
        let (k_col_ptr, k_row_idx, j_col_ptr, j_row_idx) =
            (&p.k_col_ptr[..], &p.k_row_idx[..], &p.j_col_ptr[..], &p.j_row_idx[..]);
        let (k_val, j_val, j_slot) = (system.k(), system.j(), &sym.j_slot[..]);
        let (n, m) = (self.n, self.m);
        let s = &self.scale;
        let row_sq = &mut self.tmp[..m];
        row_sq.fill(0.0);
        let mut kdiag_max = 0.0f64;
        for c in 0..n {
            for e in k_col_ptr[c]..k_col_ptr[c + 1] {
                let r = k_row_idx[e];
                if r == c {
                    kdiag_max = kdiag_max.max(k_val[e] * s[r] * s[c]);
                }
            }
            for e in j_col_ptr[c]..j_col_ptr[c + 1] {
                let i = j_row_idx[e];
                let v = j_val[e] * s[n + i] * s[c];
                self.j_hat[e] = v;
                self.a_val[j_slot[e]] = v;
                row_sq[i] += v * v;
            }
        }
        let jrow_max = row_sq.iter().fold(0.0f64, |acc, &sq| acc.max(sq));
        let rho = match sym.options.rho {
            Some(r) => r,
            None if jrow_max > 0.0 => {
                let num = if kdiag_max > 0.0 { kdiag_max } else { 1.0 };
                (num / jrow_max).clamp(1e-8, 1e8)
            }
            None => 1.0,
        };
        self.rho = rho;
        rho
    }

    /// The rest of the factor's input: the body block `K̂ + ρĴᵀĴ`, entry by entry of its pattern (`K̂`'s
    /// entry, then `ρ Ĵ_ic Ĵ_ir` over the rows `i` that the columns `c` and `r` share, in increasing `i`: a
    /// merge of the two sorted columns of `J`), and the constraint block's diagonal `−ε/ρ`.
    fn fill_augmented(&mut self, system: &KktSystem, rho: f64) {
        let sym = Arc::clone(&self.sym);
        let p = system.pattern();
        let (k_col_ptr, k_row_idx, j_col_ptr, j_row_idx) =
            (&p.k_col_ptr[..], &p.k_row_idx[..], &p.j_col_ptr[..], &p.j_row_idx[..]);
        let k_val = system.k();
        let pb_slot: &[usize] = &sym.pb_slot;
        let s = &self.scale;
        let (pb_ptr, pb_row): (&[usize], &[usize]) = match &sym.pb_pattern {
            Some((ptr, row)) => (ptr, row),
            None => (k_col_ptr, k_row_idx),
        };
        for c in 0..self.n {
            let (mut e, k_end) = (k_col_ptr[c], k_col_ptr[c + 1]);
            let jc = j_col_ptr[c]..j_col_ptr[c + 1];
            for t in pb_ptr[c]..pb_ptr[c + 1] {
                let r = pb_row[t];
                let mut acc = 0.0;
                if e < k_end && k_row_idx[e] == r {
                    acc += k_val[e] * s[r] * s[c];
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
        let reg22 = -sym.options.epsilon / rho;
        for &sl in &sym.cdiag_slot {
            self.a_val[sl] = reg22;
        }
    }

    /// faer's LDLᵀ of the factor's input with dynamic regularization; returns the magnitude a regularized
    /// pivot is given (0 when regularization is off). A zero pivot it could not regularize is named as the
    /// body coordinate or constraint row it eliminates.
    fn factor_augmented(
        &mut self,
        symbolic: &SymbolicCholesky<usize>,
        a_pattern: &SymbolicSparseColMat<usize>,
    ) -> Result<f64, FactorError> {
        let sym = Arc::clone(&self.sym);
        let (n, nn) = (self.n, self.n + self.m);
        let (delta, threshold) = if sym.options.pivot_delta > 0.0 && sym.options.pivot_threshold > 0.0 {
            (sym.options.pivot_delta, sym.options.pivot_threshold)
        } else {
            (0.0, 0.0)
        };
        let reg = LdltRegularization {
            dynamic_regularization_signs: if sym.options.signed_regularization { Some(&sym.signs[..]) } else { None },
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
            let o = sym.perm[p];
            return Err(if o < n {
                FactorError::Singular { kind: "body coordinate", index: o }
            } else {
                FactorError::Singular { kind: "constraint row", index: o - n }
            });
        }
        Ok(delta)
    }

    /// The pivots' statistics and suspects (see the module docs' diagnostics), read from the factor into
    /// `report`; `delta` is what a regularized pivot was given.
    fn pivot_report(&self, symbolic: &SymbolicCholesky<usize>, delta: f64, mut report: FactorReport) -> FactorReport {
        let sym = &self.sym;
        let (n, m, rho) = (self.n, self.m, self.rho);
        let perm: &[usize] = &sym.perm;
        let pb_slot: &[usize] = &sym.pb_slot;
        let pb_ptr: &[usize] = match &sym.pb_pattern {
            Some((ptr, _)) => ptr,
            None => &sym.pattern.k_col_ptr,
        };
        let tol = sym.options.suspect_tol;
        let eps = sym.options.epsilon;
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
        report
    }
}
