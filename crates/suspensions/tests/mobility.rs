//! Mobility at design by the sparse factorizations (`elastokin_solver::mobility`) against a dense
//! reference written here: the rank and null space of the joints' Jacobian by a singular value
//! decomposition, the reduced stiffness `ZᵀKZ` and its eigenvalues. On every shipped model (whose few
//! coordinates take the dense read-out of the reduced compliance) and on chains of bodies on bushings long
//! enough for the Lanczos iteration, with a guard that the chain's motions are real (it has many, each
//! held by the bushings).

use elastokin_core::{BodyId, BodyRef, JointSpec, Mat3, Model, Pose, Vec3, BODY_DOFS};
use elastokin_elements::{Bushing, Characteristic, CoilSpring, SpringLength};
use elastokin_solver::assembly::{Assembly, Tangent};
use elastokin_solver::mobility::{self, DENSE_CONDITION_MAX};
use elastokin_suspensions::assembly::mobility::holds_point;
use elastokin_suspensions::{Rig, Side, SuspensionFile};
use nalgebra::{DMatrix, SymmetricEigen};
use std::path::Path;

const TOLERANCE: f64 = 1e-9;

/// The sparse condition of `model`, its redundant rows found first as the check finds them.
fn condition(model: &Model) -> Option<f64> {
    mobility::reduced_condition(model, &mobility::mobility(model, TOLERANCE)).unwrap()
}

/// `J` (all rows) and the symmetric part of the elastic `K` at design, dense.
fn dense_at_design(model: &Model) -> (DMatrix<f64>, DMatrix<f64>) {
    let mut a = Assembly::new(model, (0..model.constraint_rows()).collect());
    let lambda = vec![0.0; a.m()];
    a.assemble(model, &model.design_poses(), 0.0, &lambda, Some(Tangent::Elastic));
    let n = a.n;
    let (mut j, mut k) = (DMatrix::zeros(a.m(), n), DMatrix::zeros(n, n));
    for c in 0..n {
        for p in a.j_col_ptr[c]..a.j_col_ptr[c + 1] {
            j[(a.j_row_idx[p], c)] = a.j_values[p];
        }
        for p in a.k_col_ptr[c]..a.k_col_ptr[c + 1] {
            let r = a.k_row_idx[p];
            k[(r, c)] = a.k_values[p];
            k[(c, r)] = a.k_values[p];
        }
    }
    (j, k)
}

/// The singular values of `J` over the largest below which a row counts as repeating others.
const DENSE_RANK_TOLERANCE: f64 = 1e-9;

/// The rank of `J` and an orthonormal basis of its null space, by SVD.
fn dense_null_space(j: &DMatrix<f64>, n: usize) -> (usize, DMatrix<f64>) {
    let mut square = DMatrix::zeros(n.max(j.nrows()), n);
    square.rows_mut(0, j.nrows()).copy_from(j);
    let svd = square.svd(false, true);
    let v_t = svd.v_t.unwrap();
    let largest = svd.singular_values.max().max(f64::MIN_POSITIVE);
    let free: Vec<usize> = (0..n).filter(|&i| svd.singular_values[i] <= DENSE_RANK_TOLERANCE * largest).collect();
    let mut z = DMatrix::zeros(n, free.len());
    for (col, &i) in free.iter().enumerate() {
        z.set_column(col, &v_t.row(i).transpose());
    }
    (n - free.len(), z)
}

/// The dense condition: the largest diagonal entry of `K` over the smallest eigenvalue of `ZᵀKZ`.
fn dense_condition(model: &Model) -> Option<f64> {
    let (j, k) = dense_at_design(model);
    let (_, z) = dense_null_space(&j, model.dofs());
    if z.ncols() == 0 {
        return None;
    }
    let softest =
        SymmetricEigen::new(z.transpose() * &k * &z).eigenvalues.iter().map(|v| v.abs()).fold(f64::MAX, f64::min);
    Some(k.diagonal().max() / softest)
}

/// Every model file shipped under `examples/` (its `targets/` hold design files), by path, read.
fn shipped() -> Vec<(String, SuspensionFile)> {
    fn walk(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() && !path.ends_with("targets") {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "json") {
                out.push(path);
            }
        }
    }
    let mut paths = Vec::new();
    walk(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples"), &mut paths);
    paths.sort();
    let models: Vec<(String, SuspensionFile)> =
        paths.iter().filter_map(|p| Some((p.display().to_string(), SuspensionFile::read(p).ok()?))).collect();
    assert!(models.len() >= 10, "the shipped models: {paths:?}");
    models
}

