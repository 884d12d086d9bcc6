//! Tuning to targets: inverse problems whose answers are known (a toe curve made from the model with
//! hidden moves of its tie-rod points, tuned back from the model without them), bounds and packaging that
//! hold a tune and are named for it, targets that fight, and bad TARGETS files refused by key.

mod common;

use common::{lateral_force_rig, ARM_RADIAL, TOP_RADIAL};
use elastokin_suspensions::design::targets::{read_targets, Targets, TargetsRefusal};
use elastokin_suspensions::design::tune::{evaluate, tune, NotGiven, TuneError, Tuned};
use elastokin_suspensions::design::KeyRefusal;
use elastokin_suspensions::design::Parameters;
use elastokin_suspensions::kc::{self, Analysis, Settings};
use elastokin_suspensions::study::batch::base_document;
use serde_json::{json, Value};

fn document(name: &str) -> Value {
    let path = format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"));
    base_document(&std::fs::read_to_string(&path).unwrap(), &path).unwrap()
}

const H: &str = "/suspension/macpherson/hardpoints";
const STEPS: usize = 20;
const INNER_Z: f64 = 0.004;
const OUTER_X: f64 = -0.003;

fn value(doc: &Value, pointer: &str) -> f64 {
    doc.pointer(pointer).unwrap().as_f64().unwrap()
}

/// The MacPherson with its inner tie-rod point 4 mm higher and its outer one 3 mm further back.
fn hidden() -> Value {
    let mut doc = document("macpherson.json");
    for (pointer, by) in [(format!("{H}/tie_rod_inner/2"), INNER_Z), (format!("{H}/tie_rod_outer/0"), OUTER_X)] {
        let moved = value(&doc, &pointer) + by;
        *doc.pointer_mut(&pointer).unwrap() = json!(moved);
    }
    doc
}

/// The toe curve of parallel travel over ±50 mm of `doc`, every 10 mm, as the report gives it.
fn toe_curve(doc: &Value) -> Vec<(f64, f64)> {
    let file = Parameters::new(doc, &[]).unwrap().file().unwrap();
    let settings = Settings { range: Some((-0.05, 0.05)), steps: STEPS, ..Settings::default() };
    let r = kc::run(Analysis::ParallelTravel, &file, &settings).unwrap();
    let c = r.table.columns.iter().position(|x| x == "toe_deg").unwrap();
    r.table.rows.iter().step_by(2).map(|row| (row[0].number().unwrap(), row[c].number().unwrap())).collect()
}

/// A TARGETS file: the toe curve of the hidden model, with `free` pointers each ±`span` about the
/// model's value, and `extra` targets and constraints.
fn targets_text(base: &Value, free: &[String], span: f64, extra: &[Value], constraints: &[Value]) -> String {
    let mut bounds = serde_json::Map::new();
    for pointer in free {
        let v = value(base, pointer);
        bounds.insert(pointer.clone(), json!([v - span, v + span]));
    }
    let mut targets = vec![json!({
        "curve": "parallel-travel/toe_deg", "range": [-0.05, 0.05], "points": toe_curve(&hidden()), "tolerance": 0.005
    })];
    targets.extend_from_slice(extra);
    json!({ "free": bounds, "targets": targets, "constraints": constraints, "steps": STEPS }).to_string()
}

fn run(base: &Value, text: &str) -> (Targets, Tuned) {
    let targets = read_targets(text, "targets.json", base, |f| Err(format!("no file {f}"))).unwrap();
    let pointers: Vec<String> = targets.free.iter().map(|f| f.pointer.clone()).collect();
    let parameters = Parameters::new(base, &pointers).unwrap();
    let tuned = tune(&parameters, &targets, |_| {}).unwrap();
    (targets, tuned)
}

fn worst_miss(tuned: &Tuned) -> f64 {
    tuned.end.rows.iter().map(|r| (r.value - r.aim).abs()).fold(0.0, f64::max)
}

/// The two moved numbers free: the curve is met to 1e-6 deg and the points found where they were hidden
/// (measured: 3e-12 deg and 3e-13 m, in 4 evaluations).
#[test]
fn the_hidden_moves_of_two_tie_rod_coordinates_are_found_from_the_toe_curve() {
    let base = document("macpherson.json");
    let free = vec![format!("{H}/tie_rod_inner/2"), format!("{H}/tie_rod_outer/0")];
    let (_, tuned) = run(&base, &targets_text(&base, &free, 0.02, &[], &[]));
    println!(
        "{}: {} evaluations, miss {:e} deg",
        tuned.stopped,
        tuned.iterations.last().unwrap().evaluations,
        worst_miss(&tuned)
    );
    assert!(tuned.all_met() && worst_miss(&tuned) < 1e-6, "{:?}", tuned.verdicts);
    let found = [tuned.end.x[0] - value(&base, &free[0]), tuned.end.x[1] - value(&base, &free[1])];
    assert!((found[0] - INNER_Z).abs() < 1e-11 && (found[1] - OUTER_X).abs() < 1e-11, "{found:?}");
    // The tuned model file is the model with those two numbers moved, every other key as it was.
    let mut expected = base.clone();
    *expected.pointer_mut(&free[0]).unwrap() = json!(tuned.end.x[0]);
    *expected.pointer_mut(&free[1]).unwrap() = json!(tuned.end.x[1]);
    assert_eq!(tuned.document, expected);
    let keys = |v: &Value| {
        v["suspension"]["macpherson"]["hardpoints"].as_object().unwrap().keys().cloned().collect::<Vec<_>>()
    };
    assert_eq!(keys(&tuned.document), keys(&base));
}

