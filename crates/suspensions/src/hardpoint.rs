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

/// Reads a hardpoint `[x, y, z]`, saying how many numbers were given when it is not three (the model file
/// reader puts the hardpoint's name before the message).
pub(crate) fn point<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec3, D::Error> {
    let numbers = Vec::<f64>::deserialize(d)?;
    match numbers.as_slice() {
        &[x, y, z] => Ok(Vec3::new(x, y, z)),
        other => {
            Err(serde::de::Error::custom(format!("a point is 3 numbers in metres [x, y, z], got {}", other.len())))
        }
    }
}
