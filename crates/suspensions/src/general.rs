//! The general model: any suspension corner as named hardpoints, bodies, joints, bushings and springs,
//! with a corner description that says where the wheel is. Every template expands into it
//! ([`crate::Template::expand`]) and is built by it: there is one builder.
//!
//! ```json
//! { "general": {
//!     "hardpoints": { "wheel_centre": [-0.04, 1.1, -0.026], "lower_ball_joint": [ … ], … },
//!     "bodies": [ { "name": "upright", "at": "wheel_centre" }, { "name": "lower arm", "at": "lower_ball_joint" } ],
//!     "joints": [
//!       { "name": "lower arm pivot", "kind": "revolute", "bodies": ["chassis", "lower arm"],
//!         "at": "lower_arm_front", "axis": ["lower_arm_front", "lower_arm_rear"] },
//!       { "name": "lower ball joint", "kind": "spherical", "bodies": ["lower arm", "upright"], "at": "lower_ball_joint" } ],
//!     "bushings": [ { "name": "top mount", "bodies": ["chassis", "strut rod"], "at": "top_mount",
//!                     "axis": ["strut_lower", "top_mount"],
//!                     "radial": 2e6, "axial": 5e5, "torsion": 50, "conical": 500 } ],
//!     "springs": [ { "name": "spring", "bodies": ["chassis", "upright"], "from": "top_mount", "to": "strut_lower",
//!                    "rate": 30000, "design_force": 4000 } ],
//!     "corner": { "upright": "upright", "wheel_centre": "wheel_centre",
//!                 "steering_axis": [ { "body": "upright", "at": "lower_ball_joint" },
//!                                    { "body": "strut rod", "at": "top_mount" } ],
//!                 "tie_rod": { "inner": "tie_rod_inner", "outer": "tie_rod_outer" } } } }
//! ```
//!
//! The model describes the **left** corner (y > 0, ISO 8855, metres); the right is its mirror image
//! (y → −y for points and direction vectors; a bushing frame is mirrored axis by axis and made
//! right-handed again). `"chassis"` names the ground. The tie rod of the corner description is attached by
//! the rig: to the rack when steering, to the chassis otherwise; a corner without one (a rear multi-link
//! whose toe link is an ordinary joint to the chassis) runs every analysis but steering.

use crate::anti_roll_bar::AntiRollBar;
use crate::connection::{BushingRates, Connection, TieRodMounts};
use crate::corner::{
    check_hardpoints, check_rate, check_steering_arm, check_steering_axis, part_name, CornerParts, CornerTemplate,
    CrossAxle, SteeringLink, TieRod, Wheel, MAX_WHEEL_CENTRE_DISTANCE, ROTATIONAL_RATE_RANGE, TRANSLATIONAL_RATE_RANGE,
};
use crate::hardpoint::Side;
use elastokin_core::joint::orthonormal_complement;
use elastokin_core::{BodyRef, ElementId, JointKind, JointSpec, Mat3, Model, ModelError, Pose, Vec3};
use elastokin_elements::{
    Bushing, BushingSpec, Characteristic, CoilSpring, Curve, PointForce, PointTorque, RotationLaw, Stop,
};
use serde::de::{Error as _, MapAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// The name of the ground in a general model.
pub const CHASSIS: &str = "chassis";

/// Named hardpoints of the left corner, in the order given (global coordinates, metres).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Hardpoints(pub Vec<(String, Vec3)>);

impl Hardpoints {
    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// The point named `name`.
    pub fn get(&self, name: &str) -> Option<Vec3> {
        self.0.iter().find(|(n, _)| n == name).map(|(_, p)| *p)
    }
}

impl Serialize for Hardpoints {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = s.serialize_map(Some(self.0.len()))?;
        for (name, p) in &self.0 {
            map.serialize_entry(name, &[p.x, p.y, p.z])?;
        }
        map.end()
    }
}

/// A point's own reader, named for the error messages (see `crate::hardpoint::point`).
#[derive(Deserialize)]
#[serde(transparent)]
struct PointValue(#[serde(deserialize_with = "crate::hardpoint::point")] Vec3);

impl<'de> Deserialize<'de> for Hardpoints {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Ordered;
        impl<'de> Visitor<'de> for Ordered {
            type Value = Hardpoints;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("an object of named hardpoints, each [x, y, z] in metres")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Hardpoints, A::Error> {
                let mut out: Vec<(String, Vec3)> = Vec::new();
                while let Some(name) = map.next_key::<String>()? {
                    let PointValue(p) = map.next_value()?;
                    if out.iter().any(|(n, _)| *n == name) {
                        return Err(A::Error::custom(format!("hardpoint '{name}' is given twice: keep one")));
                    }
                    out.push((name, p));
                }
                Ok(Hardpoints(out))
            }
        }
        d.deserialize_map(Ordered)
    }
}

/// A point of the model: a hardpoint by name, or coordinates `[x, y, z]` (left corner, metres).
#[derive(Debug, Clone, PartialEq)]
pub enum Place {
    /// A named hardpoint.
    Named(String),
    /// Coordinates.
    At(Vec3),
}

impl Place {
    /// A named hardpoint.
    pub fn named(name: &str) -> Place {
        Place::Named(name.to_string())
    }
    /// How the file writes it, for messages.
    fn describe(&self) -> String {
        match self {
            Place::Named(n) => format!("'{n}'"),
            Place::At(p) => format!("[{}, {}, {}]", p.x, p.y, p.z),
        }
    }
}

impl Serialize for Place {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Place::Named(n) => s.serialize_str(n),
            Place::At(p) => [p.x, p.y, p.z].serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for Place {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let value = serde_json::Value::deserialize(d)?;
        place_of(&value).map_err(D::Error::custom)
    }
}

fn place_of(value: &serde_json::Value) -> Result<Place, String> {
    if let Some(name) = value.as_str() {
        return Ok(Place::named(name));
    }
    match numbers(value) {
        Some(n) if n.len() == 3 => Ok(Place::At(Vec3::new(n[0], n[1], n[2]))),
        _ => Err(format!("a point is a hardpoint's name or 3 numbers in metres [x, y, z], got {}", short(value))),
    }
}

fn numbers(value: &serde_json::Value) -> Option<Vec<f64>> {
    value.as_array()?.iter().map(|c| c.as_f64()).collect()
}

fn short(value: &serde_json::Value) -> String {
    let text = value.to_string();
    if text.chars().count() > 40 {
        format!("{}…", text.chars().take(40).collect::<String>())
    } else {
        text
    }
}

/// A direction: from one point to another (`["a", "b"]`), or a vector `[x, y, z]` (left corner).
#[derive(Debug, Clone, PartialEq)]
pub enum Axis {
    /// From the first point towards the second.
    Through(Place, Place),
    /// A direction vector (any length but zero).
    Vector(Vec3),
}

impl Axis {
    /// From hardpoint `a` towards hardpoint `b`.
    pub fn through(a: &str, b: &str) -> Axis {
        Axis::Through(Place::named(a), Place::named(b))
    }
}

