//! Bushing: force against an independently written energy, stiffness against finite differences of the
//! force, closed forms at small and large deflection, and the paper's linear stiffness at design.

mod common;

use common::*;
use elastokin_core::math::{rotation_log, skew};
use elastokin_core::{BodyId, BodyRef, ElementRole, ForceElement, Mat3, PairMatrix, Pose, Vec3};
use elastokin_elements::{Bushing, BushingSpec, Characteristic};

/// Which body is the ground in a case.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Grounded {
    None,
    I,
    J,
}

struct Case {
    point: Vec3,
    frame: Mat3,
    kt: Vec3,
    kr: Vec3,
    f_pre: Vec3,
    m_pre: Vec3,
    design_i: Pose,
    design_j: Pose,
    bushing: Bushing,
}

fn random_case(rng: &mut Rng, grounded: Grounded, preload: bool) -> Case {
    let point = rng.vec(0.5);
    let frame = rng.orientation().to_rotation_matrix().into_inner();
    let kt = Vec3::new(rng.uniform(1e5, 1e6), rng.uniform(1e5, 1e6), rng.uniform(1e5, 1e6));
    let kr = Vec3::new(rng.uniform(2e3, 2e4), rng.uniform(2e3, 2e4), rng.uniform(2e3, 2e4));
    let (f_pre, m_pre) = if preload { (rng.vec(800.0), rng.vec(80.0)) } else { (Vec3::zeros(), Vec3::zeros()) };
    let design_i = if grounded == Grounded::I { Pose::IDENTITY } else { rng.pose(0.5) };
    let design_j = if grounded == Grounded::J { Pose::IDENTITY } else { rng.pose(0.5) };
    let body_i = if grounded == Grounded::I { BodyRef::Ground } else { BodyRef::Body(BodyId(0)) };
    let body_j = if grounded == Grounded::J { BodyRef::Ground } else { BodyRef::Body(BodyId(1)) };
    let mut bushing = Bushing::from_spec(BushingSpec {
        name: "bush".into(),
        body_i,
        body_j,
        point,
        frame,
        translational: Characteristic::rates(&kt),
        rotational: Characteristic::rates(&kr),
        preload_force: f_pre,
        preload_torque: m_pre,
        rotation_law: Default::default(),
    })
    .unwrap();
    bushing.bind(&design_i, &design_j).unwrap();
    Case { point, frame, kt, kr, f_pre, m_pre, design_i, design_j, bushing }
}

/// The energy written directly from its definition with rotation matrices and core's matrix logarithm.
fn energy(c: &Case, pi: &Pose, pj: &Pose) -> f64 {
    let (ai0, aj0) = (c.design_i.rotation(), c.design_j.rotation());
    let si0 = ai0.transpose() * (c.point - c.design_i.position);
    let sj0 = aj0.transpose() * (c.point - c.design_j.position);
    let e = pi.rotation() * ai0.transpose() * c.frame;
    let ej = pj.rotation() * aj0.transpose() * c.frame;
    let d = (pj.position + pj.rotation() * sj0) - (pi.position + pi.rotation() * si0);
    let delta = e.transpose() * d;
    let theta = rotation_log(&(e.transpose() * ej));
    0.5 * delta.dot(&c.kt.component_mul(&delta)) + 0.5 * theta.dot(&c.kr.component_mul(&theta))
        - c.f_pre.dot(&delta)
        - c.m_pre.dot(&theta)
}

/// A pose moved far from design: up to 5 cm and 1.5 rad.
fn moved(rng: &mut Rng, p: &Pose, grounded: bool) -> Pose {
    if grounded {
        return Pose::IDENTITY;
    }
    let mut q = *p;
    let dr = rng.vec(0.05);
    let dpi = rng.rotvec(0.3, 1.5);
    q.apply_increment(&dr, &dpi);
    q
}

