//! Typed errors of the solver. Each names what failed and says what to change.

use crate::kkt_factor::FactorError;
use elastokin_core::ModelError;
use thiserror::Error;

/// Why a solve or sweep did not produce a result.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SolverError {
    /// The model itself is inconsistent.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// The linear algebra refused the system.
    #[error(transparent)]
    Factor(#[from] FactorError),
    /// A body can move in some direction that no joint, bushing or spring resists.
    #[error("body '{body}' is not restrained in {motion}: add a joint, bushing or spring that holds it, or a driver")]
    Unrestrained {
        /// The body that moves most along the free direction.
        body: String,
        /// Readable description of the free motion.
        motion: String,
    },
    /// Newton did not converge even after cutting the load step.
    #[error(
        "no equilibrium found at load parameter {t}: after {iterations} iterations the force residual is \
         {force_residual:.3e} N and the constraint residual {constraint_residual:.3e} m{}; take smaller steps or \
         check the model for a mechanism",
        last_converged.map_or(String::new(), |t| format!("; last converged load parameter {t}"))
    )]
    NoConvergence {
        /// Load parameter attempted.
        t: f64,
        /// Last load parameter at which equilibrium was found (none when the first equilibrium failed).
        last_converged: Option<f64>,
        /// Iterations spent at the last attempt.
        iterations: usize,
        /// Scaled force residual at the end.
        force_residual: f64,
        /// Constraint residual at the end.
        constraint_residual: f64,
    },
    /// The path reached a limit point: the tangent turned singular along it — a load the structure cannot
    /// carry, or a driven motion the mechanism cannot reach.
    #[error(
        "the path cannot go beyond load parameter {reached:.6}: the tangent turns singular there (a load the \
         structure cannot carry, or a driven motion the mechanism cannot reach); reduce the load or travel, or \
         follow a load path through the limit point with arc-length continuation (`StaticSolver::arc_length_sweep`)"
    )]
    LimitPoint {
        /// Largest load parameter for which equilibrium was found.
        reached: f64,
    },
    /// Non-finite numbers appeared or were given.
    #[error("non-finite value in {what}: check the model's inputs for NaN or infinite values")]
    NonFinite {
        /// Where.
        what: &'static str,
    },
    /// A load path or option that makes no sense.
    #[error("invalid {what}: {why}")]
    InvalidInput {
        /// What.
        what: &'static str,
        /// Why.
        why: String,
    },
}
