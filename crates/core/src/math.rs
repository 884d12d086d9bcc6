//! Small 3-D rotation algebra used everywhere: skew matrices, the exponential and logarithm of SO(3),
//! and the left Jacobian of SO(3) with its inverse and derivative.
//!
//! Conventions: `skew(a) * b == a.cross(&b)`; rotation vectors are in radians; a rotation increment
//! `Δπ` acts on the left, `A ← exp(Δπ̃) A` (paper eq. 1 with the exact exponential).

use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

/// A 3-vector in metres, newtons, radians or whatever the context says (SI throughout).
pub type Vec3 = Vector3<f64>;
/// A 3×3 matrix.
pub type Mat3 = Matrix3<f64>;

/// The skew-symmetric (cross-product) matrix: `skew(a) * b == a × b`.
#[inline]
pub fn skew(a: &Vec3) -> Mat3 {
    Mat3::new(0.0, -a.z, a.y, a.z, 0.0, -a.x, -a.y, a.x, 0.0)
}

/// Unit quaternion of the rotation vector `phi` (exact exponential map).
#[inline]
pub fn quat_exp(phi: &Vec3) -> UnitQuaternion<f64> {
    UnitQuaternion::from_scaled_axis(*phi)
}

/// Rotation vector of a rotation matrix, |θ| ≤ π (logarithm of SO(3)), accurate down to tiny angles.
#[inline]
pub fn rotation_log(r: &Mat3) -> Vec3 {
    quat_log(&UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(*r)))
}

/// Rotation vector of a unit quaternion, |θ| ≤ π. Uses `2·atan2(|v|, w)`, which keeps full relative
/// precision at small angles (the trace or `acos(w)` forms lose it below about 1e-4 rad).
#[inline]
pub fn quat_log(q: &UnitQuaternion<f64>) -> Vec3 {
    let (mut w, mut v) = (q.w, q.imag());
    if w < 0.0 {
        w = -w;
        v = -v;
    }
    let s = v.norm();
    if s < 1e-300 {
        return Vec3::zeros();
    }
    // Axis v/|v| times angle 2·atan2(|v|, w); both are unchanged by a small error in |q|.
    v * (2.0 * s.atan2(w) / s)
}

/// `β(t) = (1 − (t/2)·cot(t/2)) / t²` and `β'(t)/t`, the scalar functions of the inverse left
/// Jacobian of SO(3), with series near zero where the closed form loses digits.
#[inline]
fn beta_and_dbeta_over_t(t: f64) -> (f64, f64) {
    if t < 0.1 {
        beta_series(t)
    } else {
        beta_closed_form(t)
    }
}

/// Taylor series of β and β'/t; truncation error below 1e-18 for t < 0.1.
#[inline]
fn beta_series(t: f64) -> (f64, f64) {
    let t2 = t * t;
    (
        1.0 / 12.0 + t2 / 720.0 + t2 * t2 / 30240.0 + t2 * t2 * t2 / 1209600.0,
        1.0 / 360.0 + t2 / 7560.0 + t2 * t2 / 201600.0 + t2 * t2 * t2 / 5987520.0,
    )
}

#[inline]
fn beta_closed_form(t: f64) -> (f64, f64) {
    let h = 0.5 * t;
    let cot = h.cos() / h.sin();
    let c = h * cot;
    let dc = 0.5 * cot - 0.25 * t / (h.sin() * h.sin());
    let beta = (1.0 - c) / (t * t);
    let dbeta = -dc / (t * t) - 2.0 * (1.0 - c) / (t * t * t);
    (beta, dbeta / t)
}

/// Body-fixed x-y-z (Tait-Bryan) angles `φ = (a, b, c)` of `R = Rx(a) Ry(b) Rz(c)`, with `b` in
/// `[−π/2, π/2]`. Singular (gimbal lock) at `|b| = π/2`.
pub fn tait_bryan_xyz(r: &Mat3) -> Vec3 {
    let b = r[(0, 2)].clamp(-1.0, 1.0).asin();
    let a = (-r[(1, 2)]).atan2(r[(2, 2)]);
    let c = (-r[(0, 1)]).atan2(r[(0, 0)]);
    Vec3::new(a, b, c)
}

/// `E(φ)` with `ω = E(φ) φ̇` for `R = Rx(a) Ry(b) Rz(c)` and `ω` the left (parent-frame) angular velocity,
/// `Ṙ Rᵀ = ω̃`: its columns are the three gimbal axes `x`, `Rx(a) y`, `Rx(a) Ry(b) z`. Also its derivatives
/// with respect to `a` and `b` (it does not depend on `c`).
pub fn tait_bryan_xyz_axes(phi: &Vec3) -> (Mat3, Mat3, Mat3) {
    let (sa, ca) = phi.x.sin_cos();
    let (sb, cb) = phi.y.sin_cos();
    let e = Mat3::new(1.0, 0.0, sb, 0.0, ca, -sa * cb, 0.0, sa, ca * cb);
    let de_da = Mat3::new(0.0, 0.0, 0.0, 0.0, -sa, -ca * cb, 0.0, ca, -sa * cb);
    let de_db = Mat3::new(0.0, 0.0, cb, 0.0, 0.0, sa * sb, 0.0, 0.0, -ca * sb);
    (e, de_da, de_db)
}

