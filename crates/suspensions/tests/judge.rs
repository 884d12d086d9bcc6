//! A run judged against a TARGETS file (`run --targets`): a figure met within its tolerance and missed
//! beyond it, a curve's point read between rows as a finer run gives it, packaging judged on the file's
//! hardpoints, and a file without free numbers read to judge but refused to tune.

use elastokin_suspensions::design::judge::judge;
use elastokin_suspensions::design::targets::{read_targets, read_targets_as, Reading, TargetsRefusal};
use elastokin_suspensions::kc::{self, Analysis, KcReport, Settings};
use elastokin_suspensions::study::batch::base_document;
use elastokin_suspensions::SuspensionFile;
use serde_json::{json, Value};

fn document() -> (SuspensionFile, Value) {
    let path = format!("{}/../../examples/macpherson.json", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap();
    (SuspensionFile::from_json(&text, &path).unwrap(), base_document(&text, &path).unwrap())
}

/// Parallel travel over ±50 mm in `steps` steps.
fn parallel_travel(file: &SuspensionFile, steps: usize) -> KcReport {
    let settings = Settings { range: Some((-0.05, 0.05)), steps, ..Settings::default() };
    kc::run_suite(file, &[Analysis::ParallelTravel], &settings, |_| {})
}

fn no_file(name: &str) -> Result<String, String> {
    Err(format!("no file {name}"))
}

#[test]
fn a_figure_target_is_met_within_its_tolerance_and_missed_beyond_it() {
    let (file, doc) = document();
    let report = parallel_travel(&file, 20);
    let figure = &report.analyses[0].figures.iter().find(|f| f.key == "bump_steer").unwrap();
    // The target is in deg/m, as the report writes bump steer under the default units; the figure is held
    // in rad/m.
    let written = figure.value.unwrap().to_degrees();
    let tolerance = 0.25;
    let text = json!({ "targets": [
        { "figure": "parallel-travel/bump_steer", "value": written + 0.9 * tolerance, "tolerance": tolerance },
        { "figure": "parallel-travel/bump_steer", "value": written - 1.1 * tolerance, "tolerance": tolerance },
        { "figure": "roll/roll_centre_height", "value": 0.1, "tolerance": 0.01 },
    ]})
    .to_string();
    let targets = read_targets_as(Reading::ToJudge, &text, "t.json", &doc, no_file).unwrap();
    let (points, constraints) = judge(&report, &doc, &targets);
    assert!(constraints.is_empty());
    assert_eq!(points.len(), 3);
    // Measured 0 (the same product, written another way).
    assert!((points[0].reached.clone().unwrap() - written).abs() <= 1e-12 * written.abs(), "{:?}", points[0]);
    assert!(points[0].met() && (points[0].miss_over_tolerance().unwrap() - 0.9).abs() < 1e-9);
    assert!(!points[1].met() && (points[1].miss_over_tolerance().unwrap() - 1.1).abs() < 1e-9);
    // An analysis the run left out gives nothing to judge, and says so; it is not met.
    assert_eq!(points[2].reached, Err("roll was not run".to_string()));
    assert!(!points[2].met());
}

#[test]
fn a_curve_point_between_rows_is_read_as_a_finer_run_gives_it() {
    let (file, doc) = document();
    let coarse = parallel_travel(&file, 20); // rows every 5 mm
    let fine = parallel_travel(&file, 40); // rows every 2.5 mm: one at 12.5 mm
    let toe = |r: &KcReport, at: f64| {
        let t = &r.analyses[0].table;
        let along = t.column("travel_m").unwrap();
        let k = along.iter().position(|v| (v.unwrap() - at).abs() < 1e-12).unwrap();
        t.column("toe_deg").unwrap()[k].unwrap()
    };
    let text = json!({ "targets": [
        { "curve": "parallel-travel/toe_deg", "points": [[0.0125, 0.0], [0.03, 0.0], [0.07, 0.0]], "tolerance": 0.05 },
    ]})
    .to_string();
    let targets = read_targets_as(Reading::ToJudge, &text, "t.json", &doc, no_file).unwrap();
    let (points, _) = judge(&coarse, &doc, &targets);
    // Between rows: the cubic through the four nearest rows against the finer run's own row there
    // (measured 9.3e-8 deg).
    let between = points[0].reached.clone().unwrap();
    assert!((between - toe(&fine, 0.0125)).abs() < 1e-6, "{between} against {}", toe(&fine, 0.0125));
    // On a row: that row's cell.
    assert_eq!(points[1].reached, Ok(toe(&coarse, 0.03)));
    // Beyond the rows run: not judged, with how to judge it.
    let why = points[2].reached.clone().unwrap_err();
    assert!(why.contains("outside the rows run") && why.contains("range"), "{why}");
}

#[test]
fn packaging_is_judged_on_the_hardpoints_of_the_file() {
    let (file, doc) = document();
    let report = parallel_travel(&file, 4);
    let h = &doc["suspension"]["macpherson"]["hardpoints"];
    let p = |name: &str| (0..3).map(|i| h[name][i].as_f64().unwrap()).collect::<Vec<f64>>();
    let (a, b) = (p("tie_rod_inner"), p("tie_rod_outer"));
    let length = a.iter().zip(&b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt();
    let text = json!({
        "targets": [{ "figure": "parallel-travel/bump_steer", "value": 0.0, "tolerance": 100.0 }],
        "constraints": [
            { "distance": ["tie_rod_inner", "tie_rod_outer"], "min": length - 0.001, "max": length + 0.001 },
            { "distance": ["tie_rod_inner", "tie_rod_outer"], "min": length + 0.001, "max": length + 0.002 },
        ]
    })
    .to_string();
    let targets = read_targets_as(Reading::ToJudge, &text, "t.json", &doc, no_file).unwrap();
    let (_, constraints) = judge(&report, &doc, &targets);
    let (value, _, _) = constraints[0].reached.clone().unwrap();
    assert!((value - length).abs() < 1e-15, "{value} against {length}");
    assert!(constraints[0].met());
    assert!(!constraints[1].met());
}

#[test]
fn a_targets_file_without_free_numbers_is_read_to_judge_and_refused_to_tune() {
    let (_, doc) = document();
    let text =
        json!({ "targets": [{ "figure": "parallel-travel/bump_steer", "value": 0.0, "tolerance": 1.0 }] }).to_string();
    assert_eq!(read_targets_as(Reading::ToJudge, &text, "t.json", &doc, no_file).unwrap().free, vec![]);
    let e = read_targets(&text, "t.json", &doc, no_file).unwrap_err();
    assert!(matches!(*e.refusal, TargetsRefusal::NoFree), "{e}");
    // Free numbers given to judge are still checked against the model.
    let wrong = json!({
        "free": { "/suspension/macpherson/hardpoints/nowhere/0": [0.0, 1.0] },
        "targets": [{ "figure": "parallel-travel/bump_steer", "value": 0.0, "tolerance": 1.0 }]
    })
    .to_string();
    assert!(read_targets_as(Reading::ToJudge, &wrong, "t.json", &doc, no_file).is_err());
}
