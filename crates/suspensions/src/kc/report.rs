//! What a K&C analysis reports: its table, its headline figures (each with its error estimate or the
//! reason it is missing), its plots and the accuracy of the whole run. Every number in a report is finite:
//! a figure that cannot be computed carries a reason instead of a value, a table cell is left empty.

use crate::drawing::Motion;
use crate::kc::chart::Chart;
use crate::kc::settings::Analysis;
use crate::kc::unit::{Unit, Units};
use serde::ser::SerializeStruct;
use serde::{Serialize, Serializer};

/// One table cell: a number, a name, or nothing (a value the row does not have).
#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    /// A finite number (a non-finite one is stored as [`Cell::Empty`] by [`Cell::from`]).
    Number(f64),
    /// A name.
    Text(String),
    /// No value.
    Empty,
}

impl From<f64> for Cell {
    fn from(v: f64) -> Cell {
        if v.is_finite() {
            Cell::Number(v)
        } else {
            Cell::Empty
        }
    }
}

impl From<Option<f64>> for Cell {
    fn from(v: Option<f64>) -> Cell {
        v.map_or(Cell::Empty, Cell::from)
    }
}

impl Serialize for Cell {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Cell::Number(v) => s.serialize_f64(*v),
            Cell::Text(t) => s.serialize_str(t),
            Cell::Empty => s.serialize_none(),
        }
    }
}

impl Cell {
    /// The number, if the cell holds one.
    pub fn number(&self) -> Option<f64> {
        match self {
            Cell::Number(v) => Some(*v),
            _ => None,
        }
    }
}

/// A table of rows: one CSV file. Column names carry their unit as a suffix (`toe_deg`, `travel_m`,
/// `wheel_load_n`), which is how the error estimate knows angles from lengths.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Table {
    /// File stem, e.g. `parallel_travel` (written as `parallel_travel.csv`).
    pub name: String,
    /// Column names with units.
    pub columns: Vec<String>,
    /// Rows, one cell per column.
    pub rows: Vec<Vec<Cell>>,
}

/// A column of a table: its name and how a row gives its cell, side by side, so that the names and the
/// values cannot drift apart.
pub(crate) struct Column<'a, R> {
    name: String,
    cell: Box<dyn Fn(&R) -> Cell + 'a>,
}

impl<'a, R> Column<'a, R> {
    /// The column `name` whose cell of a row is `cell(row)`.
    pub(crate) fn new(name: impl Into<String>, cell: impl Fn(&R) -> Cell + 'a) -> Self {
        Column { name: name.into(), cell: Box::new(cell) }
    }
}

impl Table {
    /// The numbers of the column `name` (`None` where a cell is empty), or `None` when there is no such column.
    pub fn column(&self, name: &str) -> Option<Vec<Option<f64>>> {
        let c = self.columns.iter().position(|x| x == name)?;
        Some(self.rows.iter().map(|r| r.get(c).and_then(Cell::number)).collect())
    }

    /// The table `name` of `rows`, one column per entry of `columns`.
    pub(crate) fn of_columns<'r, R: 'r>(
        name: &str,
        columns: &[Column<R>],
        rows: impl IntoIterator<Item = &'r R>,
    ) -> Table {
        Table {
            name: name.into(),
            columns: columns.iter().map(|c| c.name.clone()).collect(),
            rows: rows.into_iter().map(|r| columns.iter().map(|c| (c.cell)(r)).collect()).collect(),
        }
    }

    /// Largest difference per column between this table and `other` (same shape), over the rows where both
    /// hold numbers; `None` for a column with no such row.
    pub fn column_differences(&self, other: &Table) -> Vec<Option<f64>> {
        (0..self.columns.len())
            .map(|c| {
                self.rows
                    .iter()
                    .zip(&other.rows)
                    .filter_map(|(a, b)| Some((a.get(c)?.number()? - b.get(c)?.number()?).abs()))
                    .filter(|d| d.is_finite())
                    .reduce(f64::max)
            })
            .collect()
    }
}

