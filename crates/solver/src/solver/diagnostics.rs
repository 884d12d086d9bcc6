//! What a model's factorization says of it: bodies nothing restrains, and the redundant rows of its
//! joints at design.

use super::*;
use crate::kkt::FactorError;

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
        crate::mobility::pseudo_random_start(&mut self.work.rhs[..n]);
        for _ in 0..2 {
            self.work.factor.solve_in_place(&mut self.work.rhs, Accuracy::Refined).map_err(|e| self.named(e))?;
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

impl StaticSolver<'_> {
    /// A factorization's or solve's refusal in the model's words (see [`named`]).
    pub(super) fn named(&self, e: FactorError) -> SolverError {
        named(self.model, &self.work.assembly.active_rows, e)
    }
}

/// A factorization's or solve's refusal in the model's words: the body coordinate or joint row its index
/// stands for (`index` counts body coordinates first, then the active constraint rows).
fn named(model: &Model, active_rows: &[usize], e: FactorError) -> SolverError {
    let n = model.bodies().len() * BODY_DOFS;
    let coordinate = |k: usize| {
        let words = ["translation along x", "translation along y", "translation along z"];
        let turns = ["rotation about x", "rotation about y", "rotation about z"];
        let what = if k % BODY_DOFS < 3 { words[k % BODY_DOFS] } else { turns[k % BODY_DOFS - 3] };
        match model.bodies().get(k / BODY_DOFS) {
            Some(body) => format!("'{}', its {what}", body.name),
            None => format!("body coordinate {k}"),
        }
    };
    let row = |r: usize| active_rows.get(r).map_or_else(|| format!("constraint row {r}"), |&m| model.describe_row(m));
    match e {
        FactorError::Singular { kind: "body coordinate", index } => SolverError::Singular { part: coordinate(index) },
        FactorError::Singular { index, .. } => SolverError::Singular { part: row(index) },
        FactorError::NonFiniteSolution { index } if index < n => {
            SolverError::NonFiniteSolution { part: coordinate(index) }
        }
        FactorError::NonFiniteSolution { index } => SolverError::NonFiniteSolution { part: row(index - n) },
        other => SolverError::Factor(other),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use elastokin_core::{BodyRef, JointSpec, Vec3};

    /// A singular factorization said "singular at body coordinate 3" or "at constraint row 1", an index
    /// into the solver's matrix; it names the body's coordinate or the joint's row as the model calls them.
    #[test]
    fn a_singular_factorization_names_the_part_not_a_row_index() {
        let mut m = Model::new();
        m.add_body("upright", Pose::at(Vec3::new(0.0, 0.7, 0.3))).unwrap();
        let lever = m.add_body("lever", Pose::at(Vec3::new(0.25, 0.0, 0.0))).unwrap();
        m.add_joint(JointSpec::spherical("ball", BodyRef::Ground, lever, Vec3::zeros())).unwrap();
        let active: Vec<usize> = (0..m.constraint_rows()).collect();
        // Body coordinates are six per body, in the order bodies were added: translations, then rotations.
        let cases = [
            (FactorError::Singular { kind: "body coordinate", index: 9 }, "singular at 'lever', its rotation about x:"),
            (
                FactorError::Singular { kind: "body coordinate", index: 2 },
                "singular at 'upright', its translation along z:",
            ),
            (FactorError::Singular { kind: "constraint row", index: 1 }, "singular at joint 'ball' row "),
            (FactorError::NonFiniteSolution { index: 12 + 2 }, "not finite at joint 'ball' row "),
            (FactorError::NonFiniteSolution { index: 4 }, "not finite at 'upright', its rotation about y:"),
        ];
        for (e, said) in cases {
            let message = named(&m, &active, e.clone()).to_string();
            assert!(message.contains(said), "{e:?}: {message}");
            assert!(!message.contains("coordinate") && !message.contains("constraint row"), "{message}");
        }
        // The ball's rows are its three position rows, named by their labels.
        let row = named(&m, &active, FactorError::Singular { kind: "constraint row", index: 1 }).to_string();
        assert!(row.contains(&m.describe_row(1)), "{row}");
    }
}
