//! Batch throughput: design variants of the shipped MacPherson model per second, evaluated as
//! `elastokin batch` does (JSON-pointer edits of the model file, parse, parallel travel ±20 mm in 8
//! corrected steps, bump steer, camber gain and wheel rate at design), on a rayon pool of one thread and
//! on one of every available thread; and a design study at scale: variants × the 161-point travel sweep,
//! each thread keeping one solver workspace from variant to variant, with the time 10⁵ variants would
//! take projected from the measured rate.

use super::models;
use super::report::{Cell, Judge, Kind, SectionOutput, Table, Target};
use super::Settings;
use elastokin_solver::{LoadPath, Mode, SolverOptions, SolverWorkspace, StaticSolver};
use elastokin_suspensions::study::batch::{self, Variant};
use elastokin_suspensions::{Rig, Side};
use rayon::prelude::*;
use serde_json::Value;

/// A grid of variants: inner tie-rod height, spring rate and lower-arm radial rate.
fn variants(count: usize) -> Vec<Variant> {
    (0..count)
        .map(|k| {
            let dz = -0.010 + 0.020 * ((k % 5) as f64 / 4.0);
            let rate = 20_000.0 + 5_000.0 * ((k / 5) % 4) as f64;
            let radial = 2.0e6 * (1.0 + ((k / 20) % 5) as f64);
            let edits = [
                ("/suspension/macpherson/hardpoints/tie_rod_inner/2", -0.059 + dz),
                ("/suspension/macpherson/spring/rate", rate),
                ("/suspension/macpherson/lower_arm_mounts/bushing/radial", radial),
            ];
            Variant {
                name: format!("v{k}"),
                edits: edits.into_iter().map(|(pointer, value)| (pointer.to_string(), Value::from(value))).collect(),
            }
        })
        .collect()
}

/// One variant, start to finish, as `elastokin batch` runs it: edited and read by [`batch::apply`],
/// judged by [`batch::evaluate`].
fn evaluate(base: &Value, variant: &Variant) -> Result<batch::Outcome, String> {
    let file = batch::apply(base, variant).map_err(|e| e.to_string())?;
    batch::evaluate(&file, batch::HALF_RANGE, batch::STEPS).map_err(|e| e.to_string())
}

/// CPU time of every thread of this process (s), from `/proc/self/task/*/schedstat` (Linux); `None`
/// elsewhere. Threads that have exited are not counted, so read it while the pool is alive.
fn cpu_seconds() -> Option<f64> {
    let mut ns = 0u64;
    for task in std::fs::read_dir("/proc/self/task").ok()? {
        let text = std::fs::read_to_string(task.ok()?.path().join("schedstat")).ok()?;
        ns += text.split_whitespace().next()?.parse::<u64>().ok()?;
    }
    Some(ns as f64 * 1e-9)
}