/// Both tie-rod points free (six numbers, some combinations of which the toe curve does not see): the
/// curve is met to 1e-6 deg (measured 2.2e-9 deg in 5 evaluations), by the smallest moves.
#[test]
fn both_tie_rod_points_free_meet_the_toe_curve() {
    let base = document("macpherson.json");
    let free: Vec<String> =
        ["tie_rod_inner", "tie_rod_outer"].iter().flat_map(|p| (0..3).map(move |i| format!("{H}/{p}/{i}"))).collect();
    let (_, tuned) = run(&base, &targets_text(&base, &free, 0.02, &[], &[]));
    let last = tuned.iterations.last().unwrap();
    println!("{}: {} evaluations, miss {:e} deg", tuned.stopped, last.evaluations, worst_miss(&tuned));
    assert!(tuned.all_met() && worst_miss(&tuned) < 1e-6, "{:?}", tuned.verdicts);
    assert!(last.evaluations <= 10, "{}", last.evaluations);
    // Every iteration is listed, the objective never rising from one taken step to the next.
    let taken: Vec<f64> =
        tuned.iterations.iter().filter(|i| i.outcome == "taken" || i.outcome == "start").map(|i| i.objective).collect();
    assert!(taken.windows(2).all(|w| w[1] < w[0]), "{taken:?}");
}

/// A bound that keeps the inner point below where it was hidden: the curve cannot be met, and the verdict
/// names the bound that holds; the point ends at it.
#[test]
fn a_bound_that_holds_a_number_is_named_when_the_target_is_not_met() {
    let base = document("macpherson.json");
    let inner = format!("{H}/tie_rod_inner/2");
    let z = value(&base, &inner);
    let text = targets_text(&base, std::slice::from_ref(&inner), 0.02, &[], &[])
        .replace(&format!("{}", z + 0.02), &format!("{}", z + 0.001));
    let (_, tuned) = run(&base, &text);
    assert!(!tuned.all_met());
    let why = tuned.verdicts[0].why.as_deref().unwrap();
    // In the engineer's words: the point and its axis, the bound in millimetres.
    let said = why.split("tie_rod_inner z at its upper bound, ").nth(1).unwrap_or_else(|| panic!("{why}"));
    let bound: f64 = said.split(" mm").next().unwrap().parse().unwrap();
    assert!((bound - (z + 0.001) * 1e3).abs() < 1e-9, "{why}");
    assert!((tuned.end.x[0] - (z + 0.001)).abs() < 1e-12, "{}", tuned.end.x[0]);
}

/// A bound of −1e308 m on a hardpoint coordinate: the tune's step, in the numbers scaled by their bounds'
/// span, was a decomposition of numbers that are not finite, which panicked. Such bounds are refused
/// where the tune starts, naming the number.
#[test]
fn bounds_too_wide_for_a_step_are_refused_by_key_not_a_panic() {
    let base = document("generic/macpherson.json");
    let inner = format!("{H}/tie_rod_inner/2");
    let text = json!({
        "free": { &inner: [-1e308, -0.02] },
        "targets": [{ "figure": "parallel-travel/bump_steer", "value": -2.0, "tolerance": 0.25 }],
    })
    .to_string();
    let targets = read_targets(&text, "targets.json", &base, |f| Err(format!("no file {f}"))).unwrap();
    let parameters = Parameters::new(&base, std::slice::from_ref(&inner)).unwrap();
    let e = tune(&parameters, &targets, |_| {}).map(|_| ()).unwrap_err();
    let TuneError::Targets(e @ NotGiven::TooWide { .. }) = e else { panic!("{e:?}") };
    let e = e.to_string();
    assert!(e.starts_with(&format!("free[\"{inner}\"]: the bounds -1e308 to -0.02 are too wide")), "{e}");
}

