//! KKT assembly with a fixed sparsity pattern and an in-place slot map.
//!
//! The pattern is found once per model from what the scene contains: a dense 6×6 block on the diagonal
//! of every body, an off-diagonal block for every pair of bodies that an element or a joint couples
//! (a joint couples its bodies through the geometric stiffness of its reaction), and in `J` the 12
//! coordinates of the two bodies of every active constraint row. Each element and joint keeps where its
//! off-diagonal block sits in its columns and each row its position in its bodies' columns, the rest of
//! every slot following from the pattern's block layout, so re-assembly at a new configuration writes
//! values in place and allocates nothing.
//!
//! `K` is stored as its upper triangle in two parts, symmetric and skew: an element's exact tangent is
//! non-symmetric away from equilibrium (see `elastokin_core::constraint`), and a world-fixed torque, which
//! has no potential on SO(3), leaves a skew part `−½M̃` even at equilibrium. The LDLᵀ factorizes the
//! symmetric part; the solver restores the skew part by GMRES preconditioned with that factorization,
//! which keeps Newton quadratic.

use elastokin_core::{BodyRef, ElementEval, ElementRole, Model, PairMatrix, Pose, RowGradient, BODY_DOFS};

/// Which stiffness to assemble.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tangent {
    /// The structure's elastic stiffness only (for checking what holds the bodies).
    Elastic,
    /// Elastic + load stiffness, without the joint reactions' geometric stiffness: the `K` of paper
    /// mode, whose recurrence carries the reactions' change of direction through `Φ_q(qⁿ⁻¹)ᵀλⁿ⁻¹`.
    Paper,
    /// Elastic + geometric (joint reactions) + load stiffness: the consistent Newton tangent.
    Full,
}

/// Global dof of each of the 12 local coordinates of a body pair (`None` for the ground).
pub(crate) fn pair_dofs(i: BodyRef, j: BodyRef) -> [Option<usize>; 12] {
    let mut out = [None; 12];
    for (side, b) in [i, j].into_iter().enumerate() {
        if let Some(id) = b.id() {
            for k in 0..BODY_DOFS {
                out[side * BODY_DOFS + k] = Some(id.0 * BODY_DOFS + k);
            }
        }
    }
    out
}

/// Offset of a body pair's off-diagonal block within each of its columns of `K`'s upper triangle, or
/// [`NO_SLOT`] for a pair with one body (the other the ground): every slot of the pair's 12×12 block then
/// follows from the column pointers (see [`k_slot`]), so that no per-entry slot map is kept (one was
/// 144 entries of 24 bytes for each element and joint between two bodies: more than half of what the
/// solver held).
type PairBlock = u32;

/// Slot of the upper-triangle entry `(r, c)` of `K`, `r ≤ c`, in the block pattern of [`Assembly::new`]:
/// column `c` lists 6 rows of every off-diagonal block above its body's diagonal block in block order,
/// then the diagonal block's rows up to `c` itself, the last entry of the column.
#[inline]
fn k_slot(k_col_ptr: &[usize], offdiag: PairBlock, r: usize, c: usize) -> usize {
    if r / BODY_DOFS == c / BODY_DOFS {
        k_col_ptr[c + 1] - 1 - (c - r)
    } else {
        k_col_ptr[c] + offdiag as usize + r % BODY_DOFS
    }
}

