//! Project Chrono's vehicle suspension files, read into the general model.
//!
//! Project Chrono (BSD-3-Clause, `projectchrono/chrono`) describes each suspension subsystem of its wheeled
//! vehicles in a JSON file under `data/vehicle/*/suspension/`: a `"Template"` (the subsystem's class) and
//! its hardpoints, bodies, joints and spring-damper elements, for the left side. [`import`] reads one into
//! a [`SuspensionFile`] in the general form, so every analysis runs on it, and lists what it read and what
//! it left out ([`Imported::notes`]).
//!
//! # Conventions
//! - Chrono's suspension frame is the vehicle's: x forward, y left, z up (ISO 8855), metres; the points are
//!   the left side's and Chrono mirrors them for the right (y → −y), as the general model does.
//! - The spindle's `COM` is the wheel centre; the spindle turns on the upright, so for statics the two are
//!   one body, the upright.
//! - `Camber Angle (deg)` γ and `Toe Angle (deg)` τ turn the left spindle by `Rz(−τ) Rx(−γ)`: its
//!   outward spin axis is `(cos γ sin τ, cos γ cos τ, −sin γ)`, whose camber (top out +) is γ and toe (in +)
//!   is τ.
//! - A spring or shock (`ChLinkTSDA`) pushes its two points apart with `P − k (L − L₀)` or
//!   `P − f(L − L₀)` for a `Spring Curve Data` table `f` of extension against force: a coil spring of
//!   rate `k` (or the curve of push against compression `c = L₀ − L`, points `(−x, −f)`), free length `L₀`
//!   and preload `P`. Chrono interpolates the table linearly; elastokin passes a monotone cubic through the
//!   same points (the same at the points, smoother between). `Minimum Length` and `Maximum Length` add a
//!   bump and a rebound stop touching at those lengths, with Chrono's built-in curve (from an ADAMS/Car
//!   example: 200 N at 2 mm to 125 kN at 60 mm, and 125 kN beyond, as Chrono's table holds it). A
//!   `Minimum Length` not below the `Maximum Length` (both stops in contact at every length) is refused.
//! - A joint with `Bushing Data` is, in Chrono, a six-way bushing in the joint's frame (z along its axis):
//!   `Stiffness Linear` along the three axes, `Stiffness Rotational` about the axes the joint holds and the
//!   `DOF` rates about the ones it leaves free, the moment `M = Kθ` (`ChLoadBodyBodyBushingGeneric`). It
//!   is read as that bushing: the same frame, the six rates, [`RotationLaw::Linear`]. A zero rate (Chrono
//!   files give 0 for the free directions) is taken as the least rate the engine accepts
//!   ([`ROTATIONAL_RATE_RANGE`]`.0`, 10⁻³ N·m/rad), said in the notes.
//! - Masses, inertias, radii and widths are read and left out (statics); shocks and dampers too (no
//!   velocity); each is listed in the notes. A key the importer does not know is a note too: nothing is
//!   dropped unsaid.
//! - Chrono's suspension files give no tyre: the loaded radius is [`default_loaded_radius`]
//!   unless the caller gives one.
//! - An axle whose wheels share a body (a solid axle, a De Dion tube, a beam on leaf springs) is read whole:
//!   what Chrono builds once (the tube, a tie rod or toe bar across, a Panhard rod, a drag link) goes in the
//!   model's `axle` ([`crate::description::general::AxleDef`]), written as Chrono places it, and each side's parts in the
//!   corner, mirrored. A link Chrono builds as a body on a ball joint and a universal joint (which only
//!   stops the link spinning) is the distance constraint between its ends; a drag link is the steering
//!   input, moved along its own line. Where Chrono's ideal joints lock the axle's roll, the roll analysis is
//!   skipped with that reason.

mod de_dion_axle;
mod double_wishbone;
mod generic_wheeled;
mod hendrickson_primaxx;
mod leaf_spring_axle;
mod macpherson;
mod multi_link;
mod push_pipe_axle;
mod rigid_panhard_axle;
mod rigid_pinned_axle;
mod sae_leaf_spring_axle;
mod semi_trailing_arm;
mod single_wishbone;
mod solid_axle;
mod three_link_irs;

use crate::description::general::{
    Axis, AxleDef, BodyDef, BodyPoint, BushingDef, GeneralCorner, Hardpoints, JointDef, Place, SpringDef, StopDef,
    StopType, TieRodDef, CHASSIS,
};
use crate::description::limits::{
    default_loaded_radius, MAX_COORDINATE, ROTATIONAL_RATE_RANGE, TRANSLATIONAL_RATE_RANGE,
};
use crate::description::{Connection, Side, Template};
use crate::file::key_path::locate;
use crate::file::{without_byte_order_mark, FileError, SuspensionFile};
use elastokin_core::{JointKind, Vec3};
use elastokin_elements::RotationLaw;
use serde_json::Value;
use std::cell::RefCell;
use std::collections::BTreeSet;

/// A Chrono suspension read into the general form.
#[derive(Debug, Clone)]
pub struct Imported {
    /// The model file.
    pub file: SuspensionFile,
    /// Chrono's template name (`DoubleWishbone`, …).
    pub template: String,
    /// What was read and left out, and how values were taken, one line each.
    pub notes: Vec<String>,
}

/// The Chrono templates [`import`] reads.
pub const SUPPORTED: [&str; 22] = [
    "DoubleWishbone",
    "DoubleWishboneReduced",
    "MacPhersonStrut",
    "MultiLink",
    "SemiTrailingArm",
    "SingleWishbone",
    "ThreeLinkIRS",
    "GenericWheeledSuspension",
    "SolidAxle",
    "SolidThreeLinkAxle",
    "SolidBellcrankThreeLinkAxle",
    "RigidPanhardAxle",
    "ToeBarRigidPanhardAxle",
    "HendricksonPRIMAXX",
    "PushPipeAxle",
    "ToeBarPushPipeAxle",
    "DeDionAxle",
    "ToeBarDeDionAxle",
    "SAELeafspringAxle",
    "SAEToeBarLeafspringAxle",
    "LeafspringAxle",
    "ToeBarLeafspringAxle",
];

