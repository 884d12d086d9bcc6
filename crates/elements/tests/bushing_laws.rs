//! The bushing's rotation laws: each one's stiffness against finite differences of its force at large
//! rotations, the conservative ones' force against an energy written here, and each one's moment against
//! its closed form at a large twist.

mod common;

use common::*;
use elastokin_core::math::rotation_log;
use elastokin_core::{BodyId, BodyRef, ForceElement, Mat3, Pose, Vec3};
use elastokin_elements::{Bushing, BushingSpec, Characteristic, RotationLaw};

const LAWS: [RotationLaw; 3] = [RotationLaw::Energy, RotationLaw::Linear, RotationLaw::TaitBryanXyz];

/// A bushing from the ground to body 0 at the origin, frame = identity, with `law`.
fn grounded(kr: Vec3, m_pre: Vec3, law: RotationLaw) -> Bushing {
    let mut b = Bushing::from_spec(BushingSpec {
        name: "bush".into(),
        body_i: BodyRef::Ground,
        body_j: BodyRef::Body(BodyId(0)),
        point: Vec3::zeros(),
        frame: Mat3::identity(),
        translational: Characteristic::rates(&Vec3::new(1e6, 2e6, 3e6)),
        rotational: Characteristic::rates(&kr),
        preload_force: Vec3::zeros(),
        preload_torque: m_pre,
        rotation_law: law,
    })
    .unwrap();
    b.bind(&Pose::IDENTITY, &Pose::IDENTITY).unwrap();
    b
}

fn rx(a: f64) -> Mat3 {
    let (s, c) = a.sin_cos();
    Mat3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}
fn ry(b: f64) -> Mat3 {
    let (s, c) = b.sin_cos();
    Mat3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c)
}
fn rz(c: f64) -> Mat3 {
    let (s, co) = c.sin_cos();
    Mat3::new(co, -s, 0.0, s, co, 0.0, 0.0, 0.0, 1.0)
}

fn pose_with(r: Mat3) -> Pose {
    let q = nalgebra::UnitQuaternion::from_rotation_matrix(&nalgebra::Rotation3::from_matrix_unchecked(r));
    Pose { position: Vec3::zeros(), orientation: q }
}

/// Tait-Bryan x-y-z angles by a search over the closed-form construction: the angles whose
/// `Rx(a) Ry(b) Rz(c)` equals `r` (Newton on the nine entries; independent of the library's extraction).
fn angles_of(r: &Mat3) -> Vec3 {
    let mut phi = Vec3::zeros();
    for _ in 0..50 {
        let f = |p: &Vec3| rx(p.x) * ry(p.y) * rz(p.z);
        let res = f(&phi) - r;
        let mut jac = nalgebra::SMatrix::<f64, 9, 3>::zeros();
        for k in 0..3 {
            let mut d = Vec3::zeros();
            d[k] = 1e-7;
            let col = (f(&(phi + d)) - f(&(phi - d))) / 2e-7;
            jac.set_column(k, &nalgebra::SVector::<f64, 9>::from_iterator(col.iter().copied()));
        }
        let rhs = nalgebra::SVector::<f64, 9>::from_iterator(res.iter().copied());
        let step = (jac.transpose() * jac).try_inverse().unwrap() * jac.transpose() * rhs;
        phi -= step;
        if step.norm() < 1e-15 {
            break;
        }
    }
    phi
}

/// At random large rotations (up to ~1.2 rad) and with preload, the stiffness of every law is the
/// derivative of its force, and the element stays in self-equilibrium.
#[test]
fn every_law_has_the_derivative_of_its_force_as_stiffness() {
    let mut rng = Rng::new(0x1A5);
    for law in LAWS {
        for trial in 0..6 {
            let kr = Vec3::new(rng.uniform(2e2, 2e3), rng.uniform(2e3, 2e4), rng.uniform(2e3, 2e4));
            let m_pre = if trial % 2 == 1 { rng.vec(50.0) } else { Vec3::zeros() };
            let b = grounded(kr, m_pre, law);
            let mut pj = Pose::IDENTITY;
            pj.apply_increment(&rng.vec(0.02), &rng.rotvec(0.2, 1.2));
            let what = format!("{law:?} trial {trial}");
            let ev = eval(&b, &Pose::IDENTITY, &pj, 0.0);
            let k_fd = fd_stiffness(&b, &Pose::IDENTITY, &pj, 0.0);
            assert_mat_close(&format!("{what}: K"), &ev.stiffness, &k_fd, 1e-6);
            // A law from an energy has no asymmetry but the skew of the applied moments; `Linear` has more
            // (measured, of the largest entry: 4.5e-4 to 2.8e-3 for `Linear`, below 1e-18 for the others).
            let extra = ev.stiffness - ev.stiffness.transpose() - expected_skew_part(&ev.force);
            let relative = extra.amax() / ev.stiffness.amax();
            match law {
                RotationLaw::Linear => assert!(relative > 1e-4, "{what}: {relative}"),
                _ => assert!(relative < 1e-16, "{what}: {relative}"),
            }
        }
    }
}

