//! A curve target measured as a whole: the root mean square of its miss, or the area between the curves,
//! over its points' span. Each measure against the integral of a fine run by Simpson's rule; a tune by the
//! root mean square against the least one that re-runs of the moved model find; the verdict on both sides
//! of the tolerance, as `tune` and `run --targets` give it; and the files refused by key.

use elastokin_suspensions::design::judge::judge;
use elastokin_suspensions::design::targets::{read_targets, read_targets_as, Reading, Targets, TargetsRefusal};
use elastokin_suspensions::design::tune::{evaluate, tune};
use elastokin_suspensions::design::Parameters;
use elastokin_suspensions::kc::{self, Analysis, Settings};
use elastokin_suspensions::study::batch::base_document;
use serde_json::{json, Value};

fn document() -> Value {
    let path = format!("{}/../../examples/macpherson.json", env!("CARGO_MANIFEST_DIR"));
    base_document(&std::fs::read_to_string(&path).unwrap(), &path).unwrap()
}

const INNER_Z: &str = "/suspension/macpherson/hardpoints/tie_rod_inner/2";
const SPAN: (f64, f64) = (-0.05, 0.05);
/// The target curve: straight between these (m, deg), bent at design.
const AIMS: [(f64, f64); 3] = [(-0.05, 0.30), (0.0, 0.0), (0.05, -0.20)];

fn no_file(name: &str) -> Result<String, String> {
    Err(format!("no file {name}"))
}

fn with(doc: &Value, pointer: &str, v: f64) -> Value {
    let mut doc = doc.clone();
    *doc.pointer_mut(pointer).unwrap() = json!(v);
    doc
}

/// The target curve's value at `s`, straight between [`AIMS`].
fn aim(s: f64) -> f64 {
    let k = if s <= AIMS[1].0 { 0 } else { 1 };
    let ((s0, v0), (s1, v1)) = (AIMS[k], AIMS[k + 1]);
    v0 + (v1 - v0) * (s - s0) / (s1 - s0)
}

/// The integrals over [`SPAN`] of the toe curve's miss squared and of its size, by Simpson's rule over a
/// parallel-travel run of `steps` steps (even, and a multiple of 2 either side of design, where the target
/// bends, so that no panel straddles the bend).
fn integrals(doc: &Value, steps: usize) -> (f64, f64) {
    let file = Parameters::new(doc, &[]).unwrap().file().unwrap();
    let settings = Settings { range: Some(SPAN), steps, ..Settings::default() };
    let r = kc::run(Analysis::ParallelTravel, &file, &settings).unwrap();
    let c = r.table.columns.iter().position(|x| x == "toe_deg").unwrap();
    let e: Vec<f64> = r.table.rows.iter().map(|row| row[c].number().unwrap() - aim(row[0].number().unwrap())).collect();
    let h = (SPAN.1 - SPAN.0) / steps as f64;
    let simpson = |f: &dyn Fn(f64) -> f64| {
        (0..=steps)
            .map(|i| {
                f(e[i])
                    * if i == 0 || i == steps {
                        1.0
                    } else if i % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    }
            })
            .sum::<f64>()
            * h
            / 3.0
    };
    (simpson(&|x| x * x), simpson(&|x: f64| x.abs()))
}

/// The targets: the toe curve through [`AIMS`] measured by its root mean square (tolerance `rms`, deg) and
/// by the area between the curves (tolerance `area`, deg·m), `steps` steps, the inner tie-rod point's z
/// free within ±10 mm.
fn targets(doc: &Value, rms: f64, area: f64, steps: usize) -> Targets {
    let z = doc.pointer(INNER_Z).unwrap().as_f64().unwrap();
    let curve = |measure: &str, tolerance: f64| {
        json!({ "curve": "parallel-travel/toe_deg", "range": [SPAN.0, SPAN.1], "points": AIMS.map(|(s, v)| [s, v]),
                "measure": measure, "tolerance": tolerance })
    };
    let text = json!({ "free": { INNER_Z: [z - 0.01, z + 0.01] }, "targets": [curve("rms", rms), curve("area", area)],
                       "steps": steps })
    .to_string();
    read_targets(&text, "targets.json", doc, no_file).unwrap()
}

/// Target `k`'s measure over its tolerance at the evaluation `e` of `t`.
fn measured(t: &Targets, e: &elastokin_suspensions::design::tune::Evaluation, k: usize) -> f64 {
    let target = &t.targets[k];
    let (misses, weights): (Vec<f64>, Vec<f64>) =
        e.rows.iter().filter(|r| r.target == k).map(|r| ((r.value - r.aim) / target.tolerance, r.weight)).unzip();
    target.measured(&misses, &weights)
}