/// Adds the symmetric part of `block` (over the 12 coordinates `dofs`) to `values` and its skew part to
/// `skew` (both upper triangles): each entry and its mirror, `(p, q)` and `(q, p)`, fall in one slot, which
/// takes half their sum (their sum on the diagonal) and, in `skew`, half the one above the diagonal less
/// the one below. A pair of zeros (most of a joint's geometric stiffness) is passed over.
#[inline]
fn scatter(
    dofs: &[Option<usize>; 12],
    offdiag: PairBlock,
    k_col_ptr: &[usize],
    block: &PairMatrix,
    values: &mut [f64],
    skew: &mut [f64],
) {
    let data = block.as_slice(); // column-major: index = q*12 + p
    for p in 0..12 {
        let Some(gp) = dofs[p] else { continue };
        values[k_slot(k_col_ptr, offdiag, gp, gp)] += data[p * 12 + p];
        for q in p + 1..12 {
            let Some(gq) = dofs[q] else { continue };
            let (pq, qp) = (data[q * 12 + p], data[p * 12 + q]);
            if pq == 0.0 && qp == 0.0 {
                continue;
            }
            match gp.cmp(&gq) {
                std::cmp::Ordering::Equal => values[k_slot(k_col_ptr, offdiag, gp, gq)] += pq + qp,
                std::cmp::Ordering::Less => {
                    let slot = k_slot(k_col_ptr, offdiag, gp, gq);
                    values[slot] += 0.5 * (pq + qp);
                    skew[slot] += 0.5 * (pq - qp);
                }
                std::cmp::Ordering::Greater => {
                    let slot = k_slot(k_col_ptr, offdiag, gq, gp);
                    values[slot] += 0.5 * (pq + qp);
                    skew[slot] += 0.5 * (qp - pq);
                }
            }
        }
    }
}

/// Sparsity pattern, slot maps and value arrays of one model's KKT system.
#[derive(Debug, Default)]
pub struct Assembly {
    /// Number of body coordinates.
    pub n: usize,
    /// Model row index of each active constraint row.
    pub active_rows: Vec<usize>,
    /// Upper triangle of `K`, CSC.
    pub k_col_ptr: Vec<usize>,
    /// Row indices of `K`.
    pub k_row_idx: Vec<usize>,
    /// `J` (active rows × n), CSC.
    pub j_col_ptr: Vec<usize>,
    /// Row indices of `J`.
    pub j_row_idx: Vec<usize>,
    /// Where each element's stiffness lands in `K` (see [`k_slot`]).
    element_blocks: Vec<PairBlock>,
    /// Where each joint's geometric stiffness lands in `K`.
    joint_blocks: Vec<PairBlock>,
    /// For each active row and each of its two bodies, the row's position in that body's columns of `J`:
    /// the same in all six, as every row that touches a body touches all six of its coordinates.
    row_slots: Vec<[u32; 2]>,
    /// Which joint and row within it each active row is.
    pub(crate) row_joint: Vec<(usize, usize)>,
    /// Values of `K` (upper, symmetrised).
    pub k_values: Vec<f64>,
    /// Skew part of `K` above the diagonal: `S = ½(K − Kᵀ)`, entry `(r, c)` with `r < c`.
    pub k_skew: Vec<f64>,
    /// Whether the last assembled tangent has a skew part at all (most scenes without world-fixed
    /// torques and away from equilibrium still do; a linear spring-only scene at rest does not).
    pub has_skew: bool,
    /// Values of `J`.
    pub j_values: Vec<f64>,
    /// Applied generalized force `Q(q, t)` of all elements and loads.
    pub applied: Vec<f64>,
    /// `∂Q/∂t`: the load increment direction.
    pub load_rate: Vec<f64>,
    /// Largest generalized force of any single element (N or N·m): the scale residuals are judged by.
    pub force_scale: f64,
    /// The first element whose generalized force came out NaN or infinite at the last assembly: named in
    /// the error, since its numbers are passed over by [`Assembly::force_scale`].
    pub non_finite_element: Option<usize>,
    /// `Φ` of the active rows.
    pub phi: Vec<f64>,
    /// `∂Φ/∂t` of the active rows (minus the driver rates).
    pub phi_rate: Vec<f64>,
    /// Evaluations of one chunk of elements (see [`EVAL_CHUNK`]).
    evals: Vec<ElementEval>,
}

const NO_SLOT: u32 = u32::MAX;

