//! Chrono's `GenericWheeledSuspension` (`ChGenericWheeledSuspension`): Chrono's own general form, a list of
//! `Bodies`, `Joints`, `Distance Constraints`, `TSDAs` and `RSDAs`, each `Mirrored` (one per side, the
//! right the left's mirror image) or not (one, shared), and the `Spindle` with the body it turns on.
//!
//! Read onto the general model: each side's parts (mirrored) as the left corner, and the parts shared by
//! both sides (not mirrored: an axle tube, a tie rod or a drag link across) in the model's `axle`
//! ([`crate::description::general::AxleDef`]), so that a beam axle reads whole.
//! - A mirrored body is a body of the corner, by its Chrono name, its reference point at its `Position`;
//!   the spindle's `Attachment Body` is the corner's `upright` (the spindle turns on it: for statics they
//!   are one body). A shared body is an axle body; when the spindle turns on one, each side's upright is
//!   welded to it at the wheel centre. `Chassis` is the ground.
//! - A mirrored element names a body alone (each side's own, or a shared one); an element that is not
//!   mirrored names a shared body alone and one side's copy of a mirrored body as `[name, "Left" |
//!   "Right"]`, which is how Chrono's `FindBody` finds them.
//! - A joint is the joint of its `Type` in its frame (`Position`, `Rotation`; z is the axis of a
//!   revolute, x the line of a point-line, z the normal of a point-plane, x on `Body1` and y on `Body2` the
//!   axes of a universal) between `Body1` and `Body2`: `Lock` is fixed, `Point Line` in-line and
//!   `Point Plane` in-plane (the point of `Body1` on the line or plane of `Body2`). With `Bushing Data` it is
//!   Chrono's bushing in that frame ([`Builder::joint`]).
//! - A distance constraint is a distance link from `Point1` on `Body1` to `Point2` on `Body2`.
//! - `Steering` is Chrono's steering link (the rack): a mirrored distance constraint from it to the upright
//!   is the corner's tie rod, as is a rod body on ideal ball or universal joints from it to the upright; a
//!   shared one (a drag link) to any body is the axle's steering link, moved along its own line when
//!   steering. The rig attaches either to the rack when steering and to the chassis otherwise.
//! - A TSDA with a spring (`Spring Coefficient` or `Spring Curve Data`) is a spring between its points
//!   ([`Builder::spring`], with its stops); a damper is left out (statics: no velocity), said in the notes.
//! - An RSDA (`ChLinkRSDA`: `P − k (θ − θ₀)` about its axis on `Body2`) between two bodies that turn on a
//!   revolute joint about its axis is a torsion bushing of rate `k` on that joint ([`Builder::torsion_spring`];
//!   the joint holds the other directions), pushing `P + k θ₀` at design. A mirrored RSDA's right side is the
//!   left's mirror image; Chrono turns a right-side preload the other way, said in the notes.
//! - The steering axis is the upright's revolute axis when it turns on one (a kingpin), else the line
//!   through its lowest and highest ball joints (a ball or universal joint, or two or more distance links
//!   meeting at one point of the upright); the wheel's vertical when the upright is welded to a shared body.
//!
//! Refused by name: a mirrored element joined to one named side of a body, a shared element naming a body
//! of each side without its side, the subchassis, an RSDA on no revolute joint about its axis or given by a
//! torque curve, a joint type Chrono does not read.

use super::builder::Builder;
use super::doc::Doc;
use super::error::{Expected, Refusal};
use crate::description::general::CHASSIS;
use crate::description::general::{Place, SteeringLinkDef, TieRodDef};
use crate::description::Connection;
use crate::description::Side;
use elastokin_core::{JointKind, Vec3};
use nalgebra::{Quaternion, UnitQuaternion};
use serde_json::Value;
use std::collections::{BTreeMap, BTreeSet};

/// What an element of the file joins.
#[derive(Debug, Clone, PartialEq)]
enum Part {
    /// The chassis (`"Chassis"`).
    Chassis,
    /// Chrono's steering link, the rack (`"Steering"`).
    Steering,
    /// A body of `Bodies`, by its Chrono name: a mirrored body (each side's own) or a shared one.
    Body(String),
    /// One side's copy of a mirrored body (`[name, "Left" | "Right"]`), from an element that is not mirrored.
    Sided(String, Side),
}

/// A joint of `Joints`.
struct Joint {
    /// Its path in the document (`Joints/2`).
    path: String,
    name: String,
    kind: JointKind,
    parts: [Part; 2],
    /// Chrono's frame as `(u, w)`: its x and z axes.
    frame: (Vec3, Vec3),
    bushing: bool,
    /// One per side (the left's, mirrored), or one shared by both.
    mirrored: bool,
}

/// A distance constraint of `Distance Constraints`.
struct Link {
    path: String,
    name: String,
    parts: [Part; 2],
    points: [Vec3; 2],
    mirrored: bool,
}

