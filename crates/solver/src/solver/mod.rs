//! The quasi-static solver: equilibrium, paper-mode and corrected-mode load paths.
//!
//! ## Sign convention
//! Elements return the generalized force `Q` they apply; the constraint force on the bodies is `−Φ_qᵀλ`.
//! Equilibrium is `R(q, λ, t) = Φ_qᵀλ − Q(q, t) = 0`, `Φ(q, t) = 0`; stiffness `K = −∂Q/∂Δq` is positive for
//! a spring. A linear step therefore reads `K Δq + Φ_qᵀ λ = f` (`K` positive, loads on the right: the
//! opposite of the paper's sign in its eq. 8).
//!
//! ## Modes
//! * [`Mode::Paper`] — paper eq. 9: `K(qⁿ) Δq + Φ_q(qⁿ)ᵀ λⁿ = Δf + Φ_q(qⁿ⁻¹)ᵀ λⁿ⁻¹`,
//!   `Φ_q(qⁿ) Δq = −Δt ∂Φ/∂t`, with `Δf = Δt ∂Q/∂t` and `K` the elastic stiffness plus the load stiffness of
//!   world-fixed loads (with the elastic part alone each increment keeps the moment arm it was applied with
//!   and the recurrence does not converge as `Δf → 0`), solved with its skew part (GMRES on the symmetric
//!   LDLᵀ). Loads are accumulated linearly; the constraints drift. Error `O(Δf)`.
//! * [`Mode::Corrected`] — each step starts with the same linear predictor (the first Newton iteration from the
//!   last equilibrium at the new load is exactly that step, with the full tangent), then Newton on the true
//!   residual until the force and constraint tolerances hold. With `reuse_factorization` a step instead
//!   starts from the polynomial extrapolation of the last steps' increments (up to cubic) and corrects by
//!   chord iterations: residual-only assemblies solved with a factorization kept across steps, refreshed
//!   only when an iteration contracts the residual by less than a factor 4. Results then meet the same
//!   tolerances but, chord convergence being linear, sit nearer them than full Newton's last quadratic
//!   step leaves them.
//!
//! Both start from an equilibrium at the first load parameter, found by Newton from the design pose (so a
//! preloaded spring that does not sit at rest at design is fine).
mod arc_length;
mod corrected;
mod diagnostics;
mod kept;
mod limit;
mod newton;
mod paper;
mod predictor;
mod replayed;
mod tangent;

pub use crate::mobility::redundant_rows_at_design;

use crate::assembly::{Assembly, Tangent};
use crate::error::SolverError;
use crate::kkt::{Accuracy, AutoKkt, BackendChoice, KktBackend, KktValues};
use crate::kkt::{FactorCounters, KktOptions};
use crate::options::{ArcStep, LoadPath, Mode, SolverOptions, State};
use crate::replay::{self, Taping};
use crate::results::{Diagnostics, LimitPoint, PathRates, RedundantRow, StepResult, Sweep};
use elastokin_core::{JointId, Model, Pose, BODY_DOFS};
use kept::{KeptAt, KeptTangent};

/// Counters that prove reuse: how often each costly operation ran.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Counters {
    /// Assemblies of the KKT system.
    pub assemblies: u64,
    /// From the factorization: symbolic analyses, numeric factorizations, solves, refinement steps.
    pub factor: FactorCounters,
}

/// Solves one [`Model`]: analyses its KKT pattern once, then walks load paths with factorization reuse.
#[derive(Debug)]
pub struct StaticSolver<'m> {
    model: &'m Model,
    options: SolverOptions,
    work: SolverWorkspace,
    diagnostics: Diagnostics,
    assemblies: u64,
    /// Norm of the displacement response to a unit load-parameter increment at the start of the last
    /// corrected sweep (the reference for recognising a limit point).
    initial_response: Option<f64>,
    /// Force residual left by rounding in the stiffest element (see `update_roundoff_floor`).
    roundoff_floor: f64,
    /// The tangent last assembled with a stiffness, and the one last factorized: chord iterations start
    /// from a kept factorization only when it is of the full tangent.
    assembled: Option<Tangent>,
    factored: Option<Tangent>,
    /// Its rank in the recording or replay it takes part in, if any.
    taped: Option<replay::Taped>,
    /// A recording's second dense LU, which factorizes the tangent at each recorded equilibrium for the
    /// replays and leaves the solver's own factorization as the run left it.
    recorded_lu: Option<crate::kkt::DenseLu>,
    /// Which steps of a sweep a replay moves (all when `None`).
    replay_rows: Option<replay::ReplayRows>,
    /// In a replay, the recorded model and what this one differs from it in.
    touched: Option<replay::Touched>,
    /// In a replay, each equilibrium it moved with recorded factors, and those factors: a tangent
    /// factorized there is solved with them ([`StaticSolver::factorize_tangent`]).
    moved_equilibria: Vec<(State, replay::Factors)>,
    /// The recorded factors the tangent last factorized is solved with, when it was at one of
    /// `moved_equilibria` (then `factored` is `None`: the solver's own factorization is of no state).
    kept_tangent: Option<KeptAt>,
    /// The recording or replay it takes part in ([`replay`]), if any.
    taping: Taping,
}

