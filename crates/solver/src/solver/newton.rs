//! Newton's method on the exact residual, and the solve of a non-symmetric tangent (GMRES on the
//! symmetric factorization for the skew part of world-fixed loads and turning preloads).

use super::*;

/// What one Newton iteration ([`StaticSolver::newton_correction`], a replay's chord iteration) solves its
/// increment with.
#[derive(Clone, Copy)]
enum SolvedWith<'a> {
    /// The exact tangent, assembled and factorized here.
    Exact,
    /// What a recording kept at the step: its factors, and its right-hand side, corrected by what the
    /// replay's move touched where it can be ([`StaticSolver::touched_rhs`]).
    Kept(&'a super::replay::Kept),
}

/// Newton's failure at load parameter `t` after `iterations`, with the residual `r` it left.
pub(super) fn unconverged(t: f64, iterations: usize, r: &Residual) -> SolverError {
    SolverError::NoConvergence {
        t,
        last_converged: None,
        iterations,
        force_residual: r.force,
        constraint_residual: r.constraint,
    }
}

/// How far a corrector has walked from where its predictor put it. Its first iteration is its own; the
/// later ones may not together go further than the predictor and that first iteration did, plus what
/// closing the joints to their tolerance may take (a predictor of nothing, as an ideal linkage held by its
/// rig under a load, still leaves the start's converged joint gaps to close). A corrector that goes further
/// reaches beyond where the tangent tells the path goes: across a limit point or a crossing, onto another
/// branch. Load steps ([`StaticSolver::newton`]) and arc-length steps keep to it alike.
pub(super) struct CorrectorReach {
    predicted: f64,
    allowance: f64,
    first: f64,
    later: f64,
}

impl CorrectorReach {
    /// The reach of a corrector whose predictor went `predicted` far, with joints closed to
    /// `constraint_tolerance`.
    pub(super) fn new(predicted: f64, constraint_tolerance: f64) -> Self {
        CorrectorReach { predicted, allowance: 100.0 * constraint_tolerance, first: 0.0, later: 0.0 }
    }

    /// Takes iteration `iteration`'s length; whether the corrector has now walked beyond its reach.
    pub(super) fn walked_off(&mut self, iteration: usize, length: f64) -> bool {
        if iteration == 0 {
            self.first = length;
        } else {
            self.later += length;
        }
        self.later > self.predicted + self.first + self.allowance
    }
}

/// The largest turn of any body in the increment `dq` (its body coordinates: three translations, then three
/// rotations per body), rad.
pub(super) fn largest_turn(dq: &[f64]) -> f64 {
    dq.chunks_exact(BODY_DOFS).flat_map(|b| &b[3..]).fold(0.0f64, |a, v| a.max(v.abs()))
}

