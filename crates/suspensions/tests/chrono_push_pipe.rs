//! Project Chrono's push-pipe axles (`PushPipeAxle`, `ToeBarPushPipeAxle`: the UAZ bus's rear and front,
//! files copied unchanged into `tests/data/chrono/uaz/`, BSD-3-Clause) read into the general model with an
//! `axle`: each wheel follows, in parallel and opposite travel and in steering, the closure equations of
//! Chrono's own linkage written out here from the Chrono file (not from the import). The UAZ files' crossed
//! stops are refused by name, and with the two lengths swapped the files run through every analysis; the
//! generic `RigidPinnedAxle`, which no spring holds, is refused by name.

mod common;

use common::chrono::{
    against, axle_rows, chrono_json, corner_rows, fixture, mirror, point, read_edited, toe_camber, uncross_stops,
    wheels_on_tube, Angles, Travel, Tube, V,
};
use common::newton_fd;
use elastokin_suspensions::document::import_chrono;
use elastokin_suspensions::kc::{self, Analysis, Settings};
use elastokin_suspensions::{AxleRig, Rig, Side, SuspensionFile, Template};
use nalgebra::{DVector, Rotation3, Unit};
use serde_json::Value;

const REAR: &str = "uaz/UAZBUS_RearPushPipeAxle.json";
const FRONT: &str = "uaz/UAZBUS_FrontPushPipeAxle.json";

/// The Chrono file as JSON with its spring's `Minimum Length` and `Maximum Length` swapped (the file's are
/// crossed, and refused), and the model imported from it.
fn read_swapped(path: &str) -> (Value, SuspensionFile) {
    read_edited(path, |v| assert!(uncross_stops(&mut v["Spring"]), "{path}: the stops are not crossed"))
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
    wheels_on_tube(tube, wc, travel, held)
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

/// The corner's parallel travel (see [`common::chrono::corner_rows`]), both heights driven: the tube's ball
/// joint and Panhard rod leave it travel and roll.
fn corner_rows_both_driven(file: &SuspensionFile) -> Vec<Angles> {
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    assert!(corner.model.joint_id("right wheel travel").is_some());
    corner_rows(file)
}

/// The push-pipe axle (the UAZ bus's rear): its wheels in parallel travel (toe from the Panhard rod's arc)
/// and in roll against the loop closure.
#[test]
fn the_push_pipe_axle_travels_as_its_loop_closure() {
    let (chrono, file) = read_swapped(REAR);
    let (worst, range) = against(&corner_rows_both_driven(&file), 8, push_pipe_closure(&chrono, Travel::Parallel));
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
    let (worst, range) = against(&corner_rows_both_driven(&file), 8, toe_bar_closure(&chrono, Travel::Parallel));
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
        let e = import_chrono(&fixture(path), path, None).unwrap_err().to_string();
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
            .complete()
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
    let v = chrono_json("RigidPinnedAxle.json");
    let mut keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    keys.sort_unstable();
    assert_eq!(keys, ["Axle", "Name", "Spindle", "Template", "Tube", "Type"]);
    let e = import_chrono(&fixture("RigidPinnedAxle.json"), "RigidPinnedAxle.json", None).unwrap_err().to_string();
    assert!(e.contains("\"Tube\" / \"Pin Location\"") && e.contains("turns freely about this pin"), "{e}");
    // A malformed point is reported by its key first.
    let mut bad = v.clone();
    bad["Tube"]["Pin Location"] = serde_json::json!([0.0, 0.15]);
    let e = import_chrono(&bad.to_string(), "RigidPinnedAxle.json", None).unwrap_err().to_string();
    assert!(e.contains("must be a point [x, y, z]"), "{e}");
}
