//! Every joint kind: zero at design, Jacobians and reaction-force derivatives equal finite differences at
//! random poses, and refused degenerate input.

use elastokin_core::constraint::PairMatrix;
use elastokin_core::{BodyRef, JointKind, JointSpec, Model, ModelError, Pose, Vec3};
use nalgebra::UnitQuaternion;

/// Small deterministic generator so the test needs no extra crate.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
    }
    fn vec(&mut self, scale: f64) -> Vec3 {
        Vec3::new(self.next(), self.next(), self.next()) * scale
    }
}

fn two_bodies() -> (Model, BodyRef, BodyRef) {
    let mut m = Model::new();
    let a = m
        .add_body(
            "upright",
            Pose { position: Vec3::new(0.0, 0.8, 0.0), orientation: UnitQuaternion::from_euler_angles(0.1, 0.2, -0.3) },
        )
        .unwrap();
    let b = m
        .add_body(
            "arm",
            Pose {
                position: Vec3::new(0.1, 0.5, -0.2),
                orientation: UnitQuaternion::from_euler_angles(-0.4, 0.0, 0.7),
            },
        )
        .unwrap();
    (m, a.into(), b.into())
}

fn all_specs(i: BodyRef, j: BodyRef) -> Vec<JointSpec> {
    let p = Vec3::new(0.05, 0.7, -0.1);
    let q = Vec3::new(-0.1, 0.6, 0.2);
    let h = Vec3::new(0.3, -0.2, 0.9);
    let h_perp = h.cross(&Vec3::x());
    vec![
        JointSpec::spherical("spherical", i, j, p),
        JointSpec::revolute("revolute", i, j, p, h),
        JointSpec::cylindrical("cylindrical", i, j, p, h),
        JointSpec::translational("translational", i, j, p, h),
        JointSpec::universal("universal", i, j, p, h, h_perp),
        JointSpec::fixed("fixed", i, j, p),
        JointSpec::distance("distance", i, j, p, q),
        JointSpec::in_plane("in-plane", i, j, p, h),
        JointSpec::in_line("in-line", i, j, p, h),
        JointSpec::perpendicular("perpendicular", i, j, h, h_perp),
        JointSpec::parallel_axes("parallel", i, j, h),
        JointSpec::point_driver("point driver", j, p, Vec3::z(), 0.05),
        JointSpec::travel_driver("travel driver", i, j, p, h, 0.02),
    ]
}

fn expected_rows(kind: JointKind) -> usize {
    match kind {
        JointKind::Spherical => 3,
        JointKind::Revolute | JointKind::Translational => 5,
        JointKind::Cylindrical | JointKind::Universal => 4,
        JointKind::Fixed => 6,
        JointKind::InLine | JointKind::ParallelAxes => 2,
        _ => 1,
    }
}

#[test]
fn every_joint_is_satisfied_at_design_and_has_the_expected_rows() {
    for ground_i in [false, true] {
        let (mut m, a, b) = two_bodies();
        let i = if ground_i { BodyRef::Ground } else { a };
        for spec in all_specs(i, b) {
            let kind = spec.kind;
            let id = m.add_joint(spec).unwrap();
            let jt = &m.joints()[id.0];
            assert_eq!(jt.rows.len(), expected_rows(kind), "{kind:?}");
            let poses = m.design_poses();
            let (pi, pj) = (jt.spec.body_i.pose(&poses), jt.spec.body_j.pose(&poses));
            for r in &jt.rows {
                assert!(r.value(&pi, &pj, 0.0).abs() < 1e-14, "{kind:?} {}: {}", r.label, r.value(&pi, &pj, 0.0));
            }
        }
    }
}

