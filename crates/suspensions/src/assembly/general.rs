//! The one builder: a general description ([`GeneralCorner`]) made into bodies, joints and elements of a
//! model, on either side. Every template builds through it (templates expand into the general form), and
//! so do Project Chrono's files and Python's scenes, entry by entry: [`joint_spec`],
//! [`BushingDef::bushing`], [`SpringDef::spring`] and [`StopDef::stop`] are where a described item becomes
//! an element, with its model-file key in every error.

use crate::assembly::map::load_labels;
use crate::assembly::template::{CornerParts, CornerTemplate, CrossAxle, ElasticMember, SteeringLink, TieRod};
use crate::description::general::{
    part_name, Axis, BeamDef, BodyDef, BushingDef, ElementLists, FieldDef, GeneralCorner, Hardpoints, JointDef, Place,
    SectionDef, SpringDef, Stiffness, StopDef, StopType, CHASSIS,
};
use crate::description::limits::{
    check_hardpoints, check_rate, check_spring_force, check_steering_arm, check_steering_axis, check_tie_rod_mounts,
    MAX_HARDPOINT_REACH, MAX_WHEEL_CENTRE_DISTANCE, ROTATIONAL_RATE_RANGE, TRANSLATIONAL_RATE_RANGE,
};
use crate::description::Side;
use crate::wheel::Wheel;
use elastokin_core::joint::orthonormal_complement;
use elastokin_core::{BodyRef, ElementId, JointKind, JointSpec, Mat3, Model, ModelError, Pose, Takes, Vec3};
use elastokin_elements::{
    beam, BeamSpec, Bushing, BushingSpec, Characteristic, CoilSpring, Curve, Field, FieldSpec, PointForce, PointTorque,
    Section, SpringLength, Stop,
};
use std::collections::{HashMap, HashSet};
use std::sync::Arc;

impl Stiffness {
    /// The element's characteristic; `item` names it in errors (a rate is checked by the element).
    fn characteristic(&self, item: impl std::fmt::Display) -> Result<Characteristic, ModelError> {
        match self {
            Stiffness::Rate(k) => Ok(Characteristic::Rate(*k)),
            Stiffness::Curve(points) => Ok(Characteristic::Curve(Curve::new(&item.to_string(), points.clone())?)),
        }
    }
}

impl BushingDef {
    /// The bushing this entry describes, its geometry resolved (`placed`): between its bodies, centred at
    /// its point, its frame's x and y as given for the left corner and mirrored for `side`
    /// (`bushing_frame`), its preload mirrored with the frame. `key` is where the entry is (`bushings[2]`),
    /// for errors as the rates' checks word them.
    pub fn bushing(
        &self,
        key: impl std::fmt::Display + Copy,
        name: &str,
        placed: &FramedEntry,
        side: Side,
    ) -> Result<Bushing, ModelError> {
        let FramedEntry { bodies, point, x: x_left, y: y_hint_left } = *placed;
        let (translational, rotational) = self.rates(key)?;
        let frame = bushing_frame(format_args!("{key} ({})", self.name), x_left, y_hint_left, side)?;
        let (force, torque) = mirrored_preload(self.preload_force, self.preload_torque, side);
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
    fn rates(
        &self,
        key: impl std::fmt::Display + Copy,
    ) -> Result<([Characteristic; 3], [Characteristic; 3]), ModelError> {
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
                let item = format_args!("{key} ({}).{name} {what}", self.name);
                if let Some(rate) = stiffness.rate() {
                    check_rate(item, rate, range, unit)?;
                }
                out[set].push(stiffness.characteristic(item)?);
            }
        }
        let [t, r] = out.map(|v| <[Characteristic; 3]>::try_from(v).expect("three directions"));
        Ok((t, r))
    }
}

