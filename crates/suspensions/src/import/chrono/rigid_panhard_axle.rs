//! Chrono's rigid Panhard axles: `RigidPanhardAxle` (`ChRigidPanhardAxle`) and `ToeBarRigidPanhardAxle`
//! (`ChToeBarRigidPanhardAxle`). One axle tube carries both wheels; it is guided by a planar joint and a
//! Panhard rod, and carries an anti-roll bar. As for the other solid axles, the model gets an `axle`
//! ([`crate::description::general::AxleDef`]): the tube and what Chrono builds on it once, written as they are in the car;
//! each corner's own parts (its knuckle, its spring) as the left corner, mirrored.
//!
//! - The tube's guide (Chrono's `ChLinkLockPlanar` from the chassis to the tube at `Axle Tube / COM`, its
//!   frame the chassis's turned a quarter about y, so its normal is x) keeps the tube on the plane across
//!   the car: it holds the tube's travel along x and its turn about y and z, and leaves it to rise, slide
//!   sideways and roll. (The class comment in Chrono's header still speaks of a revolute-prismatic joint;
//!   the code builds the planar one.) It is read as an in-plane joint (the chassis's point at the tube's
//!   centre stays on the tube's plane of normal x) and a parallel-axes joint on x.
//! - The Panhard rod (`Panhard Rod`, a body on a ball joint at each end, its two points as given: one on the
//!   tube, one on the chassis across the car) is the distance constraint between its ends; Chrono's free
//!   spin of the rod about its own axis holds nothing. The tube is left two ways to move: bounce and roll.
//! - The anti-roll bar (`Anti Roll Bar`): Chrono builds two halves turning about the lateral axis through
//!   the midpoint of `Location Chassis` and its mirror image, the left on a revolute joint to the chassis,
//!   the right on a revolute joint to the left, with a rotational spring (`Rotational Stiffness`) about
//!   that joint's axis between them; each half's arm ends at `Location Axle`, where a point-plane joint
//!   (`ChLinkLockPointPlane`, frame square to the chassis) keeps the arm's end on the tube's plane of
//!   normal z: it holds the end's height on the tube and lets it slide fore-aft and sideways. The general
//!   model's `anti_roll_bars` join the arm to its corner by a drop link of fixed length (a distance
//!   constraint), which cannot be this zero-length sliding contact; so the bar is built here, on the axle,
//!   as Chrono builds it: the two halves as bodies on those revolute joints, the contact as an in-plane
//!   joint of each arm's end on the tube (normal z), and the spring as a bushing between the halves whose
//!   torsion (about the bar's axis) is the bar's rate, its other rates of the same size acting in
//!   directions the revolute joint between the halves already holds (as `anti_roll_bars` builds its
//!   torsion element), named in the axle's `anti_roll_bar_springs` so that the roll analysis reports the
//!   bar's roll stiffness and share. `Location Chassis` gives the bar's axis (its x and z)
//!   and Chrono's placing of the halves; its y places nothing else. `Rotational Damping` is a damping:
//!   left out.
//! - `RigidPanhardAxle`: the spindle turns on the tube itself: the wheel's upright is welded to the tube at
//!   the wheel centre, nothing steers it, and its steering axis is the wheel's vertical.
//! - `ToeBarRigidPanhardAxle`: a knuckle on a kingpin (revolute, from `Location Upper` to `Location Lower`)
//!   at each end of the tube, the kingpin its steering axis; the tie rod (`Tierod`, the toe bar) across
//!   from knuckle to knuckle, a body on a ball joint on the left and a universal joint on the right, which
//!   only stops the rod spinning on its own axis: the distance constraint between its ends; the drag link
//!   from the steering box (`Draglink / Location Chassis`) to `Knuckle / Location Draglink`, on the left
//!   knuckle, or on the right one at the point as given when its y is negative (as Chrono reads it): a body
//!   on a ball joint and a universal joint (whose frame Chrono takes from the cross product of the two
//!   points' positions, and which only stops its spin), so a rod: the steering input, driven along its own
//!   line. Chrono sets the spindle body square to the chassis but turns its bearing by the camber and toe;
//!   the bearing's axis is the wheel's here (the G500's files give zero for both).
//!
//! Springs (and stops from `Minimum Length` / `Maximum Length`) run from the chassis to the tube on each side
//! (Chrono hangs `RigidPanhardAxle`'s on a subchassis when the vehicle has one; a suspension alone has the
//! chassis); the shocks are dampers.

