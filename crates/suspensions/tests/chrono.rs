//! Project Chrono's suspension files: every shipped one runs or is refused with its reason; the double
//! wishbone and MacPherson readings against the loop closures; each convention on a hand-checked case.

use elastokin_core::Vec3;
use elastokin_solver::Mode;
use elastokin_suspensions::analysis::parallel_wheel_travel;
use elastokin_suspensions::chrono::{import, Imported};
use elastokin_suspensions::kc::{self, Settings};
use elastokin_suspensions::{DoubleWishboneHardpoints, MacPhersonHardpoints, Rig, Side};
use serde_json::Value;
use std::path::{Path, PathBuf};

mod common;

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/chrono")
}

fn text(name: &str) -> String {
    std::fs::read_to_string(data().join(name)).unwrap()
}

fn read(name: &str) -> Imported {
    import(&text(name), name, None).unwrap()
}

/// A point of the Chrono file, read here from its JSON.
fn point(v: &Value, object: &str, key: &str) -> Vec3 {
    let p = &v[object][key];
    Vec3::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap(), p[2].as_f64().unwrap())
}

/// Every shipped file: read and run through every analysis that applies, or refused with the reason the
/// table in `tests/data/chrono/README.md` gives for it.
#[test]
fn every_shipped_chrono_file_runs_or_is_refused_as_the_readme_says() {
    let readme = text("README.md");
    let mut files: Vec<String> = Vec::new();
    for dir in [data(), data().join("hmmwv")] {
        for e in std::fs::read_dir(&dir).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "json") {
                files.push(p.strip_prefix(data()).unwrap().to_string_lossy().into_owned());
            }
        }
    }
    files.sort();
    assert!(files.len() >= 15, "{files:?}");
    let (mut ran, mut refused) = (0, 0);
    for name in &files {
        let row = readme
            .lines()
            .find(|l| l.starts_with(&format!("| `{name}`")))
            .unwrap_or_else(|| panic!("{name} not in the README"));
        match import(&text(name), name, None) {
            Ok(imported) => {
                assert!(row.ends_with("| yes |"), "{name} reads, but the README says: {row}");
                let settings = Settings { steps: 4, ..Settings::default() };
                let report =
                    kc::run_suite(&imported.file, &[], &settings, |_| {}).unwrap_or_else(|e| panic!("{name}: {e}"));
                assert!(report.analyses.len() >= 8, "{name}: {} analyses", report.analyses.len());
                ran += 1;
            }
            Err(e) => {
                let e = e.to_string();
                let reason = row
                    .split("refused: ")
                    .nth(1)
                    .unwrap_or_else(|| panic!("{name} is refused ({e}) but the README says {row}"));
                let reason = reason.trim_end_matches(" |");
                assert!(
                    e.contains("Project Chrono template") && (e.contains(reason) || reason == "not read yet"),
                    "{name}: {e}"
                );
                refused += 1;
            }
        }
    }
    assert!(ran >= 6 && refused >= 6, "{ran} read, {refused} refused");
}

