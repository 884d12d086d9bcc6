//! A suspension corner ready to solve: the template's parts, the tie rod, the rig that holds it, and the
//! wheel characteristics read from its poses.

use crate::connection::{BushingRates, Connection, SpringSpec, TieRodMounts};
use crate::hardpoint::Side;
use elastokin_core::joint::orthonormal_complement;
use elastokin_core::Mat3;
use elastokin_core::{BodyId, BodyRef, ElementId, JointSpec, Model, ModelError, Pose, Vec3, BODY_DOFS};
use elastokin_elements::Bushing;
use elastokin_elements::{PointForce, PointTorque};

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

/// A suspension template: something that adds one corner's parts to a model.
///
/// The rig (rack, tie-rod inner attachment, drivers) is not the template's: [`Corner::build`] and
/// [`crate::Axle::build`] add it, so one template serves a lone corner and both sides of an axle.
pub trait CornerTemplate {
    /// Adds the corner on `side` to `model`, every body, joint and element name starting with `prefix`
    /// (`""` for a lone corner, `"left "` / `"right "` on an axle). The tie rod is not added: it is
    /// returned in [`CornerParts::tie_rod`] for the rig to attach to the rack or the chassis.
    fn add_corner(&self, model: &mut Model, side: Side, prefix: &str) -> Result<CornerParts, ModelError>;

    /// Whether the two corners share parts (a solid axle's tube): then the template builds only on a whole
    /// axle, and [`Corner::build`] builds both sides. False by default.
    fn builds_on_axle_only(&self) -> bool {
        false
    }

    /// Adds the bodies the two corners share, before either corner. None by default.
    fn add_axle_bodies(&self, _model: &mut Model) -> Result<(), ModelError> {
        Ok(())
    }

    /// Adds the parts that join the two corners of an axle (anti-roll bars, the shared parts' joints and
    /// elements), after both corners, each given with its name prefix. None by default.
    fn add_cross_axle(
        &self,
        _model: &mut Model,
        _left: (&str, &CornerParts),
        _right: (&str, &CornerParts),
    ) -> Result<CrossAxle, ModelError> {
        Ok(CrossAxle::default())
    }
}

/// What a template added across the two corners of an axle.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CrossAxle {
    /// The torsion element of each anti-roll bar.
    pub anti_roll_bars: Vec<ElementId>,
    /// The axle's steering input, still to be attached to the rack or the chassis, when its corners have
    /// no tie rods of their own.
    pub steering_link: Option<SteeringLink>,
}

/// A solid axle's steering input: a rod from the steering box (the rack, or the chassis when the rack is
/// fixed) to a part of the axle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteeringLink {
    /// The part it pushes.
    pub body: BodyRef,
    /// The rod: `inner` at the steering box, `outer` on `body`.
    pub rod: TieRod,
    /// Unit direction in which the steering input moves the inner end.
    pub rack_axis: Vec3,
}

/// What a template added for one corner.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CornerParts {
    /// The wheel: upright, wheel centre, contact patch, steering axis.
    pub wheel: Wheel,
    /// The tie rod, still to be attached; `None` when the corner has no steering input (its toe is held
    /// by its own links).
    pub tie_rod: Option<TieRod>,
    /// The corner's own spring (its first), whose deflection gives the spring's motion ratio; `None` when
    /// it has none.
    pub spring: Option<ElementId>,
}

/// A tie rod between the rack (or the chassis when the rack is fixed) and the upright.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TieRod {
    /// Inner end (rack), global design point.
    pub inner: Vec3,
    /// Outer end (upright), global design point.
    pub outer: Vec3,
    /// Both ends ideal: a distance constraint (ball joints at both ends). A bushing at either end: a tie-rod
    /// body, each bushing's axis along the rod, so the steering compliance of the rod's mounts is modelled;
    /// an ideal end of it is a universal joint at the rack (holding the rod's spin) or a ball joint at the
    /// upright.
    pub connection: TieRodMounts,
}