/// Whether `text` is a Chrono suspension file: a JSON object (with `//` comments allowed) whose `"Type"` is
/// `"Suspension"` and which names a `"Template"`.
pub fn is_chrono(text: &str) -> bool {
    serde_json::from_str::<Value>(&without_comments(text)).is_ok_and(|v| is_chrono_document(&v))
}

/// [`is_chrono`] of a document already parsed.
pub fn is_chrono_document(document: &Value) -> bool {
    document.get("Type").and_then(Value::as_str) == Some("Suspension") && document.get("Template").is_some()
}

/// Reads a Chrono suspension file into the general form, its values checked as a model file's are but not
/// yet built (`document::import_chrono` reads and builds); `origin` names it in errors, `loaded_radius` (m)
/// is the tyre's (Chrono's suspension files have none).
pub fn read(text: &str, origin: &str, loaded_radius: Option<f64>) -> Result<Imported, FileError> {
    let clean = without_comments(without_byte_order_mark(text));
    // An error names its keys in quotes ("Spring" / "Free Length" is missing); it is located at them, or at
    // the template's name.
    let invalid = |message: String| {
        let keys: Vec<&str> = message.split(':').next().unwrap_or("").split('"').skip(1).step_by(2).collect();
        let keys = if keys.is_empty() { vec!["Template"] } else { keys };
        let (line, column) = locate(&clean, &keys);
        FileError::Invalid { origin: origin.to_string(), line, column, message }
    };
    let value: Value = serde_json::from_str(&clean).map_err(|e| FileError::Invalid {
        origin: origin.to_string(),
        line: e.line(),
        column: e.column(),
        message: e.to_string().split(" at line ").next().unwrap_or_default().to_string(),
    })?;
    let doc = Doc::new(&value);
    let template = doc.str("Template").map_err(invalid)?;
    let name = doc.optional_str("Name").unwrap_or_else(|| template.clone());
    doc.expect("Type");
    let mut b = Builder::new(&doc, loaded_radius);
    let built = match template.as_str() {
        "DoubleWishbone" => double_wishbone::read(&doc, &mut b, false),
        "DoubleWishboneReduced" => double_wishbone::read(&doc, &mut b, true),
        "MacPhersonStrut" => macpherson::read(&doc, &mut b),
        "MultiLink" => multi_link::read(&doc, &mut b),
        "SemiTrailingArm" => semi_trailing_arm::read(&doc, &mut b),
        "SingleWishbone" => single_wishbone::read(&doc, &mut b),
        "ThreeLinkIRS" => three_link_irs::read(&doc, &mut b),
        "GenericWheeledSuspension" => generic_wheeled::read(&doc, &mut b),
        "SolidAxle" => solid_axle::read_solid_axle(&doc, &mut b),
        "SolidThreeLinkAxle" => solid_axle::read_three_link(&doc, &mut b),
        "SolidBellcrankThreeLinkAxle" => solid_axle::read_bellcrank_three_link(&doc, &mut b),
        "RigidPanhardAxle" => rigid_panhard_axle::read_rigid(&doc, &mut b),
        "ToeBarRigidPanhardAxle" => rigid_panhard_axle::read_toe_bar(&doc, &mut b),
        "HendricksonPRIMAXX" => hendrickson_primaxx::read(&doc, &mut b),
        "PushPipeAxle" => push_pipe_axle::read_push_pipe(&doc, &mut b),
        "ToeBarPushPipeAxle" => push_pipe_axle::read_toe_bar(&doc, &mut b),
        "RigidPinnedAxle" => rigid_pinned_axle::read(&doc),
        "DeDionAxle" => de_dion_axle::read_de_dion(&doc, &mut b),
        "ToeBarDeDionAxle" => de_dion_axle::read_toe_bar(&doc, &mut b),
        "SAELeafspringAxle" => sae_leaf_spring_axle::read_sae(&doc, &mut b),
        "SAEToeBarLeafspringAxle" => sae_leaf_spring_axle::read_toe_bar(&doc, &mut b),
        "LeafspringAxle" => leaf_spring_axle::read_leaf_spring_axle(&doc, &mut b),
        "ToeBarLeafspringAxle" => leaf_spring_axle::read_toe_bar_leaf_spring_axle(&doc, &mut b),
        other => Err(refused(other)),
    };
    built.map_err(invalid)?;
    let notes = b.finish(&doc);
    let file = SuspensionFile {
        name: format!("{name} (Project Chrono {template})"),
        suspension: Template::General(Box::new(b.general)),
        vehicle: None,
    };
    // The general model's own checks, as a model file's: the builder's follow in `document::import_chrono`.
    let text = file.to_json();
    let file = SuspensionFile::parse_checked(&text, origin, true)?;
    Ok(Imported { file, template, notes })
}

/// Why a Chrono template is not read.
fn refused(template: &str) -> String {
    let why = match template {
        "RigidSuspension" => "it has no suspension motion to analyse",
        _ => "not a template this importer reads",
    };
    format!("Project Chrono template '{template}': {why}; it reads {}", SUPPORTED.join(", "))
}

/// `text` without `//` and `/* */` comments outside strings (Chrono's files carry them; JSON does not).
pub fn without_comments(text: &str) -> String {
    let (mut out, mut chars) = (String::with_capacity(text.len()), text.chars().peekable());
    let mut in_string = false;
    while let Some(c) = chars.next() {
        if in_string {
            out.push(c);
            match c {
                '\\' => out.extend(chars.next()),
                '"' => in_string = false,
                _ => {}
            }
            continue;
        }
        match (c, chars.peek()) {
            ('"', _) => {
                in_string = true;
                out.push(c);
            }
            ('/', Some('/')) => {
                // Keep the line break, so that line numbers in errors stay right.
                for d in chars.by_ref() {
                    if d == '\n' {
                        out.push('\n');
                        break;
                    }
                }
            }
            ('/', Some('*')) => {
                chars.next();
                let mut last = ' ';
                for d in chars.by_ref() {
                    if d == '\n' {
                        out.push('\n');
                    }
                    if last == '*' && d == '/' {
                        break;
                    }
                    last = d;
                }
            }
            _ => out.push(c),
        }
    }
    out
}

