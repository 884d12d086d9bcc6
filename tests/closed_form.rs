//! Whole-pipeline checks against closed-form mechanics.

mod common;
use common::*;
use elastokin::core::math::{quat_exp, rotation_log};
use elastokin::elements::{Bushing, CoilSpring, PointForce, PointTorque};
use elastokin::prelude::*;
use elastokin::solver::BackendChoice;

fn bushing_frame() -> Mat3 {
    nalgebra::Rotation3::from_euler_angles(0.3, -0.2, 0.5).into_inner()
}

fn body_on_bushing(kt: Vec3, kr: Vec3, force: Vec3, torque: Vec3) -> Model {
    let mut m = Model::new();
    let p = Vec3::new(0.1, 0.7, -0.2);
    let body = m.add_body("knuckle", Pose::at(p)).unwrap();
    m.add_element(Bushing::new("mount", BodyRef::Ground, body.into(), p, bushing_frame(), kt, kr).unwrap()).unwrap();
    if force != Vec3::zeros() {
        m.add_element(PointForce::new("force", body.into(), p, force).unwrap()).unwrap();
    }
    if torque != Vec3::zeros() {
        m.add_element(PointTorque::new("torque", body.into(), torque).unwrap()).unwrap();
    }
    m
}

#[test]
fn bushing_deflects_by_inverse_stiffness_times_force() {
    // The force acts at the bushing centre, so no moment arises: δ = E K⁻¹ Eᵀ F exactly, at any size.
    let kt = Vec3::new(2e6, 5e5, 8e6);
    let kr = Vec3::new(1e3, 2e3, 3e3);
    let f = Vec3::new(300.0, -1200.0, 4000.0);
    let m = body_on_bushing(kt, kr, f, Vec3::zeros());
    let mut solver = StaticSolver::new(&m, tight()).unwrap();
    let sweep = solver.sweep(LoadPath::new(0.0, 1.0, 4), Mode::Corrected).unwrap();
    let e = bushing_frame();
    let local = e.transpose() * f;
    let expected = e * Vec3::new(local.x / kt.x, local.y / kt.y, local.z / kt.z);
    let last = sweep.steps.last().unwrap();
    let moved = last.poses[0].position - Vec3::new(0.1, 0.7, -0.2);
    assert!((moved - expected).norm() < 1e-12 * (1.0 + expected.norm()), "{moved:?} vs {expected:?}");
    assert!(last.poses[0].orientation.angle() < 1e-12);
    // The bushing reports the force it applies to the body: −F.
    let report = last.element_reports(&m)[0];
    assert!((report.force + f).norm() < 1e-6, "{:?}", report.force);
}

/// On both backends: a world-fixed torque that twists the bushing ~1 rad gives a large skew part, which the
/// dense LU factorizes and the sparse LDLᵀ leaves to GMRES.
#[test]
fn bushing_twists_by_the_rotation_vector_law_at_large_torque() {
    for backend in [BackendChoice::Dense, BackendChoice::Sparse] {
        twist_by_the_rotation_vector_law(SolverOptions { backend, ..SolverOptions::default() });
    }
}

