//! Where things are in a description: named hardpoints, a place (a hardpoint's name or coordinates), an
//! axis (through two places, or a vector), and how a part of a corner is named on its side.

use elastokin_core::Vec3;
use serde::de::{Error as _, MapAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// Named hardpoints of the left corner, in the order given (global coordinates, metres).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Hardpoints(pub Vec<(String, Vec3)>);

impl Hardpoints {
    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// The point named `name`.
    pub fn get(&self, name: &str) -> Option<Vec3> {
        self.0.iter().find(|(n, _)| n == name).map(|(_, p)| *p)
    }
}

impl Serialize for Hardpoints {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = s.serialize_map(Some(self.0.len()))?;
        for (name, p) in &self.0 {
            map.serialize_entry(name, &[p.x, p.y, p.z])?;
        }
        map.end()
    }
}

/// A point's own reader, named for the error messages (see `crate::description::side::point`).
#[derive(Deserialize)]
#[serde(transparent)]
struct PointValue(#[serde(deserialize_with = "crate::description::side::point")] Vec3);

impl<'de> Deserialize<'de> for Hardpoints {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Ordered;
        impl<'de> Visitor<'de> for Ordered {
            type Value = Hardpoints;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("an object of named hardpoints, each [x, y, z] in metres")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Hardpoints, A::Error> {
                let mut out: Vec<(String, Vec3)> = Vec::new();
                let mut seen = std::collections::HashSet::new();
                while let Some(name) = map.next_key::<String>()? {
                    let PointValue(p) = map.next_value()?;
                    if !seen.insert(name.clone()) {
                        return Err(A::Error::custom(format!("hardpoint '{name}' is given twice: keep one")));
                    }
                    out.push((name, p));
                }
                Ok(Hardpoints(out))
            }
        }
        d.deserialize_map(Ordered)
    }
}

/// A point of the model: a hardpoint by name, or coordinates `[x, y, z]` (left corner, metres).
#[derive(Debug, Clone, PartialEq)]
pub enum Place {
    /// A named hardpoint.
    Named(String),
    /// Coordinates.
    At(Vec3),
}

impl Place {
    /// A named hardpoint.
    pub fn named(name: &str) -> Place {
        Place::Named(name.to_string())
    }
    /// How the file writes it, for messages.
    pub(crate) fn describe(&self) -> String {
        match self {
            Place::Named(n) => format!("'{n}'"),
            Place::At(p) => format!("[{}, {}, {}]", p.x, p.y, p.z),
        }
    }
}

impl Serialize for Place {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Place::Named(n) => s.serialize_str(n),
            Place::At(p) => [p.x, p.y, p.z].serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for Place {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let value = serde_json::Value::deserialize(d)?;
        place_of(&value).map_err(D::Error::custom)
    }
}

fn place_of(value: &serde_json::Value) -> Result<Place, NotAPlace> {
    if let Some(name) = value.as_str() {
        return Ok(Place::named(name));
    }
    match numbers(value) {
        Some(n) if n.len() == 3 => Ok(Place::At(Vec3::new(n[0], n[1], n[2]))),
        _ => Err(NotAPlace { got: value.clone() }),
    }
}

/// A value written where a point is, that names none: neither a hardpoint's name nor three numbers.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("a point is a hardpoint's name or 3 numbers in metres [x, y, z], got {}", short(got))]
struct NotAPlace {
    /// The value, as read.
    got: serde_json::Value,
}

fn numbers(value: &serde_json::Value) -> Option<Vec<f64>> {
    value.as_array()?.iter().map(|c| c.as_f64()).collect()
}

pub(crate) fn short(value: &serde_json::Value) -> String {
    let text = value.to_string();
    if text.chars().count() > 40 {
        format!("{}…", text.chars().take(40).collect::<String>())
    } else {
        text
    }
}

/// A direction: from one point to another (`["a", "b"]`), or a vector `[x, y, z]` (left corner).
#[derive(Debug, Clone, PartialEq)]
pub enum Axis {
    /// From the first point towards the second.
    Through(Place, Place),
    /// A direction vector (any length but zero).
    Vector(Vec3),
}

impl Axis {
    /// From hardpoint `a` towards hardpoint `b`.
    pub fn through(a: &str, b: &str) -> Axis {
        Axis::Through(Place::named(a), Place::named(b))
    }
}

impl Serialize for Axis {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Axis::Through(a, b) => (a, b).serialize(s),
            Axis::Vector(v) => [v.x, v.y, v.z].serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for Axis {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let value = serde_json::Value::deserialize(d)?;
        let fail = || {
            D::Error::custom(format!(
                "an axis is two points [\"from\", \"to\"] (hardpoint names or [x, y, z]) or a direction [x, y, z], \
                 got {}",
                short(&value)
            ))
        };
        match value.as_array().map(Vec::as_slice) {
            Some([a, b]) => Ok(Axis::Through(place_of(a).map_err(|_| fail())?, place_of(b).map_err(|_| fail())?)),
            Some([_, _, _]) => match numbers(&value) {
                Some(n) => Ok(Axis::Vector(Vec3::new(n[0], n[1], n[2]))),
                None => Err(fail()),
            },
            _ => Err(fail()),
        }
    }
}

/// Name `name` of the part of the corner whose names start with `prefix`.
pub(crate) fn part_name(prefix: &str, name: &str) -> String {
    format!("{prefix}{name}")
}