/// A Chrono document, with the keys read so far (every other key is reported).
pub(crate) struct Doc<'a> {
    root: &'a Value,
    read: RefCell<BTreeSet<String>>,
}

/// What a key is for, when it is read only to be left out.
const FOR_DYNAMICS: &str = "mass, inertia and sizes: read and left out (statics)";

impl<'a> Doc<'a> {
    fn new(root: &'a Value) -> Self {
        Doc { root, read: RefCell::new(BTreeSet::new()) }
    }

    /// The value at `path`: keys joined by `/`, an index into an array as its number (`Bodies/0/Name`).
    fn at(&self, path: &str) -> Option<&'a Value> {
        path.split('/').try_fold(self.root, |v, key| match v {
            Value::Array(items) => key.parse::<usize>().ok().and_then(|i| items.get(i)),
            _ => v.get(key),
        })
    }

    /// `path` split for messages: each key, and after it the element of an array it indexes, by its `Name`
    /// when it has one (`[RevoluteUCA]`), else by its index (`[0]`).
    fn segments(&self, path: &str) -> Vec<(String, String)> {
        let mut out: Vec<(String, String)> = Vec::new();
        let mut at = Some(self.root);
        for key in path.split('/') {
            match (at, out.last_mut()) {
                (Some(Value::Array(items)), Some(last)) => {
                    let item = key.parse::<usize>().ok().and_then(|i| items.get(i));
                    let name = item.and_then(|v| v.get("Name")).and_then(Value::as_str).unwrap_or(key);
                    last.1.push_str(&format!("[{name}]"));
                    at = item;
                }
                _ => {
                    out.push((key.to_string(), String::new()));
                    at = at.and_then(|v| v.get(key));
                }
            }
        }
        out
    }

    /// `path` as the notes show it: `Joints[RevoluteUCA] / Bushing Data`.
    pub(crate) fn shown(&self, path: &str) -> String {
        self.segments(path).iter().map(|(k, element)| format!("{k}{element}")).collect::<Vec<_>>().join(" / ")
    }

    /// `path` as the errors show it, keys quoted: `"Joints"[RevoluteUCA] / "Position"`.
    fn quoted(&self, path: &str) -> String {
        self.segments(path).iter().map(|(k, element)| format!("\"{k}\"{element}")).collect::<Vec<_>>().join(" / ")
    }

    /// Marks `path` (keys joined by `/`) as read.
    pub(crate) fn expect(&self, path: &str) {
        self.read.borrow_mut().insert(path.to_string());
    }

    pub(crate) fn has(&self, path: &str) -> bool {
        self.at(path).is_some()
    }

    fn str(&self, path: &str) -> Result<String, String> {
        self.expect(path);
        self.at(path)
            .and_then(Value::as_str)
            .map(str::to_string)
            .ok_or_else(|| format!("\"{path}\" is missing: a Chrono suspension file names its template"))
    }

    fn optional_str(&self, path: &str) -> Option<String> {
        self.expect(path);
        self.at(path).and_then(Value::as_str).map(str::to_string)
    }

    /// A number at `path`.
    pub(crate) fn number(&self, path: &str) -> Result<f64, String> {
        self.expect(path);
        match self.at(path) {
            Some(v) => v.as_f64().ok_or_else(|| format!("{} must be a number, got {v}", self.quoted(path))),
            None => Err(format!("{} is missing", self.quoted(path))),
        }
    }

    /// A number at `path`, when given.
    pub(crate) fn optional_number(&self, path: &str) -> Result<Option<f64>, String> {
        if self.has(path) {
            self.number(path).map(Some)
        } else {
            Ok(None)
        }
    }

    /// A point `[x, y, z]` at `path`.
    pub(crate) fn point(&self, path: &str) -> Result<Vec3, String> {
        self.expect(path);
        let v = self.at(path).ok_or_else(|| format!("{} is missing", self.quoted(path)))?;
        match v.as_array().map(|a| a.iter().map(Value::as_f64).collect::<Option<Vec<f64>>>()) {
            Some(Some(c)) if c.len() == 3 => Ok(Vec3::new(c[0], c[1], c[2])),
            _ => Err(format!("{} must be a point [x, y, z] in metres, got {v}", self.quoted(path))),
        }
    }

    /// A table `[[x, y], …]` at `path`.
    pub(crate) fn table(&self, path: &str) -> Result<Vec<[f64; 2]>, String> {
        self.expect(path);
        let v = self.at(path).ok_or_else(|| format!("{} is missing", self.quoted(path)))?;
        let rows = v.as_array().ok_or_else(|| format!("{} must be a table [[x, y], …]", self.quoted(path)))?;
        rows.iter()
            .map(|r| match r.as_array().map(|a| a.iter().map(Value::as_f64).collect::<Option<Vec<f64>>>()) {
                Some(Some(p)) if p.len() == 2 => Ok([p[0], p[1]]),
                _ => Err(format!("{}: every row is [x, y], got {r}", self.quoted(path))),
            })
            .collect()
    }

    /// Marks the keys under `object` that carry only dynamics as read, with their reason.
    pub(crate) fn dynamics(&self, object: &str, keys: &[&str], notes: &mut Vec<String>) {
        self.left_out(object, keys, FOR_DYNAMICS, notes);
    }

    /// Marks those of `keys` under `object` that the file gives as read, and notes them with `why` they are
    /// left out.
    pub(crate) fn left_out(&self, object: &str, keys: &[&str], why: &str, notes: &mut Vec<String>) {
        let given: Vec<&str> = keys.iter().copied().filter(|k| self.has(&format!("{object}/{k}"))).collect();
        for k in &given {
            self.expect(&format!("{object}/{k}"));
        }
        if !given.is_empty() {
            notes.push(format!("{}: {} — {why}", self.shown(object), given.join(", ")));
        }
    }

    /// Every key of the document that was not read, as [`Doc::shown`] shows it. A list of objects (Chrono's
    /// `Bodies`, `Joints`, …) is walked element by element.
    fn unread(&self) -> Vec<String> {
        fn walk(v: &Value, path: String, read: &BTreeSet<String>, out: &mut Vec<String>) {
            if read.contains(&path) {
                return;
            }
            let join = |k: &str| if path.is_empty() { k.to_string() } else { format!("{path}/{k}") };
            match v {
                Value::Object(map) if !map.is_empty() => {
                    for (k, child) in map {
                        walk(child, join(k), read, out);
                    }
                }
                Value::Array(items) if !items.is_empty() && items.iter().all(Value::is_object) => {
                    for (i, child) in items.iter().enumerate() {
                        walk(child, join(&i.to_string()), read, out);
                    }
                }
                _ => out.push(path),
            }
        }
        let mut out = Vec::new();
        walk(self.root, String::new(), &self.read.borrow(), &mut out);
        out.into_iter().map(|p| self.shown(&p)).collect()
    }
}

