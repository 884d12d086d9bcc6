//! The drawing of a model and the poses of every row (`Settings::motion`): what the report's views show
//! is the configuration the analysis solved. At every row of every analysis of every shipped example and
//! of two Chrono files, the joints drawn hold as joints hold (a ball joint's two ends together, a link at
//! its length, a slider's end on its axis), the wheel drawn is the wheel of the table's row, and the
//! drawing has a part per body and a point per place a joint or an element uses.

mod common;

use common::chrono;
use elastokin_core::{JointKind, Pose, SketchKind};
use elastokin_suspensions::drawing::{Drawing, Motion};
use elastokin_suspensions::kc::{self, AnalysisReport, Settings};
use elastokin_suspensions::SuspensionFile;
use std::path::Path;

fn example(name: &str) -> SuspensionFile {
    SuspensionFile::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(name)).unwrap()
}

fn models() -> Vec<(String, SuspensionFile)> {
    let mut out: Vec<(String, SuspensionFile)> = [
        "macpherson.json",
        "double_wishbone.json",
        "five_link.json",
        "double_wishbone_axle.json",
        "four_link_axle.json",
        "twist_beam.json",
        "pushrod_rocker.json",
    ]
    .iter()
    .map(|n| (n.to_string(), example(n)))
    .collect();
    for name in ["DoubleWishbone.json", "MultiLink.json"] {
        out.push((name.to_string(), chrono::read(name).1));
    }
    out
}

/// The largest violation, over the frames, of what each drawn joint holds (m).
fn joint_violation(drawing: &Drawing, frames: &[Vec<Pose>]) -> f64 {
    let mut worst = 0.0f64;
    for poses in frames {
        for j in &drawing.joints {
            let [a, b] = j.ends.map(|e| e.placed(poses));
            let miss = match j.kind {
                JointKind::Spherical | JointKind::Revolute | JointKind::Universal | JointKind::Fixed => (a - b).norm(),
                JointKind::Translational | JointKind::Cylindrical => {
                    let axis = j.axis.expect("a slider has an axis").map(|e| e.placed(poses));
                    let along = (axis[1] - axis[0]).normalize();
                    let off = b - a;
                    (off - along * off.dot(&along)).norm()
                }
                _ => 0.0,
            };
            worst = worst.max(miss);
        }
    }
    worst
}

#[test]
fn every_rows_drawing_holds_its_joints_and_carries_the_rows_wheel() {
    let settings = Settings { motion: true, ..Settings::default() };
    let mut analyses = 0;
    let mut beam_strain = 0.0f64;
    for (name, file) in models() {
        let report = kc::run_suite(&file, &[], &settings, |_| {});
        assert!(report.failed.is_empty(), "{name}: {:?}", report.failed);
        for a in &report.analyses {
            let Some(Motion { drawing, frames }) = &a.motion else {
                assert_eq!(a.analysis, kc::Analysis::StaticLoad, "{name}: {} has no motion", a.analysis.name());
                continue;
            };
            analyses += 1;
            let what = format!("{name} {}", a.analysis.name());
            assert_eq!(frames.len(), a.table.rows.len(), "{what}: a frame per row");
            assert!(frames.iter().all(|f| f.len() == drawing.parts.len()), "{what}: a pose per part");
            assert!(drawing.parts.iter().all(|p| !p.points.is_empty()), "{what}: every part has a point");
            // The twist beam has no joint: bushings and beams hold it.
            assert!(!(drawing.joints.is_empty() && drawing.elements.is_empty()), "{what}");
            assert!(!drawing.wheels.is_empty(), "{what}");
            // The solver leaves joints apart by at most its constraint tolerance; measured up to 5e-11 m
            // (Chrono's MultiLink under vertical force), under 1e-12 m on the templates.
            let miss = joint_violation(drawing, frames);
            assert!(miss < 1e-9, "{what}: a drawn joint apart by {miss:e} m");
            // A link keeps its length.
            for j in drawing.joints.iter().filter(|j| j.kind == JointKind::Distance) {
                let length = |poses: &[Pose]| (j.ends[0].placed(poses) - j.ends[1].placed(poses)).norm();
                let design = length(&frames[0]);
                for poses in frames {
                    assert!((length(poses) - design).abs() < 1e-10, "{what}: link {} stretched", j.name);
                }
            }
            // A beam drawn from its start to its end keeps its length but for its strain: steel's stays
            // under 1e-4 (measured 2.7e-5 on the twist beam).
            for e in drawing.elements.iter().filter(|e| e.kind == SketchKind::Beam) {
                let length = |poses: &[Pose]| (e.ends[0].placed(poses) - e.ends[1].placed(poses)).norm();
                let design = length(&frames[0]);
                let strain = frames.iter().map(|p| (length(p) / design - 1.0).abs()).fold(0.0, f64::max);
                beam_strain = beam_strain.max(strain);
                assert!(design > 0.01 && strain < 1e-4, "{what}: beam {} drawn {design} m, strain {strain:e}", e.name);
            }
            wheel_is_the_rows(a, drawing, frames, &what);
        }
    }
    println!("largest drawn strain of a beam: {beam_strain:e}");
    assert!(beam_strain > 0.0, "a beam drawn");
    // Every analysis but the static load case (and the twist beam's steering), on nine models: 70.
    assert!(analyses >= 70, "{analyses} analyses drawn");
}

/// The first wheel drawn, placed by each row's poses, is where the table says its centre is.
fn wheel_is_the_rows(a: &AnalysisReport, drawing: &Drawing, frames: &[Vec<Pose>], what: &str) {
    let columns = ["wheel_centre_x_m", "wheel_centre_y_m", "wheel_centre_z_m"];
    let Some(c) = columns.map(|c| a.table.columns.iter().position(|x| x == c)).into_iter().collect::<Option<Vec<_>>>()
    else {
        return;
    };
    let wheel = &drawing.wheels[0];
    for (row, poses) in a.table.rows.iter().zip(frames) {
        let centre = wheel.upright.pose(poses).point(&wheel.centre);
        for k in 0..3 {
            let table = row[c[k]].number().unwrap();
            assert!((centre[k] - table).abs() < 1e-12, "{what}: wheel centre {k} drawn {} against {table}", centre[k]);
        }
    }
}

#[test]
fn the_drawing_has_every_bushing_and_spring_and_a_part_per_body() {
    let file = example("macpherson.json");
    let settings = Settings { motion: true, ..Settings::default() };
    let report = kc::run(kc::Analysis::ParallelTravel, &file, &settings).unwrap();
    let drawing = &report.motion.as_ref().unwrap().drawing;
    let names = |kind: SketchKind| -> Vec<&str> {
        drawing.elements.iter().filter(|e| e.kind == kind).map(|e| e.name.as_str()).collect()
    };
    assert_eq!(names(SketchKind::Bushing), ["lower arm front bushing", "lower arm rear bushing", "top mount"]);
    assert_eq!(names(SketchKind::Spring), ["spring"]);
    let parts: Vec<&str> = drawing.parts.iter().map(|p| p.name.as_str()).collect();
    for part in ["upright", "strut rod", "lower arm"] {
        assert!(parts.contains(&part), "{parts:?}");
    }
    // The lower arm: its two bushings and its ball joint.
    let arm = drawing.parts.iter().find(|p| p.name == "lower arm").unwrap();
    assert_eq!(arm.points.len(), 3);
    // Asked for nothing, a report carries no motion.
    let plain = kc::run(kc::Analysis::ParallelTravel, &file, &Settings::default()).unwrap();
    assert!(plain.motion.is_none());
}
