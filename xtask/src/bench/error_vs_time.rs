//! Error against run time on the shipped models, for the vertical force sweep (the paper's case) and for
//! parallel wheel travel: paper mode at load steps of 1…300 N (or the travel steps that match them through
//! the wheel rate), corrected mode in 1…160 steps with and without factorization reuse.
//!
//! Error is the largest difference over the sweep of toe, camber and wheel-centre position from a
//! converged reference: the same corner walked in corrected mode in fine steps at a thousand times the
//! default tolerance, then brought to equilibrium at exactly every load parameter the measured run visits.
//! Run time is the median wall time of `StaticSolver::new` + `sweep` (what a caller pays), repeated.

use super::models::{self, Case, Sweep, SHIPPED};
use super::report::{slug, Cell, Judge, Kind, SectionOutput, Table, Target};
use super::Settings;
use elastokin::plot::{self, Chart, Scale, Series, YAxis};
use elastokin_solver::{Counters, LoadPath, Mode, SolverError, SolverOptions, StaticSolver, StepResult};
use elastokin_suspensions::analysis::slope_at;
use elastokin_suspensions::WheelAttitude;
use std::collections::HashMap;

/// Paper-mode load steps (N); on parallel travel the travel step is this over the wheel rate.
const FORCE_STEPS: [f64; 6] = [1.0, 3.0, 10.0, 30.0, 100.0, 300.0];
/// Corrected-mode step counts over the whole range (160 steps = the 161 points of the 2 ms target).
const CORRECTED_STEPS: [usize; 6] = [1, 2, 5, 10, 50, 160];
/// Fine steps of the reference path.
const REFERENCE_STEPS: usize = 320;

/// The converged reference: equilibrium at any load parameter, from the nearest point of a fine path.
struct Reference<'m> {
    solver: StaticSolver<'m>,
    path: Vec<StepResult>,
    cache: HashMap<u64, WheelAttitude>,
    case: &'m Case,
}

impl<'m> Reference<'m> {
    fn new(case: &'m Case) -> Result<Self, SolverError> {
        let mut solver = StaticSolver::new(&case.corner.model, models::tight_options())?;
        let path = solver.sweep(LoadPath::new(case.from, case.to, REFERENCE_STEPS), Mode::Corrected)?.complete()?.steps;
        Ok(Reference { solver, path, cache: HashMap::new(), case })
    }

    fn at(&mut self, t: f64) -> Result<WheelAttitude, SolverError> {
        if let Some(a) = self.cache.get(&t.to_bits()) {
            return Ok(*a);
        }
        let nearest = self
            .path
            .iter()
            .min_by(|a, b| (a.t - t).abs().total_cmp(&(b.t - t).abs()))
            .expect("the reference path has its first point");
        let mut state = self.solver.state_of(nearest);
        state.t = t;
        self.solver.equilibrium(&mut state)?;
        let a = self.case.corner.wheel.attitude(&state.poses);
        self.cache.insert(t.to_bits(), a);
        Ok(a)
    }

    /// Wheel rate at design (N/m): slope of the travel driver's vertical reaction on the reference path.
    fn wheel_rate(&self) -> Option<f64> {
        let model = &self.case.corner.model;
        let driver = model.joint_id("wheel travel")?;
        let rows: Vec<(f64, f64)> =
            self.path.iter().map(|s| (s.t, s.joint_reactions(model)[driver.0].force.z)).collect();
        slope_at(&rows, 0.0, |r| r.0, |r| r.1).map(f64::abs).filter(|k| k.is_finite() && *k > 0.0)
    }
}

/// One measured configuration.
struct Run {
    mode: Mode,
    reuse: bool,
    steps: usize,
    outcome: Result<Outcome, String>,
}

struct Outcome {
    toe: f64,
    camber: f64,
    wheel_centre: f64,
    drift: f64,
    force_residual: f64,
    max_relative_residual: f64,
    iterations: usize,
    time: f64,
    reps: usize,
    counters: Counters,
}

impl Outcome {
    fn attitude_error(&self) -> f64 {
        self.toe.max(self.camber)
    }
}

