//! Chrono's `HendricksonPRIMAXX` (`ChHendricksonPRIMAXX`): a steered truck axle on a walking-beam linkage.
//! One axle housing carries both knuckles, so the model gets an `axle` ([`crate::description::general::AxleDef`]) holding
//! the housing; each corner's own parts are written for the left and mirrored, as Chrono mirrors them.
//!
//! What `ChHendricksonPRIMAXX::Construct` and `InitializeSide` build, and how it reads:
//! - The axle housing, a body at `Axle Housing / COM` (the axle's).
//! - Per side, a knuckle (the corner's upright, which carries the spindle) on a revolute kingpin to the
//!   housing, its axis through `Knuckle / Lower Attachment Point` and `Upper Attachment Point`, at their
//!   midpoint; the kingpin is the steering axis.
//! - Per side, a torque rod and a lower beam, each a body on a revolute joint to the chassis at its
//!   `Chassis Attachment Point` (Chrono's frame: the chassis's turned a quarter about x, so the axis is
//!   across the car, y) and a ball joint to the housing at its `Axle Housing Attachment Point`: each holds
//!   its point on the housing on a circle about a transverse axis. The two rods of a side make a four-bar
//!   linkage in the side view with the housing as its coupler. With ideal joints both sides hold the one
//!   housing: it can neither roll nor yaw, and has one way to move, its travel (three of the eight
//!   constraints the four rods put on it repeat others: the solver drops those rows, which `elastokin
//!   check` names, and the joints they repeat carry their load). The roll analysis is skipped with that
//!   reason, and a corner analysis drives the left wheel's height, the right following. Chrono builds it
//!   so: ideal joints, no bushings in the file.
//! - Per side, the tie rod from `Tierod / Location Chassis` (on the chassis, or on the steering link when
//!   the vehicle has a steering subsystem) to `Location Knuckle`: a distance constraint (`ChLinkDistance`),
//!   or with `Mass` a rod body with a universal joint at the inner end and a ball joint at the knuckle (the
//!   same link with ideal joints; with `Bushing Data`, both Chrono's bushings). The steering analysis moves
//!   both inner ends together across the car, as a steering link does.
//! - Per side, two spring-dampers (`ChLinkTSDA`) from the chassis to the **axle housing**: `Shock Axle
//!   Housing`, and `Shock Lower Beam`, whose comment in Chrono's code says "between lower beam and chassis"
//!   but whose `Initialize` joins the chassis to the axle housing at `Location Lower Beam`. The reading
//!   follows the code: both act on the housing. The first is read as the shock, the second (the generic
//!   file's air spring: a rate and no damping) as the spring, whose motion ratio the travel analysis gives.
//! - Neither spring-damper is given its `Free Length`: `ChHendricksonPRIMAXX` never calls `SetRestLength`,
//!   so `ChLinkTSDA::Initialize` takes the design length as the rest length. Each is read with its free
//!   length at its design length, pushing only its `Preload` at design, as in Chrono; the file's
//!   `Free Length` is noted as unused. A spring-damper of rate zero pushes nothing at rest: a damper, left
//!   out (statics).
//! - The transverse beam: Chrono makes the body (`Transverse Beam`) but joins it to nothing (its ball
//!   joints to the lower beams are declared and never made; Chrono's source carries "TODO: connect
//!   transverse beam with universal joint?!?"). A body on no joint has no position at rest and carries
//!   nothing: it is left out, and `Lower Beam / Transverse Beam Attachment Point` (used by Chrono only to
//!   draw the beam) with it.
//! - Chrono gives the spindle the chassis's orientation: `Camber Angle (deg)` and `Toe Angle (deg)` are not
//!   read by this template, so when a file gives them they are noted and the wheel stays square.
//!
//! Masses, inertias, radii and the bodies' centres of mass are read and left out (statics).

use super::builder::Builder;
use super::doc::Doc;
use super::error::Refusal;
use super::solid_axle::kingpin;
use crate::description::general::Place;
use crate::description::general::CHASSIS;
use elastokin_core::{JointKind, Vec3};