/// Farthest a hardpoint may lie from its wheel centre (m). A corner spans a metre or two; far beyond,
/// lengths and lever arms lose every digit or overflow. A corner written in millimetres (a few thousand
/// "metres") still builds, so that the plausibility check can say what it is (`millimetres`); a point a
/// little off (a few metres) is named by it too (`far-hardpoint`).
pub const MAX_HARDPOINT_REACH: f64 = 5e3;

/// Least lateral position of the left wheel centre (m): half the narrowest track accepted.
pub const MIN_HALF_TRACK: f64 = 0.05;

/// Farthest a wheel centre may lie from the vehicle origin (m); as for [`MAX_HARDPOINT_REACH`], a corner
/// in millimetres still builds.
pub const MAX_WHEEL_CENTRE_DISTANCE: f64 = 5e3;

/// Refuses hardpoints no suspension has: a wheel centre more than [`MAX_WHEEL_CENTRE_DISTANCE`] from the
/// origin, or a point more than [`MAX_HARDPOINT_REACH`] from the wheel centre. `points` are the left
/// corner's hardpoints by their model-file names, the wheel centre first.
pub(crate) fn check_hardpoints(points: &[(&str, Vec3)]) -> Result<(), ModelError> {
    let Some(&(_, wheel_centre)) = points.first() else { return Ok(()) };
    let refuse = |name: &str, p: Vec3, what: String| {
        Err(ModelError::OutOfRange {
            item: "hardpoints".into(),
            why: format!(
                "{name} [{:.4e}, {:.4e}, {:.4e}] lies {what}: hardpoints are in metres (ISO 8855, x forward, \
                 y left, z up); move it or check its units",
                p.x, p.y, p.z
            ),
        })
    };
    if let Some(&(name, _)) = points.iter().find(|(_, p)| !p.iter().all(|c| c.is_finite())) {
        return Err(ModelError::OutOfRange {
            item: "hardpoints".into(),
            why: format!("{name} has a coordinate that is not a finite number: give it in metres"),
        });
    }
    if wheel_centre.y.abs() < MIN_HALF_TRACK {
        // The right corner is the mirror image: a wheel centre near y = 0 puts the two wheels of an axle
        // on top of each other and leaves the track (Ackermann's T / L) nothing. A right corner given for
        // the left (y < 0) builds, mirrored, and the plausibility check names it (`wrong-side`).
        let what = format!(
            "within {MIN_HALF_TRACK} m of the centre line: the model describes the left corner (y > 0), half a \
             track out"
        );
        return refuse(points[0].0, wheel_centre, what);
    }
    if wheel_centre.norm() > MAX_WHEEL_CENTRE_DISTANCE {
        let what = format!("more than {MAX_WHEEL_CENTRE_DISTANCE} m from the vehicle origin");
        return refuse(points[0].0, wheel_centre, what);
    }
    for &(name, p) in &points[1..] {
        if (p - wheel_centre).norm() > MAX_HARDPOINT_REACH {
            return refuse(name, p, format!("more than {MAX_HARDPOINT_REACH} m from the wheel centre"));
        }
    }
    Ok(())
}

/// Range of the rates a model accepts: `(least, most)` for translational rates (N/m) and for rotational
/// ones (N·m/rad). Far wider than rubber or steel: below, a part is held by next to nothing and drifts
/// anywhere; above, the stiffness swamps every other digit of the equations and then overflows.
pub const TRANSLATIONAL_RATE_RANGE: (f64, f64) = (1.0, 1e15);
/// See [`TRANSLATIONAL_RATE_RANGE`].
pub const ROTATIONAL_RATE_RANGE: (f64, f64) = (1e-3, 1e15);

