//! Coil spring: force against its energy, stiffness against finite differences, the string tangent in
//! closed form, symmetry where it holds, and the degenerate zero length.

mod common;

use common::*;
use elastokin_core::{BodyId, BodyRef, ElementRole, ForceElement, Mat3, Pose, Vec3};
use elastokin_elements::{Characteristic, CoilSpring, CoilSpringSpec, SpringLength};

struct Case {
    point_i: Vec3,
    point_j: Vec3,
    k: f64,
    l0: f64,
    p: f64,
    design_i: Pose,
    design_j: Pose,
    spring: CoilSpring,
}

fn random_case(rng: &mut Rng, ground_i: bool, ground_j: bool) -> Case {
    let point_i = rng.vec(0.3);
    let point_j = point_i + rng.unit() * rng.uniform(0.2, 0.4);
    let k = rng.uniform(2e4, 1e5);
    let l0 = (point_j - point_i).norm() + rng.uniform(-0.05, 0.1);
    let p = rng.uniform(-1000.0, 1000.0);
    let design_i = if ground_i { Pose::IDENTITY } else { rng.pose(0.5) };
    let design_j = if ground_j { Pose::IDENTITY } else { rng.pose(0.5) };
    let bi = if ground_i { BodyRef::Ground } else { BodyRef::Body(BodyId(0)) };
    let bj = if ground_j { BodyRef::Ground } else { BodyRef::Body(BodyId(1)) };
    let mut spring = CoilSpring::new("spring", bi, point_i, bj, point_j, k, l0).unwrap().with_preload(p).unwrap();
    spring.bind(&design_i, &design_j).unwrap();
    Case { point_i, point_j, k, l0, p, design_i, design_j, spring }
}

fn seats(c: &Case, pi: &Pose, pj: &Pose) -> (Vec3, Vec3) {
    let si0 = c.design_i.rotation().transpose() * (c.point_i - c.design_i.position);
    let sj0 = c.design_j.rotation().transpose() * (c.point_j - c.design_j.position);
    (pi.position + pi.rotation() * si0, pj.position + pj.rotation() * sj0)
}

/// `U = ½ k (L − L₀)² − P L`, written from the seats.
fn energy(c: &Case, pi: &Pose, pj: &Pose) -> f64 {
    let (a, b) = seats(c, pi, pj);
    let l = (b - a).norm();
    0.5 * c.k * (l - c.l0).powi(2) - c.p * l
}

fn moved(rng: &mut Rng, p: &Pose, grounded: bool) -> Pose {
    if grounded {
        return Pose::IDENTITY;
    }
    let mut q = *p;
    q.apply_increment(&rng.vec(0.08), &rng.rotvec(0.2, 1.5));
    q
}

#[test]
fn force_is_minus_energy_gradient_and_stiffness_is_force_derivative_at_random_poses() {
    let mut rng = Rng::new(0x5e1);
    for (gi, gj) in [(false, false), (true, false), (false, true)] {
        for trial in 0..8 {
            let c = random_case(&mut rng, gi, gj);
            let pi = moved(&mut rng, &c.design_i, gi);
            let pj = moved(&mut rng, &c.design_j, gj);
            let what = format!("ground ({gi},{gj}) trial {trial}");
            let ev = eval(&c.spring, &pi, &pj, 0.0);
            let grad = fd_scalar(&pi, &pj, |a, b| energy(&c, a, b));
            assert_vec_close(&format!("{what}: Q = −∇U"), &ev.force, &(-grad), 1e-6);
            let k_fd = fd_stiffness(&c.spring, &pi, &pj, 0.0);
            assert_mat_close(&format!("{what}: K"), &ev.stiffness, &k_fd, 1e-6);
            let skew_part = ev.stiffness - ev.stiffness.transpose();
            assert_mat_close(&format!("{what}: K − Kᵀ"), &skew_part, &expected_skew_part(&ev.force), 1e-9);
            let (f, m) = resultant(&ev.force, &pi, &pj);
            assert!(f.norm() < 1e-9 * ev.force.amax() && m.norm() < 1e-9 * ev.force.amax(), "{what}");

            // Magnitude and direction of the push.
            let (a, b) = seats(&c, &pi, &pj);
            let l = (b - a).norm();
            let push = c.k * (c.l0 - l) + c.p;
            let rep = c.spring.report(&pi, &pj, 0.0);
            assert!((rep.force - push * (b - a) / l).norm() < 1e-9 * push.abs().max(1.0), "{what}");
            assert!((rep.deflection.x - (l - c.l0)).abs() < 1e-12 && (c.spring.push_force(l) - push).abs() < 1e-9);
            let fj = Vec3::new(ev.force[6], ev.force[7], ev.force[8]);
            assert!((fj - rep.force).norm() < 1e-9 * push.abs().max(1.0));
        }
    }
}

