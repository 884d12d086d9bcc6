//! Cost of one load step against its floor, on the shipped models in the vertical force sweep (the
//! paper's case): assembly, element evaluation, constraint rows, numeric factorization, solve and
//! characteristics, each timed alone; whole paper and corrected steps; and one bare numeric factorization +
//! solve of the same KKT, the floor. Dense LU of the same KKT for comparison.

use super::alloc;
use super::models::{self, Sweep, SHIPPED};
use super::report::{slug, Cell, Judge, Kind, SectionOutput, Table, Target};
use super::Settings;
use elastokin_core::ElementEval;
use elastokin_solver::assembly::{Assembly, Tangent};
use elastokin_solver::dense_reference::solve_dense_pivoted;
use elastokin_solver::kkt_factor::{KktFactor, KktOptions};
use elastokin_solver::{LoadPath, Mode, SolverOptions, StaticSolver};
use nalgebra::{DMatrix, DVector};
use std::hint::black_box;

/// Steps over which a whole step's cost is averaged (the sweep's start, one assembly and in corrected
/// mode one factorization, is spread over them). The same in `--quick` and full runs: the step size decides
/// the Newton iterations of a corrected step, so runs compare only on the same path.
const SWEEP_STEPS: usize = 400;

struct Part {
    what: &'static str,
    seconds: f64,
    note: String,
}

