//! Which constraint rows repeat others: a rank-revealing test of the Jacobian alone, whatever the order
//! of elimination, so that a redundant joint is named by its rows.

use crate::kkt::pattern::{amd_order, build_csc, transpose_pattern, validate_j};
use crate::kkt::{alloc_err, check_values, try_vec, FactorError};
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::sparse::linalg::cholesky::simplicial;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};

/// Pivot value used to *drop* a dependent row of the Gram matrix: its factor
/// column becomes `col / BIG ≈ 0`, i.e. the row is removed from the basis.
const DROP_PIVOT: f64 = 1e100;

/// Smallest Gram pivot distinguishable from rounding: measured noise of the
/// pivots of exactly dependent rows is 1e-16…1e-15; this keeps a ~100× margin.
/// It corresponds to an angle (relative orthogonal component) of ≈ 3.4e-7.
const GRAM_PIVOT_FLOOR: f64 = 512.0 * f64::EPSILON;

/// Rank-revealing check of J alone: indices of rows that are linearly dependent
/// on earlier rows (tolerance relative to row norms), ascending, in original
/// row numbering. Of two duplicated rows the later one is reported; an all-zero
/// row is always reported.
///
/// Row `i` counts as dependent when the part of `J_i` orthogonal to the
/// independent rows before it has norm `≤ tol·‖J_i‖`. Because the method works
/// on the Gram matrix, tolerances below ~1e-7 are not resolvable; 1e-6…1e-8
/// is the useful range.
///
/// Method: rows are normalized, the Gram matrix `G = ĴĴᵀ` is factorized by a
/// sparse simplicial LDLᵀ in AMD order, a pivot `≤ tol²` drops the row (faer's
/// dynamic regularization with a huge replacement pivot, which zeroes the row's
/// factor column). For every dropped row the null vector `ĴᵀW = 0` is recovered
/// from the factor (a triangular solve restricted to its elimination subtree),
/// and the null-space basis is brought to echelon form with respect to the
/// largest original row index; those leading indices are exactly the rows
/// dependent on earlier rows, independent of the AMD order.
///
/// Malformed input (bad CSC arrays, non-finite values, negative `tol`) yields
/// an empty list; use [`try_redundant_rows`] to get the typed error instead.
pub fn redundant_rows(
    m: usize,
    n: usize,
    j_col_ptr: &[usize],
    j_row_idx: &[usize],
    j_values: &[f64],
    tol: f64,
) -> Vec<usize> {
    try_redundant_rows(m, n, j_col_ptr, j_row_idx, j_values, tol).unwrap_or_default()
}

/// [`redundant_rows`] with typed errors for malformed input.
pub fn try_redundant_rows(
    m: usize,
    n: usize,
    j_col_ptr: &[usize],
    j_row_idx: &[usize],
    j_values: &[f64],
    tol: f64,
) -> Result<Vec<usize>, FactorError> {
    validate_j(m, n, j_col_ptr, j_row_idx)?;
    check_values("j_values", j_values, j_row_idx.len())?;
    if !(tol.is_finite() && tol >= 0.0) {
        return Err(FactorError::InvalidOption { name: "tol", reason: "must be finite and >= 0" });
    }
    if m == 0 {
        return Ok(Vec::new());
    }
    let normalized = normalized_rows(m, j_row_idx, j_values)?;
    let gram = Gram::of(m, n, j_col_ptr, j_row_idx, &normalized);
    let factor = GramFactor::of(&gram, tol)?;
    let dropped: Vec<usize> = (0..m).filter(|&k| factor.dropped(k)).collect();
    if dropped.is_empty() {
        return Ok(Vec::new());
    }
    let mut scratch = NullScratch { u: vec![0.0f64; m], desc: Vec::new(), dfs: Vec::new() };
    let basis = dropped.iter().map(|&j| factor.null_vector(j, &mut scratch)).collect();
    Ok(leading_rows(basis))
}

