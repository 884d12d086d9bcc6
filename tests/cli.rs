//! The `elastokin` command on every shipped example, and on bad input.

use sha2::{Digest, Sha256};
use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn elastokin(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_elastokin")).args(args).current_dir(env!("CARGO_MANIFEST_DIR")).output().unwrap()
}

/// Runs the command and holds it to success, showing its standard error when it fails.
fn succeeds(args: &[&str]) -> std::process::Output {
    let o = elastokin(args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o
}

/// The rows of a CSV file the command wrote, read by a CSV reader that skips the provenance comment line.
fn read_csv(path: &Path) -> Vec<csv::StringRecord> {
    let mut reader = csv::ReaderBuilder::new().comment(Some(b'#')).from_path(path).unwrap();
    reader.records().map(Result::unwrap).collect()
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
            // The five-link corner's toe is held by a link to the chassis, the live axle's by its tube, the
            // twist beam's by its arms: they have no steering to run.
            let steered = !["five_link", "four_link_axle", "twist_beam"].iter().any(|m| model.contains(m));
            for (analysis, csv, plots) in OUTPUTS.into_iter().filter(|(a, _, _)| steered || *a != "steering") {
                let csv = std::fs::read_to_string(out.join(csv)).unwrap();
                // The provenance line, the header, one row per load step.
                assert_eq!(csv.lines().count(), 2 + 9, "{model} {mode} {analysis}: {csv}");
                assert!(!csv.contains("NaN") && !csv.contains("inf"), "{csv}");
                for plot in plots {
                    let svg = std::fs::read_to_string(out.join(plot)).unwrap();
                    assert!(svg.contains("<polyline") && !svg.contains("NaN"), "{plot}");
                }
                assert!(summary["analyses"][analysis]["parameter"].is_string(), "{analysis}: {summary}");
            }
            let a = &summary["analyses"];
            assert!(a["parallel-travel"]["figures"]["bump_steer"]["value"].is_f64(), "{summary}");
            assert!(a["parallel-travel"]["figures"]["lateral_steer"]["value"].is_f64(), "{summary}");
            assert!(a["roll"]["figures"]["roll_centre_height"]["value"].is_f64(), "{summary}");
            assert!(a["roll"]["figures"]["roll_stiffness"]["value"].is_f64(), "{summary}");
            assert!(!steered || a["steering"]["figures"]["steer_per_rack_travel"]["value"].is_f64(), "{summary}");
            assert!(a["vertical-force"]["figures"]["wheel_rate"]["value"].is_f64(), "{summary}");
            assert!(a["lateral-force"]["figures"]["steer"]["value"].is_f64(), "{summary}");
            assert!(a["parallel-travel"]["wheel_compliance_at_design"][5][5].is_f64(), "{summary}");
            assert!(a["parallel-travel"]["figures"]["braking_anti_pitch"]["value"].is_f64(), "{summary}");
            // The static load case: a row per joint and element, ride height in the summary.
            let loads = read_csv(&out.join("static_load.csv"));
            let components: Vec<&str> = loads.iter().map(|r| &r[0]).collect();
            assert!(components.contains(&"spring") && components.contains(&"corner load"), "{components:?}");
            assert!(a["static-load"]["figures"]["ride_height_change"]["value"].is_f64(), "{summary}");
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
    succeeds(&["run", "examples/generic/double_wishbone.json", "--out", out.to_str().unwrap()]);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let a = &summary["analyses"];
    let wheel_rate = a["parallel-travel"]["figures"]["wheel_rate"]["value"].as_f64().unwrap() * 1e3; // N/m
    let roll_stiffness = a["roll"]["figures"]["roll_stiffness"]["value"].as_f64().unwrap().to_degrees(); // N·m/rad
    let track = 2.0 * 1.100;
    let expected = wheel_rate * track * track / 2.0;
    // Finite differences over ±5 mm and the small track change limit this to ~1 %.
    assert!((roll_stiffness - expected).abs() < 0.02 * expected, "{roll_stiffness} vs k_w T²/2 = {expected}");
    let force_rate = a["vertical-force"]["figures"]["wheel_rate"]["value"].as_f64().unwrap() * 1e3;
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
    succeeds(&[
        "run",
        no_vehicle.to_str().unwrap(),
        "--analysis",
        "lateral-force",
        "--out",
        dir.join("out").to_str().unwrap(),
    ]);
    let cases: Vec<(Vec<String>, &str)> = vec![
        (vec!["run".into(), typo.display().to_string()], "unknown field `sprung`"),
        (vec!["check".into(), "no/such/model.json".into()], "no/such/model.json"),
        (vec!["run".into(), examples()[0].clone(), "--steps".into(), "zero".into()], "--steps"),
        (vec!["run".into(), examples()[0].clone(), "--mode".into(), "exact".into()], "--mode"),
        (vec!["run".into(), examples()[0].clone(), "--range".into(), "0.1".into()], "--range"),
        (vec!["frobnicate".into()], "unrecognized subcommand 'frobnicate'"),
        (
            vec!["run".into(), examples()[0].clone(), "--analysis".into(), "pitch".into()],
            "invalid value 'pitch' for '--analysis <NAME>'",
        ),
        (vec!["run".into(), examples()[0].clone(), "--range".into(), "0,1".into()], "--range needs --analysis"),
        (vec!["run".into(), examples()[0].clone(), "--wheel".into(), "loose".into()], "--wheel"),
        (
            vec![
                "run".into(),
                no_vehicle.display().to_string(),
                "--analysis".into(),
                "static-load".into(),
                "--out".into(),
                dir.join("out").display().to_string(),
            ],
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
    for (args, usage) in [
        (&["help"][..], "Usage: elastokin [OPTIONS] <COMMAND>"),
        (&["--help"], "Usage: elastokin [OPTIONS] <COMMAND>"),
        (&["run", "--help"], "Usage: elastokin run [OPTIONS] <MODEL>"),
        (&["help", "run"], "Usage: elastokin run [OPTIONS] <MODEL>"),
        (&["batch", "-h"], "Usage: elastokin batch [OPTIONS] <MODEL> <VARIANTS>"),
        (&["check", "--help"], "Usage: elastokin check [OPTIONS] <MODEL>"),
    ] {
        let o = elastokin(args);
        let help = String::from_utf8_lossy(&o.stdout);
        assert!(o.status.success() && help.contains(usage) && help.contains("Exit status: 0 success"), "{args:?}");
    }
}

#[test]
fn batch_runs_variants_in_parallel_and_agrees_with_run() {
    let out = std::env::temp_dir().join(format!("elastokin-batch-{}", std::process::id()));
    let o = elastokin(&[
        "batch",
        "examples/generic/macpherson.json",
        "examples/generic/macpherson_variants.txt",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    let printed = String::from_utf8_lossy(&o.stdout).to_string();
    let csv = read_csv(&out.join("batch.csv"));
    let value = |row: &str, col: usize| -> f64 {
        let record = csv.iter().find(|r| &r[0] == row).unwrap();
        record[col].parse().unwrap()
    };
    // The baseline variant is the model itself: same figures as `run` (read at design, off the path there).
    let r = elastokin(&["run", "examples/generic/macpherson.json", "--out", out.to_str().unwrap()]);
    assert!(r.status.success());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let run_bump = summary["analyses"]["parallel-travel"]["figures"]["bump_steer"]["value"].as_f64().unwrap();
    let run_rate = summary["analyses"]["parallel-travel"]["figures"]["wheel_rate"]["value"].as_f64().unwrap() * 1e3;
    assert!((value("baseline", 1) - run_bump).abs() < 1e-6 * run_bump.abs(), "{} vs {run_bump}", value("baseline", 1));
    assert!((value("baseline", 3) - run_rate).abs() < 1e-6 * run_rate, "{} vs {run_rate}", value("baseline", 3));
    // Printed in run's units, as run prints bump steer.
    let baseline = printed.lines().find(|l| l.starts_with("baseline")).unwrap_or_else(|| panic!("{printed}"));
    assert!(printed.contains("bump deg/m") && baseline.contains(&format!("{run_bump:.3}")), "{printed}");
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
        let o = elastokin(&["batch", "examples/generic/macpherson.json", path.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && err.contains(expected), "{line}: {err}");
    }
    // A file with a wrong line here and there said one per try, with no line: every wrong line is said at
    // once, each with its line, and the rest counted past twenty.
    let mut lines: Vec<String> =
        (0..40).map(|k| format!("ok {k}: /suspension/macpherson/spring/rate={}", 2e4 + k as f64)).collect();
    lines[2] = cases[0].0.into();
    lines[10] = cases[1].0.into();
    lines[17] = cases[3].0.into();
    let path = dir.join("many.txt");
    std::fs::write(&path, lines.join("\n")).unwrap();
    let o = elastokin(&["batch", "examples/generic/macpherson.json", path.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    for (line, (_, expected)) in [(3, cases[0]), (11, cases[1]), (18, cases[3])] {
        let said = format!("{}:{line}: ", path.display());
        assert!(err.lines().any(|l| l.contains(&said) && l.contains(expected)), "line {line}: {err}");
    }
    let wrong: Vec<String> = (0..25).map(|k| format!("w{k}: /suspension/nope={k}")).collect();
    std::fs::write(&path, wrong.join("\n")).unwrap();
    let err = String::from_utf8_lossy(
        &elastokin(&["batch", "examples/generic/macpherson.json", path.to_str().unwrap()]).stderr,
    )
    .into_owned();
    assert_eq!(err.matches("has no '/suspension/nope'").count(), 20, "{err}");
    assert!(err.contains("… and 5 more wrong lines"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A fresh scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("elastokin-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs the command, failing the test instead of hanging when it takes longer than `limit`.
fn elastokin_within(args: &[&str], limit: Duration) -> std::process::Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_elastokin"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > limit {
            child.kill().ok();
            panic!("{args:?} still running after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

/// Every file in `dir` with its bytes.
fn snapshot(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (e.file_name().to_string_lossy().into_owned(), std::fs::read(e.path()).unwrap())
        })
        .collect()
}

/// The names in `dir`.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    v.sort();
    v
}

#[test]
fn version_help_and_argument_mistakes_are_answered_by_name() {
    let o = elastokin(&["--version"]);
    assert!(o.status.success());
    assert_eq!(String::from_utf8_lossy(&o.stdout), format!("elastokin {}\n", env!("CARGO_PKG_VERSION")));
    // The long help keeps what each analysis's load parameter is, its units and default range.
    let o = elastokin(&["run", "--help"]);
    let help = String::from_utf8_lossy(&o.stdout);
    for text in [
        "parallel-travel: wheel travel, m, bump +; default -0.08,0.08",
        "lateral-force:   lateral force at the contact patch, N, inboard +; default -3000,3000",
        "roll:            left wheel travel, m (right opposite), full axle; default -0.05,0.05",
        "static-load:     corner load of the model file's vehicle section, N, applied at once",
        "[default: 32]",
        "--quiet",
        "Exit status: 0 success; 1 a run that failed while solving or writing",
    ] {
        assert!(help.contains(text), "{text}: {help}");
    }
    let m = "examples/generic/macpherson.json";
    let v = "examples/generic/macpherson_variants.txt";
    let cases: [(&[&str], &str); 7] = [
        (&["run", m, "extra"], "unexpected argument 'extra' found"),
        (&["batch", m, v, "extra"], "unexpected argument 'extra' found"),
        (&["check", m, "--steps", "4"], "unexpected argument '--steps' found"),
        (&["run", m, "--stpes", "4"], "a similar argument exists: '--steps'"),
        (&["chek", m], "a similar subcommand exists: 'check'"),
        (&["check"], "the following required arguments were not provided:\n  <MODEL>"),
        (&["run", m, "--range", "0,1"], "--range needs --analysis NAME"),
    ];
    for (args, expected) in cases {
        let o = elastokin(args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(expected), "{args:?}: {err}");
        assert!(o.stdout.is_empty(), "{args:?}");
    }
    // No command at all: the help, on standard error, as a usage error.
    let o = elastokin(&[]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("Commands:"));
}

#[test]
fn steps_and_ranges_are_bounded_with_a_reason() {
    let out = scratch("bounds");
    let m = "examples/generic/macpherson.json";
    let limit = Duration::from_secs(60);
    let too_many = |n: &str| {
        format!("a sweep takes at most 20000 steps, got {n}: every step keeps the solved model in memory and costs solver time")
    };
    for (steps, expected) in [
        ("0", "a sweep needs at least 1 step".to_string()),
        ("-1", "'-1' is not a whole number of steps".to_string()),
        ("4294967296", too_many("4294967296")),
        ("18446744073709551615", too_many("18446744073709551615")),
        ("18446744073709551616", "is not a whole number".to_string()),
        ("20001", too_many("20001")),
    ] {
        let o = elastokin_within(&["run", m, "--steps", steps, "--out", out.to_str().unwrap()], limit);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "--steps {steps}: {err}");
        assert!(
            err.contains(&format!("invalid value '{steps}' for '--steps <N>'")) && err.contains(&expected),
            "{err}"
        );
    }
    for range in ["nan,1", "0,inf", "1e308,-1e308", "0.1", "0.02,0.02", "a,b"] {
        let o = elastokin_within(&["run", m, "--analysis", "roll", "--range", range], limit);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "--range {range}: {err}");
        assert!(err.contains(&format!("invalid value '{range}' for '--range <FROM,TO>'")), "{err}");
    }
    // Nothing was written by the refused runs.
    assert!(names(&out).is_empty());
    // The maximum itself runs, one row per step.
    let target = out.join("max");
    let o = elastokin_within(
        &["run", m, "--analysis", "parallel-travel", "--steps", "20000", "--out", target.to_str().unwrap()],
        Duration::from_secs(300),
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(read_csv(&target.join("parallel_travel.csv")).len(), 20001);
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn too_many_variants_are_refused_before_running() {
    let dir = scratch("manyvariants");
    let path = dir.join("many.txt");
    let text: String =
        (0..10_001).map(|k| format!("v{k}: /suspension/macpherson/spring/rate={}\n", 20000 + k)).collect();
    std::fs::write(&path, text).unwrap();
    let o = elastokin(&[
        "batch",
        "examples/generic/macpherson.json",
        path.to_str().unwrap(),
        "--out",
        dir.join("o").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("many.txt:10001: more than 10000 variants; split the file"), "{err}");
    assert_eq!(names(&dir), ["many.txt"]);
    std::fs::remove_dir_all(&dir).ok();
}

/// Spawns the command with its standard output (and, if asked, standard error) closed before it has
/// written anything, as `elastokin … | head -1` does once head has its line.
fn with_closed_output(args: &[&str], close_stderr: bool) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_elastokin"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let mut err = String::new();
    match child.stderr.take() {
        Some(stderr) if close_stderr => drop(stderr),
        Some(mut stderr) => {
            stderr.read_to_string(&mut err).unwrap();
        }
        None => {}
    }
    (child.wait().unwrap().code(), err)
}

#[test]
fn a_closed_pipe_is_no_crash_and_the_work_still_gets_done() {
    let out = scratch("pipe");
    let (run_out, batch_out) = (out.join("run"), out.join("batch"));
    let m = "examples/generic/macpherson.json";
    let runs: [(&[&str], Option<PathBuf>); 5] = [
        (&["check", m], None),
        (&["run", m, "--steps", "8", "--out", run_out.to_str().unwrap()], Some(run_out.join("summary.json"))),
        (
            &["batch", m, "examples/generic/macpherson_variants.txt", "--out", batch_out.to_str().unwrap()],
            Some(batch_out.join("batch.csv")),
        ),
        (&["--help"], None),
        (&["run", "--help"], None),
    ];
    for close_stderr in [false, true] {
        for (args, product) in &runs {
            if let Some(p) = product {
                std::fs::remove_dir_all(p.parent().unwrap()).ok();
            }
            let (code, err) = with_closed_output(args, close_stderr);
            assert!(!err.contains("panicked"), "{args:?}: {err}");
            assert_eq!(code, Some(0), "{args:?}: {err}");
            if let Some(p) = product {
                assert!(p.exists(), "{args:?} did not write {}", p.display());
            }
        }
        // A usage error with nobody listening is still a usage error, not a crash.
        let (code, err) = with_closed_output(&["run", m, "--steps", "0"], close_stderr);
        assert_eq!(code, Some(2), "{err}");
    }
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn a_failed_run_leaves_the_previous_results_untouched() {
    let dir = scratch("whole");
    let out = dir.join("results");
    succeeds(&["run", "examples/generic/macpherson.json", "--steps", "8", "--out", out.to_str().unwrap()]);
    let before = snapshot(&out);
    assert!(before.contains_key("summary.json") && before.contains_key("roll.csv"));
    // A corner load no spring holds: the static load case fails, and with nothing else asked for nothing ran
    // (a suite in which others ran writes theirs: see
    // `one_failing_analysis_costs_only_itself_the_others_are_written_and_the_run_exits_1`).
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/generic/macpherson.json"))
        .unwrap();
    let mut value: serde_json::Value = serde_json::from_str(&text).unwrap();
    value["vehicle"]["corner_load"] = 1.0e6.into();
    let heavy = dir.join("heavy.json");
    std::fs::write(&heavy, value.to_string()).unwrap();
    let heavy_run = |out: &Path| {
        elastokin(&["run", heavy.to_str().unwrap(), "--analysis", "static-load", "--out", out.to_str().unwrap()])
    };
    let o = heavy_run(&out);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("static-load:"), "{err}");
    assert!(err.contains(&format!("previous results in {} left untouched", out.display())), "{err}");
    assert_eq!(snapshot(&out), before);
    assert_eq!(names(&dir), ["heavy.json", "results"]);
    // Into a new directory the same failure leaves nothing at all.
    let fresh = dir.join("fresh");
    let o = heavy_run(&fresh);
    assert!(String::from_utf8_lossy(&o.stderr).contains(&format!("nothing written to {}", fresh.display())));
    assert_eq!(names(&dir), ["heavy.json", "results"]);
    // A successful run replaces the directory whole: no file of the earlier run survives beside the new ones.
    succeeds(&["run", "examples/generic/macpherson.json", "--analysis", "roll", "--out", out.to_str().unwrap()]);
    assert_eq!(names(&out), ["report.html", "roll.csv", "roll_centre.svg", "roll_toe_camber.svg", "summary.json"]);
    assert_eq!(names(&dir), ["heavy.json", "results"]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_out_that_is_not_a_results_directory_is_refused_and_kept() {
    let dir = scratch("outkinds");
    let m = "examples/generic/macpherson.json";
    let file = dir.join("x");
    std::fs::write(&file, "mine").unwrap();
    let mine = dir.join("mine");
    std::fs::create_dir(&mine).unwrap();
    std::fs::write(mine.join("notes.txt"), "mine").unwrap();
    let older = dir.join("older");
    std::fs::create_dir(&older).unwrap();
    std::fs::write(older.join("measured.csv"), "travel_m,toe_deg\n0,0\n").unwrap();
    let plots = dir.join("plots");
    std::fs::create_dir(&plots).unwrap();
    std::fs::write(plots.join("sketch.svg"), "<svg/>").unwrap();
    // Earlier results with the model file put beside them.
    let with_model = dir.join("with_model");
    let o = elastokin(&["run", m, "--analysis", "roll", "--out", with_model.to_str().unwrap()]);
    assert!(o.status.success());
    std::fs::copy(Path::new(env!("CARGO_MANIFEST_DIR")).join(m), with_model.join("model.json")).unwrap();
    let cases = [
        (&file, format!("--out DIR: '{}' is a file; give a directory", file.display())),
        (&mine, format!("--out DIR: '{}' holds 'notes.txt', which elastokin does not write", mine.display())),
        (&older, format!("--out DIR: '{}' holds 'measured.csv', which elastokin did not write", older.display())),
        (&plots, format!("--out DIR: '{}' does not hold elastokin results", plots.display())),
        (
            &with_model,
            format!("--out DIR: '{}' holds 'model.json', which elastokin does not write", with_model.display()),
        ),
    ];
    for (out, expected) in cases {
        let before = names(&dir);
        let o = elastokin(&["run", m, "--analysis", "roll", "--out", out.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains(&expected), "{err}");
        assert_eq!(names(&dir), before);
    }
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "mine");
    assert_eq!(std::fs::read_to_string(mine.join("notes.txt")).unwrap(), "mine");
    assert!(older.join("measured.csv").exists() && with_model.join("model.json").exists());
    // Results of versions before the provenance line are recognised by their summary.json, and replaced.
    let earlier = dir.join("earlier");
    std::fs::create_dir(&earlier).unwrap();
    std::fs::write(earlier.join("summary.json"), r#"{"model": "m", "mode": "corrected", "analyses": {}}"#).unwrap();
    std::fs::write(earlier.join("steering.csv"), "rack_m,toe_deg\n0.000000000,0.000000000\n").unwrap();
    succeeds(&["run", m, "--analysis", "roll", "--out", earlier.to_str().unwrap()]);
    assert_eq!(names(&earlier), ["report.html", "roll.csv", "roll_centre.svg", "roll_toe_camber.svg", "summary.json"]);
    std::fs::remove_dir_all(&dir).ok();
}

/// Significant digits of a number as written: the mantissa's digits without leading zeros.
fn significant_digits(cell: &str) -> usize {
    let mantissa = cell.split(['e', 'E']).next().unwrap();
    mantissa.chars().filter(char::is_ascii_digit).skip_while(|&c| c == '0').count()
}

#[test]
fn every_result_says_what_produced_it() {
    let out = scratch("provenance");
    let m = "examples/generic/macpherson.json";
    let sha: String = Sha256::digest(std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join(m)).unwrap())
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    let version = env!("CARGO_PKG_VERSION");
    let args = [
        "run",
        m,
        "--analysis",
        "roll",
        "--steps",
        "8",
        "--range",
        "-0.02,0.02",
        "--wheel",
        "free",
        "--out",
        out.to_str().unwrap(),
    ];
    succeeds(&args);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let p = &summary["provenance"];
    assert_eq!(p["elastokin"], version);
    assert_eq!(p["model"], m);
    assert_eq!(p["model_sha256"], sha.as_str());
    assert_eq!(p["mode"], "corrected");
    assert_eq!(p["steps"], 8);
    assert_eq!(p["wheel"], "free");
    assert_eq!(p["range"], serde_json::json!([-0.02, 0.02]));
    assert!(p["command"].as_str().unwrap().ends_with(&args.join(" ")), "{p}");
    let text = std::fs::read_to_string(out.join("roll.csv")).unwrap();
    assert_eq!(
        text.lines().next().unwrap(),
        format!("# elastokin {version}, model {m} (sha256 {}), corrected mode, 8 steps", &sha[..16])
    );
    // A CSV reader takes the rest: every cell a finite number of at most 12 significant digits.
    let rows = read_csv(&out.join("roll.csv"));
    assert_eq!(rows.len(), 9);
    for row in &rows {
        for cell in row {
            assert!(cell.parse::<f64>().is_ok_and(f64::is_finite), "{cell}");
            assert!(significant_digits(cell) <= 12, "{cell}");
        }
    }
    // Twelve digits, not fewer: the old fixed 9 decimals wrote a 0.2 mm roll centre height as 0.000200000.
    assert!(rows.iter().flat_map(|r| r.iter()).any(|c| significant_digits(c) == 12));
    // batch.csv names the variants file too.
    succeeds(&["batch", m, "examples/generic/macpherson_variants.txt", "--out", out.to_str().unwrap()]);
    let text = std::fs::read_to_string(out.join("batch.csv")).unwrap();
    let first = text.lines().next().unwrap();
    assert!(first.starts_with(&format!("# elastokin {version}, model {m} (sha256 {}), corrected mode, 8 steps, variants examples/generic/macpherson_variants.txt (sha256 ", &sha[..16])), "{first}");
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn progress_goes_to_standard_error_and_quiet_silences_all_but_errors() {
    let out = scratch("quiet");
    let m = "examples/generic/macpherson.json";
    let target = out.join("o");
    let o = elastokin(&["run", m, "--analysis", "roll", "--steps", "8", "--out", target.to_str().unwrap()]);
    assert!(o.status.success());
    // Not a terminal here: one plain line per analysis.
    assert_eq!(String::from_utf8_lossy(&o.stderr), "analyses 1/1: roll\n");
    assert!(String::from_utf8_lossy(&o.stdout).contains("roll centre"));
    let o = elastokin(&["batch", m, "examples/generic/macpherson_variants.txt", "--out", target.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    let variants = read_csv(&target.join("batch.csv")).len();
    assert_eq!(err.lines().filter(|l| l.starts_with("variants ") && l.contains(" done: ")).count(), variants, "{err}");
    assert!(err.contains(&format!("variants {variants}/{variants} done: ")) && err.contains("done: baseline"), "{err}");
    for args in [
        &["--quiet", "run", m, "--analysis", "roll", "--steps", "8", "--out", target.to_str().unwrap()][..],
        &["run", m, "-q", "--steps", "8", "--out", target.to_str().unwrap()],
        &["batch", m, "examples/generic/macpherson_variants.txt", "--quiet", "--out", target.to_str().unwrap()],
        &["check", "--quiet", m],
    ] {
        let o = elastokin(args);
        assert!(o.status.success(), "{args:?}");
        assert!(o.stdout.is_empty() && o.stderr.is_empty(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
    }
    assert!(target.join("batch.csv").exists());
    // Errors still reach standard error.
    let o = elastokin(&["--quiet", "check", "no/such/model.json"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("MODEL 'no/such/model.json': cannot open it"));
    std::fs::remove_dir_all(&out).ok();
}

/// On a terminal the progress is an indicatif bar instead of plain lines. `script` (util-linux) runs the
/// command on a pseudo-terminal.
#[cfg(target_os = "linux")]
#[test]
fn progress_on_a_terminal_is_a_bar() {
    let out = scratch("terminal");
    let bin = env!("CARGO_BIN_EXE_elastokin");
    for (args, bar) in [
        (
            format!("run examples/generic/macpherson.json --analysis roll --steps 8 --out '{}'", out.display()),
            "analyses [",
        ),
        (
            format!(
                "batch examples/generic/macpherson.json examples/generic/macpherson_variants.txt --out '{}'",
                out.display()
            ),
            "variants [",
        ),
    ] {
        let o = Command::new("script")
            .args(["-qec", &format!("'{bin}' {args} > /dev/null"), "/dev/null"])
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .stdin(Stdio::null())
            .output()
            .expect("script (util-linux) runs the command on a terminal");
        let terminal = String::from_utf8_lossy(&o.stdout);
        assert!(o.status.success(), "{args}: {terminal}");
        assert!(terminal.contains(bar), "{args}: {terminal}");
        assert!(!terminal.contains("analyses 1/1: roll") && !terminal.contains(" done: "), "{args}: {terminal}");
    }
    std::fs::remove_dir_all(&out).ok();
}

/// Paper mode at the default 32 steps gives the MacPherson wheel rate 25 % high: the command shows the
/// error estimate beside it and warns; `--tolerance` sets what is accepted; `--strict` writes nothing.
#[test]
fn paper_mode_error_is_shown_warned_about_and_refused_under_strict() {
    let dir = scratch("paper-error");
    let out = dir.join("out");
    let run = |extra: &[&str]| {
        let mut args =
            vec!["run", "examples/generic/macpherson.json", "--analysis", "parallel-travel", "--mode", "paper"];
        args.extend_from_slice(extra);
        args.extend_from_slice(&["--out", out.to_str().unwrap()]);
        elastokin(&args)
    };
    let o = run(&[]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // The rows drift (measured: 0.090 deg, and 1.2 mm of half-track; the swing arms, read off the tangent at
    // the drifted rows, 3.3 m); the wheel rate at design is read off the equilibrium there, in either mode
    // (35.03 N/mm).
    assert!(stdout.contains("error estimate: angles 0.090 deg, lengths 3318 mm"), "{stdout}");
    let line = stdout.lines().find(|l| l.trim_start().starts_with("wheel rate")).unwrap();
    assert!(line.contains("35.03") && !line.contains('±'), "{line}");
    assert!(stdout.contains("warning [error-over-tolerance]: parallel-travel:"), "{stdout}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let rate = &summary["analyses"]["parallel-travel"]["figures"]["wheel_rate"];
    assert!(rate["error"].as_f64().unwrap() < 1e-6, "{rate}");
    assert_eq!(summary["analyses"]["parallel-travel"]["accuracy"]["within_tolerance"], false);
    assert_eq!(summary["provenance"]["tolerance"]["angle_deg"], 0.001);
    // A looser tolerance (1°, 4 m, 50 %) accepts it.
    let o = run(&["--tolerance", "1,4000,50"]);
    assert!(!String::from_utf8_lossy(&o.stdout).contains("warning ["), "{}", String::from_utf8_lossy(&o.stdout));
    // Under --strict the same run fails and leaves the earlier results as they were.
    let before = snapshot(&out);
    let o = run(&["--strict"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("error-over-tolerance") && err.contains("left untouched"), "{err}");
    assert_eq!(snapshot(&out), before);
    for bad in ["1,2", "0,1,1", "a,1,1", "1,1,-5"] {
        let o = run(&["--tolerance", bad]);
        assert_eq!(o.status.code(), Some(2), "{bad}");
        assert!(String::from_utf8_lossy(&o.stderr).contains("--tolerance"), "{bad}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The generic MacPherson with its tie rod's inner point 3 mm ahead of the steering axis, written in `dir`:
/// a model the plausibility checks warn of (on the axis exactly, it is refused as degenerate).
fn tie_rod_on_axis(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/generic/macpherson.json"))
        .unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let points = &mut v["suspension"]["macpherson"]["hardpoints"];
    let point = |p: &serde_json::Value| -> [f64; 3] { [0, 1, 2].map(|k| p[k].as_f64().unwrap()) };
    let (a, b) = (point(&points["lower_ball_joint"]), point(&points["top_mount"]));
    points["tie_rod_inner"] =
        serde_json::json!([0, 1, 2].map(|k| a[k] + 0.4 * (b[k] - a[k]) + if k == 0 { 0.003 } else { 0.0 }));
    let model = dir.join("tie_rod_on_axis.json");
    std::fs::write(&model, v.to_string()).unwrap();
    model
}

/// `--strict` was honoured by `run` alone: `check --strict` on a model that warns exited 0, and every
/// other command ignored it. Each refuses the model now, exit 2, writing nothing; `check` after its report.
#[test]
fn strict_is_honoured_by_every_command_that_reads_a_model() {
    let dir = scratch("strict-every-command");
    let model = tie_rod_on_axis(&dir);
    let model = model.to_str().unwrap();
    let vehicle = dir.join("car.json");
    let mut car: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string("examples/vehicle/compact_car.json").unwrap()).unwrap();
    car["front"] = model.into();
    car["rear"] = std::fs::canonicalize("examples/five_link.json").unwrap().to_str().unwrap().into();
    std::fs::write(&vehicle, car.to_string()).unwrap();
    let out = dir.join("out");
    let out = out.to_str().unwrap();
    let rate = "/suspension/macpherson/spring/rate";
    for args in [
        vec!["check", model],
        vec!["expand", model],
        vec!["batch", model, "examples/macpherson_variants.txt", "--out", out],
        vec!["sensitivity", model, "--param", rate, "--out", out],
        vec!["tune", model, "examples/targets/bump_steer.json", "--out", out],
        vec!["tolerance", model, "examples/targets/tolerances.json", "--out", out],
        vec!["compare", "examples/generic/macpherson.json", model, "--out", out],
        vec!["vehicle", vehicle.to_str().unwrap(), "--out", out],
    ] {
        let o = elastokin(&[&args[..], &["--strict"]].concat());
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{}: {err}", args[0]);
        assert!(err.contains("under --strict"), "{}: {err}", args[0]);
        assert!(!Path::new(out).exists(), "{}", args[0]);
        // Without it, `check` reports the model's warning and exits 0.
        if args[0] == "check" {
            let o = elastokin(&args);
            assert!(o.status.success() && String::from_utf8_lossy(&o.stdout).contains("tie-rod-on-steering-axis"));
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A MacPherson tie rod whose inner point sits on the steering axis cannot steer the wheel: `check` and
/// `run` name it; `run --strict` refuses it before solving.
#[test]
fn an_implausible_model_is_named_and_refused_under_strict() {
    let dir = scratch("implausible");
    let model = tie_rod_on_axis(&dir);
    let model = model.to_str().unwrap();
    let o = elastokin(&["check", model]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("warning [tie-rod-on-steering-axis]") && stdout.contains("degrees of freedom"), "{stdout}");
    let out = dir.join("out");
    let o = elastokin(&["run", model, "--analysis", "parallel-travel", "--out", out.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success());
    assert!(
        stdout.contains("warning [tie-rod-on-steering-axis]") && stdout.contains("warning [toe-range]"),
        "{stdout}"
    );
    // The model's warning leads, before the figures it qualifies; the one the run found follows them.
    let at = |what: &str| stdout.find(what).unwrap_or_else(|| panic!("{what} in {stdout}"));
    assert!(at("warning [tie-rod-on-steering-axis]") < at("bump steer"), "{stdout}");
    assert!(at("bump steer") < at("warning [toe-range]"), "{stdout}");
    assert_eq!(stdout.matches("warning [tie-rod-on-steering-axis]").count(), 1, "{stdout}");
    std::fs::remove_dir_all(&out).ok();
    let o = elastokin(&["run", model, "--strict", "--out", out.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("refused under --strict") && err.contains("tie_rod_inner"), "{err}");
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).ok();
}

/// `--compliance` writes the 6×6 at every step; `--png` a PNG beside every SVG; every run a report.html.
#[test]
fn compliance_png_and_report_on_request() {
    let dir = scratch("extras");
    let out = dir.join("out");
    let args = ["run", "examples/generic/double_wishbone.json", "--analysis", "parallel-travel", "--steps", "4"];
    succeeds(&[&args[..], &["--compliance", "--png", "--out", out.to_str().unwrap()]].concat());
    let rows = read_csv(&out.join("parallel_travel_compliance.csv"));
    // One row per step (header and provenance line read off), the load parameter and 36 entries.
    assert_eq!(rows.len(), 5);
    assert_eq!(rows[0].len(), 37);
    for svg in ["parallel_travel_toe_camber", "parallel_travel_wheel_centre"] {
        let png = std::fs::read(out.join(format!("{svg}.png"))).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{svg}");
    }
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(html.starts_with("<!DOCTYPE html>") && html.contains("bump steer") && html.contains("<svg"));
    // A plot found alone says what made it.
    let svg = std::fs::read_to_string(out.join("parallel_travel_toe_camber.svg")).unwrap();
    assert!(
        svg.contains("<!-- elastokin ") && svg.contains("model examples/generic/double_wishbone.json (sha256 "),
        "{svg}"
    );
    // A range that leaves the design position out gives the figures at design all the same.
    let o = elastokin(&[&args[..], &["--range", "0.01,0.05", "--out", out.to_str().unwrap()]].concat());
    let stdout = String::from_utf8_lossy(&o.stdout);
    let line = stdout.lines().find(|l| l.trim_start().starts_with("bump steer")).unwrap();
    assert!(line.ends_with(" -27.600 deg/m"), "{line}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The shipped double wishbone on ideal arm pivots: with the wheel free it carries about 3.3 kN upward at
/// the contact patch, so a vertical force to 6 kN meets a limit point. Returns the model file's path.
fn ideal_pivot_double_wishbone(dir: &Path) -> PathBuf {
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/generic/double_wishbone.json"))
            .unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["suspension"]["double_wishbone"]["upper_arm_mounts"] = "ideal".into();
    v["suspension"]["double_wishbone"]["lower_arm_mounts"] = "ideal".into();
    let model = dir.join("ideal_pivots.json");
    std::fs::write(&model, v.to_string()).unwrap();
    model
}

/// A vertical force beyond what the corner carries: `run` writes the rows up to the limit point and names
/// its load; `run --through-limits` writes the whole path through it; both succeed. The limit load they
/// give is the one the static load case meets walking 3.5 kN onto the corner from its unloaded position
/// (another path, in other steps).
#[test]
fn a_limit_point_is_named_and_through_limits_writes_the_path_past_it() {
    use elastokin::solver::SolverError;
    use elastokin::suspensions::{analysis::static_load_case, Rig, Side, SuspensionFile};
    let dir = scratch("limit-point");
    let model = ideal_pivot_double_wishbone(&dir);
    let file = SuspensionFile::read(&model).unwrap();
    let reached = match static_load_case(file.suspension.build(Side::Left, Rig::Free).unwrap(), 3500.0) {
        Err(SolverError::LimitPoint { reached }) => reached,
        other => panic!("{other:?}"),
    };
    let out = dir.join("out");
    let run = |extra: &[&str]| {
        let mut args = vec!["run", model.to_str().unwrap(), "--analysis", "vertical-force", "--range", "0,6000"];
        args.extend_from_slice(extra);
        args.extend_from_slice(&["--out", out.to_str().unwrap()]);
        elastokin(&args)
    };
    let loads = || -> Vec<f64> {
        read_csv(&out.join("vertical_force.csv")).iter().map(|r| r[0].parse::<f64>().unwrap()).collect()
    };
    let summary = || -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
    };
    // Stopped at the limit point: the 32 steps of 187.5 N below it, then the row at it.
    let o = run(&[]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stopped = loads();
    let below = (reached / 187.5).floor() as usize + 1;
    assert_eq!(stopped.len(), below + 1, "{stopped:?}");
    let fold = stopped[below];
    println!("limit point {fold} N; the static load case's {reached} N");
    // Both located to 1e-6 of their ranges (6e-3 and 3.5e-3 N); measured 4.2e-3 N apart.
    assert!((fold - reached).abs() < 1e-2, "{fold} vs {reached}");
    let line = format!("warning [limit-point]: vertical-force: the suspension gives way at {reached:.2} N");
    assert!(stdout.contains(&line), "{stdout}");
    let codes = summary()["analyses"]["vertical-force"]["warnings"].to_string();
    assert!(codes.contains("limit-point") && codes.contains("--through-limits"), "{codes}");
    // Through it by arc length, steps of 100 N: the same rows up to the last step before it, then the path
    // over the limit load and down until it leaves the range below 0 N.
    let o = run(&["--through-limits", "--arc-step", "100", "--png"]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    for file in ["vertical_force.csv", "vertical_force.svg", "vertical_force.png", "report.html", "summary.json"] {
        assert!(out.join(file).exists(), "{file}");
    }
    let through = loads();
    assert_eq!(through[..below], stopped[..below]);
    assert!(through.len() > below + 5 && through.iter().all(|&f| f <= fold + 1e-6), "{through:?}");
    assert!(*through.last().unwrap() < 0.0, "{through:?}");
    assert!(stdout.contains("until it leaves the range") && stdout.contains("by arc length"), "{stdout}");
    let s = summary();
    assert_eq!(s["settings"]["through_limits"], true);
    assert_eq!(s["settings"]["arc_step"], 100.0);
    let svg = std::fs::read_to_string(out.join("vertical_force.svg")).unwrap();
    assert!(svg.contains("<polyline") && !svg.contains("NaN"));
    let csv = std::fs::read_to_string(out.join("vertical_force.csv")).unwrap();
    assert!(!csv.contains("NaN") && !csv.contains("inf"));
    // Under --strict the limit point is an error, and the results stay as they were.
    let before = snapshot(&out);
    let o = run(&["--strict"]);
    assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("limit-point"));
    assert_eq!(snapshot(&out), before);
    std::fs::remove_dir_all(&dir).ok();
}

/// One failing analysis discarded the whole suite: `run` stopped at the static load case a corner could not
/// carry and wrote nothing of the eight analyses that had run. Now each analysis that ran is written, the
/// failed one is reported with its reason (in summary.json, the report's page and on standard error) and
/// the run exits 1.
#[test]
fn one_failing_analysis_costs_only_itself_the_others_are_written_and_the_run_exits_1() {
    use elastokin::solver::SolverError;
    use elastokin::suspensions::{analysis::static_load_case, Rig, Side, SuspensionFile};
    let dir = scratch("one-fails");
    let model = ideal_pivot_double_wishbone(&dir);
    // A static load of 6 kN on a corner that gives way at about 3.3 kN.
    let mut v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&model).unwrap()).unwrap();
    v["vehicle"]["corner_load"] = 6000.0.into();
    std::fs::write(&model, v.to_string()).unwrap();
    let file = SuspensionFile::read(&model).unwrap();
    let reached = match static_load_case(file.suspension.build(Side::Left, Rig::Free).unwrap(), 6000.0) {
        Err(SolverError::LimitPoint { reached }) => reached,
        other => panic!("{other:?}"),
    };
    let out = dir.join("out");
    let o = elastokin(&["run", model.to_str().unwrap(), "--steps", "8", "--out", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{stderr}");
    let said = format!("static-load: the suspension cannot go beyond {reached:.3}");
    assert!(stderr.contains("1 of the analyses failed") && stderr.contains(&said), "{said}\n{stderr}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["failed"][0]["analysis"], "static-load", "{}", summary["failed"]);
    assert!(summary["failed"][0]["reason"].as_str().unwrap().contains(&said[13..]));
    assert_eq!(summary["failed"].as_array().unwrap().len(), 1);
    let ran: Vec<&String> = summary["analyses"].as_object().unwrap().keys().collect();
    assert_eq!(ran.len(), 8, "{ran:?}");
    assert!(!out.join("static_load.csv").exists());
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    // Skipped: the model's own load case and the wheel envelope (it has neither loads nor packaging).
    assert!(html.contains("8 analyses run, 2 skipped, 1 failed") && html.contains("Analyses that failed"));
    // What was written is what each analysis gives run alone, byte for byte after the provenance line.
    let alone = dir.join("alone");
    for (analysis, csv) in [("parallel-travel", "parallel_travel.csv"), ("aligning-torque", "aligning_torque.csv")] {
        let args = ["run", model.to_str().unwrap(), "--steps", "8", "--analysis", analysis];
        succeeds(&[&args[..], &["--out", alone.to_str().unwrap()]].concat());
        let body = |p: &Path| std::fs::read_to_string(p).unwrap().split_once('\n').unwrap().1.to_string();
        assert_eq!(body(&out.join(csv)), body(&alone.join(csv)), "{csv}");
    }
    // The static load asked for alone fails as it did, and the previous results stay as they were.
    let before = snapshot(&alone);
    let o = elastokin(&["run", model.to_str().unwrap(), "--analysis", "static-load", "--out", alone.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains(&said) && stderr.contains("left untouched"), "{stderr}");
    assert_eq!(snapshot(&alone), before);
    std::fs::remove_dir_all(&dir).ok();
}

/// `sensitivity --figures-only` writes the figures' derivatives `sensitivity` writes, to the digit, and no
/// tables of the rows' derivatives (its replays move only the rows the figures read).
#[test]
fn sensitivity_of_the_figures_alone_writes_the_same_figures() {
    let dir = scratch("sensitivity_figures");
    let run = |name: &str, extra: &[&str]| {
        let out = dir.join(name);
        let mut args = vec![
            "sensitivity",
            "examples/generic/macpherson.json",
            "--param",
            "/suspension/macpherson/hardpoints/top_mount/1",
            "--steps",
            "8",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend(extra);
        succeeds(&args);
        out
    };
    let (whole, alone) = (run("whole", &[]), run("alone", &["--figures-only"]));
    let figures = read_csv(&whole.join("sensitivity.csv"));
    assert!(figures.len() > 50);
    assert_eq!(figures, read_csv(&alone.join("sensitivity.csv")));
    assert!(whole.join("sensitivity_lateral_force.csv").exists());
    assert!(!alone.join("sensitivity_lateral_force.csv").exists());
    std::fs::remove_dir_all(&dir).ok();
}

/// `sensitivity` gives every analysis's figures' derivatives as the command's own reruns give them:
/// `run --analysis NAME` on the model with the inner tie-rod point moved ±0.1 mm and ±0.2 mm, a central
/// difference Richardson extrapolated, for the bump steer and camber gain of parallel travel and the
/// compliance steer and camber of the lateral-force sweep (measured at most 3e-9 relative apart, the CSV
/// holding 12 significant digits; the figure's value is the run's own).
#[test]
fn sensitivity_gives_the_derivatives_that_reruns_of_the_model_give() {
    let dir = scratch("sensitivity");
    let pointer = "/suspension/macpherson/hardpoints/tie_rod_inner/2";
    let out = dir.join("out");
    let o = succeeds(&[
        "sensitivity",
        "examples/generic/macpherson.json",
        "--param",
        pointer,
        "--param",
        "/suspension/macpherson/spring/rate",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    let line = stdout.lines().find(|l| l.starts_with("  bump steer")).unwrap_or_default();
    assert!(line.ends_with(" -32.691 deg/m") && stdout.contains("deg/m per mm"), "{stdout}");
    assert!(stdout.contains("      tie_rod_inner z ") && !stdout.contains("/hardpoints/"), "{stdout}");
    // The page: well formed, a bar chart of each figure's largest effects.
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    roxmltree::Document::parse(html.strip_prefix("<!DOCTYPE html>").unwrap()).unwrap();
    assert!(html.contains("bump steer (toe-in +): -32.691 deg/m") && html.contains("<rect"), "{html}");
    // Its bars name the parameter as an engineer does.
    assert!(html.contains("tie_rod_inner z (per mm)"), "{html}");
    // Every analysis the suite runs on the model, its table's derivatives in a file of its own.
    for table in ["parallel_travel", "roll", "steering", "vertical_force", "lateral_force", "static_load"] {
        assert!(out.join(format!("sensitivity_{table}.csv")).exists(), "{table}");
    }
    let rows = read_csv(&out.join("sensitivity.csv"));
    let row = |analysis: &str, figure: &str, parameter: &str| {
        rows.iter()
            .find(|r| &r[0] == analysis && &r[1] == figure && &r[4] == parameter)
            .unwrap_or_else(|| panic!("{analysis} {figure} {parameter}"))
    };
    let text = std::fs::read_to_string("examples/generic/macpherson.json").unwrap();
    let model: serde_json::Value = serde_json::from_str(&text).unwrap();
    let z = model.pointer(pointer).unwrap().as_f64().unwrap();
    let figure_at = |dz: f64, analysis: &str, key: &str| {
        let mut m = model.clone();
        *m.pointer_mut(pointer).unwrap() = (z + dz).into();
        let path = dir.join("moved.json");
        std::fs::write(&path, m.to_string()).unwrap();
        let run_out = dir.join("run");
        succeeds(&["run", path.to_str().unwrap(), "--analysis", analysis, "--out", run_out.to_str().unwrap()]);
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(run_out.join("summary.json")).unwrap()).unwrap();
        summary["analyses"][analysis]["figures"][key]["value"].as_f64().unwrap()
    };
    let h = 1e-4;
    for (analysis, key, unit) in [
        ("parallel-travel", "bump_steer", "deg/m"),
        ("parallel-travel", "camber_gain", "deg/m"),
        ("lateral-force", "steer", "deg/kN"),
        ("lateral-force", "camber", "deg/kN"),
    ] {
        let [a, b, c, d] = [2.0, 1.0, -1.0, -2.0].map(|m| figure_at(m * h, analysis, key));
        let rerun = (8.0 * (b - c) - (a - d)) / (12.0 * h);
        let r = row(analysis, key, pointer);
        let derivative: f64 = r[6].parse().unwrap();
        println!(
            "{analysis} {key}: {derivative} against reruns {rerun} ({:e} relative)",
            (derivative - rerun).abs() / rerun.abs()
        );
        // Measured: 8.8e-12 to 1.2e-8 relative (the lateral force's steer, where both differences carry
        // their rounding over their steps).
        assert!((derivative - rerun).abs() < 1e-7 * rerun.abs(), "{key}: {derivative} vs {rerun}");
        assert_eq!(r[2].to_string(), unit);
        // Its error estimate: the re-runs' difference lies within it and their own extrapolation's move.
        let error: f64 = r[7].parse().unwrap();
        let re_runs = (rerun - (b - c) / (2.0 * h)).abs();
        println!("{analysis} {key}: ± {error:e}, the re-runs' ± {re_runs:e}");
        assert!((derivative - rerun).abs() <= error + re_runs, "{key}: {derivative} ± {error} vs {rerun} ± {re_runs}");
        assert_eq!(r[9].to_string(), "mm");
        let effect: f64 = r[8].parse().unwrap();
        assert!((effect - derivative * 1e-3).abs() <= 1e-12 * derivative.abs());
        // The figure itself is the run's.
        let value: f64 = r[3].parse().unwrap();
        assert!((value - figure_at(0.0, analysis, key)).abs() < 1e-9, "{key}: {value}");
    }
    // A rate's effect is per percent.
    assert_eq!(row("parallel-travel", "bump_steer", "/suspension/macpherson/spring/rate")[9].to_string(), "%");
    // Bad parameters and settings are refused by name, before anything is written.
    for (args, says) in [
        (vec!["--param", "/suspension/macpherson/hardpoints/nowhere/0"], "names nothing in the model"),
        (vec!["--param", "/suspension/macpherson/spring"], "a section of the model, not a number"),
        (vec![], "no parameters"),
        (vec!["--hardpoints", "--range", "0.01,0.05"], "--range needs --analysis NAME"),
        (vec!["--hardpoints", "--analysis", "roll", "--range", "-1e4,1e4"], "no suspension meets that"),
    ] {
        let o = elastokin(
            &[
                &["sensitivity", "examples/generic/macpherson.json"][..],
                &args[..],
                &["--out", dir.join("bad").to_str().unwrap()],
            ]
            .concat(),
        );
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(!dir.join("bad").exists());
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_arc_step_without_its_flag_analysis_or_length_is_refused_by_name() {
    let m = "examples/generic/double_wishbone.json";
    let one = ["run", m, "--analysis", "vertical-force"];
    for (args, says) in [
        (vec!["--arc-step", "100"], "--through-limits"),
        (vec!["--through-limits", "--arc-step", "-5"], "not a positive number"),
        (vec!["--through-limits", "--arc-step", "nan"], "not a positive number"),
        (vec!["--through-limits", "--arc-step", "0"], "not a positive number"),
    ] {
        let o = elastokin(&[&one[..], &args[..]].concat());
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says) && err.contains("--arc-step"), "{args:?}: {err}");
    }
    let o = elastokin(&["run", m, "--through-limits", "--arc-step", "100"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("--arc-step needs --analysis"), "{err}");
}

/// `expand` prints the model in the general form: it reads back, and runs to the same CSV, byte for byte
/// after the provenance line.
#[test]
fn expand_prints_a_general_model_that_runs_the_same() {
    let dir = scratch("expand");
    for model in ["examples/generic/macpherson.json", "examples/generic/double_wishbone.json"] {
        let o = succeeds(&["expand", model]);
        let text = String::from_utf8(o.stdout).unwrap();
        assert!(text.contains("\"general\"") && text.contains("\"corner\""), "{text}");
        let expanded = dir.join("expanded.json");
        std::fs::write(&expanded, &text).unwrap();
        let csv = |path: &str, out: &str| {
            let out = dir.join(out);
            succeeds(&["run", path, "--analysis", "lateral-force", "--steps", "4", "--out", out.to_str().unwrap()]);
            let text = std::fs::read_to_string(out.join("lateral_force.csv")).unwrap();
            text.lines().skip(1).map(str::to_string).collect::<Vec<_>>()
        };
        assert_eq!(csv(model, "template"), csv(expanded.to_str().unwrap(), "general"), "{model}");
    }
}

/// A Project Chrono suspension file: `import chrono` writes the general model (the notes on standard
/// error), and `run` takes the Chrono file directly, saying so on its first line; a template it does not
/// read is refused by name, at its key.
#[test]
fn a_chrono_file_is_imported_and_run_directly() {
    let file = "tests/data/chrono/DoubleWishbone.json";
    let o = succeeds(&["import", "chrono", file]);
    let model = String::from_utf8(o.stdout).unwrap();
    assert!(model.contains("\"general\"") && model.contains("Project Chrono DoubleWishbone"), "{model}");
    let notes = String::from_utf8(o.stderr).unwrap();
    assert!(notes.contains("note: Shock: a damper, left out") && notes.contains("loaded tyre radius"), "{notes}");
    let dir = scratch("chrono");
    let o = succeeds(&[
        "run",
        file,
        "--analysis",
        "parallel-travel",
        "--steps",
        "4",
        "--out",
        dir.join("out").to_str().unwrap(),
    ]);
    let stdout = String::from_utf8(o.stdout).unwrap();
    assert!(
        stdout.lines().next().unwrap().starts_with("read as a Project Chrono DoubleWishbone suspension"),
        "{stdout}"
    );
    let o = elastokin(&["check", "tests/data/chrono/RigidSuspension.json"]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8(o.stderr).unwrap();
    assert!(e.contains("RigidSuspension.json:4:3") && e.contains("it has no suspension motion to analyse"), "{e}");
}

/// `batch` on a Project Chrono file: the variants edit Chrono's own keys. On the generic double wishbone,
/// whose linkage is ideal and whose only elastic part is the spring (its push at design, k (L₀ − L), is in
/// proportion to its rate too), the wheel rate is in proportion to the spring rate.
#[test]
fn batch_varies_a_chrono_file_by_its_own_keys() {
    let dir = scratch("chrono-batch");
    let variants = dir.join("variants.txt");
    std::fs::write(&variants, "soft: /Spring/Spring Coefficient=200000\nstiff: /Spring/Spring Coefficient=500000\n")
        .unwrap();
    let out = dir.join("out");
    succeeds(&[
        "batch",
        "tests/data/chrono/DoubleWishbone.json",
        variants.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let csv = read_csv(&out.join("batch.csv"));
    let rate = |name: &str| csv.iter().find(|r| &r[0] == name).unwrap()[3].parse::<f64>().unwrap();
    // Measured: 0.4 to the CSV's 12 digits.
    assert!((rate("soft") / rate("stiff") - 0.4).abs() < 1e-10, "{} {}", rate("soft"), rate("stiff"));
}

/// Runs `batch --shard I/N` of the MacPherson variants for every I into `dir/NAME-I`; returns the
/// directories.
fn run_shards(dir: &Path, name: &str, model: &str, variants: &str, n: usize) -> Vec<PathBuf> {
    (1..=n)
        .map(|i| {
            let out = dir.join(format!("{name}-{i}"));
            succeeds(&["batch", model, variants, "--shard", &format!("{i}/{n}"), "--out", out.to_str().unwrap()]);
            out
        })
        .collect()
}

/// `batch --shard I/N` for every I and `merge` give the single batch's table: the same rows byte for byte,
/// whichever order the shards are given in, and with more shards than variants too.
#[test]
fn shards_merge_into_the_single_batch() {
    let dir = scratch("shards");
    let (m, v) = ("examples/generic/macpherson.json", "examples/generic/macpherson_variants.txt");
    let single = dir.join("single");
    succeeds(&["batch", m, v, "--out", single.to_str().unwrap()]);
    let single_text = std::fs::read_to_string(single.join("batch.csv")).unwrap();
    let (single_first, single_rows) = single_text.split_once('\n').unwrap();
    let single_records = read_csv(&single.join("batch.csv"));
    let total = single_records.len();
    assert!(total >= 3, "the example needs variants for three shards");
    let three = run_shards(&dir, "three", m, v, 3);
    // Each shard: the single batch's first line with its part, and its block of the single batch's rows,
    // each with its place in the variants file.
    let mut numbers = Vec::new();
    for (i, shard) in three.iter().enumerate() {
        let text = std::fs::read_to_string(shard.join("batch.csv")).unwrap();
        assert_eq!(text.lines().next().unwrap(), format!("{single_first}, shard {}/3 of {total} variants", i + 1));
        assert!(text.lines().nth(1).unwrap().ends_with(",error,variant_number"), "{text}");
        for row in read_csv(&shard.join("batch.csv")) {
            let k: usize = row[5].parse().unwrap();
            // Variant k (counting from 1) belongs to shard ⌊(k−1)·N/V⌋ + 1, as --help says.
            assert_eq!((k - 1) * 3 / total, i, "variant {k} in shard {}", i + 1);
            assert_eq!(row.iter().take(5).collect::<Vec<_>>(), single_records[k - 1].iter().collect::<Vec<_>>());
            numbers.push(k);
        }
    }
    assert_eq!(numbers, (1..=total).collect::<Vec<_>>());
    let expected = format!("{single_first}, merged from 3 shards\n{single_rows}");
    let merge = |shards: Vec<PathBuf>, out: &Path| {
        let mut args = vec!["merge".to_string(), "--out".into(), out.display().to_string()];
        args.extend(shards.iter().map(|s| s.display().to_string()));
        succeeds(&args.iter().map(String::as_str).collect::<Vec<_>>());
        std::fs::read_to_string(out.join("batch.csv")).unwrap()
    };
    // In order, shuffled, as files or as their directories: the same bytes.
    let file = |k: usize| three[k].join("batch.csv");
    for (n, shards) in [
        vec![file(0), file(1), file(2)],
        vec![file(2), file(0), file(1)],
        vec![three[1].clone(), file(2), three[0].clone()],
    ]
    .into_iter()
    .enumerate()
    {
        assert_eq!(merge(shards, &dir.join(format!("merged-{n}"))), expected);
    }
    // More shards than variants: the surplus shards are empty, and still merge into the same rows.
    let n = total + 2;
    let many = run_shards(&dir, "many", m, v, n);
    let empty = many.iter().filter(|s| read_csv(&s.join("batch.csv")).is_empty()).count();
    assert_eq!(empty, 2);
    let mut shuffled = many.clone();
    shuffled.reverse();
    assert_eq!(
        merge(shuffled, &dir.join("merged-many")),
        format!("{single_first}, merged from {n} shards\n{single_rows}")
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_shard_that_is_not_i_of_n_is_refused_by_name() {
    let dir = scratch("bad-shard");
    let out = dir.join("out");
    for bad in ["0/3", "4/3", "1/0", "abc"] {
        let o = elastokin(&[
            "batch",
            "examples/generic/macpherson.json",
            "examples/generic/macpherson_variants.txt",
            "--shard",
            bad,
            "--out",
            out.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{bad}: {err}");
        assert!(err.contains("--shard") && err.contains(bad) && err.contains("I/N with 1 ≤ I ≤ N"), "{bad}: {err}");
        assert!(!out.exists());
    }
    let o = elastokin(&["batch", "--help"]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("SLURM_ARRAY_TASK_ID"));
    std::fs::remove_dir_all(&dir).ok();
}

/// Shards that do not make one whole batch, or whose figures are not numbers, are refused with exit status
/// 2, naming the file and what to give instead, and the previous merge is left as it was.
#[test]
fn merge_refuses_shards_that_do_not_make_one_batch() {
    let dir = scratch("merge-refusals");
    let (m, v) = ("examples/generic/macpherson.json", "examples/generic/macpherson_variants.txt");
    let shards = run_shards(&dir, "good", m, v, 3);
    let file = |k: usize| shards[k].join("batch.csv").display().to_string();
    // The same model and variants with one more byte each: other files by their hash.
    let other_model = dir.join("other-model.json");
    std::fs::write(&other_model, std::fs::read_to_string(m).unwrap() + "\n").unwrap();
    let other_variants = dir.join("other-variants.txt");
    std::fs::write(&other_variants, std::fs::read_to_string(v).unwrap() + "\n").unwrap();
    let of_model = run_shards(&dir, "model", other_model.to_str().unwrap(), v, 3)[1].join("batch.csv");
    let of_variants = run_shards(&dir, "variants", m, other_variants.to_str().unwrap(), 3)[1].join("batch.csv");
    let of_two = run_shards(&dir, "two", m, v, 2)[1].join("batch.csv");
    let single = dir.join("single");
    succeeds(&["batch", m, v, "--out", single.to_str().unwrap()]);
    // A shard with its last row lost.
    let cut = dir.join("cut.csv");
    let text = std::fs::read_to_string(file(1)).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    std::fs::write(&cut, lines[..lines.len() - 1].join("\n") + "\n").unwrap();
    // A first line that claims a vast number of shards (its one row the one such a shard holds).
    let vast = dir.join("vast.csv");
    let first = std::fs::read_to_string(file(0)).unwrap();
    let first: Vec<&str> = first.lines().collect();
    let claim = first[0].replace("shard 1/3 of", "shard 1/1000000000000 of");
    std::fs::write(&vast, [claim.as_str(), first[1], first[2]].join("\n") + "\n").unwrap();
    // A shard whose first row's first figure holds what no batch writes (merge copied them before): each
    // refused naming the shard, the row and the column.
    let (head, body) = text.split_once('\n').unwrap();
    let mut reader = csv::ReaderBuilder::new().from_reader(body.as_bytes());
    let header = reader.headers().unwrap().clone();
    let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    let figure = header.get(1).unwrap().to_string();
    let not_numbers: Vec<PathBuf> = ["inf", "NaN", "abc", "1e999", "0x10", "1\u{0}2"]
        .iter()
        .enumerate()
        .map(|(n, bad)| {
            let mut writer = csv::Writer::from_writer(Vec::new());
            writer.write_record(&header).unwrap();
            for (k, row) in rows.iter().enumerate() {
                writer
                    .write_record(row.iter().enumerate().map(|(c, x)| if k == 0 && c == 1 { *bad } else { x }))
                    .unwrap();
            }
            let shard = dir.join(format!("not-a-number-{n}.csv"));
            std::fs::write(&shard, format!("{head}\n{}", String::from_utf8(writer.into_inner().unwrap()).unwrap()))
                .unwrap();
            shard
        })
        .collect();
    let out = dir.join("merged");
    succeeds(&["merge", "--out", out.to_str().unwrap(), &file(0), &file(1), &file(2)]);
    let before = snapshot(&out);
    let show = |p: &Path| p.display().to_string();
    let missing = dir.join("no-such-shard.csv");
    let mut cases: Vec<(Vec<String>, Vec<String>)> = not_numbers
        .iter()
        .map(|bad| {
            let says = ["row 1", figure.as_str(), "not a finite number"].map(String::from);
            (vec![file(0), show(bad), file(2)], [vec![show(bad)], says.to_vec()].concat())
        })
        .collect();
    cases.extend(vec![
        (vec![file(0), file(2)], vec!["shard 2 of 3 missing".into(), "--shard 2/3".into()]),
        (vec![file(0)], vec!["shards 2, 3 of 3 missing".into()]),
        (vec![file(0), file(1), file(2), file(1)], vec!["shard 2/3 is given twice".into(), file(1)]),
        (vec![file(0), show(&of_model), file(2)], vec!["a shard of model".into(), show(&of_model), show(&other_model)]),
        (
            vec![file(0), show(&of_variants), file(2)],
            vec!["a shard of variants file".into(), show(&of_variants), show(&other_variants)],
        ),
        (vec![file(0), show(&of_two), file(2)], vec!["is shard 2/2".into(), show(&of_two)]),
        (
            vec![file(0), file(1), file(2), show(&single.join("batch.csv"))],
            vec!["is not a shard of a batch".into(), show(&single.join("batch.csv")), "--shard I/N".into()],
        ),
        (vec![file(0), m.into(), file(2)], vec!["is not a shard of a batch".into(), m.into()]),
        (vec![file(0), show(&cut), file(2)], vec!["run that shard again".into(), show(&cut)]),
        (vec![show(&vast)], vec!["shards 2, 3, 4,".into(), "(999999999999 in all)".into()]),
        (vec![file(0), file(1), show(&missing)], vec!["cannot open it".into(), show(&missing)]),
        (vec![file(0), file(1), show(&dir)], vec!["cannot open it".into(), show(&dir.join("batch.csv"))]),
    ]);
    for (shards, expected) in cases {
        let mut args = vec!["merge", "--out", out.to_str().unwrap()];
        args.extend(shards.iter().map(String::as_str));
        let o = elastokin(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{shards:?}: {err}");
        // What a shard held is shown escaped: no NUL reaches the terminal.
        assert!(!err.contains('\0'), "{shards:?}: {err}");
        for e in &expected {
            assert!(err.contains(e.as_str()), "{shards:?}: '{e}' not in {err}");
        }
        assert_eq!(snapshot(&out), before, "{shards:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A model name of 21 000 characters, markup and an unterminated right-to-left override among them (as
/// pasted from elsewhere), hung the run: the plots' subtitle was shortened one character at a time, each
/// candidate measured whole. It is now shown shortened (the plots' subtitles, the page's title and
/// heading), without bidirectional controls, in valid SVG and HTML, and kept whole where it is data (the
/// model as run in the page, `summary.json`).
#[test]
fn a_long_model_name_with_markup_and_bidi_controls_is_shown_shortened_and_kept_whole() {
    let out = scratch("long-name");
    let mut model: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string("examples/generic/macpherson.json").unwrap()).unwrap();
    let name = "<&>\u{202e}xxxxxxxxxx".repeat(1500);
    model["name"] = name.clone().into();
    let file = out.join("long_name.json");
    std::fs::write(&file, model.to_string()).unwrap();
    let results = out.join("results");
    let args = ["run", file.to_str().unwrap(), "--analysis", "parallel-travel", "--out", results.to_str().unwrap()];
    let o = elastokin_within(&args, Duration::from_secs(120));
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    // Every drawn text: valid SVG, short, no bidirectional control.
    for svg in ["parallel_travel_toe_camber.svg", "parallel_travel_wheel_centre.svg"] {
        let text = std::fs::read_to_string(results.join(svg)).unwrap();
        let doc = roxmltree::Document::parse(&text).unwrap_or_else(|e| panic!("{svg}: {e}"));
        for t in doc.descendants().filter_map(|n| n.text()) {
            assert!(t.chars().count() <= 200 && !t.contains('\u{202e}'), "{svg}: {} characters", t.chars().count());
        }
    }
    // The page: well formed; its title and heading shortened to 120 characters and an ellipsis; the name
    // whole once, in the model as run.
    let html = std::fs::read_to_string(results.join("report.html")).unwrap();
    let body = html.strip_prefix("<!DOCTYPE html>").unwrap();
    let doc = roxmltree::Document::parse(body).unwrap_or_else(|e| panic!("report.html: {e}"));
    let shown = format!("K&C report: {}…", "<&>xxxxxxxxxx".repeat(10).chars().take(120).collect::<String>());
    for tag in ["title", "h1"] {
        let node = doc.descendants().find(|n| n.has_tag_name(tag)).unwrap();
        let text: String = node.descendants().filter(|n| n.is_text()).filter_map(|n| n.text()).collect();
        assert_eq!(text, shown, "{tag}");
    }
    assert_eq!(html.matches(&*html_escape::encode_text(&name)).count(), 1);
    // summary.json: whole.
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(results.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["model"], name.as_str());
    std::fs::remove_dir_all(&out).ok();
}

/// A run stopped by Ctrl-C or SIGTERM left `.<out>.tmp-PID` beside the results, and every later run left
/// it there. The next run of the same `--out` now removes such a directory when its process is gone and it
/// holds only what the command writes; another run's (its process alive) and somebody's (anything else in
/// it) are kept.
#[test]
fn an_interrupted_run_s_staging_directory_is_removed_by_the_next_run_and_no_one_else_s() {
    if !Path::new("/proc/self").exists() {
        return; // Whether a process is gone is read from /proc.
    }
    let dir = scratch("stale");
    // Process ids that no process has: above the kernel's limit.
    let limit: u64 = std::fs::read_to_string("/proc/sys/kernel/pid_max").unwrap().trim().parse().unwrap();
    let (gone, also_gone) = (limit + 1, limit + 2);
    let stale = dir.join(format!(".out.tmp-{gone}"));
    let stale_old = dir.join(format!(".out.old-{also_gone}"));
    let alive = dir.join(format!(".out.tmp-{}", std::process::id()));
    let somebody = dir.join(format!(".out.tmp-{}", limit + 3));
    let other_out = dir.join(format!(".other.tmp-{}", limit + 4));
    for d in [&stale, &stale_old, &alive, &somebody, &other_out] {
        std::fs::create_dir_all(d).unwrap();
        std::fs::write(d.join("parallel_travel.csv"), "# elastokin 0.1.0, model m.json\ntravel_m\n0\n").unwrap();
        std::fs::write(d.join("parallel_travel.svg"), "<svg/>").unwrap();
    }
    std::fs::write(somebody.join("notes.txt"), "mine").unwrap();
    let out = dir.join("out");
    succeeds(&[
        "run",
        "examples/generic/macpherson.json",
        "--analysis",
        "parallel-travel",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(out.join("summary.json").exists());
    assert!(!stale.exists() && !stale_old.exists(), "an interrupted run's staging is left");
    assert!(alive.exists(), "a running process's staging was removed");
    assert!(somebody.join("notes.txt").exists(), "a directory holding something else was removed");
    assert!(other_out.exists(), "another --out's staging was removed");
    std::fs::remove_dir_all(&dir).ok();
}

/// `tune` on the shipped targets example meets them: tuned.json is the model with the free numbers moved
/// (every other key as it was, in its order) and gives the tuned figures when run; tune.csv lists the
/// iterations; report.html is well formed. Bad targets (a pointer that names nothing, a figure the
/// analysis has not) are refused by key with exit 2, nothing written;
/// targets not met exit 1 with their reasons, the results written.
#[test]
fn tune_meets_the_shipped_targets_and_says_why_when_it_cannot() {
    let dir = scratch("tune");
    let out = dir.join("out");
    let o = succeeds(&[
        "tune",
        "examples/generic/macpherson.json",
        "examples/targets/bump_steer.json",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("met: targets[0] (parallel-travel/bump_steer)") && !stdout.contains("NOT met"), "{stdout}");
    let tuned: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("tuned.json")).unwrap()).unwrap();
    let base: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string("examples/generic/macpherson.json").unwrap()).unwrap();
    let targets: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string("examples/targets/bump_steer.json").unwrap()).unwrap();
    // Only the free numbers moved, each within its bounds; the keys in the model file's order.
    let mut back = tuned.clone();
    for (pointer, bounds) in targets["free"].as_object().unwrap() {
        let v = tuned.pointer(pointer).unwrap().as_f64().unwrap();
        assert!(v >= bounds[0].as_f64().unwrap() && v <= bounds[1].as_f64().unwrap(), "{pointer}: {v}");
        *back.pointer_mut(pointer).unwrap() = base.pointer(pointer).unwrap().clone();
    }
    assert_eq!(back, base);
    let order =
        |v: &serde_json::Value| v["suspension"]["macpherson"].as_object().unwrap().keys().cloned().collect::<Vec<_>>();
    assert_eq!(order(&tuned), order(&base));
    // The tuned model, run, has the bump steer the tune reached.
    // Judged against the same targets, the tuned model meets each of them, as the tune said.
    let run_out = dir.join("run");
    let o = succeeds(&[
        "run",
        out.join("tuned.json").to_str().unwrap(),
        "--analysis",
        "parallel-travel",
        "--targets",
        "examples/targets/bump_steer.json",
        "--out",
        run_out.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("met: targets[0] (parallel-travel/bump_steer)") && !stdout.contains("NOT"), "{stdout}");
    let judged = read_csv(&run_out.join("targets.csv"));
    assert_eq!(judged.len(), 4, "a figure, a curve's two points and a constraint");
    assert!(judged.iter().all(|r| &r[7] == "1"), "{judged:?}");
    let html = std::fs::read_to_string(run_out.join("report.html")).unwrap();
    assert!(html.contains("every target met"));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(run_out.join("summary.json")).unwrap()).unwrap();
    let bump_steer = summary["analyses"]["parallel-travel"]["figures"]["bump_steer"]["value"].as_f64().unwrap();
    let residuals = read_csv(&out.join("tune_targets.csv"));
    let reached: f64 = residuals.iter().find(|r| r[0].contains("bump_steer")).unwrap()[4].parse().unwrap();
    assert!((bump_steer - reached).abs() < 1e-9 && (bump_steer + 2.0).abs() < 0.25, "{bump_steer} {reached}");
    let judged_bump_steer: f64 = judged[0][6].parse().unwrap();
    assert!((judged_bump_steer - reached).abs() < 1e-9, "{judged_bump_steer} {reached}");
    // The model before the tune misses them: exit 1, each miss named, the results written.
    let o = elastokin(&[
        "run",
        "examples/generic/macpherson.json",
        "--analysis",
        "parallel-travel",
        "--targets",
        "examples/targets/bump_steer.json",
        "--out",
        dir.join("before").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("3 target points and packaging constraints not met") && err.contains("NOT met: targets[0]"));
    assert!(dir.join("before/targets.csv").exists());
    let iterations = read_csv(&out.join("tune.csv"));
    assert_eq!(&iterations[0][6], "start");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    roxmltree::Document::parse(html.strip_prefix("<!DOCTYPE html>").unwrap()).unwrap();
    assert!(html.contains("Before and after") && html.contains("<td>tie_rod_inner z</td><td>mm</td>"));
    // Bad targets: refused by key, nothing written.
    let bad = dir.join("bad.json");
    std::fs::write(&bad, r#"{"free": {"/suspension/macpherson/hardpoints/nowhere/0": [0, 1]}, "targets": []}"#)
        .unwrap();
    let o = elastokin(&[
        "tune",
        "examples/generic/macpherson.json",
        bad.to_str().unwrap(),
        "--out",
        dir.join("x").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("names nothing in the model"));
    assert!(!dir.join("x").exists());
    // A figure the analysis has not, known only once it runs: bad input too (it exited 1 as a failed run).
    let unknown = dir.join("unknown.json");
    let text =
        std::fs::read_to_string("examples/targets/bump_steer.json").unwrap().replace("/bump_steer", "/bump_stear");
    std::fs::write(&unknown, text).unwrap();
    let o = elastokin(&[
        "tune",
        "examples/generic/macpherson.json",
        unknown.to_str().unwrap(),
        "--out",
        dir.join("u").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("has no figure 'bump_stear'"), "{err}");
    assert!(!dir.join("u").exists());
    // Targets that cannot be met: exit 1, why, and the results written.
    let hard = dir.join("hard.json");
    let text = std::fs::read_to_string("examples/targets/bump_steer.json")
        .unwrap()
        .replace("\"value\": -2.0", "\"value\": 40.0");
    std::fs::write(&hard, text).unwrap();
    let o = elastokin(&[
        "tune",
        "examples/generic/macpherson.json",
        hard.to_str().unwrap(),
        "--out",
        dir.join("y").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("targets and packaging constraints not met") && err.contains("bump_steer"), "{err}");
    assert!(dir.join("y").join("tuned.json").exists());
    std::fs::remove_dir_all(&dir).ok();
}

/// The tolerance's Monte Carlo run through `batch --analyses`: its samples (drawn by the library as the
/// stack-up draws them) written as a variants file, every figure of parallel travel and the static load of
/// every variant in batch_figures.csv. Each figure's spread over the variants is the stack-up's own Monte
/// Carlo's (the same models through another path: measured at most 2.7e-10 apart, the CSVs' digits) and its
/// first order's within the sampling's error (a σ from 40 samples is known to 11 %: allowed four of those,
/// measured at most 20 % apart over the 29 figures the tolerances move).
#[test]
fn a_monte_carlo_through_batch_gives_the_tolerance_spreads_of_every_figure() {
    use elastokin::suspensions::design::tolerance::read_tolerances;
    use elastokin::suspensions::design::Parameters;
    use elastokin::suspensions::study::batch::base_document;
    let dir = scratch("tolerance-batch");
    let model = "examples/macpherson.json";
    let tolerances = r#"{"hardpoints": 0.001, "tolerances": {"/suspension/macpherson/spring/rate": {"normal": "3%"}},
                         "analyses": ["parallel-travel", "static-load"], "steps": 8}"#;
    let file = dir.join("tolerances.json");
    std::fs::write(&file, tolerances).unwrap();
    let (n, seed) = (40, 2);
    let doc = base_document(&std::fs::read_to_string(model).unwrap(), model).unwrap();
    let t = read_tolerances(tolerances, "t", &doc).unwrap();
    let p = Parameters::new(&doc, &t.pointers).unwrap();
    let variants: String = (0..n)
        .map(|i| {
            let x = t.sample(&p.values, seed, i);
            let edits: Vec<String> = t.pointers.iter().zip(&x).map(|(q, v)| format!("{q}={v:e}")).collect();
            format!("sample {i}: {}\n", edits.join("; "))
        })
        .collect();
    let variants_file = dir.join("variants.txt");
    std::fs::write(&variants_file, variants).unwrap();
    let (batch, stack) = (dir.join("batch"), dir.join("stack"));
    let path = |p: &Path| p.to_str().unwrap().to_string();
    succeeds(&[
        "batch",
        model,
        &path(&variants_file),
        "--analyses",
        "parallel-travel,static-load",
        "--quiet",
        "--out",
        &path(&batch),
    ]);
    let mc = n.to_string();
    succeeds(&["tolerance", model, &path(&file), "--monte-carlo", &mc, "--seed", "2", "--out", &path(&stack)]);
    let text = std::fs::read_to_string(batch.join("batch_figures.csv")).unwrap();
    let header: Vec<String> = text.lines().nth(1).unwrap().split(',').map(String::from).collect();
    let rows = read_csv(&batch.join("batch_figures.csv"));
    assert_eq!(rows.len(), n);
    let standard_error = 1.0 / (2.0 * (n as f64 - 1.0)).sqrt();
    let (mut compared, mut worst_same, mut worst_first) = (0, 0.0_f64, 0.0_f64);
    for r in read_csv(&stack.join("tolerance.csv")) {
        let column = format!("{}/{} ({})", &r[0], &r[1], &r[2]);
        let k = header.iter().position(|h| *h == column).unwrap_or_else(|| panic!("{column} not in {header:?}"));
        let (sigma, sampled): (f64, f64) = (r[5].parse().unwrap(), r[6].parse().unwrap());
        let value: f64 = r[3].parse().unwrap();
        // A figure the tolerances do not move (the corner load, a ratio fixed by the rig) spreads by rounding.
        if sigma <= 1e-6 * value.abs().max(1.0) {
            continue;
        }
        let v: Vec<f64> = rows.iter().map(|row| row[k].parse::<f64>().unwrap()).collect();
        let mean = v.iter().sum::<f64>() / n as f64;
        let spread = (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n as f64 - 1.0)).sqrt();
        worst_same = worst_same.max((spread / sampled - 1.0).abs());
        worst_first = worst_first.max((spread / sigma - 1.0).abs());
        compared += 1;
    }
    assert!(compared >= 20, "{compared}");
    assert!(worst_same < 1e-8, "{worst_same}");
    assert!(worst_first < 4.0 * standard_error, "{worst_first}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `batch --analyses all` runs the whole suite on every variant: batch_figures.csv holds a column for each
/// figure of every analysis the model takes, each variant's row its own; with `--shard` (whose shards
/// `merge` joins by batch.csv alone) it is refused, exit 2.
#[test]
fn batch_through_the_whole_suite_writes_every_figure_and_is_no_shard() {
    let dir = scratch("batch-suite");
    let out = dir.join("out");
    let model = "examples/generic/macpherson.json";
    let variants = "examples/generic/macpherson_variants.txt";
    succeeds(&["batch", model, variants, "--analyses", "all", "--quiet", "--out", out.to_str().unwrap()]);
    let text = std::fs::read_to_string(out.join("batch_figures.csv")).unwrap();
    let header: Vec<&str> = text.lines().nth(1).unwrap().split(',').collect();
    for column in ["parallel-travel/bump_steer (deg/m)", "roll/roll_centre_height (mm)", "static-load/toe (deg)"] {
        assert!(header.contains(&column), "{column} not in {header:?}");
    }
    let rows = read_csv(&out.join("batch_figures.csv"));
    assert_eq!(rows.len(), read_csv(&out.join("batch.csv")).len());
    // The bump steer of batch.csv's own sweep is the suite's, to the digit: both read it off the design
    // equilibrium, whatever the sweep's range and steps.
    let batch = read_csv(&out.join("batch.csv"));
    let k = header.iter().position(|h| *h == "parallel-travel/bump_steer (deg/m)").unwrap();
    for (a, b) in batch.iter().zip(&rows) {
        assert_eq!(&a[1], &b[k]);
    }
    let o =
        elastokin(&["batch", model, variants, "--analyses", "all", "--shard", "1/2", "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--shard"));
    std::fs::remove_dir_all(&dir).ok();
}

/// `tolerance` with a normal band, a group, an alignment and a limit: every output carries them —
/// tolerance.csv the limit and the share outside, tolerance_adjustments.csv the number set, each sample of
/// tolerance_samples.csv the figure held at its nominal value (within 1e-6 of its σ before alignment; the
/// printed values to their ten significant digits), the report its alignment and the share outside.
#[test]
fn tolerance_writes_groups_alignment_and_limits_in_every_output() {
    let dir = scratch("tolerance-aligned");
    let file = dir.join("tolerances.json");
    std::fs::write(
        &file,
        r#"{"tolerances": {"/suspension/twist_beam/toe": {"normal": 0.05}},
            "groups": [{"name": "axle", "points": ["pivot", "junction"], "shift": {"z": 0.001}}],
            "adjust": [{"figure": "static-load/toe", "by": "/suspension/twist_beam/toe"}],
            "limits": {"static-load/camber": [-1.2, null]},
            "analyses": ["static-load"], "steps": 8}"#,
    )
    .unwrap();
    let out = dir.join("out");
    let args = ["tolerance", "examples/twist_beam_template.json", file.to_str().unwrap(), "--monte-carlo", "6"];
    let o = succeeds(&[&args[..], &["--out", out.to_str().unwrap()]].concat());
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("outside its limit:") && stdout.contains("set at alignment by"), "{stdout}");
    let header = |p: &Path| std::fs::read_to_string(p).unwrap().lines().nth(1).unwrap().to_string();
    assert!(header(&out.join("tolerance.csv")).contains("limit_min,limit_max,outside,sampled_outside"));
    let rows = read_csv(&out.join("tolerance.csv"));
    let camber = rows.iter().find(|r| &r[1] == "camber").unwrap();
    assert_eq!(&camber[11], "-1.2");
    let toe = rows.iter().find(|r| &r[1] == "toe").unwrap();
    let nominal: f64 = toe[3].parse().unwrap();
    let adjustments = read_csv(&out.join("tolerance_adjustments.csv"));
    assert_eq!((adjustments.len(), &adjustments[0][2]), (1, "/suspension/twist_beam/toe"));
    let samples_header = header(&out.join("tolerance_samples.csv"));
    let column = samples_header.split(',').position(|c| c == "static-load/toe (deg)").unwrap();
    let samples = read_csv(&out.join("tolerance_samples.csv"));
    assert_eq!(samples.len(), 6);
    for r in &samples {
        let v: f64 = r[column].parse().unwrap();
        assert!((v - nominal).abs() < 1e-6, "{v} {nominal}");
    }
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    roxmltree::Document::parse(html.strip_prefix("<!DOCTYPE html>").unwrap()).unwrap();
    assert!(html.contains("Set at alignment") && html.contains("outside its limit"));
    std::fs::remove_dir_all(&dir).ok();
}

/// `tolerance` on the shipped tolerances example: tolerance.csv holds each figure's first-order worst case
/// and σ with the Monte Carlo's beside them (the same seed, the same samples: the file again byte for
/// byte after the provenance line), the contributions sum to the worst case, report.html is well formed;
/// a bad file is refused by key with exit 2.
#[test]
fn tolerance_stacks_up_the_shipped_example_and_checks_it_by_sampling() {
    let dir = scratch("tolerance");
    let run = |out: &str| {
        let out = dir.join(out);
        let args = [
            "tolerance",
            "examples/generic/macpherson.json",
            "examples/targets/tolerances.json",
            "--monte-carlo",
            "60",
        ];
        succeeds(&[&args[..], &["--seed", "3", "--out", out.to_str().unwrap()]].concat());
        out
    };
    let (a, b) = (run("a"), run("b"));
    let body = |p: &Path| std::fs::read_to_string(p).unwrap().lines().skip(1).collect::<Vec<_>>().join("\n");
    assert_eq!(body(&a.join("tolerance.csv")), body(&b.join("tolerance.csv")));
    let rows = read_csv(&a.join("tolerance.csv"));
    let bump = rows.iter().find(|r| &r[1] == "bump_steer").unwrap();
    let (worst, sigma, sampled): (f64, f64, f64) =
        (bump[4].parse().unwrap(), bump[5].parse().unwrap(), bump[6].parse().unwrap());
    // 60 samples know a σ to 1/√118, 9 %: allowed five of those (the accuracy itself is
    // crates/suspensions/tests/tolerance.rs's).
    assert!(worst > sigma && sigma > 0.0 && (sampled / sigma - 1.0).abs() < 0.46, "{worst} {sigma} {sampled}");
    // Independent of the sensitivities: no sampled model's bump steer leaves the first-order worst case
    // (but for the second order, 5 % allowed; measured: less than half of it, -1.62 and +1.57 deg/m about
    // -32.69 against ±3.42 with 400 samples).
    let (value, low, high): (f64, f64, f64) =
        (bump[3].parse().unwrap(), bump[8].parse().unwrap(), bump[9].parse().unwrap());
    assert!(value - low <= 1.05 * worst && high - value <= 1.05 * worst, "{low}..{high} about {value} ±{worst}");
    let contributions = read_csv(&a.join("tolerance_contributions.csv"));
    let sum: f64 = contributions
        .iter()
        .filter(|r| &r[1] == "bump_steer" && &r[0] == "parallel-travel" && &r[2] == "deg/m")
        .map(|r| r[6].parse::<f64>().unwrap().abs())
        .sum();
    assert!((sum - worst).abs() <= 1e-9 * worst, "{sum} {worst}");
    let html = std::fs::read_to_string(a.join("report.html")).unwrap();
    roxmltree::Document::parse(html.strip_prefix("<!DOCTYPE html>").unwrap()).unwrap();
    assert!(html.contains("The largest contributors") && html.contains("<rect"));
    // The samples' histogram, one per figure sampled.
    assert_eq!(html.matches("60 samples</text>").count(), rows.len());
    assert_eq!(read_csv(&a.join("tolerance_samples.csv")).len(), 60);
    let bad = dir.join("bad.json");
    std::fs::write(&bad, r#"{"tolerances": {"/suspension/macpherson/spring/rate": "lots"}}"#).unwrap();
    let o = elastokin(&[
        "tolerance",
        "examples/generic/macpherson.json",
        bad.to_str().unwrap(),
        "--out",
        dir.join("x").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("tolerances[\"/suspension/macpherson/spring/rate\"]"));
    assert!(!dir.join("x").exists());
    std::fs::remove_dir_all(&dir).ok();
}

/// `run --sensitivity`: the report gains a section of each figure's largest effects, and the run writes
/// the same sensitivity.csv as `sensitivity --hardpoints` for the same analysis, byte for byte after the
/// provenance line.
#[test]
fn run_with_sensitivity_adds_the_sensitivity_command_s_numbers_to_the_report() {
    let dir = scratch("run-sensitivity");
    let (run, alone) = (dir.join("run"), dir.join("alone"));
    let model = "examples/generic/macpherson.json";
    succeeds(&["run", model, "--analysis", "parallel-travel", "--sensitivity", "--out", run.to_str().unwrap()]);
    succeeds(&[
        "sensitivity",
        model,
        "--hardpoints",
        "--analysis",
        "parallel-travel",
        "--out",
        alone.to_str().unwrap(),
    ]);
    let body = |p: &Path| std::fs::read_to_string(p).unwrap().lines().skip(1).collect::<Vec<_>>().join("\n");
    for file in ["sensitivity.csv", "sensitivity_parallel_travel.csv"] {
        assert_eq!(body(&run.join(file)), body(&alone.join(file)), "{file}");
    }
    let html = std::fs::read_to_string(run.join("report.html")).unwrap();
    roxmltree::Document::parse(html.strip_prefix("<!DOCTYPE html>").unwrap()).unwrap();
    assert!(html.contains("<h2>Sensitivities</h2>") && html.contains("tie_rod_inner z (per mm)"));
    std::fs::remove_dir_all(&dir).ok();
}

/// `compare`: two models and a measured file written from one of them; the figures' differences are the
/// models' own `run` figures subtracted; what cannot be compared exits 2 naming it, writing nothing.
#[test]
fn compare_overlays_two_models_and_a_measured_file_and_refuses_a_mixed_pair() {
    let dir = scratch("compare");
    let rig = dir.join("rig.csv");
    std::fs::write(&rig, "# analysis: parallel-travel\ntravel_m,toe_deg\n-0.05,1.1\n0,0\n0.05,-1.3\n").unwrap();
    let out = dir.join("out");
    let models = ["examples/generic/macpherson.json", "examples/generic/double_wishbone.json"];
    succeeds(&["compare", models[0], models[1], rig.to_str().unwrap(), "--steps", "8", "--out", out.to_str().unwrap()]);
    let rows = read_csv(&out.join("compare.csv"));
    // Each model's own figures, from `run`.
    let run_figure = |model: &str, key: &str| -> f64 {
        let o = dir.join(format!("run-{}", model.replace('/', "_")));
        if !o.exists() {
            succeeds(&["run", model, "--steps", "8", "--quiet", "--out", o.to_str().unwrap()]);
        }
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(o.join("summary.json")).unwrap()).unwrap();
        summary["analyses"]["parallel-travel"]["figures"][key]["value"].as_f64().unwrap()
    };
    for key in ["bump_steer", "camber_gain", "wheel_rate"] {
        let row = rows.iter().find(|r| &r[0] == "parallel-travel" && &r[1] == key).unwrap();
        let (a, b, d): (f64, f64, f64) = (row[3].parse().unwrap(), row[5].parse().unwrap(), row[7].parse().unwrap());
        // The CSV holds 12 significant digits, summary.json all of them: 1e-11 relative (measured 8e-14).
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-11 * x.abs().max(y.abs());
        assert!(close(a, run_figure(models[0], key)), "{key}");
        assert!(close(b, run_figure(models[1], key)), "{key}");
        assert!((d - (b - a)).abs() <= 2e-11 * a.abs().max(b.abs()), "{key}: {d} against {b} − {a}");
    }
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    roxmltree::Document::parse(html.strip_prefix("<!DOCTYPE html>").unwrap()).unwrap();
    assert!(html.contains("rig.csv") && html.contains("id=\"overlay-front\""));
    // The page's table names each figure in words; compare.csv keeps the keys (read above).
    assert!(html.contains("<td>bump steer (toe-in +)</td>") && !html.contains("<td>bump_steer</td>"), "{html}");
    // Each value at its figure's decimals (bump steer's three), its estimate on hover.
    let bump_steer = format!("{:.3}</td>", run_figure(models[0], "bump_steer"));
    assert!(html.contains(&bump_steer), "{bump_steer}");
    // Two designs of one name (a copy, as a tuned model keeps its parent's name) are told apart by file.
    let copy = dir.join("copy.json");
    std::fs::copy(models[0], &copy).unwrap();
    let twins = dir.join("twins");
    succeeds(&[
        "compare",
        models[0],
        copy.to_str().unwrap(),
        "--analysis",
        "parallel-travel",
        "--steps",
        "4",
        "--out",
        twins.to_str().unwrap(),
    ]);
    let header = std::fs::read_to_string(twins.join("compare.csv")).unwrap();
    assert!(header.contains(&format!("{}: ", models[0])) && header.contains("copy.json: "), "{header}");
    assert!(!header.contains(" (2)"), "{header}");

    let o =
        elastokin(&["compare", models[0], "examples/four_link_axle.json", "--out", dir.join("x").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("solid axle"), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(!dir.join("x").exists());
    let o = elastokin(&["compare", models[0], "--out", dir.join("x").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    std::fs::remove_dir_all(&dir).ok();
}

/// `vehicle` on the shipped car: vehicle.csv holds the library's budget, its terms summing to the
/// gradient; a vehicle file with a value out of range, or front and rear swapped, exits 2 naming the key.
#[test]
fn vehicle_gives_the_shipped_cars_budget_and_refuses_a_car_that_cannot_be_by_key() {
    let dir = scratch("vehicle");
    let out = dir.join("out");
    let o =
        elastokin(&["vehicle", "examples/vehicle/compact_car.json", "--steps", "8", "--out", out.to_str().unwrap()]);
    assert!(o.status.success());
    // The rear's ideal links give no compliance steer: its terms print 0, not the rounding (6e-30 deg/g)
    // that the sums leave, and every other term prints its digits.
    let stdout = String::from_utf8_lossy(&o.stdout);
    let terms: Vec<&str> = stdout.lines().filter(|l| l.starts_with("    ") && l.ends_with(" deg/g")).collect();
    assert_eq!(terms.len(), 12, "{stdout}");
    let compliance_rear = |l: &&&str| l.contains("compliance") && l.contains(" rear ");
    assert!(terms.iter().filter(compliance_rear).all(|l| l.split_whitespace().rev().nth(1) == Some("0")), "{stdout}");
    assert!(
        terms.iter().filter(|l| !compliance_rear(l)).all(|l| l.split_whitespace().rev().nth(1) != Some("0")),
        "{stdout}"
    );
    let rows = read_csv(&out.join("vehicle.csv"));
    let value = |what: &str, axle: &str| -> f64 {
        rows.iter().find(|r| &r[0] == what && &r[1] == axle).unwrap_or_else(|| panic!("{what}"))[2].parse().unwrap()
    };
    let terms: f64 = rows.iter().filter(|r| &r[1] != "car").map(|r| r[2].parse::<f64>().unwrap()).sum();
    let gradient = value("understeer gradient", "car");
    // Twelve terms, each written to 12 significant digits: measured 2e-12 deg/g apart.
    assert!((terms - gradient).abs() < 1e-10, "{terms} against {gradient}");
    assert!((value("at the steering wheel", "car") - 15.5 * gradient).abs() < 1e-9);
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    roxmltree::Document::parse(html.strip_prefix("<!DOCTYPE html>").unwrap()).unwrap();
    assert!(html.contains("Understeer budget") && html.contains("<rect"));

    let car = std::fs::read_to_string("examples/vehicle/compact_car.json").unwrap();
    for (edit, said) in [
        (car.replace("\"mass\": 1413", "\"mass\": 0"), "car.mass"),
        (
            car.replace("front_macpherson_with_bar.json", "SWAP")
                .replace("../five_link.json", "front_macpherson_with_bar.json")
                .replace("SWAP", "../five_link.json"),
            "vehicle.axle",
        ),
    ] {
        let bad = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("examples/vehicle")
            .join(format!("bad-{}.json", std::process::id()));
        std::fs::write(&bad, edit).unwrap();
        let o = elastokin(&["vehicle", bad.to_str().unwrap(), "--out", dir.join("x").to_str().unwrap()]);
        std::fs::remove_file(&bad).ok();
        assert_eq!(o.status.code(), Some(2), "{said}");
        assert!(String::from_utf8_lossy(&o.stderr).contains(said), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(!dir.join("x").exists());
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `run --units`: the rig's units in summary.json's figures and settings and on the terminal, the same
/// numbers as the default's times the factor.
#[test]
fn run_writes_bump_steer_in_the_units_asked_for() {
    let dir = scratch("units");
    let figure = |units: &str| -> (serde_json::Value, String) {
        let out = dir.join(units);
        let o = elastokin(&[
            "run",
            "examples/macpherson.json",
            "--analysis",
            "parallel-travel",
            "--units",
            units,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
        assert_eq!(summary["settings"]["units"], units);
        (
            summary["analyses"]["parallel-travel"]["figures"]["bump_steer"].clone(),
            String::from_utf8_lossy(&o.stdout).into(),
        )
    };
    let (si, _) = figure("deg-per-m");
    let (rig, printed) = figure("deg-per-10mm");
    assert_eq!((si["unit"].as_str(), rig["unit"].as_str()), (Some("deg/m"), Some("deg/10 mm")));
    // Both written from the value held in SI: the same to the rounding of the factor's last bit.
    let (rig, si) = (rig["value"].as_f64().unwrap(), si["value"].as_f64().unwrap());
    assert!((rig - si * 1e-2).abs() <= 4.0 * f64::EPSILON * rig.abs(), "{rig} against {si}");
    assert!(printed.contains("deg/10 mm"), "{printed}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A model named with ESC, NUL, BEL, VT, DEL, U+FFFE or U+2028 made every SVG ill-formed XML and put raw
/// ESC into report.html and the terminal (which it recoloured). Such a name is refused, naming the key
/// and the character as its escape; a measured file whose own name holds one is compared, its name
/// written as the escape in the terminal, the SVGs (well-formed) and the page.
#[test]
fn control_characters_in_names_never_reach_a_terminal_svg_or_page_raw() {
    let dir = std::env::temp_dir().join(format!("elastokin-control-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let base: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string("examples/macpherson.json").unwrap()).unwrap();
    let raw = |bytes: &[u8]| bytes.iter().any(|&b| b == 0x1b || b == 0 || b == 7 || b == 0x0b || b == 0x7f);
    for c in ['\u{1b}', '\0', '\u{7}', '\u{b}', '\u{7f}', '\u{fffe}', '\u{2028}'] {
        let mut doc = base.clone();
        doc["name"] = format!("Mac{c}Pherson").into();
        let model = dir.join("named.json");
        std::fs::write(&model, serde_json::to_string_pretty(&doc).unwrap()).unwrap();
        let o = elastokin(&["run", model.to_str().unwrap(), "--out", dir.join("o").to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{c:?}: {err}");
        let escape = c.escape_unicode().to_string();
        assert!(err.contains(&format!("name: \"Mac{escape}Pherson\" holds the character U+")), "{c:?}: {err}");
        assert!(!raw(&o.stderr) && !err.contains(c), "{c:?}: {err}");
        assert!(!dir.join("o").exists());
    }
    // A measured file's name is the user's text too.
    let rig = dir.join("rig\u{1b}[31m.csv");
    std::fs::write(&rig, "# analysis: parallel-travel\ntravel_m,toe_deg\n-0.05,0.8\n0,0\n0.05,-0.9\n").unwrap();
    let out = dir.join("c");
    let o = succeeds(&[
        "compare",
        "examples/macpherson.json",
        rig.to_str().unwrap(),
        "--analysis",
        "parallel-travel",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!raw(&o.stdout) && !raw(&o.stderr), "{}", String::from_utf8_lossy(&o.stdout));
    let mut shown = false;
    for entry in std::fs::read_dir(&out).unwrap() {
        let path = entry.unwrap().path();
        let bytes = std::fs::read(&path).unwrap();
        assert!(!raw(&bytes), "{}", path.display());
        let text = String::from_utf8(bytes).unwrap();
        shown |= text.contains("rig\\u{1b}[31m.csv");
        if path.extension().is_some_and(|e| e == "svg") {
            roxmltree::Document::parse(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        }
    }
    assert!(shown, "the measured file's name written as its escape");
    std::fs::remove_dir_all(&dir).ok();
}

/// `--loaded-radius nan` on import was blamed on line 63 of the Chrono file; a `range` inside a TARGETS file
/// that no analysis can walk exited 1 (a failed run) where the same `--range` exits 2. Each is refused as
/// the bad input it is, naming the flag or the target.
#[test]
fn bad_numbers_given_beside_a_file_are_refused_as_what_the_user_gave() {
    let chrono = "tests/data/chrono/DoubleWishbone.json";
    for radius in ["nan", "-0.3", "50", "inf"] {
        let o = elastokin(&["import", "chrono", chrono, "--loaded-radius", radius]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{radius}: {err}");
        assert!(
            err.contains(&format!("'{radius}' is not a loaded tyre radius: give metres from 0.05 to 2"))
                && !err.contains(":63:"),
            "{radius}: {err}"
        );
    }
    let dir = scratch("bad-target-range");
    let targets = dir.join("targets.json");
    let text = r#"{"free": {"/suspension/macpherson/hardpoints/tie_rod_inner/2": [-0.1, -0.02]},
        "targets": [{"figure": "parallel-travel/bump_steer", "value": -2.0, "tolerance": 0.25, "range": [0.01, 0.01]}]}"#;
    std::fs::write(&targets, text).unwrap();
    let o = elastokin(&[
        "tune",
        "examples/generic/macpherson.json",
        targets.to_str().unwrap(),
        "--out",
        dir.join("o").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("targets[0] (parallel-travel/bump_steer): range: the range needs two finite ends"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `--strict` promises that every warning is an error: a warning of the results (the toe beyond ±10° over
/// ±200 mm of travel) refused `run` alone; `compare`, `sensitivity` and `tune` wrote their results. Each
/// refuses them now, writing nothing, and writes them without `--strict`.
#[test]
fn strict_refuses_results_an_analysis_warned_of_in_every_command() {
    let dir = scratch("strict-results");
    let model = "examples/generic/macpherson.json";
    let targets = dir.join("targets.json");
    std::fs::write(
        &targets,
        r#"{"free": {"/suspension/macpherson/hardpoints/tie_rod_inner/2": [-0.1, -0.02]},
            "targets": [{"figure": "parallel-travel/bump_steer", "value": -2.0, "tolerance": 0.25, "range": [-0.2, 0.2]}]}"#,
    )
    .unwrap();
    let wide = ["--analysis", "parallel-travel", "--range=-0.2,0.2"];
    let commands: [Vec<&str>; 4] = [
        [&["run", model][..], &wide[..]].concat(),
        [&["compare", model, model][..], &wide[..]].concat(),
        [&["sensitivity", model, "--param", "/suspension/macpherson/spring/rate"][..], &wide[..]].concat(),
        vec!["tune", model, targets.to_str().unwrap()],
    ];
    for (k, command) in commands.iter().enumerate() {
        let out = dir.join(format!("o{k}"));
        let mut args = command.clone();
        args.extend(["--out", out.to_str().unwrap()]);
        // Written whole (the tune, whose target the bound holds from, exits 1 having written).
        let o = elastokin(&args);
        assert!(out.join("report.html").exists(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
        std::fs::remove_dir_all(&out).unwrap();
        let strict = [&["--strict"][..], &args[..]].concat();
        let o = elastokin(&strict);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{strict:?}: {err}");
        assert!(err.contains("warning(s) under --strict: toe-range"), "{strict:?}: {err}");
        assert!(!out.exists(), "{strict:?} wrote {}", out.display());
    }
    // A stack-up of a model whose toe passes 10° over the default travel (its tie rod's inner point 120 mm
    // low): said without --strict, refused with it.
    let mut steer: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(model).unwrap()).unwrap();
    let z = &mut steer["suspension"]["macpherson"]["hardpoints"]["tie_rod_inner"][2];
    *z = serde_json::json!(z.as_f64().unwrap() - 0.12);
    let steer_model = dir.join("steer.json");
    std::fs::write(&steer_model, steer.to_string()).unwrap();
    let tolerances = dir.join("tolerances.json");
    std::fs::write(&tolerances, r#"{"hardpoints": 0.001, "analyses": ["parallel-travel"]}"#).unwrap();
    let out = dir.join("stack");
    let args =
        ["tolerance", steer_model.to_str().unwrap(), tolerances.to_str().unwrap(), "--out", out.to_str().unwrap()];
    let o = succeeds(&args);
    assert!(
        String::from_utf8_lossy(&o.stdout).contains("warning [toe-range]"),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    std::fs::remove_dir_all(&out).unwrap();
    let o = elastokin(&[&["--strict"][..], &args[..]].concat());
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("warning(s) under --strict: toe-range"), "{err}");
    assert!(!out.exists(), "tolerance --strict wrote {}", out.display());
    std::fs::remove_dir_all(&dir).ok();
}

/// Ctrl-C or SIGTERM while a command ran left `.NAME.tmp-PID/` with partial files beside `--out` (the next
/// run cleaned it up): an interrupted command removes it, leaves the previous results as they were, and
/// exits 130 saying so.
#[test]
fn an_interrupted_command_leaves_nothing_beside_its_out() {
    let dir = scratch("interrupted");
    let out = dir.join("out");
    let variants = dir.join("variants.txt");
    // The previous results: a batch of two.
    std::fs::write(&variants, "a: /suspension/macpherson/spring/rate=2e4\nb: /suspension/macpherson/spring/rate=3e4")
        .unwrap();
    succeeds(&[
        "batch",
        "examples/generic/macpherson.json",
        variants.to_str().unwrap(),
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    let previous = std::fs::read_to_string(out.join("batch.csv")).unwrap();
    let lines: Vec<String> =
        (0..4000).map(|k| format!("v{k}: /suspension/macpherson/spring/rate={}", 2e4 + k as f64)).collect();
    std::fs::write(&variants, lines.join("\n")).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_elastokin"))
        .args(["batch", "examples/generic/macpherson.json", variants.to_str().unwrap(), "--quiet"])
        .args(["--out", out.to_str().unwrap()])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let staging = dir.join(format!(".out.tmp-{}", child.id()));
    let started = std::time::Instant::now();
    while !staging.exists() && started.elapsed() < Duration::from_secs(60) && child.try_wait().unwrap().is_none() {
        std::thread::sleep(Duration::from_millis(2));
    }
    assert!(staging.exists(), "the batch made no staging directory: {:?}", child.wait_with_output());
    Command::new("kill").args(["-TERM", &child.id().to_string()]).status().unwrap();
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(130), "{err}");
    assert!(err.contains("interrupted: nothing written"), "{err}");
    let beside: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".out."))
        .collect();
    assert!(beside.is_empty(), "{beside:?}");
    assert_eq!(std::fs::read_to_string(out.join("batch.csv")).unwrap(), previous);
    std::fs::remove_dir_all(&dir).ok();
}

/// `run --targets` with a curve measured by its root mean square: the target judged whole, one line with
/// its measure in words, one row in the report's summary; `targets.csv` lists every reading (its three
/// points, of which design is a row, and the 18 other rows between its ends at 20 steps over ±50 mm),
/// each met with it. A tolerance a
/// hundredth of the measure is not met, and exits 1 naming it.
#[test]
fn run_judges_a_curve_by_its_root_mean_square_in_one_line() {
    let dir = scratch("rms-targets");
    for (tolerance, met) in [(10.0, true), (1e-4, false)] {
        let targets = dir.join(format!("rms-{met}.json"));
        let text = serde_json::json!({ "targets": [
            { "curve": "parallel-travel/toe_deg", "points": [[-0.05, 0.3], [0.0, 0.0], [0.05, -0.2]],
              "measure": "rms", "tolerance": tolerance } ]});
        std::fs::write(&targets, text.to_string()).unwrap();
        let out = dir.join(format!("out-{met}"));
        let o = elastokin(&[
            "run",
            "examples/generic/macpherson.json",
            "--analysis",
            "parallel-travel",
            "--range=-0.05,0.05",
            "--steps",
            "20",
            "--targets",
            targets.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        let (stdout, stderr) = (String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
        let said = "targets[0] (parallel-travel/toe_deg): root mean square of the miss over the curve's span";
        assert_eq!(stdout.matches("targets[0]").count(), 1, "{stdout}");
        if met {
            assert!(o.status.success() && stdout.contains(&format!("met: {said}")), "{stdout}{stderr}");
        } else {
            assert_eq!(o.status.code(), Some(1), "{stderr}");
            assert!(stderr.contains(&format!("NOT met: {said}")), "{stderr}");
        }
        let judged = read_csv(&out.join("targets.csv"));
        assert_eq!(judged.len(), 21, "{judged:?}");
        assert!(judged.iter().all(|r| &r[7] == if met { "1" } else { "0" }), "{judged:?}");
        let html = std::fs::read_to_string(out.join("report.html")).unwrap();
        assert_eq!(html.matches("root mean square of the miss over the curve").count(), 1);
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `tune` with an objective: the figure before and after and what holds it, in the terminal and the
/// report; no uncertainty for an optimum, which is no fit; each target kept as a bound.
#[test]
fn tune_with_an_objective_says_the_figure_and_what_holds_it() {
    let dir = scratch("objective");
    let targets = dir.join("objective.json");
    let text = serde_json::json!({
        "free": { "/suspension/macpherson/hardpoints/tie_rod_inner/2": [-0.099, -0.019],
                  "/suspension/macpherson/hardpoints/lower_arm_front/2": [-0.196, -0.116] },
        "objective": { "most": "parallel-travel/bump_steer" },
        "targets": [ { "figure": "parallel-travel/camber_gain", "value": -15.059, "tolerance": 0.5 } ],
        "steps": 20 });
    std::fs::write(&targets, text.to_string()).unwrap();
    let out = dir.join("out");
    let o = succeeds(&[
        "tune",
        "examples/generic/macpherson.json",
        targets.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    let said = stdout.lines().find(|l| l.contains("objective (most parallel-travel/bump_steer): -32.69 ->")).unwrap();
    assert!(said.contains("at the lower end of its tolerance"), "{stdout}");
    assert!(stdout.contains("met: targets[0] (parallel-travel/camber_gain)") && !stdout.contains("±"), "{stdout}");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(html.contains("objective (most parallel-travel/bump_steer)") && html.contains("no uncertainty"));
    let uncertainty = read_csv(&out.join("tune_uncertainty.csv"));
    assert!(uncertainty.iter().all(|r| r[2].is_empty()), "{uncertainty:?}");
    std::fs::remove_dir_all(&dir).ok();
}