pub(super) fn read(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    let steerable = flag(doc, "Steerable")?;
    let independent = flag(doc, "Independent")?;
    b.wheel(doc)?;
    if doc.has("Output") {
        doc.expect("Output");
        b.notes.push("Output: Chrono's output switch, not part of the suspension".into());
    }
    let bodies = bodies(doc)?;
    let upright = upright(doc, &bodies)?;
    let elements = Elements::read(doc, &bodies)?;
    let steering = Steering::read(doc, &elements, &bodies, &upright)?;
    let (tie_rod, steering_link) = steering.tie_rod_and_link(&upright)?;
    if !steerable && !steering.inputs.is_empty() {
        return Err(Refusal::unusable(
            &["Steerable", "Steering"],
            "\"Steerable\" is false, yet an element joins \"Steering\": Chrono gives an unsteered suspension \
                    no steering link; join the toe link to the chassis, or make the suspension steerable",
        ));
    }

    write_bodies(doc, b, &bodies, &upright, &steering.rods)?;
    let mut names = BTreeSet::new();
    let upright_joints = write_joints(doc, b, &elements.joints, &steering.joints, &upright, &mut names)?;
    let link_ends = write_links(doc, b, &elements.links, &upright, &mut names)?;
    if let Some(input) = tie_rod {
        write_tie_rod(b, input);
    }
    if let Some(input) = steering_link {
        write_steering_link(b, input, &upright)?;
    }
    if steerable && steering.inputs.is_empty() {
        b.notes.push(
            "\"Steerable\" is true but nothing joins \"Steering\": no tie rod, the steering analysis does not apply"
                .into(),
        );
    }
    write_springs(doc, b, &elements.tsdas, &upright, &mut names)?;
    write_rsdas(doc, b, &elements.rsdas, &upright, &mut names)?;
    if upright.welded {
        b.wheel_vertical_steering_axis()?;
        b.notes.push("steering axis: the wheel's vertical (the wheel turns on a shared body, no kingpin)".into());
    } else {
        steering_axis(doc, b, &upright.name, &upright_joints, &link_ends)?;
    }
    if doc.has("Antiroll Body") {
        doc.expect("Antiroll Body");
        b.notes.push(
            "Antiroll Body: where Chrono attaches an anti-roll bar subsystem (its own file); no bar is read".into(),
        );
    }
    if !independent {
        b.notes.push("\"Independent\" is false: read as the independent corners its bodies describe".into());
    }
    Ok(())
}

/// The file's bodies: one per side (mirrored), or one shared by both sides (an axle tube, a tie rod across),
/// which goes in the model's axle.
fn bodies(doc: &Doc) -> Result<Bodies, Refusal> {
    let mut bodies = Bodies { positions: BTreeMap::new(), order: Vec::new(), shared: BTreeSet::new() };
    for path in list(doc, "Bodies") {
        let name = text(doc, &format!("{path}/Name"))?;
        if !flag(doc, &format!("{path}/Mirrored"))? {
            bodies.shared.insert(name.clone());
        }
        let at = doc.point(&format!("{path}/Position"))?;
        bodies.order.push(name.clone());
        if bodies.positions.insert(name.clone(), (path.clone(), at)).is_some() {
            return Err(Refusal::unusable(
                &[],
                format!(
                    "{}: a second body named '{name}' (Chrono keeps the first): give each body its own name",
                    doc.shown(&path)
                ),
            ));
        }
    }
    Ok(bodies)
}

/// The corner's upright as the file gives it.
struct Upright {
    /// The body the spindle turns on (`Spindle / Attachment Body`).
    name: String,
    /// Whether that body is shared by both sides (an axle tube carrying both spindles): each side's upright
    /// is then welded to it at the wheel centre.
    welded: bool,
}

impl Upright {
    /// The general model's name of a body of the file: the upright's is `upright` unless it is welded.
    fn general_name(&self, n: &str) -> String {
        if n == self.name && !self.welded {
            "upright".to_string()
        } else {
            n.to_string()
        }
    }

    /// The general model's name of `part`.
    fn name_of(&self, part: &Part) -> String {
        match part {
            Part::Body(n) => self.general_name(n),
            Part::Sided(n, Side::Left) => format!("left {}", self.general_name(n)),
            Part::Sided(n, Side::Right) => format!("right {}", self.general_name(n)),
            // The steering link has been taken as the tie rod's rack before any element is written.
            Part::Chassis | Part::Steering => CHASSIS.to_string(),
        }
    }
}

/// The upright: the body the spindle turns on. No other body may take the general model's names of the
/// ground and the upright.
fn upright(doc: &Doc, bodies: &Bodies) -> Result<Upright, Refusal> {
    let name = match part(doc, "Spindle/Attachment Body", bodies, true)? {
        Part::Body(name) => name,
        Part::Chassis => {
            return Err(Refusal::unusable(
                &["Spindle", "Attachment Body"],
                "\"Spindle\" / \"Attachment Body\" is the chassis: the wheel has no suspension motion to \
                        analyse; name the body the spindle turns on",
            ))
        }
        Part::Steering | Part::Sided(..) => {
            return Err(Refusal::unusable(
                &["Spindle", "Attachment Body"],
                "\"Spindle\" / \"Attachment Body\" is the steering link: name the body the spindle turns on \
                        (the upright)",
            ))
        }
    };
    let welded = bodies.shared.contains(&name);
    for body in bodies.positions.keys() {
        if (body != &name || welded) && (body.eq_ignore_ascii_case(CHASSIS) || body == "upright") {
            return Err(Refusal::unusable(
                &[],
                format!(
                    "body '{body}': the general model names the ground 'chassis' and the spindle's body 'upright'; \
                 rename this body"
                ),
            ));
        }
    }
    Ok(Upright { name, welded })
}

/// A spring or damper of `TSDAs`: its path and what it joins, the rest read when it is written.
struct Tsda {
    path: String,
    parts: [Part; 2],
    mirrored: bool,
}