fn measure(case: &Case, reference: &mut Reference, mode: Mode, steps: usize, reuse: bool, s: &Settings) -> Run {
    let options = SolverOptions { reuse_factorization: reuse, ..SolverOptions::default() };
    let path = LoadPath::new(case.from, case.to, steps);
    let once = || -> Result<_, SolverError> {
        let mut solver = StaticSolver::new(&case.corner.model, options.clone())?;
        let sweep = solver.sweep(path, mode)?.complete()?;
        Ok((sweep, solver.counters()))
    };
    let outcome = (|| -> Result<Outcome, String> {
        let (sweep, counters) = once().map_err(|e| e.to_string())?;
        let (mut toe, mut camber, mut wc) = (0.0f64, 0.0f64, 0.0f64);
        for step in &sweep.steps {
            let a = case.corner.wheel.attitude(&step.poses);
            let r = reference.at(step.t).map_err(|e| format!("reference at t = {}: {e}", step.t))?;
            toe = toe.max((a.toe - r.toe).abs().to_degrees());
            camber = camber.max((a.camber - r.camber).abs().to_degrees());
            wc = wc.max((a.wheel_centre - r.wheel_centre).norm() * 1e3);
        }
        let last = sweep.steps.last().expect("a sweep has its first state");
        let timing = s.budget().time(once);
        Ok(Outcome {
            toe,
            camber,
            wheel_centre: wc,
            drift: last.constraint_residual,
            force_residual: last.force_residual / last.force_scale,
            max_relative_residual: sweep.steps.iter().map(|r| r.force_residual / r.force_scale).fold(0.0, f64::max),
            iterations: sweep.steps.iter().map(|r| r.iterations).sum(),
            time: timing.median,
            reps: timing.reps,
            counters,
        })
    })();
    Run { mode, reuse, steps, outcome }
}

fn mode_label(mode: Mode, reuse: bool) -> &'static str {
    match (mode, reuse) {
        (Mode::Paper, _) => "paper",
        (Mode::Corrected, false) => "corrected",
        (Mode::Corrected, true) => "corrected, reuse",
    }
}

