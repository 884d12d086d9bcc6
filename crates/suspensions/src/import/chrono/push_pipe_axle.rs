//! Chrono's push-pipe axles: `PushPipeAxle` (`ChPushPipeAxle`) and `ToeBarPushPipeAxle`
//! (`ChToeBarPushPipeAxle`). One axle tube carries both wheels and a push pipe (torque tube) forward or back
//! to a ball joint on the chassis; a Panhard rod holds it across. The model gets an `axle`
//! ([`crate::description::general::AxleDef`]): the tube, its ball joint and the Panhard rod are written as they are in
//! the car, each corner's own parts (its spring, its knuckle) as the left corner, mirrored.
//!
//! - The push pipe: a ball joint from the tube to the chassis at `Axle Tube / Location Connector Chassis`,
//!   the point as given (Chrono does not mirror it; it lies on the centre plane).
//! - The Panhard rod: Chrono's rod body on a ball joint at each end (`Panhard Rod / Location Connector
//!   Axle` on the tube, `… Chassis` on the chassis, both as given, not mirrored). The rod spinning on its own
//!   axis holds nothing: it is the distance constraint between its ends. Ball joint and rod leave the tube
//!   two ways to move, the wheels' travel (pitch about the ball joint) and roll.
//! - `PushPipeAxle`: the spindle turns on the tube itself: the wheel's upright is welded to the tube at
//!   the wheel centre, and nothing steers it; its steering axis is the wheel's vertical (as a trailing
//!   arm's).
//! - `ToeBarPushPipeAxle`: a knuckle (the upright) on a kingpin (revolute, from `Knuckle / Location Lower`
//!   to `Location Upper`, in Chrono's frame) at each end of the tube; the kingpin is the steering axis. The
//!   toe bar (`Tierod`) across, knuckle to knuckle, is Chrono's rod body on a ball joint at the left
//!   knuckle and a universal joint at the right one: the universal only stops the rod spinning on its own
//!   axis, so the rod is the distance constraint between its ends. The drag link, Chrono's body on a ball
//!   joint at the steering box (`Draglink / Location Chassis`, as given) and a universal joint at the
//!   knuckle's arm (`Knuckle / Location Draglink`), is likewise a rod; it is the steering input, driven
//!   along its own line (a pitman arm's end moves across its arm). Chrono's frame for that universal is
//!   built from the cross product of the two points' positions (it depends on where the origin is), but
//!   it turns only the link's spin, which holds nothing. As in Chrono, the drag link acts on the left
//!   knuckle when the point's y is positive or zero, on the right knuckle (the point as given) when it is
//!   negative.
//! - The spring (and the stops of `Minimum Length` / `Maximum Length`, unless crossed: below) and the shock
//!   of each side run from the chassis to the tube. `Axle Tube / Portal Offset` only moves the drawn tube:
//!   read, left out.
//!
//! # Crossed stops
//!
//! The UAZ bus's files give `Minimum Length` 0.28 m above `Maximum Length` 0.12 m, about a spring 0.2 m long
//! at design: read as Chrono builds it, the two stops press at once, 80 mm deep, cancel between 0.18 and
//! 0.22 m and stop the spring within 10 mm outside that (±20 mm of travel), where the data evidently mean
//! stops 80 mm either side. [`super::Builder::spring`] refuses such a pair by name, with the two swapped as the fix.
//! (Read as Chrono builds it, the vertical-force sweep could not even start: from design, its first Newton
//! iterate at half the design load lands 11 mm into a stop that has flattened from 11 MN/m to 0.5 MN/m.)

use super::builder::Builder;
use super::doc::Doc;
use super::error::Refusal;
use super::solid_axle::{knuckle, knuckle_drag_link, toe_bar, wheel_on_tube, AXLE_TUBE};
use crate::description::general::Place;
use crate::description::general::CHASSIS;
use elastokin_core::JointKind;

/// The axle tube (`Axle Tube / COM`) on its push pipe's ball joint to the chassis, and the Panhard rod:
/// read onto the axle.
fn tube_push_pipe_and_panhard_rod(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.on_axle(true);
    let at = b.hardpoint(doc, "axle_tube", "Axle Tube/COM")?;
    b.body(AXLE_TUBE, &at);
    doc.dynamics("Axle Tube", &["Mass", "Inertia", "Radius"], &mut b.notes);
    doc.left_out("Axle Tube", &["Portal Offset"], "the drawn tube's height at the wheels: drawing only", &mut b.notes);
    let pipe = b.hardpoint(doc, "push_pipe_chassis", "Axle Tube/Location Connector Chassis")?;
    b.joint(doc, "push pipe ball joint", JointKind::Spherical, [AXLE_TUBE, CHASSIS], Place::named(&pipe), None, None)?;
    let on_axle = b.hardpoint(doc, "panhard_rod_axle", "Panhard Rod/Location Connector Axle")?;
    let on_chassis = b.hardpoint(doc, "panhard_rod_chassis", "Panhard Rod/Location Connector Chassis")?;
    if (b.point_of(&on_axle)? - b.point_of(&on_chassis)?).norm() < 1e-6 {
        return Err(Refusal::unusable(
            &["Panhard Rod", "Location Connector Axle", "Location Connector Chassis"],
            "\"Panhard Rod\" / \"Location Connector Axle\" and \"Location Connector Chassis\" coincide: \
                    they are the rod's two ends; give two distinct points",
        ));
    }
    doc.dynamics("Panhard Rod", &["Mass", "Inertia", "Radius"], &mut b.notes);
    b.link("panhard rod", [AXLE_TUBE, CHASSIS], &on_axle, &on_chassis);
    b.on_axle(false);
    Ok(())
}

/// The spring and the shock of each side, from the chassis to the tube.
fn spring_and_shock(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.spring_and_shock(doc, AXLE_TUBE, "Axle")
}

/// `PushPipeAxle`.
pub(super) fn read_push_pipe(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    tube_push_pipe_and_panhard_rod(doc, b)?;
    wheel_on_tube(doc, b)?;
    spring_and_shock(doc, b)
}

/// `ToeBarPushPipeAxle`.
pub(super) fn read_toe_bar(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    tube_push_pipe_and_panhard_rod(doc, b)?;
    knuckle(doc, b, &[])?;
    toe_bar(doc, b)?;
    knuckle_drag_link(doc, b)?;
    spring_and_shock(doc, b)
}
