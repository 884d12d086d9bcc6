//! Field element: its force against the gradient of its energy and its stiffness against finite
//! differences, with the blocks coupled and a preload, at random poses and deflections; a diagonal field
//! is the bushing of those rates; a matrix that is not an elastic element's is refused by name.

mod common;

use common::*;
use elastokin_core::{BodyId, BodyRef, ForceElement, ModelError, Pose, Vec3};
use elastokin_elements::{Bushing, Field, FieldSpec};
use nalgebra::Matrix6;

/// A symmetric positive definite 6×6 with rates of a bushing's size on its diagonal and coupled terms of a
/// fifth of the geometric mean of the rates they couple.
fn coupled(rng: &mut Rng) -> Matrix6<f64> {
    let diag = [
        rng.uniform(1e6, 5e6),
        rng.uniform(1e6, 5e6),
        rng.uniform(5e5, 2e6),
        rng.uniform(500.0, 3000.0),
        rng.uniform(500.0, 3000.0),
        rng.uniform(100.0, 800.0),
    ];
    let mut k = Matrix6::from_diagonal(&nalgebra::Vector6::from_row_slice(&diag));
    for r in 0..6 {
        for c in r + 1..6 {
            let v = 0.2 * rng.uniform(-1.0, 1.0) * (diag[r] * diag[c]).sqrt();
            k[(r, c)] = v;
            k[(c, r)] = v;
        }
    }
    assert!(k.symmetric_eigenvalues().min() > 0.0);
    k
}

fn field(rng: &mut Rng, k: Matrix6<f64>, grounded: bool) -> (Field, Pose, Pose) {
    let frame = rot(&rng.rotvec(0.0, 1.5));
    let (bi, bj) = (if grounded { BodyRef::Ground } else { BodyRef::Body(BodyId(0)) }, BodyRef::Body(BodyId(1)));
    let spec = FieldSpec {
        name: "field".into(),
        body_i: bi,
        body_j: bj,
        point: rng.vec(0.4),
        frame,
        stiffness: k,
        preload_force: rng.vec(300.0),
        preload_torque: rng.vec(20.0),
    };
    let mut f = Field::from_spec(spec).unwrap();
    let (di, dj) = (if grounded { Pose::IDENTITY } else { rng.pose(0.4) }, rng.pose(0.4));
    f.bind(&di, &dj).unwrap();
    (f, di, dj)
}

/// Poses near the design ones: a deflection of millimetres and a rotation of up to `angle` rad.
fn deflected(rng: &mut Rng, di: &Pose, dj: &Pose, grounded: bool, angle: f64) -> (Pose, Pose) {
    let mut pi = *di;
    if !grounded {
        pi.apply_increment(&rng.vec(0.05), &rng.rotvec(0.0, 0.5));
    }
    // j moved as i was (a rigid motion of the pair), then deflected.
    let rel = pi.orientation * di.orientation.inverse();
    let mut pj = Pose { position: pi.position + rel * (dj.position - di.position), orientation: rel * dj.orientation };
    pj.apply_increment(&rng.vec(0.004), &rng.rotvec(0.0, angle));
    (pi, pj)
}

#[test]
fn force_is_minus_the_energy_gradient_and_stiffness_matches_finite_differences() {
    let mut rng = Rng::new(21);
    let (mut worst_q, mut worst_k) = (0.0f64, 0.0f64);
    for case in 0..24 {
        let grounded = case % 3 == 0;
        let k = coupled(&mut rng);
        let (f, di, dj) = field(&mut rng, k, grounded);
        for angle in [0.05, 0.4] {
            let (pi, pj) = deflected(&mut rng, &di, &dj, grounded, angle);
            let ev = eval(&f, &pi, &pj, 0.0);
            let grad = fd_scalar(&pi, &pj, |a, b| f.energy(a, b));
            worst_q = worst_q.max(vec_close_error(&ev.force, &(-grad)));
            worst_k = worst_k.max(mat_close_error(&ev.stiffness, &fd_stiffness(&f, &pi, &pj, 0.0)));
        }
    }
    // Central differences with steps of 1e-6: measured 4.8e-10 (force) and 6.2e-10 (stiffness).
    println!("force against −∇U {worst_q:e}, stiffness against differences {worst_k:e}");
    assert!(worst_q < 5e-8, "Q = −∇U: {worst_q:e}");
    assert!(worst_k < 5e-8, "K: {worst_k:e}");
}