/// Runs the section.
pub fn run(s: &Settings) -> SectionOutput {
    let mut out = SectionOutput {
        title: "Error against run time".into(),
        intro: "Shipped models, default solver options. Error: largest difference over the sweep from a \
                converged reference (corrected mode, 320 steps, tolerances ×1e-3, re-solved at every load \
                parameter the run visits). Time: median wall time of `StaticSolver::new` + `sweep`. Drift \
                and force residual: at the last step (force residual relative to the force scale). Paper-mode \
                travel steps are the force steps over the measured wheel rate."
            .into(),
        ..SectionOutput::default()
    };
    let mut table = Table::new(
        "Error against run time",
        "error_vs_time.csv",
        &[
            "model",
            "sweep",
            "mode",
            "steps",
            "step",
            "step unit",
            "time (ms)",
            "reps",
            "toe error (deg)",
            "camber error (deg)",
            "wheel-centre error (mm)",
            "drift at end (m)",
            "force residual at end (rel.)",
            "iterations",
            "symbolic",
            "factorizations",
            "solves",
            "status",
        ],
    );
    for (model_name, stem) in SHIPPED {
        for sweep in Sweep::ALL {
            let case_name = format!("{model_name}, {}", sweep.name());
            let prepared = models::shipped(stem).and_then(|f| models::case(&f, sweep));
            let case = match prepared {
                Ok(c) => c,
                Err(e) => {
                    table.row(
                        vec![Cell::text(model_name), Cell::text(sweep.name())].into_iter().chain(failed(&e)).collect(),
                    );
                    continue;
                }
            };
            let mut reference = match Reference::new(&case) {
                Ok(r) => r,
                Err(e) => {
                    let e = format!("reference failed: {e}");
                    table.row(
                        vec![Cell::text(model_name), Cell::text(sweep.name())].into_iter().chain(failed(&e)).collect(),
                    );
                    continue;
                }
            };
            // Paper steps: force steps directly, or travel steps through the wheel rate.
            let (unit, per_newton) = match sweep {
                Sweep::VerticalForce => ("N", Some(1.0)),
                Sweep::ParallelTravel => ("mm", reference.wheel_rate().map(|k| 1e3 / k)),
            };
            let range = case.to - case.from;
            let mut runs = Vec::new();
            match per_newton {
                Some(per_n) => {
                    for df in FORCE_STEPS {
                        let step = df * per_n; // N, or mm of travel
                        let range_in_unit = if unit == "mm" { range * 1e3 } else { range };
                        let steps = (range_in_unit / step).round().max(1.0) as usize;
                        runs.push(measure(&case, &mut reference, Mode::Paper, steps, false, s));
                    }
                }
                None => out.notes.push(format!("{case_name}: no wheel rate from the reference, paper rows not run")),
            }
            for steps in CORRECTED_STEPS {
                for reuse in [false, true] {
                    runs.push(measure(&case, &mut reference, Mode::Corrected, steps, reuse, s));
                }
            }
            let setup = s.budget().time(|| StaticSolver::new(&case.corner.model, SolverOptions::default()).map(drop));
            out.figure(&format!("error_vs_time.{}.setup_s", slug(&case_name)), setup.median, "s", Kind::Time);
            let mut series: Vec<Series> = Vec::new();
            for r in &runs {
                let label = mode_label(r.mode, r.reuse);
                let step = range / r.steps as f64 * if unit == "mm" { 1e3 } else { 1.0 };
                let mut row = vec![
                    Cell::text(model_name),
                    Cell::text(sweep.name()),
                    Cell::text(label),
                    Cell::count(r.steps as u64),
                    Cell::num(step),
                    Cell::text(unit),
                ];
                match &r.outcome {
                    Ok(o) => {
                        row.extend([
                            Cell::num(o.time * 1e3),
                            Cell::count(o.reps as u64),
                            Cell::Num(o.toe, 2),
                            Cell::Num(o.camber, 2),
                            Cell::Num(o.wheel_centre, 2),
                            Cell::Num(o.drift, 2),
                            Cell::Num(o.force_residual, 2),
                            Cell::count(o.iterations as u64),
                            Cell::count(o.counters.factor.symbolic_analyses),
                            Cell::count(o.counters.factor.numeric_factorizations),
                            Cell::count(o.counters.factor.solves),
                            Cell::text("ok"),
                        ]);
                        let key = format!("error_vs_time.{}.{}.{}", slug(&case_name), slug(label), r.steps);
                        out.figure(&format!("{key}.time_s"), o.time, "s", Kind::Time);
                        out.figure(&format!("{key}.attitude_error_deg"), o.attitude_error(), "deg", Kind::Accuracy);
                        out.figure(&format!("{key}.wheel_centre_error_mm"), o.wheel_centre, "mm", Kind::Accuracy);
                        out.figure(
                            &format!("{key}.factorizations"),
                            o.counters.factor.numeric_factorizations as f64,
                            "",
                            Kind::Other,
                        );
                        let name = label.to_string();
                        match series.iter_mut().find(|x| x.name == name) {
                            Some(x) => x.points.push((o.time, o.attitude_error())),
                            None => series.push(Series { name, points: vec![(o.time, o.attitude_error())] }),
                        }
                    }
                    Err(e) => row.extend(failed(e).into_iter().skip(4)),
                }
                table.row(row);
            }
            // The 161-point corrected travel sweep target.
            if sweep == Sweep::ParallelTravel {
                let best = runs
                    .iter()
                    .filter(|r| r.mode == Mode::Corrected && r.steps == 160)
                    .filter_map(|r| r.outcome.as_ref().ok().map(|o| (r.reuse, o)))
                    .min_by(|a, b| a.1.time.total_cmp(&b.1.time));
                let points = 161.0;
                out.targets.push(Target {
                    goal: format!(
                        "{model_name}: corrected parallel travel, 161 points to 1e-9 relative residual, one core, per point"
                    ),
                    measured: best
                        .map(|(_, o)| o.time * 1e6 / points)
                        .ok_or_else(|| "the 160-step corrected sweep failed".into()),
                    limit: 6.0,
                    unit: "µs".into(),
                    judge: Judge::AtMost,
                    detail: best.map_or_else(String::new, |(reuse, o)| {
                        format!(
                            "median of {} runs of StaticSolver::new + sweep, {:.3} ms in all ({:.3} ms of it setup), {}, largest relative residual {:.1e}, {} factorizations",
                            o.reps,
                            o.time * 1e3,
                            setup.median * 1e3,
                            if reuse { "predictor and chord iterations (reuse_factorization)" } else { "full Newton" },
                            o.max_relative_residual,
                            o.counters.factor.numeric_factorizations
                        )
                    }),
                });
            }
            for x in &mut series {
                x.points.sort_by(|a, b| a.0.total_cmp(&b.0));
            }
            let chart = Chart {
                name: format!("error_vs_time_{}", slug(&case_name)),
                title: "error against run time".into(),
                subtitle: case_name.clone(),
                x_label: "median run time [s]".into(),
                x_scale: Scale::Log,
                left: YAxis { label: "largest toe or camber error [deg]".into(), scale: Scale::Log, series },
                right: None,
                design_x: None,
            };
            match plot::svg(&chart) {
                Ok(svg) => out.plots.push((
                    format!("{}.svg", chart.name),
                    svg,
                    format!("{case_name}: error against run time, one line per mode"),
                )),
                Err(e) => out.notes.push(format!("{case_name}: the error against run time plot was not drawn: {e}")),
            }
        }
    }
    out.tables.push(table);
    out
}

/// The cells of a failed row from the "time" column on: empty measurements and the error as status.
fn failed(e: &str) -> Vec<Cell> {
    let mut cells = vec![Cell::Empty; 16];
    cells[15] = Cell::text(format!("failed: {e}"));
    cells
}
