//! Tests of the sparse quasi-definite KKT factorization (`kkt_factor`) against
//! independent sources: the dense nalgebra reference (`dense_reference`:
//! equilibrated full-pivot LU, or SVD least squares for singular systems), and
//! closed-form / range-space solutions computed here with nalgebra.
//!
//! Sign convention of the KKT system: `[K Jᵀ; J 0] [x; y] = [a; b]`.

use elastokin_solver::dense_reference::{solve_dense_least_squares, solve_dense_pivoted};
use elastokin_solver::kkt::{FactorError, FactorKind, KktFactor, KktOptions, KktPattern};
use elastokin_solver::redundancy::{redundant_rows, try_redundant_rows};
use nalgebra::{DMatrix, DVector};

mod common;
use common::{all_finite, random_j, random_spd, random_vec, rel_err, to_sparse, Rng};

const KINDS: [FactorKind; 3] = [FactorKind::Auto, FactorKind::Simplicial, FactorKind::Supernodal];

fn opts(kind: FactorKind) -> KktOptions {
    KktOptions { kind, ..KktOptions::default() }
}

#[test]
fn random_spd_full_rank_matches_dense_reference() {
    let mut rng = Rng(0x1234_5678_9abc_def1);
    let mut worst = (0.0f64, 0.0f64);
    for &(n, m) in &[(30, 25), (60, 20), (48, 6), (12, 8)] {
        for _ in 0..3 {
            let k = random_spd(&mut rng, n, 0.05);
            let j = random_j(&mut rng, m, n, 4);
            let rhs = random_vec(&mut rng, n + m);
            let reference = solve_dense_pivoted(n, m, &k, &j, &rhs).expect("reference: nonsingular");
            let (p, kv, jv) = to_sparse(&k, &j);
            for kind in KINDS {
                let mut f = KktFactor::analyze(&p, opts(kind)).unwrap();
                let rep = f.factorize(&kv, &jv).unwrap();
                assert_eq!(rep.regularized_pivots, 0);
                assert_eq!(rep.negative_body_pivots, 0);
                assert!(rep.suspect_body_dofs.is_empty() && rep.suspect_constraint_rows.is_empty(), "{rep:?}");
                assert!(rep.min_body_pivot > 0.0 && rep.min_constraint_pivot > 0.0);
                let mut z = rhs.clone();
                let s = f.solve_in_place(&mut z).unwrap();
                assert!(s.converged, "{s:?}");
                let ex = rel_err(&z[..n], &reference[..n]);
                let ey = rel_err(&z[n..], &reference[n..]);
                worst = (worst.0.max(ex), worst.1.max(ey));
                assert!(ex < 1e-12 && ey < 1e-12, "n={n} m={m} {kind:?}: ex={ex:e} ey={ey:e}");
            }
        }
    }
    // Measured: worst relative error ≈ 1e-15 for both x and y.
    println!("random SPD: worst rel. error x {:.1e}, y {:.1e}", worst.0, worst.1);
}

/// Two springs k1, k2 tied by x0 − x1 = b, loads a0, a1 (k1 x0 + y = a0, k2 x1 − y = a1). Closed form,
/// written without cancellation: x0 = (a0 + a1 + k2 b)/(k1 + k2), x1 = (a0 + a1 − k1 b)/(k1 + k2),
/// y = (k2 a0 − k1 a1 − k1 k2 b)/(k1 + k2).
#[test]
fn closed_form_two_springs_one_constraint() {
    for &(k1, k2) in &[(1.0, 1.0), (1.0, 1e8), (1e8, 1.0), (3e-4, 7e5), (1e10, 1e10)] {
        for kind in KINDS {
            let p = KktPattern {
                n: 2,
                m: 1,
                k_col_ptr: vec![0, 1, 2],
                k_row_idx: vec![0, 1],
                j_col_ptr: vec![0, 1, 2],
                j_row_idx: vec![0, 0],
            };
            let (a0, a1, b) = (2.5, -1.25, 0.125);
            let s = k1 + k2;
            let exact = [(a0 + a1 + k2 * b) / s, (a0 + a1 - k1 * b) / s, (k2 * a0 - k1 * a1 - k1 * k2 * b) / s];
            let mut f = KktFactor::analyze(&p, opts(kind)).unwrap();
            f.factorize(&[k1, k2], &[1.0, -1.0]).unwrap();
            let mut z = vec![a0, a1, b];
            f.solve_in_place(&mut z).unwrap();
            for i in 0..3 {
                assert!(
                    (z[i] - exact[i]).abs() <= 1e-14 * exact[i].abs().max(1e-300),
                    "k=({k1},{k2}) {z:?} vs {exact:?}"
                );
            }
        }
    }
}

