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
