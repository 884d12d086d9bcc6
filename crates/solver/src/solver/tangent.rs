//! The tangent of the equilibrium equations at a state, and solves with it: the KKT system as
//! triplets or Matrix Market, a tangent solve, the path's tangent `dq/dt`, a kept factorization.

use super::*;

impl<'m> StaticSolver<'m> {
    /// The tangent KKT matrix `[K, Jᵀ; J, 0]` at `state` (with `K` the exact, possibly non-symmetric
    /// tangent) as `(row, col, value)` triplets, of order `n + m`: for inspection, dumps and dense
    /// reference solves.
    pub fn kkt_triplets(&mut self, state: &State) -> (usize, Vec<(usize, usize, f64)>) {
        self.assemble(state, Some(Tangent::Full));
        let n = self.work.assembly.n;
        let a = &self.work.assembly;
        let mut out = Vec::with_capacity(2 * (a.k_values.len() + a.j_values.len()));
        for c in 0..n {
            for p in a.k_col_ptr[c]..a.k_col_ptr[c + 1] {
                let (r, v, s) = (a.k_row_idx[p], a.k_values[p], a.k_skew[p]);
                out.push((r, c, v + s));
                if r != c {
                    out.push((c, r, v - s));
                }
            }
            for p in a.j_col_ptr[c]..a.j_col_ptr[c + 1] {
                let (r, v) = (n + a.j_row_idx[p], a.j_values[p]);
                out.push((r, c, v));
                out.push((c, r, v));
            }
        }
        (n + a.m(), out)
    }

    /// Solves the tangent system `[K, Jᵀ; J, 0] z = rhs` at `state` in place (`rhs` of length `n + m`):
    /// the response of the equilibrium to a load or constraint perturbation. For several right-hand sides
    /// at one state, call [`StaticSolver::factorize_tangent`] once and [`StaticSolver::solve_factored`] for
    /// each: a compliance matrix is a handful of back-substitutions.
    pub fn tangent_solve(&mut self, state: &State, rhs: &mut [f64]) -> Result<(), SolverError> {
        self.factorize_tangent(state)?;
        self.solve_factored(rhs)
    }

    /// The rate of the equilibrium along the load path at `state` (an equilibrium): `dq/dt`, `BODY_DOFS`
    /// per body (translation of the reference point, then rotation as in Δπ), from
    /// `[K Jᵀ; J 0] [q_t; λ_t] = [∂Q/∂t; −∂Φ/∂t]` with the exact tangent. Under a travel driver it gives the
    /// velocity of every point per unit travel: instant centres, roll centres and anti-dive lines.
    pub fn path_tangent(&mut self, state: &State) -> Result<Vec<f64>, SolverError> {
        self.factorize_tangent(state)?;
        self.path_tangent_factored()
    }

    /// [`StaticSolver::path_tangent`] at the state the tangent was last factorized at
    /// ([`StaticSolver::factorize_tangent`]), solved with that factorization: for a caller that reads more
    /// off the one tangent (a compliance and a path tangent at design), with no solve between that assembles
    /// another state.
    pub fn path_tangent_factored(&mut self) -> Result<Vec<f64>, SolverError> {
        Ok(self.path_rates_factored()?.dq)
    }

    /// [`StaticSolver::path_tangent_factored`] with the drivers of each joint of `scaled` moving at their
    /// rates along the path times its factor: the equilibrium's rate along another path through the same
    /// state, one the model's drivers would walk with their rates so changed (a rig's other motion: the
    /// wheels driven opposite at a state of parallel travel, the right wheel's driver scaled by −1).
    pub fn path_tangent_factored_with_drivers_scaled(
        &mut self,
        scaled: &[(JointId, f64)],
    ) -> Result<Vec<f64>, SolverError> {
        self.load_direction_rhs();
        let n = self.work.assembly.n;
        for (k, &(joint, _)) in self.work.assembly.row_joint.iter().enumerate() {
            if let Some(&(_, factor)) = scaled.iter().find(|(j, _)| j.0 == joint) {
                self.work.rhs[n + k] *= factor;
            }
        }
        self.solve_with_skew(Accuracy::Refined)?;
        Ok(self.rates_in_rhs("path tangent")?.dq)
    }

    /// The rates of the equilibrium along the load path at the state the tangent was last factorized at:
    /// `dq/dt` and `dλ/dt` of the active rows, the one solve of [`StaticSolver::path_tangent_factored`]
    /// read whole. What a rig measures as a rate at that state (a wheel rate is `dλ/dt` of the travel
    /// driver's row) is a reading of the state differentiated along them ([`StaticSolver::along_path`]).
    pub fn path_rates_factored(&mut self) -> Result<PathRates, SolverError> {
        self.load_direction_rhs();
        self.solve_with_skew(Accuracy::Refined)?;
        self.rates_in_rhs("path tangent")
    }

    /// The solution in hand split into the rates of the poses and of the active multipliers; `what` names
    /// it where it is no finite number.
    fn rates_in_rhs(&self, what: &'static str) -> Result<PathRates, SolverError> {
        let (n, rhs) = (self.work.assembly.n, &self.work.rhs);
        if !rhs.iter().all(|v| v.is_finite()) {
            return Err(SolverError::NonFinite { what });
        }
        Ok(PathRates { dq: rhs[..n].to_vec(), dlambda: rhs[n..].to_vec() })
    }