#[test]
fn string_tangent_in_closed_form() {
    // Body j's reference point at its seat and i the ground: the translational block is
    // k nnᵀ − (F_push / L)(I − nnᵀ): eigenvalue k along the spring, −F_push/L across it.
    let mut rng = Rng::new(21);
    for _ in 0..6 {
        let point_i = rng.vec(0.3);
        let point_j = point_i + rng.unit() * 0.3;
        let (k, l0, p) = (5e4, 0.35, 300.0);
        let design_j = Pose { position: point_j, orientation: rng.orientation() };
        let mut s = CoilSpring::new("s", BodyRef::Ground, point_i, BodyRef::Body(BodyId(0)), point_j, k, l0)
            .unwrap()
            .with_preload(p)
            .unwrap();
        s.bind(&Pose::IDENTITY, &design_j).unwrap();
        let mut pj = design_j;
        pj.apply_increment(&rng.vec(0.05), &rng.rotvec(0.0, 1.0));
        let d = pj.position - point_i;
        let (l, n) = (d.norm(), d.normalize());
        let push = k * (l0 - l) + p;
        let kjj: Mat3 = eval(&s, &Pose::IDENTITY, &pj, 0.0).stiffness.fixed_view::<3, 3>(6, 6).into();
        assert!((kjj * n - k * n).norm() < 1e-9 * k);
        let t = n.cross(&rng.unit()).normalize();
        assert!((kjj * t + push / l * t).norm() < 1e-9 * k, "{} vs {}", (kjj * t).dot(&t), -push / l);
        // The transverse stiffness from the geometry alone: the force on j at P + εt is
        // F_push(L') (P + εt − Pᵢ)/L'; its component along t changes by F_push ε / L.
        let force_at = |x: Vec3| {
            let dd = x - point_i;
            (k * (l0 - dd.norm()) + p) * dd.normalize()
        };
        let eps = 1e-6;
        let dft = (force_at(pj.position + eps * t) - force_at(pj.position - eps * t)).dot(&t) / (2.0 * eps);
        assert!((dft - push / l).abs() < 1e-6 * k, "transverse {dft} vs F/L {}", push / l);
        assert!(((kjj * t).dot(&t) + dft).abs() < 1e-6 * k);
    }
}

#[test]
fn symmetric_when_the_seats_are_the_reference_points() {
    // With sᵢ = sⱼ = 0 the applied moments vanish, and so does the skew part, at any pose.
    let mut rng = Rng::new(22);
    for _ in 0..5 {
        let point_i = rng.vec(0.3);
        let point_j = point_i + rng.unit() * 0.25;
        let di = Pose { position: point_i, orientation: rng.orientation() };
        let dj = Pose { position: point_j, orientation: rng.orientation() };
        let mut s =
            CoilSpring::new("s", BodyRef::Body(BodyId(0)), point_i, BodyRef::Body(BodyId(1)), point_j, 3e4, 0.3)
                .unwrap();
        s.bind(&di, &dj).unwrap();
        let (mut pi, mut pj) = (di, dj);
        pi.apply_increment(&rng.vec(0.05), &rng.rotvec(0.0, 1.0));
        pj.apply_increment(&rng.vec(0.05), &rng.rotvec(0.0, 1.0));
        let k = eval(&s, &pi, &pj, 0.0).stiffness;
        assert!((k - k.transpose()).amax() < 1e-9 * k.amax());
    }
    // With lever arms and a non-zero force it is not symmetric.
    let c = random_case(&mut rng, false, false);
    let mut pj = c.design_j;
    pj.apply_increment(&Vec3::new(0.02, 0.0, 0.0), &Vec3::new(0.3, 0.0, 0.0));
    let k = eval(&c.spring, &c.design_i, &pj, 0.0).stiffness;
    assert!((k - k.transpose()).amax() > 1e-6 * k.amax());
}

#[test]
fn design_force_variant_and_role() {
    let (a, b) = (Vec3::new(0.0, 0.5, 0.1), Vec3::new(0.0, 0.55, 0.4));
    let s = CoilSpring::seated(
        "s",
        [(BodyRef::Ground, a), (BodyRef::Body(BodyId(0)), b)],
        Characteristic::Rate(4e4),
        SpringLength::DesignForce(2500.0),
    )
    .unwrap();
    let l = (b - a).norm();
    assert!((s.push_force(l) - 2500.0).abs() < 1e-9);
    assert!((s.spec().free_length - (l + 2500.0 / 4e4)).abs() < 1e-15);
    assert_eq!(s.role(), ElementRole::Elastic);
    let rep = s.report(&Pose::IDENTITY, &Pose::IDENTITY, 0.0);
    assert!((rep.force - 2500.0 * (b - a) / l).norm() < 1e-9);
    assert_eq!(rep.torque, Vec3::zeros());
    let spec = CoilSpringSpec { preload: 100.0, ..s.spec().clone() };
    let s2 = CoilSpring::from_spec(spec).unwrap();
    assert!((s2.push_force(l) - 2600.0).abs() < 1e-9);
}

#[test]
fn zero_length_gives_finite_values_along_the_design_direction() {
    let (a, b) = (Vec3::new(0.1, 0.2, 0.3), Vec3::new(0.1, 0.2, 0.6));
    let di = Pose::at(Vec3::new(0.0, 0.2, 0.3));
    let mut s = CoilSpring::new("s", BodyRef::Body(BodyId(0)), a, BodyRef::Body(BodyId(1)), b, 1e4, 0.3).unwrap();
    s.bind(&di, &Pose::IDENTITY).unwrap();
    // Body j moved so that its seat lands exactly on the seat of i; body i turned by 90° about x.
    let mut pi = di;
    pi.apply_increment(&Vec3::zeros(), &Vec3::new(std::f64::consts::FRAC_PI_2, 0.0, 0.0));
    let seat_i = pi.point(&di.to_local_point(&a));
    let pj = Pose::at(seat_i - b);
    let ev = eval(&s, &pi, &pj, 0.0);
    assert!(ev.force.iter().chain(ev.stiffness.iter()).all(|v| v.is_finite()));
    // Push k L₀ along the design direction (+z) carried by i (now −y).
    let fj = Vec3::new(ev.force[6], ev.force[7], ev.force[8]);
    assert!((fj - 3000.0 * Vec3::new(0.0, -1.0, 0.0)).norm() < 1e-9, "{fj:?}");
}
