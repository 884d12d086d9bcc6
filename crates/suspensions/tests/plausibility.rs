//! Plausibility checks: the shipped examples pass clean, and each kind of nonsense a new user wrote gives
//! its own named warning, naming the hardpoints to change.

use elastokin_suspensions::{check_model, ModelCheck, SuspensionFile};
use serde_json::Value;
use std::path::Path;

fn example(name: &str) -> Value {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(name);
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The template object (`suspension.macpherson` or `suspension.double_wishbone`).
fn template(v: &mut Value) -> &mut Value {
    v["suspension"].as_object_mut().unwrap().values_mut().next().unwrap()
}

fn hardpoint(v: &mut Value, name: &str) -> [f64; 3] {
    let p = &template(v)["hardpoints"][name];
    [0, 1, 2].map(|i| p[i].as_f64().unwrap())
}

fn set_hardpoint(v: &mut Value, name: &str, p: [f64; 3]) {
    template(v)["hardpoints"][name] = serde_json::json!(p);
}

/// Every hardpoint passed through `f`.
fn map_hardpoints(v: &mut Value, f: impl Fn([f64; 3]) -> [f64; 3]) {
    let names: Vec<String> = template(v)["hardpoints"].as_object().unwrap().keys().cloned().collect();
    for name in names {
        let p = hardpoint(v, &name);
        set_hardpoint(v, &name, f(p));
    }
}

fn ideal(mut v: Value) -> Value {
    for key in ["lower_arm_mounts", "upper_arm_mounts", "top_mount"] {
        if template(&mut v).get(key).is_some() {
            template(&mut v)[key] = Value::from("ideal");
        }
    }
    v
}

/// Checks a model as the library sees it: deserialised without the file reader's range checks, so the
/// warnings are reached even for coordinates the reader refuses.
fn check(v: &Value) -> ModelCheck {
    let file: SuspensionFile = serde_json::from_value(v.clone()).unwrap();
    check_model(&file).unwrap()
}

fn codes(c: &ModelCheck) -> Vec<&'static str> {
    c.warnings.iter().map(|w| w.code).collect()
}

fn lerp(a: [f64; 3], b: [f64; 3], s: f64) -> [f64; 3] {
    [0, 1, 2].map(|i| a[i] + s * (b[i] - a[i]))
}

/// A point 3 mm ahead of the line from `a` to `b`, 40 % of the way along: a tie-rod point that leaves the
/// tie rod a lever of millimetres about that steering axis (exactly on it the model is refused as
/// degenerate; see `corner::check_steering_arm`).
fn near_axis(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    let p = lerp(a, b, 0.4);
    [p[0] + 0.003, p[1], p[2]]
}

const EXAMPLES: [&str; 2] = ["generic/macpherson.json", "generic/double_wishbone.json"];

#[test]
fn shipped_examples_give_no_warnings() {
    for name in EXAMPLES {
        for v in [example(name), ideal(example(name))] {
            let c = check(&v);
            assert!(c.warnings.is_empty(), "{name}: {:#?}", c.warnings);
            // Measured: 79 (MacPherson), 300 (double wishbone); all-ideal corners have no motion left on
            // the rig, hence no estimate.
            let measured = if name == "generic/macpherson.json" { 79.0 } else { 300.0 };
            match c.condition_estimate {
                Some(k) => assert!(k < 100.0 * measured && k > measured / 100.0, "{name}: {k}"),
                None => assert_eq!(c.degrees_of_freedom_on_rig, 0),
            }
        }
    }
}

#[test]
fn degrees_of_freedom_match_the_hand_count() {
    // Ideal arms and tie rod: three bodies (upright and two arms, or upright, strut rod and lower arm) =
    // 18 coordinates. Double wishbone: 2 hinges × 5 + 2 ball joints × 3 + tie rod 1 = 17 rows → 1 (wheel
    // travel). MacPherson: hinge 5 + ball joint 3 + strut slide 5 + top-mount ball joint 3 + tie rod 1 = 17
    // → 1. The rig's wheel-travel driver takes that one: 0.
    for name in EXAMPLES {
        let c = check(&ideal(example(name)));
        assert_eq!((c.degrees_of_freedom, c.degrees_of_freedom_on_rig, c.redundant_rows), (1, 0, 0), "{name}");
    }
    // Bushed arms: the bushings hold motions but remove none. Double wishbone: 18 − (2 ball joints × 3 + tie
    // rod 1) = 11. MacPherson with a bushed lower arm and top mount: 18 − (ball joint 3 + strut slide 5 + tie
    // rod 1) = 9.
    let dw = check(&example("generic/double_wishbone.json"));
    assert_eq!((dw.degrees_of_freedom, dw.degrees_of_freedom_on_rig), (11, 10));
    let mp = check(&example("generic/macpherson.json"));
    assert_eq!((mp.degrees_of_freedom, mp.degrees_of_freedom_on_rig), (9, 8));
}