#[test]
fn pure_mechanism_with_square_jacobian() {
    // K = 0 (e.g. a linkage without compliance), J square and nonsingular:
    // x = J⁻¹ b and y = J⁻ᵀ a.
    let mut rng = Rng(0xabcdef);
    for &n in &[6usize, 30] {
        let k = DMatrix::<f64>::zeros(n, n);
        let mut j = random_j(&mut rng, n, n, 3);
        for i in 0..n {
            j[(i, i)] += 4.0; // keep it comfortably nonsingular
        }
        let rhs = random_vec(&mut rng, 2 * n);
        let reference = solve_dense_pivoted(n, n, &k, &j, &rhs).expect("nonsingular KKT");
        // Independent closed form through nalgebra LU of J alone.
        let lu = j.clone().lu();
        let x = lu.solve(&DVector::from_column_slice(&rhs[n..])).unwrap();
        let y = j.transpose().lu().solve(&DVector::from_column_slice(&rhs[..n])).unwrap();
        assert!(rel_err(&reference[..n], x.as_slice()) < 1e-13);
        assert!(rel_err(&reference[n..], y.as_slice()) < 1e-13);
        let (p, kv, jv) = to_sparse(&k, &j);
        for kind in KINDS {
            let mut f = KktFactor::analyze(&p, opts(kind)).unwrap();
            let rep = f.factorize(&kv, &jv).unwrap();
            assert!(rep.suspect_body_dofs.is_empty(), "{rep:?}");
            assert!(rep.suspect_constraint_rows.is_empty(), "{rep:?}");
            let mut z = rhs.clone();
            let s = f.solve_in_place(&mut z).unwrap();
            assert!(s.converged, "{s:?}");
            assert!(rel_err(&z[..n], x.as_slice()) < 1e-12, "{kind:?}");
            assert!(rel_err(&z[n..], y.as_slice()) < 1e-12, "{kind:?}");
        }
    }
}

/// Range-space solution for diagonal K (exact inverse):
/// y = (J K⁻¹ Jᵀ)⁻¹ (J K⁻¹ a − b), x = K⁻¹ (a − Jᵀ y).
fn range_space(kdiag: &[f64], j: &DMatrix<f64>, rhs: &[f64]) -> Vec<f64> {
    let n = kdiag.len();
    let kinv = DMatrix::from_diagonal(&DVector::from_iterator(n, kdiag.iter().map(|k| 1.0 / k)));
    let a = DVector::from_column_slice(&rhs[..n]);
    let b = DVector::from_column_slice(&rhs[n..]);
    let s = j * &kinv * j.transpose();
    let y = s.cholesky().expect("J K⁻¹ Jᵀ SPD").solve(&(j * &kinv * &a - b));
    let x = &kinv * (a - j.transpose() * &y);
    x.iter().chain(y.iter()).cloned().collect()
}

#[test]
fn stiffness_ratio_sweep() {
    // K = diag with entries geometrically spread over [1, ratio]; J with unit-scale rows (3–4 entries of
    // magnitude ≤ 2). Placement: which coordinates the constraints touch.
    //   Soft: the softest 20 of 40; Stiff: the stiffest 20; Mixed: every row couples a stiff and a soft dof.
    // Measured (this file, both kernels, ε = 1e-10): worst relative error of x and y against the dense
    // reference (equilibrated full-pivot LU + refinement) is 1.6e-15 over all ratios up to 1e8 and all
    // placements, with at most 2 refinement steps. Against the range-space formula it is 7.8e-13: that formula
    // itself loses digits (cond(J K⁻¹ Jᵀ) grows with the ratio), the two references agree to the same level.
    // Asserted with margin: 1e-13 against the dense reference, 1e-11 against the range-space formula.
    let mut rng = Rng(0x5eed_0001);
    let (n, m) = (40usize, 15usize);
    let mut worst_dense = 0.0f64;
    let mut worst_closed = 0.0f64;
    let mut max_steps = 0;
    for &ratio in &[1.0f64, 1e2, 1e4, 1e6, 1e8] {
        for placement in ["soft", "stiff", "mixed"] {
            // kdiag[i] increases with i.
            let kdiag: Vec<f64> = (0..n).map(|i| ratio.powf(i as f64 / (n - 1) as f64)).collect();
            let k = DMatrix::from_diagonal(&DVector::from_column_slice(&kdiag));
            let mut j = DMatrix::<f64>::zeros(m, n);
            for i in 0..m {
                let pick = |rng: &mut Rng, stiff: bool| if stiff { n - 20 + rng.below(20) } else { rng.below(20) };
                for t in 0..3 {
                    let stiff = match placement {
                        "soft" => false,
                        "stiff" => true,
                        _ => t % 2 == 0,
                    };
                    let c = pick(&mut rng, stiff);
                    j[(i, c)] = rng.uniform();
                }
                let c = match placement {
                    "soft" => i,
                    _ => n - 20 + i,
                };
                j[(i, c)] += 1.0;
            }
            let rhs = random_vec(&mut rng, n + m);
            let dense = solve_dense_pivoted(n, m, &k, &j, &rhs).expect("dense reference");
            let closed = range_space(&kdiag, &j, &rhs);
            let (p, kv, jv) = to_sparse(&k, &j);
            for kind in [FactorKind::Simplicial, FactorKind::Supernodal] {
                let mut f = KktFactor::analyze(&p, opts(kind)).unwrap();
                let rep = f.factorize(&kv, &jv).unwrap();
                assert!(rep.suspect_body_dofs.is_empty() && rep.suspect_constraint_rows.is_empty(), "{rep:?}");
                let mut z = rhs.clone();
                let s = f.solve_in_place(&mut z).unwrap();
                max_steps = max_steps.max(s.refinement_steps);
                let ed = rel_err(&z[n..], &dense[n..]).max(rel_err(&z[..n], &dense[..n]));
                let ec = rel_err(&z[n..], &closed[n..]).max(rel_err(&z[..n], &closed[..n]));
                worst_dense = worst_dense.max(ed);
                worst_closed = worst_closed.max(ec);
                assert!(s.converged, "ratio {ratio:e} {placement} {kind:?}: {s:?}");
                assert!(ed < 1e-13, "ratio {ratio:e} {placement} {kind:?}: vs dense {ed:e}");
                assert!(ec < 1e-11, "ratio {ratio:e} {placement} {kind:?}: vs range-space {ec:e}");
                assert!(s.refinement_steps <= 2, "{s:?}");
            }
        }
    }
    println!(
        "stiffness sweep: worst rel. error vs dense {worst_dense:.1e}, vs range-space {worst_closed:.1e}, \
         max refinement steps {max_steps}"
    );
}

