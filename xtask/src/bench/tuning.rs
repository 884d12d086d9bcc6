//! Tuning: the MacPherson's toe curve over ±50 mm (11 points, tolerance 0.005°) made from the model with
//! its inner tie-rod point 4 mm higher and its outer one 3 mm further back, tuned back from the model as it
//! is with both tie-rod points free (six numbers, ±20 mm each), by the two candidates measured for
//! `elastokin tune`: its bound-constrained Gauss–Newton (`design::tune`, Clarabel for the steps that meet
//! a bound) and `optimization_engine`'s PANOC (a first-order method with L-BFGS for problems with simple
//! constraints) on the same objective and exact gradient. Each evaluation is a K&C run with its
//! sensitivities; the time, the evaluations and the miss left say which to ship.

use super::models;
use super::report::{Cell, Judge, Kind, SectionOutput, Table, Target};
use super::Settings;
use elastokin_suspensions::design::targets::{read_targets, Targets};
use elastokin_suspensions::design::tune::{evaluate, tune};
use elastokin_suspensions::design::Parameters;
use elastokin_suspensions::kc::{self, Analysis};
use serde_json::{json, Value};
use std::cell::RefCell;

const H: &str = "/suspension/macpherson/hardpoints";

/// The problem: the model, its targets, the free numbers.
fn problem() -> Result<(Parameters, Targets), String> {
    let base = models::shipped_document("generic/macpherson")?;
    let mut hidden = base.clone();
    for (pointer, by) in [(format!("{H}/tie_rod_inner/2"), 0.004), (format!("{H}/tie_rod_outer/0"), -0.003)] {
        let v = hidden.pointer(&pointer).and_then(Value::as_f64).ok_or("no tie rod")? + by;
        *hidden.pointer_mut(&pointer).ok_or("no tie rod")? = json!(v);
    }
    let file = Parameters::new(&hidden, &[]).and_then(|p| p.file()).map_err(|e| e.to_string())?;
    let settings = kc::Settings { range: Some((-0.05, 0.05)), steps: 20, ..kc::Settings::default() };
    let r = kc::run(Analysis::ParallelTravel, &file, &settings).map_err(|e| e.to_string())?;
    let c = r.table.columns.iter().position(|x| x == "toe_deg").ok_or("no toe column")?;
    let points: Vec<(f64, f64)> =
        r.table.rows.iter().step_by(2).filter_map(|row| Some((row[0].number()?, row[c].number()?))).collect();
    let mut free = serde_json::Map::new();
    for point in ["tie_rod_inner", "tie_rod_outer"] {
        for i in 0..3 {
            let pointer = format!("{H}/{point}/{i}");
            let v = base.pointer(&pointer).and_then(Value::as_f64).ok_or("no tie rod")?;
            free.insert(pointer, json!([v - 0.02, v + 0.02]));
        }
    }
    let text = json!({
        "free": free,
        "targets": [{ "curve": "parallel-travel/toe_deg", "range": [-0.05, 0.05], "points": points, "tolerance": 0.005 }],
        "steps": 20,
    })
    .to_string();
    let targets = read_targets(&text, "bench", &base, |_| Err("no files".into())).map_err(|e| e.to_string())?;
    let pointers: Vec<String> = targets.free.iter().map(|f| f.pointer.clone()).collect();
    Ok((Parameters::new(&base, &pointers).map_err(|e| e.to_string())?, targets))
}

/// What one candidate reached: the largest miss of the curve (deg) and the evaluations it took.
struct Outcome {
    miss: f64,
    evaluations: usize,
}

fn gauss_newton(p: &Parameters, targets: &Targets) -> Result<Outcome, String> {
    let tuned = tune(p, targets, |_| {}).map_err(|e| e.to_string())?;
    let miss = tuned.end.rows.iter().map(|r| (r.value - r.aim).abs()).fold(0.0, f64::max);
    Ok(Outcome { miss, evaluations: tuned.iterations.last().map_or(0, |i| i.evaluations) })
}

/// A point, the cost there and its gradient.
type Evaluated = (Vec<f64>, f64, Vec<f64>);

