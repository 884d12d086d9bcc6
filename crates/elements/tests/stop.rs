//! Bump and rebound stops: nothing before contact, the force of a parabolic table against its closed-form
//! energy after it, the stiffness against finite differences before contact, in every piece of a table and
//! past its end, and refusals.

mod common;

use common::*;
use elastokin_core::{BodyId, BodyRef, ForceElement, ModelError, PairMatrix, Pose, RowGradient, Vec3};
use elastokin_elements::{Curve, Stop, StopKind, StopSpec};

/// A progressive rubber stop: force against penetration with uneven steps and a steep end.
fn rubber() -> Curve {
    Curve::new("stop", [[0.0, 0.0], [0.004, 150.0], [0.01, 700.0], [0.016, 2200.0], [0.02, 6000.0]]).unwrap()
}

/// `F = c p² + b p` on `0 ≤ p ≤ 0.02`, reproduced exactly between the table's points.
const C: f64 = 1.5e7;
const B: f64 = 2.0e4;

fn parabola_table() -> Curve {
    Curve::new("stop", [0.0, 0.003, 0.008, 0.014, 0.02].map(|p| [p, C * p * p + B * p])).unwrap()
}

/// A stop's design geometry and poses at which its points are a chosen distance apart.
struct Case {
    stop: Stop,
    design_i: Pose,
    design_j: Pose,
    point_i: Vec3,
    point_j: Vec3,
    gi: bool,
    gj: bool,
}

impl Case {
    fn new(rng: &mut Rng, gi: bool, gj: bool, kind: StopKind, clearance: f64, curve: Curve) -> Self {
        let point_i = rng.vec(0.3);
        let point_j = point_i + rng.unit() * rng.uniform(0.2, 0.3);
        let design_i = if gi { Pose::IDENTITY } else { rng.pose(0.5) };
        let design_j = if gj { Pose::IDENTITY } else { rng.pose(0.5) };
        let spec = StopSpec {
            name: "stop".into(),
            body_i: body(gi, 0),
            point_i,
            body_j: body(gj, 1),
            point_j,
            kind,
            clearance,
            curve,
        };
        let mut stop = Stop::from_spec(spec).unwrap();
        stop.bind(&design_i, &design_j).unwrap();
        Case { stop, design_i, design_j, point_i, point_j, gi, gj }
    }

    fn seat(design: &Pose, point: &Vec3, at: &Pose) -> Vec3 {
        at.position + at.rotation() * (design.rotation().transpose() * (point - design.position))
    }

    /// The two seats at poses `a`, `b` (independent of the element).
    fn seats(&self, a: &Pose, b: &Pose) -> (Vec3, Vec3) {
        (Self::seat(&self.design_i, &self.point_i, a), Self::seat(&self.design_j, &self.point_j, b))
    }

    /// Random poses at which the points are `length` apart. A grounded `j` stays put, and `i` moves then.
    fn poses_at(&self, rng: &mut Rng, length: f64) -> (Pose, Pose) {
        let turn = |rng: &mut Rng, p: &Pose| {
            let mut q = *p;
            q.apply_increment(&rng.vec(0.05), &rng.rotvec(0.2, 1.2));
            q
        };
        let n = rng.unit();
        if self.gj {
            let pi = turn(rng, &self.design_i);
            let mut pi = pi;
            let target = self.point_j - n * length;
            pi.position += target - Self::seat(&self.design_i, &self.point_i, &pi);
            (pi, Pose::IDENTITY)
        } else {
            let pi = if self.gi { Pose::IDENTITY } else { turn(rng, &self.design_i) };
            let mut pj = turn(rng, &self.design_j);
            let target = Self::seat(&self.design_i, &self.point_i, &pi) + n * length;
            pj.position += target - Self::seat(&self.design_j, &self.point_j, &pj);
            (pi, pj)
        }
    }

    /// The length at penetration `p`.
    fn length_at(&self, p: f64) -> f64 {
        let spec = self.stop.spec();
        match spec.kind {
            StopKind::Bump => spec.design_length() - spec.clearance - p,
            StopKind::Rebound => spec.design_length() + spec.clearance + p,
        }
    }
}

