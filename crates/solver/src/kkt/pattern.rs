//! The fixed sparsity of one KKT system and what is done with it once: the checks of its compressed
//! columns, row-wise copies and assembled patterns, and the AMD ordering.

use crate::kkt::{alloc_err, check_options, FactorError, KktOptions};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;
use faer::sparse::SymbolicSparseColMat;

/// Fixed sparsity of one KKT system: K's upper triangle (incl. diagonal) and J,
/// both column-compressed (CSC).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct KktPattern {
    /// Number of body coordinates (rows/columns of `K`, columns of `J`).
    pub n: usize,
    /// Number of constraint rows (rows of `J`).
    pub m: usize,
    /// Column pointers of the upper triangle of `K` (length `n + 1`).
    pub k_col_ptr: Vec<usize>,
    /// Row indices of the upper triangle of `K`, sorted strictly increasing per
    /// column, all `≤` the column index; every diagonal entry must be present
    /// (store an explicit zero for a structurally zero diagonal).
    pub k_row_idx: Vec<usize>,
    /// Column pointers of `J` (m×n, length `n + 1`).
    pub j_col_ptr: Vec<usize>,
    /// Row indices of `J`, sorted strictly increasing per column, `< m`.
    pub j_row_idx: Vec<usize>,
}

pub(crate) fn validate_col_ptr(
    matrix: &'static str,
    ncols: usize,
    col_ptr: &[usize],
    nnz: usize,
) -> Result<(), FactorError> {
    if col_ptr.len() != ncols + 1 {
        return Err(FactorError::InvalidPattern {
            matrix,
            col: col_ptr.len(),
            reason: format!("column pointer has length {}, expected {}", col_ptr.len(), ncols + 1),
        });
    }
    if col_ptr[0] != 0 {
        return Err(FactorError::InvalidPattern {
            matrix,
            col: 0,
            reason: format!("column pointer starts at {} instead of 0", col_ptr[0]),
        });
    }
    for c in 0..ncols {
        if col_ptr[c + 1] < col_ptr[c] {
            return Err(FactorError::InvalidPattern { matrix, col: c, reason: "column pointer decreases".into() });
        }
    }
    if col_ptr[ncols] != nnz {
        return Err(FactorError::InvalidPattern {
            matrix,
            col: ncols,
            reason: format!("column pointer ends at {} but {} row indices were given", col_ptr[ncols], nnz),
        });
    }
    Ok(())
}

pub(crate) fn validate_rows(
    matrix: &'static str,
    ncols: usize,
    nrows: usize,
    col_ptr: &[usize],
    row_idx: &[usize],
    upper: bool,
) -> Result<(), FactorError> {
    for c in 0..ncols {
        let rows = &row_idx[col_ptr[c]..col_ptr[c + 1]];
        for (t, &r) in rows.iter().enumerate() {
            let limit = if upper { c + 1 } else { nrows };
            if r >= limit {
                return Err(FactorError::InvalidPattern {
                    matrix,
                    col: c,
                    reason: if upper {
                        format!("row index {r} is below the diagonal (only the upper triangle may be stored)")
                    } else {
                        format!("row index {r} is out of range (number of rows is {nrows})")
                    },
                });
            }
            if t > 0 && rows[t - 1] >= r {
                return Err(FactorError::InvalidPattern {
                    matrix,
                    col: c,
                    reason: format!("row indices not strictly increasing ({} then {r})", rows[t - 1]),
                });
            }
        }
        if upper && rows.last() != Some(&c) {
            return Err(FactorError::MissingDiagonal { col: c });
        }
    }
    Ok(())
}

pub(crate) fn validate_j(m: usize, n: usize, col_ptr: &[usize], row_idx: &[usize]) -> Result<(), FactorError> {
    validate_col_ptr("J", n, col_ptr, row_idx.len())?;
    validate_rows("J", n, m, col_ptr, row_idx, false)
}

/// Checks a pattern and options as every KKT backend needs them: CSC arrays well formed, `K` upper with
/// every diagonal stored, options in range.
pub(crate) fn validate(pattern: &KktPattern, options: &KktOptions) -> Result<(), FactorError> {
    check_options(options)?;
    let (n, m) = (pattern.n, pattern.m);
    validate_col_ptr("K", n, &pattern.k_col_ptr, pattern.k_row_idx.len())?;
    validate_rows("K", n, n, &pattern.k_col_ptr, &pattern.k_row_idx, true)?;
    validate_j(m, n, &pattern.j_col_ptr, &pattern.j_row_idx)
}

/// Row-wise copy of a CSC pattern: (row_ptr, col, source position).
pub(crate) fn transpose_pattern(
    nrows: usize,
    ncols: usize,
    col_ptr: &[usize],
    row_idx: &[usize],
) -> (Vec<usize>, Vec<usize>, Vec<usize>) {
    let nnz = row_idx.len();
    let mut ptr = vec![0usize; nrows + 1];
    for &r in row_idx {
        ptr[r + 1] += 1;
    }
    for i in 0..nrows {
        ptr[i + 1] += ptr[i];
    }
    let mut next = ptr.clone();
    let mut col = vec![0usize; nnz];
    let mut src = vec![0usize; nnz];
    for c in 0..ncols {
        for e in col_ptr[c]..col_ptr[c + 1] {
            let r = row_idx[e];
            let q = next[r];
            next[r] += 1;
            col[q] = c;
            src[q] = e;
        }
    }
    (ptr, col, src)
}

/// Builds a CSC pattern (dimension `dim`) from `(row, col)` entries already in
/// the desired triangle; returns (col_ptr, row_idx, slot of every entry).
pub(crate) fn build_csc(dim: usize, entries: &[(usize, usize)]) -> (Vec<usize>, Vec<usize>, Vec<usize>) {
    let mut ptr = vec![0usize; dim + 1];
    for &(_, c) in entries {
        ptr[c + 1] += 1;
    }
    for c in 0..dim {
        ptr[c + 1] += ptr[c];
    }
    let mut next = ptr.clone();
    let mut tagged = vec![(0usize, 0usize); entries.len()];
    for (id, &(r, c)) in entries.iter().enumerate() {
        tagged[next[c]] = (r, id);
        next[c] += 1;
    }
    for c in 0..dim {
        tagged[ptr[c]..ptr[c + 1]].sort_unstable();
    }
    let mut row_idx = vec![0usize; entries.len()];
    let mut slot = vec![0usize; entries.len()];
    for (q, &(r, id)) in tagged.iter().enumerate() {
        row_idx[q] = r;
        slot[id] = q;
    }
    (ptr, row_idx, slot)
}

/// AMD ordering of a sorted upper-triangular pattern. Returns (perm, perm_inv).
pub(crate) fn amd_order(
    dim: usize,
    col_ptr: &[usize],
    row_idx: &[usize],
) -> Result<(Vec<usize>, Vec<usize>), FactorError> {
    let mut perm = vec![0usize; dim];
    let mut perm_inv = vec![0usize; dim];
    if dim == 0 {
        return Ok((perm, perm_inv));
    }
    let sym = SymbolicSparseColMat::<usize>::new_checked(dim, dim, col_ptr.to_vec(), None, row_idx.to_vec());
    let mut mem = MemBuffer::try_new(amd::order_scratch::<usize>(dim, row_idx.len())).map_err(alloc_err)?;
    amd::order(&mut perm, &mut perm_inv, sym.as_ref(), amd::Control::default(), MemStack::new(&mut mem))
        .map_err(|e| FactorError::Analysis(format!("{e:?}")))?;
    Ok((perm, perm_inv))
}