#[test]
fn force_is_minus_energy_gradient_and_stiffness_is_force_derivative_at_random_poses() {
    let mut rng = Rng::new(0xB05);
    let mut max_theta: f64 = 0.0;
    for grounded in [Grounded::None, Grounded::I, Grounded::J] {
        for trial in 0..8 {
            let c = random_case(&mut rng, grounded, trial % 2 == 1);
            let pi = moved(&mut rng, &c.design_i, grounded == Grounded::I);
            let pj = moved(&mut rng, &c.design_j, grounded == Grounded::J);
            let what = format!("{grounded:?} trial {trial}");
            max_theta = max_theta.max(c.bushing.report(&pi, &pj, 0.0).rotation.norm());

            let ev = eval(&c.bushing, &pi, &pj, 0.0);
            let grad = fd_scalar(&pi, &pj, |a, b| energy(&c, a, b));
            assert_vec_close(&format!("{what}: Q = −∇U"), &ev.force, &(-grad), 1e-6);

            let k_fd = fd_stiffness(&c.bushing, &pi, &pj, 0.0);
            assert_mat_close(&format!("{what}: K"), &ev.stiffness, &k_fd, 1e-6);

            // The only non-symmetric part is the skew of the applied moments.
            let skew_part = ev.stiffness - ev.stiffness.transpose();
            assert_mat_close(&format!("{what}: K − Kᵀ"), &skew_part, &expected_skew_part(&ev.force), 1e-9);

            // An internal element is in self-equilibrium: no net force, no net moment.
            let (f, m) = resultant(&ev.force, &pi, &pj);
            let scale = ev.force.amax();
            assert!(f.norm() < 1e-9 * scale && m.norm() < 1e-9 * scale, "{what}: resultant {f:?} {m:?}");
        }
    }
    assert!(max_theta > 1.0, "the random poses should reach large rotations, got {max_theta}");
}

#[test]
fn paper_linear_stiffness_at_design() {
    // At design without preload: K = Bᵀ K_T B + Cᵀ K_R C with B = [−I, s̃ᵢ, I, −s̃ⱼ], C = [0, −I, 0, I].
    let mut rng = Rng::new(7);
    for grounded in [Grounded::None, Grounded::I, Grounded::J] {
        let c = random_case(&mut rng, grounded, false);
        let (pi, pj) = (c.design_i, c.design_j);
        let ev = eval(&c.bushing, &pi, &pj, 0.0);
        assert!(ev.force.amax() < 1e-9, "no force at design: {:?}", ev.force);
        let si = c.point - pi.position;
        let sj = c.point - pj.position;
        let kt = c.frame * Mat3::from_diagonal(&c.kt) * c.frame.transpose();
        let kr = c.frame * Mat3::from_diagonal(&c.kr) * c.frame.transpose();
        let mut b = nalgebra::SMatrix::<f64, 3, 12>::zeros();
        b.fixed_view_mut::<3, 3>(0, 0).copy_from(&(-Mat3::identity()));
        b.fixed_view_mut::<3, 3>(0, 3).copy_from(&skew(&si));
        b.fixed_view_mut::<3, 3>(0, 6).copy_from(&Mat3::identity());
        b.fixed_view_mut::<3, 3>(0, 9).copy_from(&(-skew(&sj)));
        let mut cm = nalgebra::SMatrix::<f64, 3, 12>::zeros();
        cm.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-Mat3::identity()));
        cm.fixed_view_mut::<3, 3>(0, 9).copy_from(&Mat3::identity());
        let k: PairMatrix = b.transpose() * kt * b + cm.transpose() * kr * cm;
        assert_mat_close(&format!("{grounded:?}"), &ev.stiffness, &k, 1e-9);
    }
}

fn ground_bushing(frame: Mat3, point: Vec3, design_j: &Pose) -> Bushing {
    let mut b = Bushing::new(
        "bush",
        BodyRef::Ground,
        BodyRef::Body(BodyId(0)),
        point,
        frame,
        Vec3::new(1.0e6, 2.0e6, 0.5e6),
        Vec3::new(800.0, 1500.0, 300.0),
    )
    .unwrap();
    b.bind(&Pose::IDENTITY, design_j).unwrap();
    b
}

fn part(q: &elastokin_core::RowGradient, blk: usize) -> Vec3 {
    Vec3::new(q[3 * blk], q[3 * blk + 1], q[3 * blk + 2])
}

