//! Model files: a suspension template in JSON, SI units, ISO 8855 axes (x forward, y left, z up), left
//! corner (the right is mirrored).
//!
//! ```json
//! { "name": "generic double wishbone",
//!   "suspension": { "double_wishbone": {
//!       "hardpoints": { "wheel_centre": [-0.04, 1.1, -0.026], … },
//!       "upper_arm_mounts": "ideal",
//!       "lower_arm_mounts": { "bushing": { "radial": 5e6, "axial": 1e6, "torsion": 573, "conical": 5730 } },
//!       "spring": { "rate": 30000, "design_force": 4000 } } } }
//! ```
//!
//! Unknown keys, missing hardpoints, points that are not three numbers, and values no suspension has (a
//! coordinate beyond ±1000 m, a rate outside (0, 10¹²], a wheelbase outside 0.5–20 m, …) are errors that
//! name the key, its line and column in the file and, for a value, the accepted range. A UTF-8 byte-order
//! mark at the start is skipped.

pub mod key_path;
pub mod numbers;

use crate::description::limits::{looks_like_millimetres, MAX_COORDINATE, MAX_FORCE, MAX_RATE};
use crate::description::{
    ArmMounts, BushingDef, Connection, GeneralCorner, LoadDef, Packaging, SpringSpec, Stiffness, Template,
    VehicleParameters,
};
use elastokin_core::ModelError;
pub use key_path::key_path_at;
use key_path::{first_unprintable, key_before, locate};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// The content of a model file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SuspensionFile {
    /// A name for reports.
    pub name: String,
    /// The suspension.
    pub suspension: Template,
    /// The vehicle around it, for the static load case, the road loads and the anti-pitch figures;
    /// optional (those analyses are then skipped or take the design wheel load).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vehicle: Option<VehicleParameters>,
    /// What the wheel must clear, for its swept envelope over travel and steer; optional (the
    /// `wheel-envelope` analysis is then skipped).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub packaging: Option<Packaging>,
}

/// The templates a model file may name in `suspension`.
const TEMPLATES: [&str; 4] = ["macpherson", "double_wishbone", "twist_beam", "general"];

/// How the point reader's error starts (see [`crate::description::side::point`]); the hardpoint's name is put before it.
const POINT_ERROR: &str = "a point is 3 numbers";

/// A value outside what any suspension has, with the keys leading to it in the file.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{message}")]
pub struct OutOfRange {
    /// The keys from the template (or the file's top level, for `vehicle`) down to the value.
    pub keys: Vec<String>,
    /// What is wrong, the accepted range and why.
    pub message: String,
}

impl OutOfRange {
    /// As a file error at the value's key in `text`.
    fn at(self, text: &str, origin: &str) -> FileError {
        let keys: Vec<&str> = self.keys.iter().map(String::as_str).collect();
        let (line, column) = locate(text, &keys);
        FileError::Invalid { origin: origin.to_string(), line, column, message: self.message }
    }
}

/// serde's words for what it expected, in the model file's words: the library's type names mean nothing
/// to the file's author. Longer names first, so that a name is not replaced inside a longer one.
const EXPECTED_IN_FILE_WORDS: [(&str, &str); 9] = [
    ("invalid type: sequence, expected {\"radial\"", "a list of numbers; give the rates by name, {\"radial\""),
    ("struct MacPhersonHardpoints", "an object of named hardpoints"),
    ("struct DoubleWishboneHardpoints", "an object of named hardpoints"),
    ("struct MacPherson", "an object with the template's hardpoints, mounts, spring and loaded_radius"),
    ("struct DoubleWishbone", "an object with the template's hardpoints, mounts, spring and loaded_radius"),
    ("struct SpringSpec", "{\"rate\": N/m, \"design_force\": N}"),
    (
        "struct VehicleParameters",
        "an object with corner_load, wheelbase, cg_height, brake_front_fraction, drive_front_fraction and axle",
    ),
    ("struct SuspensionFile", "an object with name, suspension and, optionally, vehicle"),
    ("f64", "a number"),
];

fn in_file_words(message: &str) -> String {
    EXPECTED_IN_FILE_WORDS.iter().fold(message.to_string(), |m, (code, words)| m.replace(code, words))
}