fn panoc(p: &Parameters, targets: &Targets) -> Result<Outcome, String> {
    use optimization_engine::{constraints::Rectangle, panoc::PANOCCache, panoc::PANOCOptimizer, Problem, SolverError};
    // PANOC asks for the cost and the gradient apart; one evaluation gives both, kept for the next call.
    let last: RefCell<Option<Evaluated>> = RefCell::new(None);
    let evaluations = RefCell::new(0usize);
    let at = |u: &[f64]| -> Result<(f64, Vec<f64>), SolverError> {
        if let Some((x, f, g)) = last.borrow().as_ref() {
            if x == u {
                return Ok((*f, g.clone()));
            }
        }
        *evaluations.borrow_mut() += 1;
        let e = evaluate(p, targets, u).map_err(|_| SolverError::Cost("the model could not be evaluated"))?;
        let (f, g) = (e.objective(), e.gradient());
        *last.borrow_mut() = Some((u.to_vec(), f, g.clone()));
        Ok((f, g))
    };
    let f = |u: &[f64], c: &mut f64| -> Result<(), SolverError> {
        *c = at(u)?.0;
        Ok(())
    };
    let df = |u: &[f64], grad: &mut [f64]| -> Result<(), SolverError> {
        grad.copy_from_slice(&at(u)?.1);
        Ok(())
    };
    let lo: Vec<f64> = targets.free.iter().map(|f| f.min).collect();
    let hi: Vec<f64> = targets.free.iter().map(|f| f.max).collect();
    let bounds = Rectangle::new(Some(&lo), Some(&hi));
    let problem = Problem::new(&bounds, df, f);
    let mut cache = PANOCCache::new(p.len(), 1e-12, 10);
    let mut optimizer = PANOCOptimizer::new(problem, &mut cache).with_max_iter(300);
    let mut u = p.values.clone();
    optimizer.solve(&mut u).map_err(|e| format!("{e:?}"))?;
    let e = evaluate(p, targets, &u).map_err(|e| e.to_string())?;
    let miss = e.rows.iter().map(|r| (r.value - r.aim).abs()).fold(0.0, f64::max);
    let evaluations = *evaluations.borrow();
    Ok(Outcome { miss, evaluations })
}

/// Runs the section.
pub fn run(s: &Settings) -> SectionOutput {
    let mut out = SectionOutput {
        title: "Tuning".into(),
        intro: "The MacPherson's toe curve over ±50 mm (11 points, tolerance 0.005°), made from the model with \
                hidden moves of its tie-rod points (inner +4 mm in z, outer −3 mm in x), tuned back with both \
                tie-rod points free (six numbers, ±20 mm each): `elastokin tune`'s bound-constrained \
                Gauss–Newton against optimization_engine's PANOC on the same objective and exact gradient. \
                Each evaluation is a run of parallel travel with its sensitivities. Medians of repeated runs."
            .into(),
        ..SectionOutput::default()
    };
    let mut table = Table::new(
        "Tuning",
        "tuning.csv",
        &["method", "median time (s)", "evaluations", "largest miss (deg)", "status"],
    );
    let (p, targets) = match problem() {
        Ok(v) => v,
        Err(e) => {
            table.failed_row(Vec::new(), e);
            out.tables.push(table);
            return out;
        }
    };
    let mut gn_time = None;
    for (name, method) in [
        (
            "Gauss–Newton, Clarabel where bounds bind (elastokin tune)",
            gauss_newton as fn(&Parameters, &Targets) -> Result<Outcome, String>,
        ),
        ("PANOC with L-BFGS (optimization_engine)", panoc),
    ] {
        match method(&p, &targets) {
            Err(e) => table.failed_row(vec![Cell::text(name)], e),
            Ok(outcome) => {
                let timing = s.batch_budget().time(|| method(&p, &targets));
                if gn_time.is_none() {
                    gn_time = Some((timing.median, outcome.miss, outcome.evaluations));
                }
                let key = if name.starts_with("Gauss") { "gauss_newton" } else { "panoc" };
                out.figure(&format!("tuning.{key}_s"), timing.median, "s", Kind::Time);
                table.row(vec![
                    Cell::text(name),
                    Cell::num(timing.median),
                    Cell::count(outcome.evaluations as u64),
                    Cell::num(outcome.miss),
                    Cell::text(if outcome.miss <= 1e-6 { "ok" } else { "miss over 1e-6 deg" }),
                ]);
            }
        }
    }
    if let Some((time, miss, evaluations)) = gn_time {
        out.targets.push(Target {
            goal: "tune the MacPherson's toe curve with both tie-rod points free to within 1e-6 deg".into(),
            measured: Ok(time),
            limit: 0.5,
            unit: "s".into(),
            judge: Judge::AtMost,
            detail: format!("{evaluations} evaluations, largest miss {miss:.1e} deg"),
        });
    }
    out.tables.push(table);
    out
}
