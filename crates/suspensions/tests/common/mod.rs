//! Reference machinery of the loop-closure tests, independent of the engine; what the tests of Chrono's
//! files share (their fixtures, and the engine's rows they walk a closure along) is in [`chrono`].

#![allow(dead_code, reason = "each test file uses the closures it needs")]

use elastokin_core::Vec3;
use elastokin_suspensions::{DoubleWishboneHardpoints, MacPhersonHardpoints, SuspensionFile};
use nalgebra::{DMatrix, DVector, Matrix3, Rotation3, Unit};
use std::path::{Path, PathBuf};

pub mod chrono;

/// Every suspension model shipped in `examples/` (the vehicle file `vehicle/compact_car.json` joins two
/// of them; `targets/` holds tuning and tolerance files).
pub const MODELS: [&str; 12] = [
    "macpherson.json",
    "double_wishbone.json",
    "double_wishbone_axle.json",
    "five_link.json",
    "four_link_axle.json",
    "pushrod_rocker.json",
    "twist_beam.json",
    "twist_beam_template.json",
    "generic/macpherson.json",
    "generic/double_wishbone.json",
    "vehicle/front_macpherson_with_bar.json",
    "vehicle/compact_car.json",
];

/// The shipped MacPherson's lower-arm and top-mount radial bushing rates, by pointer.
pub const ARM_RADIAL: &str = "/suspension/macpherson/lower_arm_mounts/bushing/radial";
pub const TOP_RADIAL: &str = "/suspension/macpherson/top_mount/bushing/radial";

/// A lateral-force test (16 steps) "measured" on a rig: the MacPherson `base` (a model file's document)
/// with its lower-arm and top-mount radial rates times `arm` and `top`. The rig's document, and its load,
/// toe and camber columns.
pub fn lateral_force_rig(base: &serde_json::Value, arm: f64, top: f64) -> (serde_json::Value, [Vec<f64>; 3]) {
    use elastokin_suspensions::analysis::WheelLoad;
    use elastokin_suspensions::design::Parameters;
    use elastokin_suspensions::kc::{self, Analysis, Settings};
    let mut rig = base.clone();
    for (pointer, factor) in [(ARM_RADIAL, arm), (TOP_RADIAL, top)] {
        let moved = base.pointer(pointer).and_then(serde_json::Value::as_f64).unwrap() * factor;
        *rig.pointer_mut(pointer).unwrap() = serde_json::json!(moved);
    }
    let file = Parameters::new(&rig, &[]).unwrap().file().unwrap();
    let settings = Settings { steps: 16, ..Settings::default() };
    let measured = kc::run(Analysis::Road(WheelLoad::Lateral), &file, &settings).unwrap();
    let column = |c: &str| measured.table.column(c).unwrap().into_iter().map(Option::unwrap).collect::<Vec<f64>>();
    let columns = [column("load_n"), column("toe_deg"), column("camber_deg")];
    (rig, columns)
}

pub fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// The models of [`MODELS`], each read, the vehicle file left out.
pub fn models() -> impl Iterator<Item = (&'static str, SuspensionFile)> {
    MODELS
        .into_iter()
        .filter(|m| *m != "vehicle/compact_car.json")
        .map(|m| (m, SuspensionFile::read(&examples().join(m)).unwrap()))
}

/// Newton's method with a central-difference Jacobian on `residual(x) = 0`, from the guess in `x`;
/// panics when it does not close (the tests start it near a solution).
pub fn newton_fd<const N: usize>(residual: impl Fn(&[f64; N]) -> DVector<f64>, x: &mut [f64; N]) {
    newton_fd_by(residual, x, |jac, f| jac.lu().solve(f).expect("loop closure Jacobian is regular away from lock-up"));
}

/// Newton's method on `residual(x) = 0` with more equations than unknowns, all holding at the solution
/// (Chrono's joints repeat some constraints): each step the least-squares solution of the linearised
/// equations, with a central-difference Jacobian; from the guess in `x`, panicking when it does not close.
pub fn newton_least_squares<const N: usize>(residual: impl Fn(&[f64; N]) -> DVector<f64>, x: &mut [f64; N]) {
    newton_fd_by(residual, x, |jac, f| jac.svd(true, true).solve(f, 1e-12).expect("SVD of the closure Jacobian"));
}

/// The Newton iteration of [`newton_fd`] and [`newton_least_squares`], which differ only in how a step
/// `solve(J, −f)` solves the linearised equations.
fn newton_fd_by<const N: usize>(
    residual: impl Fn(&[f64; N]) -> DVector<f64>,
    x: &mut [f64; N],
    solve: impl Fn(DMatrix<f64>, &DVector<f64>) -> DVector<f64>,
) {
    for _ in 0..60 {
        let f = residual(x);
        if f.norm() < 1e-14 {
            return;
        }
        let mut jac = DMatrix::zeros(f.len(), N);
        for c in 0..N {
            let (mut xp, mut xm) = (*x, *x);
            xp[c] += 1e-7;
            xm[c] -= 1e-7;
            jac.set_column(c, &((residual(&xp) - residual(&xm)) / 2e-7));
        }
        let dx = solve(jac, &(-f));
        for c in 0..N {
            x[c] += dx[c];
        }
    }
    assert!(residual(x).norm() < 1e-12, "loop closure did not close: {:?}", residual(x));
}

/// Toe and camber of a left wheel whose upright is turned by `r` from design (spin axis +y there),
/// written out from their definitions: toe = atan2(aₓ, a_y), camber = atan2(−a_z, √(aₓ² + a_y²)).
pub fn left_toe_camber(r: &nalgebra::Matrix3<f64>) -> (f64, f64) {
    let a = r * nalgebra::Vector3::y();
    (a.x.atan2(a.y), (-a.z).atan2((a.x * a.x + a.y * a.y).sqrt()))
}