/// What a [`StaticSolver`] allocates for one topology of model: the KKT pattern and slot maps, the
/// factorization's analysis and every buffer. A design study keeps it from one variant to the next
/// ([`StaticSolver::into_workspace`], [`StaticSolver::with_workspace`]); a replay's solvers leave theirs
/// to the next replays of the same recording ([`crate::replay`]). Its default holds nothing: what a solver
/// that gave its workspace away keeps.
#[derive(Debug, Default)]
pub struct SolverWorkspace {
    topology: Topology,
    backend: BackendChoice,
    kkt: KktOptions,
    assembly: Assembly,
    factor: AutoKkt,
    rhs: Vec<f64>,
    /// `Jᵀλ` of the last residual, and a solve's working vector after it.
    scratch: Vec<f64>,
    krylov: Krylov,
    /// The last corrected steps' increments, for the next step's predictor.
    history: Option<PathHistory>,
    /// What the Newton iterations of the current call have moved `[Δq; Δλ]`, summed.
    moved: Vec<f64>,
    /// The tangent a replay solves with recorded factors, as assembled at the moved equilibrium, and a
    /// solve's right-hand side ([`StaticSolver::solve_kept`]).
    kept: KeptTangent,
    /// The replay its solver took part in, whose tape it goes to when dropped.
    taping: Taping,
}

/// A replay's solver leaves its workspace to the next replays of the recording: dropped while its replay
/// is under way, a solver's workspace goes to the replay's tape (the default left in its place holds
/// nothing).
impl Drop for SolverWorkspace {
    fn drop(&mut self) {
        if self.holds() && self.taping.replaying() {
            let taping = std::mem::take(&mut self.taping);
            // Dropped here, with no taping left to offer it to again, when the tape keeps no more.
            drop(taping.leave_workspace(std::mem::take(self)));
        }
    }
}

impl SolverWorkspace {
    /// Whether it holds a solver's allocations (not the default a solver that gave them away keeps).
    pub(crate) fn holds(&self) -> bool {
        self.assembly.n > 0 || !self.rhs.is_empty()
    }

    /// Forgets the steps the predictor extrapolates from, keeping their storage for the next path: the
    /// next corrected step starts from the last equilibrium.
    fn forget_path(&mut self) {
        if let Some(h) = self.history.as_mut() {
            h.count = 0;
        }
    }
}

/// What a model's KKT pattern is made from: its bodies, and the bodies each element and joint couples
/// (with the joint's row count).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
struct Topology {
    bodies: usize,
    elements: Vec<[Option<usize>; 2]>,
    joints: Vec<([Option<usize>; 2], usize)>,
}

impl Topology {
    fn of(model: &Model) -> Self {
        let id = |b: elastokin_core::BodyRef| b.id().map(|i| i.0);
        Topology {
            bodies: model.bodies().len(),
            elements: model.elements().iter().map(|e| e.bodies().map(id)).collect(),
            joints: model.joints().iter().map(|j| ([id(j.spec.body_i), id(j.spec.body_j)], j.rows.len())).collect(),
        }
    }
}

/// The increments `[Δq; Δλ]` of the last converged corrected steps along a path, newest first, the
/// newest ending at load parameter `t_end`.
#[derive(Debug)]
struct PathHistory {
    /// Each step's increment and its change of load parameter; the first `count` are in use, each
    /// ending where the one before it (newer) began.
    steps: [Vec<f64>; PREDICTOR_STEPS],
    dts: [f64; PREDICTOR_STEPS],
    count: usize,
    t_end: f64,
    /// The increment the predictor applied to the step now being taken.
    predicted: Vec<f64>,
}

