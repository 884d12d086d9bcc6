//! One KKT solver over small factorization engines: the solver keeps the true system, checks what it is
//! given, solves, refines against the true matrix and counts; an engine only factorizes the values its
//! own way (scaled, regularized, permuted as it likes) and applies the inverse of what it factorized. A
//! new engine is one file implementing [`KktEngine`]; [`KktSolver`] makes it a [`KktBackend`].

use crate::kkt::pattern::KktPattern;
use crate::kkt::refinement::{Factored, Refinement};
use crate::kkt::system::KktSystem;
use crate::kkt::{
    check_values, max_abs, Accuracy, FactorCounters, FactorError, FactorReport, KktBackend, KktOptions, KktValues,
    SolveReport,
};
use std::sync::Arc;

/// A factorization of the KKT system, with no refinement or bookkeeping of its own: what [`KktSolver`]
/// needs of it.
pub trait KktEngine: std::fmt::Debug + Send {
    /// What it is, for reports ("dense LU", "sparse LDLᵀ").
    fn name(&self) -> &'static str;

    /// Whether it factorizes the skew part too, so that a solve solves the non-symmetric system directly.
    fn solves_skew(&self) -> bool;

    /// Factorizes the values of `system` (checked and stored by the solver); the report of its pivots.
    fn factorize(&mut self, system: &KktSystem) -> Result<FactorReport, FactorError>;

    /// `out ← A⁻¹ src` in original units, by the last factorization (with whatever scaling and
    /// regularization it carries).
    fn apply_inverse(&mut self, src: &[f64], out: &mut [f64]);

    /// Whether a solve asked for at `accuracy` is refined against the true system.
    fn refines(&self, accuracy: Accuracy) -> bool;

    /// Forgets what the values left (the scaling), keeping the analysis and the buffers.
    fn reset(&mut self);
}

/// A KKT backend made of an engine: the true system of the last factorization, the solve with its
/// iterative refinement and backward error, and the work counters, written once for every engine.
#[derive(Debug, Clone)]
pub struct KktSolver<E> {
    engine: E,
    system: KktSystem,
    options: KktOptions,
    // Solve workspaces.
    rhs0: Vec<f64>,
    z: Vec<f64>,
    refinement: Refinement,
    factorized: bool,
    counters: FactorCounters,
}

impl<E: KktEngine> KktSolver<E> {
    /// The solver of `engine`, analysed for `pattern` with `options`; `analyses` is what its counters
    /// start with (1 where the engine's analysis was made for it, 0 where it shares another's).
    pub(crate) fn new(engine: E, pattern: Arc<KktPattern>, options: KktOptions, analyses: u64) -> Self {
        let size = pattern.n + pattern.m;
        KktSolver {
            engine,
            system: KktSystem::new(pattern),
            options,
            rhs0: vec![0.0; size],
            z: vec![0.0; size],
            refinement: Refinement::new(size),
            factorized: false,
            counters: FactorCounters { symbolic_analyses: analyses, ..FactorCounters::default() },
        }
    }

    /// The engine.
    pub fn engine(&self) -> &E {
        &self.engine
    }

    /// The true system of the last factorization.
    pub fn system(&self) -> &KktSystem {
        &self.system
    }

    /// Number of body coordinates `n`.
    pub fn n(&self) -> usize {
        self.system.n()
    }

    /// Number of constraint rows `m`.
    pub fn m(&self) -> usize {
        self.system.m()
    }

    /// The options it was analysed with.
    pub fn options(&self) -> &KktOptions {
        &self.options
    }

    /// Whether the last factorization succeeded (a solve is possible).
    pub(crate) fn factorized(&self) -> bool {
        self.factorized
    }
}

/// The engine and the true system as refinement sees them: the engine's inverse, the true residual.
struct Refining<'a, E> {
    engine: &'a mut E,
    system: &'a KktSystem,
    rhs: &'a [f64],
}

impl<E: KktEngine> Factored for Refining<'_, E> {
    fn apply_inverse(&mut self, src: &[f64], out: &mut [f64]) {
        self.engine.apply_inverse(src, out);
    }

    fn residual(&self, z: &[f64], r: &mut [f64], den: &mut [f64]) -> f64 {
        self.system.residual(self.rhs, z, r, den)
    }
}

impl<E: KktEngine> KktBackend for KktSolver<E> {
    fn name(&self) -> &'static str {
        self.engine.name()
    }

    fn solves_skew(&self) -> bool {
        self.engine.solves_skew()
    }

    fn factorize(&mut self, values: KktValues<'_>) -> Result<FactorReport, FactorError> {
        self.factorized = false;
        self.system.store(values, self.engine.solves_skew())?;
        let report = self.engine.factorize(&self.system)?;
        self.factorized = true;
        self.counters.numeric_factorizations += 1;
        Ok(report)
    }

    /// On error `rhs` is left unchanged.
    fn solve_in_place(&mut self, rhs: &mut [f64], accuracy: Accuracy) -> Result<SolveReport, FactorError> {
        if !self.factorized {
            return Err(FactorError::NotFactorized);
        }
        check_values("rhs", rhs, self.rhs0.len())?;
        self.rhs0.copy_from_slice(rhs);
        let mut z = std::mem::take(&mut self.z);
        self.engine.apply_inverse(rhs, &mut z);
        if let Some(index) = z.iter().position(|v| !v.is_finite()) {
            self.z = z;
            return Err(FactorError::NonFiniteSolution { index });
        }
        let mut report = SolveReport::default();
        if self.engine.refines(accuracy) {
            self.system.measure_rows();
            let n = self.system.n();
            let mut refining = Refining { engine: &mut self.engine, system: &self.system, rhs: &self.rhs0 };
            let (steps, omega) =
                self.refinement.refine(&mut refining, &mut z, self.options.max_refinement, self.options.refinement_tol);
            let r = self.refinement.residual();
            report = SolveReport {
                refinement_steps: steps,
                residual_x: max_abs(&r[..n]),
                residual_y: max_abs(&r[n..]),
                backward_error: omega,
                converged: omega <= self.options.refinement_tol,
                measured: true,
            };
            self.counters.refinement_steps += steps as u64;
        }
        rhs.copy_from_slice(&z);
        self.z = z;
        self.counters.solves += 1;
        Ok(report)
    }

    fn counters(&self) -> FactorCounters {
        self.counters
    }

    fn reset(&mut self) {
        self.engine.reset();
        self.factorized = false;
        self.counters = FactorCounters::default();
    }
}
