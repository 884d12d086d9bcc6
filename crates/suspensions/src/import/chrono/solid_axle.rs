//! Chrono's solid axles: `SolidAxle` (`ChSolidAxle`), `SolidThreeLinkAxle` (`ChSolidThreeLinkAxle`) and
//! `SolidBellcrankThreeLinkAxle` (`ChSolidBellcrankThreeLinkAxle`). One axle tube carries both wheels, so
//! the model gets an `axle` ([`crate::description::general::AxleDef`]): the tube and what Chrono builds on it once are
//! written as they are in the car, and each corner's own parts (its links, its knuckle, its spring) as the
//! left corner, mirrored. Every corner analysis then moves and loads both wheels alike.
//!
//! - A link that Chrono builds as a body on a ball joint at one end and a universal joint at the other (the
//!   universal only stops the link spinning on its own axis) is the distance constraint between its ends,
//!   which holds the axle the same way; so is a rod on two ball joints (Chrono's free spin of such a rod
//!   holds nothing).
//! - `SolidAxle`: four links from the chassis to the tube, a Panhard rod (`Trackbar`, its two points as
//!   given: one on the tube, one on the chassis across the car), a knuckle on a kingpin (revolute, from
//!   `Location Upper` to `Location Lower`) at each end of the tube, one tie rod across from knuckle to
//!   knuckle (a body: a ball joint on the left, a universal joint on the right whose cross is x and z), a
//!   bell crank on the tube turning about the vertical (Chrono's frame for that joint, though it builds
//!   another from the crank's points and does not use it), holding the tie rod by a point-plane joint
//!   (the crank's point stays on the rod's plane normal to y), and the drag link from the steering box to
//!   the crank: the steering input, driven along its own line (a pitman arm's end moves across its arm).
//! - `SolidThreeLinkAxle`: a triangular link on a revolute joint to the chassis about y at the midpoint of
//!   its two chassis points, a ball joint to the tube at the midpoint of its axle points; two longitudinal
//!   links. The spindle turns on the tube itself: the wheel's upright is welded to the tube at the wheel
//!   centre, and nothing steers it.
//! - `SolidBellcrankThreeLinkAxle`: the three-link axle with knuckles on kingpins, a bell crank on the tube
//!   turning about the vertical, a tie rod from the crank to each knuckle, and the drag link from the
//!   steering box to the crank.
//!
//! Springs (and stops from `Minimum Length` / `Maximum Length`) run from the chassis to the tube on each side.
//! Steering axis: the kingpin where there is one, else the wheel's vertical (as for a trailing arm).

use super::builder::{midpoint, Builder};
use super::doc::Doc;
use super::error::Refusal;
use crate::description::general::CHASSIS;
use crate::description::general::{Place, SteeringLinkDef};
use crate::description::Side;
use elastokin_core::{JointKind, Vec3};

/// The name of the axle tube.
pub(super) const AXLE_TUBE: &str = "axle tube";

/// The axle tube (`Axle Tube / COM`), read onto the axle.
pub(super) fn axle_tube(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.on_axle(true);
    let at = b.hardpoint(doc, "axle_tube", "Axle Tube/COM")?;
    b.body(AXLE_TUBE, &at);
    doc.dynamics("Axle Tube", &["Mass", "Inertia", "Radius"], &mut b.notes);
    b.on_axle(false);
    Ok(())
}

/// The wheel turning on the tube itself: the corner's upright welded to the tube at the wheel centre, its
/// steering axis the wheel's vertical (nothing steers it).
pub(super) fn wheel_on_tube(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.joint(
        doc,
        "spindle housing",
        JointKind::Fixed,
        [AXLE_TUBE, "upright"],
        Place::named("wheel_centre"),
        None,
        None,
    )?;
    b.wheel_vertical_steering_axis()
}

/// The knuckle (the upright) on its kingpin to the tube from `Knuckle / Location Lower` to `Location Upper`,
/// the kingpin its steering axis; `extra` are the knuckle's further keys that statics leaves out.
pub(super) fn knuckle(doc: &Doc, b: &mut Builder, extra: &[&str]) -> Result<(), Refusal> {
    kingpin(doc, b, ["Location Lower", "Location Upper"], AXLE_TUBE, extra)
}

