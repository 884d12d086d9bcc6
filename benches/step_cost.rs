//! Cost of one load step against its floor, on the swing-arm scene of `examples/swing_arm.rs`'s kind:
//! median wall time of a paper-mode step, a corrected-mode step, and of one `KktFactor` numeric factorization +
//! solve of the same KKT. Run with `cargo bench --bench step_cost`; `cargo xtask bench` measures the same
//! on the shipped suspension models, with the parts of a step timed alone (`xtask/src/bench/step_cost.rs`).
//!
//! Medians and ratios from one run; the machine may be shared, so read the ratios, not the absolutes.

use elastokin::elements::{Bushing, Characteristic, CoilSpring, PointForce, SpringLength};
use elastokin::prelude::*;
use elastokin::solver::kkt::KktFactor;
use std::hint::black_box;
use std::time::Instant;

fn scene() -> Model {
    let mut m = Model::new();
    let upright = m.add_body("upright", Pose::at(Vec3::new(0.0, 0.8, 0.0))).unwrap();
    let lower = m.add_body("lower arm", Pose::at(Vec3::new(0.0, 0.6, -0.2))).unwrap();
    let upper = m.add_body("upper arm", Pose::at(Vec3::new(0.0, 0.65, 0.2))).unwrap();
    let k = Vec3::new(5e6, 5e6, 1e6);
    let kr = Vec3::new(600.0, 6000.0, 6000.0);
    for (name, body, p) in [
        ("lower front", lower, Vec3::new(0.2, 0.45, -0.2)),
        ("lower rear", lower, Vec3::new(-0.2, 0.45, -0.2)),
        ("upper front", upper, Vec3::new(0.15, 0.5, 0.2)),
        ("upper rear", upper, Vec3::new(-0.15, 0.5, 0.2)),
    ] {
        m.add_element(Bushing::new(name, BodyRef::Ground, body.into(), p, Mat3::identity(), k, kr).unwrap()).unwrap();
    }
    m.add_joint(JointSpec::spherical("lower ball", lower, upright, Vec3::new(0.0, 0.75, -0.2))).unwrap();
    m.add_joint(JointSpec::spherical("upper ball", upper, upright, Vec3::new(0.0, 0.72, 0.2))).unwrap();
    m.add_joint(JointSpec::distance(
        "tie rod",
        BodyRef::Ground,
        upright,
        Vec3::new(-0.15, 0.45, 0.0),
        Vec3::new(-0.15, 0.78, 0.0),
    ))
    .unwrap();
    m.add_element(
        CoilSpring::seated(
            "spring",
            [(BodyRef::Ground, Vec3::new(0.0, 0.6, 0.3)), (lower.into(), Vec3::new(0.0, 0.6, -0.2))],
            Characteristic::Rate(3e4),
            SpringLength::DesignForce(3000.0),
        )
        .unwrap(),
    )
    .unwrap();
    m.add_element(
        PointForce::new("wheel", upright.into(), Vec3::new(0.0, 0.9, 0.0), Vec3::new(0.0, 0.0, 2000.0)).unwrap(),
    )
    .unwrap();
    m
}

fn median_ns(mut f: impl FnMut(), reps: usize) -> f64 {
    let mut times: Vec<f64> = (0..reps)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_nanos() as f64
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[reps / 2]
}

fn main() {
    let model = scene();
    let steps = 100;
    let mut solver = StaticSolver::new(&model, SolverOptions::default()).unwrap();
    let paper = median_ns(|| drop(black_box(solver.sweep(LoadPath::new(0.0, 1.0, steps), Mode::Paper).unwrap())), 31)
        / steps as f64;
    let corrected =
        median_ns(|| drop(black_box(solver.sweep(LoadPath::new(0.0, 1.0, steps), Mode::Corrected).unwrap())), 31)
            / steps as f64;

    // The floor: one numeric factorization + solve of the same KKT, assembled once.
    let state = solver.design_state(0.5);
    let (size, _) = solver.kkt_triplets(&state);
    let assembly = elastokin::solver::assembly::Assembly::new(&model, solver.active_rows().to_vec());
    let mut a = assembly;
    a.assemble(&model, &state.poses, 0.5, &state.lambda, Some(elastokin::solver::assembly::Tangent::Full));
    let pattern = a.kkt_pattern();
    let mut factor = KktFactor::analyze(&pattern, Default::default()).unwrap();
    let mut rhs = vec![1.0; size];
    let bare = median_ns(
        || {
            factor.factorize(&a.k_values, &a.j_values).unwrap();
            rhs.fill(1.0);
            factor.solve_in_place(&mut rhs).unwrap();
        },
        2001,
    );
    println!("step cost, {} unknowns + {} multipliers (median of runs)", a.n, a.m());
    println!("{:<40} {:>12}", "KktFactor factorization + solve", format!("{:.2} µs", bare / 1e3));
    println!("{:<40} {:>12} {:>8.2}x", "paper-mode step", format!("{:.2} µs", paper / 1e3), paper / bare);
    println!("{:<40} {:>12} {:>8.2}x", "corrected-mode step", format!("{:.2} µs", corrected / 1e3), corrected / bare);
}
