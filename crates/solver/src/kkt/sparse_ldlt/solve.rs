//! The solve stage: one application of the factorization's inverse to a right-hand side in original
//! units — the scaling, the augmented-Lagrangian map, the permutation and faer's triangular solves. The
//! [`KktSolver`](crate::kkt::KktSolver) refines around it.

use super::QuasiDefiniteLdlt;
use faer::dyn_stack::MemStack;
use faer::sparse::linalg::cholesky::LdltRef;
use faer::{Conj, MatMut, Par};
use std::sync::Arc;

impl QuasiDefiniteLdlt {
    /// `out = M⁻¹ T S r` mapped back by `S` (one application of the
    /// regularized inverse to a residual in original units).
    pub(super) fn apply_inverse(&mut self, src: &[f64], t: &mut [f64]) {
        // The analysis's arrays as slices: held in registers across the loops that write this factor's
        // buffers.
        let sym = Arc::clone(&self.sym);
        let j_col_ptr: &[usize] = &sym.pattern.j_col_ptr;
        let j_row_idx: &[usize] = &sym.pattern.j_row_idx;
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
}