fn rotate_about(axis_point: Vec3, axis: Vec3, angle: f64, p: Vec3) -> Vec3 {
    let r = Rotation3::from_axis_angle(&Unit::new_normalize(axis), angle);
    axis_point + r * (p - axis_point)
}

/// Independent loop closure: the arms turn by α (lower) and β (upper) about their pivot axes; the upright
/// follows its two ball joints (shortest rotation of the kingpin, then γ about it) and keeps its tie-rod
/// length; the wheel centre is at the asked height. Three equations in (α, β, γ), solved by Newton with a
/// finite-difference Jacobian. Returns (toe, camber) of the left wheel.
pub fn double_wishbone_closure(h: &DoubleWishboneHardpoints, travel: f64, guess: &mut [f64; 3]) -> (f64, f64) {
    let upright = |x: &[f64; 3]| -> (Vec3, Matrix3<f64>) {
        let lbj = rotate_about(h.lower_arm_front, h.lower_arm_rear - h.lower_arm_front, x[0], h.lower_ball_joint);
        let ubj = rotate_about(h.upper_arm_front, h.upper_arm_rear - h.upper_arm_front, x[1], h.upper_ball_joint);
        let k0 = (h.upper_ball_joint - h.lower_ball_joint).normalize();
        let k1 = (ubj - lbj).normalize();
        // Shortest rotation taking the design kingpin onto the current one.
        let cross = k0.cross(&k1);
        let align = if cross.norm() > 0.0 {
            Rotation3::from_axis_angle(&Unit::new_normalize(cross), cross.norm().atan2(k0.dot(&k1)))
        } else {
            Rotation3::identity()
        };
        let spin = Rotation3::from_axis_angle(&Unit::new_normalize(k1), x[2]);
        (lbj, (spin * align).into_inner())
    };
    let tie_len = (h.tie_rod_outer - h.tie_rod_inner).norm();
    let kp_len = (h.upper_ball_joint - h.lower_ball_joint).norm();
    let residual = |x: &[f64; 3]| -> DVector<f64> {
        let (lbj, r) = upright(x);
        let ubj = rotate_about(h.upper_arm_front, h.upper_arm_rear - h.upper_arm_front, x[1], h.upper_ball_joint);
        let place = |p: Vec3| lbj + r * (p - h.lower_ball_joint);
        DVector::from_vec(vec![
            (ubj - lbj).norm() - kp_len,
            (place(h.tie_rod_outer) - h.tie_rod_inner).norm() - tie_len,
            place(h.wheel_centre).z - (h.wheel_centre.z + travel),
        ])
    };
    newton_fd(residual, guess);
    let (_, r) = upright(guess);
    left_toe_camber(&r)
}

/// Independent loop closure: the lower arm turns by α about its pivot axis; the upright, pinned at the
/// lower ball joint, turns by the rotation vector ω; its strut line (strut lower → top mount at design)
/// must pass through the top mount, its tie rod keep its length, its wheel centre sit at the asked
/// height. Four equations in (α, ω), Newton with a finite-difference Jacobian. Returns (toe, camber).
pub fn macpherson_closure(h: &MacPhersonHardpoints, travel: f64, x: &mut [f64; 4]) -> (f64, f64) {
    let place = |x: &[f64; 4]| {
        let axis = Unit::new_normalize(h.lower_arm_rear - h.lower_arm_front);
        let lbj =
            h.lower_arm_front + Rotation3::from_axis_angle(&axis, x[0]) * (h.lower_ball_joint - h.lower_arm_front);
        let r = Rotation3::from_scaled_axis(Vec3::new(x[1], x[2], x[3]));
        (lbj, r)
    };
    let strut0 = (h.top_mount - h.strut_lower).normalize();
    let tie = (h.tie_rod_outer - h.tie_rod_inner).norm();
    let residual = |x: &[f64; 4]| {
        let (lbj, r) = place(x);
        let at = |p: Vec3| lbj + r * (p - h.lower_ball_joint);
        let dir = r * strut0;
        let off = (h.top_mount - at(h.strut_lower)).cross(&dir);
        // Two independent components of the offset: project on two axes across the strut.
        let u = dir.cross(&Vec3::x()).normalize();
        let v = dir.cross(&u);
        DVector::from_vec(vec![
            off.dot(&u),
            off.dot(&v),
            (at(h.tie_rod_outer) - h.tie_rod_inner).norm() - tie,
            at(h.wheel_centre).z - (h.wheel_centre.z + travel),
        ])
    };
    newton_fd(residual, x);
    let (_, r) = place(x);
    left_toe_camber(r.matrix())
}

/// The largest toe or camber difference (rad) between a corner's parallel travel of ±80 mm in 16 steps and
/// a loop closure `closure(travel, guess) -> (toe, camber)`, walked outwards from design in both directions
/// so that each closure starts from its neighbour's solution.
pub fn travel_against_closure<const N: usize>(
    corner: &elastokin_suspensions::Corner,
    closure: impl Fn(f64, &mut [f64; N]) -> (f64, f64),
) -> f64 {
    use elastokin_solver::Mode;
    let rows =
        elastokin_suspensions::analysis::parallel_wheel_travel(corner, -0.08, 0.08, 16, Mode::Corrected).unwrap();
    let mut worst: f64 = 0.0;
    for half in [rows[8..].iter().collect::<Vec<_>>(), rows[..=8].iter().rev().collect()] {
        let mut guess = [0.0; N];
        for row in half {
            let (toe, camber) = closure(row.travel, &mut guess);
            worst = worst.max((row.attitude.toe - toe).abs()).max((row.attitude.camber - camber).abs());
        }
    }
    worst
}