/// One headline figure: its value in SI, the unit it is written in, its error estimate, or the reason it
/// could not be computed. Written (terminal, JSON, HTML) in its unit under the report's [`Units`]; in JSON
/// as `{"value": …, "unit": …, "error": …, "si_value": …, "si_unit": …, "si_error": …}`, or with `"value":
/// null` and the `"reason"`.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// Key in the JSON summary, e.g. `bump_steer`.
    pub key: String,
    /// What it is, in words, e.g. `bump steer (toe-in +)`.
    pub label: String,
    /// The unit it is written in (which fixes the SI unit `value` is held in).
    pub unit: Unit,
    /// Decimals to write it with, in `unit` under the default units.
    pub decimals: usize,
    /// The value in SI (always finite), or `None` with `reason`.
    pub value: Option<f64>,
    /// Why there is no value.
    pub reason: Option<String>,
    /// Estimated error of the value (SI): how far it is from the figure of the exact equilibria.
    pub error: Option<f64>,
}

/// A figure as an analysis declares it, once: its key, its words, the unit it is written in and the
/// decimals it is written with ([`crate::kc::figures`] lists them all).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FigureKind {
    /// Key in the JSON summary.
    pub key: &'static str,
    /// What it is, in words.
    pub label: &'static str,
    /// The unit it is written in.
    pub unit: Unit,
    /// Decimals it is written with.
    pub decimals: usize,
}

impl Figure {
    /// A figure from a computed value in SI: a non-finite value becomes a missing one, with the reason.
    pub fn new(key: &str, label: &str, unit: Unit, decimals: usize, value: f64) -> Figure {
        Figure::maybe(key, label, unit, decimals, Some(value), "")
    }

    /// A figure that may be missing: `None` or a non-finite value gives no value and `reason` (or, for a
    /// non-finite value, a reason saying so).
    pub fn maybe(key: &str, label: &str, unit: Unit, decimals: usize, value: Option<f64>, reason: &str) -> Figure {
        let (value, reason) = match value {
            Some(v) if v.is_finite() => (Some(v), None),
            Some(_) => (
                None,
                Some(
                    "not a finite number here: the geometry makes it undefined (e.g. a slope of a quantity that \
                     does not move); check the model with `elastokin check`"
                        .to_string(),
                ),
            ),
            None => (None, Some(reason.to_string())),
        };
        Figure { key: key.into(), label: label.into(), unit, decimals, value, reason, error: None }
    }

    /// The figure `kind` of a value in SI, or missing with `reason`.
    pub fn of(kind: &FigureKind, value: Option<f64>, reason: &str) -> Figure {
        Figure::maybe(kind.key, kind.label, kind.unit, kind.decimals, value, reason)
    }

    /// The same figure under another label (one that names what this model's figure is, e.g. anti-dive
    /// on a front axle).
    pub fn labelled(mut self, label: impl Into<String>) -> Figure {
        self.label = label.into();
        self
    }

    /// Whether an error of `e` (SI) shows in the decimals the figure is written with under the default
    /// units (more than half its last digit).
    pub fn shows(&self, e: f64) -> bool {
        e * self.unit.shown().factor > 0.5 * 10f64.powi(-(self.decimals as i32))
    }

    /// Whether its error estimate matters to a reader: over `relative` of its value (the tolerance on
    /// figures) and showing in its printed decimals. A figure with no value or no estimate has none that
    /// matters.
    pub fn estimate_matters(&self, relative: f64) -> bool {
        match (self.value, self.error) {
            (Some(v), Some(e)) => e > relative * v.abs() && self.shows(e),
            _ => false,
        }
    }

    /// The figure as written under `units`: its unit, value, error estimate and decimals.
    pub fn written(&self, units: Units) -> Written<'_> {
        let shown = self.unit.shown_in(units);
        Written {
            figure: self,
            unit: shown.symbol,
            factor: shown.factor,
            value: self.value.map(|v| v * shown.factor),
            error: self.error.map(|e| e * shown.factor),
            decimals: self.decimals + shown.more_decimals,
        }
    }

    /// The figure as the terminal shows it under `units`: `label  value unit  (± error)` or
    /// `label  — reason`.
    pub fn line(&self, units: Units) -> String {
        let w = self.written(units);
        match w.value {
            Some(v) => {
                let err = match (self.error, w.error) {
                    (Some(e), Some(written)) if self.shows(e) => format!("  (± {})", significant(written, 2)),
                    _ => String::new(),
                };
                let unit = if w.unit == "-" { "" } else { w.unit };
                format!("  {:<58} {:>10} {unit}{err}", self.label, w.number(v))
            }
            None => format!("  {:<58} {:>10} — {}", self.label, "n/a", self.reason.as_deref().unwrap_or("")),
        }
    }
}

