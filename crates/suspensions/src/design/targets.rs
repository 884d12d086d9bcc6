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

use super::keys::{analysis_named, name_in, number, only, pair, steps, triple, KeyRefusal};
use super::parameter::{hardpoint_pointer, number_at, NoNumber};
use crate::kc::{self, Analysis};
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
    /// points, the table interpolated between its rows, its miss measured as `measure` says.
    Curve { column: String, points: Vec<(f64, f64)>, measure: CurveMeasure },
}

/// How a curve target's miss is measured (its `measure`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CurveMeasure {
    /// At each of its points: met when every point's miss is within the tolerance.
    Points,
    /// The root mean square of the miss over the points' span, the target curve straight between its
    /// points: met when it is within the tolerance (in the column's unit).
    Rms,
    /// The area between the two curves over the points' span: met when it is within the tolerance (in the
    /// column's unit times the load parameter's: deg·m for a toe curve over wheel travel).
    Area,
}

impl CurveMeasure {
    /// The measure's name in the TARGETS file.
    pub fn name(self) -> &'static str {
        match self {
            CurveMeasure::Points => "points",
            CurveMeasure::Rms => "rms",
            CurveMeasure::Area => "area",
        }
    }
}

/// One place a curve target is read: the load parameter `at`, the target curve's value there, and the
/// reading's quadrature weight over the span (load parameter's unit; 1 for a point of a [`CurveMeasure::Points`]
/// target, and for a figure).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveReading {
    /// The load parameter.
    pub at: f64,
    /// The target's value there.
    pub aim: f64,
    /// The reading's weight.
    pub weight: f64,
}

/// Where a curve target with `points` is read under `measure`, given the load parameters of the table's
/// rows, `rows`. At its points alone for [`CurveMeasure::Points`]. Over the points' span otherwise, the
/// target curve straight between its points: at each point and at each row inside the span, weighted by
/// the trapezoidal rule, so that `Σ w e²` and `Σ w |e|` of the misses `e` are the span's integrals of the
/// miss squared and of its size, to the second order in the rows' spacing; the points are nodes too, so
/// the target's corners fall between panels, not inside one.
pub fn readings(points: &[(f64, f64)], measure: CurveMeasure, rows: &[f64]) -> Vec<CurveReading> {
    if measure == CurveMeasure::Points {
        return points.iter().map(|&(at, aim)| CurveReading { at, aim, weight: 1.0 }).collect();
    }
    // Read as sorted by load parameter, each load once (the file's checks).
    let (a, b) = (points[0].0, points[points.len() - 1].0);
    let mut at: Vec<f64> = points.iter().map(|p| p.0).chain(rows.iter().copied().filter(|&t| a < t && t < b)).collect();
    at.sort_by(f64::total_cmp);
    at.dedup();
    let aim = |t: f64| {
        let k = points.windows(2).position(|w| t <= w[1].0).unwrap_or(points.len() - 2);
        let ((t0, v0), (t1, v1)) = (points[k], points[k + 1]);
        v0 + (v1 - v0) * (t - t0) / (t1 - t0)
    };
    (0..at.len())
        .map(|i| {
            let left = if i > 0 { at[i] - at[i - 1] } else { 0.0 };
            let right = if i + 1 < at.len() { at[i + 1] - at[i] } else { 0.0 };
            CurveReading { at: at[i], aim: aim(at[i]), weight: 0.5 * (left + right) }
        })
        .collect()
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
    /// The miss that counts as met, or the measured data's noise (the figure's or column's unit): each
    /// residual is the miss over it.
    pub tolerance: f64,
    /// Which of the two `tolerance` is, and so how the target is judged.
    pub scale: MissScale,
    /// How much the target counts in a tune against the others (`weight`, default 1): its residuals are
    /// its misses over its tolerance times it. Whether it is met is judged unweighted.
    pub weight: f64,
}

/// What a target's misses are measured by, and how it is judged.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MissScale {
    /// A tolerance: met when every point's miss is within it.
    Tolerance,
    /// The measured data's noise, one standard deviation (a measured target's `noise`): met when the misses
    /// are as large as the noise makes them, `χ²/n = Σ (miss/noise)² / n` within three of its standard
    /// deviations, `√(2/n)`, above its mean, 1. A fit to noisy data misses every point by the noise; judged
    /// point by point against it, it would be "not met" although it found the truth.
    Noise,
}

impl Target {
    /// The curve measure, [`CurveMeasure::Points`] for a figure.
    pub fn measure(&self) -> CurveMeasure {
        match self.aim {
            Aim::Curve { measure, .. } => measure,
            Aim::Figure { .. } => CurveMeasure::Points,
        }
    }

