//! What a tune aims at: the TARGETS file. The numbers of the model free to move, each within its bounds;
//! the figures, curves and measured K&C rig data to meet, each with the tolerance that scales its miss;
//! the packaging the moved hardpoints must keep. Read and checked against the model before anything is
//! run, every error naming its key and the fix.
//!
//! ```json
//! { "free":    { "/suspension/macpherson/hardpoints/tie_rod_inner/2": [-0.080, -0.040] },
//!   "targets": [ { "figure": "parallel-travel/bump_steer", "value": 0.0, "tolerance": 0.5 },
//!                { "curve": "parallel-travel/toe_deg", "points": [[-0.05, 0.10], [0.05, -0.12]],
//!                  "tolerance": 0.005 },
//!                { "measured": "rig.csv", "analysis": "lateral-force", "columns": ["toe_deg"],
//!                  "tolerance": 0.002 } ],
//!   "constraints": [ { "distance": ["tie_rod_inner", "tie_rod_outer"], "min": 0.30, "max": 0.40 },
//!                    { "outside_sphere": "tie_rod_inner", "centre": [0.1, 0.4, 0.2], "radius": 0.05 },
//!                    { "outside_box": "tie_rod_inner", "min": [0, 0, 0], "max": [0.1, 0.1, 0.1] } ],
//!   "steps": 32 }
//! ```

use super::keys::{analysis_named, name_in, number, only, pair, steps, triple};
use super::parameter::{hardpoint_pointer, number_at};
use crate::kc::Analysis;
use serde_json::Value;

/// A number of the model free to move, within `[min, max]` (the file's units).
#[derive(Debug, Clone, PartialEq)]
pub struct Free {
    /// Its JSON pointer into the model file.
    pub pointer: String,
    /// Lower bound.
    pub min: f64,
    /// Upper bound.
    pub max: f64,
}

/// What one target asks of an analysis.
#[derive(Debug, Clone, PartialEq)]
pub enum Aim {
    /// A headline figure (by its key in `summary.json`) to equal `value`, in the unit the figure is written
    /// in with the default units (`deg/m`, `N/mm`, `%`: `docs/figures.md`, "printed").
    Figure { key: String, value: f64 },
    /// A column of the analysis's table (by its name in the CSV) to pass through `(load parameter, value)`
    /// points, the table interpolated between its rows.
    Curve { column: String, points: Vec<(f64, f64)> },
}

/// One target: an analysis, what it is to show, the tolerance its miss is measured in, and where it was
/// said (`targets[2]`, or a measured file's row).
#[derive(Debug, Clone, PartialEq)]
pub struct Target {
    /// Where the target was given, for messages: `targets[1] (parallel-travel/toe_deg)`.
    pub label: String,
    /// The analysis.
    pub analysis: Analysis,
    /// The load parameter's range to walk, when the target gives one (else the analysis's default).
    pub range: Option<(f64, f64)>,
    /// What to meet.
    pub aim: Aim,
    /// The miss that counts as met (the figure's or column's unit): each residual is the miss over it.
    pub tolerance: f64,
}

/// Packaging a moved hardpoint must keep.
#[derive(Debug, Clone, PartialEq)]
pub enum Constraint {
    /// Two hardpoints' distance (a link's length) within `[min, max]` (m).
    Distance { points: [String; 2], min: f64, max: f64 },
    /// A hardpoint kept out of a sphere.
    OutsideSphere { point: String, centre: [f64; 3], radius: f64 },
    /// A hardpoint kept out of a box (global axes).
    OutsideBox { point: String, min: [f64; 3], max: [f64; 3] },
}

impl Constraint {
    /// What it keeps, in the TARGETS file's words.
    pub fn said(&self) -> String {
        match self {
            Constraint::Distance { points: [a, b], .. } => format!("distance {a}–{b}"),
            Constraint::OutsideSphere { point, .. } => format!("{point} outside the sphere"),
            Constraint::OutsideBox { point, .. } => format!("{point} outside the box"),
        }
    }
}

/// A TARGETS file, read and checked against the model.
#[derive(Debug, Clone, PartialEq)]
pub struct Targets {
    /// The free numbers, in the file's order.
    pub free: Vec<Free>,
    /// The targets, a measured file's columns each its own curve target.
    pub targets: Vec<Target>,
    /// The packaging.
    pub constraints: Vec<Constraint>,
    /// Load steps of every sweep.
    pub steps: usize,
}

