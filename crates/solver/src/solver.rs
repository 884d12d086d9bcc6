//! The quasi-static solver: equilibrium, paper-mode and corrected-mode load paths.
//!
//! ## Sign convention
//! Elements return the generalized force `Q` they apply; the constraint force on the bodies is `−Φ_qᵀλ`.
//! Equilibrium is `R(q, λ, t) = Φ_qᵀλ − Q(q, t) = 0`, `Φ(q, t) = 0`; stiffness `K = −∂Q/∂Δq` is positive for
//! a spring. A linear step therefore reads `K Δq + Φ_qᵀ λ = f` (DESIGN §4: `K` positive, loads on the
//! right, the opposite of the paper's sign of eq. 8).
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

use crate::assembly::{Assembly, Tangent};
use crate::error::SolverError;
use crate::kkt_backend::{Accuracy, AutoKkt, BackendChoice, KktBackend, KktValues};
use crate::kkt_factor::{redundant_rows, FactorCounters, KktOptions};
use crate::results::{Diagnostics, LimitPoint, RedundantRow, StepResult, Sweep};
use elastokin_core::{Model, Pose, BODY_DOFS};

/// How to walk a load path.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// The paper's linear recurrence (eq. 9).
    Paper,
    /// Linear predictor + Newton corrector on the true residual.
    Corrected,
}

/// Tolerances and switches of the solver.
#[derive(Debug, Clone, PartialEq)]
pub struct SolverOptions {
    /// Force residual tolerance, relative to the largest force of any element, load or joint (and at
    /// least 1 N): the net applied force vanishes at equilibrium, so it cannot be the scale. It is never
    /// asked below the rounding noise of the stiffest element, `64 ε k_max |P|_max` (a 1e9 N/m bushing
    /// 0.5 m from the origin leaves ~7e-6 N).
    pub force_tolerance: f64,
    /// Constraint residual tolerance (metres for position rows, radians for orientation rows).
    pub constraint_tolerance: f64,
    /// Newton iterations per load step before the step is cut.
    pub max_iterations: usize,
    /// The fast policy for corrected steps: predict each step by extrapolating the last steps, then
    /// correct by chord iterations (modified Newton) with the factorization kept across iterations and
    /// steps, assembling only the residual, and refactor when contraction is slow. On the shipped
    /// MacPherson's 161-point travel sweep it takes 8 factorizations where full Newton takes 326, at about
    /// a quarter of the time (`cargo xtask bench --only error-vs-time`). Off (default): full Newton from
    /// the last equilibrium, whose last quadratic step leaves results far inside the tolerance.
    pub reuse_factorization: bool,
    /// How many times a step may be halved before the path is declared stuck.
    pub max_step_cuts: usize,
    /// Largest rotation increment per Newton iteration (rad); bigger steps are scaled down.
    pub max_rotation_step: f64,
    /// Relative tolerance for declaring a constraint row redundant.
    pub redundancy_tolerance: f64,
    /// Options of the KKT factorization.
    pub kkt: KktOptions,
    /// Which factorization of the KKT system: by default the dense LU for small systems and the sparse
    /// LDLᵀ for large ones ([`crate::kkt_backend`]).
    pub backend: BackendChoice,
}

impl Default for SolverOptions {
    fn default() -> Self {
        SolverOptions {
            force_tolerance: 1e-9,
            constraint_tolerance: 1e-10,
            max_iterations: 30,
            reuse_factorization: false,
            max_step_cuts: 10,
            max_rotation_step: 0.5,
            redundancy_tolerance: 1e-9,
            kkt: KktOptions::default(),
            backend: BackendChoice::Auto,
        }
    }
}