/// The root mean square and the area over the rows of 20 and of 80 steps, against Simpson's rule over 400:
/// both converge at the second order of the rows' spacing (measured: the root mean square, 0.141 deg, is
/// 4.7e-4 deg off at 20 steps and 3.0e-5 deg at 80, a 16× fall; the area, 0.0102 deg·m, 2.2e-5 and
/// 1.4e-6 deg·m); and the objective of the root mean square's readings is its square over the
/// tolerance's.
#[test]
fn the_root_mean_square_and_the_area_of_a_curve_miss_are_its_integrals_over_the_span() {
    let doc = document();
    let (squared, size) = integrals(&doc, 400);
    let length = SPAN.1 - SPAN.0;
    let (rms, area) = ((squared / length).sqrt(), size);
    assert!(rms > 0.01 && area > 1e-3, "the miss is real: {rms} deg, {area} deg·m");
    let z = doc.pointer(INNER_Z).unwrap().as_f64().unwrap();
    let mut errors = Vec::new();
    for steps in [20, 80] {
        let t = targets(&doc, 0.01, 0.001, steps);
        let e = evaluate(&Parameters::new(&doc, &[INNER_Z.to_string()]).unwrap(), &t, &[z]).unwrap();
        let (got_rms, got_area) = (measured(&t, &e, 0) * 0.01, measured(&t, &e, 1) * 0.001);
        errors.push(((got_rms - rms).abs(), (got_area - area).abs()));
        // The readings' residuals square to the measure over the tolerance, squared.
        let objective: f64 = e.rows.iter().zip(&e.residuals).filter(|(r, _)| r.target == 0).map(|(_, r)| r * r).sum();
        assert!((objective.sqrt() - got_rms / 0.01).abs() < 1e-12 * objective.sqrt(), "{objective} {got_rms}");
        // The area's residuals square to the span times the root mean square, which bounds the area.
        let bound: f64 = e.rows.iter().zip(&e.residuals).filter(|(r, _)| r.target == 1).map(|(_, r)| r * r).sum();
        assert!((bound.sqrt() * 0.001 - length * got_rms).abs() < 1e-12 * length * got_rms, "{bound}");
        assert!(got_area <= length * got_rms, "{got_area} {got_rms}");
    }
    let [(rms20, area20), (rms80, area80)] = errors[..] else { unreachable!() };
    assert!(rms20 < 1e-3 && area20 < 5e-5, "{errors:?}");
    assert!(rms80 < rms20 / 8.0 && area80 < area20 / 8.0, "second order: {errors:?}");
}

/// The verdict on either side of the tolerance, as `tune` and `run --targets` give it: a root mean square
/// (and an area) 5 % inside its tolerance is met though the worst reading misses by several tolerances; 5 %
/// beyond it, not. The measures are Simpson's over 400 steps, which the 20 steps' quadrature meets to 0.3 %
/// (the first test), well inside the 5 %.
#[test]
fn a_curve_measured_whole_is_met_on_its_measure_not_its_worst_reading() {
    let doc = document();
    let steps = 20;
    let (squared, size) = integrals(&doc, 400);
    let (rms, area) = ((squared / (SPAN.1 - SPAN.0)).sqrt(), size);
    let t = targets(&doc, 1.0, 1.0, steps);
    let z = doc.pointer(INNER_Z).unwrap().as_f64().unwrap();
    let e = evaluate(&Parameters::new(&doc, &[INNER_Z.to_string()]).unwrap(), &t, &[z]).unwrap();
    let worst = e.rows.iter().filter(|r| r.target == 0).map(|r| (r.value - r.aim).abs()).fold(0.0, f64::max);
    assert!(worst > 1.5 * rms, "the worst reading misses by more than the root mean square: {worst} {rms}");
    let file = Parameters::new(&doc, &[]).unwrap().file().unwrap();
    let settings = Settings { range: Some(SPAN), steps, ..Settings::default() };
    let report = kc::run_suite(&file, &[Analysis::ParallelTravel], &settings, |_| {});
    for (scale, met) in [(1.05, true), (0.95, false)] {
        let (rms_tolerance, area_tolerance) = (scale * rms, scale * area);
        let t = targets(&doc, rms_tolerance, area_tolerance, steps);
        let parameters = Parameters::new(&doc, &[INNER_Z.to_string()]).unwrap();
        let e = evaluate(&parameters, &t, &[z]).unwrap();
        for k in 0..2 {
            assert_eq!(measured(&t, &e, k) <= 1.0, met, "target {k} at {scale}");
        }
        // Judged as `run --targets` judges: every reading of a target met or not with it.
        let text = json!({ "targets": [
            { "curve": "parallel-travel/toe_deg", "points": AIMS.map(|(s, v)| [s, v]), "measure": "rms",
              "tolerance": rms_tolerance },
            { "curve": "parallel-travel/toe_deg", "points": AIMS.map(|(s, v)| [s, v]), "measure": "area",
              "tolerance": area_tolerance } ]})
        .to_string();
        let judged = read_targets_as(Reading::ToJudge, &text, "t.json", &doc, no_file).unwrap();
        let (points, _) = judge(&report, &doc, &judged);
        // Three points and the 19 rows between the ends, each target.
        assert_eq!(points.len(), 2 * 21, "{}", points.len());
        assert!(points.iter().all(|p| p.met() == met), "{scale}");
    }
}

