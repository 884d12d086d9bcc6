//! Constraint primitives (paper Table 1) as scalar rows `Φ = α (u · w) − c − ρ t`.
//!
//! Every joint row of elastokin is a dot product of two *kinematic vectors* of the two bodies `i`, `j`
//! it connects: a constant global vector, a body-fixed direction `h = A h'`, a body-fixed point
//! `P = r + A s'`, or the separation `d = Pⱼ − Pᵢ` of two body-fixed points. That one form covers the
//! primitives of paper Table 1 and every joint built from them:
//!
//! | primitive | row |
//! |---|---|
//! | spherical (3 rows) | `eₖ · d` for the global axes `eₖ` |
//! | distance | `(d·d − L²) / (2L)` (scaled so that λ is the link force in N) |
//! | in-plane | `hⱼ · d` |
//! | perpendicular | `hᵢ · hⱼ` |
//! | point driver | `e · Pⱼ − g₀ − ρ t` |
//!
//! Each kinematic vector `X` knows its value, its Jacobian `J_X = ∂X/∂(Δqᵢ, Δqⱼ)` (3×12) and, for a fixed
//! vector `c`, `D_X[c] = ∂(J_Xᵀ c)/∂Δq` (12×12). A row then has the gradient
//! `∇Φ = α (J_uᵀ w + J_wᵀ u)` and the derivative of its constraint force `λ ∇Φ`,
//! `λ α (J_uᵀ J_w + J_wᵀ J_u + D_u[w] + D_w[u])`. That matrix is the *consistent* tangent for the
//! left-increment coordinates `Δπ`: it is the derivative of the gradient along `A ← exp(Δπ̃)A`, which
//! differs from the symmetric second derivative of `Φ` by a skew part proportional to the gradient.
//! Newton needs the former; the solver factorizes its symmetric part and restores the skew part by
//! GMRES preconditioned with that factorization.
//!
//! Columns 0..6 belong to body `i` (`Δr`, `Δπ`), 6..12 to body `j`.

use crate::math::{skew, Mat3, Vec3};
use crate::pose::Pose;
use nalgebra::{SMatrix, SVector};

/// Gradient of one row with respect to the 12 coordinates of its two bodies.
pub type RowGradient = SVector<f64, 12>;
/// A 12×12 block over the coordinates of two bodies.
pub type PairMatrix = SMatrix<f64, 12, 12>;

/// Which of the two bodies of a joint a body-fixed quantity belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The first body (`i`).
    I,
    /// The second body (`j`).
    J,
}

/// A kinematic vector of a body pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum KinVec {
    /// A constant global vector.
    Constant(Vec3),
    /// A body-fixed direction (local components).
    Direction(Side, Vec3),
    /// A body-fixed point (local offset from the body's reference point).
    Point(Side, Vec3),
    /// `Pⱼ − Pᵢ` for body-fixed points with local offsets `on_i`, `on_j`.
    Separation {
        /// Local offset on body `i`.
        on_i: Vec3,
        /// Local offset on body `j`.
        on_j: Vec3,
    },
}

/// A kinematic vector evaluated at a configuration.
struct KinEval {
    value: Vec3,
    /// For each side, the global lever arm `s = A s'` (points) or the direction `h` (directions),
    /// with a sign: the π-columns of `J` are `−sign·s̃`.
    arm: [Option<(f64, Vec3)>; 2],
    /// Sign of the identity in the r-columns of each side (0 when the vector does not depend on `r`).
    translation: [f64; 2],
}