/// Refuses a rate outside its range, naming its model-file key.
pub(crate) fn check_rate(key: &str, value: f64, (least, most): (f64, f64), unit: &str) -> Result<(), ModelError> {
    if value >= least && value <= most {
        return Ok(());
    }
    let got = if value.is_finite() { format!("{value:e}") } else { "not a finite number".into() };
    Err(ModelError::OutOfRange {
        item: key.into(),
        why: format!("{key} must be a rate in {unit} from {least:e} to {most:e}, got {got}"),
    })
}

/// Refuses a bushing whose rates are outside [`TRANSLATIONAL_RATE_RANGE`] and [`ROTATIONAL_RATE_RANGE`];
/// `key` is the connection's model-file key (`lower_arm_mounts`, `tie_rod`, …).
pub(crate) fn check_connection(key: &str, connection: &Connection) -> Result<(), ModelError> {
    let Connection::Bushing(r) = connection else { return Ok(()) };
    for (what, value) in [("radial", r.radial), ("axial", r.axial)] {
        check_rate(&format!("{key}.bushing.{what}"), value, TRANSLATIONAL_RATE_RANGE, "N/m")?;
    }
    for (what, value) in [("torsion", r.torsion), ("conical", r.conical)] {
        check_rate(&format!("{key}.bushing.{what}"), value, ROTATIONAL_RATE_RANGE, "N·m/rad")?;
    }
    Ok(())
}

/// [`check_connection`] for each end of a tie rod.
pub(crate) fn check_tie_rod_mounts(key: &str, mounts: &TieRodMounts) -> Result<(), ModelError> {
    if mounts.inner == mounts.outer {
        return check_connection(key, &mounts.inner);
    }
    check_connection(&format!("{key}.inner"), &mounts.inner)?;
    check_connection(&format!("{key}.outer"), &mounts.outer)
}

/// [`check_connection`] for each end of an arm.
pub(crate) fn check_arm_mounts(key: &str, mounts: &crate::connection::ArmMounts) -> Result<(), ModelError> {
    if mounts.front == mounts.rear {
        return check_connection(key, &mounts.front);
    }
    check_connection(&format!("{key}.front"), &mounts.front)?;
    check_connection(&format!("{key}.rear"), &mounts.rear)
}

/// Largest spring force at design accepted (N): a hundred times a heavy truck's; beyond, the spring's
/// geometric stiffness (force over length) overflows.
pub const MAX_SPRING_FORCE: f64 = 1e8;

/// Refuses a coil spring whose design force and rate give no free length: `L₀ = L + F/k` must be a
/// positive length (a coil spring pushes; a tension larger than `k·L` would need a negative one).
pub(crate) fn check_spring(spring: &SpringSpec, design_length: f64) -> Result<(), ModelError> {
    check_rate("spring.rate", spring.rate, TRANSLATIONAL_RATE_RANGE, "N/m")?;
    check_spring_force("spring", spring.rate, spring.design_force, design_length)
}

/// [`check_spring`]'s design-force part for the spring at model-file key `key`, whose rate was checked.
pub(crate) fn check_spring_force(
    key: &str,
    rate: f64,
    design_force: f64,
    design_length: f64,
) -> Result<(), ModelError> {
    if design_force.is_nan() || design_force.abs() > MAX_SPRING_FORCE {
        let got = if design_force.is_finite() { format!("{design_force:e}") } else { "not a finite number".into() };
        return Err(ModelError::OutOfRange {
            item: key.into(),
            why: format!(
                "{key}.design_force must be a force in N from {:e} to {MAX_SPRING_FORCE:e}, got {got}",
                -MAX_SPRING_FORCE
            ),
        });
    }
    if !design_force.is_finite() {
        // The spring element names these with its own messages.
        return Ok(());
    }
    let free_length = design_length + design_force / rate;
    let why = if !free_length.is_finite() {
        format!(
            "{key}.design_force {design_force:.4e} N at {key}.rate {rate:.4e} N/m would compress the spring by \
             more than any length: give the rate in N/m and the push at design in N"
        )
    } else if free_length <= 0.0 {
        format!(
            "{key}.design_force {design_force:.4e} N at {key}.rate {rate:.4e} N/m would need a free length of \
             {free_length:.4e} m for a design length of {design_length:.4} m: a coil spring pushes, so give \
             {key}.design_force as its push at design (N, above -rate × design length)"
        )
    } else {
        return Ok(());
    };
    Err(ModelError::OutOfRange { item: key.into(), why })
}