#[test]
fn duplicated_constraint_row() {
    let mut rng = Rng(0xd0d0);
    let (n, m) = (30usize, 10usize);
    for trial in 0..4 {
        let k = random_spd(&mut rng, n, 0.1);
        let mut j = random_j(&mut rng, m, n, 3);
        // Row 7 duplicates row 2 (a redundant joint), the right-hand sides are consistent.
        let (first, dup) = (2usize, 7usize);
        for c in 0..n {
            j[(dup, c)] = j[(first, c)];
        }
        let mut rhs = random_vec(&mut rng, n + m);
        rhs[n + dup] = rhs[n + first];
        // Reference: the same system without the duplicate row.
        let j_red = j.clone().remove_row(dup);
        let mut rhs_red = rhs.clone();
        rhs_red.remove(n + dup);
        let reference = solve_dense_pivoted(n, m - 1, &k, &j_red, &rhs_red).expect("reduced KKT nonsingular");
        assert!(solve_dense_pivoted(n, m, &k, &j, &rhs).is_none(), "full KKT is singular");
        let y_single = reference[n + first];

        let (p, kv, jv) = to_sparse(&k, &j);
        assert_eq!(redundant_rows(m, n, &p.j_col_ptr, &p.j_row_idx, &jv, 1e-8), vec![dup]);
        for kind in KINDS {
            let mut f = KktFactor::analyze(&p, opts(kind)).unwrap();
            let rep = f.factorize(&kv, &jv).unwrap();
            assert_eq!(rep.suspect_constraint_rows, vec![dup], "trial {trial} {kind:?}: {rep:?}");
            assert!(rep.suspect_body_dofs.is_empty());
            let mut z = rhs.clone();
            let s = f.solve_in_place(&mut z).unwrap();
            assert!(all_finite(&z));
            assert!(s.converged, "{s:?}");
            assert!(rel_err(&z[..n], &reference[..n]) < 1e-12, "x");
            // J x = b, including the duplicated row.
            let jx = &j * DVector::from_column_slice(&z[..n]);
            for i in 0..m {
                assert!((jx[i] - rhs[n + i]).abs() < 1e-13, "row {i}");
            }
            assert!(s.residual_y < 1e-13 && s.residual_x < 1e-13, "{s:?}");
            // The pair carries the single-row multiplier between them; the ε regularization splits it evenly.
            let scale = reference[n..].iter().fold(0.0f64, |a, v| a.max(v.abs()));
            assert!((z[n + first] + z[n + dup] - y_single).abs() < 1e-12 * scale);
            assert!((z[n + first] - z[n + dup]).abs() < 1e-6 * scale);
            // Other multipliers are unique.
            for i in (0..m).filter(|&i| i != first && i != dup) {
                let r = if i < dup { i } else { i - 1 };
                assert!((z[n + i] - reference[n + r]).abs() < 1e-12 * scale);
            }
            // The minimum-norm least-squares reference agrees on the whole vector.
            let lsq = solve_dense_least_squares(n, m, &k, &j, &rhs, 1e-12).unwrap();
            assert!(rel_err(&z, &lsq) < 1e-6, "{}", rel_err(&z, &lsq));
        }
    }
}

