//! Bushing with measured curves per direction: straight curves are the linear bushing under every rotation
//! law, the stiffness against finite differences with progressive tables under combined translations and
//! large rotations (inside the tables and past their ends), the energy law's force against its closed-form
//! energy, each law's moment against its closed form, and refusals.

mod common;

use common::*;
use elastokin_core::math::{quat_exp, rotation_log, tait_bryan_xyz};
use elastokin_core::{BodyId, BodyRef, ForceElement, Mat3, ModelError, Pose, Vec3};
use elastokin_elements::{Bushing, BushingSpec, Characteristic, Curve, RotationLaw};

const LAWS: [RotationLaw; 3] = [RotationLaw::Energy, RotationLaw::Linear, RotationLaw::TaitBryanXyz];

fn spec(
    frame: Mat3,
    point: Vec3,
    grounded_i: bool,
    translational: [Characteristic; 3],
    rotational: [Characteristic; 3],
    law: RotationLaw,
) -> BushingSpec {
    BushingSpec {
        name: "bush".into(),
        body_i: body(grounded_i, 0),
        body_j: BodyRef::Body(BodyId(1)),
        point,
        frame,
        translational,
        rotational,
        preload_force: Vec3::zeros(),
        preload_torque: Vec3::zeros(),
        rotation_law: law,
    }
}

/// A progressive, asymmetric rubber characteristic `y = k x (1 + (x/x₀)²)`, softer by `soft` on the
/// negative side, sampled at uneven points out to `reach` on each side (through (0, 0)).
fn progressive(rng: &mut Rng, k: f64, x0: f64, reach: f64) -> Characteristic {
    let soft = rng.uniform(0.5, 1.0);
    let f = |x: f64| k * x * (1.0 + (x / x0).powi(2)) * if x < 0.0 { soft } else { 1.0 };
    let mut xs = vec![0.0];
    for side in [-1.0, 1.0] {
        let (a, b) = (rng.uniform(0.1, 0.3), rng.uniform(0.4, 0.7));
        xs.extend([a, b, 1.0].map(|u| side * u * reach));
    }
    xs.sort_by(f64::total_cmp);
    Characteristic::Curve(Curve::new("bush", xs.iter().map(|&x| [x, f(x)]).collect::<Vec<_>>()).unwrap())
}

/// The straight curve of rate `k` through (−1, −k), (0, 0), (1, k).
fn straight(k: f64) -> Characteristic {
    Characteristic::Curve(Curve::new("bush", [[-1.0, -k], [0.0, 0.0], [1.0, k]]).unwrap())
}

/// A pose turned by a random rotation of `lo..hi` rad about `point` and shifted by up to `dr` per axis:
/// large rotations, deflections of the order of `dr` at a bushing there.
fn moved(rng: &mut Rng, p: &Pose, point: &Vec3, dr: f64, lo: f64, hi: f64) -> Pose {
    let omega = rng.rotvec(lo, hi);
    let r = quat_exp(&omega);
    Pose { position: point + r * (p.position - point) + rng.vec(dr), orientation: r * p.orientation }
}