    /// The path's second rates at `state` (an equilibrium whose first `rates` these are, its tangent the
    /// one last factorized): `d²q/dt²` and `d²λ/dt²`, from `A w = −G''`, with `A` the tangent and `G''` the
    /// second difference of the residual `G = (Φ_qᵀλ − Q, Φ)` over the points `±h` on the tangent line
    /// (of error `O(h²)`; the residual vanishes on the path, so its second difference along the line is
    /// what the path's curvature must undo). Three residual assemblies and one solve; the tangent's
    /// factorization is kept.
    pub fn path_second_rates(&mut self, state: &State, rates: &PathRates, h: f64) -> Result<PathRates, SolverError> {
        let n = self.work.assembly.n;
        let size = n + self.work.assembly.m();
        let mut second = vec![0.0; size];
        for (at, weight) in [(h, 1.0), (-h, 1.0), (0.0, -2.0)] {
            let point = self.state_along(state, rates, None, at);
            self.assemble(&point, None);
            self.finite_residual(&point, "residual")?;
            // −G at the point.
            Self::residual_rhs(&self.work.assembly, &self.work.scratch, &mut self.work.rhs);
            for (s, r) in second.iter_mut().zip(&self.work.rhs) {
                *s += weight * r / (h * h);
            }
        }
        // The design's own assembly again (its constraint rows), for the refinement of the solve; a
        // replay's kept tangent is refined against its own copy.
        if self.kept_tangent.is_none() {
            self.assemble(state, None);
        }
        self.work.rhs.copy_from_slice(&second);
        self.solve_with_skew(Accuracy::Refined)?;
        self.rates_in_rhs("path curvature")
    }

    /// The point at `t + h` of the path through `state` (an equilibrium whose `rates` these are) expanded
    /// to first order (on its tangent line), or to second with its `second` rates
    /// ([`StaticSolver::path_second_rates`]): poses moved by `h·dq/dt + ½h²·d²q/dt²` (each body's rotation
    /// by the exact update), multipliers likewise, load parameter `t + h`. It is no equilibrium (it leaves
    /// the path by `O(h²)` or `O(h³)`), and its residuals read zero: it exists to be read, since a reading
    /// `g` of it has `dg/dh = dg/dt` at `h = 0` on either, and `d²g/dh² = d²g/dt²` on the second, so
    /// differences of readings there are the path rates of any reading.
    pub fn along_path(&self, state: &State, rates: &PathRates, second: Option<&PathRates>, h: f64) -> StepResult {
        let moved = self.state_along(state, rates, second, h);
        self.step_result(&moved, 0, &Residual { force: 0.0, constraint: 0.0, force_scale: 1.0 })
    }

    fn state_along(&self, state: &State, rates: &PathRates, second: Option<&PathRates>, h: f64) -> State {
        let half = 0.5 * h * h;
        let moved = |first: &[f64], second: Option<&[f64]>| -> Vec<f64> {
            let curve = |k: usize| second.map_or(0.0, |s| half * s[k]);
            first.iter().enumerate().map(|(k, v)| h * v + curve(k)).collect()
        };
        let mut poses = state.poses.clone();
        Self::apply(&mut poses, &moved(&rates.dq, second.map(|s| &s.dq[..])), 1.0);
        let dlambda = moved(&rates.dlambda, second.map(|s| &s.dlambda[..]));
        let lambda = state.lambda.iter().zip(dlambda).map(|(l, d)| l + d).collect();
        State { poses, lambda, t: state.t + h }
    }

    /// Assembles and factorizes the tangent at `state` for [`StaticSolver::solve_factored`].
    ///
    /// In a replay ([`crate::replay`]), at an equilibrium it moved with the recorded tangent's factors,
    /// the moved tangent is assembled but not factorized: every solve with it until the next factorization
    /// is the recorded factors' solve and one step of refinement against it (`StaticSolver::solve_kept`),
    /// whose rate with respect to the move is the exact solve's. Elsewhere in a replay the factorization
    /// is scaled afresh, so that it is the same whichever steps the replay factorized before (a replay
    /// that moves only some rows, `replay::ReplayRows`, reads there what a whole replay reads, to the
    /// bit).
    pub fn factorize_tangent(&mut self, state: &State) -> Result<(), SolverError> {
        if self.taping.replaying() {
            if let Some(at) = self.moved_equilibrium(state) {
                // The tangent kept there, if it is the last, still holds: nothing factorized since.
                if self.kept_tangent.as_ref().is_none_or(|kept| kept.at != at) {
                    self.assemble(state, Some(Tangent::Full));
                    self.keep_tangent(at);
                }
                return Ok(());
            }
            self.assemble(state, Some(Tangent::Full));
            self.work.factor.reset();
        } else {
            self.assemble(state, Some(Tangent::Full));
        }
        self.factorize()?;
        Ok(())
    }

    /// Solves with the tangent last factorized (by [`StaticSolver::factorize_tangent`] or any solve).
    pub fn solve_factored(&mut self, rhs: &mut [f64]) -> Result<(), SolverError> {
        let size = self.work.assembly.n + self.work.assembly.m();
        if rhs.len() != size {
            return Err(SolverError::InvalidInput {
                what: "right-hand side",
                why: format!("length {} but the system has {size} unknowns", rhs.len()),
            });
        }
        self.work.rhs.copy_from_slice(rhs);
        self.solve_with_skew(Accuracy::Refined)?;
        rhs.copy_from_slice(&self.work.rhs);
        Ok(())
    }

    /// Writes the KKT matrix at `state` in Matrix Market format (feature `matrix-market`).
    #[cfg(feature = "matrix-market")]
    pub fn write_kkt_matrix_market(&mut self, state: &State, path: &std::path::Path) -> std::io::Result<()> {
        let (size, triplets) = self.kkt_triplets(state);
        let mut tri = sprs::TriMat::new((size, size));
        for (r, c, v) in triplets {
            tri.add_triplet(r, c, v);
        }
        let csc: sprs::CsMat<f64> = tri.to_csc();
        sprs::io::write_matrix_market(path, &csc)
    }
}