/// `value` as pretty JSON at `depth` (two spaces each), arrays of plain values on one line.
fn write_json(value: &serde_json::Value, depth: usize, out: &mut String) {
    use serde_json::Value;
    let indent = |d: usize| "  ".repeat(d);
    let plain = |v: &Value| !(v.is_array() || v.is_object());
    let short = inline(value);
    if value.is_object() && short.len() + 2 * depth <= 110 && !short[1..].contains('{') {
        out.push_str(&short);
        return;
    }
    match value {
        Value::Object(map) if !map.is_empty() => {
            out.push_str("{\n");
            for (k, (key, v)) in map.iter().enumerate() {
                out.push_str(&format!("{}{}: ", indent(depth + 1), Value::String(key.clone())));
                write_json(v, depth + 1, out);
                out.push_str(if k + 1 < map.len() { ",\n" } else { "\n" });
            }
            out.push_str(&format!("{}}}", indent(depth)));
        }
        Value::Array(items)
            if !items.is_empty()
                && !items.iter().all(|v| plain(v) || v.as_array().is_some_and(|a| a.iter().all(plain))) =>
        {
            out.push_str("[\n");
            for (k, v) in items.iter().enumerate() {
                out.push_str(&indent(depth + 1));
                write_json(v, depth + 1, out);
                out.push_str(if k + 1 < items.len() { ",\n" } else { "\n" });
            }
            out.push_str(&format!("{}]", indent(depth)));
        }
        other => out.push_str(&inline(other)),
    }
}

/// A plain value, or an array of them, on one line.
fn inline(value: &serde_json::Value) -> String {
    match value {
        serde_json::Value::Array(items) => format!("[{}]", items.iter().map(inline).collect::<Vec<_>>().join(", ")),
        serde_json::Value::Object(map) if !map.is_empty() => {
            let entries: Vec<String> =
                map.iter().map(|(k, v)| format!("{}: {}", serde_json::Value::String(k.clone()), inline(v))).collect();
            format!("{{ {} }}", entries.join(", "))
        }
        other => other.to_string(),
    }
}

/// Text editors on some systems save UTF-8 with a byte-order mark; JSON has no use for it.
pub(crate) fn without_byte_order_mark(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// A model file that cannot be read.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum FileError {
    /// The file could not be opened or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The file is not a valid model (bad JSON, unknown key, missing hardpoint, wrong type).
    #[error("{origin}:{line}:{column}: {message}")]
    Invalid {
        /// The file (or the origin given to [`SuspensionFile::from_json`]).
        origin: String,
        /// Line, from 1.
        line: usize,
        /// Column, from 1.
        column: usize,
        /// What is wrong, naming the key.
        message: String,
    },
    /// The file parses but describes an inconsistent model.
    #[error("{origin}: {source}")]
    Model {
        /// The file.
        origin: String,
        /// The model error.
        source: ModelError,
    },
}

impl FileError {
    /// The error of a document that is no file (a Python dict, a variant's edited model), placed by the keys
    /// that lead there (`key_path_at`) in `text`, the document's text the error is of.
    pub fn in_document(self, text: &str) -> InDocument {
        let keys = match &self {
            FileError::Invalid { line, column, .. } => key_path_at(without_byte_order_mark(text), *line, *column),
            _ => String::new(),
        };
        InDocument { error: self, keys }
    }
}

/// A [`FileError`] of a document that is no file: its place named by the keys that lead there, not by a
/// line and column of text the user never saw.
#[derive(Debug, Error)]
pub struct InDocument {
    /// The error, as a file's.
    pub error: FileError,
    /// The keys that lead to its place (`bodies[1].mass`); empty where it has none.
    pub keys: String,
}

impl std::fmt::Display for InDocument {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match (&self.error, self.keys.as_str()) {
            (FileError::Invalid { origin, message, .. }, "") => write!(f, "{origin}: {message}"),
            (FileError::Invalid { origin, message, .. }, keys) => write!(f, "{origin}: {message} (at {keys})"),
            (other, _) => other.fmt(f),
        }
    }
}

