//! The two ways of walking a load path: paper mode converges to the corrected solution at first order,
//! and the symbolic analysis is done once for a whole sweep.

mod common;
use common::*;
use elastokin::prelude::*;

fn final_angle(mode: Mode, steps: usize) -> f64 {
    let m = lever(Pivot::Revolute, lever_spring_design_length());
    let mut solver = StaticSolver::new(&m, SolverOptions::default()).unwrap();
    let sweep = solver.sweep(LoadPath::new(0.0, 1.0, steps), mode).unwrap();
    rotation_about_y(&sweep.steps.last().unwrap().poses[0])
}

#[test]
fn paper_mode_converges_at_first_order_to_the_corrected_solution() {
    let exact = lever_angle(F_TIP, lever_spring_design_length());
    let corrected = final_angle(Mode::Corrected, 4);
    assert!((corrected - exact).abs() < 1e-10);
    let errors: Vec<f64> =
        [80, 160, 320, 640].iter().map(|&n| (final_angle(Mode::Paper, n) - corrected).abs()).collect();
    let orders: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    for (k, p) in orders.iter().enumerate() {
        assert!(
            (0.85..1.15).contains(p),
            "observed order {p} between refinements {k} and {} (errors {errors:?})",
            k + 1
        );
    }
    // Halving Δf halves the error: the finest paper run is within 0.5 % of the angle.
    assert!(errors[3] < 5e-3 * exact.abs(), "{errors:?}");
}

#[test]
fn symbolic_analysis_runs_once_for_a_whole_sweep() {
    let m = lever(Pivot::Revolute, lever_spring_design_length());
    let mut solver = StaticSolver::new(&m, SolverOptions::default()).unwrap();
    let before = solver.counters();
    let sweep = solver.sweep(LoadPath::new(0.0, 1.0, 25), Mode::Corrected).unwrap();
    let paper = solver.sweep(LoadPath::new(0.0, 1.0, 25), Mode::Paper).unwrap();
    let after = solver.counters();
    assert_eq!(after.factor.symbolic_analyses, 1);
    let newton: usize = sweep.steps.iter().map(|s| s.iterations).sum::<usize>() + paper.steps[0].iterations;
    // One numeric factorization per Newton iteration and per paper step, one for the load response that
    // a corrected sweep takes as its limit-point reference, and no symbolic work.
    assert_eq!((after.factor.numeric_factorizations - before.factor.numeric_factorizations) as usize, newton + 25 + 1);
}

#[test]
fn chord_corrector_reuses_the_factorization_and_reaches_the_same_answer() {
    let m = lever(Pivot::Revolute, lever_spring_design_length());
    let exact = lever_angle(F_TIP, lever_spring_design_length());
    let mut full = StaticSolver::new(&m, SolverOptions::default()).unwrap();
    let a = full.sweep(LoadPath::new(0.0, 1.0, 10), Mode::Corrected).unwrap();
    let mut chord =
        StaticSolver::new(&m, SolverOptions { reuse_factorization: true, ..SolverOptions::default() }).unwrap();
    let b = chord.sweep(LoadPath::new(0.0, 1.0, 10), Mode::Corrected).unwrap();
    let (pa, pb) = (rotation_about_y(&a.steps[10].poses[0]), rotation_about_y(&b.steps[10].poses[0]));
    assert!((pa - exact).abs() < 1e-9 && (pb - exact).abs() < 1e-9, "{pa} {pb} {exact}");
    let its_b: usize = b.steps.iter().map(|s| s.iterations).sum();
    assert!(
        chord.counters().factor.numeric_factorizations < its_b as u64,
        "chord iterations must reuse factorizations"
    );
}

/// A body on a bushing pushed through the bushing's own point: the deflection is `F t / k` exactly, a
/// straight path. The predictor extrapolates it exactly from the first step on, so every later step is
/// an equilibrium before any Newton iteration. The one factorization is the load response's that a
/// corrected sweep starts with: the first step's single chord iteration solves with it.
#[test]
fn a_straight_path_is_predicted_exactly_and_takes_no_iteration_after_its_first_step() {
    use elastokin::elements::{Bushing, PointForce};
    let mut m = Model::new();
    let at = Vec3::new(0.1, 0.7, -0.2);
    let body = m.add_body("block", Pose::at(at)).unwrap();
    let k = Vec3::new(2e5, 5e5, 1e6);
    m.add_element(
        Bushing::new("mount", BodyRef::Ground, body.into(), at, Mat3::identity(), k, Vec3::new(1e3, 1e3, 1e3)).unwrap(),
    )
    .unwrap();
    let force = Vec3::new(300.0, -200.0, 1000.0);
    m.add_element(PointForce::new("push", body.into(), at, force).unwrap()).unwrap();
    let options = SolverOptions { reuse_factorization: true, ..SolverOptions::default() };
    let mut solver = StaticSolver::new(&m, options).unwrap();
    let before = solver.counters();
    let sweep = solver.sweep(LoadPath::new(0.0, 1.0, 20), Mode::Corrected).unwrap();
    let after = solver.counters();
    let iterations: Vec<usize> = sweep.steps.iter().map(|s| s.iterations).collect();
    assert_eq!(iterations[0], 0, "the design pose is the equilibrium at t = 0");
    assert_eq!(iterations[1], 1, "the first step has nothing to extrapolate from");
    assert!(iterations[2..].iter().all(|&i| i == 0), "{iterations:?}");
    assert_eq!(after.factor.numeric_factorizations - before.factor.numeric_factorizations, 1);
    let mut worst: f64 = 0.0;
    for s in &sweep.steps {
        let expected = at + force.component_div(&k) * s.t;
        worst = worst.max((s.poses[0].position - expected).norm());
    }
    // Measured: 5.9e-16 m (the deflections are up to 1 mm).
    assert!(worst < 5e-14, "{worst:e}");
}

