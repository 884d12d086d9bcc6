//! Dense LU with partial pivoting of the whole KKT matrix, skew part included: the backend for the small
//! systems of a suspension corner or an axle.
//!
//! # Method
//! 1. **Scaling, when the values ask for it.** A symmetric Ruiz equilibration `S = diag(s)` (every row's
//!    largest entry near 1, powers of two so that scaling is exact) is computed at the first
//!    factorization. Each later one scatters its values with that scaling and measures every row's
//!    largest entry on the way; only when one has left `[1/16, 16]` — values changed by more than an
//!    order of magnitude — are the Ruiz sweeps run again, from the current scaling.
//! 2. **Factorization.** `P Â = L U` of the scaled matrix `Â = S A S` (`A` the true KKT: zero (2,2)
//!    block, no regularization), right-looking, in place in one column-major buffer allocated once.
//!    Partial pivoting is what makes the saddle point's zero diagonal harmless; equilibration makes the
//!    pivot choice compare rows of one size whatever the stiffness ratio.
//! 3. **Solve.** `z = S Û⁻¹ L̂⁻¹ P S b`. For [`Accuracy::Refined`] the componentwise (Oettli–Prager)
//!    backward error of `z` against the true matrix in original units is measured, and a refinement step
//!    is taken only while it is above [`KktOptions::refinement_tol`]; partial-pivoting LU usually meets it
//!    with none. [`Accuracy::Increment`] skips the measurement.
//!
//! # Diagnostics
//! A column whose pivot `|u_kk| ≤ pivot_threshold` (scaled units) makes the factorization fail with
//! [`FactorError::Singular`] naming that body coordinate or constraint row; [`super::AutoKkt`] then
//! factorizes those values with the sparse LDLᵀ, which regularizes. A pivot `≤ suspect_tol` marks the
//! coordinate or row as suspect in the [`FactorReport`], as the sparse path does. An LU does not reveal the
//! inertia: [`FactorReport::negative_body_pivots`] stays 0 and [`FactorReport::rho`] is 0 (no penalty).
//!
//! # Why written here
//! nalgebra's `LU::new` consumes an owned matrix (an allocation per factorization) and keeps its pivots
//! out of reach; faer's dense LU costs 3.3 µs against nalgebra's 2.1 µs at order 27 (`cargo xtask bench
//! --only step-cost`). This kernel reuses one buffer, reads its pivots, and skips the zero multipliers
//! of a sparse KKT column by column.

use crate::kkt::pattern::{validate, KktPattern};
use crate::kkt::scaling::equilibrate;
use crate::kkt::solver::{KktEngine, KktSolver};
use crate::kkt::system::KktSystem;
use crate::kkt::{Accuracy, FactorError, FactorReport, KktOptions};
use std::sync::Arc;

/// A row's largest scaled entry may drift this far from 1 (either way) before the scaling is renewed.
const SCALING_DRIFT: f64 = 16.0;

/// Whether every row's largest scaled entry is within a factor `drift` of 1 (empty rows are left to the
/// factorization to report).
fn within(row_max: &[f64], drift: f64) -> bool {
    row_max.iter().all(|&x| x == 0.0 || (x >= 1.0 / drift && x <= drift))
}

/// The equilibrated dense LU with partial pivoting of a KKT system of fixed pattern: the
/// [`KktSolver`] of a [`PivotedLu`].
pub type DenseLu = KktSolver<PivotedLu>;

/// The engine of [`DenseLu`]: the scaling, the factors and the row exchanges of the last factorization.
#[derive(Debug, Clone)]
pub struct PivotedLu {
    n: usize,
    m: usize,
    options: KktOptions,
    scale: Vec<f64>,
    /// Whether `scale` was equilibrated for values of this pattern (not after `analyze` or `reset`).
    scaled: bool,
    row_max: Vec<f64>,
    /// `L` (unit, below the diagonal) and `U` of the scaled matrix, column-major, order `n + m`.
    lu: Vec<f64>,
    /// Row exchanged with row `k` at elimination step `k`.
    swap: Vec<usize>,
}

