//! Newton's method on the exact tangents of tabulated characteristics: a slider on a vertical guide, held
//! by a progressive coil spring whose push force is a data-sheet table and caught by a bump stop, pushed
//! down by a ramped force. The walk crosses the spring table's points, the stop's contact and the
//! stop table's points, and leaves the spring table past its last point. Each step's equilibrium is
//! checked against the tables' curves written here independently; the iterations per step stay few,
//! and successive Newton corrections shrink the residual quadratically, also across points of a table
//! and at contact.

use elastokin_core::{BodyRef, JointSpec, Model, Pose, Vec3};
use elastokin_elements::{Characteristic, CoilSpring, Curve, PointForce, SpringLength, Stop};
use elastokin_solver::{LoadPath, Mode, SolverOptions, StaticSolver, StepResult};

/// The spring's data sheet: push force (N) against compression (m), every 20 mm.
const SPRING: [[f64; 2]; 6] =
    [[-0.02, -400.0], [0.0, 0.0], [0.02, 400.0], [0.04, 900.0], [0.06, 1600.0], [0.08, 2600.0]];

/// Its slopes by Fritsch and Carlson's steps, worked by hand. Equal steps h = 0.02 m, secants
/// Δ = (20000, 20000, 25000, 35000, 50000) N/m; three-point slopes inside (Δₖ₋₁ + Δₖ)/2, at the ends
/// (3Δ₀ − Δ₁)/2 and (3Δ₄ − Δ₃)/2; every αₖ = mₖ/Δₖ and βₖ = mₖ₊₁/Δₖ lies between 0.85 and 1.22, well
/// inside the circle of radius 3, so none is limited.
const SPRING_SLOPES: [f64; 6] = [20000.0, 20000.0, 22500.0, 30000.0, 42500.0, 57500.0];

/// The spring's force at compression `c`: the Hermite cubic (textbook basis) between the points, the
/// end lines past them.
fn spring_force(c: f64) -> f64 {
    let (first, last) = (SPRING[0], SPRING[5]);
    if c <= first[0] {
        return first[1] + SPRING_SLOPES[0] * (c - first[0]);
    }
    if c >= last[0] {
        return last[1] + SPRING_SLOPES[5] * (c - last[0]);
    }
    let k = SPRING.iter().rposition(|p| p[0] <= c).unwrap();
    let (x0, x1, y0, y1) = (SPRING[k][0], SPRING[k + 1][0], SPRING[k][1], SPRING[k + 1][1]);
    let (m0, m1) = (SPRING_SLOPES[k], SPRING_SLOPES[k + 1]);
    let h = x1 - x0;
    let t = (c - x0) / h;
    (2.0 * t.powi(3) - 3.0 * t * t + 1.0) * y0
        + (t.powi(3) - 2.0 * t * t + t) * h * m0
        + (-2.0 * t.powi(3) + 3.0 * t * t) * y1
        + (t.powi(3) - t * t) * h * m1
}

/// Design length between the seats, and the stop's clearance.
const LENGTH: f64 = 0.3;
const CLEARANCE: f64 = 0.05;

/// A progressive stop, `F = b p²` sampled every 10 mm: the curve is that parabola up to the last point
/// (three-point slopes are a parabola's own, tests/curve.rs) and starts with slope zero.
const B: f64 = 1.0e6;
const STOP_END: f64 = 0.03;

fn progressive_stop_force(p: f64) -> f64 {
    if p <= 0.0 {
        0.0
    } else if p <= STOP_END {
        B * p * p
    } else {
        B * STOP_END * STOP_END + 2.0 * B * STOP_END * (p - STOP_END)
    }
}

/// A linear stop, 40 kN/m from contact: its force has a kink there.
const LINEAR_STOP: f64 = 4.0e4;

fn linear_stop_force(p: f64) -> f64 {
    LINEAR_STOP * p.max(0.0)
}

/// Full load (N, downwards) and steps: 101.25 N a step, so that no step ends on a point of the spring's
/// table (they lie at 400, 900, 1600 and 2600 N): steps 4 and 9 cross its points at 0.02 and 0.04 m.
const LOAD: f64 = 4050.0;
const STEPS: usize = 40;