/// The general model being written, and what was noted on the way.
pub(crate) struct Builder {
    pub(crate) general: GeneralCorner,
    pub(crate) notes: Vec<String>,
    /// Whether parts go to the axle (the parts the two corners share, [`AxleDef`]) rather than the corner.
    shared: bool,
}

impl Builder {
    fn new(doc: &Doc, loaded_radius: Option<f64>) -> Self {
        let mut notes = Vec::new();
        if loaded_radius.is_none() {
            notes.push(format!(
                "loaded tyre radius: not in a Chrono suspension file; {} m taken (edit corner.loaded_radius)",
                default_loaded_radius()
            ));
        }
        doc.expect("Name");
        // The steering axis is the reader's to give; until then it is a point.
        let at_centre = || BodyPoint { body: "upright".into(), at: Place::named("wheel_centre") };
        let loaded_radius = loaded_radius.unwrap_or_else(default_loaded_radius);
        let general = GeneralCorner::empty(loaded_radius, [at_centre(), at_centre()], None);
        Builder { general, notes, shared: false }
    }

    /// Sends the parts that follow to the axle (`true`: shared by both corners, written as they are, not
    /// mirrored) or to the corner (`false`).
    pub(crate) fn on_axle(&mut self, shared: bool) {
        if shared && self.general.axle.is_none() {
            self.general.axle = Some(AxleDef::default());
        }
        self.shared = shared;
    }

    /// The axle's parts; made by [`Builder::on_axle`].
    pub(crate) fn axle(&mut self) -> &mut AxleDef {
        self.general.axle.as_mut().expect("on_axle(true) came first")
    }

    fn hardpoints_mut(&mut self) -> &mut Hardpoints {
        if self.shared {
            &mut self.axle().hardpoints
        } else {
            &mut self.general.hardpoints
        }
    }

    fn bodies_mut(&mut self) -> &mut Vec<BodyDef> {
        if self.shared {
            &mut self.axle().bodies
        } else {
            &mut self.general.bodies
        }
    }

    fn joints_mut(&mut self) -> &mut Vec<JointDef> {
        if self.shared {
            &mut self.axle().joints
        } else {
            &mut self.general.joints
        }
    }

    fn bushings_mut(&mut self) -> &mut Vec<BushingDef> {
        if self.shared {
            &mut self.axle().bushings
        } else {
            &mut self.general.bushings
        }
    }

    fn springs_mut(&mut self) -> &mut Vec<SpringDef> {
        if self.shared {
            &mut self.axle().springs
        } else {
            &mut self.general.springs
        }
    }

    fn stops_mut(&mut self) -> &mut Vec<StopDef> {
        if self.shared {
            &mut self.axle().stops
        } else {
            &mut self.general.stops
        }
    }

    /// The point of the hardpoint `name` where the parts go: the corner's (left side), or on the axle its
    /// own or a corner's as `"left …"` / `"right …"` placed on that side.
    pub(crate) fn point_of(&self, name: &str) -> Result<Vec3, String> {
        let corner = |n: &str| self.general.hardpoints.get(n);
        let found = match (&self.general.axle, self.shared) {
            (Some(axle), true) => axle.hardpoints.get(name).or_else(|| {
                let (side, rest) = match name.strip_prefix("left ") {
                    Some(rest) => (Side::Left, rest),
                    None => (Side::Right, name.strip_prefix("right ")?),
                };
                corner(rest).map(|p| side.place(p))
            }),
            _ => corner(name),
        };
        found.ok_or_else(|| format!("no hardpoint {name}"))
    }

    /// Adds the hardpoint `name` at the point read from `path`; returns its name.
    pub(crate) fn hardpoint(&mut self, doc: &Doc, name: &str, path: &str) -> Result<String, String> {
        let p = doc.point(path)?;
        // Refused here, by the file's key, before a frame or a midpoint is taken from it.
        if p.amax() > MAX_COORDINATE {
            return Err(format!(
                "\"{}\" [{:?}, {:?}, {:?}]: a coordinate beyond ±{MAX_COORDINATE} m; Chrono's points are in metres from the \
                 suspension's reference point",
                path.replace('/', "\" / \""),
                p.x,
                p.y,
                p.z
            ));
        }
        self.hardpoints_mut().0.push((name.to_string(), p));
        Ok(name.to_string())
    }