/// The values of `J` with each row scaled to unit length, `Ĵ_i = J_i / ‖J_i‖` (zero rows stay zero), in
/// the order of `j_row_idx`.
fn normalized_rows(m: usize, j_row_idx: &[usize], j_values: &[f64]) -> Result<Vec<f64>, FactorError> {
    let mut rmax = try_vec(m, 0.0f64)?;
    // Row scaling by powers of two first (overflow-safe norms), then exact norms.
    for (e, &i) in j_row_idx.iter().enumerate() {
        rmax[i] = rmax[i].max(j_values[e].abs());
    }
    let mut sq = vec![0.0f64; m];
    for (e, &i) in j_row_idx.iter().enumerate() {
        if rmax[i] > 0.0 {
            let v = j_values[e] / rmax[i];
            sq[i] += v * v;
        }
    }
    Ok(j_row_idx
        .iter()
        .zip(j_values)
        .map(|(&i, &v)| if rmax[i] > 0.0 { (v / rmax[i]) / sq[i].sqrt() } else { 0.0 })
        .collect())
}

/// The upper triangle of the Gram matrix `G = ĴĴᵀ` of the normalized rows, column by column (CSC).
struct Gram {
    m: usize,
    col_ptr: Vec<usize>,
    row: Vec<usize>,
    values: Vec<f64>,
}

impl Gram {
    /// `G` of the `m × n` Jacobian whose pattern is `j_col_ptr`, `j_row_idx` and whose normalized values are
    /// `normalized`.
    fn of(m: usize, n: usize, j_col_ptr: &[usize], j_row_idx: &[usize], normalized: &[f64]) -> Gram {
        let (jr_ptr, jr_col, jr_src) = transpose_pattern(m, n, j_col_ptr, j_row_idx);
        let mut gram = Gram { m, col_ptr: vec![0usize], row: Vec::new(), values: Vec::new() };
        let mut mark = vec![usize::MAX; m];
        let mut acc = vec![0.0f64; m];
        let mut list: Vec<usize> = Vec::new();
        for i in 0..m {
            list.clear();
            mark[i] = i;
            acc[i] = 0.0;
            list.push(i);
            for q in jr_ptr[i]..jr_ptr[i + 1] {
                let c = jr_col[q];
                let vic = normalized[jr_src[q]];
                for e in j_col_ptr[c]..j_col_ptr[c + 1] {
                    let r = j_row_idx[e];
                    if r > i {
                        break;
                    }
                    if mark[r] != i {
                        mark[r] = i;
                        acc[r] = 0.0;
                        list.push(r);
                    }
                    acc[r] += normalized[e] * vic;
                }
            }
            list.sort_unstable();
            for &r in &list {
                gram.row.push(r);
                gram.values.push(acc[r]);
            }
            gram.col_ptr.push(gram.row.len());
        }
        gram
    }
}

/// The LDLᵀ factor of the Gram matrix in AMD order, a pivot at or below `tol²` replaced by [`DROP_PIVOT`]
/// (the row dropped from the basis), with the elimination tree's children for the null vectors.
struct GramFactor {
    /// The AMD order: `perm[k]` is the original row eliminated `k`-th.
    perm: Vec<usize>,
    symbolic: simplicial::SymbolicSimplicialCholesky<usize>,
    l_values: Vec<f64>,
    /// Row access to `L`: for each row, its columns and where their values are.
    l_row_ptr: Vec<usize>,
    l_row_col: Vec<usize>,
    l_row_src: Vec<usize>,
    /// Each column's children in the elimination tree (CSR-like).
    child_ptr: Vec<usize>,
    child: Vec<usize>,
}

