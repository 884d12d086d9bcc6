//! Sweeps of a whole axle: parallel and opposite wheel travel and steering of both wheels by one rack,
//! with track, roll angle, wheel loads, roll moment, the anti-roll bars' energy and the roll centre from
//! the path's exact tangent.

use crate::analysis::sweep::{read_sweep, walk, whole, Reading, SweepExtras, SweepOutput};
use crate::assembly::rig::WHEEL_TRAVEL;
use crate::assembly::{Axle, AxleRig};
use crate::wheel::{Wheel, WheelAttitude};
use elastokin_core::Pose;
use elastokin_solver::{LoadPath, Mode, SolverError, SolverOptions, StaticSolver};

/// The roll centre at one configuration, in the front view (body axes: the rig holds the body).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollCentre {
    /// Lateral position (m, +y left); zero on the centre plane.
    pub lateral: f64,
    /// Height above the ground line through the two contact patches, measured at `lateral` (m).
    pub height: f64,
}

/// One row of a driven axle sweep.
#[derive(Debug, Clone, PartialEq)]
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
    /// Twist of each of the axle's shared beams ([`Axle::members`], in order), rad: the sum of its
    /// segments' relative rotations about their own axes, positive by the right hand about the beam's
    /// direction from its first end to its last.
    pub member_twists: Vec<f64>,
    /// Moment of the two wheel loads about the x axis, Σ yᵢ·Fᵢ at the wheel centres (N·m). The roll
    /// stiffness is −dM/dφ.
    pub roll_moment: f64,
    /// Roll centre from the instantaneous motion of the contact patches in roll (the wheels driven
    /// opposite: the path itself in opposite travel, the drivers' rates so changed at a state of parallel
    /// travel); `None` under steering (the motion is not a travel), for a solid axle whose joints lock its
    /// roll, or when the two force lines are parallel (roll centre at infinity).
    pub roll_centre: Option<RollCentre>,
}

impl Axle {
    /// The roll centre at `poses`, for body velocities `rates` of the wheels driven opposite (from
    /// [`StaticSolver::path_tangent`] in opposite travel, or
    /// [`StaticSolver::path_tangent_factored_with_drivers_scaled`] at a state of parallel travel). For
    /// wheels whose motions do not depend on each other the rates of parallel travel give the same lines.
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

/// Walks the axle's driven path from `from` to `to` in `steps` steps: parallel travel, opposite travel or
/// steering, whichever the axle was built for (refused for [`AxleRig::HeightHeld`] and [`AxleRig::Free`],
/// where `t` drives nothing). Each row carries both wheels, track, roll angle, wheel loads, roll moment and
/// — for the travel rigs — the roll centre from the exact tangent at the row (one more factorization per
/// row), of the roll there: in parallel travel, of the wheels driven opposite from the row's state.
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
    let mut solver = StaticSolver::taped(model, SolverOptions::default(), extras.taping())?;
    let mut start = solver.design_state(from);
    let walked = walk(&mut solver, &mut start, LoadPath::new(from, to, steps), mode, &extras)?;
    let drivers = (model.joint_id(&format!("left {WHEEL_TRAVEL}")), model.joint_id(&format!("right {WHEEL_TRAVEL}")));
    read_sweep(&mut solver, &axle.left, None, walked, extras, |solver, step, reading| {
        let load = |d: Option<elastokin_core::JointId>| d.map_or(0.0, |d| step.joint_reaction(model, d).force.z);
        let (left, right) = (axle.left.attitude(&step.poses), axle.right.attitude(&step.poses));
        let (left_load, right_load) = (load(drivers.0), load(drivers.1));
        let (track, roll_angle) = axle.track_and_roll(&step.poses);
        // Read for the figures alone, the roll centre at design only: the figure's.
        let roll_centre = if axle.rig == AxleRig::Steering
            || reading == Reading::Expansion
            || (extras.figures_only && reading == Reading::Row)
        {
            None
        } else {
            let (state, opposite) = (solver.state_of(step), drivers.1.map(|right| [(right, -1.0)]));
            match (axle.rig, opposite) {
                // The roll centre is the roll's: at a state of parallel travel, the wheels driven opposite.
                (AxleRig::ParallelTravel, Some(opposite)) => {
                    solver.factorize_tangent(&state)?;
                    let rates = solver.path_tangent_factored_with_drivers_scaled(&opposite)?;
                    axle.roll_centre(&step.poses, &rates)
                }
                // A solid axle whose joints lock its roll has its right wheel's height follow the left's
                // (no driver of its own): it cannot roll, and has no roll centre.
                (AxleRig::ParallelTravel, None) => None,
                _ => axle.roll_centre(&step.poses, &solver.path_tangent(&state)?),
            }
        };
        let reports =
            (!(axle.anti_roll_bars.is_empty() && axle.members.is_empty())).then(|| step.element_reports(model));
        let member_twists = match &reports {
            None => Vec::new(),
            Some(reports) => {
                axle.members.iter().map(|m| m.segments.iter().map(|e| reports[e.0].rotation.x).sum()).collect()
            }
        };
        Ok(AxleRow {
            member_twists,
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
                let reports = reports.as_ref().expect("read when the axle has bars");
                // A bar's beams keep their energy in closed form; a bar's torsion element twists about its
                // own x axis only (its two halves turn on one axis): half the moment times the twist.
                axle.anti_roll_bars
                    .iter()
                    .map(|e| {
                        let element = &model.elements()[e.0];
                        let [i, j] = element.bodies().map(|b| b.pose(&step.poses));
                        element
                            .energy(&i, &j)
                            .unwrap_or_else(|| 0.5 * reports[e.0].torque.norm() * reports[e.0].rotation.x.abs())
                    })
                    .sum()
            },
            roll_centre,
        })
    })
}