    /// What the target's misses `misses` (each reading's miss over [`Target::tolerance`], unweighted by the
    /// target's `weight`), read with the `weights` of its [`CurveReading`]s, measure against its tolerance: the
    /// largest miss; the misses' root mean square or the area between the curves; or, against noise, `χ²/n`
    /// over the most that noise alone gives. It is met when this is at most 1.
    pub fn measured(&self, misses: &[f64], weights: &[f64]) -> f64 {
        let span: f64 = weights.iter().sum();
        match (self.scale, self.measure()) {
            (MissScale::Noise, _) => {
                let (chi2, limit) = chi_square_per_point(misses);
                chi2 / limit
            }
            (MissScale::Tolerance, CurveMeasure::Points) => misses.iter().fold(0.0f64, |m, r| m.max(r.abs())),
            (MissScale::Tolerance, CurveMeasure::Rms) => {
                (misses.iter().zip(weights).map(|(m, w)| w * m * m).sum::<f64>() / span).sqrt()
            }
            (MissScale::Tolerance, CurveMeasure::Area) => misses.iter().zip(weights).map(|(m, w)| w * m.abs()).sum(),
        }
    }

    /// Whether the misses read with `weights` meet the target ([`Target::measured`] at most 1).
    pub fn met_by(&self, misses: &[f64], weights: &[f64]) -> bool {
        self.measured(misses, weights) <= 1.0
    }

    /// How the target is judged on `misses` read with `weights`, in words: the largest miss against the
    /// tolerance, the root mean square or area of the miss against it, or the misses' χ² per point against
    /// what the noise allows.
    pub fn judged_words(&self, misses: &[f64], weights: &[f64]) -> String {
        let measured = kc::significant(self.measured(misses, weights), 3);
        match (self.scale, self.measure()) {
            (MissScale::Tolerance, CurveMeasure::Points) => format!("largest miss {measured} of its tolerance"),
            (MissScale::Tolerance, CurveMeasure::Rms) => {
                format!("root mean square of the miss over the curve's span {measured} of its tolerance")
            }
            (MissScale::Tolerance, CurveMeasure::Area) => {
                format!("area between the curves over its span {measured} of its tolerance")
            }
            (MissScale::Noise, _) => {
                let (chi2, limit) = chi_square_per_point(misses);
                format!(
                    "χ²/n {} over {} points against the noise, {} the {} that noise alone reaches",
                    kc::significant(chi2, 3),
                    misses.len(),
                    if chi2 <= limit { "within" } else { "beyond" },
                    kc::significant(limit, 3)
                )
            }
        }
    }
}

/// The misses' `χ²/n` over the `residuals` (each miss over the noise) and the largest that noise alone
/// gives but rarely: its mean, 1, and three standard deviations, `3 √(2/n)`.
pub fn chi_square_per_point(residuals: &[f64]) -> (f64, f64) {
    let n = residuals.len().max(1) as f64;
    (residuals.iter().map(|r| r * r).sum::<f64>() / n, 1.0 + 3.0 * (2.0 / n).sqrt())
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

/// A figure to make as small or as large as the targets, held as bounds, allow (the `objective`).
#[derive(Debug, Clone, PartialEq)]
pub struct Objective {
    /// Where it was given, for messages: `objective (parallel-travel/bump_steer)`.
    pub label: String,
    /// The analysis.
    pub analysis: Analysis,
    /// The load parameter's range to walk, when given.
    pub range: Option<(f64, f64)>,
    /// The figure's key.
    pub key: String,
    /// Least or most.
    pub sense: Sense,
}

/// Which way an [`Objective`] moves its figure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sense {
    /// As small as it can be (the most negative, for a signed figure).
    Least,
    /// As large as it can be.
    Most,
}

impl Sense {
    /// The word, as the TARGETS file gives it.
    pub fn name(self) -> &'static str {
        match self {
            Sense::Least => "least",
            Sense::Most => "most",
        }
    }
}

/// A TARGETS file, read and checked against the model.
#[derive(Debug, Clone, PartialEq)]
pub struct Targets {
    /// The figure to make least or most, if any: then each target is a bound the tune must keep (each
    /// point's miss within its tolerance), not a miss to make small.
    pub objective: Option<Objective>,
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

/// A measured K&C file refused, naming the file (`origin`) and, where there is one, its line.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeasuredError {
    /// A row with another count of values than the header has columns.
    #[error("{origin}:{line}: {values} values where the header names {columns} columns")]
    RowLength {
        /// The file.
        origin: String,
        /// The line, from 1.
        line: usize,
        /// The row's values.
        values: usize,
        /// The header's columns.
        columns: usize,
    },
    /// A row with a value that is not a finite number.
    #[error("{origin}:{line}: a value that is not a finite number")]
    NotNumber {
        /// The file.
        origin: String,
        /// The line, from 1.
        line: usize,
    },
    /// No header line.
    #[error("{origin}: no header line naming the columns")]
    NoHeader {
        /// The file.
        origin: String,
    },
    /// A header and no rows.
    #[error("{origin}: no rows of numbers under the header")]
    NoRows {
        /// The file.
        origin: String,
    },
    /// A column of the header without a name.
    #[error("{origin}:{line}: column {column} has no name: name every column as the analysis's table does")]
    Unnamed {
        /// The file.
        origin: String,
        /// The header's line, from 1.
        line: usize,
        /// The column, from 1.
        column: usize,
    },
    /// A column's name with a control character in it.
    #[error(
        "{origin}:{line}: the name of column {column} holds a control character ({}): name it in plain text",
        crate::file::key_path::printable(name)
    )]
    Unprintable {
        /// The file.
        origin: String,
        /// The header's line, from 1.
        line: usize,
        /// The column, from 1.
        column: usize,
        /// Its name, as written.
        name: String,
    },
    /// A column named twice.
    #[error("{origin}:{line}: the column '{name}' is named twice: give each column once")]
    Twice {
        /// The file.
        origin: String,
        /// The header's line, from 1.
        line: usize,
        /// The name.
        name: String,
    },
}