impl Serialize for Axis {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Axis::Through(a, b) => (a, b).serialize(s),
            Axis::Vector(v) => [v.x, v.y, v.z].serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for Axis {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let value = serde_json::Value::deserialize(d)?;
        let fail = || {
            D::Error::custom(format!(
                "an axis is two points [\"from\", \"to\"] (hardpoint names or [x, y, z]) or a direction [x, y, z], \
                 got {}",
                short(&value)
            ))
        };
        match value.as_array().map(Vec::as_slice) {
            Some([a, b]) => Ok(Axis::Through(place_of(a).map_err(|_| fail())?, place_of(b).map_err(|_| fail())?)),
            Some([_, _, _]) => match numbers(&value) {
                Some(n) => Ok(Axis::Vector(Vec3::new(n[0], n[1], n[2]))),
                None => Err(fail()),
            },
            _ => Err(fail()),
        }
    }
}

/// A rigid part: its name and where its reference point is at design (axes global).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyDef {
    /// Name (not `"chassis"`, which is the ground).
    pub name: String,
    /// Reference point at design; results give the body's motion there.
    pub at: Place,
}

/// A kinematic joint between two bodies (by name; `"chassis"` is the ground).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointDef {
    /// Name; reactions are reported under it.
    pub name: String,
    /// Kind (every kind of [`JointKind`] but the drivers, which are the rig's): what each takes is in
    /// `docs/model-file.md`.
    pub kind: JointKind,
    /// The two bodies; reactions are those on the second.
    pub bodies: [String; 2],
    /// Hardpoint (see [`JointKind`] for what each kind uses).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at: Option<Place>,
    /// Second point: the far end of a distance link; the second body's point of an in-plane or in-line
    /// joint.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub to: Option<Place>,
    /// Axis: hinge, slide, plane normal, line direction, or the first body's axis.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis: Option<Axis>,
    /// The second body's axis (universal, perpendicular).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis_j: Option<Axis>,
}

/// What a bushing direction or a spring is given: a rate (a number: N/m, or N·m/rad for a twist), or a
/// measured curve `{"curve": [[deflection, force], …]}` (m and N, or rad and N·m), passed through by a
/// monotone cubic and continued as a straight line past its ends (see `elastokin_elements::Curve`).
#[derive(Debug, Clone, PartialEq)]
pub enum Stiffness {
    /// A constant rate.
    Rate(f64),
    /// A table of points, `x` increasing.
    Curve(Vec<[f64; 2]>),
}

impl Stiffness {
    /// The rate, when it is one.
    pub fn rate(&self) -> Option<f64> {
        match self {
            Stiffness::Rate(k) => Some(*k),
            Stiffness::Curve(_) => None,
        }
    }

    /// The element's characteristic; `item` names it in errors (a rate is checked by the element).
    fn characteristic(&self, item: &str) -> Result<Characteristic, ModelError> {
        match self {
            Stiffness::Rate(k) => Ok(Characteristic::Rate(*k)),
            Stiffness::Curve(points) => Ok(Characteristic::Curve(Curve::new(item, points.clone())?)),
        }
    }
}

impl From<f64> for Stiffness {
    fn from(rate: f64) -> Self {
        Stiffness::Rate(rate)
    }
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct CurveForm {
    curve: Vec<[f64; 2]>,
}

impl Serialize for Stiffness {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Stiffness::Rate(k) => s.serialize_f64(*k),
            Stiffness::Curve(points) => CurveForm { curve: points.clone() }.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for Stiffness {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let value = serde_json::Value::deserialize(d)?;
        if let Some(k) = value.as_f64() {
            return Ok(Stiffness::Rate(k));
        }
        serde_json::from_value::<CurveForm>(value.clone()).map(|c| Stiffness::Curve(c.curve)).map_err(|_| {
            D::Error::custom(format!(
                "a stiffness is a rate (a number) or {{\"curve\": [[deflection, force], …]}}, got {}",
                short(&value)
            ))
        })
    }
}

/// A rubber bushing between two bodies, in its own frame: x along `axis`, y towards `y_axis` (made
/// perpendicular), z completing a right-handed frame. Either the four rates of a cylindrical bushing
/// (`radial`, `axial`, `torsion`, `conical`: x is the bushing's axis) or six (`translation` along and
/// `rotation` about x, y, z).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BushingDef {
    /// Name; forces and deflections are reported under it.
    pub name: String,
    /// The two bodies: the frame moves with the first; forces are those on the second.
    pub bodies: [String; 2],
    /// Centre of the bushing at design.
    pub at: Place,
    /// The frame's x axis (default: global x).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis: Option<Axis>,
    /// A direction the frame's y axis leans towards (default: any perpendicular to x, which a cylindrical
    /// bushing does not tell apart).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y_axis: Option<Axis>,
    /// Radial rate (across x), N/m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radial: Option<Stiffness>,
    /// Axial rate (along x), N/m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axial: Option<Stiffness>,
    /// Torsion rate (about x), N·m/rad.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torsion: Option<Stiffness>,
    /// Conical rate (tilt of x), N·m/rad.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub conical: Option<Stiffness>,
    /// Rates along x, y, z, N/m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub translation: Option<[Stiffness; 3]>,
    /// Rates about x, y, z, N·m/rad.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotation: Option<[Stiffness; 3]>,
    /// How the moment follows the twist (see [`RotationLaw`]).
    #[serde(default, skip_serializing_if = "is_default_law")]
    pub law: RotationLaw,
    /// Force on the second body at zero deflection, in the bushing frame (N).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preload_force: Option<[f64; 3]>,
    /// Moment on the second body at zero twist, in the bushing frame (N·m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preload_torque: Option<[f64; 3]>,
}

fn is_default_law(law: &RotationLaw) -> bool {
    *law == RotationLaw::default()
}

impl BushingDef {
    /// A cylindrical bushing with `rates`, its axis `axis`.
    pub fn cylindrical(name: &str, bodies: [&str; 2], at: Place, axis: Axis, rates: &BushingRates) -> BushingDef {
        BushingDef {
            name: name.to_string(),
            bodies: bodies.map(str::to_string),
            at,
            axis: Some(rates.axis.map_or(axis, |a| Axis::Vector(a.into()))),
            y_axis: None,
            radial: Some(rates.radial.into()),
            axial: Some(rates.axial.into()),
            torsion: Some(rates.torsion.into()),
            conical: Some(rates.conical.into()),
            translation: None,
            rotation: None,
            law: rates.law,
            preload_force: None,
            preload_torque: None,
        }
    }

    /// The bushing this entry describes, its geometry resolved: between `bodies`, centred at `point`, its
    /// frame's x along `x_left` and y towards `y_hint_left` as given for the left corner and mirrored for
    /// `side` (`bushing_frame`), its preload mirrored with the frame. `key` is where the entry is
    /// (`bushings[2]`), for errors as the rates' checks word them.
    pub fn bushing(
        &self,
        key: &str,
        name: &str,
        bodies: [BodyRef; 2],
        point: Vec3,
        x_left: Vec3,
        y_hint_left: Option<Vec3>,
        side: Side,
    ) -> Result<Bushing, ModelError> {
        let (translational, rotational) = self.rates(key)?;
        let frame = bushing_frame(x_left, y_hint_left, side)
            .map_err(|why| ModelError::OutOfRange { item: format!("{key} ({})", self.name), why })?;
        // Mirroring turns the frame's z axis over (see `bushing_frame`): a preload's z force and x, y
        // moments change sign in the right corner's frame, so that the right bushing pushes as the mirror
        // image of the left.
        let s = side.sign();
        let force = self.preload_force.map_or(Vec3::zeros(), |f| Vec3::new(f[0], f[1], s * f[2]));
        let torque = self.preload_torque.map_or(Vec3::zeros(), |m| Vec3::new(s * m[0], s * m[1], m[2]));
        Bushing::from_spec(BushingSpec {
            name: name.to_string(),
            body_i: bodies[0],
            body_j: bodies[1],
            point,
            frame,
            translational,
            rotational,
            preload_force: force,
            preload_torque: torque,
            rotation_law: self.law,
        })
    }