/// A measured file (the `measured` target) read: its columns and rows, by name.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// The analysis its header comment names, if it names one (`# analysis: lateral-force`).
    pub analysis: Option<String>,
    /// Column names, the first the load parameter.
    pub columns: Vec<String>,
    /// Rows of numbers.
    pub rows: Vec<Vec<f64>>,
}

/// Reads a measured K&C file: `#` comment lines (one may say `analysis: NAME`), a header of column names,
/// rows of numbers. `origin` names it in errors. A header whose column has no name, a name with a
/// control character in it, or the same name twice is refused: whichever column a reader then took would
/// be a guess.
pub fn read_measured(text: &str, origin: &str) -> Result<Measured, String> {
    let mut analysis = None;
    let mut columns: Option<Vec<String>> = None;
    let mut rows = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if let Some(comment) = line.strip_prefix('#') {
            if let Some(name) = comment.trim().strip_prefix("analysis:") {
                analysis = Some(name.trim().to_string());
            }
            continue;
        }
        if line.is_empty() {
            continue;
        }
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        match &columns {
            None => columns = Some(header(&cells, &format!("{origin}:{}", k + 1))?),
            Some(names) => {
                if cells.len() != names.len() {
                    return Err(format!(
                        "{origin}:{}: {} values where the header names {} columns",
                        k + 1,
                        cells.len(),
                        names.len()
                    ));
                }
                let row = cells
                    .iter()
                    .map(|c| c.parse::<f64>().ok().filter(|v| v.is_finite()))
                    .collect::<Option<Vec<f64>>>()
                    .ok_or_else(|| format!("{origin}:{}: a value that is not a finite number", k + 1))?;
                rows.push(row);
            }
        }
    }
    let columns = columns.ok_or_else(|| format!("{origin}: no header line naming the columns"))?;
    if rows.is_empty() {
        return Err(format!("{origin}: no rows of numbers under the header"));
    }
    Ok(Measured { analysis, columns, rows })
}

/// The column names of a measured file's header line `at`, each named once and in plain text.
fn header(cells: &[&str], at: &str) -> Result<Vec<String>, String> {
    for (k, name) in cells.iter().enumerate() {
        if name.is_empty() {
            return Err(format!("{at}: column {} has no name: name every column as the analysis's table does", k + 1));
        }
        if name.chars().any(crate::file::key_path::unprintable) {
            return Err(format!(
                "{at}: the name of column {} holds a control character ({}): name it in plain text",
                k + 1,
                crate::file::key_path::printable(name)
            ));
        }
        if cells[..k].contains(name) {
            return Err(format!("{at}: the column '{name}' is named twice: give each column once"));
        }
    }
    Ok(cells.iter().map(|c| c.to_string()).collect())
}

fn tolerance(object: &serde_json::Map<String, Value>, key: &str) -> Result<f64, String> {
    let t =
        object.get("tolerance").ok_or_else(|| format!("{key}: give its \"tolerance\": the miss that counts as met"))?;
    let t = number(t, &format!("{key}.tolerance"))?;
    if t > 0.0 {
        Ok(t)
    } else {
        Err(format!("{key}.tolerance: give a positive miss in the target's unit, got {}", crate::kc::plain(t)))
    }
}

