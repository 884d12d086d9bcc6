//! Project Chrono's push-pipe axles (`PushPipeAxle`, `ToeBarPushPipeAxle`: the UAZ bus's rear and front,
//! files copied unchanged into `tests/data/chrono/uaz/`, BSD-3-Clause) read into the general model with an
//! `axle`: each wheel follows, in parallel and opposite travel and in steering, the closure equations of
//! Chrono's own linkage written out here from the Chrono file (not from the import). The UAZ files' crossed
//! stops are refused by name, and with the two lengths swapped the files run through every analysis; the
//! generic `RigidPinnedAxle`, which no spring holds, is refused by name.

mod common;

use common::newton_fd;
use elastokin_solver::Mode;
use elastokin_suspensions::analysis::parallel_wheel_travel;
use elastokin_suspensions::axle::axle_sweep;
use elastokin_suspensions::chrono::{import, without_comments};
use elastokin_suspensions::kc::{self, Analysis, Settings};
use elastokin_suspensions::{Axle, AxleRig, Rig, Side, SuspensionFile, Template};
use nalgebra::{DVector, Rotation3, Unit, Vector3};
use serde_json::Value;
use std::path::Path;

type V = Vector3<f64>;

const REAR: &str = "uaz/UAZBUS_RearPushPipeAxle.json";
const FRONT: &str = "uaz/UAZBUS_FrontPushPipeAxle.json";

fn fixture(path: &str) -> String {
    let full = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/chrono").join(path);
    std::fs::read_to_string(&full).unwrap_or_else(|e| panic!("{}: {e}", full.display()))
}

fn chrono(path: &str) -> Value {
    serde_json::from_str(&without_comments(&fixture(path))).unwrap()
}

/// The Chrono file as JSON, and the model imported from it with its spring's `Minimum Length` and `Maximum
/// Length` swapped (the file's are crossed, and refused).
fn read_swapped(path: &str) -> (Value, SuspensionFile) {
    let original = chrono(path);
    let mut swapped = original.clone();
    let spring = &mut swapped["Spring"];
    let (min, max) = (spring["Minimum Length"].clone(), spring["Maximum Length"].clone());
    spring["Minimum Length"] = max;
    spring["Maximum Length"] = min;
    let file = import(&swapped.to_string(), path, None).unwrap_or_else(|e| panic!("{path}: {e}")).file;
    (original, file)
}

/// The point at `path` (keys joined by `/`) of a Chrono file: as Chrono gives it.
fn point(chrono: &Value, path: &str) -> V {
    let v = path.split('/').fold(chrono, |v, key| &v[key]);
    let c: Vec<f64> = v.as_array().unwrap_or_else(|| panic!("{path}")).iter().map(|x| x.as_f64().unwrap()).collect();
    V::new(c[0], c[1], c[2])
}

/// The right side's mirror image of a left point, as Chrono places it (y → −y).
fn mirror(p: V) -> V {
    V::new(p.x, -p.y, p.z)
}

#[derive(Clone, Copy)]
/// The axle tube moved by `x[0..3]` (translation) and `x[3..6]` (rotation vector about the tube's `COM`).
struct Tube {
    centre: V,
}

impl Tube {
    fn rotation(&self, x: &[f64]) -> Rotation3<f64> {
        Rotation3::new(V::new(x[3], x[4], x[5]))
    }

    fn moved(&self, x: &[f64], p: V) -> V {
        self.centre + V::new(x[0], x[1], x[2]) + self.rotation(x) * (p - self.centre)
    }
}

/// Toe and camber of a wheel on side `s` (+1 left) whose outward spin axis is `a`, from their definitions.
fn toe_camber(a: V, s: f64) -> (f64, f64) {
    (a.x.atan2(s * a.y), (-a.z).atan2(a.x.hypot(a.y)))
}

/// What the rig drives with `t`.
#[derive(Clone, Copy)]
enum Travel {
    /// Both wheel-centre heights by `t`.
    Parallel,
    /// The left wheel-centre height by `t`, the right by `−t`.
    Opposite,
    /// The steering box's end of the drag link by `t` along the drag link, both heights held.
    Steering,
}

impl Travel {
    /// Left and right wheel-centre travel, and steering-box travel, at `t`.
    fn at(self, t: f64) -> (f64, f64, f64) {
        match self {
            Travel::Parallel => (t, t, 0.0),
            Travel::Opposite => (t, -t, 0.0),
            Travel::Steering => (0.0, 0.0, t),
        }
    }
}

