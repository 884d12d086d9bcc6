//! Picks the backend for a pattern by its order, and falls back to the sparse LDLᵀ where the dense LU
//! meets a singular matrix.

use crate::kkt::dense_lu::DenseLu;
use crate::kkt::pattern::KktPattern;
use crate::kkt::sparse_ldlt::KktFactor;
use crate::kkt::{Accuracy, FactorCounters, FactorError, FactorReport, KktBackend, KktOptions, KktValues, SolveReport};

/// Largest KKT order `n + m` that [`BackendChoice::Auto`] gives to the dense LU.
///
/// Measured by `cargo xtask bench --only step-cost` (table "Dense LU against sparse LDLᵀ by order"):
/// factorization + solve of the full tangent of the bench's chain of suspension-like cells. The dense
/// LU takes 2.7 µs at order 20, 17 µs at 60 and 30 µs at 80; the sparse LDLᵀ, timed on the symmetric part
/// alone, 5.0, 18 and 28 µs (ratios 0.53, 0.92, 1.04). A chain is the sparse path's best case (its factor
/// is banded), and a skew part costs the sparse path GMRES iterations on top that the dense LU does not
/// need, so the limit sits at the crossover of the bare factorizations, order 80. A MacPherson corner is
/// 27, a double wishbone 25, the shipped four-link axle 60.
pub const DENSE_MAX_ORDER: usize = 80;

/// Which backend a solver uses. Every choice is held against the dense pivoted reference
/// (`crates/solver/tests/kkt_backend.rs` walks them all, by `strum::IntoEnumIterator`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, strum::EnumIter)]
pub enum BackendChoice {
    /// The dense LU up to [`DENSE_MAX_ORDER`], the sparse LDLᵀ above.
    #[default]
    Auto,
    /// The dense LU at any order (its memory grows as the order squared).
    Dense,
    /// The sparse LDLᵀ at any order.
    Sparse,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
enum Active {
    #[default]
    Dense,
    Sparse,
}

/// The backend [`BackendChoice`] picked, with the sparse LDLᵀ behind a dense LU as its fallback. (Its
/// default has neither: what a spent solver's workspace holds, see `SolverWorkspace`.)
#[derive(Debug, Default)]
pub struct AutoKkt {
    options: KktOptions,
    dense: Option<DenseLu>,
    sparse: Option<KktFactor>,
    active: Active,
}

impl AutoKkt {
    /// Analyses `pattern` for the backend `choice` picks.
    pub fn analyze(pattern: &KktPattern, options: KktOptions, choice: BackendChoice) -> Result<Self, FactorError> {
        let dense = match choice {
            BackendChoice::Auto => pattern.n + pattern.m <= DENSE_MAX_ORDER,
            BackendChoice::Dense => true,
            BackendChoice::Sparse => false,
        };
        if dense {
            Ok(AutoKkt {
                dense: Some(DenseLu::analyze(pattern, options.clone())?),
                options,
                sparse: None,
                active: Active::Dense,
            })
        } else {
            Ok(AutoKkt {
                sparse: Some(KktFactor::analyze(pattern, options.clone())?),
                options,
                dense: None,
                active: Active::Sparse,
            })
        }
    }

    /// A dense LU of the same pattern, unfactorized, when this backend has one: a second factorization
    /// beside the solver's own (a recording's, [`crate::replay`]), which leaves the solver's as it was.
    pub fn dense_twin(&self) -> Option<DenseLu> {
        self.dense.clone().map(|mut d| {
            d.reset();
            d
        })
    }

    /// The sparse LDLᵀ, analysed on first need from the dense LU's pattern.
    fn sparse(&mut self) -> Result<&mut KktFactor, FactorError> {
        if self.sparse.is_none() {
            let pattern = self.dense.as_ref().ok_or(FactorError::NotFactorized)?.pattern();
            self.sparse = Some(KktFactor::analyze(&pattern, self.options.clone())?);
        }
        self.sparse.as_mut().ok_or(FactorError::NotFactorized)
    }

    fn active(&mut self) -> Result<&mut dyn KktBackend, FactorError> {
        match self.active {
            Active::Dense => self.dense.as_mut().map(|d| d as &mut dyn KktBackend),
            Active::Sparse => self.sparse.as_mut().map(|s| s as &mut dyn KktBackend),
        }
        .ok_or(FactorError::NotFactorized)
    }
}

impl KktBackend for AutoKkt {
    fn name(&self) -> &'static str {
        match self.active {
            Active::Dense => "dense LU",
            Active::Sparse => "sparse LDLᵀ",
        }
    }

    fn solves_skew(&self) -> bool {
        self.active == Active::Dense
    }

    fn factorize(&mut self, values: KktValues<'_>) -> Result<FactorReport, FactorError> {
        if let Some(dense) = self.dense.as_mut() {
            match dense.factorize(values) {
                Ok(report) => {
                    self.active = Active::Dense;
                    return Ok(report);
                }
                // The sparse path regularizes a singular pivot and names what it suspects.
                Err(FactorError::Singular { .. }) => {}
                Err(e) => return Err(e),
            }
        }
        self.active = Active::Sparse;
        KktBackend::factorize(self.sparse()?, values)
    }

    fn solve_in_place(&mut self, rhs: &mut [f64], accuracy: Accuracy) -> Result<SolveReport, FactorError> {
        self.active()?.solve_in_place(rhs, accuracy)
    }

    fn counters(&self) -> FactorCounters {
        let mut sum = FactorCounters::default();
        for c in [self.dense.as_ref().map(|d| d.counters()), self.sparse.as_ref().map(KktFactor::counters)]
            .into_iter()
            .flatten()
        {
            sum.symbolic_analyses += c.symbolic_analyses;
            sum.numeric_factorizations += c.numeric_factorizations;
            sum.solves += c.solves;
            sum.refinement_steps += c.refinement_steps;
        }
        sum
    }

    fn reset(&mut self) {
        if let Some(d) = self.dense.as_mut() {
            d.reset();
        }
        if let Some(s) = self.sparse.as_mut() {
            KktBackend::reset(s);
        }
        self.active = if self.dense.is_some() { Active::Dense } else { Active::Sparse };
    }
}