/// The file's elements, each side's (mirrored) or one shared, as read before any is written.
struct Elements {
    joints: Vec<Joint>,
    links: Vec<Link>,
    tsdas: Vec<Tsda>,
    rsdas: Vec<Rsda>,
}

impl Elements {
    /// `Joints`, `Distance Constraints`, `TSDAs` and `RSDAs`, in that order.
    fn read(doc: &Doc, bodies: &Bodies) -> Result<Self, Refusal> {
        let joints: Vec<Joint> =
            list(doc, "Joints").into_iter().map(|path| joint(doc, path, bodies)).collect::<Result<_, _>>()?;
        let mut links = Vec::new();
        for path in list(doc, "Distance Constraints") {
            let name = text(doc, &format!("{path}/Name"))?;
            let mirrored = flag(doc, &format!("{path}/Mirrored"))?;
            let parts = two_parts(doc, &path, bodies, mirrored)?;
            let points = [doc.point(&format!("{path}/Point1"))?, doc.point(&format!("{path}/Point2"))?];
            links.push(Link { path, name, parts, points, mirrored });
        }
        let tsdas = list(doc, "TSDAs").into_iter().map(|path| tsda(doc, path, bodies)).collect::<Result<_, _>>()?;
        let rsdas = rsdas(doc, bodies, &joints)?;
        Ok(Elements { joints, links, tsdas, rsdas })
    }
}

/// The joint at `path` of `Joints`: the joint of its `Type` in its frame, or Chrono's bushing there.
fn joint(doc: &Doc, path: String, bodies: &Bodies) -> Result<Joint, Refusal> {
    let name = text(doc, &format!("{path}/Name"))?;
    let mirrored = flag(doc, &format!("{path}/Mirrored"))?;
    let chrono_type = text(doc, &format!("{path}/Type"))?;
    let kind = match chrono_type.as_str() {
        "Spherical" => JointKind::Spherical,
        "Revolute" => JointKind::Revolute,
        "Universal" => JointKind::Universal,
        "Lock" => JointKind::Fixed,
        "Point Line" => JointKind::InLine,
        "Point Plane" => JointKind::InPlane,
        other => {
            return Err(Refusal::unusable(
                &[],
                format!(
                    "{}: \"Type\" '{other}' is not one Chrono reads (it would take it as \"Lock\"); give \
                     \"Spherical\", \"Revolute\", \"Universal\", \"Lock\", \"Point Line\" or \"Point Plane\"",
                    doc.shown(&path)
                ),
            ));
        }
    };
    let parts = two_parts(doc, &path, bodies, mirrored)?;
    let frame = rotation(doc, &format!("{path}/Rotation"))?;
    doc.expect(&format!("{path}/Position"));
    let bushing = doc.at(&format!("{path}/Bushing Data")).is_some_and(Value::is_object);
    if bushing && matches!(kind, JointKind::InLine | JointKind::InPlane) {
        return Err(Refusal::unusable(
            &[],
            format!(
                "{}: Chrono builds no joint at all for a \"{chrono_type}\" with \"Bushing Data\"; remove the \
                 \"Bushing Data\" for the joint, or the joint",
                doc.shown(&path)
            ),
        ));
    }
    let frame = (frame * Vec3::x(), frame * Vec3::z());
    Ok(Joint { path, name, kind, parts, frame, bushing, mirrored })
}

/// The spring or damper at `path` of `TSDAs`: what it joins, which is never the steering link.
fn tsda(doc: &Doc, path: String, bodies: &Bodies) -> Result<Tsda, Refusal> {
    let mirrored = flag(doc, &format!("{path}/Mirrored"))?;
    let parts = two_parts(doc, &path, bodies, mirrored)?;
    if parts.contains(&Part::Steering) {
        return Err(Refusal::unusable(
            &[],
            format!(
                "{}: a spring or damper on the steering link; the general model reaches the rack only through the \
                 tie rod: attach it to the chassis or a body of the corner",
                doc.shown(&path)
            ),
        ));
    }
    Ok(Tsda { path, parts, mirrored })
}

/// A steering input: a rod from the steering link to the body it pushes.
struct Input {
    /// The rod's end at the steering link.
    inner: Vec3,
    outer: Vec3,
    target: Part,
    /// Each side's (the corner's tie rod) or one shared (the axle's steering link).
    mirrored: bool,
    /// What it is in the file, for notes and refusals.
    what: String,
}

/// The steering inputs: a distance constraint from the steering link, or a rod body on ideal ball or
/// universal joints from it to another body. Mirrored, it is the corner's tie rod (to the upright); shared,
/// the axle's steering link (a drag link) to whatever it pushes.
struct Steering {
    inputs: Vec<Input>,
    /// The rod bodies, written as the inputs they are rather than as bodies.
    rods: BTreeSet<String>,
    /// The joints of the rods (indices of `Joints`), written as the inputs they are rather than as joints.
    joints: BTreeSet<usize>,
}

