//! Scaling with the number of bodies: a synthetic chain of suspension-like cells (each body an arm on a
//! bushing to the ground, tied to the previous body by a ball joint and a link, with a coil spring between
//! them), grounded at one end through its first cell's joints and loaded at the other. Time per paper and
//! corrected step, memory per body (kept by the solver and at the peak, and by part of its setup), symbolic
//! analysis against numeric factorization (the gain from reusing the symbolic analysis), and the fitted
//! exponent of time against N.

use super::alloc;
use super::report::{Cell, Judge, Kind, SectionOutput, Table, Target};
use super::stats::power_law_exponent;
use super::Settings;
use elastokin_core::{BodyRef, JointSpec, Mat3, Model, ModelError, Pose, Vec3};
use elastokin_elements::{Bushing, Characteristic, CoilSpring, PointForce, SpringLength};
use elastokin_solver::assembly::{Assembly, Tangent};
use elastokin_solver::kkt::{KktFactor, KktOptions};
use elastokin_solver::solver::redundant_rows_at_design;
use elastokin_solver::{LoadPath, Mode, SolverOptions, StaticSolver, Sweep};

const MIB: f64 = 1024.0 * 1024.0;

/// The memory limits per body, in bytes (1 KB = 1000 B), from N = 1 000 to 10 000: kept by a
/// `StaticSolver` once `StaticSolver::new` has returned, and at the peak of `new` and a corrected sweep.
const KEPT_PER_BODY: f64 = 12_000.0;
const PEAK_PER_BODY: f64 = 20_000.0;
/// Smallest N the memory targets are judged from.
const MEMORY_FROM: usize = 1000;

/// Distance between cells along x (m).
const PITCH: f64 = 0.4;

/// The chain of `n` cells.
pub fn chain(n: usize) -> Result<Model, ModelError> {
    let mut m = Model::new();
    let mut prev = BodyRef::Ground;
    let k = Vec3::new(1.0e6, 5.0e5, 5.0e5);
    let kr = Vec3::new(1.0e3, 5.0e3, 5.0e3);
    for i in 0..n {
        let x = PITCH * (i as f64 + 1.0);
        let body = m.add_body(&format!("arm {i}"), Pose::at(Vec3::new(x, 0.0, 0.0)))?;
        let mount = Vec3::new(x, -0.15, 0.0);
        m.add_element(Bushing::new(
            &format!("mount {i}"),
            BodyRef::Ground,
            body.into(),
            mount,
            Mat3::identity(),
            k,
            kr,
        )?)?;
        let joint = x - PITCH / 2.0;
        m.add_joint(JointSpec::spherical(&format!("ball {i}"), prev, body, Vec3::new(joint, 0.0, 0.0)))?;
        m.add_joint(JointSpec::distance(
            &format!("link {i}"),
            prev,
            body,
            Vec3::new(joint - 0.1, 0.15, 0.0),
            Vec3::new(joint + 0.1, 0.15, 0.08),
        ))?;
        m.add_element(CoilSpring::seated(
            &format!("spring {i}"),
            [(prev, Vec3::new(joint - 0.1, -0.1, 0.2)), (body.into(), Vec3::new(x, -0.1, 0.0))],
            Characteristic::Rate(3.0e4),
            SpringLength::DesignForce(500.0),
        )?)?;
        prev = body.into();
    }
    let tip = Vec3::new(PITCH * n as f64 + 0.1, 0.0, 0.0);
    m.add_element(PointForce::new("tip load", prev, tip, Vec3::new(0.0, 300.0, -1000.0))?)?;
    Ok(m)
}

struct SizeResult {
    n: usize,
    dofs: usize,
    rows: usize,
    setup: f64,
    symbolic: f64,
    numeric: f64,
    solve: f64,
    factor_nnz: usize,
    paper_step: f64,
    corrected_step: f64,
    corrected_iterations: f64,
    peak_bytes: usize,
    setup_peak_bytes: usize,
    sweep_peak_bytes: usize,
    /// Live bytes a `StaticSolver` holds once `new` has returned.
    kept_bytes: isize,
    parts: Parts,
}

/// Memory of the parts of `StaticSolver::new`, measured one by one in the order `new` runs them.
struct Parts {
    /// Peak of the redundancy check: an assembly of every row at design and `redundant_rows` on its `J`.
    redundancy_peak: usize,
    /// Kept by `Assembly::new` of the active rows.
    assembly_kept: isize,
    /// Kept by `KktFactor::analyze` of that assembly's pattern (the pattern copy made for it included in
    /// the peak, freed after).
    factor_kept: isize,
    /// Peak of that analysis.
    factor_peak: usize,
}