    /// The wheel: the spindle's centre, camber and toe, and the upright that carries it.
    pub(crate) fn wheel(&mut self, doc: &Doc) -> Result<(), String> {
        self.hardpoint(doc, "wheel_centre", "Spindle/COM")?;
        self.general.bodies.push(BodyDef { name: "upright".into(), at: Place::named("wheel_centre") });
        doc.dynamics("Spindle", &["Mass", "Inertia", "Radius", "Width"], &mut self.notes);
        doc.dynamics(
            "Upright",
            &["Mass", "COM", "Inertia", "Moments of Inertia", "Products of Inertia", "Radius"],
            &mut self.notes,
        );
        doc.dynamics("Axle", &["Inertia"], &mut self.notes);
        doc.expect("Vehicle-Frame Inertia");
        let camber = doc.optional_number("Camber Angle (deg)")?.unwrap_or(0.0).to_radians();
        let toe = doc.optional_number("Toe Angle (deg)")?.unwrap_or(0.0).to_radians();
        self.general.corner.spin_axis = [camber.cos() * toe.sin(), camber.cos() * toe.cos(), -camber.sin()];
        Ok(())
    }

    /// A rigid link named `name` from `from` on `bodies[0]` to `to` on `bodies[1]` (hardpoint names): a
    /// distance constraint.
    pub(crate) fn link(&mut self, name: &str, bodies: [&str; 2], from: &str, to: &str) {
        self.joints_mut().push(JointDef {
            name: name.into(),
            kind: JointKind::Distance,
            bodies: bodies.map(str::to_string),
            at: Some(Place::named(from)),
            to: Some(Place::named(to)),
            axis: None,
            axis_j: None,
        });
    }

    /// Adds a body at the hardpoint `at`.
    pub(crate) fn body(&mut self, name: &str, at: &str) {
        self.body_at(name, Place::named(at));
    }

    /// Adds a body with its reference point at `at`.
    pub(crate) fn body_at(&mut self, name: &str, at: Place) {
        self.bodies_mut().push(BodyDef { name: name.into(), at });
    }

    /// A rotational spring of `rate` (N·m/rad) about `axis` between `bodies`, pushing `preload` (N·m) about
    /// it on the second at design: a bushing of that torsion rate on the revolute joint the two bodies turn
    /// on about that axis, which holds its other directions (their rates, the least the engine takes, meet
    /// no deflection there), with Chrono's law `M = Kθ`.
    pub(crate) fn torsion_spring(
        &mut self,
        name: &str,
        bodies: [&str; 2],
        at: Place,
        axis: Vec3,
        rate: f64,
        preload: f64,
    ) {
        let (t, r) = (TRANSLATIONAL_RATE_RANGE.0, ROTATIONAL_RATE_RANGE.0);
        self.bushings_mut().push(BushingDef {
            name: name.into(),
            bodies: bodies.map(str::to_string),
            at,
            axis: Some(Axis::Vector(axis)),
            y_axis: None,
            radial: None,
            axial: None,
            torsion: None,
            conical: None,
            translation: Some([t.into(), t.into(), t.into()]),
            rotation: Some([rate.into(), r.into(), r.into()]),
            law: RotationLaw::Linear,
            preload_force: None,
            preload_torque: (preload != 0.0).then_some([preload, 0.0, 0.0]),
        });
    }

    /// The steering axis of a wheel carrier without a kingpin (a trailing arm that carries the spindle): the
    /// wheel's own vertical through its centre — the z axis of Chrono's spindle frame, the chassis's z turned
    /// by the toe and camber — from the wheel centre to the hardpoint `steering_axis_upper` 0.1 m up it, both
    /// on the upright. With no camber it is the vertical through the wheel centre: caster, kingpin
    /// inclination and kingpin offset zero.
    pub(crate) fn wheel_vertical_steering_axis(&mut self) -> Result<(), String> {
        let centre = self.general.hardpoints.get("wheel_centre").ok_or("no hardpoint wheel_centre")?;
        let spin = Vec3::from(self.general.corner.spin_axis);
        let up = Vec3::z() - spin * spin.z;
        // Within the 60° of camber the general model takes, |up| = cos γ ≥ 0.5.
        if up.norm() <= 0.5 {
            return Err(format!(
                "\"Camber Angle (deg)\" {:.1}: the wheel lies too flat to have a vertical; give a camber within ±60°",
                (-spin.z).asin().to_degrees()
            ));
        }
        self.general.hardpoints.0.push(("steering_axis_upper".into(), centre + 0.1 * up.normalize()));
        self.steering_axis(("upright", "wheel_centre"), ("upright", "steering_axis_upper"));
        Ok(())
    }

    /// The steering axis from `lower` on `lower_body` to `upper` on `upper_body`.
    pub(crate) fn steering_axis(&mut self, lower: (&str, &str), upper: (&str, &str)) {
        let at = |(body, point): (&str, &str)| BodyPoint { body: body.into(), at: Place::named(point) };
        self.general.corner.steering_axis = [at(lower), at(upper)];
    }

