//! Point loads: generalized force against the virtual work of a world-fixed force, load stiffness
//! against finite differences, load rate against a difference in t.

mod common;

use common::*;
use elastokin_core::{BodyId, BodyRef, ElementRole, ForceElement, Pose, RowGradient, Vec3};
use elastokin_elements::{PointForce, PointTorque};

#[test]
fn point_force_matches_virtual_work_and_its_load_stiffness() {
    let mut rng = Rng::new(31);
    for trial in 0..10 {
        let design = rng.pose(0.5);
        let point = rng.vec(0.6);
        let (f, f0) = (rng.vec(2000.0), rng.vec(500.0));
        let mut load = PointForce::new("load", BodyRef::Body(BodyId(3)), point, f).unwrap();
        if trial % 2 == 1 {
            load = load.with_constant(f0).unwrap();
        }
        let f0 = if trial % 2 == 1 { f0 } else { Vec3::zeros() };
        load.bind(&Pose::IDENTITY, &design).unwrap();
        let mut pj = design;
        pj.apply_increment(&rng.vec(0.1), &rng.rotvec(0.2, 1.5));
        let t = rng.uniform(0.1, 1.5);
        let ft = f0 + t * f;
        // Virtual work of the world-fixed force: δW = F·δP, so Q = ∂(F·P)/∂q.
        let local = design.to_local_point(&point);
        let work = |a: &Pose, b: &Pose| {
            let _ = a;
            ft.dot(&(b.position + b.rotation() * local))
        };
        let q_vw = fd_scalar(&Pose::IDENTITY, &pj, work);
        let ev = eval(&load, &Pose::IDENTITY, &pj, t);
        assert_vec_close(&format!("trial {trial}: Q"), &ev.force, &q_vw, 1e-6);
        assert!(ev.force.fixed_rows::<6>(0).amax() == 0.0, "nothing on the ground side");
        let k_fd = fd_stiffness(&load, &Pose::IDENTITY, &pj, t);
        assert_mat_close(&format!("trial {trial}: K"), &ev.stiffness, &k_fd, 1e-6);
        // Load rate ∂Q/∂t: Q is linear in t, so a difference is exact up to round-off.
        let mut rate = RowGradient::zeros();
        load.load_rate(&Pose::IDENTITY, &pj, t, &mut rate);
        let dq = (force(&load, &Pose::IDENTITY, &pj, t + 0.5) - force(&load, &Pose::IDENTITY, &pj, t - 0.5)) / 1.0;
        assert_vec_close(&format!("trial {trial}: rate"), &rate, &dq, 1e-9);
        let rep = load.report(&Pose::IDENTITY, &pj, t);
        assert!((rep.force - ft).norm() < 1e-12 && rep.torque == Vec3::zeros());
    }
}

#[test]
fn point_force_through_the_reference_point_has_no_load_stiffness() {
    // s = 0: no moment and no stiffness.
    let design = Pose::at(Vec3::new(0.1, 0.7, 0.3));
    let mut load =
        PointForce::new("wheel load", BodyRef::Body(BodyId(0)), design.position, Vec3::new(0.0, 0.0, 4000.0)).unwrap();
    load.bind(&Pose::IDENTITY, &design).unwrap();
    let ev = eval(&load, &Pose::IDENTITY, &design, 0.5);
    assert_eq!(ev.force[8], 2000.0);
    assert!(ev.stiffness.amax() == 0.0 && ev.force.fixed_rows::<3>(9).amax() == 0.0);
    assert_eq!(load.role(), ElementRole::Load);
    assert_eq!(load.bodies(), [BodyRef::Ground, BodyRef::Body(BodyId(0))]);
}

#[test]
fn point_torque_is_world_fixed_and_ramped() {
    let mut rng = Rng::new(32);
    let m = Vec3::new(10.0, -200.0, 35.0);
    let m0 = Vec3::new(1.0, 2.0, 3.0);
    let mut load = PointTorque::new("aligning torque", BodyRef::Body(BodyId(1)), m).unwrap().with_constant(m0).unwrap();
    let design = rng.pose(0.5);
    load.bind(&Pose::IDENTITY, &design).unwrap();
    let mut pj = design;
    pj.apply_increment(&rng.vec(0.1), &rng.rotvec(0.5, 1.5));
    let t = 0.7;
    let ev = eval(&load, &Pose::IDENTITY, &pj, t);
    let mut expected = RowGradient::zeros();
    expected.fixed_rows_mut::<3>(9).copy_from(&(m0 + t * m));
    assert_eq!(ev.force, expected);
    assert!(ev.stiffness.amax() == 0.0);
    assert!(fd_stiffness(&load, &Pose::IDENTITY, &pj, t).amax() == 0.0);
    let mut rate = RowGradient::zeros();
    load.load_rate(&Pose::IDENTITY, &pj, t, &mut rate);
    assert_eq!(Vec3::new(rate[9], rate[10], rate[11]), m);
    assert!(rate.fixed_rows::<9>(0).amax() == 0.0);
    let rep = load.report(&Pose::IDENTITY, &pj, t);
    assert_eq!(rep.torque, m0 + t * m);
    assert_eq!(rep.force, Vec3::zeros());
    assert_eq!(load.role(), ElementRole::Load);
}
