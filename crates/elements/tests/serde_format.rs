//! The parameter structs as the `serde` feature writes and reads them (JSON here): a curve is its list of
//! `[x, y]` points and is checked when read; a characteristic is `{"rate": k}` or `{"curve": [...]}`.
//! Run with `cargo test -p elastokin-elements --features serde --test serde_format`.
#![cfg(feature = "serde")]

use elastokin_core::{BodyId, BodyRef, Mat3, Vec3};
use elastokin_elements::{
    Bushing, BushingSpec, Characteristic, CoilSpring, CoilSpringSpec, Curve, Stop, StopKind, StopSpec,
};

#[test]
fn specs_with_curves_read_back_as_written() {
    let curve = Curve::new("spring", [[0.0, 0.0], [0.02, 500.0], [0.05, 1800.0]]).unwrap();
    let spring = CoilSpringSpec {
        name: "spring".into(),
        body_i: BodyRef::Ground,
        point_i: Vec3::new(0.0, 0.5, 0.6),
        body_j: BodyRef::Body(BodyId(0)),
        point_j: Vec3::new(0.0, 0.5, 0.3),
        characteristic: Characteristic::Curve(curve.clone()),
        free_length: 0.32,
        preload: 0.0,
    };
    let text = serde_json::to_string(&spring).unwrap();
    assert!(text.contains(r#""characteristic":{"curve":[[0.0,0.0],[0.02,500.0],[0.05,1800.0]]}"#), "{text}");
    let back: CoilSpringSpec = serde_json::from_str(&text).unwrap();
    assert_eq!(back, spring);
    assert!(CoilSpring::from_spec(back).is_ok());

    let bushing = BushingSpec {
        name: "bush".into(),
        body_i: BodyRef::Ground,
        body_j: BodyRef::Body(BodyId(0)),
        point: Vec3::zeros(),
        frame: Mat3::identity(),
        translational: [
            Characteristic::Rate(1e6),
            Characteristic::Curve(Curve::new("bush", [[-0.01, -8000.0], [0.0, 0.0], [0.01, 12000.0]]).unwrap()),
            Characteristic::Rate(2e6),
        ],
        rotational: Characteristic::rates(&Vec3::new(100.0, 200.0, 300.0)),
        preload_force: Vec3::zeros(),
        preload_torque: Vec3::zeros(),
        rotation_law: Default::default(),
    };
    let text = serde_json::to_string(&bushing).unwrap();
    assert!(text.contains(r#""translational":[{"rate":1000000.0},{"curve":[[-0.01,-8000.0]"#), "{text}");
    let back: BushingSpec = serde_json::from_str(&text).unwrap();
    assert_eq!(back, bushing);
    assert!(Bushing::from_spec(back).is_ok());

    let stop = StopSpec {
        name: "bump stop".into(),
        body_i: BodyRef::Ground,
        point_i: Vec3::new(0.0, 0.5, 0.6),
        body_j: BodyRef::Body(BodyId(0)),
        point_j: Vec3::new(0.0, 0.5, 0.3),
        kind: StopKind::Bump,
        clearance: 0.04,
        curve: Curve::new("bump stop", [[0.0, 0.0], [0.01, 400.0], [0.02, 1600.0]]).unwrap(),
    };
    let text = serde_json::to_string(&stop).unwrap();
    assert!(text.contains(r#""kind":"bump""#), "{text}");
    let back: StopSpec = serde_json::from_str(&text).unwrap();
    assert_eq!(back, stop);
    assert!(Stop::from_spec(back).is_ok());
}

#[test]
fn a_bad_table_is_refused_when_read() {
    let err = serde_json::from_str::<Curve>("[[0.0, 0.0], [0.02, 500.0], [0.01, 800.0]]").unwrap_err();
    let text = err.to_string();
    assert!(text.contains("point 2") && text.contains("strictly increasing x"), "{text}");
    let err = serde_json::from_str::<Curve>("[[0.0, 0.0]]").unwrap_err();
    assert!(err.to_string().contains("at least two points"), "{err}");
}
