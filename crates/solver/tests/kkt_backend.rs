//! Tests of the KKT backends (`kkt_backend`): the dense LU of the whole non-symmetric matrix and the
//! automatic choice with its sparse fallback, against the dense pivoted reference (`dense_reference`:
//! equilibrated full-pivot LU, built on nalgebra alone) on random systems.
//!
//! Sign convention: `[K + S, Jᵀ; J, 0] [x; y] = [a; b]`, `S` skew.

use elastokin_solver::dense_reference::solve_dense_pivoted;
use elastokin_solver::kkt::{Accuracy, AutoKkt, BackendChoice, DenseLu, KktBackend, KktValues, DENSE_MAX_ORDER};
use elastokin_solver::kkt::{FactorError, KktOptions, KktPattern};
use nalgebra::DMatrix;
use strum::IntoEnumIterator;

mod common;
use common::{random_j, random_spd, random_vec, rel_err, to_sparse, Rng};

/// A random skew part on the stored upper entries of `pattern` (above the diagonal), of size `size`
/// relative to `k`'s entries there; returns the values and the full non-symmetric `K + S`.
fn random_skew(rng: &mut Rng, k: &DMatrix<f64>, pattern: &KktPattern, size: f64) -> (Vec<f64>, DMatrix<f64>) {
    let mut full = k.clone();
    let mut skew = Vec::with_capacity(pattern.k_row_idx.len());
    for c in 0..pattern.n {
        for &r in &pattern.k_row_idx[pattern.k_col_ptr[c]..pattern.k_col_ptr[c + 1]] {
            let s = if r < c { size * rng.uniform() * (k[(r, r)] * k[(c, c)]).sqrt() } else { 0.0 };
            full[(r, c)] += s;
            full[(c, r)] -= s;
            skew.push(s);
        }
    }
    (skew, full)
}

/// `D K D` with `D` spreading the diagonal geometrically over `[1, ratio]`.
fn spread(k: &DMatrix<f64>, ratio: f64) -> DMatrix<f64> {
    let n = k.nrows();
    let d: Vec<f64> = (0..n).map(|i| ratio.powf(i as f64 / (n - 1).max(1) as f64).sqrt()).collect();
    DMatrix::from_fn(n, n, |r, c| d[r] * k[(r, c)] * d[c])
}

#[test]
fn dense_lu_solves_the_non_symmetric_tangent_as_the_pivoted_reference() {
    let mut rng = Rng(0x0005_eed1);
    let mut worst: f64 = 0.0;
    let mut worst_omega: f64 = 0.0;
    for &ratio in &[1.0, 1e4, 1e8, 1e12] {
        for _ in 0..4 {
            let (n, m) = (18, 9);
            let k = spread(&random_spd(&mut rng, n, 0.1), ratio);
            let j = random_j(&mut rng, m, n, 3);
            let (pattern, kv, jv) = to_sparse(&k, &j);
            let (skew, full) = random_skew(&mut rng, &k, &pattern, 0.3);
            let rhs = random_vec(&mut rng, n + m);
            let reference = solve_dense_pivoted(n, m, &full, &j, &rhs).expect("nonsingular");
            let mut lu = DenseLu::analyze(&pattern, KktOptions::default()).unwrap();
            lu.factorize(KktValues { k: &kv, k_skew: Some(&skew), j: &jv }).unwrap();
            let mut z = rhs.clone();
            let report = lu.solve_in_place(&mut z, Accuracy::Refined).unwrap();
            worst = worst.max(rel_err(&z[..n], &reference[..n])).max(rel_err(&z[n..], &reference[n..]));
            worst_omega = worst_omega.max(report.backward_error);
            // The report is true: measured, and converged exactly when ω is at the tolerance.
            assert!(report.measured);
            assert_eq!(report.converged, report.backward_error <= 2.0 * f64::EPSILON, "{report:?}");
        }
    }
    // Measured: 3.5e-15 over stiffness ratios up to 1e12, with the componentwise backward error at most
    // 3.9e-16, within the refinement tolerance 2ε = 4.4e-16.
    assert!(worst <= 3e-13, "largest relative error against the pivoted reference {worst:e}");
    assert!(worst_omega <= 2.0 * f64::EPSILON, "backward error {worst_omega:e}");
}