/// Steps of every sweep, the same for every N: a per-step time compared across N must come from the same
/// load path (a longer step takes more Newton iterations).
const STEPS: usize = 10;

fn measure(n: usize, s: &Settings) -> Result<SizeResult, String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let model = chain(n).map_err(|e| err(&e))?;
    let budget = s.budget_large(n);
    let k = STEPS;
    let path = LoadPath::new(0.0, 1.0, k);
    // Peak memory: solver setup, the first equilibrium and a corrected sweep with its results; then the
    // setup and the sweep alone.
    let (measured, usage) = alloc::track(|| -> Result<_, String> {
        let mut solver = StaticSolver::new(&model, SolverOptions::default()).map_err(|e| err(&e))?;
        let sweep = solver.sweep(path, Mode::Corrected).and_then(Sweep::complete).map_err(|e| err(&e))?;
        let iterations: usize = sweep.steps.iter().skip(1).map(|r| r.iterations).sum();
        Ok(iterations as f64 / k as f64)
    });
    let corrected_iterations = measured?;
    let (solver, setup_usage) = alloc::track(|| StaticSolver::new(&model, SolverOptions::default()));
    let mut solver = solver.map_err(|e| err(&e))?;
    let options = SolverOptions::default();
    let ((), redundancy) = alloc::track(|| {
        std::hint::black_box(redundant_rows_at_design(&model, options.redundancy_tolerance));
    });
    let (mut assembly, assembly_usage) = alloc::track(|| Assembly::new(&model, solver.active_rows().to_vec()));
    let (factor, factor_usage) = alloc::track(|| KktFactor::analyze(&assembly.kkt_pattern(), options.kkt.clone()));
    drop(factor.map_err(|e| err(&e))?);
    let parts = Parts {
        redundancy_peak: redundancy.peak_bytes,
        assembly_kept: assembly_usage.balance_bytes,
        factor_kept: factor_usage.balance_bytes,
        factor_peak: factor_usage.peak_bytes,
    };
    let (swept, sweep_usage) = alloc::track(|| solver.sweep(path, Mode::Corrected).map(drop));
    swept.map_err(|e| err(&e))?;
    let setup = budget.time(|| StaticSolver::new(&model, SolverOptions::default()).map(drop));
    let mut start = solver.design_state(0.0);
    solver.equilibrium(&mut start).map_err(|e| err(&e))?;
    let paper = budget.time(|| solver.sweep_from(&mut start.clone(), path, Mode::Paper).map(drop));
    let corrected = budget.time(|| solver.sweep_from(&mut start.clone(), path, Mode::Corrected).map(drop));

    // Symbolic analysis against numeric factorization of the same KKT.
    assembly.assemble(&model, &start.poses, start.t, &start.lambda, Some(Tangent::Full));
    let pattern = assembly.kkt_pattern();
    let symbolic = budget.time(|| KktFactor::analyze(&pattern, KktOptions::default()).map(drop));
    let mut factor = KktFactor::analyze(&pattern, KktOptions::default()).map_err(|e| err(&e))?;
    let numeric = budget.time(|| factor.factorize(&assembly.k_values, &assembly.j_values).map(drop));
    factor.factorize(&assembly.k_values, &assembly.j_values).map_err(|e| err(&e))?;
    let rhs0: Vec<f64> =
        (0..assembly.n + assembly.m()).map(|i| if i < assembly.n { assembly.load_rate[i] } else { 0.0 }).collect();
    let mut rhs = rhs0.clone();
    let solve = budget.time(|| {
        rhs.copy_from_slice(&rhs0);
        factor.solve_in_place(&mut rhs).map(drop)
    });
    Ok(SizeResult {
        n,
        dofs: assembly.n,
        rows: assembly.m(),
        setup: setup.median,
        symbolic: symbolic.median,
        numeric: numeric.median,
        solve: solve.median,
        factor_nnz: factor.factor_nnz(),
        paper_step: paper.median / k as f64,
        corrected_step: corrected.median / k as f64,
        corrected_iterations,
        peak_bytes: usage.peak_bytes,
        setup_peak_bytes: setup_usage.peak_bytes,
        sweep_peak_bytes: sweep_usage.peak_bytes,
        kept_bytes: setup_usage.balance_bytes,
        parts,
    })
}