/// Refuses a steering axis (from `axis.0` up to `axis.1`, named by `axis_names`) that is too short to
/// define a line or does not rise: the scrub radius, trail and kingpin offset are where it meets the
/// ground and the wheel-centre height, which a level axis never does. It must rise by a tenth of its
/// length (lean less than 84° from the vertical).
pub(crate) fn check_steering_axis(axis: (Vec3, Vec3), axis_names: (&str, &str)) -> Result<(), ModelError> {
    let u = axis.1 - axis.0;
    let (length, rise) = (u.norm(), u.z);
    let why = if length < 1e-3 {
        format!(
            "{} and {} are {length:.1e} m apart: they must be distinct to define the steering axis",
            axis_names.0, axis_names.1
        )
    } else if rise < 0.1 * length {
        format!(
            "the steering axis from {} up to {} rises {rise:.4} m over its {length:.4} m: it must rise (lean less than \
             84 deg from the vertical) to meet the ground; check the two points",
            axis_names.0, axis_names.1
        )
    } else {
        return Ok(());
    };
    Err(ModelError::OutOfRange { item: "steering axis".into(), why })
}

/// Shortest lever a tie-rod pull may have about the steering axis (m). Steering arms are 100–150 mm; a
/// tie rod along the axis, or through it, has none, and then only rubber holds the wheel's steer. A
/// micrometre keeps near-aligned geometry open to conditioning studies while refusing the degenerate.
pub const MIN_STEERING_ARM: f64 = 1e-6;

/// The lever of the tie rod about the steering axis (from `axis.0` to `axis.1`): the moment about the
/// axis of a unit pull along the rod, `û · ((outer − axis.0) × d̂)` (m, signed). `None` when the axis or
/// the rod has no length.
pub(crate) fn tie_rod_lever(axis: (Vec3, Vec3), tie_rod_inner: Vec3, tie_rod_outer: Vec3) -> Option<f64> {
    let (u, rod) = (axis.1 - axis.0, tie_rod_outer - tie_rod_inner);
    (u.norm() > 1e-9 && rod.norm() > 1e-9).then(|| u.normalize().dot(&(tie_rod_outer - axis.0).cross(&rod.normalize())))
}

/// Refuses a tie rod that cannot steer: the moment about the steering axis (from `axis.0` to `axis.1`,
/// named by `axis_names`) of a unit pull along the tie rod, `û · ((outer − lower) × d̂)`, is its lever.
pub(crate) fn check_steering_arm(
    axis: (Vec3, Vec3),
    axis_names: (&str, &str),
    tie_rod_inner: Vec3,
    tie_rod_outer: Vec3,
) -> Result<(), ModelError> {
    // Coincident points: the joints and bushings built on them refuse them with their own message.
    let Some(lever) = tie_rod_lever(axis, tie_rod_inner, tie_rod_outer) else { return Ok(()) };
    if lever.abs() >= MIN_STEERING_ARM {
        return Ok(());
    }
    Err(ModelError::OutOfRange {
        item: "tie rod".into(),
        why: format!(
            "a pull along the tie rod (tie_rod_inner to tie_rod_outer) has a lever of {:.1e} m about the steering \
             axis ({} to {}), under the {MIN_STEERING_ARM:e} m it needs to hold the wheel's steer: move \
             tie_rod_outer off the steering axis, to the side of it, by a steering arm (typically 100 to 150 mm)",
            lever.abs(),
            axis_names.0,
            axis_names.1
        ),
    })
}