/// Runs the section.
pub fn run(s: &Settings) -> SectionOutput {
    let count = if s.quick { 32 } else { 128 };
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut out = SectionOutput {
        title: "Batch throughput".into(),
        intro: format!(
            "{count} variants of the shipped MacPherson (inner tie-rod height, spring rate, lower-arm radial \
             rate), each parsed from edited JSON and run as `elastokin batch` runs it. Median wall time of \
             the whole batch on a rayon pool of 1 thread and of {threads} (all available). CPU time / wall \
             time is the process's CPU time over the repetitions (Linux): near the thread count when the \
             threads ran, near 1 when they waited for a core."
        ),
        ..SectionOutput::default()
    };
    let mut table = Table::new(
        "Batch throughput",
        "batch.csv",
        &[
            "threads",
            "variants",
            "failed variants",
            "median batch time (s)",
            "variants per second",
            "speed-up over 1 thread",
            "CPU time / wall time",
            "status",
        ],
    );
    let base = match models::shipped_document("generic/macpherson") {
        Ok(v) => v,
        Err(e) => {
            table.failed_row(Vec::new(), e);
            out.tables.push(table);
            return out;
        }
    };
    let list = variants(count);
    let mut single = None;
    let mut pools: Vec<usize> = vec![1, threads];
    pools.dedup();
    for t in pools {
        let pool = match rayon::ThreadPoolBuilder::new().num_threads(t).build() {
            Ok(p) => p,
            Err(e) => {
                table.failed_row(vec![Cell::count(t as u64)], e);
                continue;
            }
        };
        let run_all = || pool.install(|| list.par_iter().map(|v| evaluate(&base, v)).collect::<Vec<_>>());
        let results = run_all();
        let failures: Vec<&String> = results.iter().filter_map(|r| r.as_ref().err()).collect();
        let cpu_before = cpu_seconds();
        let wall = std::time::Instant::now();
        let timing = s.batch_budget().time(run_all);
        let busy = cpu_before.zip(cpu_seconds()).map(|(a, b)| (b - a) / wall.elapsed().as_secs_f64());
        let rate = count as f64 / timing.median;
        if t == 1 {
            single = Some(rate);
        }
        let speedup = single.map(|r1| rate / r1);
        table.row(vec![
            Cell::count(t as u64),
            Cell::count(count as u64),
            Cell::count(failures.len() as u64),
            Cell::num(timing.median),
            Cell::num(rate),
            Cell::opt(speedup),
            Cell::opt(busy),
            Cell::text(if failures.is_empty() {
                "ok".to_string()
            } else {
                format!("failed variants: {}", failures[0])
            }),
        ]);
        let key = if t == 1 { "batch.one_thread" } else { "batch.all_threads" };
        out.figure(&format!("{key}.variants_per_s"), rate, "1/s", Kind::Rate);
        if let Some(x) = speedup.filter(|_| t > 1) {
            out.figure("batch.speedup", x, "", Kind::Other);
        }
    }
    if threads == 1 {
        out.notes.push("only one thread is available: the all-core row is the one-thread row".into());
    }
    out.tables.push(table);
    design_study(s, &base, threads, &mut out);
    out
}

/// Points of a design study's sweep: parallel travel ±80 mm in 1 mm steps.
const STUDY_POINTS: usize = 161;

/// Variants the design study asks for in a minute on 2 cores.
const STUDY_PROJECTED: f64 = 1e5;

/// How a design study's variant is solved.
#[derive(Clone, Copy, PartialEq)]
enum StudyPolicy {
    /// One workspace per thread, kept across variants; predictor and chord iterations.
    Reused,
    /// A fresh solver per variant; predictor and chord iterations.
    Fresh,
    /// A fresh solver per variant; full Newton.
    FullNewton,
}

impl StudyPolicy {
    fn name(self) -> &'static str {
        match self {
            StudyPolicy::Reused => "workspace kept across variants, predictor + chord",
            StudyPolicy::Fresh => "fresh solver per variant, predictor + chord",
            StudyPolicy::FullNewton => "fresh solver per variant, full Newton",
        }
    }
}

/// One variant of the study: edited, parsed, built on the travel rig and swept over 161 points; returns
/// the largest |toe| over the sweep (rad), so that nothing is optimised away, and the workspace.
fn study_variant(
    base: &Value,
    variant: &Variant,
    policy: StudyPolicy,
    workspace: Option<SolverWorkspace>,
) -> (Result<f64, String>, Option<SolverWorkspace>) {
    let corner = match batch::apply(base, variant)
        .map_err(|e| e.to_string())
        .and_then(|f| f.suspension.build(Side::Left, Rig::WheelTravel).map_err(|e| e.to_string()))
    {
        Ok(c) => c,
        Err(e) => return (Err(e), workspace),
    };
    let options = SolverOptions { reuse_factorization: policy != StudyPolicy::FullNewton, ..SolverOptions::default() };
    let kept = if policy == StudyPolicy::Reused { workspace } else { None };
    let mut solver = match StaticSolver::with_workspace(&corner.model, options, kept) {
        Ok(s) => s,
        Err(e) => return (Err(e.to_string()), None),
    };
    let result = solver
        .sweep(LoadPath::new(-0.08, 0.08, STUDY_POINTS - 1), Mode::Corrected)
        .map_err(|e| e.to_string())
        .map(|sweep| sweep.steps.iter().map(|r| corner.wheel.attitude(&r.poses).toe.abs()).fold(0.0, f64::max));
    (result, Some(solver.into_workspace()))
}

