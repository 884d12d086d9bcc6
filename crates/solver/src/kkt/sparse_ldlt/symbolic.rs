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
        // J by rows, for the pattern of JᵀJ and the ordering only.
        let (jr_ptr, jr_col, jr_src) = transpose_pattern(m, n, &pattern.j_col_ptr, &pattern.j_row_idx);
        drop(jr_src);
        let (pb_ptr, mut pb_row) = body_pattern(pattern, &jr_ptr, &jr_col);
        let perm = elimination_order(n, m, &pb_ptr, &pb_row, (jr_ptr, jr_col))?;
        let signs: Vec<i8> = if options.signed_regularization {
            perm.iter().map(|&o| if o < n { 1 } else { -1 }).collect()
        } else {
            Vec::new()
        };
        let entries = augmented_entries(pattern, &pb_ptr, &pb_row, &perm);
        let (pb_nnz, j_nnz, a_nnz) = (pb_row.len(), pattern.j_row_idx.len(), entries.len());
        // J adds nothing to K's pattern in every assembly's KKT: the body block is then read through K's.
        let pb_pattern = if pb_ptr == pattern.k_col_ptr && pb_row == pattern.k_row_idx {
            None
        } else {
            pb_row.shrink_to_fit();
            Some((pb_ptr, pb_row))
        };
        let FaerAnalysis { symbolic, a_pattern, mut slot, req, l_len } = faer_analysis(nn, entries, options.kind)?;
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

/// The upper pattern of the body block `K + JᵀJ`, column by column (`J` by rows in `jr_ptr`, `jr_col`).
fn body_pattern(pattern: &KktPattern, jr_ptr: &[usize], jr_col: &[usize]) -> (Vec<usize>, Vec<usize>) {
    let n = pattern.n;
    let mut pb_ptr = Vec::with_capacity(n + 1);
    pb_ptr.push(0usize);
    let mut pb_row: Vec<usize> = Vec::with_capacity(pattern.k_row_idx.len() + pattern.j_row_idx.len());
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
    (pb_ptr, pb_row)
}

/// The elimination order, `perm[p]` the original index eliminated at step `p`: AMD on the body block,
/// each constraint row right after the last of the body coordinates it touches (`J` by rows, dropped once
/// read), so that its pivot is a well-sized Schur complement.
fn elimination_order(
    n: usize,
    m: usize,
    pb_ptr: &[usize],
    pb_row: &[usize],
    (jr_ptr, jr_col): (Vec<usize>, Vec<usize>),
) -> Result<Vec<usize>, FactorError> {
    let (bperm, bperm_inv) = amd_order(n, pb_ptr, pb_row)?;
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
    let mut next = bucket_ptr.clone();
    for (i, &k) in key.iter().enumerate() {
        bucket[next[k]] = i;
        next[k] += 1;
    }
    drop(next);
    let mut perm = Vec::with_capacity(n + m);
    for p in 0..=n {
        if p < n {
            perm.push(bperm[p]);
        }
        for &i in &bucket[bucket_ptr[p]..bucket_ptr[p + 1]] {
            perm.push(n + i);
        }
    }
    Ok(perm)
}

/// The entries of the augmented matrix's upper triangle in permuted numbering, listed in original
/// numbering: the body block, then `J` in its CSC order, then the constraint diagonal (the order the slot
/// maps split at).
fn augmented_entries(pattern: &KktPattern, pb_ptr: &[usize], pb_row: &[usize], perm: &[usize]) -> Vec<(usize, usize)> {
    let (n, m) = (pattern.n, pattern.m);
    let mut perm_inv = vec![0usize; n + m];
    for (p, &o) in perm.iter().enumerate() {
        perm_inv[o] = p;
    }
    let mut entries: Vec<(usize, usize)> = Vec::with_capacity(pb_row.len() + pattern.j_row_idx.len() + m);
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
    entries
}

/// What faer's symbolic Cholesky makes of the augmented pattern: the analysis, the pattern of its input
/// (the lower triangle for the supernodal kernel, which reads that one), each entry's slot in it, and the
/// scratch and factor sizes a numeric factor allocates.
struct FaerAnalysis {
    symbolic: Option<SymbolicCholesky<usize>>,
    a_pattern: Option<SymbolicSparseColMat<usize>>,
    slot: Vec<usize>,
    req: StackReq,
    l_len: usize,
}

/// faer's symbolic analysis of the augmented matrix of order `nn` from its upper `entries` (in the
/// identity ordering: the permutation is already applied), with the kernel `kind` asks for.
fn faer_analysis(nn: usize, mut entries: Vec<(usize, usize)>, kind: FactorKind) -> Result<FaerAnalysis, FactorError> {
    let (a_ptr, a_row, slot) = build_csc(nn, &entries);
    if nn == 0 {
        return Ok(FaerAnalysis { symbolic: None, a_pattern: None, slot, req: StackReq::EMPTY, l_len: 0 });
    }
    let upper = SymbolicSparseColMat::<usize>::new_checked(nn, nn, a_ptr, None, a_row);
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: match kind {
            FactorKind::Auto => SupernodalThreshold::AUTO,
            FactorKind::Simplicial => SupernodalThreshold::FORCE_SIMPLICIAL,
            FactorKind::Supernodal => SupernodalThreshold::FORCE_SUPERNODAL,
        },
        ..CholeskySymbolicParams::default()
    };
    let sym = factorize_symbolic_cholesky(upper.as_ref(), Side::Upper, SymmetricOrdering::Identity, params)
        .map_err(|e| FactorError::Analysis(format!("{e:?}")))?;
    let (req, a_pattern, slot) = match sym.raw() {
        SymbolicCholeskyRaw::Simplicial(_) => {
            (simplicial::factorize_simplicial_numeric_ldlt_scratch::<usize, f64>(nn), upper, slot)
        }
        SymbolicCholeskyRaw::Supernodal(s) => {
            let req = supernodal::factorize_supernodal_numeric_ldlt_scratch::<usize, f64>(s, Par::Seq, Spec::default());
            // The supernodal kernel reads the lower triangle.
            drop((upper, slot));
            for e in entries.iter_mut() {
                *e = (e.1, e.0);
            }
            let (a_ptr, a_row, slot) = build_csc(nn, &entries);
            (req, SymbolicSparseColMat::<usize>::new_checked(nn, nn, a_ptr, None, a_row), slot)
        }
    };
    drop(entries);
    let req = StackReq::any_of(&[req, sym.solve_in_place_scratch::<f64>(1, Par::Seq)]);
    Ok(FaerAnalysis { l_len: sym.len_val(), symbolic: Some(sym), a_pattern: Some(a_pattern), slot, req })
}
