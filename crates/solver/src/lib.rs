//! # elastokin-solver
//!
//! KKT assembly with a fixed pattern, a quasi-definite sparse LDLᵀ with factorization reuse, and the two
//! ways of walking a load path (paper eq. 9, and predictor + Newton corrector).
pub mod assembly;
pub mod dense_reference;
pub mod error;
pub mod kkt_factor;
pub mod results;
pub mod solver;

pub use error::SolverError;
pub use kkt_factor::{FactorCounters, KktOptions};
pub use results::{Diagnostics, JointReaction, RedundantRow, StepResult, Sweep};
pub use solver::{Counters, LoadPath, Mode, SolverOptions, State, StaticSolver};