/// The first key or text of `value` (read from `text`) holding an [`key_path::unprintable`] character,
/// refused as [`FileError::Invalid`] at its line and column in `text`.
pub(crate) fn refuse_unprintable(value: &serde_json::Value, text: &str, origin: &str) -> Result<(), FileError> {
    let Some((path, said)) = first_unprintable(value) else { return Ok(()) };
    let keys: Vec<&str> = path.iter().map(String::as_str).collect();
    let (line, column) = locate(text, &keys);
    Err(FileError::Invalid { origin: origin.to_string(), line, column, message: unprintable_message(&path, &said) })
}

/// Why a text with an [`key_path::unprintable`] character in it is refused, naming where it is (the path
/// shown printable too: the character may be in a key).
pub(crate) fn unprintable_message(path: &[String], said: &str) -> String {
    let c = said.chars().find(|c| key_path::unprintable(*c)).unwrap_or('\u{0}');
    let shown = key_path::printable(&said.chars().take(60).collect::<String>()).into_owned();
    let more = if said.chars().nth(60).is_some() { "…" } else { "" };
    format!(
        "{}: \"{shown}{more}\" holds the character U+{:04X}, which no name is written with and a terminal or \
         report cannot show: write it in plain text",
        key_path::printable(&path.join(".")),
        c as u32
    )
}

impl SuspensionFile {
    /// Parses JSON text into a description, `origin` naming the source in errors, and with `ranges` refuses
    /// values no suspension has (see [`SuspensionFile::check_ranges`]) with the key, its line and column,
    /// and the accepted range. Nothing is built: [`SuspensionFile::from_json`] builds it too.
    pub(crate) fn parse_checked(text: &str, origin: &str, ranges: bool) -> Result<Self, FileError> {
        let text = without_byte_order_mark(text);
        let file = Self::parse(text, origin)?;
        if ranges {
            file.check_ranges().map_err(|e| e.at(text, origin))?;
        }
        Ok(file)
    }

