//! # elastokin-elements
//!
//! The force elements of elastokin, each an implementation of [`elastokin_core::ForceElement`]:
//!
//! | element | role | model |
//! |---|---|---|
//! | [`Bushing`] | elastic | six springs (rates or curves) in a local frame, finite-rotation energy (paper eqs. 5–8) |
//! | [`CoilSpring`] | elastic | spring between two body points: a rate, or the data sheet's push force curve |
//! | [`Stop`] | elastic | bump or rebound stop between two body points: a clearance, then a force curve |
//! | [`PointForce`] | load | world-fixed force at a body point, ramped by the load parameter |
//! | [`PointTorque`] | load | world-fixed moment on a body, ramped by the load parameter |
//!
//! Every element is described by global design data (hardpoints, frames, SI units), validated when it is
//! built and again when [`Model::add_element`](elastokin_core::Model::add_element) binds it to the design
//! poses; a bad value is a [`ModelError`](elastokin_core::ModelError) that names the element. Each returns
//! the generalized force it *applies* to its two bodies, `Q = (Fᵢ, Mᵢ, Fⱼ, Mⱼ)` with moments about the
//! bodies' reference points, and `K = −∂Q/∂Δq`, the derivative along the exact left increments of
//! [`Pose::apply_increment6`](elastokin_core::Pose::apply_increment6). For the elastic elements `K` is
//! the derivative of the energy gradient; its only non-symmetric parts are the skew matrices
//! `½[Q_πᵢ]~` and `½[Q_πⱼ]~` of the moments it applies, in the two rotation–rotation blocks
//! (`K − Kᵀ = diag(0, [Q_πᵢ]~, 0, [Q_πⱼ]~)`).
//! Evaluation neither allocates nor panics; non-finite poses give non-finite results, so that the solver
//! sees them.
//!
//! Measured characteristics are [`Curve`]s: a table of points, the monotone C¹ cubic of Fritsch and Carlson
//! through it (continuous force and rate, no overshoot between points) and straight lines past its ends
//! with the end slopes. A [`Characteristic`] is a rate or a curve; the elements' tangents take the curve's
//! slope where the linear law takes the rate, so Newton's method stays quadratic across the points of a
//! table.
//!
//! ```
//! use elastokin_core::{BodyRef, ElementEval, Mat3, Model, ModelError, Pose, Vec3};
//! use elastokin_elements::Bushing;
//!
//! let mut model = Model::new();
//! let arm = model.add_body("lower arm", Pose::at(Vec3::new(0.0, 0.7, -0.2))).unwrap();
//! let bush = Bushing::new(
//!     "front bush",
//!     BodyRef::Ground,
//!     arm.into(),
//!     Vec3::new(0.2, 0.4, -0.2),
//!     Mat3::identity(),
//!     Vec3::new(2e6, 1e6, 2e6),      // N/m
//!     Vec3::new(500.0, 50.0, 500.0), // N·m/rad
//! )
//! .unwrap();
//! let id = model.add_element(bush).unwrap();
//!
//! // Move the arm 1 mm along +y: the bushing pulls it back with Ky · 1 mm = 1000 N.
//! let mut pose = model.design_poses()[0];
//! pose.position.y += 1e-3;
//! let mut eval = ElementEval::default();
//! model.elements()[id.0].evaluate(&Pose::IDENTITY, &pose, 0.0, &mut eval, true);
//! assert!((eval.force[7] + 1000.0).abs() < 1e-9); // F_y on body j (the arm)
//! assert!((eval.stiffness[(7, 7)] - 1e6).abs() < 1e-6);
//!
//! // A stiffness that is not positive is refused with an error naming the bushing.
//! let err = Bushing::new(
//!     "rear bush", BodyRef::Ground, arm.into(), Vec3::zeros(), Mat3::identity(),
//!     Vec3::new(2e6, 0.0, 2e6), Vec3::new(500.0, 50.0, 500.0),
//! )
//! .unwrap_err();
//! assert!(matches!(err, ModelError::NotPositive { ref item, .. } if item == "rear bush"));
//! ```
//!
//! Dependencies: elastokin-core for the interface and rotation algebra, nalgebra for the fixed-size
//! 3×3 and 12×12 blocks (stack values, so evaluation does not allocate), serde behind the `serde`
//! feature (it derives `Serialize`/`Deserialize` on the parameter structs [`BushingSpec`],
//! [`CoilSpringSpec`], [`StopSpec`], [`PointForceSpec`], [`PointTorqueSpec`], on [`Characteristic`] and
//! [`Curve`] — a curve is written as its list of `[x, y]` points and checked when read — and forwards
//! core's `serde` feature).
//! faer, sprs and rayon are left out: an element works on one body pair with 12×12 dense blocks, so
//! there is no sparse or parallel work here — assembly, factorization and any parallel evaluation are
//! the solver's. Model files (and with them serde as a default) live in the suspensions crate.

pub mod beam;
pub mod bushing;
pub mod coil_spring;
pub mod curve;
pub mod field;
mod geometry;
pub mod point_load;
pub mod stop;

pub use beam::{beam, Beam, BeamSpec, Section};
pub use bushing::{Bushing, BushingSpec, RotationLaw};
pub use coil_spring::{CoilSpring, CoilSpringSpec, SpringLength};
pub use curve::{Characteristic, Curve};
pub use field::{Field, FieldSpec};
pub use point_load::{PointForce, PointForceSpec, PointTorque, PointTorqueSpec};
pub use stop::{Stop, StopKind, StopSpec};
