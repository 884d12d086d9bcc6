//! Bad input is refused with the right `ModelError`, naming the element, without panicking.

use elastokin_core::{BodyId, BodyRef, ElementEval, ForceElement, Mat3, Model, ModelError, Pose, Vec3};
use elastokin_elements::{Bushing, BushingSpec, Characteristic, CoilSpring, PointForce, PointTorque, SpringLength};

const A: BodyRef = BodyRef::Body(BodyId(0));
const B: BodyRef = BodyRef::Body(BodyId(1));

fn bushing_spec() -> BushingSpec {
    BushingSpec {
        name: "front bush".into(),
        body_i: BodyRef::Ground,
        body_j: A,
        point: Vec3::new(0.2, 0.4, -0.2),
        frame: Mat3::identity(),
        translational: Characteristic::rates(&Vec3::new(1e6, 2e6, 3e6)),
        rotational: Characteristic::rates(&Vec3::new(100.0, 200.0, 300.0)),
        preload_force: Vec3::zeros(),
        preload_torque: Vec3::zeros(),
        rotation_law: Default::default(),
    }
}

fn bushing_err(f: impl FnOnce(&mut BushingSpec)) -> ModelError {
    let mut spec = bushing_spec();
    f(&mut spec);
    let err = Bushing::from_spec(spec).unwrap_err();
    assert!(err.to_string().contains("'front bush'"), "{err}");
    err
}

#[test]
fn bushing_stiffness_must_be_positive_and_finite() {
    match bushing_err(|s| s.translational[0] = Characteristic::Rate(0.0)) {
        ModelError::NotPositive { item, what, value } => {
            assert_eq!(item, "front bush");
            assert!(what.contains("Kx"), "{what}");
            assert_eq!(value, 0.0);
        }
        e => panic!("{e:?}"),
    }
    match bushing_err(|s| s.rotational[2] = Characteristic::Rate(-5.0)) {
        ModelError::NotPositive { what, value, .. } => assert!(what.contains("Kw") && value == -5.0),
        e => panic!("{e:?}"),
    }
    match bushing_err(|s| s.translational[1] = Characteristic::Rate(f64::NAN)) {
        ModelError::NonFinite { what, .. } => assert!(what.contains("Ky")),
        e => panic!("{e:?}"),
    }
    assert!(matches!(
        bushing_err(|s| s.rotational[1] = Characteristic::Rate(f64::INFINITY)),
        ModelError::NonFinite { .. }
    ));
    assert!(matches!(bushing_err(|s| s.point.z = f64::NAN), ModelError::NonFinite { .. }));
    assert!(matches!(bushing_err(|s| s.preload_torque.x = f64::NAN), ModelError::NonFinite { .. }));
    assert!(matches!(bushing_err(|s| s.body_i = A), ModelError::SelfJoint { .. }));
    let err = Bushing::from_spec(bushing_spec()).unwrap().with_preload(Vec3::new(f64::NAN, 0.0, 0.0), Vec3::zeros());
    assert!(matches!(err, Err(ModelError::NonFinite { what: "preload force", .. })));
}

#[test]
fn bushing_frame_must_be_a_rotation() {
    match bushing_err(|s| s.frame = Mat3::identity() * 1.01) {
        ModelError::NotOrthonormal { error, .. } => assert!(error > 0.01),
        e => panic!("{e:?}"),
    }
    // A reflection is orthonormal but left-handed.
    assert!(matches!(
        bushing_err(|s| s.frame = Mat3::from_diagonal(&Vec3::new(1.0, 1.0, -1.0))),
        ModelError::NotOrthonormal { .. }
    ));
    assert!(matches!(bushing_err(|s| s.frame[(0, 1)] = f64::NAN), ModelError::NonFinite { .. }));
    assert!(matches!(bushing_err(|s| s.frame = Mat3::zeros()), ModelError::NotOrthonormal { .. }));
    // Round-off-sized deviations are accepted and the frame made exact: no force at design.
    let mut spec = bushing_spec();
    spec.frame = nalgebra::Rotation3::from_euler_angles(0.3, 0.2, -0.1).into_inner();
    spec.frame[(0, 0)] += 5e-7;
    let design = Pose::at(Vec3::new(0.1, 0.5, -0.2));
    let mut b = Bushing::from_spec(spec).unwrap();
    b.bind(&Pose::IDENTITY, &design).unwrap();
    let mut ev = ElementEval::default();
    b.evaluate(&Pose::IDENTITY, &design, 0.0, &mut ev, true);
    assert!(ev.force.amax() < 1e-9 && ev.stiffness.iter().all(|v| v.is_finite()));
}

