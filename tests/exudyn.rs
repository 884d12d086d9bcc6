//! elastokin against an independent multibody code: the shipped MacPherson's vertical force sweep (the
//! wheel free on its spring, a vertical force at the contact patch from 0.5 to 1.5 times the design wheel
//! load, 100 equal steps from the equilibrium at the first) as Exudyn solved it. The curves in
//! `tests/data/exudyn/` were made by `bench/exudyn/macpherson.py` (see `tests/data/exudyn/README.md` for the
//! version and the commands); no Python is needed here.
//!
//! Exudyn's bushing (`ObjectConnectorRigidBodySpringDamper`) takes its moment from the Tait-Bryan angles of
//! the relative rotation, elastokin's from the energy of the rotation vector: the two agree to first order
//! in the twist. Three curves: Exudyn's connector as it is (the one the bench times), its intrinsic
//! formulation, and the connector with elastokin's law given to it as a user function; the last tells the
//! mapping of the model and the solution apart from the laws.

use elastokin::prelude::*;
use elastokin::solver::Sweep;
use elastokin::suspensions::analysis::design_wheel_load;
use elastokin::suspensions::{Corner, Rig, Side, SuspensionFile};
use std::path::Path;

/// Exudyn's curve with its own bushing law (the one the bench times).
const OWN_LAW: &str = "macpherson_vertical_force.csv";
/// Exudyn's curve with the connector's intrinsic formulation.
const INTRINSIC: &str = "macpherson_vertical_force_intrinsic.csv";
/// Exudyn's curve with elastokin's bushing law as the connector's user function.
const ENERGY_LAW: &str = "macpherson_vertical_force_energy_law.csv";

/// A row of Exudyn's curve: load (N), wheel centre x, y, z (m), toe, camber (rad).
type Row = [f64; 6];

fn exudyn_curve(name: &str) -> Vec<Row> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/exudyn").join(name);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header = lines.next().expect("a header");
    assert!(header.starts_with("load_n,wheel_centre_x_m,wheel_centre_y_m,wheel_centre_z_m,toe_rad,camber_rad"));
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap_or_else(|e| panic!("'{x}': {e}"))).collect();
            [v[0], v[1], v[2], v[3], v[4], v[5]]
        })
        .collect()
}

/// The corner with the force at its contact patch, the first and last loads, and elastokin's sweep of
/// `steps` corrected steps between them (as the bench's `models::case` and the `elastokin run` default).
fn elastokin_sweep(steps: usize) -> (Corner, f64, f64, Sweep) {
    let file =
        SuspensionFile::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/generic/macpherson.json")).unwrap();
    let held = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let load = design_wheel_load(&held).unwrap();
    let mut corner = file.suspension.build(Side::Left, Rig::Free).unwrap();
    let patch = corner.wheel.contact_patch;
    corner.add_wheel_force("vertical force", patch, Vec3::z()).unwrap();
    let (from, to) = (0.5 * load, 1.5 * load);
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default()).unwrap();
    let sweep = solver.sweep(LoadPath::new(from, to, steps), Mode::Corrected).unwrap().complete().unwrap();
    (corner, from, to, sweep)
}

/// At each step: the load and the differences of wheel centre (m), toe and camber (rad), elastokin − Exudyn.
fn differences(name: &str) -> Vec<(f64, [f64; 3])> {
    let exudyn = exudyn_curve(name);
    let (corner, _, _, sweep) = elastokin_sweep(exudyn.len() - 1);
    assert_eq!(sweep.steps.len(), exudyn.len());
    sweep
        .steps
        .iter()
        .zip(&exudyn)
        .map(|(step, row)| {
            let a = corner.wheel.attitude(&step.poses);
            let centre = (a.wheel_centre - Vec3::new(row[1], row[2], row[3])).norm();
            (step.t, [centre, (a.toe - row[4]).abs(), (a.camber - row[5]).abs()])
        })
        .collect()
}

/// The largest differences over the steps `steps` (step 0 is the first load, 50 the design load, 100 the
/// last).
fn largest(diffs: &[(f64, [f64; 3])], steps: std::ops::RangeInclusive<usize>) -> [f64; 3] {
    let mut max = [0.0f64; 3];
    for (_, d) in &diffs[steps] {
        for k in 0..3 {
            max[k] = max[k].max(d[k]);
        }
    }
    max
}