/// Name `name` of the part of the corner whose names start with `prefix`.
pub(crate) fn part_name(prefix: &str, name: &str) -> String {
    format!("{prefix}{name}")
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
    mount_rod(model, &part_name(prefix, "tie rod"), inner_body, wheel.upright.into(), wheel.side, tie_rod)
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
    let rack = model.add_body("rack", Pose::at(at))?;
    model.add_joint(JointSpec::translational("rack slide", BodyRef::Ground, rack, at, axis))?;
    model.add_joint(JointSpec::travel_driver("rack travel", BodyRef::Ground, rack, at, axis, 1.0))?;
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
        &part_name(prefix, "wheel travel"),
        wheel.upright,
        wheel.wheel_centre,
        Vec3::z(),
        travel_rate,
    ))?;
    Ok(())
}

/// A suspension corner ready to solve: its model, how it is held and where its wheel is.
#[derive(Debug)]
pub struct Corner {
    /// The multibody model.
    pub model: Model,
    /// How it is held.
    pub rig: Rig,
    /// The wheel.
    pub wheel: Wheel,
    /// The corner's own spring (see [`CornerParts::spring`]).
    pub spring: Option<ElementId>,
    /// The wheel across the axle when the corner cannot stand alone (a solid axle; see [`Corner::build`]):
    /// held by the same rig and loaded as `wheel` is, in phase.
    pub partner: Option<Wheel>,
    /// Where the rig applies the vertical, lateral and braking forces of the load analyses.
    pub load_point: LoadPoint,
}

/// Where a K&C rig applies its forces to the wheel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LoadPoint {
    /// At the contact patch, as the tyre does (the default): the force's lever about the wheel centre
    /// (the loaded radius) turns the wheel too.
    #[default]
    ContactPatch,
    /// At the wheel centre, as a rig that loads the hub does: the force alone, without the tyre's lever.
    WheelCentre,
}

/// Where a wheel is in a model: its upright, and the wheel's points and axes on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wheel {
    /// Which side it is on.
    pub side: Side,
    /// The upright (knuckle with the wheel).
    pub upright: BodyId,
    /// Wheel centre at design (global).
    pub wheel_centre: Vec3,
    /// Wheel centre as a local point of the upright.
    pub wheel_centre_local: Vec3,
    /// Outward spin axis as a local direction of the upright.
    pub spin_axis_local: Vec3,
    /// Contact patch centre at design (global): below the wheel centre by the loaded radius.
    pub contact_patch: Vec3,
    /// The steering axis: its lower and upper points as body-fixed points (lower ball joint on the upright;
    /// upper ball joint, or the top mount on the strut rod).
    pub steering_axis: [(BodyRef, Vec3); 2],
}

/// Steering-axis geometry at one configuration (angles in radians, lengths in metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteeringGeometry {
    /// Caster: the axis leans back at the top (positive).
    pub caster: f64,
    /// Kingpin inclination: the axis leans inboard at the top (positive).
    pub kingpin_inclination: f64,
    /// Scrub radius at the ground: positive when the axis meets the ground inboard of the contact patch.
    pub scrub_radius: f64,
    /// Mechanical (caster) trail at the ground: positive when the axis meets the ground ahead of the
    /// contact patch.
    pub mechanical_trail: f64,
    /// Kingpin offset at wheel-centre height: lateral distance from the axis to the wheel centre,
    /// positive when the axis is inboard.
    pub kingpin_offset: f64,
    /// Contact patch centre: the lowest point of the wheel-plane circle of the loaded radius.
    pub contact_patch: Vec3,
}
/// Largest loaded tyre radius accepted when a corner is built (m): far beyond, the contact patch's lever
/// swamps every other length. As for [`MAX_HARDPOINT_REACH`], a corner in millimetres still builds (a
/// model file is held to a tyre's range, 0.05–2 m, where it is read).
pub const MAX_LOADED_RADIUS: f64 = 5e3;

