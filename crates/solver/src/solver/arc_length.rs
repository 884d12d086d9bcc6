//! Arc-length continuation: the path followed through its limit points, each step of a fixed length
//! in the scaled space of motions and load.

use super::newton::{self, largest_turn, CorrectorReach};
use super::*;

impl<'m> StaticSolver<'m> {
    /// Follows the equilibrium path by arc length from the equilibrium at `path.start` (found from the
    /// design pose), through limit points: see [`StaticSolver::arc_length_sweep_from`].
    pub fn arc_length_sweep(&mut self, path: LoadPath, step: ArcStep) -> Result<Sweep, SolverError> {
        let mut state = self.design_state(path.start);
        self.arc_length_sweep_from(&mut state, path, step)
    }

    /// Follows the equilibrium path by arc length (Riks' normal-plane continuation with a bordered solve of
    /// the same KKT factorization), so the load parameter may rise, pass a limit point and fall: where a
    /// [`StaticSolver::sweep`] stops at a fold, this goes on along the path through it (snap-through under
    /// a load, or a mechanism folding over under a driven motion), and never reports one.
    ///
    /// Starts from `state`, brought first to equilibrium at its own load parameter `state.t` (which must
    /// lie between `path.start` and `path.end`), heading towards `path.end`; stops after `path.steps`
    /// steps or at the first step outside `[min(start, end), max(start, end)]` (that step is kept).
    ///
    /// A step that finds no equilibrium within its predictor's reach even at its shortest (after
    /// [`SolverOptions::max_step_cuts`] halvings) ends the path there, its rows kept and the place in
    /// [`Sweep::stuck`]: where the path branches or bends too sharply, a corrector that went further would
    /// land on another branch.
    ///
    /// Every step has the same length in the scaled space `‖Δq‖² + ψ² Δt²`, with `ψ = ‖dq/dt‖` at the
    /// start so that both parts weigh the same there; `step` gives it in that space or, with
    /// [`ArcStep::Load`], as the change of the load parameter of the first step (`arc = |Δt₀| ·
    /// √(‖dq/dt‖² + ψ²) = √2 ψ |Δt₀|`): where the path softens the steps change the load less and the
    /// displacement more, and at a limit point they go into displacement alone. A step whose corrector
    /// does not converge is halved, at most [`SolverOptions::max_step_cuts`] times.
    pub fn arc_length_sweep_from(
        &mut self,
        state: &mut State,
        path: LoadPath,
        step: ArcStep,
    ) -> Result<Sweep, SolverError> {
        self.taped_sweep(state, path, |solver, state| solver.follow_arc(state, path, step))
    }

    fn follow_arc(&mut self, state: &mut State, path: LoadPath, step: ArcStep) -> Result<Sweep, SolverError> {
        let length = match step {
            ArcStep::Load(v) | ArcStep::Scaled(v) => v,
        };
        let (lo, hi) = (path.start.min(path.end), path.start.max(path.end));
        LoadPath::check_steps(path.steps)
            .map_err(|e| SolverError::InvalidInput { what: "arc-length path", why: e.to_string() })?;
        if !(length.is_finite() && length > 0.0 && lo.is_finite() && hi.is_finite()) {
            return Err(SolverError::InvalidInput {
                what: "arc-length path",
                why: format!(
                    "need finite ends and a positive step length, got {} to {} in steps of {length}",
                    path.start, path.end
                ),
            });
        }
        if !(lo..=hi).contains(&state.t) {
            return Err(SolverError::InvalidInput {
                what: "arc-length path",
                why: format!("the starting load {} lies outside the range {} to {}", state.t, path.start, path.end),
            });
        }
        let n = self.work.assembly.n;
        let m = self.work.assembly.m();
        let first = self.solve_equilibrium(state)?;
        let mut steps = vec![first];
        let direction = (path.end - path.start).signum();
        let q_t0 = self.load_response(state).ok_or(SolverError::LimitPoint { reached: state.t })?;
        let psi2 = (q_t0 * q_t0).max(1e-300);
        let arc = match step {
            ArcStep::Scaled(arc) => arc,
            ArcStep::Load(dt) => dt * (q_t0 * q_t0 + psi2).sqrt(),
        };
        let mut prev_dq = vec![0.0; n];
        let mut prev_dt = direction;
        let mut q_t = vec![0.0; n];
        let mut r_dq = vec![0.0; n + m];
        let mut dq_total = vec![0.0; n];
        let mut start = state.clone();
        for _ in 0..path.steps {
            start.clone_from(state);
            let mut cuts = 0;
            let (iterations, r, dt_total) = loop {
                let length = arc * 0.5f64.powi(cuts);
                match self.arc_length_step(
                    state,
                    length,
                    psi2,
                    (&prev_dq, prev_dt),
                    (&mut q_t, &mut r_dq, &mut dq_total),
                ) {
                    Ok(done) => break done,
                    Err(
                        e @ (SolverError::NoConvergence { .. }
                        | SolverError::NonFinite { .. }
                        | SolverError::NonFiniteForce { .. }),
                    ) => {
                        state.clone_from(&start);
                        cuts += 1;
                        if cuts as usize > self.options.max_step_cuts {
                            // No step stays on the path; a force that is no number is the model's to say.
                            return match e {
                                SolverError::NoConvergence { .. } => {
                                    Ok(Sweep { mode: Mode::Corrected, steps, limit: None, stuck: Some(start.t) })
                                }
                                other => Err(other),
                            };
                        }
                    }
                    Err(e) => return Err(e),
                }
            };
            prev_dq.copy_from_slice(&dq_total);
            prev_dt = dt_total;
            steps.push(self.step_result(state, iterations, &r));
            if state.t < lo - 1e-12 || state.t > hi + 1e-12 {
                break;
            }
        }
        Ok(Sweep { mode: Mode::Corrected, steps, limit: None, stuck: None })
    }

