//! The rates of an equilibrium along its load path (`StaticSolver::path_rates_factored`) and the tangent
//! line they span (`StaticSolver::along_path`): the lever's turn rate against the implicit function
//! theorem on its moment balance written here, the multipliers' rates against differences of equilibria
//! solved apart; the rates with a driver scaled (`StaticSolver::path_tangent_factored_with_drivers_scaled`)
//! against two driven levers' geometry.

mod lever;

use elastokin_solver::{PathRates, SolverOptions, State, StaticSolver, StepResult};
use lever::{angle, lever, moment};

/// The lever's rate (N/m).
const RATE: f64 = 2e4;

/// The lever's equilibrium at load `t`, its tangent factorized there, and the path's rates.
fn equilibrium_and_rates(solver: &mut StaticSolver, t: f64) -> (State, StepResult, PathRates) {
    let mut state = solver.design_state(t);
    let at = solver.equilibrium(&mut state).unwrap();
    solver.factorize_tangent(&state).unwrap();
    let rates = solver.path_rates_factored().unwrap();
    (state, at, rates)
}

#[test]
fn the_tangent_line_turns_the_lever_at_the_rate_its_moment_balance_gives() {
    let model = lever(RATE);
    let mut solver = StaticSolver::new(&model, SolverOptions::default()).unwrap();
    let t = 0.6;
    let (state, at, rates) = equilibrium_and_rates(&mut solver, t);
    assert_eq!(rates.dq, solver.path_tangent_factored().unwrap());
    // The implicit function theorem on M(θ, t) = 0: dθ/dt = −M_t / M_θ, M's partials by central differences.
    let theta = angle(&at);
    let (ht, hl) = (1e-6, 1e-6);
    let m_theta = (moment(theta + ht, RATE, t) - moment(theta - ht, RATE, t)) / (2.0 * ht);
    let m_t = (moment(theta, RATE, t + hl) - moment(theta, RATE, t - hl)) / (2.0 * hl);
    let exact = -m_t / m_theta;
    // The turn read on the tangent line, differenced (Richardson over ±h, ±2h).
    let h = 1e-4;
    let read = |k: f64| angle(&solver.along_path(&state, &rates, None, k * h));
    let line = (8.0 * (read(1.0) - read(-1.0)) - (read(2.0) - read(-2.0))) / (12.0 * h);
    // Measured 2.7e-10 relative: the balance's own differences and the solver's tolerance.
    assert!((line - exact).abs() <= 1e-8 * exact.abs(), "dθ/dt {line:e} against the balance's {exact:e}");
    assert!(exact.abs() > 0.1, "the lever turns under the tip load: {exact}");
    // The point on the line at h = 0 is the equilibrium itself, at its load parameter.
    let zero = solver.along_path(&state, &rates, None, 0.0);
    assert_eq!((zero.poses.clone(), zero.multipliers.clone(), zero.t), (at.poses.clone(), at.multipliers.clone(), t));
    assert_eq!(solver.along_path(&state, &rates, None, h).t, t + h);
}

#[test]
fn the_multipliers_rates_are_those_of_equilibria_solved_apart() {
    let model = lever(RATE);
    let mut solver = StaticSolver::new(&model, SolverOptions::default()).unwrap();
    let t = 0.6;
    let (_, at, rates) = equilibrium_and_rates(&mut solver, t);
    let mut solved = |s: f64| {
        let mut st = solver.design_state(s);
        solver.equilibrium(&mut st).unwrap()
    };
    let h = 1e-3;
    let (p1, m1, p2, m2) = (solved(t + h), solved(t - h), solved(t + 2.0 * h), solved(t - 2.0 * h));
    let active = solver.active_rows().to_vec();
    assert_eq!(active.len(), rates.dlambda.len());
    let mut largest = 0.0f64;
    for (k, &row) in active.iter().enumerate() {
        let d = |a: &StepResult, b: &StepResult| a.multipliers[row] - b.multipliers[row];
        let apart = (8.0 * d(&p1, &m1) - d(&p2, &m2)) / (12.0 * h);
        let scale = at.multipliers.iter().fold(1.0f64, |a, v| a.max(v.abs()));
        // Measured 3.7e-9 of the multipliers' scale: the equilibria's tolerance over the step.
        assert!((rates.dlambda[k] - apart).abs() <= 1e-7 * scale, "row {row}: {} against {apart}", rates.dlambda[k]);
        largest = largest.max(apart.abs());
    }
    assert!(largest > 10.0, "the hinge's reaction grows with the tip load: {largest}");
}