    /// `(translation, rotation)` characteristics along and about x, y, z, from whichever set is given
    /// (a cylindrical bushing's radial rate across x, axial along it, torsion about it, conical across it),
    /// each rate checked against the model file's ranges; the error names what is missing or out of range,
    /// as `{key} ({name})…` (`key` is where the entry is, `bushings[2]` in a model file).
    fn rates(&self, key: &str) -> Result<([Characteristic; 3], [Characteristic; 3]), ModelError> {
        let cylindrical = [&self.radial, &self.axial, &self.torsion, &self.conical];
        let six = [&self.translation, &self.rotation];
        let refuse = |why: &str| {
            Err(ModelError::OutOfRange {
                item: format!("{key} ({})", self.name),
                why: format!(
                    "{why}: give either radial, axial, torsion and conical (a cylindrical bushing, x its axis) or \
                     translation and rotation (three rates or curves each, along and about x, y, z)"
                ),
            })
        };
        let (t, r): ([&Stiffness; 3], [&Stiffness; 3]) =
            match (cylindrical.iter().any(|c| c.is_some()), six.iter().any(|c| c.is_some())) {
                (true, true) => return refuse("both sets of rates are given"),
                (false, false) => return refuse("no rates are given"),
                (true, false) => match cylindrical {
                    [Some(radial), Some(axial), Some(torsion), Some(conical)] => {
                        ([axial, radial, radial], [torsion, conical, conical])
                    }
                    _ => return refuse("a cylindrical bushing needs all four rates"),
                },
                (false, true) => match six {
                    [Some(t), Some(r)] => (t.each_ref(), r.each_ref()),
                    _ => return refuse("six rates need both translation and rotation"),
                },
            };
        let mut out: [Vec<Characteristic>; 2] = [Vec::new(), Vec::new()];
        for (k, what) in ["x", "y", "z"].iter().enumerate() {
            for (set, (name, stiffness, range, unit)) in [
                ("translation", t[k], TRANSLATIONAL_RATE_RANGE, "N/m"),
                ("rotation", r[k], ROTATIONAL_RATE_RANGE, "N·m/rad"),
            ]
            .into_iter()
            .enumerate()
            {
                let item = format!("{key} ({}).{name} {what}", self.name);
                if let Some(rate) = stiffness.rate() {
                    check_rate(&item, rate, range, unit)?;
                }
                out[set].push(stiffness.characteristic(&item)?);
            }
        }
        let [t, r] = out.map(|v| <[Characteristic; 3]>::try_from(v).expect("three directions"));
        Ok((t, r))
    }
}

/// A coil spring between two bodies: a rate or a measured curve, with its push at design or its free
/// length.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringDef {
    /// Name.
    pub name: String,
    /// The two bodies; the force reported is the one on the second.
    pub bodies: [String; 2],
    /// Seat on the first body.
    pub from: Place,
    /// Seat on the second body.
    pub to: Place,
    /// Rate, N/m (give this or `curve`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rate: Option<f64>,
    /// The data sheet: push force (N) against compression from the free length (m), `[[0, 0], …]`
    /// (give this or `rate`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curve: Option<Vec<[f64; 2]>>,
    /// Push at the design length, N (give this or `free_length`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub design_force: Option<f64>,
    /// Free length, m (give this or `design_force`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub free_length: Option<f64>,
    /// A constant push added to the rate's or the curve's, N (with `free_length`; with `design_force` the
    /// push at design already says it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preload: Option<f64>,
}

impl SpringDef {
    /// The coil spring this entry describes, named `name`, between `bodies` from the seat `from` on the
    /// first to `to` on the second (global, at design): either the rate or the curve, either the push at
    /// design or the free length, the rate and the push checked against the model file's ranges. `key`
    /// names the entry in errors (`springs[0] (spring)` in a model file).
    pub fn spring(
        &self,
        key: &str,
        name: &str,
        bodies: [BodyRef; 2],
        from: Vec3,
        to: Vec3,
    ) -> Result<CoilSpring, ModelError> {
        let [bi, bj] = bodies;
        let refuse = |why: &str| Err(ModelError::OutOfRange { item: key.to_string(), why: why.to_string() });
        if self.preload.is_some() && self.design_force.is_some() {
            return refuse("give a preload with free_length only: with design_force the push at design includes it");
        }
        let spring = match (self.rate, &self.curve, self.design_force, self.free_length) {
            (Some(_), Some(_), _, _) | (None, None, _, _) => {
                return refuse("give either rate (N/m) or curve (push force in N against compression in m)")
            }
            (_, _, Some(_), Some(_)) | (_, _, None, None) => {
                return refuse("give either design_force (N, its push at design) or free_length (m)")
            }
            (Some(rate), None, Some(force), None) => {
                check_rate(&format!("{key}.rate"), rate, TRANSLATIONAL_RATE_RANGE, "N/m")?;
                crate::corner::check_spring_force(key, rate, force, (to - from).norm())?;
                CoilSpring::with_design_force(name, bi, from, bj, to, rate, force)?
            }
            (Some(rate), None, None, Some(free)) => {
                check_rate(&format!("{key}.rate"), rate, TRANSLATIONAL_RATE_RANGE, "N/m")?;
                CoilSpring::new(name, bi, from, bj, to, rate, free)?
            }
            (None, Some(points), Some(force), None) => {
                let curve = Curve::new(&format!("{key}.curve"), points.clone())?;
                CoilSpring::with_curve_and_design_force(name, bi, from, bj, to, curve, force)?
            }
            (None, Some(points), None, Some(free)) => {
                let curve = Curve::new(&format!("{key}.curve"), points.clone())?;
                CoilSpring::with_curve(name, bi, from, bj, to, curve, free)?
            }
        };
        match self.preload {
            Some(preload) => spring.with_preload(preload),
            None => Ok(spring),
        }
    }
}

/// Bump or rebound.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StopType {
    /// Acts when the two points come closer than at design by more than the clearance; pushes them apart.
    Bump,
    /// Acts when they move apart by more than the clearance; pulls them together.
    Rebound,
}

/// A bump or rebound stop along the line of two points (the spring or damper axis): free over its
/// clearance from the design length, then the force of its curve against the travel past contact.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StopDef {
    /// Name.
    pub name: String,
    /// Bump or rebound.
    pub kind: StopType,
    /// The two bodies; the force reported is the one on the second.
    pub bodies: [String; 2],
    /// Point on the first body.
    pub from: Place,
    /// Point on the second body.
    pub to: Place,
    /// Travel from the design length to first contact, m.
    pub clearance: f64,
    /// Force (N) against travel past contact (m), from `[0, 0]`.
    pub curve: Vec<[f64; 2]>,
}

impl StopDef {
    /// The stop this entry describes, named `name`, between `bodies` along the line from `from` on the
    /// first to `to` on the second (global, at design). `key` names the entry in errors (`stops[0] (bump
    /// stop)` in a model file).
    pub fn stop(&self, key: &str, name: &str, bodies: [BodyRef; 2], from: Vec3, to: Vec3) -> Result<Stop, ModelError> {
        let [bi, bj] = bodies;
        let curve = Curve::new(&format!("{key}.curve"), self.curve.clone())?;
        match self.kind {
            StopType::Bump => Stop::bump(name, bi, from, bj, to, self.clearance, curve),
            StopType::Rebound => Stop::rebound(name, bi, from, bj, to, self.clearance, curve),
        }
    }
}