/// A figure as written: in its unit under the chosen units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Written<'a> {
    /// The figure.
    pub figure: &'a Figure,
    /// The unit written.
    pub unit: &'static str,
    /// Written value per SI value: what a derivative or a spread of the figure is scaled by to be written
    /// beside it.
    pub factor: f64,
    /// The value in that unit.
    pub value: Option<f64>,
    /// The error estimate in that unit.
    pub error: Option<f64>,
    /// Decimals.
    pub decimals: usize,
}

impl Written<'_> {
    /// `v` (in the written unit) at the figure's decimals ([`fixed`]).
    pub fn number(&self, v: f64) -> String {
        fixed(v, self.decimals)
    }
}

/// `v` with `decimals` decimals (how figures and coordinates are written); a value that rounds to zero is
/// zero, not `-0.00`; nothing for a non-finite `v`.
pub fn fixed(v: f64, decimals: usize) -> String {
    if !v.is_finite() {
        return String::new();
    }
    let shown = format!("{v:.decimals$}");
    match shown.strip_prefix('-') {
        Some(rest) if rest.bytes().all(|b| b == b'0' || b == b'.') => rest.to_string(),
        _ => shown,
    }
}

impl Serialize for Written<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let f = self.figure;
        let mut st = s.serialize_struct("Figure", 8)?;
        st.serialize_field("label", &f.label)?;
        st.serialize_field("value", &self.value)?;
        st.serialize_field("unit", self.unit)?;
        match &f.reason {
            Some(r) => st.serialize_field("reason", r)?,
            None => st.skip_field("reason")?,
        }
        match self.error {
            Some(e) => st.serialize_field("error", &e)?,
            None => st.skip_field("error")?,
        }
        st.serialize_field("si_value", &f.value)?;
        st.serialize_field("si_unit", f.unit.si())?;
        match f.error {
            Some(e) => st.serialize_field("si_error", &e)?,
            None => st.skip_field("si_error")?,
        }
        st.end()
    }
}

/// `v` with `digits` significant digits, in plain or scientific notation as fits (how error estimates are
/// shown); nothing for a non-finite `v`.
pub fn significant(v: f64, digits: usize) -> String {
    if !v.is_finite() {
        return String::new();
    }
    if v == 0.0 {
        return "0".into();
    }
    let magnitude = v.abs().log10().floor() as i32;
    if (-4..6).contains(&magnitude) {
        let decimals = (digits as i32 - 1 - magnitude).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.*e}", digits.saturating_sub(1))
    }
}

/// [`significant`] of `v` among values of size `scale`: `0` where `v` is rounding beside them (below 1e-12
/// of `scale`), as a term that is zero by the model's form (the compliance steer of ideal links) comes out
/// of sums and differences of numbers of that size.
pub fn significant_among(v: f64, digits: usize, scale: f64) -> String {
    if v.abs() < 1e-12 * scale.abs() {
        return "0".into();
    }
    significant(v, digits)
}

/// How accurate an analysis's rows are, and how that was estimated.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Accuracy {
    /// How the estimate was made, in words.
    pub method: String,
    /// Largest estimated error of any angle in the table (deg).
    pub angle_error_deg: f64,
    /// Largest estimated error of any length in the table (m).
    pub length_error_m: f64,
    /// Largest force residual of a row, relative to its force scale.
    pub force_residual: f64,
    /// Largest constraint residual of a row (m and rad): the drift off the joints.
    pub constraint_residual: f64,
    /// Estimated error of every column (its largest over the rows; `null` where the column has no numbers).
    pub columns: Vec<(String, Option<f64>)>,
    /// Whether the errors are within the tolerance asked for.
    pub within_tolerance: bool,
}

/// Something a user should know about a model or a result: the plausibility checks' warning type, also
/// used for results (an error estimate over the tolerance), with no hardpoints named.
pub use crate::check::Warning;