impl GramFactor {
    fn of(gram: &Gram, tol: f64) -> Result<GramFactor, FactorError> {
        let m = gram.m;
        let (perm, perm_inv) = amd_order(m, &gram.col_ptr, &gram.row)?;
        let mut entries = Vec::with_capacity(gram.row.len());
        for i in 0..m {
            for &r in &gram.row[gram.col_ptr[i]..gram.col_ptr[i + 1]] {
                let (a, b) = (perm_inv[r], perm_inv[i]);
                entries.push((a.min(b), a.max(b)));
            }
        }
        let (p_ptr, p_row, slot) = build_csc(m, &entries);
        let mut p_val = vec![0.0f64; gram.values.len()];
        for (e, &v) in gram.values.iter().enumerate() {
            p_val[slot[e]] = v;
        }
        let gp = SymbolicSparseColMat::<usize>::new_checked(m, m, p_ptr, None, p_row);
        let mut etree = vec![0isize; m];
        let mut col_counts = vec![0usize; m];
        let mut mem = MemBuffer::try_new(StackReq::any_of(&[
            simplicial::prefactorize_symbolic_cholesky_scratch::<usize>(m, gram.values.len()),
            simplicial::factorize_simplicial_symbolic_cholesky_scratch::<usize>(m),
            simplicial::factorize_simplicial_numeric_ldlt_scratch::<usize, f64>(m),
        ]))
        .map_err(alloc_err)?;
        let stack = MemStack::new(&mut mem);
        let et = simplicial::prefactorize_symbolic_cholesky::<usize>(&mut etree, &mut col_counts, gp.as_ref(), stack);
        let symbolic = simplicial::factorize_simplicial_symbolic_cholesky(gp.as_ref(), et, &col_counts, stack)
            .map_err(|e| FactorError::Analysis(format!("{e:?}")))?;
        let mut l_values = vec![0.0f64; symbolic.len_val()];
        let signs = vec![1i8; m];
        let reg = LdltRegularization {
            dynamic_regularization_signs: Some(&signs),
            dynamic_regularization_delta: DROP_PIVOT,
            dynamic_regularization_epsilon: (tol * tol).max(GRAM_PIVOT_FLOOR),
        };
        simplicial::factorize_simplicial_numeric_ldlt(
            &mut l_values,
            SparseColMatRef::new(gp.as_ref(), &p_val),
            reg,
            &symbolic,
            stack,
        )
        .map_err(|_| FactorError::Singular { kind: "constraint row", index: 0 })?;
        let (l_row_ptr, l_row_col, l_row_src) = transpose_pattern(m, m, symbolic.col_ptr(), symbolic.row_idx());
        let (child_ptr, child) = children(&etree);
        Ok(GramFactor { perm, symbolic, l_values, l_row_ptr, l_row_col, l_row_src, child_ptr, child })
    }

    /// Whether the row eliminated `k`-th was dropped (its pivot replaced by [`DROP_PIVOT`]).
    fn dropped(&self, k: usize) -> bool {
        self.l_values[self.symbolic.col_ptr()[k]] == DROP_PIVOT
    }

    /// The null vector `ĴᵀW = 0` of the dropped row eliminated `j`-th, in original numbering, sorted: a
    /// triangular solve restricted to its elimination subtree, in `scratch`.
    fn null_vector(&self, j: usize, scratch: &mut NullScratch) -> Vec<(usize, f64)> {
        let (lcp, lri, l_val) = (self.symbolic.col_ptr(), self.symbolic.row_idx(), &self.l_values);
        let NullScratch { u, desc, dfs } = scratch;
        desc.clear();
        dfs.clear();
        dfs.extend_from_slice(&self.child[self.child_ptr[j]..self.child_ptr[j + 1]]);
        while let Some(k) = dfs.pop() {
            desc.push(k);
            dfs.extend_from_slice(&self.child[self.child_ptr[k]..self.child_ptr[k + 1]]);
        }
        desc.sort_unstable_by(|a, b| b.cmp(a));
        for q in self.l_row_ptr[j]..self.l_row_ptr[j + 1] {
            let k = self.l_row_col[q];
            if k < j {
                u[k] = l_val[self.l_row_src[q]];
            }
        }
        for &k in desc.iter() {
            let mut s = u[k];
            for e in lcp[k] + 1..lcp[k + 1] {
                let i = lri[e];
                if i >= j {
                    break;
                }
                s -= l_val[e] * u[i];
            }
            u[k] = s;
        }
        let mut v: Vec<(usize, f64)> = Vec::with_capacity(desc.len() + 1);
        v.push((self.perm[j], 1.0));
        for &k in desc.iter() {
            if u[k] != 0.0 && u[k].is_finite() {
                v.push((self.perm[k], -u[k]));
            }
            u[k] = 0.0;
        }
        v.sort_unstable_by_key(|e| e.0);
        prune(&mut v);
        v
    }
}

