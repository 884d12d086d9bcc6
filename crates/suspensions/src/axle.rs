//! A full axle: both corners of one template, mirrored, with one rack shared by the two tie rods — for
//! the tests that need both wheels: opposite wheel travel (roll), parallel travel with track change and
//! roll-centre migration, and steering of both wheels by one rack.

use crate::analysis::{read_sweep, walk, whole, SweepExtras, SweepOutput};
use crate::corner::{
    add_rack, add_wheel_travel_driver, mount_rod, mount_tie_rod, CornerParts, CornerTemplate, CrossAxle, Wheel,
    WheelAttitude,
};
use crate::hardpoint::Side;
use elastokin_core::{BodyRef, ElementId, Model, ModelError, Pose, Vec3};
use elastokin_solver::{LoadPath, Mode, SolverError, SolverOptions, StaticSolver};

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

/// Both corners of an axle in one model. Part names start with `"left "` or `"right "` (`"left upright"`,
/// `"right wheel travel"`, …); the rack, when there is one, is `"rack"`.
#[derive(Debug)]
pub struct Axle {
    /// The multibody model.
    pub model: Model,
    /// How it is held.
    pub rig: AxleRig,
    /// The left wheel.
    pub left: Wheel,
    /// The right wheel (the left mirrored, y → −y).
    pub right: Wheel,
    /// The torsion element of each anti-roll bar.
    pub anti_roll_bars: Vec<ElementId>,
}

/// The roll centre at one configuration, in the front view (body axes: the rig holds the body).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollCentre {
    /// Lateral position (m, +y left); zero on the centre plane.
    pub lateral: f64,
    /// Height above the ground line through the two contact patches, measured at `lateral` (m).
    pub height: f64,
}

/// One row of a driven axle sweep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxleRow {
    /// The driven parameter: wheel travel (m; the left wheel's in opposite travel) or rack travel (m).
    pub travel: f64,
    /// Left wheel attitude.
    pub left: WheelAttitude,
    /// Right wheel attitude.
    pub right: WheelAttitude,
    /// Track: lateral distance between the two contact patches (m).
    pub track: f64,
    /// Body roll relative to the ground line through the contact patches (rad, positive about +x: the
    /// body's left side up).
    pub roll_angle: f64,
    /// Vertical force the rig applies at the left wheel centre (N, up +); zero when the height is free.
    pub left_load: f64,
    /// Vertical force the rig applies at the right wheel centre (N, up +).
    pub right_load: f64,
    /// Strain energy in the anti-roll bars (J): ½·rate·twist² summed over the bars. Its second derivative
    /// against the roll angle is the bars' roll stiffness.
    pub anti_roll_bar_energy: f64,
    /// Moment of the two wheel loads about the x axis, Σ yᵢ·Fᵢ at the wheel centres (N·m). The roll
    /// stiffness is −dM/dφ.
    pub roll_moment: f64,
    /// Roll centre from the instantaneous motion of the contact patches; `None` under steering (the
    /// motion is not a travel) or when the two force lines are parallel (roll centre at infinity).
    pub roll_centre: Option<RollCentre>,
}

impl Axle {
    /// Builds both corners of `template`, the left as described and the right mirrored, their tie rods on
    /// one rack (a body on a lateral slide when steering, else the chassis), held as `rig` says.
    pub fn build(template: &impl CornerTemplate, rig: AxleRig) -> Result<Axle, ModelError> {
        let mut model = Model::new();
        let (left, right, cross) =
            add_both_corners(&mut model, template, ["left ", "right "], rig == AxleRig::Steering)?;
        let travel_rates = match rig {
            AxleRig::ParallelTravel => Some((1.0, 1.0)),
            AxleRig::OppositeTravel => Some((1.0, -1.0)),
            AxleRig::Steering | AxleRig::HeightHeld => Some((0.0, 0.0)),
            AxleRig::Free => None,
        };
        if let Some((l, r)) = travel_rates {
            let axle_only = template.builds_on_axle_only();
            add_travel_drivers(&mut model, axle_only, ("left ", &left.wheel, l), ("right ", &right.wheel, r))?;
        }
        Ok(Axle { model, rig, left: left.wheel, right: right.wheel, anti_roll_bars: cross.anti_roll_bars })
    }

