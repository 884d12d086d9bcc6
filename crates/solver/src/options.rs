//! How a solver is asked to walk: the mode of its steps, the load path and its step limit, the state it
//! carries, the arc-length step, and the tolerances and policies of [`SolverOptions`].

use crate::error::SolverError;
use crate::kkt::auto::BackendChoice;
use crate::kkt::KktOptions;
use elastokin_core::Pose;

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
    /// LDLᵀ for large ones ([`crate::kkt`]).
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

    /// Refuses a step count no sweep takes: none, or more than [`MAX_STEPS`]. The error is why, in the
    /// words every front end shows (the command's `--steps`, a Python sweep's `steps`, a library call's
    /// [`LoadPath`]).
    pub fn check_steps(steps: usize) -> Result<(), StepsError> {
        match steps {
            0 => Err(StepsError::NoSteps),
            1..=MAX_STEPS => Ok(()),
            _ => Err(StepsError::TooMany { steps }),
        }
    }
}

/// A step count no sweep takes ([`LoadPath::check_steps`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum StepsError {
    /// None.
    #[error("a sweep needs at least 1 step, got 0")]
    NoSteps,
    /// More than [`MAX_STEPS`].
    #[error(
        "a sweep takes at most {MAX_STEPS} steps, got {steps}: every step keeps the solved model in memory and \
         costs solver time; for a finer look, narrow its range"
    )]
    TooMany {
        /// The steps asked for.
        steps: usize,
    },
}

/// The most load steps one sweep takes: every step keeps its solved state in memory and costs solver time,
/// so a finer look is a narrower range, not more steps. The one limit of every front end
/// ([`LoadPath::check_steps`]).
pub const MAX_STEPS: usize = 20_000;

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

/// The length of each step of an arc-length path ([`StaticSolver::arc_length_sweep`](crate::StaticSolver::arc_length_sweep)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ArcStep {
    /// In the load parameter's own unit (N for a force, m for a driven travel): the change of the load
    /// parameter that the first step makes along the path's tangent. Every later step has the same
    /// length in the scaled space, so it changes the load less where the path softens.
    Load(f64),
    /// In the scaled space `‖Δq‖² + ψ² Δt²` itself (ψ = ‖dq/dt‖ at the start).
    Scaled(f64),
}
