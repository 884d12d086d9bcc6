//! # elastokin-suspensions
//!
//! Suspension templates built from named hardpoints, the kinematics-and-compliance analyses a K&C rig
//! runs, and the wheel characteristics engineers read from them.
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
//! Dependencies: serde and serde_json for the model files and the K&C reports ([`kc`]), nalgebra for
//! vectors and the small symmetric eigenproblem of the plausibility check's condition estimate, thiserror
//! for errors. faer, sprs and rayon are left out here: the solving is the solver crate's. The tests use
//! rand and rand_chacha for the seeded model mutations of `tests/fuzz_models.rs` (a fixed seed: the same
//! cases every run).

pub mod analysis;
pub mod anti_roll_bar;
pub mod axle;
pub mod batch;
pub mod chrono;
pub mod connection;
pub mod corner;
pub mod double_wishbone;
pub mod general;
pub mod hardpoint;
pub mod kc;
pub mod macpherson;
pub mod model_file;
pub mod plausibility;

pub use anti_roll_bar::AntiRollBar;
pub use axle::{Axle, AxleRig, AxleRow, RollCentre};
pub use connection::{ArmMounts, BushingRates, Connection, SpringSpec, TieRodMounts};
pub use corner::{
    Corner, CornerParts, CornerTemplate, CrossAxle, LoadPoint, Rig, SteeringGeometry, TieRod, Wheel, WheelAttitude,
};
pub use double_wishbone::{DoubleWishbone, DoubleWishboneHardpoints};
pub use general::{AxleDef, GeneralCorner, SteeringLinkDef};
pub use hardpoint::Side;
pub use macpherson::{MacPherson, MacPhersonHardpoints};
pub use model_file::{FileError, SuspensionFile, Template};
pub use plausibility::{check_model, check_travel_rows, ModelCheck, Warning};
