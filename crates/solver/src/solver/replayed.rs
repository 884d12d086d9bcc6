//! The solves of a replayed run (see [`crate::replay`]): each a recorded equilibrium moved by one exact
//! Newton iteration of the solver's model.

use super::kept::KeptAt;
use super::StaticSolver;
use crate::assembly::pair_dofs;
use crate::error::SolverError;
use crate::options::{LoadPath, State};
use crate::replay::{moved_t, Factors, Kept, RecordedEquilibrium, RecordedSweep, Replayed};
use crate::results::{StepResult, Sweep};
use elastokin_core::ElementEval;
use std::sync::Arc;

impl StaticSolver<'_> {
    /// A sweep along `path` as the recording or replay the solver takes part in has it: `solve` it (and keep what it
    /// returned when recording), or move the recorded one when replaying.
    pub(super) fn taped_sweep(
        &mut self,
        state: &mut State,
        path: LoadPath,
        solve: impl FnOnce(&mut Self, &mut State) -> Result<Sweep, SolverError>,
    ) -> Result<Sweep, SolverError> {
        match self.taping.next_sweep(self.taped)? {
            Replayed::Solve => solve(self, state),
            Replayed::Record(taped) => {
                let result = solve(self, state);
                // The factors where the replays will move the step: every step, or those of `replay_rows`
                // (every step where the run names rows it read afterwards, `Taping::rows_read`)
                // (a replayed step without them, should its load parameter move across the edge of the
                // rows asked for, takes the exact Newton iteration instead).
                let factors = match &result {
                    Ok(sweep) => {
                        let (rows, count) = (self.replay_rows, sweep.steps.len());
                        let moved = |i: usize, t: f64| rows.is_none_or(|r| r.extremes || r.moves(t, i, count, &path));
                        let steps = sweep.steps.iter().enumerate();
                        steps.map(|(i, s)| if moved(i, s.t) { self.recorded_factors(s) } else { None }).collect()
                    }
                    Err(_) => Vec::new(),
                };
                self.taping.keep_sweep(taped, self.model, path, &result, factors);
                result
            }
            Replayed::Call(recorded) => self.replay_sweep(recorded, path, state),
        }
    }

    /// A recorded equilibrium moved to this solver's model at load `t`: one Newton iteration, solved with
    /// the recorded tangent's `factors` where they were kept, else with this model's exact tangent.
    /// A stop touching or leaving between the recorded model there (`pieces`) and the moved is noted.
    fn moved(
        &mut self,
        recorded: StepResult,
        pieces: &[u8],
        factors: Option<&Factors>,
        t: f64,
    ) -> Result<StepResult, SolverError> {
        let at = StepResult { t, ..recorded };
        let moved = match factors {
            Some(factors) => self.kept_chord_correction(&at, factors)?,
            None => self.newton_correction(&at)?,
        };
        if moved.element_pieces(self.model) != pieces {
            self.taping.note_kink();
        }
        if let Some(factors) = factors {
            self.moved_equilibria.push((self.state_of(&moved), factors.clone()));
        }
        Ok(moved)
    }

    /// The replay of a single equilibrium, `state` left at it.
    pub(super) fn replay_equilibrium(
        &mut self,
        recorded: RecordedEquilibrium,
        state: &mut State,
    ) -> Result<StepResult, SolverError> {
        let step = self.moved(recorded.0?, &recorded.1, recorded.2.as_ref(), state.t)?;
        *state = self.state_of(&step);
        Ok(step)
    }

    /// The replay of a sweep along `path`, `state` left at its last equilibrium (of the steps moved, with
    /// [`ReplayRows`](crate::replay::ReplayRows): the others are left out).
    pub(super) fn replay_sweep(
        &mut self,
        recorded: Arc<RecordedSweep>,
        path: LoadPath,
        state: &mut State,
    ) -> Result<Sweep, SolverError> {
        let RecordedSweep { path: from, result, pieces, factors, read } = &*recorded;
        let sweep = result.as_ref().map_err(Clone::clone)?;
        let count = sweep.steps.len();
        let mut steps = Vec::with_capacity(count);
        // Each recorded step is copied only where it is moved; the others are left out.
        for (i, (s, pieces)) in sweep.steps.iter().zip(pieces).enumerate() {
            let t = moved_t(s.t, Some(i), from, &path);
            if self.replay_rows.is_some_and(|rows| !rows.moves(t, i, count, &path)) && !read.contains(&i) {
                continue;
            }
            let factors = factors.get(i).and_then(Option::as_ref);
            steps.push(self.moved(s.clone(), pieces, factors, t)?);
        }
        if let Some(last) = steps.last() {
            *state = self.state_of(last);
        }
        let limit = sweep.limit.clone().map(|mut l| {
            l.t = moved_t(l.t, None, from, &path);
            l.beyond = moved_t(l.beyond, None, from, &path);
            l
        });
        let stuck = sweep.stuck.map(|t| moved_t(t, None, from, &path));
        Ok(Sweep { mode: sweep.mode, steps, limit, stuck })
    }

    /// The Newton right-hand side (`Q − Jᵀλ`, `−Φ`) of this model at `state` into the workspace's, as the
    /// recorded one `kept` there corrected by the touched elements and joints, when `state` is at the
    /// recorded load parameter; `false` (nothing written) when it cannot be: not a replay, another load
    /// parameter (the loads and drivers moved too), or other parts. (The system is the recorded one's
    /// size: a replayed solver of other coordinates or kept rows is refused at its creation.)
    pub(super) fn touched_rhs(&mut self, state: &State, kept: &Kept) -> bool {
        let Some(touched) = &self.touched else { return false };
        if state.t != kept.t {
            return false;
        }
        let (out, row_joint, n) = (&mut self.work.rhs, &self.work.assembly.row_joint, self.work.assembly.n);
        let (moved, recorded) = (self.model, touched.recorded.as_ref());
        let (poses, t) = (&state.poses, state.t);
        out.copy_from_slice(&kept.rhs);
        // The moved model's part added, the recorded one's taken away, each on its own bodies.
        let mut eval = ElementEval::default();
        for &e in &touched.elements {
            for (element, sign) in [(&moved.elements()[e], 1.0), (&recorded.elements()[e], -1.0)] {
                let [i, j] = element.bodies();
                element.evaluate(&i.pose(poses), &j.pose(poses), t, &mut eval, false);
                for (local, d) in pair_dofs(i, j).iter().enumerate() {
                    if let Some(g) = d {
                        out[*g] += sign * eval.force[local];
                    }
                }
            }
        }
        for (k, &(joint, row)) in row_joint.iter().enumerate() {
            if !touched.joints[joint] {
                continue;
            }
            let lambda = state.lambda[k];
            for (jt, sign) in [(&moved.joints()[joint], 1.0), (&recorded.joints()[joint], -1.0)] {
                let (bi, bj) = (jt.spec.body_i, jt.spec.body_j);
                let ev = jt.rows[row].evaluate(&bi.pose(poses), &bj.pose(poses), t);
                out[n + k] -= sign * ev.value;
                for (local, d) in pair_dofs(bi, bj).iter().enumerate() {
                    if let Some(g) = d {
                        out[*g] -= sign * ev.gradient[local] * lambda;
                    }
                }
            }
        }
        true
    }
}