impl Steering {
    /// The links from the steering link first, then the rods, in the file's order.
    fn read(doc: &Doc, elements: &Elements, bodies: &Bodies, upright: &Upright) -> Result<Self, Refusal> {
        let mut steering = Steering { inputs: Vec::new(), rods: BTreeSet::new(), joints: BTreeSet::new() };
        for link in elements.links.iter().filter(|l| l.parts.contains(&Part::Steering)) {
            let k = usize::from(link.parts[0] != Part::Steering);
            steering.inputs.push(Input {
                inner: link.points[k],
                outer: link.points[1 - k],
                target: link.parts[1 - k].clone(),
                mirrored: link.mirrored,
                what: doc.shown(&link.path),
            });
        }
        let joints = &elements.joints;
        for (i, j) in joints.iter().enumerate().filter(|(_, j)| j.parts.contains(&Part::Steering)) {
            let (rod, outer) = rod(doc, i, elements, bodies, upright)?;
            let o = &joints[outer].parts;
            let target = if o[0] == Part::Body(rod.clone()) { o[1].clone() } else { o[0].clone() };
            let at = |m: usize| doc.point(&format!("{}/Position", joints[m].path));
            steering.inputs.push(Input {
                inner: at(i)?,
                outer: at(outer)?,
                target,
                mirrored: j.mirrored,
                what: format!("the rod '{rod}' ({} and {})", doc.shown(&j.path), doc.shown(&joints[outer].path)),
            });
            steering.rods.insert(rod);
            steering.joints.extend([i, outer]);
        }
        Ok(steering)
    }

    /// The corner's tie rod (the mirrored input, to the upright) and the axle's steering link (the shared
    /// one), at most one of each.
    fn tie_rod_and_link(&self, upright: &Upright) -> Result<(Option<&Input>, Option<&Input>), Refusal> {
        let mut tie_rod: Option<&Input> = None;
        let mut steering_link: Option<&Input> = None;
        for input in &self.inputs {
            let slot = if input.mirrored { &mut tie_rod } else { &mut steering_link };
            if let Some(first) = slot {
                return Err(Refusal::unusable(
                    &[],
                    format!(
                        "{}: a second steering input of its kind (the first is {}); the general model steers by one \
                         tie rod per corner and one steering link across",
                        input.what, first.what
                    ),
                ));
            }
            if input.mirrored && (input.target != Part::Body(upright.name.clone()) || upright.welded) {
                let upright = &upright.name;
                return Err(Refusal::unusable(
                    &[],
                    format!(
                        "{}: a link from the steering link to {}, not to the upright '{upright}'; the general model's \
                         tie rod runs from the rack to the upright",
                        input.what,
                        describe(&input.target)
                    ),
                ));
            }
            *slot = Some(input);
        }
        Ok((tie_rod, steering_link))
    }
}

/// The rod that joint `i`, a joint to the steering link, holds: a body on ball or universal joints (without
/// bushings) to the steering link and to one other body alone. Returns the rod and its other joint.
fn rod(
    doc: &Doc,
    i: usize,
    elements: &Elements,
    bodies: &Bodies,
    upright: &Upright,
) -> Result<(String, usize), Refusal> {
    let Elements { joints, links, tsdas, rsdas } = elements;
    let j = &joints[i];
    let k = usize::from(j.parts[0] != Part::Steering);
    let refuse = |why: &str| {
        Refusal::unusable(
            &[],
            format!(
                "{}: a joint to the steering link ({why}); the general model reaches the rack only through a rod: a \
                 distance constraint from \"Steering\" (to the upright, or for one shared by both sides to any \
                 body), or a rod body on ball or universal joints (without \"Bushing Data\") from it to one body",
                doc.shown(&j.path)
            ),
        )
    };
    let Part::Body(rod) = &j.parts[1 - k] else {
        return Err(refuse(&format!("to {}", describe(&j.parts[1 - k]))));
    };
    if rod == &upright.name {
        return Err(refuse("to the upright itself"));
    }
    if j.bushing {
        return Err(refuse("with \"Bushing Data\""));
    }
    if !matches!(j.kind, JointKind::Spherical | JointKind::Universal) {
        return Err(refuse(&format!("a {:?} joint, where a rod has a ball or universal joint", j.kind)));
    }
    if bodies.shared.contains(rod) == j.mirrored {
        return Err(refuse(&format!("'{rod}' and the joint are not both mirrored or both shared")));
    }
    let on_rod = |parts: &[Part; 2]| parts.contains(&Part::Body(rod.clone()));
    let others: Vec<usize> = (0..joints.len()).filter(|&m| m != i && on_rod(&joints[m].parts)).collect();
    match others.as_slice() {
        [m] if !joints[*m].bushing
            && !joints[*m].parts.contains(&Part::Steering)
            && matches!(joints[*m].kind, JointKind::Spherical | JointKind::Universal)
            && !links.iter().any(|l| on_rod(&l.parts))
            && !tsdas.iter().any(|t| on_rod(&t.parts))
            && !rsdas.iter().any(|r| on_rod(&r.parts)) =>
        {
            Ok((rod.clone(), *m))
        }
        _ => Err(refuse(&format!("'{rod}' is not a rod to one body alone"))),
    }
}

/// The bodies: each side's in the corner, the shared ones on the axle; the upright, when shared, welded to
/// each side's.
fn write_bodies(
    doc: &Doc,
    b: &mut Builder,
    bodies: &Bodies,
    upright: &Upright,
    rods: &BTreeSet<String>,
) -> Result<(), Refusal> {
    for name in &bodies.order {
        let (path, at) = &bodies.positions[name];
        doc.dynamics(path, &["Mass", "Rotation", "Moments of Inertia", "Products of Inertia"], &mut b.notes);
        shapes(doc, path, &mut b.notes);
        if rods.contains(name) {
            continue;
        }
        if name == &upright.name && !upright.welded {
            b.notes.push(format!(
                "{}: the spindle's attachment body, the corner's upright (the spindle turns on it: for statics one \
                 body), its reference point the wheel centre",
                doc.shown(path)
            ));
            continue;
        }
        b.on_axle(bodies.shared.contains(name));
        b.body_at(name, Place::At(*at));
        b.on_axle(false);
    }
    if upright.welded {
        // Each spindle turns on the shared body: the corner's upright is that body's end, welded to it.
        let name = &upright.name;
        b.joint(doc, "spindle housing", JointKind::Fixed, [name, "upright"], Place::named("wheel_centre"), None, None)?;
        b.notes.push(format!(
            "\"Spindle\" / \"Attachment Body\" '{name}' is shared by both sides: each side's upright is welded to \
             it at the wheel centre"
        ));
    }
    Ok(())
}