/// The knuckle (the upright) on a kingpin to `on`, between `Knuckle / <keys[0]>` (lower) and `Knuckle /
/// <keys[1]>` (upper, hardpoints `knuckle_lower`, `knuckle_upper`), in Chrono's frame: w down the kingpin, u
/// normal to the plane of the kingpin and the spindle (any normal to the kingpin when the spindle is on it:
/// a revolute joint turns about w alone); the kingpin is the steering axis.
pub(super) fn kingpin(doc: &Doc, b: &mut Builder, keys: [&str; 2], on: &str, extra: &[&str]) -> Result<(), Refusal> {
    let lower = b.hardpoint(doc, "knuckle_lower", &format!("Knuckle/{}", keys[0]))?;
    let upper = b.hardpoint(doc, "knuckle_upper", &format!("Knuckle/{}", keys[1]))?;
    let mut dynamics = vec!["Mass", "COM", "Inertia", "Radius"];
    dynamics.extend_from_slice(extra);
    doc.dynamics("Knuckle", &dynamics, &mut b.notes);
    let (l, u, s) = (b.point_of(&lower)?, b.point_of(&upper)?, b.point_of("wheel_centre")?);
    let w = l - u;
    if w.norm() < 1e-6 {
        return Err(Refusal::unusable(
            &["Knuckle", keys[0], keys[1]],
            format!(
                "\"Knuckle\" / \"{}\" and \"{}\" coincide: they are the kingpin's two ends; give two distinct points",
                keys[0], keys[1]
            ),
        ));
    }
    let u_axis = (u - s).cross(&(l - s));
    let u_axis = if u_axis.norm() > 1e-9 {
        u_axis.normalize()
    } else {
        elastokin_core::joint::orthonormal_complement(&w.normalize()).0
    };
    let at = midpoint(b, &upper, &lower)?;
    b.joint(doc, "kingpin", JointKind::Revolute, [on, "upright"], at, Some((u_axis, w.normalize())), None)?;
    b.steering_axis(("upright", &lower), ("upright", &upper));
    Ok(())
}

/// The toe bar across, from the left knuckle's `Tierod / Location Knuckle` to its mirror image on the right:
/// Chrono's rod on a ball joint and a universal joint (which only stops its spin), a distance link.
pub(super) fn toe_bar(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    let end = b.hardpoint(doc, "tie_rod_knuckle", "Tierod/Location Knuckle")?;
    doc.dynamics("Tierod", &["Mass", "Inertia", "Radius"], &mut b.notes);
    let p = b.point_of(&end)?;
    if p.y.abs() < 1e-6 {
        return Err(Refusal::unusable(
            &["Tierod", "Location Knuckle"],
            format!(
                "\"Tierod\" / \"Location Knuckle\" [{:?}, {:?}, {:?}] is on the centre line: the toe bar runs from \
             the left knuckle's point to its mirror image on the right; give the left knuckle's point (y > 0)",
                p.x, p.y, p.z
            ),
        ));
    }
    b.on_axle(true);
    b.link("tie rod", ["left upright", "right upright"], &format!("left {end}"), &format!("right {end}"));
    b.on_axle(false);
    Ok(())
}

/// The drag link from the steering box (`Draglink / Location Chassis`) to a knuckle's arm (`Knuckle /
/// Location Draglink`, on the left knuckle, or on the right one at the point as given when its y is negative,
/// as Chrono reads it): the axle's steering input, moved along its own line.
pub(super) fn knuckle_drag_link(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.on_axle(true);
    let inner = b.hardpoint(doc, "drag_link_steering", "Draglink/Location Chassis")?;
    let outer = b.hardpoint(doc, "drag_link_knuckle", "Knuckle/Location Draglink")?;
    doc.dynamics("Draglink", &["Mass", "Inertia", "Radius"], &mut b.notes);
    let (p, q) = (b.point_of(&inner)?, b.point_of(&outer)?);
    let along = q - p;
    if along.norm() < 1e-6 {
        return Err(Refusal::unusable(
            &["Draglink", "Location Chassis", "Knuckle", "Location Draglink"],
            "\"Draglink\" / \"Location Chassis\" and \"Knuckle\" / \"Location Draglink\" coincide: they are \
                    the drag link's two ends; give two distinct points",
        ));
    }
    // Chrono: a negative y puts the drag link on the right knuckle, at the point as given.
    let side = if q.y < 0.0 { "right" } else { "left" };
    let axis = along.normalize();
    b.axle().steering_link = Some(SteeringLinkDef {
        body: format!("{side} upright"),
        inner: Place::named(&inner),
        outer: Place::named(&outer),
        connection: crate::description::Connection::Ideal.into(),
        rack_axis: [axis.x, axis.y, axis.z],
    });
    b.notes.push(format!(
        "Draglink: the steering input, on the {side} knuckle; the steering analysis moves its steering-box end along \
         the drag link"
    ));
    b.on_axle(false);
    Ok(())
}