#[test]
fn a_diagonal_field_is_the_bushing_of_its_rates() {
    let mut rng = Rng::new(22);
    let mut worst = 0.0f64;
    for case in 0..12 {
        let grounded = case % 2 == 0;
        let rates = [2e6, 3e6, 1e6, 900.0, 1200.0, 300.0].map(|r| r * rng.uniform(0.5, 2.0));
        let k = Matrix6::from_diagonal(&nalgebra::Vector6::from_row_slice(&rates));
        let (f, di, dj) = field(&mut rng, k, grounded);
        let s = f.spec();
        let mut b = Bushing::new(
            "bushing",
            s.body_i,
            s.body_j,
            s.point,
            s.frame,
            Vec3::new(rates[0], rates[1], rates[2]),
            Vec3::new(rates[3], rates[4], rates[5]),
        )
        .unwrap()
        .with_preload(s.preload_force, s.preload_torque)
        .unwrap();
        b.bind(&di, &dj).unwrap();
        let (pi, pj) = deflected(&mut rng, &di, &dj, grounded, 0.3);
        let (ef, eb) = (eval(&f, &pi, &pj, 0.0), eval(&b, &pi, &pj, 0.0));
        worst = worst.max(vec_close_error(&ef.force, &eb.force)).max(mat_close_error(&ef.stiffness, &eb.stiffness));
        assert_eq!(f.report(&pi, &pj, 0.0).deflection, b.report(&pi, &pj, 0.0).deflection);
    }
    // Measured: 0, bit for bit (the coupled blocks are zero, and add nothing).
    assert!(worst <= 1e-12, "field against bushing: {worst:e}");
}

#[test]
fn a_coupled_term_gives_the_force_its_twist_asks_for() {
    // Twist j about the local x axis by a small angle: the coupled term K_tr[(1, 0)] (lateral force per
    // radian of twist) pushes j along local y by that much, to first order, against its preload-free rest.
    let mut k = Matrix6::from_diagonal(&nalgebra::Vector6::from_row_slice(&[2e6, 2e6, 1e6, 1000.0, 1000.0, 500.0]));
    k[(1, 3)] = 4000.0;
    k[(3, 1)] = 4000.0;
    let spec = FieldSpec {
        name: "field".into(),
        body_i: BodyRef::Ground,
        body_j: BodyRef::Body(BodyId(0)),
        point: Vec3::zeros(),
        frame: nalgebra::Matrix3::identity(),
        stiffness: k,
        preload_force: Vec3::zeros(),
        preload_torque: Vec3::zeros(),
    };
    let mut f = Field::from_spec(spec).unwrap();
    f.bind(&Pose::IDENTITY, &Pose::IDENTITY).unwrap();
    let twist = 1e-4;
    let mut pj = Pose::IDENTITY;
    pj.apply_increment(&Vec3::zeros(), &Vec3::new(twist, 0.0, 0.0));
    let report = f.report(&Pose::IDENTITY, &pj, 0.0);
    // The force on j is −K q: −4000 N/rad × 1e-4 rad along y, and the moment −1000 N·m/rad × 1e-4 about x.
    assert!((report.force.y - (-0.4)).abs() < 1e-12, "{:?}", report.force);
    assert!((report.torque.x - (-0.1)).abs() < 1e-9, "{:?}", report.torque);
}

#[test]
fn a_matrix_no_elastic_element_has_is_refused_by_name() {
    let base = FieldSpec {
        name: "front bush".into(),
        body_i: BodyRef::Ground,
        body_j: BodyRef::Body(BodyId(0)),
        point: Vec3::zeros(),
        frame: nalgebra::Matrix3::identity(),
        stiffness: Matrix6::identity() * 1e3,
        preload_force: Vec3::zeros(),
        preload_torque: Vec3::zeros(),
    };
    let mut skew = base.clone();
    skew.stiffness[(0, 4)] = 10.0;
    let e = Field::from_spec(skew).unwrap_err();
    assert!(
        matches!(&e, ModelError::OutOfRange { item, why } if item == "front bush" && why.contains("(0, 4)")),
        "{e}"
    );
    let mut negative = base.clone();
    negative.stiffness[(0, 1)] = 2e3;
    negative.stiffness[(1, 0)] = 2e3;
    let e = Field::from_spec(negative).unwrap_err();
    assert!(matches!(&e, ModelError::OutOfRange { why, .. } if why.contains("negative eigenvalue")), "{e}");
    let mut nan = base;
    nan.stiffness[(2, 2)] = f64::NAN;
    assert!(matches!(Field::from_spec(nan), Err(ModelError::NonFinite { .. })));
}