#[test]
fn straight_curves_are_the_linear_bushing_under_every_law() {
    let mut rng = Rng::new(0x57A);
    let mut worst: f64 = 0.0;
    for law in LAWS {
        for trial in 0..6 {
            let frame = rng.orientation().to_rotation_matrix().into_inner();
            let point = rng.vec(0.4);
            let kt = Vec3::new(rng.uniform(1e5, 1e6), rng.uniform(1e5, 1e6), rng.uniform(1e5, 1e6));
            let kr = Vec3::new(rng.uniform(2e2, 2e3), rng.uniform(2e3, 2e4), rng.uniform(2e3, 2e4));
            let (f_pre, m_pre) = (rng.vec(500.0), rng.vec(50.0));
            let grounded_i = trial % 3 == 0;
            let (di, dj) = (if grounded_i { Pose::IDENTITY } else { rng.pose(0.5) }, rng.pose(0.5));
            let build = |t: [Characteristic; 3], r: [Characteristic; 3]| {
                let mut b = Bushing::from_spec(spec(frame, point, grounded_i, t, r, law))
                    .unwrap()
                    .with_preload(f_pre, m_pre)
                    .unwrap();
                b.bind(&di, &dj).unwrap();
                b
            };
            let linear = build(Characteristic::rates(&kt), Characteristic::rates(&kr));
            let curved = build([0, 1, 2].map(|a| straight(kt[a])), [0, 1, 2].map(|a| straight(kr[a])));
            let pi = if grounded_i { Pose::IDENTITY } else { moved(&mut rng, &di, &point, 0.01, 0.1, 0.8) };
            let pj = moved(&mut rng, &dj, &point, 0.01, 0.3, 1.2);
            let (a, b) = (eval(&linear, &pi, &pj, 0.0), eval(&curved, &pi, &pj, 0.0));
            worst = worst
                .max((a.force - b.force).amax() / a.force.amax())
                .max((a.stiffness - b.stiffness).amax() / a.stiffness.amax());
        }
    }
    // Measured: 4.1e-14 (rounding, mostly in the rotation laws' products at ~1 rad).
    assert!(worst < 1e-12, "{worst}");
}

/// Progressive tables in all six directions, combined translations of up to 8 mm (tables to ±3–6 mm:
/// inside, in different pieces, and past the ends) and rotations of 0.2–1.2 rad (tables to ±0.5 rad),
/// with and without preload, under each law: the stiffness is the derivative of the force; the
/// conservative laws keep only the skew part of the applied moments.
#[test]
fn stiffness_is_the_force_derivative_with_curves_under_every_law() {
    let mut rng = Rng::new(0xC0B);
    let mut worst_skew: f64 = 0.0;
    // Directions past a table's end and inside it: (translations, rotations) each.
    let (mut beyond, mut inside) = ([0usize; 2], [0usize; 2]);
    for law in LAWS {
        for trial in 0..12 {
            let frame = rng.orientation().to_rotation_matrix().into_inner();
            let point = rng.vec(0.4);
            let reach_t = rng.uniform(0.003, 0.006);
            let translational = [0, 1, 2].map(|_| {
                let k = rng.uniform(1e5, 1e6);
                progressive(&mut rng, k, 0.004, reach_t)
            });
            let rotational = [0, 1, 2].map(|_| {
                let k = rng.uniform(2e2, 2e4);
                progressive(&mut rng, k, 0.3, 0.5)
            });
            let grounded_i = trial % 3 == 0;
            let (di, dj) = (if grounded_i { Pose::IDENTITY } else { rng.pose(0.5) }, rng.pose(0.5));
            let mut b = Bushing::from_spec(spec(frame, point, grounded_i, translational, rotational, law)).unwrap();
            if trial % 2 == 1 {
                b = b.with_preload(rng.vec(500.0), rng.vec(50.0)).unwrap();
            }
            b.bind(&di, &dj).unwrap();
            // The curvature of a table jumps at its points: a central difference straddling one is off by
            // O(step), so configurations within 1e-5 (m or rad) of a point are drawn again.
            let (pi, pj, rep) = loop {
                let pi = if grounded_i { Pose::IDENTITY } else { moved(&mut rng, &di, &point, 0.004, 0.05, 0.5) };
                let pj = moved(&mut rng, &dj, &point, 0.004, 0.2, 1.2);
                let rep = b.report(&pi, &pj, 0.0);
                // The Tait-Bryan law's curves take the angles of the relative rotation, the others its vector.
                let angles = match law {
                    RotationLaw::TaitBryanXyz => {
                        tait_bryan_xyz(&quat_exp(&rep.rotation).to_rotation_matrix().into_inner())
                    }
                    _ => rep.rotation,
                };
                if clear_of_points(&b.spec().translational, &rep.deflection)
                    && clear_of_points(&b.spec().rotational, &angles)
                {
                    break (pi, pj, rep);
                }
            };
            beyond[0] += rep.deflection.iter().filter(|d| d.abs() > reach_t).count();
            beyond[1] += rep.rotation.iter().filter(|r| r.abs() > 0.5).count();
            inside[0] += rep.deflection.iter().filter(|d| d.abs() < reach_t).count();
            inside[1] += rep.rotation.iter().filter(|r| r.abs() < 0.5).count();
            let ev = eval(&b, &pi, &pj, 0.0);
            let k_fd = fd_stiffness(&b, &pi, &pj, 0.0);
            let what = format!("{law:?} trial {trial}");
            // Measured: 6.3e-7 at worst under `Linear`, 4.1e-7 `Energy`, 3.5e-7 `TaitBryanXyz`: the
            // central difference's truncation on cubic pieces a fraction of a millimetre long.
            assert_mat_close(&what, &ev.stiffness, &k_fd, 5e-6);
            if law != RotationLaw::Linear {
                let extra = ev.stiffness - ev.stiffness.transpose() - expected_skew_part(&ev.force);
                worst_skew = worst_skew.max(extra.amax() / ev.stiffness.amax());
            }
        }
    }
    // Measured: 1.5e-16 of the largest entry.
    assert!(worst_skew < 1e-14, "{worst_skew}");
    // The poses reach past the tables' ends in some directions (and stay inside in others).
    assert!(beyond.iter().chain(&inside).all(|&n| n > 10), "{beyond:?} {inside:?}");
}