impl<'m> StaticSolver<'m> {
    /// Newton on the true residual at the state's load parameter. Returns iterations used.
    ///
    /// With [`SolverOptions::reuse_factorization`] it is a chord method: iterations solve with the
    /// factorization kept from an earlier full tangent — of this call, or of an earlier step when
    /// nothing else has been factorized since — and assemble the residual alone; a fresh tangent is
    /// assembled and factorized only when an iteration's residual (each part over its tolerance) falls by
    /// less than [`CHORD_CONTRACTION`]. Convergence is judged on the true residual either way.
    ///
    /// With `start.guard`, the corrector may not travel further than the first increment plus any
    /// predictor applied before the call, nor take an increment that turns a body by more than
    /// [`SolverOptions::max_rotation_step`] (which Newton elsewhere shortens): a longer walk, or a linear
    /// response that large, means the step reaches beyond where the tangent tells where the path goes —
    /// across a limit point to another branch, typically — and the step is refused so that the caller
    /// cuts it.
    pub(super) fn newton(&mut self, state: &mut State, start: NewtonStart) -> Result<(usize, Residual), SolverError> {
        let n = self.work.assembly.n;
        let m = self.work.assembly.m();
        let reuse = self.options.reuse_factorization;
        // Whether the factorization in hand may serve this iteration.
        let mut factored = reuse && !start.fresh && self.factored == Some(Tangent::Full);
        let mut reach = CorrectorReach::new(start.predicted, self.options.constraint_tolerance);
        let mut last_merit = f64::INFINITY;
        let mut iter = 0;
        self.work.moved.fill(0.0);
        loop {
            let refactor = !factored;
            self.assemble(state, if refactor { Some(Tangent::Full) } else { None });
            if refactor {
                self.update_roundoff_floor(&state.poses);
            }
            let r = self.finite_residual(state, "residual")?;
            if self.converged(&r) {
                return Ok((iter, r));
            }
            if iter == self.options.max_iterations {
                return Err(unconverged(state.t, iter, &r));
            }
            let merit = self.merit(&r);
            // A chord iteration that stops contracting gets a fresh tangent.
            if factored && merit > CHORD_CONTRACTION * last_merit {
                self.assemble(state, Some(Tangent::Full));
                self.update_roundoff_floor(&state.poses);
                self.factorize()?;
            } else if refactor {
                self.factorize()?;
                factored = reuse;
            }
            last_merit = merit;
            self.newton_increment()?;
            let step_norm = self.work.rhs[..n].iter().map(|v| v * v).sum::<f64>().sqrt();
            let max_rot = largest_turn(&self.work.rhs[..n]);
            let walked_off = reach.walked_off(iter, step_norm);
            if start.guard && (walked_off || max_rot > self.options.max_rotation_step) {
                return Err(unconverged(state.t, iter, &r));
            }
            let scale =
                if max_rot > self.options.max_rotation_step { self.options.max_rotation_step / max_rot } else { 1.0 };
            Self::apply(&mut state.poses, &self.work.rhs[..n], scale);
            for k in 0..m {
                state.lambda[k] += scale * self.work.rhs[n + k];
            }
            // Only the predictor reads what the iterations moved.
            if reuse {
                for (moved, d) in self.work.moved.iter_mut().zip(&self.work.rhs) {
                    *moved += scale * d;
                }
            }
            iter += 1;
        }
    }

    /// The residual against its tolerance, the worse of its two parts: at most 1 when converged.
    pub(super) fn merit(&self, r: &Residual) -> f64 {
        let force = (self.options.force_tolerance * r.force_scale).max(self.roundoff_floor);
        (r.force / force).max(r.constraint / self.options.constraint_tolerance)
    }