impl DenseLu {
    /// Allocates the buffers for the pattern, all but the factor (its order `n + m` squared), which the first
    /// factorization allocates.
    pub fn analyze(pattern: &KktPattern, options: KktOptions) -> Result<Self, FactorError> {
        let (n, m) = (pattern.n, pattern.m);
        let size = n + m;
        validate(pattern, &options)?;
        // The factor itself is allocated at the first factorization: many solvers never factorize (a
        // replay's solves with recorded factors), and its order squared dominates what a solver holds.
        size.checked_mul(size).filter(|&d| d <= (isize::MAX as usize) / 64).ok_or(FactorError::OutOfMemory)?;
        let engine = PivotedLu {
            n,
            m,
            options: options.clone(),
            scale: vec![1.0; size],
            scaled: false,
            row_max: vec![0.0; size],
            lu: Vec::new(),
            swap: vec![0; size],
        };
        Ok(KktSolver::new(engine, Arc::new(pattern.clone()), options, 1))
    }

    /// The pattern this factor was analysed for (the sparse fallback analyses it on first need).
    pub fn pattern(&self) -> KktPattern {
        self.system().pattern().clone()
    }

    /// The symmetric scaling in use (powers of two).
    pub fn scaling(&self) -> &[f64] {
        &self.engine().scale
    }

    /// The factors of the last factorization, apart from this workspace (`None` before one succeeded).
    pub fn factors(&self) -> Option<LuFactors> {
        let lu = self.engine();
        self.factorized().then(|| LuFactors { lu: lu.lu.clone(), swap: lu.swap.clone(), scale: lu.scale.clone() })
    }
}

impl PivotedLu {
    /// Ruiz sweeps from the current scaling (see [`equilibrate`]) on the whole matrix, skew part included.
    fn equilibrate(&mut self, system: &KktSystem) {
        equilibrate(&mut self.scale, &mut self.row_max, self.options.scaling_iterations.max(1), |s, rm| {
            system.for_each_entry(|r, c, v| {
                let a = v.abs() * s[r] * s[c];
                if a > rm[r] {
                    rm[r] = a;
                }
            });
        });
    }

    /// Scatters the scaled values into the factor buffer, on the same pass measuring each row's largest
    /// scaled entry into `row_max`; returns whether they are still within [`SCALING_DRIFT`] of 1.
    fn scatter(&mut self, system: &KktSystem) -> bool {
        let size = self.n + self.m;
        let (lu, row_max, s) = (&mut self.lu, &mut self.row_max, &self.scale);
        lu.fill(0.0);
        row_max.fill(0.0);
        system.for_each_entry(|r, c, v| {
            let scaled = v * s[r] * s[c];
            lu[c * size + r] += scaled;
            row_max[r] = row_max[r].max(scaled.abs());
        });
        within(row_max, SCALING_DRIFT)
    }
    /// `P Â = L U` in place; returns the first column whose pivot is at or below `singular` in magnitude,
    /// if any (the factorization stops there).
    fn factor_in_place(&mut self, singular: f64) -> Option<usize> {
        let size = self.n + self.m;
        let a = &mut self.lu;
        for k in 0..size {
            let col = &a[k * size..(k + 1) * size];
            let (mut p, mut big) = (k, 0.0f64);
            for (i, v) in col.iter().enumerate().skip(k) {
                if v.abs() > big {
                    big = v.abs();
                    p = i;
                }
            }
            if big <= singular {
                return Some(k);
            }
            self.swap[k] = p;
            if p != k {
                for c in 0..size {
                    a.swap(c * size + k, c * size + p);
                }
            }
            let (left, right) = a.split_at_mut((k + 1) * size);
            let pivot_col = &mut left[k * size..];
            let inv = 1.0 / pivot_col[k];
            for v in &mut pivot_col[k + 1..] {
                *v *= inv;
            }
            let below = &pivot_col[k + 1..];
            for col in right.chunks_exact_mut(size) {
                let f = col[k];
                if f != 0.0 {
                    for (x, l) in col[k + 1..].iter_mut().zip(below) {
                        *x -= f * l;
                    }
                }
            }
        }
        None
    }

    /// `t ← Â⁻¹ t` with the factors (scaled units).
    fn apply_factors(lu: &[f64], swap: &[usize], t: &mut [f64]) {
        let size = t.len();
        for (k, &p) in swap.iter().enumerate() {
            t.swap(k, p);
        }
        for k in 0..size {
            let v = t[k];
            if v != 0.0 {
                for (x, l) in t[k + 1..].iter_mut().zip(&lu[k * size + k + 1..(k + 1) * size]) {
                    *x -= l * v;
                }
            }
        }
        for k in (0..size).rev() {
            t[k] /= lu[k * size + k];
            let v = t[k];
            if v != 0.0 {
                for (x, u) in t[..k].iter_mut().zip(&lu[k * size..k * size + k]) {
                    *x -= u * v;
                }
            }
        }
    }
}