/// What one K&C analysis produced.
#[derive(Debug, Clone, PartialEq)]
pub struct AnalysisReport {
    /// The analysis.
    pub analysis: Analysis,
    /// What the load parameter is, with its unit.
    pub parameter: String,
    /// What was run, in one line, e.g. `parallel wheel travel -80..+80 mm, 32 steps`.
    pub description: String,
    /// The load parameter's range walked (in the parameter's unit).
    pub range: (f64, f64),
    /// Load steps.
    pub steps: usize,
    /// Headline figures, in SI (in JSON an object keyed by each figure's key, written in `units`).
    pub figures: Vec<Figure>,
    /// The units the figures are written in (the settings' choice: only the writers read it).
    pub units: Units,
    /// The rows (written as CSV; left out of the JSON summary, which would only repeat them).
    pub table: Table,
    /// The 6×6 wheel compliance at every row, when asked for (CSV too).
    pub compliance: Option<Table>,
    /// The 6×6 wheel compliance at design (rows: wheel-centre x, y, z in m and rotation in rad; columns:
    /// unit force in N and torque in N·m at the wheel centre), where the analysis takes it.
    pub wheel_compliance_at_design: Option<[[f64; 6]; 6]>,
    /// Plots.
    pub charts: Vec<Chart>,
    /// The rows' accuracy.
    pub accuracy: Accuracy,
    /// Warnings about the result.
    pub warnings: Vec<Warning>,
    /// The model drawn and its parts' poses at every row, when the settings ask for them
    /// ([`Settings::motion`](crate::kc::Settings::motion)).
    pub motion: Option<Motion>,
    /// The instant centres' construction at every row, for the views to draw (parallel travel's; empty
    /// for the others).
    pub construction: Vec<Construction>,
    /// The wheel's swept envelope, for the views to draw (the wheel envelope's; `None` for the others).
    pub envelope: Option<Envelope>,
}

/// The wheel's swept envelope as a view draws it: the tyre, the left wheel's centre and outward spin axis
/// at every point of the travel × rack grid (global, m; the right wheel's are their mirror images), and
/// the packaging it is measured against.
#[derive(Debug, Clone, PartialEq)]
pub struct Envelope {
    /// The tyre.
    pub tyre: crate::description::Tyre,
    /// The left wheel's centre and outward spin axis at each point of the grid.
    pub placements: Vec<(elastokin_core::Vec3, elastokin_core::Vec3)>,
    /// The points and boxes of the body.
    pub packaging: crate::description::Packaging,
}

/// How a row's instant centres are found, as a view draws it (global coordinates, m): the contact patch
/// and the wheel centre, the wheel's front-view instant centre (y, z) and side-view instant centre (x, z),
/// and the axle's roll centre (y, z); each centre `None` where there is none. In the front view the patch,
/// its instant centre and the roll centre lie on one line; in the side view the patch's and the wheel
/// centre's lines to the instant centre are the anti-pitch constructions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Construction {
    /// The contact patch.
    pub patch: [f64; 3],
    /// The wheel centre.
    pub wheel_centre: [f64; 3],
    /// The front-view instant centre, (y, z).
    pub front_view_centre: Option<[f64; 2]>,
    /// The side-view instant centre, (x, z).
    pub side_view_centre: Option<[f64; 2]>,
    /// The roll centre, (y, z).
    pub roll_centre: Option<[f64; 2]>,
}

/// The JSON summary of an analysis: what was run, the figures written in the report's units, the wheel
/// compliance at design where there is one, the accuracy and the warnings (the rows, compliance tables,
/// plots and motion are written as their own files).
impl Serialize for AnalysisReport {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut st = s.serialize_struct("AnalysisReport", 9)?;
        st.serialize_field("analysis", &self.analysis)?;
        st.serialize_field("parameter", &self.parameter)?;
        st.serialize_field("description", &self.description)?;
        st.serialize_field("range", &self.range)?;
        st.serialize_field("steps", &self.steps)?;
        let written: Vec<(&str, Written)> =
            self.figures.iter().map(|f| (f.key.as_str(), f.written(self.units))).collect();
        st.serialize_field("figures", &ByKey(&written))?;
        match &self.wheel_compliance_at_design {
            Some(c) => st.serialize_field("wheel_compliance_at_design", c)?,
            None => st.skip_field("wheel_compliance_at_design")?,
        }
        st.serialize_field("accuracy", &self.accuracy)?;
        st.serialize_field("warnings", &self.warnings)?;
        st.end()
    }
}

/// Pairs serialised as a JSON object.
struct ByKey<'a, K, V>(&'a [(K, V)]);

impl<K: Serialize, V: Serialize> Serialize for ByKey<'_, K, V> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_map(self.0.iter().map(|(k, v)| (k, v)))
    }
}