/// Reads a measured K&C file: `#` comment lines (one may say `analysis: NAME`), a header of column names,
/// rows of numbers. `origin` names it in errors. A header whose column has no name, a name with a
/// control character in it, or the same name twice is refused: whichever column a reader then took would
/// be a guess.
pub fn read_measured(text: &str, origin: &str) -> Result<Measured, MeasuredError> {
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
            None => columns = Some(header(&cells, origin, k + 1)?),
            Some(names) => {
                if cells.len() != names.len() {
                    return Err(MeasuredError::RowLength {
                        origin: origin.into(),
                        line: k + 1,
                        values: cells.len(),
                        columns: names.len(),
                    });
                }
                let row = cells
                    .iter()
                    .map(|c| c.parse::<f64>().ok().filter(|v| v.is_finite()))
                    .collect::<Option<Vec<f64>>>()
                    .ok_or_else(|| MeasuredError::NotNumber { origin: origin.into(), line: k + 1 })?;
                rows.push(row);
            }
        }
    }
    let columns = columns.ok_or_else(|| MeasuredError::NoHeader { origin: origin.into() })?;
    if rows.is_empty() {
        return Err(MeasuredError::NoRows { origin: origin.into() });
    }
    Ok(Measured { analysis, columns, rows })
}

/// The column names of a measured file's header, at `line` of `origin`, each named once and in plain text.
fn header(cells: &[&str], origin: &str, line: usize) -> Result<Vec<String>, MeasuredError> {
    for (k, name) in cells.iter().enumerate() {
        let (origin, column) = (origin.to_string(), k + 1);
        if name.is_empty() {
            return Err(MeasuredError::Unnamed { origin, line, column });
        }
        if name.chars().any(crate::file::key_path::unprintable) {
            return Err(MeasuredError::Unprintable { origin, line, column, name: name.to_string() });
        }
        if cells[..k].contains(name) {
            return Err(MeasuredError::Twice { origin, line, name: name.to_string() });
        }
    }
    Ok(cells.iter().map(|c| c.to_string()).collect())
}

/// A TARGETS file refused: the file, and what is wrong where in it.
#[derive(Debug, Clone, thiserror::Error)]
#[error("{origin}: {refusal}")]
pub struct TargetsError {
    /// The file.
    pub origin: String,
    /// What is wrong, naming the key (boxed: a refusal carries the key, what it holds and what it may).
    pub refusal: Box<TargetsRefusal>,
}

