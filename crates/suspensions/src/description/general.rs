//! The general model: any suspension corner as named hardpoints, bodies, joints, bushings and springs,
//! with a corner description that says where the wheel is. Every template expands into it
//! ([`crate::description::Template::expand`]) and is built by it: there is one builder.
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

use crate::description::anti_roll_bar::AntiRollBar;
use crate::description::connection::{ArmMounts, BushingRates, Connection, SpringSpec, TieRodMounts};
use crate::description::layout::Layout;
use crate::description::limits::default_loaded_radius;
pub(crate) use crate::description::place::{part_name, short};
pub use crate::description::place::{Axis, Hardpoints, Place};
pub use crate::description::section::SectionDef;
use elastokin_core::{JointKind, Vec3};
use elastokin_elements::RotationLaw;
use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// The name of the ground in a general model.
pub const CHASSIS: &str = "chassis";

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
}

/// A field element between two bodies: a general 6×6 stiffness in a frame at a point, the coupled terms of
/// a data sheet allowed (a bushing is its diagonal case; see `elastokin_elements::Field`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FieldDef {
    /// Name; forces and deflections are reported under it.
    pub name: String,
    /// The two bodies: the frame moves with the first; forces are those on the second.
    pub bodies: [String; 2],
    /// Its point at design.
    pub at: Place,
    /// The frame's x axis (default: global x).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis: Option<Axis>,
    /// A direction the frame's y axis leans towards (default: any perpendicular to x).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y_axis: Option<Axis>,
    /// The stiffness over the deflection along x, y, z and the rotation about them, in the frame: six rows
    /// of six (N/m, N/rad, N·m/m, N·m/rad), symmetric and positive semi-definite.
    pub stiffness: [[f64; 6]; 6],
    /// Force on the second body at zero deflection, in the frame (N).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preload_force: Option<[f64; 3]>,
    /// Moment on the second body at zero rotation, in the frame (N·m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preload_torque: Option<[f64; 3]>,
}

/// A straight elastic beam from a point of its first body to a point of its second, by its section; split
/// into `segments` with bodies between them for a member that bends far (see `docs/model-file.md`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BeamDef {
    /// Name; with segments, each is named `<name> segment k` and the bodies between `<name> node k`.
    pub name: String,
    /// The body at its start and the body at its end.
    pub bodies: [String; 2],
    /// Its start.
    pub from: Place,
    /// Its end.
    pub to: Place,
    /// A direction the section's y axis leans towards (made perpendicular to the beam).
    pub y_axis: Axis,
    /// The section.
    pub section: SectionDef,
    /// How many straight segments it is made of (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub segments: Option<usize>,
}

impl BeamDef {
    /// The most segments a beam may be split into.
    pub const MOST_SEGMENTS: usize = 200;