#[test]
fn a_repeated_joint_is_counted_once() {
    use elastokin_core::{BodyRef, JointSpec};
    use elastokin_suspensions::{assembly::mobility, Rig, Side};
    let file: SuspensionFile = serde_json::from_value(ideal(example("generic/double_wishbone.json"))).unwrap();
    let mut corner = file.suspension.build(Side::Left, Rig::Free).unwrap();
    assert_eq!(mobility(&corner.model), (1, 0));
    // A second tie rod along the first repeats its row: still one way to move, one redundant row.
    let h = file.suspension.hardpoints();
    let at = |n: &str| h.iter().find(|(k, _)| k == n).unwrap().1;
    let upright = corner.model.body_id("upright").unwrap();
    let second =
        JointSpec::distance("second tie rod", BodyRef::Ground, upright, at("tie_rod_inner"), at("tie_rod_outer"));
    corner.model.add_joint(second).unwrap();
    assert_eq!(mobility(&corner.model), (1, 1));
}

#[test]
fn tie_rod_on_the_steering_axis_is_named() {
    for (name, upper) in
        [("generic/macpherson.json", "top_mount"), ("generic/double_wishbone.json", "upper_ball_joint")]
    {
        for mut v in [example(name), ideal(example(name))] {
            let (a, b) = (hardpoint(&mut v, "lower_ball_joint"), hardpoint(&mut v, upper));
            set_hardpoint(&mut v, "tie_rod_inner", near_axis(a, b));
            let c = check(&v);
            // With an ideal tie rod the wheel cannot rise without steering (the rod's line meets the
            // axis): the spring's length then does not change either.
            let expected: &[&str] = if c.degrees_of_freedom == 1 {
                &["tie-rod-on-steering-axis", "motion-ratio"]
            } else {
                &["tie-rod-on-steering-axis"]
            };
            assert_eq!(codes(&c), expected, "{name}: {:#?}", c.warnings);
            let w = &c.warnings[0];
            assert_eq!(w.hardpoints, ["tie_rod_inner", "tie_rod_outer", "lower_ball_joint", upper]);
        }
    }
}

#[test]
fn millimetres_are_recognised() {
    for name in EXAMPLES {
        let mut v = example(name);
        map_hardpoints(&mut v, |p| p.map(|c| c * 1000.0));
        let c = check(&v);
        assert_eq!(codes(&c), ["millimetres"], "{name}: {:#?}", c.warnings);
        assert!(c.warnings[0].message.contains("divide by 1000"), "{}", c.warnings[0].message);
    }
}

/// A spring rate given in N/mm where the file reads N/m (70 for 70 N/mm) solves, to a spring deflected by
/// metres: it is named at `check`, with the rate to give.
#[test]
fn a_spring_rate_in_newtons_per_millimetre_is_named() {
    for name in EXAMPLES {
        let mut v = example(name);
        template(&mut v)["spring"]["rate"] = serde_json::json!(70.0);
        let c = check(&v);
        let w =
            c.warnings.iter().find(|w| w.code == "spring-rate").unwrap_or_else(|| panic!("{name}: {:#?}", c.warnings));
        assert!(
            w.message.contains("70 N/m (0.07 N/mm)") && w.message.contains("for 70 N/mm give 70000"),
            "{}",
            w.message
        );
    }
    // In the general form too, and not for a rate a car's spring has.
    let mut v = example("five_link.json");
    v["suspension"]["general"]["springs"][0]["rate"] = serde_json::json!(35.0);
    assert!(codes(&check(&v)).contains(&"spring-rate"));
    v["suspension"]["general"]["springs"][0]["rate"] = serde_json::json!(1500.0);
    assert!(!codes(&check(&v)).contains(&"spring-rate"));
}

#[test]
fn a_right_corner_is_named() {
    for name in EXAMPLES {
        let mut v = example(name);
        map_hardpoints(&mut v, |[x, y, z]| [x, -y, z]);
        let c = check(&v);
        assert_eq!(codes(&c), ["wrong-side"], "{name}: {:#?}", c.warnings);
        let mut all: Vec<String> = template(&mut v)["hardpoints"].as_object().unwrap().keys().cloned().collect();
        all.sort();
        assert_eq!(c.warnings[0].hardpoints, all);
    }
}

