//! How two parts are connected: an ideal joint or a rubber bushing.

use serde::{Deserialize, Serialize};

/// Rates of a cylindrical rubber bushing (SI: N/m and N·m/rad), in its own frame whose x axis is the
/// bushing's axis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BushingRates {
    /// Radial rate (both directions across the axis), N/m.
    pub radial: f64,
    /// Axial rate, N/m.
    pub axial: f64,
    /// Torsion about the axis, N·m/rad.
    pub torsion: f64,
    /// Conical (tilt of the axis), N·m/rad.
    pub conical: f64,
}

impl BushingRates {
    /// Every rate multiplied by `factor` (for stiffness studies).
    pub fn scaled(self, factor: f64) -> Self {
        BushingRates {
            radial: self.radial * factor,
            axial: self.axial * factor,
            torsion: self.torsion * factor,
            conical: self.conical * factor,
        }
    }
}

/// A connection of a template: ideal kinematic joint, or bushing.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Connection {
    /// The template's ideal joint (revolute arm pivot, spherical ball joint, …).
    Ideal,
    /// A bushing with these rates.
    Bushing(BushingRates),
}