/// What is wrong in a TARGETS file, naming the key (`targets[2].tolerance`) and what to give instead.
#[derive(Debug, Clone, thiserror::Error)]
pub enum TargetsRefusal {
    /// A key that holds what no key of its name may.
    #[error(transparent)]
    Key(#[from] KeyRefusal),
    /// The file is no JSON object.
    #[error("the file must be a JSON object with \"free\" and \"targets\"")]
    NotObject,
    /// No `free` object.
    #[error("free: give the numbers free to move, {{\"/json/pointer\": [min, max], …}}")]
    NoFree,
    /// An empty `free` object.
    #[error("free: no numbers free to move; name at least one by its JSON pointer")]
    NothingFree,
    /// A free pointer that names no number of the model.
    #[error("free[\"{pointer}\"]: {why}")]
    FreeNoNumber {
        /// The pointer.
        pointer: String,
        /// What it names instead.
        why: NoNumber,
    },
    /// Bounds with nothing between them.
    #[error("free[\"{pointer}\"]: the bounds [{min}, {max}] hold nothing; give [min, max] with min < max")]
    EmptyBounds {
        /// The free number's pointer.
        pointer: String,
        /// Lower bound.
        min: f64,
        /// Upper bound.
        max: f64,
    },
    /// Bounds that leave out the model's own value.
    #[error(
        "free[\"{pointer}\"]: the bounds [{min}, {max}] exclude the model's own value {value}; widen them to hold it"
    )]
    BoundsExclude {
        /// The free number's pointer.
        pointer: String,
        /// Lower bound.
        min: f64,
        /// Upper bound.
        max: f64,
        /// The model's value.
        value: f64,
    },
    /// No `targets` list.
    #[error("targets: give a list of targets ({{\"figure\": …}}, {{\"curve\": …}}, {{\"measured\": …}})")]
    NoTargetList,
    /// An empty `targets` list.
    #[error("targets: no targets; give at least one")]
    NoTargets,
    /// A target or constraint that is not an object.
    #[error("{key}: give an object")]
    NotObjectAt {
        /// The key.
        key: String,
    },
    /// A figure or curve not named `analysis/name`.
    #[error("{key}.{what}: give \"analysis/{what}\", e.g. \"parallel-travel/bump_steer\", got '{path}'")]
    NotAnalysisPath {
        /// The target's key.
        key: String,
        /// `figure` or `curve`.
        what: &'static str,
        /// What was given.
        path: String,
    },
    /// A curve without points.
    #[error("{key}.points: give [[load parameter, value], …]")]
    NoPoints {
        /// The target's key.
        key: String,
    },
    /// A curve measure of no known name.
    #[error("{key}: '{got}' is no curve measure: give \"points\" (each point's miss), \"rms\" (the miss's root mean square over the points' span) or \"area\" (the area between the curves)")]
    NoMeasure {
        /// The measure's key.
        key: String,
        /// The name given.
        got: String,
    },
    /// An `rms` or `area` curve whose points span no range.
    #[error(
        "{key}: a curve measured by its {measure} needs at least two points in increasing order of the load \
         parameter, which span the curve it measures"
    )]
    NoSpan {
        /// The points' key.
        key: String,
        /// The measure.
        measure: &'static str,
    },
    /// An objective that names neither `least` nor `most`, or both.
    #[error("objective: give one of \"least\" or \"most\", the figure by \"analysis/key\"")]
    NoSense,
    /// A target that cannot be a bound under an objective.
    #[error(
        "{label}: with an objective each target is a bound, every point's miss within its tolerance: give a \
         figure or a curve measured at its points, with a tolerance (no noise, rms or area)"
    )]
    NotBound {
        /// The target.
        label: String,
    },
    /// A weight on a target that is a bound.
    #[error("{label}: with an objective each target is a bound, which a weight does not change: leave out \"weight\"")]
    WeightedBound {
        /// The target.
        label: String,
    },
    /// A target without a tolerance.
    #[error("{key}: give its \"tolerance\": the miss that counts as met")]
    NoTolerance {
        /// The target's key.
        key: String,
    },
    /// A tolerance or noise that is not positive.
    #[error("{key}: give a positive miss in the target's unit, got {}", kc::plain(*got))]
    ToleranceNotPositive {
        /// The target's key.
        key: String,
        /// The tolerance given.
        got: f64,
    },
    /// A weight that is not a positive number.
    #[error(
        "{key}: give a positive number, how much the target counts against the others in a tune (default 1), got {}",
        kc::plain(*got)
    )]
    WeightNotPositive {
        /// The weight's key.
        key: String,
        /// The weight given.
        got: f64,
    },
    /// A measured target with both a tolerance and a noise.
    #[error(
        "{key}: give its \"tolerance\" (the miss that counts as met, every point within it) or its \"noise\" (the \
         data's, one standard deviation: judged by χ² against it), not both"
    )]
    ToleranceAndNoise {
        /// The target's key.
        key: String,
    },
    /// A per-column tolerance or noise naming a column the target does not aim at.
    #[error("{key}: '{name}' is not one of the target's columns")]
    NotAColumn {
        /// The key of the tolerance or noise.
        key: String,
        /// The name given.
        name: String,
    },
    /// A per-column tolerance or noise without a column's.
    #[error("{key}: give one for '{column}' too, or one number for every column")]
    NoColumnScale {
        /// The key of the tolerance or noise.
        key: String,
        /// The column.
        column: String,
    },
    /// A measured file that cannot be read, in the words of the caller that reads it.
    #[error("{key}.measured: {why}")]
    Unreadable {
        /// The target's key.
        key: String,
        /// Why.
        why: String,
    },
    /// A measured file that is refused.
    #[error("{key}.measured: {error}")]
    Measured {
        /// The target's key.
        key: String,
        /// Why.
        error: MeasuredError,
    },
    /// A measured file of another analysis than the target names.
    #[error("{key}: {file} says it is of the analysis '{said}', but the target names '{name}'")]
    OtherAnalysis {
        /// The target's key.
        key: String,
        /// The measured file.
        file: String,
        /// The analysis it says it is of.
        said: String,
        /// The analysis the target names.
        name: String,
    },
    /// `columns` that is not a list.
    #[error("{key}.columns: give a list of column names")]
    ColumnsNotList {
        /// The target's key.
        key: String,
    },
    /// A column the measured file has not.
    #[error("{key}.columns: {file} has no column '{column}' (it has: {})", has.join(", "))]
    NoColumn {
        /// The target's key.
        key: String,
        /// The measured file.
        file: String,
        /// The column asked for.
        column: String,
        /// The columns it has.
        has: Vec<String>,
    },
    /// A target that names no figure, curve or measured file.
    #[error("{key}: give \"figure\", \"curve\" or \"measured\"")]
    NoAim {
        /// The target's key.
        key: String,
    },
    /// A range the analysis cannot walk, said as the command says it of `--range`.
    #[error("{label}: range: {cause}")]
    Range {
        /// The target's label.
        label: String,
        /// Why.
        cause: kc::Cause,
    },
    /// A hardpoint the model has not.
    #[error("{key}: the model has no hardpoint '{name}' (a template's or the general form's hardpoints)")]
    NoHardpoint {
        /// The constraint's key.
        key: String,
        /// The name given.
        name: String,
    },
    /// A distance not between two hardpoints.
    #[error("{key}.distance: give two hardpoint names [\"a\", \"b\"]")]
    NotTwoNames {
        /// The constraint's key.
        key: String,
    },
    /// A distance's bounds with nothing between them.
    #[error("{key}: min {min} is not below max {max}")]
    MinNotBelowMax {
        /// The constraint's key.
        key: String,
        /// Lower bound.
        min: f64,
        /// Upper bound.
        max: f64,
    },
    /// A sphere's radius that is not positive.
    #[error("{key}.radius: give a positive radius in m, got {}", kc::plain(*got))]
    RadiusNotPositive {
        /// The constraint's key.
        key: String,
        /// The radius given.
        got: f64,
    },
    /// A box with a corner not below the other.
    #[error("{key}: each of min's coordinates must be below max's")]
    BoxInsideOut {
        /// The constraint's key.
        key: String,
    },
    /// A constraint that names no kind of packaging.
    #[error("{key}: give \"distance\", \"outside_sphere\" or \"outside_box\"")]
    NoPackaging {
        /// The constraint's key.
        key: String,
    },
}