    /// The roll centre at `poses`, for body velocities `rates` along a wheel-travel path (from
    /// [`StaticSolver::path_tangent`]).
    ///
    /// Each contact patch `P` (the wheel's lowest point) belongs, for an instant, to the upright, whose
    /// material point there moves with velocity `v`. A force at `P` along the front-view line perpendicular
    /// to `v` does no virtual work in wheel travel: the linkage carries it without the wheel moving, and the
    /// line passes through the wheel's front-view instant centre. The roll centre is where the left and
    /// right lines cross: lateral forces applied to the body there produce no suspension roll (SAE J670).
    /// `None` when a patch does not move or the lines are parallel.
    pub fn roll_centre(&self, poses: &[Pose], rates: &[f64]) -> Option<RollCentre> {
        let line = |wheel: &Wheel| {
            let p = wheel.steering_geometry(poses).contact_patch;
            let v = wheel.point_velocity(poses, rates, p);
            // Front view (y, z): the direction perpendicular to (v_y, v_z).
            let d = (v.z, -v.y);
            let size = d.0.hypot(d.1);
            (size.is_finite() && size > 0.0).then_some(((p.y, p.z), (d.0 / size, d.1 / size)))
        };
        let ((pl, dl), (pr, dr)) = (line(&self.left)?, line(&self.right)?);
        // pl + a·dl = pr + b·dr, by Cramer's rule on the columns dl and −dr.
        let det = -dl.0 * dr.1 + dr.0 * dl.1;
        if det.abs() < 1e-12 {
            return None;
        }
        let r = (pr.0 - pl.0, pr.1 - pl.1);
        let a = (-r.0 * dr.1 + dr.0 * r.1) / det;
        let centre = (pl.0 + a * dl.0, pl.1 + a * dl.1);
        let ground = pl.1 + (pr.1 - pl.1) * (centre.0 - pl.0) / (pr.0 - pl.0);
        Some(RollCentre { lateral: centre.0, height: centre.1 - ground })
    }

    /// Track and body roll angle at `poses`.
    fn track_and_roll(&self, poses: &[Pose]) -> (f64, f64) {
        let pl = self.left.steering_geometry(poses).contact_patch;
        let pr = self.right.steering_geometry(poses).contact_patch;
        // The ground line through the patches tilts by β in the body's front view; the body rolls by −β
        // relative to it.
        let beta = (pl.z - pr.z).atan2(pl.y - pr.y);
        (pl.y - pr.y, -beta)
    }
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
        (true, ..) => return Err(crate::corner::no_steering_input()),
    };
    for (prefix, parts) in [(prefixes[0], &left), (prefixes[1], &right)] {
        if let Some(tie_rod) = parts.tie_rod {
            mount_tie_rod(model, prefix, inner, &parts.wheel, tie_rod)?;
        }
    }
    if let Some(link) = cross.steering_link {
        mount_rod(model, "steering link", inner, link.body, Side::Left, link.rod)?;
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
    if axle_only && crate::plausibility::mobility(model).0 == 0 {
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

/// Walks the axle's driven path from `from` to `to` in `steps` steps: parallel travel, opposite travel or
/// steering, whichever the axle was built for (refused for [`AxleRig::HeightHeld`] and [`AxleRig::Free`],
/// where `t` drives nothing). Each row carries both wheels, track, roll angle, wheel loads, roll moment and
/// — for the travel rigs — the roll centre from the path's exact tangent (one more factorization per row).
pub fn axle_sweep(axle: &Axle, from: f64, to: f64, steps: usize, mode: Mode) -> Result<Vec<AxleRow>, SolverError> {
    whole(axle_sweep_with(axle, from, to, steps, mode, SweepExtras::default())?)
}

/// [`axle_sweep`] with [`SweepExtras`] (the compliance, when asked, is the left wheel's).
pub fn axle_sweep_with(
    axle: &Axle,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
    extras: SweepExtras,
) -> Result<SweepOutput<AxleRow>, SolverError> {
    if matches!(axle.rig, AxleRig::HeightHeld | AxleRig::Free) {
        return Err(SolverError::InvalidInput {
            what: "axle",
            why: format!(
                "Axle built with AxleRig::{:?} has nothing driven by the load parameter: build it with \
                 ParallelTravel, OppositeTravel or Steering",
                axle.rig
            ),
        });
    }
    let model = &axle.model;
    let mut solver = StaticSolver::new(model, SolverOptions::default())?;
    let mut start = solver.design_state(from);
    let walked = walk(&mut solver, &mut start, LoadPath::new(from, to, steps), mode, extras.through_limits)?;
    let drivers = (model.joint_id("left wheel travel"), model.joint_id("right wheel travel"));
    read_sweep(&mut solver, &axle.left, None, walked, extras, |solver, step| {
        let reactions = step.joint_reactions(model);
        let load = |d: Option<elastokin_core::JointId>| d.map_or(0.0, |d| reactions[d.0].force.z);
        let (left, right) = (axle.left.attitude(&step.poses), axle.right.attitude(&step.poses));
        let (left_load, right_load) = (load(drivers.0), load(drivers.1));
        let (track, roll_angle) = axle.track_and_roll(&step.poses);
        let roll_centre = if axle.rig == AxleRig::Steering {
            None
        } else {
            let rates = solver.path_tangent(&solver.state_of(step))?;
            axle.roll_centre(&step.poses, &rates)
        };
        Ok(AxleRow {
            travel: step.t,
            left,
            right,
            track,
            roll_angle,
            left_load,
            right_load,
            roll_moment: left.wheel_centre.y * left_load + right.wheel_centre.y * right_load,
            anti_roll_bar_energy: if axle.anti_roll_bars.is_empty() {
                0.0
            } else {
                let reports = step.element_reports(model);
                // A bar's torsion element twists about its own x axis only (its two halves turn on one
                // axis): the energy is half the moment times the twist.
                axle.anti_roll_bars
                    .iter()
                    .map(|e| 0.5 * reports[e.0].torque.norm() * reports[e.0].rotation.x.abs())
                    .sum()
            },
            roll_centre,
        })
    })
}
