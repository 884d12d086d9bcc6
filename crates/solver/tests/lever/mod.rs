//! A lever hinged at the origin about y, held by a coil spring, its tip loaded: the model the replay and
//! path-rate tests solve, with its moment balance written out for them to check against.
#![allow(dead_code, reason = "each test file uses the helpers it needs")]

use elastokin_core::{BodyRef, JointSpec, Model, Pose, Vec3};
use elastokin_elements::{CoilSpring, PointForce};
use elastokin_solver::StepResult;

pub const TIP_LOAD: f64 = 500.0;
pub const TOP: [f64; 3] = [0.0, 0.0, 0.2];
pub const SEAT: f64 = 0.3;
pub const TIP: f64 = 0.5;

/// A lever hinged at the origin about y, held by a spring of rate `k` (N/m) from `TOP` to its seat, its tip
/// loaded downward by `TIP_LOAD` times the load parameter.
pub fn lever(k: f64) -> Model {
    let mut model = Model::new();
    let lever = model.add_body("lever", Pose::at(Vec3::new(0.25, 0.0, 0.0))).unwrap();
    model.add_joint(JointSpec::revolute("pivot", BodyRef::Ground, lever, Vec3::zeros(), Vec3::y())).unwrap();
    let seat = Vec3::new(SEAT, 0.0, 0.0);
    let top = Vec3::from(TOP);
    let spring = CoilSpring::new("spring", BodyRef::Ground, top, lever.into(), seat, k, (seat - top).norm()).unwrap();
    model.add_element(spring).unwrap();
    let tip = PointForce::new("tip", lever.into(), Vec3::new(TIP, 0.0, 0.0), Vec3::new(0.0, 0.0, -TIP_LOAD)).unwrap();
    model.add_element(tip).unwrap();
    model
}

/// The lever's rotation about y (tip down +) at a step.
pub fn angle(step: &StepResult) -> f64 {
    let p = step.poses[0].position;
    (-p.z).atan2(p.x)
}

/// The moment about the hinge (y) of the spring and the tip load on the lever turned by `theta`.
pub fn moment(theta: f64, k: f64, load: f64) -> f64 {
    let (c, s) = (theta.cos(), theta.sin());
    let seat = Vec3::new(SEAT * c, 0.0, -SEAT * s);
    let top = Vec3::from(TOP);
    let free = (Vec3::new(SEAT, 0.0, 0.0) - top).norm();
    let d = seat - top;
    let spring = -k * (d.norm() - free) * d / d.norm();
    let tip = Vec3::new(TIP * c, 0.0, -TIP * s);
    seat.cross(&spring).y + tip.cross(&Vec3::new(0.0, 0.0, -load * TIP_LOAD)).y
}