/// For each body's column block of `K`'s upper triangle, the row blocks `a ≤ b` coupled to it (itself
/// and every body an element or joint joins it to), sorted.
fn coupled_blocks(model: &Model) -> Vec<Vec<usize>> {
    let mut couplings: Vec<(usize, usize)> = Vec::new();
    let mut couple = |i: BodyRef, j: BodyRef| {
        if let (Some(a), Some(b)) = (i.id(), j.id()) {
            if a != b {
                couplings.push((a.0.min(b.0), a.0.max(b.0)));
            }
        }
    };
    for e in model.elements() {
        let [i, j] = e.bodies();
        couple(i, j);
    }
    for jt in model.joints() {
        couple(jt.spec.body_i, jt.spec.body_j);
    }
    couplings.sort_unstable();
    couplings.dedup();
    let mut col_blocks: Vec<Vec<usize>> = (0..model.bodies().len()).map(|b| vec![b]).collect();
    for &(a, b) in &couplings {
        col_blocks[b].push(a);
    }
    for blocks in &mut col_blocks {
        blocks.sort_unstable();
    }
    col_blocks
}

/// The CSC pattern (column pointers, row indices) of `K`'s upper triangle with the column blocks
/// `col_blocks`: 6×6 entries per off-diagonal block and the 21 of each diagonal block's upper triangle,
/// reserved exactly, as the pattern is kept for the solver's lifetime.
fn k_pattern(col_blocks: &[Vec<usize>]) -> (Vec<usize>, Vec<usize>) {
    let nnz_k: usize = col_blocks
        .iter()
        .map(|blocks| BODY_DOFS * BODY_DOFS * (blocks.len() - 1) + BODY_DOFS * (BODY_DOFS + 1) / 2)
        .sum();
    let mut k_col_ptr = Vec::with_capacity(col_blocks.len() * BODY_DOFS + 1);
    let mut k_row_idx = Vec::with_capacity(nnz_k);
    k_col_ptr.push(0);
    for (b, blocks) in col_blocks.iter().enumerate() {
        for cl in 0..BODY_DOFS {
            let col = b * BODY_DOFS + cl;
            for &a in blocks {
                for rl in 0..BODY_DOFS {
                    let row = a * BODY_DOFS + rl;
                    if row <= col {
                        k_row_idx.push(row);
                    }
                }
            }
            k_col_ptr.push(k_row_idx.len());
        }
    }
    debug_assert_eq!(k_row_idx.len(), nnz_k);
    (k_col_ptr, k_row_idx)
}

/// The CSC pattern of `J` over the active rows, with where each row sits in its bodies' columns and which
/// joint row it is.
struct JPattern {
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    row_slots: Vec<[u32; 2]>,
    row_joint: Vec<(usize, usize)>,
}

impl JPattern {
    fn of(model: &Model, active_rows: &[usize]) -> JPattern {
        let n = model.dofs();
        let mut row_joint = Vec::with_capacity(active_rows.len());
        let mut row_dofs = Vec::with_capacity(active_rows.len());
        for &r in active_rows {
            let o = model.row_origin(r).expect("active rows are model rows");
            let jt = &model.joints()[o.joint.0];
            row_joint.push((o.joint.0, o.row));
            row_dofs.push(pair_dofs(jt.spec.body_i, jt.spec.body_j));
        }
        let mut counts = vec![0usize; n];
        for dofs in &row_dofs {
            for d in dofs.iter().flatten() {
                counts[*d] += 1;
            }
        }
        let mut col_ptr = vec![0usize; n + 1];
        for c in 0..n {
            col_ptr[c + 1] = col_ptr[c] + counts[c];
        }
        let mut fill = col_ptr[..n].to_vec();
        let mut row_idx = vec![0usize; col_ptr[n]];
        let mut row_slots = vec![[NO_SLOT; 2]; active_rows.len()];
        // Rows are visited in increasing order, so each column's row list comes out sorted.
        for (k, dofs) in row_dofs.iter().enumerate() {
            for (local, d) in dofs.iter().enumerate() {
                if let Some(c) = *d {
                    row_idx[fill[c]] = k;
                    row_slots[k][local / BODY_DOFS] = (fill[c] - col_ptr[c]) as u32;
                    fill[c] += 1;
                }
            }
        }
        JPattern { col_ptr, row_idx, row_slots, row_joint }
    }
}