/// A load on a body: a force at a point and/or a moment, world-fixed in direction, swept by the `loads`
/// analysis from zero to these values (the load parameter is the fraction applied).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadDef {
    /// Name; the table's columns and the messages use it.
    pub name: String,
    /// The body it acts on.
    pub body: String,
    /// Where the force acts (needed with `force`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at: Option<Place>,
    /// Force, N, global axes (left corner; mirrored for the right).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub force: Option<[f64; 3]>,
    /// Moment, N·m, global axes (left corner; mirrored for the right).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torque: Option<[f64; 3]>,
}

/// A point on a body, for the steering axis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyPoint {
    /// The body (or `"chassis"`).
    pub body: String,
    /// The point at design.
    pub at: Place,
}

/// The tie rod: attached by the rig to the rack (steering) or to the chassis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TieRodDef {
    /// Inner end (rack).
    pub inner: Place,
    /// Outer end (upright).
    pub outer: Place,
    /// A distance constraint (`"ideal"`, the default), a rod with a bushing at each end, or
    /// `{"inner": …, "outer": …}` (see [`TieRodMounts`]).
    #[serde(default)]
    pub connection: TieRodMounts,
}

/// Where the wheel is and how it is steered: what turns a linkage into a suspension corner.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CornerDef {
    /// The body that carries the wheel.
    pub upright: String,
    /// The hardpoint at the wheel centre.
    pub wheel_centre: String,
    /// Outward spin axis of the left wheel at design (default `[0, 1, 0]`; static toe and camber tilt it).
    #[serde(default = "outward", skip_serializing_if = "is_outward")]
    pub spin_axis: [f64; 3],
    /// Loaded tyre radius (m): the contact patch is this far from the wheel centre, down the wheel plane.
    #[serde(default = "crate::corner::default_loaded_radius")]
    pub loaded_radius: f64,
    /// Lower and upper point of the steering (kingpin) axis, each on a body: it gives caster, kingpin
    /// inclination, scrub radius and trail. For a multi-link, the virtual axis through the link-pair
    /// intersections.
    pub steering_axis: [BodyPoint; 2],
    /// The steering input; without one the steering analysis does not apply.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tie_rod: Option<TieRodDef>,
}

fn outward() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}

fn is_outward(a: &[f64; 3]) -> bool {
    *a == outward()
}

/// The steering input of a solid axle: a rod (a drag link) from the steering box's arm to a part of the
/// axle, which the rig moves along `rack_axis` when steering and holds on the chassis otherwise.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SteeringLinkDef {
    /// The part it pushes (an axle body, or `"left …"` / `"right …"` for a corner's).
    pub body: String,
    /// End at the steering box (axle hardpoint or coordinates, not mirrored).
    pub inner: Place,
    /// End on `body`.
    pub outer: Place,
    /// A distance constraint (`"ideal"`, the default), or a rod with bushings (see [`TieRodMounts`]).
    #[serde(default)]
    pub connection: TieRodMounts,
    /// Direction in which the steering input moves the inner end (default `[0, 1, 0]`, a rack's; a
    /// pitman arm's end moves along the drag link).
    #[serde(default = "outward", skip_serializing_if = "is_outward")]
    pub rack_axis: [f64; 3],
}

/// The parts two corners share: the axle tube of a solid axle and what hangs on it once (a tie rod
/// across, a Panhard rod, a bell crank). Written as they are in the car, both sides given, nothing
/// mirrored; built once, on the whole axle. A corner names an axle body by its name; an axle part names a
/// corner's body or hardpoint as `"left …"` or `"right …"` (the corner's, placed on that side). A model
/// with an `axle` builds only whole: every corner analysis moves and loads both wheels alike.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxleDef {
    /// Named points of the axle's own parts (global, not mirrored).
    #[serde(default, skip_serializing_if = "Hardpoints::is_empty")]
    pub hardpoints: Hardpoints,
    /// The shared bodies.
    pub bodies: Vec<BodyDef>,
    /// Kinematic joints of the shared parts.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub joints: Vec<JointDef>,
    /// Bushings of the shared parts.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bushings: Vec<BushingDef>,
    /// Springs between shared parts (each corner's own springs go in the corner).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub springs: Vec<SpringDef>,
    /// Stops between shared parts.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub stops: Vec<StopDef>,
    /// The steering input, when the corners have no tie rods of their own.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steering_link: Option<SteeringLinkDef>,
    /// Names of the axle's bushings that are anti-roll bars' torsion springs (a bar built of its own parts,
    /// twisting about the bushing's x axis): the roll analysis counts their energy as the bars'.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub anti_roll_bar_springs: Vec<String>,
}

/// A suspension corner of any topology (see the [module docs](self)).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GeneralCorner {
    /// Named hardpoints of the left corner.
    pub hardpoints: Hardpoints,
    /// The moving parts.
    pub bodies: Vec<BodyDef>,
    /// Kinematic joints.
    #[serde(default)]
    pub joints: Vec<JointDef>,
    /// Rubber bushings.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bushings: Vec<BushingDef>,
    /// Coil springs.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub springs: Vec<SpringDef>,
    /// Bump and rebound stops.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub stops: Vec<StopDef>,
    /// Anti-roll bars: built on a full axle, coupling the two corners.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub anti_roll_bars: Vec<AntiRollBar>,
    /// A load case at any point of any body, run by the `loads` analysis.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub loads: Vec<LoadDef>,
    /// Parts shared by the two corners (a solid axle): the model then builds only as a whole axle.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axle: Option<AxleDef>,
    /// Where the wheel is.
    pub corner: CornerDef,
}

/// The bodies of one corner by their file names, and the places resolved on one side; or, for the parts
/// two corners share ([`AxleDef`]), the axle's own names and each side's by `"left …"` / `"right …"`.
pub(crate) struct Resolver<'a> {
    general: &'a GeneralCorner,
    side: Side,
    prefix: &'a str,
    /// For the shared parts: the left and right corners' name prefixes.
    shared: Option<(&'a str, &'a str)>,
}