/// Reads a TARGETS file against the model `document` (the model file as read). `origin` names the file;
/// `read_file` reads a measured file named in it (its path as given, relative to the TARGETS file).
pub fn read_targets(
    text: &str,
    origin: &str,
    document: &Value,
    read_file: impl Fn(&str) -> Result<String, String>,
) -> Result<Targets, String> {
    let root = super::keys::read_json(text, origin)?;
    let at = |key: &str| format!("{origin}: {key}");
    let object = root.as_object().ok_or_else(|| at("the file must be a JSON object with \"free\" and \"targets\""))?;
    only(object, &["free", "targets", "constraints", "steps"], &at("the top level"))?;
    let steps = steps(object, at)?;
    let free_object = object
        .get("free")
        .and_then(Value::as_object)
        .ok_or_else(|| at("free: give the numbers free to move, {\"/json/pointer\": [min, max], …}"))?;
    if free_object.is_empty() {
        return Err(at("free: no numbers free to move; name at least one by its JSON pointer"));
    }
    let mut free = Vec::new();
    for (pointer, bounds) in free_object {
        let key = format!("free[\"{pointer}\"]");
        let (min, max) = pair(bounds, &at(&key))?;
        let value = number_at(document, pointer).map_err(|why| at(&format!("{key}: {why}")))?;
        // Both finite (`pair` checks).
        if min >= max {
            return Err(at(&format!("{key}: the bounds [{min}, {max}] hold nothing; give [min, max] with min < max")));
        }
        if !(min..=max).contains(&value) {
            return Err(at(&format!(
                "{key}: the bounds [{min}, {max}] exclude the model's own value {value}; widen them to hold it"
            )));
        }
        free.push(Free { pointer: pointer.clone(), min, max });
    }
    let listed = object
        .get("targets")
        .and_then(Value::as_array)
        .ok_or_else(|| at("targets: give a list of targets ({\"figure\": …}, {\"curve\": …}, {\"measured\": …})"))?;
    if listed.is_empty() {
        return Err(at("targets: no targets; give at least one"));
    }
    let mut targets = Vec::new();
    for (k, t) in listed.iter().enumerate() {
        let key = format!("targets[{k}]");
        let o = t.as_object().ok_or_else(|| at(&format!("{key}: give an object")))?;
        let range = match o.get("range") {
            None => None,
            Some(r) => Some(pair(r, &at(&format!("{key}.range")))?),
        };
        let split = |path: &str, what: &str| -> Result<(Analysis, String), String> {
            let (analysis, name) = path.split_once('/').ok_or_else(|| {
                at(&format!(
                    "{key}.{what}: give \"analysis/{what}\", e.g. \"parallel-travel/bump_steer\", got '{path}'"
                ))
            })?;
            Ok((analysis_named(analysis, &at(&format!("{key}.{what}")))?, name.to_string()))
        };
        if let Some(path) = o.get("figure") {
            only(o, &["figure", "value", "tolerance", "range"], &at(&key))?;
            let (analysis, name) = split(name_in(path, &at(&format!("{key}.figure")))?, "figure")?;
            let value = number(o.get("value").unwrap_or(&Value::Null), &at(&format!("{key}.value")))?;
            targets.push(Target {
                label: format!("{key} ({}/{name})", analysis.name()),
                analysis,
                range,
                aim: Aim::Figure { key: name, value },
                tolerance: tolerance(o, &at(&key))?,
            });
        } else if let Some(path) = o.get("curve") {
            only(o, &["curve", "points", "tolerance", "range"], &at(&key))?;
            let (analysis, column) = split(name_in(path, &at(&format!("{key}.curve")))?, "curve")?;
            let points = o
                .get("points")
                .and_then(Value::as_array)
                .filter(|p| !p.is_empty())
                .ok_or_else(|| at(&format!("{key}.points: give [[load parameter, value], …]")))?
                .iter()
                .enumerate()
                .map(|(i, p)| pair(p, &at(&format!("{key}.points[{i}]"))))
                .collect::<Result<Vec<_>, _>>()?;
            targets.push(Target {
                label: format!("{key} ({}/{column})", analysis.name()),
                analysis,
                range,
                aim: Aim::Curve { column, points },
                tolerance: tolerance(o, &at(&key))?,
            });
        } else if let Some(file) = o.get("measured") {
            only(o, &["measured", "analysis", "columns", "tolerance", "range"], &at(&key))?;
            let file = name_in(file, &at(&format!("{key}.measured")))?;
            let name = name_in(o.get("analysis").unwrap_or(&Value::Null), &at(&format!("{key}.analysis")))?;
            let analysis = analysis_named(name, &at(&format!("{key}.analysis")))?;
            let measured = read_measured(&read_file(file).map_err(|e| at(&format!("{key}.measured: {e}")))?, file)
                .map_err(|e| at(&format!("{key}.measured: {e}")))?;
            if let Some(said) = measured.analysis.as_deref().filter(|a| *a != name) {
                return Err(at(&format!(
                    "{key}: {file} says it is of the analysis '{said}', but the target names '{name}'"
                )));
            }
            let columns: Vec<String> = match o.get("columns") {
                None => measured.columns[1..].to_vec(),
                Some(c) => c
                    .as_array()
                    .ok_or_else(|| at(&format!("{key}.columns: give a list of column names")))?
                    .iter()
                    .map(|v| name_in(v, &at(&format!("{key}.columns"))).map(String::from))
                    .collect::<Result<_, _>>()?,
            };
            let tolerance = tolerance(o, &at(&key))?;
            for column in columns {
                let c = measured.columns.iter().position(|x| *x == column).ok_or_else(|| {
                    at(&format!(
                        "{key}.columns: {file} has no column '{column}' (it has: {})",
                        measured.columns.join(", ")
                    ))
                })?;
                let points = measured.rows.iter().map(|r| (r[0], r[c])).collect();
                targets.push(Target {
                    label: format!("{key} ({file}: {}/{column})", analysis.name()),
                    analysis,
                    range,
                    aim: Aim::Curve { column, points },
                    tolerance,
                });
            }
        } else {
            return Err(at(&format!("{key}: give \"figure\", \"curve\" or \"measured\"")));
        }
    }
    // A range the analysis cannot walk is a mistake in the file, said as the command says it of --range.
    for target in targets.iter().filter(|t| t.range.is_some()) {
        let settings = crate::kc::Settings { range: target.range, steps, ..crate::kc::Settings::default() };
        crate::kc::check_settings(target.analysis, &settings)
            .map_err(|e| at(&format!("{}: range: {}", target.label, e.cause)))?;
    }
    let mut constraints = Vec::new();
    let hardpoint = |name: &str, key: &str| -> Result<String, String> {
        hardpoint_pointer(document, name).map(|_| name.to_string()).ok_or_else(|| {
            at(&format!("{key}: the model has no hardpoint '{name}' (a template's or the general form's hardpoints)"))
        })
    };
    for (k, c) in object.get("constraints").and_then(Value::as_array).into_iter().flatten().enumerate() {
        let key = format!("constraints[{k}]");
        let o = c.as_object().ok_or_else(|| at(&format!("{key}: give an object")))?;
        if let Some(points) = o.get("distance") {
            only(o, &["distance", "min", "max"], &at(&key))?;
            let names = points
                .as_array()
                .filter(|p| p.len() == 2)
                .ok_or_else(|| at(&format!("{key}.distance: give two hardpoint names [\"a\", \"b\"]")))?;
            let a = hardpoint(name_in(&names[0], &at(&key))?, &format!("{key}.distance"))?;
            let b = hardpoint(name_in(&names[1], &at(&key))?, &format!("{key}.distance"))?;
            let min = o.get("min").map(|v| number(v, &at(&format!("{key}.min")))).transpose()?.unwrap_or(0.0);
            let max = o.get("max").map(|v| number(v, &at(&format!("{key}.max")))).transpose()?.unwrap_or(f64::INFINITY);
            if min >= max {
                return Err(at(&format!("{key}: min {min} is not below max {max}")));
            }
            constraints.push(Constraint::Distance { points: [a, b], min, max });
        } else if let Some(point) = o.get("outside_sphere") {
            only(o, &["outside_sphere", "centre", "radius"], &at(&key))?;
            let point = hardpoint(name_in(point, &at(&key))?, &format!("{key}.outside_sphere"))?;
            let centre = triple(o.get("centre").unwrap_or(&Value::Null), &at(&format!("{key}.centre")))?;
            let radius = number(o.get("radius").unwrap_or(&Value::Null), &at(&format!("{key}.radius")))?;
            if radius <= 0.0 {
                return Err(at(&format!(
                    "{key}.radius: give a positive radius in m, got {}",
                    crate::kc::plain(radius)
                )));
            }
            constraints.push(Constraint::OutsideSphere { point, centre, radius });
        } else if let Some(point) = o.get("outside_box") {
            only(o, &["outside_box", "min", "max"], &at(&key))?;
            let point = hardpoint(name_in(point, &at(&key))?, &format!("{key}.outside_box"))?;
            let min = triple(o.get("min").unwrap_or(&Value::Null), &at(&format!("{key}.min")))?;
            let max = triple(o.get("max").unwrap_or(&Value::Null), &at(&format!("{key}.max")))?;
            if (0..3).any(|i| min[i] >= max[i]) {
                return Err(at(&format!("{key}: each of min's coordinates must be below max's")));
            }
            constraints.push(Constraint::OutsideBox { point, min, max });
        } else {
            return Err(at(&format!("{key}: give \"distance\", \"outside_sphere\" or \"outside_box\"")));
        }
    }
    Ok(Targets { free, targets, constraints, steps })
}
