//! Typed errors of the solver. Each names what failed and says what to change.

use crate::kkt::FactorError;
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
    /// The factorization met a zero pivot it could not regularize, at the named body coordinate or joint
    /// row (the model's names: `'upright', its rotation about x`; `joint 'ball' row 'x'`).
    #[error(
        "the equations are singular at {part}: a part is free to move where nothing holds it, or a joint \
         repeats another; check the model's degrees of freedom and redundant joints, and add the missing mount \
         or remove the repeated joint"
    )]
    Singular {
        /// The body coordinate or joint row, in the model's names.
        part: String,
    },
    /// A solve gave a non-finite number, first at the named body coordinate or joint row.
    #[error(
        "the solution is not finite at {part}: the equations are numerically singular — a part is held by next \
         to nothing or a joint nearly repeats another; check the model's degrees of freedom and redundant joints"
    )]
    NonFiniteSolution {
        /// The body coordinate or joint row, in the model's names.
        part: String,
    },
    /// A body can move in some direction that no joint, bushing or spring resists.
    #[error(
        "'{body}' is free to move ({motion}): no joint, bushing or spring holds it that way; check the hardpoints \
         of its mounts (mounts all on one line leave it free to spin about that line) or add a mount"
    )]
    Unrestrained {
        /// The body that moves most along the free direction.
        body: String,
        /// Readable description of the free motion.
        motion: String,
    },
    /// Newton did not converge even after cutting the load step.
    #[error(
        "no equilibrium found at {t} (in the analysis's own unit: travel in m, force in N){}: after {iterations} \
         iterations the forces are out of balance by {force_residual:.3e} N and the joints open by \
         {constraint_residual:.3e} m; take more steps, or check the model for a part that is free to move",
        last_converged.map_or(String::new(), |t| format!(", the last one found at {t}"))
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
    /// carry, or a driven motion the mechanism cannot reach. A sweep itself returns what it found up to
    /// the limit point ([`Sweep::limit`](crate::Sweep::limit)); this error is for a caller that needs the
    /// whole path ([`Sweep::complete`](crate::Sweep::complete)), or an arc-length path that starts on one.
    #[error(
        "the suspension cannot go beyond {reached:.6} (in the analysis's own unit: travel in m, force in N): there it \
         locks or gives way (a load it cannot carry, or a travel its arms and tie rod cannot reach); narrow the \
         range, or check the hardpoints for an arm or tie rod that reaches its end of travel"
    )]
    LimitPoint {
        /// Largest load parameter for which equilibrium was found: the limit point's, to
        /// [`LIMIT_POINT_TOLERANCE`](crate::LIMIT_POINT_TOLERANCE) of the sweep's range.
        reached: f64,
    },
    /// Non-finite numbers appeared or were given.
    #[error("non-finite value in {what}: check the model's inputs for NaN or infinite values")]
    NonFinite {
        /// Where.
        what: &'static str,
    },
    /// An element's force came out NaN or infinite: its data, or its geometry degenerating at that state.
    #[error(
        "the force of '{element}' is no finite number at {t} (in the analysis's own unit: travel in m, force in \
         N): check its numbers in the model, and whether its geometry degenerates there (a spring whose seats \
         meet, a bushing turned half a turn)"
    )]
    NonFiniteForce {
        /// The element's name.
        element: String,
        /// Where on the path (the analysis's own unit: travel in m, force in N).
        t: f64,
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
