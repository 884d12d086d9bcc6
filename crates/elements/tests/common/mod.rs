//! Test helpers: a small deterministic RNG, random poses and rotations, central differences along the
//! exact left increments of `Pose::apply_increment6`, and block-wise comparisons.
#![allow(dead_code, reason = "each test file uses the helpers it needs")]

use elastokin_core::math::quat_exp;
use elastokin_core::{BodyId, BodyRef, ElementEval, ForceElement, Mat3, PairMatrix, Pose, RowGradient, Vec3};
use nalgebra::UnitQuaternion;

/// SplitMix64: deterministic, dependency-free.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [lo, hi).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next_u64() >> 11) as f64 / (1u64 << 53) as f64)
    }
    pub fn vec(&mut self, half: f64) -> Vec3 {
        Vec3::new(self.uniform(-half, half), self.uniform(-half, half), self.uniform(-half, half))
    }
    /// A random unit vector.
    pub fn unit(&mut self) -> Vec3 {
        loop {
            let v = self.vec(1.0);
            let n = v.norm();
            if n > 0.1 && n <= 1.0 {
                return v / n;
            }
        }
    }
    /// A rotation vector with norm uniform in [lo, hi].
    pub fn rotvec(&mut self, lo: f64, hi: f64) -> Vec3 {
        self.unit() * self.uniform(lo, hi)
    }
    /// An arbitrary orientation.
    pub fn orientation(&mut self) -> UnitQuaternion<f64> {
        quat_exp(&self.rotvec(0.0, 3.0))
    }
    pub fn pose(&mut self, half: f64) -> Pose {
        Pose { position: self.vec(half), orientation: self.orientation() }
    }
}

/// The ground, or body `id` when `grounded` is false.
pub fn body(grounded: bool, id: usize) -> BodyRef {
    if grounded {
        BodyRef::Ground
    } else {
        BodyRef::Body(BodyId(id))
    }
}

/// `exp(ω̃)` as a matrix.
pub fn rot(omega: &Vec3) -> Mat3 {
    quat_exp(omega).to_rotation_matrix().into_inner()
}

/// `pose` moved by `dq` (12 coordinates, the 6 of `side` 0 = i, 1 = j).
pub fn perturbed(pi: &Pose, pj: &Pose, c: usize, h: f64) -> (Pose, Pose) {
    let mut dq = [0.0; 12];
    dq[c] = h;
    let (mut a, mut b) = (*pi, *pj);
    a.apply_increment6(&dq[0..6]);
    b.apply_increment6(&dq[6..12]);
    (a, b)
}

pub const H: f64 = 1e-6;

/// Central difference of a scalar function of the two poses along every coordinate.
pub fn fd_scalar(pi: &Pose, pj: &Pose, f: impl Fn(&Pose, &Pose) -> f64) -> RowGradient {
    let mut g = RowGradient::zeros();
    for c in 0..12 {
        let (ap, bp) = perturbed(pi, pj, c, H);
        let (am, bm) = perturbed(pi, pj, c, -H);
        g[c] = (f(&ap, &bp) - f(&am, &bm)) / (2.0 * H);
    }
    g
}

/// Generalized force of an element.
pub fn force(e: &dyn ForceElement, pi: &Pose, pj: &Pose, t: f64) -> RowGradient {
    let mut out = ElementEval::default();
    e.evaluate(pi, pj, t, &mut out, false);
    out.force
}

/// Force and stiffness of an element.
pub fn eval(e: &dyn ForceElement, pi: &Pose, pj: &Pose, t: f64) -> ElementEval {
    let mut out = ElementEval::default();
    e.evaluate(pi, pj, t, &mut out, true);
    out
}

/// `−∂Q/∂Δq` by central differences along the exact increments.
pub fn fd_stiffness(e: &dyn ForceElement, pi: &Pose, pj: &Pose, t: f64) -> PairMatrix {
    let mut k = PairMatrix::zeros();
    for c in 0..12 {
        let (ap, bp) = perturbed(pi, pj, c, H);
        let (am, bm) = perturbed(pi, pj, c, -H);
        let col = -(force(e, &ap, &bp, t) - force(e, &am, &bm, t)) / (2.0 * H);
        k.set_column(c, &col);
    }
    k
}