#[test]
fn unrestrained_body_dof_is_reported_without_nan() {
    let mut rng = Rng(0xf4ee);
    let (n, m) = (20usize, 6usize);
    let free = 5usize;
    let mut k = random_spd(&mut rng, n, 0.1);
    let mut j = random_j(&mut rng, m, n, 3);
    for c in 0..n {
        k[(free, c)] = 0.0;
        k[(c, free)] = 0.0;
    }
    for r in 0..m {
        j[(r, free)] = 0.0;
    }
    let mut rhs = random_vec(&mut rng, n + m);
    rhs[free] = 0.0; // consistent: no load on the free coordinate
    let reference = solve_dense_least_squares(n, m, &k, &j, &rhs, 1e-12).unwrap();
    assert!(solve_dense_pivoted(n, m, &k, &j, &rhs).is_none(), "singular: dense reference says None");
    let (p, kv, jv) = to_sparse(&k, &j);
    for kind in KINDS {
        let mut f = KktFactor::analyze(&p, opts(kind)).unwrap();
        let rep = f.factorize(&kv, &jv).unwrap();
        assert_eq!(rep.suspect_body_dofs, vec![free], "{kind:?}: {rep:?}");
        assert!(rep.suspect_constraint_rows.is_empty());
        assert_eq!(rep.regularized_pivots, 1);
        let mut z = rhs.clone();
        let s = f.solve_in_place(&mut z).unwrap();
        assert!(all_finite(&z));
        assert_eq!(z[free], 0.0);
        assert!(rel_err(&z, &reference) < 1e-12, "{kind:?}");
        assert!(s.converged);
        // A load on the free coordinate cannot be carried: still no NaN, the residual says so.
        let mut z = rhs.clone();
        z[free] = 1.0;
        let s = f.solve_in_place(&mut z).unwrap();
        assert!(all_finite(&z));
        assert!(!s.converged && (s.residual_x - 1.0).abs() < 1e-12, "{s:?}");
    }
    // A floating pair: two dofs joined only by a spring (rank-one 2×2 block) — one of them is reported.
    let mut k2 = random_spd(&mut rng, n, 0.1);
    let j2 = DMatrix::<f64>::zeros(0, n);
    for c in 0..n {
        for r in [3usize, 11] {
            k2[(r, c)] = 0.0;
            k2[(c, r)] = 0.0;
        }
    }
    k2[(3, 3)] = 5.0;
    k2[(11, 11)] = 5.0;
    k2[(3, 11)] = -5.0;
    k2[(11, 3)] = -5.0;
    let (p, kv, jv) = to_sparse(&k2, &j2);
    let mut f = KktFactor::analyze(&p, KktOptions::default()).unwrap();
    let rep = f.factorize(&kv, &jv).unwrap();
    assert_eq!(rep.suspect_body_dofs.len(), 1, "{rep:?}");
    assert!([3, 11].contains(&rep.suspect_body_dofs[0]));
}

#[test]
fn indefinite_stiffness_on_the_constraint_manifold() {
    // K = SPD − shift·I is indefinite on {Jx = 0} for the larger shifts (an unstable equilibrium, past a limit
    // point). The KKT matrix is still nonsingular and must be solved; the negative pivots are counted.
    // With KktOptions::signed_regularization = true, faer overwrites these negative body pivots by +δ, which
    // ruins the factor (measured: `Singular` or a non-finite solution) — the reason it is off by default.
    let mut rng = Rng(0x1de7);
    let (n, m) = (20usize, 8usize);
    let k0 = random_spd(&mut rng, n, 0.0);
    let j = random_j(&mut rng, m, n, 3);
    let mut saw_negative = false;
    let mut signed_failures = 0usize;
    for &shift in &[0.0, 0.5, 2.0, 5.0] {
        let k = &k0 - DMatrix::<f64>::identity(n, n) * shift;
        let rhs = random_vec(&mut rng, n + m);
        let Some(reference) = solve_dense_pivoted(n, m, &k, &j, &rhs) else { continue };
        let (p, kv, jv) = to_sparse(&k, &j);
        for kind in KINDS {
            let mut f = KktFactor::analyze(&p, opts(kind)).unwrap();
            let rep = f.factorize(&kv, &jv).unwrap();
            saw_negative |= rep.negative_body_pivots > 0;
            if shift == 0.0 {
                assert_eq!(rep.negative_body_pivots, 0);
            }
            let mut z = rhs.clone();
            let s = f.solve_in_place(&mut z).unwrap();
            assert!(s.converged, "{s:?}");
            assert!(rel_err(&z, &reference) < 1e-12, "shift {shift} {kind:?}: {}", rel_err(&z, &reference));
            if rep.negative_body_pivots > 0 {
                let signed = KktOptions { signed_regularization: true, ..opts(kind) };
                let mut g = KktFactor::analyze(&p, signed).unwrap();
                let mut z = rhs.clone();
                let ok =
                    g.factorize(&kv, &jv).is_ok() && g.solve_in_place(&mut z).is_ok() && rel_err(&z, &reference) < 1e-6;
                signed_failures += usize::from(!ok);
            }
        }
    }
    assert!(saw_negative);
    assert!(signed_failures > 0);
}

