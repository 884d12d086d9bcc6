//! The sparse quasi-definite LDLᵀ ([`KktFactor`]) as a [`KktBackend`]: see [`crate::kkt_factor`] for the
//! method. It factorizes the symmetric part only; a skew part is left to the caller.

use super::{Accuracy, KktBackend, KktValues};
use crate::kkt_factor::{FactorCounters, FactorError, FactorReport, KktFactor, SolveReport};

impl KktBackend for KktFactor {
    fn name(&self) -> &'static str {
        "sparse LDLᵀ"
    }

    fn solves_skew(&self) -> bool {
        false
    }

    fn factorize(&mut self, values: KktValues<'_>) -> Result<FactorReport, FactorError> {
        KktFactor::factorize(self, values.k, values.j)
    }

    /// Both accuracies refine: the solution of the regularized form is `O(ε)` off the true one until
    /// refined, and on stiff models that costs Newton more iterations than refinement costs solves.
    fn solve_in_place(&mut self, rhs: &mut [f64], _accuracy: Accuracy) -> Result<SolveReport, FactorError> {
        KktFactor::solve_in_place(self, rhs)
    }

    fn counters(&self) -> FactorCounters {
        KktFactor::counters(self)
    }

    fn reset(&mut self) {
        KktFactor::reset(self)
    }
}