fn tolerance(object: &serde_json::Map<String, Value>, key: &str) -> Result<f64, TargetsRefusal> {
    let t = object.get("tolerance").ok_or_else(|| TargetsRefusal::NoTolerance { key: key.into() })?;
    positive(number(t, &format!("{key}.tolerance"))?, &format!("{key}.tolerance"))
}

/// The `objective`: `{"least": "analysis/figure"}` or `{"most": …}`, and an optional `range`.
fn objective(o: &Value) -> Result<Objective, TargetsRefusal> {
    use TargetsRefusal as R;
    let key = "objective";
    let o = o.as_object().ok_or_else(|| R::NotObjectAt { key: key.into() })?;
    only(o, &["least", "most", "range"], key)?;
    let (sense, path) = match (o.get("least"), o.get("most")) {
        (Some(p), None) => (Sense::Least, p),
        (None, Some(p)) => (Sense::Most, p),
        _ => return Err(R::NoSense),
    };
    let named = format!("{key}.{}", sense.name());
    let path = name_in(path, &named)?;
    let (analysis, figure) = path.split_once('/').ok_or_else(|| R::NotAnalysisPath {
        key: key.into(),
        what: "figure",
        path: path.to_string(),
    })?;
    let analysis = analysis_named(analysis, &named)?;
    let range = o.get("range").map(|r| pair(r, &format!("{key}.range"))).transpose()?;
    Ok(Objective {
        label: format!("{key} ({} {}/{figure})", sense.name(), analysis.name()),
        analysis,
        range,
        key: figure.to_string(),
        sense,
    })
}

/// A curve target's `measure` (`"points"` when not given); an `rms` or `area` measure needs at least two
/// `points` in increasing order of the load parameter, which span the curve it measures.
fn curve_measure(
    object: &serde_json::Map<String, Value>,
    key: &str,
    points: &[(f64, f64)],
) -> Result<CurveMeasure, TargetsRefusal> {
    let measures = [CurveMeasure::Points, CurveMeasure::Rms, CurveMeasure::Area];
    let Some(m) = object.get("measure") else { return Ok(CurveMeasure::Points) };
    let name = name_in(m, &format!("{key}.measure"))?;
    let measure = measures
        .into_iter()
        .find(|m| m.name() == name)
        .ok_or_else(|| TargetsRefusal::NoMeasure { key: format!("{key}.measure"), got: name.to_string() })?;
    if measure != CurveMeasure::Points
        && (points.len() < 2
            || points.windows(2).any(|w| w[0].0.partial_cmp(&w[1].0) != Some(std::cmp::Ordering::Less)))
    {
        return Err(TargetsRefusal::NoSpan { key: format!("{key}.points"), measure: measure.name() });
    }
    Ok(measure)
}

/// A target's `weight`: a positive number, 1 when not given.
fn weight(object: &serde_json::Map<String, Value>, key: &str) -> Result<f64, TargetsRefusal> {
    let Some(w) = object.get("weight") else { return Ok(1.0) };
    let w = number(w, &format!("{key}.weight"))?;
    if w > 0.0 && w.is_finite() {
        Ok(w)
    } else {
        Err(TargetsRefusal::WeightNotPositive { key: format!("{key}.weight"), got: w })
    }
}

/// A tolerance or a noise at `key`, which must be positive.
fn positive(t: f64, key: &str) -> Result<f64, TargetsRefusal> {
    if t > 0.0 {
        Ok(t)
    } else {
        Err(TargetsRefusal::ToleranceNotPositive { key: key.into(), got: t })
    }
}