/// Relative agreement of the sparse condition with the dense one. Measured at most 3.6e-11 on the shipped
/// models (the dense read-out of the reduced compliance) and 5.1e-15 on the chains (Lanczos, stopped when its
/// largest Ritz value moves by less than 1e-10 of itself over ten steps).
const CONDITION_AGREEMENT: f64 = 1e-9;

fn agree(name: &str, sparse: Option<f64>, dense: Option<f64>) -> f64 {
    match (sparse, dense) {
        (Some(s), Some(d)) => {
            let off = (s - d).abs() / d;
            assert!(off <= CONDITION_AGREEMENT, "{name}: sparse {s:e} against dense {d:e} ({off:.1e} apart)");
            off
        }
        (s, d) => {
            assert_eq!(s, d, "{name}: whether the joints leave a motion");
            0.0
        }
    }
}

#[test]
fn mobility_and_condition_of_every_shipped_model_are_those_of_a_dense_svd() {
    let mut worst: f64 = 0.0;
    for (name, file) in shipped() {
        for rig in [Rig::Free, Rig::WheelTravel] {
            let Ok(corner) = file.suspension.build(Side::Left, rig) else { continue };
            let model = &corner.model;
            assert!(model.dofs() <= DENSE_CONDITION_MAX, "{name}: a shipped corner takes the dense read-out");
            let (j, _) = dense_at_design(model);
            let (rank, _) = dense_null_space(&j, model.dofs());
            let found = mobility::mobility(model, TOLERANCE);
            assert_eq!(found.degrees_of_freedom, model.dofs() - rank, "{name} {rig:?}");
            assert_eq!(found.redundant_rows.len(), model.constraint_rows() - rank, "{name} {rig:?}");
            let sparse = condition(model);
            worst = worst.max(agree(&name, sparse, dense_condition(model)));
        }
    }
    println!("worst relative difference of the shipped models' conditions: {worst:.1e}");
}

/// A chain of `cells` arms, each on a bushing to the ground (but those `bushed` leaves out), tied to the one
/// before by a ball joint and a link, with a coil spring between them (the bench's scaling chain, in
/// `xtask/src/bench/scaling.rs`).
fn chain(cells: usize, turning: f64, bushed: impl Fn(usize) -> bool) -> Model {
    let mut m = Model::new();
    let mut previous = BodyRef::Ground;
    for i in 0..cells {
        let x = 0.4 * (i as f64 + 1.0);
        let body = m.add_body(&format!("arm {i}"), Pose::at(Vec3::new(x, 0.0, 0.0))).unwrap();
        if bushed(i) {
            let (rates, turning) = (Vec3::new(1.0e6, 5.0e5, 5.0e5), turning * Vec3::new(1.0, 5.0, 5.0));
            let mount = Vec3::new(x, -0.15, 0.0);
            let bushing = Bushing::new(
                &format!("mount {i}"),
                BodyRef::Ground,
                body.into(),
                mount,
                Mat3::identity(),
                rates,
                turning,
            );
            m.add_element(bushing.unwrap()).unwrap();
        }
        let joint = x - 0.2;
        m.add_joint(JointSpec::spherical(&format!("ball {i}"), previous, body, Vec3::new(joint, 0.0, 0.0))).unwrap();
        let (a, b) = (Vec3::new(joint - 0.1, 0.15, 0.0), Vec3::new(joint + 0.1, 0.15, 0.08));
        m.add_joint(JointSpec::distance(&format!("link {i}"), previous, body, a, b)).unwrap();
        let (top, seat) = (Vec3::new(joint - 0.1, -0.1, 0.2), Vec3::new(x, -0.1, 0.0));
        let spring = CoilSpring::seated(
            &format!("spring {i}"),
            [(previous, top), (body.into(), seat)],
            Characteristic::Rate(3.0e4),
            SpringLength::DesignForce(500.0),
        );
        m.add_element(spring.unwrap()).unwrap();
        previous = body.into();
    }
    m
}

