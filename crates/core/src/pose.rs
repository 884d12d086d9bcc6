//! Body poses and the small-motion coordinates of paper eq. 1.
//!
//! A moving body `i` has a pose `(rᵢ, Aᵢ)`: the position of its reference point and its orientation,
//! stored as a unit quaternion. A small motion is `Δqᵢ = (Δrᵢ, Δπᵢ) ∈ ℝ⁶`, with `Δπᵢ` a small rotation
//! about global axes. The update is exact: `rᵢ += Δrᵢ`, `Aᵢ ← exp(Δπ̃ᵢ) Aᵢ`, then renormalised.
//! A body-fixed point `s'` sits at `P = r + A s'` and moves by `ΔP = Δr − s̃ Δπ`.

use crate::math::{quat_exp, Mat3, Vec3};
use nalgebra::UnitQuaternion;

/// Number of small-motion coordinates of one body: `(Δx, Δy, Δz, Δπx, Δπy, Δπz)`.
pub const BODY_DOFS: usize = 6;

/// Position and orientation of a rigid body in the global (ISO 8855) frame.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Pose {
    /// Position of the body's reference point, metres.
    pub position: Vec3,
    /// Orientation: maps body-fixed vectors to global ones.
    pub orientation: UnitQuaternion<f64>,
}

impl Default for Pose {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Pose {
    /// The ground pose: origin, no rotation.
    pub const IDENTITY: Pose = Pose {
        position: Vec3::new(0.0, 0.0, 0.0),
        orientation: UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(1.0, 0.0, 0.0, 0.0)),
    };

    /// A pose at `position` with the global orientation.
    pub fn at(position: Vec3) -> Self {
        Pose { position, orientation: UnitQuaternion::identity() }
    }

    /// Rotation matrix `A`.
    #[inline]
    pub fn rotation(&self) -> Mat3 {
        self.orientation.to_rotation_matrix().into_inner()
    }

    /// Global position of a body-fixed point with local offset `local`.
    #[inline]
    pub fn point(&self, local: &Vec3) -> Vec3 {
        self.position + self.orientation * local
    }

    /// Global direction of a body-fixed vector.
    #[inline]
    pub fn direction(&self, local: &Vec3) -> Vec3 {
        self.orientation * local
    }

    /// Body-fixed offset of a global point.
    #[inline]
    pub fn to_local_point(&self, global: &Vec3) -> Vec3 {
        self.orientation.inverse() * (global - self.position)
    }

    /// Body-fixed components of a global direction.
    #[inline]
    pub fn to_local_direction(&self, global: &Vec3) -> Vec3 {
        self.orientation.inverse() * global
    }

    /// Applies a small motion `(Δr, Δπ)` exactly: `r += Δr`, `A ← exp(Δπ̃) A`, renormalised.
    pub fn apply_increment(&mut self, dr: &Vec3, dpi: &Vec3) {
        self.position += dr;
        let q = quat_exp(dpi) * self.orientation;
        self.orientation = UnitQuaternion::new_normalize(q.into_inner());
    }

    /// Applies the 6-vector `[Δr, Δπ]`.
    pub fn apply_increment6(&mut self, dq: &[f64]) {
        self.apply_increment(&Vec3::new(dq[0], dq[1], dq[2]), &Vec3::new(dq[3], dq[4], dq[5]));
    }

    /// True when every component is finite.
    pub fn is_finite(&self) -> bool {
        self.position.iter().all(|v| v.is_finite()) && self.orientation.coords.iter().all(|v| v.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_moves_by_dr_minus_s_tilde_dpi() {
        let mut pose = Pose {
            position: Vec3::new(0.1, -0.2, 0.3),
            orientation: UnitQuaternion::from_euler_angles(0.3, -0.2, 1.0),
        };
        let local = Vec3::new(0.5, 0.1, -0.4);
        let p0 = pose.point(&local);
        let s = p0 - pose.position;
        let dr = Vec3::new(1e-7, -3e-7, 2e-7);
        let dpi = Vec3::new(-2e-7, 1e-7, 4e-7);
        pose.apply_increment(&dr, &dpi);
        let moved = pose.point(&local) - p0;
        // ΔP = Δr − s̃Δπ = Δr − s × Δπ, up to second order in Δπ.
        let expected = dr - s.cross(&dpi);
        assert!((moved - expected).norm() < 1e-13, "{moved:?} vs {expected:?}");
    }
}
