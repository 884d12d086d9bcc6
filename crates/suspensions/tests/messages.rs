//! What the solver says about a broken corner is in the model's words: the part's name and what to change,
//! never the library's type names or matrix numbering.

use elastokin_core::{BodyRef, JointSpec};
use elastokin_solver::{Mode, SolverOptions, StaticSolver};
use elastokin_suspensions::analysis::parallel_wheel_travel;
use elastokin_suspensions::{Corner, Rig, Side, SuspensionFile};
use serde_json::Value;
use std::path::Path;

/// The shipped MacPherson with ideal mounts, edited by `edit`, built on `rig`.
fn ideal_macpherson(rig: Rig, edit: impl FnOnce(&mut Value)) -> (SuspensionFile, Corner) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/generic/macpherson.json");
    let mut v: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let t = &mut v["suspension"]["macpherson"];
    t["lower_arm_mounts"] = "ideal".into();
    t["top_mount"] = "ideal".into();
    edit(t);
    let file: SuspensionFile = serde_json::from_value(v).unwrap();
    let corner = file.suspension.build(Side::Left, rig).unwrap();
    (file, corner)
}

fn point(t: &Value, name: &str) -> [f64; 3] {
    [0, 1, 2].map(|i| t["hardpoints"][name][i].as_f64().unwrap())
}

/// No type or function names of the code (`Rig::Free`, `StaticSolver::…`) nor matrix numbering.
fn assert_plain(message: &str) {
    for code in ["::", "original numbering", "FactorReport", "StaticSolver", "Δπ", "body dof"] {
        assert!(!message.contains(code), "'{code}' in: {message}");
    }
}

#[test]
fn an_arm_spinning_freely_is_named_with_what_to_check() {
    // The lower arm's hinge line through its ball joint: nothing holds the arm's spin about that line.
    let (_, corner) = ideal_macpherson(Rig::WheelTravel, |t| {
        let (front, ball) = (point(t, "lower_arm_front"), point(t, "lower_ball_joint"));
        t["hardpoints"]["lower_arm_rear"] = serde_json::json!([0, 1, 2].map(|i| (front[i] + ball[i]) / 2.0));
    });
    let message = StaticSolver::new(&corner.model, SolverOptions::default()).unwrap_err().to_string();
    assert!(message.starts_with("'lower arm' is free to move (rotation about the axis"), "{message}");
    assert!(message.contains("check the hardpoints of its mounts"), "{message}");
    assert_plain(&message);
}

#[test]
fn a_travel_the_mechanism_cannot_reach_says_to_narrow_the_range() {
    // 0.6 m of bump travel is beyond what arms of 0.3–0.4 m reach: the walk from design meets the limit.
    let (_, corner) = ideal_macpherson(Rig::WheelTravel, |_| {});
    let message = parallel_wheel_travel(&corner, 0.0, 0.6, 8, Mode::Corrected).unwrap_err().to_string();
    assert!(message.contains("narrow the range"), "{message}");
    assert_plain(&message);
}

/// A tie rod whose line meets the steering axis cannot hold the wheel's steer: refused when the corner is
/// built, naming the hardpoints and what to move.
#[test]
fn a_tie_rod_through_the_steering_axis_is_refused_by_name() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/generic/macpherson.json");
    let mut v: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let t = &mut v["suspension"]["macpherson"];
    let (a, b) = (point(t, "lower_ball_joint"), point(t, "top_mount"));
    t["hardpoints"]["tie_rod_inner"] = serde_json::json!([0, 1, 2].map(|i| a[i] + 0.4 * (b[i] - a[i])));
    let file: SuspensionFile = serde_json::from_value(v).unwrap();
    let message = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap_err().to_string();
    assert!(message.contains("tie_rod_inner") && message.contains("steering axis"), "{message}");
    assert_plain(&message);
}

#[test]
fn a_repeated_joint_is_named_with_what_to_do() {
    let (file, mut corner) = ideal_macpherson(Rig::WheelTravel, |_| {});
    let h = file.suspension.hardpoints();
    let at = |n: &str| h.iter().find(|(k, _)| k == n).unwrap().1;
    let upright = corner.model.body_id("upright").unwrap();
    let second =
        JointSpec::distance("second tie rod", BodyRef::Ground, upright, at("tie_rod_inner"), at("tie_rod_outer"));
    corner.model.add_joint(second).unwrap();
    let solver = StaticSolver::new(&corner.model, SolverOptions::default()).unwrap();
    let messages = solver.diagnostics().messages();
    assert_eq!(messages.len(), 1, "{messages:?}");
    assert!(messages[0].starts_with("joint '"), "{}", messages[0]);
    assert!(messages[0].contains("tie rod' repeats what other joints already hold"), "{}", messages[0]);
    assert!(messages[0].contains("remove it"), "{}", messages[0]);
    assert_plain(&messages[0]);
}

#[test]
fn an_analysis_on_the_wrong_rig_says_how_the_wheel_must_be_held() {
    let (file, _) = ideal_macpherson(Rig::Free, |_| {});
    let corner = file.suspension.build(Side::Left, Rig::Free).unwrap();
    let message = parallel_wheel_travel(&corner, -0.01, 0.01, 2, Mode::Corrected).unwrap_err().to_string();
    assert!(message.contains("with the wheel-centre height driven, but it is held with the wheel free"), "{message}");
    assert_plain(&message);
}