/// Chrono's `Triangular Link` and `Longitudinal Link`s of a three-link axle.
fn three_links(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    let chassis = b.hardpoint(doc, "triangle_chassis", "Triangular Link/Location Chassis")?;
    let axle = b.hardpoint(doc, "triangle_axle", "Triangular Link/Location Axle")?;
    doc.dynamics("Triangular Link", &["Mass", "Inertia"], &mut b.notes);
    // Chrono joins the triangle at the midpoints of the left points and their mirror images.
    let centred = |p: Vec3| (p + Side::Right.place(p)) / 2.0;
    let (pivot, apex) = (centred(b.point_of(&chassis)?), centred(b.point_of(&axle)?));
    b.on_axle(true);
    b.axle().hardpoints.0.push(("triangle_pivot".into(), pivot));
    b.axle().hardpoints.0.push(("triangle_apex".into(), apex));
    b.axle().hardpoints.0.push(("triangle_centre".into(), (pivot + apex) / 2.0));
    b.body("triangular link", "triangle_centre");
    b.joint(
        doc,
        "triangular link pivot",
        JointKind::Revolute,
        ["triangular link", CHASSIS],
        Place::named("triangle_pivot"),
        Some((Vec3::x(), -Vec3::y())),
        None,
    )?;
    b.joint(
        doc,
        "triangular link ball joint",
        JointKind::Spherical,
        ["triangular link", AXLE_TUBE],
        Place::named("triangle_apex"),
        None,
        None,
    )?;
    b.on_axle(false);
    let c = b.hardpoint(doc, "link_chassis", "Longitudinal Link/Location Chassis")?;
    let a = b.hardpoint(doc, "link_axle", "Longitudinal Link/Location Axle")?;
    doc.dynamics("Longitudinal Link", &["Mass", "Inertia", "Radius"], &mut b.notes);
    b.link("longitudinal link", [CHASSIS, AXLE_TUBE], &c, &a);
    Ok(())
}

/// The drag link from `Draglink / <steering>` on the steering box to `Draglink / <crank>` on the crank body
/// `crank`: the axle's steering input, moved along its own line.
fn drag_link(doc: &Doc, b: &mut Builder, crank: &str, (steering, on_crank): (&str, &str)) -> Result<(), Refusal> {
    b.on_axle(true);
    let inner = b.hardpoint(doc, "drag_link_steering", &format!("Draglink/{steering}"))?;
    let outer = b.hardpoint(doc, "drag_link_crank", &format!("Draglink/{on_crank}"))?;
    doc.dynamics("Draglink", &["Mass", "Inertia", "Radius"], &mut b.notes);
    let along = b.point_of(&outer)? - b.point_of(&inner)?;
    if along.norm() < 1e-6 {
        return Err(Refusal::unusable(
            &["Draglink", steering, on_crank],
            format!(
            "\"Draglink\" / \"{steering}\" and \"{on_crank}\" coincide: they are the drag link's two ends; give two \
             distinct points"
        ),
        ));
    }
    let axis = along.normalize();
    b.axle().steering_link = Some(SteeringLinkDef {
        body: crank.into(),
        inner: Place::named(&inner),
        outer: Place::named(&outer),
        connection: crate::description::Connection::Ideal.into(),
        rack_axis: [axis.x, axis.y, axis.z],
    });
    b.notes.push(
        "Draglink: the steering input; the steering analysis moves its steering-box end along the drag link".into(),
    );
    b.on_axle(false);
    Ok(())
}

/// The spring (and its stops) and the shock of each side, from the chassis to the tube.
fn spring_and_shock(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.spring_and_shock(doc, AXLE_TUBE, "Axle")
}