/// Reads a TARGETS file against the model `document` (the model file as read). `origin` names the file;
/// `read_file` reads a measured file named in it (its path as given, relative to the TARGETS file), or says
/// why it cannot.
pub fn read_targets(
    text: &str,
    origin: &str,
    document: &Value,
    read_file: impl Fn(&str) -> Result<String, String>,
) -> Result<Targets, TargetsError> {
    read_targets_as(Reading::ToTune, text, origin, document, read_file)
}

/// What a TARGETS file is read for: to tune, which moves its free numbers, or to judge a run against its
/// targets (`run --targets`), which moves nothing, so that `free` may be left out (free numbers given are
/// still checked against the model).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reading {
    /// For `tune`: `free` names at least one number.
    ToTune,
    /// For judging a run: `free` may be left out.
    ToJudge,
}

/// [`read_targets`], read for `reading`.
pub fn read_targets_as(
    reading: Reading,
    text: &str,
    origin: &str,
    document: &Value,
    read_file: impl Fn(&str) -> Result<String, String>,
) -> Result<Targets, TargetsError> {
    targets_in(text, document, read_file, reading)
        .map_err(|refusal| TargetsError { origin: origin.into(), refusal: Box::new(refusal) })
}

fn targets_in(
    text: &str,
    document: &Value,
    read_file: impl Fn(&str) -> Result<String, String>,
    reading: Reading,
) -> Result<Targets, TargetsRefusal> {
    use TargetsRefusal as R;
    let root = super::keys::read_json(text)?;
    let object = root.as_object().ok_or(R::NotObject)?;
    only(object, &["free", "objective", "targets", "constraints", "steps"], "the top level")?;
    let steps = steps(object)?;
    let free = if reading == Reading::ToJudge && !object.contains_key("free") {
        Vec::new()
    } else {
        free_numbers(object, document)?
    };
    let listed = object.get("targets").and_then(Value::as_array).ok_or(R::NoTargetList)?;
    if listed.is_empty() {
        return Err(R::NoTargets);
    }
    let mut targets = Vec::new();
    for (k, t) in listed.iter().enumerate() {
        targets.extend(targets_of(k, t, &read_file)?);
    }
    // A range the analysis cannot walk is a mistake in the file, said as the command says it of --range.
    for target in targets.iter().filter(|t| t.range.is_some()) {
        let settings = kc::Settings { range: target.range, steps, ..kc::Settings::default() };
        kc::check_settings(target.analysis, &settings)
            .map_err(|e| R::Range { label: target.label.clone(), cause: e.cause })?;
    }
    let listed = object.get("constraints").and_then(Value::as_array).into_iter().flatten();
    let constraints = listed.enumerate().map(|(k, c)| constraint(k, c, document)).collect::<Result<_, _>>()?;
    let objective = object.get("objective").map(objective).transpose()?;
    if objective.is_some() {
        // Each target a bound: a miss within its tolerance at every point, as given.
        if let Some(t) = targets.iter().find(|t| t.scale == MissScale::Noise || t.measure() != CurveMeasure::Points) {
            return Err(R::NotBound { label: t.label.clone() });
        }
        if let Some(t) = targets.iter().find(|t| t.weight != 1.0) {
            return Err(R::WeightedBound { label: t.label.clone() });
        }
    }
    if let Some(o) = &objective {
        let settings = kc::Settings { range: o.range, steps, ..kc::Settings::default() };
        kc::check_settings(o.analysis, &settings).map_err(|e| R::Range { label: o.label.clone(), cause: e.cause })?;
    }
    Ok(Targets { objective, free, targets, constraints, steps })
}

/// The `free` numbers of the TARGETS file's top level `object`, each with its bounds, which must hold its
/// value in the model `document`.
fn free_numbers(object: &serde_json::Map<String, Value>, document: &Value) -> Result<Vec<Free>, TargetsRefusal> {
    use TargetsRefusal as R;
    let free_object = object.get("free").and_then(Value::as_object).ok_or(R::NoFree)?;
    if free_object.is_empty() {
        return Err(R::NothingFree);
    }
    let mut free = Vec::new();
    for (pointer, bounds) in free_object {
        let key = format!("free[\"{pointer}\"]");
        let (min, max) = pair(bounds, &key)?;
        let value = number_at(document, pointer).map_err(|why| R::FreeNoNumber { pointer: pointer.clone(), why })?;
        // Both finite (`pair` checks).
        if min >= max {
            return Err(R::EmptyBounds { pointer: pointer.clone(), min, max });
        }
        if !(min..=max).contains(&value) {
            return Err(R::BoundsExclude { pointer: pointer.clone(), min, max, value });
        }
        free.push(Free { pointer: pointer.clone(), min, max });
    }
    Ok(free)
}

