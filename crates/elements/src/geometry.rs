//! Validation of design data and small block helpers shared by the elements.

use elastokin_core::{BodyRef, Mat3, ModelError, PairMatrix, Vec3};
use nalgebra::SMatrix;

/// A 3×12 Jacobian of a 3-vector over the coordinates `(Δrᵢ, Δπᵢ, Δrⱼ, Δπⱼ)`.
pub(crate) type Jac3 = SMatrix<f64, 3, 12>;

/// Every component finite, else [`ModelError::NonFinite`].
pub(crate) fn check_finite(item: &str, what: &'static str, v: &Vec3) -> Result<(), ModelError> {
    if v.iter().all(|c| c.is_finite()) {
        Ok(())
    } else {
        Err(ModelError::NonFinite { item: item.to_string(), what })
    }
}

/// A finite, strictly positive scalar, else [`ModelError::NonFinite`] / [`ModelError::NotPositive`].
pub(crate) fn check_positive(item: &str, what: &'static str, value: f64) -> Result<(), ModelError> {
    if !value.is_finite() {
        return Err(ModelError::NonFinite { item: item.to_string(), what });
    }
    if value <= 0.0 {
        return Err(ModelError::NotPositive { item: item.to_string(), what, value });
    }
    Ok(())
}

/// A finite scalar, else [`ModelError::NonFinite`].
pub(crate) fn check_finite_scalar(item: &str, what: &'static str, value: f64) -> Result<(), ModelError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(ModelError::NonFinite { item: item.to_string(), what })
    }
}

/// The two bodies of a two-body element must differ ([`ModelError::SelfJoint`] names the element).
pub(crate) fn check_distinct(item: &str, i: BodyRef, j: BodyRef) -> Result<(), ModelError> {
    if i == j {
        Err(ModelError::SelfJoint { joint: item.to_string() })
    } else {
        Ok(())
    }
}

/// Adds `m` to the 3×3 block of `out` at block row `r`, block column `c` (block indices 0..4).
#[inline]
pub(crate) fn add_block(out: &mut PairMatrix, r: usize, c: usize, m: &Mat3) {
    let mut v = out.fixed_view_mut::<3, 3>(3 * r, 3 * c);
    v += m;
}

/// Adds the 3×12 rows `m` to block row `r` of `out`.
#[inline]
pub(crate) fn add_rows(out: &mut PairMatrix, r: usize, m: &Jac3) {
    let mut v = out.fixed_view_mut::<3, 12>(3 * r, 0);
    v += m;
}

/// Sets the 3×3 block `c` (0..4) of a 3×12 Jacobian.
#[inline]
pub(crate) fn set_jac_block(jac: &mut Jac3, c: usize, m: &Mat3) {
    jac.fixed_view_mut::<3, 3>(0, 3 * c).copy_from(m);
}
