//! K&C analyses: load paths walked by the engine, reduced to wheel characteristics.

use crate::corner::{Corner, WheelAttitude};
use elastokin_solver::{LoadPath, Mode, SolverError, SolverOptions, StaticSolver};

/// One row of a wheel-travel table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TravelRow {
    /// Wheel travel (m, bump positive): the load parameter.
    pub travel: f64,
    /// Wheel attitude.
    pub attitude: WheelAttitude,
}

/// Parallel wheel travel from `from` to `to` metres in `steps` steps (the corner must have been built
/// with its wheel-travel driver). Starts from the equilibrium at `from`.
pub fn parallel_wheel_travel(
    corner: &Corner,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
) -> Result<Vec<TravelRow>, SolverError> {
    if corner.model.joint_id("wheel travel").is_none() {
        return Err(SolverError::InvalidInput {
            what: "corner",
            why: "parallel wheel travel needs the wheel-travel driver: build the corner with wheel_travel = true"
                .into(),
        });
    }
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default())?;
    let sweep = solver.sweep(LoadPath::new(from, to, steps), mode)?;
    Ok(sweep.steps.iter().map(|s| TravelRow { travel: s.t, attitude: corner.attitude(&s.poses) }).collect())
}
