//! Where a drawing places an element ([`ForceElement::sketch`]): its points, moved by the bodies' poses,
//! are the points the element's own law measures, so what a drawing shows is what the element feels.
//! Checked against each element's report at random poses: a spring's drawn length less its deflection is
//! its free length at every pose, a stop's drawn length tells its contact as its report does, a bushing's
//! two drawn points apart, in its drawn axes, are its deflection, a beam's line less its length is its
//! deflection, and a load sits on its body.

mod common;

use common::*;
use elastokin_core::{BodyId, BodyRef, ForceElement, Pose, SketchKind, Vec3};
use elastokin_elements::{beam, BeamSpec, Bushing, CoilSpring, Curve, PointForce, Section, Stop};

/// A point of body `b` (its local coordinates; global on the ground) at `pose`.
fn placed(body: BodyRef, pose: &Pose, local: &Vec3) -> Vec3 {
    match body {
        BodyRef::Ground => *local,
        BodyRef::Body(_) => pose.point(local),
    }
}

/// Both drawn points of `element` at the poses of its bodies.
fn drawn(element: &dyn ForceElement, pi: &Pose, pj: &Pose) -> (Vec3, Vec3) {
    let sketch = element.sketch().expect("every element here has a place");
    let [bi, bj] = element.bodies();
    (placed(bi, pi, &sketch.on_i), placed(bj, pj, &sketch.on_j))
}

#[test]
fn a_springs_drawn_length_less_its_deflection_is_its_free_length_at_any_pose() {
    let mut rng = Rng::new(11);
    let (a, b) = (BodyRef::Body(BodyId(0)), BodyRef::Body(BodyId(1)));
    for grounded in [false, true] {
        let bi = if grounded { BodyRef::Ground } else { a };
        let (point_i, point_j) = (rng.vec(0.3), rng.vec(0.3) + Vec3::new(0.0, 0.0, 0.5));
        let free = (point_j - point_i).norm() + 0.04;
        let mut spring = CoilSpring::new("spring", bi, point_i, b, point_j, 3e4, free).unwrap();
        let (di, dj) = (if grounded { Pose::IDENTITY } else { rng.pose(0.3) }, rng.pose(0.3));
        spring.bind(&di, &dj).unwrap();
        assert_eq!(spring.sketch().unwrap().kind, SketchKind::Spring);
        let (pi0, pj0) = drawn(&spring, &di, &dj);
        assert!((pi0 - point_i).norm() < 1e-14 && (pj0 - point_j).norm() < 1e-14, "at design, the design points");
        let mut worst = 0.0f64;
        for _ in 0..20 {
            let (pi, pj) = (if grounded { Pose::IDENTITY } else { rng.pose(0.3) }, rng.pose(0.3));
            let (si, sj) = drawn(&spring, &pi, &pj);
            let report = spring.report(&pi, &pj, 0.0);
            worst = worst.max(((sj - si).norm() - report.deflection.x - free).abs());
            // The force on j lies along the drawn line.
            assert!(report.force.cross(&(sj - si)).norm() <= 1e-12 * report.force.norm() * (sj - si).norm());
        }
        // Measured: 1e-16 m.
        assert!(worst < 1e-14, "drawn length − deflection − free length up to {worst:e} m");
    }
}

#[test]
fn a_stops_drawn_points_are_the_ones_it_measures_contact_between() {
    let mut rng = Rng::new(12);
    let (point_i, point_j) = (Vec3::new(0.0, 0.0, 0.1), Vec3::new(0.0, 0.0, 0.2));
    let curve = Curve::new("bump stop", vec![[0.0, 0.0], [0.02, 2000.0]]).unwrap();
    let mut stop =
        Stop::bump("bump stop", BodyRef::Ground, point_i, BodyRef::Body(BodyId(0)), point_j, 0.03, curve).unwrap();
    stop.bind(&Pose::IDENTITY, &Pose::IDENTITY).unwrap();
    assert_eq!(stop.sketch().unwrap().kind, SketchKind::Stop);
    for _ in 0..20 {
        let pj = Pose::at(rng.vec(0.05));
        let (si, sj) = drawn(&stop, &Pose::IDENTITY, &pj);
        let report = stop.report(&Pose::IDENTITY, &pj, 0.0);
        // Penetration: the contact length (0.1 − 0.03) less the drawn length (negative out of contact).
        let expected = 0.07 - (sj - si).norm();
        assert!((report.deflection.x - expected).abs() < 1e-14, "{} against {expected}", report.deflection.x);
    }
}