#[test]
fn a_symmetric_system_gives_the_pivoted_reference_solution_on_every_backend() {
    let mut rng = Rng(0xb0b);
    let mut worst: f64 = 0.0;
    let choices: Vec<BackendChoice> = BackendChoice::iter().collect();
    assert_eq!(choices.len(), 3, "Auto, Dense, Sparse: {choices:?}");
    for _ in 0..6 {
        let (n, m) = (24, 10);
        let k = random_spd(&mut rng, n, 0.05);
        let j = random_j(&mut rng, m, n, 2);
        let (pattern, kv, jv) = to_sparse(&k, &j);
        let rhs = random_vec(&mut rng, n + m);
        let reference = solve_dense_pivoted(n, m, &k, &j, &rhs).expect("nonsingular");
        for &choice in &choices {
            let mut backend = AutoKkt::analyze(&pattern, KktOptions::default(), choice).unwrap();
            backend.factorize(KktValues { k: &kv, k_skew: None, j: &jv }).unwrap();
            let mut z = rhs.clone();
            backend.solve_in_place(&mut z, Accuracy::Refined).unwrap();
            let error = rel_err(&z[..n], &reference[..n]).max(rel_err(&z[n..], &reference[n..]));
            worst = worst.max(error);
        }
    }
    // Measured: 5.2e-16.
    assert!(worst <= 4e-14, "a backend differs from the pivoted reference by {worst:e}");
}

#[test]
fn auto_picks_the_dense_lu_up_to_the_crossover_order() {
    let mut rng = Rng(0xa070);
    for (n, m, dense) in [(18, 9, true), (60, DENSE_MAX_ORDER - 60, true), (80, DENSE_MAX_ORDER - 79, false)] {
        let k = random_spd(&mut rng, n, 0.1);
        let j = random_j(&mut rng, m, n, 2);
        let (pattern, kv, jv) = to_sparse(&k, &j);
        let (skew, full) = random_skew(&mut rng, &k, &pattern, 0.2);
        let mut backend = AutoKkt::analyze(&pattern, KktOptions::default(), BackendChoice::Auto).unwrap();
        backend.factorize(KktValues { k: &kv, k_skew: Some(&skew), j: &jv }).unwrap();
        assert_eq!(backend.name(), if dense { "dense LU" } else { "sparse LDLᵀ" }, "order {}", n + m);
        assert_eq!(backend.solves_skew(), dense);
        if dense {
            // It solves the skew part with the rest.
            let rhs = random_vec(&mut rng, n + m);
            let reference = solve_dense_pivoted(n, m, &full, &j, &rhs).expect("nonsingular");
            let mut z = rhs.clone();
            backend.solve_in_place(&mut z, Accuracy::Refined).unwrap();
            // Measured: 5.1e-16.
            assert!(rel_err(&z, &reference) <= 5e-14, "{:e}", rel_err(&z, &reference));
        }
    }
}