#[test]
fn refactorize_many_times_reuses_the_analysis() {
    let mut rng = Rng(0xc0c0);
    let (n, m) = (30usize, 25usize);
    let k0 = random_spd(&mut rng, n, 0.1);
    let j0 = random_j(&mut rng, m, n, 4);
    let (p, kv0, jv0) = to_sparse(&k0, &j0);
    let mut f = KktFactor::analyze(&p, KktOptions::default()).unwrap();
    let steps = 40u64;
    let mut refinements = 0u64;
    for step in 0..steps {
        // New values on the same pattern: scale the stiffness by up to 1e3, perturb J.
        let t = step as f64 / steps as f64;
        let kscale = 1e3f64.powf(t);
        let kv: Vec<f64> = kv0.iter().map(|v| v * kscale).collect();
        let jv: Vec<f64> = jv0.iter().map(|v| v * (1.0 + 0.3 * rng.uniform())).collect();
        f.factorize(&kv, &jv).unwrap();
        let rhs = random_vec(&mut rng, n + m);
        let mut z = rhs.clone();
        refinements += f.solve_in_place(&mut z).unwrap().refinement_steps as u64;
        if step % 8 == 0 {
            // Dense check of a sample of the steps.
            let mut k = DMatrix::<f64>::zeros(n, n);
            let mut j = DMatrix::<f64>::zeros(m, n);
            for c in 0..n {
                for e in p.k_col_ptr[c]..p.k_col_ptr[c + 1] {
                    k[(p.k_row_idx[e], c)] = kv[e];
                    k[(c, p.k_row_idx[e])] = kv[e];
                }
                for e in p.j_col_ptr[c]..p.j_col_ptr[c + 1] {
                    j[(p.j_row_idx[e], c)] = jv[e];
                }
            }
            let reference = solve_dense_pivoted(n, m, &k, &j, &rhs).unwrap();
            assert!(rel_err(&z, &reference) < 1e-12);
        }
    }
    let c = f.counters();
    assert_eq!(c.symbolic_analyses, 1);
    assert_eq!(c.numeric_factorizations, steps);
    assert_eq!(c.solves, steps);
    assert_eq!(c.refinement_steps, refinements);
    assert!(c.refinement_steps >= steps, "at least one refinement step per solve: {c:?}");
}

#[test]
fn non_finite_input_is_a_typed_error() {
    let mut rng = Rng(0xbad);
    let (n, m) = (8usize, 3usize);
    let k = random_spd(&mut rng, n, 0.1);
    let j = random_j(&mut rng, m, n, 2);
    let (p, kv, jv) = to_sparse(&k, &j);
    let mut f = KktFactor::analyze(&p, KktOptions::default()).unwrap();

    let mut z = vec![1.0; n + m];
    assert_eq!(f.solve_in_place(&mut z), Err(FactorError::NotFactorized));

    let mut bad = kv.clone();
    bad[3] = f64::NAN;
    assert_eq!(f.factorize(&bad, &jv), Err(FactorError::NonFinite { what: "k_values", index: 3 }));
    let mut bad = jv.clone();
    bad[1] = f64::INFINITY;
    assert_eq!(f.factorize(&kv, &bad), Err(FactorError::NonFinite { what: "j_values", index: 1 }));
    assert_eq!(f.solve_in_place(&mut z), Err(FactorError::NotFactorized), "failed factorize invalidates");
    assert_eq!(
        f.factorize(&kv[1..], &jv),
        Err(FactorError::PatternMismatch { what: "k_values", expected: kv.len(), got: kv.len() - 1 })
    );

    f.factorize(&kv, &jv).unwrap();
    let mut z = vec![1.0; n + m];
    z[n + 1] = f64::NEG_INFINITY;
    let before = z.clone();
    assert_eq!(f.solve_in_place(&mut z), Err(FactorError::NonFinite { what: "rhs", index: n + 1 }));
    assert_eq!(z[..n], before[..n], "rhs untouched on error");
    let mut short = vec![1.0; n];
    assert!(matches!(f.solve_in_place(&mut short), Err(FactorError::PatternMismatch { what: "rhs", .. })));

    let e = f.factorize(&[f64::NAN; 1].repeat(kv.len()), &jv).unwrap_err();
    assert!(e.to_string().contains("k_values[0]"), "{e}");
    assert_eq!(
        try_redundant_rows(m, n, &p.j_col_ptr, &p.j_row_idx, &[f64::NAN].repeat(jv.len()), 1e-8),
        Err(FactorError::NonFinite { what: "j_values", index: 0 })
    );
    assert!(redundant_rows(m, n, &p.j_col_ptr, &p.j_row_idx, &[f64::NAN].repeat(jv.len()), 1e-8).is_empty());
}

