//! Mobility at design, by the sparse factorizations a step uses, so that it costs what a step costs at any
//! size: how many ways a model can move counting only its joints, how many joint rows repeat others, how
//! much of a load direction the joints leave to the elements, and how well the elements' stiffness holds
//! the motions the joints allow.
//!
//! The rank is the redundancy test's (a sparse factorization of `JJᵀ`, [`crate::redundancy`]). The rest
//! is one factorization of a KKT matrix `[K Jᵀ; J 0]` of the independent rows at the design pose, whose
//! solve with `[g; 0]` gives `Z(ZᵀKZ)⁻¹Zᵀg`, `Z` an orthonormal basis of the motions `J` allows: with
//! `K = I` the part of `g` those motions see; with the elastic stiffness the compliance to `g`, whose
//! largest eigenvalue (by Lanczos, a solve a step) is the softest motion's. Nothing is dense but the reduced
//! compliance of a model of at most [`DENSE_CONDITION_MAX`] coordinates.

use crate::assembly::{Assembly, Tangent};
use crate::error::SolverError;
use crate::kkt::{Accuracy, AutoKkt, BackendChoice, KktBackend, KktOptions, KktValues};
use crate::redundancy::redundant_rows;
use elastokin_core::Model;

/// The constraint rows of `model` that depend on earlier rows at the design pose (model row numbering,
/// ascending): the rank-revealing check of the whole Jacobian that
/// [`StaticSolver::new`](crate::StaticSolver::new) drops them by, at relative tolerance `tolerance`. Its
/// all-rows assembly is dropped on return, before the solver makes the active one, so that the two are
/// never held at once.
pub fn redundant_rows_at_design(model: &Model, tolerance: f64) -> Vec<usize> {
    let mut full = Assembly::new(model, (0..model.constraint_rows()).collect());
    full.assemble(model, &model.design_poses(), 0.0, &[], None);
    redundant_rows(full.m(), full.n, &full.j_col_ptr, &full.j_row_idx, &full.j_values, tolerance)
}

/// How a model can move at design, counting only its joints.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Mobility {
    /// Body coordinates less independent joint rows.
    pub degrees_of_freedom: usize,
    /// The joint rows that repeat earlier ones, as the solver drops them ([`redundant_rows_at_design`]).
    pub redundant_rows: Vec<usize>,
}

/// The mobility of `model` at design, its redundant rows found at relative `tolerance`
/// (the solver's `redundancy_tolerance`).
pub fn mobility(model: &Model, tolerance: f64) -> Mobility {
    let redundant_rows = redundant_rows_at_design(model, tolerance);
    let independent = model.constraint_rows() - redundant_rows.len();
    Mobility { degrees_of_freedom: model.dofs().saturating_sub(independent), redundant_rows }
}

/// The KKT matrix of the independent rows of a model at its design pose, factorized with a chosen `K`.
struct DesignKkt {
    factor: AutoKkt,
    n: usize,
    /// The right-hand side `[x; 0]` and solution, kept for every solve.
    rhs: Vec<f64>,
}

/// What stands in the `K` block of a [`DesignKkt`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Block {
    /// The identity: a solve gives the part of a vector the joints' motions see.
    Identity,
    /// The symmetric part of the elements' own stiffness at design (no joint-force term: the joints
    /// carry nothing there): a solve gives the compliance to a load.
    Elastic,
}

/// What a [`DesignKkt`] found as it was factorized.
struct Factorized {
    kkt: DesignKkt,
    /// The largest diagonal entry of `K`.
    stiffest: f64,
    /// Whether the factorization met a motion nothing holds (a pivot of a body coordinate lost to rounding).
    unrestrained: bool,
}

