//! Chrono's `GenericWheeledSuspension` (`ChGenericWheeledSuspension`): Chrono's own general form, a list of
//! `Bodies`, `Joints`, `Distance Constraints`, `TSDAs` and `RSDAs`, each `Mirrored` (one per side, the
//! right the left's mirror image) or not (one, shared), and the `Spindle` with the body it turns on.
//!
//! Read onto the general model, one left corner:
//! - A mirrored body is a body of the corner, by its Chrono name, its reference point at its `Position`;
//!   the spindle's `Attachment Body` is the corner's `upright` (the spindle turns on it: for statics they
//!   are one body). `Chassis` is the ground.
//! - A joint is the joint of its `Type` in its frame (`Position`, `Rotation`; z is the axis of a
//!   revolute, x the line of a point-line, z the normal of a point-plane, x on `Body1` and y on `Body2` the
//!   axes of a universal) between `Body1` and `Body2`: `Lock` is fixed, `Point Line` in-line and
//!   `Point Plane` in-plane (the point of `Body1` on the line or plane of `Body2`). With `Bushing Data` it is
//!   Chrono's bushing in that frame ([`Builder::joint`]).
//! - A distance constraint is a distance link from `Point1` on `Body1` to `Point2` on `Body2`.
//! - `Steering` is Chrono's steering link (the rack): a distance constraint from it to the upright is the
//!   corner's tie rod, as is a rod body on ideal ball or universal joints from it to the upright. The rig
//!   attaches the tie rod to the rack when steering and to the chassis otherwise.
//! - A TSDA with a spring (`Spring Coefficient` or `Spring Curve Data`) is a spring between its points
//!   ([`Builder::spring`], with its stops); a damper is left out (statics: no velocity), said in the notes.
//! - The steering axis is the upright's revolute axis when it turns on one (a kingpin), else the line
//!   through its lowest and highest ball joints (a ball or universal joint, or two or more distance links
//!   meeting at one point of the upright).
//!
//! Refused by name: a body or element that is not mirrored (one part shared by both sides, such as an axle
//! beam: the general model is one corner and its mirror image), an element joined to one named side of a
//! mirrored body, the subchassis, rotational spring-dampers (`RSDAs`: the general model has no rotational
//! spring), a joint type Chrono does not read.

use super::{Builder, Doc, CHASSIS};
use crate::general::{BodyDef, JointDef, Place, TieRodDef};
use crate::Connection;
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
    /// A body of `Bodies`, by its Chrono name.
    Body(String),
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
}

/// A distance constraint of `Distance Constraints`.
struct Link {
    path: String,
    name: String,
    parts: [Part; 2],
    points: [Vec3; 2],
}