    fn parse(text: &str, origin: &str) -> Result<Self, FileError> {
        let invalid = |line: usize, column: usize, message: String| FileError::Invalid {
            origin: origin.to_string(),
            line,
            column,
            message,
        };
        let plain = |e: &serde_json::Error| e.to_string().split(" at line ").next().unwrap_or_default().to_string();
        // Syntax first, then the one thing serde cannot say in the file's words: how many templates.
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|e| invalid(e.line(), e.column(), plain(&e)))?;
        if let Some(path) = key_path::first_duplicate_key(text) {
            let keys: Vec<&str> = path.iter().map(String::as_str).collect();
            let (line, column) = locate(text, &keys);
            return Err(invalid(
                line,
                column,
                format!("{}: the key is given twice: give each key once", path.join(".")),
            ));
        }
        refuse_unprintable(&value, text, origin)?;
        if let Some(suspension) = value.get("suspension").filter(|s| !s.is_object()) {
            let (line, column) = locate(text, &["suspension"]);
            return Err(invalid(
                line,
                column,
                format!(
                    "suspension: give one template as an object, {{\"macpherson\": {{…}}}}, \
                     {{\"double_wishbone\": {{…}}}}, {{\"twist_beam\": {{…}}}} or {{\"general\": {{…}}}}, got \
                     {suspension}"
                ),
            ));
        }
        if let Some(serde_json::Value::Object(templates)) = value.get("suspension") {
            let found: Vec<&str> = templates.keys().map(String::as_str).collect();
            let (line, column) = locate(text, &["suspension"]);
            let known = "macpherson, double_wishbone, twist_beam or general";
            match found.as_slice() {
                [one] if !TEMPLATES.contains(one) => {
                    return Err(invalid(
                        line,
                        column,
                        format!("suspension: unknown template '{one}': give one of {known}"),
                    ));
                }
                [_] => {}
                [] => {
                    return Err(invalid(line, column, format!("suspension: give one template ({known}), found none")))
                }
                _ => {
                    return Err(invalid(
                        line,
                        column,
                        format!("suspension: give one template ({known}), found {}: {}", found.len(), found.join(", ")),
                    ));
                }
            }
        }
        serde_json::from_str(text).map_err(|e| {
            let message = in_file_words(&plain(&e));
            // A point's own error cannot know its name: the key just before the error in the text is it.
            let message = match (message.starts_with(POINT_ERROR), key_before(text, e.line(), e.column())) {
                (true, Some(key)) => format!("hardpoint '{key}': {message}"),
                _ => message,
            };
            invalid(e.line(), e.column(), message)
        })
    }

    /// Refuses values no suspension has: hardpoint coordinates beyond ±1000 m, rates outside
    /// (0, 10¹²], a loaded radius outside 0.05–2 m, a design force beyond ±10⁶ N, and vehicle
    /// parameters outside the ranges of road vehicles. The first refused is the first of: a hardpoint, a
    /// general model's load, a spring's or bar's rate, a spring's design force, the loaded radius, any other
    /// rate, the vehicle, the packaging (tyre sizes, rack travel, points and boxes).
    pub fn check_ranges(&self) -> Result<(), OutOfRange> {
        self.check_hardpoints()?;
        if let Template::General(g) = &self.suspension {
            check_loads(&g.loads)?;
        }
        RangedValues::of(&self.suspension).check()?;
        self.vehicle.as_ref().map_or(Ok(()), check_vehicle)?;
        match self.packaging.as_ref().map(Packaging::check) {
            Some(Err((keys, message))) => Err(OutOfRange { keys, message }),
            _ => Ok(()),
        }
    }

    /// Every hardpoint coordinate within ±[`MAX_COORDINATE`]; a file in millimetres is told so.
    fn check_hardpoints(&self) -> Result<(), OutOfRange> {
        let points = self.suspension.hardpoints();
        for (name, p) in &points {
            for (axis, c) in ["x", "y", "z"].into_iter().zip(p.iter()) {
                if c.is_nan() || c.abs() > MAX_COORDINATE {
                    let wc = points.iter().find(|(n, _)| n == self.suspension.wheel_centre_name()).map(|(_, p)| *p);
                    let hint = if wc.is_some_and(|wc| looks_like_millimetres(&points, wc)) {
                        "; the hardpoints look like millimetres: divide every coordinate by 1000"
                    } else {
                        ""
                    };
                    return Err(OutOfRange {
                        keys: vec!["hardpoints".into(), name.clone()],
                        message: format!(
                            "hardpoint '{name}': {axis} = {} m is beyond ±{MAX_COORDINATE} m; hardpoints are in \
                             metres from the car's reference point (ISO 8855: x forward, y left, z up){hint}",
                            crate::description::limits::plain(*c)
                        ),
                    });
                }
            }
        }
        Ok(())
    }

    /// The file as pretty JSON, as people write it: one key per line, a point or a pair of names on one.
    pub fn to_json(&self) -> String {
        let value = serde_json::to_value(self).expect("a model of plain numbers and strings always serialises");
        let mut out = String::new();
        write_json(&value, 0, &mut out);
        out
    }

    /// Writes the file.
    pub fn write(&self, path: &Path) -> Result<(), FileError> {
        std::fs::write(path, self.to_json()).map_err(|source| FileError::Io { path: path.to_path_buf(), source })
    }
}

/// A bushing's translational rates, as a rate out of range says.
const TYPICAL_TRANSLATION: &str = "a suspension bushing is 1e5–1e8 N/m";
/// A bushing's rotational rates.
const TYPICAL_ROTATION: &str = "a suspension bushing is 10–1e5 N·m/rad";
/// A coil spring's rate.
const TYPICAL_SPRING: &str = "a car's coil spring is 1e4–3e5 N/m";
/// An anti-roll bar's rate.
const TYPICAL_ANTI_ROLL_BAR: &str = "a car's anti-roll bar is 1e3–1e5 N·m/rad";

/// The keys `k` as owned strings.
fn keys(k: &[&str]) -> Vec<String> {
    k.iter().map(|k| k.to_string()).collect()
}