impl AnalysisReport {
    /// The figure with `key` (a key the user gave: a target's, a tolerance's).
    pub fn figure(&self, key: &str) -> Option<&Figure> {
        self.figures.iter().find(|f| f.key == key)
    }

    /// The figure `kind` (one of [`crate::kc::figures`]), if the analysis reports it.
    pub fn figure_of(&self, kind: &FigureKind) -> Option<&Figure> {
        self.figure(kind.key)
    }

    /// The value of figure `kind` in SI, or why there is none ([`NoFigure`], naming the analysis and the
    /// figure).
    pub fn value_of(&self, kind: &FigureKind) -> Result<f64, NoFigure> {
        let (analysis, key) = (self.analysis.name(), kind.key);
        let f = self.figure_of(kind).ok_or(NoFigure::NotReported { analysis, key })?;
        f.value.ok_or_else(|| NoFigure::NoValue {
            analysis,
            key,
            reason: f.reason.clone().unwrap_or_else(|| "no value".into()),
        })
    }

    /// The row of the design position: the one whose load parameter (the table's first column) is nearest
    /// zero when the range spans zero (travel, roll, steering, lateral force), else the middle row.
    pub fn design_row(&self) -> usize {
        let t: Vec<f64> =
            self.table.rows.iter().map(|r| r.first().and_then(Cell::number).unwrap_or(f64::NAN)).collect();
        let spans_zero = t.iter().any(|v| *v <= 0.0) && t.iter().any(|v| *v >= 0.0);
        if spans_zero {
            (0..t.len()).min_by(|&i, &j| t[i].abs().total_cmp(&t[j].abs())).unwrap_or(0)
        } else {
            t.len() / 2
        }
    }

    /// The lines the terminal shows: what was run, the figures, the accuracy, the warnings.
    pub fn headline(&self) -> Vec<String> {
        let mut out = vec![self.description.clone()];
        out.extend(self.figures.iter().map(|f| f.line(self.units)));
        let a = &self.accuracy;
        out.push(format!(
            "  error estimate: angles {} deg, lengths {} mm ({})",
            significant(a.angle_error_deg, 2),
            significant(a.length_error_m * 1e3, 2),
            a.method
        ));
        out.extend(self.warnings.iter().map(|w| format!("  warning [{}]: {}", w.code, w.message)));
        out
    }
}

fn analyses_by_name<S: Serializer>(analyses: &[AnalysisReport], s: S) -> Result<S::Ok, S::Error> {
    s.collect_map(analyses.iter().map(|a| (a.analysis.name(), a)))
}

/// An analysis not run, and why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Skipped {
    /// The analysis.
    pub analysis: Analysis,
    /// Why.
    pub reason: String,
}

/// An analysis that was run and failed, and why: the suite goes on past it, and its report says so
/// as it says what it skipped.
#[derive(Debug, Clone, PartialEq, Serialize, thiserror::Error)]
#[error("{}: {reason}", analysis.name())]
pub struct Failed {
    /// The analysis.
    pub analysis: Analysis,
    /// The engine's reason, with what to change.
    pub reason: String,
}

/// The whole K&C suite's report on one model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KcReport {
    /// The model's name.
    pub model: String,
    /// How the paths were walked.
    pub settings: super::Settings,
    /// Every analysis run, in order (in JSON an object keyed by the analysis's name).
    #[serde(serialize_with = "analyses_by_name")]
    pub analyses: Vec<AnalysisReport>,
    /// Analyses left out, with the reason.
    pub skipped: Vec<Skipped>,
    /// Analyses that were run and failed, with the reason; the others' results stand.
    pub failed: Vec<Failed>,
    /// What the plausibility checks found in the model before it was solved (degrees of freedom,
    /// condition, warnings), when they could run.
    pub model_check: Option<crate::check::ModelCheck>,
    /// Warnings about the model (plausibility) and the results.
    pub warnings: Vec<Warning>,
}

impl KcReport {
    /// The report of `analysis`, if it ran.
    pub fn analysis(&self, analysis: Analysis) -> Option<&AnalysisReport> {
        self.analyses.iter().find(|a| a.analysis == analysis)
    }

    /// The report whole, or the first analysis that failed as an error: for a caller that needs every
    /// analysis asked for.
    pub fn complete(self) -> Result<KcReport, Failed> {
        match self.failed.first() {
            Some(f) => Err(f.clone()),
            None => Ok(self),
        }
    }