/// How many past steps the predictor extrapolates from: the polynomial through the last
/// `PREDICTOR_STEPS + 1` equilibria (cubic). Measured on the MacPherson's 161-point travel sweep: the
/// residual a predicted state leaves is 0.05 N with the quadratic and 4e-4 N with the cubic, and the
/// chord iterations per step fall from 3.7 to 2.1 (`cargo xtask bench --only error-vs-time`).
const PREDICTOR_STEPS: usize = 3;

/// How a Newton solve starts and what bounds it.
#[derive(Debug, Clone, Copy)]
struct NewtonStart {
    /// Refuse a corrector that travels further than the predictor (see [`StaticSolver::newton`]).
    guard: bool,
    /// How far a predictor applied before the call moved the state (norm of its `Δq`).
    predicted: f64,
    /// Start from a freshly factorized tangent even when a kept one could be used.
    fresh: bool,
}

/// A chord iteration whose scaled residual falls by less than this factor gets a fresh tangent: measured
/// on the shipped models' 161-point travel sweeps (`cargo xtask bench --only error-vs-time`), where a
/// refactorization costs about as much as four chord iterations.
const CHORD_CONTRACTION: f64 = 0.25;

/// Rounding noise of a stiff element's force, in units of `ε·k·|P|`: a few operations each add `ε`.
const ROUNDOFF_FACTOR: f64 = 64.0;

/// Krylov dimension and restarts of the skew-part GMRES, and its relative tolerance.
const KRYLOV_DIM: usize = 30;
const KRYLOV_RESTARTS: usize = 4;
const KRYLOV_TOL: f64 = 1e-13;

/// Which vector the preconditioned skew operator acts on.
#[derive(Clone, Copy)]
enum KrylovSlot {
    Iterate,
    Basis(usize),
}

/// GMRES workspace, allocated once, the first time a skew part appears.
#[derive(Debug, Default)]
struct Krylov {
    basis: Vec<Vec<f64>>,
    work: Vec<f64>,
    b: Vec<f64>,
    h: Vec<Vec<f64>>,
    cs: Vec<f64>,
    sn: Vec<f64>,
    g: Vec<f64>,
    y: Vec<f64>,
}

impl Krylov {
    fn ensure(&mut self, size: usize) {
        if self.work.len() != size {
            self.basis = vec![vec![0.0; size]; KRYLOV_DIM];
            self.work = vec![0.0; size];
            self.b = vec![0.0; size];
            self.h = vec![vec![0.0; KRYLOV_DIM]; KRYLOV_DIM + 1];
            self.cs = vec![0.0; KRYLOV_DIM];
            self.sn = vec![0.0; KRYLOV_DIM];
            self.g = vec![0.0; KRYLOV_DIM + 1];
            self.y = vec![0.0; KRYLOV_DIM];
        }
    }
}