/// A general model's point loads: each component of a force or torque within ±[`MAX_FORCE`].
fn check_loads(loads: &[LoadDef]) -> Result<(), OutOfRange> {
    for load in loads {
        for (what, values) in [("force", load.force), ("torque", load.torque)] {
            let largest = values
                .map_or(0.0, |v| v.iter().fold(0.0_f64, |m, c| if c.is_nan() { f64::NAN } else { m.max(c.abs()) }));
            if largest.is_nan() || largest > MAX_FORCE {
                return Err(OutOfRange {
                    keys: vec!["loads".into(), load.name.clone(), what.into()],
                    message: format!(
                        "loads.{}.{what}: a component of {} is beyond ±{MAX_FORCE:e} (N or N·m): give a load a \
                         suspension carries",
                        load.name,
                        crate::description::limits::plain(largest)
                    ),
                });
            }
        }
    }
    Ok(())
}

/// A rate of the file: the keys leading to it, its unit, its value and what such a rate typically is.
struct Rate {
    keys: Vec<String>,
    unit: &'static str,
    value: f64,
    typical: &'static str,
}

impl Rate {
    /// Refused outside (0, [`MAX_RATE`]].
    fn check(&self) -> Result<(), OutOfRange> {
        let Rate { keys, unit, value, typical } = self;
        if *value > 0.0 && *value <= MAX_RATE {
            return Ok(());
        }
        Err(OutOfRange {
            keys: keys.to_vec(),
            message: format!(
                "{}: {} {unit} is outside the accepted range (0, 1e12] {unit} ({typical})",
                keys.join("."),
                crate::description::limits::plain(*value)
            ),
        })
    }
}

/// A suspension's values held to a range other than its hardpoints and loads: every rate (bushings,
/// springs, bars), every spring's design force, and the loaded radius, each with its keys, in file order.
struct RangedValues {
    rates: Vec<Rate>,
    forces: Vec<(Vec<String>, f64)>,
    loaded_radius: f64,
    radius_keys: Vec<String>,
}

impl RangedValues {
    /// The values of `template`.
    fn of(template: &Template) -> Self {
        let mut values =
            RangedValues { rates: Vec::new(), forces: Vec::new(), loaded_radius: 0.0, radius_keys: Vec::new() };
        match template {
            Template::DoubleWishbone(t) => {
                values.arm("upper_arm_mounts", &t.upper_arm_mounts);
                values.arm("lower_arm_mounts", &t.lower_arm_mounts);
                values.connection(keys(&["tie_rod"]), &t.tie_rod);
                values.template_spring(&t.spring, t.loaded_radius);
            }
            Template::TwistBeam(t) => {
                values.connection(keys(&["pivots"]), &t.pivots);
                values.template_spring(&t.spring, t.loaded_radius);
            }
            Template::MacPherson(t) => {
                values.arm("lower_arm_mounts", &t.lower_arm_mounts);
                values.connection(keys(&["top_mount"]), &t.top_mount);
                values.connection(keys(&["tie_rod"]), &t.tie_rod);
                values.template_spring(&t.spring, t.loaded_radius);
            }
            Template::General(g) => values.general(g),
        }
        values
    }

    /// A bushing connection's four rates, under `key`; an ideal joint has none.
    fn connection(&mut self, key: Vec<String>, c: &Connection) {
        if let Connection::Bushing(r) = c {
            for (what, unit, value, typical) in [
                ("radial", "N/m", r.radial, TYPICAL_TRANSLATION),
                ("axial", "N/m", r.axial, TYPICAL_TRANSLATION),
                ("torsion", "N·m/rad", r.torsion, TYPICAL_ROTATION),
                ("conical", "N·m/rad", r.conical, TYPICAL_ROTATION),
            ] {
                let mut keys = key.clone();
                keys.extend(["bushing".to_string(), what.to_string()]);
                self.rates.push(Rate { keys, unit, value, typical });
            }
        }
    }

    /// An arm's mounts: one connection for both pivots, or the front's and the rear's.
    fn arm(&mut self, key: &str, m: &ArmMounts) {
        if m.front == m.rear {
            self.connection(keys(&[key]), &m.front);
        } else {
            self.connection(keys(&[key, "front"]), &m.front);
            self.connection(keys(&[key, "rear"]), &m.rear);
        }
    }