    /// Every warning: the model's and each analysis's.
    pub fn all_warnings(&self) -> impl Iterator<Item = &Warning> {
        self.warnings.iter().chain(self.analyses.iter().flat_map(|a| &a.warnings))
    }
}

/// A figure as the column of a table of many analyses' figures (`parallel-travel/bump_steer (deg/m)`):
/// its analysis, its key and the unit its values are written in.
pub fn figure_column(analysis: Analysis, key: &str, unit: Unit) -> String {
    format!("{}/{key} ({})", analysis.name(), unit.shown().symbol)
}

/// A name as part of a key or a file name: its letters and digits in lower case, the rest one underscore.
pub(crate) fn slug(name: &str) -> String {
    let mut out = String::new();
    for c in name.chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('_') {
            out.push('_');
        }
    }
    out.trim_matches('_').to_string()
}

/// Why an analysis's report has no value of a figure ([`AnalysisReport::value_of`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NoFigure {
    /// The analysis does not report the figure at all.
    #[error("{analysis} gives no `{key}`")]
    NotReported {
        /// The analysis's name.
        analysis: &'static str,
        /// The figure's key.
        key: &'static str,
    },
    /// It reports the figure without a value, and why.
    #[error("{analysis} has no `{key}`: {reason}")]
    NoValue {
        /// The analysis's name.
        analysis: &'static str,
        /// The figure's key.
        key: &'static str,
        /// Why it has no value, as the report says it.
        reason: String,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_non_finite_figure_has_a_reason_and_serialises_as_null() {
        let f = Figure::new("wheel_rate", "wheel rate", Unit::NewtonPerMillimetre, 2, f64::NAN);
        assert_eq!(f.value, None);
        let json = serde_json::to_value(f.written(Units::DegPerM)).unwrap();
        assert!(json["value"].is_null() && json["reason"].as_str().unwrap().contains("not a finite"), "{json}");
        assert!(!f.line(Units::DegPerM).contains("NaN"), "{}", f.line(Units::DegPerM));
        // Held in SI, written in its unit: 35 000 N/m is 35 N/mm.
        let g = Figure::new("wheel_rate", "wheel rate", Unit::NewtonPerMillimetre, 2, 35e3);
        let json = serde_json::to_value(g.written(Units::DegPerM)).unwrap();
        assert_eq!((json["value"].as_f64(), json["unit"].as_str()), (Some(35.0), Some("N/mm")));
        assert_eq!((json["si_value"].as_f64(), json["si_unit"].as_str()), (Some(35e3), Some("N/m")));
    }

    #[test]
    fn cells_never_hold_non_finite_numbers() {
        for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(Cell::from(v), Cell::Empty);
        }
        assert_eq!(Cell::from(1.5), Cell::Number(1.5));
    }

    #[test]
    fn column_differences_take_the_largest_over_rows() {
        let columns =
            [Column::new("x_m", |r: &[f64; 2]| r[0].into()), Column::new("y_deg", |r: &[f64; 2]| r[1].into())];
        let a = Table::of_columns("t", &columns, &[[0.0, 1.0], [1.0, 2.0]]);
        let b = Table::of_columns("t", &columns, &[[0.0, 1.5], [1.0, 1.75]]);
        assert_eq!(a.column_differences(&b), vec![Some(0.0), Some(0.5)]);
    }

    /// The headline printed `-0.0 N` for the design wheel load of a corner that carries nothing.
    #[test]
    fn a_figure_of_nothing_prints_zero_without_a_sign() {
        for v in [-0.0, -0.04, -1e-300] {
            let line = Figure::new("design_wheel_load", "design wheel load", Unit::Newton, 1, v).line(Units::DegPerM);
            assert!(line.ends_with(" 0.0 N") && !line.contains('-'), "{v:e}: {line}");
        }
        let line = Figure::new("design_wheel_load", "design wheel load", Unit::Newton, 1, -0.05).line(Units::DegPerM);
        assert!(line.ends_with(" -0.1 N"), "{line}");
    }

    #[test]
    fn significant_digits() {
        assert_eq!(significant(0.000123456, 2), "0.00012");
        assert_eq!(significant(123.456, 2), "123");
        assert_eq!(significant(1.2e-9, 2), "1.2e-9");
    }
}