#[test]
fn every_solver_failure_reads_without_the_librarys_words() {
    use elastokin_solver::kkt::FactorError;
    use elastokin_solver::SolverError;
    let failures = [
        SolverError::LimitPoint { reached: 0.0065 },
        SolverError::NoConvergence {
            t: 0.05,
            last_converged: Some(0.04),
            iterations: 30,
            force_residual: 1.0,
            constraint_residual: 1e-9,
        },
        SolverError::Factor(FactorError::Singular { kind: "body coordinate", index: 7 }),
        SolverError::Factor(FactorError::NonFiniteSolution { index: 7 }),
        SolverError::Factor(FactorError::NotFactorized),
        SolverError::Singular { part: "'upright', its rotation about x".into() },
        SolverError::NonFiniteSolution { part: "joint 'ball' row 'x'".into() },
        SolverError::NonFiniteForce { element: "front spring".into(), t: 0.03 },
    ];
    for failure in failures {
        let message = failure.to_string();
        assert_plain(&message);
        assert!(!message.contains("load parameter") && !message.contains("factorize()"), "{message}");
    }
}

/// `static-load` with a range walked nothing of it, and summary.json's settings claimed the range: the
/// range is refused, saying why. Every analysis's load parameter reads after "in the" (the static load's
/// said "in the the model file's").
#[test]
fn static_load_refuses_a_range_it_would_ignore_and_every_parameter_reads_in_a_sentence() {
    use elastokin_suspensions::kc::{self, Analysis, Settings};
    let settings = Settings { range: Some((0.0, 1000.0)), ..Settings::default() };
    let e = kc::check_settings(Analysis::StaticLoad, &settings).unwrap_err().to_string();
    assert!(e.contains("with no range to walk: leave the range out"), "{e}");
    assert!(kc::check_settings(Analysis::StaticLoad, &Settings::default()).is_ok());
    for a in kc::ALL {
        assert!(!a.parameter().starts_with("the "), "{}: {}", a.name(), a.parameter());
    }
    let e = kc::check_settings(Analysis::ModelLoads, &Settings { range: Some((0.0, 0.0)), ..settings }).unwrap_err();
    assert!(e.to_string().contains("apart in the fraction of the model file's loads"), "{e}");
}

/// A travel range in millimetres (`--range -100,100` for ±100 mm) is refused before solving, saying the range
/// is in metres and what it is in metres; a range no unit makes a suspension's, or a force, gets no such guess.
#[test]
fn a_travel_range_in_millimetres_is_named_before_solving() {
    use elastokin_suspensions::kc::{self, Analysis, Settings};
    let check =
        |a: Analysis, range: (f64, f64)| kc::check_settings(a, &Settings { range: Some(range), ..Settings::default() });
    for a in [Analysis::ParallelTravel, Analysis::Roll, Analysis::Steering] {
        let e = check(a, (-100.0, 100.0)).unwrap_err().to_string();
        assert!(e.contains("millimetres? in metres that is --range -0.1,0.1"), "{}: {e}", a.name());
        assert!(check(a, (-0.1, 0.1)).is_ok());
    }
    let e = check(Analysis::ParallelTravel, (-5000.0, 5000.0)).unwrap_err().to_string();
    assert!(e.contains("reaches beyond 1 in the") && !e.contains("millimetres"), "{e}");
    assert!(check(Analysis::Road(elastokin_suspensions::analysis::WheelLoad::Lateral), (-3000.0, 3000.0)).is_ok());
}

/// An unrestrained corner's condition printed as "condition at design: inf": it says what that means.
#[test]
fn an_infinite_condition_is_said_in_words() {
    use elastokin_suspensions::check::ModelCheck;
    let check = ModelCheck {
        degrees_of_freedom: 1,
        degrees_of_freedom_on_rig: 0,
        redundant_rows: 0,
        condition_estimate: Some(f64::INFINITY),
        warnings: Vec::new(),
    };
    let lines = check.report();
    assert_eq!(lines[1], "condition at design: infinite: some motion is held by nothing (see the warnings)");
    assert!(lines.iter().all(|l| !l.contains("inf ") && !l.ends_with("inf")), "{lines:?}");
}

/// Numbers a user gave, written back in a message: 1e308 was written with 309 digits, 1e-300 with 300
/// zeros, 1.5 as "1.5e0" and a range as "from 1e0 to 1e6 kg". They read as people write them.
#[test]
fn numbers_in_messages_are_written_as_people_write_them() {
    use elastokin_suspensions::kc::{self, plain, Analysis, Settings};
    for (v, written) in [
        (1.5, "1.5"),
        (0.02, "0.02"),
        (40000.0, "40000"),
        (0.0, "0"),
        (1e6, "1e6"),
        (1e308, "1e308"),
        (-1e-300, "-1e-300"),
        (2.5e-7, "2.5e-7"),
        (f64::NAN, "not a finite number"),
    ] {
        assert_eq!(plain(v), written);
    }
    let e = kc::check_settings(Analysis::ParallelTravel, &Settings { arc_step: Some(-1.5), ..Settings::default() })
        .unwrap_err()
        .to_string();
    assert!(e.ends_with("got -1.5"), "{e}");
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/generic/macpherson.json");
    let mut v: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    v["suspension"]["macpherson"]["spring"]["rate"] = 1e308.into();
    let e = SuspensionFile::from_json(&v.to_string(), "m.json").unwrap_err().to_string();
    assert!(e.contains("spring.rate: 1e308 N/m is outside"), "{e}");
    assert!(!e.contains("00000") && !e.contains("e0,") && !e.ends_with("e0"), "{e}");
}