impl Assembly {
    /// Analyses the pattern of `model` with the given active constraint rows (model row numbering).
    pub fn new(model: &Model, active_rows: Vec<usize>) -> Self {
        let n = model.dofs();
        let col_blocks = coupled_blocks(model);
        let (k_col_ptr, k_row_idx) = k_pattern(&col_blocks);
        let pair_block = |i: BodyRef, j: BodyRef| -> PairBlock {
            match (i.id(), j.id()) {
                (Some(a), Some(b)) if a != b => {
                    let (a, b) = (a.0.min(b.0), a.0.max(b.0));
                    let pos = col_blocks[b].binary_search(&a).expect("pattern holds every coupled pair");
                    (BODY_DOFS * pos) as PairBlock
                }
                _ => NO_SLOT,
            }
        };
        let element_blocks: Vec<PairBlock> = model
            .elements()
            .iter()
            .map(|e| {
                let [i, j] = e.bodies();
                pair_block(i, j)
            })
            .collect();
        let joint_blocks: Vec<PairBlock> =
            model.joints().iter().map(|jt| pair_block(jt.spec.body_i, jt.spec.body_j)).collect();
        let j = JPattern::of(model, &active_rows);
        let (m, nnz_k, nnz_j) = (active_rows.len(), k_row_idx.len(), j.row_idx.len());
        Assembly {
            n,
            active_rows,
            k_col_ptr,
            k_row_idx,
            j_col_ptr: j.col_ptr,
            j_row_idx: j.row_idx,
            element_blocks,
            joint_blocks,
            row_slots: j.row_slots,
            row_joint: j.row_joint,
            k_values: vec![0.0; nnz_k],
            k_skew: vec![0.0; nnz_k],
            has_skew: false,
            j_values: vec![0.0; nnz_j],
            applied: vec![0.0; n],
            load_rate: vec![0.0; n],
            force_scale: 0.0,
            non_finite_element: None,
            phi: vec![0.0; m],
            phi_rate: vec![0.0; m],
            evals: vec![ElementEval::default(); model.elements().len().min(EVAL_CHUNK)],
        }
    }

    /// Number of active constraint rows.
    pub fn m(&self) -> usize {
        self.active_rows.len()
    }

    /// The sparsity pattern of the KKT system this assembly fills, for [`KktFactor::analyze`].
    ///
    /// [`KktFactor::analyze`]: crate::kkt::KktFactor::analyze
    pub fn kkt_pattern(&self) -> crate::kkt::KktPattern {
        crate::kkt::KktPattern {
            n: self.n,
            m: self.m(),
            k_col_ptr: self.k_col_ptr.clone(),
            k_row_idx: self.k_row_idx.clone(),
            j_col_ptr: self.j_col_ptr.clone(),
            j_row_idx: self.j_row_idx.clone(),
        }
    }

    /// Evaluates everything at `(poses, t)`: applied forces, load rate, `Φ`, `J` and, if asked, `K`.
    /// `lambda` holds one multiplier per active row (used by the geometric stiffness of [`Tangent::Full`]).
    pub fn assemble(&mut self, model: &Model, poses: &[Pose], t: f64, lambda: &[f64], tangent: Option<Tangent>) {
        let with_k = tangent.is_some();
        self.applied.fill(0.0);
        self.load_rate.fill(0.0);
        // Without a tangent, K keeps the values of the last one: chord iterations solve with the factorized
        // symmetric part and must see the skew part that belongs to it.
        if with_k {
            self.k_values.fill(0.0);
            self.k_skew.fill(0.0);
        }
        self.assemble_elements(model, poses, t, tangent);
        self.assemble_rows(model, poses, t, lambda, tangent);
        if with_k {
            self.has_skew = self.k_skew.iter().any(|&v| v != 0.0);
        }
    }