    /// A template's coil spring and loaded radius.
    fn template_spring(&mut self, spring: &SpringSpec, loaded_radius: f64) {
        self.rates.push(Rate {
            keys: keys(&["spring", "rate"]),
            unit: "N/m",
            value: spring.rate,
            typical: TYPICAL_SPRING,
        });
        self.forces.push((keys(&["spring", "design_force"]), spring.design_force));
        (self.loaded_radius, self.radius_keys) = (loaded_radius, keys(&["loaded_radius"]));
    }

    /// The general model's bushings, springs, anti-roll bars, tie rod and loaded radius.
    fn general(&mut self, g: &GeneralCorner) {
        for b in &g.bushings {
            self.bushing(b);
        }
        for s in &g.springs {
            if let Some(rate) = s.rate {
                let keys = vec!["springs".into(), s.name.clone(), "rate".into()];
                self.rates.push(Rate { keys, unit: "N/m", value: rate, typical: TYPICAL_SPRING });
            }
            if let Some(f) = s.design_force {
                self.forces.push((vec!["springs".into(), s.name.clone(), "design_force".into()], f));
            }
        }
        for bar in &g.anti_roll_bars {
            if let Some(rate) = bar.rate {
                let keys = vec!["anti_roll_bars".into(), bar.name.clone(), "rate".into()];
                self.rates.push(Rate { keys, unit: "N·m/rad", value: rate, typical: TYPICAL_ANTI_ROLL_BAR });
            }
        }
        if let Some(t) = &g.corner.tie_rod {
            let m = &t.connection;
            if m.inner == m.outer {
                self.connection(keys(&["corner", "tie_rod", "connection"]), &m.inner);
            } else {
                self.connection(keys(&["corner", "tie_rod", "connection", "inner"]), &m.inner);
                self.connection(keys(&["corner", "tie_rod", "connection", "outer"]), &m.outer);
            }
        }
        (self.loaded_radius, self.radius_keys) = (g.corner.loaded_radius, keys(&["corner", "loaded_radius"]));
    }

    /// A general bushing's rates; a curve's points are checked by the curve, naming the point.
    fn bushing(&mut self, b: &BushingDef) {
        let key = |what: &str| vec!["bushings".to_string(), b.name.clone(), what.to_string()];
        let given = [
            ("radial", "N/m", &b.radial, TYPICAL_TRANSLATION),
            ("axial", "N/m", &b.axial, TYPICAL_TRANSLATION),
            ("torsion", "N·m/rad", &b.torsion, TYPICAL_ROTATION),
            ("conical", "N·m/rad", &b.conical, TYPICAL_ROTATION),
        ];
        for (what, unit, value, typical) in given {
            if let Some(value) = value.as_ref().and_then(Stiffness::rate) {
                self.rates.push(Rate { keys: key(what), unit, value, typical });
            }
        }
        for (what, unit, values, typical) in [
            ("translation", "N/m", &b.translation, TYPICAL_TRANSLATION),
            ("rotation", "N·m/rad", &b.rotation, TYPICAL_ROTATION),
        ] {
            for value in values.iter().flatten().filter_map(Stiffness::rate) {
                self.rates.push(Rate { keys: key(what), unit, value, typical });
            }
        }
    }

    /// The springs' and bars' rates first and their design forces, as the file reads, then the loaded
    /// radius, then every other rate.
    fn check(&self) -> Result<(), OutOfRange> {
        for rate in self.rates.iter().filter(|r| r.keys.last().is_some_and(|k| k == "rate")) {
            rate.check()?;
        }
        for (keys, force) in &self.forces {
            if force.is_nan() || force.abs() > MAX_FORCE {
                return Err(OutOfRange {
                    keys: keys.clone(),
                    message: format!(
                        "{}: {} N is beyond ±{MAX_FORCE:e} N (a car's spring carries 2e3–2e4 N)",
                        keys.join("."),
                        crate::description::limits::plain(*force)
                    ),
                });
            }
        }
        if !crate::description::limits::LOADED_RADIUS.contains(&self.loaded_radius) {
            return Err(OutOfRange {
                keys: self.radius_keys.clone(),
                message: format!(
                    "{}: {} m is outside 0.05–2 m (a car's tyre is 0.25–0.40 m, in metres)",
                    self.radius_keys.join("."),
                    crate::description::limits::plain(self.loaded_radius)
                ),
            });
        }
        self.rates.iter().try_for_each(Rate::check)
    }
}