impl Resolver<'_> {
    /// The prefix of the corner's part names.
    pub(crate) fn prefix(&self) -> &str {
        self.prefix
    }

    /// The axle's bodies, none without one.
    fn axle_bodies(&self) -> &[BodyDef] {
        self.general.axle.as_ref().map_or(&[], |a| a.bodies.as_slice())
    }

    /// A corner's name `"left x"` / `"right x"` split into its side, that side's prefix and `x`.
    fn sided<'n>(&self, name: &'n str) -> Option<(Side, &str, &'n str)> {
        let (left, right) = self.shared?;
        if let Some(rest) = name.strip_prefix("left ") {
            return Some((Side::Left, left, rest));
        }
        name.strip_prefix("right ").map(|rest| (Side::Right, right, rest))
    }

    /// A point placed on the side; `key` names where it is used, for the error.
    pub(crate) fn point(&self, key: &str, place: &Place) -> Result<Vec3, ModelError> {
        let missing = |name: &str| {
            let why = match self.shared {
                None => format!(
                    "there is no hardpoint '{name}': add it to hardpoints or use one of {}",
                    list(self.general.hardpoints.0.iter().map(|(n, _)| n.as_str()))
                ),
                Some(_) => {
                    let own = self.general.axle.as_ref().map(|a| &a.hardpoints.0);
                    format!(
                        "there is no hardpoint '{name}': add it to axle.hardpoints, name a corner's as \
                         \"left …\" or \"right …\", or use one of {}",
                        list(own.into_iter().flatten().map(|(n, _)| n.as_str()))
                    )
                }
            };
            ModelError::OutOfRange { item: key.to_string(), why }
        };
        let (side, left) = match place {
            Place::At(p) => (self.side, *p),
            Place::Named(name) => match self.shared {
                None => (self.side, self.general.hardpoints.get(name).ok_or_else(|| missing(name))?),
                Some(_) => match (self.general.axle.as_ref().and_then(|a| a.hardpoints.get(name)), self.sided(name)) {
                    (Some(p), _) => (Side::Left, p),
                    (None, Some((side, _, corner))) => {
                        (side, self.general.hardpoints.get(corner).ok_or_else(|| missing(name))?)
                    }
                    (None, None) => return Err(missing(name)),
                },
            },
        };
        if !left.iter().all(|c| c.is_finite()) {
            return Err(ModelError::OutOfRange {
                item: key.to_string(),
                why: format!("{} is not three finite numbers in metres", place.describe()),
            });
        }
        // As far as a corner's points may reach (a model in millimetres still builds, for the plausibility
        // check to name it); beyond, lengths and lever arms overflow.
        let limit = MAX_WHEEL_CENTRE_DISTANCE + crate::corner::MAX_HARDPOINT_REACH;
        if left.norm() > limit {
            return Err(ModelError::OutOfRange {
                item: key.to_string(),
                why: format!(
                    "{} lies more than {limit:e} m from the vehicle origin: points are in metres (ISO 8855, x \
                     forward, y left, z up); check its units",
                    place.describe()
                ),
            });
        }
        Ok(side.place(left))
    }

    /// A direction placed on the side.
    pub(crate) fn direction(&self, key: &str, axis: &Axis) -> Result<Vec3, ModelError> {
        let v = match axis {
            Axis::Vector(v) => self.side.place(*v),
            Axis::Through(a, b) => self.point(key, b)? - self.point(key, a)?,
        };
        let n = v.norm();
        if !(n.is_finite() && n > 1e-9) {
            let why = match axis {
                Axis::Through(a, b) => format!(
                    "the axis from {} to {} has no length ({n:.1e} m): give two distinct points",
                    a.describe(),
                    b.describe()
                ),
                Axis::Vector(_) => "the axis vector has no length: give a non-zero direction".to_string(),
            };
            return Err(ModelError::OutOfRange { item: key.to_string(), why });
        }
        Ok(v)
    }

    /// A body by its file name (`"chassis"` is the ground): a corner's own, else an axle body; on the
    /// shared parts, an axle body or a corner's as `"left …"` / `"right …"`.
    pub(crate) fn body(&self, model: &Model, key: &str, name: &str) -> Result<BodyRef, ModelError> {
        if name == CHASSIS {
            return Ok(BodyRef::Ground);
        }
        let corner_body = |prefix: &str, name: &str| {
            let known = self.general.bodies.iter().any(|b| b.name == name);
            model.body_id(&part_name(prefix, name)).filter(|_| known)
        };
        let axle_body = || model.body_id(name).filter(|_| self.axle_bodies().iter().any(|b| b.name == name));
        let found = match self.shared {
            None => corner_body(self.prefix, name).or_else(axle_body),
            Some(_) => axle_body().or_else(|| self.sided(name).and_then(|(_, prefix, rest)| corner_body(prefix, rest))),
        };
        if let Some(id) = found {
            return Ok(id.into());
        }
        let axle = self.axle_bodies().iter().map(|b| b.name.as_str());
        let why = match self.shared {
            None => format!(
                "there is no body '{name}': use \"{CHASSIS}\" or one of {}",
                list(self.general.bodies.iter().map(|b| b.name.as_str()).chain(axle))
            ),
            Some(_) => format!(
                "there is no body '{name}': use \"{CHASSIS}\", a corner's as \"left …\" or \"right …\" (one of \
                 {}), or one of the axle's, {}",
                list(self.general.bodies.iter().map(|b| b.name.as_str())),
                list(axle)
            ),
        };
        Err(ModelError::OutOfRange { item: key.to_string(), why })
    }
}

/// The places of a joint entry, resolved: its points and axes in global coordinates at design, each
/// present when the entry gives its key (`at`, `to`, `axis`, `axis_j`; which kind uses which is in
/// `docs/model-file.md`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct JointGeometry {
    /// The hardpoint; the first body's point of a distance link, in-plane or in-line joint.
    pub at: Option<Vec3>,
    /// The second body's point: the far end of a distance link; the point of the plane or line.
    pub to: Option<Vec3>,
    /// Hinge or slide axis, plane normal, line direction, or the first body's axis.
    pub axis: Option<Vec3>,
    /// The second body's axis (universal, perpendicular).
    pub axis_j: Option<Vec3>,
}

/// A driver in a model: the rig drives the wheel and the rack, a model holds joints.
fn driver_refusal(key: &str) -> ModelError {
    ModelError::OutOfRange {
        item: key.to_string(),
        why: "a driver is the rig's (wheel travel, rack travel), not the model's: use a joint".into(),
    }
}

/// Refuses a driver (the rig's, not a model's), a key `kind` needs and is not given, and a key `kind`
/// does not use; `given` says which of `at`, `to`, `axis` and `axis_j` are, and `key` names the entry.
fn check_joint_keys(key: &str, kind: JointKind, given: [bool; 4]) -> Result<(), ModelError> {
    use JointKind as T;
    let refuse = |why: String| Err(ModelError::OutOfRange { item: key.to_string(), why });
    let uses = match kind {
        T::Spherical | T::Fixed => ["at"].as_slice(),
        T::Revolute | T::Cylindrical | T::Translational => &["at", "axis"],
        T::Universal => &["at", "axis", "axis_j"],
        T::Distance => &["at", "to"],
        T::InPlane | T::InLine => &["at", "axis", "to?"],
        T::Perpendicular => &["axis", "axis_j"],
        T::ParallelAxes => &["axis"],
        // Before the keys: a driver's keys are not the question.
        T::PointDriver | T::TravelDriver => return Err(driver_refusal(key)),
    };
    for (what, given) in ["at", "to", "axis", "axis_j"].into_iter().zip(given) {
        if uses.contains(&what) {
            if !given {
                return refuse(format!("a {} joint needs '{what}': add it", kind_name(kind)));
            }
        } else if !uses.contains(&format!("{what}?").as_str()) && given {
            return refuse(format!("'{what}' means nothing to a {} joint: remove it", kind_name(kind)));
        }
    }
    Ok(())
}

