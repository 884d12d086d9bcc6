//! A description made into something to solve: the `elastokin_core::Model` of one corner ([`Corner`]) or
//! of a whole axle ([`Axle`]), held by a K&C rig ([`rig`]).
//!
//! Every description builds through one builder, the general form's ([`general`]); a template checks what
//! only it says and builds its expansion ([`templates`]). The rig's rack, tie-rod mounts and drivers are
//! added in [`rig`] alone, and the mobility at design, which the rig asks of a solid axle, is
//! [`mobility`](mod@mobility).
//!
//! Each described item can be found in what it became ([`BuildMap`]): the bodies, joints and elements of
//! every entry, on each side.
//!
//! Invariant: building reads descriptions and the wheel, never a file, an analysis or a check; it solves
//! nothing (the mobility is a rank of the joints' Jacobian at design).

pub mod anti_roll_bar;
pub mod axle;
pub mod corner;
pub mod general;
pub mod map;
pub mod mobility;
pub mod rig;
pub mod template;
pub mod templates;

pub use axle::Axle;
pub use corner::{Corner, LoadPoint};
pub use general::{joint_spec, JointGeometry};
pub use map::{BuildMap, Built};
pub use mobility::mobility;
pub use rig::{AxleRig, Rig};
pub use template::{CornerParts, CornerTemplate, CrossAxle, ElasticMember, SteeringLink, TieRod};