/// The joints but the rods', by their hardpoints, named after them; a shared one on the axle. Returns each
/// side's joints on the upright, with their hardpoints.
fn write_joints<'a>(
    doc: &Doc,
    b: &mut Builder,
    joints: &'a [Joint],
    rods: &BTreeSet<usize>,
    upright: &Upright,
    names: &mut BTreeSet<String>,
) -> Result<Vec<(&'a Joint, String)>, Refusal> {
    let mut upright_joints = Vec::new();
    for (i, j) in joints.iter().enumerate() {
        if rods.contains(&i) {
            continue;
        }
        b.on_axle(!j.mirrored);
        let at = fresh_point(b, doc, &j.name, &format!("{}/Position", j.path))?;
        let bodies = j.parts.clone().map(|p| upright.name_of(&p));
        let name = fresh(names, &j.name);
        let bushing = j.bushing.then(|| format!("{}/Bushing Data", j.path));
        b.joint(doc, &name, j.kind, [&bodies[0], &bodies[1]], Place::named(&at), Some(j.frame), bushing.as_deref())?;
        b.on_axle(false);
        if j.mirrored && !upright.welded && j.parts.contains(&Part::Body(upright.name.clone())) {
            upright_joints.push((j, at));
        }
    }
    Ok(upright_joints)
}

/// The distance links but those from the steering link; a shared one on the axle. Returns each side's
/// links' ends on the upright: where they are and their hardpoints.
fn write_links(
    doc: &Doc,
    b: &mut Builder,
    links: &[Link],
    upright: &Upright,
    names: &mut BTreeSet<String>,
) -> Result<Vec<(Vec3, String)>, Refusal> {
    let mut link_ends = Vec::new();
    for link in links {
        if link.parts.contains(&Part::Steering) {
            continue;
        }
        b.on_axle(!link.mirrored);
        let from = fresh_point(b, doc, &format!("{} point 1", link.name), &format!("{}/Point1", link.path))?;
        let to = fresh_point(b, doc, &format!("{} point 2", link.name), &format!("{}/Point2", link.path))?;
        let bodies = link.parts.clone().map(|p| upright.name_of(&p));
        b.link(&fresh(names, &link.name), [&bodies[0], &bodies[1]], &from, &to);
        b.on_axle(false);
        for (k, end) in [from, to].into_iter().enumerate() {
            if link.mirrored && !upright.welded && link.parts[k] == Part::Body(upright.name.clone()) {
                link_ends.push((link.points[k], end));
            }
        }
    }
    Ok(link_ends)
}

/// The corner's tie rod, from the rack (or the chassis) to the upright.
fn write_tie_rod(b: &mut Builder, input: &Input) {
    b.general.hardpoints.0.push(("tie_rod_inner".into(), input.inner));
    b.general.hardpoints.0.push(("tie_rod_outer".into(), input.outer));
    b.general.corner.tie_rod = Some(TieRodDef {
        inner: Place::named("tie_rod_inner"),
        outer: Place::named("tie_rod_outer"),
        connection: Connection::Ideal.into(),
    });
    b.notes
        .push(format!("{}: the corner's tie rod, from the rack (steering) or the chassis to the upright", input.what));
}

/// The axle's steering link (a drag link), moved along its own line when steering.
fn write_steering_link(b: &mut Builder, input: &Input, upright: &Upright) -> Result<(), Refusal> {
    let along = input.outer - input.inner;
    if along.norm() < 1e-6 {
        return Err(Refusal::unusable(&[], format!("{}: its two ends coincide; give the rod its length", input.what)));
    }
    let axis = along.normalize();
    b.on_axle(true);
    b.axle().steering_link = Some(SteeringLinkDef {
        body: upright.name_of(&input.target),
        inner: Place::At(input.inner),
        outer: Place::At(input.outer),
        connection: Connection::Ideal.into(),
        rack_axis: [axis.x, axis.y, axis.z],
    });
    b.on_axle(false);
    b.notes.push(format!(
        "{}: the axle's steering link, from the steering box to {}; the steering analysis moves its steering-box \
         end along the rod",
        input.what,
        describe(&input.target)
    ));
    Ok(())
}