/// The push pipe's ball joint (`Axle Tube / Location Connector Chassis`) holds its point on the tube; the
/// Panhard rod (its two points as given) keeps its length. Returns those residuals for the tube moved by `x`.
fn push_pipe_and_panhard_rod(chrono: &Value, tube: Tube) -> impl Fn(&[f64]) -> Vec<f64> {
    let ball = point(chrono, "Axle Tube/Location Connector Chassis");
    let (on_axle, on_chassis) =
        (point(chrono, "Panhard Rod/Location Connector Axle"), point(chrono, "Panhard Rod/Location Connector Chassis"));
    move |x| {
        let mut f: Vec<f64> = (tube.moved(x, ball) - ball).iter().copied().collect();
        f.push((tube.moved(x, on_axle) - on_chassis).norm() - (on_axle - on_chassis).norm());
        f
    }
}

/// `ChPushPipeAxle`: the tube on its ball joint and Panhard rod; the wheels turn with the tube. Unknowns:
/// the tube's six.
fn push_pipe_closure(chrono: &Value, travel: Travel) -> impl Fn(f64, &mut [f64; 6]) -> [(f64, f64); 2] {
    let tube = Tube { centre: point(chrono, "Axle Tube/COM") };
    let held = push_pipe_and_panhard_rod(chrono, tube);
    let wc = point(chrono, "Spindle/COM");
    assert_eq!((chrono["Camber Angle (deg)"].as_f64(), chrono["Toe Angle (deg)"].as_f64()), (Some(0.0), Some(0.0)));
    move |t, x| {
        let residual = |x: &[f64; 6]| {
            let mut f = held(x);
            let (left, right, _) = travel.at(t);
            f.push(tube.moved(x, wc).z - wc.z - left);
            f.push(tube.moved(x, mirror(wc)).z - wc.z - right);
            DVector::from_vec(f)
        };
        newton_fd(residual, x);
        let r = tube.rotation(x);
        [toe_camber(r * V::y(), 1.0), toe_camber(r * -V::y(), -1.0)]
    }
}

/// `ChToeBarPushPipeAxle`: the tube on its ball joint and Panhard rod; each knuckle turns by ψ about its
/// kingpin (lower to upper point) on the tube; the toe bar from knuckle to knuckle and the drag link from the
/// steering box (held, or moved along the drag link when steering) to the left knuckle's arm keep their
/// lengths. Unknowns: the tube's six, ψ left, ψ right.
fn toe_bar_closure(chrono: &Value, travel: Travel) -> impl Fn(f64, &mut [f64; 8]) -> [(f64, f64); 2] {
    let tube = Tube { centre: point(chrono, "Axle Tube/COM") };
    let held = push_pipe_and_panhard_rod(chrono, tube);
    let wc = point(chrono, "Spindle/COM");
    assert_eq!((chrono["Camber Angle (deg)"].as_f64(), chrono["Toe Angle (deg)"].as_f64()), (Some(0.0), Some(0.0)));
    let (kl, ku) = (point(chrono, "Knuckle/Location Lower"), point(chrono, "Knuckle/Location Upper"));
    let bar = point(chrono, "Tierod/Location Knuckle");
    let (box_end, arm) = (point(chrono, "Draglink/Location Chassis"), point(chrono, "Knuckle/Location Draglink"));
    // Chrono joins the drag link to the left knuckle when this point's y is positive.
    assert!(arm.y > 0.0);
    // A knuckle point (left, or mirrored for the right) turned by ψ about its kingpin, on the tube.
    let knuckle = move |x: &[f64], side: f64, psi: f64, p: V| {
        let m = |q: V| if side > 0.0 { q } else { mirror(q) };
        let (lower, upper) = (m(kl), m(ku));
        let turned = lower + Rotation3::from_axis_angle(&Unit::new_normalize(upper - lower), psi) * (m(p) - lower);
        tube.moved(x, turned)
    };
    move |t, x| {
        let residual = |x: &[f64; 8]| {
            let mut f = held(x);
            let (left, right, rack) = travel.at(t);
            f.push(knuckle(x, 1.0, x[6], wc).z - wc.z - left);
            f.push(knuckle(x, -1.0, x[7], wc).z - wc.z - right);
            f.push((knuckle(x, 1.0, x[6], bar) - knuckle(x, -1.0, x[7], bar)).norm() - 2.0 * bar.y);
            let box_now = box_end + (arm - box_end).normalize() * rack;
            f.push((knuckle(x, 1.0, x[6], arm) - box_now).norm() - (arm - box_end).norm());
            DVector::from_vec(f)
        };
        newton_fd(residual, x);
        // Each wheel's outward spin axis (the left's design axis, or its mirror image) turned with its knuckle.
        let spin = |side: f64, psi: f64| knuckle(x, side, psi, wc + V::y()) - knuckle(x, side, psi, wc);
        [toe_camber(spin(1.0, x[6]), 1.0), toe_camber(spin(-1.0, x[7]), -1.0)]
    }
}