/// The joint a model file's joint entry describes: `name`, of `kind`, between `bodies` (reactions on the
/// second), at the resolved `geometry`. `key` names the entry in errors: a driver (the rig's), a kind
/// without a key it needs and a key the kind does not use are refused, as a model file's are. The
/// geometry itself (a zero axis, axes not perpendicular) is checked when the joint is added to a model.
pub fn joint_spec(
    key: &str,
    name: &str,
    kind: JointKind,
    bodies: [BodyRef; 2],
    geometry: &JointGeometry,
) -> Result<JointSpec, ModelError> {
    let JointGeometry { at, to, axis, axis_j } = *geometry;
    check_joint_keys(key, kind, [at.is_some(), to.is_some(), axis.is_some(), axis_j.is_some()])?;
    use JointKind as T;
    let [bi, bj] = bodies;
    let p = at.unwrap_or_else(Vec3::zeros);
    let axis = axis.unwrap_or_default();
    let axis_j = axis_j.unwrap_or_default();
    Ok(match kind {
        T::Spherical => JointSpec::spherical(name, bi, bj, p),
        T::Revolute => JointSpec::revolute(name, bi, bj, p, axis),
        T::Cylindrical => JointSpec::cylindrical(name, bi, bj, p, axis),
        T::Translational => JointSpec::translational(name, bi, bj, p, axis),
        T::Universal => JointSpec::universal(name, bi, bj, p, axis, axis_j),
        T::Fixed => JointSpec::fixed(name, bi, bj, p),
        T::Distance => JointSpec::distance(name, bi, bj, p, to.unwrap_or_default()),
        T::InPlane => JointSpec { point_j: to, ..JointSpec::in_plane(name, bi, bj, p, axis) },
        T::InLine => JointSpec { point_j: to, ..JointSpec::in_line(name, bi, bj, p, axis) },
        T::Perpendicular => JointSpec::perpendicular(name, bi, bj, axis, axis_j),
        T::ParallelAxes => JointSpec::parallel_axes(name, bi, bj, axis),
        T::PointDriver | T::TravelDriver => return Err(driver_refusal(key)),
    })
}

/// `'a', 'b' or 'c'` for messages.
fn list<'a>(names: impl Iterator<Item = &'a str>) -> String {
    let names: Vec<String> = names.map(|n| format!("'{n}'")).collect();
    match names.as_slice() {
        [] => "none (the list is empty)".into(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}

/// A bushing frame as the model file gives it, placed on `side`: x along `x_left`, y towards `y_hint_left`
/// made perpendicular (any perpendicular without it), both mirrored for the right corner, z completing a
/// right-handed frame. The columns are the frame's x, y, z axes in global components. The error says why
/// the hint gives no y axis (it is parallel to x). `x_left` must have a length.
fn bushing_frame(x_left: Vec3, y_hint_left: Option<Vec3>, side: Side) -> Result<Mat3, String> {
    let x = x_left / x_left.norm();
    let y = match y_hint_left {
        None => orthonormal_complement(&x).0,
        Some(h) => {
            let y = h - x * x.dot(&h);
            let n = y.norm();
            if n.is_nan() || n <= 1e-6 * h.norm() {
                return Err("y_axis is parallel to the bushing's axis: give a direction across it".into());
            }
            y / n
        }
    };
    let (x, y) = (side.place(x), side.place(y));
    Ok(Mat3::from_columns(&[x, y, x.cross(&y)]))
}

impl GeneralCorner {
    /// A corner with nothing in it yet but its description: the upright, named `upright`, carries the wheel
    /// whose centre is the hardpoint `wheel_centre`, its spin axis outward (+y).
    pub(crate) fn empty(loaded_radius: f64, steering_axis: [BodyPoint; 2], tie_rod: Option<TieRodDef>) -> Self {
        GeneralCorner {
            hardpoints: Hardpoints::default(),
            bodies: Vec::new(),
            joints: Vec::new(),
            bushings: Vec::new(),
            springs: Vec::new(),
            stops: Vec::new(),
            anti_roll_bars: Vec::new(),
            loads: Vec::new(),
            axle: None,
            corner: CornerDef {
                upright: "upright".into(),
                wheel_centre: "wheel_centre".into(),
                spin_axis: outward(),
                loaded_radius,
                steering_axis,
                tie_rod,
            },
        }
    }

    /// A template's corner in the general form, before its parts: its hardpoints (the wheel centre named
    /// `wheel_centre`), its bodies as `(name, hardpoint)` (the upright, named `upright`, first), its tyre's
    /// loaded radius, its steering axis as `(body, hardpoint)` from the lower to the upper point, its tie rod
    /// from `tie_rod_inner` to `tie_rod_outer`, and its linear coil spring between `seats` on `bodies`.
    pub(crate) fn template(
        hardpoints: Vec<(&str, Vec3)>,
        bodies: Vec<(&str, Place)>,
        loaded_radius: f64,
        steering_axis: [(&str, &str); 2],
        tie_rod: Connection,
        spring: (&crate::SpringSpec, [&str; 2], [&str; 2]),
    ) -> GeneralCorner {
        let (spec, spring_bodies, seats) = spring;
        let at = |(body, at): (&str, &str)| BodyPoint { body: body.into(), at: Place::named(at) };
        let tie_rod = TieRodDef {
            inner: Place::named("tie_rod_inner"),
            outer: Place::named("tie_rod_outer"),
            connection: tie_rod.into(),
        };
        let mut g = GeneralCorner::empty(loaded_radius, steering_axis.map(at), Some(tie_rod));
        g.hardpoints = Hardpoints(hardpoints.into_iter().map(|(n, p)| (n.to_string(), p)).collect());
        g.bodies = bodies.into_iter().map(|(name, at)| BodyDef { name: name.into(), at }).collect();
        g.springs.push(SpringDef {
            name: "spring".into(),
            bodies: spring_bodies.map(str::to_string),
            from: Place::named(seats[0]),
            to: Place::named(seats[1]),
            rate: Some(spec.rate),
            curve: None,
            design_force: Some(spec.design_force),
            free_length: None,
            preload: None,
        });
        g
    }

    /// Whether it has a steering input: the corner's tie rod, or a solid axle's steering link.
    pub fn is_steered(&self) -> bool {
        self.corner.tie_rod.is_some() || self.axle.as_ref().is_some_and(|a| a.steering_link.is_some())
    }

    /// Adds a joint of `kind` named `name` between `bodies` at the hardpoint `at`, about `axis`.
    pub(crate) fn push_joint(&mut self, name: &str, kind: JointKind, bodies: [&str; 2], at: &str, axis: Option<Axis>) {
        self.joints.push(JointDef {
            name: name.into(),
            kind,
            bodies: bodies.map(str::to_string),
            at: Some(Place::named(at)),
            to: None,
            axis,
            axis_j: None,
        });
    }

    fn resolver<'a>(&'a self, side: Side, prefix: &'a str) -> Resolver<'a> {
        Resolver { general: self, side, prefix, shared: None }
    }

    /// The resolver of the shared parts, between corners named with `left` and `right` prefixes.
    fn shared_resolver<'a>(&'a self, left: &'a str, right: &'a str) -> Resolver<'a> {
        Resolver { general: self, side: Side::Left, prefix: "", shared: Some((left, right)) }
    }

    /// Hardpoints with the wheel centre first, for the reach checks.
    fn hardpoints_wheel_centre_first(&self) -> Result<Vec<(&str, Vec3)>, ModelError> {
        let left = self.resolver(Side::Left, "");
        let name = self.corner.wheel_centre.as_str();
        let wc = left.point("corner.wheel_centre", &Place::named(name))?;
        let mut points = vec![(name, wc)];
        points.extend(self.hardpoints.0.iter().map(|(n, p)| (n.as_str(), *p)));
        Ok(points)
    }

    fn add_joint(&self, model: &mut Model, r: &Resolver, k: usize, j: &JointDef) -> Result<(), ModelError> {
        let key = format!("joints[{k}] ({})", j.name);
        let bi = r.body(model, &format!("{key}.bodies"), &j.bodies[0])?;
        let bj = r.body(model, &format!("{key}.bodies"), &j.bodies[1])?;
        // The keys before the points: a key the kind does not use is the mistake to name first.
        check_joint_keys(&key, j.kind, [j.at.is_some(), j.to.is_some(), j.axis.is_some(), j.axis_j.is_some()])?;
        let geometry = JointGeometry {
            at: j.at.as_ref().map(|p| r.point(&format!("{key}.at"), p)).transpose()?,
            to: j.to.as_ref().map(|p| r.point(&format!("{key}.to"), p)).transpose()?,
            axis: j.axis.as_ref().map(|a| r.direction(&format!("{key}.axis"), a)).transpose()?,
            axis_j: j.axis_j.as_ref().map(|a| r.direction(&format!("{key}.axis_j"), a)).transpose()?,
        };
        model.add_joint(joint_spec(&key, &part_name(r.prefix, &j.name), j.kind, [bi, bj], &geometry)?)?;
        Ok(())
    }

    fn add_bushing(&self, model: &mut Model, r: &Resolver, k: usize, b: &BushingDef) -> Result<(), ModelError> {
        let entry = format!("bushings[{k}]");
        let key = format!("{entry} ({})", b.name);
        let bi = r.body(model, &format!("{key}.bodies"), &b.bodies[0])?;
        let bj = r.body(model, &format!("{key}.bodies"), &b.bodies[1])?;
        let left = Resolver { side: Side::Left, ..*r };
        let x = b.axis.as_ref().map(|a| left.direction(&format!("{key}.axis"), a)).transpose()?.unwrap_or(Vec3::x());
        let y = b.y_axis.as_ref().map(|a| left.direction(&format!("{key}.y_axis"), a)).transpose()?;
        let point = r.point(&format!("{key}.at"), &b.at)?;
        model.add_element(b.bushing(&entry, &part_name(r.prefix, &b.name), [bi, bj], point, x, y, r.side)?)?;
        Ok(())
    }

    fn add_spring(&self, model: &mut Model, r: &Resolver, k: usize, s: &SpringDef) -> Result<ElementId, ModelError> {
        let key = format!("springs[{k}] ({})", s.name);
        let bi = r.body(model, &format!("{key}.bodies"), &s.bodies[0])?;
        let bj = r.body(model, &format!("{key}.bodies"), &s.bodies[1])?;
        let (from, to) = (r.point(&format!("{key}.from"), &s.from)?, r.point(&format!("{key}.to"), &s.to)?);
        model.add_element(s.spring(&key, &part_name(r.prefix, &s.name), [bi, bj], from, to)?)
    }

    fn add_stop(&self, model: &mut Model, r: &Resolver, k: usize, s: &StopDef) -> Result<(), ModelError> {
        let key = format!("stops[{k}] ({})", s.name);
        let bi = r.body(model, &format!("{key}.bodies"), &s.bodies[0])?;
        let bj = r.body(model, &format!("{key}.bodies"), &s.bodies[1])?;
        let (from, to) = (r.point(&format!("{key}.from"), &s.from)?, r.point(&format!("{key}.to"), &s.to)?);
        model.add_element(s.stop(&key, &part_name(r.prefix, &s.name), [bi, bj], from, to)?)?;
        Ok(())
    }
}