/// The springs of `TSDAs` between their points; a damper is left out with a note, anything else refused.
fn write_springs(
    doc: &Doc,
    b: &mut Builder,
    tsdas: &[Tsda],
    upright: &Upright,
    names: &mut BTreeSet<String>,
) -> Result<(), Refusal> {
    for Tsda { path, parts, mirrored } in tsdas {
        let name = text(doc, &format!("{path}/Name"))?;
        shapes(doc, path, &mut b.notes);
        let key = |k: &str| format!("{path}/{k}");
        if doc.has(&key("Spring Coefficient")) || doc.has(&key("Spring Curve Data")) {
            b.on_axle(!mirrored);
            let mut seats = [
                fresh_point(b, doc, &format!("{name} point 1"), &key("Point1"))?,
                fresh_point(b, doc, &format!("{name} point 2"), &key("Point2"))?,
            ];
            let mut bodies = parts.clone().map(|p| upright.name_of(&p));
            // The chassis first, as the general model's checks read a spring.
            if bodies[1] == CHASSIS {
                bodies.swap(0, 1);
                seats.swap(0, 1);
            }
            let name = fresh(names, &name);
            b.spring(doc, path, &name, [&bodies[0], &bodies[1]], [&seats[0], &seats[1]])?;
            b.on_axle(false);
        } else if doc.has(&key("Map Data")) {
            return Err(Refusal::unusable(
                &[],
                format!(
                    "{}: \"Map Data\", a force against length and speed; give the spring as \"Spring Coefficient\" or \
                 \"Spring Curve Data\" and \"Free Length\"",
                    doc.shown(path)
                ),
            ));
        } else if doc.has(&key("Damping Coefficient")) || doc.has(&key("Damping Curve Data")) {
            damper(doc, b, path);
        } else {
            return Err(Refusal::unusable(
                &[],
                format!(
                    "{}: neither a spring (\"Spring Coefficient\", \"Spring Curve Data\") nor a damper (\"Damping \
                 Coefficient\", \"Damping Curve Data\"); Chrono builds nothing from it: give one or remove it",
                    doc.shown(path)
                ),
            ));
        }
    }
    Ok(())
}

/// A damper of `TSDAs` at `path`, left out (statics: no velocity): its keys read, with a note.
fn damper(doc: &Doc, b: &mut Builder, path: &str) {
    for k in [
        "Point1",
        "Point2",
        "Damping Coefficient",
        "Damping Curve Data",
        "Degressivity Compression",
        "Degressivity Expansion",
        "Preload",
        "Free Length",
        "Minimum Length",
        "Maximum Length",
    ] {
        doc.expect(&format!("{path}/{k}"));
    }
    b.notes.push(format!("{}: a damper, left out (statics: no velocity)", doc.shown(path)));
}

/// The rotational springs: torsion bushings on the revolute joints they sit on.
fn write_rsdas(
    doc: &Doc,
    b: &mut Builder,
    rsdas: &[Rsda],
    upright: &Upright,
    names: &mut BTreeSet<String>,
) -> Result<(), Refusal> {
    for r in rsdas {
        if r.mirrored && r.preload != 0.0 {
            b.notes.push(format!(
                "{}: Chrono turns the right side's preload the other way (it mirrors the axis as a direction, not as \
                 a moment's axis); elastokin makes the right side the left's mirror image",
                doc.shown(&r.path)
            ));
        }
        b.on_axle(!r.mirrored);
        let at = fresh_point(b, doc, &r.name, &r.at)?;
        let bodies = r.parts.clone().map(|p| upright.name_of(&p));
        b.torsion_spring(
            &fresh(names, &r.name),
            [&bodies[0], &bodies[1]],
            Place::named(&at),
            r.axis,
            r.rate,
            r.preload,
        );
        b.on_axle(false);
    }
    Ok(())
}