fn twist_by_the_rotation_vector_law(options: SolverOptions) {
    let kt = Vec3::new(1e6, 1e6, 1e6);
    let kr = Vec3::new(500.0, 800.0, 1500.0);
    let e = bushing_frame();
    // Principal axis: θ = M / K exactly, however large.
    let m_u = 0.9 * 500.0; // 0.9 rad about local x
    let m = body_on_bushing(kt, kr, Vec3::zeros(), e * Vec3::new(m_u, 0.0, 0.0));
    let mut solver = StaticSolver::new(&m, options.clone()).unwrap();
    let sweep = solver.sweep(LoadPath::new(0.0, 1.0, 5), Mode::Corrected).unwrap();
    let rel = e.transpose() * sweep.steps.last().unwrap().poses[0].rotation() * e;
    let theta = rotation_log(&rel);
    assert!((theta - Vec3::new(0.9, 0.0, 0.0)).norm() < 1e-10, "{theta:?}");

    // Off-axis: pick the twist θ* and find the torque that holds it from the energy U = ½θᵀKθ by a
    // finite difference along left rotations (independent of the element's formula), then solve.
    let theta_star = Vec3::new(0.6, -0.5, 0.7);
    let k = Mat3::from_diagonal(&kr);
    let energy = |r: &Mat3| {
        let t = rotation_log(r);
        0.5 * t.dot(&(k * t))
    };
    let r_star = quat_exp(&theta_star).to_rotation_matrix().into_inner();
    let h = 1e-6;
    let mut torque_local = Vec3::zeros();
    for c in 0..3 {
        let mut w = Vec3::zeros();
        w[c] = h;
        let rp = quat_exp(&w).to_rotation_matrix().into_inner() * r_star;
        let rm = quat_exp(&-w).to_rotation_matrix().into_inner() * r_star;
        torque_local[c] = (energy(&rp) - energy(&rm)) / (2.0 * h);
    }
    let m = body_on_bushing(kt, kr, Vec3::zeros(), e * torque_local);
    let mut solver = StaticSolver::new(&m, options.clone()).unwrap();
    let sweep = solver.sweep(LoadPath::new(0.0, 1.0, 10), Mode::Corrected).unwrap();
    let rel = e.transpose() * sweep.steps.last().unwrap().poses[0].rotation() * e;
    let theta = rotation_log(&rel);
    assert!((theta - theta_star).norm() < 1e-7, "{theta:?} vs {theta_star:?}");
}

#[test]
fn lever_on_revolute_with_spring_reaches_the_closed_form_angle_and_reaction() {
    let l0 = lever_spring_design_length();
    let m = lever(Pivot::Revolute, l0);
    let mut solver = StaticSolver::new(&m, tight()).unwrap();
    let sweep = solver.sweep(LoadPath::new(0.0, 1.0, 10), Mode::Corrected).unwrap();
    for step in &sweep.steps {
        let expected = lever_angle(F_TIP * step.t, l0);
        let phi = rotation_about_y(&step.poses[0]);
        assert!((phi - expected).abs() < 1e-9, "t={} φ={phi} expected {expected}", step.t);
    }
    let last = sweep.steps.last().unwrap();
    let phi = lever_angle(F_TIP, l0);
    assert!(phi.to_degrees() > 35.0, "the test should reach a large angle, got {}°", phi.to_degrees());
    // Hand-computed reaction: the pivot balances the tip load and the spring force on the lever.
    let p = B * Vec3::new(phi.cos(), 0.0, -phi.sin());
    let g = Vec3::new(0.0, 0.0, H);
    let len = (p - g).norm();
    let push = K_SPRING * (l0 - len);
    let spring_on_lever = push * (p - g) / len;
    let expected = -(Vec3::new(0.0, 0.0, -F_TIP) + spring_on_lever);
    let reaction = last.joint_reactions(&m)[0];
    assert!((reaction.force - expected).norm() < 1e-6 * F_TIP, "{:?} vs {expected:?}", reaction.force);
    // A hinge about y carries no moment about y.
    assert!(reaction.torque.y.abs() < 1e-6, "{:?}", reaction.torque);
}

#[test]
fn preloaded_spring_finds_equilibrium_from_a_design_that_is_not_at_rest() {
    // No load (t = 0) but the spring's free length differs from its design length: the lever must swing
    // to where the spring is at its free length (the only equilibrium with cos φ ≠ 0 at zero load).
    let l0 = lever_spring_design_length() * 1.15;
    let m = lever(Pivot::Revolute, l0);
    let mut solver = StaticSolver::new(&m, tight()).unwrap();
    let mut state = solver.design_state(0.0);
    let eq = solver.equilibrium(&mut state).unwrap();
    let phi = rotation_about_y(&eq.poses[0]);
    assert!((phi - lever_angle(0.0, l0)).abs() < 1e-10, "φ={phi}");
    assert!(eq.iterations > 1);
}