/// An aim of −1e308 deg/m for the bump steer: its miss over the tolerance, squared in the objective, was
/// infinite, and the tune's step was taken from it. It is refused, naming the target.
#[test]
fn an_aim_too_far_to_be_squared_is_refused_naming_the_target() {
    let base = document("generic/macpherson.json");
    let inner = format!("{H}/tie_rod_inner/2");
    for (value, tolerance) in [(-1e308, 0.25), (-2.0, 1e-300)] {
        let text = json!({
            "free": { &inner: [-0.1, -0.02] },
            "targets": [{ "figure": "parallel-travel/bump_steer", "value": value, "tolerance": tolerance }],
        })
        .to_string();
        let targets = read_targets(&text, "targets.json", &base, |f| Err(format!("no file {f}"))).unwrap();
        let parameters = Parameters::new(&base, std::slice::from_ref(&inner)).unwrap();
        let e = tune(&parameters, &targets, |_| {}).map(|_| ()).unwrap_err();
        let TuneError::Targets(e @ NotGiven::TooFar { .. }) = e else { panic!("{e:?}") };
        let e = e.to_string();
        assert!(e.starts_with("targets[0]") && e.contains("is too large to be worked with"), "{e}");
    }
}

/// A bump steer of −10 deg/m asked with a tight tolerance beside the hidden model's toe curve (whose bump
/// steer is some −30 deg/m), one number free with room for either: they fight, and the verdict says so.
#[test]
fn targets_that_fight_are_said_to() {
    let base = document("macpherson.json");
    let fight =
        json!({ "figure": "parallel-travel/bump_steer", "range": [-0.05, 0.05], "value": -10.0, "tolerance": 0.01 });
    let (_, tuned) = run(&base, &targets_text(&base, &[format!("{H}/tie_rod_inner/2")], 0.1, &[fight], &[]));
    assert!(!tuned.all_met());
    let unmet: Vec<&str> = tuned.verdicts.iter().filter(|v| !v.met).filter_map(|v| v.why.as_deref()).collect();
    assert!(!unmet.is_empty() && unmet.iter().all(|w| w.contains("fight one another")), "{unmet:?}");
}

/// A weight of 10 on the fighting bump-steer target: the tune ends where the same target with a tenth of
/// its tolerance and no weight ends (the objective is the same), nearer its aim than unweighted; its verdict
/// is still judged against its own tolerance.
#[test]
fn a_targets_weight_counts_as_a_tolerance_that_much_tighter_in_the_objective() {
    let base = document("macpherson.json");
    let free = [format!("{H}/tie_rod_inner/2")];
    let end = |fight: Value| run(&base, &targets_text(&base, &free, 0.1, &[fight], &[])).1;
    let figure = |extra: Value| {
        let mut f = json!({ "figure": "parallel-travel/bump_steer", "range": [-0.05, 0.05], "value": -10.0 });
        f.as_object_mut().unwrap().extend(extra.as_object().unwrap().clone());
        f
    };
    let weighted = end(figure(json!({ "tolerance": 0.5, "weight": 10.0 })));
    let tighter = end(figure(json!({ "tolerance": 0.05 })));
    let plain = end(figure(json!({ "tolerance": 0.5 })));
    // Measured 0 m apart: the same objective, the same steps.
    assert!((weighted.end.x[0] - tighter.end.x[0]).abs() < 1e-12, "{} {}", weighted.end.x[0], tighter.end.x[0]);
    let miss = |t: &Tuned| t.end.rows.iter().find(|r| r.at.is_none()).map(|r| (r.value - r.aim).abs()).unwrap();
    // The weight moves the compromise towards the weighted target (measured misses 6.8 and 12.7 deg/m).
    assert!(miss(&weighted) < 0.75 * miss(&plain), "{} {}", miss(&weighted), miss(&plain));
    // Judged unweighted: the largest miss over its own tolerance of 0.5.
    let v = weighted.verdicts.iter().find(|v| v.target.contains("bump_steer")).unwrap();
    assert!((v.worst - miss(&weighted) / 0.5).abs() < 1e-12, "{v:?}");
    let bad = targets_text(&base, &free, 0.1, &[figure(json!({ "tolerance": 0.5, "weight": 0 }))], &[]);
    let e = read_targets(&bad, "t.json", &base, |f| Err(format!("no file {f}"))).unwrap_err().to_string();
    assert!(e.contains("targets[1].weight: give a positive number"), "{e}");
}

