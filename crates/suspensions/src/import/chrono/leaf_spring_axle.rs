//! Chrono's leaf-spring axles: `LeafspringAxle` (`ChLeafspringAxle`) and `ToeBarLeafspringAxle`
//! (`ChToeBarLeafspringAxle`). Chrono does not model the leaf as a beam in these templates: the axle tube
//! rides on a guide to the chassis and is carried by a coil spring on each side, so they read into joints
//! and springs. One tube carries both wheels: the model gets an `axle` ([`crate::description::general::AxleDef`]) with
//! the tube, its guide and what Chrono builds once across, and each corner's own parts (its knuckle, its
//! spring) as the left corner, mirrored.
//!
//! - The guide (`ChLinkLockRevolutePrismatic` between the chassis and the tube, at `Axle Tube / COM`, its
//!   frame the chassis's turned a quarter about y: x down, z forward) locks the link coordinates y, z and the
//!   rotations about x and y: the tube slides along the frame's x and turns about its z. Chrono measures
//!   the offset of the chassis's marker from the tube's in the tube's marker frame (`ChLinkMarkers`), so the
//!   chassis's point stays on the tube's vertical line through that point, which turns with the tube: an
//!   `in_line` joint whose line is the tube's (`[chassis, axle tube]`, the point on the first body, the line
//!   on the second), and a `parallel_axes` joint keeping the tube's forward axis along the chassis's. The
//!   tube then travels and rolls; it does not pitch, yaw, or move sideways or fore and aft.
//! - `LeafspringAxle`: the spindle turns on the tube itself (a revolute joint), so the wheel's upright is
//!   welded to the tube at the wheel centre and nothing steers it; the steering axis is the wheel's
//!   vertical. Chrono joins the spring to a subchassis beam when the vehicle has one; in a suspension file
//!   alone it is the chassis.
//! - `ToeBarLeafspringAxle`: a knuckle on a kingpin (revolute, from `Location Upper` to `Location Lower`,
//!   Chrono's frame: w down the kingpin, u normal to the plane of the kingpin and the spindle) at each end
//!   of the tube; the toe bar (`Tierod`) across from knuckle to knuckle, a body on a ball joint on the left
//!   and a universal joint on the right (which only stops the rod spinning on its own axis): the distance
//!   between its two ends; the drag link from the steering link (`Draglink / Location Chassis`, as given) to
//!   the knuckle's arm (`Knuckle / Location Draglink`, as given: the left knuckle's when its y is not
//!   negative, else the right one's), a body on a ball joint at the steering end and a universal joint at
//!   the knuckle: the axle's steering input, driven along its own line (a pitman arm's end moves across
//!   its arm). The steering axis is the kingpin. Chrono reads the knuckle's centre of mass as a point and
//!   places the knuckle's body there; statics has no use for it.
//!
//! Springs (and stops from `Minimum Length` / `Maximum Length`) run from the chassis to the tube on each
//! side; the shocks are dampers, left out.

use super::builder::Builder;
use super::doc::Doc;
use super::error::Refusal;
use super::solid_axle::{knuckle, knuckle_drag_link, toe_bar, wheel_on_tube, AXLE_TUBE};
use crate::description::general::CHASSIS;
use crate::description::general::{Axis, JointDef, Place};
use elastokin_core::{JointKind, Vec3};

/// The axle tube (`Axle Tube / COM`) on Chrono's guide to the chassis, read onto the axle.
fn axle_tube_on_guide(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.on_axle(true);
    let at = b.hardpoint(doc, "axle_tube", "Axle Tube/COM")?;
    b.body(AXLE_TUBE, &at);
    doc.dynamics("Axle Tube", &["Mass", "Inertia", "Radius"], &mut b.notes);
    // The guide's frame: x along the chassis's −z (its slide), z along the chassis's x (its turn).
    let (slide, turn) = (-Vec3::z(), Vec3::x());
    b.joint(doc, "axle guide", JointKind::InLine, [CHASSIS, AXLE_TUBE], Place::named(&at), Some((slide, turn)), None)?;
    b.axle().joints.push(JointDef {
        name: "axle guide roll axis".into(),
        kind: JointKind::ParallelAxes,
        bodies: [CHASSIS.into(), AXLE_TUBE.into()],
        at: None,
        to: None,
        axis: Some(Axis::Vector(turn)),
        axis_j: None,
    });
    b.notes.push(
        "Axle Tube: on Chrono's revolute-prismatic guide to the chassis, an in-line joint (the tube slides along \
         its vertical through its COM) and a parallel-axes joint (it turns only about the forward axis)"
            .into(),
    );
    b.on_axle(false);
    Ok(())
}

/// `LeafspringAxle`.
pub(super) fn read_leaf_spring_axle(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    axle_tube_on_guide(doc, b)?;
    wheel_on_tube(doc, b)?;
    b.spring_and_shock(doc, AXLE_TUBE, "Axle")
}

/// `ToeBarLeafspringAxle`.
pub(super) fn read_toe_bar_leaf_spring_axle(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    axle_tube_on_guide(doc, b)?;
    knuckle(doc, b, &[])?;
    toe_bar(doc, b)?;
    knuckle_drag_link(doc, b)?;
    b.spring_and_shock(doc, AXLE_TUBE, "Axle")
}