const GROUNDINGS: [(bool, bool); 3] = [(false, false), (true, false), (false, true)];
const KINDS: [StopKind; 2] = [StopKind::Bump, StopKind::Rebound];

#[test]
fn no_force_and_no_stiffness_before_contact() {
    let mut rng = Rng::new(0x0FF);
    for kind in KINDS {
        for (gi, gj) in GROUNDINGS {
            let case = Case::new(&mut rng, gi, gj, kind, 0.03, rubber());
            // Anywhere from the far side of design to just short of contact.
            for gap in [0.05, 0.03, 0.01, 1e-6] {
                let (pi, pj) = case.poses_at(&mut rng, case.length_at(-gap));
                let ev = eval(&case.stop, &pi, &pj, 0.0);
                assert_eq!(ev.force, RowGradient::zeros(), "{kind:?} gap {gap}");
                assert_eq!(ev.stiffness, PairMatrix::zeros(), "{kind:?} gap {gap}");
                let rep = case.stop.report(&pi, &pj, 0.0);
                assert_eq!(rep.force, Vec3::zeros());
                // Measured: 3.5e-16 m at worst (lengths of ≈ 0.3 m rebuilt from poses).
                assert!((rep.deflection.x + gap).abs() < 1e-14, "{} vs {}", rep.deflection.x, -gap);
            }
        }
    }
    // Touching at design with zero clearance: still no force there.
    let case = Case::new(&mut rng, false, false, StopKind::Bump, 0.0, rubber());
    assert_eq!(eval(&case.stop, &case.design_i, &case.design_j, 0.0).force, RowGradient::zeros());
}

/// In contact, with a parabolic table: the force is `c p² + b p`, pushing the points apart for a bump
/// stop and pulling them together for a rebound stop, and the generalized force is minus the gradient of
/// `U = c p³/3 + b p²/2`.
#[test]
fn force_in_contact_against_the_closed_form_energy() {
    let mut rng = Rng::new(0xB0B);
    for kind in KINDS {
        for (gi, gj) in GROUNDINGS {
            let clearance = rng.uniform(0.0, 0.05);
            let case = Case::new(&mut rng, gi, gj, kind, clearance, parabola_table());
            for p in [0.001, 0.006, 0.012, 0.019] {
                let (pi, pj) = case.poses_at(&mut rng, case.length_at(p));
                let spec = case.stop.spec().clone();
                let energy = |a: &Pose, b: &Pose| {
                    let (x, y) = case.seats(a, b);
                    let l = (y - x).norm();
                    let p = match spec.kind {
                        StopKind::Bump => spec.design_length() - spec.clearance - l,
                        StopKind::Rebound => l - spec.design_length() - spec.clearance,
                    };
                    C * p * p * p / 3.0 + B * p * p / 2.0
                };
                let ev = eval(&case.stop, &pi, &pj, 0.0);
                let grad = fd_scalar(&pi, &pj, energy);
                // Measured: 1.4e-7 at worst (central differences of an energy of a few mJ at p = 1 mm).
                assert_vec_close(&format!("{kind:?} p = {p}"), &ev.force, &(-grad), 1e-6);
                let (x, y) = case.seats(&pi, &pj);
                let apart = (y - x).normalize();
                let force = C * p * p + B * p;
                let on_j = match kind {
                    StopKind::Bump => force * apart,
                    StopKind::Rebound => -force * apart,
                };
                let rep = case.stop.report(&pi, &pj, 0.0);
                // Measured: 2.4e-13 of the force and 2.3e-16 m at worst (the penetration is a difference of
                // lengths ≈ 0.3 m).
                assert!((rep.force - on_j).norm() < 1e-11 * force, "{kind:?} p = {p}: {:?} vs {on_j:?}", rep.force);
                assert!((rep.deflection.x - p).abs() < 1e-14, "{}", rep.deflection.x);
            }
        }
    }
}