/// A tune of the inner tie-rod point's z to the least root mean square of the toe curve's miss, against
/// the least that re-runs of the moved model find (the vertex of the parabola through Simpson's integrals
/// at the tuned z and 0.5 mm either side, over 200 steps): they agree to what the tune's 20 steps of
/// quadrature leave (measured 1.1e-6 m); the tune by the three points alone ends 48 times as far away
/// (5.5e-5 m), so the measure is what was tuned.
#[test]
fn a_tune_by_the_root_mean_square_ends_at_its_least() {
    let doc = document();
    let t = targets(&doc, 1e-4, 1.0, 20);
    // The root mean square alone.
    let t = Targets { targets: vec![t.targets[0].clone()], ..t };
    let parameters = Parameters::new(&doc, &[INNER_Z.to_string()]).unwrap();
    let tuned = tune(&parameters, &t, |_| {}).unwrap();
    let z = tuned.end.x[0];
    // tune_targets.csv gives each reading's own miss over the tolerance, not its scaled residual.
    let table = tuned.residual_table(&t);
    let column = |name: &str| table.column(name).unwrap();
    let (aim, after, miss) = (column("aim"), column("after"), column("miss_over_tolerance_after"));
    for ((aim, after), miss) in aim.iter().zip(&after).zip(&miss) {
        assert_eq!(*miss, Some((after.unwrap() - aim.unwrap()) / 1e-4), "{aim:?} {after:?}");
    }
    let d = 5e-4;
    let f = |z: f64| integrals(&with(&doc, INNER_Z, z), 200).0;
    let (a, b, c) = (f(z - d), f(z), f(z + d));
    assert!(a > b && c > b, "the tuned z is a least: {a} {b} {c}");
    let vertex = z + d * (a - c) / (2.0 * (a - 2.0 * b + c));
    assert!((vertex - z).abs() < 2e-5, "tuned {z}, least of the re-runs {vertex}");
    // The same curve tuned by its three points: the least squares of the points alone.
    let mut by_points = t.clone();
    let text = json!({ "free": { INNER_Z: [t.free[0].min, t.free[0].max] }, "targets": [
        { "curve": "parallel-travel/toe_deg", "range": [SPAN.0, SPAN.1], "points": AIMS.map(|(s, v)| [s, v]),
          "tolerance": 1e-4 } ], "steps": 20 })
    .to_string();
    by_points.targets = read_targets(&text, "t.json", &doc, no_file).unwrap().targets;
    let other = tune(&parameters, &by_points, |_| {}).unwrap().end.x[0];
    assert!((other - z).abs() > 20.0 * (vertex - z).abs(), "points {other}, rms {z}, least {vertex}");
}

#[test]
fn a_curve_measure_without_a_span_or_of_no_known_name_is_refused_by_key() {
    let doc = document();
    let z = doc.pointer(INNER_Z).unwrap().as_f64().unwrap();
    let file = |curve: Value| json!({ "free": { INNER_Z: [z - 0.01, z + 0.01] }, "targets": [curve] }).to_string();
    let cases = [
        (
            json!({ "curve": "parallel-travel/toe_deg", "points": [[0.0, 0.0], [0.01, 0.0]], "measure": "mean",
                    "tolerance": 0.1 }),
            "targets[0].measure: 'mean' is no curve measure",
        ),
        (
            json!({ "curve": "parallel-travel/toe_deg", "points": [[0.0, 0.0]], "measure": "rms", "tolerance": 0.1 }),
            "targets[0].points: a curve measured by its rms needs at least two points",
        ),
        (
            json!({ "curve": "parallel-travel/toe_deg", "points": [[0.01, 0.0], [0.0, 0.0]], "measure": "area",
                    "tolerance": 0.1 }),
            "in increasing order of the load parameter",
        ),
    ];
    for (curve, said) in cases {
        let e = read_targets(&file(curve), "t.json", &doc, no_file).unwrap_err();
        assert!(matches!(*e.refusal, TargetsRefusal::NoMeasure { .. } | TargetsRefusal::NoSpan { .. }), "{e}");
        assert!(e.to_string().contains(said), "{e}");
    }
}