/// The name of the axle housing.
const AXLE_HOUSING: &str = "axle housing";

/// `HendricksonPRIMAXX`.
pub(super) fn read(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    if doc.has("Camber Angle (deg)") || doc.has("Toe Angle (deg)") {
        // `Builder::wheel` read them; this template's spindle does not turn by them.
        b.general.corner.spin_axis = [0.0, 1.0, 0.0];
        b.notes.push(
            "Camber Angle (deg), Toe Angle (deg): not read by Chrono's HendricksonPRIMAXX (its spindle takes the \
             chassis's orientation); left out, the wheel square at design"
                .into(),
        );
    }
    b.on_axle(true);
    let housing = b.hardpoint(doc, "axle_housing", "Axle Housing/COM")?;
    b.body(AXLE_HOUSING, &housing);
    doc.dynamics("Axle Housing", &["Mass", "Inertia", "Radius"], &mut b.notes);
    b.on_axle(false);
    doc.left_out(
        "Transverse Beam",
        &["Mass", "COM", "Inertia", "Radius"],
        "Chrono makes this body but joins it to nothing (its ball joints to the lower beams are never made): it \
         has no position at rest and carries nothing; left out",
        &mut b.notes,
    );
    // The kingpin's axis points down it, as the other axles' (Chrono's frame here points it up; a revolute
    // joint turns about the line alone).
    kingpin(doc, b, ["Lower Attachment Point", "Upper Attachment Point"], AXLE_HOUSING, &[])?;
    rod(doc, b, "Torque Rod", "torque rod", "torque_rod")?;
    rod(doc, b, "Lower Beam", "lower beam", "lower_beam")?;
    doc.left_out(
        "Lower Beam",
        &["Transverse Beam Attachment Point"],
        "where Chrono draws the transverse beam, which it joins to nothing; left out",
        &mut b.notes,
    );
    let inner = b.hardpoint(doc, "tie_rod_chassis", "Tierod/Location Chassis")?;
    let outer = b.hardpoint(doc, "tie_rod_knuckle", "Tierod/Location Knuckle")?;
    b.tie_rod(doc, &inner, &outer)?;
    spring_damper(
        doc,
        b,
        ("Shock Axle Housing", "Location Axle Housing"),
        "shock",
        ["shock_chassis", "shock_axle_housing"],
    )?;
    spring_damper(
        doc,
        b,
        ("Shock Lower Beam", "Location Lower Beam"),
        "spring",
        ["spring_chassis", "spring_lower_beam"],
    )
}

/// A torque rod or a lower beam (`key`): the body `name` on a revolute joint across the car (y) to the
/// chassis at `Chassis Attachment Point` and a ball joint to the housing at `Axle Housing Attachment Point`
/// (hardpoints `<short>_chassis`, `<short>_axle_housing`).
fn rod(doc: &Doc, b: &mut Builder, key: &str, name: &str, short: &str) -> Result<(), Refusal> {
    let chassis = b.hardpoint(doc, &format!("{short}_chassis"), &format!("{key}/Chassis Attachment Point"))?;
    let housing =
        b.hardpoint(doc, &format!("{short}_axle_housing"), &format!("{key}/Axle Housing Attachment Point"))?;
    doc.dynamics(key, &["Mass", "COM", "Inertia", "Radius"], &mut b.notes);
    let (c, a) = (b.point_of(&chassis)?, b.point_of(&housing)?);
    // On the pivot's own axis the ball joint would hold nothing and the rod would turn freely about it.
    if (a.x - c.x).hypot(a.z - c.z) < 1e-6 {
        return Err(Refusal::unusable(
            &[key, "Chassis Attachment Point", "Axle Housing Attachment Point"],
            format!(
            "\"{key}\" / \"Chassis Attachment Point\" and \"Axle Housing Attachment Point\" lie on one line across \
             the car: the {name} turns about that line and would hold nothing; give points apart in x or z"
        ),
        ));
    }
    b.body(name, &housing);
    // Chrono's frame: the chassis's turned a quarter about x (u = x, w = −y).
    b.joint(
        doc,
        &format!("{name} pivot"),
        JointKind::Revolute,
        [CHASSIS, name],
        Place::named(&chassis),
        Some((Vec3::x(), -Vec3::y())),
        None,
    )?;
    b.joint(
        doc,
        &format!("{name} ball joint"),
        JointKind::Spherical,
        [AXLE_HOUSING, name],
        Place::named(&housing),
        None,
        None,
    )
}

