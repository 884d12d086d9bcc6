//! KKT assembly with a fixed sparsity pattern and an in-place slot map.
//!
//! The pattern is found once per model from what the scene contains: a dense 6×6 block on the diagonal
//! of every body, an off-diagonal block for every pair of bodies that an element or a joint couples
//! (a joint couples its bodies through the geometric stiffness of its reaction), and in `J` the 12
//! coordinates of the two bodies of every active constraint row. Each element, joint and row keeps a
//! list of slots into the value arrays, so re-assembly at a new configuration writes values in place
//! and allocates nothing.
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
fn pair_dofs(i: BodyRef, j: BodyRef) -> [Option<usize>; 12] {
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

/// Where a 12×12 pair block lands in the upper-triangular value array.
#[derive(Debug, Clone, Default)]
struct PairSlots {
    /// `(local index p·12+q, slot, weight, skew weight)`: weight ½ off the diagonal (symmetrisation), 1 on
    /// it; skew weight +½ when the entry lands above the diagonal, −½ below, 0 on it.
    entries: Vec<(u16, u32, f64, f64)>,
}

impl PairSlots {
    /// Adds the symmetric part of `block` to `values` and its skew part to `skew` (both upper triangles).
    #[inline]
    fn scatter(&self, block: &PairMatrix, values: &mut [f64], skew: &mut [f64]) {
        let data = block.as_slice(); // column-major: index = q*12 + p
        for &(local, slot, weight, skew_weight) in &self.entries {
            let (p, q) = (local as usize / 12, local as usize % 12);
            let v = data[q * 12 + p];
            values[slot as usize] += weight * v;
            skew[slot as usize] += skew_weight * v;
        }
    }
}

/// Sparsity pattern, slot maps and value arrays of one model's KKT system.
#[derive(Debug)]
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
    element_slots: Vec<PairSlots>,
    joint_slots: Vec<PairSlots>,
    /// For each active row, the slot in `j_values` of each of its 12 local coordinates.
    row_slots: Vec<[u32; 12]>,
    /// Which joint and row within it each active row is.
    row_joint: Vec<(usize, usize)>,
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
    /// `Φ` of the active rows.
    pub phi: Vec<f64>,
    /// `∂Φ/∂t` of the active rows (minus the driver rates).
    pub phi_rate: Vec<f64>,
    evals: Vec<ElementEval>,
}

const NO_SLOT: u32 = u32::MAX;