    /// Solves `[K_sym + S, Jᵀ; J, 0] z = rhs` in place with the factorization of the symmetric part `P`.
    /// Without a skew part `S` this is one solve. With one, it runs GMRES on the preconditioned system
    /// `(I + P⁻¹[S; 0]) z = P⁻¹ rhs` from `z₀ = P⁻¹ rhs`: each iteration is one more back-substitution, and
    /// the count does not depend on how large `S` is against `K` (a fixed-point sweep would stall once
    /// `‖P⁻¹S‖` nears 1, e.g. a bushing twisted ~1 rad by a world-fixed torque).
    ///
    /// A backend that factorizes the skew part with the rest (the dense LU) solves the whole system at
    /// once, and GMRES is left out.
    pub(super) fn solve_with_skew(&mut self, accuracy: Accuracy) -> Result<(), SolverError> {
        // A replay's tangent at a moved equilibrium, solved with the recorded factors there.
        if let Some(factors) = self.kept_tangent.as_ref().map(|k| k.factors.clone()) {
            return self.solve_kept(&factors);
        }
        let size = self.work.rhs.len();
        self.work.factor.solve_in_place(&mut self.work.rhs, accuracy).map_err(|e| self.named(e))?;
        if !self.work.assembly.has_skew || self.work.factor.solves_skew() {
            return Ok(());
        }
        let b_norm = norm2(&self.work.rhs);
        if b_norm == 0.0 {
            return Ok(());
        }
        self.work.krylov.ensure(size);
        self.work.krylov.b[..size].copy_from_slice(&self.work.rhs);
        for _restart in 0..KRYLOV_RESTARTS {
            // r = b − A x = −P⁻¹[S x; 0] (b = x₀ = z₀ on entry, and x holds the current iterate).
            self.preconditioned_skew(KrylovSlot::Iterate)?;
            let k = &mut self.work.krylov;
            for c in 0..size {
                k.basis[0][c] = -k.work[c];
            }
            // On restarts, b − A x needs the original b: add (b − x) back.
            for c in 0..size {
                k.basis[0][c] += k.b[c] - self.work.rhs[c];
            }
            let beta = norm2(&k.basis[0][..size]);
            if beta <= KRYLOV_TOL * b_norm {
                return Ok(());
            }
            for v in k.basis[0][..size].iter_mut() {
                *v /= beta;
            }
            k.g.fill(0.0);
            k.g[0] = beta;
            let mut used = 0;
            for j in 0..KRYLOV_DIM {
                // w = A v_j = v_j + P⁻¹[S v_j; 0]
                self.preconditioned_skew(KrylovSlot::Basis(j))?;
                let k = &mut self.work.krylov;
                for c in 0..size {
                    k.work[c] += k.basis[j][c];
                }
                // Modified Gram–Schmidt.
                for i in 0..=j {
                    let h: f64 = k.work[..size].iter().zip(&k.basis[i][..size]).map(|(a, b)| a * b).sum();
                    k.h[i][j] = h;
                    for c in 0..size {
                        k.work[c] -= h * k.basis[i][c];
                    }
                }
                let h_next = norm2(&k.work[..size]);
                k.h[j + 1][j] = h_next;
                // Apply the previous Givens rotations, then make a new one for row j+1.
                for i in 0..j {
                    let (c, s) = (k.cs[i], k.sn[i]);
                    let (a, b) = (k.h[i][j], k.h[i + 1][j]);
                    k.h[i][j] = c * a + s * b;
                    k.h[i + 1][j] = -s * a + c * b;
                }
                let (a, b) = (k.h[j][j], k.h[j + 1][j]);
                let r = a.hypot(b);
                let (c, s) = if r == 0.0 { (1.0, 0.0) } else { (a / r, b / r) };
                k.cs[j] = c;
                k.sn[j] = s;
                k.h[j][j] = r;
                k.h[j + 1][j] = 0.0;
                k.g[j + 1] = -s * k.g[j];
                k.g[j] *= c;
                used = j + 1;
                if k.g[j + 1].abs() <= KRYLOV_TOL * b_norm || h_next == 0.0 {
                    break;
                }
                if j + 1 < KRYLOV_DIM {
                    for c in 0..size {
                        k.basis[j + 1][c] = k.work[c] / h_next;
                    }
                }
            }
            // x += V y with H y = g (upper triangular).
            let k = &mut self.work.krylov;
            for i in (0..used).rev() {
                let mut v = k.g[i];
                for l in i + 1..used {
                    v -= k.h[i][l] * k.y[l];
                }
                k.y[i] = if k.h[i][i] != 0.0 { v / k.h[i][i] } else { 0.0 };
            }
            for i in 0..used {
                let yi = k.y[i];
                for c in 0..size {
                    self.work.rhs[c] += yi * k.basis[i][c];
                }
            }
            if k.g[used].abs() <= KRYLOV_TOL * b_norm {
                return Ok(());
            }
        }
        Ok(())
    }

    /// `work ← P⁻¹ [S v; 0]` for `v` the current iterate (`self.work.rhs`) or a Krylov basis vector.
    pub(super) fn preconditioned_skew(&mut self, which: KrylovSlot) -> Result<(), SolverError> {
        let n = self.work.assembly.n;
        let size = self.work.rhs.len();
        let k = &mut self.work.krylov;
        let v: &[f64] = match which {
            KrylovSlot::Iterate => &self.work.rhs[..n],
            KrylovSlot::Basis(j) => &k.basis[j][..n],
        };
        self.work.assembly.skew_times(v, &mut k.work[..n]);
        k.work[n..size].fill(0.0);
        self.work.factor.solve_in_place(&mut k.work[..size], Accuracy::Refined).map_err(|e| self.named(e))?;
        Ok(())
    }