#[test]
fn malformed_patterns_are_typed_errors() {
    let good = KktPattern {
        n: 3,
        m: 2,
        k_col_ptr: vec![0, 1, 3, 5],
        k_row_idx: vec![0, 0, 1, 1, 2],
        j_col_ptr: vec![0, 1, 2, 3],
        j_row_idx: vec![0, 1, 0],
    };
    assert!(KktFactor::analyze(&good, KktOptions::default()).is_ok());
    let check = |p: KktPattern| KktFactor::analyze(&p, KktOptions::default()).unwrap_err();

    // Missing diagonal in column 2.
    let e = check(KktPattern { k_col_ptr: vec![0, 1, 3, 4], k_row_idx: vec![0, 0, 1, 1], ..good.clone() });
    assert_eq!(e, FactorError::MissingDiagonal { col: 2 });
    // Entry below the diagonal (row 2 in column 1).
    let e = check(KktPattern { k_row_idx: vec![0, 0, 2, 1, 2], ..good.clone() });
    assert!(matches!(e, FactorError::InvalidPattern { matrix: "K", col: 1, .. }), "{e:?}");
    // Unsorted rows.
    let e = check(KktPattern { k_row_idx: vec![0, 1, 0, 1, 2], ..good.clone() });
    assert!(matches!(e, FactorError::InvalidPattern { matrix: "K", col: 1, .. }), "{e:?}");
    // Wrong pointer length / end / decreasing.
    assert!(matches!(
        check(KktPattern { k_col_ptr: vec![0, 1, 3], ..good.clone() }),
        FactorError::InvalidPattern { .. }
    ));
    assert!(matches!(
        check(KktPattern { k_col_ptr: vec![0, 1, 3, 9], ..good.clone() }),
        FactorError::InvalidPattern { .. }
    ));
    assert!(matches!(
        check(KktPattern { k_col_ptr: vec![1, 1, 3, 5], ..good.clone() }),
        FactorError::InvalidPattern { .. }
    ));
    assert!(matches!(
        check(KktPattern { j_col_ptr: vec![0, 2, 1, 3], ..good.clone() }),
        FactorError::InvalidPattern { .. }
    ));
    // J row out of range.
    let e = check(KktPattern { j_row_idx: vec![0, 2, 0], ..good.clone() });
    assert!(matches!(e, FactorError::InvalidPattern { matrix: "J", col: 1, .. }), "{e:?}");
    // Absurd m with an empty J: an error, not an abort.
    let e = check(KktPattern { m: usize::MAX / 2, j_col_ptr: vec![0, 0, 0, 0], j_row_idx: vec![], ..good.clone() });
    assert_eq!(e, FactorError::OutOfMemory);
    // Bad options.
    let e = KktFactor::analyze(&good, KktOptions { epsilon: -1.0, ..KktOptions::default() }).unwrap_err();
    assert!(matches!(e, FactorError::InvalidOption { name: "epsilon", .. }));
    // The messages tell how to fix the input.
    assert!(FactorError::MissingDiagonal { col: 2 }.to_string().contains("explicit 0.0"));
}

#[test]
fn empty_and_unconstrained_systems() {
    let empty = KktPattern { n: 0, m: 0, k_col_ptr: vec![0], k_row_idx: vec![], j_col_ptr: vec![0], j_row_idx: vec![] };
    let mut f = KktFactor::analyze(&empty, KktOptions::default()).unwrap();
    f.factorize(&[], &[]).unwrap();
    let s = f.solve_in_place(&mut []).unwrap();
    assert!(s.converged);

    // m = 0: plain SPD solve.
    let mut rng = Rng(7);
    let n = 15;
    let k = random_spd(&mut rng, n, 0.1);
    let j = DMatrix::<f64>::zeros(0, n);
    let rhs = random_vec(&mut rng, n);
    let reference = k.clone().lu().solve(&DVector::from_column_slice(&rhs)).unwrap();
    let (p, kv, jv) = to_sparse(&k, &j);
    let mut f = KktFactor::analyze(&p, KktOptions::default()).unwrap();
    f.factorize(&kv, &jv).unwrap();
    let mut z = rhs.clone();
    f.solve_in_place(&mut z).unwrap();
    assert!(rel_err(&z, reference.as_slice()) < 1e-13);
}

#[test]
fn redundant_rows_reports_rows_dependent_on_earlier_rows() {
    let mut rng = Rng(0x4ed);
    let n = 60usize;
    // Independent rows: nothing reported.
    let j = random_j(&mut rng, 20, n, 3);
    let (p, _, jv) = to_sparse(&DMatrix::zeros(n, n), &j);
    assert!(redundant_rows(20, n, &p.j_col_ptr, &p.j_row_idx, &jv, 1e-8).is_empty());

    // Duplicates (scaled copies) at many positions: always the later one, whatever the AMD order is.
    for trial in 0..30 {
        let m = 40usize;
        let mut j = random_j(&mut rng, m, n, 3);
        let a = rng.below(m);
        let mut b = rng.below(m);
        while b == a {
            b = rng.below(m);
        }
        let (first, later) = (a.min(b), a.max(b));
        let factor = if trial % 2 == 0 { -3.0 } else { 1e-3 };
        for c in 0..n {
            j[(later, c)] = factor * j[(first, c)];
        }
        let (p, _, jv) = to_sparse(&DMatrix::zeros(n, n), &j);
        assert_eq!(redundant_rows(m, n, &p.j_col_ptr, &p.j_row_idx, &jv, 1e-8), vec![later], "trial {trial}");
        // The earlier copy is what is reported when it comes later in the numbering.
        let mut swapped = j.clone();
        swapped.swap_rows(first, later);
        let (p, _, jv) = to_sparse(&DMatrix::zeros(n, n), &swapped);
        assert_eq!(redundant_rows(m, n, &p.j_col_ptr, &p.j_row_idx, &jv, 1e-8), vec![later], "trial {trial}");
    }

    // A combination: row 9 = row 1 + 2·row 4 (a closed loop); row 12 is all zero; row 15 duplicates row 9.
    let m = 16usize;
    let mut j = random_j(&mut rng, m, n, 3);
    for c in 0..n {
        j[(9, c)] = j[(1, c)] + 2.0 * j[(4, c)];
        j[(12, c)] = 0.0;
    }
    for c in 0..n {
        j[(15, c)] = j[(9, c)];
    }
    let (p, _, jv) = to_sparse(&DMatrix::zeros(n, n), &j);
    assert_eq!(redundant_rows(m, n, &p.j_col_ptr, &p.j_row_idx, &jv, 1e-8), vec![9, 12, 15]);

    // Nearly dependent: a perturbation of 1e-4 relative is independent at tol 1e-6, dependent at tol 1e-3.
    let mut j = random_j(&mut rng, 10, n, 3);
    for c in 0..n {
        j[(6, c)] = j[(2, c)];
    }
    j[(6, 0)] += 1e-4 * j.row(2).norm();
    let (p, _, jv) = to_sparse(&DMatrix::zeros(n, n), &j);
    assert!(redundant_rows(10, n, &p.j_col_ptr, &p.j_row_idx, &jv, 1e-6).is_empty());
    assert_eq!(redundant_rows(10, n, &p.j_col_ptr, &p.j_row_idx, &jv, 1e-3), vec![6]);
}

