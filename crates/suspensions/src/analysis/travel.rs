//! Driven sweeps of one corner: parallel wheel travel and steering, a row of toe, camber, wheel-centre
//! position, steering geometry and wheel load at every step.

use crate::analysis::sweep::{read_sweep, require_rig, walk, whole, Reading, SweepExtras, SweepOutput};
use crate::analysis::swing_arm::SwingArms;
use crate::assembly::rig::WHEEL_TRAVEL;
use crate::assembly::{Corner, Rig};
use crate::wheel::{SteeringGeometry, WheelAttitude};
use elastokin_solver::{LoadPath, Mode, SolverError, SolverOptions, StaticSolver, StepResult};

/// One row of a driven sweep (wheel travel or steering).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TravelRow {
    /// The driven travel (m): wheel travel (bump positive) or rack travel (towards +y).
    pub travel: f64,
    /// Wheel attitude.
    pub attitude: WheelAttitude,
    /// Steering-axis geometry.
    pub steering: SteeringGeometry,
    /// Vertical force the rig applies at the wheel centre to hold its height (N, up +); zero when the
    /// rig does not hold the height. Its slope against wheel travel is the wheel rate.
    pub wheel_load: f64,
    /// Spring deflection `L − L₀` (m, compression negative). Its slope against wheel travel is the
    /// (signed) spring motion ratio.
    pub spring_deflection: f64,
    /// The front-view and side-view swing arms from the path's exact tangent, in wheel travel; `None` in
    /// steering, at the points of the path's expansion through design, and on rows read for the figures
    /// alone ([`SweepExtras::figures_only`]).
    pub swing_arms: Option<SwingArms>,
}

/// Parallel wheel travel from `from` to `to` metres in `steps` steps (the corner must be built with
/// [`Rig::WheelTravel`]). Starts from the equilibrium at `from`.
pub fn parallel_wheel_travel(
    corner: &Corner,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
) -> Result<Vec<TravelRow>, SolverError> {
    driven_sweep(corner, Rig::WheelTravel, from, to, steps, mode)
}

/// Steering: rack travel from `from` to `to` metres (towards +y) with the wheel-centre height held (the
/// corner must be built with [`Rig::Steering`]). The rows' `travel` is the rack travel.
pub fn steering(corner: &Corner, from: f64, to: f64, steps: usize, mode: Mode) -> Result<Vec<TravelRow>, SolverError> {
    driven_sweep(corner, Rig::Steering, from, to, steps, mode)
}

fn driven_sweep(
    corner: &Corner,
    rig: Rig,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
) -> Result<Vec<TravelRow>, SolverError> {
    whole(driven_sweep_with(corner, rig, from, to, steps, mode, SweepExtras::default())?)
}

/// [`parallel_wheel_travel`] with [`SweepExtras`].
pub fn parallel_wheel_travel_with(
    corner: &Corner,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
    extras: SweepExtras,
) -> Result<SweepOutput<TravelRow>, SolverError> {
    driven_sweep_with(corner, Rig::WheelTravel, from, to, steps, mode, extras)
}

fn driven_sweep_with(
    corner: &Corner,
    rig: Rig,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
    extras: SweepExtras,
) -> Result<SweepOutput<TravelRow>, SolverError> {
    require_rig(corner, &[rig])?;
    let mut solver = StaticSolver::taped(&corner.model, SolverOptions::default(), extras.taping())?;
    let mut start = solver.design_state(from);
    let walked = walk(&mut solver, &mut start, LoadPath::new(from, to, steps), mode, &extras)?;
    read_sweep(&mut solver, &corner.wheel, corner.partner.as_ref(), walked, extras, |solver, s, reading| {
        // The swing arms cost a factorization of the exact tangent at the row (the walk's own are of other
        // states, or of the paper tangent); no rate is taken of them.
        let swing_arms = match reading {
            _ if rig != Rig::WheelTravel => None,
            Reading::Row if extras.figures_only => None,
            Reading::Expansion => None,
            Reading::Row | Reading::Design => {
                let rates = solver.path_tangent(&solver.state_of(s))?;
                Some(SwingArms::of(&corner.wheel, &s.poses, &rates))
            }
        };
        Ok(TravelRow { swing_arms, ..travel_row(corner, s) })
    })
}

/// One row of a driven sweep of `corner`, read from a state of its model: the wheel's attitude and steering
/// geometry from the poses, the wheel load from the travel driver's multiplier, the spring's deflection.
fn travel_row(corner: &Corner, s: &StepResult) -> TravelRow {
    let driver = corner.model.joint_id(WHEEL_TRAVEL);
    TravelRow {
        travel: s.t,
        attitude: corner.wheel.attitude(&s.poses),
        steering: corner.wheel.steering_geometry(&s.poses),
        wheel_load: driver.map_or(0.0, |d| s.joint_reaction(&corner.model, d).force.z),
        spring_deflection: corner.spring.map_or(0.0, |e| s.element_report(&corner.model, e).deflection.x),
        swing_arms: None,
    }
}