/// The spring-damper `key` from its `Location Chassis` to its point `on_housing`, from the chassis to the
/// housing, as the spring `name` at the hardpoints `seats`; its free length is its design length (Chrono
/// never sets the rest length of this template's spring-dampers).
fn spring_damper(
    doc: &Doc,
    b: &mut Builder,
    (key, on_housing): (&str, &str),
    name: &str,
    seats: [&str; 2],
) -> Result<(), Refusal> {
    let from = b.hardpoint(doc, seats[0], &format!("{key}/Location Chassis"))?;
    let to = b.hardpoint(doc, seats[1], &format!("{key}/{on_housing}"))?;
    if doc.has(&format!("{key}/Map Data")) {
        return Err(Refusal::unusable(
            &[key, "Map Data"],
            format!(
                "\"{key}\" / \"Map Data\": a map of force against deformation and speed, which this importer does not \
             read; give \"Spring Coefficient\" or \"Spring Curve Data\""
            ),
        ));
    }
    if key == "Shock Lower Beam" {
        b.notes.push(
            "Shock Lower Beam: Chrono joins it to the axle housing (not the lower beam its name and comment give), at \
             Location Lower Beam; read so"
                .into(),
        );
    }
    let design = (b.point_of(&to)? - b.point_of(&from)?).norm();
    let has = |k: &str| doc.has(&format!("{key}/{k}"));
    // Chrono takes the curve over the coefficient when both are given.
    let curve = has("Spring Curve Data");
    let rate = if curve { None } else { doc.optional_number(&format!("{key}/Spring Coefficient"))? };
    if !curve && rate.unwrap_or(0.0) == 0.0 {
        // Chrono's force is P − k (L − L₀) − c v: with k = 0 at rest only a preload or the stops (both lengths
        // given) would act.
        let preload = doc.optional_number(&format!("{key}/Preload"))?.unwrap_or(0.0);
        let stops = has("Minimum Length") && has("Maximum Length");
        if preload != 0.0 || stops {
            let (what, at) = if stops {
                ("\"Minimum Length\" and \"Maximum Length\"", vec![key, "Minimum Length", "Maximum Length"])
            } else {
                ("\"Preload\"", vec![key, "Preload"])
            };
            return Err(Refusal::unusable(
                &at,
                format!(
                    "\"{key}\" / {what} on a spring-damper of rate zero: a push at rest that elastokin's springs take \
                     only with a rate; give \"Spring Coefficient\" of at least 1 N/m"
                ),
            ));
        }
        let given: Vec<&str> = [
            "Spring Coefficient",
            "Free Length",
            "Damping Coefficient",
            "Damping Curve Data",
            "Degressivity Compression",
            "Degressivity Expansion",
        ]
        .into_iter()
        .filter(|k| has(k))
        .collect();
        for k in &given {
            doc.expect(&format!("{key}/{k}"));
        }
        b.notes.push(format!(
            "{key}: a damper of rate zero, pushing nothing at rest ({}); left out (statics: no velocity)",
            given.join(", ")
        ));
        return Ok(());
    }
    b.spring(doc, key, name, [CHASSIS, AXLE_HOUSING], [&from, &to])?;
    let spring = b.general.springs.last_mut().expect("the spring just read");
    let free = spring.free_length.replace(design);
    b.notes.push(format!(
        "{key} / Free Length {}: not used by Chrono (ChHendricksonPRIMAXX sets no rest length, so it is the design \
         length, {design:.4} m, and the spring pushes only its preload at design); read so",
        free.map_or_else(|| "-".into(), |f| format!("{f} m"))
    ));
    Ok(())
}