use super::builder::Builder;
use super::doc::Doc;
use super::error::Refusal;
use super::solid_axle::{knuckle, knuckle_drag_link, toe_bar, wheel_on_tube, AXLE_TUBE};
use crate::description::general::CHASSIS;
use crate::description::general::{Axis, BushingDef, JointDef, Place};
use crate::description::limits::{ROTATIONAL_RATE_RANGE, TRANSLATIONAL_RATE_RANGE};
use crate::description::Side;
use elastokin_core::{JointKind, Vec3};
use elastokin_elements::RotationLaw;

/// The names of the anti-roll bar's halves.
const BAR_HALVES: [&str; 2] = ["anti-roll bar left half", "anti-roll bar right half"];

/// The chassis's −y: the axis (w) of Chrono's frames turned a quarter about x.
const RIGHTWARD: Vec3 = Vec3::new(0.0, -1.0, 0.0);

/// The axle tube (`Axle Tube / COM`) on its planar guide to the chassis, read onto the axle.
fn axle_tube(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.on_axle(true);
    let at = b.hardpoint(doc, "axle_tube", "Axle Tube/COM")?;
    b.body(AXLE_TUBE, &at);
    doc.dynamics("Axle Tube", &["Mass", "Inertia", "Radius"], &mut b.notes);
    // Chrono's frame: the chassis's turned a quarter about y (u = −z, w = x); the plane's normal is w, and
    // the plane is the tube's (the second body's).
    b.joint(
        doc,
        "axle tube guide plane",
        JointKind::InPlane,
        [CHASSIS, AXLE_TUBE],
        Place::named(&at),
        Some((Vec3::new(0.0, 0.0, -1.0), Vec3::x())),
        None,
    )?;
    // The planar joint holds the turns about the plane's two axes: the tube's x stays the chassis's.
    b.axle().joints.push(JointDef {
        name: "axle tube guide axis".into(),
        kind: JointKind::ParallelAxes,
        bodies: [CHASSIS.into(), AXLE_TUBE.into()],
        at: None,
        to: None,
        axis: Some(Axis::Vector(Vec3::x())),
        axis_j: None,
    });
    b.on_axle(false);
    Ok(())
}

/// The Panhard rod, its points as Chrono places them (not mirrored): a distance constraint.
fn panhard_rod(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.on_axle(true);
    let a = b.hardpoint(doc, "panhard_rod_axle", "Panhard Rod/Location Axle")?;
    let c = b.hardpoint(doc, "panhard_rod_chassis", "Panhard Rod/Location Chassis")?;
    doc.dynamics("Panhard Rod", &["Mass", "Inertia", "Radius"], &mut b.notes);
    let along = b.point_of(&c)? - b.point_of(&a)?;
    if along.norm() < 1e-6 {
        return Err(Refusal::unusable(
            &["Panhard Rod", "Location Axle", "Location Chassis"],
            "\"Panhard Rod\" / \"Location Axle\" and \"Location Chassis\" coincide: they are the rod's two \
                    ends, one on the axle tube and one on the chassis across the car; give two distinct points",
        ));
    }
    // A rod along the car does not hold the tube sideways: the tube would slide freely across.
    if along.y.abs() < 1e-6 {
        return Err(Refusal::unusable(
            &["Panhard Rod", "Location Axle", "Location Chassis"],
            format!(
            "\"Panhard Rod\" / \"Location Axle\" and \"Location Chassis\" are at the same y ({:.4} m): the rod holds \
             the axle tube sideways, so it runs across the car, from the tube to the chassis on the other side",
            b.point_of(&a)?.y
        ),
        ));
    }
    b.link("panhard rod", [AXLE_TUBE, CHASSIS], &a, &c);
    b.on_axle(false);
    Ok(())
}

