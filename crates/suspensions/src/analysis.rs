//! K&C analyses: load paths walked by the engine, reduced to wheel characteristics.

use crate::corner::{Corner, Rig, SteeringGeometry, WheelAttitude};
use elastokin_solver::{LoadPath, Mode, SolverError, SolverOptions, StaticSolver};

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

/// The vertical force the rig applies at the wheel centre to hold the corner at design (N, up +): the
/// corner load the design position carries. The corner must hold its wheel-centre height
/// ([`Rig::WheelTravel`] at `t = 0`, or [`Rig::HeightHeld`]).
pub fn design_wheel_load(corner: &Corner) -> Result<f64, SolverError> {
    let driver =
        corner.model.joint_id("wheel travel").filter(|_| matches!(corner.rig, Rig::WheelTravel | Rig::HeightHeld));
    let Some(driver) = driver else {
        return Err(SolverError::InvalidInput {
            what: "corner",
            why: format!(
                "the design wheel load needs the wheel-centre height held, but the corner was built with Rig::{:?}",
                corner.rig
            ),
        });
    };
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default())?;
    let mut state = solver.design_state(0.0);
    let step = solver.equilibrium(&mut state)?;
    Ok(step.joint_reactions(&corner.model)[driver.0].force.z)
}

/// Refuses a corner held differently from what the analysis needs.
fn require_rig(corner: &Corner, rig: Rig) -> Result<(), SolverError> {
    if corner.rig == rig {
        return Ok(());
    }
    Err(SolverError::InvalidInput {
        what: "corner",
        why: format!(
            "this analysis needs the corner built with Rig::{rig:?}, but it was built with Rig::{:?}",
            corner.rig
        ),
    })
}

/// Slope of `y` against `x` at `x = at` over sweep rows (in either order): a central difference of the
/// rows on either side when a row sits exactly at `at`, else the chord of the two rows that bracket it.
/// `None` when `at` is outside the rows' range or there are fewer than two rows.
pub fn slope_at<R>(rows: &[R], at: f64, x: impl Fn(&R) -> f64, y: impl Fn(&R) -> f64) -> Option<f64> {
    let xs: Vec<f64> = rows.iter().map(&x).collect();
    let (a, b) = match xs.iter().position(|&v| v == at) {
        Some(k) if rows.len() >= 2 => (k.saturating_sub(1), (k + 1).min(rows.len() - 1)),
        Some(_) => return None,
        None => {
            let i = xs.windows(2).position(|w| (w[0] - at) * (w[1] - at) < 0.0)?;
            (i, i + 1)
        }
    };
    Some((y(&rows[b]) - y(&rows[a])) / (xs[b] - xs[a]))
}

fn driven_sweep(
    corner: &Corner,
    rig: Rig,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
) -> Result<Vec<TravelRow>, SolverError> {
    require_rig(corner, rig)?;
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default())?;
    let sweep = solver.sweep(LoadPath::new(from, to, steps), mode)?;
    let driver = corner.model.joint_id("wheel travel");
    let spring = corner.model.element_id("spring");
    Ok(sweep
        .steps
        .iter()
        .map(|s| TravelRow {
            travel: s.t,
            attitude: corner.wheel.attitude(&s.poses),
            steering: corner.wheel.steering_geometry(&s.poses),
            wheel_load: driver.map_or(0.0, |d| s.joint_reactions(&corner.model)[d.0].force.z),
            spring_deflection: spring.map_or(0.0, |e| s.element_reports(&corner.model)[e.0].deflection.x),
        })
        .collect())
}

/// The 6×6 compliance of the wheel at the equilibrium of load parameter `t`: column `k` is the response
/// `(Δ wheel centre, Δ rotation)` to a unit force (k < 3, N, global axes) or unit torque (k ≥ 3, N·m) at
/// the wheel centre, in m/N and rad/(N·m). It is the inverse tangent of the constrained system, so it
/// costs one factorization and six back-substitutions. Drivers present in the corner stay held (a
/// wheel-travel driver makes the vertical row and column zero, as on a K&C rig holding the wheel-centre
/// height).
pub fn wheel_compliance(corner: &Corner, t: f64) -> Result<[[f64; 6]; 6], SolverError> {
    Ok(compliance_at(corner, t)?.0)
}

/// The wheel compliance and the equilibrium poses it was taken at.
fn compliance_at(corner: &Corner, t: f64) -> Result<([[f64; 6]; 6], Vec<elastokin_core::Pose>), SolverError> {
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default())?;
    let mut state = solver.design_state(t);
    solver.equilibrium(&mut state)?;
    let n = corner.model.dofs();
    let m = solver.active_rows().len();
    let pose = state.poses[corner.wheel.upright.0];
    let s = pose.point(&corner.wheel.wheel_centre_local) - pose.position;
    let base = corner.wheel.upright.0 * elastokin_core::BODY_DOFS;
    let mut columns = [[0.0; 6]; 6];
    let mut rhs = vec![0.0; n + m];
    solver.factorize_tangent(&state)?;
    for (k, column) in columns.iter_mut().enumerate() {
        rhs.fill(0.0);
        let mut unit = elastokin_core::Vec3::zeros();
        unit[k % 3] = 1.0;
        // Generalized force of a force at the wheel centre (F, s × F), or of a torque (0, M).
        let (f, moment) = if k < 3 { (unit, s.cross(&unit)) } else { (elastokin_core::Vec3::zeros(), unit) };
        for c in 0..3 {
            rhs[base + c] = f[c];
            rhs[base + 3 + c] = moment[c];
        }
        solver.solve_factored(&mut rhs)?;
        let dr = elastokin_core::Vec3::new(rhs[base], rhs[base + 1], rhs[base + 2]);
        let dpi = elastokin_core::Vec3::new(rhs[base + 3], rhs[base + 4], rhs[base + 5]);
        let dwc = dr + dpi.cross(&s);
        for c in 0..3 {
            column[c] = dwc[c];
            column[3 + c] = dpi[c];
        }
    }
    // Stored by columns above; return rows × columns.
    let mut out = [[0.0; 6]; 6];
    for r in 0..6 {
        for c in 0..6 {
            out[r][c] = columns[c][r];
        }
    }
    Ok((out, state.poses))
}