#[test]
fn a_far_hardpoint_is_named() {
    for name in EXAMPLES {
        let mut v = example(name);
        let p = hardpoint(&mut v, "tie_rod_inner");
        // 5 m up: a typo, not beyond what the corner can be built with (1e6 m is refused when it is built).
        set_hardpoint(&mut v, "tie_rod_inner", [p[0], p[1], 5.0]);
        let c = check(&v);
        assert!(codes(&c).contains(&"far-hardpoint"), "{name}: {:#?}", c.warnings);
        let far: Vec<_> = c.warnings.iter().filter(|w| w.code == "far-hardpoint").collect();
        assert_eq!(far.len(), 1);
        assert_eq!(far[0].hardpoints, ["tie_rod_inner"]);
    }
}

#[test]
fn an_arm_pivoting_through_its_ball_joint_is_named() {
    // With a hinge the arm spins freely about its own line: on the MacPherson nothing holds that (the
    // condition estimate measured 1.5e33); on the double wishbone the spring seat on the arm does, but the
    // arm cannot compress the spring (motion ratio 0). Bushings hold the spin (estimates 8.7e3, 7.2e3).
    let cases: [(&str, Value, &[&str]); 4] = [
        ("generic/macpherson.json", example("generic/macpherson.json"), &["pivot-through-ball-joint"]),
        (
            "generic/macpherson.json",
            ideal(example("generic/macpherson.json")),
            &["pivot-through-ball-joint", "near-singular"],
        ),
        ("generic/double_wishbone.json", example("generic/double_wishbone.json"), &["pivot-through-ball-joint"]),
        (
            "generic/double_wishbone.json",
            ideal(example("generic/double_wishbone.json")),
            &["pivot-through-ball-joint", "motion-ratio"],
        ),
    ];
    for (name, mut v, expected) in cases {
        {
            let (front, ball) = (hardpoint(&mut v, "lower_arm_front"), hardpoint(&mut v, "lower_ball_joint"));
            set_hardpoint(&mut v, "lower_arm_rear", lerp(front, ball, 0.5));
            let c = check(&v);
            assert_eq!(codes(&c), expected, "{name}: {:#?}", c.warnings);
            let w = &c.warnings[0];
            assert_eq!(w.hardpoints, ["lower_arm_front", "lower_arm_rear", "lower_ball_joint"]);
        }
    }
}

#[test]
fn travel_rows_beyond_plausible_toe_and_a_falling_wheel_rate_are_named() {
    use elastokin_solver::Mode;
    use elastokin_suspensions::analysis::parallel_wheel_travel;
    use elastokin_suspensions::{check_travel_rows, Rig, Side};
    let travel = |v: &Value| {
        let file: SuspensionFile = serde_json::from_value(v.clone()).unwrap();
        let corner = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
        parallel_wheel_travel(&corner, -0.08, 0.08, 16, Mode::Corrected).unwrap()
    };
    for name in EXAMPLES {
        let rows = travel(&example(name));
        assert!(check_travel_rows(&rows).is_empty(), "{name}: {:#?}", check_travel_rows(&rows));
        // The same sweep read backwards (force falling as the wheel rises): the rate is negative.
        let mut falling = rows.clone();
        for r in &mut falling {
            r.wheel_load = -r.wheel_load;
        }
        let codes: Vec<_> = check_travel_rows(&falling).iter().map(|w| w.code).collect();
        assert_eq!(codes, ["wheel-rate"], "{name}");
    }
    // A tie rod whose line meets the steering axis: driving the wheel height turns the wheel instead
    // (measured on the bushed MacPherson within ±80 mm: toe −119.7°, camber 23.3° at −80 mm, and the wheel
    // rate −45.8 N/mm between 60 and 70 mm).
    let mut v = example("generic/macpherson.json");
    let (a, b) = (hardpoint(&mut v, "lower_ball_joint"), hardpoint(&mut v, "top_mount"));
    set_hardpoint(&mut v, "tie_rod_inner", near_axis(a, b));
    let rows = travel(&v);
    let worst = rows.iter().map(|r| r.attitude.toe.to_degrees().abs()).fold(0.0, f64::max);
    assert!(worst > 100.0, "{worst}");
    let warnings = check_travel_rows(&rows);
    let codes: Vec<_> = warnings.iter().map(|w| w.code).collect();
    assert_eq!(codes, ["toe-range", "camber-range", "wheel-rate"], "{warnings:#?}");
    assert!(warnings[0].message.contains("toe reaches"), "{}", warnings[0].message);
}

