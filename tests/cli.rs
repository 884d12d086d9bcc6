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

#[test]
fn run_and_check_every_example() {
    let out = std::env::temp_dir().join(format!("elastokin-cli-{}", std::process::id()));
    for model in examples() {
        let o = elastokin(&["check", &model]);
        assert!(o.status.success(), "{model}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(String::from_utf8_lossy(&o.stdout).contains("every body is restrained"));
        for mode in ["corrected", "paper"] {
            let o = elastokin(&["run", &model, "--steps", "8", "--mode", mode, "--out", out.to_str().unwrap()]);
            assert!(o.status.success(), "{model} {mode}: {}", String::from_utf8_lossy(&o.stderr));
            let csv = std::fs::read_to_string(out.join("parallel_travel.csv")).unwrap();
            assert_eq!(csv.lines().count(), 1 + 9, "{csv}");
            assert!(!csv.contains("NaN") && !csv.contains("inf"), "{csv}");
            let summary: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
            assert!(summary["bump_steer_deg_per_m"].is_f64(), "{summary}");
            assert!(summary["compliance_at_design"]["lateral_steer_deg_per_kn"].is_f64(), "{summary}");
            let svg = std::fs::read_to_string(out.join("parallel_travel_toe_camber.svg")).unwrap();
            assert!(svg.contains("<polyline") && !svg.contains("NaN"));
        }
    }
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn bad_files_and_arguments_exit_non_zero_with_a_named_problem() {
    let dir = std::env::temp_dir().join(format!("elastokin-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let typo = dir.join("typo.json");
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(&examples()[0])).unwrap();
    std::fs::write(&typo, text.replacen("\"spring\"", "\"sprung\"", 1)).unwrap();
    let cases: Vec<(Vec<String>, &str)> = vec![
        (vec!["run".into(), typo.display().to_string()], "unknown field `sprung`"),
        (vec!["check".into(), "no/such/model.json".into()], "no/such/model.json"),
        (vec!["run".into(), examples()[0].clone(), "--steps".into(), "zero".into()], "--steps"),
        (vec!["run".into(), examples()[0].clone(), "--mode".into(), "exact".into()], "--mode"),
        (vec!["run".into(), examples()[0].clone(), "--range".into(), "0.1".into()], "--range"),
        (vec!["frobnicate".into()], "unknown command"),
    ];
    for (args, expected) in cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = elastokin(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} should fail");
        assert!(err.contains(expected), "{args:?}: {err}");
    }
    std::fs::remove_dir_all(&dir).ok();
    let o = elastokin(&["help"]);
    assert!(o.status.success() && String::from_utf8_lossy(&o.stdout).contains("elastokin run MODEL"));
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
    let run_bump = summary["bump_steer_deg_per_m"].as_f64().unwrap();
    let run_rate = summary["wheel_rate_n_per_m"].as_f64().unwrap();
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