    /// A joint of `kind` at `at` (hardpoint name or coordinates), or — when `bushing` holds Chrono's
    /// `Bushing Data` — the bushing Chrono puts there instead. `frame` is Chrono's joint frame as `(u, w)`:
    /// w its axis, u its x axis (v = w × u).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn joint(
        &mut self,
        doc: &Doc,
        name: &str,
        kind: JointKind,
        bodies: [&str; 2],
        at: Place,
        frame: Option<(Vec3, Vec3)>,
        bushing: Option<&str>,
    ) -> Result<(), String> {
        let data = bushing.filter(|path| doc.has(path));
        let Some(path) = data else {
            // Chrono's universal joint crosses the frame's u (on the first body) and v (on the second).
            let (axis, axis_j) = match (kind, frame) {
                (JointKind::Revolute | JointKind::Cylindrical, Some((_, w))) => (Some(Axis::Vector(w)), None),
                (JointKind::Universal, Some((u, w))) => (Some(Axis::Vector(u)), Some(Axis::Vector(w.cross(&u)))),
                // Chrono's point-line keeps the first body's point on the frame's x axis; point-plane on its
                // xy plane (normal z).
                (JointKind::InLine, Some((u, _))) => (Some(Axis::Vector(u)), None),
                (JointKind::InPlane, Some((_, w))) => (Some(Axis::Vector(w)), None),
                _ => (None, None),
            };
            self.joints_mut().push(JointDef {
                name: name.into(),
                kind,
                bodies: bodies.map(str::to_string),
                at: Some(at),
                to: None,
                axis,
                axis_j,
            });
            return Ok(());
        };
        // Chrono's K: translations all K_lin; rotations K_rot about the axes the joint holds, the DOF rate
        // about the ones it frees. The frame here: x = w (the axis), y = u, z = v.
        let k_lin = doc.number(&format!("{path}/Stiffness Linear"))?;
        let k_rot = doc.number(&format!("{path}/Stiffness Rotational"))?;
        let (k_lin_dof, k_rot_dof) = if doc.has(&format!("{path}/DOF")) {
            (
                doc.number(&format!("{path}/DOF/Stiffness Linear"))?,
                doc.number(&format!("{path}/DOF/Stiffness Rotational"))?,
            )
        } else {
            (0.0, 0.0)
        };
        for damping in ["Damping Linear", "Damping Rotational", "DOF/Damping Linear", "DOF/Damping Rotational"] {
            doc.expect(&format!("{path}/{damping}"));
        }
        let _ = k_lin_dof; // Chrono applies it to no direction of the joints it uses for suspensions.
        let (u, w) = frame.unwrap_or((Vec3::x(), Vec3::z()));
        // About (w, u, v):
        let rotation = match kind {
            JointKind::Spherical => [k_rot_dof; 3],
            JointKind::Revolute => [k_rot_dof, k_rot, k_rot],
            JointKind::Universal => [k_rot, k_rot_dof, k_rot_dof],
            _ => [k_rot; 3],
        };
        let least = |k: f64, (lo, _): (f64, f64), what: &str, notes: &mut Vec<String>| {
            if k < lo {
                notes.push(format!(
                    "{}: {what} rate {k} taken as {lo} (the least the engine takes: a rate of zero holds nothing)",
                    doc.shown(path)
                ));
                lo
            } else {
                k
            }
        };
        let t = least(k_lin, TRANSLATIONAL_RATE_RANGE, "linear", &mut self.notes);
        let mut r = [0.0; 3];
        for (slot, k) in r.iter_mut().zip(rotation) {
            *slot = least(k, ROTATIONAL_RATE_RANGE, "rotational", &mut self.notes);
        }
        self.notes.dedup();
        self.bushings_mut().push(BushingDef {
            name: name.into(),
            bodies: bodies.map(str::to_string),
            at,
            axis: Some(Axis::Vector(w)),
            y_axis: Some(Axis::Vector(u)),
            radial: None,
            axial: None,
            torsion: None,
            conical: None,
            translation: Some([t.into(), t.into(), t.into()]),
            rotation: Some(r.map(Into::into)),
            law: RotationLaw::Linear,
            preload_force: None,
            preload_torque: None,
        });
        Ok(())
    }

    /// A Chrono spring (`ChLinkTSDA` read by its functor) named `name` between `bodies`, seats `from`, `to`
    /// (hardpoint names); with its stops when it has `Minimum Length` and `Maximum Length`. `object` is
    /// its JSON object.
    pub(crate) fn spring(
        &mut self,
        doc: &Doc,
        object: &str,
        name: &str,
        bodies: [&str; 2],
        seats: [&str; 2],
    ) -> Result<(), String> {
        let key = |k: &str| format!("{object}/{k}");
        let free_length = doc.number(&key("Free Length"))?;
        let preload = doc.optional_number(&key("Preload"))?;
        let (rate, curve) = if doc.has(&key("Spring Curve Data")) {
            // Chrono: push = P − f(L − L₀); here: push against compression c = L₀ − L, so (−x, −f).
            let mut table: Vec<[f64; 2]> =
                doc.table(&key("Spring Curve Data"))?.into_iter().map(|[x, f]| [-x, -f]).collect();
            table.reverse();
            (None, Some(table))
        } else {
            (Some(doc.number(&key("Spring Coefficient"))?), None)
        };
        for damping in
            ["Damping Coefficient", "Damping Curve Data", "Degressivity Compression", "Degressivity Expansion"]
        {
            if doc.has(&key(damping)) {
                doc.expect(&key(damping));
                self.notes.push(format!("{} / {damping}: damping, left out (statics: no velocity)", doc.shown(object)));
            }
        }
        self.springs_mut().push(SpringDef {
            name: name.into(),
            bodies: bodies.map(str::to_string),
            from: Place::named(seats[0]),
            to: Place::named(seats[1]),
            rate,
            curve,
            design_force: None,
            free_length: Some(free_length),
            preload: preload.filter(|p| *p != 0.0),
        });
        if let (Some(min), Some(max)) =
            (doc.optional_number(&key("Minimum Length"))?, doc.optional_number(&key("Maximum Length"))?)
        {
            if min >= max {
                // Chrono would press both stops at once: past its table each holds its last force, so between
                // the two they cancel, and the spring meets a wall where either leaves that plateau.
                let design = (self.point_of(seats[1])? - self.point_of(seats[0])?).norm();
                let [.., [reach, most]] = CHRONO_STOP_CURVE;
                return Err(format!(
                    "\"{object}\" / \"Minimum Length\" {min} m is not below \"Maximum Length\" {max} m: the stops are \
                     crossed (the bump stop acts below the minimum, the rebound stop above the maximum, so here both \
                     press at once: in Chrono {most} N each way, cancelling from {:.4} to {:.4} m and stopping the \
                     spring hard outside that); give Minimum Length below the spring's design length {design:.4} m \
                     and Maximum Length above it ({max} and {min}, swapped), or remove them to leave the spring \
                     without stops",
                    max + reach,
                    min - reach
                ));
            }
            let design = (self.point_of(seats[1])? - self.point_of(seats[0])?).norm();
            for (kind, clearance, what) in
                [(StopType::Bump, design - min, "Minimum Length"), (StopType::Rebound, max - design, "Maximum Length")]
            {
                if clearance < 0.0 {
                    self.notes.push(format!(
                        "{} / {what} {} m: the stop is in contact at the design length {design:.4} m, by {:.4} m",
                        doc.shown(object),
                        if kind == StopType::Bump { min } else { max },
                        -clearance
                    ));
                }
                let stop = if kind == StopType::Bump { "bump stop" } else { "rebound stop" };
                self.stops_mut().push(StopDef {
                    name: format!("{name} {stop}"),
                    kind,
                    bodies: bodies.map(str::to_string),
                    from: Place::named(seats[0]),
                    to: Place::named(seats[1]),
                    clearance,
                    curve: CHRONO_STOP_CURVE.to_vec(),
                });
            }
            self.notes.push(format!(
                "{} / Minimum Length, Maximum Length: a bump and a rebound stop with Chrono's built-in curve",
                doc.shown(object)
            ));
        }
        Ok(())
    }

    /// A Chrono shock: a damper, left out in statics; a spring-damper's spring (`Spring Coefficient` or a
    /// curve) is a spring named `name` between `bodies`, at the shock's points `seats` (JSON keys under
    /// `Shock`).
    pub(crate) fn shock(&mut self, doc: &Doc, name: &str, bodies: [&str; 2], seats: [&str; 2]) -> Result<(), String> {
        if doc.has("Shock/Spring Coefficient") || doc.has("Shock/Spring Curve Data") {
            let from = self.hardpoint(doc, "shock_chassis", &format!("Shock/{}", seats[0]))?;
            let to = self.hardpoint(
                doc,
                &format!("shock_{}", seats[1].trim_start_matches("Location ").to_lowercase()),
                &format!("Shock/{}", seats[1]),
            )?;
            return self.spring(doc, "Shock", name, bodies, [&from, &to]);
        }
        for key in seats.iter().copied().chain([
            "Damping Coefficient",
            "Damping Curve Data",
            "Degressivity Compression",
            "Degressivity Expansion",
            "Map Data",
        ]) {
            doc.expect(&format!("Shock/{key}"));
        }
        if doc.has("Shock") {
            self.notes.push("Shock: a damper, left out (statics: no velocity)".into());
        }
        Ok(())
    }

    /// An arm's points: its pivots `<key> / Location Chassis Front` and `… Back` and its ball joint
    /// `… Location Upright`, as the hardpoints `<short>_arm_front`, `<short>_arm_back` and `<short>_ball_joint`;
    /// its `dynamics` keys read and left out. Returns the three names.
    pub(crate) fn arm_points(
        &mut self,
        doc: &Doc,
        key: &str,
        short: &str,
        dynamics: &[&str],
    ) -> Result<[String; 3], String> {
        let front = self.hardpoint(doc, &format!("{short}_arm_front"), &format!("{key}/Location Chassis Front"))?;
        let back = self.hardpoint(doc, &format!("{short}_arm_back"), &format!("{key}/Location Chassis Back"))?;
        let ball = self.hardpoint(doc, &format!("{short}_ball_joint"), &format!("{key}/Location Upright"))?;
        doc.dynamics(key, dynamics, &mut self.notes);
        Ok([front, back, ball])
    }

    /// The arm `<short> arm` on the points of [`Builder::arm_points`]: a revolute joint `<short> arm pivot` to
    /// the chassis at the pivots' midpoint in [`arm_frame`] (Chrono's bushing there when `bushing`, its path,
    /// holds `Bushing Data`) and the ball joint `<short> ball joint` to the upright. With `degenerate`, an arm
    /// with no plane (its ball joint on its pivot axis) is refused with that message.
    pub(crate) fn arm_joints(
        &mut self,
        doc: &Doc,
        short: &str,
        [front, back, ball]: &[String; 3],
        bushing: Option<&str>,
        degenerate: Option<&str>,
    ) -> Result<(), String> {
        let arm = format!("{short} arm");
        self.body(&arm, ball);
        let mut frame = arm_frame(self.point_of(front)?, self.point_of(back)?, self.point_of(ball)?);
        if let Some(why) = degenerate {
            frame = checked_frame(frame, why)?;
        }
        let at = midpoint(self, front, back)?;
        self.joint(doc, &format!("{arm} pivot"), JointKind::Revolute, [CHASSIS, &arm], at, Some(frame), bushing)?;
        self.joint(
            doc,
            &format!("{short} ball joint"),
            JointKind::Spherical,
            [&arm, "upright"],
            Place::named(ball),
            None,
            None,
        )
    }

    /// The spring from `Spring / Location Chassis` to `Spring / Location <seat>` (hardpoints `spring_chassis`
    /// and `spring_<seat>`) and the shock between the same keys under `Shock`, both from the chassis to
    /// `body`.
    pub(crate) fn spring_and_shock(&mut self, doc: &Doc, body: &str, seat: &str) -> Result<(), String> {
        let on_body = format!("Location {seat}");
        let c = self.hardpoint(doc, "spring_chassis", "Spring/Location Chassis")?;
        let s = self.hardpoint(doc, &format!("spring_{}", seat.to_lowercase()), &format!("Spring/{on_body}"))?;
        self.spring(doc, "Spring", "spring", [CHASSIS, body], [&c, &s])?;
        self.shock(doc, "shock", [CHASSIS, body], ["Location Chassis", &on_body])
    }

    /// The tie rod from `inner` to `outer`: a distance link, or Chrono's rod body (`Mass` given) with a
    /// universal joint at the rack and a ball joint at the upright, which with ideal joints is the same
    /// link. With `Bushing Data` on the rod both joints are Chrono's bushings.
    pub(crate) fn tie_rod(&mut self, doc: &Doc, inner: &str, outer: &str) -> Result<(), String> {
        doc.dynamics("Tierod", &["Mass", "Inertia", "Radius"], &mut self.notes);
        if doc.has("Tierod/Bushing Data") {
            let path = "Tierod/Bushing Data";
            let k_lin = doc.number(&format!("{path}/Stiffness Linear"))?;
            let k_rot = doc.number(&format!("{path}/Stiffness Rotational"))?;
            let k_rot_dof = doc.optional_number(&format!("{path}/DOF/Stiffness Rotational"))?.unwrap_or(0.0);
            for k in [
                "Damping Linear",
                "Damping Rotational",
                "DOF/Damping Linear",
                "DOF/Damping Rotational",
                "DOF/Stiffness Linear",
            ] {
                doc.expect(&format!("{path}/{k}"));
            }
            // Chrono's rod has a universal joint at the rack (its twist about the rod held: k_rot) and a ball
            // joint at the upright (every rotation free: the DOF rate), each a bushing with this data.
            let (lo, _) = ROTATIONAL_RATE_RANGE;
            let dof = k_rot_dof.max(lo);
            let rates = |torsion: f64| {
                Connection::Bushing(crate::description::BushingRates {
                    radial: k_lin.max(TRANSLATIONAL_RATE_RANGE.0),
                    axial: k_lin.max(TRANSLATIONAL_RATE_RANGE.0),
                    torsion,
                    conical: dof,
                    law: RotationLaw::Linear,
                    axis: None,
                })
            };
            self.notes.push(format!(
                "Tierod / Bushing Data: a rod with a bushing at each end, radial and axial {k_lin} N/m, conical {dof} \
                 N·m/rad; torsion {} N·m/rad at the rack (Chrono's universal joint), {dof} at the upright (its ball joint)",
                k_rot.max(lo)
            ));
            self.general.corner.tie_rod = Some(TieRodDef {
                inner: Place::named(inner),
                outer: Place::named(outer),
                connection: crate::description::connection::TieRodMounts {
                    inner: rates(k_rot.max(lo)),
                    outer: rates(dof),
                },
            });
        } else {
            self.general.corner.tie_rod = Some(TieRodDef {
                inner: Place::named(inner),
                outer: Place::named(outer),
                connection: Connection::Ideal.into(),
            });
        }
        Ok(())
    }

    /// The notes, with every key of the document that was not read.
    fn finish(&mut self, doc: &Doc) -> Vec<String> {
        let mut notes = std::mem::take(&mut self.notes);
        notes.extend(doc.unread().into_iter().map(|k| format!("{k}: not understood, left out")));
        notes
    }
}

