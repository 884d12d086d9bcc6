//! The anti-roll bar: a torsion bar across the car, turning in bearings on the chassis, its arms joined by
//! drop links to a part of each corner. When one wheel rises relative to the other the arms turn by
//! different angles and the bar twists; in parallel travel they turn alike and it does nothing.
//!
//! Model: each half of the bar is a body on a revolute joint to the chassis, about the bar's axis (from
//! the left bearing `pivot` to its mirror image: a lateral axis); the two halves meet at the car's centre
//! line in a torsion element of the bar's rate (a bushing whose other rates act only in directions the two
//! bearings already hold, so they carry no load); each drop link is a distance constraint from the arm's
//! end to its point on the corner (ball joints at both ends). Only an axle builds it: every corner
//! analysis moves the two wheels alike (parallel travel, the same force on both), where a bar does not
//! twist. Given by its section instead of a rate, the middle is an elastic beam between the halves and
//! each arm a beam from its bearing to a body at its end, where the drop link meets it: the bar's rate
//! is then its own torsion and its arms' bending.

use crate::description::place::{part_name, Place};
use crate::description::section::SectionDef;
use serde::{Deserialize, Serialize};

/// Least distance of the bar's bearing from the centre line (m): the two bearings define its axis.
pub const MIN_BEARING_OFFSET: f64 = 0.05;

/// An anti-roll bar, described on the left (see the [module docs](self)).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AntiRollBar {
    /// Name: the torsion element's; the halves, bearings and links are named after it per side.
    pub name: String,
    /// Torsional rate of the bar, N·m/rad: the moment per radian of twist of one arm relative to the
    /// other (give this or `section`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rate: Option<f64>,
    /// The bar as the steel it is, by its section (give this or `rate`): its middle, from bearing to
    /// bearing, an elastic beam that twists, and each arm, from its bearing to its end, a beam that bends.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub section: Option<SectionDef>,
    /// The left bearing on the chassis, on the bar's axis.
    pub pivot: Place,
    /// The end of the left arm, where the drop link meets it.
    pub arm_end: Place,
    /// The drop link's other end, on `link_body`.
    pub link_end: Place,
    /// The part of the corner the drop link meets (a lower arm, a strut).
    pub link_body: String,
}

impl AntiRollBar {
    /// Names of one half of the bar, of its bearing and of its drop link, on the corner whose part names
    /// start with `prefix` (`"left "`, `"right "`; `""` for the corner of a solid axle built whole, whose
    /// half must not take the torsion element's own name).
    pub fn part_names(&self, prefix: &str) -> [String; 3] {
        [
            part_name(prefix, &format!("{} half", self.name)),
            part_name(prefix, &format!("{} bearing", self.name)),
            part_name(prefix, &format!("{} drop link", self.name)),
        ]
    }

    /// Names of a bar given by its section: the body at the arm's end and the arm's beam, per side.
    pub fn arm_names(&self, prefix: &str) -> [String; 2] {
        [part_name(prefix, &format!("{} arm end", self.name)), part_name(prefix, &format!("{} arm", self.name))]
    }
}
