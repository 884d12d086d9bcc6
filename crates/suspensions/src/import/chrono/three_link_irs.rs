//! Chrono's `ThreeLinkIRS` (`ChThreeLinkIRS`): the trailing arm carries the spindle, so it is the upright;
//! it hangs from the chassis on a ball joint at its front (`Bushing Data Chassis`), and the upper and the
//! lower link each join it with a ball joint (`Bushing Data Arm`) and the chassis with a universal joint
//! (`Bushing Data Chassis`) whose cross is the link's `Universal Joint Axis` (fixed in the link) and, fixed in
//! the chassis, the direction square to it in the vertical plane through it (Chrono's frame: w = axis ×
//! z, v = w × axis); each joint with bushing data is Chrono's bushing there instead. The spring and the
//! shock run from the chassis to the arm. Chrono gives it no tie rod: nothing steers it (`corner.tie_rod`
//! is left out, so the steering analysis is skipped with its reason).
//!
//! Steering axis: the arm has no kingpin; the axis is the wheel's own vertical through its centre (see
//! [`super::Builder::wheel_vertical_steering_axis`]), as for the semi-trailing arm.

use super::builder::{cross_frame, direction, Builder};
use super::doc::Doc;
use super::error::Refusal;
use crate::description::general::Place;
use crate::description::general::CHASSIS;
use elastokin_core::{JointKind, Vec3};

pub(super) fn read(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    let pivot = b.hardpoint(doc, "arm_chassis", "Trailing Arm/Location Chassis")?;
    // The arm's shape only (Chrono orients the arm's body by it): kept as a hardpoint for reference.
    b.hardpoint(doc, "arm_spindle", "Trailing Arm/Location Spindle")?;
    doc.dynamics("Trailing Arm", &["Mass", "COM", "Inertia", "Radius"], &mut b.notes);
    b.joint(
        doc,
        "trailing arm pivot",
        JointKind::Spherical,
        [CHASSIS, "upright"],
        Place::named(&pivot),
        None,
        Some("Trailing Arm/Bushing Data Chassis"),
    )?;
    for (link, key, short) in [("upper link", "Upper Link", "upper_link"), ("lower link", "Lower Link", "lower_link")] {
        let chassis = b.hardpoint(doc, &format!("{short}_chassis"), &format!("{key}/Location Chassis"))?;
        let arm = b.hardpoint(doc, &format!("{short}_arm"), &format!("{key}/Location Arm"))?;
        let pin = direction(doc, &format!("{key}/Universal Joint Axis"))?;
        doc.dynamics(key, &["Mass", "COM", "Inertia", "Radius"], &mut b.notes);
        let frame = cross_frame(
            pin,
            Vec3::z(),
            Refusal::unusable(
                &[key, "Universal Joint Axis"],
                format!(
                    "\"{key}\" / \"Universal Joint Axis\" is vertical: Chrono crosses it with the vertical; give \
                     the link's pin a horizontal direction"
                ),
            ),
        )?;
        b.body(link, &arm);
        b.joint(
            doc,
            &format!("{link} ball joint"),
            JointKind::Spherical,
            [link, "upright"],
            Place::named(&arm),
            None,
            Some(&format!("{key}/Bushing Data Arm")),
        )?;
        b.joint(
            doc,
            &format!("{link} mount"),
            JointKind::Universal,
            [link, CHASSIS],
            Place::named(&chassis),
            Some(frame),
            Some(&format!("{key}/Bushing Data Chassis")),
        )?;
    }
    b.wheel_vertical_steering_axis()?;
    b.spring_and_shock(doc, "upright", "Arm")
}
