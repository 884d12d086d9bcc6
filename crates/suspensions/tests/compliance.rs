//! The wheel compliance matrix equals finite differences of small force and torque sweeps.

use elastokin_core::Vec3;
use elastokin_elements::{PointForce, PointTorque};
use elastokin_solver::{SolverOptions, StaticSolver};
use elastokin_suspensions::analysis::wheel_compliance;
use elastokin_suspensions::{MacPherson, Rig, Side, SuspensionFile, Template};

fn bushed_macpherson() -> MacPherson {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/macpherson.json");
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
    let upright = corner.upright.into();
    if k < 3 {
        let probe =
            PointForce::new("probe", upright, corner.wheel_centre, Vec3::zeros()).unwrap().with_constant(unit).unwrap();
        corner.model.add_element(probe).unwrap();
    } else {
        let probe = PointTorque::new("probe", upright, Vec3::zeros()).unwrap().with_constant(unit).unwrap();
        corner.model.add_element(probe).unwrap();
    }
    let mut solver =
        StaticSolver::new(&corner.model, SolverOptions { force_tolerance: 1e-13, ..SolverOptions::default() }).unwrap();
    let mut state = solver.design_state(0.0);
    solver.equilibrium(&mut state).unwrap();
    let pose = state.poses[corner.upright.0];
    (pose.point(&corner.wheel_centre_local), pose.orientation)
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
            assert!((fd - c[r][k]).abs() < 1e-5 * scale, "C[{r}][{k}] = {} vs finite difference {fd}", c[r][k]);
        }
    }
    // The rig holds the wheel-centre height: no vertical compliance.
    assert!(c[2][2].abs() < 1e-12);
    // Lateral force at the wheel centre moves it outward (y) on a bushed corner.
    assert!(c[1][1] > 0.0);
}