/// The vehicle's parameters within the ranges of road vehicles: each as a rule of its key, value, range,
/// unit and why; the optional ones when given.
fn check_vehicle(v: &VehicleParameters) -> Result<(), OutOfRange> {
    let fields = [
        ("wheelbase", v.wheelbase, 0.5, 20.0, "m", "from a kart's to a long bus's"),
        ("cg_height", v.cg_height, 0.05, 5.0, "m", "the centre of gravity's height above the ground"),
        ("corner_load", v.corner_load, 1.0, 1e6, "N", "the corner's share of the weight, in newtons"),
        ("brake_front_fraction", v.brake_front_fraction, 0.0, 1.0, "", "the front axle's share of the braking force"),
        ("drive_front_fraction", v.drive_front_fraction, 0.0, 1.0, "", "the front axle's share of the drive force"),
    ];
    let optional = [
        ("tyre_rate", v.tyre_rate, 1e4, 1e7, "N/m", "a car's tyre is 2e5–3e5 N/m"),
        (
            "rack_travel_per_revolution",
            v.rack_travel_per_revolution,
            0.01,
            0.2,
            "m",
            "rack travel per turn of the hand wheel: a car's is 0.04–0.06 m",
        ),
        (
            "half_shaft",
            v.half_shaft.map(|h| h.length()),
            0.1,
            1.5,
            "m",
            "the distance between the shaft's joint centres: a car's is 0.3–0.9 m",
        ),
    ];
    let given = optional
        .into_iter()
        .filter_map(|(key, value, lo, hi, unit, why)| value.map(|value| (key, value, lo, hi, unit, why)));
    for (key, value, lo, hi, unit, why) in fields.into_iter().chain(given) {
        if !(lo..=hi).contains(&value) {
            return Err(OutOfRange {
                keys: vec!["vehicle".into(), key.into()],
                message: format!(
                    "vehicle.{key}: {} {unit} is outside {}–{} {unit} ({why})",
                    crate::description::limits::plain(value),
                    crate::description::limits::plain(lo),
                    crate::description::limits::plain(hi)
                )
                .replace("  ", " ")
                .replace(" )", ")"),
            });
        }
    }
    Ok(())
}

/// The largest model or variants file read: far beyond any real one, small enough to read at once.
pub const MAX_FILE_BYTES: u64 = 16 << 20;

/// Reads an input file whole, as bytes and as text; errors name the file and `what` it is for (`MODEL`,
/// `VARIANTS`), as the command says them.
pub fn read_input(path: &Path, what: &str) -> Result<(Vec<u8>, String), InputError> {
    use std::io::Read;
    let fail = |why| InputError { what: what.to_string(), path: path.display().to_string(), why };
    let file = std::fs::File::open(path).map_err(|e| fail(InputRefusal::Open(e.to_string())))?;
    let mut bytes = Vec::new();
    file.take(MAX_FILE_BYTES + 1).read_to_end(&mut bytes).map_err(|e| fail(InputRefusal::Read(e.to_string())))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(fail(InputRefusal::TooLarge));
    }
    let text = String::from_utf8(bytes.clone()).map_err(|_| fail(InputRefusal::NotText))?;
    Ok((bytes, text))
}

/// An input file not read ([`read_input`]): which, what it is for, and why.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{what} '{path}': {why}")]
pub struct InputError {
    /// What the file is for (`MODEL`, `VARIANTS`).
    pub what: String,
    /// The file as given.
    pub path: String,
    /// Why it is not read.
    pub why: InputRefusal,
}

/// Why an input file is not read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InputRefusal {
    /// It cannot be opened, in the system's words.
    #[error("cannot open it: {0}")]
    Open(String),
    /// It cannot be read, in the system's words.
    #[error("cannot read it: {0}")]
    Read(String),
    /// It is larger than [`MAX_FILE_BYTES`].
    #[error("larger than {} MiB; is it the right file?", MAX_FILE_BYTES >> 20)]
    TooLarge,
    /// It is no UTF-8 text.
    #[error("not UTF-8 text")]
    NotText,
}