    /// The elements' part: forces into `Q`, the loads' rates into `∂Q/∂t`, and (with a `tangent` that
    /// takes them) their stiffnesses into `K`; the elements are evaluated a chunk at a time, in parallel
    /// where a chunk is large.
    fn assemble_elements(&mut self, model: &Model, poses: &[Pose], t: f64, tangent: Option<Tangent>) {
        let with_k = tangent.is_some();
        let elements = model.elements();
        let eval_one = |e: &dyn elastokin_core::ForceElement, out: &mut ElementEval| {
            let [i, j] = e.bodies();
            e.evaluate(&i.pose(poses), &j.pose(poses), t, out, with_k);
        };
        let mut rate = RowGradient::zeros();
        self.force_scale = 0.0;
        self.non_finite_element = None;
        for start in (0..elements.len()).step_by(EVAL_CHUNK) {
            let chunk = &elements[start..(start + EVAL_CHUNK).min(elements.len())];
            let evals = &mut self.evals[..chunk.len()];
            #[cfg(feature = "parallel")]
            {
                use rayon::prelude::*;
                if chunk.len() >= PARALLEL_ELEMENTS {
                    evals.par_iter_mut().zip(chunk.par_iter()).for_each(|(out, e)| eval_one(e.as_ref(), out));
                } else {
                    evals.iter_mut().zip(chunk.iter()).for_each(|(out, e)| eval_one(e.as_ref(), out));
                }
            }
            #[cfg(not(feature = "parallel"))]
            evals.iter_mut().zip(chunk.iter()).for_each(|(out, e)| eval_one(e.as_ref(), out));
            for (offset, e) in chunk.iter().enumerate() {
                self.add_element(start + offset, offset, e.as_ref(), poses, t, tangent, &mut rate);
            }
        }
    }

