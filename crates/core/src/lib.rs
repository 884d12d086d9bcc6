//! # elastokin-core
//!
//! Coordinates and constraints of the elastokin engine: body poses and the small-motion coordinates
//! `(Δr, Δπ)` of paper eq. 1 with their exact update, the constraint primitives of paper Table 1 and the
//! joints built from them, drivers, the [`ForceElement`] interface that bushings, springs and loads
//! implement, and the [`Model`] that owns a scene by name.
//!
//! ```
//! use elastokin_core::{JointSpec, Model, Pose, Vec3, BodyRef};
//!
//! let mut model = Model::new();
//! let arm = model.add_body("lower arm", Pose::at(Vec3::new(0.0, 0.7, -0.2))).unwrap();
//! model
//!     .add_joint(JointSpec::revolute("arm pivot", BodyRef::Ground, arm, Vec3::new(0.0, 0.5, -0.2), Vec3::x()))
//!     .unwrap();
//! assert_eq!(model.dofs(), 6);
//! assert_eq!(model.constraint_rows(), 5);
//! // A joint on a zero-length axis is refused with an error that names it.
//! let err = model
//!     .add_joint(JointSpec::revolute("bad", BodyRef::Ground, arm, Vec3::zeros(), Vec3::zeros()))
//!     .unwrap_err();
//! assert!(err.to_string().contains("'bad'"));
//! ```
//!
//! Dependencies: nalgebra for the fixed-size 3-D algebra (its `UnitQuaternion`, `Matrix3` and the
//! 12×12 pair blocks are stack values, so element evaluation does not allocate); thiserror for
//! [`ModelError`]; serde behind the `serde` feature. faer, sprs and rayon are left out: this crate has no
//! sparse or parallel work — that is the solver's.

pub mod body;
pub mod constraint;
pub mod element;
pub mod error;
pub mod joint;
pub mod math;
pub mod model;
pub mod pose;

pub use body::{Body, BodyId, BodyRef};
pub use constraint::{ConstraintRow, KinVec, PairMatrix, RowGradient, Side};
pub use element::{CloneElement, ElementEval, ElementReport, ElementRole, ForceElement, Sketch, SketchKind};
pub use error::ModelError;
pub use joint::{Joint, JointGeometryTaken, JointKind, JointSpec, Takes};
pub use math::{skew, Mat3, Vec3};
pub use model::{ElementId, JointId, Model, RowOrigin};
pub use pose::{Pose, BODY_DOFS};