fn measure_model(model_name: &str, stem: &str, s: &Settings, out: &mut SectionOutput) -> Result<Vec<Part>, String> {
    let case = models::shipped(stem).and_then(|f| models::case(&f, Sweep::VerticalForce))?;
    let model = &case.corner.model;
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let mut solver = StaticSolver::new(model, SolverOptions::default()).map_err(|e| err(&e))?;
    let mid = 0.5 * (case.from + case.to);
    let mut state = solver.design_state(mid);
    solver.equilibrium(&mut state).map_err(|e| err(&e))?;
    let budget = s.budget();
    let mut parts = Vec::new();

    // Assembly (element evaluation + constraint rows + scatter), with the paper tangent and the full one.
    let mut assembly = Assembly::new(model, solver.active_rows().to_vec());
    let (n, m) = (assembly.n, assembly.m());
    for (what, tangent) in [("assembly, paper tangent", Tangent::Paper), ("assembly, full tangent", Tangent::Full)] {
        let t = budget.time(|| assembly.assemble(model, &state.poses, state.t, &state.lambda, Some(tangent)));
        parts.push(Part { what, seconds: t.median, note: "includes the two rows below".into() });
    }
    // Element evaluation alone: every force element's force and 12×12 stiffness.
    let mut eval = ElementEval::default();
    let t = budget.time(|| {
        for e in model.elements() {
            let [i, j] = e.bodies();
            e.evaluate(&i.pose(&state.poses), &j.pose(&state.poses), state.t, &mut eval, true);
            black_box(&eval);
        }
    });
    parts.push(Part {
        what: "element evaluation",
        seconds: t.median,
        note: format!("{} elements, force and stiffness", model.elements().len()),
    });
    let t = budget.time(|| {
        for jt in model.joints() {
            let (pi, pj) = (jt.spec.body_i.pose(&state.poses), jt.spec.body_j.pose(&state.poses));
            for row in &jt.rows {
                black_box(row.evaluate(&pi, &pj, state.t));
            }
        }
    });
    parts.push(Part {
        what: "constraint rows",
        seconds: t.median,
        note: format!("{} rows, value and gradient", model.constraint_rows()),
    });

    // The floor: numeric factorization and solve of the same (paper-tangent) KKT on its own KktFactor.
    assembly.assemble(model, &state.poses, state.t, &state.lambda, Some(Tangent::Paper));
    let pattern = assembly.kkt_pattern();
    let symbolic = budget.time(|| KktFactor::analyze(&pattern, KktOptions::default()).map(drop));
    let mut factor = KktFactor::analyze(&pattern, KktOptions::default()).map_err(|e| err(&e))?;
    factor.factorize(&assembly.k_values, &assembly.j_values).map_err(|e| err(&e))?;
    let rhs0: Vec<f64> = (0..n + m).map(|k| if k < n { assembly.load_rate[k] } else { 0.0 }).collect();
    let mut rhs = rhs0.clone();
    let numeric = budget.time(|| factor.factorize(&assembly.k_values, &assembly.j_values).map(drop));
    let solve = budget.time(|| {
        rhs.copy_from_slice(&rhs0);
        factor.solve_in_place(&mut rhs).map(drop)
    });
    let (bare, bare_usage) = alloc::track(|| {
        budget.time(|| {
            factor.factorize(&assembly.k_values, &assembly.j_values).map(drop)?;
            rhs.copy_from_slice(&rhs0);
            factor.solve_in_place(&mut rhs).map(drop)
        })
    });
    parts.push(Part {
        what: "symbolic analysis",
        seconds: symbolic.median,
        note: "once per model; not part of a step".into(),
    });
    parts.push(Part {
        what: "numeric factorization",
        seconds: numeric.median,
        note: format!("n + m = {} + {}, {} factor entries", n, m, factor.factor_nnz()),
    });
    parts.push(Part { what: "solve (with refinement)", seconds: solve.median, note: String::new() });
    parts.push(Part {
        what: "bare factorization + solve (the floor)",
        seconds: bare.median,
        note: format!("{} allocations over {} runs", bare_usage.allocations, bare.reps + 1),
    });

    // Characteristics of one step: what a K&C sweep reads from its poses.
    let wheel = case.corner.wheel;
    let t = budget.time(|| {
        black_box(wheel.attitude(&state.poses));
        black_box(wheel.steering_geometry(&state.poses));
    });
    parts.push(Part {
        what: "characteristics",
        seconds: t.median,
        note: "toe, camber, wheel centre, steering axis".into(),
    });
    let result = solver.equilibrium(&mut state.clone()).map_err(|e| err(&e))?;
    let t = budget.time(|| {
        black_box(result.joint_reactions(model));
        black_box(result.element_reports(model));
    });
    parts.push(Part {
        what: "joint and element reports",
        seconds: t.median,
        note: "every joint reaction and element force".into(),
    });

    // Whole steps: a sweep of k steps from the equilibrium at the start, over k.
    let k = SWEEP_STEPS;
    let mut start = solver.design_state(case.from);
    solver.equilibrium(&mut start).map_err(|e| err(&e))?;
    let path = LoadPath::new(case.from, case.to, k);
    for (what, mode, reuse) in [
        ("paper step", Mode::Paper, false),
        ("corrected step", Mode::Corrected, false),
        ("corrected step, reuse", Mode::Corrected, true),
    ] {
        let options = SolverOptions { reuse_factorization: reuse, ..SolverOptions::default() };
        let mut solver = StaticSolver::new(model, options).map_err(|e| err(&e))?;
        let before = solver.counters();
        let (sweep, usage) = alloc::track(|| {
            solver.sweep_from(&mut start.clone(), path, mode).and_then(elastokin_solver::Sweep::complete)
        });
        let sweep = sweep.map_err(|e| format!("{what}: {e}"))?;
        let after = solver.counters();
        let t = budget.time(|| solver.sweep_from(&mut start.clone(), path, mode).map(drop));
        let iterations: usize = sweep.steps.iter().map(|r| r.iterations).sum();
        parts.push(Part {
            what,
            seconds: t.median / k as f64,
            note: format!(
                "{k} steps of {:.1} N: {:.2} iterations, {:.2} factorizations, {:.2} solves, {:.1} allocations per step",
                (case.to - case.from) / k as f64,
                iterations as f64 / k as f64,
                (after.factor.numeric_factorizations - before.factor.numeric_factorizations) as f64 / k as f64,
                (after.factor.solves - before.factor.solves) as f64 / k as f64,
                usage.allocations as f64 / k as f64,
            ),
        });
    }

    // Dense: the same tangent KKT as a dense matrix, LU with partial pivoting, and the pivoted reference.
    let (size, triplets) = solver.kkt_triplets(&state);
    let mut dense = DMatrix::<f64>::zeros(size, size);
    for (r, c, v) in triplets {
        dense[(r, c)] += v;
    }
    let b = DVector::from_column_slice(&rhs0);
    let t = budget.time(|| dense.clone().lu().solve(&b));
    parts.push(Part {
        what: "dense LU + solve (nalgebra, partial pivoting)",
        seconds: t.median,
        note: format!("order {size}"),
    });
    let kd = dense.view((0, 0), (n, n)).into_owned();
    let jd = dense.view((n, 0), (m, n)).into_owned();
    let t = budget.time(|| solve_dense_pivoted(n, m, &kd, &jd, &rhs0));
    parts.push(Part {
        what: "dense pivoted reference (equilibrated full-pivot LU + 2 refinements)",
        seconds: t.median,
        note: String::new(),
    });

    let key = slug(model_name);
    for p in &parts {
        out.figure(&format!("step_cost.{key}.{}_s", slug(p.what)), p.seconds, "s", Kind::Time);
    }
    Ok(parts)
}