pub(super) fn read(doc: &Doc, b: &mut Builder) -> Result<(), String> {
    let steerable = flag(doc, "Steerable")?;
    let independent = flag(doc, "Independent")?;
    b.wheel(doc)?;
    if doc.has("Output") {
        doc.expect("Output");
        b.notes.push("Output: Chrono's output switch, not part of the suspension".into());
    }

    // Bodies: every one mirrored, or the file is not one corner and its mirror image.
    let bodies = list(doc, "Bodies");
    let mut positions: BTreeMap<String, (String, Vec3)> = BTreeMap::new();
    let mut order = Vec::new();
    let mut shared = Vec::new();
    for path in &bodies {
        let name = text(doc, &format!("{path}/Name"))?;
        if !flag(doc, &format!("{path}/Mirrored"))? {
            shared.push(format!("'{name}'"));
        }
        let at = doc.point(&format!("{path}/Position"))?;
        order.push(name.clone());
        if positions.insert(name.clone(), (path.clone(), at)).is_some() {
            return Err(format!(
                "{}: a second body named '{name}' (Chrono keeps the first): give each body its own name",
                doc.shown(path)
            ));
        }
    }
    if !shared.is_empty() {
        let (them, are) = if shared.len() == 1 { ("it", "is") } else { ("each", "are") };
        return Err(format!(
            "GenericWheeledSuspension: the bodies {} {are} not mirrored (\"Mirrored\": false): {them} is one body \
             shared by both sides, on the centre line (an axle beam, a tie rod or drag link across the car). \
             elastokin's general model is one left corner and its mirror image, and cannot express a body shared \
             by both sides yet. Give a body \"Mirrored\": true if it is in fact one per side; a beam axle needs a \
             whole-axle model, which elastokin does not have",
            shared.join(", ")
        ));
    }

    // The upright: the body the spindle turns on.
    let upright = match part(doc, "Spindle/Attachment Body", &positions)? {
        Part::Body(name) => name,
        Part::Chassis => {
            return Err("\"Spindle\" / \"Attachment Body\" is the chassis: the wheel has no suspension motion to \
                        analyse; name the body the spindle turns on"
                .into())
        }
        Part::Steering => {
            return Err("\"Spindle\" / \"Attachment Body\" is the steering link: name the body the spindle turns on \
                        (the upright)"
                .into())
        }
    };
    let general_name = |n: &str| if n == upright { "upright".to_string() } else { n.to_string() };
    for name in positions.keys() {
        if name != &upright && (name.eq_ignore_ascii_case(CHASSIS) || name == "upright") {
            return Err(format!(
                "body '{name}': the general model names the ground 'chassis' and the spindle's body 'upright'; \
                 rename this body"
            ));
        }
    }

    // Joints and distance constraints, each mirrored.
    let mut joints = Vec::new();
    for path in list(doc, "Joints") {
        let name = text(doc, &format!("{path}/Name"))?;
        mirrored(doc, &path)?;
        let chrono_type = text(doc, &format!("{path}/Type"))?;
        let kind = match chrono_type.as_str() {
            "Spherical" => JointKind::Spherical,
            "Revolute" => JointKind::Revolute,
            "Universal" => JointKind::Universal,
            "Lock" => JointKind::Fixed,
            "Point Line" => JointKind::InLine,
            "Point Plane" => JointKind::InPlane,
            other => {
                return Err(format!(
                    "{}: \"Type\" '{other}' is not one Chrono reads (it would take it as \"Lock\"); give \
                     \"Spherical\", \"Revolute\", \"Universal\", \"Lock\", \"Point Line\" or \"Point Plane\"",
                    doc.shown(&path)
                ));
            }
        };
        let parts =
            [part(doc, &format!("{path}/Body1"), &positions)?, part(doc, &format!("{path}/Body2"), &positions)?];
        let frame = rotation(doc, &format!("{path}/Rotation"))?;
        doc.expect(&format!("{path}/Position"));
        let bushing = doc.at(&format!("{path}/Bushing Data")).is_some_and(Value::is_object);
        if bushing && matches!(kind, JointKind::InLine | JointKind::InPlane) {
            return Err(format!(
                "{}: Chrono builds no joint at all for a \"{chrono_type}\" with \"Bushing Data\"; remove the \
                 \"Bushing Data\" for the joint, or the joint",
                doc.shown(&path)
            ));
        }
        joints.push(Joint { path, name, kind, parts, frame: (frame * Vec3::x(), frame * Vec3::z()), bushing });
    }
    let mut links = Vec::new();
    for path in list(doc, "Distance Constraints") {
        let name = text(doc, &format!("{path}/Name"))?;
        mirrored(doc, &path)?;
        let parts =
            [part(doc, &format!("{path}/Body1"), &positions)?, part(doc, &format!("{path}/Body2"), &positions)?];
        let points = [doc.point(&format!("{path}/Point1"))?, doc.point(&format!("{path}/Point2"))?];
        links.push(Link { path, name, parts, points });
    }
    let tsdas = list(doc, "TSDAs");
    let mut tsda_parts = Vec::new();
    for path in &tsdas {
        mirrored(doc, path)?;
        let parts =
            [part(doc, &format!("{path}/Body1"), &positions)?, part(doc, &format!("{path}/Body2"), &positions)?];
        if parts.contains(&Part::Steering) {
            return Err(format!(
                "{}: a spring or damper on the steering link; the general model reaches the rack only through the \
                 tie rod: attach it to the chassis or a body of the corner",
                doc.shown(path)
            ));
        }
        tsda_parts.push(parts);
    }
    if let Some(path) = list(doc, "RSDAs").first() {
        return Err(format!(
            "{}: a rotational spring-damper; the general model has no rotational spring yet (a bushing would add \
             stiffness in the five other directions). Remove the RSDAs to read the rest without their stiffness",
            doc.shown(path)
        ));
    }

    // The tie rod: a distance constraint from the steering link to the upright, or a rod body on ideal ball
    // or universal joints from one to the other.
    let mut tie_rod: Option<(Vec3, Vec3, String)> = None;
    let mut rods = BTreeSet::new();
    let mut steering_joints = BTreeSet::new();
    let mut set_tie_rod = |inner: Vec3, outer: Vec3, what: String| match &tie_rod {
        Some((_, _, first)) => Err(format!(
            "{what}: a second tie rod (the first is {first}); the general model steers the upright by one tie rod"
        )),
        None => {
            tie_rod = Some((inner, outer, what));
            Ok(())
        }
    };
    for link in links.iter().filter(|l| l.parts.contains(&Part::Steering)) {
        let k = usize::from(link.parts[0] != Part::Steering);
        if link.parts[1 - k] != Part::Body(upright.clone()) {
            return Err(format!(
                "{}: a link from the steering link to {}, not to the upright '{upright}'; the general model's tie rod \
                 runs from the rack to the upright",
                doc.shown(&link.path),
                describe(&link.parts[1 - k])
            ));
        }
        set_tie_rod(link.points[k], link.points[1 - k], doc.shown(&link.path))?;
    }
    for (i, j) in joints.iter().enumerate().filter(|(_, j)| j.parts.contains(&Part::Steering)) {
        let k = usize::from(j.parts[0] != Part::Steering);
        let refuse = |why: &str| {
            format!(
                "{}: a joint to the steering link ({why}); the general model reaches the rack only through the tie \
                 rod: a distance constraint from \"Steering\" to the upright, or a rod body on ball or universal \
                 joints (without \"Bushing Data\") from one to the other",
                doc.shown(&j.path)
            )
        };
        let Part::Body(rod) = &j.parts[1 - k] else {
            return Err(refuse(&format!("to {}", describe(&j.parts[1 - k]))));
        };
        if rod == &upright {
            return Err(refuse("to the upright itself"));
        }
        if j.bushing {
            return Err(refuse("with \"Bushing Data\""));
        }
        if !matches!(j.kind, JointKind::Spherical | JointKind::Universal) {
            return Err(refuse(&format!("a {:?} joint, where a rod has a ball or universal joint", j.kind)));
        }
        let on_rod = |parts: &[Part; 2]| parts.contains(&Part::Body(rod.clone()));
        let others: Vec<usize> = (0..joints.len()).filter(|&m| m != i && on_rod(&joints[m].parts)).collect();
        let outer = match others.as_slice() {
            [m] if joints[*m].parts.contains(&Part::Body(upright.clone()))
                && !joints[*m].bushing
                && matches!(joints[*m].kind, JointKind::Spherical | JointKind::Universal)
                && !links.iter().any(|l| on_rod(&l.parts))
                && !tsda_parts.iter().any(on_rod) =>
            {
                *m
            }
            _ => return Err(refuse(&format!("'{rod}' is not a rod to the upright alone"))),
        };
        let at = |m: usize| doc.point(&format!("{}/Position", joints[m].path));
        set_tie_rod(
            at(i)?,
            at(outer)?,
            format!("the rod '{rod}' ({} and {})", doc.shown(&j.path), doc.shown(&joints[outer].path)),
        )?;
        rods.insert(rod.clone());
        steering_joints.extend([i, outer]);
    }
    if !steerable && tie_rod.is_some() {
        return Err("\"Steerable\" is false, yet an element joins \"Steering\": Chrono gives an unsteered suspension \
                    no steering link; join the toe link to the chassis, or make the suspension steerable"
            .into());
    }

    // Bodies.
    for name in &order {
        let (path, at) = &positions[name];
        doc.dynamics(path, &["Mass", "Rotation", "Moments of Inertia", "Products of Inertia"], &mut b.notes);
        shapes(doc, path, &mut b.notes);
        if rods.contains(name) {
            continue;
        }
        if name == &upright {
            b.notes.push(format!(
                "{}: the spindle's attachment body, the corner's upright (the spindle turns on it: for statics one \
                 body), its reference point the wheel centre",
                doc.shown(path)
            ));
        } else {
            b.general.bodies.push(BodyDef { name: name.clone(), at: Place::At(*at) });
        }
    }
    // Joints (by their hardpoints, named after them).
    let mut names = BTreeSet::new();
    let mut upright_joints = Vec::new();
    for (i, j) in joints.iter().enumerate() {
        if steering_joints.contains(&i) {
            continue;
        }
        let at = fresh_point(b, doc, &j.name, &format!("{}/Position", j.path))?;
        let bodies = j.parts.clone().map(|p| body_name(&p, &general_name));
        let name = fresh(&mut names, &j.name);
        let bushing = j.bushing.then(|| format!("{}/Bushing Data", j.path));
        b.joint(doc, &name, j.kind, [&bodies[0], &bodies[1]], Place::named(&at), Some(j.frame), bushing.as_deref())?;
        if j.parts.contains(&Part::Body(upright.clone())) {
            upright_joints.push((j, at));
        }
    }
    let mut link_ends: Vec<(Vec3, String)> = Vec::new();
    for link in &links {
        if link.parts.contains(&Part::Steering) {
            continue;
        }
        let from = fresh_point(b, doc, &format!("{} point 1", link.name), &format!("{}/Point1", link.path))?;
        let to = fresh_point(b, doc, &format!("{} point 2", link.name), &format!("{}/Point2", link.path))?;
        let bodies = link.parts.clone().map(|p| body_name(&p, &general_name));
        b.general.joints.push(JointDef {
            name: fresh(&mut names, &link.name),
            kind: JointKind::Distance,
            bodies,
            at: Some(Place::named(&from)),
            to: Some(Place::named(&to)),
            axis: None,
            axis_j: None,
        });
        for (k, end) in [from, to].into_iter().enumerate() {
            if link.parts[k] == Part::Body(upright.clone()) {
                link_ends.push((link.points[k], end));
            }
        }
    }
    // The tie rod.
    match tie_rod {
        Some((inner, outer, what)) => {
            b.general.hardpoints.0.push(("tie_rod_inner".into(), inner));
            b.general.hardpoints.0.push(("tie_rod_outer".into(), outer));
            b.general.corner.tie_rod = Some(TieRodDef {
                inner: Place::named("tie_rod_inner"),
                outer: Place::named("tie_rod_outer"),
                connection: Connection::Ideal.into(),
            });
            b.notes
                .push(format!("{what}: the corner's tie rod, from the rack (steering) or the chassis to the upright"));
        }
        None if steerable => b.notes.push(
            "\"Steerable\" is true but nothing joins \"Steering\" to the upright: no tie rod, the steering analysis \
             does not apply"
                .into(),
        ),
        None => {}
    }
    // Springs and dampers.
    for (path, parts) in tsdas.iter().zip(tsda_parts) {
        let name = text(doc, &format!("{path}/Name"))?;
        shapes(doc, path, &mut b.notes);
        let key = |k: &str| format!("{path}/{k}");
        if doc.has(&key("Spring Coefficient")) || doc.has(&key("Spring Curve Data")) {
            let mut seats = [
                fresh_point(b, doc, &format!("{name} point 1"), &key("Point1"))?,
                fresh_point(b, doc, &format!("{name} point 2"), &key("Point2"))?,
            ];
            let mut bodies = parts.map(|p| body_name(&p, &general_name));
            // The chassis first, as the general model's checks read a spring.
            if bodies[1] == CHASSIS {
                bodies.swap(0, 1);
                seats.swap(0, 1);
            }
            let name = fresh(&mut names, &name);
            b.spring(doc, path, &name, [&bodies[0], &bodies[1]], [&seats[0], &seats[1]])?;
        } else if doc.has(&key("Map Data")) {
            return Err(format!(
                "{}: \"Map Data\", a force against length and speed; give the spring as \"Spring Coefficient\" or \
                 \"Spring Curve Data\" and \"Free Length\"",
                doc.shown(path)
            ));
        } else if doc.has(&key("Damping Coefficient")) || doc.has(&key("Damping Curve Data")) {
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
                doc.expect(&key(k));
            }
            b.notes.push(format!("{}: a damper, left out (statics: no velocity)", doc.shown(path)));
        } else {
            return Err(format!(
                "{}: neither a spring (\"Spring Coefficient\", \"Spring Curve Data\") nor a damper (\"Damping \
                 Coefficient\", \"Damping Curve Data\"); Chrono builds nothing from it: give one or remove it",
                doc.shown(path)
            ));
        }
    }
    // The steering axis: the upright's kingpin, or its lowest and highest ball joints.
    if let Some((j, at)) = upright_joints.iter().find(|(j, _)| j.kind == JointKind::Revolute) {
        let (_, w) = j.frame;
        let up = if w.z < 0.0 { -w } else { w };
        let p = b.general.hardpoints.get(at).ok_or("the joint's hardpoint was added above")?;
        let top = fresh_name(b, &format!("{} axis", j.name));
        b.general.hardpoints.0.push((top.clone(), p + 0.1 * up));
        b.steering_axis(("upright", at), ("upright", &top));
        b.notes.push(format!("steering axis: the axis of {}, the upright's kingpin", doc.shown(&j.path)));
    } else {
        let mut balls: Vec<(Vec3, String)> = upright_joints
            .iter()
            .filter(|(j, _)| matches!(j.kind, JointKind::Spherical | JointKind::Universal))
            .map(|(_, at)| b.general.hardpoints.get(at).map(|p| (p, at.clone())).ok_or("added above"))
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
                return Err(format!(
                    "the upright '{upright}' turns neither on a revolute joint (a kingpin) nor on two ball \
                     joints (ball or universal joints, or distance constraints meeting at a point): elastokin \
                     takes the steering axis (caster, kingpin inclination, scrub, trail) from one of those and \
                     does not yet find a virtual axis from links; join the upright to its arms by one of them"
                ));
            }
        }
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
fn text(doc: &Doc, path: &str) -> Result<String, String> {
    doc.expect(path);
    doc.at(path)
        .and_then(Value::as_str)
        .map(str::to_string)
        .ok_or_else(|| format!("{} must be a name (a string)", doc.quoted(path)))
}