#[test]
fn a_singular_matrix_is_named_by_the_dense_lu_and_solved_by_the_sparse_fallback() {
    let mut rng = Rng(0xf4ee);
    let (n, m) = (12, 4);
    let mut k = random_spd(&mut rng, n, 0.1);
    let free = 8;
    for i in 0..n {
        k[(free, i)] = 0.0;
        k[(i, free)] = 0.0;
    }
    let mut j = random_j(&mut rng, m, n, 2);
    j.column_mut(free).fill(0.0);
    // The free coordinate is the one defect: every constraint row keeps an entry in another column.
    assert!(j.row_iter().all(|row| row.iter().any(|&v| v != 0.0)), "{j}");
    let (pattern, kv, jv) = to_sparse(&k, &j);
    let values = KktValues { k: &kv, k_skew: None, j: &jv };
    let mut lu = DenseLu::analyze(&pattern, KktOptions::default()).unwrap();
    assert_eq!(lu.factorize(values), Err(FactorError::Singular { kind: "body coordinate", index: free }));
    let mut auto = AutoKkt::analyze(&pattern, KktOptions::default(), BackendChoice::Auto).unwrap();
    let report = auto.factorize(values).unwrap();
    assert_eq!(auto.name(), "sparse LDLᵀ");
    assert_eq!(report.suspect_body_dofs, vec![free]);
    // The fallback's analysis is counted: the dense one and the sparse one.
    assert_eq!(auto.counters().symbolic_analyses, 2);
    // A solve gives finite numbers, and the next regular matrix goes back to the dense LU.
    let mut z = random_vec(&mut rng, n + m);
    z[free] = 0.0;
    auto.solve_in_place(&mut z, Accuracy::Refined).unwrap();
    assert!(z.iter().all(|v| v.is_finite()));
    // The free coordinate given a stiffness of its own: the same pattern (every diagonal is stored), now
    // regular.
    k[(free, free)] = 1.0;
    let (same, kv, _) = to_sparse(&k, &j);
    assert_eq!(same, pattern);
    auto.factorize(KktValues { k: &kv, k_skew: None, j: &jv }).unwrap();
    assert_eq!(auto.name(), "dense LU");
    let rhs = random_vec(&mut rng, n + m);
    let reference = solve_dense_pivoted(n, m, &k, &j, &rhs).expect("nonsingular");
    let mut z = rhs.clone();
    auto.solve_in_place(&mut z, Accuracy::Refined).unwrap();
    // Measured: 1.2e-16.
    assert!(rel_err(&z, &reference) <= 1e-14, "{:e}", rel_err(&z, &reference));
}

#[test]
fn the_scaling_is_renewed_only_when_values_change_by_orders_of_magnitude() {
    let mut rng = Rng(0x5ca1e);
    let (n, m) = (18, 9);
    let k = spread(&random_spd(&mut rng, n, 0.1), 1e6);
    let j = random_j(&mut rng, m, n, 3);
    let (pattern, kv, jv) = to_sparse(&k, &j);
    let mut lu = DenseLu::analyze(&pattern, KktOptions::default()).unwrap();
    lu.factorize(KktValues { k: &kv, k_skew: None, j: &jv }).unwrap();
    let first = lu.scaling().to_vec();
    let solve = |lu: &mut DenseLu, factor: f64| {
        let kv: Vec<f64> = kv.iter().map(|v| v * factor).collect();
        lu.factorize(KktValues { k: &kv, k_skew: None, j: &jv }).unwrap();
        let rhs = random_vec(&mut Rng(7), n + m);
        let reference = solve_dense_pivoted(n, m, &(&k * factor), &j, &rhs).unwrap();
        let mut z = rhs.clone();
        lu.solve_in_place(&mut z, Accuracy::Refined).unwrap();
        rel_err(&z, &reference)
    };
    // A load step's change: the scaling stays.
    let small = solve(&mut lu, 1.5);
    assert_eq!(lu.scaling(), &first[..]);
    // A thousandfold change: renewed.
    let large = solve(&mut lu, 1e3);
    assert_ne!(lu.scaling(), &first[..]);
    // Both solved as the reference does. Measured: 4.5e-16 and 8.7e-17.
    assert!(small <= 4e-14 && large <= 8e-15, "{small:e} {large:e}");
}