/// Runs the section.
pub fn run(s: &Settings) -> SectionOutput {
    let mut out = SectionOutput {
        title: "Cost of one step against its floor".into(),
        intro: "Vertical force sweep (the paper's case) of the shipped models, at the equilibrium halfway \
                along it. Each part is timed alone (median); a whole step is a sweep of many steps from the \
                equilibrium at the start, divided by the step count. Ratios are to one bare numeric \
                factorization + solve of the same KKT on its own factorization object."
            .into(),
        ..SectionOutput::default()
    };
    let mut table = Table::new(
        "Cost of one step",
        "step_cost.csv",
        &["model", "part", "median (µs)", "× bare factorization + solve", "notes"],
    );
    for (model_name, stem) in SHIPPED {
        match measure_model(model_name, stem, s, &mut out) {
            Ok(parts) => {
                let bare = parts.iter().find(|p| p.what.starts_with("bare")).map(|p| p.seconds);
                for p in &parts {
                    let ratio = bare.filter(|b| *b > 0.0).map(|b| p.seconds / b);
                    table.row(vec![
                        Cell::text(model_name),
                        Cell::text(p.what),
                        Cell::num(p.seconds * 1e6),
                        Cell::opt(ratio),
                        Cell::text(&p.note),
                    ]);
                    if let Some(r) = ratio {
                        out.figure(
                            &format!("step_cost.{}.{}_ratio", slug(model_name), slug(p.what)),
                            r,
                            "",
                            Kind::Other,
                        );
                    }
                }
                if model_name == "MacPherson" {
                    let paper = parts.iter().find(|p| p.what == "paper step").map(|p| p.seconds);
                    out.targets.push(Target {
                        goal: "MacPherson: one paper-mode step within 3× one bare numeric factorization + solve".into(),
                        measured: paper.zip(bare).map(|(p, b)| p / b).ok_or_else(|| "not measured".to_string()),
                        limit: 3.0,
                        unit: "×".into(),
                        judge: Judge::AtMost,
                        detail: format!(
                            "vertical force sweep; paper step {} µs, bare factorization + solve {} µs (medians)",
                            paper.map_or(String::new(), |p| format!("{:.2}", p * 1e6)),
                            bare.map_or(String::new(), |b| format!("{:.2}", b * 1e6))
                        ),
                    });
                }
            }
            Err(e) => {
                table.row(vec![
                    Cell::text(model_name),
                    Cell::text("all"),
                    Cell::Empty,
                    Cell::Empty,
                    Cell::text(format!("failed: {e}")),
                ]);
                if model_name == "MacPherson" {
                    out.targets.push(Target {
                        goal: "MacPherson: one paper-mode step within 3× one bare numeric factorization + solve".into(),
                        measured: Err(format!("failed: {e}")),
                        limit: 3.0,
                        unit: "×".into(),
                        judge: Judge::AtMost,
                        detail: String::new(),
                    });
                }
            }
        }
    }
    out.tables.push(table);
    out
}
