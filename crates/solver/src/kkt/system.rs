//! The true KKT system of one factorization, in original units: the values an engine factorizes, and
//! what every solve is refined and judged against — the residual of the unregularized, unscaled matrix
//! and the largest entry of each of its rows.

use crate::kkt::pattern::KktPattern;
use crate::kkt::refinement::backward_error;
use crate::kkt::{check_values, FactorError, KktValues};
use std::sync::Arc;

/// The values of one KKT system of a fixed pattern, as given (see [`KktValues`]), and the largest entry of
/// each row of the whole matrix, both triangles and the skew part included, measured when a refined solve
/// first needs it (a Newton increment's solve, which is not refined, never does).
#[derive(Debug, Clone)]
pub struct KktSystem {
    pattern: Arc<KktPattern>,
    k: Vec<f64>,
    skew: Vec<f64>,
    has_skew: bool,
    j: Vec<f64>,
    row_norm: Vec<f64>,
    /// Whether `row_norm` is of the values stored.
    rows_measured: bool,
}

impl KktSystem {
    /// Buffers for the values of `pattern`, all zero.
    pub(crate) fn new(pattern: Arc<KktPattern>) -> KktSystem {
        let (k_nnz, j_nnz, size) = (pattern.k_row_idx.len(), pattern.j_row_idx.len(), pattern.n + pattern.m);
        KktSystem {
            k: vec![0.0; k_nnz],
            skew: vec![0.0; k_nnz],
            has_skew: false,
            j: vec![0.0; j_nnz],
            row_norm: vec![0.0; size],
            rows_measured: false,
            pattern,
        }
    }

    /// Takes `values` (the skew part only when `with_skew`: an engine that factorizes the symmetric part
    /// alone is refined against it alone), refusing an array of the wrong length or a value that is not
    /// finite.
    pub(crate) fn store(&mut self, values: KktValues<'_>, with_skew: bool) -> Result<(), FactorError> {
        copy_checked("k_values", values.k, &mut self.k)?;
        copy_checked("j_values", values.j, &mut self.j)?;
        self.has_skew = with_skew && values.k_skew.is_some();
        if let (true, Some(skew)) = (self.has_skew, values.k_skew) {
            copy_checked("k_skew", skew, &mut self.skew)?;
        }
        self.rows_measured = false;
        Ok(())
    }

    /// Measures each row's largest entry, for [`KktSystem::residual`]'s backward error, once per set of
    /// values.
    pub(crate) fn measure_rows(&mut self) {
        if self.rows_measured {
            return;
        }
        let mut row_norm = std::mem::take(&mut self.row_norm);
        row_norm.fill(0.0);
        self.for_each_entry(|r, _, v| row_norm[r] = row_norm[r].max(v.abs()));
        self.row_norm = row_norm;
        self.rows_measured = true;
    }

    /// The pattern.
    pub fn pattern(&self) -> &KktPattern {
        &self.pattern
    }

    /// The number of body coordinates `n`.
    pub fn n(&self) -> usize {
        self.pattern.n
    }

    /// The number of constraint rows `m`.
    pub fn m(&self) -> usize {
        self.pattern.m
    }

    /// The upper triangle of the symmetric part `K`, aligned with the pattern's `k_row_idx`.
    pub fn k(&self) -> &[f64] {
        &self.k
    }

    /// `J`, aligned with the pattern's `j_row_idx`.
    pub fn j(&self) -> &[f64] {
        &self.j
    }

    /// Every stored entry of the whole matrix in original units, `(row, col, value)`, both triangles, the
    /// skew part included when it was stored: column by column, `K`'s entries then `J`'s.
    pub fn for_each_entry(&self, mut f: impl FnMut(usize, usize, f64)) {
        let p = &*self.pattern;
        let n = p.n;
        for c in 0..n {
            for e in p.k_col_ptr[c]..p.k_col_ptr[c + 1] {
                let r = p.k_row_idx[e];
                let (v, s) = (self.k[e], if self.has_skew { self.skew[e] } else { 0.0 });
                f(r, c, v + s);
                if r != c {
                    f(c, r, v - s);
                }
            }
            for e in p.j_col_ptr[c]..p.j_col_ptr[c + 1] {
                let i = n + p.j_row_idx[e];
                f(i, c, self.j[e]);
                f(c, i, self.j[e]);
            }
        }
    }

    /// `r = rhs − A z` in original units, `den = |A|·|z| + |rhs|`; returns the backward error of `z`
    /// ([`backward_error`]: componentwise, rows at rounding level normwise), the rows measured first
    /// ([`KktSystem::measure_rows`]).
    pub(crate) fn residual(&self, rhs: &[f64], z: &[f64], r: &mut [f64], den: &mut [f64]) -> f64 {
        r.copy_from_slice(rhs);
        for (d, b) in den.iter_mut().zip(rhs) {
            *d = b.abs();
        }
        self.for_each_entry(|row, col, v| {
            r[row] -= v * z[col];
            den[row] += (v * z[col]).abs();
        });
        debug_assert!(self.rows_measured, "the rows are measured before a residual is judged");
        backward_error(r, den, &self.row_norm, rhs, z)
    }
}

/// `to ← from`, refusing values of the wrong length or not finite.
fn copy_checked(what: &'static str, from: &[f64], to: &mut [f64]) -> Result<(), FactorError> {
    check_values(what, from, to.len())?;
    to.copy_from_slice(from);
    Ok(())
}