impl DesignKkt {
    /// Factorizes at design with the rows `dropped` left out.
    fn factorize(model: &Model, dropped: &[usize], block: Block) -> Result<Factorized, SolverError> {
        let active: Vec<usize> = (0..model.constraint_rows()).filter(|r| dropped.binary_search(r).is_err()).collect();
        let mut assembly = Assembly::new(model, active);
        let lambda = vec![0.0; assembly.m()];
        assembly.assemble(model, &model.design_poses(), 0.0, &lambda, Some(Tangent::Elastic));
        let n = assembly.n;
        let mut stiffest: f64 = 0.0;
        for c in 0..n {
            for p in assembly.k_col_ptr[c]..assembly.k_col_ptr[c + 1] {
                let diagonal = assembly.k_row_idx[p] == c;
                if diagonal {
                    stiffest = stiffest.max(assembly.k_values[p]);
                }
                if block == Block::Identity {
                    assembly.k_values[p] = if diagonal { 1.0 } else { 0.0 };
                }
            }
        }
        let mut factor = AutoKkt::analyze(&assembly.kkt_pattern(), KktOptions::default(), BackendChoice::Auto)?;
        let report = factor.factorize(KktValues { k: &assembly.k_values, k_skew: None, j: &assembly.j_values })?;
        let unrestrained = !report.suspect_body_dofs.is_empty();
        let rhs = vec![0.0; n + assembly.m()];
        Ok(Factorized { kkt: DesignKkt { factor, n, rhs }, stiffest, unrestrained })
    }

    /// `x ← Z(ZᵀKZ)⁻¹Zᵀx`: the body coordinates of the solve with `[x; 0]`.
    fn solve(&mut self, x: &mut [f64]) -> Result<(), SolverError> {
        self.rhs.fill(0.0);
        self.rhs[..self.n].copy_from_slice(x);
        self.factor.solve_in_place(&mut self.rhs, Accuracy::Refined)?;
        x.copy_from_slice(&self.rhs[..self.n]);
        Ok(())
    }
}

/// The parts of generalized directions `loads` (each of `model.dofs()` entries) that the motions the
/// joints allow at design see: each direction's orthogonal projection onto those motions. A part of
/// nothing (to rounding) is a direction the joints alone hold; one factorization for all.
pub fn free_parts(model: &Model, tolerance: f64, loads: &[Vec<f64>]) -> Result<Vec<Vec<f64>>, SolverError> {
    let dropped = redundant_rows_at_design(model, tolerance);
    let mut kkt = DesignKkt::factorize(model, &dropped, Block::Identity)?.kkt;
    loads
        .iter()
        .map(|g| {
            let mut x = g.clone();
            kkt.solve(&mut x)?;
            Ok(x)
        })
        .collect()
}

/// Fills `x` with the fixed pseudo-random start of an iteration that seeks an extreme mode (xorshift, the
/// same every run): Lanczos here, the inverse iteration that names an unrestrained motion.
pub(crate) fn pseudo_random_start(x: &mut [f64]) {
    let mut seed = 0x2545F4914F6CDD1Du64;
    for v in x {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        *v = (seed % 1000) as f64 / 1000.0 - 0.5;
    }
}

/// Up to this many body coordinates, [`reduced_condition`] reads the reduced compliance whole, one solve
/// per coordinate, and takes its eigenvalues densely; above, by Lanczos iteration, a solve a step.
pub const DENSE_CONDITION_MAX: usize = 128;

/// The condition of the elements' stiffness over the motions the joints allow at design: the stiffest
/// body coordinate's diagonal stiffness over the softest allowed motion's (the smallest eigenvalue of
/// `ZᵀKZ`, the inverse of the largest of the compliance `Z(ZᵀKZ)⁻¹Zᵀ`). Against the stiffest single
/// coordinate rather than the stiffest allowed motion, so that a model left with one motion that nothing
/// holds does not read as perfectly conditioned: that motion makes it infinite. `None` when the joints
/// allow no motion or the elements have no stiffness.
/// `mobility` is the model's ([`mobility`]), whose redundant rows are left out.
pub fn reduced_condition(model: &Model, mobility: &Mobility) -> Result<Option<f64>, SolverError> {
    if mobility.degrees_of_freedom == 0 {
        return Ok(None);
    }
    let found = DesignKkt::factorize(model, &mobility.redundant_rows, Block::Elastic)?;
    let Factorized { kkt, stiffest, unrestrained } = found;
    if !(stiffest > 0.0 && stiffest.is_finite()) {
        return Ok(None);
    }
    if unrestrained {
        return Ok(Some(f64::INFINITY));
    }
    let mut compliance = Compliance { kkt, scale: stiffest };
    let largest = if compliance.kkt.n <= DENSE_CONDITION_MAX {
        compliance.largest_dense()?
    } else {
        compliance.largest_lanczos()?
    };
    Ok(Some(if largest.is_finite() { largest } else { f64::INFINITY }))
}