/// No component within 1e-5 of a point of its curve.
fn clear_of_points(curves: &[Characteristic; 3], x: &Vec3) -> bool {
    curves.iter().zip(x.iter()).all(|(c, &x)| match c {
        Characteristic::Curve(c) => c.points().iter().all(|p| (p[0] - x).abs() > 1e-5),
        Characteristic::Rate(_) => true,
    })
}

/// Under the energy law the force is minus the gradient of the sum of the six curves' integrals, written
/// here in closed form for parabolic tables `y = k x + c x²` (which the curve reproduces between its
/// points) and configurations inside them.
#[test]
fn energy_law_force_derives_from_the_curves_integrals() {
    let mut rng = Rng::new(0xE6E);
    for trial in 0..8 {
        let frame = rng.orientation().to_rotation_matrix().into_inner();
        let point = rng.vec(0.4);
        // Rising on the whole table: k > 2 |c| · reach.
        let parabola = |rng: &mut Rng, lo: f64, hi: f64, reach: f64| {
            let k = rng.uniform(lo, hi);
            let c = rng.uniform(-0.4, 0.4) * k / reach;
            let xs = [-1.0, -0.6, -0.25, 0.0, 0.3, 0.7, 1.0].map(|u| u * reach);
            let curve = Curve::new("bush", xs.map(|x| [x, k * x + c * x * x])).unwrap();
            (Characteristic::Curve(curve), k, c)
        };
        let t = [0, 1, 2].map(|_| parabola(&mut rng, 1e5, 1e6, 0.01));
        let r = [0, 1, 2].map(|_| parabola(&mut rng, 2e2, 2e4, 1.6));
        let (f_pre, m_pre) = (rng.vec(500.0), rng.vec(50.0));
        let (di, dj) = (rng.pose(0.5), rng.pose(0.5));
        let tr = t.clone().map(|(ch, _, _)| ch);
        let ro = r.clone().map(|(ch, _, _)| ch);
        let mut b = Bushing::from_spec(spec(frame, point, false, tr, ro, RotationLaw::Energy))
            .unwrap()
            .with_preload(f_pre, m_pre)
            .unwrap();
        b.bind(&di, &dj).unwrap();
        let pi = moved(&mut rng, &di, &point, 0.003, 0.05, 0.4);
        let pj = moved(&mut rng, &dj, &point, 0.003, 0.2, 1.0);
        let integral = |(_, k, c): &(Characteristic, f64, f64), x: f64| k * x * x / 2.0 + c * x * x * x / 3.0;
        let energy = |a: &Pose, bj: &Pose| {
            let (ai0, aj0) = (di.rotation(), dj.rotation());
            let si0 = ai0.transpose() * (point - di.position);
            let sj0 = aj0.transpose() * (point - dj.position);
            let e = a.rotation() * ai0.transpose() * frame;
            let ej = bj.rotation() * aj0.transpose() * frame;
            let d = (bj.position + bj.rotation() * sj0) - (a.position + a.rotation() * si0);
            let delta = e.transpose() * d;
            let theta = rotation_log(&(e.transpose() * ej));
            (0..3).map(|k| integral(&t[k], delta[k]) + integral(&r[k], theta[k])).sum::<f64>()
                - f_pre.dot(&delta)
                - m_pre.dot(&theta)
        };
        let rep = b.report(&pi, &pj, 0.0);
        assert!(rep.deflection.amax() < 0.01 && rep.rotation.amax() < 1.6, "inside the tables: {rep:?}");
        let ev = eval(&b, &pi, &pj, 0.0);
        let grad = fd_scalar(&pi, &pj, energy);
        // Measured: 7.4e-9 at worst (central differences of the energy).
        assert_vec_close(&format!("trial {trial}"), &ev.force, &(-grad), 5e-7);
    }
}

