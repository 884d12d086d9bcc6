//! The rig: how a K&C machine holds a built corner or axle. The rack on its slide, the tie rods and a
//! solid axle's steering link mounted on it (or on the chassis when the rack is fixed), and the drivers of
//! the wheel-centre heights. Every rig driver of the crate is added here.

use crate::assembly::mobility::mobility;
use crate::assembly::template::{CornerParts, CornerTemplate, CrossAxle, TieRod};
use crate::description::connection::{BushingRates, Connection, TieRodMounts};
use crate::description::general::part_name;
use crate::description::Side;
use crate::wheel::Wheel;
use elastokin_core::joint::orthonormal_complement;
use elastokin_core::{BodyRef, JointSpec, Mat3, Model, ModelError, Pose, Vec3};
use elastokin_elements::Bushing;

/// The rack's body, named once: the steering rig's.
pub const RACK: &str = "rack";
/// The rack's slide on the chassis.
pub const RACK_SLIDE: &str = "rack slide";
/// The driver of the rack's travel.
pub const RACK_TRAVEL: &str = "rack travel";
/// A corner's tie rod (after its part-name prefix).
pub const TIE_ROD: &str = "tie rod";
/// A solid axle's steering link.
pub const STEERING_LINK: &str = "steering link";
/// The driver of a wheel centre's height (after its part-name prefix).
pub const WHEEL_TRAVEL: &str = "wheel travel";

/// How the corner is held on the K&C rig, and what the load parameter `t` drives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rig {
    /// Wheel-centre height driven, `t` = travel in metres (bump positive); rack fixed.
    WheelTravel,
    /// Rack driven, `t` = rack travel in metres (towards +y); wheel-centre height held.
    Steering,
    /// Wheel-centre height held at design, rack fixed: for forces with the height held as a rig does.
    HeightHeld,
    /// No drivers, rack fixed: the wheel rides on the spring (force sweeps with the wheel free).
    Free,
}

/// A bushing between `carrier` (whose frame it moves with) and `body` at `point`, its local x along `axis`.
fn axial_bushing(
    name: &str,
    carrier: BodyRef,
    body: BodyRef,
    point: Vec3,
    axis: Vec3,
    r: BushingRates,
) -> Result<Bushing, ModelError> {
    let n = axis.norm();
    if !(n.is_finite() && n > 1e-9) {
        return Err(ModelError::CoincidentPoints { item: name.to_string(), distance: n });
    }
    // The rates were checked by their model-file keys when the corner began (`check_connection`).
    let x = axis / n;
    let (y, z) = orthonormal_complement(&x);
    Bushing::new(
        name,
        carrier,
        body,
        point,
        Mat3::from_columns(&[x, y, z]),
        Vec3::new(r.axial, r.radial, r.radial),
        Vec3::new(r.torsion, r.conical, r.conical),
    )
    .map(|b| b.with_rotation_law(r.law))
}

/// Attaches a tie rod between `inner_body` and the wheel's upright.
pub(crate) fn mount_tie_rod(
    model: &mut Model,
    prefix: &str,
    inner_body: BodyRef,
    wheel: &Wheel,
    tie_rod: TieRod,
) -> Result<(), ModelError> {
    mount_rod(model, &part_name(prefix, TIE_ROD), inner_body, wheel.upright.into(), wheel.side, tie_rod)
}

/// Attaches a rod named `name` from `inner_body` at `rod.inner` to `outer_body` at `rod.outer`: a distance
/// constraint when both ends are ideal, else a rod body with its end connections (a bushing's own axis
/// given on the left is placed on `side`).
pub(crate) fn mount_rod(
    model: &mut Model,
    name: &str,
    inner_body: BodyRef,
    outer_body: BodyRef,
    side: Side,
    rod: TieRod,
) -> Result<(), ModelError> {
    let TieRodMounts { inner, outer } = rod.connection;
    if (inner, outer) == (Connection::Ideal, Connection::Ideal) {
        model.add_joint(JointSpec::distance(name, inner_body, outer_body, rod.inner, rod.outer))?;
        return Ok(());
    }
    let rod_axis = rod.outer - rod.inner;
    let body = model.add_body(name, Pose::at((rod.inner + rod.outer) / 2.0))?;
    let ends = [
        ("inner", inner_body, BodyRef::from(body), rod.inner, inner),
        ("outer", BodyRef::from(body), outer_body, rod.outer, outer),
    ];
    for (end, carrier, body, point, connection) in ends {
        match connection {
            Connection::Bushing(rates) => {
                let axis = rates.axis.map_or(rod_axis, |a| side.place(a.into()));
                let bushing = axial_bushing(&format!("{name} {end} bushing"), carrier, body, point, axis, rates)?;
                model.add_element(bushing)?;
            }
            // At the rack a universal joint, its cross across the rod, so that the rod cannot spin.
            Connection::Ideal if end == "inner" => {
                let (u, v) = orthonormal_complement(&rod_axis.normalize());
                model.add_joint(JointSpec::universal(&format!("{name} {end} joint"), carrier, body, point, u, v))?;
            }
            Connection::Ideal => {
                model.add_joint(JointSpec::spherical(&format!("{name} {end} joint"), carrier, body, point))?;
            }
        }
    }
    Ok(())
}