impl SpringDef {
    /// The coil spring this entry describes, named `name`, between `bodies` from the seat `from` on the
    /// first to `to` on the second (global, at design): either the rate or the curve, either the push at
    /// design or the free length, the rate and the push checked against the model file's ranges. `key`
    /// names the entry in errors (`springs[0] (spring)` in a model file).
    pub fn spring(
        &self,
        key: impl std::fmt::Display + Copy,
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
        // What pushes, and how long it is free: one of each.
        let characteristic = match (self.rate, &self.curve) {
            (Some(rate), None) => {
                check_rate(format_args!("{key}.rate"), rate, TRANSLATIONAL_RATE_RANGE, "N/m")?;
                Characteristic::Rate(rate)
            }
            (None, Some(points)) => Characteristic::Curve(Curve::new(&format!("{key}.curve"), points.clone())?),
            _ => return refuse("give either rate (N/m) or curve (push force in N against compression in m)"),
        };
        let length = match (self.design_force, self.free_length) {
            (Some(force), None) => {
                if let Some(rate) = self.rate {
                    check_spring_force(key, rate, force, (to - from).norm())?;
                }
                SpringLength::DesignForce(force)
            }
            (None, Some(free)) => SpringLength::Free(free),
            _ => return refuse("give either design_force (N, its push at design) or free_length (m)"),
        };
        let spring = CoilSpring::seated(name, [(bi, from), (bj, to)], characteristic, length)?;
        match self.preload {
            Some(preload) => spring.with_preload(preload),
            None => Ok(spring),
        }
    }
}

impl StopDef {
    /// The stop this entry describes, named `name`, between `bodies` along the line from `from` on the
    /// first to `to` on the second (global, at design). `key` names the entry in errors (`stops[0] (bump
    /// stop)` in a model file).
    pub fn stop(
        &self,
        key: impl std::fmt::Display + Copy,
        name: &str,
        bodies: [BodyRef; 2],
        from: Vec3,
        to: Vec3,
    ) -> Result<Stop, ModelError> {
        let [bi, bj] = bodies;
        let curve = Curve::new(&format!("{key}.curve"), self.curve.clone())?;
        match self.kind {
            StopType::Bump => Stop::bump(name, bi, from, bj, to, self.clearance, curve),
            StopType::Rebound => Stop::rebound(name, bi, from, bj, to, self.clearance, curve),
        }
    }
}