/// On the lever's curved path (closed form), the kept factorization and the extrapolating predictor
/// reach the closed-form angle at every step, with a few factorizations for the whole sweep.
#[test]
fn chord_steps_from_the_predictor_follow_the_lever_with_few_factorizations() {
    let l0 = lever_spring_design_length();
    let m = lever(Pivot::Revolute, l0);
    let options = SolverOptions { reuse_factorization: true, ..SolverOptions::default() };
    let mut solver = StaticSolver::new(&m, options).unwrap();
    let sweep = solver.sweep(LoadPath::new(0.0, 1.0, 200), Mode::Corrected).unwrap();
    let mut worst: f64 = 0.0;
    for step in &sweep.steps {
        worst = worst.max((rotation_about_y(&step.poses[0]) - lever_angle(F_TIP * step.t, l0)).abs());
    }
    let iterations: usize = sweep.steps.iter().map(|s| s.iterations).sum();
    let factorizations = solver.counters().factor.numeric_factorizations;
    println!("worst angle error {worst:e} rad, {iterations} iterations, {factorizations} factorizations");
    // Measured: 8.4e-10 rad against the closed form (chord iterations stop as soon as the residual is
    // within the tolerance, where full Newton's last quadratic step overshoots far below it), 264
    // iterations and 5 factorizations for 200 steps of a lever that turns past 35°.
    assert!(worst < 1e-8, "{worst:e}");
    assert!(factorizations <= 10, "{factorizations}");
    assert!(iterations <= 300, "{iterations}");
}

/// A design study's variants share one workspace: the second MacPherson (another spring rate and inner
/// tie-rod height) reuses the first's analysis, and its sweep is the one a fresh solver walks, to the
/// bit, whichever variant the workspace served before. A double wishbone, another topology, is analysed
/// afresh.
#[test]
fn variants_of_one_topology_share_a_workspace_and_get_a_fresh_solvers_results() {
    use elastokin::solver::SolverWorkspace;
    use elastokin::suspensions::{Rig, Side, SuspensionFile};
    let read = |name: &str, edit: &dyn Fn(&mut serde_json::Value)| {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name);
        let mut doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        edit(&mut doc);
        let file = SuspensionFile::from_json(&doc.to_string(), name).unwrap();
        file.suspension.build(Side::Left, Rig::WheelTravel).unwrap()
    };
    let base = read("macpherson.json", &|_| {});
    let variant = read("macpherson.json", &|d| {
        d["suspension"]["macpherson"]["spring"]["rate"] = 24_000.0.into();
        d["suspension"]["macpherson"]["hardpoints"]["tie_rod_inner"][2] = (-0.049).into();
    });
    let other = read("double_wishbone.json", &|_| {});
    let options = SolverOptions { reuse_factorization: true, ..SolverOptions::default() };
    let path = LoadPath::new(-0.08, 0.08, 160);
    let walk = |model: &Model, workspace: Option<SolverWorkspace>| {
        let mut solver = StaticSolver::with_workspace(model, options.clone(), workspace).unwrap();
        let sweep = solver.sweep(path, Mode::Corrected).unwrap();
        let symbolic = solver.counters().factor.symbolic_analyses;
        (sweep, symbolic, solver.into_workspace())
    };
    let (fresh, symbolic, _) = walk(&variant.model, None);
    assert_eq!(symbolic, 1);
    let (base_sweep, _, workspace) = walk(&base.model, None);
    let (reused, symbolic, workspace) = walk(&variant.model, Some(workspace));
    assert_eq!(symbolic, 0, "the variant's analysis is the base's");
    assert_eq!(reused.steps.len(), 161);
    for (a, b) in fresh.steps.iter().zip(&reused.steps) {
        assert_eq!(a.poses, b.poses);
        assert_eq!(a.multipliers, b.multipliers);
    }
    // The variant moved the wheel somewhere else: the comparison above is not of two identical models.
    let toe = |s: &elastokin::solver::StepResult, c: &elastokin::suspensions::Corner| c.wheel.attitude(&s.poses).toe;
    assert!((toe(&base_sweep.steps[160], &base) - toe(&reused.steps[160], &variant)).abs() > 1e-4);
    // Another topology: analysed afresh, and the same as a fresh solver's.
    let (other_reused, symbolic, _) = walk(&other.model, Some(workspace));
    assert_eq!(symbolic, 1);
    let (other_fresh, _, _) = walk(&other.model, None);
    assert_eq!(other_fresh.steps, other_reused.steps);
}