/// Chrono's built-in stop curve (`SpringForce::enable_stops`, from an ADAMS/Car example): force (N)
/// against travel past contact (m). Chrono's table (`ChFunctionInterp`, not extrapolating) holds its last
/// force past 60 mm; elastokin's curve continues straight with its end slope, so that flat end is written
/// out as a last point at 70 mm (the cubic then arrives level at 60 mm, where Chrono's straight pieces
/// turn sharply: between 50 and 60 mm the two differ by up to 13 kN, as they did without that point, now
/// mostly above Chrono's). It matters where a stop is driven past 60 mm: Chrono's `DeDionAxle` file has
/// both stops 80 mm in contact at design, where they cancel.
pub const CHRONO_STOP_CURVE: [[f64; 2]; 12] = [
    [0.0, 0.0],
    [2.0e-3, 200.0],
    [4.0e-3, 400.0],
    [6.0e-3, 600.0],
    [8.0e-3, 800.0],
    [10.0e-3, 1000.0],
    [20.0e-3, 2500.0],
    [30.0e-3, 4500.0],
    [40.0e-3, 7500.0],
    [50.0e-3, 12500.0],
    [60.0e-3, 125000.0],
    [70.0e-3, 125000.0],
];

/// Chrono's frame of a revolute joint between an arm and the chassis, from the arm's front and back pivots
/// and its outer point: w along the pivot axis (front − back), v normal to the arm's plane, u = v × w.
/// Returns `(u, w)`.
pub(crate) fn arm_frame(front: Vec3, back: Vec3, outer: Vec3) -> (Vec3, Vec3) {
    let v = (back - outer).cross(&(front - outer)).normalize();
    let w = (front - back).normalize();
    (v.cross(&w), w)
}