/// The tie rod's length kept within ±0.5 mm of its own while both its points are free: the tune keeps
/// it there (to 1e-9 m) and still meets the curve.
#[test]
fn the_packaging_is_kept() {
    let base = document("macpherson.json");
    let a: Vec<f64> = (0..3).map(|i| value(&base, &format!("{H}/tie_rod_inner/{i}"))).collect();
    let b: Vec<f64> = (0..3).map(|i| value(&base, &format!("{H}/tie_rod_outer/{i}"))).collect();
    let length = (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt();
    let free: Vec<String> =
        ["tie_rod_inner", "tie_rod_outer"].iter().flat_map(|p| (0..3).map(move |i| format!("{H}/{p}/{i}"))).collect();
    let keep = json!({ "distance": ["tie_rod_inner", "tie_rod_outer"], "min": length - 5e-4, "max": length + 5e-4 });
    let (_, tuned) = run(&base, &targets_text(&base, &free, 0.02, &[], &[keep]));
    let end = &tuned.end.packaging[0];
    assert!(end.value >= length - 5e-4 - 1e-9 && end.value <= length + 5e-4 + 1e-9, "{}", end.value);
    assert!(tuned.all_met(), "{:?}", tuned.verdicts);
}

/// The tie rod's length held within a micrometre of its own while the inner point's z alone is free: the
/// curve needs that point 4 mm higher, which the length forbids, and the verdict names the packaging in
/// words.
#[test]
fn a_packaging_constraint_that_holds_a_tune_is_named_in_words() {
    let base = document("macpherson.json");
    let a: Vec<f64> = (0..3).map(|i| value(&base, &format!("{H}/tie_rod_inner/{i}"))).collect();
    let b: Vec<f64> = (0..3).map(|i| value(&base, &format!("{H}/tie_rod_outer/{i}"))).collect();
    let length = (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt();
    let keep = json!({ "distance": ["tie_rod_inner", "tie_rod_outer"], "min": length - 1e-6, "max": length + 1e-6 });
    let (_, tuned) = run(&base, &targets_text(&base, &[format!("{H}/tie_rod_inner/2")], 0.02, &[], &[keep]));
    let why = tuned.verdicts[0].why.as_deref().unwrap_or_else(|| panic!("{:?}", tuned.verdicts));
    assert!(why.contains("the packaging's distance tie_rod_inner–tie_rod_outer at its"), "{why}");
    assert!(why.contains("(constraints[0])") && !why.contains("holding"), "{why}");
    // The constraint holds the one free number: the fit has nothing left to place, and claims nothing.
    let u = tuned.uncertainty.as_ref().unwrap();
    assert_eq!(u.held_by_packaging, 1, "{u:?}");
    assert!(u.standard.iter().all(Option::is_none), "{u:?}");
}

/// The residuals' Jacobian is the derivative of the residuals (central differences of evaluations,
/// measured 6e-9 relative).
#[test]
fn the_jacobian_of_a_tune_is_the_derivative_of_its_residuals() {
    let base = document("macpherson.json");
    let free = vec![format!("{H}/tie_rod_inner/2"), format!("{H}/top_mount/1")];
    let fig =
        json!({ "figure": "parallel-travel/camber_gain", "range": [-0.05, 0.05], "value": -10.0, "tolerance": 0.1 });
    let targets =
        read_targets(&targets_text(&base, &free, 0.02, &[fig], &[]), "t", &base, |_| Err(String::new())).unwrap();
    let p = Parameters::new(&base, &free).unwrap();
    let e = evaluate(&p, &targets, &p.values).unwrap();
    let h = 1e-5;
    let mut worst: f64 = 0.0;
    for k in 0..2 {
        let moved = |d: f64| {
            let mut x = p.values.clone();
            x[k] += d;
            evaluate(&p, &targets, &x).unwrap().residuals
        };
        let (up, down) = (moved(h), moved(-h));
        for (i, row) in e.jacobian.iter().enumerate() {
            let fd = (up[i] - down[i]) / (2.0 * h);
            worst = worst.max((row[k] - fd).abs() / fd.abs().max(1.0));
        }
    }
    assert!(worst < 1e-7, "{worst:e}");
}

/// Bad TARGETS files are refused by key, with the fix.
#[test]
fn bad_targets_are_refused_by_key() {
    let base = document("macpherson.json");
    let inner = format!("{H}/tie_rod_inner/2");
    let z = value(&base, &inner);
    let curve = json!({ "curve": "parallel-travel/toe_deg", "points": [[0.0, 0.0]], "tolerance": 0.01 });
    let cases: Vec<(Value, &str)> = vec![
        (
            json!({ "free": { "/suspension/macpherson/nowhere": [0, 1] }, "targets": [curve] }),
            "free[\"/suspension/macpherson/nowhere\"]: names nothing",
        ),
        (
            json!({ "free": { inner.clone(): [z + 0.01, z + 0.02] }, "targets": [curve] }),
            "exclude the model's own value",
        ),
        (json!({ "free": { inner.clone(): [z + 0.01, z - 0.02] }, "targets": [curve] }), "hold nothing"),
        (
            json!({ "free": { inner.clone(): [z - 0.01, z + 0.02] }, "targets": [{ "figure": "bumpy/bump_steer", "value": 0, "tolerance": 1 }] }),
            "targets[0].figure: no analysis 'bumpy'",
        ),
        (
            json!({ "free": { inner.clone(): [z - 0.01, z + 0.02] }, "targets": [{ "curve": "roll/toe_deg", "points": [[0, 0]], "tolerance": 0 }] }),
            "targets[0].tolerance: give a positive miss",
        ),
        (
            json!({ "free": { inner.clone(): [z - 0.01, z + 0.02] }, "targets": [{ "curve": "roll/toe_deg", "points": [[0, 0]], "tolerance": 1, "tolerence": 1 }] }),
            "unknown key 'tolerence'",
        ),
        (
            json!({ "free": { inner.clone(): [z - 0.01, z + 0.02] }, "targets": [{ "measured": "rig.csv", "analysis": "roll", "tolerance": 1 }] }),
            "no file rig.csv",
        ),
        (
            json!({ "free": { inner.clone(): [z - 0.01, z + 0.02] }, "targets": [curve], "constraints": [{ "distance": ["tie_rod_inner", "nowhere"], "max": 1 }] }),
            "constraints[0].distance: the model has no hardpoint 'nowhere'",
        ),
    ];
    for (text, says) in cases {
        let e = read_targets(&text.to_string(), "targets.json", &base, |f| Err(format!("no file {f}")))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("targets.json: ") && e.contains(says), "{says}: {e}");
    }
    // What is known only when run: a figure or column the analysis lacks, a point outside its range, rows
    // that move with the model.
    let p = Parameters::new(&base, std::slice::from_ref(&inner)).unwrap();
    for (target, says) in [
        (
            json!({ "figure": "parallel-travel/bump_stear", "value": 0, "tolerance": 1 }),
            "has no figure 'bump_stear' (it has: bump_steer",
        ),
        (
            json!({ "curve": "parallel-travel/toe", "points": [[0, 0]], "tolerance": 1 }),
            "has no column 'toe' (it has: travel_m, toe_deg",
        ),
        (
            json!({ "curve": "parallel-travel/toe_deg", "points": [[0.5, 0]], "tolerance": 1 }),
            "the point at 0.5 lies outside the range -0.08..0.08",
        ),
        (
            json!({ "curve": "vertical-force/toe_deg", "points": [[3000, 0]], "tolerance": 1 }),
            "its default range follows the model); give the target a \"range\"",
        ),
    ] {
        let text = json!({ "free": { inner.clone(): [z - 0.01, z + 0.02] }, "targets": [target] }).to_string();
        let targets = read_targets(&text, "t", &base, |_| Err(String::new())).unwrap();
        // Bad input (the command exits 2), not a model that cannot be analysed.
        let TuneError::Targets(e) = evaluate(&p, &targets, &p.values).unwrap_err() else { panic!("{says}") };
        let e = e.to_string();
        assert!(e.contains(says), "{says}: {e}");
    }
}

/// Fitting to K&C rig data: a lateral-force test "measured" on the MacPherson with its lower-arm bushings
/// 25 % stiffer radially and its top mount 20 % softer radially (the rig's CSV: load and the toe and
/// camber columns, a header comment naming the analysis), fitted from the model as it is with those two
/// rates free: the rates are found (measured: to 2.3e-10 relative, in 5 evaluations) and the curves met.
#[test]
fn bushing_rates_are_fitted_to_a_measured_lateral_force_test() {
    let base = document("macpherson.json");
    let (arm, top) = (ARM_RADIAL, TOP_RADIAL);
    let (rig, [load, toe, camber]) = lateral_force_rig(&base, 1.25, 0.8);
    let mut csv = "# analysis: lateral-force\n# the wheel-centre height held, the force at the contact patch\nload_n,toe_deg,camber_deg\n".to_string();
    for k in (0..load.len()).step_by(2) {
        csv.push_str(&format!("{},{},{}\n", load[k], toe[k], camber[k]));
    }
    let text = json!({
        "free": { arm: [2e6, 1e7], top: [1e6, 4e6] },
        "targets": [ { "measured": "rig.csv", "analysis": "lateral-force", "columns": ["toe_deg", "camber_deg"], "tolerance": 0.001 } ],
        "steps": 16,
    })
    .to_string();
    let targets = read_targets(&text, "fit.json", &base, |name| {
        assert_eq!(name, "rig.csv");
        Ok(csv.clone())
    })
    .unwrap();
    assert_eq!(targets.targets.len(), 2, "a curve target per measured column");
    let p = Parameters::new(&base, &[arm.to_string(), top.to_string()]).unwrap();
    let tuned = tune(&p, &targets, |_| {}).unwrap();
    let found = [tuned.end.x[0] / value(&rig, arm) - 1.0, tuned.end.x[1] / value(&rig, top) - 1.0];
    assert!(tuned.all_met() && found.iter().all(|f| f.abs() < 1e-8), "{found:?} {:?}", tuned.verdicts);
}

/// A target that asks for a negative wheel rate, the spring rate free down to negative numbers: every step
/// past where the model can be built is stepped back from, the tune ends at the edge of what the model
/// accepts (a positive rate), and the verdict says the model stopped it, with the model's own reason.
#[test]
fn a_tune_whose_steps_leave_what_the_model_accepts_steps_back_and_says_so() {
    // Lower-arm bushings stiff in torsion (10 N·m/deg), which carry the corner when the spring goes soft:
    // the steps reach a rate the model refuses (not positive) before any sweep fails to solve.
    let mut base = document("macpherson.json");
    *base.pointer_mut("/suspension/macpherson/lower_arm_mounts/bushing/torsion").unwrap() = json!(573.0);
    let text = json!({
        "free": { "/suspension/macpherson/spring/rate": [-1e5, 1e5] },
        "targets": [ { "figure": "parallel-travel/wheel_rate", "value": -5.0, "tolerance": 0.01 } ],
        "steps": 8,
    })
    .to_string();
    let (_, tuned) = run(&base, &text);
    assert!(tuned.iterations.iter().any(|i| i.outcome.starts_with("stepped back: parallel-travel")));
    assert!(tuned.end.x[0] > 0.0 && tuned.end.x[0] < tuned.start.x[0], "{}", tuned.end.x[0]);
    let why = tuned.verdicts[0].why.as_deref().unwrap();
    assert!(why.contains("held where the model stops") && why.contains("spring.rate"), "{why}");
}

/// The shipped front MacPherson and double wishbone are tuned by `elastokin tune` to the targets kept
/// beside them (`examples/targets/macpherson.json`, `examples/targets/double_wishbone.json`): tuned again
/// from themselves they meet every target as they are, and their figures are a passenger car's — each in
/// the range a production car's lies in; the five-link rear's too.
#[test]
fn the_shipped_fronts_meet_their_tuning_targets_and_a_passenger_cars_ranges() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    for (model, ranges) in [
        (
            "macpherson",
            &[
                ("parallel-travel", "bump_steer", -5.0, 1.0),
                ("parallel-travel", "scrub_radius", -10.0, 30.0),
                ("parallel-travel", "kingpin_inclination", 10.0, 15.0),
                ("parallel-travel", "caster", 3.0, 7.0),
                ("parallel-travel", "mechanical_trail", 10.0, 35.0),
                ("roll", "roll_centre_height", 30.0, 120.0),
                ("parallel-travel", "wheel_rate", 20.0, 35.0),
            ][..],
        ),
        (
            "double_wishbone",
            &[
                ("parallel-travel", "bump_steer", -5.0, 1.0),
                ("parallel-travel", "camber_gain", -30.0, -10.0),
                ("parallel-travel", "scrub_radius", -10.0, 30.0),
                ("parallel-travel", "kingpin_inclination", 7.0, 13.0),
                ("parallel-travel", "caster", 3.0, 7.0),
                ("parallel-travel", "mechanical_trail", 10.0, 35.0),
                ("roll", "roll_centre_height", 30.0, 120.0),
                ("parallel-travel", "wheel_rate", 20.0, 35.0),
            ][..],
        ),
    ] {
        let read = |p: &str| std::fs::read_to_string(root.join(p)).unwrap();
        let base = base_document(&read(&format!("{model}.json")), model).unwrap();
        let (_, tuned) = run(&base, &read(&format!("targets/{model}.json")));
        assert!(tuned.all_met(), "{model}: {:?}", tuned.verdicts);
        // The model as shipped (its tuned numbers rounded as an engineer writes them) meets them as it is.
        let targets =
            read_targets(&read(&format!("targets/{model}.json")), "t", &base, |_| Err(String::new())).unwrap();
        let file = Parameters::new(&base, &[]).unwrap().file().unwrap();
        let settings = Settings { steps: targets.steps, ..Settings::default() };
        let which: Vec<Analysis> = targets.targets.iter().map(|t| t.analysis).collect();
        let report = kc::run_suite(&file, &which, &settings, |_| {});
        let (points, _) = elastokin_suspensions::design::judge::judge(&report, &base, &targets);
        assert!(points.iter().all(|p| p.met()), "{model}: {points:?}");
        let file = Parameters::new(&base, &[]).unwrap().file().unwrap();
        in_ranges(model, &file, ranges);
    }
    let rear = base_document(&std::fs::read_to_string(root.join("five_link.json")).unwrap(), "five_link").unwrap();
    let rear = Parameters::new(&rear, &[]).unwrap().file().unwrap();
    in_ranges(
        "five_link",
        &rear,
        &[
            ("parallel-travel", "bump_steer", -5.0, 5.0),
            ("parallel-travel", "camber_gain", -35.0, -10.0),
            ("roll", "roll_centre_height", 30.0, 150.0),
            ("parallel-travel", "wheel_rate", 15.0, 40.0),
        ],
    );
}

