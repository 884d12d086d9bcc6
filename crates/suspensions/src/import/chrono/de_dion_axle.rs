//! Chrono's De Dion axles: `DeDionAxle` (`ChDeDionAxle`) and `ToeBarDeDionAxle` (`ChToeBarDeDionAxle`). A
//! De Dion tube carries both wheels but no differential; like the solid axles
//! ([`super::solid_axle`]) the tube and what Chrono builds on it once go in the model's `axle`, written as
//! they are in the car, and each side's own parts (its knuckle, its spring) in the corner, mirrored.
//!
//! What Chrono's `Construct` and `InitializeSide` build, and how it is read:
//! - the tube (`Axle Tube / COM`) on a ball joint to the chassis at `Axle Tube / Location Connector
//!   Chassis` (the longitudinal guide, a push bar or an A-frame ahead of or behind the axle);
//! - the lateral guide, a Watt linkage (`Watt Mechanism`): a centre link turning on the tube about x, and
//!   a side link on a ball joint at each end from the chassis (`Location Left Link to Chassis`, `Location
//!   Right Link to Chassis`) to the centre link (`Location Left Link to Center`, `Location Right Link to
//!   Center`). The four points are taken as given, not mirrored (Chrono's "left" link may sit on the right).
//!   A side link on two ball joints is the distance constraint between its ends (its free spin holds
//!   nothing). The centre link's pivot is where Chrono puts it: for `ToeBarDeDionAxle` the midpoint of its
//!   two link points; for `DeDionAxle` `Left Link to Center + Right Link to Center / 2` — its code halves only
//!   the second point (operator precedence), and the joint is built there, so it is read there and said in
//!   the notes;
//! - `DeDionAxle`: the spindle turns on the tube itself (the upright is welded to the tube at the wheel
//!   centre); nothing steers it, and the steering axis is the wheel's vertical. Chrono hangs the springs on a
//!   subchassis when the vehicle has one; a suspension file names none, so they hang on the chassis;
//! - `ToeBarDeDionAxle`: a knuckle on a kingpin at each end of the tube (revolute, from `Location Upper`
//!   to `Location Lower`: the steering axis), the toe bar (`Tierod`) across from knuckle to knuckle (Chrono's
//!   rod body on a ball joint on the left and a universal joint on the right: the distance constraint
//!   between its ends), and the drag link from the steering arm (`Draglink / Location Chassis`, not mirrored)
//!   to one knuckle, at `Knuckle / Location Draglink`: the left knuckle when its y is positive (or zero), the
//!   right when negative, at the point as given (Chrono flips y, then mirrors it back for the right). The
//!   drag link is the steering input, driven along its own line;
//! - springs (with their stops, from `Minimum Length` / `Maximum Length`) and shocks (dampers, left out)
//!   from the chassis to the tube on each side.
//!
//! Chrono reads `Axle Tube / Location Stabilizer` not at all (it puts the anti-roll bar's connector at the
//! origin, and the bar is another subsystem's file): it is listed in the notes as left out.

use super::builder::Builder;
use super::doc::Doc;
use super::error::Refusal;
use super::solid_axle::{axle_tube, knuckle, knuckle_drag_link, toe_bar, wheel_on_tube, AXLE_TUBE};
use crate::description::general::Place;
use crate::description::general::CHASSIS;
use elastokin_core::{JointKind, Vec3};

/// Where the Watt centre link turns on the tube.
#[derive(Clone, Copy)]
enum WattPivot {
    /// `ChDeDionAxle`: `Left Link to Center + Right Link to Center / 2`.
    DeDion,
    /// `ChToeBarDeDionAxle`: the midpoint of the two link points.
    Midpoint,
}