#[test]
fn an_increment_solve_skips_the_measurement_and_says_so() {
    let mut rng = Rng(0x1c);
    let (n, m) = (18, 9);
    let k = spread(&random_spd(&mut rng, n, 0.1), 1e8);
    let j = random_j(&mut rng, m, n, 3);
    let (pattern, kv, jv) = to_sparse(&k, &j);
    let mut lu = DenseLu::analyze(&pattern, KktOptions::default()).unwrap();
    lu.factorize(KktValues { k: &kv, k_skew: None, j: &jv }).unwrap();
    let rhs = random_vec(&mut rng, n + m);
    let reference = solve_dense_pivoted(n, m, &k, &j, &rhs).unwrap();
    let mut z = rhs.clone();
    let report = lu.solve_in_place(&mut z, Accuracy::Increment).unwrap();
    assert!(!report.measured && !report.converged && report.refinement_steps == 0);
    // Unrefined, still as good as the pivoting allows. Measured: 1.0e-12 at stiffness ratio 1e8.
    assert!(rel_err(&z, &reference) <= 1e-11, "{:e}", rel_err(&z, &reference));
    assert_eq!(lu.counters().refinement_steps, 0);
}

#[test]
fn bad_values_are_typed_errors_naming_the_entry() {
    let mut rng = Rng(0xbad);
    let (n, m) = (6, 2);
    let k = random_spd(&mut rng, n, 0.1);
    let j = random_j(&mut rng, m, n, 2);
    let (pattern, mut kv, jv) = to_sparse(&k, &j);
    let mut lu = DenseLu::analyze(&pattern, KktOptions::default()).unwrap();
    let mut z = vec![1.0; n + m];
    assert_eq!(lu.solve_in_place(&mut z, Accuracy::Refined), Err(FactorError::NotFactorized));
    kv[3] = f64::NAN;
    assert_eq!(
        lu.factorize(KktValues { k: &kv, k_skew: None, j: &jv }),
        Err(FactorError::NonFinite { what: "k_values", index: 3 })
    );
    assert!(matches!(
        lu.factorize(KktValues { k: &kv[..2], k_skew: None, j: &jv }),
        Err(FactorError::PatternMismatch { what: "k_values", .. })
    ));
    kv[3] = 1.0;
    lu.factorize(KktValues { k: &kv, k_skew: None, j: &jv }).unwrap();
    let mut short = vec![1.0; n];
    assert!(matches!(lu.solve_in_place(&mut short, Accuracy::Refined), Err(FactorError::PatternMismatch { .. })));
    z[1] = f64::INFINITY;
    assert_eq!(lu.solve_in_place(&mut z, Accuracy::Refined), Err(FactorError::NonFinite { what: "rhs", index: 1 }));
}

/// A body nothing turns, on the dense backend: the dense LU's zero pivot is left to the sparse fallback,
/// whose suspects the solver names as a motion of the body (never an index).
#[test]
fn a_free_lever_on_the_dense_backend_is_named_with_its_free_motion() {
    use elastokin_core::{BodyRef, JointSpec, Model, Pose, Vec3};
    use elastokin_elements::CoilSpring;
    use elastokin_solver::{SolverOptions, StaticSolver};
    // A lever on a ball joint, a spring from its tip on along its own line: nothing holds its rotation
    // about that line.
    let mut m = Model::new();
    let lever = m.add_body("lever", Pose::at(Vec3::new(0.25, 0.0, 0.0))).unwrap();
    m.add_joint(JointSpec::spherical("ball", BodyRef::Ground, lever, Vec3::zeros())).unwrap();
    let spring = CoilSpring::new(
        "spring",
        BodyRef::Ground,
        Vec3::new(1.0, 0.0, 0.0),
        lever.into(),
        Vec3::new(0.5, 0.0, 0.0),
        1e4,
        0.4,
    );
    m.add_element(spring.unwrap()).unwrap();
    let options = SolverOptions { backend: BackendChoice::Dense, ..SolverOptions::default() };
    let message = match StaticSolver::new(&m, options) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("a free lever was accepted"),
    };
    let said =
        "'lever' is free to move (rotation about the axis (1.000, 0.000, 0.000) through (0.2500, 0.0000, 0.0000) m)";
    assert!(message.starts_with(said), "{message}");
}
