//! Chrono's `MultiLink` (`ChMultiLink`): the upper arm on a revolute joint to the chassis (at the midpoint
//! of its pivots, about the pivot axis) and a ball joint to the upright; the lateral link and the trailing
//! link each on a universal joint to the chassis and a ball joint to the upright; the tie rod (see
//! [`super::Builder::tie_rod`]), which Chrono joins to the steering link when the axle is steered and to
//! the chassis otherwise — the corner's steering input either way; the spring and the shock from the chassis
//! to the trailing link. Chrono gives none of these joints bushing data (the tie rod's may have it).
//!
//! A universal joint crosses the file's `Universal Joint Axis Chassis`, a pin fixed in the link, with
//! `Universal Joint Axis Link`, fixed in the chassis (Chrono's `ChLinkUniversal` joins the link's frame x
//! to the chassis's frame y, and builds the frame from those two keys in that order).
//!
//! Steering axis: a multi-link has no kingpin. Its axis is taken from the upper arm's ball joint down to
//! the midpoint of the lateral and trailing links' ball joints on the upright (`steering_axis_lower`), the
//! two lower links standing in for one lower ball joint.

use super::builder::{cross_frame, direction, Builder};
use super::doc::Doc;
use super::error::Refusal;
use crate::description::general::Place;
use crate::description::general::CHASSIS;
use elastokin_core::JointKind;

pub(super) fn read(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    let points = b.arm_points(doc, "Upper Arm", "upper", &["Mass", "COM", "Inertia", "Radius"])?;
    b.arm_joints(
        doc,
        "upper",
        &points,
        None,
        Some(Refusal::unusable(
            &["Upper Arm"],
            "\"Upper Arm\": \"Location Upright\" lies on the line of \"Location Chassis Front\" and \"Location \
             Chassis Back\", or these two coincide: the arm has no plane to turn in; move the upright point off \
             the pivot axis",
        )),
    )?;
    let ball = &points[2];
    let p = |b: &Builder, n: &str| b.general.hardpoints.get(n).ok_or_else(|| Refusal::no_hardpoint(n));
    let mut lower = Vec::new();
    for (link, key, short) in
        [("lateral link", "Lateral", "lateral"), ("trailing link", "Trailing Link", "trailing_link")]
    {
        let inner = b.hardpoint(doc, &format!("{short}_chassis"), &format!("{key}/Location Chassis"))?;
        let outer = b.hardpoint(doc, &format!("{short}_upright"), &format!("{key}/Location Upright"))?;
        let on_link = direction(doc, &format!("{key}/Universal Joint Axis Chassis"))?;
        let on_chassis = direction(doc, &format!("{key}/Universal Joint Axis Link"))?;
        doc.dynamics(key, &["Mass", "COM", "Inertia", "Radius"], &mut b.notes);
        let pins = format!("\"{key}\" / \"Universal Joint Axis Chassis\" and \"Universal Joint Axis Link\"");
        // Chrono builds the joint's frame from the two as given: they must be the cross's perpendicular pins.
        let cosine = on_link.normalize().dot(&on_chassis.normalize());
        if cosine.abs() > 1e-2 {
            return Err(Refusal::unusable(
                &[key, "Universal Joint Axis Chassis", "Universal Joint Axis Link"],
                format!(
                    "{pins} are {:.2}° from perpendicular: they are the two pins of a universal joint's cross; give \
                 perpendicular directions",
                    90.0 - cosine.abs().acos().to_degrees()
                ),
            ));
        }
        let parallel = Refusal::unusable(
            &[key, "Universal Joint Axis Chassis", "Universal Joint Axis Link"],
            format!("{pins} are parallel: give the cross's two pins"),
        );
        let frame = cross_frame(on_link, on_chassis, parallel)?;
        b.body(link, &outer);
        b.joint(
            doc,
            &format!("{link} mount"),
            JointKind::Universal,
            [link, CHASSIS],
            Place::named(&inner),
            Some(frame),
            None,
        )?;
        b.joint(
            doc,
            &format!("{link} ball joint"),
            JointKind::Spherical,
            [link, "upright"],
            Place::named(&outer),
            None,
            None,
        )?;
        lower.push(outer);
    }
    let inner = b.hardpoint(doc, "tie_rod_inner", "Tierod/Location Chassis")?;
    let outer = b.hardpoint(doc, "tie_rod_outer", "Tierod/Location Upright")?;
    b.tie_rod(doc, &inner, &outer)?;
    let virtual_joint = (p(b, &lower[0])? + p(b, &lower[1])?) / 2.0;
    b.general.hardpoints.0.push(("steering_axis_lower".into(), virtual_joint));
    b.steering_axis(("upright", "steering_axis_lower"), ("upright", ball));
    b.spring_and_shock(doc, "trailing link", "Link")
}
