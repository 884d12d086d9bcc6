//! The compliance of a corner's wheel at an equilibrium: the 6×6 response of the wheel centre to unit
//! forces and torques there (one factorization, six back-substitutions), and the compliance steer,
//! camber and stiffness at the contact patch read from it.

use crate::assembly::Corner;
use crate::wheel::Wheel;
use elastokin_core::Vec3;
use elastokin_solver::replay::{Taping, NO_TAPING};
use elastokin_solver::{SolverError, SolverOptions, State, StaticSolver};

/// The 6×6 compliance of the wheel at the equilibrium of load parameter `t`: column `k` is the response
/// `(Δ wheel centre, Δ rotation)` to a unit force (k < 3, N, global axes) or unit torque (k ≥ 3, N·m) at
/// the wheel centre, in m/N and rad/(N·m). It is the inverse tangent of the constrained system, so it
/// costs one factorization and six back-substitutions. Drivers present in the corner stay held (a
/// wheel-travel driver makes the vertical row and column zero, as on a K&C rig holding the wheel-centre
/// height). With a partner wheel (a solid axle) each unit load acts on both wheels alike, in phase, as the
/// load sweeps apply them; the response is the corner's own wheel's.
pub fn wheel_compliance(corner: &Corner, t: f64) -> Result<[[f64; 6]; 6], SolverError> {
    Ok(compliance_at(corner, t, &NO_TAPING)?.wheel)
}

/// The wheel compliance at an equilibrium, with the solver that found it and factorized its tangent there:
/// what else is read off that tangent (the patch compliance, a path tangent) takes no solver, equilibrium
/// or factorization of its own.
pub(crate) struct ComplianceAt<'m> {
    /// The wheel compliance ([`wheel_compliance`]).
    pub wheel: [[f64; 6]; 6],
    /// The solver of the corner's model, its tangent at `state` factorized.
    pub solver: StaticSolver<'m>,
    /// The equilibrium.
    pub state: State,
    /// The equilibrium as the solve returned it (to take a Newton iteration on from it).
    pub at: elastokin_solver::StepResult,
}

/// The wheel compliance at the equilibrium of load parameter `t`, and the solver and equilibrium it was
/// taken at, the solver taking part in `taping`.
pub(crate) fn compliance_at<'c>(corner: &'c Corner, t: f64, taping: &Taping) -> Result<ComplianceAt<'c>, SolverError> {
    let mut solver = StaticSolver::taped(&corner.model, SolverOptions::default(), taping)?;
    let mut state = solver.design_state(t);
    let at = solver.equilibrium(&mut state)?;
    let wheel = compliance_with(&mut solver, &corner.wheel, corner.partner.as_ref(), &state)?;
    Ok(ComplianceAt { wheel, solver, state, at })
}

/// The wheel compliance at `state` (an equilibrium of `solver`'s model): see [`wheel_compliance`].
pub(crate) fn compliance_with(
    solver: &mut StaticSolver,
    wheel: &Wheel,
    partner: Option<&Wheel>,
    state: &elastokin_solver::State,
) -> Result<[[f64; 6]; 6], SolverError> {
    let n = solver.model().dofs();
    let m = solver.active_rows().len();
    // Generalized force on `w`'s upright of a force `f` at its wheel centre and a torque `moment`.
    let load = |rhs: &mut [f64], w: &Wheel, f: Vec3, moment: Vec3| {
        let pose = state.poses[w.upright.0];
        let arm = pose.point(&w.wheel_centre_local) - pose.position;
        let (f, moment) = (f, arm.cross(&f) + moment);
        let base = w.upright.0 * elastokin_core::BODY_DOFS;
        for c in 0..3 {
            rhs[base + c] += f[c];
            rhs[base + 3 + c] += moment[c];
        }
    };
    let pose = state.poses[wheel.upright.0];
    let s = pose.point(&wheel.wheel_centre_local) - pose.position;
    let base = wheel.upright.0 * elastokin_core::BODY_DOFS;
    let mut columns = [[0.0; 6]; 6];
    let mut rhs = vec![0.0; n + m];
    solver.factorize_tangent(state)?;
    for (k, column) in columns.iter_mut().enumerate() {
        rhs.fill(0.0);
        let mut unit = Vec3::zeros();
        unit[k % 3] = 1.0;
        // A force at the wheel centre, or a torque.
        let (f, moment) = if k < 3 { (unit, Vec3::zeros()) } else { (Vec3::zeros(), unit) };
        load(&mut rhs, wheel, f, moment);
        if let Some(partner) = partner {
            // The same load on the partner's wheel centre, in phase (as `Corner::add_wheel_force`).
            load(&mut rhs, partner, f, moment);
        }
        solver.solve_factored(&mut rhs)?;
        let dr = Vec3::new(rhs[base], rhs[base + 1], rhs[base + 2]);
        let dpi = Vec3::new(rhs[base + 3], rhs[base + 4], rhs[base + 5]);
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
    Ok(out)
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
fn attitude_change(a: &Vec3, s: f64, dpi: &Vec3) -> (f64, f64) {
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
    let at = compliance_at(corner, t, &NO_TAPING)?;
    Ok(patch_compliance_from(corner, &at.wheel, &at.state.poses))
}

/// [`PatchCompliance`] from the wheel compliance `c` at the equilibrium `poses`.
pub(crate) fn patch_compliance_from(
    corner: &Corner,
    c: &[[f64; 6]; 6],
    poses: &[elastokin_core::Pose],
) -> PatchCompliance {
    let pose = poses[corner.wheel.upright.0];
    let a = pose.direction(&corner.wheel.spin_axis_local);
    let w = pose.point(&corner.wheel.wheel_centre_local);
    let patch = corner.wheel.steering_geometry(poses).contact_patch;
    let arm = patch - w;
    let s = corner.wheel.side.sign();
    // Response (Δ patch, Δπ) to a unit force `f` at the patch or a unit torque `m`.
    let respond = |f: Vec3, m: Vec3| {
        let load = [f, arm.cross(&f) + m];
        let mut out = [0.0; 6];
        for r in 0..6 {
            out[r] = (0..3).map(|k| c[r][k] * load[0][k] + c[r][3 + k] * load[1][k]).sum();
        }
        let dw = Vec3::new(out[0], out[1], out[2]);
        let dpi = Vec3::new(out[3], out[4], out[5]);
        (dw + dpi.cross(&arm), dpi)
    };
    let inboard = Vec3::new(0.0, -s, 0.0);
    let rearward = Vec3::new(-1.0, 0.0, 0.0);
    let zero = Vec3::zeros();
    let (dp_lat, dpi_lat) = respond(inboard, zero);
    let (dp_long, dpi_long) = respond(rearward, zero);
    let (_, dpi_mz) = respond(zero, Vec3::z());
    let (lateral_steer, lateral_camber) = attitude_change(&a, s, &dpi_lat);
    PatchCompliance {
        lateral_steer,
        lateral_camber,
        lateral_stiffness: 1.0 / dp_lat.dot(&inboard),
        braking_steer: attitude_change(&a, s, &dpi_long).0,
        longitudinal_stiffness: 1.0 / dp_long.dot(&rearward),
        aligning_torque_steer: attitude_change(&a, s, &dpi_mz).0,
    }
}