/// Closed forms with curves, bushing on the ground at body `j`'s origin, frame = identity:
/// * translation alone: the force on `j` is minus the curves' forces at the deflection, componentwise;
/// * `Linear`: the moment on `j` is minus the curves' moments at the rotation vector, for any rotation;
/// * `TaitBryanXyz`: its component about each gimbal axis is minus that angle's curve at the angle;
/// * `Energy`: a rotation about a local axis gives minus that axis's curve at the angle about it.
#[test]
fn each_law_meets_its_closed_form_with_curves() {
    // Parabolic tables (reproduced exactly between their points): y = k x + c x².
    let (kt, ct) = (Vec3::new(4e5, 6e5, 8e5), Vec3::new(2e7, -1e7, 3e7));
    let (kr, cr) = (Vec3::new(500.0, 4000.0, 3000.0), Vec3::new(150.0, -800.0, 600.0));
    let table = |k: f64, c: f64, reach: f64| {
        let xs = [-1.0, -0.5, -0.2, 0.0, 0.1, 0.4, 1.0].map(|u| u * reach);
        Characteristic::Curve(Curve::new("bush", xs.map(|x| [x, k * x + c * x * x])).unwrap())
    };
    let bushing = |law| {
        let t = [0, 1, 2].map(|a| table(kt[a], ct[a], 0.01));
        let r = [0, 1, 2].map(|a| table(kr[a], cr[a], 1.5));
        let mut b = Bushing::from_spec(spec(Mat3::identity(), Vec3::zeros(), true, t, r, law)).unwrap();
        b.bind(&Pose::IDENTITY, &Pose::IDENTITY).unwrap();
        b
    };
    let curve_of = |k: &Vec3, c: &Vec3, x: &Vec3| Vec3::from_fn(|a, _| k[a] * x[a] + c[a] * x[a] * x[a]);
    let mut worst: f64 = 0.0;
    // Translation alone (any law).
    let delta = Vec3::new(0.004, -0.007, 0.009);
    let rep = bushing(RotationLaw::Energy).report(&Pose::IDENTITY, &Pose::at(delta), 0.0);
    let expected = -curve_of(&kt, &ct, &delta);
    worst = worst.max((rep.force - expected).amax() / expected.amax());
    // Linear.
    let theta = Vec3::new(0.8, -0.4, 0.3);
    let pose = |r: Mat3| Pose {
        position: Vec3::zeros(),
        orientation: nalgebra::UnitQuaternion::from_rotation_matrix(&nalgebra::Rotation3::from_matrix_unchecked(r)),
    };
    let pj = pose(quat_exp(&theta).to_rotation_matrix().into_inner());
    let m = bushing(RotationLaw::Linear).report(&Pose::IDENTITY, &pj, 0.0).torque;
    let expected = -curve_of(&kr, &cr, &theta);
    worst = worst.max((m - expected).amax() / expected.amax());
    // Tait-Bryan x-y-z: R = Rx(a) Ry(b) Rz(c), gimbal axes x, Rx(a) y, Rx(a) Ry(b) z.
    let (a, b, c) = (0.5, 0.3, -0.4);
    let (rx, ry, rz) = (
        nalgebra::Rotation3::from_axis_angle(&Vec3::x_axis(), a).into_inner(),
        nalgebra::Rotation3::from_axis_angle(&Vec3::y_axis(), b).into_inner(),
        nalgebra::Rotation3::from_axis_angle(&Vec3::z_axis(), c).into_inner(),
    );
    let m = bushing(RotationLaw::TaitBryanXyz).report(&Pose::IDENTITY, &pose(rx * ry * rz), 0.0).torque;
    let angles = Vec3::new(a, b, c);
    let moments = curve_of(&kr, &cr, &angles);
    for (k, axis) in [Vec3::x(), rx * Vec3::y(), rx * ry * Vec3::z()].iter().enumerate() {
        worst = worst.max((m.dot(axis) + moments[k]).abs() / moments[k].abs());
    }
    // Energy, about each local axis in turn, both ways.
    for axis in 0..3 {
        for angle in [1.2, -0.7] {
            let mut th = Vec3::zeros();
            th[axis] = angle;
            let pj = pose(quat_exp(&th).to_rotation_matrix().into_inner());
            let m = bushing(RotationLaw::Energy).report(&Pose::IDENTITY, &pj, 0.0).torque;
            let expected = -curve_of(&kr, &cr, &th);
            worst = worst.max((m - expected).amax() / expected.amax());
        }
    }
    // Measured: 5.3e-16.
    assert!(worst < 2e-14, "{worst}");
}