#[test]
fn translation_of_one_body_on_a_grounded_bushing_is_linear() {
    // Frame fixed to the ground: any translation δ of j gives Fⱼ = −E K_T Eᵀ δ exactly.
    let mut rng = Rng::new(11);
    for _ in 0..5 {
        let frame = rng.orientation().to_rotation_matrix().into_inner();
        let point = rng.vec(0.4);
        let design = rng.pose(0.5);
        let b = ground_bushing(frame, point, &design);
        let delta = rng.vec(0.02);
        let pj = Pose { position: design.position + delta, ..design };
        let q = force(&b, &Pose::IDENTITY, &pj, 0.0);
        let f_expected = -(frame * Mat3::from_diagonal(&Vec3::new(1.0e6, 2.0e6, 0.5e6)) * frame.transpose() * delta);
        let arm = point - design.position;
        assert!((part(&q, 2) - f_expected).norm() < 1e-9 * f_expected.norm());
        assert!((part(&q, 3) - arm.cross(&f_expected)).norm() < 1e-9 * f_expected.norm());
        assert!((part(&q, 0) + f_expected).norm() < 1e-9 * f_expected.norm());
        let rep = b.report(&Pose::IDENTITY, &pj, 0.0);
        assert!((rep.deflection - frame.transpose() * delta).norm() < 1e-15);
        assert!((rep.force - f_expected).norm() < 1e-9 * f_expected.norm() && rep.rotation.norm() < 1e-12);
    }
}

/// Pose of a body at `design` turned by `angle` about the global `axis` through `point`.
fn turned(design: &Pose, point: &Vec3, axis: &Vec3, angle: f64) -> Pose {
    let r = rot(&(axis * angle));
    let mut p = *design;
    p.position = point + r * (design.position - point);
    p.orientation = elastokin_core::math::quat_exp(&(axis * angle)) * design.orientation;
    p
}

#[test]
fn rotation_about_a_principal_axis_gives_minus_k_theta_exactly() {
    let mut rng = Rng::new(12);
    let ks = [800.0, 1500.0, 300.0];
    for axis_index in 0..3 {
        let frame = rng.orientation().to_rotation_matrix().into_inner();
        let point = rng.vec(0.4);
        let design = rng.pose(0.5);
        let b = ground_bushing(frame, point, &design);
        let axis: Vec3 = frame.column(axis_index).into();
        for angle in [1e-4, 0.3, 1.2, -1.4] {
            let pj = turned(&design, &point, &axis, angle);
            let q = force(&b, &Pose::IDENTITY, &pj, 0.0);
            let expected = -ks[axis_index] * angle * axis;
            // Round-off of the hardpoint positions (~1e-16 m) through K_T ~ 1e6 N/m gives ~1e-9 N·m.
            let tol = 1e-9 * expected.norm() + 1e-8;
            assert!(part(&q, 2).norm() < 1e-6, "no force when turning about the bushing point: {q:?}");
            assert!(
                (part(&q, 3) - expected).norm() < tol,
                "axis {axis_index} angle {angle}: {:?} vs {expected:?}",
                part(&q, 3)
            );
            let rep = b.report(&Pose::IDENTITY, &pj, 0.0);
            assert!((rep.torque - expected).norm() < tol);
            assert!((rep.rotation - frame.transpose() * axis * angle).norm() < 1e-12);
        }
    }
}

#[test]
fn rotation_of_the_frame_carrying_body_restores_with_the_same_law() {
    // Body i (which carries the frame) turned by α about a principal axis, j the ground: the moment on i
    // is −K α a, and the force on i is zero.
    let mut rng = Rng::new(13);
    let frame = rng.orientation().to_rotation_matrix().into_inner();
    let point = rng.vec(0.4);
    let design = rng.pose(0.5);
    let mut b = Bushing::new(
        "bush",
        BodyRef::Body(BodyId(0)),
        BodyRef::Ground,
        point,
        frame,
        Vec3::new(1.0e6, 2.0e6, 0.5e6),
        Vec3::new(800.0, 1500.0, 300.0),
    )
    .unwrap();
    b.bind(&design, &Pose::IDENTITY).unwrap();
    let axis: Vec3 = frame.column(1).into();
    let alpha = 0.9;
    let pi = turned(&design, &point, &axis, alpha);
    let q = force(&b, &pi, &Pose::IDENTITY, 0.0);
    assert!(part(&q, 0).norm() < 1e-6);
    assert!((part(&q, 1) + 1500.0 * alpha * axis).norm() < 1e-9 * 1500.0);
    assert!((part(&q, 3) - 1500.0 * alpha * axis).norm() < 1e-9 * 1500.0);
}

