//! How parts meet the chassis and each other: an ideal joint or a rubber bushing, and the coil spring.

use crate::general::{Axis, BushingDef, GeneralCorner, Place, CHASSIS};
use elastokin_core::JointKind;
use elastokin_elements::RotationLaw;
use serde::{Deserialize, Serialize};

/// Rates of a cylindrical rubber bushing (SI: N/m and N·m/rad), in its own frame whose x axis is the
/// bushing's axis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BushingRates {
    /// Radial rate (both directions across the axis), N/m.
    pub radial: f64,
    /// Axial rate, N/m.
    pub axial: f64,
    /// Torsion about the axis, N·m/rad.
    pub torsion: f64,
    /// Conical (tilt of the axis), N·m/rad.
    pub conical: f64,
    /// How the moment follows the twist: `"energy"` (default), `"linear"` (M = Kθ of the rotation vector)
    /// or `"tait_bryan_xyz"` (the energy of body-fixed x-y-z angles); see [`RotationLaw`].
    #[serde(default, skip_serializing_if = "is_default_law")]
    pub law: RotationLaw,
    /// The bushing's axis (left corner, any length), when it is not the template's (the arm's pivot axis,
    /// the strut axis, the tie rod).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis: Option<[f64; 3]>,
}

fn is_default_law(law: &RotationLaw) -> bool {
    *law == RotationLaw::default()
}

impl BushingRates {
    /// Rates with the default rotation law.
    pub fn new(radial: f64, axial: f64, torsion: f64, conical: f64) -> Self {
        BushingRates { radial, axial, torsion, conical, law: RotationLaw::default(), axis: None }
    }

    /// Every rate multiplied by `factor` (for stiffness studies).
    pub fn scaled(self, factor: f64) -> Self {
        BushingRates {
            radial: self.radial * factor,
            axial: self.axial * factor,
            torsion: self.torsion * factor,
            conical: self.conical * factor,
            ..self
        }
    }
}

/// A connection of a template: ideal kinematic joint, or bushing.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Connection {
    /// The template's ideal joint (revolute arm pivot, spherical ball joint, …).
    #[default]
    Ideal,
    /// A bushing with these rates.
    Bushing(BushingRates),
}

/// Coil spring of a template: rate and push force at design.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringSpec {
    /// Rate, N/m.
    pub rate: f64,
    /// Push force at the design position, N.
    pub design_force: f64,
}

/// How an arm meets the chassis at its front and rear pivots. Written as one connection for both
/// (`"ideal"`: a revolute about the pivot axis; a bushing: the same bushing at each pivot), or as
/// `{"front": …, "rear": …}` when they differ (an ideal end is then a ball joint).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ArmMounts {
    /// At the front pivot.
    pub front: Connection,
    /// At the rear pivot.
    pub rear: Connection,
}

impl From<Connection> for ArmMounts {
    fn from(both: Connection) -> Self {
        ArmMounts { front: both, rear: both }
    }
}

/// The two-key form of [`ArmMounts`].
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct EachEnd {
    front: Connection,
    rear: Connection,
}

impl Serialize for ArmMounts {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        if self.front == self.rear {
            self.front.serialize(s)
        } else {
            EachEnd { front: self.front, rear: self.rear }.serialize(s)
        }
    }
}

impl<'de> Deserialize<'de> for ArmMounts {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let value = serde_json::Value::deserialize(d)?;
        let each = value.as_object().is_some_and(|o| o.contains_key("front") || o.contains_key("rear"));
        if each {
            let e: EachEnd = serde_json::from_value(value).map_err(|e| {
                D::Error::custom(format!("an arm's mounts {{\"front\": …, \"rear\": …}} need both ends: {e}"))
            })?;
            Ok(ArmMounts { front: e.front, rear: e.rear })
        } else {
            serde_json::from_value::<Connection>(value).map(ArmMounts::from).map_err(D::Error::custom)
        }
    }
}

impl ArmMounts {
    /// The general model's joints and bushings of the arm `arm` on the chassis, pivots at the hardpoints
    /// `front` and `rear`: a revolute `"{arm} pivot"` when both ends are ideal; otherwise, per end, a ball
    /// joint `"{arm} {end} ball joint"` or a bushing `"{arm} {end} bushing"` along the pivot axis.
    pub(crate) fn expand(&self, arm: &str, front: &str, rear: &str, into: &mut GeneralCorner) {
        if *self == ArmMounts::from(Connection::Ideal) {
            let axis = Some(Axis::through(front, rear));
            into.push_joint(&format!("{arm} pivot"), JointKind::Revolute, [CHASSIS, arm], front, axis);
            return;
        }
        for (end, point, connection) in [("front", front, self.front), ("rear", rear, self.rear)] {
            match connection {
                Connection::Ideal => into.push_joint(
                    &format!("{arm} {end} ball joint"),
                    JointKind::Spherical,
                    [CHASSIS, arm],
                    point,
                    None,
                ),
                Connection::Bushing(rates) => into.bushings.push(BushingDef::cylindrical(
                    &format!("{arm} {end} bushing"),
                    [CHASSIS, arm],
                    Place::named(point),
                    Axis::through(front, rear),
                    &rates,
                )),
            }
        }
    }
}
