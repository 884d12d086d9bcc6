//! Mobility at design: how many ways a built model can move, counting only its joints, and how many of
//! its joint rows repeat others; which load directions at a point the joints alone hold. The rig asks it
//! to tell a solid axle whose roll is locked; the plausibility check reports it; the travel analysis reads
//! whether the joints hold the contact patch. By the solver's sparse factorizations
//! ([`elastokin_solver::mobility`]), at the tolerance its solves drop redundant rows by.

use elastokin_core::{BodyId, Model, Vec3, BODY_DOFS};
use elastokin_solver::mobility;
use elastokin_solver::SolverOptions;

/// The tolerance the solver drops redundant rows by, which the counts here share.
fn tolerance() -> f64 {
    SolverOptions::default().redundancy_tolerance
}

/// Body coordinates − independent joint rows at design, and the number of rows that repeat others.
pub fn mobility(model: &Model) -> (usize, usize) {
    let found = joint_mobility(model);
    (found.degrees_of_freedom, found.redundant_rows.len())
}

/// [`mobility`] with the rows that repeat others named, for [`reduced_condition`].
pub(crate) fn joint_mobility(model: &Model) -> mobility::Mobility {
    mobility::mobility(model, tolerance())
}

/// The condition of the elements' stiffness over the motions the joints allow at design
/// ([`mobility::reduced_condition`]; `found` is the model's [`joint_mobility`]): infinite when a motion is
/// held by nothing, `None` when the joints allow none (or the solve fails, which the run itself then
/// reports).
pub(crate) fn reduced_condition(model: &Model, found: &mobility::Mobility) -> Option<f64> {
    mobility::reduced_condition(model, found).ok().flatten()
}

/// For each of `directions`, whether the joints alone hold point `at` of `body` from moving that way at
/// design: every motion the joints allow moves the point across it by nothing (to the rank's rounding). A
/// load that way then meets no element: the corner is rigid in it, whatever its springs and bushings.
pub fn holds_point(model: &Model, body: BodyId, at: Vec3, directions: &[Vec3]) -> Vec<bool> {
    let arm = at - model.design_poses()[body.0].position;
    let base = body.0 * BODY_DOFS;
    // The generalized direction of a unit displacement of the point: a motion moves the point across `d`
    // by its translation · d + its rotation · (arm × d).
    let loads: Vec<Vec<f64>> = directions
        .iter()
        .map(|d| {
            let d = d.normalize();
            let turn = arm.cross(&d);
            let mut g = vec![0.0; model.dofs()];
            g[base..base + BODY_DOFS].copy_from_slice(&[d.x, d.y, d.z, turn.x, turn.y, turn.z]);
            g
        })
        .collect();
    match mobility::free_parts(model, tolerance(), &loads) {
        Ok(parts) => parts.iter().map(|p| p.iter().map(|v| v * v).sum::<f64>().sqrt() <= RANK_TOLERANCE).collect(),
        Err(_) => vec![false; directions.len()],
    }
}

/// Relative size under which a motion counts as none: rounding of rows of unit size.
const RANK_TOLERANCE: f64 = 1e-9;
