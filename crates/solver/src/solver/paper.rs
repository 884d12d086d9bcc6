//! The paper's linear recurrence (eq. 9): one factorization a step, the loads accumulated linearly,
//! and the exact walk under a paper sweep that tells a limit point from a paper step's drift.

use super::*;

impl<'m> StaticSolver<'m> {
    /// One paper step's increment `[Δq; λⁿ]` into `rhs` from `state`, with what tells a fold: see
    /// [`PaperStep`].
    pub(super) fn paper_increment(
        &mut self,
        state: &State,
        dt: f64,
        carried: &[f64],
    ) -> Result<PaperStep, SolverError> {
        let n = self.work.assembly.n;
        let m = self.work.assembly.m();
        self.assemble(state, Some(Tangent::Paper));
        self.factorize()?;
        for c in 0..n {
            self.work.rhs[c] = dt * self.work.assembly.load_rate[c] + carried[c];
        }
        for k in 0..m {
            self.work.rhs[n + k] = -dt * self.work.assembly.phi_rate[k];
        }
        // The Jacobian at qⁿ carries λⁿ into the next step. The tangent's non-symmetric part (the load
        // stiffness of world-fixed loads, preloads turning with their lever arms) is solved for too:
        // without it the walk converges, as the step shrinks, to a different path.
        self.solve_with_skew(Accuracy::Refined)?;
        let response = if dt == 0.0 { 0.0 } else { norm2(&self.work.rhs[..n]) / dt.abs() };
        let largest = |v: &[f64]| v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        Ok(PaperStep {
            response,
            load_change: dt.abs() * largest(&self.work.assembly.load_rate),
            drive_change: dt.abs() * largest(&self.work.assembly.phi_rate),
        })
    }

    pub(super) fn paper_steps(
        &mut self,
        state: &mut State,
        path: LoadPath,
        dt: f64,
        steps: &mut Vec<StepResult>,
    ) -> Result<Option<LimitPoint>, SolverError> {
        let n = self.work.assembly.n;
        let m = self.work.assembly.m();
        // Φ_q(qⁿ⁻¹)ᵀ λⁿ⁻¹: the constraint force carried from the previous step.
        let mut carried = vec![0.0; n];
        self.assemble(state, None);
        self.work.assembly.jt_times(&state.lambda, &mut carried);
        // What a step's response is compared with to suspect a fold: the first step's (raised past a step
        // that was checked and found no fold).
        let mut reference: Option<f64> = None;
        // The exact path, walked only as far as a suspect step needs (`None` once it cannot be walked).
        let mut exact = Some(self.state_of(&steps[0]));
        for step in 1..=path.steps {
            let paper = self.paper_increment(state, dt, &carried)?;
            if self.work.rhs.iter().any(|v| !v.is_finite()) {
                return Err(self.non_finite("paper-mode step", state.t + dt));
            }
            let response = *reference.get_or_insert(paper.response);
            let before = &steps[steps.len() - 1];
            let previous = (before.force_residual, before.constraint_residual);
            state.lambda.copy_from_slice(&self.work.rhs[n..n + m]);
            self.work.assembly.jt_times(&state.lambda, &mut carried);
            Self::apply(&mut state.poses, &self.work.rhs[..n], 1.0);
            state.t = path.start + dt * step as f64;
            // Report the true residual of the paper solution (drift), without correcting it.
            self.assemble(state, None);
            let r = self.finite_residual(state, "paper-mode step")?;
            // A fold ahead or behind: the response grew tenfold, or the step left its linearisation (its drift
            // grew by more than the change of load or travel it made: a step that jumped across a fold to
            // another branch). (The paper tangent's negative pivots tell nothing: it lacks the joint
            // reactions' geometric stiffness, and a stable lever under a world-fixed load has some.)
            let suspect = paper.response > LIMIT_RESPONSE_GROWTH * response
                || (paper.load_change > 0.0 && r.force - previous.0 > paper.load_change)
                || (paper.drive_change > 0.0 && r.constraint - previous.1 > paper.drive_change);
            if suspect {
                if let Some(mut at) = exact.take() {
                    match self.exact_walk(&mut at, steps, state.t, path, dt)? {
                        ExactWalk::Reached => {
                            exact = Some(at);
                            reference = Some(paper.response);
                        }
                        ExactWalk::Limit(limit) => return Ok(Some(limit)),
                        // Paper mode never promised the exact path: it goes on without the check.
                        ExactWalk::Failed => {}
                    }
                }
            }
            steps.push(self.step_result(state, 0, &r));
        }
        Ok(None)
    }

    /// Walks the exact path of a paper-mode sweep from `at` (an equilibrium on it) to `target` in corrected
    /// steps of `dt`, to check a suspected fold.
    pub(super) fn exact_walk(
        &mut self,
        at: &mut State,
        steps: &[StepResult],
        target: f64,
        path: LoadPath,
        dt: f64,
    ) -> Result<ExactWalk, SolverError> {
        if self.initial_response.is_none() {
            let first = self.state_of(&steps[0]);
            self.initial_response = self.load_response(&first);
        }
        let mut saved = at.clone();
        self.work.forget_path();
        while (target - at.t) * dt.signum() > 0.0 {
            let next = if (target - at.t).abs() <= dt.abs() * (1.0 + 1e-12) { target } else { at.t + dt };
            if let StepOutcome::Stuck { attempted, iterations, force, constraint } =
                self.corrected_step(at, next, dt, &mut saved)?
            {
                return Ok(match self.stuck(at, attempted, iterations, force, constraint, path) {
                    Ok(limit) => ExactWalk::Limit(limit),
                    Err(_) => ExactWalk::Failed,
                });
            }
        }
        Ok(ExactWalk::Reached)
    }
}
