//! Chrono's `DoubleWishbone` (`ChDoubleWishbone`) and `DoubleWishboneReduced` (`ChDoubleWishboneReduced`).
//!
//! Full: upper and lower control arms on revolute joints to the chassis (at the midpoint of their pivots,
//! about the pivot axis; a bushing there with `Bushing Data`), ball joints to the upright, the tie rod
//! (see [`super::Builder::tie_rod`]), the spring from the chassis to the lower arm. Reduced: each arm is two
//! distance links from its pivots to its ball joint on the upright, and its `Shock` is the spring-damper
//! from the chassis to the upright.

use super::builder::Builder;
use super::doc::Doc;
use super::error::Refusal;
use crate::description::general::CHASSIS;

pub(super) fn read(doc: &Doc, b: &mut Builder, reduced: bool) -> Result<(), Refusal> {
    b.wheel(doc)?;
    for (arm, key, short) in [("upper arm", "Upper Control Arm", "upper"), ("lower arm", "Lower Control Arm", "lower")]
    {
        let points = b.arm_points(
            doc,
            key,
            short,
            &["Mass", "COM", "Inertia", "Moments of Inertia", "Products of Inertia", "Radius"],
        )?;
        let [front, back, ball] = &points;
        if reduced {
            for (end, pivot) in [("front", front), ("back", back)] {
                b.link(&format!("{arm} {end} link"), [CHASSIS, "upright"], pivot, ball);
            }
            continue;
        }
        b.arm_joints(doc, short, &points, Some(&format!("{key}/Bushing Data")), None)?;
    }
    let inner = b.hardpoint(doc, "tie_rod_inner", "Tierod/Location Chassis")?;
    let outer = b.hardpoint(doc, "tie_rod_outer", "Tierod/Location Upright")?;
    b.tie_rod(doc, &inner, &outer)?;
    b.steering_axis(("upright", "lower_ball_joint"), ("upright", "upper_ball_joint"));
    if reduced {
        b.shock(doc, "spring", [CHASSIS, "upright"], ["Location Chassis", "Location Upright"])?;
    } else {
        b.spring_and_shock(doc, "lower arm", "Arm")?;
    }
    Ok(())
}