/// Inverse of the left Jacobian of SO(3): `δθ = J_l(θ)⁻¹ ω` for a left perturbation
/// `exp(ω̃) exp(θ̃)` of a rotation with rotation vector θ.
pub fn left_jacobian_inv(theta: &Vec3) -> Mat3 {
    let (beta, _) = beta_and_dbeta_over_t(theta.norm());
    let th = skew(theta);
    Mat3::identity() - 0.5 * th + beta * th * th
}

/// The rotation-vector law of a torsion spring: for an energy whose derivative with respect to the
/// rotation vector θ of a relative rotation is `m(θ)` (for a linear bushing with preload,
/// `m = K θ − M_pre`, `dm = ∂m/∂θ = K`), returns the moment conjugate to a left rotation increment,
/// `g = J_l(θ)⁻ᵀ m`, and its derivative `∂g/∂θ`. With `J_l⁻ᵀ = I + ½θ̃ + βθ̃²`,
/// `g = m + ½ θ×m + β θ×(θ×m)`, each product differentiated, and `∂β/∂θ = (β'/t) θᵀ`.
pub fn rotation_vector_moment(theta: &Vec3, m: &Vec3, dm: &Mat3) -> (Vec3, Mat3) {
    let t = theta.norm();
    let (beta, dbeta_t) = beta_and_dbeta_over_t(t);
    let th = skew(theta);
    let k = dm;
    let p = theta.cross(m);
    let tp = theta.cross(&p);
    // J_l⁻ᵀ = I + ½θ̃ + βθ̃²  (θ̃ is skew, so the transpose flips the odd term)
    let g = m + 0.5 * p + beta * tp;
    let dp = -skew(m) + th * k;
    let dtp = -skew(&p) + th * dp;
    let dg = k + 0.5 * dp + beta * dtp + tp * (dbeta_t * theta.transpose());
    (g, dg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotation_vector_moment_derivative_matches_finite_difference() {
        let k = Mat3::new(3.0, 0.2, 0.1, 0.2, 2.0, -0.3, 0.1, -0.3, 5.0);
        for theta in [
            Vec3::new(0.3, -0.7, 1.1),
            Vec3::new(1e-3, 2e-3, -1e-3),
            Vec3::new(0.099, 0.001, 0.0),
            Vec3::new(0.0, 0.0, 0.0),
        ] {
            let (_, dg) = rotation_vector_moment(&theta, &(k * theta), &k);
            let h = 1e-6;
            for c in 0..3 {
                let mut tp = theta;
                let mut tm = theta;
                tp[c] += h;
                tm[c] -= h;
                let fd = (rotation_vector_moment(&tp, &(k * tp), &k).0 - rotation_vector_moment(&tm, &(k * tm), &k).0)
                    / (2.0 * h);
                for r in 0..3 {
                    assert!((fd[r] - dg[(r, c)]).abs() < 1e-7, "θ={theta:?} ({r},{c}): fd {} vs {}", fd[r], dg[(r, c)]);
                }
            }
        }
    }

    #[test]
    fn inverse_left_jacobian_maps_left_perturbation_to_rotation_vector_change() {
        let theta = Vec3::new(0.4, 1.2, -0.5);
        let omega = Vec3::new(1e-7, -2e-7, 0.5e-7);
        let r = quat_exp(&theta).to_rotation_matrix().into_inner();
        let rp = quat_exp(&omega).to_rotation_matrix().into_inner() * r;
        let d = rotation_log(&rp) - theta;
        let pred = left_jacobian_inv(&theta) * omega;
        assert!((d - pred).norm() < 1e-13, "{d:?} vs {pred:?}");
    }

    #[test]
    fn rotation_log_keeps_precision_at_tiny_angles() {
        for angle in [1e-12, 1e-9, 1e-7, 1e-5, 0.3, 3.0] {
            let theta = Vec3::new(0.6, -0.48, 0.64) * angle;
            let r = quat_exp(&theta).to_rotation_matrix().into_inner();
            let back = rotation_log(&r);
            assert!((back - theta).norm() <= 1e-10 * angle, "{angle}: {back:?} vs {theta:?}");
        }
    }

    #[test]
    fn beta_series_meets_closed_form() {
        let (a, da) = beta_series(0.1);
        let (b, db) = beta_closed_form(0.1);
        assert!((a - b).abs() < 1e-13 && (da - db).abs() < 1e-11, "{a} {b} {da} {db}");
    }
}
