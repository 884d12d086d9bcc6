//! The side of the car a corner is on, and how a hardpoint is read from a model file.

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

    /// The side across the axle.
    pub fn other(self) -> Side {
        match self {
            Side::Left => Side::Right,
            Side::Right => Side::Left,
        }
    }

    /// A left-side hardpoint placed on this side.
    pub fn place(self, left: Vec3) -> Vec3 {
        Vec3::new(left.x, self.sign() * left.y, left.z)
    }

    /// The outward spin axis of a wheel on this side at `toe` and `camber` (rad): the lateral axis turned by
    /// the toe about z (toe-in turns the wheel's front inward) and tilted by the camber about the wheel's
    /// heading (negative camber, the top inward, lifts the outward axis),
    /// `(sin toe cos camber, s cos toe cos camber, −sin camber)`.
    pub fn spin_axis(self, toe: f64, camber: f64) -> Vec3 {
        self.place(Vec3::new(camber.cos() * toe.sin(), camber.cos() * toe.cos(), -camber.sin()))
    }
}

/// Reads a hardpoint `[x, y, z]`, saying what was given when it is not three numbers (the model file
/// reader puts the hardpoint's name before the message).
pub(crate) fn point<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec3, D::Error> {
    let value = serde_json::Value::deserialize(d)?;
    let numbers: Option<Vec<f64>> = value.as_array().map(|a| a.iter().filter_map(|c| c.as_f64()).collect());
    let got = match (&value, numbers) {
        (_, Some(n)) if n.len() == 3 && value.as_array().is_some_and(|a| a.len() == 3) => {
            return Ok(Vec3::new(n[0], n[1], n[2]));
        }
        (serde_json::Value::Array(a), Some(n)) if n.len() == a.len() => a.len().to_string(),
        (other, _) => {
            let text = other.to_string();
            if text.chars().count() > 40 {
                format!("{}…", text.chars().take(40).collect::<String>())
            } else {
                text
            }
        }
    };
    Err(serde::de::Error::custom(format!("a point is 3 numbers in metres [x, y, z], got {got}")))
}