#[test]
fn a_bushings_drawn_points_apart_in_its_drawn_axes_are_its_deflection() {
    let mut rng = Rng::new(13);
    let point = rng.vec(0.3);
    let frame = rot(&rng.rotvec(0.0, 1.0));
    let (a, b) = (BodyRef::Body(BodyId(0)), BodyRef::Body(BodyId(1)));
    let mut bushing =
        Bushing::new("bushing", a, b, point, frame, Vec3::new(1e6, 2e6, 3e6), Vec3::new(1e3, 1e3, 1e3)).unwrap();
    let (di, dj) = (rng.pose(0.3), rng.pose(0.3));
    bushing.bind(&di, &dj).unwrap();
    let sketch = bushing.sketch().unwrap();
    assert_eq!(sketch.kind, SketchKind::Bushing);
    let axes = sketch.axes_i.expect("a bushing has axes");
    assert!((di.rotation() * axes - frame).norm() < 1e-14, "at design, the bushing's axes");
    let mut worst = 0.0f64;
    for _ in 0..20 {
        let (pi, pj) = (rng.pose(0.3), rng.pose(0.3));
        let (si, sj) = drawn(&bushing, &pi, &pj);
        let in_axes = (pi.rotation() * axes).transpose() * (sj - si);
        worst = worst.max((in_axes - bushing.report(&pi, &pj, 0.0).deflection).norm());
    }
    // Measured: 1e-16 m.
    assert!(worst < 1e-14, "drawn separation in the drawn axes against the deflection: {worst:e} m");
}

#[test]
fn a_beams_drawn_line_less_its_length_along_its_drawn_axis_is_its_deflection() {
    let mut rng = Rng::new(17);
    let (from, to) = (rng.vec(0.3), rng.vec(0.3) + Vec3::new(0.0, 0.6, 0.0));
    let section = Section {
        youngs_modulus: 210e9,
        shear_modulus: 80e9,
        area: 1e-3,
        iy: 1e-6,
        iz: 2e-6,
        j: 3e-8,
        shear_areas: None,
        shear_centre: (0.0, 0.02),
    };
    let (a, b) = (BodyRef::Body(BodyId(0)), BodyRef::Body(BodyId(1)));
    let spec = BeamSpec { name: "beam".into(), body_i: a, body_j: b, from, to, y_axis: Vec3::x(), section };
    let mut beam = beam(&spec).unwrap();
    let (di, dj) = (rng.pose(0.3), rng.pose(0.3));
    beam.bind(&di, &dj).unwrap();
    let sketch = beam.sketch().unwrap();
    assert_eq!(sketch.kind, SketchKind::Beam);
    let axes = sketch.axes_i.expect("a beam has axes");
    let (s0, e0) = drawn(&beam, &di, &dj);
    assert!((s0 - from).norm() < 1e-15 && (e0 - to).norm() < 1e-15, "at design, from its start to its end");
    let length = (to - from).norm();
    let mut worst = 0.0f64;
    for _ in 0..20 {
        let (pi, pj) = (rng.pose(0.3), rng.pose(0.3));
        let (start, end) = drawn(&beam, &pi, &pj);
        let in_axes = (pi.rotation() * axes).transpose() * (end - start) - Vec3::new(length, 0.0, 0.0);
        worst = worst.max((in_axes - beam.report(&pi, &pj, 0.0).deflection).norm());
    }
    // Measured: 2e-16 m.
    assert!(worst < 1e-14, "drawn line in the drawn axes against the deflection: {worst:e} m");
}

#[test]
fn a_load_is_drawn_at_its_point_on_its_body() {
    let mut rng = Rng::new(14);
    let point = rng.vec(0.3);
    let mut load = PointForce::new("load", BodyRef::Body(BodyId(0)), point, Vec3::new(0.0, 0.0, 100.0)).unwrap();
    let design = rng.pose(0.3);
    load.bind(&Pose::IDENTITY, &design).unwrap();
    let sketch = load.sketch().unwrap();
    assert_eq!(sketch.kind, SketchKind::Load);
    let moved = rng.pose(0.3);
    let on_body = moved.point(&sketch.on_j);
    let expected = moved.point(&design.to_local_point(&point));
    assert!((on_body - expected).norm() < 1e-14);
}