/// A flag at `path` (Chrono requires it).
fn flag(doc: &Doc, path: &str) -> Result<bool, String> {
    doc.expect(path);
    doc.at(path).and_then(Value::as_bool).ok_or_else(|| format!("{} must be true or false", doc.quoted(path)))
}

/// Refuses the element at `path` unless it is mirrored.
fn mirrored(doc: &Doc, path: &str) -> Result<(), String> {
    if flag(doc, &format!("{path}/Mirrored"))? {
        return Ok(());
    }
    Err(format!(
        "{}: not mirrored (\"Mirrored\": false): one element, not one per side, so not part of a corner and its \
         mirror image, which is what elastokin's general model describes; give it \"Mirrored\": true if each side \
         has one",
        doc.shown(path)
    ))
}

/// The body an element names at `path`: a name, or `[name, side]` (Chrono's `ReadBodyIdentifierJSON`).
fn part(doc: &Doc, path: &str, bodies: &BTreeMap<String, (String, Vec3)>) -> Result<Part, String> {
    doc.expect(path);
    let v = doc.at(path).ok_or_else(|| format!("{} is missing", doc.quoted(path)))?;
    let (name, side) = match v {
        Value::String(s) => (s.as_str(), None),
        Value::Array(a) if a.len() == 2 && a.iter().all(Value::is_string) => {
            let side = a[1].as_str().filter(|s| *s == "Left" || *s == "Right");
            (a[0].as_str().unwrap_or_default(), side)
        }
        _ => {
            return Err(format!("{} must be a body's name or [name, \"Left\" | \"Right\"], got {v}", doc.quoted(path)))
        }
    };
    match name {
        "Chassis" => Ok(Part::Chassis),
        "Steering" => Ok(Part::Steering),
        "Subchassis" => Err(format!(
            "{}: the subchassis, a separate Chrono subsystem (a walking beam) that the general model does not have; \
             join the element to the chassis or a body of the corner",
            doc.shown(path)
        )),
        _ if !bodies.contains_key(name) => {
            Err(format!("{}: there is no body '{name}' in \"Bodies\"; name one of them", doc.shown(path)))
        }
        _ => match side {
            Some(side) => Err(format!(
                "{}: [\"{name}\", \"{side}\"] names one side's body, so the element joins both sides' elements to \
                 the {side} one: not a corner and its mirror image; name the body alone (\"{name}\") to join each \
                 side's own",
                doc.shown(path)
            )),
            None => Ok(Part::Body(name.to_string())),
        },
    }
}