impl GeneralCorner {
    /// Adds the file's load case to a corner built from this model on `side` (names prefixed by
    /// `prefix`): each force and moment ramped by the load parameter. A force needs a point; a load needs
    /// a force or a moment.
    pub fn add_loads(&self, model: &mut Model, side: Side, prefix: &str) -> Result<(), ModelError> {
        let r = self.resolver(side, prefix);
        for (k, load) in self.loads.iter().enumerate() {
            let key = format!("loads[{k}] ({})", load.name);
            let refuse = |why: &str| Err(ModelError::OutOfRange { item: key.clone(), why: why.to_string() });
            let body = r.body(model, &format!("{key}.body"), &load.body)?;
            let finite = |v: &[f64; 3]| v.iter().all(|c| c.is_finite());
            match (load.force, load.torque, &load.at) {
                (None, None, _) => {
                    return refuse("give a force (N, with the point 'at' where it acts) or a torque (N·m)")
                }
                (Some(_), _, None) => return refuse("a force needs the point 'at' where it acts"),
                (None, Some(_), Some(_)) => return refuse("'at' means nothing to a torque alone: remove it"),
                _ => {}
            }
            if load.force.is_some_and(|f| !finite(&f)) || load.torque.is_some_and(|t| !finite(&t)) {
                return refuse("the force and torque must be finite numbers");
            }
            let name = part_name(prefix, &load.name);
            let s = side.sign();
            if let (Some(f), Some(at)) = (load.force, &load.at) {
                let point = r.point(&format!("{key}.at"), at)?;
                let force = Vec3::new(f[0], s * f[1], f[2]);
                let label = if load.torque.is_some() { format!("{name} force") } else { name.clone() };
                model.add_element(PointForce::new(&label, body, point, force)?)?;
            }
            if let Some(t) = load.torque {
                // A moment is a pseudo-vector: its mirror image keeps y and turns x and z over.
                let torque = Vec3::new(s * t[0], t[1], s * t[2]);
                let label = if load.force.is_some() { format!("{name} torque") } else { name.clone() };
                model.add_element(PointTorque::new(&label, body, torque)?)?;
            }
        }
        Ok(())
    }
}

fn kind_name(kind: JointKind) -> String {
    serde_json::to_value(kind).ok().and_then(|v| v.as_str().map(str::to_string)).unwrap_or_default()
}