/// The steering axis: the upright's kingpin (a revolute joint on it), or the line through its lowest and
/// highest ball joints (ball or universal joints, or two or more links meeting at a point of it).
fn steering_axis(
    doc: &Doc,
    b: &mut Builder,
    upright: &str,
    upright_joints: &[(&Joint, String)],
    link_ends: &[(Vec3, String)],
) -> Result<(), Refusal> {
    if let Some((j, at)) = upright_joints.iter().find(|(j, _)| j.kind == JointKind::Revolute) {
        let (_, w) = j.frame;
        let up = if w.z < 0.0 { -w } else { w };
        let p = b
            .general
            .hardpoints
            .get(at)
            .ok_or_else(|| Refusal::Unwritten { what: "the joint's hardpoint was added above".into() })?;
        let top = fresh_name(b, &format!("{} axis", j.name));
        b.general.hardpoints.0.push((top.clone(), p + 0.1 * up));
        b.steering_axis(("upright", at), ("upright", &top));
        b.notes.push(format!("steering axis: the axis of {}, the upright's kingpin", doc.shown(&j.path)));
    } else {
        let mut balls: Vec<(Vec3, String)> = upright_joints
            .iter()
            .filter(|(j, _)| matches!(j.kind, JointKind::Spherical | JointKind::Universal))
            .map(|(_, at)| {
                b.general
                    .hardpoints
                    .get(at)
                    .map(|p| (p, at.clone()))
                    .ok_or_else(|| Refusal::Unwritten { what: "added above".into() })
            })
            .collect::<Result<_, _>>()?;
        for (k, (p, end)) in link_ends.iter().enumerate() {
            let meets = link_ends.iter().skip(k + 1).any(|(q, _)| (p - q).norm() < 1e-9);
            if meets && !balls.iter().any(|(q, _)| (p - q).norm() < 1e-9) {
                balls.push((*p, end.clone()));
            }
        }
        balls.sort_by(|a, b| a.0.z.total_cmp(&b.0.z));
        match (balls.first(), balls.last()) {
            (Some(lower), Some(upper)) if balls.len() >= 2 => {
                b.steering_axis(("upright", &lower.1), ("upright", &upper.1));
                b.notes.push(format!(
                    "steering axis: from '{}' to '{}', the upright's lowest and highest ball joints",
                    lower.1, upper.1
                ));
            }
            _ => {
                return Err(Refusal::unusable(
                    &[],
                    format!(
                        "the upright '{upright}' turns neither on a revolute joint (a kingpin) nor on two ball \
                     joints (ball or universal joints, or distance constraints meeting at a point): elastokin \
                     takes the steering axis (caster, kingpin inclination, scrub, trail) from one of those and \
                     does not yet find a virtual axis from links; join the upright to its arms by one of them"
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The paths of the elements of the list `key` (`Bodies/0`, …); an empty or absent list has none.
fn list(doc: &Doc, key: &str) -> Vec<String> {
    let n = doc.at(key).and_then(Value::as_array).map_or(0, Vec::len);
    if n == 0 {
        // A list with elements is read element by element: whatever is left in them is reported.
        doc.expect(key);
    }
    (0..n).map(|i| format!("{key}/{i}")).collect()
}

/// A string at `path`.
fn text(doc: &Doc, path: &str) -> Result<String, Refusal> {
    doc.expect(path);
    doc.at(path).and_then(Value::as_str).map(str::to_string).ok_or_else(|| doc.wrong(path, Expected::Name))
}

/// A flag at `path` (Chrono requires it).
fn flag(doc: &Doc, path: &str) -> Result<bool, Refusal> {
    doc.expect(path);
    doc.at(path).and_then(Value::as_bool).ok_or_else(|| doc.wrong(path, Expected::Flag))
}

/// The file's bodies: where each is (its path and `Position`, by name), their order in the file, and which
/// are shared by both sides (not mirrored).
struct Bodies {
    positions: BTreeMap<String, (String, Vec3)>,
    order: Vec<String>,
    shared: BTreeSet<String>,
}

/// The two parts joined by the element at `path` (its `Body1` and `Body2`, each read by [`part`]).
fn two_parts(doc: &Doc, path: &str, bodies: &Bodies, mirrored: bool) -> Result<[Part; 2], Refusal> {
    Ok([part(doc, &format!("{path}/Body1"), bodies, mirrored)?, part(doc, &format!("{path}/Body2"), bodies, mirrored)?])
}

/// The body an element names at `path`: a name, or `[name, side]` (Chrono's `ReadBodyIdentifierJSON`).
/// A mirrored element (one per side) names a body alone: each side's own, or a shared one. An element that
/// is not mirrored names a shared body alone, or one side's copy of a mirrored body by `[name, side]`
/// (Chrono's `FindBody` finds nothing else for it).
fn part(doc: &Doc, path: &str, bodies: &Bodies, element_mirrored: bool) -> Result<Part, Refusal> {
    doc.expect(path);
    let v = doc.at(path).ok_or_else(|| doc.missing(path))?;
    let (name, side) = match v {
        Value::String(s) => (s.as_str(), None),
        Value::Array(a) if a.len() == 2 && a.iter().all(Value::is_string) => {
            let side = match a[1].as_str() {
                Some("Left") => Some(Side::Left),
                Some("Right") => Some(Side::Right),
                _ => None,
            };
            (a[0].as_str().unwrap_or_default(), side)
        }
        _ => return Err(doc.wrong(path, Expected::Body { got: v.to_string() })),
    };
    let shared = bodies.shared.contains(name);
    match name {
        "Chassis" => Ok(Part::Chassis),
        "Steering" => Ok(Part::Steering),
        "Subchassis" => Err(Refusal::unusable(
            &[],
            format!(
            "{}: the subchassis, a separate Chrono subsystem (a walking beam) that the general model does not have; \
             join the element to the chassis or a body of the suspension",
            doc.shown(path)
        ),
        )),
        _ if !bodies.positions.contains_key(name) => Err(Refusal::unusable(
            &[],
            format!("{}: there is no body '{name}' in \"Bodies\"; name one of them", doc.shown(path)),
        )),
        _ => match (side, element_mirrored, shared) {
            (Some(side), true, _) => Err(Refusal::unusable(
                &[],
                format!(
                "{}: [\"{name}\", \"{side:?}\"] names one side's body, so the element joins both sides' elements to \
                 the {side:?} one: not a corner and its mirror image; name the body alone (\"{name}\") to join each \
                 side's own",
                doc.shown(path)
            ),
            )),
            (Some(_), false, true) => Err(Refusal::unusable(
                &[],
                format!(
                "{}: '{name}' is one body shared by both sides (\"Mirrored\": false): it has no sides; name it alone",
                doc.shown(path)
            ),
            )),
            (Some(side), false, false) => Ok(Part::Sided(name.to_string(), side)),
            (None, false, false) => Err(Refusal::unusable(
                &[],
                format!(
                    "{}: '{name}' is a body of each side, named by an element shared by both sides (\"Mirrored\": \
                 false), which cannot tell which side's; name it [\"{name}\", \"Left\"] or [\"{name}\", \"Right\"]",
                    doc.shown(path)
                ),
            )),
            (None, _, _) => Ok(Part::Body(name.to_string())),
        },
    }
}

/// A rotational spring of `RSDAs`, read as the torsion bushing it is on its revolute joint.
struct Rsda {
    path: String,
    name: String,
    parts: [Part; 2],
    /// Where its bushing goes: the position of the revolute joint it is on (a path of the file).
    at: String,
    /// Its axis (Chrono's `Axis`, the left side's when mirrored).
    axis: Vec3,
    /// `Spring Coefficient`, N·m/rad.
    rate: f64,
    /// The moment on `Body2` about the axis at the design angle: `Preload` + rate × `Free Angle` (N·m).
    preload: f64,
    mirrored: bool,
}

/// The rotational springs. Chrono's `ChLinkRSDA` applies `P − k (θ − θ₀)` about its axis to `Body2` (and the
/// opposite to `Body1`), θ the turn of `Body2` about the axis from the design position. Where the two bodies
/// turn on a revolute joint about that axis, that is a bushing with the rate `k` about the axis, whose other
/// directions the joint holds (their rates, the least the engine takes, meet no deflection). An RSDA without
/// such a joint, or given by a curve, is refused by name; a damper-only RSDA is left out with a note.
fn rsdas(doc: &Doc, bodies: &Bodies, joints: &[Joint]) -> Result<Vec<Rsda>, Refusal> {
    let mut out = Vec::new();
    for path in list(doc, "RSDAs") {
        let name = text(doc, &format!("{path}/Name"))?;
        let mirrored = flag(doc, &format!("{path}/Mirrored"))?;
        let parts = two_parts(doc, &path, bodies, mirrored)?;
        let key = |k: &str| format!("{path}/{k}");
        doc.expect(&key("Position"));
        let axis = super::builder::direction(doc, &key("Axis"))?.normalize();
        for damping in ["Damping Coefficient", "Damping Curve Data"] {
            doc.expect(&key(damping));
        }
        if doc.has(&key("Spring Curve Data")) {
            return Err(Refusal::unusable(
                &[],
                format!(
                    "{}: a torque curve (\"Spring Curve Data\"); elastokin reads a rotational spring by its \
                 \"Spring Coefficient\": give that instead",
                    doc.shown(&path)
                ),
            ));
        }
        if !doc.has(&key("Spring Coefficient")) {
            for k in ["Preload", "Free Angle"] {
                doc.expect(&key(k));
            }
            continue;
        }
        let rate = doc.number(&key("Spring Coefficient"))?;
        let preload = doc.optional_number(&key("Preload"))?.unwrap_or(0.0);
        let free_angle = doc.number(&key("Free Angle"))?;
        let revolute = joints.iter().find(|j| {
            j.kind == JointKind::Revolute
                && !j.bushing
                && j.mirrored == mirrored
                && (j.parts == parts || j.parts == [parts[1].clone(), parts[0].clone()])
                && j.frame.1.cross(&axis).norm() < 1e-6
        });
        let Some(revolute) = revolute else {
            return Err(Refusal::unusable(
                &[],
                format!(
                    "{}: a rotational spring between {} and {} that turn on no revolute joint about its axis; \
                 elastokin reads an RSDA as a torsion bushing on such a joint (the joint holds the other five \
                 directions): join the two bodies by a revolute joint about the RSDA's axis",
                    doc.shown(&path),
                    describe(&parts[0]),
                    describe(&parts[1])
                ),
            ));
        };
        // A moment acts the same wherever it is applied: at the joint's point the bushing's other directions
        // meet no deflection at all.
        let at = format!("{}/Position", revolute.path);
        out.push(Rsda { path, name, parts, at, axis, rate, preload: preload + rate * free_angle, mirrored });
    }
    Ok(out)
}

/// A Chrono quaternion `[e0, e1, e2, e3]` at `path` (normalized, as Chrono does) as a rotation.
fn rotation(doc: &Doc, path: &str) -> Result<UnitQuaternion<f64>, Refusal> {
    doc.expect(path);
    let v = doc.at(path).ok_or_else(|| doc.missing(path))?;
    match v.as_array().map(|a| a.iter().map(Value::as_f64).collect::<Option<Vec<f64>>>()) {
        Some(Some(e)) if e.len() == 4 && e.iter().map(|x| x * x).sum::<f64>() > 1e-20 => {
            Ok(UnitQuaternion::from_quaternion(Quaternion::new(e[0], e[1], e[2], e[3])))
        }
        _ => Err(doc.wrong(path, Expected::Rotation { got: v.to_string() })),
    }
}

fn describe(part: &Part) -> String {
    match part {
        Part::Chassis => "the chassis".into(),
        Part::Steering => "the steering link".into(),
        Part::Body(n) => format!("'{n}'"),
        Part::Sided(n, side) => format!("the {side:?} '{n}'"),
    }
}

/// Marks a body's or element's drawing and contact shapes as read, with a note.
fn shapes(doc: &Doc, path: &str, notes: &mut Vec<String>) {
    doc.left_out(path, &["Visualization", "Contact"], "shapes to draw and collide, left out", notes);
}

/// `name`, or `name 2`, `name 3`, … when taken.
fn fresh(names: &mut BTreeSet<String>, name: &str) -> String {
    let mut out = name.to_string();
    let mut k = 1;
    while !names.insert(out.clone()) {
        k += 1;
        out = format!("{name} {k}");
    }
    out
}

/// A hardpoint name not yet taken (in the corner or on the axle), from `name`.
fn fresh_name(b: &Builder, name: &str) -> String {
    let axle = b.general.axle.iter().flat_map(|a| a.hardpoints.0.iter());
    let mut taken: BTreeSet<String> = b.general.hardpoints.0.iter().chain(axle).map(|(n, _)| n.clone()).collect();
    taken.extend(["tie_rod_inner".to_string(), "tie_rod_outer".to_string()]);
    fresh(&mut taken, name)
}

/// Adds the point at `path` as a hardpoint named from `name`; returns its name.
fn fresh_point(b: &mut Builder, doc: &Doc, name: &str, path: &str) -> Result<String, Refusal> {
    let name = fresh_name(b, name);
    b.hardpoint(doc, &name, path)
}
