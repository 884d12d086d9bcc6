//! The `elastokin` command on every shipped example, and on bad input.

use std::path::Path;
use std::process::Command;

fn elastokin(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_elastokin")).args(args).current_dir(env!("CARGO_MANIFEST_DIR")).output().unwrap()
}

fn examples() -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .map(|p| format!("examples/{}", p.file_name().unwrap().to_string_lossy()))
        .collect();
    v.sort();
    v
}

/// The files `run` writes for each analysis: (CSV, plots).
const OUTPUTS: [(&str, &str, &[&str]); 8] = [
    ("parallel-travel", "parallel_travel.csv", &["parallel_travel_toe_camber.svg"]),
    ("roll", "roll.csv", &["roll_toe_camber.svg", "roll_centre.svg"]),
    ("steering", "steering.csv", &["steering.svg"]),
    ("vertical-force", "vertical_force.csv", &["vertical_force.svg"]),
    ("lateral-force", "lateral_force.csv", &["lateral_force.svg"]),
    ("braking-force", "braking_force.csv", &["braking_force.svg"]),
    ("traction-force", "traction_force.csv", &["traction_force.svg"]),
    ("aligning-torque", "aligning_torque.csv", &["aligning_torque.svg"]),
];

#[test]
fn run_and_check_every_example() {
    let out = std::env::temp_dir().join(format!("elastokin-cli-{}", std::process::id()));
    for model in examples() {
        let o = elastokin(&["check", &model]);
        assert!(o.status.success(), "{model}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(String::from_utf8_lossy(&o.stdout).contains("every body is restrained"));
        for mode in ["corrected", "paper"] {
            std::fs::remove_dir_all(&out).ok();
            let o = elastokin(&["run", &model, "--steps", "8", "--mode", mode, "--out", out.to_str().unwrap()]);
            assert!(o.status.success(), "{model} {mode}: {}", String::from_utf8_lossy(&o.stderr));
            let summary: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
            for (analysis, csv, plots) in OUTPUTS {
                let csv = std::fs::read_to_string(out.join(csv)).unwrap();
                assert_eq!(csv.lines().count(), 1 + 9, "{model} {mode} {analysis}: {csv}");
                assert!(!csv.contains("NaN") && !csv.contains("inf"), "{csv}");
                for plot in plots {
                    let svg = std::fs::read_to_string(out.join(plot)).unwrap();
                    assert!(svg.contains("<polyline") && !svg.contains("NaN"), "{plot}");
                }
                assert!(summary["analyses"][analysis]["parameter"].is_string(), "{analysis}: {summary}");
            }
            let a = &summary["analyses"];
            assert!(a["parallel-travel"]["bump_steer_deg_per_m"].is_f64(), "{summary}");
            assert!(a["parallel-travel"]["compliance_at_design"]["lateral_steer_deg_per_kn"].is_f64(), "{summary}");
            assert!(a["roll"]["roll_centre_height_at_design_m"].is_f64(), "{summary}");
            assert!(a["roll"]["roll_stiffness_nm_per_rad"].is_f64(), "{summary}");
            assert!(a["steering"]["steer_per_rack_travel_deg_per_m"].is_f64(), "{summary}");
            assert!(a["vertical-force"]["wheel_rate_n_per_m"].is_f64(), "{summary}");
            assert!(a["lateral-force"]["steer_deg_per_unit"].is_f64(), "{summary}");
            assert!(a["parallel-travel"]["wheel_compliance_at_design"][5][5].is_f64(), "{summary}");
            assert!(a["parallel-travel"]["anti_pitch"]["braking_percent"].is_f64(), "{summary}");
            // The static load case: a row per joint and element, ride height in the summary.
            let loads = std::fs::read_to_string(out.join("static_load.csv")).unwrap();
            assert!(loads.contains("\"spring\"") && loads.contains("\"corner load\"") && !loads.contains("NaN"));
            assert!(a["static-load"]["ride_height_change_m"].is_f64(), "{summary}");
        }
        // One analysis alone, with its own range.
        std::fs::remove_dir_all(&out).ok();
        let o =
            elastokin(&["run", &model, "--analysis", "roll", "--range", "-0.02,0.02", "--out", out.to_str().unwrap()]);
        assert!(o.status.success(), "{model}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(out.join("roll.csv").exists() && !out.join("parallel_travel.csv").exists());
        // A road load with the wheel free.
        let o = elastokin(&[
            "run",
            &model,
            "--analysis",
            "braking-force",
            "--wheel",
            "free",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{model}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(String::from_utf8_lossy(&o.stdout).contains("wheel free on its spring"));
    }
    std::fs::remove_dir_all(&out).ok();
}

/// The figures `run` reports are the engine's, read back through the files: the roll stiffness of the
/// springs equals the closed form from the wheel rate, k_φ = k_w · T² / 2 (both wheels on their springs,
/// track T), and the wheel rate from the vertical force sweep matches the one from parallel travel.
#[test]
fn run_figures_agree_with_each_other_by_closed_form() {
    let out = std::env::temp_dir().join(format!("elastokin-figures-{}", std::process::id()));
    let o = elastokin(&["run", "examples/double_wishbone.json", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let a = &summary["analyses"];
    let wheel_rate = a["parallel-travel"]["wheel_rate_n_per_m"].as_f64().unwrap();
    let roll_stiffness = a["roll"]["roll_stiffness_nm_per_rad"].as_f64().unwrap();
    let track = 2.0 * 1.100;
    let expected = wheel_rate * track * track / 2.0;
    // Finite differences over ±5 mm and the small track change limit this to ~1 %.
    assert!((roll_stiffness - expected).abs() < 0.02 * expected, "{roll_stiffness} vs k_w T²/2 = {expected}");
    let force_rate = a["vertical-force"]["wheel_rate_n_per_m"].as_f64().unwrap();
    assert!((force_rate - wheel_rate).abs() < 0.05 * wheel_rate, "{force_rate} vs {wheel_rate}");
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn bad_files_and_arguments_exit_non_zero_with_a_named_problem() {
    let dir = std::env::temp_dir().join(format!("elastokin-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let typo = dir.join("typo.json");
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(&examples()[0])).unwrap();
    std::fs::write(&typo, text.replacen("\"spring\"", "\"sprung\"", 1)).unwrap();
    // The model without its vehicle section: everything but the static load case still runs.
    let no_vehicle = dir.join("no_vehicle.json");
    let mut value: serde_json::Value = serde_json::from_str(&text).unwrap();
    value.as_object_mut().unwrap().remove("vehicle");
    std::fs::write(&no_vehicle, value.to_string()).unwrap();
    let o = elastokin(&[
        "run",
        no_vehicle.to_str().unwrap(),
        "--analysis",
        "lateral-force",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let cases: Vec<(Vec<String>, &str)> = vec![
        (vec!["run".into(), typo.display().to_string()], "unknown field `sprung`"),
        (vec!["check".into(), "no/such/model.json".into()], "no/such/model.json"),
        (vec!["run".into(), examples()[0].clone(), "--steps".into(), "zero".into()], "--steps"),
        (vec!["run".into(), examples()[0].clone(), "--mode".into(), "exact".into()], "--mode"),
        (vec!["run".into(), examples()[0].clone(), "--range".into(), "0.1".into()], "--range"),
        (vec!["frobnicate".into()], "unknown command"),
        (vec!["run".into(), examples()[0].clone(), "--analysis".into(), "pitch".into()], "unknown analysis 'pitch'"),
        (vec!["run".into(), examples()[0].clone(), "--range".into(), "0,1".into()], "--range needs --analysis"),
        (vec!["run".into(), examples()[0].clone(), "--wheel".into(), "loose".into()], "--wheel"),
        (
            vec!["run".into(), no_vehicle.display().to_string(), "--analysis".into(), "static-load".into()],
            "no \"vehicle\" section",
        ),
    ];
    for (args, expected) in cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = elastokin(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} should fail");
        assert!(err.contains(expected), "{args:?}: {err}");
    }
    std::fs::remove_dir_all(&dir).ok();
    for args in [&["help"][..], &["run", "--help"], &["batch", "-h"], &["check", "--help"]] {
        let o = elastokin(args);
        assert!(o.status.success() && String::from_utf8_lossy(&o.stdout).contains("elastokin run MODEL"), "{args:?}");
    }
}

#[test]
fn batch_runs_variants_in_parallel_and_agrees_with_run() {
    let out = std::env::temp_dir().join(format!("elastokin-batch-{}", std::process::id()));
    let o = elastokin(&[
        "batch",
        "examples/macpherson.json",
        "examples/macpherson_variants.txt",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("batch.csv")).unwrap();
    let value = |row: &str, col: usize| -> f64 {
        let line = csv.lines().find(|l| l.starts_with(&format!("\"{row}\""))).unwrap();
        line.split(',').nth(col).unwrap().parse().unwrap()
    };
    // The baseline variant is the model itself: same figures as `run` (same ±5 mm points around design).
    let r = elastokin(&["run", "examples/macpherson.json", "--out", out.to_str().unwrap()]);
    assert!(r.status.success());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let run_bump = summary["analyses"]["parallel-travel"]["bump_steer_deg_per_m"].as_f64().unwrap();
    let run_rate = summary["analyses"]["parallel-travel"]["wheel_rate_n_per_m"].as_f64().unwrap();
    assert!((value("baseline", 1) - run_bump).abs() < 1e-6 * run_bump.abs(), "{} vs {run_bump}", value("baseline", 1));
    assert!((value("baseline", 3) - run_rate).abs() < 1e-6 * run_rate, "{} vs {run_rate}", value("baseline", 3));
    // Moving the inner tie-rod point up and down moves bump steer in opposite directions around the baseline.
    let (up, base, down) =
        (value("tie rod inner up 10 mm", 1), value("baseline", 1), value("tie rod inner down 10 mm", 1));
    assert!((up - base) * (down - base) < 0.0, "{up} {base} {down}");
    // A softer spring lowers the wheel rate.
    assert!(value("soft spring", 3) < value("baseline", 3));
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn bad_variants_are_named_before_anything_runs() {
    let dir = std::env::temp_dir().join(format!("elastokin-badvar-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases = [
        ("typo: /suspension/macpherson/sprung/rate=1", "has no '/suspension/macpherson/sprung/rate'"),
        ("no equals sign: /suspension/macpherson/spring/rate", "is not pointer=value"),
        ("# only a comment", "no variants"),
        ("bad json: /suspension/macpherson/spring/rate=fast", "is not JSON"),
    ];
    for (k, (line, expected)) in cases.iter().enumerate() {
        let path = dir.join(format!("v{k}.txt"));
        std::fs::write(&path, line).unwrap();
        let o = elastokin(&["batch", "examples/macpherson.json", path.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && err.contains(expected), "{line}: {err}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