/// Each figure of `file` named in `ranges` lies in its range (in the figure's printed unit).
fn in_ranges(model: &str, file: &elastokin_suspensions::SuspensionFile, ranges: &[(&str, &str, f64, f64)]) {
    for (analysis, key, lo, hi) in ranges {
        let a = kc::run(Analysis::from_name(analysis).unwrap(), file, &Settings::default()).unwrap();
        let v = a.figure(key).and_then(|f| f.written(kc::Units::DegPerM).value).unwrap();
        assert!((*lo..=*hi).contains(&v), "{model}: {analysis} {key} {v} outside {lo}..{hi}");
    }
}

/// The tie rod's length asked 2 mm longer than it is, and asked 5–6 m (it is 0.33 m): the tune said every
/// target was met and kept the broken packaging. Now a constraint the start breaks is brought back where
/// the free numbers can (the tie rod's length, measured from the tuned file's points, ends inside its
/// range, with the curve met), and where they cannot it is a miss, named, by how far it is broken.
#[test]
fn a_packaging_constraint_the_start_breaks_is_restored_or_named_as_a_miss() {
    let base = document("macpherson.json");
    let free: Vec<String> =
        ["tie_rod_inner", "tie_rod_outer"].iter().flat_map(|p| (0..3).map(move |i| format!("{H}/{p}/{i}"))).collect();
    let length = |doc: &Value| {
        let at = |p: &str| (0..3).map(|i| value(doc, &format!("{H}/{p}/{i}"))).collect::<Vec<f64>>();
        let (a, b) = (at("tie_rod_inner"), at("tie_rod_outer"));
        (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt()
    };
    let l0 = length(&base);
    let (min, max) = (l0 + 2e-3, l0 + 3e-3);
    let longer = json!({ "distance": ["tie_rod_inner", "tie_rod_outer"], "min": min, "max": max });
    let (_, tuned) = run(&base, &targets_text(&base, &free, 0.02, &[], &[longer]));
    let l = length(&tuned.document);
    println!("restored: {l} m in [{min}, {max}], {:?}", tuned.verdicts);
    assert!(l >= min - 1e-9 && l <= max + 1e-9, "{l} vs [{min}, {max}]");
    assert_eq!(tuned.packaging[0].broken_by, 0.0);
    assert!(tuned.all_met(), "{:?} {:?}", tuned.verdicts, tuned.packaging);

    let far = json!({ "distance": ["tie_rod_inner", "tie_rod_outer"], "min": 5.0, "max": 6.0 });
    let (_, tuned) = run(&base, &targets_text(&base, &free, 0.02, &[], &[far]));
    let p = &tuned.packaging[0];
    assert!(!tuned.all_met());
    assert_eq!(p.constraint, "constraints[0]: distance tie_rod_inner–tie_rod_outer");
    // Broken by what the tuned file's points leave of the 5 m asked.
    let l = length(&tuned.document);
    assert!((p.broken_by - (5.0 - l)).abs() < 1e-12, "{} vs {}", p.broken_by, 5.0 - l);
    assert!(tuned.stopped.contains("the packaging is still broken"), "{}", tuned.stopped);
    // Brought as near as the bounds let it: the longest tie rod with each coordinate within ±20 mm of its
    // own, each end moved 20 mm along every axis away from the other (a convex length's largest value on
    // the box of bounds is at a corner).
    let at = |p: &str| (0..3).map(|i| value(&base, &format!("{H}/{p}/{i}"))).collect::<Vec<f64>>();
    let (a, b) = (at("tie_rod_inner"), at("tie_rod_outer"));
    let longest = (0..3).map(|i| ((a[i] - b[i]).abs() + 0.04).powi(2)).sum::<f64>().sqrt();
    println!("unreachable: {l} m against the longest the bounds allow {longest} m, {}", tuned.stopped);
    // Measured 3.7e-11 m apart.
    assert!((l - longest).abs() < 1e-9, "{l} vs {longest}");
}

/// A key given twice in a TARGETS file (two bounds for one free number), a TOLERANCES file or a model file
/// was read as the last of the two, silently. Each is refused, naming the key's place.
#[test]
fn a_key_given_twice_in_a_design_or_model_file_is_refused_naming_it() {
    use elastokin_suspensions::design::tolerance::read_tolerances;
    use elastokin_suspensions::SuspensionFile;
    let base = document("macpherson.json");
    let inner = format!("{H}/tie_rod_inner/2");
    let targets = format!(
        r#"{{"free": {{"{inner}": [-0.1, -0.02], "{inner}": [-0.2, 0.0]}},
            "targets": [{{"figure": "parallel-travel/bump_steer", "value": -2.0, "tolerance": 0.25}}]}}"#
    );
    let e = read_targets(&targets, "targets.json", &base, |f| Err(format!("no file {f}"))).unwrap_err();
    assert!(matches!(*e.refusal, TargetsRefusal::Key(KeyRefusal::Twice { .. })), "{e:?}");
    assert_eq!(e.to_string(), format!("targets.json: free.{inner}: the key is given twice: give each key once"));
    let tolerances = r#"{"hardpoints": 0.001, "steps": 8, "steps": 16}"#;
    let e = read_tolerances(tolerances, "tolerances.json", &base).unwrap_err().to_string();
    assert_eq!(e, "tolerances.json: steps: the key is given twice: give each key once");
    let path = format!("{}/../../examples/macpherson.json", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap().replacen("\"name\"", "\"name\": \"first\", \"name\"", 1);
    let e = SuspensionFile::from_json(&text, "twice.json").unwrap_err().to_string();
    assert!(e.contains("name: the key is given twice: give each key once"), "{e}");
    let e = elastokin_suspensions::study::batch::base_document(&text, "twice.json").unwrap_err();
    use elastokin_suspensions::study::batch::BaseDocumentError;
    assert_eq!(e, BaseDocumentError::KeyTwice { origin: "twice.json".into(), keys: vec!["name".into()] });
    assert_eq!(e.to_string(), "twice.json: name: the key is given twice: give each key once");
}