/// Loaded tyre radius when a model file does not give one (m); `shared/data/hardpoints.md` quotes ~0.30.
pub fn default_loaded_radius() -> f64 {
    0.30
}

/// Wheel position and orientation at one configuration (angles in radians, ISO 8855 / SAE J670 signs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelAttitude {
    /// Toe, toe-in positive.
    pub toe: f64,
    /// Camber, top of the wheel outward positive.
    pub camber: f64,
    /// Wheel-centre position (global).
    pub wheel_centre: Vec3,
}

impl Wheel {
    /// The wheel on `upright`: its centre `wheel_centre` and outward `spin_axis` at design (global, this
    /// side), the contact patch a loaded radius from the centre down the wheel plane; `steering_axis`
    /// holds global design points with their bodies. Refuses a loaded radius that is not a length.
    pub fn on(
        model: &Model,
        side: Side,
        upright: BodyId,
        wheel_centre: Vec3,
        spin_axis: Vec3,
        loaded_radius: f64,
        steering_axis: [(BodyRef, Vec3); 2],
    ) -> Result<Wheel, ModelError> {
        if loaded_radius > MAX_LOADED_RADIUS {
            return Err(ModelError::OutOfRange {
                item: "suspension".into(),
                why: format!(
                    "loaded_radius must be a tyre radius in metres, at most {MAX_LOADED_RADIUS}, got {loaded_radius:e}"
                ),
            });
        }
        if !(loaded_radius.is_finite() && loaded_radius > 0.0) {
            return Err(ModelError::NotPositive {
                item: "suspension".into(),
                what: "loaded_radius (m)",
                value: loaded_radius,
            });
        }
        let local = |(body, point): (BodyRef, Vec3)| {
            let pose = match body {
                BodyRef::Ground => Pose::IDENTITY,
                BodyRef::Body(b) => model.bodies()[b.0].design_pose,
            };
            (body, pose.to_local_point(&point))
        };
        let pose = model.bodies()[upright.0].design_pose;
        let a = spin_axis / spin_axis.norm();
        Ok(Wheel {
            side,
            upright,
            wheel_centre,
            wheel_centre_local: pose.to_local_point(&wheel_centre),
            spin_axis_local: pose.to_local_direction(&a),
            contact_patch: wheel_centre + down_the_wheel_plane(&a) * loaded_radius,
            steering_axis: [local(steering_axis[0]), local(steering_axis[1])],
        })
    }

    /// Toe, camber and wheel centre at the given poses.
    ///
    /// With `a` the outward spin axis and `s` = +1 left, −1 right: toe = atan2(aₓ, s·a_y) (a toe-in left
    /// wheel turns its spin axis forward), camber = atan2(−a_z, √(aₓ² + a_y²)) (top outward tips the outward
    /// axis down).
    pub fn attitude(&self, poses: &[Pose]) -> WheelAttitude {
        let pose = poses[self.upright.0];
        let a = pose.direction(&self.spin_axis_local);
        WheelAttitude {
            toe: a.x.atan2(self.side.sign() * a.y),
            camber: (-a.z).atan2((a.x * a.x + a.y * a.y).sqrt()),
            wheel_centre: pose.point(&self.wheel_centre_local),
        }
    }

    /// Velocity of the upright's material point now at global `point`, for body velocities `rates`
    /// (`BODY_DOFS` per body: translation of the reference point, then angular velocity, as in Δq).
    pub fn point_velocity(&self, poses: &[Pose], rates: &[f64], point: Vec3) -> Vec3 {
        let base = self.upright.0 * BODY_DOFS;
        let v = Vec3::new(rates[base], rates[base + 1], rates[base + 2]);
        let w = Vec3::new(rates[base + 3], rates[base + 4], rates[base + 5]);
        v + w.cross(&(point - poses[self.upright.0].position))
    }