#[test]
fn a_chain_long_enough_for_lanczos_has_the_dense_condition_and_mobility() {
    let mut worst: f64 = 0.0;
    // Soft turning rates in one variant spread the condition (measured 3.3e2 and 8.6e3).
    for (cells, turning) in [(30, 1.0e3), (40, 1.0e-2), (150, 1.0e3)] {
        let model = chain(cells, turning, |_| true);
        assert!(model.dofs() > DENSE_CONDITION_MAX, "the chain takes the Lanczos iteration");
        let found = mobility::mobility(&model, TOLERANCE);
        // Each cell: six coordinates less a ball joint's three rows and a link's one.
        assert_eq!(found.degrees_of_freedom, 2 * cells);
        assert!(found.redundant_rows.is_empty());
        let sparse = condition(&model);
        let dense = dense_condition(&model);
        assert!(dense.is_some_and(|d| d > 10.0), "the chain's motions are held, some softly: {dense:?}");
        worst = worst.max(agree(&format!("chain of {cells}"), sparse, dense));
        println!("chain of {cells}, turning rate {turning}: condition {:.3e}", sparse.unwrap());
    }
    println!("worst relative difference of the chains' conditions: {worst:.1e}");
}

#[test]
fn a_motion_held_by_nothing_makes_the_condition_infinite_and_a_welded_model_has_none() {
    // A last arm on a ball joint alone: it turns every way with nothing to hold it.
    let mut loose = chain(2, 1.0e3, |_| true);
    let last = loose.add_body("loose arm", Pose::at(Vec3::new(1.2, 0.0, 0.0))).unwrap();
    let arm = loose.body_id("arm 1").unwrap();
    loose.add_joint(JointSpec::spherical("loose ball", arm, last, Vec3::new(1.0, 0.0, 0.0))).unwrap();
    assert_eq!(condition(&loose), Some(f64::INFINITY));
    let dense = dense_condition(&loose).unwrap();
    assert!(dense > 1e12, "the dense reduced stiffness is singular to rounding: {dense:e}");
    assert!(condition(&chain(3, 1.0e3, |_| true)).is_some_and(f64::is_finite));
    // One arm welded to the ground: no motion left, no estimate.
    let mut welded = Model::new();
    let at = Vec3::new(0.4, 0.0, 0.0);
    let body = welded.add_body("arm", Pose::at(at)).unwrap();
    welded.add_joint(JointSpec::fixed("weld", BodyRef::Ground, body, at)).unwrap();
    let (rates, turning) = (Vec3::repeat(1e6), Vec3::repeat(1e3));
    let bushing = Bushing::new("mount", BodyRef::Ground, body.into(), at, Mat3::identity(), rates, turning);
    welded.add_element(bushing.unwrap()).unwrap();
    assert_eq!(mobility::mobility(&welded, TOLERANCE).degrees_of_freedom, 0);
    assert_eq!(condition(&welded), None);
    assert_eq!(dense_condition(&welded), None);
}

#[test]
fn which_ways_the_joints_hold_a_point_are_those_of_the_dense_null_space() {
    let directions = [Vec3::x(), Vec3::y(), Vec3::z(), Vec3::new(1.0, -2.0, 0.5)];
    let mut compared = 0;
    let mut held = 0;
    for (name, file) in shipped() {
        let Ok(corner) = file.suspension.build(Side::Left, Rig::WheelTravel) else { continue };
        let model = &corner.model;
        let (j, _) = dense_at_design(model);
        let (_, z) = dense_null_space(&j, model.dofs());
        for body in 0..model.bodies().len() {
            let at = model.design_poses()[body].position + Vec3::new(0.05, 0.1, -0.2);
            let sparse = holds_point(model, BodyId(body), at, &directions);
            let arm = at - model.design_poses()[body].position;
            for (d, &s) in directions.iter().zip(&sparse) {
                let d = d.normalize();
                let dense = (0..z.ncols()).all(|c| {
                    let v = z.column(c);
                    let base = body * BODY_DOFS;
                    let t = Vec3::new(v[base], v[base + 1], v[base + 2]);
                    let r = Vec3::new(v[base + 3], v[base + 4], v[base + 5]);
                    (t + r.cross(&arm)).dot(&d).abs() <= 1e-9
                });
                assert_eq!(s, dense, "{name}: body {body} along {d:?}");
                compared += 1;
                held += s as usize;
            }
        }
    }
    // Both answers occur: the ideal-jointed corners hold some of these points, every corner leaves others.
    assert!(held > 0 && held < compared, "{held} of {compared} held");
}
