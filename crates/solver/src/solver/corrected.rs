//! Corrected steps: each load step predicted, then Newton (or chord iterations on a kept
//! factorization) on the exact residual to the tolerances, the step cut where it does not converge.

use super::*;

impl<'m> StaticSolver<'m> {
    pub(super) fn corrected_steps(
        &mut self,
        state: &mut State,
        path: LoadPath,
        dt: f64,
        steps: &mut Vec<StepResult>,
    ) -> Result<Option<LimitPoint>, SolverError> {
        // Where a refused sub-step goes back to; `clone_from` reuses its storage, so no step allocates.
        let mut saved = state.clone();
        for step in 1..=path.steps {
            let target = path.start + dt * step as f64;
            match self.corrected_step(state, target, dt, &mut saved)? {
                StepOutcome::Reached { iterations, residual } => {
                    steps.push(self.step_result(state, iterations, &residual))
                }
                StepOutcome::Stuck { attempted, iterations, force, constraint } => {
                    return self.stuck(state, attempted, iterations, force, constraint, path).map(Some);
                }
            }
        }
        Ok(None)
    }

    /// Brings `state`, an equilibrium, to the equilibrium at `target` by Newton steps of at most `dt`,
    /// halving a step that does not converge (at most [`SolverOptions::max_step_cuts`] times in all).
    pub(super) fn corrected_step(
        &mut self,
        state: &mut State,
        target: f64,
        dt: f64,
        saved: &mut State,
    ) -> Result<StepOutcome, SolverError> {
        let mut sub = dt;
        let mut cuts = 0;
        let mut iterations = 0;
        loop {
            saved.clone_from(state);
            let next = if (target - state.t).abs() <= sub.abs() * (1.0 + 1e-12) { target } else { state.t + sub };
            let predicted = self.predict(state, next - state.t);
            state.t = next;
            match self.newton(state, NewtonStart { guard: true, predicted: predicted.unwrap_or(0.0), fresh: false }) {
                Ok((it, residual)) => {
                    iterations += it;
                    self.remember_step(predicted.is_some(), next - saved.t, next);
                    if next == target {
                        return Ok(StepOutcome::Reached { iterations, residual });
                    }
                }
                Err(SolverError::NoConvergence { iterations: it, force_residual, constraint_residual, .. }) => {
                    state.clone_from(saved);
                    // The shorter step starts from the last equilibrium without extrapolating: a step
                    // that failed may have failed because the path turned.
                    self.work.forget_path();
                    cuts += 1;
                    if cuts > self.options.max_step_cuts {
                        return Ok(StepOutcome::Stuck {
                            attempted: next,
                            iterations: it,
                            force: force_residual,
                            constraint: constraint_residual,
                        });
                    }
                    sub *= 0.5;
                }
                Err(e) => return Err(e),
            }
        }
    }
}