#[test]
fn exudyn_swept_the_same_loads() {
    // The script was given the range by hand (the command in the CSV's header): its rows must be
    // elastokin's steps, to the last digit the CSV keeps.
    for name in [OWN_LAW, INTRINSIC, ENERGY_LAW] {
        let exudyn = exudyn_curve(name);
        assert_eq!(exudyn.len(), 101, "{name}: 100 steps and the first load");
        let (_, from, to, sweep) = elastokin_sweep(exudyn.len() - 1);
        assert!((exudyn[0][0] - from).abs() <= 1e-12 * from && (exudyn[100][0] - to).abs() <= 1e-12 * to, "{name}");
        for (step, row) in sweep.steps.iter().zip(&exudyn) {
            assert!((step.t - row[0]).abs() <= 1e-9 * step.t, "{name}: {} N against {} N", step.t, row[0]);
        }
    }
}

#[test]
fn with_the_same_bushing_law_exudyn_agrees_to_the_solvers_tolerance() {
    let diffs = differences(ENERGY_LAW);
    let [centre, toe, camber] = largest(&diffs, 0..=100);
    // Measured: 2.6e-11 m, 1.7e-11 rad, 3.8e-12 rad (Exudyn 1.13.6, both at Newton's relative tolerance 1e-9).
    assert!(centre < 1e-9, "wheel centre {centre:e} m");
    assert!(toe < 1e-9, "toe {toe:e} rad");
    assert!(camber < 2e-10, "camber {camber:e} rad");
}

#[test]
fn with_exudyn_s_own_bushing_law_the_curves_part_at_second_order_in_the_twist() {
    let diffs = differences(OWN_LAW);
    // Step 50 is the design load: there the bushings are barely twisted, and the two laws give the same
    // moment.
    assert!((diffs[50].0 - 0.5 * (diffs[0].0 + diffs[100].0)).abs() < 1e-9 * diffs[50].0);
    let [centre, toe, camber] = largest(&diffs, 50..=50);
    // Measured: 3.2e-10 m, 2.4e-10 rad, 1.3e-11 rad.
    assert!(centre < 1e-8 && toe < 1e-8 && camber < 1e-9, "at design: {centre:e} m, {toe:e}, {camber:e} rad");
    // Within a tenth of the range of it (ten steps either side) the twist is small and the difference,
    // second order in it, too.
    let [centre, toe, camber] = largest(&diffs, 40..=60);
    // Measured: 6.9e-8 m, 7.0e-8 rad, 5.4e-8 rad.
    assert!(centre < 3e-7 && toe < 3e-7 && camber < 3e-7, "near design: {centre:e} m, {toe:e}, {camber:e} rad");
    // Over the whole sweep, out to half the design load either side.
    let [centre, toe, camber] = largest(&diffs, 0..=100);
    // Measured: 3.6e-6 m, 2.7e-6 rad, 2.1e-6 rad (of a wheel travel of 0.12 m and a toe change of 0.068 rad).
    assert!(centre < 1e-5 && toe < 1e-5 && camber < 1e-5, "whole sweep: {centre:e} m, {toe:e}, {camber:e} rad");
}

#[test]
fn with_exudyn_s_intrinsic_bushing_the_curves_differ_already_at_the_design_load() {
    let diffs = differences(INTRINSIC);
    // At the design load the bushings are barely twisted but carry their share of the wheel load: the
    // intrinsic connector takes and applies its force in the frame and through the point halfway between
    // its two markers, elastokin's bushing in the chassis's frame at the second body's point, so the two
    // differ there at second order in the deflection.
    let [centre, toe, camber] = largest(&diffs, 50..=50);
    // Measured: 7.4e-8 m, 1.3e-7 rad, 3.5e-9 rad.
    assert!(centre < 3e-7 && toe < 5e-7 && camber < 2e-8, "at design: {centre:e} m, {toe:e}, {camber:e} rad");
    // Its moment is elastokin's to second order in the twist, and over the whole sweep the curves stay
    // closer than with the Tait-Bryan connector.
    let [centre, toe, camber] = largest(&diffs, 0..=100);
    // Measured: 2.2e-7 m, 4.8e-7 rad, 4.1e-7 rad.
    assert!(centre < 1e-6 && toe < 2e-6 && camber < 2e-6, "whole sweep: {centre:e} m, {toe:e}, {camber:e} rad");
}
