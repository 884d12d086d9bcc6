//! Chrono's `DoubleWishbone` (`ChDoubleWishbone`) and `DoubleWishboneReduced` (`ChDoubleWishboneReduced`).
//!
//! Full: upper and lower control arms on revolute joints to the chassis (at the midpoint of their pivots,
//! about the pivot axis; a bushing there with `Bushing Data`), ball joints to the upright, the tie rod
//! (see [`super::Builder::tie_rod`]), the spring from the chassis to the lower arm. Reduced: each arm is two
//! distance links from its pivots to its ball joint on the upright, and its `Shock` is the spring-damper
//! from the chassis to the upright.

use super::{arm_frame, midpoint, Builder, Doc, GROUND};
use crate::general::Place;
use elastokin_core::JointKind;

pub(super) fn read(doc: &Doc, b: &mut Builder, reduced: bool) -> Result<(), String> {
    b.wheel(doc)?;
    for (arm, key, short) in [("upper arm", "Upper Control Arm", "upper"), ("lower arm", "Lower Control Arm", "lower")]
    {
        let front = b.hardpoint(doc, &format!("{short}_arm_front"), &format!("{key}/Location Chassis Front"))?;
        let back = b.hardpoint(doc, &format!("{short}_arm_back"), &format!("{key}/Location Chassis Back"))?;
        let ball = b.hardpoint(doc, &format!("{short}_ball_joint"), &format!("{key}/Location Upright"))?;
        doc.dynamics(
            key,
            &["Mass", "COM", "Inertia", "Moments of Inertia", "Products of Inertia", "Radius"],
            &mut b.notes,
        );
        if reduced {
            for (end, pivot) in [("front", &front), ("back", &back)] {
                b.general.joints.push(crate::general::JointDef {
                    name: format!("{arm} {end} link"),
                    kind: JointKind::Distance,
                    bodies: [GROUND.into(), "upright".into()],
                    at: Some(Place::named(pivot)),
                    to: Some(Place::named(&ball)),
                    axis: None,
                    axis_j: None,
                });
            }
            continue;
        }
        b.body(arm, &ball);
        let p = |n: &str| b.general.hardpoints.get(n).expect("read above");
        let frame = arm_frame(p(&front), p(&back), p(&ball));
        let at = midpoint(b, &front, &back)?;
        let bushing = format!("{key}/Bushing Data");
        b.joint(doc, &format!("{arm} pivot"), JointKind::Revolute, [GROUND, arm], at, Some(frame), Some(&bushing))?;
        b.joint(
            doc,
            &format!("{short} ball joint"),
            JointKind::Spherical,
            [arm, "upright"],
            Place::named(&ball),
            None,
            None,
        )?;
    }
    let inner = b.hardpoint(doc, "tie_rod_inner", "Tierod/Location Chassis")?;
    let outer = b.hardpoint(doc, "tie_rod_outer", "Tierod/Location Upright")?;
    b.tie_rod(doc, &inner, &outer)?;
    b.steering_axis(("upright", "lower_ball_joint"), ("upright", "upper_ball_joint"));
    if reduced {
        b.shock(doc, "spring", [GROUND, "upright"], ["Location Chassis", "Location Upright"])?;
    } else {
        b.spring_and_shock(doc, "lower arm", "Arm")?;
    }
    Ok(())
}
