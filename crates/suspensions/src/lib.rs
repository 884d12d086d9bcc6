//! # elastokin-suspensions
//!
//! Suspensions described by named hardpoints, built into multibody models, run through the
//! kinematics-and-compliance analyses a K&C rig runs, and read into the wheel characteristics engineers
//! use.
//!
//! ```
//! use elastokin_suspensions::{DoubleWishbone, DoubleWishboneHardpoints, Connection, Rig, SpringSpec, Side};
//! use elastokin_suspensions::analysis::parallel_wheel_travel;
//! use elastokin_solver::Mode;
//!
//! let corner = DoubleWishbone {
//!     hardpoints: DoubleWishboneHardpoints::generic(),
//!     upper_arm_mounts: Connection::Ideal.into(),
//!     lower_arm_mounts: Connection::Ideal.into(),
//!     spring: SpringSpec { rate: 30e3, design_force: 4000.0 },
//!     tie_rod: Connection::Ideal,
//!     loaded_radius: 0.30,
//! }
//! .build(Side::Left, Rig::WheelTravel)
//! .unwrap();
//! let rows = parallel_wheel_travel(&corner, -0.08, 0.08, 16, Mode::Corrected).unwrap();
//! // At design the spin axis is +y: no toe, no camber.
//! assert!(rows[8].attitude.toe.abs() < 1e-12 && rows[8].attitude.camber.abs() < 1e-12);
//! ```
//!
//! ## Layers
//! Each module imports only those below it (`ARCHITECTURE.md` draws them; `xtask/src/tidy.rs` holds the
//! rule):
//! - [`description`]: what a user writes — the general form, the templates that expand into it, the
//!   vehicle, the limits;
//! - [`wheel`]: toe, camber and steering geometry read from a built model's poses;
//! - [`file`](mod@file): the model-file format — reading, key paths, line and column errors;
//! - [`drawing`]: what a view of a built model draws, each point on the body that carries it;
//! - [`import`]: other programs' files (Project Chrono's) read into descriptions;
//! - [`assembly`]: a description made into a model, with the rig that holds it;
//! - [`document`]: one way in for every document, read and built;
//! - [`analysis`]: the sweeps, solved;
//! - [`check`]: the plausibility of a model and of its sweeps;
//! - [`kc`]: the K&C suite, its figures and typed report;
//! - [`study`]: design studies of many variants;
//! - [`full_vehicle`]: the whole car from its two axles — roll, load transfer, the understeer budget;
//! - [`design`]: parameters of a model file and the sensitivities of the figures to them (each with its error estimate);
//! - [`compare`]: designs side by side, curves overlaid, figures and their differences.
//!
//! Dependencies: serde and serde_json for the model files and the K&C reports ([`kc`]), nalgebra for
//! the rank of the joints' Jacobian, the small symmetric eigenproblem of the plausibility check's
//! condition estimate and a tune's least-squares step, thiserror for errors; for [`design`], rayon to
//! take the parameters' sensitivities and a Monte Carlo's samples in parallel, clarabel for a tune's step
//! where bounds or packaging bind, rand and rand_chacha for the Monte Carlo's seeded samples (also the
//! seeded model mutations of `tests/fuzz_models.rs`). faer and sprs are left out here: the solving is the
//! solver crate's.

pub mod analysis;
pub mod assembly;
pub mod check;
pub mod compare;
pub mod description;
pub mod design;
pub mod document;
pub mod drawing;
pub mod file;
pub mod full_vehicle;
pub mod import;
pub mod kc;
pub mod study;
pub mod wheel;

pub use analysis::{AxleRow, RollCentre};
pub use assembly::{
    Axle, AxleRig, BuildMap, Built, Corner, CornerParts, CornerTemplate, CrossAxle, LoadPoint, Rig, TieRod,
};
pub use check::{check_model, check_travel_rows, ModelCheck, Warning};
pub use description::{
    AntiRollBar, ArmMounts, AxleDef, BushingRates, Connection, DoubleWishbone, DoubleWishboneHardpoints, GeneralCorner,
    MacPherson, MacPhersonHardpoints, Side, SpringSpec, SteeringLinkDef, Template, TieRodMounts,
};
pub use file::{FileError, SuspensionFile};
pub use wheel::{SteeringGeometry, Wheel, WheelAttitude};