/// `t ← A⁻¹ t` in original units from the factors of `Â = S A S`: `S Â⁻¹ S t`.
fn apply_inverse_scaled(lu: &[f64], swap: &[usize], scale: &[f64], t: &mut [f64]) {
    for (v, s) in t.iter_mut().zip(scale) {
        *v *= s;
    }
    PivotedLu::apply_factors(lu, swap, t);
    for (v, s) in t.iter_mut().zip(scale) {
        *v *= s;
    }
}

/// The factors of one factorization of a [`DenseLu`], kept apart from its workspace: solves with them
/// need no workspace and no `&mut`, so one factorization serves any number of later solves from any
/// thread (a recorded equilibrium's tangent, solved with by every replay of a run, [`crate::replay`]).
#[derive(Debug, Clone)]
pub struct LuFactors {
    lu: Vec<f64>,
    swap: Vec<usize>,
    scale: Vec<f64>,
}

impl LuFactors {
    /// `rhs ← A⁻¹ rhs` (one application of the factors, no refinement: a Newton increment's accuracy).
    pub fn solve_in_place(&self, rhs: &mut [f64]) {
        apply_inverse_scaled(&self.lu, &self.swap, &self.scale, rhs);
    }

    /// The order `n + m` of the system.
    pub fn order(&self) -> usize {
        self.swap.len()
    }
}

impl KktEngine for PivotedLu {
    fn name(&self) -> &'static str {
        "dense LU"
    }

    fn solves_skew(&self) -> bool {
        true
    }

    fn factorize(&mut self, system: &KktSystem) -> Result<FactorReport, FactorError> {
        let dense = (self.n + self.m).pow(2);
        if self.lu.len() != dense {
            self.lu.try_reserve_exact(dense).map_err(|_| FactorError::OutOfMemory)?;
            self.lu.resize(dense, 0.0);
        }
        if !self.scaled {
            self.equilibrate(system);
            self.scaled = true;
        }
        // The scatter measures the drift; only values that moved an order of magnitude are equilibrated
        // again and scattered anew.
        if !self.scatter(system) {
            self.equilibrate(system);
            self.scatter(system);
        }
        let n = self.n;
        if let Some(k) = self.factor_in_place(self.options.pivot_threshold) {
            return Err(if k < n {
                FactorError::Singular { kind: "body coordinate", index: k }
            } else {
                FactorError::Singular { kind: "constraint row", index: k - n }
            });
        }
        let size = n + self.m;
        let mut report = FactorReport::default();
        let (mut bmin, mut bmax, mut cmin, mut cmax) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
        for k in 0..size {
            let d = self.lu[k * size + k].abs();
            let suspect = d <= self.options.suspect_tol;
            if k < n {
                bmin = bmin.min(d);
                bmax = bmax.max(d);
                if suspect {
                    report.suspect_body_dofs.push(k);
                }
            } else {
                cmin = cmin.min(d);
                cmax = cmax.max(d);
                if suspect {
                    report.suspect_constraint_rows.push(k - n);
                }
            }
        }
        report.min_body_pivot = if n > 0 { bmin } else { 0.0 };
        report.max_body_pivot = bmax;
        report.min_constraint_pivot = if self.m > 0 { cmin } else { 0.0 };
        report.max_constraint_pivot = cmax;
        Ok(report)
    }

    /// `out = A⁻¹ src` in original units: `S Â⁻¹ S src`.
    fn apply_inverse(&mut self, src: &[f64], out: &mut [f64]) {
        out.copy_from_slice(src);
        apply_inverse_scaled(&self.lu, &self.swap, &self.scale, out);
    }

    /// A partial-pivoting LU usually meets the refinement tolerance at once: only a solve asked to be
    /// accurate measures it ([`Accuracy::Refined`]); a Newton increment is one application.
    fn refines(&self, accuracy: Accuracy) -> bool {
        accuracy == Accuracy::Refined
    }

    fn reset(&mut self) {
        self.scale.fill(1.0);
        self.scaled = false;
    }
}