/// Large-scale timing (not run by default): a chain of `bodies` bodies with 6 dofs each, every body tied to the
/// next by a 5-row joint and a bushing, and grounded at both ends.
/// `cargo test --release -p elastokin-solver --test kkt_factor -- --ignored large_chain --nocapture`
#[test]
#[ignore]
fn large_chain_timing() {
    let bodies = 10_000usize;
    let n = 6 * bodies;
    let mut rng = Rng(99);
    // K: per body a dense 6×6 SPD block plus bushing coupling to the next body (upper triangle, CSC).
    let mut cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
    for b in 0..bodies {
        for c in 0..6 {
            for r in 0..=c {
                let v = if r == c { 10.0 + rng.uniform().abs() } else { 0.1 * rng.uniform() };
                cols[6 * b + c].push((6 * b + r, v));
            }
        }
        if b + 1 < bodies {
            for c in 0..6 {
                for r in 0..6 {
                    cols[6 * (b + 1) + c].push((6 * b + r, if r == c { -1.0 } else { 0.0 }));
                }
            }
        }
    }
    let mut p = KktPattern { n, m: 0, k_col_ptr: vec![0], j_col_ptr: vec![0], ..KktPattern::default() };
    let mut kv = Vec::new();
    for col in cols.iter_mut() {
        col.sort_by_key(|e| e.0);
        for &(r, v) in col.iter() {
            p.k_row_idx.push(r);
            kv.push(v);
        }
        p.k_col_ptr.push(p.k_row_idx.len());
    }
    // J: joint i (between body i and i+1) has 5 rows touching 12 dofs.
    let m = 5 * (bodies - 1);
    let mut jcols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
    for i in 0..bodies - 1 {
        for r in 0..5 {
            for d in 0..6 {
                jcols[6 * i + d].push((5 * i + r, rng.uniform()));
                jcols[6 * (i + 1) + d].push((5 * i + r, rng.uniform()));
            }
        }
    }
    let mut jv = Vec::new();
    for col in jcols.iter_mut() {
        col.sort_by_key(|e| e.0);
        for &(r, v) in col.iter() {
            p.j_row_idx.push(r);
            jv.push(v);
        }
        p.j_col_ptr.push(p.j_row_idx.len());
    }
    p.m = m;
    let t = std::time::Instant::now();
    let mut f = KktFactor::analyze(&p, KktOptions::default()).unwrap();
    let ta = t.elapsed();
    let t = std::time::Instant::now();
    let rep = f.factorize(&kv, &jv).unwrap();
    let tf = t.elapsed();
    let rhs = random_vec(&mut rng, n + m);
    let mut z = rhs.clone();
    let t = std::time::Instant::now();
    let s = f.solve_in_place(&mut z).unwrap();
    let ts = t.elapsed();
    let t = std::time::Instant::now();
    let rr = redundant_rows(m, n, &p.j_col_ptr, &p.j_row_idx, &jv, 1e-8);
    let tr = t.elapsed();
    println!(
        "n={n} m={m}: analyze {ta:?}, factorize {tf:?}, solve {ts:?} ({} steps, backward error {:.1e}), \
         redundant_rows {tr:?} ({} rows); factor nnz {}; {f:?}; suspects {} / {}",
        s.refinement_steps,
        s.backward_error,
        rr.len(),
        f.factor_nnz(),
        rep.suspect_body_dofs.len(),
        rep.suspect_constraint_rows.len()
    );
    assert!(all_finite(&z));
}