/// The design-study table: variants × 161 points under each policy, the reused one on every thread.
fn design_study(s: &Settings, base: &Value, threads: usize, out: &mut SectionOutput) {
    let count = if s.quick { 200 } else { 10_000 };
    let mut table = Table::new(
        "Design study: variants × 161-point travel sweep",
        "batch_study.csv",
        &[
            "policy",
            "threads",
            "variants",
            "failed variants",
            "wall time (s)",
            "per variant (µs)",
            "per point (µs)",
            &format!("projected {STUDY_PROJECTED:.0e} variants (s)"),
            "status",
        ],
    );
    let list = variants(count);
    let mut projected = None;
    for (policy, threads) in [
        (StudyPolicy::Reused, threads),
        (StudyPolicy::Reused, 1),
        (StudyPolicy::Fresh, 1),
        (StudyPolicy::FullNewton, 1),
    ] {
        // The slower policies on a tenth of the variants: their per-variant cost is what is compared.
        let n = if policy == StudyPolicy::Reused { count } else { (count / 10).max(10) };
        let pool = match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
            Ok(p) => p,
            Err(e) => {
                table.failed_row(vec![Cell::text(policy.name()), Cell::count(threads as u64)], e);
                continue;
            }
        };
        let run = || {
            pool.install(|| {
                list[..n]
                    .par_iter()
                    .map_init(
                        || None,
                        |workspace, v| {
                            let (result, kept) = study_variant(base, v, policy, workspace.take());
                            *workspace = kept;
                            result
                        },
                    )
                    .collect::<Vec<_>>()
            })
        };
        let start = std::time::Instant::now();
        let results = run();
        let wall = start.elapsed().as_secs_f64();
        let failures: Vec<&String> = results.iter().filter_map(|r| r.as_ref().err()).collect();
        let per_variant = wall / n as f64;
        let projection = STUDY_PROJECTED * per_variant;
        if policy == StudyPolicy::Reused && threads > 1 {
            projected = Some((projection, threads, wall, n));
        }
        let key = format!("batch.study.{}_{}_threads", slug_policy(policy), threads);
        out.figure(&format!("{key}.per_variant_s"), per_variant * threads as f64, "s", Kind::Time);
        table.row(vec![
            Cell::text(policy.name()),
            Cell::count(threads as u64),
            Cell::count(n as u64),
            Cell::count(failures.len() as u64),
            Cell::num(wall),
            Cell::num(per_variant * 1e6),
            Cell::num(per_variant * 1e6 / STUDY_POINTS as f64),
            Cell::num(projection),
            Cell::text(if failures.is_empty() { "ok".to_string() } else { format!("failed: {}", failures[0]) }),
        ]);
    }
    out.notes.push(
        "Design study: each variant is edited, parsed, built and swept (161 points, 1e-9 relative residual); \
         the wall time is one run of the whole list (the figure keys hold CPU time per variant: wall × threads \
         / variants). The projection is 10⁵ × the measured wall time per variant on that many threads."
            .into(),
    );
    let (measured, detail) = match projected {
        Some((p, t, wall, n)) => {
            (Ok(p), format!("{n} variants in {wall:.2} s on {t} threads (wall time), workspace kept across variants"))
        }
        None if threads == 1 => {
            (Err("only one thread is available; the target is for 2 cores".to_string()), String::new())
        }
        None => (Err("the study did not run".to_string()), String::new()),
    };
    out.targets.push(Target {
        goal: "10⁵ MacPherson variants × 161 travel points on 2 cores, projected from the measured rate".into(),
        measured,
        limit: 60.0,
        unit: "s".into(),
        judge: Judge::AtMost,
        detail,
    });
    out.tables.push(table);
}

fn slug_policy(policy: StudyPolicy) -> &'static str {
    match policy {
        StudyPolicy::Reused => "reused",
        StudyPolicy::Fresh => "fresh",
        StudyPolicy::FullNewton => "full_newton",
    }
}