fn refusal(translational: [Characteristic; 3], rotational: [Characteristic; 3]) -> String {
    let mut s = spec(Mat3::identity(), Vec3::zeros(), true, translational, rotational, RotationLaw::Energy);
    s.name = "front bush".into();
    match Bushing::from_spec(s) {
        Err(e @ ModelError::OutOfRange { .. }) => e.to_string(),
        other => panic!("{other:?}"),
    }
}

#[test]
fn curves_a_bushing_cannot_use_are_refused_by_name_and_direction() {
    let rates = || Characteristic::rates(&Vec3::new(1e6, 1e6, 1e6));
    let curve = |points: &[[f64; 2]]| Characteristic::Curve(Curve::new("front bush", points).unwrap());
    // Not through (0, 0): a force at zero deflection belongs to the preload.
    let mut t = rates();
    t[1] = curve(&[[-0.01, -9000.0], [0.01, 11000.0]]);
    let text = refusal(t, rates());
    assert!(text.starts_with("'front bush'") && text.contains("Ky") && text.contains("(0, 0)"), "{text}");
    assert!(text.contains("preload"), "{text}");
    // A moment that drops with the twist.
    let mut r = rates();
    r[2] = curve(&[[-0.2, -100.0], [0.0, 0.0], [0.1, 60.0], [0.2, 50.0]]);
    let text = refusal(rates(), r);
    assert!(text.contains("Kw") && text.contains("point 3") && text.contains("never decreases"), "{text}");
    // A flat curve gives no stiffness.
    let mut r = rates();
    r[0] = curve(&[[-0.2, 0.0], [0.0, 0.0], [0.2, 0.0]]);
    assert!(refusal(rates(), r).contains("flat"));
    // `with_characteristics` checks the same way.
    let mut t = rates();
    t[0] = curve(&[[0.0, 100.0], [0.01, 10000.0]]);
    let err = Bushing::with_characteristics(
        "front bush",
        BodyRef::Ground,
        BodyRef::Body(BodyId(0)),
        Vec3::zeros(),
        Mat3::identity(),
        t,
        rates(),
    )
    .unwrap_err();
    assert!(err.to_string().contains("Kx"), "{err}");
}