/// The targets of entry `k`, `t`, of the `targets` list: one for a figure or a curve, one per column for
/// a measured file (read by `read_file`).
fn targets_of(
    k: usize,
    t: &Value,
    read_file: &impl Fn(&str) -> Result<String, String>,
) -> Result<Vec<Target>, TargetsRefusal> {
    use TargetsRefusal as R;
    let key = format!("targets[{k}]");
    let o = t.as_object().ok_or_else(|| R::NotObjectAt { key: key.clone() })?;
    let range = match o.get("range") {
        None => None,
        Some(r) => Some(pair(r, &format!("{key}.range"))?),
    };
    let split = |path: &str, what: &'static str| -> Result<(Analysis, String), TargetsRefusal> {
        let (analysis, name) = path.split_once('/').ok_or_else(|| R::NotAnalysisPath {
            key: key.clone(),
            what,
            path: path.to_string(),
        })?;
        Ok((analysis_named(analysis, &format!("{key}.{what}"))?, name.to_string()))
    };
    if let Some(path) = o.get("figure") {
        only(o, &["figure", "value", "tolerance", "range", "weight"], &key)?;
        let (analysis, name) = split(name_in(path, &format!("{key}.figure"))?, "figure")?;
        let value = number(o.get("value").unwrap_or(&Value::Null), &format!("{key}.value"))?;
        Ok(vec![Target {
            label: format!("{key} ({}/{name})", analysis.name()),
            analysis,
            range,
            aim: Aim::Figure { key: name, value },
            tolerance: tolerance(o, &key)?,
            scale: MissScale::Tolerance,
            weight: weight(o, &key)?,
        }])
    } else if let Some(path) = o.get("curve") {
        only(o, &["curve", "points", "measure", "tolerance", "range", "weight"], &key)?;
        let (analysis, column) = split(name_in(path, &format!("{key}.curve"))?, "curve")?;
        let points = o
            .get("points")
            .and_then(Value::as_array)
            .filter(|p| !p.is_empty())
            .ok_or_else(|| R::NoPoints { key: key.clone() })?
            .iter()
            .enumerate()
            .map(|(i, p)| pair(p, &format!("{key}.points[{i}]")))
            .collect::<Result<Vec<_>, _>>()?;
        let measure = curve_measure(o, &key, &points)?;
        Ok(vec![Target {
            label: format!("{key} ({}/{column})", analysis.name()),
            analysis,
            range,
            aim: Aim::Curve { column, points, measure },
            tolerance: tolerance(o, &key)?,
            scale: MissScale::Tolerance,
            weight: weight(o, &key)?,
        }])
    } else if let Some(file) = o.get("measured") {
        measured_targets(key, o, file, range, read_file)
    } else {
        Err(R::NoAim { key })
    }
}

/// The targets of the entry `key`, `o`, that aims at the measured `file` (read by `read_file`): one curve
/// per column it names (every column but the first when it names none).
fn measured_targets(
    key: String,
    o: &serde_json::Map<String, Value>,
    file: &Value,
    range: Option<(f64, f64)>,
    read_file: &impl Fn(&str) -> Result<String, String>,
) -> Result<Vec<Target>, TargetsRefusal> {
    use TargetsRefusal as R;
    only(o, &["measured", "analysis", "columns", "tolerance", "noise", "range", "weight"], &key)?;
    let file = name_in(file, &format!("{key}.measured"))?;
    let name = name_in(o.get("analysis").unwrap_or(&Value::Null), &format!("{key}.analysis"))?;
    let analysis = analysis_named(name, &format!("{key}.analysis"))?;
    let text = read_file(file).map_err(|why| R::Unreadable { key: key.clone(), why })?;
    let measured = read_measured(&text, file).map_err(|error| R::Measured { key: key.clone(), error })?;
    if let Some(said) = measured.analysis.as_deref().filter(|a| *a != name) {
        return Err(R::OtherAnalysis { key: key.clone(), file: file.into(), said: said.into(), name: name.into() });
    }
    let columns: Vec<String> = match o.get("columns") {
        None => measured.columns[1..].to_vec(),
        Some(c) => c
            .as_array()
            .ok_or_else(|| R::ColumnsNotList { key: key.clone() })?
            .iter()
            .map(|v| name_in(v, &format!("{key}.columns")).map(String::from))
            .collect::<Result<_, _>>()?,
    };
    // A tolerance, or the data's noise: one number for every column, or one per column by its name.
    let (scale, word) = match (o.contains_key("tolerance"), o.contains_key("noise")) {
        (true, true) => return Err(R::ToleranceAndNoise { key }),
        (false, true) => (MissScale::Noise, "noise"),
        _ => (MissScale::Tolerance, "tolerance"),
    };
    let per_column = |column: &str| -> Result<f64, TargetsRefusal> {
        let given = o.get(word);
        match given.and_then(Value::as_object) {
            Some(by_column) => {
                if let Some(other) = by_column.keys().find(|k| !columns.contains(k)) {
                    return Err(R::NotAColumn { key: format!("{key}.{word}"), name: other.clone() });
                }
                let one = by_column
                    .get(column)
                    .ok_or_else(|| R::NoColumnScale { key: format!("{key}.{word}"), column: column.into() })?;
                positive(number(one, &format!("{key}.{word}.{column}"))?, &format!("{key}.{word}.{column}"))
            }
            None => {
                let one = given.ok_or_else(|| R::NoTolerance { key: key.clone() })?;
                positive(number(one, &format!("{key}.{word}"))?, &format!("{key}.{word}"))
            }
        }
    };
    // The rows walked cover the measured loads, which a rig's noise carries past its nominal range.
    let loads = measured.rows.iter().map(|r| r[0]);
    let span = (loads.clone().fold(f64::INFINITY, f64::min), loads.fold(f64::NEG_INFINITY, f64::max));
    let range = range.or((span.0 < span.1).then_some(span));
    let mut targets = Vec::new();
    for column in &columns {
        let Some(c) = measured.columns.iter().position(|x| x == column) else {
            return Err(R::NoColumn { key, file: file.into(), column: column.clone(), has: measured.columns });
        };
        let points = measured.rows.iter().map(|r| (r[0], r[c])).collect();
        targets.push(Target {
            label: format!("{key} ({file}: {}/{column})", analysis.name()),
            analysis,
            range,
            aim: Aim::Curve { column: column.clone(), points, measure: CurveMeasure::Points },
            tolerance: per_column(column)?,
            scale,
            weight: weight(o, &key)?,
        });
    }
    Ok(targets)
}