/// `SolidAxle`.
pub(super) fn read_solid_axle(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    axle_tube(doc, b)?;
    knuckle(doc, b, &[])?;
    for (key, short) in [("Upper Link", "upper_link"), ("Lower Link", "lower_link")] {
        let c = b.hardpoint(doc, &format!("{short}_chassis"), &format!("{key}/Location Chassis"))?;
        let a = b.hardpoint(doc, &format!("{short}_axle"), &format!("{key}/Location Axle"))?;
        doc.dynamics(key, &["Mass", "COM", "Inertia", "Radius"], &mut b.notes);
        b.link(&key.to_lowercase(), [CHASSIS, AXLE_TUBE], &c, &a);
    }
    let knuckle_tie_rod = b.hardpoint(doc, "tie_rod_knuckle", "Tierod/Location Knuckle")?;
    doc.dynamics("Tierod", &["Mass", "Inertia", "Radius"], &mut b.notes);
    b.on_axle(true);
    // The Panhard rod, its points as Chrono places them: not mirrored. Chrono's code builds it always;
    // a file without one (the city bus's) would leave it at the origin, so it is left out.
    if doc.has("Trackbar") {
        let a = b.hardpoint(doc, "trackbar_axle", "Trackbar/Location Axle")?;
        let c = b.hardpoint(doc, "trackbar_chassis", "Trackbar/Location Chassis")?;
        doc.dynamics("Trackbar", &["Mass", "Inertia", "Radius"], &mut b.notes);
        b.link("trackbar", [AXLE_TUBE, CHASSIS], &a, &c);
    } else {
        b.notes.push("Trackbar: not in the file; the axle has no Panhard rod".into());
    }
    // The tie rod across, knuckle to knuckle.
    let (left, right) = (format!("left {knuckle_tie_rod}"), format!("right {knuckle_tie_rod}"));
    let centre = (b.point_of(&left)? + b.point_of(&right)?) / 2.0;
    b.axle().hardpoints.0.push(("tie_rod_centre".into(), centre));
    b.body("tie rod", "tie_rod_centre");
    b.joint(
        doc,
        "tie rod left joint",
        JointKind::Spherical,
        ["tie rod", "left upright"],
        Place::named(&left),
        None,
        None,
    )?;
    // Chrono's frame: the chassis's turned a quarter about x (u = x, v = z, w = −y); the cross is u and v.
    b.joint(
        doc,
        "tie rod right joint",
        JointKind::Universal,
        ["tie rod", "right upright"],
        Place::named(&right),
        Some((Vec3::x(), -Vec3::y())),
        None,
    )?;
    b.on_axle(false);
    drag_link(doc, b, "bell crank", ("Location Chassis", "Location Bell Crank"))?;
    b.on_axle(true);
    let crank_axle = b.hardpoint(doc, "bell_crank_axle", "Bell Crank/Location Axle")?;
    let crank_tie_rod = b.hardpoint(doc, "bell_crank_tie_rod", "Bell Crank/Location Tierod")?;
    doc.dynamics("Bell Crank", &["Mass", "Inertia", "Radius"], &mut b.notes);
    let corners = [b.point_of("drag_link_crank")?, b.point_of(&crank_axle)?, b.point_of(&crank_tie_rod)?];
    b.axle().hardpoints.0.push(("bell_crank_centre".into(), corners.iter().sum::<Vec3>() / 3.0));
    b.body("bell crank", "bell_crank_centre");
    b.joint(
        doc,
        "bell crank pivot",
        JointKind::Revolute,
        ["bell crank", AXLE_TUBE],
        Place::named(&crank_axle),
        Some((Vec3::x(), Vec3::z())),
        None,
    )?;
    b.joint(
        doc,
        "bell crank tie rod joint",
        JointKind::InPlane,
        ["bell crank", "tie rod"],
        Place::named(&crank_tie_rod),
        Some((Vec3::x(), -Vec3::y())),
        None,
    )?;
    b.on_axle(false);
    spring_and_shock(doc, b)
}

/// `SolidThreeLinkAxle`.
pub(super) fn read_three_link(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    axle_tube(doc, b)?;
    wheel_on_tube(doc, b)?;
    three_links(doc, b)?;
    spring_and_shock(doc, b)
}

/// `SolidBellcrankThreeLinkAxle`.
pub(super) fn read_bellcrank_three_link(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    axle_tube(doc, b)?;
    knuckle(doc, b, &["Location Tierod"])?;
    let knuckle_tie_rod = b.hardpoint(doc, "tie_rod_knuckle", "Knuckle/Location Tierod")?;
    three_links(doc, b)?;
    b.on_axle(true);
    let pivot = b.hardpoint(doc, "bell_crank_axle", "Bellcrank/Location Axle")?;
    b.body("bell crank", &pivot);
    doc.dynamics("Bellcrank", &["Mass", "Inertia"], &mut b.notes);
    b.joint(
        doc,
        "bell crank pivot",
        JointKind::Revolute,
        [AXLE_TUBE, "bell crank"],
        Place::named(&pivot),
        Some((Vec3::x(), Vec3::z())),
        None,
    )?;
    b.on_axle(false);
    // Each side's tie rod, from its mirrored point on the crank to its knuckle.
    let crank_tie_rod = b.hardpoint(doc, "tie_rod_bell_crank", "Bellcrank/Location Tierod")?;
    doc.dynamics("Tierod", &["Mass", "Inertia", "Radius"], &mut b.notes);
    b.link("tie rod", ["bell crank", "upright"], &crank_tie_rod, &knuckle_tie_rod);
    drag_link(doc, b, "bell crank", ("Location Steering", "Location Bellcrank"))?;
    spring_and_shock(doc, b)
}
