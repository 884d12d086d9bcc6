//! The wheel compliance matrix equals finite differences of small force and torque sweeps.

use elastokin_core::Vec3;
use elastokin_elements::{PointForce, PointTorque};
use elastokin_solver::{SolverOptions, StaticSolver};
use elastokin_suspensions::analysis::wheel_compliance;
use elastokin_suspensions::{MacPherson, Rig, Side, SuspensionFile, Template};

fn bushed_macpherson() -> MacPherson {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/generic/macpherson.json");
    match SuspensionFile::read(path.as_ref()).unwrap().suspension {
        Template::MacPherson(mp) => mp,
        other => panic!("{other:?}"),
    }
}

/// Wheel-centre position and upright orientation at the equilibrium under a load (force at the wheel
/// centre for k < 3, torque for k ≥ 3) of size `size` along axis k.
fn wheel_response(k: usize, size: f64) -> (Vec3, nalgebra::UnitQuaternion<f64>) {
    let mp = bushed_macpherson();
    let mut corner = mp.build(Side::Left, Rig::WheelTravel).unwrap();
    let mut unit = Vec3::zeros();
    unit[k % 3] = size;
    // A constant load (present at t = 0): the load parameter also drives the wheel-travel driver.
    let upright = corner.wheel.upright.into();
    if k < 3 {
        let probe = PointForce::new("probe", upright, corner.wheel.wheel_centre, Vec3::zeros())
            .unwrap()
            .with_constant(unit)
            .unwrap();
        corner.model.add_element(probe).unwrap();
    } else {
        let probe = PointTorque::new("probe", upright, Vec3::zeros()).unwrap().with_constant(unit).unwrap();
        corner.model.add_element(probe).unwrap();
    }
    let mut solver =
        StaticSolver::new(&corner.model, SolverOptions { force_tolerance: 1e-13, ..SolverOptions::default() }).unwrap();
    let mut state = solver.design_state(0.0);
    solver.equilibrium(&mut state).unwrap();
    let pose = state.poses[corner.wheel.upright.0];
    (pose.point(&corner.wheel.wheel_centre_local), pose.orientation)
}

#[test]
fn compliance_matrix_equals_finite_differences_of_small_load_sweeps() {
    let corner = bushed_macpherson().build(Side::Left, Rig::WheelTravel).unwrap();
    let c = wheel_compliance(&corner, 0.0).unwrap();
    for k in 0..6 {
        let h = if k < 3 { 1.0 } else { 0.5 }; // 1 N, 0.5 N·m: deep in the linear range
        let (wp, qp) = wheel_response(k, h);
        let (wm, qm) = wheel_response(k, -h);
        // Rotation as a global (left) increment, like the compliance's Δπ.
        let (dw, dq) = (wp - wm, (qp * qm.inverse()).scaled_axis());
        let diff = [dw.x, dw.y, dw.z, dq.x, dq.y, dq.z];
        for r in 0..6 {
            let fd = diff[r] / (2.0 * h);
            let scale = c.iter().flat_map(|row| row.iter()).fold(0.0f64, |a, v| a.max(v.abs()));
            // Measured: every nonzero entry agrees to 3.6e-9 relative (C[3][0]); the held vertical column,
            // zero in C, reads 3.2e-17 m/N by differences (1.2e-11 of the largest entry).
            assert!(
                (fd - c[r][k]).abs() < 1e-7 * c[r][k].abs() + 4e-10 * scale,
                "C[{r}][{k}] = {} vs finite difference {fd}",
                c[r][k]
            );
        }
    }
    // The rig holds the wheel-centre height: no vertical compliance.
    assert!(c[2][2].abs() < 1e-12);
    // Lateral force at the wheel centre moves it outward (y) on a bushed corner.
    assert!(c[1][1] > 0.0);
}

/// Toe and camber of the equilibrium under a constant force `f` at the contact patch of the unloaded
/// equilibrium (the lowest point of the wheel there, then carried by the upright as the force grows).
fn attitude_under_patch_force(f: Vec3) -> (f64, f64, Vec3) {
    let mut corner = bushed_macpherson().build(Side::Left, Rig::WheelTravel).unwrap();
    let point = {
        let mut solver = StaticSolver::new(&corner.model, SolverOptions::default()).unwrap();
        let mut state = solver.design_state(0.0);
        solver.equilibrium(&mut state).unwrap();
        let patch = corner.wheel.steering_geometry(&state.poses).contact_patch;
        let local = state.poses[corner.wheel.upright.0].to_local_point(&patch);
        corner.model.bodies()[corner.wheel.upright.0].design_pose.point(&local)
    };
    let upright = corner.wheel.upright.into();
    let probe = PointForce::new("probe", upright, point, Vec3::zeros()).unwrap().with_constant(f).unwrap();
    corner.model.add_element(probe).unwrap();
    let mut solver =
        StaticSolver::new(&corner.model, SolverOptions { force_tolerance: 1e-13, ..SolverOptions::default() }).unwrap();
    let mut state = solver.design_state(0.0);
    solver.equilibrium(&mut state).unwrap();
    let a = corner.wheel.attitude(&state.poses);
    let patch = corner.wheel.steering_geometry(&state.poses).contact_patch;
    (a.toe, a.camber, patch)
}

#[test]
fn compliance_steer_and_camber_equal_finite_differences_of_patch_force_sweeps() {
    let corner = bushed_macpherson().build(Side::Left, Rig::WheelTravel).unwrap();
    let pc = elastokin_suspensions::analysis::patch_compliance(&corner, 0.0).unwrap();
    let h = 2.0; // N
    let inboard = Vec3::new(0.0, -1.0, 0.0);
    let (tp, cp, pp) = attitude_under_patch_force(inboard * h);
    let (tm, cm, pm) = attitude_under_patch_force(-inboard * h);
    let steer = (tp - tm) / (2.0 * h);
    let camber = (cp - cm) / (2.0 * h);
    let stiffness = 2.0 * h / (pp - pm).dot(&inboard);
    assert!(
        // Measured 4.4e-10 relative.
        (steer - pc.lateral_steer).abs() < 2e-8 * pc.lateral_steer.abs(),
        "{steer:e} vs {:e}",
        pc.lateral_steer
    );
    assert!(
        // Measured 1.5e-10 relative.
        (camber - pc.lateral_camber).abs() < 1e-8 * pc.lateral_camber.abs(),
        "{camber:e} vs {:e}",
        pc.lateral_camber
    );
    assert!(
        // Measured 8.7e-6 relative.
        (stiffness - pc.lateral_stiffness).abs() < 1e-4 * pc.lateral_stiffness,
        "{stiffness} vs {}",
        pc.lateral_stiffness
    );
    let rear = Vec3::new(-1.0, 0.0, 0.0);
    let (tp, _, _) = attitude_under_patch_force(rear * h);
    let (tm, _, _) = attitude_under_patch_force(-rear * h);
    let braking = (tp - tm) / (2.0 * h);
    assert!(
        // Measured 2.0e-9 relative.
        (braking - pc.braking_steer).abs() < 1e-7 * pc.braking_steer.abs(),
        "{braking:e} vs {:e}",
        pc.braking_steer
    );
    // A bushed corner steers measurably under side force: more than 0.01°/kN.
    assert!(pc.lateral_steer.abs().to_degrees() * 1e3 > 0.01, "{}", pc.lateral_steer.to_degrees() * 1e3);
}