/// Largest toe or camber difference (rad) of both wheels between `rows` (travel, left, right attitudes)
/// and `closure`, walked outwards from the design row (index `design`) in both directions, each closure
/// starting from its neighbour's solution; and the largest range of the four angles over the rows.
fn against<const N: usize>(
    rows: &[(f64, [(f64, f64); 2])],
    design: usize,
    closure: impl Fn(f64, &mut [f64; N]) -> [(f64, f64); 2],
) -> (f64, f64) {
    let mut worst: f64 = 0.0;
    for half in [rows[design..].iter().collect::<Vec<_>>(), rows[..=design].iter().rev().collect()] {
        let mut guess = [0.0; N];
        for (t, engine) in half {
            let reference = closure(*t, &mut guess);
            for (e, r) in engine.iter().zip(reference) {
                worst = worst.max((e.0 - r.0).abs()).max((e.1 - r.1).abs());
            }
        }
    }
    let mut range: f64 = 0.0;
    for k in 0..4 {
        let angle = |r: &(f64, [(f64, f64); 2])| if k % 2 == 0 { r.1[k / 2].0 } else { r.1[k / 2].1 };
        let (lo, hi) = rows.iter().map(angle).fold((f64::MAX, f64::MIN), |(lo, hi), a| (lo.min(a), hi.max(a)));
        range = range.max(hi - lo);
    }
    (worst, range)
}

/// Both wheels of the axle over `rig`'s sweep of ±`reach`, in 12 steps (design at row 6).
fn axle_rows(file: &SuspensionFile, rig: AxleRig, reach: f64) -> Vec<(f64, [(f64, f64); 2])> {
    let axle = Axle::build(&file.suspension, rig).unwrap();
    let rows = axle_sweep(&axle, -reach, reach, 12, Mode::Corrected).unwrap();
    rows.iter().map(|r| (r.travel, [(r.left.toe, r.left.camber), (r.right.toe, r.right.camber)])).collect()
}

/// The corner's parallel travel of ±80 mm in 16 steps (design at row 8): the axle built whole, both wheels
/// (the partner's read from the same poses).
fn corner_rows(file: &SuspensionFile) -> Vec<(f64, [(f64, f64); 2])> {
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let partner = corner.partner.expect("an axle builds whole");
    // Both heights driven: the tube's ball joint and Panhard rod leave it travel and roll.
    assert!(corner.model.joint_id("right wheel travel").is_some());
    let solver_rows = parallel_wheel_travel(&corner, -0.08, 0.08, 16, Mode::Corrected).unwrap();
    // The partner's attitude needs the poses: walk the same path again with the poses kept.
    let mut solver = elastokin_solver::StaticSolver::new(&corner.model, Default::default()).unwrap();
    let mut state = solver.design_state(-0.08);
    let sweep =
        solver.sweep_from(&mut state, elastokin_solver::LoadPath::new(-0.08, 0.08, 16), Mode::Corrected).unwrap();
    solver_rows
        .iter()
        .zip(&sweep.steps)
        .map(|(r, s)| {
            let p = partner.attitude(&s.poses);
            (r.travel, [(r.attitude.toe, r.attitude.camber), (p.toe, p.camber)])
        })
        .collect()
}

/// The push-pipe axle (the UAZ bus's rear): its wheels in parallel travel (toe from the Panhard rod's arc)
/// and in roll against the loop closure.
#[test]
fn the_push_pipe_axle_travels_as_its_loop_closure() {
    let (chrono, file) = read_swapped(REAR);
    let (worst, range) = against(&corner_rows(&file), 8, push_pipe_closure(&chrono, Travel::Parallel));
    // The Panhard rod's arc yaws the tube as it pitches about the ball joint.
    assert!(range > 1e-3, "push-pipe axle travel: the wheels toe {range} rad");
    // Measured: 5.4e-13 rad, of a toe range of 3.5e-3 rad.
    assert!(worst < 5e-11, "push-pipe axle travel: {worst:e} rad");
    let (worst, range) =
        against(&axle_rows(&file, AxleRig::OppositeTravel, 0.05), 6, push_pipe_closure(&chrono, Travel::Opposite));
    assert!(range > 1e-2, "push-pipe axle roll: the wheels camber {range} rad");
    // Measured: 1.2e-11 rad, of a camber range of 0.14 rad.
    assert!(worst < 1e-9, "push-pipe axle roll: {worst:e} rad");
}