    /// Static equilibrium at `state.t`, by Newton from `state`.
    pub fn equilibrium(&mut self, state: &mut State) -> Result<StepResult, SolverError> {
        use super::replay::Replayed;
        match self.taping.next_equilibrium(self.taped)? {
            Replayed::Solve => self.solve_equilibrium(state),
            Replayed::Record(taped) => {
                let result = self.solve_equilibrium(state);
                let factors = result.as_ref().ok().and_then(|step| self.recorded_factors(step));
                self.taping.keep_equilibrium(taped, self.model, &result, factors);
                result
            }
            Replayed::Call(recorded) => self.replay_equilibrium(recorded, state),
        }
    }

    pub(super) fn solve_equilibrium(&mut self, state: &mut State) -> Result<StepResult, SolverError> {
        let (iterations, r) = self.newton(state, NewtonStart { guard: false, predicted: 0.0, fresh: false })?;
        Ok(self.step_result(state, iterations, &r))
    }

    /// One full Newton iteration on the exact equilibrium at `step.t`, from `step`: the step moved by
    /// `−T⁻¹R` with `T` the exact tangent and `R` its force and constraint residual. How far it moves
    /// estimates how far `step` is from the equilibrium at its load parameter: the drift of a paper-mode
    /// step (first order, so the corrected step is that equilibrium to second order in the drift), or
    /// what remains after a corrected step converged (Newton's next increment). Costs one factorization.
    /// The returned step reports the residual at the corrected state and `iterations = 1`.
    pub fn newton_correction(&mut self, step: &StepResult) -> Result<StepResult, SolverError> {
        self.one_iteration(step, SolvedWith::Exact)
    }

    /// One Newton iteration on the exact equilibrium at `step.t` from `step`, as
    /// [`StaticSolver::newton_correction`], but solved with what a recording kept at `step` (`kept`,
    /// [`crate::replay`]): the factors of the recorded model's tangent there, `T₀`, so that the step moves
    /// by `−T₀⁻¹R`, with `R` this model's residual at `step`, and nothing is factorized. This model being a
    /// move of the recorded one, the result's rate with respect to the move is the exact one's: both are
    /// `−T₀⁻¹ ∂R/∂p` there. Where the move touched only some elements and joints and `step` is at the
    /// recorded load parameter, `R` is the recorded right-hand side corrected by those
    /// ([`StaticSolver::touched_rhs`]), not assembled whole; the same to rounding.
    ///
    /// The returned step reports `step`'s residuals, not its own: it is a move of an equilibrium by a
    /// first-order step, whose residual is of the second order in the move, and what a replay reads off it
    /// are its poses and multipliers (assembling the residual once more there cost a replay a fifth of its
    /// time).
    pub(super) fn kept_chord_correction(
        &mut self,
        step: &StepResult,
        kept: &super::replay::Kept,
    ) -> Result<StepResult, SolverError> {
        self.one_iteration(step, SolvedWith::Kept(kept))
    }