    /// Caster, kingpin inclination, scrub radius, trail and kingpin offset at the given poses.
    ///
    /// With the axis `u` from its lower to its upper point and `s` = +1 left, −1 right: caster =
    /// atan2(−uₓ, u_z), KPI = atan2(−s·u_y, u_z). The contact patch is the wheel-plane point a loaded
    /// radius below the wheel centre, the ground the horizontal plane through it, and `G` the point where
    /// the axis meets that plane: scrub = s·(P_y − G_y), trail = Gₓ − Pₓ; the kingpin offset is
    /// s·(W_y − A_y) with `A` the axis point at wheel-centre height `W`.
    pub fn steering_geometry(&self, poses: &[Pose]) -> SteeringGeometry {
        let [(lb, ll), (ub, ul)] = self.steering_axis;
        let lower = lb.pose(poses).point(&ll);
        let upper = ub.pose(poses).point(&ul);
        let u = upper - lower;
        let s = self.side.sign();
        let pose = poses[self.upright.0];
        let a = pose.direction(&self.spin_axis_local);
        let wc = pose.point(&self.wheel_centre_local);
        let down = down_the_wheel_plane(&a);
        let radius = (self.wheel_centre - self.contact_patch).norm();
        let patch = wc + down * radius;
        let at_height = |z: f64| lower + u * ((z - lower.z) / u.z);
        let g = at_height(patch.z);
        let w = at_height(wc.z);
        SteeringGeometry {
            caster: (-u.x).atan2(u.z),
            kingpin_inclination: (-s * u.y).atan2(u.z),
            scrub_radius: s * (patch.y - g.y),
            mechanical_trail: g.x - patch.x,
            kingpin_offset: s * (wc.y - w.y),
            contact_patch: patch,
        }
    }
}

/// The downward direction in the plane of a wheel whose spin axis is `a` (unit).
fn down_the_wheel_plane(a: &Vec3) -> Vec3 {
    let up_in_plane = Vec3::z() - a * a.z;
    -up_in_plane / up_in_plane.norm()
}

impl Corner {
    /// The design point where the rig's forces act (see [`LoadPoint`]): `patch` (a contact-patch point) or
    /// the wheel centre.
    pub fn load_point_at(&self, patch: Vec3) -> Vec3 {
        match self.load_point {
            LoadPoint::ContactPatch => patch,
            LoadPoint::WheelCentre => self.wheel.wheel_centre,
        }
    }

    /// Builds `template`'s corner on `side` with its tie rod and held as `rig` says: a rack on a lateral
    /// slide when steering (else the tie rod's inner end is on the chassis), and the wheel-centre height
    /// driver the rig needs.
    ///
    /// A template whose corners share parts ([`CornerTemplate::builds_on_axle_only`], a solid axle) is
    /// built whole: the corner on `side` named as a lone corner's (`"upright"`, `"wheel travel"`), its
    /// partner on the other side named `"left …"` or `"right …"` and held by the same rig, so that travel
    /// moves both wheels alike; the loads of [`Corner::add_wheel_force`] and [`Corner::add_wheel_torque`]
    /// act on both, in phase (see there).
    pub fn build(template: &impl CornerTemplate, side: Side, rig: Rig) -> Result<Corner, ModelError> {
        let mut model = Model::new();
        let travel_rate = match rig {
            Rig::WheelTravel => Some(1.0),
            Rig::Steering | Rig::HeightHeld => Some(0.0),
            Rig::Free => None,
        };
        if template.builds_on_axle_only() {
            let other = partner_prefix(side);
            let prefixes = match side {
                Side::Left => ["", other],
                Side::Right => [other, ""],
            };
            let (left, right, _) = crate::axle::add_both_corners(&mut model, template, prefixes, rig == Rig::Steering)?;
            let (own, partner) = match side {
                Side::Left => (left, right),
                Side::Right => (right, left),
            };
            let (spring, own, partner) = (own.spring, own.wheel, partner.wheel);
            if let Some(rate) = travel_rate {
                crate::axle::add_travel_drivers(&mut model, true, ("", &own, rate), (other, &partner, rate))?;
            }
            let load_point = LoadPoint::default();
            return Ok(Corner { model, rig, wheel: own, spring, partner: Some(partner), load_point });
        }
        let parts = template.add_corner(&mut model, side, "")?;
        match (parts.tie_rod, rig) {
            (Some(tie_rod), Rig::Steering) => {
                let rack = add_rack(&mut model, tie_rod.inner, Vec3::y())?;
                mount_tie_rod(&mut model, "", rack, &parts.wheel, tie_rod)?;
            }
            (Some(tie_rod), _) => mount_tie_rod(&mut model, "", BodyRef::Ground, &parts.wheel, tie_rod)?,
            (None, Rig::Steering) => return Err(no_steering_input()),
            (None, _) => {}
        }
        if let Some(rate) = travel_rate {
            add_wheel_travel_driver(&mut model, "", &parts.wheel, rate)?;
        }
        let spring = parts.spring;
        Ok(Corner { model, rig, wheel: parts.wheel, spring, partner: None, load_point: LoadPoint::default() })
    }