#[test]
fn joint_jacobians_and_reaction_derivatives_match_finite_differences_at_random_poses() {
    let mut rng = Lcg(7);
    let (mut m, a, b) = two_bodies();
    for spec in all_specs(a, b) {
        m.add_joint(spec).unwrap();
    }
    let h = 1e-6;
    for trial in 0..5 {
        // Random poses far from design, so rows are far from zero and reactions non-trivial.
        let poses: Vec<Pose> = (0..2)
            .map(|_| Pose { position: rng.vec(0.5), orientation: UnitQuaternion::from_scaled_axis(rng.vec(1.2)) })
            .collect();
        for jt in m.joints() {
            let (pi, pj) = (jt.spec.body_i.pose(&poses), jt.spec.body_j.pose(&poses));
            for row in &jt.rows {
                let t = 0.3;
                let ev = row.evaluate(&pi, &pj, t);
                let lambda = 1.7;
                let mut dg = PairMatrix::zeros();
                row.add_force_derivative(&pi, &pj, lambda, &mut dg);
                for c in 0..12 {
                    let mut plus = [pi, pj];
                    let mut minus = [pi, pj];
                    let mut d = [0.0; 6];
                    d[c % 6] = h;
                    plus[c / 6].apply_increment6(&d);
                    d[c % 6] = -h;
                    minus[c / 6].apply_increment6(&d);
                    let fd = (row.value(&plus[0], &plus[1], t) - row.value(&minus[0], &minus[1], t)) / (2.0 * h);
                    let scale = 1.0 + ev.gradient.abs().max();
                    assert!(
                        (fd - ev.gradient[c]).abs() < 1e-7 * scale,
                        "trial {trial} {} row {} col {c}: fd {fd} vs {}",
                        jt.name(),
                        row.label,
                        ev.gradient[c]
                    );
                    let gp = row.evaluate(&plus[0], &plus[1], t).gradient;
                    let gm = row.evaluate(&minus[0], &minus[1], t).gradient;
                    for r in 0..12 {
                        let fd = lambda * (gp[r] - gm[r]) / (2.0 * h);
                        assert!(
                            (fd - dg[(r, c)]).abs() < 1e-6 * scale,
                            "trial {trial} {} row {} ({r},{c}): fd {fd} vs {}",
                            jt.name(),
                            row.label,
                            dg[(r, c)]
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn degenerate_joints_are_refused_with_named_errors() {
    let (mut m, a, b) = two_bodies();
    let p = Vec3::new(0.0, 0.7, 0.0);
    let e = m.add_joint(JointSpec::revolute("zero axis", a, b, p, Vec3::zeros())).unwrap_err();
    assert!(matches!(e, ModelError::ZeroLengthAxis { ref item, .. } if item == "zero axis"), "{e}");
    let e = m.add_joint(JointSpec::distance("short link", a, b, p, p)).unwrap_err();
    assert!(matches!(e, ModelError::CoincidentPoints { ref item, .. } if item == "short link"), "{e}");
    let e = m.add_joint(JointSpec::spherical("nan", a, b, Vec3::new(f64::NAN, 0.0, 0.0))).unwrap_err();
    assert!(matches!(e, ModelError::NonFinite { .. }), "{e}");
    let e = m.add_joint(JointSpec::spherical("self", a, a, p)).unwrap_err();
    assert!(matches!(e, ModelError::SelfJoint { .. }), "{e}");
    let e = m.add_joint(JointSpec::universal("skew cardan", a, b, p, Vec3::x(), Vec3::new(1.0, 1.0, 0.0))).unwrap_err();
    assert!(matches!(e, ModelError::NotPerpendicular { .. }), "{e}");
    let e = m.add_joint(JointSpec::spherical("ghost", BodyRef::Body(elastokin_core::BodyId(9)), b, p)).unwrap_err();
    assert!(matches!(e, ModelError::UnknownBody { index: 9, .. }), "{e}");
    m.add_joint(JointSpec::spherical("ball", a, b, p)).unwrap();
    let e = m.add_joint(JointSpec::spherical("ball", a, b, p)).unwrap_err();
    assert!(matches!(e, ModelError::DuplicateName { .. }), "{e}");
    // A body nobody holds is named.
    m.add_body("loose wheel", Pose::default()).unwrap();
    let e = m.validate().unwrap_err();
    assert!(matches!(e, ModelError::NothingHolds { ref body } if body == "loose wheel"), "{e}");
}

/// A constraint row's joint and its row within it: for a model of joints of every row count, each global
/// row against the rows counted out joint by joint in the test, and nothing past the last.
#[test]
fn each_constraint_row_is_found_in_its_joint() {
    let mut m = Model::new();
    let p = Pose { position: Vec3::new(0.0, 0.5, 0.0), orientation: UnitQuaternion::identity() };
    let bodies: Vec<BodyRef> = (0..4).map(|k| m.add_body(&format!("b{k}"), p).unwrap().into()).collect();
    let at = Vec3::new(0.0, 0.5, 0.0);
    let specs = [
        JointSpec::spherical("ball", BodyRef::Ground, bodies[0], at),
        JointSpec::distance("link", bodies[0], bodies[1], at, at + Vec3::x()),
        JointSpec::revolute("hinge", bodies[1], bodies[2], at, Vec3::y()),
        JointSpec::fixed("weld", bodies[2], bodies[3], at),
        JointSpec::in_plane("plane", BodyRef::Ground, bodies[3], at, Vec3::z()),
    ];
    let mut expected = Vec::new();
    for spec in specs {
        let id = m.add_joint(spec).unwrap();
        let rows = m.joints()[id.0].rows.len();
        expected.extend((0..rows).map(|r| (id.0, r)));
    }
    // 3 + 1 + 5 + 6 + 1 rows.
    assert_eq!(expected.len(), 16);
    assert_eq!(m.constraint_rows(), expected.len());
    for (row, &(joint, within)) in expected.iter().enumerate() {
        let o = m.row_origin(row).unwrap();
        assert_eq!((o.joint.0, o.row), (joint, within), "row {row}");
    }
    assert!(m.row_origin(expected.len()).is_none());
}

#[test]
fn a_held_driver_holds_its_point_at_the_travel_whatever_the_load_parameter() {
    // Each driver's body moved by 30 mm along its direction: the held driver is met there at any `t`, the
    // driver as built only at the `t` its rate takes to travel 30 mm; a joint that is no driver is refused.
    let (mut m, i, j) = two_bodies();
    let travel = 0.03;
    let h = Vec3::new(0.3, -0.2, 0.9).normalize();
    let specs = all_specs(i, j);
    let drivers: Vec<_> = specs.into_iter().filter(|s| s.kind.is_driver()).collect();
    assert_eq!(drivers.len(), 2);
    for spec in drivers {
        let (direction, rate) = (if spec.kind == JointKind::PointDriver { Vec3::z() } else { h }, spec.travel);
        let id = m.add_joint(spec).unwrap();
        let mut poses = m.design_poses();
        let BodyRef::Body(b) = j else { unreachable!() };
        poses[b.0].position += direction * travel;
        let value = |m: &Model, t: f64| {
            let jt = &m.joints()[id.0];
            jt.rows[0].value(&jt.spec.body_i.pose(&poses), &jt.spec.body_j.pose(&poses), t)
        };
        // Measured 0 and 1e-17.
        assert!(value(&m, travel / rate).abs() < 1e-15, "{}", value(&m, travel / rate));
        let mut held = m.clone();
        held.hold_driver(id, travel).unwrap();
        for t in [-1.0, 0.0, 0.4, 7.0] {
            assert!(value(&held, t).abs() < 1e-15, "{t}: {}", value(&held, t));
        }
        assert!(!held.joints()[id.0].rows[0].is_driver());
        // A hold is from design, not from the last hold: held elsewhere first, then at the travel, it holds there.
        let mut again = m.clone();
        again.hold_driver(id, 0.5).unwrap();
        again.hold_driver(id, travel).unwrap();
        assert!(value(&again, 3.0).abs() < 1e-15, "{}", value(&again, 3.0));
    }
    let mut m = m;
    let ball = m.add_joint(JointSpec::spherical("ball", i, j, Vec3::new(0.0, 0.6, 0.0))).unwrap();
    let refused = m.hold_driver(ball, travel).unwrap_err().to_string();
    assert!(refused.contains("only a driver can be held"), "{refused}");
}
