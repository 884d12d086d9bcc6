//! # elastokin
//!
//! Quasi-static elastokinematics of suspensions: rigid parts joined by kinematic joints, rubber bushings
//! and springs, solved along a load path for the design parameters vehicle-dynamics engineers use.
//!
//! This facade re-exports the workspace crates so a user can depend on one package:
//! - [`core`]: poses, constraint primitives and joints, the [`Model`](core::Model);
//! - [`elements`]: bushings, coil springs, point loads;
//! - [`solver`]: KKT assembly, the quasi-definite LDLᵀ with reuse, paper and corrected stepping;
//! - [`suspensions`]: double-wishbone and MacPherson templates, model files, K&C analyses.
//!
//! Pick the crates directly to leave out what a build does not need: the solver alone pulls in neither
//! serde nor rayon (rayon and sprs are behind its `parallel` and `matrix-market` features). This facade
//! package also carries the `elastokin` command. What the command alone needs is behind the default
//! feature `command` (a package cannot keep dependencies for its binary alone): clap for its arguments,
//! csv for its tables, indicatif for progress bars on a terminal, ctrlc to stop on Ctrl-C; without it
//! (`default-features = false`, as the Python module builds) the library stands on its own. The library
//! itself uses serde_json for its reports and sha2 for the model file's hash in every result and humantime
//! for its date ([`provenance`]).
//!
//! [`plot`] draws the plots of the command and of the benchmark report: on plotters (SVG, and PNG
//! through the png encoder, with its text in a font compiled in so that no system font is needed), and
//! thiserror for its error type. Its tests read the SVG back with roxmltree.
//!
//! [`live`] serves a design edited from a browser: its routes as plain functions from request to response,
//! and the server that carries requests to them on a thread of its own (`live::LiveServer`, on tiny_http),
//! which the command and the Python module start; getrandom gives its token, subtle compares it in
//! constant time.
//!
//! [`html`] writes the K&C report as one self-contained HTML page; it escapes every text it prints with
//! html-escape, so names and messages from a model file cannot break the page.

pub use elastokin_core as core;
pub use elastokin_elements as elements;
pub use elastokin_solver as solver;
pub use elastokin_suspensions as suspensions;

pub mod html;
pub mod live;
mod markup;
pub mod plot;
pub mod provenance;
pub mod view;

/// The names most programs use.
pub mod prelude {
    pub use elastokin_core::{BodyId, BodyRef, JointSpec, Mat3, Model, ModelError, Pose, Vec3};
    pub use elastokin_solver::{LoadPath, Mode, SolverError, SolverOptions, StaticSolver, StepResult};
}
