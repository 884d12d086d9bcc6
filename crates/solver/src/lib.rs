//! # elastokin-solver
//!
//! KKT assembly with a fixed pattern, a quasi-definite sparse LDLᵀ with factorization reuse, and the two
//! ways of walking a load path: the paper's linear recurrence (eq. 9) and a linear predictor followed by
//! Newton iterations on the exact residual. A sweep that meets a limit point stops there with every
//! equilibrium it found and the limit point located by bisection; arc-length continuation follows the path
//! through it.
//!
//! ```
//! use elastokin_core::{BodyRef, JointSpec, Model, Pose, Vec3};
//! use elastokin_elements::{CoilSpring, PointForce};
//! use elastokin_solver::{LoadPath, Mode, SolverOptions, StaticSolver};
//!
//! // A lever hinged at the origin about y, held by a spring, loaded at its tip.
//! let mut model = Model::new();
//! let lever = model.add_body("lever", Pose::at(Vec3::new(0.25, 0.0, 0.0))).unwrap();
//! model.add_joint(JointSpec::revolute("pivot", BodyRef::Ground, lever, Vec3::zeros(), Vec3::y())).unwrap();
//! let seat = Vec3::new(0.3, 0.0, 0.0);
//! let top = Vec3::new(0.0, 0.0, 0.2);
//! model.add_element(CoilSpring::new("spring", BodyRef::Ground, top, lever.into(), seat, 2e4, (seat - top).norm()).unwrap()).unwrap();
//! model.add_element(PointForce::new("tip", lever.into(), Vec3::new(0.5, 0.0, 0.0), Vec3::new(0.0, 0.0, -500.0)).unwrap()).unwrap();
//!
//! let mut solver = StaticSolver::new(&model, SolverOptions::default()).unwrap();
//! let sweep = solver.sweep(LoadPath::new(0.0, 1.0, 10), Mode::Corrected).unwrap();
//! let last = sweep.steps.last().unwrap();
//! assert!(last.force_residual <= 1e-9 * last.force_scale);
//! // One symbolic analysis for the whole sweep.
//! assert_eq!(solver.counters().factor.symbolic_analyses, 1);
//! ```
//!
//! ## Layers
//! Lowest first; each module imports only those before it (`xtask/src/tidy.rs` keeps the rule,
//! `ARCHITECTURE.md` draws it).
//! - [`kkt`]: the KKT system and its factorizations behind one interface ([`KktBackend`]), one module a
//!   stage: the pattern, the scaling, the refinement written once for every backend, the quasi-definite
//!   sparse LDLᵀ ([`KktFactor`](kkt::KktFactor): `analyze` once, `factorize` and `solve_in_place` per
//!   step, explicit workspaces), the dense LU, and the automatic choice. The sparse path factorizes the
//!   augmented-Lagrangian form `[K + ρJᵀJ, Jᵀ; J, −(ε/ρ)I]` after symmetric scaling and refines against the
//!   true KKT, because plain, Bunch–Kaufman and dynamically regularised LDLᵀ on the saddle-point matrix
//!   either fail or lose the multipliers (joint forces) on stiff models (see [`kkt::sparse_ldlt`]).
//!   [`dense_reference`] beside it: a pivoted dense solve of the true KKT, the independent reference of
//!   tests and benchmarks.
//! - [`error`] and [`redundancy`] (which constraint rows repeat others, by a rank test of `J` alone).
//! - [`assembly`]: the pattern and slot maps of one model; values written in place. [`options`]: the mode,
//!   the load path and its step limit, the state, the solver's options.
//! - [`mobility`]: how a model can move at design counting only its joints, and how well its elements hold
//!   those motions (the condition of the reduced stiffness), by the sparse factorizations.
//! - [`results`]: what a solve returns.
//! - [`replay`]: a run's solves recorded, and the run replayed on a moved model with each equilibrium
//!   moved by one Newton iteration, solved with the recorded tangent's factors: the derivatives of
//!   whatever a run computes, through its equilibria, with none solved again.
//! - [`solver`]: [`StaticSolver`] — equilibrium, sweeps in both modes, the predictor, limit points, arc
//!   length, diagnostics.
//!
//! ## Dependencies
//! faer for the sparse LDLᵀ; nalgebra for the small fixed-size algebra and the dense reference;
//! thiserror for [`SolverError`]. rayon behind `parallel` evaluates elements in parallel when a scene has
//! at least [`assembly::PARALLEL_ELEMENTS`]-many (below that the pool costs more than it saves); sprs
//! behind `matrix-market` writes a KKT system as Matrix Market for inspection in other tools. serde is
//! left out: results are plain structs that the suspensions crate serialises in its own file formats.

pub mod assembly;
pub mod dense_reference;
pub mod error;
pub mod kkt;
pub mod mobility;
pub mod options;
pub mod redundancy;
pub mod replay;
pub mod results;
pub mod solver;

pub use error::SolverError;
pub use kkt::{Accuracy, BackendChoice, FactorCounters, KktBackend, KktOptions};
pub use options::{ArcStep, LoadPath, Mode, SolverOptions, State, StepsError, MAX_STEPS};
pub use results::{Diagnostics, JointReaction, LimitPoint, PathRates, RedundantRow, StepResult, Sweep};
pub use solver::{Counters, SolverWorkspace, StaticSolver, LIMIT_POINT_TOLERANCE};
