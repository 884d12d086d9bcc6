//! How parts meet the chassis and each other: an ideal joint or a rubber bushing, and the coil spring.

use elastokin_elements::RotationLaw;
use serde::{Deserialize, Serialize};

/// Rates of a cylindrical rubber bushing (SI: N/m and N·m/rad), in its own frame whose x axis is the
/// bushing's axis. Read only by name, as every other value of a model file: four numbers in a list would
/// say nothing of which rate is which, so a list is refused with the named form.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
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

/// The named form of [`BushingRates`], as serde derives it (which would take a list too).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct NamedRates {
    radial: f64,
    axial: f64,
    torsion: f64,
    conical: f64,
    #[serde(default)]
    law: RotationLaw,
    #[serde(default)]
    axis: Option<[f64; 3]>,
}

impl<'de> Deserialize<'de> for BushingRates {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Named;
        impl<'de> serde::de::Visitor<'de> for Named {
            type Value = BushingRates;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(BUSHING_RATES_NAMED)
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(self, map: A) -> Result<BushingRates, A::Error> {
                let NamedRates { radial, axial, torsion, conical, law, axis } =
                    NamedRates::deserialize(serde::de::value::MapAccessDeserializer::new(map))?;
                Ok(BushingRates { radial, axial, torsion, conical, law, axis })
            }
        }
        d.deserialize_map(Named)
    }
}

/// How bushing rates are written, for the refusal of any other form.
pub const BUSHING_RATES_NAMED: &str = "{\"radial\": N/m, \"axial\": N/m, \"torsion\": N·m/rad, \"conical\": N·m/rad}";

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

/// A part with two ends, each its own [`Connection`], written as one connection for both or as an object of
/// the two ends by name.
fn serialize_ends<S: serde::Serializer>(s: S, names: [&str; 2], ends: [Connection; 2]) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeMap;
    if ends[0] == ends[1] {
        return ends[0].serialize(s);
    }
    let mut map = s.serialize_map(Some(2))?;
    map.serialize_entry(names[0], &ends[0])?;
    map.serialize_entry(names[1], &ends[1])?;
    map.end()
}

/// Reads what [`serialize_ends`] writes; `what` names the part in the error.
fn deserialize_ends<'de, D: serde::Deserializer<'de>>(
    d: D,
    names: [&str; 2],
    what: &str,
) -> Result<[Connection; 2], D::Error> {
    use serde::de::Error;
    let value = serde_json::Value::deserialize(d)?;
    let Some(object) = value.as_object().filter(|o| names.iter().any(|n| o.contains_key(*n))) else {
        return serde_json::from_value::<Connection>(value).map(|c| [c, c]).map_err(D::Error::custom);
    };
    let needs = || D::Error::custom(format!("{what} {{\"{}\": …, \"{}\": …}} need both ends", names[0], names[1]));
    if let Some(other) = object.keys().find(|k| !names.contains(&k.as_str())) {
        return Err(D::Error::custom(format!(
            "{what}: unknown end '{other}', give \"{}\" and \"{}\"",
            names[0], names[1]
        )));
    }
    let end = |name: &str| -> Result<Connection, D::Error> {
        let v = object.get(name).ok_or_else(needs)?;
        serde_json::from_value(v.clone()).map_err(|e| D::Error::custom(format!("{what}, {name}: {e}")))
    };
    Ok([end(names[0])?, end(names[1])?])
}

impl Serialize for ArmMounts {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        serialize_ends(s, ["front", "rear"], [self.front, self.rear])
    }
}

impl<'de> Deserialize<'de> for ArmMounts {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let [front, rear] = deserialize_ends(d, ["front", "rear"], "an arm's mounts")?;
        Ok(ArmMounts { front, rear })
    }
}

/// How a tie rod meets the rack (its inner end) and the upright (its outer end): one connection for both
/// (`"ideal"`: a distance link, ball joints at both ends), or `{"inner": …, "outer": …}`. With a bushing at
/// either end the rod is a body; an ideal end is then a universal joint at the rack (which holds the rod's
/// spin) or a ball joint at the upright.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TieRodMounts {
    /// At the rack (or the chassis).
    pub inner: Connection,
    /// At the upright.
    pub outer: Connection,
}

impl From<Connection> for TieRodMounts {
    fn from(both: Connection) -> Self {
        TieRodMounts { inner: both, outer: both }
    }
}

impl Serialize for TieRodMounts {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        serialize_ends(s, ["inner", "outer"], [self.inner, self.outer])
    }
}

impl<'de> Deserialize<'de> for TieRodMounts {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let [inner, outer] = deserialize_ends(d, ["inner", "outer"], "a tie rod's mounts")?;
        Ok(TieRodMounts { inner, outer })
    }
}