    /// The prefix of the partner wheel's part names, when the corner has one.
    pub fn partner_prefix(&self) -> Option<&'static str> {
        self.partner.map(|_| partner_prefix(self.wheel.side))
    }

    /// Adds a world-fixed force `force · t` (N per unit load parameter) at the global design point `point`
    /// of the upright: a contact-patch or wheel-centre load of a K&C test. With a partner wheel (a solid
    /// axle), the same force acts on the partner too, at the mirror image of `point`: in phase, as a K&C
    /// rig loads an axle in a turn (the lateral forces of both tyres point the same way; mirror images would
    /// only squeeze the tube).
    pub fn add_wheel_force(&mut self, name: &str, point: Vec3, force: Vec3) -> Result<ElementId, ModelError> {
        self.add_wheel_force_with_constant(name, point, force, Vec3::zeros())
    }

    /// [`Corner::add_wheel_force`] with a constant part `constant` (N) beside the ramped `force · t`.
    pub fn add_wheel_force_with_constant(
        &mut self,
        name: &str,
        point: Vec3,
        force: Vec3,
        constant: Vec3,
    ) -> Result<ElementId, ModelError> {
        let element = |upright: BodyId, name: &str, point: Vec3, force: Vec3, constant: Vec3| {
            PointForce::new(name, upright.into(), point, force)?.with_constant(constant)
        };
        let id = self.model.add_element(element(self.wheel.upright, name, point, force, constant)?)?;
        if let (Some(partner), Some(prefix)) = (self.partner, self.partner_prefix()) {
            let point = Vec3::new(point.x, -point.y, point.z);
            self.model.add_element(element(partner.upright, &part_name(prefix, name), point, force, constant)?)?;
        }
        Ok(id)
    }

    /// Adds a world-fixed torque `torque · t` (N·m per unit load parameter) on the upright; with a partner
    /// wheel, the same torque on the partner (in phase, as [`Corner::add_wheel_force`]).
    pub fn add_wheel_torque(&mut self, name: &str, torque: Vec3) -> Result<ElementId, ModelError> {
        let id = self.model.add_element(PointTorque::new(name, self.wheel.upright.into(), torque)?)?;
        if let (Some(partner), Some(prefix)) = (self.partner, self.partner_prefix()) {
            self.model.add_element(PointTorque::new(&part_name(prefix, name), partner.upright.into(), torque)?)?;
        }
        Ok(id)
    }
}

/// The part-name prefix of the wheel across the axle from one on `side`.
fn partner_prefix(side: Side) -> &'static str {
    match side {
        Side::Left => "right ",
        Side::Right => "left ",
    }
}
