//! Beams refused by name where no beam is: no length, a section value that is not positive, a shear centre
//! beyond any section of its area, a section axis along the beam. (Beams solved against closed forms and
//! the elastica: `crates/solver/tests/beam.rs`.)

use elastokin_core::{BodyId, BodyRef, ModelError, Vec3};
use elastokin_elements::{beam, BeamSpec, Section};

fn spec() -> BeamSpec {
    BeamSpec {
        name: "cross member".into(),
        body_i: BodyRef::Ground,
        body_j: BodyRef::Body(BodyId(0)),
        from: Vec3::zeros(),
        to: Vec3::new(1.0, 0.0, 0.0),
        y_axis: Vec3::y(),
        section: Section {
            youngs_modulus: 210e9,
            shear_modulus: 80e9,
            area: 4e-4,
            iy: 2e-8,
            iz: 3e-8,
            j: 5e-8,
            shear_areas: Some((2e-4, 2e-4)),
            shear_centre: (0.0, 0.02),
        },
    }
}

fn refused(s: BeamSpec, says: &str) {
    match beam(&s) {
        Err(ModelError::OutOfRange { item, why }) => {
            assert_eq!(item, "cross member");
            assert!(why.contains(says), "{why}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn what_is_no_beam_is_refused_by_name() {
    assert!(beam(&spec()).is_ok());
    refused(BeamSpec { to: Vec3::zeros(), ..spec() }, "length");
    let mut s = spec();
    s.section.iy = 0.0;
    refused(s, "second moment Iy");
    let mut s = spec();
    s.section.shear_areas = Some((2e-4, -1.0));
    refused(s, "shear area Az");
    let mut s = spec();
    s.section.shear_centre = (0.5, 0.0);
    refused(s, "shear centre lies");
    refused(BeamSpec { y_axis: Vec3::x(), ..spec() }, "y_axis lies along the beam");
}