/// Left Jacobian of SO(3) in closed form: `J_l(θ) = I + (1 − cos t)/t² θ̃ + (t − sin t)/t³ θ̃²`.
fn left_jacobian(theta: &Vec3) -> Mat3 {
    let t = theta.norm();
    let th = skew(theta);
    Mat3::identity() + (1.0 - t.cos()) / (t * t) * th + (t - t.sin()) / (t * t * t) * th * th
}

#[test]
fn large_rotation_about_a_general_axis_follows_the_rotation_vector_law() {
    // g = J_l(θ)⁻ᵀ K θ with J_l from its closed form (independent of the element's series for J_l⁻¹).
    let mut rng = Rng::new(14);
    let k = Vec3::new(800.0, 1500.0, 300.0);
    for _ in 0..5 {
        let frame = rng.orientation().to_rotation_matrix().into_inner();
        let point = rng.vec(0.4);
        let design = rng.pose(0.5);
        let b = ground_bushing(frame, point, &design);
        let theta_local = rng.rotvec(0.8, 1.5);
        let axis_global = frame * theta_local.normalize();
        let pj = turned(&design, &point, &axis_global, theta_local.norm());
        let q = force(&b, &Pose::IDENTITY, &pj, 0.0);
        let jl = left_jacobian(&theta_local);
        let g = jl.try_inverse().unwrap().transpose() * k.component_mul(&theta_local);
        let expected = -(frame * g);
        // The law is not K θ: the difference is large at this angle.
        assert!((frame * k.component_mul(&theta_local) + expected).norm() > 1e-2 * expected.norm());
        assert!((part(&q, 3) - expected).norm() < 1e-9 * expected.norm(), "{:?} vs {expected:?}", part(&q, 3));
        assert!(part(&q, 2).norm() < 1e-6);
    }
}

#[test]
fn preload_is_the_force_and_moment_applied_to_j_at_design() {
    let mut rng = Rng::new(15);
    let frame = rng.orientation().to_rotation_matrix().into_inner();
    let point = rng.vec(0.4);
    let (di, dj) = (rng.pose(0.5), rng.pose(0.5));
    let f_pre = Vec3::new(0.0, 0.0, 500.0);
    let m_pre = Vec3::new(20.0, -5.0, 0.0);
    let mut b = Bushing::new(
        "bush",
        BodyRef::Body(BodyId(0)),
        BodyRef::Body(BodyId(1)),
        point,
        frame,
        Vec3::new(1.0e6, 2.0e6, 0.5e6),
        Vec3::new(800.0, 1500.0, 300.0),
    )
    .unwrap()
    .with_preload(f_pre, m_pre)
    .unwrap();
    b.bind(&di, &dj).unwrap();
    let q = force(&b, &di, &dj, 0.0);
    let (fg, mg) = (frame * f_pre, frame * m_pre);
    assert!((part(&q, 2) - fg).norm() < 1e-9);
    assert!((part(&q, 3) - ((point - dj.position).cross(&fg) + mg)).norm() < 1e-9);
    assert!((part(&q, 0) + fg).norm() < 1e-9);
    assert!((part(&q, 1) + ((point - di.position).cross(&fg) + mg)).norm() < 1e-9);
    let rep = b.report(&di, &dj, 0.0);
    assert!((rep.force - fg).norm() < 1e-9 && (rep.torque - mg).norm() < 1e-9);
    assert_eq!(b.role(), ElementRole::Elastic);
    assert_eq!(b.bodies(), [BodyRef::Body(BodyId(0)), BodyRef::Body(BodyId(1))]);
}

#[test]
fn rotations_up_to_half_a_turn_stay_finite() {
    let mut rng = Rng::new(16);
    let frame = rng.orientation().to_rotation_matrix().into_inner();
    let point = rng.vec(0.4);
    let design = rng.pose(0.5);
    let b = ground_bushing(frame, point, &design);
    for angle in [3.0, std::f64::consts::PI - 1e-9, std::f64::consts::PI, 3.5, 6.0] {
        let pj = turned(&design, &point, &rng.unit(), angle);
        let ev = eval(&b, &Pose::IDENTITY, &pj, 0.0);
        assert!(ev.force.iter().chain(ev.stiffness.iter()).all(|v| v.is_finite()), "angle {angle}");
        assert!(b.report(&Pose::IDENTITY, &pj, 0.0).rotation.norm() <= std::f64::consts::PI + 1e-12);
    }
}
