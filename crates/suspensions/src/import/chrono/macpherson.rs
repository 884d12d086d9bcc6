//! Chrono's `MacPhersonStrut` (`ChMacPhersonStrut`): the control arm on a revolute joint to the chassis (at
//! the midpoint of its pivots; a bushing there with `Bushing Data`) and a ball joint to the upright; the
//! strut on a universal joint to the chassis at the spring's upper point, the upright sliding and turning
//! on it (cylindrical joint along the spring axis), so the upright steers about the strut; the tie rod; the
//! spring from the chassis to the upright.

use super::builder::Builder;
use super::doc::Doc;
use super::error::Refusal;
use crate::description::general::Place;
use crate::description::general::CHASSIS;
use elastokin_core::JointKind;

pub(super) fn read(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    let points = b.arm_points(doc, "Control Arm", "lower", &["Mass", "COM", "Inertia", "Radius"])?;
    doc.dynamics("Strut", &["Mass", "Inertia", "Radius"], &mut b.notes);
    let top = b.hardpoint(doc, "strut_top", "Spring/Location Chassis")?;
    let lower = b.hardpoint(doc, "strut_lower", "Spring/Location Upright")?;
    b.arm_joints(doc, "lower", &points, Some("Control Arm/Bushing Data"), None)?;
    b.body("strut", &top);
    let [_, back, ball] = &points;
    let p = |b: &Builder, n: &str| b.general.hardpoints.get(n).expect("read above");
    // Chrono's strut frame: w along the strut (up), v normal to the plane of the strut and the arm's back
    // pivot, u = v × w.
    let w = (p(b, &top) - p(b, &lower)).normalize();
    let v = (p(b, &lower) - p(b, back)).cross(&(p(b, &top) - p(b, back))).normalize();
    let strut_frame = (v.cross(&w), w);
    b.joint(
        doc,
        "strut slide",
        JointKind::Cylindrical,
        ["strut", "upright"],
        Place::named(&lower),
        Some(strut_frame),
        None,
    )?;
    b.joint(doc, "top mount", JointKind::Universal, [CHASSIS, "strut"], Place::named(&top), Some(strut_frame), None)?;
    let inner = b.hardpoint(doc, "tie_rod_inner", "Tierod/Location Chassis")?;
    let outer = b.hardpoint(doc, "tie_rod_outer", "Tierod/Location Upright")?;
    b.tie_rod(doc, &inner, &outer)?;
    b.steering_axis(("upright", ball), ("strut", &top));
    b.spring(doc, "Spring", "spring", [CHASSIS, "upright"], [&top, &lower])?;
    b.shock(doc, "shock", [CHASSIS, "upright"], ["Location Chassis", "Location Upright"])?;
    Ok(())
}