/// The bodies of one corner by their file names, and the places resolved on one side; or, for the parts
/// two corners share ([`AxleDef`]), the axle's own names and each side's by `"left …"` / `"right …"`.
#[derive(Clone)]
pub(crate) struct Resolver<'a> {
    general: &'a GeneralCorner,
    /// The corner's body names, as the file gives them.
    corner_bodies: Arc<HashSet<&'a str>>,
    /// The corner's hardpoints and the axle's, by name (the first of a name, as [`Hardpoints::get`]).
    points: Arc<[HashMap<&'a str, Vec3>; 2]>,
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

    /// The side it places points on.
    pub(crate) fn side(&self) -> Side {
        self.side
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
    pub(crate) fn point(&self, key: impl std::fmt::Display + Copy, place: &Place) -> Result<Vec3, ModelError> {
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
                None => (self.side, *self.points[0].get(name.as_str()).ok_or_else(|| missing(name))?),
                Some(_) => match (self.points[1].get(name.as_str()), self.sided(name)) {
                    (Some(p), _) => (Side::Left, *p),
                    (None, Some((side, _, corner))) => {
                        (side, *self.points[0].get(corner).ok_or_else(|| missing(name))?)
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
        let limit = MAX_WHEEL_CENTRE_DISTANCE + MAX_HARDPOINT_REACH;
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
    pub(crate) fn direction(&self, key: impl std::fmt::Display + Copy, axis: &Axis) -> Result<Vec3, ModelError> {
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
    pub(crate) fn body(
        &self,
        model: &Model,
        key: impl std::fmt::Display + Copy,
        name: &str,
    ) -> Result<BodyRef, ModelError> {
        if name == CHASSIS {
            return Ok(BodyRef::Ground);
        }
        let corner_body = |prefix: &str, name: &str| {
            model.body_id(&part_name(prefix, name)).filter(|_| self.corner_bodies.contains(name))
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

/// Hardpoints by name, the first of a name kept (as [`Hardpoints::get`]).
fn by_name(hardpoints: &Hardpoints) -> HashMap<&str, Vec3> {
    hardpoints.0.iter().rev().map(|(n, p)| (n.as_str(), *p)).collect()
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
fn driver_refusal(key: impl std::fmt::Display) -> ModelError {
    ModelError::OutOfRange {
        item: key.to_string(),
        why: "a driver is the rig's (wheel travel, rack travel), not the model's: use a joint".into(),
    }
}

/// Refuses a driver (the rig's, not a model's), a key `kind` needs and is not given, and a key `kind`
/// does not use; `given` says which of `at`, `to`, `axis` and `axis_j` are, and `key` names the entry.
fn check_joint_keys(key: impl std::fmt::Display + Copy, kind: JointKind, given: [bool; 4]) -> Result<(), ModelError> {
    // Before the keys: a driver's keys are not the question.
    if kind.is_driver() {
        return Err(driver_refusal(key));
    }
    let refuse = |why: String| Err(ModelError::OutOfRange { item: key.to_string(), why });
    let taken = kind.geometry();
    let keys = [("at", taken.point), ("to", taken.point_j), ("axis", taken.axis), ("axis_j", taken.axis_j)];
    for ((what, takes), given) in keys.into_iter().zip(given) {
        match takes {
            Takes::Needed if !given => return refuse(format!("a {} joint needs '{what}': add it", kind_name(kind))),
            Takes::Unused if given => {
                return refuse(format!("'{what}' means nothing to a {} joint: remove it", kind_name(kind)))
            }
            _ => {}
        }
    }
    Ok(())
}

/// The joint a model file's joint entry describes: `name`, of `kind`, between `bodies` (reactions on the
/// second), at the resolved `geometry`. `key` names the entry in errors: a driver (the rig's), a kind
/// without a key it needs and a key the kind does not use are refused, as a model file's are. The
/// geometry itself (a zero axis, axes not perpendicular) is checked when the joint is added to a model.
pub fn joint_spec(
    key: impl std::fmt::Display + Copy,
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

/// The model-file key of entry `k` of the list `list`, with its name (`bushings[2] (lower arm front)`):
/// written only into an error, not for every entry of every build.
#[derive(Clone, Copy)]
struct EntryKey<'a> {
    list: &'static str,
    k: usize,
    name: Option<&'a str>,
}

impl std::fmt::Display for EntryKey<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}[{}]", self.list, self.k)?;
        match self.name {
            Some(name) => write!(f, " ({name})"),
            None => Ok(()),
        }
    }
}

/// What the callers keep of the elements [`GeneralCorner::add_elements`] adds: each spring's element, and
/// each beam as the segments it was built in.
struct AddedElements {
    springs: Vec<ElementId>,
    members: Vec<ElasticMember>,
}

/// What a bushing or a field entry names, resolved: its bodies, its point (on the side built), and its
/// frame's x axis and y hint as the left corner gives them (the frame is mirrored as a whole).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FramedEntry {
    /// Its two bodies.
    pub bodies: [BodyRef; 2],
    /// Its centre.
    pub point: Vec3,
    /// Its frame's x axis, as the left corner gives it.
    pub x: Vec3,
    /// Where its frame's y axis leans, as the left corner gives it (else chosen square to x).
    pub y: Option<Vec3>,
}

fn framed_entry(
    model: &Model,
    r: &Resolver,
    key: impl std::fmt::Display + Copy,
    bodies: &[String; 2],
    axis: Option<&Axis>,
    y_axis: Option<&Axis>,
    at: &Place,
) -> Result<FramedEntry, ModelError> {
    let bi = r.body(model, format_args!("{key}.bodies"), &bodies[0])?;
    let bj = r.body(model, format_args!("{key}.bodies"), &bodies[1])?;
    let left = Resolver { side: Side::Left, ..r.clone() };
    let x = axis.map(|a| left.direction(format_args!("{key}.axis"), a)).transpose()?.unwrap_or(Vec3::x());
    let y = y_axis.map(|a| left.direction(format_args!("{key}.y_axis"), a)).transpose()?;
    Ok(FramedEntry { bodies: [bi, bj], point: r.point(format_args!("{key}.at"), at)?, x, y })
}

/// A preload force and moment given in a left corner's frame, in `side`'s. Mirroring turns the frame's z
/// axis over (see [`bushing_frame`]): a preload's z force and x, y moments change sign in the right
/// corner's frame, so that the right element pushes as the mirror image of the left.
fn mirrored_preload(force: Option<[f64; 3]>, torque: Option<[f64; 3]>, side: Side) -> (Vec3, Vec3) {
    let s = side.sign();
    (
        force.map_or(Vec3::zeros(), |f| Vec3::new(f[0], f[1], s * f[2])),
        torque.map_or(Vec3::zeros(), |m| Vec3::new(s * m[0], s * m[1], m[2])),
    )
}

/// A bushing frame as the model file gives it, placed on `side`: x along `x_left`, y towards `y_hint_left`
/// made perpendicular (any perpendicular without it), both mirrored for the right corner, z completing a
/// right-handed frame. The columns are the frame's x, y, z axes in global components. The error names the
/// entry, `item`, and says why the hint gives no y axis (it is parallel to x). `x_left` must have a length.
fn bushing_frame(
    item: impl std::fmt::Display,
    x_left: Vec3,
    y_hint_left: Option<Vec3>,
    side: Side,
) -> Result<Mat3, ModelError> {
    let x = x_left / x_left.norm();
    let y = match y_hint_left {
        None => orthonormal_complement(&x).0,
        Some(h) => {
            let y = h - x * x.dot(&h);
            let n = y.norm();
            if n.is_nan() || n <= 1e-6 * h.norm() {
                let why = "y_axis is parallel to the bushing's axis: give a direction across it".into();
                return Err(ModelError::OutOfRange { item: item.to_string(), why });
            }
            y / n
        }
    };
    let (x, y) = (side.place(x), side.place(y));
    Ok(Mat3::from_columns(&[x, y, x.cross(&y)]))
}

impl FieldDef {
    /// The field element of this entry (`key` names it in errors) between `bodies`, at `point`, its frame
    /// from the left corner's `x_left` and `y_hint_left` mirrored to `side`. The mirror image turns the
    /// frame's z axis over (as a bushing's frame does): in the right corner's frame the deflection along z and
    /// the rotation about x and y change sign, so the matrix is `T K T` with `T = diag(1, 1, −1, −1, −1, 1)`,
    /// and the preload changes as a bushing's.
    #[allow(
        clippy::too_many_arguments,
        reason = "an entry's name and key for messages, its bodies and point, its frame as written for the left corner and the side it is mirrored to"
    )]
    pub fn field(
        &self,
        key: impl std::fmt::Display + Copy,
        name: &str,
        bodies: [BodyRef; 2],
        point: Vec3,
        x_left: Vec3,
        y_hint_left: Option<Vec3>,
        side: Side,
    ) -> Result<Field, ModelError> {
        let frame = bushing_frame(key, x_left, y_hint_left, side)?;
        let s = side.sign();
        let t = nalgebra::Vector6::new(1.0, 1.0, s, s, s, 1.0);
        let stiffness = nalgebra::Matrix6::from_fn(|a, b| t[a] * self.stiffness[a][b] * t[b]);
        let (force, torque) = mirrored_preload(self.preload_force, self.preload_torque, side);
        Field::from_spec(FieldSpec {
            name: name.to_string(),
            body_i: bodies[0],
            body_j: bodies[1],
            point,
            frame,
            stiffness,
            preload_force: force,
            preload_torque: torque,
        })
        // The matrix as the file gives it, named by its key.
        .map_err(|e| e.out_of_range_as(format!("{key}.stiffness")))
    }
}

impl GeneralCorner {
    fn resolver<'a>(&'a self, side: Side, prefix: &'a str) -> Resolver<'a> {
        Resolver { general: self, corner_bodies: self.body_names(), points: self.points(), side, prefix, shared: None }
    }

    /// The resolver of the shared parts, between corners named with `left` and `right` prefixes.
    fn shared_resolver<'a>(&'a self, left: &'a str, right: &'a str) -> Resolver<'a> {
        Resolver {
            general: self,
            corner_bodies: self.body_names(),
            points: self.points(),
            side: Side::Left,
            prefix: "",
            shared: Some((left, right)),
        }
    }

    fn points(&self) -> Arc<[HashMap<&str, Vec3>; 2]> {
        let axle = self.axle.as_ref().map(|a| by_name(&a.hardpoints)).unwrap_or_default();
        Arc::new([by_name(&self.hardpoints), axle])
    }

    fn body_names(&self) -> Arc<HashSet<&str>> {
        Arc::new(self.bodies.iter().map(|b| b.name.as_str()).collect())
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
        let key = EntryKey { list: "joints", k, name: Some(&j.name) };
        let bi = r.body(model, format_args!("{key}.bodies"), &j.bodies[0])?;
        let bj = r.body(model, format_args!("{key}.bodies"), &j.bodies[1])?;
        // The keys before the points: a key the kind does not use is the mistake to name first.
        check_joint_keys(key, j.kind, [j.at.is_some(), j.to.is_some(), j.axis.is_some(), j.axis_j.is_some()])?;
        let geometry = JointGeometry {
            at: j.at.as_ref().map(|p| r.point(format_args!("{key}.at"), p)).transpose()?,
            to: j.to.as_ref().map(|p| r.point(format_args!("{key}.to"), p)).transpose()?,
            axis: j.axis.as_ref().map(|a| r.direction(format_args!("{key}.axis"), a)).transpose()?,
            axis_j: j.axis_j.as_ref().map(|a| r.direction(format_args!("{key}.axis_j"), a)).transpose()?,
        };
        model.add_joint(joint_spec(key, &part_name(r.prefix, &j.name), j.kind, [bi, bj], &geometry)?)?;
        Ok(())
    }

    /// Adds every element of `elements`, kind after kind in their declared order, each entry keyed by its
    /// place in its kind's list (`bushings[2]`); what the corner and the axle keep of them is returned.
    fn add_elements(
        &self,
        model: &mut Model,
        r: &Resolver,
        elements: ElementLists,
    ) -> Result<AddedElements, ModelError> {
        // Every kind named: a kind declared without its build here does not compile.
        let ElementLists { bushings, fields, beams, springs, stops } = elements;
        for (k, b) in bushings.iter().enumerate() {
            self.add_bushing(model, r, k, b)?;
        }
        for (k, f) in fields.iter().enumerate() {
            self.add_field(model, r, k, f)?;
        }
        let mut members = Vec::with_capacity(beams.len());
        for (k, b) in beams.iter().enumerate() {
            let segments = self.add_beam(model, r, k, b)?;
            members.push(ElasticMember { name: b.name.clone(), segments });
        }
        let mut added_springs = Vec::with_capacity(springs.len());
        for (k, s) in springs.iter().enumerate() {
            added_springs.push(self.add_spring(model, r, k, s)?);
        }
        for (k, s) in stops.iter().enumerate() {
            self.add_stop(model, r, k, s)?;
        }
        Ok(AddedElements { springs: added_springs, members })
    }

    fn add_bushing(&self, model: &mut Model, r: &Resolver, k: usize, b: &BushingDef) -> Result<(), ModelError> {
        let entry = EntryKey { list: "bushings", k, name: None };
        let key = EntryKey { name: Some(&b.name), ..entry };
        let e = framed_entry(model, r, key, &b.bodies, b.axis.as_ref(), b.y_axis.as_ref(), &b.at)?;
        model.add_element(b.bushing(entry, &part_name(r.prefix, &b.name), &e, r.side)?)?;
        Ok(())
    }

    fn add_field(&self, model: &mut Model, r: &Resolver, k: usize, f: &FieldDef) -> Result<(), ModelError> {
        let key = EntryKey { list: "fields", k, name: Some(&f.name) };
        let e = framed_entry(model, r, key, &f.bodies, f.axis.as_ref(), f.y_axis.as_ref(), &f.at)?;
        model.add_element(f.field(key, &part_name(r.prefix, &f.name), e.bodies, e.point, e.x, e.y, r.side)?)?;
        Ok(())
    }

    /// A beam, in its segments with a body at each joint between them; returns the segments' elements in
    /// order along it. Mirrored, its section's z axis turns over (the frame is made from the mirrored x and
    /// y), so the shear centre's z offset changes sign.
    fn add_beam(&self, model: &mut Model, r: &Resolver, k: usize, b: &BeamDef) -> Result<Vec<ElementId>, ModelError> {
        let key = format!("beams[{k}] ({})", b.name);
        let bi = r.body(model, format_args!("{key}.bodies"), &b.bodies[0])?;
        let bj = r.body(model, format_args!("{key}.bodies"), &b.bodies[1])?;
        let (from, to) = (r.point(format_args!("{key}.from"), &b.from)?, r.point(format_args!("{key}.to"), &b.to)?);
        let y = r.direction(format_args!("{key}.y_axis"), &b.y_axis)?;
        let n = b.segments.unwrap_or(1);
        if !(1..=BeamDef::MOST_SEGMENTS).contains(&n) {
            return Err(ModelError::OutOfRange {
                item: format!("{key}.segments"),
                why: format!("give 1 to {} segments, got {n}", BeamDef::MOST_SEGMENTS),
            });
        }
        let section = b.section.section(r.side);
        let (ey, ez) = section.shear_centre;
        let turned_section = Section { shear_centre: (ey, -ez), ..section };
        let names = b.part_names(r.prefix);
        let mut segments = Vec::with_capacity(n);
        let at = |s: usize| from + (to - from) * (s as f64 / n as f64);
        let mut previous = bi;
        for s in 1..=n {
            let body_j = if s == n { bj } else { BodyRef::Body(model.add_body(&names[n + s - 1], Pose::at(at(s)))?) };
            // Each segment is carried by the body nearer the beam's end (the middle one of an odd number by
            // its start), so a beam between mirror-image points, a twist beam's cross member, bends as the
            // mirror image of itself: a segment's own finite rotation makes it differ from its ends
            // exchanged at second order. Turned end for end, its section's z axis turns over.
            let turned = 2 * s > n + 1;
            let spec = BeamSpec {
                name: names[s - 1].clone(),
                body_i: if turned { body_j } else { previous },
                body_j: if turned { previous } else { body_j },
                from: at(if turned { s } else { s - 1 }),
                to: at(if turned { s - 1 } else { s }),
                y_axis: y,
                section: if turned { turned_section } else { section },
            };
            segments.push(model.add_element(beam(&spec).map_err(|e| e.out_of_range_as(key.clone()))?)?);
            previous = body_j;
        }
        Ok(segments)
    }

    fn add_spring(&self, model: &mut Model, r: &Resolver, k: usize, s: &SpringDef) -> Result<ElementId, ModelError> {
        let key = EntryKey { list: "springs", k, name: Some(&s.name) };
        let bi = r.body(model, format_args!("{key}.bodies"), &s.bodies[0])?;
        let bj = r.body(model, format_args!("{key}.bodies"), &s.bodies[1])?;
        let (from, to) = (r.point(format_args!("{key}.from"), &s.from)?, r.point(format_args!("{key}.to"), &s.to)?);
        model.add_element(s.spring(key, &part_name(r.prefix, &s.name), [bi, bj], from, to)?)
    }

    fn add_stop(&self, model: &mut Model, r: &Resolver, k: usize, s: &StopDef) -> Result<(), ModelError> {
        let key = EntryKey { list: "stops", k, name: Some(&s.name) };
        let bi = r.body(model, format_args!("{key}.bodies"), &s.bodies[0])?;
        let bj = r.body(model, format_args!("{key}.bodies"), &s.bodies[1])?;
        let (from, to) = (r.point(format_args!("{key}.from"), &s.from)?, r.point(format_args!("{key}.to"), &s.to)?);
        model.add_element(s.stop(key, &part_name(r.prefix, &s.name), [bi, bj], from, to)?)?;
        Ok(())
    }
}

impl SectionDef {
    /// The section of a beam built on `side`: the mirror image turns the section's z axis over, so the
    /// shear centre's z offset changes sign on the right.
    pub(crate) fn section(&self, side: Side) -> Section {
        let (ey, ez) = self.shear_centre.map_or((0.0, 0.0), |[y, z]| (y, z));
        Section {
            youngs_modulus: self.youngs_modulus,
            shear_modulus: self.shear_modulus,
            area: self.area,
            iy: self.iy,
            iz: self.iz,
            j: self.j,
            shear_areas: self.shear_areas.map(|[y, z]| (y, z)),
            shear_centre: (ey, side.sign() * ez),
        }
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
            let body = r.body(model, format_args!("{key}.body"), &load.body)?;
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
            let s = side.sign();
            let (force_label, torque_label) = load_labels(load, prefix);
            if let (Some(f), Some(at), Some(label)) = (load.force, &load.at, force_label) {
                let point = r.point(format_args!("{key}.at"), at)?;
                let force = Vec3::new(f[0], s * f[1], f[2]);
                model.add_element(PointForce::new(&label, body, point, force)?)?;
            }
            if let (Some(t), Some(label)) = (load.torque, torque_label) {
                // A moment is a pseudo-vector: its mirror image keeps y and turns x and z over.
                let torque = Vec3::new(s * t[0], t[1], s * t[2]);
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
            let at = r.point(format_args!("bodies[{k}] ({}).at", body.name), &body.at)?;
            model.add_body(&part_name(prefix, &body.name), Pose::at(at))?;
        }
        for (k, j) in self.joints.iter().enumerate() {
            self.add_joint(model, &r, k, j)?;
        }
        let AddedElements { springs, .. } = self.add_elements(model, &r, self.elements())?;
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
            check_tie_rod_mounts("corner.tie_rod.connection", connection)?;
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
            let at = r.point(format_args!("{key}.at"), &body.at)?;
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
            .collect::<Result<Vec<_>, _>>()?
            .concat();
        let Some(axle) = &self.axle else {
            return Ok(CrossAxle { anti_roll_bars, steering_link: None, members: Vec::new() });
        };
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
        let AddedElements { members, .. } = self.add_elements(model, &r, axle.elements()).map_err(under_axle)?;
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
                    inner: r.point(format_args!("{key}.inner"), &link.inner)?,
                    outer: r.point(format_args!("{key}.outer"), &link.outer)?,
                    connection: link.connection,
                };
                check_tie_rod_mounts(&format!("{key}.connection"), &link.connection)?;
                let axis = r.direction(format_args!("{key}.rack_axis"), &Axis::Vector(Vec3::from(link.rack_axis)))?;
                let body = r.body(model, format_args!("{key}.body"), &link.body)?;
                Some(SteeringLink { body, rod, rack_axis: axis.normalize() })
            }
        };
        Ok(CrossAxle { anti_roll_bars, steering_link, members })
    }
}
