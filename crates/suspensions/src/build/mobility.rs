//! Mobility at design: how many ways a built model can move, counting only its joints, and how many of
//! its joint rows repeat others, from the rank of the joints' Jacobian. The rig asks it to tell a solid
//! axle whose roll is locked; the plausibility check reports it and reads the allowed motions.

use elastokin_core::{BodyId, Model, Vec3};
use elastokin_solver::assembly::{Assembly, Tangent};
use nalgebra::DMatrix;

/// Body coordinates − independent joint rows at design, and the number of rows that repeat others.
pub fn mobility(model: &Model) -> (usize, usize) {
    let (j, n) = jacobian(model);
    let rank = rank(&j);
    (n - rank, j.nrows() - rank)
}

/// For each of `directions`, whether the joints alone hold point `at` of `body` from moving that way at
/// design: every motion the joints allow moves the point across it by nothing (to the rank's rounding). A
/// load that way then meets no element: the corner is rigid in it, whatever its springs and bushings.
pub fn holds_point(model: &Model, body: BodyId, at: Vec3, directions: &[Vec3]) -> Vec<bool> {
    let (j, n) = jacobian(model);
    let Some(free) = null_space(&j, n) else {
        return vec![true; directions.len()];
    };
    let arm = at - model.design_poses()[body.0].position;
    let base = body.0 * elastokin_core::BODY_DOFS;
    // Each free motion is a unit vector of body coordinates (translations of body origins, rotations).
    let moves: Vec<Vec3> = (0..free.ncols())
        .map(|c| {
            let v = free.column(c);
            let translation = Vec3::new(v[base], v[base + 1], v[base + 2]);
            let rotation = Vec3::new(v[base + 3], v[base + 4], v[base + 5]);
            translation + rotation.cross(&arm)
        })
        .collect();
    directions.iter().map(|d| moves.iter().all(|m| m.dot(&d.normalize()).abs() <= RANK_TOLERANCE)).collect()
}

/// The joints' Jacobian at design (all rows × body coordinates).
pub(crate) fn jacobian(model: &Model) -> (DMatrix<f64>, usize) {
    let rows: Vec<usize> = (0..model.constraint_rows()).collect();
    let mut assembly = Assembly::new(model, rows);
    let lambda = vec![0.0; assembly.m()];
    assembly.assemble(model, &model.design_poses(), 0.0, &lambda, Some(Tangent::Elastic));
    let (m, n) = (assembly.m(), assembly.n);
    let mut j = DMatrix::zeros(m, n);
    for c in 0..n {
        for p in assembly.j_col_ptr[c]..assembly.j_col_ptr[c + 1] {
            j[(assembly.j_row_idx[p], c)] = assembly.j_values[p];
        }
    }
    (j, n)
}

/// Relative size under which a singular value counts as zero: rounding of rows of unit size.
pub(crate) const RANK_TOLERANCE: f64 = 1e-9;

fn rank(j: &DMatrix<f64>) -> usize {
    if j.nrows() == 0 || j.ncols() == 0 {
        return 0;
    }
    let s = j.clone().svd(false, false).singular_values;
    let largest = s.max();
    s.iter().filter(|&&v| v > RANK_TOLERANCE * largest).count()
}

pub(crate) fn null_space(j: &DMatrix<f64>, n: usize) -> Option<DMatrix<f64>> {
    if j.nrows() == 0 {
        return Some(DMatrix::identity(n, n));
    }
    // Pad J to square so the SVD returns a full set of right singular vectors.
    let mut square = DMatrix::zeros(n.max(j.nrows()), n);
    square.rows_mut(0, j.nrows()).copy_from(j);
    let svd = square.svd(false, true);
    let v_t = svd.v_t?;
    let largest = svd.singular_values.max();
    let free: Vec<usize> =
        (0..n).filter(|&i| svd.singular_values[i] <= RANK_TOLERANCE * largest.max(f64::MIN_POSITIVE)).collect();
    if free.is_empty() {
        return None;
    }
    let mut z = DMatrix::zeros(n, free.len());
    for (col, &i) in free.iter().enumerate() {
        z.set_column(col, &v_t.row(i).transpose());
    }
    Some(z)
}