fn slider(stop_table: &[[f64; 2]]) -> Model {
    let mut m = Model::new();
    let slider = m.add_body("slider", Pose::at(Vec3::zeros())).unwrap();
    m.add_joint(JointSpec::translational("guide", BodyRef::Ground, slider, Vec3::zeros(), Vec3::z())).unwrap();
    let (seat, top) = (Vec3::new(0.0, 0.0, -LENGTH), Vec3::zeros());
    let spring = Curve::new("spring", SPRING).unwrap();
    m.add_element(
        CoilSpring::seated(
            "spring",
            [(BodyRef::Ground, seat), (slider.into(), top)],
            Characteristic::Curve(spring),
            SpringLength::Free(LENGTH),
        )
        .unwrap(),
    )
    .unwrap();
    let stop = Curve::new("bump stop", stop_table).unwrap();
    m.add_element(Stop::bump("bump stop", BodyRef::Ground, seat, slider.into(), top, CLEARANCE, stop).unwrap())
        .unwrap();
    m.add_element(PointForce::new("load", slider.into(), top, Vec3::new(0.0, 0.0, -LOAD)).unwrap()).unwrap();
    m
}

/// The compression at which spring and stop carry `force`, by bisection (the sum rises with `c`).
fn compression_for(force: f64, stop: fn(f64) -> f64) -> f64 {
    let total = |c: f64| spring_force(c) + stop(c - CLEARANCE);
    let (mut lo, mut hi) = (-0.05, 0.2);
    while hi - lo > 1e-15 {
        let mid = 0.5 * (lo + hi);
        if total(mid) < force {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The compression of a step (the slider moves down by it).
fn compression(step: &StepResult) -> f64 {
    -step.poses[0].position.z
}

/// The largest distance (m) of a step's compression from the one the curves written here give at its load.
fn worst_compression_error(steps: &[StepResult], stop: fn(f64) -> f64) -> f64 {
    steps.iter().map(|s| (compression(s) - compression_for(s.t * LOAD, stop)).abs()).fold(0.0, f64::max)
}

/// Relative force residuals `e₀, e₁, …, e_count` of Newton's iteration from the equilibrium `from` with the
/// load raised to `t`: `e₀` is the load step itself (`from` is converged), each further one the residual
/// after one more [`StaticSolver::newton_correction`] — the exact Newton iteration the sweep runs, one at a
/// time. All relative to the force scale the solver judges convergence by.
fn residual_history(solver: &mut StaticSolver, from: &StepResult, t: f64, count: usize) -> Vec<f64> {
    let mut step = StepResult { t, ..from.clone() };
    let mut history = vec![0.0];
    for _ in 0..count {
        step = solver.newton_correction(&step).unwrap();
        history.push(step.force_residual / step.force_scale);
    }
    history[0] = (t - from.t) * LOAD / step.force_scale;
    history
}

/// Residuals below this are rounding (the solver's floor here is ~1e-15 of the force scale).
const NOISE: f64 = 1e-13;

/// `log e_{k+1} / log e_k` for the corrections after the first (`k ≥ 1`) while the residual is above
/// rounding: 2 for Newton's quadratic convergence (more when its constant is small).
fn orders(history: &[f64]) -> Vec<f64> {
    history.windows(2).skip(1).filter(|w| w[1] > NOISE).map(|w| w[1].ln() / w[0].ln()).collect()
}

/// The first step whose slider has gone past first contact.
fn contact_step(steps: &[StepResult]) -> usize {
    steps.iter().position(|s| compression(s) > CLEARANCE).unwrap()
}

#[test]
fn newton_stays_quadratic_across_table_points_and_a_smooth_stop_contact() {
    let stop_table = [0.0, 0.01, 0.02, STOP_END].map(|p| [p, B * p * p]);
    let model = slider(&stop_table);
    let mut solver = StaticSolver::new(&model, SolverOptions::default()).unwrap();
    let sweep = solver.sweep(LoadPath::new(0.0, 1.0, STEPS), Mode::Corrected).unwrap();
    let steps = &sweep.steps;

    // (a) Every step's equilibrium against the curves written here.
    let worst = worst_compression_error(steps, progressive_stop_force);
    // Measured: 2.3e-11 m, the solver's force tolerance (1e-9 of ~2 kN) over the rate (~4e4 N/m).
    assert!(worst < 1e-9, "{worst}");
    // The walk crosses the spring's points at 0.02 and 0.04 m at steps 4 and 9, touches the stop, and
    // leaves both tables (past 0.08 m compression, 0.03 m penetration).
    let c = |k: usize| compression(&steps[k]);
    assert!(c(3) < 0.02 && c(4) > 0.02 && c(8) < 0.04 && c(9) > 0.04, "{} {} {} {}", c(3), c(4), c(8), c(9));
    let contact = contact_step(steps);
    assert!(c(STEPS) > SPRING[5][0] && c(STEPS) - CLEARANCE > STOP_END, "{}", c(STEPS));

    // (b) Iterations per step. Measured: 3 on every step before contact and after it, 4 on the contact
    // step (13), 2 on the step that leaves both tables and 1 on every step past them, where spring and
    // stop follow their end lines: the problem is linear there and the exact tangent solves it at once.
    let iterations: Vec<usize> = steps.iter().map(|s| s.iterations).collect();
    for (k, &n) in iterations.iter().enumerate().skip(1) {
        let limit = if k == contact { 5 } else { 4 };
        assert!(n <= limit, "step {k}: {n} iterations ({iterations:?})");
        if c(k - 1) > SPRING[5][0] {
            assert_eq!(n, 1, "step {k}, past both tables ({iterations:?})");
        }
    }
    assert!(iterations.iter().filter(|&&n| n == 1).count() >= 4, "{iterations:?}");

    // (c) Quadratic convergence: inside a piece of the spring's table (step 2), crossing its points
    // (4, 9), at contact, and in contact (contact + 2). Measured orders 2.45; 3.16; 2.38, 2.16; 2.00, 1.99;
    // 2.05, 2.02.
    for k in [2, 4, 9, contact, contact + 2] {
        let history = residual_history(&mut solver, &steps[k - 1], steps[k].t, 4);
        let orders = orders(&history);
        assert!(!orders.is_empty() && orders.iter().all(|&p| p > 1.8), "step {k}: {history:?} → {orders:?}");
        if k == contact {
            // The first correction at contact already gains (measured: e₁/e₀ = 0.11), the stop's force
            // being C¹ there.
            assert!(history[1] < 0.3 * history[0], "{history:?}");
        }
    }
}

/// A stop whose curve rises at once from contact (a linear stop, 40 kN/m) puts a kink in the force. The
/// step on which it engages starts from a state before contact, with a tangent that does not see the stop:
/// the first correction overshoots into the stop and makes no headway (measured: the residual after it is
/// 1.15 times the load step's, against 0.11 for the stop that starts with slope zero). From there Newton
/// is quadratic again; on this model the engagement step takes 4 iterations against 3 on its neighbours,
/// as many as the smooth stop's.
#[test]
fn a_stop_with_a_kink_at_contact_costs_at_most_an_extra_iteration() {
    let stop_table = [[0.0, 0.0], [0.01, 0.01 * LINEAR_STOP]];
    let model = slider(&stop_table);
    let mut solver = StaticSolver::new(&model, SolverOptions::default()).unwrap();
    let sweep = solver.sweep(LoadPath::new(0.0, 1.0, STEPS), Mode::Corrected).unwrap();
    let steps = &sweep.steps;
    let worst = worst_compression_error(steps, linear_stop_force);
    // Measured: 7.5e-13 m.
    assert!(worst < 5e-11, "{worst}");
    let contact = contact_step(steps);
    let iterations: Vec<usize> = steps.iter().map(|s| s.iterations).collect();
    // Measured: 3 on the steps around contact, 4 on it.
    let neighbours = iterations[contact - 1].max(iterations[contact + 1]);
    assert!(iterations[contact] <= neighbours + 1 && neighbours <= 4, "{iterations:?}");
    let history = residual_history(&mut solver, &steps[contact - 1], steps[contact].t, 4);
    // Measured: e₁/e₀ = 1.15; then orders 3.04 and 2.35.
    assert!(history[1] > 0.5 * history[0], "{history:?}");
    let orders = orders(&history);
    assert!(!orders.is_empty() && orders.iter().all(|&p| p > 1.8), "{history:?} → {orders:?}");
}