    /// Adds element `k`, evaluated into `evals[offset]`, to `Q`, `∂Q/∂t` (a load, its rate computed into
    /// `rate`) and, where `tangent` takes its role, `K`.
    #[inline]
    #[allow(
        clippy::too_many_arguments,
        reason = "the element, where its evaluation is, the state and the tangent asked: each once, in the assembly's inner loop"
    )]
    fn add_element(
        &mut self,
        k: usize,
        offset: usize,
        e: &dyn elastokin_core::ForceElement,
        poses: &[Pose],
        t: f64,
        tangent: Option<Tangent>,
        rate: &mut RowGradient,
    ) {
        let [i, j] = e.bodies();
        let dofs = pair_dofs(i, j);
        let ev = &self.evals[offset];
        // Plain comparisons, not `f64::max`, whose NaN handling, twelve times in a chain, cost 5 to
        // 7 % of a corrected sweep; a force that is no finite number is noted instead.
        for v in ev.force.iter() {
            let size = v.abs();
            if !size.is_finite() {
                self.non_finite_element.get_or_insert(k);
            } else if size > self.force_scale {
                self.force_scale = size;
            }
        }
        for (local, d) in dofs.iter().enumerate() {
            if let Some(g) = d {
                self.applied[*g] += ev.force[local];
            }
        }
        if e.role() == ElementRole::Load {
            e.load_rate(&i.pose(poses), &j.pose(poses), t, rate);
            for (local, d) in dofs.iter().enumerate() {
                if let Some(g) = d {
                    self.load_rate[*g] += rate[local];
                }
            }
        }
        let include = match tangent {
            Some(Tangent::Full) | Some(Tangent::Paper) => true,
            Some(Tangent::Elastic) => e.role() == ElementRole::Elastic,
            None => false,
        };
        if include {
            let block = self.element_blocks[k];
            scatter(&dofs, block, &self.k_col_ptr, &ev.stiffness, &mut self.k_values, &mut self.k_skew);
        }
    }

    /// The constraint rows' part: `Φ`, its rate and `J`, and with the full tangent the geometric stiffness
    /// `Σ λ ∂(∇Φ)/∂q` of each joint into `K`.
    fn assemble_rows(&mut self, model: &Model, poses: &[Pose], t: f64, lambda: &[f64], tangent: Option<Tangent>) {
        let mut geometric = PairMatrix::zeros();
        let mut current_joint = usize::MAX;
        for k in 0..self.row_joint.len() {
            let (jidx, ridx) = self.row_joint[k];
            let jt = &model.joints()[jidx];
            let (pi, pj) = (jt.spec.body_i.pose(poses), jt.spec.body_j.pose(poses));
            let row = &jt.rows[ridx];
            let with_geometric = tangent == Some(Tangent::Full) && lambda[k] != 0.0;
            if with_geometric && jidx != current_joint {
                if current_joint != usize::MAX {
                    self.scatter_joint(model, current_joint, &geometric);
                }
                geometric.fill(0.0);
                current_joint = jidx;
            }
            // The constraint force applied to the bodies is −Jᵀλ, so its stiffness is +λ ∂(∇Φ)/∂q.
            let ev = if with_geometric {
                row.evaluate_with_force_derivative(&pi, &pj, t, lambda[k], &mut geometric)
            } else {
                row.evaluate(&pi, &pj, t)
            };
            self.phi[k] = ev.value;
            self.phi_rate[k] = -row.driver_rate;
            for (local, d) in pair_dofs(jt.spec.body_i, jt.spec.body_j).iter().enumerate() {
                if let Some(c) = *d {
                    let slot = self.j_col_ptr[c] + self.row_slots[k][local / BODY_DOFS] as usize;
                    self.j_values[slot] = ev.gradient[local];
                }
            }
        }
        if current_joint != usize::MAX {
            self.scatter_joint(model, current_joint, &geometric);
        }
    }

    /// Adds a joint's geometric stiffness `block` to `K`.
    fn scatter_joint(&mut self, model: &Model, joint: usize, block: &PairMatrix) {
        let spec = &model.joints()[joint].spec;
        let dofs = pair_dofs(spec.body_i, spec.body_j);
        scatter(&dofs, self.joint_blocks[joint], &self.k_col_ptr, block, &mut self.k_values, &mut self.k_skew);
    }

    /// `y ← Jᵀ λ` over the body coordinates.
    pub fn jt_times(&self, lambda: &[f64], y: &mut [f64]) {
        for c in 0..self.n {
            let mut s = 0.0;
            for p in self.j_col_ptr[c]..self.j_col_ptr[c + 1] {
                s += self.j_values[p] * lambda[self.j_row_idx[p]];
            }
            y[c] = s;
        }
    }

    /// `y ← S x` with the skew part of `K`; returns `max |S|` (0 when `K` is symmetric).
    pub fn skew_times(&self, x: &[f64], y: &mut [f64]) -> f64 {
        y.fill(0.0);
        let mut largest: f64 = 0.0;
        for c in 0..self.n {
            for p in self.k_col_ptr[c]..self.k_col_ptr[c + 1] {
                let (r, s) = (self.k_row_idx[p], self.k_skew[p]);
                if s != 0.0 {
                    largest = largest.max(s.abs());
                    y[r] += s * x[c];
                    y[c] -= s * x[r];
                }
            }
        }
        largest
    }
}

/// Element count from which the `parallel` feature evaluates elements on the rayon pool.
pub const PARALLEL_ELEMENTS: usize = 256;

/// Elements evaluated before their results are added in: an evaluation is 1.2 KB (mostly the 12×12
/// stiffness), so holding one per element of the model made it a third of the assembly's memory. One at a
/// time serially; with the `parallel` feature, chunks large enough to spread over the pool.
#[cfg(not(feature = "parallel"))]
const EVAL_CHUNK: usize = 1;
#[cfg(feature = "parallel")]
const EVAL_CHUNK: usize = 4 * PARALLEL_ELEMENTS;

#[cfg(test)]
mod tests {
    use super::*;
    use elastokin_core::{JointSpec, Mat3, Vec3};
    use elastokin_elements::{Bushing, Characteristic, CoilSpring, SpringLength};

