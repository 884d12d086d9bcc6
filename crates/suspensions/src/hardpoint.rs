//! Hardpoints: the named points a suspension is drawn from, and the side of the car.

use elastokin_core::Vec3;
use serde::{Deserialize, Serialize};

/// Which corner of an axle. Templates are described on the left (y > 0, ISO 8855) and mirrored
/// (y → −y) for the right.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// y > 0.
    Left,
    /// y < 0, mirrored from the left.
    Right,
}

impl Side {
    /// +1 on the left, −1 on the right: the sign of the outward y direction.
    pub fn sign(self) -> f64 {
        match self {
            Side::Left => 1.0,
            Side::Right => -1.0,
        }
    }

    /// A left-side hardpoint placed on this side.
    pub fn place(self, left: Vec3) -> Vec3 {
        Vec3::new(left.x, self.sign() * left.y, left.z)
    }
}