#[test]
fn random_garbage_never_panics_and_never_yields_nan() {
    let mut rng = Rng(0x09a4_ba9e);
    for trial in 0..400 {
        let n = rng.below(7);
        let m = rng.below(6);
        // Random CSC arrays, sometimes valid, often not.
        let gen = |rows: usize, upper: bool, rng: &mut Rng| -> (Vec<usize>, Vec<usize>) {
            let mut ptr = vec![0usize];
            let mut idx = Vec::new();
            for c in 0..n {
                let lim = if upper { c + 1 } else { rows.max(1) };
                for r in 0..lim {
                    if (upper && r == c && rng.below(10) > 0) || rng.below(3) == 0 {
                        idx.push(r);
                    }
                }
                ptr.push(idx.len());
            }
            match rng.below(8) {
                0 if !idx.is_empty() => {
                    let k = rng.below(idx.len());
                    idx[k] = rng.below(rows + 2);
                }
                1 if !ptr.is_empty() => {
                    let k = rng.below(ptr.len());
                    ptr[k] = rng.below(idx.len() + 2);
                }
                2 => {
                    ptr.pop();
                }
                _ => {}
            }
            (ptr, idx)
        };
        let (k_col_ptr, k_row_idx) = gen(n, true, &mut rng);
        let (j_col_ptr, j_row_idx) = gen(m, false, &mut rng);
        let p = KktPattern { n, m, k_col_ptr, k_row_idx, j_col_ptr, j_row_idx };
        let _ = try_redundant_rows(m, n, &p.j_col_ptr, &p.j_row_idx, &vec![1.0; p.j_row_idx.len()], 1e-8);
        let Ok(mut f) = KktFactor::analyze(&p, opts(KINDS[trial % 3])) else { continue };
        for _ in 0..3 {
            // Values: random, zero, huge, tiny — all finite.
            let val = |rng: &mut Rng| match rng.below(6) {
                0 => 0.0,
                1 => 1e150 * rng.uniform(),
                2 => 1e-150 * rng.uniform(),
                _ => rng.uniform(),
            };
            let kv: Vec<f64> = (0..p.k_row_idx.len()).map(|_| val(&mut rng)).collect();
            let jv: Vec<f64> = (0..p.j_row_idx.len()).map(|_| val(&mut rng)).collect();
            let rr = redundant_rows(m, n, &p.j_col_ptr, &p.j_row_idx, &jv, 1e-8);
            assert!(rr.iter().all(|&r| r < m));
            let rep = match f.factorize(&kv, &jv) {
                Ok(rep) => rep,
                Err(e) => {
                    assert!(matches!(e, FactorError::Singular { .. }), "{e:?}");
                    continue;
                }
            };
            for v in
                [rep.rho, rep.min_body_pivot, rep.max_body_pivot, rep.min_constraint_pivot, rep.max_constraint_pivot]
            {
                assert!(v.is_finite(), "{rep:?}");
            }
            let rhs = random_vec(&mut rng, n + m);
            let mut z = rhs.clone();
            match f.solve_in_place(&mut z) {
                Ok(s) => {
                    assert!(all_finite(&z), "trial {trial}");
                    assert!(!s.backward_error.is_nan() && !s.residual_x.is_nan() && !s.residual_y.is_nan());
                }
                Err(e) => {
                    assert!(matches!(e, FactorError::NonFiniteSolution { .. }), "{e:?}");
                    assert_eq!(z, rhs, "rhs untouched on error");
                }
            }
        }
    }
}

/// Threads of a batch share one symbolic analysis: two numeric factors made from one `Arc<KktSymbolic>`
/// and used on two threads at once give, value set for value set, the results of factors analysed each
/// on their own, to the bit; the shared analysis is counted once, by whoever made it.
#[test]
fn factors_sharing_one_symbolic_analysis_give_separately_analysed_results_to_the_bit() {
    use elastokin_solver::kkt::KktSymbolic;
    use std::sync::Arc;
    let mut rng = Rng(0x5a4ed);
    let (n, m) = (48usize, 18usize);
    let k = random_spd(&mut rng, n, 0.2);
    let j = random_j(&mut rng, m, n, 3);
    let (p, kv, jv) = to_sparse(&k, &j);
    let rhs = random_vec(&mut rng, n + m);
    for kind in [FactorKind::Simplicial, FactorKind::Supernodal] {
        // Two value sets along a path: the second stiffer.
        let sets: Vec<Vec<f64>> = (0..2).map(|s| kv.iter().map(|v| v * (1.0 + s as f64)).collect()).collect();
        let alone: Vec<Vec<f64>> = sets
            .iter()
            .map(|values| {
                let mut f = KktFactor::analyze(&p, opts(kind)).unwrap();
                f.factorize(values, &jv).unwrap();
                let mut z = rhs.clone();
                f.solve_in_place(&mut z).unwrap();
                z
            })
            .collect();
        let shared = KktSymbolic::analyze(&p, opts(kind)).unwrap();
        let together: Vec<Vec<f64>> = std::thread::scope(|scope| {
            let tasks: Vec<_> = sets
                .iter()
                .map(|values| {
                    let sym = Arc::clone(&shared);
                    let (jv, rhs) = (&jv, &rhs);
                    scope.spawn(move || {
                        let mut f = KktFactor::from_symbolic(sym).unwrap();
                        assert_eq!(f.counters().symbolic_analyses, 0);
                        f.factorize(values, jv).unwrap();
                        let mut z = rhs.clone();
                        f.solve_in_place(&mut z).unwrap();
                        z
                    })
                })
                .collect();
            tasks.into_iter().map(|t| t.join().unwrap()).collect()
        });
        assert_eq!(together, alone, "{kind:?}");
        assert_eq!(Arc::strong_count(&shared), 1, "the threads' factors are gone, their shares with them");
    }
}
