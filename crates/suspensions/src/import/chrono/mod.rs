//! Project Chrono's vehicle suspension files, read into the general model.
//!
//! Project Chrono (BSD-3-Clause, `projectchrono/chrono`) describes each suspension subsystem of its wheeled
//! vehicles in a JSON file under `data/vehicle/*/suspension/`: a `"Template"` (the subsystem's class) and
//! its hardpoints, bodies, joints and spring-damper elements, for the left side. [`read`] reads one into
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
//!   is read as that bushing: the same frame, the six rates, [`RotationLaw::Linear`](elastokin_elements::RotationLaw::Linear). A zero rate (Chrono
//!   files give 0 for the free directions) is taken as the least rate the engine accepts
//!   ([`ROTATIONAL_RATE_RANGE`](crate::description::limits::ROTATIONAL_RATE_RANGE)`.0`, 10⁻³ N·m/rad), said in the notes.
//! - Masses, inertias, radii and widths are read and left out (statics); shocks and dampers too (no
//!   velocity); each is listed in the notes. A key the importer does not know is a note too: nothing is
//!   dropped unsaid.
//! - Chrono's suspension files give no tyre: the loaded radius is [`default_loaded_radius`](crate::description::limits::default_loaded_radius)
//!   unless the caller gives one.
//! - An axle whose wheels share a body (a solid axle, a De Dion tube, a beam on leaf springs) is read whole:
//!   what Chrono builds once (the tube, a tie rod or toe bar across, a Panhard rod, a drag link) goes in the
//!   model's `axle` ([`crate::description::general::AxleDef`]), written as Chrono places it, and each side's parts in the
//!   corner, mirrored. A link Chrono builds as a body on a ball joint and a universal joint (which only
//!   stops the link spinning) is the distance constraint between its ends; a drag link is the steering
//!   input, moved along its own line. Where Chrono's ideal joints lock the axle's roll, the roll analysis is
//!   skipped with that reason.

mod builder;
mod de_dion_axle;
mod doc;
mod double_wishbone;
mod error;
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
mod templates;
mod three_link_irs;

use crate::description::Template;
use crate::file::key_path::locate;
use crate::file::{without_byte_order_mark, FileError, SuspensionFile};
use builder::Builder;
pub use builder::CHRONO_STOP_CURVE;
use doc::Doc;
pub use error::{Expected, ImportError, KeyPath, Refusal};
use serde_json::Value;
pub use templates::SUPPORTED;

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
pub fn read(text: &str, origin: &str, loaded_radius: Option<f64>) -> Result<Imported, ImportError> {
    let clean = without_comments(without_byte_order_mark(text));
    // A refusal is placed at the keys it names, or at the template's name.
    let at = |refusal: Refusal| {
        let keys: Vec<&str> = refusal.keys().iter().map(String::as_str).collect();
        let keys = if keys.is_empty() { vec!["Template"] } else { keys };
        let (line, column) = locate(&clean, &keys);
        ImportError::At { origin: origin.to_string(), line, column, refusal }
    };
    let value: Value = serde_json::from_str(&clean).map_err(|e| FileError::Invalid {
        origin: origin.to_string(),
        line: e.line(),
        column: e.column(),
        message: e.to_string().split(" at line ").next().unwrap_or_default().to_string(),
    })?;
    crate::file::refuse_unprintable(&value, &clean, origin)?;
    let doc = Doc::new(&value);
    let template = doc.template().map_err(at)?;
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
        other => Err(Refusal::Template { template: other.to_string() }),
    };
    built.map_err(at)?;
    let notes = b.finish(&doc);
    let file = SuspensionFile {
        name: format!("{name} (Project Chrono {template})"),
        suspension: Template::General(Box::new(b.general)),
        vehicle: None,
        packaging: None,
    };
    // The general model's own checks, as a model file's: the builder's follow in `document::import_chrono`.
    let text = file.to_json();
    let file = SuspensionFile::parse_checked(&text, origin, true)?;
    Ok(Imported { file, template, notes })
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