    /// Five bodies, each on a bushing to the ground, with springs and joints between bodies that are not
    /// neighbours in either order, so that columns hold several off-diagonal blocks.
    fn tangle() -> Model {
        let mut m = Model::new();
        let b: Vec<BodyRef> = (0..5)
            .map(|i| m.add_body(&format!("b{i}"), Pose::at(Vec3::new(i as f64, 0.0, 0.0))).unwrap().into())
            .collect();
        let k = Vec3::new(1e5, 1e5, 1e5);
        for (i, &body) in b.iter().enumerate() {
            let at = Vec3::new(i as f64, 0.1, 0.0);
            m.add_element(
                Bushing::new(&format!("mount {i}"), BodyRef::Ground, body, at, Mat3::identity(), k, k).unwrap(),
            )
            .unwrap();
        }
        for (name, i, j) in [("s03", 0, 3), ("s41", 4, 1), ("s23", 2, 3)] {
            let (pi, pj) = (Vec3::new(i as f64, 0.0, 0.2), Vec3::new(j as f64, 0.1, -0.2));
            m.add_element(
                CoilSpring::seated(
                    name,
                    [(b[i], pi), (b[j], pj)],
                    Characteristic::Rate(1e4),
                    SpringLength::DesignForce(10.0),
                )
                .unwrap(),
            )
            .unwrap();
        }
        m.add_joint(JointSpec::spherical("ball 3-0", b[3], b[0], Vec3::new(1.5, 0.0, 0.0))).unwrap();
        let (p, q) = (Vec3::new(2.0, 0.3, 0.0), Vec3::new(4.0, 0.3, 0.1));
        m.add_joint(JointSpec::distance("link 2-4", b[2], b[4], p, q)).unwrap();
        m
    }

    /// Every slot an element or joint writes, worked out from the pattern's block layout, is where a search
    /// of the stored pattern finds that entry.
    #[test]
    fn pair_slots_from_the_block_layout_are_the_searched_slots() {
        let model = tangle();
        let a = Assembly::new(&model, (0..model.constraint_rows()).collect());
        let searched = |r: usize, c: usize| {
            let range = a.k_col_ptr[c]..a.k_col_ptr[c + 1];
            range.start + a.k_row_idx[range].binary_search(&r).expect("entry in the pattern")
        };
        let pairs = model.elements().iter().map(|e| e.bodies()).zip(&a.element_blocks);
        let pairs = pairs.chain(model.joints().iter().map(|j| [j.spec.body_i, j.spec.body_j]).zip(&a.joint_blocks));
        let mut checked = 0;
        for ([i, j], &block) in pairs {
            let dofs = pair_dofs(i, j);
            for gp in dofs.iter().flatten() {
                for gq in dofs.iter().flatten() {
                    let (r, c) = (*gp.min(gq), *gp.max(gq));
                    assert_eq!(k_slot(&a.k_col_ptr, block, r, c), searched(r, c), "({r}, {c})");
                    checked += 1;
                }
            }
        }
        // 5 bushings to the ground (36 entries each), 3 springs and 2 joints between bodies (144 each).
        assert_eq!(checked, 5 * 36 + 5 * 144);
    }

    /// Every row's position in its bodies' columns of `J` is where the pattern lists that row.
    #[test]
    fn row_slots_find_their_row_in_every_column() {
        let model = tangle();
        let a = Assembly::new(&model, (0..model.constraint_rows()).collect());
        assert_eq!(a.m(), 4);
        for (k, &(joint, _)) in a.row_joint.iter().enumerate() {
            let spec = &model.joints()[joint].spec;
            for (local, c) in pair_dofs(spec.body_i, spec.body_j).iter().enumerate() {
                let c = c.expect("both bodies are bodies");
                assert_eq!(a.j_row_idx[a.j_col_ptr[c] + a.row_slots[k][local / BODY_DOFS] as usize], k);
            }
        }
    }
}
