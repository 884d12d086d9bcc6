//! Chrono's `SingleWishbone` (`ChSingleWishbone`): the control arm turns on a revolute joint to the chassis
//! at `Location Chassis` about the chassis's x axis (a bushing there with `Bushing Data`, in Chrono's
//! frame: the chassis turned 90° about y), and the upright turns on it about a vertical revolute joint at
//! `Location Upright` (Chrono's frame there is the chassis's: z up) — the kingpin; the tie rod (see
//! [`super::Builder::tie_rod`]), which Chrono joins to the steering link when the axle is steered and to
//! the chassis otherwise; the shock, Chrono's one spring-damper, from the chassis to the control arm.
//!
//! Steering axis: that kingpin, from the arm's upright joint (`arm_upright`) to `steering_axis_upper`
//! 0.1 m above it, both on the upright.

use super::builder::Builder;
use super::doc::Doc;
use super::error::Refusal;
use crate::description::general::Place;
use crate::description::general::CHASSIS;
use elastokin_core::{JointKind, Vec3};

pub(super) fn read(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    let pivot = b.hardpoint(doc, "arm_chassis", "Control Arm/Location Chassis")?;
    let kingpin = b.hardpoint(doc, "arm_upright", "Control Arm/Location Upright")?;
    doc.dynamics(
        "Control Arm",
        &["Mass", "COM", "Inertia", "Moments of Inertia", "Products of Inertia", "Radius"],
        &mut b.notes,
    );
    b.body("control arm", &kingpin);
    // Chrono's frame at the pivot, Ry(90°): x down, z forward (the hinge).
    b.joint(
        doc,
        "arm pivot",
        JointKind::Revolute,
        [CHASSIS, "control arm"],
        Place::named(&pivot),
        Some((-Vec3::z(), Vec3::x())),
        Some("Control Arm/Bushing Data"),
    )?;
    b.joint(
        doc,
        "kingpin",
        JointKind::Revolute,
        ["control arm", "upright"],
        Place::named(&kingpin),
        Some((Vec3::x(), Vec3::z())),
        None,
    )?;
    let top = b.general.hardpoints.get(&kingpin).ok_or_else(|| Refusal::no_hardpoint("arm_upright"))? + 0.1 * Vec3::z();
    b.general.hardpoints.0.push(("steering_axis_upper".into(), top));
    b.steering_axis(("upright", &kingpin), ("upright", "steering_axis_upper"));
    let inner = b.hardpoint(doc, "tie_rod_inner", "Tierod/Location Chassis")?;
    let outer = b.hardpoint(doc, "tie_rod_outer", "Tierod/Location Upright")?;
    b.tie_rod(doc, &inner, &outer)?;
    b.shock(doc, "spring", [CHASSIS, "control arm"], ["Location Chassis", "Location Arm"])?;
    Ok(())
}