impl KinVec {
    fn eval(&self, pi: &Pose, pj: &Pose) -> KinEval {
        let pose = |s: Side| if s == Side::I { pi } else { pj };
        let idx = |s: Side| if s == Side::I { 0 } else { 1 };
        let mut e = KinEval { value: Vec3::zeros(), arm: [None, None], translation: [0.0, 0.0] };
        match *self {
            KinVec::Constant(c) => e.value = c,
            KinVec::Direction(side, h) => {
                let g = pose(side).direction(&h);
                e.value = g;
                e.arm[idx(side)] = Some((1.0, g));
            }
            KinVec::Point(side, s) => {
                let arm = pose(side).direction(&s);
                e.value = pose(side).position + arm;
                e.arm[idx(side)] = Some((1.0, arm));
                e.translation[idx(side)] = 1.0;
            }
            KinVec::Separation { on_i, on_j } => {
                let si = pi.direction(&on_i);
                let sj = pj.direction(&on_j);
                e.value = (pj.position + sj) - (pi.position + si);
                e.arm = [Some((-1.0, si)), Some((1.0, sj))];
                e.translation = [-1.0, 1.0];
            }
        }
        e
    }
}

impl KinEval {
    /// Block `b` of `J = ∂X/∂Δq` (3×12 in four 3×3 blocks: `Δrᵢ`, `Δπᵢ`, `Δrⱼ`, `Δπⱼ`): the
    /// translation's `t·I`, the rotation's `−sign·s̃`, or nothing.
    #[inline]
    fn block(&self, b: usize) -> JacobianBlock {
        let side = b / 2;
        if b.is_multiple_of(2) {
            let t = self.translation[side];
            if t == 0.0 {
                JacobianBlock::Zero
            } else {
                JacobianBlock::Identity(t)
            }
        } else {
            match self.arm[side] {
                Some((sign, arm)) => JacobianBlock::Matrix(-sign * skew(&arm)),
                None => JacobianBlock::Zero,
            }
        }
    }

    /// `D[c] = ∂(Jᵀ c)/∂Δq` for a fixed vector `c`: only π–π blocks, `sign · c̃ s̃`.
    fn add_d(&self, c: &Vec3, scale: f64, out: &mut PairMatrix) {
        for side in 0..2 {
            if let Some((sign, arm)) = self.arm[side] {
                let k = 6 * side + 3;
                let blk = skew(c) * skew(&arm) * (sign * scale);
                let mut v = out.fixed_view_mut::<3, 3>(k, k);
                v += blk;
            }
        }
    }
}

/// One 3×3 block of a kinematic vector's Jacobian: most are zero or a multiple of the identity, and a
/// row's products of them are formed block by block, not as 12×12 products of mostly zeros.
#[derive(Clone, Copy)]
enum JacobianBlock {
    Zero,
    Identity(f64),
    Matrix(Mat3),
}

impl JacobianBlock {
    /// `aᵀ b`, or `None` when it is zero.
    #[inline]
    fn transpose_times(a: JacobianBlock, b: JacobianBlock) -> Option<Mat3> {
        use JacobianBlock::*;
        match (a, b) {
            (Zero, _) | (_, Zero) => None,
            (Identity(s), Identity(t)) => Some(Mat3::identity() * (s * t)),
            (Identity(s), Matrix(m)) => Some(m * s),
            (Matrix(m), Identity(t)) => Some(m.transpose() * t),
            (Matrix(m), Matrix(n)) => Some(m.transpose() * n),
        }
    }

    /// `aᵀ v` added to `out`.
    #[inline]
    fn add_transpose_times(self, v: &Vec3, scale: f64, out: &mut [f64]) {
        let product = match self {
            JacobianBlock::Zero => return,
            JacobianBlock::Identity(t) => v * t,
            JacobianBlock::Matrix(m) => m.transpose() * v,
        };
        for k in 0..3 {
            out[k] += scale * product[k];
        }
    }
}

/// One scalar constraint row `Φ = α (u · w) − c − ρ t` of a joint or driver.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstraintRow {
    /// Short label used in diagnostics ("x", "axis ⊥ u", "travel").
    pub label: &'static str,
    /// First factor.
    pub u: KinVec,
    /// Second factor.
    pub w: KinVec,
    /// Scale α (1 except for distance rows).
    pub scale: f64,
    /// Constant c, chosen so that Φ = 0 at design.
    pub offset: f64,
    /// Rate ρ of a driver row with the load parameter t (0 for a plain constraint).
    pub driver_rate: f64,
}