/// Slider-crank: crank on a revolute about +y at the origin (radius R), rod from the crank pin to the
/// slider (spherical at the crank, universal at the slider), slider on a translational joint along x, a
/// coil spring from the slider to a chassis seat further along x, a torque M about +y on the crank.
#[test]
fn slider_crank_with_spring_matches_virtual_work() {
    const R: f64 = 0.1;
    const L: f64 = 0.3;
    const K: f64 = 5e4;
    const M: f64 = 150.0;
    // Crank angle θ about +y (θ = 0: pin on +x); the design stands well away from dead centre.
    let x_of = |th: f64| R * th.cos() + (L * L - R * R * th.sin().powi(2)).sqrt();
    let dx_of = |th: f64| -R * th.sin() - R * R * th.sin() * th.cos() / (L * L - R * R * th.sin().powi(2)).sqrt();
    let theta0 = 0.6;
    let xb0 = x_of(theta0);
    let xg = 0.7;
    let pin = R * Vec3::new(theta0.cos(), 0.0, -theta0.sin());
    let b = Vec3::new(xb0, 0.0, 0.0);
    let mut m = Model::new();
    let crank = m.add_body("crank", Pose::at(pin / 2.0)).unwrap();
    let rod = m.add_body("rod", Pose::at((pin + b) / 2.0)).unwrap();
    let slider = m.add_body("slider", Pose::at(b)).unwrap();
    m.add_joint(JointSpec::revolute("crank bearing", BodyRef::Ground, crank, Vec3::zeros(), Vec3::y())).unwrap();
    m.add_joint(JointSpec::spherical("crank pin", crank, rod, pin)).unwrap();
    m.add_joint(JointSpec::universal("wrist pin", rod, slider, b, Vec3::y(), Vec3::z())).unwrap();
    m.add_joint(JointSpec::translational("slideway", BodyRef::Ground, slider, b, Vec3::x())).unwrap();
    let free = (xg - xb0) + 0.02; // compressed by 20 mm at design
    m.add_element(
        CoilSpring::new("return spring", slider.into(), b, BodyRef::Ground, Vec3::new(xg, 0.0, 0.0), K, free).unwrap(),
    )
    .unwrap();
    m.add_element(PointTorque::new("crank torque", crank.into(), Vec3::new(0.0, M, 0.0)).unwrap()).unwrap();
    let mut solver = StaticSolver::new(&m, tight()).unwrap();
    assert!(solver.diagnostics().redundant.is_empty(), "{:?}", solver.diagnostics());
    let sweep = solver.sweep(LoadPath::new(0.0, 1.0, 8), Mode::Corrected).unwrap();

    // Virtual work: x(θ) = R cos θ + √(L² − R² sin² θ); spring push on the slider −k(L₀ − (x_g − x)) along x;
    // M + F_x dx/dθ = 0, solved for θ by bisection.
    let fx_of = |th: f64| -K * (free - (xg - x_of(th)));
    let g = |th: f64| M + fx_of(th) * dx_of(th);
    let (mut lo, mut hi) = (-0.9f64, 1.5f64);
    assert!(g(lo).signum() != g(hi).signum());
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(lo).signum() == g(mid).signum() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let theta = 0.5 * (lo + hi);
    let last = sweep.steps.last().unwrap();
    let got = theta0 + rotation_about_y(&last.poses[0]);
    assert!((got - theta).abs() < 1e-9, "θ {got} vs {theta}");
    assert!((theta - theta0).abs() > 0.3, "the test should swing the crank well away from design, θ = {theta}");
    let xb = last.poses[2].position.x;
    assert!((xb - x_of(theta)).abs() < 1e-9);
    // The rod is a two-force member: the bearing reaction on the crank is T e_AB with T from the slider's
    // x-balance, T e_AB,x + F_x = 0.
    let a = R * Vec3::new(theta.cos(), 0.0, -theta.sin());
    let e_ab = (Vec3::new(x_of(theta), 0.0, 0.0) - a) / L;
    let tension = -fx_of(theta) / e_ab.x;
    let expected = e_ab * tension;
    let reaction = last.joint_reactions(&m)[0];
    assert!((reaction.force - expected).norm() < 1e-6 * expected.norm(), "{:?} vs {expected:?}", reaction.force);
}