/// Chrono's generic double wishbone, read, against the double wishbone's loop closure on the file's own
/// points.
#[test]
fn the_double_wishbone_reading_matches_the_loop_closure() {
    for name in ["DoubleWishbone.json", "hmmwv/HMMWV_DoubleWishboneFront.json"] {
        let v: Value = serde_json::from_str(&text(name)).unwrap();
        let h = DoubleWishboneHardpoints {
            wheel_centre: point(&v, "Spindle", "COM"),
            upper_ball_joint: point(&v, "Upper Control Arm", "Location Upright"),
            upper_arm_front: point(&v, "Upper Control Arm", "Location Chassis Front"),
            upper_arm_rear: point(&v, "Upper Control Arm", "Location Chassis Back"),
            lower_ball_joint: point(&v, "Lower Control Arm", "Location Upright"),
            lower_arm_front: point(&v, "Lower Control Arm", "Location Chassis Front"),
            lower_arm_rear: point(&v, "Lower Control Arm", "Location Chassis Back"),
            tie_rod_inner: point(&v, "Tierod", "Location Chassis"),
            tie_rod_outer: point(&v, "Tierod", "Location Upright"),
            spring_chassis: point(&v, "Spring", "Location Chassis"),
            spring_arm: point(&v, "Spring", "Location Arm"),
        };
        let corner = read(name).file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
        let rows = parallel_wheel_travel(&corner, -0.08, 0.08, 16, Mode::Corrected).unwrap();
        let mut worst: f64 = 0.0;
        for half in [rows[8..].iter().collect::<Vec<_>>(), rows[..=8].iter().rev().collect()] {
            let mut guess = [0.0; 3];
            for row in half {
                let (toe, camber) = common::double_wishbone_closure(&h, row.travel, &mut guess);
                worst = worst.max((row.attitude.toe - toe).abs()).max((row.attitude.camber - camber).abs());
            }
        }
        // Measured: 1.7e-14 rad (generic), 1.6e-11 rad (HMMWV).
        assert!(worst < 1e-9, "{name}: {worst:e}");
    }
}

/// Chrono's MacPherson strut — a cylindrical joint on a strut held by a universal joint, so the upright
/// steers about the strut — has the kinematics of the strut line through the top mount: the MacPherson
/// loop closure on the file's points.
#[test]
fn the_macpherson_reading_matches_the_loop_closure() {
    let v: Value = serde_json::from_str(&text("MacPhersonStrut.json")).unwrap();
    let h = MacPhersonHardpoints {
        wheel_centre: point(&v, "Spindle", "COM"),
        lower_ball_joint: point(&v, "Control Arm", "Location Upright"),
        lower_arm_front: point(&v, "Control Arm", "Location Chassis Front"),
        lower_arm_rear: point(&v, "Control Arm", "Location Chassis Back"),
        tie_rod_outer: point(&v, "Tierod", "Location Upright"),
        tie_rod_inner: point(&v, "Tierod", "Location Chassis"),
        strut_lower: point(&v, "Spring", "Location Upright"),
        top_mount: point(&v, "Spring", "Location Chassis"),
    };
    let corner = read("MacPhersonStrut.json").file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let rows = parallel_wheel_travel(&corner, -0.08, 0.08, 16, Mode::Corrected).unwrap();
    let mut worst: f64 = 0.0;
    for half in [rows[8..].iter().collect::<Vec<_>>(), rows[..=8].iter().rev().collect()] {
        let mut guess = [0.0; 4];
        for row in half {
            let (toe, camber) = common::macpherson_closure(&h, row.travel, &mut guess);
            worst = worst.max((row.attitude.toe - toe).abs()).max((row.attitude.camber - camber).abs());
        }
    }
    // Measured: 4.5e-12 rad.
    assert!(worst < 1e-10, "{worst:e}");
}

/// Regression: Chrono's ideal MacPherson, height held, under a lateral force in four steps. Nothing moves
/// (every part is held by ideal joints and the rig), so the step's predictor is nothing, and the corrector
/// closing the start's joint gaps (within their tolerance) was taken for Newton leaving the path: every
/// step was cut to nothing.
#[test]
fn a_road_load_on_an_ideal_linkage_is_not_cut_to_nothing() {
    let file = read("MacPhersonStrut.json").file;
    let settings = Settings { steps: 4, ..Settings::default() };
    let report =
        kc::run(kc::Analysis::Road(elastokin_suspensions::analysis::WheelLoad::Lateral), &file, &settings).unwrap();
    let toe = report.table.columns.iter().position(|c| c == "toe_deg").unwrap();
    let moved = report.table.rows.iter().map(|r| r[toe].number().unwrap().abs()).fold(0.0, f64::max);
    // Measured: 2.9e-10 deg: an ideal linkage on the rig does not steer (the rest is its joints closed to
    // their 1e-10 m tolerance).
    assert!(moved < 1e-8, "{moved:e} deg");
}