/// The conservative laws' force is minus the gradient of their energy, written here from the relative
/// rotation: `½ θᵀKθ − M_preᵀθ` of the rotation vector, `½ φᵀKφ − M_preᵀφ` of the Tait-Bryan angles.
#[test]
fn the_conservative_laws_derive_from_their_energy() {
    let mut rng = Rng::new(0xE6);
    let kt = Vec3::new(1e6, 2e6, 3e6);
    for law in [RotationLaw::Energy, RotationLaw::TaitBryanXyz] {
        for _ in 0..5 {
            let kr = Vec3::new(rng.uniform(2e2, 2e3), rng.uniform(2e3, 2e4), rng.uniform(2e3, 2e4));
            let m_pre = rng.vec(50.0);
            let b = grounded(kr, m_pre, law);
            let mut pj = Pose::IDENTITY;
            pj.apply_increment(&rng.vec(0.02), &rng.rotvec(0.2, 1.0));
            // The bushing sits at both bodies' origins with the identity frame at design: its frame rides
            // on `i`, so the deflection and the rotation are read in `i`'s axes.
            let energy = |pi: &Pose, p: &Pose| {
                let r = pi.rotation().transpose() * p.rotation();
                let rot = match law {
                    RotationLaw::TaitBryanXyz => angles_of(&r),
                    _ => rotation_log(&r),
                };
                let d = pi.rotation().transpose() * (p.position - pi.position);
                0.5 * d.dot(&kt.component_mul(&d)) + 0.5 * rot.dot(&kr.component_mul(&rot)) - m_pre.dot(&rot)
            };
            let grad = fd_scalar(&Pose::IDENTITY, &pj, energy);
            let ev = eval(&b, &Pose::IDENTITY, &pj, 0.0);
            assert_vec_close(&format!("{law:?}: Q = −∇U"), &ev.force, &(-grad), 1e-6);
        }
    }
}

/// Closed forms at a large twist. `Linear`: the moment on `j` is `−K θ` for any rotation vector.
/// `TaitBryanXyz`: for `R = Rx(a) Ry(b) Rz(c)`, virtual work along each gimbal axis (`x`, `Rx(a) y`,
/// `Rx(a) Ry(b) z`) gives the moment's component about it as minus that angle's rate times the angle.
/// `Energy`: about a rate-equal axis pair the moment is `−Kθ` too; the example of the law's docs
/// (torsion 500, conical 4000 N·m/rad, θ = (0.10, 0, 0.01) rad) against its published figures.
#[test]
fn each_law_meets_its_closed_form_at_a_large_twist() {
    let kr = Vec3::new(500.0, 4000.0, 3000.0);
    // Linear.
    let theta = Vec3::new(0.8, -0.4, 0.3);
    let b = grounded(kr, Vec3::zeros(), RotationLaw::Linear);
    let pj = pose_with(elastokin_core::math::quat_exp(&theta).to_rotation_matrix().into_inner());
    let m = b.report(&Pose::IDENTITY, &pj, 0.0).torque;
    assert!((m + kr.component_mul(&theta)).norm() < 1e-9 * m.norm(), "{m:?}");
    // Tait-Bryan x-y-z.
    let (a, bb, c) = (0.5, 0.3, -0.4);
    let b = grounded(kr, Vec3::zeros(), RotationLaw::TaitBryanXyz);
    let m = b.report(&Pose::IDENTITY, &pose_with(rx(a) * ry(bb) * rz(c)), 0.0).torque;
    let axes = [Vec3::x(), rx(a) * Vec3::y(), rx(a) * ry(bb) * Vec3::z()];
    for (k, (axis, angle)) in axes.iter().zip([a, bb, c]).enumerate() {
        let expected = -kr[k] * angle;
        assert!((m.dot(axis) - expected).abs() < 1e-9 * expected.abs(), "axis {k}: {} vs {expected}", m.dot(axis));
    }
    // The law docs' example, all three laws (moment on j, local = global here).
    let kr = Vec3::new(500.0, 4000.0, 4000.0);
    let theta = Vec3::new(0.10, 0.0, 0.01);
    let pj = pose_with(elastokin_core::math::quat_exp(&theta).to_rotation_matrix().into_inner());
    let moment = |law| grounded(kr, Vec3::zeros(), law).report(&Pose::IDENTITY, &pj, 0.0).torque;
    let (energy, linear, tait_bryan) =
        (moment(RotationLaw::Energy), moment(RotationLaw::Linear), moment(RotationLaw::TaitBryanXyz));
    let close = |a: Vec3, b: [f64; 3]| (a - Vec3::from(b)).amax() < 1e-3;
    assert!(close(energy, [-50.003, 1.750, -39.971]), "{energy:?}");
    // The figures above are the law's docs', read off this code; the energy law's moment from its energy
    // `½ θᵀKθ`, written here and differentiated along `j`'s rotation increments, is the independent check.
    let u = |pi: &Pose, p: &Pose| {
        let rot = rotation_log(&(pi.rotation().transpose() * p.rotation()));
        0.5 * rot.dot(&kr.component_mul(&rot))
    };
    let grad = fd_scalar(&Pose::IDENTITY, &pj, u);
    let expected = -Vec3::new(grad[9], grad[10], grad[11]);
    assert!((energy - expected).amax() < 1e-6 * expected.amax(), "{energy:?} vs {expected:?}");
    assert!(close(linear, [-50.0, 0.0, -40.0]), "{linear:?}");
    // The Tait-Bryan moment from its gimbal-axis form, written here: the angles of this rotation by the
    // test's own search, the axes built from them, and the moment whose component about each axis is
    // minus that angle's rate times the angle. The law's docs quote it to three decimals.
    let phi = angles_of(&elastokin_core::math::quat_exp(&theta).to_rotation_matrix().into_inner());
    let axes = Mat3::from_columns(&[Vec3::x(), rx(phi.x) * Vec3::y(), rx(phi.x) * ry(phi.y) * Vec3::z()]);
    let expected = -(axes.transpose().try_inverse().unwrap() * kr.component_mul(&phi));
    assert!((tait_bryan - expected).amax() < 1e-9 * expected.amax(), "{tait_bryan:?} vs {expected:?}");
    assert!(close(expected, [-49.999, 1.996, -39.909]), "{expected:?}");
}