impl Assembly {
    /// Analyses the pattern of `model` with the given active constraint rows (model row numbering).
    pub fn new(model: &Model, active_rows: Vec<usize>) -> Self {
        let n = model.dofs();
        let nb = model.bodies().len();
        // Body-pair coupling (a < b) in the upper triangle.
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
        // Column structure of the upper triangle: for body column block b, the row blocks a ≤ b coupled to it.
        let mut col_blocks: Vec<Vec<usize>> = (0..nb).map(|b| vec![b]).collect();
        for &(a, b) in &couplings {
            col_blocks[b].push(a);
        }
        for blocks in &mut col_blocks {
            blocks.sort_unstable();
        }
        let mut k_col_ptr = Vec::with_capacity(n + 1);
        let mut k_row_idx = Vec::new();
        k_col_ptr.push(0);
        for b in 0..nb {
            for cl in 0..BODY_DOFS {
                let col = b * BODY_DOFS + cl;
                for &a in &col_blocks[b] {
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
        let k_slot = |row: usize, col: usize| -> u32 {
            let (r, c) = if row <= col { (row, col) } else { (col, row) };
            let range = k_col_ptr[c]..k_col_ptr[c + 1];
            let pos = k_row_idx[range.clone()].binary_search(&r).expect("pattern holds every coupled pair");
            (range.start + pos) as u32
        };
        let pair_slots = |i: BodyRef, j: BodyRef| -> PairSlots {
            let dofs = pair_dofs(i, j);
            let mut entries = Vec::new();
            for p in 0..12 {
                for q in 0..12 {
                    if let (Some(gp), Some(gq)) = (dofs[p], dofs[q]) {
                        let (weight, skew_weight) = match gp.cmp(&gq) {
                            std::cmp::Ordering::Equal => (1.0, 0.0),
                            std::cmp::Ordering::Less => (0.5, 0.5),
                            std::cmp::Ordering::Greater => (0.5, -0.5),
                        };
                        entries.push(((p * 12 + q) as u16, k_slot(gp, gq), weight, skew_weight));
                    }
                }
            }
            PairSlots { entries }
        };
        let element_slots = model.elements().iter().map(|e| {
            let [i, j] = e.bodies();
            pair_slots(i, j)
        });
        let element_slots: Vec<PairSlots> = element_slots.collect();
        let joint_slots: Vec<PairSlots> =
            model.joints().iter().map(|jt| pair_slots(jt.spec.body_i, jt.spec.body_j)).collect();

        // J: triplets (row, col) of the active rows, then CSC.
        let mut row_joint = Vec::with_capacity(active_rows.len());
        let mut row_dofs = Vec::with_capacity(active_rows.len());
        for &r in &active_rows {
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
        let mut j_col_ptr = vec![0usize; n + 1];
        for c in 0..n {
            j_col_ptr[c + 1] = j_col_ptr[c] + counts[c];
        }
        let mut fill = j_col_ptr[..n].to_vec();
        let mut j_row_idx = vec![0usize; j_col_ptr[n]];
        let mut row_slots = vec![[NO_SLOT; 12]; active_rows.len()];
        // Rows are visited in increasing order, so each column's row list comes out sorted.
        for (k, dofs) in row_dofs.iter().enumerate() {
            for (local, d) in dofs.iter().enumerate() {
                if let Some(c) = *d {
                    j_row_idx[fill[c]] = k;
                    row_slots[k][local] = fill[c] as u32;
                    fill[c] += 1;
                }
            }
        }
        let m = active_rows.len();
        let nnz_k = k_row_idx.len();
        let nnz_j = j_row_idx.len();
        Assembly {
            n,
            active_rows,
            k_col_ptr,
            k_row_idx,
            j_col_ptr,
            j_row_idx,
            element_slots,
            joint_slots,
            row_slots,
            row_joint,
            k_values: vec![0.0; nnz_k],
            k_skew: vec![0.0; nnz_k],
            has_skew: false,
            j_values: vec![0.0; nnz_j],
            applied: vec![0.0; n],
            load_rate: vec![0.0; n],
            force_scale: 0.0,
            phi: vec![0.0; m],
            phi_rate: vec![0.0; m],
            evals: vec![ElementEval::default(); model.elements().len()],
        }
    }

    /// Number of active constraint rows.
    pub fn m(&self) -> usize {
        self.active_rows.len()
    }

    /// The sparsity pattern of the KKT system this assembly fills, for [`KktFactor::analyze`].
    ///
    /// [`KktFactor::analyze`]: crate::kkt_factor::KktFactor::analyze
    pub fn kkt_pattern(&self) -> crate::kkt_factor::KktPattern {
        crate::kkt_factor::KktPattern {
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
        let elements = model.elements();
        let eval_one = |e: &dyn elastokin_core::ForceElement, out: &mut ElementEval| {
            let [i, j] = e.bodies();
            e.evaluate(&i.pose(poses), &j.pose(poses), t, out, with_k);
        };
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            if elements.len() >= PARALLEL_ELEMENTS {
                self.evals.par_iter_mut().zip(elements.par_iter()).for_each(|(out, e)| eval_one(e.as_ref(), out));
            } else {
                self.evals.iter_mut().zip(elements.iter()).for_each(|(out, e)| eval_one(e.as_ref(), out));
            }
        }
        #[cfg(not(feature = "parallel"))]
        self.evals.iter_mut().zip(elements.iter()).for_each(|(out, e)| eval_one(e.as_ref(), out));

        let mut rate = RowGradient::zeros();
        self.force_scale = 0.0;
        for (k, e) in elements.iter().enumerate() {
            let [i, j] = e.bodies();
            let dofs = pair_dofs(i, j);
            let ev = &self.evals[k];
            self.force_scale = self.force_scale.max(ev.force.abs().max());
            for (local, d) in dofs.iter().enumerate() {
                if let Some(g) = d {
                    self.applied[*g] += ev.force[local];
                }
            }
            if e.role() == ElementRole::Load {
                e.load_rate(&i.pose(poses), &j.pose(poses), t, &mut rate);
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
                self.element_slots[k].scatter(&ev.stiffness, &mut self.k_values, &mut self.k_skew);
            }
        }

        // Constraint rows: Φ, J and (Full) the geometric stiffness Σ λ ∂(∇Φ)/∂q per joint.
        let mut geometric = PairMatrix::zeros();
        let mut current_joint = usize::MAX;
        for (k, &(jidx, ridx)) in self.row_joint.iter().enumerate() {
            let jt = &model.joints()[jidx];
            let (pi, pj) = (jt.spec.body_i.pose(poses), jt.spec.body_j.pose(poses));
            let row = &jt.rows[ridx];
            let ev = row.evaluate(&pi, &pj, t);
            self.phi[k] = ev.value;
            self.phi_rate[k] = -row.driver_rate;
            for local in 0..12 {
                let s = self.row_slots[k][local];
                if s != NO_SLOT {
                    self.j_values[s as usize] = ev.gradient[local];
                }
            }
            if tangent == Some(Tangent::Full) && lambda[k] != 0.0 {
                if jidx != current_joint {
                    if current_joint != usize::MAX {
                        self.joint_slots[current_joint].scatter(&geometric, &mut self.k_values, &mut self.k_skew);
                    }
                    geometric.fill(0.0);
                    current_joint = jidx;
                }
                // The constraint force applied to the bodies is −Jᵀλ, so its stiffness is +λ ∂(∇Φ)/∂q.
                row.add_force_derivative(&pi, &pj, lambda[k], &mut geometric);
            }
        }
        if current_joint != usize::MAX {
            self.joint_slots[current_joint].scatter(&geometric, &mut self.k_values, &mut self.k_skew);
        }
        if with_k {
            self.has_skew = self.k_skew.iter().any(|&v| v != 0.0);
        }
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