/// One row of a force sweep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceRow {
    /// The applied force (N): the load parameter.
    pub force: f64,
    /// Wheel attitude at equilibrium.
    pub attitude: WheelAttitude,
    /// Contact-patch point of the upright at equilibrium (global).
    pub contact_patch: elastokin_core::Vec3,
}

/// Vertical force at the contact patch from `from` to `to` newtons (upward positive) in `steps` steps —
/// the paper's vertical force sweep. The corner must be built without the wheel-travel driver: the wheel
/// is free and the spring and bushings carry the load.
pub fn vertical_force_sweep(
    mut corner: Corner,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
) -> Result<Vec<ForceRow>, SolverError> {
    require_rig(&corner, Rig::Free)?;
    let patch = corner.wheel.contact_patch;
    corner.add_wheel_force("vertical force", patch, elastokin_core::Vec3::z())?;
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default())?;
    let sweep = solver.sweep(LoadPath::new(from, to, steps), mode)?;
    let local_patch = corner.model.bodies()[corner.wheel.upright.0].design_pose.to_local_point(&patch);
    Ok(sweep
        .steps
        .iter()
        .map(|s| ForceRow {
            force: s.t,
            attitude: corner.wheel.attitude(&s.poses),
            contact_patch: s.poses[corner.wheel.upright.0].point(&local_patch),
        })
        .collect())
}

/// Compliance characteristics at the contact patch, read from the wheel compliance matrix (SI: rad/N,
/// rad/(N·m), N/m). Lateral force is positive inboard (the cornering force on a loaded outer wheel),
/// longitudinal force positive rearward (braking at the contact patch), aligning torque positive about +z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchCompliance {
    /// Toe change per lateral force (rad/N).
    pub lateral_steer: f64,
    /// Camber change per lateral force (rad/N).
    pub lateral_camber: f64,
    /// Lateral stiffness at the contact patch: inboard force per inboard patch displacement (N/m).
    pub lateral_stiffness: f64,
    /// Toe change per braking force (rad/N).
    pub braking_steer: f64,
    /// Longitudinal stiffness at the contact patch under braking force (N/m).
    pub longitudinal_stiffness: f64,
    /// Toe change per aligning torque (rad/(N·m)).
    pub aligning_torque_steer: f64,
}

/// Toe and camber changes of a small rotation `dpi` of the wheel with outward spin axis `a` on side `s`.
fn attitude_change(a: &elastokin_core::Vec3, s: f64, dpi: &elastokin_core::Vec3) -> (f64, f64) {
    let da = dpi.cross(a);
    let (ax, ay, az) = (a.x, s * a.y, a.z);
    let (dax, day, daz) = (da.x, s * da.y, da.z);
    let h2 = ax * ax + ay * ay;
    let h = h2.sqrt();
    let dtoe = (ay * dax - ax * day) / h2;
    let dh = (ax * dax + ay * day) / h;
    let dcamber = (-daz * h + az * dh) / (h2 + az * az);
    (dtoe, dcamber)
}

/// [`PatchCompliance`] at the equilibrium of load parameter `t` (see [`wheel_compliance`]).
pub fn patch_compliance(corner: &Corner, t: f64) -> Result<PatchCompliance, SolverError> {
    let (c, poses) = compliance_at(corner, t)?;
    let pose = poses[corner.wheel.upright.0];
    let a = pose.direction(&corner.wheel.spin_axis_local);
    let w = pose.point(&corner.wheel.wheel_centre_local);
    let patch = corner.wheel.steering_geometry(&poses).contact_patch;
    let arm = patch - w;
    let s = corner.wheel.side.sign();
    // Response (Δ patch, Δπ) to a unit force `f` at the patch or a unit torque `m`.
    let respond = |f: elastokin_core::Vec3, m: elastokin_core::Vec3| {
        let load = [f, arm.cross(&f) + m];
        let mut out = [0.0; 6];
        for r in 0..6 {
            out[r] = (0..3).map(|k| c[r][k] * load[0][k] + c[r][3 + k] * load[1][k]).sum();
        }
        let dw = elastokin_core::Vec3::new(out[0], out[1], out[2]);
        let dpi = elastokin_core::Vec3::new(out[3], out[4], out[5]);
        (dw + dpi.cross(&arm), dpi)
    };
    let inboard = elastokin_core::Vec3::new(0.0, -s, 0.0);
    let rearward = elastokin_core::Vec3::new(-1.0, 0.0, 0.0);
    let zero = elastokin_core::Vec3::zeros();
    let (dp_lat, dpi_lat) = respond(inboard, zero);
    let (dp_long, dpi_long) = respond(rearward, zero);
    let (_, dpi_mz) = respond(zero, elastokin_core::Vec3::z());
    let (lateral_steer, lateral_camber) = attitude_change(&a, s, &dpi_lat);
    Ok(PatchCompliance {
        lateral_steer,
        lateral_camber,
        lateral_stiffness: 1.0 / dp_lat.dot(&inboard),
        braking_steer: attitude_change(&a, s, &dpi_long).0,
        longitudinal_stiffness: 1.0 / dp_long.dot(&rearward),
        aligning_torque_steer: attitude_change(&a, s, &dpi_mz).0,
    })
}