impl StaticSolver<'_> {
    /// Which of the equilibria this replayed solver moved with recorded factors `state` is, if any.
    pub(super) fn moved_equilibrium(&self, state: &State) -> Option<usize> {
        self.moved_equilibria.iter().rposition(|(s, _)| s == state)
    }

    /// Keeps the tangent just assembled at moved equilibrium `at`, to be solved with the recorded
    /// tangent's factors there, until the next factorization.
    pub(super) fn keep_tangent(&mut self, at: usize) {
        self.work.kept.keep(&self.work.assembly);
        self.factored = None;
        self.kept_tangent = Some(KeptAt { at, factors: self.moved_equilibria[at].1.clone() });
    }

    /// Solves the kept tangent `A` of a moved equilibrium ([`StaticSolver::keep_tangent`]) for the
    /// right-hand side `b` in the workspace's, with the recorded tangent's factors `M` there: one solve
    /// and one step of refinement against `A`, `x = M b + M (b − A M b)`. As a function of the move `δ`
    /// this is smooth, and at `δ = 0` (`A = M⁻¹`) both it and its rate are those of `A⁻¹ b`
    /// (`d(A⁻¹b) = A⁻¹(db − dA·x)`): the differences of a replay's readings of it are the derivatives of
    /// the readings of the exact solve, with no factorization of the moved tangent. One step always, where
    /// a refinement run to a tolerance would take a count of steps that changes with the move, and its
    /// result would no longer be smooth in it.
    ///
    /// The residual `b − A x` is summed with each product's and each sum's rounding carried
    /// (error-free transformations, `K`'s symmetric and skew parts apart): where stiff members' large
    /// forces cancel in it, a plain sum leaves their rounding in the soft modes of `x` (a twist beam's
    /// lateral roll-centre offset, zero by symmetry, had derivatives of up to 9.3e-10 m/m from it; 4.4e-10
    /// summed so, 4.7e-10 with the moved tangent factorized).
    pub(super) fn solve_kept(&mut self, factors: &Kept) -> Result<(), SolverError> {
        let (x, kept) = (&mut self.work.rhs, &mut self.work.kept);
        kept.solve(&self.work.assembly, &factors.lu, x);
        if x.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(SolverError::NonFinite { what: "tangent solve" })
        }
    }
}
