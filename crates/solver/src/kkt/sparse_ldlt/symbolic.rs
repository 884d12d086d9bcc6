//! The symbolic stage: what depends on the pattern and the options only — the pattern of `K + ρJᵀJ`, the
//! ordering, faer's elimination tree and supernodes, the slot of every value in the factor's input, and
//! the workspace sizes a numeric factor allocates once.

use crate::kkt::pattern::{amd_order, build_csc, transpose_pattern, validate, KktPattern};
use crate::kkt::{try_vec, FactorError, FactorKind, KktOptions};
use faer::dyn_stack::StackReq;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, simplicial, supernodal, CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::SymbolicSparseColMat;
use faer::{Par, Side, Spec};
use std::sync::Arc;

/// The symbolic analysis of one KKT pattern (see the module docs for the method): the pattern of
/// `K + ρJᵀJ`, the ordering, the elimination tree, the slot maps of every value, the workspace sizes. It
/// depends on the pattern and the options only, never on values, and does not change once made: one
/// `Arc<KktSymbolic>` serves any number of numeric factors ([`KktFactor::from_symbolic`](super::KktFactor::from_symbolic)), as the
/// threads of a batch over one model's variants need.
pub struct KktSymbolic {
    pub(super) n: usize,
    pub(super) m: usize,
    pub(super) options: KktOptions,
    /// The pattern analysed, shared with the true system of every factor of it.
    pub(super) pattern: Arc<KktPattern>,
    // Slot in the factor input of every entry of J (CSC order). J's pattern is kept by columns only.
    pub(super) j_slot: Vec<usize>,
    // Pattern of the body block of K + ρJᵀJ (upper, original numbering), `None` when it is K's own (J
    // adds no entry to K's pattern, as in every assembly's, where each joint couples its two bodies in
    // K), and the slots of its entries.
    pub(super) pb_pattern: Option<(Vec<usize>, Vec<usize>)>,
    pub(super) pb_slot: Vec<usize>,
    pub(super) cdiag_slot: Vec<usize>,
    // Permutation: perm[p] = original index eliminated at step p.
    pub(super) perm: Vec<usize>,
    // Signs for faer's signed regularization (+1 body, −1 constraint, factor order); empty unless
    // `options.signed_regularization`.
    pub(super) signs: Vec<i8>,
    // faer structures.
    pub(super) a_pattern: Option<SymbolicSparseColMat<usize>>,
    pub(super) symbolic: Option<SymbolicCholesky<usize>>,
    // What a numeric factor allocates: its kernels' scratch, the factor input's and the factor's entries.
    pub(super) req: StackReq,
    pub(super) a_nnz: usize,
    pub(super) l_len: usize,
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
            pattern: Arc::new(pattern.clone()),
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