/// The error for a steering rig on a corner without a tie rod.
pub(crate) fn no_steering_input() -> ModelError {
    ModelError::OutOfRange {
        item: "corner.tie_rod".into(),
        why: "the steering analysis needs a steering input: this corner has no tie rod (corner.tie_rod, or a solid \
              axle's axle.steering_link), so its toe is held by its own links and it cannot be steered"
            .into(),
    }
}

/// Adds a rack: a body on a slide along the unit `axis` at `at`, driven by `t` (m along `axis`), named
/// "rack".
pub(crate) fn add_rack(model: &mut Model, at: Vec3, axis: Vec3) -> Result<BodyRef, ModelError> {
    let rack = model.add_body(RACK, Pose::at(at))?;
    model.add_joint(JointSpec::translational(RACK_SLIDE, BodyRef::Ground, rack, at, axis))?;
    model.add_joint(JointSpec::travel_driver(RACK_TRAVEL, BodyRef::Ground, rack, at, axis, 1.0))?;
    Ok(rack.into())
}

/// Adds a driver of the wheel-centre height: `travel_rate` metres per unit `t` (0 holds the height).
pub(crate) fn add_wheel_travel_driver(
    model: &mut Model,
    prefix: &str,
    wheel: &Wheel,
    travel_rate: f64,
) -> Result<(), ModelError> {
    model.add_joint(JointSpec::point_driver(
        &part_name(prefix, WHEEL_TRAVEL),
        wheel.upright,
        wheel.wheel_centre,
        Vec3::z(),
        travel_rate,
    ))?;
    Ok(())
}

/// How the axle is held on the K&C rig, and what the load parameter `t` drives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AxleRig {
    /// Both wheel-centre heights driven together, `t` = travel in metres (bump positive); rack fixed.
    ParallelTravel,
    /// Opposite wheel travel: the left wheel-centre height driven by `+t`, the right by `−t` (metres), so
    /// the body rolls relative to the wheels (left bump rolls the body's left side down); rack fixed.
    OppositeTravel,
    /// Rack driven, `t` = rack travel in metres (towards +y); both wheel-centre heights held.
    Steering,
    /// Both wheel-centre heights held at design, rack fixed.
    HeightHeld,
    /// No drivers, rack fixed: both wheels ride on their springs.
    Free,
}

/// Adds both corners of `template` to `model`, their part names starting with `prefixes` (left, right),
/// the parts they share and those across, and the steering: the tie rods (and a solid axle's steering
/// link) on one rack when `steering` (a body on a slide at the middle of the tie rods' inner ends, along
/// y; at the steering link's inner end, along its axis), else on the chassis.
pub(crate) fn add_both_corners(
    model: &mut Model,
    template: &impl CornerTemplate,
    prefixes: [&str; 2],
    steering: bool,
) -> Result<(CornerParts, CornerParts, CrossAxle), ModelError> {
    template.add_axle_bodies(model)?;
    let left = template.add_corner(model, Side::Left, prefixes[0])?;
    let right = template.add_corner(model, Side::Right, prefixes[1])?;
    let cross = template.add_cross_axle(model, (prefixes[0], &left), (prefixes[1], &right))?;
    let inner = match (steering, left.tie_rod, right.tie_rod, cross.steering_link) {
        (false, ..) => BodyRef::Ground,
        (true, _, _, Some(link)) => add_rack(model, link.rod.inner, link.rack_axis)?,
        (true, Some(l), Some(r), None) => add_rack(model, (l.inner + r.inner) / 2.0, Vec3::y())?,
        (true, ..) => return Err(no_steering_input()),
    };
    for (prefix, parts) in [(prefixes[0], &left), (prefixes[1], &right)] {
        if let Some(tie_rod) = parts.tie_rod {
            mount_tie_rod(model, prefix, inner, &parts.wheel, tie_rod)?;
        }
    }
    if let Some(link) = cross.steering_link {
        mount_rod(model, STEERING_LINK, inner, link.body, Side::Left, link.rod)?;
    }
    Ok((left, right, cross))
}

/// Adds the wheel-centre height drivers of two wheels, each `(prefix, wheel, travel rate)`. On a solid
/// axle (`axle_only`) whose joints leave it one way to move once the first wheel's height is driven (its
/// roll locked, as a four-link axle with a Panhard rod on ideal joints is), the second wheel's height
/// follows from the first's: its driver is left out when it would drive the same travel, and the rig is
/// refused when it would drive another (opposite travel).
pub(crate) fn add_travel_drivers(
    model: &mut Model,
    axle_only: bool,
    first: (&str, &Wheel, f64),
    second: (&str, &Wheel, f64),
) -> Result<(), ModelError> {
    add_wheel_travel_driver(model, first.0, first.1, first.2)?;
    if axle_only && mobility(model).0 == 0 {
        if first.2 == second.2 {
            return Ok(());
        }
        return Err(roll_locked());
    }
    add_wheel_travel_driver(model, second.0, second.1, second.2)
}

/// The refusal of opposite wheel travel on a solid axle whose joints lock its roll.
pub(crate) fn roll_locked() -> ModelError {
    ModelError::OutOfRange {
        item: "axle".into(),
        why: "the axle's joints leave it one way to move, in travel: its roll is locked (ideal links that bind \
              in roll, such as four angled links and a Panhard rod), so its wheels cannot travel opposite; make a \
              link a bushing to give it roll"
            .into(),
    }
}