/// Runs the section.
pub fn run(s: &Settings) -> SectionOutput {
    let sizes: &[usize] = if s.quick { &[10, 100, 300, 1000] } else { &[10, 100, 1000, 2000, 5000, 10000] };
    let fit_from = if s.quick { 100 } else { 1000 };
    let mut out = SectionOutput {
        title: "Scaling with the number of bodies".into(),
        intro: format!(
            "A chain of N suspension-like cells: each body an arm on a 6-axis bushing to the ground, tied to \
             the previous body (the ground for the first) by a ball joint and a link, with a coil spring \
             across; a tip load at the far end. Load parameter 0 → 1 in {STEPS} steps from the first \
             equilibrium (the same path for every N), time divided by the step count. Peak memory: live bytes \
             above the start during `StaticSolver::new` + a corrected sweep (results included), and each \
             alone; kept: live bytes the solver holds once `new` has returned. Gain from \
             symbolic reuse: (symbolic + numeric) / numeric. Exponents: least squares of ln time against ln N \
             for N ≥ {fit_from}."
        ),
        ..SectionOutput::default()
    };
    let mut table = Table::new(
        "Scaling",
        "scaling.csv",
        &[
            "N bodies",
            "n",
            "m",
            "setup (ms)",
            "symbolic (ms)",
            "numeric factorization (ms)",
            "solve (ms)",
            "gain from symbolic reuse",
            "factor entries",
            "paper step (ms)",
            "corrected step (ms)",
            "iterations per corrected step",
            "peak memory (MiB)",
            "peak per body (B)",
            "kept per body (B)",
            "of which StaticSolver::new (MiB)",
            "sweep alone (MiB)",
            "status",
        ],
    );
    let mut results = Vec::new();
    for &n in sizes {
        match measure(n, s) {
            Ok(r) => {
                let gain = (r.symbolic + r.numeric) / r.numeric;
                table.row(vec![
                    Cell::count(r.n as u64),
                    Cell::count(r.dofs as u64),
                    Cell::count(r.rows as u64),
                    Cell::num(r.setup * 1e3),
                    Cell::num(r.symbolic * 1e3),
                    Cell::num(r.numeric * 1e3),
                    Cell::num(r.solve * 1e3),
                    Cell::num(gain),
                    Cell::count(r.factor_nnz as u64),
                    Cell::num(r.paper_step * 1e3),
                    Cell::num(r.corrected_step * 1e3),
                    Cell::num(r.corrected_iterations),
                    Cell::num(r.peak_bytes as f64 / MIB),
                    Cell::num(r.peak_bytes as f64 / r.n as f64),
                    Cell::num(r.kept_bytes as f64 / r.n as f64),
                    Cell::num(r.setup_peak_bytes as f64 / MIB),
                    Cell::num(r.sweep_peak_bytes as f64 / MIB),
                    Cell::text("ok"),
                ]);
                let key = format!("scaling.n{}", r.n);
                out.figure(&format!("{key}.paper_step_s"), r.paper_step, "s", Kind::Time);
                out.figure(&format!("{key}.corrected_step_s"), r.corrected_step, "s", Kind::Time);
                out.figure(&format!("{key}.symbolic_s"), r.symbolic, "s", Kind::Time);
                out.figure(&format!("{key}.numeric_factorization_s"), r.numeric, "s", Kind::Time);
                out.figure(&format!("{key}.setup_s"), r.setup, "s", Kind::Time);
                out.figure(&format!("{key}.peak_bytes"), r.peak_bytes as f64, "B", Kind::Memory);
                out.figure(&format!("{key}.kept_bytes"), r.kept_bytes as f64, "B", Kind::Memory);
                out.figure(&format!("{key}.symbolic_reuse_gain"), gain, "", Kind::Other);
                results.push(r);
            }
            Err(e) => {
                let mut row = vec![Cell::count(n as u64)];
                row.resize(17, Cell::Empty);
                row.push(Cell::text(format!("failed: {e}")));
                table.row(row);
            }
        }
    }
    out.tables.push(table);

    let mut parts = Table::new(
        "Memory per body by part of StaticSolver::new",
        "scaling_memory.csv",
        &[
            "N bodies",
            "redundancy check, peak (B)",
            "Assembly::new, kept (B)",
            "KktFactor::analyze, kept (B)",
            "KktFactor::analyze, peak (B)",
            "StaticSolver::new, kept (B)",
            "StaticSolver::new, peak (B)",
            "corrected sweep, peak above kept (B)",
        ],
    );
    for r in &results {
        let per = |bytes: f64| Cell::num(bytes / r.n as f64);
        let p = &r.parts;
        parts.row(vec![
            Cell::count(r.n as u64),
            per(p.redundancy_peak as f64),
            per(p.assembly_kept as f64),
            per(p.factor_kept as f64),
            per(p.factor_peak as f64),
            per(r.kept_bytes as f64),
            per(r.setup_peak_bytes as f64),
            per(r.sweep_peak_bytes as f64),
        ]);
    }
    out.tables.push(parts);

    let fitted: Vec<&SizeResult> = results.iter().filter(|r| r.n >= fit_from).collect();
    let largest = fitted.iter().map(|r| r.n).max().unwrap_or(0);
    let mut fits =
        Table::new("Fitted exponents", "scaling_exponents.csv", &["quantity", "exponent", "over N", "points"]);
    let mut exponents = Vec::new();
    for (what, get) in [
        ("paper step", (|r: &SizeResult| r.paper_step) as fn(&SizeResult) -> f64),
        ("corrected step", |r: &SizeResult| r.corrected_step),
        ("numeric factorization", |r: &SizeResult| r.numeric),
        ("symbolic analysis", |r: &SizeResult| r.symbolic),
        ("setup (StaticSolver::new)", |r: &SizeResult| r.setup),
        ("peak memory", |r: &SizeResult| r.peak_bytes as f64),
    ] {
        let points: Vec<(f64, f64)> = fitted.iter().map(|r| (r.n as f64, get(r))).collect();
        let p = power_law_exponent(&points);
        fits.row(vec![
            Cell::text(what),
            Cell::Num(p.unwrap_or(f64::NAN), 3),
            Cell::text(format!("{fit_from}–{largest}")),
            Cell::count(points.len() as u64),
        ]);
        if let Some(p) = p {
            out.figure(&format!("scaling.exponent.{}", super::report::slug(what)), p, "", Kind::Other);
        }
        exponents.push((what, p, points.len()));
    }
    out.tables.push(fits);
    // A step may grow somewhat faster than N (fill, cache); the setup is asked to stay linear.
    for (what, goal, limit) in [
        ("paper step", "time per paper step", 1.2),
        ("corrected step", "time per corrected step", 1.2),
        ("setup (StaticSolver::new)", "setup time (StaticSolver::new)", 1.05),
    ] {
        let (_, p, count) = exponents.iter().find(|e| e.0 == what).copied().unwrap_or((what, None, 0));
        out.targets.push(Target {
            goal: format!("{goal} growing no faster than N^{limit} from 1 000 to 10 000 bodies"),
            measured: p.ok_or_else(|| "too few sizes measured for a fit".to_string()),
            limit,
            unit: "exponent".into(),
            judge: Judge::ExponentAtMost,
            detail: format!(
                "least-squares fit over N = {fit_from}–{largest} ({count} sizes){}",
                if s.quick { "; --quick stops at 1 000, the full run fits 1 000–10 000" } else { "" }
            ),
        });
    }
    let judged: Vec<&SizeResult> = results.iter().filter(|r| r.n >= MEMORY_FROM).collect();
    let sizes_judged = judged.iter().map(|r| r.n.to_string()).collect::<Vec<_>>().join(", ");
    for (what, limit, get) in [
        (
            "kept by a StaticSolver once StaticSolver::new has returned",
            KEPT_PER_BODY,
            (|r: &SizeResult| r.kept_bytes as f64) as fn(&SizeResult) -> f64,
        ),
        ("at the peak of StaticSolver::new and a corrected sweep", PEAK_PER_BODY, |r: &SizeResult| r.peak_bytes as f64),
    ] {
        let worst =
            judged.iter().map(|r| get(r) / r.n as f64).fold(None, |m: Option<f64>, v| Some(m.map_or(v, |m| m.max(v))));
        out.targets.push(Target {
            goal: format!("memory {what} at most {} KB per body from 1 000 to 10 000 bodies", limit / 1000.0),
            measured: worst.ok_or_else(|| format!("no size of {MEMORY_FROM} bodies or more measured")),
            limit,
            unit: "B per body".into(),
            judge: Judge::AtMost,
            detail: format!(
                "the largest over N = {sizes_judged}{}",
                if s.quick { "; --quick stops at 1 000, the full run measures 1 000–10 000" } else { "" }
            ),
        });
    }
    out
}
