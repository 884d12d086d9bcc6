//! What a model's factorization says of it: bodies nothing restrains, and the redundant rows of its
//! joints at design.

use super::*;

impl<'m> StaticSolver<'m> {
    /// Checks at design that every body is restrained, by inverse iteration on the factorized tangent.
    pub(super) fn check_restrained(&mut self, poses: &[Pose]) -> Result<(), SolverError> {
        let n = self.work.assembly.n;
        if n == 0 {
            return Ok(());
        }
        let state = State { poses: poses.to_vec(), lambda: vec![0.0; self.work.assembly.m()], t: 0.0 };
        self.assemble(&state, Some(Tangent::Elastic));
        let report = self.factorize()?;
        if report.suspect_body_dofs.is_empty() {
            return Ok(());
        }
        // Inverse iteration: the solution of K x = random is dominated by the free direction.
        self.work.rhs.fill(0.0);
        let mut seed = 0x2545F4914F6CDD1Du64;
        for c in 0..n {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            self.work.rhs[c] = (seed % 1000) as f64 / 1000.0 - 0.5;
        }
        for _ in 0..2 {
            self.work.factor.solve_in_place(&mut self.work.rhs, Accuracy::Refined)?;
            let norm = self.work.rhs[..n].iter().map(|v| v * v).sum::<f64>().sqrt();
            if !(norm.is_finite() && norm > 0.0) {
                break;
            }
            for v in self.work.rhs[..n].iter_mut() {
                *v /= norm;
            }
            self.work.rhs[n..].fill(0.0);
        }
        let (body, motion) = describe_free_motion(self.model, &self.work.rhs[..n], &report.suspect_body_dofs);
        Err(SolverError::Unrestrained { body, motion })
    }
}

/// The constraint rows of `model` that depend on earlier rows at the design pose (model row numbering,
/// ascending): the rank-revealing check of the whole Jacobian that [`StaticSolver::new`] drops them by,
/// at relative tolerance `tolerance`. Its all-rows assembly is dropped on return, before the solver makes
/// the active one, so that the two are never held at once.
pub fn redundant_rows_at_design(model: &Model, tolerance: f64) -> Vec<usize> {
    let mut full = Assembly::new(model, (0..model.constraint_rows()).collect());
    full.assemble(model, &model.design_poses(), 0.0, &[], None);
    redundant_rows(full.m(), full.n, &full.j_col_ptr, &full.j_row_idx, &full.j_values, tolerance)
}

/// Names the body and motion of a (near-)null vector of the tangent.
fn describe_free_motion(model: &Model, x: &[f64], suspects: &[usize]) -> (String, String) {
    let nb = model.bodies().len();
    let mut best = (0usize, -1.0f64);
    for b in 0..nb {
        let w: f64 = x[b * BODY_DOFS..(b + 1) * BODY_DOFS].iter().map(|v| v * v).sum();
        if w > best.1 {
            best = (b, w);
        }
    }
    let b = if best.1 > 0.0 && best.1.is_finite() { best.0 } else { suspects.first().map_or(0, |d| d / BODY_DOFS) };
    let v = &x[b * BODY_DOFS..(b + 1) * BODY_DOFS];
    let t = elastokin_core::Vec3::new(v[0], v[1], v[2]);
    let r = elastokin_core::Vec3::new(v[3], v[4], v[5]);
    let pose = model.bodies()[b].design_pose;
    let motion = if !(t.norm().is_finite() && r.norm().is_finite()) || (t.norm() == 0.0 && r.norm() == 0.0) {
        let coordinate = ["x", "y", "z", "rotation about x", "rotation about y", "rotation about z"];
        coordinate[suspects.first().map_or(0, |d| d % BODY_DOFS)].to_string()
    } else if r.norm() > 1e-3 * t.norm() {
        // Any rotation (per metre of lever) beyond noise: a pure translation has none.
        // A rotation about an axis through the point p where the velocity is parallel to the axis.
        let axis = r / r.norm();
        let p = pose.position + r.cross(&t) / r.norm_squared();
        format!(
            "rotation about the axis ({:.3}, {:.3}, {:.3}) through ({:.4}, {:.4}, {:.4}) m",
            axis.x, axis.y, axis.z, p.x, p.y, p.z
        )
    } else {
        let d = t / t.norm();
        format!("translation along ({:.3}, {:.3}, {:.3})", d.x, d.y, d.z)
    };
    (model.bodies()[b].name.clone(), motion)
}