/// What the null vectors are worked out in, kept from one dropped row to the next: `u` (zero between them:
/// the nonzeros of a row of `L` lie in its elimination subtree, whose entries each leaves zero), and the
/// subtree's nodes and the search that finds them.
struct NullScratch {
    u: Vec<f64>,
    desc: Vec<usize>,
    dfs: Vec<usize>,
}

/// The children of each node of the elimination tree `etree` (`-1` for a root), as a pointer array and
/// the children in order.
fn children(etree: &[isize]) -> (Vec<usize>, Vec<usize>) {
    let m = etree.len();
    let mut child_ptr = vec![0usize; m + 1];
    for &p in etree {
        if p >= 0 {
            child_ptr[p as usize + 1] += 1;
        }
    }
    for k in 0..m {
        child_ptr[k + 1] += child_ptr[k];
    }
    let mut child = vec![0usize; child_ptr[m]];
    let mut next = child_ptr.clone();
    for (k, &p) in etree.iter().enumerate() {
        if p >= 0 {
            child[next[p as usize]] = k;
            next[p as usize] += 1;
        }
    }
    (child_ptr, child)
}

/// The rows the null-space `basis` makes dependent on earlier rows: its leading indices once in echelon
/// form with respect to the largest original index, ascending.
fn leading_rows(basis: Vec<Vec<(usize, f64)>>) -> Vec<usize> {
    let mut result = Vec::with_capacity(basis.len());
    let mut live: Vec<Vec<(usize, f64)>> = basis.into_iter().filter(|v| !v.is_empty()).collect();
    while !live.is_empty() {
        let top = live.iter().filter_map(|v| v.last().map(|e| e.0)).max().unwrap_or(0);
        let mut piv = usize::MAX;
        let mut best = -1.0f64;
        for (t, v) in live.iter().enumerate() {
            if let Some(&(i, c)) = v.last() {
                if i == top && c.abs() > best {
                    best = c.abs();
                    piv = t;
                }
            }
        }
        if piv == usize::MAX {
            break;
        }
        let p = live.swap_remove(piv);
        let pc = p.last().map(|e| e.1).unwrap_or(1.0);
        result.push(top);
        for v in live.iter_mut() {
            if let Some(&(i, c)) = v.last() {
                if i == top {
                    let f = c / pc;
                    *v = axpy_sparse(v, -f, &p);
                    v.retain(|e| e.0 != top);
                    prune(v);
                }
            }
        }
        live.retain(|v| !v.is_empty());
    }
    result.sort_unstable();
    result
}

/// Drops entries below `1e-9 ×` the largest magnitude (rounding noise of the
/// null-vector computation).
fn prune(v: &mut Vec<(usize, f64)>) {
    let mx = v.iter().fold(0.0f64, |a, e| a.max(e.1.abs()));
    v.retain(|e| e.1.abs() > 1e-9 * mx);
}

/// `a + f·b` for index-sorted sparse vectors.
fn axpy_sparse(a: &[(usize, f64)], f: f64, b: &[(usize, f64)]) -> Vec<(usize, f64)> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut p, mut q) = (0, 0);
    while p < a.len() || q < b.len() {
        if q == b.len() || (p < a.len() && a[p].0 < b[q].0) {
            out.push(a[p]);
            p += 1;
        } else if p == a.len() || b[q].0 < a[p].0 {
            out.push((b[q].0, f * b[q].1));
            q += 1;
        } else {
            out.push((a[p].0, a[p].1 + f * b[q].1));
            p += 1;
            q += 1;
        }
    }
    out
}
