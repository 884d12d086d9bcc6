//! A driven corner's half-shaft (`vehicle.half_shaft`): its plunge and its joints' angles over parallel
//! travel and steer equal a second reading written here — the outer joint carried rigidly by the
//! upright's pose at each row of the analysis's motion, not through the wheel's toe and camber — with a
//! guard that the shaft really moves; the right wheel's mirrors the left's; an outer joint off the spin
//! axis is named and its columns left out.

use elastokin_core::{Pose, Vec3};
use elastokin_suspensions::assembly::{AxleRig, Rig};
use elastokin_suspensions::kc::{self, Analysis, AnalysisReport, Models, Settings};
use elastokin_suspensions::wheel::Wheel;
use elastokin_suspensions::SuspensionFile;
use serde_json::{json, Value};

fn document() -> Value {
    let path = format!("{}/../../examples/macpherson.json", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn run(doc: &Value, analysis: Analysis) -> AnalysisReport {
    let file = SuspensionFile::from_json(&doc.to_string(), "m.json").unwrap();
    kc::run(analysis, &file, &Settings { motion: true, steps: 16, ..Settings::default() }).unwrap()
}

fn column(a: &AnalysisReport, name: &str) -> Vec<f64> {
    let cells = a.table.column(name).unwrap_or_else(|| panic!("no column {name} in {:?}", a.table.columns));
    cells.into_iter().map(Option::unwrap).collect()
}

/// The inner joint at the differential's output, and the outer on the left wheel's spin axis 90 mm inboard
/// of its centre at design.
fn with_shaft(doc: &Value) -> (Value, Vec3, Vec3) {
    let file = SuspensionFile::from_json(&doc.to_string(), "m.json").unwrap();
    let models = Models::new(&file);
    let corner = models.corner_ref(Rig::WheelTravel).unwrap();
    let pose = corner.model.design_poses()[corner.wheel.upright.0];
    let outer = pose.point(&corner.wheel.wheel_centre_local) - pose.direction(&corner.wheel.spin_axis_local) * 0.090;
    let inner = Vec3::new(0.010, 0.250, -0.020);
    let mut doc = doc.clone();
    doc["vehicle"]["half_shaft"] =
        json!({ "inner": [inner.x, inner.y, inner.z], "outer": [outer.x, outer.y, outer.z] });
    (doc, inner, outer)
}

/// The shaft read a second way at a row's `frame`: the outer joint carried rigidly by `wheel`'s upright from
/// its place at `design`; its plunge from `inner` and `length`, and its direction (unit) and the spin axis.
fn carried(wheel: &Wheel, design: &[Pose], frame: &[Pose], inner: Vec3, outer: Vec3) -> (f64, Vec3, Vec3) {
    let local = design[wheel.upright.0].to_local_point(&outer);
    let pose = frame[wheel.upright.0];
    let shaft = pose.point(&local) - inner;
    (shaft.norm() - (outer - inner).norm(), shaft / shaft.norm(), pose.direction(&wheel.spin_axis_local))
}

#[test]
fn the_shafts_plunge_and_joint_angles_follow_the_upright_over_travel() {
    let (doc, inner, outer) = with_shaft(&document());
    let a = run(&doc, Analysis::ParallelTravel);
    let file = SuspensionFile::from_json(&doc.to_string(), "m.json").unwrap();
    let models = Models::new(&file);
    let corner = models.corner_ref(Rig::WheelTravel).unwrap();
    let design = corner.model.design_poses();
    let motion = a.motion.as_ref().unwrap();
    let (plunge, inner_angle, outer_angle) = (
        column(&a, "half_shaft_plunge_m"),
        column(&a, "half_shaft_inner_angle_deg"),
        column(&a, "half_shaft_outer_angle_deg"),
    );
    let mut worst: f64 = 0.0;
    for (r, frame) in motion.frames.iter().enumerate() {
        let (p, u, spin) = carried(&corner.wheel, &design, frame, inner, outer);
        worst = worst
            .max((plunge[r] - p).abs())
            .max((inner_angle[r] - u.y.abs().acos().to_degrees()).abs() * 1e-3)
            .max((outer_angle[r] - u.dot(&spin).acos().to_degrees()).abs() * 1e-3);
    }
    // Measured 1.9e-16 (m, and 1e-3 × deg).
    assert!(worst < 1e-14, "{worst}");
    // The motion is real: over ±80 mm the shaft plunges millimetres and its joints turn degrees.
    let span = |v: &[f64]| {
        v.iter().cloned().fold(f64::NEG_INFINITY, f64::max) - v.iter().cloned().fold(f64::INFINITY, f64::min)
    };
    assert!(
        span(&plunge) > 0.002 && span(&inner_angle) > 5.0 && span(&outer_angle) > 2.0,
        "{plunge:?} {inner_angle:?}"
    );
    // The chart draws the table's columns.
    let chart = a.charts.iter().find(|c| c.name == "parallel_travel_half_shaft").unwrap();
    let drawn = |s: &elastokin_suspensions::kc::Series| s.points.iter().map(|p| p.1).collect::<Vec<f64>>();
    assert_eq!(drawn(&chart.left.series[0]), inner_angle);
    assert_eq!(drawn(&chart.left.series[1]), outer_angle);
    let plunge_mm: Vec<f64> = plunge.iter().map(|p| p * 1e3).collect();
    assert_eq!(drawn(&chart.right.as_ref().unwrap().series[0]), plunge_mm);
    // At travel 0 the wheel sits where its bushings let it under the spring, not at the design poses: the
    // shaft has plunged a little.
    assert!(plunge[a.design_row()].abs() < 5e-4, "{}", plunge[a.design_row()]);
}

#[test]
fn both_shafts_follow_the_wheels_in_steer_the_right_mirroring_the_left() {
    let (doc, inner, outer) = with_shaft(&document());
    let a = run(&doc, Analysis::Steering);
    let file = SuspensionFile::from_json(&doc.to_string(), "m.json").unwrap();
    let models = Models::new(&file);
    let axle = models.axle_ref(AxleRig::Steering).unwrap();
    let design = axle.model.design_poses();
    let motion = a.motion.as_ref().unwrap();
    let rows = a.table.rows.len();
    for (side, wheel, s) in [("left", &axle.left, 1.0), ("right", &axle.right, -1.0)] {
        let (inner, outer) = (Vec3::new(inner.x, s * inner.y, inner.z), Vec3::new(outer.x, s * outer.y, outer.z));
        let plunge = column(&a, &format!("{side}_half_shaft_plunge_m"));
        let outer_angle = column(&a, &format!("{side}_half_shaft_outer_angle_deg"));
        for (r, frame) in motion.frames.iter().enumerate() {
            let (p, u, spin) = carried(wheel, &design, frame, inner, outer);
            // Measured 1.1e-16 m and 1.0e-13 deg.
            assert!((plunge[r] - p).abs() < 1e-14, "{side} row {r}: {} against {p}", plunge[r]);
            assert!((outer_angle[r] - u.dot(&spin).acos().to_degrees()).abs() < 1e-11, "{side} row {r}");
        }
        // Steered, the outer joint turns by degrees.
        assert!(outer_angle.iter().cloned().fold(0.0, f64::max) > 5.0, "{side}: {outer_angle:?}");
    }
    // The axle is symmetric: the right wheel at a rack travel is the left at the opposite one.
    let (left, right) = (column(&a, "left_half_shaft_plunge_m"), column(&a, "right_half_shaft_plunge_m"));
    for r in 0..rows {
        // Measured 2.2e-16 m.
        assert!((left[r] - right[rows - 1 - r]).abs() < 1e-14, "row {r}: {} against {}", left[r], right[rows - 1 - r]);
    }
}

#[test]
fn an_outer_joint_off_the_spin_axis_is_named_and_its_columns_left_out() {
    let (mut doc, _, outer) = with_shaft(&document());
    doc["vehicle"]["half_shaft"]["outer"] = json!([outer.x, outer.y, outer.z + 0.005]);
    let a = run(&doc, Analysis::ParallelTravel);
    let w = a.warnings.iter().find(|w| w.code == "half-shaft-off-axis").expect("a warning");
    assert!(w.message.contains("5.0 mm off the wheel's spin axis"), "{}", w.message);
    assert!(!a.table.columns.iter().any(|c| c.starts_with("half_shaft")));
    // A shaft whose joints coincide is refused with the file.
    let mut same = document();
    same["vehicle"]["half_shaft"] = json!({ "inner": [0.0, 0.5, 0.0], "outer": [0.0, 0.5, 0.0] });
    let e = SuspensionFile::from_json(&same.to_string(), "m.json").unwrap_err().to_string();
    assert!(e.contains("half_shaft"), "{e}");
}