/// A Chrono quaternion `[e0, e1, e2, e3]` at `path` (normalized, as Chrono does) as a rotation.
fn rotation(doc: &Doc, path: &str) -> Result<UnitQuaternion<f64>, String> {
    doc.expect(path);
    let v = doc.at(path).ok_or_else(|| format!("{} is missing", doc.quoted(path)))?;
    match v.as_array().map(|a| a.iter().map(Value::as_f64).collect::<Option<Vec<f64>>>()) {
        Some(Some(e)) if e.len() == 4 && e.iter().map(|x| x * x).sum::<f64>() > 1e-20 => {
            Ok(UnitQuaternion::from_quaternion(Quaternion::new(e[0], e[1], e[2], e[3])))
        }
        _ => Err(format!("{} must be a rotation, a quaternion [e0, e1, e2, e3] not zero; got {v}", doc.quoted(path))),
    }
}

/// The general model's name of `part`.
fn body_name(part: &Part, general_name: &impl Fn(&str) -> String) -> String {
    match part {
        Part::Body(n) => general_name(n),
        // The steering link has been taken as the tie rod's rack before any element is written.
        Part::Chassis | Part::Steering => CHASSIS.to_string(),
    }
}

fn describe(part: &Part) -> String {
    match part {
        Part::Chassis => "the chassis".into(),
        Part::Steering => "the steering link".into(),
        Part::Body(n) => format!("'{n}'"),
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

/// A hardpoint name not yet taken, from `name`.
fn fresh_name(b: &Builder, name: &str) -> String {
    let mut taken: BTreeSet<String> = b.general.hardpoints.0.iter().map(|(n, _)| n.clone()).collect();
    taken.extend(["tie_rod_inner".to_string(), "tie_rod_outer".to_string()]);
    fresh(&mut taken, name)
}

/// Adds the point at `path` as a hardpoint named from `name`; returns its name.
fn fresh_point(b: &mut Builder, doc: &Doc, name: &str, path: &str) -> Result<String, String> {
    let name = fresh_name(b, name);
    b.hardpoint(doc, &name, path)
}