impl SolverOptions {
    /// Refuses tolerances and limits that cannot work (NaN, zero, negative).
    pub fn validate(&self) -> Result<(), SolverError> {
        let positive = [
            ("force_tolerance", self.force_tolerance),
            ("constraint_tolerance", self.constraint_tolerance),
            ("max_rotation_step", self.max_rotation_step),
            ("redundancy_tolerance", self.redundancy_tolerance),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(SolverError::InvalidInput {
                    what: "solver option",
                    why: format!("{name} must be finite and positive, got {v}"),
                });
            }
        }
        if self.max_iterations == 0 {
            return Err(SolverError::InvalidInput {
                what: "solver option",
                why: "max_iterations must be at least 1".into(),
            });
        }
        Ok(())
    }
}

/// A load path: the load parameter `t` from `start` to `end` in `steps` equal steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadPath {
    /// First load parameter (equilibrium is found there first).
    pub start: f64,
    /// Last load parameter.
    pub end: f64,
    /// Number of steps.
    pub steps: usize,
}

impl LoadPath {
    /// `start..end` in `steps` steps.
    pub fn new(start: f64, end: f64, steps: usize) -> Self {
        LoadPath { start, end, steps }
    }
}

/// The evolving state: poses, multipliers (one per active row) and the load parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Body poses.
    pub poses: Vec<Pose>,
    /// Multipliers of the active constraint rows.
    pub lambda: Vec<f64>,
    /// Load parameter.
    pub t: f64,
}

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
}

/// What a [`StaticSolver`] allocates for one topology of model: the KKT pattern and slot maps, the
/// factorization's analysis and every buffer. A design study keeps it from one variant to the next
/// ([`StaticSolver::into_workspace`], [`StaticSolver::with_workspace`]).
#[derive(Debug)]
pub struct SolverWorkspace {
    topology: Topology,
    backend: BackendChoice,
    kkt: KktOptions,
    assembly: Assembly,
    factor: AutoKkt,
    rhs: Vec<f64>,
    scratch: Vec<f64>,
    krylov: Krylov,
    /// The last corrected steps' increments, for the next step's predictor.
    history: Option<PathHistory>,
    /// What the Newton iterations of the current call have moved `[Δq; Δλ]`, summed.
    moved: Vec<f64>,
}