#[test]
fn bind_refuses_non_finite_design_poses() {
    let mut b = Bushing::from_spec(bushing_spec()).unwrap();
    let bad = Pose::at(Vec3::new(f64::NAN, 0.0, 0.0));
    assert!(matches!(b.bind(&Pose::IDENTITY, &bad), Err(ModelError::NonFinite { .. })));
    let mut s = CoilSpring::new("spring", A, Vec3::zeros(), B, Vec3::z(), 1e4, 0.5).unwrap();
    assert!(matches!(s.bind(&bad, &Pose::IDENTITY), Err(ModelError::NonFinite { .. })));
    let mut f = PointForce::new("load", A, Vec3::zeros(), Vec3::z()).unwrap();
    assert!(matches!(f.bind(&Pose::IDENTITY, &bad), Err(ModelError::NonFinite { .. })));
}

#[test]
fn spring_validation() {
    let p = Vec3::new(0.0, 0.5, 0.1);
    match CoilSpring::new("spring", A, p, B, p + Vec3::new(1e-12, 0.0, 0.0), 1e4, 0.3) {
        Err(ModelError::CoincidentPoints { item, distance }) => assert!(item == "spring" && distance < 1e-11),
        e => panic!("{e:?}"),
    }
    let q = p + Vec3::z() * 0.3;
    assert!(matches!(
        CoilSpring::new("spring", A, p, B, q, 0.0, 0.3),
        Err(ModelError::NotPositive { what: "spring rate", .. })
    ));
    assert!(matches!(
        CoilSpring::new("spring", A, p, B, q, 1e4, -0.3),
        Err(ModelError::NotPositive { what: "free length", .. })
    ));
    assert!(matches!(CoilSpring::new("spring", A, p, B, q, f64::NAN, 0.3), Err(ModelError::NonFinite { .. })));
    assert!(matches!(
        CoilSpring::new("spring", A, p, B, Vec3::new(f64::INFINITY, 0.0, 0.0), 1e4, 0.3),
        Err(ModelError::NonFinite { .. })
    ));
    assert!(matches!(CoilSpring::new("spring", A, p, A, q, 1e4, 0.3), Err(ModelError::SelfJoint { .. })));
    let s = CoilSpring::new("spring", A, p, B, q, 1e4, 0.3).unwrap();
    assert!(matches!(s.with_preload(f64::NAN), Err(ModelError::NonFinite { what: "preload", .. })));
    // A tensile design force longer than the spring would need L₀ ≤ 0.
    assert!(matches!(
        CoilSpring::seated("spring", [(A, p), (B, q)], Characteristic::Rate(1e4), SpringLength::DesignForce(-1e4)),
        Err(ModelError::NotPositive { what: "free length", .. })
    ));
    assert!(matches!(
        CoilSpring::seated("spring", [(A, p), (B, q)], Characteristic::Rate(1e4), SpringLength::DesignForce(f64::NAN)),
        Err(ModelError::NonFinite { .. })
    ));
}

#[test]
fn load_validation() {
    assert!(matches!(
        PointForce::new("load", BodyRef::Ground, Vec3::zeros(), Vec3::z()),
        Err(ModelError::SelfJoint { .. })
    ));
    assert!(matches!(
        PointForce::new("load", A, Vec3::zeros(), Vec3::new(0.0, f64::NAN, 0.0)),
        Err(ModelError::NonFinite { what: "force", .. })
    ));
    assert!(matches!(
        PointForce::new("load", A, Vec3::zeros(), Vec3::z()).unwrap().with_constant(Vec3::repeat(f64::INFINITY)),
        Err(ModelError::NonFinite { .. })
    ));
    assert!(matches!(PointTorque::new("t", BodyRef::Ground, Vec3::z()), Err(ModelError::SelfJoint { .. })));
    assert!(matches!(PointTorque::new("t", A, Vec3::repeat(f64::NAN)), Err(ModelError::NonFinite { .. })));
}

#[test]
fn elements_go_into_a_model_and_a_duplicate_name_is_refused() {
    let mut model = Model::new();
    let arm = model.add_body("arm", Pose::at(Vec3::new(0.0, 0.6, 0.0))).unwrap();
    let wheel = model.add_body("wheel", Pose::at(Vec3::new(0.0, 0.8, 0.0))).unwrap();
    model.add_element(Bushing::from_spec(bushing_spec()).unwrap()).unwrap();
    model
        .add_element(
            CoilSpring::new(
                "spring",
                BodyRef::Ground,
                Vec3::new(0.0, 0.5, 0.5),
                arm.into(),
                Vec3::new(0.0, 0.5, 0.1),
                3e4,
                0.45,
            )
            .unwrap(),
        )
        .unwrap();
    model
        .add_element(PointForce::new("fz", wheel.into(), Vec3::new(0.0, 0.8, -0.3), Vec3::z() * 4e3).unwrap())
        .unwrap();
    model.add_element(PointTorque::new("mz", wheel.into(), Vec3::z() * 50.0).unwrap()).unwrap();
    let dup = model.add_element(PointTorque::new("mz", wheel.into(), Vec3::z()).unwrap());
    assert!(matches!(dup, Err(ModelError::DuplicateName { .. })));
    assert_eq!(model.elements().len(), 4);
}