/// The midpoint of two hardpoints of `b`.
pub(crate) fn midpoint(b: &Builder, p: &str, q: &str) -> Result<Place, String> {
    Ok(Place::At((b.point_of(p)? + b.point_of(q)?) / 2.0))
}

/// A direction `[x, y, z]` at `path` (any length but zero).
pub(crate) fn direction(doc: &Doc, path: &str) -> Result<Vec3, String> {
    let shown = path.replace('/', "\" / \"");
    let d =
        doc.point(path).map_err(|_| format!("\"{shown}\" must be a direction [x, y, z], of any length but zero"))?;
    // Scaled by its largest component, so that its length is finite however long it is given.
    let largest = d.amax();
    if largest == 0.0 {
        return Err(format!("\"{shown}\" is [0, 0, 0]: give the direction [x, y, z], of any length but zero"));
    }
    Ok(d / largest)
}

/// Chrono's frame of a universal joint whose cross pins are `u` (on the first body) and `v` made
/// perpendicular to it (on the second), as [`Builder::joint`] takes it: `(û, ŵ)` with ŵ = û × v
/// normalised, so that the joint crosses û with ŵ × û. `parallel` is the refusal when the two are
/// parallel.
pub(crate) fn cross_frame(u: Vec3, v: Vec3, parallel: &str) -> Result<(Vec3, Vec3), String> {
    let (u, v) = (u.normalize(), v.normalize());
    let w = u.cross(&v);
    // Finite: a zero direction is refused by `direction`, which also scales a long one.
    if w.norm() <= 1e-6 {
        return Err(parallel.to_string());
    }
    Ok((u, w.normalize()))
}

/// `frame` (a `(u, w)` of [`Builder::joint`]) when it is one: finite, of unit axes. `why` says what makes it
/// fail, and how to fix that.
pub(crate) fn checked_frame(frame: (Vec3, Vec3), why: &str) -> Result<(Vec3, Vec3), String> {
    let unit = |a: Vec3| (a.norm() - 1.0).abs() < 1e-9;
    if unit(frame.0) && unit(frame.1) {
        Ok(frame)
    } else {
        Err(why.to_string())
    }
}