/// A bound given as one number: `TargetsError` names the file, and its `KeyRefusal` the key and what it
/// holds.
#[test]
fn a_free_number_with_one_bound_is_refused_as_a_key_naming_it() {
    let base = document("macpherson.json");
    let inner = format!("{H}/tie_rod_inner/2");
    let text = json!({
        "free": { &inner: 0.5 },
        "targets": [{ "figure": "parallel-travel/bump_steer", "value": -2.0, "tolerance": 0.25 }],
    })
    .to_string();
    let e = read_targets(&text, "mine.json", &base, |f| Err(format!("no file {f}"))).unwrap_err();
    assert!(matches!(*e.refusal, TargetsRefusal::Key(KeyRefusal::NotPair { .. })), "{e:?}");
    assert_eq!(e.to_string(), format!("mine.json: free[\"{inner}\"]: give two numbers [a, b], got 0.5"));
}

/// A distance's bounds the wrong way round: `TargetsRefusal::MinNotBelowMax`, naming the constraint and both.
#[test]
fn a_distance_whose_min_is_above_its_max_is_refused_naming_the_constraint() {
    let base = document("macpherson.json");
    let inner = format!("{H}/tie_rod_inner/2");
    let z = value(&base, &inner);
    let text = json!({
        "free": { &inner: [z - 0.01, z + 0.01] },
        "targets": [{ "figure": "parallel-travel/bump_steer", "value": -2.0, "tolerance": 0.25 }],
        "constraints": [{ "distance": ["tie_rod_inner", "tie_rod_outer"], "min": 0.4, "max": 0.3 }],
    })
    .to_string();
    let e = read_targets(&text, "mine.json", &base, |f| Err(format!("no file {f}"))).unwrap_err();
    assert!(matches!(*e.refusal, TargetsRefusal::MinNotBelowMax { .. }), "{e:?}");
    assert_eq!(e.to_string(), "mine.json: constraints[0]: min 0.4 is not below max 0.3");
}