impl CornerTemplate for GeneralCorner {
    fn add_corner(&self, model: &mut Model, side: Side, prefix: &str) -> Result<CornerParts, ModelError> {
        check_hardpoints(&self.hardpoints_wheel_centre_first()?)?;
        let r = self.resolver(side, prefix);
        if let Some(k) = self.bodies.iter().position(|b| b.name == CHASSIS) {
            return Err(ModelError::OutOfRange {
                item: format!("bodies[{k}]"),
                why: format!("'{CHASSIS}' names the ground: give the body another name"),
            });
        }
        let c = &self.corner;
        if !self.bodies.iter().any(|b| b.name == c.upright) {
            return Err(ModelError::OutOfRange {
                item: "corner.upright".into(),
                why: format!(
                    "there is no body '{}': name the body that carries the wheel, one of {}",
                    c.upright,
                    list(self.bodies.iter().map(|b| b.name.as_str()))
                ),
            });
        }
        let wheel_centre = r.point("corner.wheel_centre", &Place::named(&c.wheel_centre))?;
        let steering = [
            r.point("corner.steering_axis[0].at", &c.steering_axis[0].at)?,
            r.point("corner.steering_axis[1].at", &c.steering_axis[1].at)?,
        ];
        let left = self.resolver(Side::Left, prefix);
        let axis_left = (
            left.point("corner.steering_axis[0].at", &c.steering_axis[0].at)?,
            left.point("corner.steering_axis[1].at", &c.steering_axis[1].at)?,
        );
        let axis_names = (c.steering_axis[0].at.describe(), c.steering_axis[1].at.describe());
        let unquoted = |s: &str| s.trim_matches('\'').to_string();
        let axis_names = (unquoted(&axis_names.0), unquoted(&axis_names.1));
        check_steering_axis(axis_left, (&axis_names.0, &axis_names.1))?;
        if let Some(t) = &c.tie_rod {
            let (inner, outer) =
                (left.point("corner.tie_rod.inner", &t.inner)?, left.point("corner.tie_rod.outer", &t.outer)?);
            check_steering_arm(axis_left, (&axis_names.0, &axis_names.1), inner, outer)?;
        }
        for (k, body) in self.bodies.iter().enumerate() {
            let at = r.point(&format!("bodies[{k}] ({}).at", body.name), &body.at)?;
            model.add_body(&part_name(prefix, &body.name), Pose::at(at))?;
        }
        for (k, j) in self.joints.iter().enumerate() {
            self.add_joint(model, &r, k, j)?;
        }
        for (k, b) in self.bushings.iter().enumerate() {
            self.add_bushing(model, &r, k, b)?;
        }
        let mut springs = Vec::with_capacity(self.springs.len());
        for (k, s) in self.springs.iter().enumerate() {
            springs.push(self.add_spring(model, &r, k, s)?);
        }
        for (k, s) in self.stops.iter().enumerate() {
            self.add_stop(model, &r, k, s)?;
        }
        let upright =
            r.body(model, "corner.upright", &c.upright)?.id().expect("the upright is a body, not the chassis");
        let spin = Vec3::from(c.spin_axis);
        if !(spin.iter().all(|v| v.is_finite()) && spin.norm() > 1e-9) {
            return Err(ModelError::OutOfRange {
                item: "corner.spin_axis".into(),
                why: "give the wheel's outward spin axis as a non-zero direction [x, y, z]".into(),
            });
        }
        if spin.y < 0.5 * spin.norm() {
            return Err(ModelError::OutOfRange {
                item: "corner.spin_axis".into(),
                why: format!(
                    "[{}, {}, {}] is more than 60 deg from the left wheel's outward axis [0, 1, 0]: \
                     give the spin axis of the left wheel, pointing out of the car",
                    spin.x, spin.y, spin.z
                ),
            });
        }
        let steering_axis = [
            (r.body(model, "corner.steering_axis[0].body", &c.steering_axis[0].body)?, steering[0]),
            (r.body(model, "corner.steering_axis[1].body", &c.steering_axis[1].body)?, steering[1]),
        ];
        let wheel = Wheel::on(model, side, upright, wheel_centre, side.place(spin), c.loaded_radius, steering_axis)?;
        let tie_rod = match &c.tie_rod {
            None => None,
            Some(t) => Some(TieRod {
                inner: r.point("corner.tie_rod.inner", &t.inner)?,
                outer: r.point("corner.tie_rod.outer", &t.outer)?,
                connection: t.connection,
            }),
        };
        if let Some(TieRod { connection, .. }) = &tie_rod {
            crate::corner::check_tie_rod_mounts("corner.tie_rod.connection", connection)?;
        }
        Ok(CornerParts { wheel, tie_rod, spring: springs.first().copied() })
    }

    fn builds_on_axle_only(&self) -> bool {
        self.axle.is_some()
    }

    fn add_axle_bodies(&self, model: &mut Model) -> Result<(), ModelError> {
        let Some(axle) = &self.axle else { return Ok(()) };
        let r = self.shared_resolver("left ", "right ");
        let refuse = |item: String, why: String| Err(ModelError::OutOfRange { item, why });
        for (name, p) in &axle.hardpoints.0 {
            if !(p.iter().all(|c| c.is_finite()) && p.norm() <= MAX_WHEEL_CENTRE_DISTANCE) {
                let why = format!(
                    "{name} must lie within {MAX_WHEEL_CENTRE_DISTANCE} m of the vehicle origin, in metres (ISO 8855, \
                     x forward, y left, z up)"
                );
                return refuse("axle.hardpoints".into(), why);
            }
        }
        for (k, body) in axle.bodies.iter().enumerate() {
            let key = format!("axle.bodies[{k}] ({})", body.name);
            if body.name == CHASSIS {
                return refuse(key, format!("'{CHASSIS}' names the ground: give the body another name"));
            }
            if self.bodies.iter().any(|b| b.name == body.name) || r.sided(&body.name).is_some() {
                let why = "a corner's body has this name, or the axle's parts call a corner's body so: give the \
                           axle's body another name";
                return refuse(key, why.into());
            }
            let at = r.point(&format!("{key}.at"), &body.at)?;
            model.add_body(&body.name, Pose::at(at))?;
        }
        Ok(())
    }

    fn add_cross_axle(
        &self,
        model: &mut Model,
        left: (&str, &CornerParts),
        right: (&str, &CornerParts),
    ) -> Result<CrossAxle, ModelError> {
        let sides = || (self.resolver(Side::Left, left.0), self.resolver(Side::Right, right.0));
        let anti_roll_bars = self
            .anti_roll_bars
            .iter()
            .enumerate()
            .map(|(k, bar)| bar.add(model, k, sides()))
            .collect::<Result<_, _>>()?;
        let Some(axle) = &self.axle else { return Ok(CrossAxle { anti_roll_bars, steering_link: None }) };
        let r = self.shared_resolver(left.0, right.0);
        // The shared parts' messages name them under `axle.`.
        let under_axle = |e: ModelError| match e {
            ModelError::OutOfRange { item, why } if !item.starts_with("axle") => {
                ModelError::OutOfRange { item: format!("axle.{item}"), why }
            }
            other => other,
        };
        for (k, j) in axle.joints.iter().enumerate() {
            self.add_joint(model, &r, k, j).map_err(under_axle)?;
        }
        for (k, b) in axle.bushings.iter().enumerate() {
            self.add_bushing(model, &r, k, b).map_err(under_axle)?;
        }
        for (k, sp) in axle.springs.iter().enumerate() {
            self.add_spring(model, &r, k, sp).map_err(under_axle)?;
        }
        for (k, st) in axle.stops.iter().enumerate() {
            self.add_stop(model, &r, k, st).map_err(under_axle)?;
        }
        let mut anti_roll_bars = anti_roll_bars;
        for (k, name) in axle.anti_roll_bar_springs.iter().enumerate() {
            let known = axle.bushings.iter().any(|b| &b.name == name);
            match model.element_id(name).filter(|_| known) {
                Some(id) => anti_roll_bars.push(id),
                None => {
                    return Err(ModelError::OutOfRange {
                        item: format!("axle.anti_roll_bar_springs[{k}]"),
                        why: format!(
                            "there is no axle bushing '{name}': name one of {}",
                            list(axle.bushings.iter().map(|b| b.name.as_str()))
                        ),
                    })
                }
            }
        }
        let steering_link = match &axle.steering_link {
            None => None,
            Some(link) => {
                let key = "axle.steering_link";
                let rod = TieRod {
                    inner: r.point(&format!("{key}.inner"), &link.inner)?,
                    outer: r.point(&format!("{key}.outer"), &link.outer)?,
                    connection: link.connection,
                };
                crate::corner::check_tie_rod_mounts(&format!("{key}.connection"), &link.connection)?;
                let axis = r.direction(&format!("{key}.rack_axis"), &Axis::Vector(Vec3::from(link.rack_axis)))?;
                let body = r.body(model, &format!("{key}.body"), &link.body)?;
                Some(SteeringLink { body, rod, rack_axis: axis.normalize() })
            }
        };
        Ok(CrossAxle { anti_roll_bars, steering_link })
    }
}