    /// One Newton iteration from `step`, its increment solved as `with` says.
    fn one_iteration(&mut self, step: &StepResult, with: SolvedWith) -> Result<StepResult, SolverError> {
        let n = self.work.assembly.n;
        let m = self.work.assembly.m();
        let mut state = self.state_of(step);
        let factors = match with {
            SolvedWith::Exact => None,
            SolvedWith::Kept(kept) => Some(&kept.lu),
        };
        // The right-hand side from what the recording kept, corrected by what the move touched; else
        // assembled here.
        if matches!(with, SolvedWith::Kept(kept) if self.touched_rhs(&state, kept)) {
            if self.work.rhs.iter().any(|v| !v.is_finite()) {
                return Err(SolverError::NonFinite { what: "residual" });
            }
        } else {
            self.assemble(&state, factors.is_none().then_some(Tangent::Full));
            self.finite_residual(&state, "residual")?;
            if factors.is_some() {
                Self::residual_rhs(&self.work.assembly, &self.work.scratch, &mut self.work.rhs);
            }
        }
        match factors {
            None => {
                self.factorize()?;
                self.newton_increment()?;
            }
            Some(factors) => {
                factors.solve_in_place(&mut self.work.rhs);
                if self.work.rhs.iter().any(|v| !v.is_finite()) {
                    return Err(SolverError::NonFinite { what: "Newton increment" });
                }
            }
        }
        Self::apply(&mut state.poses, &self.work.rhs[..n], 1.0);
        for k in 0..m {
            state.lambda[k] += self.work.rhs[n + k];
        }
        let after = match factors {
            None => {
                self.assemble(&state, None);
                self.finite_residual(&state, "residual")?
            }
            Some(_) => Residual {
                force: step.force_residual,
                constraint: step.constraint_residual,
                force_scale: step.force_scale,
            },
        };
        Ok(self.step_result(&state, 1, &after))
    }

    /// The factors of the exact tangent at `step` (an equilibrium this solver found), for a recording's
    /// replays ([`crate::replay`]); `None` when the solver's backend is not the dense LU or the dense LU
    /// finds the tangent singular there (the replays then factorize their own). The solver's own
    /// factorization, which the next step may keep, is left as it was.
    pub(super) fn recorded_factors(&mut self, step: &StepResult) -> Option<super::replay::Factors> {
        if self.recorded_lu.is_none() {
            self.recorded_lu = Some(self.work.factor.dense_twin()?);
        }
        let state = self.state_of(step);
        self.assemble(&state, Some(Tangent::Full));
        let a = &self.work.assembly;
        let values = KktValues { k: &a.k_values, k_skew: a.has_skew.then_some(&a.k_skew[..]), j: &a.j_values };
        let lu = self.recorded_lu.as_mut()?;
        // Scaled afresh: the factors at a step are then the same whichever steps were factorized before
        // it (a recording may keep them at only the steps its replays move, `replay::ReplayRows`).
        lu.reset();
        lu.factorize(values).ok()?;
        let lu = lu.factors()?;
        let (n, m) = (self.work.assembly.n, self.work.assembly.m());
        self.work.assembly.jt_times(&state.lambda, &mut self.work.scratch[..n]);
        let mut rhs = vec![0.0; n + m];
        Self::residual_rhs(&self.work.assembly, &self.work.scratch, &mut rhs);
        Some(std::sync::Arc::new(super::replay::Kept { lu, t: state.t, rhs }))
    }

    /// The Newton increment `[Δq; Δλ]` into `rhs`, from `rhs = [Q − Jᵀλ ; −Φ]` at the assembled state and
    /// the factorized tangent (`scratch` holds `Jᵀλ` from [`Self::residual`]).
    pub(super) fn newton_increment(&mut self) -> Result<(), SolverError> {
        Self::residual_rhs(&self.work.assembly, &self.work.scratch, &mut self.work.rhs);
        self.solve_with_skew(Accuracy::Increment)?;
        if self.work.rhs.iter().any(|v| !v.is_finite()) {
            return Err(SolverError::NonFinite { what: "Newton increment" });
        }
        Ok(())
    }

    /// `out = [Q − Jᵀλ ; −Φ]` at the assembled state, `jt_lambda` holding `Jᵀλ` (from [`Self::residual`]).
    pub(super) fn residual_rhs(assembly: &Assembly, jt_lambda: &[f64], out: &mut [f64]) {
        let n = assembly.n;
        for c in 0..n {
            out[c] = assembly.applied[c] - jt_lambda[c];
        }
        for k in 0..assembly.m() {
            out[n + k] = -assembly.phi[k];
        }
    }
}