fn norm2(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// A path counts as stuck at a limit point when the response to a load increment has grown this much.
const LIMIT_RESPONSE_GROWTH: f64 = 10.0;

/// How closely a sweep locates a limit point it stops at, relative to the range of its load parameter
/// `|end − start|`: the fold lies between [`LimitPoint::t`] and [`LimitPoint::beyond`], which bisection
/// brings this close.
pub const LIMIT_POINT_TOLERANCE: f64 = 1e-6;

/// What a paper step tells of a fold.
struct PaperStep {
    /// `‖Δq‖ / |Δt|`.
    response: f64,
    /// The largest change of a generalized load it makes (N, N·m).
    load_change: f64,
    /// The largest change of a driven constraint it makes (m, rad).
    drive_change: f64,
}

/// How a walk of the exact path under a paper-mode sweep ended.
enum ExactWalk {
    /// At its target.
    Reached,
    /// At a limit point.
    Limit(LimitPoint),
    /// Stuck, not at a limit point.
    Failed,
}

/// How a corrected step ended.
enum StepOutcome {
    /// At its target load, with the Newton iterations spent and the residual there.
    Reached { iterations: usize, residual: Residual },
    /// Not even after every cut: `attempted` is the load that failed last (the state is left at the last
    /// equilibrium found).
    Stuck { attempted: f64, iterations: usize, force: f64, constraint: f64 },
}

/// The larger of `a` and `b`, NaN if either is: a residual with a NaN in it is no residual (`f64::max`
/// would pass the NaN over, and call a state with a NaN force an equilibrium).
fn largest(a: f64, b: f64) -> f64 {
    if a.is_nan() {
        a
    } else if b > a || b.is_nan() {
        b
    } else {
        a
    }
}

struct Residual {
    force: f64,
    constraint: f64,
    force_scale: f64,
}

impl<'m> StaticSolver<'m> {
    /// Validates the model, finds redundant constraint rows (they are dropped and named in
    /// [`StaticSolver::diagnostics`]), analyses the KKT pattern once and checks at design that every body is
    /// restrained.
    pub fn new(model: &'m Model, options: SolverOptions) -> Result<Self, SolverError> {
        Self::build(model, options, None, Taping::default())
    }

    /// As [`StaticSolver::new`], the solver taking part in `taping`: the recording ([`replay::record`])
    /// or replay ([`replay::replay`]) the run that creates it was handed, if any.
    pub fn taped(model: &'m Model, options: SolverOptions, taping: &Taping) -> Result<Self, SolverError> {
        Self::build(model, options, None, taping.clone())
    }

    /// As [`StaticSolver::new`], reusing `workspace` — the pattern, slot maps, factorization analysis and
    /// buffers a solver of another model left ([`StaticSolver::into_workspace`]) — when `model` has the same
    /// topology: the same bodies, elements and joints between the same bodies, the same rows kept after
    /// the redundancy check, and the same factorization options. A design study's variants (other
    /// hardpoints, rates, loads) then skip the analysis. Whatever depends on values is done again for
    /// `model`: validation, the redundancy check and the restraint check at design. The factorization
    /// forgets its scaling and counters, so results do not depend on which variant the workspace served
    /// before (they are those of [`StaticSolver::new`], to the bit) and [`StaticSolver::counters`] shows
    /// `symbolic_analyses: 0` when the analysis was reused. A workspace of another topology is dropped
    /// and the model analysed afresh.
    pub fn with_workspace(
        model: &'m Model,
        options: SolverOptions,
        workspace: Option<SolverWorkspace>,
    ) -> Result<Self, SolverError> {
        Self::build(model, options, workspace, Taping::default())
    }

    fn build(
        model: &'m Model,
        options: SolverOptions,
        workspace: Option<SolverWorkspace>,
        taping: Taping,
    ) -> Result<Self, SolverError> {
        options.validate()?;
        model.validate()?;
        let poses = model.design_poses();
        // A replay of a solver that kept every row needs neither check again (see
        // `replay::replays_independent_rows`).
        let checked = taping.replays_independent_rows(model.constraint_rows());
        let dropped = if checked { Vec::new() } else { redundant_rows_at_design(model, options.redundancy_tolerance) };
        let mut is_dropped = vec![false; model.constraint_rows()];
        for &r in &dropped {
            is_dropped[r] = true;
        }
        let active: Vec<usize> = (0..model.constraint_rows()).filter(|&r| !is_dropped[r]).collect();
        let redundant = dropped
            .iter()
            .map(|&r| {
                let o = model.row_origin(r).expect("row exists");
                let jt = &model.joints()[o.joint.0];
                RedundantRow { row: r, joint: jt.name().to_string(), label: jt.rows[o.row].label }
            })
            .collect();
        let topology = Topology::of(model);
        let fits = |w: &SolverWorkspace| {
            w.topology == topology
                && w.assembly.active_rows == active
                && w.backend == options.backend
                && w.kkt == options.kkt
        };
        // A replay's solver takes the workspace a solver of an earlier replay of the recording left.
        let reusable = workspace.filter(fits).or_else(|| taping.spare_workspace(fits));
        let mut workspace = match reusable {
            Some(mut w) => {
                w.factor.reset();
                w.forget_path();
                w
            }
            None => {
                let assembly = Assembly::new(model, active);
                let pattern = assembly.kkt_pattern();
                let factor = AutoKkt::analyze(&pattern, options.kkt.clone(), options.backend)?;
                let size = assembly.n + assembly.m();
                SolverWorkspace {
                    topology,
                    backend: options.backend,
                    kkt: options.kkt.clone(),
                    assembly,
                    factor,
                    rhs: vec![0.0; size],
                    scratch: vec![0.0; size],
                    krylov: Krylov::default(),
                    history: None,
                    moved: vec![0.0; size],
                    kept: KeptTangent::default(),
                    taping: Taping::default(),
                }
            }
        };
        workspace.taping = taping.clone();
        let (taped, touched) = match taping.register(model, &workspace.assembly.active_rows)? {
            Some((taped, recorded)) => (Some(taped), recorded.and_then(|r| replay::Touched::between(r, model))),
            None => (None, None),
        };
        let mut solver = StaticSolver {
            model,
            options,
            work: workspace,
            diagnostics: Diagnostics { redundant },
            assemblies: 0,
            initial_response: None,
            roundoff_floor: 0.0,
            assembled: None,
            factored: None,
            taped,
            recorded_lu: None,
            replay_rows: None,
            touched,
            moved_equilibria: Vec::new(),
            kept_tangent: None,
            taping,
        };
        if !checked {
            solver.check_restrained(&poses)?;
        }
        Ok(solver)
    }

    /// Which steps of the sweeps a replay of this solver moves ([`replay::ReplayRows`]; every step when
    /// `None`, as without). Outside a replay it changes nothing.
    pub fn replay_rows(&mut self, rows: Option<replay::ReplayRows>) {
        self.replay_rows = rows;
    }

    /// The solver's allocations, to solve another model of the same topology with
    /// [`StaticSolver::with_workspace`].
    pub fn into_workspace(mut self) -> SolverWorkspace {
        // Given away, it is no replay's to take back.
        self.work.taping = Taping::default();
        self.work
    }

    /// The model.
    pub fn model(&self) -> &'m Model {
        self.model
    }

    /// What the analysis found (redundant rows dropped).
    pub fn diagnostics(&self) -> &Diagnostics {
        &self.diagnostics
    }

    /// Operation counters since construction.
    pub fn counters(&self) -> Counters {
        Counters { assemblies: self.assemblies, factor: self.work.factor.counters() }
    }

    /// Model row index of each active multiplier.
    pub fn active_rows(&self) -> &[usize] {
        &self.work.assembly.active_rows
    }

    /// The design state at load parameter `t` (multipliers zero).
    pub fn design_state(&self, t: f64) -> State {
        State { poses: self.model.design_poses(), lambda: vec![0.0; self.work.assembly.m()], t }
    }

    fn assemble(&mut self, state: &State, tangent: Option<Tangent>) {
        self.assemblies += 1;
        if tangent.is_some() {
            self.assembled = tangent;
        }
        self.work.assembly.assemble(self.model, &state.poses, state.t, &state.lambda, tangent);
    }

    fn factorize(&mut self) -> Result<crate::kkt::FactorReport, SolverError> {
        let a = &self.work.assembly;
        let values = KktValues { k: &a.k_values, k_skew: a.has_skew.then_some(&a.k_skew[..]), j: &a.j_values };
        self.factored = None;
        self.kept_tangent = None;
        let report = self.work.factor.factorize(values).map_err(|e| self.named(e))?;
        self.factored = self.assembled;
        Ok(report)
    }

    /// Applies `Δq` (first `n` entries of `dx`) to the poses.
    fn apply(poses: &mut [Pose], dx: &[f64], scale: f64) {
        let mut d = [0.0; BODY_DOFS];
        for (b, pose) in poses.iter_mut().enumerate() {
            for k in 0..BODY_DOFS {
                d[k] = scale * dx[b * BODY_DOFS + k];
            }
            pose.apply_increment6(&d);
        }
    }

    /// Residual norms at the assembled state: `R = Jᵀλ − Q` and `Φ`.
    fn residual(&mut self, lambda: &[f64]) -> Residual {
        let n = self.work.assembly.n;
        self.work.assembly.jt_times(lambda, &mut self.work.scratch[..n]);
        let mut force: f64 = 0.0;
        let mut force_scale: f64 = self.work.assembly.force_scale.max(1.0);
        for c in 0..n {
            let jl = self.work.scratch[c];
            let q = self.work.assembly.applied[c];
            force = largest(force, (jl - q).abs());
            force_scale = force_scale.max(jl.abs()).max(q.abs());
        }
        let constraint = self.work.assembly.phi.iter().fold(0.0f64, |a, v| largest(a, v.abs()));
        Residual { force, constraint, force_scale }
    }

    /// [`StaticSolver::residual`] at `state`, refused where it is no finite number ([`Self::non_finite`]).
    fn finite_residual(&mut self, state: &State, what: &'static str) -> Result<Residual, SolverError> {
        let r = self.residual(&state.lambda);
        if r.force.is_finite() && r.constraint.is_finite() {
            Ok(r)
        } else {
            Err(self.non_finite(what, state.t))
        }
    }

    /// The error of a residual that is no finite number: the element whose force was none, by name, or
    /// else `what`.
    fn non_finite(&self, what: &'static str, t: f64) -> SolverError {
        match self.work.assembly.non_finite_element {
            Some(k) => SolverError::NonFiniteForce { element: self.model.elements()[k].name().to_string(), t },
            None => SolverError::NonFinite { what },
        }
    }

    fn converged(&self, r: &Residual) -> bool {
        let floor = self.roundoff_floor;
        r.force <= (self.options.force_tolerance * r.force_scale).max(floor)
            && r.constraint <= self.options.constraint_tolerance
    }

    /// The force residual that rounding alone leaves in a stiff element: `δ = Pⱼ − Pᵢ` is known to about
    /// `ε·|P|`, so a stiffness `k` leaves `k·ε·|P|` of noise. Below that no tolerance can be met.
    fn update_roundoff_floor(&mut self, poses: &[Pose]) {
        let k_max = self.work.assembly.k_values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let reach = poses.iter().fold(1.0f64, |a, p| a.max(p.position.amax()));
        self.roundoff_floor = ROUNDOFF_FACTOR * f64::EPSILON * k_max * reach;
    }

    /// The state of a step result (its poses, its active rows' multipliers and its load parameter), to
    /// continue from it or to ask for its [`StaticSolver::path_tangent`].
    pub fn state_of(&self, step: &StepResult) -> State {
        let lambda = self.work.assembly.active_rows.iter().map(|&row| step.multipliers[row]).collect();
        State { poses: step.poses.clone(), lambda, t: step.t }
    }

    fn step_result(&self, state: &State, iterations: usize, r: &Residual) -> StepResult {
        let mut multipliers = vec![0.0; self.model.constraint_rows()];
        for (k, &row) in self.work.assembly.active_rows.iter().enumerate() {
            multipliers[row] = state.lambda[k];
        }
        StepResult {
            t: state.t,
            poses: state.poses.clone(),
            multipliers,
            force_residual: r.force,
            force_scale: r.force_scale,
            constraint_residual: r.constraint,
            iterations,
        }
    }

    /// Walks `path` in `mode`, starting from the equilibrium at `path.start` found from the design pose.
    /// A path that meets a limit point stops there and returns what it found: see
    /// [`StaticSolver::sweep_from`].
    pub fn sweep(&mut self, path: LoadPath, mode: Mode) -> Result<Sweep, SolverError> {
        let mut state = self.design_state(path.start);
        self.sweep_from(&mut state, path, mode)
    }

    /// Walks `path` from `state` (which is first brought to equilibrium at `path.start`).
    ///
    /// ## At a limit point
    /// Where the path folds (its tangent turns singular: a load the structure cannot carry, or a driven
    /// motion the mechanism cannot make), load control finds no equilibrium beyond. The sweep stops there
    /// and still returns `Ok`: [`Sweep::steps`] holds every equilibrium found before the fold and
    /// [`Sweep::limit`] the fold itself, its load parameter located by bisection to
    /// [`LIMIT_POINT_TOLERANCE`]` · |end − start|`, with its equilibrium. [`Sweep::complete`] turns such a
    /// sweep into [`SolverError::LimitPoint`] for a caller that needs the whole path;
    /// [`StaticSolver::arc_length_sweep`] follows the path through the fold.
    ///
    /// How a fold is told from a failure: in [`Mode::Corrected`], a step that does not converge even
    /// after [`SolverOptions::max_step_cuts`] halvings is a limit point when the displacement response to
    /// a load increment has grown more than tenfold since the start of the path, and
    /// [`SolverError::NoConvergence`] otherwise. [`Mode::Paper`] takes no Newton steps: a paper step
    /// whose response grew tenfold, or whose drift grew by more than the load (or driven travel) it added
    /// (it jumped across a fold), is checked on the exact path, walked in corrected steps from the starting equilibrium as far
    /// as that step (and no further than the last check had to); a fold found there ends the sweep, and
    /// the paper steps past it are dropped. In both modes the bisection then narrows between
    /// the last load parameter with an equilibrium and the first without one, each trial a Newton solve
    /// from the last equilibrium found, its corrector kept within the reach of its predictor so that it
    /// cannot jump to another branch of the path.
    pub fn sweep_from(&mut self, state: &mut State, path: LoadPath, mode: Mode) -> Result<Sweep, SolverError> {
        self.taped_sweep(state, path, |solver, state| solver.walk_path(state, path, mode))
    }

    /// Corrected steps along `path` from `state`, an equilibrium at its start, with the load response
    /// there as the reference that tells a limit point.
    fn corrected_path(
        &mut self,
        state: &mut State,
        path: LoadPath,
        steps: &mut Vec<StepResult>,
    ) -> Result<Option<LimitPoint>, SolverError> {
        self.initial_response = self.load_response(state);
        let dt = (path.end - path.start) / path.steps as f64;
        self.corrected_steps(state, path, dt, steps)
    }

    /// Brings `state` (a pose at its own load parameter) to the equilibrium at `target` in corrected steps
    /// from the equilibrium at its own. Fails with [`SolverError::LimitPoint`] where the path meets a limit
    /// point short of `target`, and with `None` where it finds no equilibrium to start from or cannot go on.
    fn walk_to(&mut self, state: &mut State, target: f64) -> Result<StepResult, Option<SolverError>> {
        const STEPS: usize = 32;
        self.solve_equilibrium(state).map_err(|_| None)?;
        self.work.forget_path();
        let path = LoadPath::new(state.t, target, STEPS);
        let mut steps = Vec::with_capacity(STEPS);
        match self.corrected_path(state, path, &mut steps) {
            Ok(None) => steps.pop().ok_or(None),
            Ok(Some(limit)) => Err(Some(SolverError::LimitPoint { reached: limit.t })),
            Err(_) => Err(None),
        }
    }

    fn walk_path(&mut self, state: &mut State, path: LoadPath, mode: Mode) -> Result<Sweep, SolverError> {
        LoadPath::check_steps(path.steps)
            .map_err(|e| SolverError::InvalidInput { what: "load path", why: e.to_string() })?;
        if !path.start.is_finite() || !path.end.is_finite() {
            return Err(SolverError::InvalidInput {
                what: "load path",
                why: format!("need finite ends, got {} to {}", path.start, path.end),
            });
        }
        let from = state.poses.clone();
        state.t = path.start;
        self.work.forget_path();
        // Newton from the given pose straight to the path's start, guarded as a step is. Where that reaches
        // beyond what the tangent tells (past a limit point, onto another branch), or finds nothing, a start
        // away from load parameter 0 is walked to from the pose's equilibrium there (no travel, no load,
        // where every rig's path starts from its design pose): a limit point met on the way is said. Where
        // the walk finds no way either, Newton goes on unguarded from the pose (a design pose the preloads
        // do not balance settles far from it).
        let guarded = self.newton(state, NewtonStart { guard: true, predicted: 0.0, fresh: false });
        let first = match guarded.map(|(iterations, r)| self.step_result(state, iterations, &r)) {
            Ok(first) => first,
            Err(SolverError::NoConvergence { .. }) => {
                let m = state.lambda.len();
                let at = |t| State { poses: from.clone(), lambda: vec![0.0; m], t };
                let walked = if path.start != 0.0 {
                    *state = at(0.0);
                    self.walk_to(state, path.start)
                } else {
                    Err(None)
                };
                match walked {
                    Ok(first) => first,
                    Err(Some(limit)) => return Err(limit),
                    Err(None) => {
                        *state = at(path.start);
                        self.work.forget_path();
                        self.solve_equilibrium(state)?
                    }
                }
            }
            Err(e) => return Err(e),
        };
        let mut steps = Vec::with_capacity(path.steps + 1);
        steps.push(first);
        let dt = (path.end - path.start) / path.steps as f64;
        let limit = match mode {
            Mode::Paper => {
                // Taken only if a paper step looks like a fold (see `exact_walk`).
                self.initial_response = None;
                self.paper_steps(state, path, dt, &mut steps)?
            }
            Mode::Corrected => self.corrected_path(state, path, &mut steps)?,
        };
        if let Some(limit) = &limit {
            // The steps before the fold (paper steps may have gone past it; the last corrected step may be
            // the fold itself, which the limit point holds), after the starting equilibrium.
            let before = steps[1..].iter().take_while(|s| (limit.t - s.t) * dt.signum() > 0.0).count();
            steps.truncate(1 + before);
        }
        Ok(Sweep { mode, steps, limit, stuck: None })
    }
}