/// The toe-bar push-pipe axle (the UAZ bus's front): its wheels in parallel travel, in roll and in steering
/// against the loop closure.
#[test]
fn the_toe_bar_push_pipe_axle_travels_and_steers_as_its_loop_closure() {
    let (chrono, file) = read_swapped(FRONT);
    let (worst, range) = against(&corner_rows(&file), 8, toe_bar_closure(&chrono, Travel::Parallel));
    assert!(range > 1e-2, "toe-bar axle travel: the wheels toe {range} rad");
    // Measured: 2.6e-12 rad, of a toe range of 0.30 rad (the drag link, 0.2 m above the ball joint's
    // height, pulls the knuckle's arm as the tube pitches).
    assert!(worst < 2e-10, "toe-bar axle travel: {worst:e} rad");
    let (worst, range) =
        against(&axle_rows(&file, AxleRig::OppositeTravel, 0.05), 6, toe_bar_closure(&chrono, Travel::Opposite));
    assert!(range > 1e-2, "toe-bar axle roll: {range} rad");
    // Measured: 4.9e-15 rad, of a range of 0.14 rad.
    assert!(worst < 4e-13, "toe-bar axle roll: {worst:e} rad");
    let (worst, range) =
        against(&axle_rows(&file, AxleRig::Steering, 0.04), 6, toe_bar_closure(&chrono, Travel::Steering));
    assert!(range > 1e-1, "toe-bar axle steering: {range} rad");
    // Measured: 2.3e-11 rad, of a toe range of 0.75 rad.
    assert!(worst < 2e-9, "toe-bar axle steering: {worst:e} rad");
}

/// The UAZ files' spring has `Minimum Length` 0.28 m above `Maximum Length` 0.12 m: refused, naming both
/// keys, with the lengths swapped as the fix; swapped, they are stops 80 mm either side of the 0.2 m spring
/// and each file runs through every analysis (the rear's steering skipped: nothing steers it).
#[test]
fn crossed_stops_are_refused_by_name_and_the_files_run_with_them_swapped() {
    for path in [REAR, FRONT] {
        let e = import(&fixture(path), path, None).unwrap_err().to_string();
        assert!(
            e.contains("\"Spring\" / \"Minimum Length\" 0.28 m is not below \"Maximum Length\" 0.12 m")
                && e.contains("(0.12 and 0.28, swapped)"),
            "{path}: {e}"
        );
        let (chrono, file) = read_swapped(path);
        let design = (point(&chrono, "Spring/Location Axle") - point(&chrono, "Spring/Location Chassis")).norm();
        let Template::General(g) = &file.suspension else { panic!("general form") };
        let clearances: Vec<f64> = g.stops.iter().map(|s| s.clearance).collect();
        assert_eq!(clearances.len(), 2);
        // Measured: 4.2e-17 m (0.28 − 0.2 and 0.2 − 0.12 in floating point) and 2.8e-17 m (the design length).
        assert!(clearances.iter().all(|c| (c - 0.08).abs() < 1e-15) && (design - 0.2).abs() < 1e-15, "{clearances:?}");
        let report = kc::run_suite(&file, &[], &Settings { steps: 4, ..Default::default() }, |_| {})
            .unwrap_or_else(|e| panic!("{path}: {e}"));
        assert_eq!(report.analyses.len() + report.skipped.len(), kc::ALL.len(), "{path}");
        let ran = |a: Analysis| report.analyses.iter().any(|r| r.analysis == a);
        assert!(ran(Analysis::ParallelTravel) && ran(Analysis::Roll) && ran(Analysis::VerticalForce), "{path}");
        assert_eq!(ran(Analysis::Steering), path == FRONT, "{path}");
    }
}

/// Chrono's `RigidPinnedAxle` has no spring (its file, and its template, give a tube on a pin and the
/// spindles only): refused by name, at the pin.
#[test]
fn a_rigid_pinned_axle_is_refused_by_name() {
    let v = chrono("RigidPinnedAxle.json");
    let mut keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    keys.sort_unstable();
    assert_eq!(keys, ["Axle", "Name", "Spindle", "Template", "Tube", "Type"]);
    let e = import(&fixture("RigidPinnedAxle.json"), "RigidPinnedAxle.json", None).unwrap_err().to_string();
    assert!(e.contains("\"Tube\" / \"Pin Location\"") && e.contains("turns freely about this pin"), "{e}");
    // A malformed point is reported by its key first.
    let mut bad = v.clone();
    bad["Tube"]["Pin Location"] = serde_json::json!([0.0, 0.15]);
    let e = import(&bad.to_string(), "RigidPinnedAxle.json", None).unwrap_err().to_string();
    assert!(e.contains("must be a point [x, y, z]"), "{e}");
}