/// Value, gradient and optionally the force-derivative of one row.
#[derive(Debug, Clone)]
pub struct RowEval {
    /// Φ.
    pub value: f64,
    /// ∇Φ over `[Δqᵢ, Δqⱼ]`.
    pub gradient: RowGradient,
}

impl ConstraintRow {
    /// A row with scale 1, offset 0 and no driver.
    pub fn new(label: &'static str, u: KinVec, w: KinVec) -> Self {
        ConstraintRow { label, u, w, scale: 1.0, offset: 0.0, driver_rate: 0.0 }
    }

    /// `Φ` at poses `pi`, `pj` and load parameter `t`.
    pub fn value(&self, pi: &Pose, pj: &Pose, t: f64) -> f64 {
        let u = self.u.eval(pi, pj).value;
        let w = self.w.eval(pi, pj).value;
        self.scale * u.dot(&w) - self.offset - self.driver_rate * t
    }

    /// Value and gradient.
    pub fn evaluate(&self, pi: &Pose, pj: &Pose, t: f64) -> RowEval {
        let u = self.u.eval(pi, pj);
        let w = self.w.eval(pi, pj);
        self.evaluation_of(&u, &w, t)
    }

    /// Value and gradient of the row whose kinematic vectors evaluate to `u` and `w`.
    fn evaluation_of(&self, u: &KinEval, w: &KinEval, t: f64) -> RowEval {
        RowEval {
            value: self.scale * u.value.dot(&w.value) - self.offset - self.driver_rate * t,
            gradient: self.gradient(u, w),
        }
    }

    /// `∇Φ = α (J_uᵀ w + J_wᵀ u)`, block by block.
    fn gradient(&self, u: &KinEval, w: &KinEval) -> RowGradient {
        let mut gradient = RowGradient::zeros();
        for b in 0..4 {
            let out = &mut gradient.as_mut_slice()[3 * b..3 * b + 3];
            u.block(b).add_transpose_times(&w.value, self.scale, out);
            w.block(b).add_transpose_times(&u.value, self.scale, out);
        }
        gradient
    }

    /// Value and gradient ([`ConstraintRow::evaluate`]), and `λ · ∂(∇Φ)/∂Δq` added to `out`
    /// ([`ConstraintRow::add_force_derivative`]), the kinematic vectors evaluated once for both.
    pub fn evaluate_with_force_derivative(
        &self,
        pi: &Pose,
        pj: &Pose,
        t: f64,
        lambda: f64,
        out: &mut PairMatrix,
    ) -> RowEval {
        let u = self.u.eval(pi, pj);
        let w = self.w.eval(pi, pj);
        self.add_derivative_of(&u, &w, lambda, out);
        self.evaluation_of(&u, &w, t)
    }

    /// Adds `λ · ∂(∇Φ)/∂Δq` (the geometric stiffness of the joint reaction λ) to `out`.
    pub fn add_force_derivative(&self, pi: &Pose, pj: &Pose, lambda: f64, out: &mut PairMatrix) {
        let u = self.u.eval(pi, pj);
        let w = self.w.eval(pi, pj);
        self.add_derivative_of(&u, &w, lambda, out);
    }

    /// `λ α (J_uᵀ J_w + J_wᵀ J_u + D_u[w] + D_w[u])` added to `out`, the products formed block by block
    /// where neither block is zero.
    fn add_derivative_of(&self, u: &KinEval, w: &KinEval, lambda: f64, out: &mut PairMatrix) {
        let s = lambda * self.scale;
        let (ub, wb) = ([0, 1, 2, 3].map(|b| u.block(b)), [0, 1, 2, 3].map(|b| w.block(b)));
        for a in 0..4 {
            for b in 0..4 {
                if let Some(c) = JacobianBlock::transpose_times(ub[a], wb[b]) {
                    let mut ab = out.fixed_view_mut::<3, 3>(3 * a, 3 * b);
                    ab += c * s;
                    let mut ba = out.fixed_view_mut::<3, 3>(3 * b, 3 * a);
                    ba += c.transpose() * s;
                }
            }
        }
        u.add_d(&w.value, s, out);
        w.add_d(&u.value, s, out);
    }