/// The reduced compliance `Z(ZᵀKZ)⁻¹Zᵀ` times the stiffest diagonal entry: its eigenvalues are the
/// condition of each allowed motion.
struct Compliance {
    kkt: DesignKkt,
    scale: f64,
}

/// The relative move of the largest Ritz value over [`LANCZOS_CHECK_EVERY`] steps at which
/// [`Compliance::largest_lanczos`] stops.
const LANCZOS_SETTLED: f64 = 1e-10;
/// Steps between two looks at the largest Ritz value.
const LANCZOS_CHECK_EVERY: usize = 10;
/// The most steps [`Compliance::largest_lanczos`] takes.
const LANCZOS_MAX_STEPS: usize = 120;

impl Compliance {
    fn apply(&mut self, x: &mut [f64]) -> Result<(), SolverError> {
        self.kkt.solve(x)?;
        x.iter_mut().for_each(|v| *v *= self.scale);
        Ok(())
    }

    /// The largest eigenvalue's size, of the operator read whole (symmetrized against rounding).
    fn largest_dense(&mut self) -> Result<f64, SolverError> {
        let n = self.kkt.n;
        let mut whole = nalgebra::DMatrix::<f64>::zeros(n, n);
        let mut x = vec![0.0; n];
        for c in 0..n {
            x.fill(0.0);
            x[c] = 1.0;
            self.apply(&mut x)?;
            whole.column_mut(c).copy_from_slice(&x);
        }
        let symmetric = (&whole + whole.transpose()) * 0.5;
        Ok(nalgebra::SymmetricEigen::new(symmetric).eigenvalues.amax())
    }

    /// The largest eigenvalue's size by Lanczos iteration with full reorthogonalization from a fixed
    /// pseudo-random start, until the largest Ritz value moves by less than [`LANCZOS_SETTLED`] of itself
    /// over [`LANCZOS_CHECK_EVERY`] steps, or after [`LANCZOS_MAX_STEPS`]. The largest Ritz value is the
    /// largest eigenvalue's size from below, and it settles even where the eigenvalues near it cluster (a
    /// chain of like parts), where a restarted iteration that waits for its Ritz vector's residual (faer's
    /// `partial_self_adjoint_eigen`) restarts many times and grows faster than the model.
    fn largest_lanczos(&mut self) -> Result<f64, SolverError> {
        let n = self.kkt.n;
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let mut q = vec![0.0; n];
        pseudo_random_start(&mut q);
        let size = dot(&q, &q).sqrt();
        q.iter_mut().for_each(|v| *v /= size);
        let (mut basis, mut alpha, mut beta): (Vec<Vec<f64>>, Vec<f64>, Vec<f64>) = Default::default();
        let mut largest: f64 = 0.0;
        let steps = LANCZOS_MAX_STEPS.min(n);
        for step in 0..steps {
            let mut w = q.clone();
            self.apply(&mut w)?;
            alpha.push(dot(&q, &w));
            basis.push(q);
            // Twice against every vector so far: the basis stays orthogonal to rounding.
            for _ in 0..2 {
                for v in &basis {
                    let c = dot(v, &w);
                    w.iter_mut().zip(v).for_each(|(x, y)| *x -= c * y);
                }
            }
            let next = dot(&w, &w).sqrt();
            // The Krylov space holds an invariant subspace: its Ritz values are eigenvalues.
            let exhausted = next <= f64::EPSILON * largest.max(alpha[step].abs());
            if exhausted || (step + 1) % LANCZOS_CHECK_EVERY == 0 || step + 1 == steps {
                let now = largest_ritz_value(&alpha, &beta);
                let settled = (now - largest).abs() <= LANCZOS_SETTLED * now;
                largest = now;
                if settled || exhausted {
                    break;
                }
            }
            beta.push(next);
            q = w.iter().map(|v| v / next).collect();
        }
        Ok(largest)
    }
}

/// The largest eigenvalue's size of the symmetric tridiagonal matrix of diagonal `alpha` and off-diagonal
/// `beta` (one shorter, or as long when the last is not yet used).
fn largest_ritz_value(alpha: &[f64], beta: &[f64]) -> f64 {
    let k = alpha.len();
    let t = nalgebra::DMatrix::from_fn(k, k, |r, c| match r.abs_diff(c) {
        0 => alpha[r],
        1 => beta[r.min(c)],
        _ => 0.0,
    });
    nalgebra::SymmetricEigen::new(t).eigenvalues.amax()
}
