//! Chrono's `SemiTrailingArm` (`ChSemiTrailingArm`): the trailing arm carries the spindle, so it is the
//! upright; it turns on a revolute joint to the chassis at the midpoint of its two pivots, about the line
//! from the inner pivot to the outer one (a bushing there with `Bushing Data`, in Chrono's frame: y normal
//! to the plane of the pivots and `Location Spindle`); the spring and the shock from the chassis to the arm.
//! Chrono gives it no tie rod: nothing steers it (`corner.tie_rod` is left out, so the steering analysis is
//! skipped with its reason).
//!
//! Steering axis: the arm has no kingpin; the axis is the wheel's own vertical through its centre (see
//! [`super::Builder::wheel_vertical_steering_axis`]).

use super::builder::{checked_frame, midpoint, Builder};
use super::doc::Doc;
use super::error::Refusal;
use crate::description::general::CHASSIS;
use elastokin_core::JointKind;

pub(super) fn read(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    let outer = b.hardpoint(doc, "arm_chassis_outer", "Trailing Arm/Location Chassis Outer")?;
    let inner = b.hardpoint(doc, "arm_chassis_inner", "Trailing Arm/Location Chassis Inner")?;
    let spindle = b.hardpoint(doc, "arm_spindle", "Trailing Arm/Location Spindle")?;
    doc.dynamics("Trailing Arm", &["Mass", "COM", "Inertia", "Radius"], &mut b.notes);
    let p = |n: &str| b.general.hardpoints.get(n).ok_or_else(|| Refusal::no_hardpoint(n));
    let (o, i, s) = (p(&outer)?, p(&inner)?, p(&spindle)?);
    // Chrono's pivot frame: w from the inner pivot to the outer, v normal to the arm's plane, u = v × w.
    let v = (o - s).cross(&(i - s)).normalize();
    let w = (o - i).normalize();
    let frame = checked_frame(
        (v.cross(&w), w),
        Refusal::unusable(
            &["Trailing Arm"],
            "\"Trailing Arm\": \"Location Spindle\" lies on the line of \"Location Chassis Outer\" and \"Location \
         Chassis Inner\", or these two coincide: the arm has no plane for its pivot's frame; move the spindle \
         point off the pivot axis",
        ),
    )?;
    let at = midpoint(b, &outer, &inner)?;
    b.joint(
        doc,
        "trailing arm pivot",
        JointKind::Revolute,
        [CHASSIS, "upright"],
        at,
        Some(frame),
        Some("Trailing Arm/Bushing Data"),
    )?;
    b.wheel_vertical_steering_axis()?;
    b.spring_and_shock(doc, "upright", "Arm")
}
