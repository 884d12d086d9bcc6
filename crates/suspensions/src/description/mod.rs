//! What a user writes: a suspension as data, before anything is built or solved.
//!
//! The general form ([`general`]: named hardpoints, bodies, joints, bushings, springs, stops, anti-roll
//! bars, loads, the parts a solid axle's corners share, and the corner description) is what every
//! suspension is written in; the templates ([`macpherson`], [`double_wishbone`], [`twist_beam`]) are descriptions that
//! expand into it (`From<&MacPherson> for GeneralCorner`), and [`Template`] says which a model holds.
//! Beside them: how parts meet ([`connection`]), the vehicle around the corner ([`vehicle`]), the limits
//! of what a description may say and the checks that hold it to them ([`limits`]), and where a
//! template's parts are by hardpoint name (`layout`, for the plausibility check).
//!
//! Invariant: nothing here builds a model or solves one. This layer imports no other layer of the crate,
//! and no solver type.

pub mod anti_roll_bar;
pub mod connection;
pub mod double_wishbone;
pub mod general;
pub(crate) mod layout;
pub mod limits;
pub mod macpherson;
pub mod packaging;
pub mod place;
pub mod section;
pub mod side;
pub mod template;
pub mod twist_beam;
pub mod vehicle;

pub use anti_roll_bar::AntiRollBar;
pub use connection::{ArmMounts, BushingRates, Connection, SpringSpec, TieRodMounts};
pub use double_wishbone::{DoubleWishbone, DoubleWishboneHardpoints};
pub use general::{
    Axis, AxleDef, BodyDef, BodyPoint, BushingDef, CornerDef, GeneralCorner, Hardpoints, JointDef, LoadDef, Place,
    SpringDef, SteeringLinkDef, Stiffness, StopDef, StopType, TieRodDef, CHASSIS,
};
pub use macpherson::{MacPherson, MacPhersonHardpoints, StrutJoint};
pub use packaging::{Obstacle, Packaging, PackagingBox, PackagingPoint, Tyre};
pub use side::Side;
pub use template::Template;
pub use twist_beam::{CrossMember, TwistBeam, TwistBeamHardpoints};
pub use vehicle::{AxlePosition, HalfShaft, VehicleError, VehicleParameters};
