//! Limit points: a path that stops responding to its load, located by bisection between the last
//! equilibrium and the load that failed.

use super::*;

impl<'m> StaticSolver<'m> {
    /// Classifies a path that cannot be continued past `state` (the last equilibrium; `attempted` is the
    /// load parameter that failed): a limit point when the displacement response to a load increment has
    /// grown far beyond its value at the start of the path (the tangent along the path is losing its
    /// stiffness), then located by [`Self::locate_limit`]; otherwise a plain convergence failure.
    pub(super) fn stuck(
        &mut self,
        state: &State,
        attempted: f64,
        iterations: usize,
        force: f64,
        constraint: f64,
        path: LoadPath,
    ) -> Result<LimitPoint, SolverError> {
        let now = self.load_response(state);
        let limit = match (now, self.initial_response) {
            (None, _) => true,
            (Some(now), Some(start)) => now > LIMIT_RESPONSE_GROWTH * start,
            (Some(_), None) => false,
        };
        if limit {
            Ok(self.locate_limit(state, attempted, path))
        } else {
            Err(SolverError::NoConvergence {
                t: attempted,
                last_converged: Some(state.t),
                iterations,
                force_residual: force,
                constraint_residual: constraint,
            })
        }
    }

    /// Narrows a limit point by bisection on the load parameter, between `state` (the last equilibrium
    /// found) and `failed` (a load parameter at which none was found), to [`LIMIT_POINT_TOLERANCE`] of the
    /// path's range. Each trial is a Newton solve from the last equilibrium found, with the corrector kept
    /// within its predictor's reach: a trial that does not converge so has no equilibrium on this branch.
    pub(super) fn locate_limit(&mut self, state: &State, failed: f64, path: LoadPath) -> LimitPoint {
        let tolerance = LIMIT_POINT_TOLERANCE * (path.end - path.start).abs();
        let mut good = state.clone();
        let mut trial = state.clone();
        let mut found = None;
        let mut beyond = failed;
        while (beyond - good.t).abs() > tolerance {
            let mid = 0.5 * (good.t + beyond);
            if mid == good.t || mid == beyond {
                break;
            }
            trial.clone_from(&good);
            trial.t = mid;
            // From a fresh tangent: near the fold a kept one is the worst guide.
            match self.newton(&mut trial, NewtonStart { guard: true, predicted: 0.0, fresh: true }) {
                Ok(result) => {
                    good.clone_from(&trial);
                    found = Some(result);
                }
                Err(_) => beyond = mid,
            }
        }
        let (iterations, residual) = found.unwrap_or_else(|| {
            self.assemble(&good, None);
            (0, self.residual(&good.lambda))
        });
        LimitPoint { t: good.t, beyond, step: self.step_result(&good, iterations, &residual) }
    }

    /// Solves the tangent system for the load direction at `state`: `[K Jᵀ; J 0] [q_t; λ_t] = [∂Q/∂t; −∂Φ/∂t]`,
    /// leaving `q_t` in `self.work.rhs[..n]`. Returns `‖q_t‖`, or `None` when the tangent is singular.
    pub(super) fn load_response(&mut self, state: &State) -> Option<f64> {
        let n = self.work.assembly.n;
        self.assemble(state, Some(Tangent::Full));
        self.factorize().ok()?;
        self.load_direction_rhs();
        self.work.factor.solve_in_place(&mut self.work.rhs, Accuracy::Refined).ok()?;
        let norm = self.work.rhs[..n].iter().map(|v| v * v).sum::<f64>().sqrt();
        norm.is_finite().then_some(norm)
    }

    /// `rhs = [∂Q/∂t; −∂Φ/∂t]` from the assembled state.
    pub(super) fn load_direction_rhs(&mut self) {
        let n = self.work.assembly.n;
        // A replay's kept tangent keeps the rates assembled with it.
        let (load_rate, phi_rate) = match self.kept_tangent {
            Some(_) => self.work.kept.rates(),
            None => (&self.work.assembly.load_rate[..], &self.work.assembly.phi_rate[..]),
        };
        self.work.rhs[..n].copy_from_slice(load_rate);
        for (k, r) in phi_rate.iter().enumerate() {
            self.work.rhs[n + k] = -r;
        }
    }
}