/// The anti-roll bar as Chrono builds it (see the module docs): two halves turning about the lateral axis
/// through the midpoint of `Location Chassis` and its mirror image, a bushing of the bar's rate between
/// them, each arm's end (`Location Axle`) kept on the tube's plane of normal z.
fn anti_roll_bar(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    let chassis = b.hardpoint(doc, "anti_roll_bar_chassis", "Anti Roll Bar/Location Chassis")?;
    let arm_end = b.hardpoint(doc, "anti_roll_bar_axle", "Anti Roll Bar/Location Axle")?;
    doc.dynamics("Anti Roll Bar", &["Mass", "Inertia", "Radius"], &mut b.notes);
    let rate = doc.number("Anti Roll Bar/Rotational Stiffness")?;
    if !rate.is_finite() || rate < 0.0 {
        return Err(Refusal::unusable(
            &["Anti Roll Bar", "Rotational Stiffness"],
            format!(
                "\"Anti Roll Bar\" / \"Rotational Stiffness\" {rate}: the bar's torsional rate (N·m/rad) is a number \
             of zero or more"
            ),
        ));
    }
    if doc.has("Anti Roll Bar/Rotational Damping") {
        doc.expect("Anti Roll Bar/Rotational Damping");
        b.notes.push("Anti Roll Bar / Rotational Damping: damping, left out (statics: no velocity)".into());
    }
    let (least, _) = ROTATIONAL_RATE_RANGE;
    let rate = if rate < least {
        b.notes.push(format!(
            "Anti Roll Bar / Rotational Stiffness: rate {rate} taken as {least} (the least the engine takes: a rate \
             of zero holds nothing)"
        ));
        least
    } else {
        rate
    };
    let (c, a) = (b.point_of(&chassis)?, b.point_of(&arm_end)?);
    // The arm's end moves up and down as the bar turns only when it lies fore or aft of the bar's axis.
    if (a.x - c.x).abs() < 1e-6 {
        return Err(Refusal::unusable(
            &["Anti Roll Bar", "Location Axle", "Location Chassis"],
            format!(
            "\"Anti Roll Bar\" / \"Location Axle\" and \"Location Chassis\" have the same x ({:.4} m): the arm's end \
             at \"Location Axle\" must lie fore or aft of the bar's axis (through \"Location Chassis\", across the \
             car) for the bar to turn as the axle moves; give the arm a length along x",
            a.x
        ),
        ));
    }
    b.on_axle(true);
    let centre = (c + Side::Right.place(c)) / 2.0;
    b.axle().hardpoints.0.push(("anti_roll_bar_centre".into(), centre));
    for (half, side) in BAR_HALVES.iter().zip(["left", "right"]) {
        let on_side = b.point_of(&format!("{side} {chassis}"))?;
        let at = format!("anti_roll_bar_{side}_half");
        b.axle().hardpoints.0.push((at.clone(), (on_side + centre) / 2.0));
        b.body(half, &at);
    }
    // Chrono's frame for both revolute joints: the chassis's turned a quarter about x (u = x, w = −y).
    let frame = Some((Vec3::x(), RIGHTWARD));
    let at = Place::named("anti_roll_bar_centre");
    b.joint(doc, "anti-roll bar bearing", JointKind::Revolute, [CHASSIS, BAR_HALVES[0]], at.clone(), frame, None)?;
    b.joint(doc, "anti-roll bar centre", JointKind::Revolute, BAR_HALVES, at.clone(), frame, None)?;
    let rates = |k: f64| [k.into(), k.into(), k.into()];
    b.axle().bushings.push(BushingDef {
        name: "anti-roll bar".into(),
        bodies: BAR_HALVES.map(str::to_string),
        at,
        axis: Some(Axis::Vector(RIGHTWARD)),
        y_axis: Some(Axis::Vector(Vec3::x())),
        radial: None,
        axial: None,
        torsion: None,
        conical: None,
        translation: Some(rates(rate.max(TRANSLATIONAL_RATE_RANGE.0))),
        rotation: Some(rates(rate)),
        law: RotationLaw::Linear,
        preload_force: None,
        preload_torque: None,
    });
    for (half, side) in BAR_HALVES.iter().zip(["left", "right"]) {
        // Chrono's point-plane frame is the chassis's: the plane's normal is z, on the tube.
        b.joint(
            doc,
            &format!("anti-roll bar {side} contact"),
            JointKind::InPlane,
            [half, AXLE_TUBE],
            Place::named(&format!("{side} {arm_end}")),
            Some((Vec3::x(), Vec3::z())),
            None,
        )?;
    }
    // The roll analysis reports the bar's share of the roll stiffness from this bushing's energy.
    b.axle().anti_roll_bar_springs.push("anti-roll bar".into());
    b.notes.push(format!(
        "Anti Roll Bar: two halves on revolute joints about the lateral axis, a bushing of torsional rate {rate} \
         N·m/rad between them, each arm's end held on the axle tube's horizontal plane (Chrono's point-plane joint)"
    ));
    b.on_axle(false);
    Ok(())
}

/// `RigidPanhardAxle`.
pub(super) fn read_rigid(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    axle_tube(doc, b)?;
    wheel_on_tube(doc, b)?;
    panhard_rod(doc, b)?;
    anti_roll_bar(doc, b)?;
    b.spring_and_shock(doc, AXLE_TUBE, "Axle")
}

/// `ToeBarRigidPanhardAxle`.
pub(super) fn read_toe_bar(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    axle_tube(doc, b)?;
    knuckle(doc, b, &[])?;
    toe_bar(doc, b)?;
    knuckle_drag_link(doc, b)?;
    panhard_rod(doc, b)?;
    anti_roll_bar(doc, b)?;
    b.spring_and_shock(doc, AXLE_TUBE, "Axle")
}