/// A figure the analysis does not report: `NotGiven::NoFigure`, naming the target, the analysis and the
/// figure.
#[test]
fn a_figure_the_analysis_has_not_is_not_given_naming_the_target() {
    let base = document("macpherson.json");
    let inner = format!("{H}/tie_rod_inner/2");
    let z = value(&base, &inner);
    let text = json!({
        "free": { &inner: [z - 0.01, z + 0.01] },
        "targets": [{ "figure": "roll/bump_steer", "value": 0, "tolerance": 1 }],
        "steps": 8,
    })
    .to_string();
    let targets = read_targets(&text, "t", &base, |_| Err(String::new())).unwrap();
    let p = Parameters::new(&base, std::slice::from_ref(&inner)).unwrap();
    let e = evaluate(&p, &targets, &p.values).unwrap_err();
    let TuneError::Targets(e @ NotGiven::NoFigure { .. }) = e else { panic!("{e:?}") };
    assert!(
        e.to_string().starts_with("targets[0] (roll/bump_steer): roll has no figure 'bump_steer' (it has: "),
        "{e}"
    );
}

/// What a target without a rate says: `NoReading` names the target, the row and why.
#[test]
fn a_target_without_a_rate_is_said_naming_the_target_and_the_row() {
    use elastokin_suspensions::design::tune::NoReading;
    use elastokin_suspensions::design::NoDerivative;
    let e = NoReading::CellRate { label: "targets[1] (roll/toe_deg)".into(), at: 2.5, why: NoDerivative::Kink };
    assert_eq!(
        e.to_string(),
        "targets[1] (roll/toe_deg): at 2.5: not smooth in the parameter here (a stop touching or a reading \
         switching as it moves): no derivative"
    );
}