#[test]
fn the_report_gives_the_counts_the_condition_and_each_warning_with_its_code() {
    let clean = check(&example("generic/macpherson.json")).report();
    assert_eq!(clean.len(), 2, "{clean:#?}");
    assert!(clean[0].starts_with("degrees of freedom: 9 with the wheel free"), "{}", clean[0]);
    assert!(clean[0].contains("8 with the rig's wheel-travel driver"), "{}", clean[0]);
    // Measured 79.
    assert!(clean[1].starts_with("condition at design: 7.9e1"), "{}", clean[1]);
    let all_ideal = check(&ideal(example("generic/macpherson.json"))).report();
    assert!(all_ideal[1].contains("the joints leave no motion"), "{}", all_ideal[1]);
    let mut v = example("generic/macpherson.json");
    let (a, b) = (hardpoint(&mut v, "lower_ball_joint"), hardpoint(&mut v, "top_mount"));
    set_hardpoint(&mut v, "tie_rod_inner", near_axis(a, b));
    let lines = check(&v).report();
    assert_eq!(lines.len(), 3, "{lines:#?}");
    assert!(lines[2].starts_with("warning [tie-rod-on-steering-axis]: the tie rod ('tie_rod_inner'"), "{}", lines[2]);
}

/// The templates' named hardpoint lists (what the checks and warnings read) hold every hardpoint of the
/// model file, with the file's values.
#[test]
fn every_hardpoint_of_the_file_is_named() {
    for name in EXAMPLES {
        let v = example(name);
        let file: SuspensionFile = serde_json::from_value(v.clone()).unwrap();
        let (_, t) = v["suspension"].as_object().unwrap().iter().next().unwrap();
        let from_file = t["hardpoints"].as_object().unwrap();
        let named = file.suspension.hardpoints();
        assert_eq!(named.len(), from_file.len(), "{name}");
        for (key, p) in &named {
            let q = &from_file[key.as_str()];
            assert_eq!([p.x, p.y, p.z], [0, 1, 2].map(|k| q[k].as_f64().unwrap()), "{name}: {key}");
        }
    }
}

/// The shipped MacPherson as a car's front an engineer would draw: numbers written as one writes them (to
/// 0.1 mm and round rates, not a tune's seventeen digits), a ride frequency inside the 1.0–1.5 Hz of a
/// passenger car's front, a static spring deflection of 100–250 mm, and bushings under 15 % of the wheel
/// rate (against the same model with ideal joints in their place).
#[test]
fn the_shipped_macpherson_is_a_plausible_cars_front_in_round_numbers() {
    use elastokin_suspensions::kc::{self, Analysis, Settings};
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/macpherson.json")).unwrap();
    // Round numbers: every number of the file has at most four decimals (0.1 mm in metres).
    let mut numbers = Vec::new();
    fn collect(v: &Value, out: &mut Vec<f64>) {
        match v {
            Value::Number(n) => out.push(n.as_f64().unwrap()),
            Value::Array(a) => a.iter().for_each(|v| collect(v, out)),
            Value::Object(o) => o.values().for_each(|v| collect(v, out)),
            _ => {}
        }
    }
    let mut doc: Value = serde_json::from_str(&text).unwrap();
    collect(&doc, &mut numbers);
    for v in &numbers {
        assert!((v * 1e4 - (v * 1e4).round()).abs() < 1e-6 * v.abs().max(1.0) * 1e4, "{v} is no round number");
    }
    let run = |doc: &Value| {
        let file = SuspensionFile::from_json(&doc.to_string(), "m.json").unwrap();
        let settings = Settings { steps: 8, ..Settings::default() };
        let travel = kc::run(Analysis::ParallelTravel, &file, &settings).unwrap();
        let rest = kc::run(Analysis::StaticLoad, &file, &settings).unwrap();
        let figure = |a: &kc::AnalysisReport, key: &str| a.figure(key).unwrap().value.unwrap();
        (figure(&travel, "wheel_rate"), figure(&travel, "ride_rate"), figure(&rest, "spring_deflection"))
    };
    let (wheel_rate, ride_rate, deflection) = run(&doc);
    // The corner's sprung mass: its load over g, less an unsprung 33 kg.
    let corner_load = doc["vehicle"]["corner_load"].as_f64().unwrap();
    let sprung = corner_load / 9.81 - 33.0;
    let frequency = (ride_rate / sprung).sqrt() / (2.0 * std::f64::consts::PI);
    assert!((1.0..=1.5).contains(&frequency), "ride frequency {frequency} Hz");
    assert!((0.100..=0.250).contains(&-deflection), "static spring deflection {deflection} m");
    for mount in ["lower_arm_mounts", "top_mount"] {
        template(&mut doc)[mount] = serde_json::json!("ideal");
    }
    let (joints_alone, _, _) = run(&doc);
    let share = 1.0 - joints_alone / wheel_rate;
    assert!(share > 0.0 && share < 0.15, "the bushings carry {share} of the wheel rate");
}
