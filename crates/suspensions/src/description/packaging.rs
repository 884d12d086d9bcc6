//! What the wheel must clear: the tyre's size and the parts of the car around it, fixed to the body (points
//! and boxes, in the left corner's coordinates like every hardpoint), for the wheel's swept envelope over
//! travel and steer and its least clearance to each (the `wheel-envelope` analysis).

use crate::description::limits::plain;
use serde::{Deserialize, Serialize};

/// The tyre as the envelope sweeps it: a solid cylinder about the wheel's spin axis, centred on the wheel
/// centre (its shoulders square: a real tyre's rounded ones clear a little more).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tyre {
    /// The unloaded radius (m): half the tyre's outer diameter, as it grows at speed if that is allowed for.
    pub radius: f64,
    /// The section width (m).
    pub width: f64,
}

/// A point of the body the tyre must clear.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PackagingPoint {
    /// What it is (a bracket, a brake line's clip).
    pub name: String,
    /// Where (m).
    pub at: [f64; 3],
}

/// A box of the body the tyre must clear, its faces along the car's axes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PackagingBox {
    /// What it is (the wheel-arch liner, a frame rail).
    pub name: String,
    /// Its lowest corner (m).
    pub min: [f64; 3],
    /// Its highest corner (m).
    pub max: [f64; 3],
}

/// The model file's `packaging` section.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Packaging {
    /// The tyre.
    pub tyre: Tyre,
    /// The rack travel swept at each wheel height (m, towards +y, from its design position): the steering
    /// analysis's range when left out. A corner without steering is swept over its travel alone.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rack_travel: Option<[f64; 2]>,
    /// Points of the body near the wheel.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub points: Vec<PackagingPoint>,
    /// Boxes of the body near the wheel.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub boxes: Vec<PackagingBox>,
}

/// What the tyre must clear, as the envelope measures it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Obstacle<'a> {
    /// A point.
    Point(&'a PackagingPoint),
    /// A box.
    Box(&'a PackagingBox),
}

impl Obstacle<'_> {
    /// Its name in the file.
    pub fn name(&self) -> &str {
        match self {
            Obstacle::Point(p) => &p.name,
            Obstacle::Box(b) => &b.name,
        }
    }
}

/// The largest tyre radius and width accepted (m): beyond a truck's.
const MAX_TYRE: f64 = 1.5;
/// The smallest (m): below a kart's.
const MIN_TYRE: f64 = 0.05;
/// Farthest a packaging point or box corner may lie from the origin (m): a few car lengths.
const MAX_PACKAGING_REACH: f64 = 20.0;
/// The largest rack travel swept either way (m): beyond any rack's.
const MAX_RACK_TRAVEL: f64 = 0.2;

impl Packaging {
    /// The points and boxes, points first, each in the file's order.
    pub fn obstacles(&self) -> impl Iterator<Item = Obstacle<'_>> {
        self.points.iter().map(Obstacle::Point).chain(self.boxes.iter().map(Obstacle::Box))
    }

    /// Refuses what no car has, naming the key and how to mend it: `Err((keys, message))`, the keys from
    /// `packaging` down to the value.
    pub fn check(&self) -> Result<(), (Vec<String>, String)> {
        let at = |keys: &[&str]| std::iter::once("packaging").chain(keys.iter().copied()).map(String::from).collect();
        for (key, value, typical) in [
            ("radius", self.tyre.radius, "a car's unloaded tyre radius is 0.28–0.40 m"),
            ("width", self.tyre.width, "a car's tyre is 0.155–0.335 m wide"),
        ] {
            if !(MIN_TYRE..=MAX_TYRE).contains(&value) {
                let millimetres = if (MIN_TYRE..=MAX_TYRE).contains(&(value * 1e-3)) {
                    format!(" (millimetres? in metres that is {})", plain(value * 1e-3))
                } else {
                    String::new()
                };
                return Err((
                    at(&["tyre", key]),
                    format!(
                        "packaging.tyre.{key}: {} m is outside {MIN_TYRE}–{MAX_TYRE} m ({typical}){millimetres}",
                        plain(value)
                    ),
                ));
            }
        }
        if let Some([from, to]) = self.rack_travel {
            let ends_ok = [from, to].iter().all(|v| v.is_finite() && v.abs() <= MAX_RACK_TRAVEL);
            if !ends_ok || from >= to {
                return Err((
                    at(&["rack_travel"]),
                    format!(
                        "packaging.rack_travel: give the rack's travel from design as [from, to] in metres, from \
                         below to above, within ±{MAX_RACK_TRAVEL} m (a car's rack travels ±0.03–0.08 m), got [{}, {}]",
                        plain(from),
                        plain(to)
                    ),
                ));
            }
        }
        let mut names: Vec<&str> = Vec::new();
        for obstacle in self.obstacles() {
            let (list, name) = match obstacle {
                Obstacle::Point(p) => ("points", p.name.as_str()),
                Obstacle::Box(b) => ("boxes", b.name.as_str()),
            };
            if name.trim().is_empty() || names.contains(&name) {
                return Err((
                    at(&[list]),
                    format!(
                        "packaging.{list}: '{name}' {}: give every point and box a name of its own",
                        if name.trim().is_empty() { "is no name" } else { "is named twice" }
                    ),
                ));
            }
            names.push(name);
            let corners = match obstacle {
                Obstacle::Point(p) => vec![("at", p.at)],
                Obstacle::Box(b) => vec![("min", b.min), ("max", b.max)],
            };
            for (key, c) in corners {
                if !c.iter().all(|v| v.is_finite() && v.abs() <= MAX_PACKAGING_REACH) {
                    return Err((
                        at(&[list]),
                        format!(
                            "packaging.{list} '{name}': {key} [{}, {}, {}] is not a point within {MAX_PACKAGING_REACH} \
                             m of the car's origin: give it in metres (ISO 8855: x forward, y left, z up)",
                            plain(c[0]),
                            plain(c[1]),
                            plain(c[2])
                        ),
                    ));
                }
            }
            if let Obstacle::Box(b) = obstacle {
                if let Some(axis) = (0..3).find(|&k| b.min[k] >= b.max[k]) {
                    let axis = ["x", "y", "z"][axis];
                    return Err((
                        at(&[list]),
                        format!(
                            "packaging.boxes '{name}': its min {axis} is not below its max {axis}: give min the \
                             lowest corner and max the highest, each a box's extent along x, y and z"
                        ),
                    ));
                }
            }
        }
        Ok(())
    }
}