/// Entry `k`, `c`, of the `constraints` list, on hardpoints of the model `document`.
fn constraint(k: usize, c: &Value, document: &Value) -> Result<Constraint, TargetsRefusal> {
    use TargetsRefusal as R;
    let hardpoint = |name: &str, key: &str| -> Result<String, TargetsRefusal> {
        hardpoint_pointer(document, name)
            .map(|_| name.to_string())
            .ok_or_else(|| R::NoHardpoint { key: key.into(), name: name.into() })
    };
    let key = format!("constraints[{k}]");
    let o = c.as_object().ok_or_else(|| R::NotObjectAt { key: key.clone() })?;
    if let Some(points) = o.get("distance") {
        only(o, &["distance", "min", "max"], &key)?;
        let names = points.as_array().filter(|p| p.len() == 2).ok_or_else(|| R::NotTwoNames { key: key.clone() })?;
        let a = hardpoint(name_in(&names[0], &key)?, &format!("{key}.distance"))?;
        let b = hardpoint(name_in(&names[1], &key)?, &format!("{key}.distance"))?;
        let min = o.get("min").map(|v| number(v, &format!("{key}.min"))).transpose()?.unwrap_or(0.0);
        let max = o.get("max").map(|v| number(v, &format!("{key}.max"))).transpose()?.unwrap_or(f64::INFINITY);
        if min >= max {
            return Err(R::MinNotBelowMax { key, min, max });
        }
        Ok(Constraint::Distance { points: [a, b], min, max })
    } else if let Some(point) = o.get("outside_sphere") {
        only(o, &["outside_sphere", "centre", "radius"], &key)?;
        let point = hardpoint(name_in(point, &key)?, &format!("{key}.outside_sphere"))?;
        let centre = triple(o.get("centre").unwrap_or(&Value::Null), &format!("{key}.centre"))?;
        let radius = number(o.get("radius").unwrap_or(&Value::Null), &format!("{key}.radius"))?;
        if radius <= 0.0 {
            return Err(R::RadiusNotPositive { key, got: radius });
        }
        Ok(Constraint::OutsideSphere { point, centre, radius })
    } else if let Some(point) = o.get("outside_box") {
        only(o, &["outside_box", "min", "max"], &key)?;
        let point = hardpoint(name_in(point, &key)?, &format!("{key}.outside_box"))?;
        let min = triple(o.get("min").unwrap_or(&Value::Null), &format!("{key}.min"))?;
        let max = triple(o.get("max").unwrap_or(&Value::Null), &format!("{key}.max"))?;
        if (0..3).any(|i| min[i] >= max[i]) {
            return Err(R::BoxInsideOut { key });
        }
        Ok(Constraint::OutsideBox { point, min, max })
    } else {
        Err(R::NoPackaging { key })
    }
}

/// The value of `column` at `at` from the table's rows by the cubic through the four nearest rows (fewer
/// when the table has fewer): its weights on the rows, which also carry the rows' derivatives. Outside the
/// rows' range (or with no row bracketing `at`), the range `(lo, hi)` the rows span.
pub(super) fn interpolation(t: &[f64], at: f64) -> Result<Vec<(usize, f64)>, (f64, f64)> {
    let n = t.len();
    let (lo, hi) = t.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    if n == 0 || !(lo..=hi).contains(&at) {
        return Err((lo, hi));
    }
    if let Some(k) = t.iter().position(|&v| v == at) {
        return Ok(vec![(k, 1.0)]);
    }
    let i = t.windows(2).position(|w| (w[0] - at) * (w[1] - at) < 0.0).ok_or((lo, hi))?;
    let first = i.saturating_sub(1).min(n.saturating_sub(4));
    let near: Vec<usize> = (first..(first + 4).min(n)).collect();
    Ok(near
        .iter()
        .map(|&j| {
            let w = near.iter().filter(|&&m| m != j).map(|&m| (at - t[m]) / (t[j] - t[m])).product();
            (j, w)
        })
        .collect())
}