/// A parameter is printed as an engineer names it: a hardpoint's coordinate as the point and its axis, its
/// value in millimetres; any other number by its pointer, as the file gives it.
#[test]
fn parameters_are_named_and_valued_as_an_engineer_writes_them() {
    use elastokin_suspensions::design::{parameter_value_words, parameter_words};
    for (pointer, words) in [
        ("/suspension/macpherson/hardpoints/tie_rod_inner/2", "tie_rod_inner z"),
        ("/suspension/general/hardpoints/toe_link_outer/0", "toe_link_outer x"),
        ("/suspension/general/axle/hardpoints/tube_left/1", "axle tube_left y"),
        ("/Tierod/Location Chassis/2", "Tierod Location Chassis z"),
        ("/suspension/macpherson/spring/rate", "/suspension/macpherson/spring/rate"),
        ("/suspension/general/bodies/2/at/1", "/suspension/general/bodies/2/at/1"),
    ] {
        assert_eq!(parameter_words(pointer), words, "{pointer}");
    }
    assert_eq!(parameter_value_words("/suspension/macpherson/hardpoints/tie_rod_inner/2", -0.0374142), "-37.4142 mm");
    assert_eq!(parameter_value_words("/suspension/macpherson/spring/rate", 30000.0), "30000.0");
}