    /// True when this row moves with the load parameter.
    pub fn is_driver(&self) -> bool {
        self.driver_rate != 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::UnitQuaternion;

    fn perturbed(p: &Pose, dq: &[f64]) -> Pose {
        let mut q = *p;
        q.apply_increment6(dq);
        q
    }

    fn rows() -> Vec<ConstraintRow> {
        let a = Vec3::new(0.3, -0.1, 0.2);
        let b = Vec3::new(-0.2, 0.4, 0.1);
        let h = Vec3::new(0.6, 0.0, 0.8);
        let g = Vec3::new(0.0, 1.0, 0.0);
        vec![
            ConstraintRow::new(
                "sep·const",
                KinVec::Separation { on_i: a, on_j: b },
                KinVec::Constant(Vec3::new(0.2, 0.5, -1.0)),
            ),
            ConstraintRow::new("dir·sep", KinVec::Direction(Side::J, h), KinVec::Separation { on_i: a, on_j: b }),
            ConstraintRow::new("dir·sep(i)", KinVec::Direction(Side::I, g), KinVec::Separation { on_i: b, on_j: a }),
            ConstraintRow::new("dir·dir", KinVec::Direction(Side::I, h), KinVec::Direction(Side::J, g)),
            ConstraintRow::new(
                "sep·sep",
                KinVec::Separation { on_i: a, on_j: b },
                KinVec::Separation { on_i: a, on_j: b },
            ),
            ConstraintRow::new("point·const", KinVec::Point(Side::J, b), KinVec::Constant(Vec3::new(0.0, 0.0, 1.0))),
        ]
    }

    #[test]
    fn row_gradient_and_force_derivative_match_finite_differences() {
        let pi = Pose {
            position: Vec3::new(0.1, 0.2, -0.3),
            orientation: UnitQuaternion::from_euler_angles(0.4, -0.3, 0.9),
        };
        let pj = Pose {
            position: Vec3::new(-0.2, 0.5, 0.1),
            orientation: UnitQuaternion::from_euler_angles(-1.1, 0.2, 0.3),
        };
        let h = 1e-6;
        for row in rows() {
            let ev = row.evaluate(&pi, &pj, 0.0);
            let mut dgrad = PairMatrix::zeros();
            row.add_force_derivative(&pi, &pj, 1.0, &mut dgrad);
            // The assembly's one pass for both gives the same numbers as the two apart.
            let mut fused = PairMatrix::zeros();
            let both = row.evaluate_with_force_derivative(&pi, &pj, 0.0, 1.0, &mut fused);
            assert_eq!((both.value, both.gradient, fused), (ev.value, ev.gradient, dgrad), "{}", row.label);
            for c in 0..12 {
                let mut dq = [0.0; 12];
                dq[c] = h;
                let mut dm = [0.0; 12];
                dm[c] = -h;
                let (ip, jp) = (perturbed(&pi, &dq[0..6]), perturbed(&pj, &dq[6..12]));
                let (im, jm) = (perturbed(&pi, &dm[0..6]), perturbed(&pj, &dm[6..12]));
                let fd = (row.value(&ip, &jp, 0.0) - row.value(&im, &jm, 0.0)) / (2.0 * h);
                assert!((fd - ev.gradient[c]).abs() < 1e-8, "{} col {c}: fd {fd} vs {}", row.label, ev.gradient[c]);
                let gfd = (row.evaluate(&ip, &jp, 0.0).gradient - row.evaluate(&im, &jm, 0.0).gradient) / (2.0 * h);
                for r in 0..12 {
                    assert!(
                        (gfd[r] - dgrad[(r, c)]).abs() < 1e-7,
                        "{} ({r},{c}): fd {} vs {}",
                        row.label,
                        gfd[r],
                        dgrad[(r, c)]
                    );
                }
            }
        }
    }
}