#[test]
fn the_second_rates_are_the_curvature_of_equilibria_solved_apart() {
    let model = lever(RATE);
    let mut solver = StaticSolver::new(&model, SolverOptions::default()).unwrap();
    let t = 0.6;
    let (state, at, rates) = equilibrium_and_rates(&mut solver, t);
    let second = solver.path_second_rates(&state, &rates, 1e-4).unwrap();
    // The turn's second derivative read on the path's second-order expansion, against the second
    // differences of equilibria solved apart (Richardson over ±h, ±2h).
    let h = 1e-3;
    let on_path = |k: f64| angle(&solver.along_path(&state, &rates, Some(&second), k * h));
    let expanded =
        (16.0 * (on_path(1.0) + on_path(-1.0)) - (on_path(2.0) + on_path(-2.0)) - 30.0 * angle(&at)) / (12.0 * h * h);
    let mut solved = |s: f64| {
        let mut st = solver.design_state(t + s);
        angle(&solver.equilibrium(&mut st).unwrap())
    };
    let apart =
        (16.0 * (solved(h) + solved(-h)) - (solved(2.0 * h) + solved(-2.0 * h)) - 30.0 * angle(&at)) / (12.0 * h * h);
    assert!(apart.abs() > 1e-3, "the lever's turn bends with the load: {apart}");
    // Measured 7.1e-8 relative: the equilibria's tolerance over h², and the residual's rounding over the
    // second rates' step.
    assert!((expanded - apart).abs() <= 1e-6 * apart.abs(), "d²θ/dt² {expanded:e} against {apart:e}");
    // On the tangent line alone the turn's second difference misses the path's curvature (the lever turns
    // about a fixed hinge: its turn is linear on the line, and the whole of it is missed).
    let line = |k: f64| angle(&solver.along_path(&state, &rates, None, k * h));
    let straight = (line(1.0) + line(-1.0) - 2.0 * angle(&at)) / (h * h);
    assert!((straight - apart).abs() > 0.5 * apart.abs(), "{straight:e} against {apart:e}");
}

/// Two levers hinged about y, side by side, each tip driven up by the load parameter: with the second
/// driver's rate scaled by −1 the rates are those of the second tip driven down, each lever turning at the
/// rate its tip's height gives, dθ/dt = −(tip's rate) / (TIP cos θ) (z = −TIP sin θ), from the state the
/// path reached with both driven up.
#[test]
fn scaling_a_driver_gives_the_rates_of_the_path_it_would_drive() {
    use elastokin_core::{BodyRef, JointSpec, Model, Pose, Vec3, BODY_DOFS};
    let mut model = Model::new();
    let mut drivers = Vec::new();
    for (k, y) in [0.0, 1.0].into_iter().enumerate() {
        let lever = model.add_body(&format!("lever {k}"), Pose::at(Vec3::new(0.25, y, 0.0))).unwrap();
        let hinge =
            JointSpec::revolute(&format!("hinge {k}"), BodyRef::Ground, lever, Vec3::new(0.0, y, 0.0), Vec3::y());
        model.add_joint(hinge).unwrap();
        let tip = Vec3::new(lever::TIP, y, 0.0);
        drivers
            .push(model.add_joint(JointSpec::point_driver(&format!("tip {k}"), lever, tip, Vec3::z(), 1.0)).unwrap());
    }
    let mut solver = StaticSolver::new(&model, SolverOptions::default()).unwrap();
    let t = 0.05;
    let mut state = solver.design_state(t);
    let at = solver.equilibrium(&mut state).unwrap();
    solver.factorize_tangent(&state).unwrap();
    let path = solver.path_tangent_factored().unwrap();
    let scaled = solver.path_tangent_factored_with_drivers_scaled(&[(drivers[1], -1.0)]).unwrap();
    // Each lever's turn about y, its rate about y, and its tip's rate along the path that was driven.
    for (k, tip_rate) in [1.0, -1.0].into_iter().enumerate() {
        let p = at.poses[k].position;
        let theta = (-p.z).atan2(p.x);
        let expected = -tip_rate / (lever::TIP * theta.cos());
        let got = scaled[k * BODY_DOFS + 4];
        // Measured: equal to the bit; a few ulps allowed.
        assert!((got - expected).abs() <= 1e-15 * expected.abs(), "lever {k}: {got} against {expected}");
        // The path's own rates turn both levers alike.
        assert!((path[k * BODY_DOFS + 4] + 1.0 / (lever::TIP * theta.cos())).abs() <= 1e-15 * expected.abs());
    }
}