impl SolverWorkspace {
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
#[derive(Debug, Clone, PartialEq, Eq)]
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

/// The length of each step of an arc-length path ([`StaticSolver::arc_length_sweep`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ArcStep {
    /// In the load parameter's own unit (N for a force, m for a driven travel): the change of the load
    /// parameter that the first step makes along the path's tangent. Every later step has the same
    /// length in the scaled space, so it changes the load less where the path softens.
    Load(f64),
    /// In the scaled space `‖Δq‖² + ψ² Δt²` itself (ψ = ‖dq/dt‖ at the start).
    Scaled(f64),
}

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
        Self::with_workspace(model, options, None)
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
        options.validate()?;
        model.validate()?;
        let poses = model.design_poses();
        let dropped = redundant_rows_at_design(model, options.redundancy_tolerance);
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
        let reusable = workspace.filter(|w| {
            w.topology == topology
                && w.assembly.active_rows == active
                && w.backend == options.backend
                && w.kkt == options.kkt
        });
        let workspace = match reusable {
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
                }
            }
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
        };
        solver.check_restrained(&poses)?;
        Ok(solver)
    }

    /// The solver's allocations, to solve another model of the same topology with
    /// [`StaticSolver::with_workspace`].
    pub fn into_workspace(self) -> SolverWorkspace {
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
        let n = self.work.assembly.n;
        self.factorize_tangent(state)?;
        self.load_direction_rhs();
        self.solve_with_skew(Accuracy::Refined)?;
        Ok(self.work.rhs[..n].to_vec())
    }

    /// Assembles and factorizes the tangent at `state` for [`StaticSolver::solve_factored`].
    pub fn factorize_tangent(&mut self, state: &State) -> Result<(), SolverError> {
        self.assemble(state, Some(Tangent::Full));
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

    fn factorize(&mut self) -> Result<crate::kkt_factor::FactorReport, SolverError> {
        let a = &self.work.assembly;
        let values = KktValues { k: &a.k_values, k_skew: a.has_skew.then_some(&a.k_skew[..]), j: &a.j_values };
        self.factored = None;
        let report = self.work.factor.factorize(values)?;
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
            force = force.max((jl - q).abs());
            force_scale = force_scale.max(jl.abs()).max(q.abs());
        }
        let constraint = self.work.assembly.phi.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        Residual { force, constraint, force_scale }
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

    /// Newton on the true residual at the state's load parameter. Returns iterations used.
    ///
    /// With [`SolverOptions::reuse_factorization`] it is a chord method: iterations solve with the
    /// factorization kept from an earlier full tangent — of this call, or of an earlier step when
    /// nothing else has been factorized since — and assemble the residual alone; a fresh tangent is
    /// assembled and factorized only when an iteration's residual (each part over its tolerance) falls by
    /// less than [`CHORD_CONTRACTION`]. Convergence is judged on the true residual either way.
    ///
    /// With `start.guard`, the corrector may not travel further than the first increment plus any
    /// predictor applied before the call: a longer walk means Newton left the path — across a limit
    /// point to another branch, typically — and the step is refused so that the caller cuts it.
    fn newton(&mut self, state: &mut State, start: NewtonStart) -> Result<(usize, Residual), SolverError> {
        let n = self.work.assembly.n;
        let m = self.work.assembly.m();
        let reuse = self.options.reuse_factorization;
        // Whether the factorization in hand may serve this iteration.
        let mut factored = reuse && !start.fresh && self.factored == Some(Tangent::Full);
        let mut first_norm = 0.0;
        let mut corrector_travel = 0.0;
        let mut last_merit = f64::INFINITY;
        let mut iter = 0;
        self.work.moved.fill(0.0);
        loop {
            let refactor = !factored;
            self.assemble(state, if refactor { Some(Tangent::Full) } else { None });
            if refactor {
                self.update_roundoff_floor(&state.poses);
            }
            let r = self.residual(&state.lambda);
            if !(r.force.is_finite() && r.constraint.is_finite()) {
                return Err(SolverError::NonFinite { what: "residual" });
            }
            if self.converged(&r) {
                return Ok((iter, r));
            }
            if iter == self.options.max_iterations {
                return Err(SolverError::NoConvergence {
                    t: state.t,
                    last_converged: None,
                    iterations: iter,
                    force_residual: r.force,
                    constraint_residual: r.constraint,
                });
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
            if iter == 0 {
                first_norm = step_norm;
            } else {
                corrector_travel += step_norm;
                // The allowance is what closing the joints to their tolerance may take: a predictor of
                // nothing (an ideal linkage held by its rig does not move under a load) still leaves the
                // start's converged joint gaps, up to the tolerance, to close.
                let allowance = 100.0 * self.options.constraint_tolerance;
                if start.guard && corrector_travel > start.predicted + first_norm + allowance {
                    return Err(SolverError::NoConvergence {
                        t: state.t,
                        last_converged: None,
                        iterations: iter,
                        force_residual: r.force,
                        constraint_residual: r.constraint,
                    });
                }
            }
            let max_rot = (0..n).filter(|c| c % BODY_DOFS >= 3).fold(0.0f64, |a, c| a.max(self.work.rhs[c].abs()));
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
    fn merit(&self, r: &Residual) -> f64 {
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
    fn solve_with_skew(&mut self, accuracy: Accuracy) -> Result<(), SolverError> {
        let size = self.work.rhs.len();
        self.work.factor.solve_in_place(&mut self.work.rhs, accuracy)?;
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
    fn preconditioned_skew(&mut self, which: KrylovSlot) -> Result<(), SolverError> {
        let n = self.work.assembly.n;
        let size = self.work.rhs.len();
        let k = &mut self.work.krylov;
        let v: &[f64] = match which {
            KrylovSlot::Iterate => &self.work.rhs[..n],
            KrylovSlot::Basis(j) => &k.basis[j][..n],
        };
        self.work.assembly.skew_times(v, &mut k.work[..n]);
        k.work[n..size].fill(0.0);
        self.work.factor.solve_in_place(&mut k.work[..size], Accuracy::Refined)?;
        Ok(())
    }

    /// Static equilibrium at `state.t`, by Newton from `state`.
    pub fn equilibrium(&mut self, state: &mut State) -> Result<StepResult, SolverError> {
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
        let n = self.work.assembly.n;
        let m = self.work.assembly.m();
        let mut state = self.state_of(step);
        self.assemble(&state, Some(Tangent::Full));
        let r = self.residual(&state.lambda);
        if !(r.force.is_finite() && r.constraint.is_finite()) {
            return Err(SolverError::NonFinite { what: "residual" });
        }
        self.factorize()?;
        self.newton_increment()?;
        Self::apply(&mut state.poses, &self.work.rhs[..n], 1.0);
        for k in 0..m {
            state.lambda[k] += self.work.rhs[n + k];
        }
        self.assemble(&state, None);
        let after = self.residual(&state.lambda);
        Ok(self.step_result(&state, 1, &after))
    }

    /// The Newton increment `[Δq; Δλ]` into `rhs`, from `rhs = [Q − Jᵀλ ; −Φ]` at the assembled state and
    /// the factorized tangent (`scratch` holds `Jᵀλ` from [`Self::residual`]).
    fn newton_increment(&mut self) -> Result<(), SolverError> {
        Self::residual_rhs(&self.work.assembly, &self.work.scratch, &mut self.work.rhs);
        self.solve_with_skew(Accuracy::Increment)?;
        if self.work.rhs.iter().any(|v| !v.is_finite()) {
            return Err(SolverError::NonFinite { what: "Newton increment" });
        }
        Ok(())
    }

    /// `out = [Q − Jᵀλ ; −Φ]` at the assembled state, `jt_lambda` holding `Jᵀλ` (from [`Self::residual`]).
    fn residual_rhs(assembly: &Assembly, jt_lambda: &[f64], out: &mut [f64]) {
        let n = assembly.n;
        for c in 0..n {
            out[c] = assembly.applied[c] - jt_lambda[c];
        }
        for k in 0..assembly.m() {
            out[n + k] = -assembly.phi[k];
        }
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
        if path.steps == 0 || !path.start.is_finite() || !path.end.is_finite() {
            return Err(SolverError::InvalidInput {
                what: "load path",
                why: format!(
                    "need finite ends and at least one step, got {} to {} in {} steps",
                    path.start, path.end, path.steps
                ),
            });
        }
        state.t = path.start;
        self.work.forget_path();
        let first = self.equilibrium(state)?;
        let mut steps = Vec::with_capacity(path.steps + 1);
        steps.push(first);
        let dt = (path.end - path.start) / path.steps as f64;
        let limit = match mode {
            Mode::Paper => {
                // Taken only if a paper step looks like a fold (see `exact_walk`).
                self.initial_response = None;
                self.paper_steps(state, path, dt, &mut steps)?
            }
            Mode::Corrected => {
                self.initial_response = self.load_response(state);
                self.corrected_steps(state, path, dt, &mut steps)?
            }
        };
        if let Some(limit) = &limit {
            // The steps before the fold (paper steps may have gone past it; the last corrected step may be
            // the fold itself, which the limit point holds), after the starting equilibrium.
            let before = steps[1..].iter().take_while(|s| (limit.t - s.t) * dt.signum() > 0.0).count();
            steps.truncate(1 + before);
        }
        Ok(Sweep { mode, steps, limit })
    }

    /// One paper step's increment `[Δq; λⁿ]` into `rhs` from `state`, with what tells a fold: see
    /// [`PaperStep`].
    fn paper_increment(&mut self, state: &State, dt: f64, carried: &[f64]) -> Result<PaperStep, SolverError> {
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

    fn paper_steps(
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
                return Err(SolverError::NonFinite { what: "paper-mode step" });
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
            let r = self.residual(&state.lambda);
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
    fn exact_walk(
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

    fn corrected_steps(
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
    fn corrected_step(
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

    /// The predictor of a corrected step under [`SolverOptions::reuse_factorization`]: moves `state` (an
    /// equilibrium) by the increment extrapolated to a step of `dt` from the last steps' increments —
    /// the polynomial through the last equilibria, up to [`PREDICTOR_STEPS`] steps back — when the last
    /// step ended where `state` is. Returns the norm of the `Δq` it applied, `None` when it applied
    /// nothing.
    ///
    /// The increments are those the steps' Newton iterations summed in the tangent space: along a smooth
    /// path they are a smooth function of the load parameter, so a polynomial of degree `p` through the
    /// last `p + 1` equilibria errs by `O(dt^{p+1})`, and the chord iterations that follow start that
    /// much closer.
    fn predict(&mut self, state: &mut State, dt: f64) -> Option<f64> {
        let n = self.work.assembly.n;
        if !self.options.reuse_factorization {
            return None;
        }
        let h = self.work.history.as_mut().filter(|h| h.t_end == state.t && h.count > 0)?;
        // Nodes: the load parameter of each equilibrium relative to the newest, 0, −dt₁, −dt₁−dt₂, …
        let mut nodes = [0.0; PREDICTOR_STEPS + 1];
        for k in 1..=h.count {
            nodes[k] = nodes[k - 1] - h.dts[k - 1];
        }
        // Lagrange weights of the equilibria at `dt`; the state at node k is minus the sum of the newer
        // increments, so increment i weighs minus the weights of every node older than it.
        let mut lagrange = [0.0; PREDICTOR_STEPS + 1];
        for (k, l) in lagrange.iter_mut().enumerate().take(h.count + 1) {
            *l = (0..=h.count).filter(|&j| j != k).map(|j| (dt - nodes[j]) / (nodes[k] - nodes[j])).product();
        }
        h.predicted.fill(0.0);
        for i in 0..h.count {
            let w = -lagrange[i + 1..=h.count].iter().sum::<f64>();
            for (p, d) in h.predicted.iter_mut().zip(&h.steps[i]) {
                *p += w * d;
            }
        }
        if h.predicted.iter().any(|v| !v.is_finite()) {
            return None;
        }
        Self::apply(&mut state.poses, &h.predicted[..n], 1.0);
        for (l, d) in state.lambda.iter_mut().zip(&h.predicted[n..]) {
            *l += d;
        }
        Some(norm2(&h.predicted[..n]))
    }

    /// Keeps the increment of a corrected step that converged — the predictor's, if `predicted`, plus
    /// what Newton moved — for the next step's predictor.
    fn remember_step(&mut self, predicted: bool, dt: f64, t_end: f64) {
        if !self.options.reuse_factorization {
            return;
        }
        let size = self.work.moved.len();
        let h = self.work.history.get_or_insert_with(|| PathHistory {
            steps: std::array::from_fn(|_| vec![0.0; size]),
            dts: [0.0; PREDICTOR_STEPS],
            count: 0,
            t_end,
            predicted: vec![0.0; size],
        });
        // Older steps stay only when this one began where the newest of them ended (it was predicted).
        h.count = if predicted { (h.count + 1).min(PREDICTOR_STEPS) } else { 1 };
        h.steps.rotate_right(1);
        h.dts.rotate_right(1);
        // Not `0 · predicted + moved`: a refused prediction may have left non-finite numbers there.
        if predicted {
            for ((s, p), d) in h.steps[0].iter_mut().zip(&h.predicted).zip(&self.work.moved) {
                *s = p + d;
            }
        } else {
            h.steps[0].copy_from_slice(&self.work.moved);
        }
        h.dts[0] = dt;
        h.t_end = t_end;
    }

    /// Classifies a path that cannot be continued past `state` (the last equilibrium; `attempted` is the
    /// load parameter that failed): a limit point when the displacement response to a load increment has
    /// grown far beyond its value at the start of the path (the tangent along the path is losing its
    /// stiffness), then located by [`Self::locate_limit`]; otherwise a plain convergence failure.
    fn stuck(
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
    fn locate_limit(&mut self, state: &State, failed: f64, path: LoadPath) -> LimitPoint {
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
    fn load_response(&mut self, state: &State) -> Option<f64> {
        let n = self.work.assembly.n;
        self.assemble(state, Some(Tangent::Full));
        self.factorize().ok()?;
        self.load_direction_rhs();
        self.work.factor.solve_in_place(&mut self.work.rhs, Accuracy::Refined).ok()?;
        let norm = self.work.rhs[..n].iter().map(|v| v * v).sum::<f64>().sqrt();
        norm.is_finite().then_some(norm)
    }

    /// `rhs = [∂Q/∂t; −∂Φ/∂t]` from the assembled state.
    fn load_direction_rhs(&mut self) {
        let n = self.work.assembly.n;
        self.work.rhs[..n].copy_from_slice(&self.work.assembly.load_rate);
        for (k, r) in self.work.assembly.phi_rate.iter().enumerate() {
            self.work.rhs[n + k] = -r;
        }
    }

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
        let length = match step {
            ArcStep::Load(v) | ArcStep::Scaled(v) => v,
        };
        let (lo, hi) = (path.start.min(path.end), path.start.max(path.end));
        if path.steps == 0 || !(length.is_finite() && length > 0.0) || !(lo.is_finite() && hi.is_finite()) {
            return Err(SolverError::InvalidInput {
                what: "arc-length path",
                why: format!(
                    "need finite ends, at least one step and a positive step length, got {} to {} in {} steps \
                     of {length}",
                    path.start, path.end, path.steps
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
        let first = self.equilibrium(state)?;
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
                    Err(mut e @ (SolverError::NoConvergence { .. } | SolverError::NonFinite { .. })) => {
                        state.clone_from(&start);
                        cuts += 1;
                        if cuts as usize > self.options.max_step_cuts {
                            if let SolverError::NoConvergence { last_converged, .. } = &mut e {
                                *last_converged = Some(start.t);
                            }
                            return Err(e);
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
        Ok(Sweep { mode: Mode::Corrected, steps, limit: None })
    }

    /// One arc-length step of scaled length `arc` from the equilibrium `state`, oriented like the previous
    /// step `(Δq, Δt)`: the predictor along the tangent, then Newton on `(R, Φ)` with the normal-plane
    /// constraint. Leaves the step's `Δq` in `dq_total`; returns the iterations, the residual and `Δt`.
    fn arc_length_step(
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
        let mut last = (f64::INFINITY, f64::INFINITY);
        for iter in 0..self.options.max_iterations {
            self.assemble(state, Some(Tangent::Full));
            self.update_roundoff_floor(&state.poses);
            let r = self.residual(&state.lambda);
            last = (r.force, r.constraint);
            if self.converged(&r) {
                return Ok((iter, r, dt_total));
            }
            self.factorize()?;
            // Residual part: [Q − Jᵀλ; −Φ]
            Self::residual_rhs(&self.work.assembly, &self.work.scratch, r_dq);
            self.work.factor.solve_in_place(r_dq, Accuracy::Refined)?;
            self.load_direction_rhs();
            self.work.factor.solve_in_place(&mut self.work.rhs, Accuracy::Refined)?;
            let num: f64 = dq_total.iter().zip(&r_dq[..n]).map(|(a, b)| a * b).sum();
            let den: f64 = dq_total.iter().zip(&self.work.rhs[..n]).map(|(a, b)| a * b).sum::<f64>() + psi2 * dt_total;
            let dt = if den.abs() > 0.0 { -num / den } else { 0.0 };
            for c in 0..n + m {
                r_dq[c] += dt * self.work.rhs[c];
            }
            if r_dq.iter().any(|v| !v.is_finite()) {
                return Err(SolverError::NonFinite { what: "arc-length corrector" });
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

    /// Checks at design that every body is restrained, by inverse iteration on the factorized tangent.
    fn check_restrained(&mut self, poses: &[Pose]) -> Result<(), SolverError> {
        let n = self.work.assembly.n;
        if n == 0 {
            return Ok(());
        }
        let state = State { poses: poses.to_vec(), lambda: vec![0.0; self.work.assembly.m()], t: 0.0 };
        self.assemble(&state, Some(Tangent::Elastic));
        let report = self.factorize()?;
        if report.suspect_body_dofs.is_empty() {
            return Ok(());
        }
        // Inverse iteration: the solution of K x = random is dominated by the free direction.
        self.work.rhs.fill(0.0);
        let mut seed = 0x2545F4914F6CDD1Du64;
        for c in 0..n {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            self.work.rhs[c] = (seed % 1000) as f64 / 1000.0 - 0.5;
        }
        for _ in 0..2 {
            self.work.factor.solve_in_place(&mut self.work.rhs, Accuracy::Refined)?;
            let norm = self.work.rhs[..n].iter().map(|v| v * v).sum::<f64>().sqrt();
            if !(norm.is_finite() && norm > 0.0) {
                break;
            }
            for v in self.work.rhs[..n].iter_mut() {
                *v /= norm;
            }
            self.work.rhs[n..].fill(0.0);
        }
        let (body, motion) = describe_free_motion(self.model, &self.work.rhs[..n], &report.suspect_body_dofs);
        Err(SolverError::Unrestrained { body, motion })
    }
}

/// The constraint rows of `model` that depend on earlier rows at the design pose (model row numbering,
/// ascending): the rank-revealing check of the whole Jacobian that [`StaticSolver::new`] drops them by,
/// at relative tolerance `tolerance`. Its all-rows assembly is dropped on return, before the solver makes
/// the active one, so that the two are never held at once.
pub fn redundant_rows_at_design(model: &Model, tolerance: f64) -> Vec<usize> {
    let mut full = Assembly::new(model, (0..model.constraint_rows()).collect());
    full.assemble(model, &model.design_poses(), 0.0, &[], None);
    redundant_rows(full.m(), full.n, &full.j_col_ptr, &full.j_row_idx, &full.j_values, tolerance)
}

/// Names the body and motion of a (near-)null vector of the tangent.
fn describe_free_motion(model: &Model, x: &[f64], suspects: &[usize]) -> (String, String) {
    let nb = model.bodies().len();
    let mut best = (0usize, -1.0f64);
    for b in 0..nb {
        let w: f64 = x[b * BODY_DOFS..(b + 1) * BODY_DOFS].iter().map(|v| v * v).sum();
        if w > best.1 {
            best = (b, w);
        }
    }
    let b = if best.1 > 0.0 && best.1.is_finite() { best.0 } else { suspects.first().map_or(0, |d| d / BODY_DOFS) };
    let v = &x[b * BODY_DOFS..(b + 1) * BODY_DOFS];
    let t = elastokin_core::Vec3::new(v[0], v[1], v[2]);
    let r = elastokin_core::Vec3::new(v[3], v[4], v[5]);
    let pose = model.bodies()[b].design_pose;
    let motion = if !(t.norm().is_finite() && r.norm().is_finite()) || (t.norm() == 0.0 && r.norm() == 0.0) {
        let coordinate = ["x", "y", "z", "rotation about x", "rotation about y", "rotation about z"];
        coordinate[suspects.first().map_or(0, |d| d % BODY_DOFS)].to_string()
    } else if r.norm() > 1e-3 * t.norm() {
        // Any rotation (per metre of lever) beyond noise: a pure translation has none.
        // A rotation about an axis through the point p where the velocity is parallel to the axis.
        let axis = r / r.norm();
        let p = pose.position + r.cross(&t) / r.norm_squared();
        format!(
            "rotation about the axis ({:.3}, {:.3}, {:.3}) through ({:.4}, {:.4}, {:.4}) m",
            axis.x, axis.y, axis.z, p.x, p.y, p.z
        )
    } else {
        let d = t / t.norm();
        format!("translation along ({:.3}, {:.3}, {:.3})", d.x, d.y, d.z)
    };
    (model.bodies()[b].name.clone(), motion)
}