/// The stiffness is the derivative of the force before contact (zero), in every piece of a rubber
/// table, and past its last point, at random poses with lever arms, for both kinds.
#[test]
fn stiffness_is_the_force_derivative_before_in_and_past_the_table() {
    let mut rng = Rng::new(0x5D);
    // Before contact, in each of the four pieces (the first close to contact), past the last point.
    let penetrations = [-0.004, 0.0005, 0.007, 0.013, 0.018, 0.03];
    for kind in KINDS {
        for (gi, gj) in GROUNDINGS {
            for &p in &penetrations {
                let clearance = rng.uniform(0.0, 0.05);
                let case = Case::new(&mut rng, gi, gj, kind, clearance, rubber());
                let (pi, pj) = case.poses_at(&mut rng, case.length_at(p));
                let ev = eval(&case.stop, &pi, &pj, 0.0);
                let k_fd = fd_stiffness(&case.stop, &pi, &pj, 0.0);
                // Measured: 5.3e-8 at worst over the 36 configurations.
                assert_mat_close(&format!("{kind:?} ({gi},{gj}) p = {p}"), &ev.stiffness, &k_fd, 1e-6);
                let skew_part = ev.stiffness - ev.stiffness.transpose();
                // Measured: 1.7e-9 at worst, at p = 0.5 mm: rounding of K (rate ~2e4 N/m) against the small
                // moments of an 8 N force.
                assert_mat_close("K − Kᵀ", &skew_part, &expected_skew_part(&ev.force), 1e-7);
            }
        }
    }
}

fn refused(spec: StopSpec) -> ModelError {
    let err = Stop::from_spec(spec).unwrap_err();
    assert!(err.to_string().contains("'bump stop'"), "{err}");
    err
}

#[test]
fn stops_that_cannot_work_are_refused_by_name() {
    let (a, b) = (Vec3::new(0.0, 0.5, 0.1), Vec3::new(0.0, 0.5, 0.4));
    let good = StopSpec {
        name: "bump stop".into(),
        body_i: BodyRef::Ground,
        point_i: a,
        body_j: BodyRef::Body(BodyId(0)),
        point_j: b,
        kind: StopKind::Bump,
        clearance: 0.05,
        curve: rubber(),
    };
    assert!(Stop::from_spec(good.clone()).is_ok());
    let text = |e: ModelError| e.to_string();
    // A negative clearance: in contact at design (another tool's data); a rebound stop touching at a length
    // of zero or less is refused.
    assert!(Stop::from_spec(StopSpec { clearance: -0.01, ..good.clone() }).is_ok());
    let t = text(refused(StopSpec { clearance: -0.5, kind: StopKind::Rebound, ..good.clone() }));
    assert!(t.contains("clearance") && t.contains("-0.5"), "{t}");
    assert!(matches!(
        refused(StopSpec { clearance: f64::NAN, ..good.clone() }),
        ModelError::NonFinite { what: "clearance", .. }
    ));
    // A bump stop whose clearance is the whole length never touches; a rebound stop may have any.
    let t = text(refused(StopSpec { clearance: 0.35, ..good.clone() }));
    assert!(t.contains("never touch"), "{t}");
    assert!(Stop::from_spec(StopSpec { clearance: 0.3, kind: StopKind::Rebound, ..good.clone() }).is_ok());
    // The curve starts at (0, 0), and its force never decreases.
    let late = Curve::new("bump stop", [[0.002, 0.0], [0.01, 500.0]]).unwrap();
    let t = text(refused(StopSpec { curve: late, ..good.clone() }));
    assert!(t.contains("starts at (0.002, 0)") && t.contains("start the table at (0, 0)"), "{t}");
    let soft = Curve::new("bump stop", [[0.0, 0.0], [0.01, 500.0], [0.02, 400.0]]).unwrap();
    let t = text(refused(StopSpec { curve: soft, ..good.clone() }));
    assert!(t.contains("point 2") && t.contains("never decreases"), "{t}");
    assert!(matches!(refused(StopSpec { body_j: BodyRef::Ground, ..good.clone() }), ModelError::SelfJoint { .. }));
    assert!(matches!(refused(StopSpec { point_j: a, ..good.clone() }), ModelError::CoincidentPoints { .. }));
    let stop = Stop::rebound("rebound stop", BodyRef::Ground, a, BodyRef::Body(BodyId(0)), b, 0.02, rubber()).unwrap();
    assert_eq!(stop.spec().kind, StopKind::Rebound);
    assert!((stop.spec().contact_length() - 0.32).abs() < 1e-15);
}