/// The longitudinal guide (the tube's ball joint to the chassis) and the Watt linkage.
fn guides(doc: &Doc, b: &mut Builder, pivot: WattPivot) -> Result<(), Refusal> {
    b.on_axle(true);
    let ball = b.hardpoint(doc, "axle_tube_chassis", "Axle Tube/Location Connector Chassis")?;
    b.joint(doc, "axle tube ball joint", JointKind::Spherical, [AXLE_TUBE, CHASSIS], Place::named(&ball), None, None)?;
    doc.left_out(
        "Axle Tube",
        &["Location Stabilizer"],
        "Chrono does not read it (its code puts the anti-roll bar's connector at the origin; the bar is another \
         subsystem's file): left out",
        &mut b.notes,
    );

    let w = "Watt Mechanism";
    let left_chassis = b.hardpoint(doc, "watt_left_chassis", &format!("{w}/Location Left Link to Chassis"))?;
    let left_centre = b.hardpoint(doc, "watt_left_centre", &format!("{w}/Location Left Link to Center"))?;
    let right_chassis = b.hardpoint(doc, "watt_right_chassis", &format!("{w}/Location Right Link to Chassis"))?;
    let right_centre = b.hardpoint(doc, "watt_right_centre", &format!("{w}/Location Right Link to Center"))?;
    doc.dynamics(
        w,
        &["Center Link Mass", "Side Link Mass", "Center Link Inertia", "Side Link Inertia", "Link Radius"],
        &mut b.notes,
    );
    let (le, ri) = (b.point_of(&left_centre)?, b.point_of(&right_centre)?);
    if (le - ri).norm() < 1e-6 {
        return Err(Refusal::unusable(
            &[w, "Location Left Link to Center", "Location Right Link to Center"],
            format!(
            "\"{w}\" / \"Location Left Link to Center\" and \"Location Right Link to Center\" coincide: they are the \
             centre link's two ends; give two distinct points"
        ),
        ));
    }
    for (chassis, centre, which) in [(&left_chassis, le, "Left"), (&right_chassis, ri, "Right")] {
        if (b.point_of(chassis)? - centre).norm() < 1e-6 {
            return Err(Refusal::unusable(
                &[w, &format!("Location {which} Link to Chassis"), &format!("Location {which} Link to Center")],
                format!(
                "\"{w}\" / \"Location {which} Link to Chassis\" and \"Location {which} Link to Center\" coincide: they \
                 are the side link's two ends; give two distinct points"
            ),
            ));
        }
    }
    let at = match pivot {
        WattPivot::DeDion => {
            let at = le + ri / 2.0;
            b.notes.push(format!(
                "{w}: the centre link turns on the tube at [{:.4}, {:.4}, {:.4}], where Chrono's DeDionAxle builds its \
                 joint (Left Link to Center + Right Link to Center / 2, not their midpoint)",
                at.x, at.y, at.z
            ));
            at
        }
        WattPivot::Midpoint => (le + ri) / 2.0,
    };
    b.axle().hardpoints.0.push(("watt_pivot".into(), at));
    b.body("watt centre link", "watt_pivot");
    // Chrono's frame: the chassis's turned a quarter about y, its z (the joint's axis) along x.
    b.joint(
        doc,
        "watt centre link pivot",
        JointKind::Revolute,
        ["watt centre link", AXLE_TUBE],
        Place::named("watt_pivot"),
        Some((-Vec3::z(), Vec3::x())),
        None,
    )?;
    b.link("watt left link", [CHASSIS, "watt centre link"], &left_chassis, &left_centre);
    b.link("watt right link", [CHASSIS, "watt centre link"], &right_chassis, &right_centre);
    b.on_axle(false);
    Ok(())
}

/// `DeDionAxle`.
pub(super) fn read_de_dion(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    axle_tube(doc, b)?;
    wheel_on_tube(doc, b)?;
    guides(doc, b, WattPivot::DeDion)?;
    b.notes.push(
        "Spring: Chrono hangs it on the subchassis when the vehicle has one; a suspension file names none: on the \
         chassis"
            .into(),
    );
    b.spring_and_shock(doc, AXLE_TUBE, "Axle")
}

/// `ToeBarDeDionAxle`.
pub(super) fn read_toe_bar(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    axle_tube(doc, b)?;
    knuckle(doc, b, &[])?;
    guides(doc, b, WattPivot::Midpoint)?;

    toe_bar(doc, b)?;
    knuckle_drag_link(doc, b)?;
    b.spring_and_shock(doc, AXLE_TUBE, "Axle")
}