    /// One arc-length step of scaled length `arc` from the equilibrium `state`, oriented like the previous
    /// step `(Δq, Δt)`: the predictor along the tangent, then Newton on `(R, Φ)` with the normal-plane
    /// constraint. Leaves the step's `Δq` in `dq_total`; returns the iterations, the residual and `Δt`.
    pub(super) fn arc_length_step(
        &mut self,
        state: &mut State,
        arc: f64,
        psi2: f64,
        (prev_dq, prev_dt): (&[f64], f64),
        (q_t, r_dq, dq_total): (&mut [f64], &mut [f64], &mut [f64]),
    ) -> Result<(usize, Residual, f64), SolverError> {
        let n = self.work.assembly.n;
        let m = self.work.assembly.m();
        // Predictor along the tangent, oriented like the previous step.
        self.load_response(state).ok_or(SolverError::LimitPoint { reached: state.t })?;
        q_t.copy_from_slice(&self.work.rhs[..n]);
        let norm = (q_t.iter().map(|v| v * v).sum::<f64>() + psi2).sqrt();
        let mut dt = arc / norm;
        let along: f64 = q_t.iter().zip(prev_dq).map(|(a, b)| a * b).sum::<f64>() + psi2 * prev_dt;
        if along < 0.0 {
            dt = -dt;
        }
        for (d, v) in dq_total.iter_mut().zip(q_t.iter()) {
            *d = v * dt;
        }
        Self::apply(&mut state.poses, dq_total, 1.0);
        for k in 0..m {
            state.lambda[k] += dt * self.work.rhs[n + k];
        }
        state.t += dt;
        let mut dt_total = dt;
        // Corrector: Newton on (R, Φ) with the normal-plane constraint (Δq_totalᵀ δq + ψ² Δt_total δt = 0).
        // It keeps to its reach in the scaled space, whose predictor went `arc`, and turns no body by more
        // than `max_rotation_step` at once, as a load step's corrector does; a step that does not is cut.
        let mut reach = CorrectorReach::new(arc, self.options.constraint_tolerance);
        let mut last = (f64::INFINITY, f64::INFINITY);
        for iter in 0..self.options.max_iterations {
            self.assemble(state, Some(Tangent::Full));
            self.update_roundoff_floor(&state.poses);
            let r = self.finite_residual(state, "arc-length corrector")?;
            last = (r.force, r.constraint);
            if self.converged(&r) {
                return Ok((iter, r, dt_total));
            }
            self.factorize()?;
            // Residual part: [Q − Jᵀλ; −Φ]
            Self::residual_rhs(&self.work.assembly, &self.work.scratch, r_dq);
            self.work.factor.solve_in_place(r_dq, Accuracy::Refined).map_err(|e| self.named(e))?;
            self.load_direction_rhs();
            self.work.factor.solve_in_place(&mut self.work.rhs, Accuracy::Refined).map_err(|e| self.named(e))?;
            let num: f64 = dq_total.iter().zip(&r_dq[..n]).map(|(a, b)| a * b).sum();
            let den: f64 = dq_total.iter().zip(&self.work.rhs[..n]).map(|(a, b)| a * b).sum::<f64>() + psi2 * dt_total;
            let dt = if den.abs() > 0.0 { -num / den } else { 0.0 };
            for c in 0..n + m {
                r_dq[c] += dt * self.work.rhs[c];
            }
            if r_dq.iter().any(|v| !v.is_finite()) {
                return Err(SolverError::NonFinite { what: "arc-length corrector" });
            }
            let length = (r_dq[..n].iter().map(|v| v * v).sum::<f64>() + psi2 * dt * dt).sqrt();
            if reach.walked_off(iter, length) || largest_turn(&r_dq[..n]) > self.options.max_rotation_step {
                return Err(newton::unconverged(state.t, iter, &r));
            }
            Self::apply(&mut state.poses, &r_dq[..n], 1.0);
            for k in 0..m {
                state.lambda[k] += r_dq[n + k];
            }
            for c in 0..n {
                dq_total[c] += r_dq[c];
            }
            state.t += dt;
            dt_total += dt;
        }
        Err(SolverError::NoConvergence {
            t: state.t,
            last_converged: None,
            iterations: self.options.max_iterations,
            force_residual: last.0,
            constraint_residual: last.1,
        })
    }
}