/// Block-wise relative comparison of two 12-vectors: each 3-block within `rel` of its own size, with a
/// floor of `1e-4` of the largest entry (finite-difference noise).
pub fn assert_vec_close(what: &str, a: &RowGradient, b: &RowGradient, rel: f64) {
    let (err, blk) = worst_vec_block(a, b);
    assert!(
        err <= rel,
        "{what}: block {blk}: {:?} vs {:?} (relative error {err:e})",
        a.fixed_rows::<3>(3 * blk),
        b.fixed_rows::<3>(3 * blk)
    );
}

/// The figure [`assert_vec_close`] judges: the largest block-wise relative difference.
pub fn vec_close_error(a: &RowGradient, b: &RowGradient) -> f64 {
    worst_vec_block(a, b).0
}

/// Largest `|x − y|∞ / max(|x|∞, |y|∞, floor)` over the 3-blocks, and where.
fn worst_vec_block(a: &RowGradient, b: &RowGradient) -> (f64, usize) {
    let floor = 1e-4 * a.amax().max(b.amax()).max(1e-300);
    let mut worst = (0.0, 0);
    for blk in 0..4 {
        let x = a.fixed_rows::<3>(3 * blk);
        let y = b.fixed_rows::<3>(3 * blk);
        let err = (x - y).amax() / x.amax().max(y.amax()).max(floor);
        if err.is_nan() {
            return (f64::NAN, blk);
        }
        if err > worst.0 {
            worst = (err, blk);
        }
    }
    worst
}

/// Block-wise relative comparison of two 12×12 matrices (3×3 blocks, same floor as above).
pub fn assert_mat_close(what: &str, a: &PairMatrix, b: &PairMatrix, rel: f64) {
    let (err, r, c) = worst_block(a, b);
    assert!(
        err <= rel,
        "{what}: block ({r},{c}): {} vs {} (relative error {err:e})",
        a.fixed_view::<3, 3>(3 * r, 3 * c),
        b.fixed_view::<3, 3>(3 * r, 3 * c)
    );
}

/// The figure [`assert_mat_close`] judges: the largest block-wise relative difference (the measured
/// agreement a tolerance is set from).
pub fn mat_close_error(a: &PairMatrix, b: &PairMatrix) -> f64 {
    worst_block(a, b).0
}

/// Largest `|x − y|∞ / max(|x|∞, |y|∞, floor)` over the 3×3 blocks, and where.
fn worst_block(a: &PairMatrix, b: &PairMatrix) -> (f64, usize, usize) {
    let floor = 1e-4 * a.amax().max(b.amax()).max(1e-300);
    let mut worst = (0.0, 0, 0);
    for r in 0..4 {
        for c in 0..4 {
            let x = a.fixed_view::<3, 3>(3 * r, 3 * c);
            let y = b.fixed_view::<3, 3>(3 * r, 3 * c);
            let err = (x - y).amax() / x.amax().max(y.amax()).max(floor);
            if err.is_nan() {
                return (f64::NAN, r, c);
            }
            if err > worst.0 {
                worst = (err, r, c);
            }
        }
    }
    worst
}

/// `K − Kᵀ` predicted for a left-increment tangent: `diag(0, [Q_πᵢ]~, 0, [Q_πⱼ]~)`.
pub fn expected_skew_part(q: &RowGradient) -> PairMatrix {
    let mut m = PairMatrix::zeros();
    for side in [3usize, 9] {
        let v = Vec3::new(q[side], q[side + 1], q[side + 2]);
        m.fixed_view_mut::<3, 3>(side, side).copy_from(&elastokin_core::skew(&v));
    }
    m
}

/// Net force and net moment about the origin of a generalized force acting on bodies at `pi`, `pj`.
pub fn resultant(q: &RowGradient, pi: &Pose, pj: &Pose) -> (Vec3, Vec3) {
    let f_i = Vec3::new(q[0], q[1], q[2]);
    let m_i = Vec3::new(q[3], q[4], q[5]);
    let f_j = Vec3::new(q[6], q[7], q[8]);
    let m_j = Vec3::new(q[9], q[10], q[11]);
    (f_i + f_j, pi.position.cross(&f_i) + m_i + pj.position.cross(&f_j) + m_j)
}
