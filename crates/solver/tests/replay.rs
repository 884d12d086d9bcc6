//! A run recorded and replayed with a moved model (`elastokin_solver::replay`): what the replay
//! returns moves with the model at the rate of its equilibrium, against the lever's moment balance
//! written out here, and a replay that takes another path says so.

use elastokin_core::{BodyRef, JointSpec, Model, Pose, Vec3};
use elastokin_elements::{CoilSpring, PointForce};
use elastokin_solver::replay::{record, replay, Diverged, ReplayRows, Taping};
use elastokin_solver::{BackendChoice, LoadPath, Mode, SolverError, SolverOptions, State, StaticSolver, StepResult};
use std::sync::Arc;

mod lever;
use lever::{angle, lever, moment, SEAT, TIP, TIP_LOAD, TOP};

/// The turn (rad) between −0.5 and 1 where the moment `m` about the hinge vanishes, by bisection.
fn turn_where_balanced(m: impl Fn(f64) -> f64) -> f64 {
    let (mut lo, mut hi) = (-0.5, 1.0);
    assert!(m(lo) * m(hi) < 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if m(lo) * m(mid) <= 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The angle at equilibrium and its rate with respect to `k`, from the moment balance alone: bisection,
/// then the implicit function theorem `dθ/dk = −(∂M/∂k)/(∂M/∂θ)` by central differences of `M`.
fn balance(k: f64, load: f64) -> (f64, f64) {
    let theta = turn_where_balanced(|theta| moment(theta, k, load));
    let (ht, hk) = (1e-6, 1e-3 * k);
    let m_theta = (moment(theta + ht, k, load) - moment(theta - ht, k, load)) / (2.0 * ht);
    let m_k = (moment(theta, k + hk, load) - moment(theta, k - hk, load)) / (2.0 * hk);
    (theta, -m_k / m_theta)
}

/// The sweep's angles: a sweep of the lever of rate `k` from no load to the full tip load, its solver
/// taking part in `taping`.
fn angles(k: f64, taping: &Taping) -> Result<Vec<f64>, SolverError> {
    angles_by(k, BackendChoice::Auto, taping)
}

/// [`angles`] with the KKT backend `backend`.
fn angles_by(k: f64, backend: BackendChoice, taping: &Taping) -> Result<Vec<f64>, SolverError> {
    let model = lever(k);
    let mut solver = StaticSolver::taped(&model, SolverOptions { backend, ..Default::default() }, taping)?;
    Ok(solver.sweep(LoadPath::new(0.0, 1.0, 8), Mode::Corrected)?.steps.iter().map(angle).collect())
}

#[test]
fn a_replay_moves_every_equilibrium_at_the_rate_the_moment_balance_gives() {
    // The dense LU (whose factors the recording keeps, and the replays solve with) and the sparse LDLᵀ
    // (whose replays factorize the moved model's exact tangent).
    for backend in [BackendChoice::Auto, BackendChoice::Sparse] {
        replays_move_at_the_balances_rate(backend);
    }
}

fn replays_move_at_the_balances_rate(backend: BackendChoice) {
    let angles = |k, taping: &Taping| angles_by(k, backend, taping);
    let k = 2e4;
    let (base, tape) = record(|t| angles(k, t));
    let base = base.unwrap();
    assert_eq!((tape.solvers(), tape.equilibria(), tape.limit_point()), (1, 9, None));
    let tape = Arc::new(tape);
    // The replay of the model itself is the recording, one Newton iteration on: the same to the solver's
    // tolerance (measured 8.4e-10 rad at most: what the sweep's chord iterations left).
    let again = replay(&tape, |t| angles(k, t)).unwrap().value.unwrap();
    for (a, b) in base.iter().zip(&again) {
        assert!((a - b).abs() < 1e-8, "{a} {b}");
    }
    // The rate of every angle with k: replays at k ± h, ± 2h, Richardson extrapolated, against the balance.
    let h = 1e-4 * k;
    let replayed: Vec<Vec<f64>> = [h, -h, 2.0 * h, -2.0 * h]
        .iter()
        .map(|d| replay(&tape, |t| angles(k + d, t)).unwrap().value.unwrap())
        .collect();
    for (i, theta) in base.iter().enumerate() {
        let load = i as f64 / 8.0;
        let (exact, rate) = balance(k, load);
        assert!((theta - exact).abs() < 1e-9, "step {i}: angle {theta} against the balance's {exact}");
        let d = (8.0 * (replayed[0][i] - replayed[1][i]) - (replayed[2][i] - replayed[3][i])) / (12.0 * h);
        // Measured: within 3.1e-9 of the rate, relative, solved with the kept factors, and 7.0e-10 by the
        // sparse backend's exact iterations: the balance's own differences, and the recorded equilibria's
        // distance from the exact ones (the derivative is taken there, and errs by as much, relative).
        assert!((d - rate).abs() <= 1e-8 * rate.abs().max(1e-6), "step {i}: dθ/dk {d:e} against {rate:e}");
    }
}

#[test]
fn a_replay_that_creates_other_solvers_or_asks_other_solves_says_so() {
    let (_, tape) = record(|t| angles(2e4, t));
    let tape = Arc::new(tape);
    // One solver more.
    let more = replay(&tape, |t| {
        let first = angles(2e4, t);
        (first, angles(2e4, t))
    });
    assert!(matches!(&more, Err(Diverged(why)) if why.contains("more solvers")), "{more:?}");
    // A single equilibrium where a sweep was recorded.
    let other = replay(&tape, |t| {
        let model = lever(2e4);
        let mut solver = StaticSolver::taped(&model, SolverOptions::default(), t).unwrap();
        let mut state = solver.design_state(0.0);
        solver.equilibrium(&mut state).map(|s| angle(&s))
    });
    assert!(matches!(&other, Err(Diverged(why)) if why.contains("single equilibrium where a sweep")), "{other:?}");
    // No solve at all.
    let fewer = replay(&tape, |_| ());
    assert!(matches!(&fewer, Err(Diverged(why)) if why.contains("created 0 solvers")), "{fewer:?}");
    // A solver that takes part in no recording or replay solves as always.
    assert_eq!(angles(2e4, &Taping::default()), record(|t| angles(2e4, t)).0);
    // And one that holds a recording that has ended solves too.
    let (kept, _) = record(Taping::clone);
    assert_eq!(angles(2e4, &kept), angles(2e4, &Taping::default()));
}

/// Equilibria one after another on one solver that keeps its factorization, each from the last (at loads
/// 0.3, 0.6, 1.0, 0.8, 0.5), then a sweep from where they ended: each solve's chord iterations start from
/// the factorization the one before left.
fn solves_on(k: f64, taping: &Taping) -> Result<Vec<f64>, SolverError> {
    let model = lever(k);
    let options = SolverOptions { reuse_factorization: true, ..Default::default() };
    let mut solver = StaticSolver::taped(&model, options, taping)?;
    let mut state = solver.design_state(0.0);
    let mut angles = Vec::new();
    for t in [0.3, 0.6, 1.0, 0.8, 0.5] {
        state.t = t;
        angles.push(angle(&solver.equilibrium(&mut state)?));
    }
    let sweep = solver.sweep_from(&mut state, LoadPath::new(0.5, 1.0, 8), Mode::Corrected)?;
    angles.extend(sweep.steps.iter().map(angle));
    Ok(angles)
}

/// The tangents' factors a recording keeps for its replays are a second LU's: the solver's own
/// factorization, which its next steps keep, is the one an unrecorded run leaves, and the recorded run's
/// results are the unrecorded one's to the bit.
#[test]
fn a_recorded_run_returns_what_it_returns_unrecorded_to_the_bit() {
    let plain = solves_on(2e4, &Taping::default()).unwrap();
    let (recorded, tape) = record(|t| solves_on(2e4, t));
    assert_eq!(tape.equilibria(), 5 + 9);
    assert_eq!(plain, recorded.unwrap());
}

/// What the solver reads off the tangent at a state.
type TangentReading = fn(&mut StaticSolver, &State) -> Result<Vec<f64>, SolverError>;

/// The lever's path tangent `dq/dt` at `state`.
fn path_tangent(solver: &mut StaticSolver, state: &State) -> Result<Vec<f64>, SolverError> {
    solver.path_tangent(state)
}

/// The lever's compliance at `state`: the tangent solved for a unit moment about the hinge axis on the
/// lever ([`StaticSolver::factorize_tangent`], [`StaticSolver::solve_factored`]).
fn moment_compliance(solver: &mut StaticSolver, state: &State) -> Result<Vec<f64>, SolverError> {
    solver.factorize_tangent(state)?;
    let mut rhs = vec![0.0; solver.model().dofs() + solver.active_rows().len()];
    rhs[4] = 1.0;
    solver.solve_factored(&mut rhs)?;
    Ok(rhs)
}

/// `read` at every step of a sweep of the lever of rate `k`, and the steps.
fn read_at_steps(
    k: f64,
    read: TangentReading,
    taping: &Taping,
) -> Result<(Vec<StepResult>, Vec<Vec<f64>>), SolverError> {
    let model = lever(k);
    let mut solver = StaticSolver::taped(&model, SolverOptions::default(), taping)?;
    let steps = solver.sweep(LoadPath::new(0.0, 1.0, 8), Mode::Corrected)?.steps;
    let read = read_each(&mut solver, &steps, read)?;
    Ok((steps, read))
}

/// `read` by `solver` at each of `steps`.
fn read_each(
    solver: &mut StaticSolver,
    steps: &[StepResult],
    read: TangentReading,
) -> Result<Vec<Vec<f64>>, SolverError> {
    steps
        .iter()
        .map(|s| {
            let state = solver.state_of(s);
            read(solver, &state)
        })
        .collect()
}

/// `read` recorded at every step of the lever of rate `k`, then replayed on the lever of rate `(1 + move) k`:
/// the largest gap between what the replay reads at its moved steps and what `read` reads at the same
/// states on that lever solved outright, as a fraction of the largest recorded reading.
fn replayed_reading_gap(k: f64, move_by: f64, read: TangentReading) -> f64 {
    let (base, tape) = record(|t| read_at_steps(k, read, t));
    let (_, readings) = base.unwrap();
    let largest = readings.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    let tape = Arc::new(tape);
    let moved = (1.0 + move_by) * k;
    let (steps, replayed) = replay(&tape, |t| read_at_steps(moved, read, t)).unwrap().value.unwrap();
    let model = lever(moved);
    let mut solver = StaticSolver::new(&model, SolverOptions::default()).unwrap();
    let exact = read_each(&mut solver, &steps, read).unwrap();
    let gap = replayed.iter().flatten().zip(exact.iter().flatten()).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    gap / largest
}

/// The rate of `read` with `k` at every step of the lever of rate `k`: from replays of its recording at
/// `k ± h, ± 2h`, and from `read` on the lever of each of those rates solved outright to a tight tolerance,
/// each Richardson extrapolated. The largest gap between the two, and the largest rate.
fn replayed_rate_gap(k: f64, read: TangentReading) -> (f64, f64) {
    let (base, tape) = record(|t| read_at_steps(k, read, t));
    let (_, base_readings) = base.unwrap();
    let tape = Arc::new(tape);
    let h = 1e-4 * k;
    let shifts = [h, -h, 2.0 * h, -2.0 * h];
    let replayed: Vec<Vec<Vec<f64>>> =
        shifts.iter().map(|d| replay(&tape, |t| read_at_steps(k + d, read, t)).unwrap().value.unwrap().1).collect();
    let resolved: Vec<Vec<Vec<f64>>> = shifts
        .iter()
        .map(|d| {
            let options = SolverOptions { force_tolerance: 1e-13, constraint_tolerance: 1e-14, ..Default::default() };
            let model = lever(k + d);
            let mut solver = StaticSolver::new(&model, options).unwrap();
            let steps = solver.sweep(LoadPath::new(0.0, 1.0, 8), Mode::Corrected).unwrap().steps;
            read_each(&mut solver, &steps, read).unwrap()
        })
        .collect();
    let richardson = |v: &[Vec<Vec<f64>>], i: usize, c: usize| {
        (8.0 * (v[0][i][c] - v[1][i][c]) - (v[2][i][c] - v[3][i][c])) / (12.0 * h)
    };
    let (mut worst, mut largest) = (0.0f64, 0.0f64);
    for i in 0..base_readings.len() {
        for c in 0..base_readings[i].len() {
            let (a, b) = (richardson(&replayed, i, c), richardson(&resolved, i, c));
            worst = worst.max((a - b).abs());
            largest = largest.max(b.abs());
        }
    }
    (worst, largest)
}

/// A path tangent asked for in a replay, at a moved equilibrium, is solved with the recorded tangent's
/// factors there and one step of refinement against the moved model's tangent: it is the moved model's
/// own to the square of the move (halving the move quarters the gap), and its rate with respect to the
/// move is the exact path tangent's rate at the re-solved equilibria of moved models.
#[test]
fn a_replayed_path_tangent_is_the_moved_models_own_to_the_square_of_the_move() {
    let (large, small) = (replayed_reading_gap(2e4, 2e-3, path_tangent), replayed_reading_gap(2e4, 1e-3, path_tangent));
    // Measured: gaps 3.4e-5 and 8.5e-6 of the largest rate, ratio 3.98.
    println!("gaps {large:.2e} at 0.2 %, {small:.2e} at 0.1 %, ratio {:.3}", large / small);
    assert!(small > 0.0 && (large / small - 4.0).abs() < 0.2, "gaps {large:e} and {small:e}");
    let (worst, largest) = replayed_rate_gap(2e4, path_tangent);
    println!("rate: {:.2e} of the largest", worst / largest);
    // Measured: 1.0e-9 of the largest rate (the re-solves' convergence over the step).
    assert!(largest > 0.0 && worst <= 1e-7 * largest, "{worst:e} of {largest:e}");
}

/// The lever of [`lever`] hinged also at a second point, `0.1` along y, about an axis turned by `tilt`
/// (rad) about x from the first hinge's: coaxial (`tilt = 0`), the second hinge repeats the first and its
/// rows are redundant; turned, it locks the lever.
fn lever_hinged_twice(tilt: f64) -> Model {
    let mut model = lever(2e4);
    let lever = elastokin_core::BodyId(0);
    let axis = Vec3::new(0.0, tilt.cos(), tilt.sin());
    model
        .add_joint(JointSpec::revolute("second pivot", BodyRef::Ground, lever, Vec3::new(0.0, 0.1, 0.0), axis))
        .unwrap();
    model
}

/// A replayed solver looks for redundant rows again where its recorded one dropped some: a move that turns
/// the lever's second hinge off the first's axis makes the rows it repeated independent (the lever is
/// locked), and the replay says so instead of keeping the recorded rows and differentiating another
/// mechanism. (A solver that kept every row is replayed without the check: independence with a margin
/// survives a small move.)
#[test]
fn a_replay_whose_move_makes_a_dropped_row_independent_says_so() {
    let sweep = |tilt: f64, taping: &Taping| -> Result<(Vec<f64>, usize), SolverError> {
        let model = lever_hinged_twice(tilt);
        let mut solver = StaticSolver::taped(&model, SolverOptions::default(), taping)?;
        let dropped = solver.diagnostics().redundant.len();
        Ok((solver.sweep(LoadPath::new(0.0, 1.0, 4), Mode::Corrected)?.steps.iter().map(angle).collect(), dropped))
    };
    let (base, tape) = record(|t| sweep(0.0, t));
    let (angles, dropped) = base.unwrap();
    assert!(dropped > 0, "the coaxial second hinge's rows are redundant");
    let tape = Arc::new(tape);
    // Coaxial still (a move of the load alone): the same rows, replayed.
    let same = replay(&tape, |t| sweep(0.0, t)).unwrap().value.unwrap();
    assert_eq!(same.1, dropped);
    for (a, b) in angles.iter().zip(&same.0) {
        assert!((a - b).abs() < 1e-8, "{a} {b}");
    }
    // Turned by a milliradian: every row independent, which the replay tells.
    let turned = replay(&tape, |t| sweep(1e-3, t));
    assert!(matches!(&turned, Err(Diverged(why)) if why.contains("redundant joints differ")), "{turned:?}");
}

/// A replayed equilibrium is the recorded one moved by one iteration solved with the recorded tangent: the
/// moved model's own residual there is of the second order in the move (halving the move quarters it),
/// which is why a replay reports the recorded step's residuals rather than assembling its own.
#[test]
fn a_replayed_equilibrium_is_the_moved_models_to_the_square_of_the_move() {
    let k = 2e4;
    let sweep = |k: f64, taping: &Taping| -> Result<Vec<StepResult>, SolverError> {
        let model = lever(k);
        let mut solver = StaticSolver::taped(&model, SolverOptions::default(), taping)?;
        Ok(solver.sweep(LoadPath::new(0.0, 1.0, 8), Mode::Corrected)?.steps)
    };
    let (base, tape) = record(|t| sweep(k, t));
    let base = base.unwrap();
    let tape = Arc::new(tape);
    // The gap between a replayed angle and the moved model's exact equilibrium (the moment balance).
    let gap = |d: f64| -> Vec<f64> {
        let moved = replay(&tape, |t| sweep(k + d, t)).unwrap().value.unwrap();
        moved.iter().enumerate().map(|(i, s)| (angle(s) - balance(k + d, i as f64 / 8.0).0).abs()).collect()
    };
    let (large, small) = (gap(0.02 * k), gap(0.01 * k));
    for (i, (l, s)) in large.iter().zip(&small).enumerate().skip(1) {
        // Measured: ratios 3.908 to 3.959 over the steps (the cube of the move shows at the loaded end).
        println!("step {i}: gap {l:e} at 2 %, {s:e} at 1 %, ratio {:.3}", l / s);
        assert!((l / s - 4.0).abs() < 0.2, "step {i}: gaps {l:e} and {s:e}");
    }
    // And the replayed steps report the recorded residuals.
    let moved = replay(&tape, |t| sweep(k * 1.01, t)).unwrap().value.unwrap();
    for (b, m) in base.iter().zip(&moved) {
        assert_eq!((b.force_residual, b.constraint_residual), (m.force_residual, m.constraint_residual));
    }
}

/// The sweep's angles with a replay moving only `rows` of it.
fn angles_moving(k: f64, rows: Option<ReplayRows>, taping: &Taping) -> Result<Vec<f64>, SolverError> {
    let model = lever(k);
    let mut solver = StaticSolver::taped(&model, SolverOptions::default(), taping)?;
    solver.replay_rows(rows);
    Ok(solver.sweep(LoadPath::new(0.0, 1.0, 8), Mode::Corrected)?.steps.iter().map(angle).collect())
}

#[test]
fn a_replay_asked_for_some_rows_moves_those_alone_as_a_whole_replay_does() {
    let k = 2e4;
    let (base, tape) = record(|t| angles_moving(k, None, t));
    let (base, tape) = (base.unwrap(), Arc::new(tape));
    let moved = k * 1.01;
    let all = replay(&tape, |t| angles_moving(moved, None, t)).unwrap().value.unwrap();
    // Rows within one step (1/8) of load 0.5, and the last: steps 3, 4, 5 and 8.
    let rows = ReplayRows { near: Some(0.5), last: true, extremes: false };
    let some = replay(&tape, |t| angles_moving(moved, Some(rows), t)).unwrap().value.unwrap();
    // Those steps alone, in order, each as the whole replay moves it.
    assert_eq!(some, [3, 4, 5, 8].map(|i| all[i]));
    assert!([3, 4, 5, 8].iter().all(|&i| all[i] != base[i]));
    // Outside a replay the rows asked for change nothing.
    let none = Taping::default();
    assert_eq!(angles_moving(k, Some(rows), &none).unwrap(), angles_moving(k, None, &none).unwrap());
}

/// The sweep's angles with a replay moving the rows within one step of load 0.5 and the row the run finds
/// its largest angle at, named once read ([`Taping::rows_read`]).
fn angles_moving_the_largest(k: f64, taping: &Taping) -> Result<Vec<f64>, SolverError> {
    let model = lever(k);
    let mut solver = StaticSolver::taped(&model, SolverOptions::default(), taping)?;
    solver.replay_rows(Some(ReplayRows { near: Some(0.5), last: false, extremes: true }));
    let angles: Vec<f64> = solver.sweep(LoadPath::new(0.0, 1.0, 8), Mode::Corrected)?.steps.iter().map(angle).collect();
    let largest = (0..angles.len()).max_by(|&a, &b| angles[a].abs().total_cmp(&angles[b].abs())).unwrap();
    taping.rows_read(&[largest]);
    Ok(angles)
}

#[test]
fn a_row_a_run_names_once_read_is_moved_by_the_replays_as_a_whole_replay_moves_it() {
    let k = 2e4;
    let (base, tape) = record(|t| angles_moving_the_largest(k, t));
    let (base, tape) = (base.unwrap(), Arc::new(tape));
    let largest = (0..base.len()).max_by(|&a, &b| base[a].abs().total_cmp(&base[b].abs())).unwrap();
    assert!(![3, 4, 5].contains(&largest), "the largest angle is at step {largest}, among the rows near 0.5");
    let moved = k * 1.01;
    let all = replay(&tape, |t| angles_moving(moved, None, t)).unwrap().value.unwrap();
    let some = replay(&tape, |t| angles_moving_the_largest(moved, t)).unwrap().value.unwrap();
    // The steps near 0.5 and the one named, in order, each as the whole replay moves it.
    let mut named = [3, 4, 5, largest];
    named.sort_unstable();
    assert_eq!(some, named.iter().map(|&i| all[i]).collect::<Vec<_>>());
    assert!(named.iter().all(|&i| all[i] != base[i]));
    // Outside a recording, naming rows changes nothing.
    let none = Taping::default();
    assert_eq!(angles_moving_the_largest(k, &none).unwrap(), angles_moving(k, None, &none).unwrap());
}

/// The lever's sweep angles, and whether its solver analysed the KKT pattern itself (not reusing a
/// workspace).
fn angles_analysed(k: f64, taping: &Taping) -> Result<(Vec<f64>, bool), SolverError> {
    let model = lever(k);
    let mut solver = StaticSolver::taped(&model, SolverOptions::default(), taping)?;
    let analysed = solver.counters().factor.symbolic_analyses > 0;
    Ok((solver.sweep(LoadPath::new(0.0, 1.0, 8), Mode::Corrected)?.steps.iter().map(angle).collect(), analysed))
}

#[test]
fn a_replays_solver_takes_the_workspace_an_earlier_replay_left_and_reads_what_a_fresh_one_reads() {
    let k = 2e4;
    let (_, tape) = record(|t| angles_analysed(k, t));
    let tape = Arc::new(tape);
    let moved = k * 1.01;
    let (first, analysed) = replay(&tape, |t| angles_analysed(moved, t)).unwrap().value.unwrap();
    assert!(analysed, "the first replay's solver has no workspace to take");
    let (second, analysed) = replay(&tape, |t| angles_analysed(moved, t)).unwrap().value.unwrap();
    assert!(!analysed, "the second replay's solver takes the first's workspace");
    assert_eq!(second, first);
    // A copy of the recording keeps no workspaces: its replay analyses afresh, and reads the same.
    let copy = Arc::new((*tape).clone());
    let (third, analysed) = replay(&copy, |t| angles_analysed(moved, t)).unwrap().value.unwrap();
    assert!(analysed);
    assert_eq!(third, first);
}

#[test]
fn a_decision_a_recording_took_is_its_replays_without_deciding_again() {
    // The run decides twice, then sweeps: the decisions are `k`'s, as a model's form is its own.
    let run = |k: f64, taping: &Taping| -> (u32, Vec<bool>, Result<Vec<f64>, SolverError>) {
        let first = taping.decided(|| (k / 1e4) as u32);
        let second = taping.decided(|| vec![k > 1e4, k > 3e4]);
        (first, second, angles_moving(k, None, taping))
    };
    let ((first, second, _), tape) = record(|t| run(2e4, t));
    assert_eq!((first, second.as_slice()), (2, [true, false].as_slice()));
    let tape = Arc::new(tape);
    // Replayed on a model whose own decisions would differ: the recording's, not decided again.
    let (first, second, angles) = replay(&tape, |t| run(4e4, t)).unwrap().value;
    assert_eq!((first, second.as_slice()), (2, [true, false].as_slice()));
    assert!(angles.is_ok());
    // Outside a recording or replay, decided.
    assert_eq!(Taping::default().decided(|| 7_u32), 7);
}

/// The lever with its spring's top `top_z` higher and its hinge `pivot_x` along x: moves that touch one
/// element (the spring) and one joint (the hinge), of which a replay corrects the recorded right-hand side
/// alone.
fn lever_moved(top_z: f64, pivot_x: f64) -> Model {
    let mut model = Model::new();
    let lever = model.add_body("lever", Pose::at(Vec3::new(0.25, 0.0, 0.0))).unwrap();
    let pivot = Vec3::new(pivot_x, 0.0, 0.0);
    model.add_joint(JointSpec::revolute("pivot", BodyRef::Ground, lever, pivot, Vec3::y())).unwrap();
    let seat = Vec3::new(SEAT, 0.0, 0.0);
    let top = Vec3::new(TOP[0], TOP[1], TOP[2] + top_z);
    let free = (Vec3::new(SEAT, 0.0, 0.0) - Vec3::from(TOP)).norm();
    let spring = CoilSpring::new("spring", BodyRef::Ground, top, lever.into(), seat, 2e4, free).unwrap();
    model.add_element(spring).unwrap();
    let tip = PointForce::new("tip", lever.into(), Vec3::new(TIP, 0.0, 0.0), Vec3::new(0.0, 0.0, -TIP_LOAD)).unwrap();
    model.add_element(tip).unwrap();
    model
}

/// The moment about the hinge of the lever of [`lever_moved`] turned by `theta` about it.
fn moment_moved(theta: f64, load: f64, top_z: f64, pivot_x: f64) -> f64 {
    let (c, s) = (theta.cos(), theta.sin());
    let pivot = Vec3::new(pivot_x, 0.0, 0.0);
    let turned = |x: f64| pivot + Vec3::new((x - pivot_x) * c, 0.0, -(x - pivot_x) * s);
    let (seat, tip) = (turned(SEAT), turned(TIP));
    let top = Vec3::new(TOP[0], TOP[1], TOP[2] + top_z);
    let free = (Vec3::new(SEAT, 0.0, 0.0) - Vec3::from(TOP)).norm();
    let d = seat - top;
    let spring = -2e4 * (d.norm() - free) * d / d.norm();
    (seat - pivot).cross(&spring).y + (tip - pivot).cross(&Vec3::new(0.0, 0.0, -load * TIP_LOAD)).y
}

/// The lever's turn about its hinge at equilibrium, by bisection of the moment balance.
fn turn_moved(load: f64, top_z: f64, pivot_x: f64) -> f64 {
    turn_where_balanced(|theta| moment_moved(theta, load, top_z, pivot_x))
}

#[test]
fn a_replay_moving_a_spring_end_or_a_hinge_moves_at_the_balances_rate() {
    let turns = |top_z: f64, pivot_x: f64, taping: &Taping| -> Vec<f64> {
        let model = lever_moved(top_z, pivot_x);
        let mut solver = StaticSolver::taped(&model, SolverOptions::default(), taping).unwrap();
        let steps = solver.sweep(LoadPath::new(0.0, 1.0, 8), Mode::Corrected).unwrap().steps;
        // The body's reference is 0.25 m along the lever from the origin: its turn about the hinge.
        steps.iter().map(|s| (-s.poses[0].position.z).atan2(s.poses[0].position.x - pivot_x)).collect()
    };
    let (_, tape) = record(|t| turns(0.0, 0.0, t));
    let tape = Arc::new(tape);
    let h = 1e-4;
    for (name, at) in [("spring top z", [1.0, 0.0]), ("hinge x", [0.0, 1.0])] {
        let replayed: Vec<Vec<f64>> = [h, -h, 2.0 * h, -2.0 * h]
            .iter()
            .map(|d| replay(&tape, |t| turns(d * at[0], d * at[1], t)).unwrap().value)
            .collect();
        for i in 0..9 {
            let load = i as f64 / 8.0;
            let d = (8.0 * (replayed[0][i] - replayed[1][i]) - (replayed[2][i] - replayed[3][i])) / (12.0 * h);
            let balance = |x: f64| turn_moved(load, x * at[0], x * at[1]);
            let e = 1e-4;
            let exact = (8.0 * (balance(e) - balance(-e)) - (balance(2.0 * e) - balance(-2.0 * e))) / (12.0 * e);
            // Measured: within 3.1e-9 of the balance's rate, relative (the hinge, step 6): the balance's own
            // differences and the recorded equilibria's distance from the exact ones.
            println!("{name}, step {i}: replays {d:e}, balance {exact:e}");
            assert!((d - exact).abs() <= 1e-7 * exact.abs().max(1e-3), "{name}, step {i}: {d:e} against {exact:e}");
        }
    }
}

/// Tangent solves asked for in a replay, at its moved equilibria, are the moved model's own there to the
/// square of the move, and their rates the exact ones', as the path tangent's are.
#[test]
fn a_replayed_tangent_solve_is_the_moved_models_own_to_the_square_of_the_move() {
    let gap = |by: f64| replayed_reading_gap(2e4, by, moment_compliance);
    let (large, small) = (gap(2e-3), gap(1e-3));
    // Measured: gaps 3.4e-5 and 8.5e-6 of the largest solve, ratio 3.98.
    println!("gaps {large:.2e} at 0.2 %, {small:.2e} at 0.1 %, ratio {:.3}", large / small);
    assert!(small > 0.0 && (large / small - 4.0).abs() < 0.2, "gaps {large:e} and {small:e}");
    let (worst, largest) = replayed_rate_gap(2e4, moment_compliance);
    println!("rate: {:.2e} of the largest", worst / largest);
    // Measured: 1.0e-9 of the largest rate.
    assert!(largest > 0.0 && worst <= 1e-7 * largest, "{worst:e} of {largest:e}");
}