    /// The names of its parts on the corner whose names start with `prefix`: its elements and the bodies
    /// between its segments.
    pub fn part_names(&self, prefix: &str) -> Vec<String> {
        let n = self.segments.unwrap_or(1);
        if n <= 1 {
            return vec![part_name(prefix, &self.name)];
        }
        let segments = (1..=n).map(|k| part_name(prefix, &format!("{} segment {k}", self.name)));
        let nodes = (1..n).map(|k| part_name(prefix, &format!("{} node {k}", self.name)));
        segments.chain(nodes).collect()
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
    #[serde(default = "default_loaded_radius")]
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

/// An entry of an element kind's list, as the build map reads any kind: its name and the names of what it
/// becomes.
pub trait ElementEntry {
    /// Its name in the description.
    fn name(&self) -> &str;

    /// The names of its parts on a corner whose names start with `prefix` (`""` on the axle): its element
    /// alone, unless the kind builds more.
    fn part_names(&self, prefix: &str) -> Vec<String> {
        vec![part_name(prefix, self.name())]
    }
}

impl ElementEntry for BushingDef {
    fn name(&self) -> &str {
        &self.name
    }
}

impl ElementEntry for FieldDef {
    fn name(&self) -> &str {
        &self.name
    }
}

impl ElementEntry for BeamDef {
    fn name(&self) -> &str {
        &self.name
    }

    fn part_names(&self, prefix: &str) -> Vec<String> {
        BeamDef::part_names(self, prefix)
    }
}

impl ElementEntry for SpringDef {
    fn name(&self) -> &str {
        &self.name
    }
}

impl ElementEntry for StopDef {
    fn name(&self) -> &str {
        &self.name
    }
}

/// Declares the one list of element kinds, [`ElementLists`] (a slice of each kind), and the structs that
/// hold elements, each with every kind's list where its `..elements` stands and an `elements()` that lends
/// them. A corner and the axle's shared parts thus take the same kinds, under the same keys, in the same
/// place of the file, and a kind is declared once. Each kind's list is optional and left out of a written
/// file when empty.
macro_rules! holding_elements {
    (kinds $kinds:tt $( $(#[$meta:meta])* pub struct $name:ident $body:tt )*) => {
        holding_elements!(@lists $kinds);
        $( holding_elements!(@holder $kinds $(#[$meta])* pub struct $name $body); )*
    };
    (@lists { $( $(#[$doc:meta])* $kind:ident: $def:ty, )* }) => {
        /// The element lists of a corner or of the axle's shared parts, one slice of each kind, in the order
        /// of the file and of the build.
        #[derive(Debug, Clone, Copy)]
        pub struct ElementLists<'a> {
            $( $(#[$doc])* pub $kind: &'a [$def], )*
        }

        impl<'a> ElementLists<'a> {
            /// The kinds' keys in a model file, in the order of the file.
            pub const KINDS: &'static [&'static str] = &[$( stringify!($kind) ),*];

            /// Each kind's key with its entries, in the order of [`Self::KINDS`].
            pub fn by_kind(&self) -> Vec<(&'static str, Vec<&'a dyn ElementEntry>)> {
                vec![$( (stringify!($kind), self.$kind.iter().map(|e| e as &dyn ElementEntry).collect()) ),*]
            }
        }
    };
    (@holder { $( $(#[$doc:meta])* $kind:ident: $def:ty, )* }
        $(#[$meta:meta])*
        pub struct $name:ident {
            $( $(#[$before_meta:meta])* pub $before:ident: $before_ty:ty, )*
            ..elements,
            $( $(#[$after_meta:meta])* pub $after:ident: $after_ty:ty, )*
        }
    ) => {
        $(#[$meta])*
        pub struct $name {
            $( $(#[$before_meta])* pub $before: $before_ty, )*
            $(
                $(#[$doc])*
                #[serde(default, skip_serializing_if = "Vec::is_empty")]
                pub $kind: Vec<$def>,
            )*
            $( $(#[$after_meta])* pub $after: $after_ty, )*
        }

        impl $name {
            /// Its element lists, by kind.
            pub fn elements(&self) -> ElementLists<'_> {
                ElementLists { $( $kind: &self.$kind ),* }
            }
        }
    };
}

holding_elements! {
    kinds {
        /// Rubber bushings.
        bushings: BushingDef,
        /// Field elements: coupled 6×6 stiffnesses.
        fields: FieldDef,
        /// Elastic beams.
        beams: BeamDef,
        /// Coil springs.
        springs: SpringDef,
        /// Bump and rebound stops.
        stops: StopDef,
    }

    /// The parts two corners share: the axle tube of a solid axle and what hangs on it once (a tie rod
    /// across, a Panhard rod, a bell crank). Written as they are in the car, both sides given, nothing
    /// mirrored; built once, on the whole axle. A corner names an axle body by its name; an axle part names a
    /// corner's body or hardpoint as `"left …"` or `"right …"` (the corner's, placed on that side). A model
    /// with an `axle` builds only whole: every corner analysis moves and loads both wheels alike. Its
    /// elements are those between shared parts (each corner's own go in the corner); a twist-beam axle's
    /// cross member is one of its beams, from `"left …"` to `"right …"`.
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
        ..elements,
        /// The steering input, when the corners have no tie rods of their own.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub steering_link: Option<SteeringLinkDef>,
        /// Names of the axle's bushings that are anti-roll bars' torsion springs (a bar built of its own
        /// parts, twisting about the bushing's x axis): the roll analysis counts their energy as the bars'.
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
        ..elements,
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
            fields: Vec::new(),
            beams: Vec::new(),
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
        spring: (&SpringSpec, [&str; 2], [&str; 2]),
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

    /// The general model's joints and bushings of the arm `arm` on the chassis, pivots at the hardpoints
    /// `front` and `rear`: a revolute `"{arm} pivot"` when both ends are ideal; otherwise, per end, a ball
    /// joint `"{arm} {end} ball joint"` or a bushing `"{arm} {end} bushing"` along the pivot axis.
    pub(crate) fn push_arm_mounts(&mut self, mounts: &ArmMounts, arm: &str, front: &str, rear: &str) {
        if *mounts == ArmMounts::from(Connection::Ideal) {
            let axis = Some(Axis::through(front, rear));
            self.push_joint(&format!("{arm} pivot"), JointKind::Revolute, [CHASSIS, arm], front, axis);
            return;
        }
        for (end, point, connection) in [("front", front, mounts.front), ("rear", rear, mounts.rear)] {
            match connection {
                Connection::Ideal => self.push_joint(
                    &format!("{arm} {end} ball joint"),
                    JointKind::Spherical,
                    [CHASSIS, arm],
                    point,
                    None,
                ),
                Connection::Bushing(rates) => self.bushings.push(BushingDef::cylindrical(
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

impl GeneralCorner {
    /// The same suspension with every bushing rigid — a fixed joint between its two bodies at its centre —
    /// for a model whose elastic beams still leave it a structure then (a twist beam): what its figures
    /// owe to the bushings' give is the difference. `None` without beams (a bushed linkage with its
    /// bushings rigid locks) or without bushings.
    pub fn with_rigid_bushings(&self) -> Option<GeneralCorner> {
        let axle = self.axle.as_ref();
        let beams = !self.beams.is_empty() || axle.is_some_and(|a| !a.beams.is_empty());
        let bushings = !self.bushings.is_empty() || axle.is_some_and(|a| !a.bushings.is_empty());
        if !(beams && bushings) {
            return None;
        }
        let rigid = |bushings: &mut Vec<BushingDef>, joints: &mut Vec<JointDef>| {
            joints.extend(bushings.drain(..).map(|b| JointDef {
                name: b.name,
                kind: JointKind::Fixed,
                bodies: b.bodies,
                at: Some(b.at),
                to: None,
                axis: None,
                axis_j: None,
            }));
        };
        let mut g = self.clone();
        rigid(&mut g.bushings, &mut g.joints);
        if let Some(a) = g.axle.as_mut() {
            rigid(&mut a.bushings, &mut a.joints);
            // A bar's torsion spring among the axle's bushings is rigid now: the bar is part of the axle.
            a.anti_roll_bar_springs.clear();
        }
        Some(g)
    }
}

impl GeneralCorner {
    /// Where its parts are, by hardpoint name (see [`Layout`]): the wheel centre, the steering axis and
    /// the tie rod when their points are hardpoints, and the first spring from the chassis when its seats
    /// are. A general corner names no arms.
    pub(crate) fn layout(&self) -> Layout {
        let name = |p: &Place| match p {
            Place::Named(n) => Some(n.clone()),
            Place::At(_) => None,
        };
        let both = |a: &Place, b: &Place| Some([name(a)?, name(b)?]);
        let c = &self.corner;
        let spring = self.springs.iter().find(|s| s.bodies[0] == CHASSIS).and_then(|s| {
            let seats = both(&s.from, &s.to)?;
            let advice = format!("move '{}' so that the spring works with the wheel's travel", seats[1]);
            Some((seats, s.bodies[1].clone(), advice))
        });
        Layout {
            wheel_centre: c.wheel_centre.clone(),
            steering_axis: both(&c.steering_axis[0].at, &c.steering_axis[1].at),
            tie_rod: c.tie_rod.as_ref().and_then(|t| both(&t.inner, &t.outer)),
            arms: Vec::new(),
            spring,
        }
    }
}
