//! A run judged against a TARGETS file (`run --targets`): each figure target, each point of a curve
//! target and each packaging constraint met or not, counted as `tune` counts them (a miss within the
//! tolerance, a constraint within its bounds), on the model as it is. Nothing is moved.

use super::targets::{
    interpolation, readings, Aim, Constraint, CurveMeasure, CurveReading, MissScale, Target, Targets,
};
use super::tune::linearise;
use crate::kc::report::Column;
use crate::kc::{AnalysisReport, Cell, KcReport, Table};
use serde_json::Value;

/// One point of a target judged: a figure target is one point, a curve target one per point it gives.
#[derive(Debug, Clone, PartialEq)]
pub struct TargetPoint<'a> {
    /// The target.
    pub target: &'a Target,
    /// The load parameter of a curve target's reading (the analysis's own unit); `None` for a figure.
    pub at: Option<f64>,
    /// The reading's weight in its target's measure ([`CurveReading::weight`]; 1 for a figure and a point).
    pub weight: f64,
    /// What the target asks, in its own unit (a figure's unit as written under the default units, a
    /// column's unit).
    pub aim: f64,
    /// What the run gives there, in the same unit, or why it gives nothing to judge.
    pub reached: Result<f64, String>,
    /// For a target judged whole — against a measured file's noise (its points' χ²), or a curve by its
    /// root mean square or area ([`Target::met_by`]) — whether it is met: a reading of it is met when its
    /// target is.
    pub whole: Option<bool>,
}

impl TargetPoint<'_> {
    /// Whether the run meets the point: its miss within the target's tolerance, or, for a target judged
    /// whole, its target met.
    pub fn met(&self) -> bool {
        self.whole.unwrap_or(matches!(self.reached, Ok(r) if (r - self.aim).abs() <= self.target.tolerance))
    }

    /// The miss over the tolerance (1 at the tolerance's edge), when the run gives a value.
    pub fn miss_over_tolerance(&self) -> Option<f64> {
        self.reached.as_ref().ok().map(|r| (r - self.aim).abs() / self.target.tolerance)
    }
}

/// The points judged, a slice per target in the file's order (a target's readings are consecutive).
pub fn by_target<'r, 'a>(points: &'r [TargetPoint<'a>]) -> impl Iterator<Item = &'r [TargetPoint<'a>]> {
    points.chunk_by(|a, b| std::ptr::eq(a.target, b.target))
}

/// How a target judged whole (its readings `readings`, [`TargetPoint::whole`]) was judged, in words
/// ([`Target::judged_words`]); `None` for a target judged point by point, or when a reading has no value
/// (each says why).
pub fn judged_whole(readings: &[TargetPoint]) -> Option<String> {
    readings.first()?.whole?;
    let (misses, weights) = misses_and_weights(readings)?;
    Some(readings[0].target.judged_words(&misses, &weights))
}

/// The misses over the tolerance and the weights of one target's `readings`, as [`Target::measured`] takes
/// them; `None` when a reading has no value.
fn misses_and_weights(readings: &[TargetPoint]) -> Option<(Vec<f64>, Vec<f64>)> {
    readings
        .iter()
        .map(|p| p.reached.as_ref().ok().map(|r| ((r - p.aim) / p.target.tolerance, p.weight)))
        .collect::<Option<Vec<(f64, f64)>>>()
        .map(|pairs| pairs.into_iter().unzip())
}

/// A packaging constraint of the TARGETS file judged on the model file: its value and bounds (m), or why
/// it could not be read.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstraintCheck<'a> {
    /// The constraint.
    pub constraint: &'a Constraint,
    /// Its value and allowed range on the model as it is (m).
    pub reached: Result<(f64, f64, f64), String>,
}

impl ConstraintCheck<'_> {
    /// Whether the model keeps it.
    pub fn met(&self) -> bool {
        matches!(self.reached, Ok((v, min, max)) if (min..=max).contains(&v))
    }
}

/// The targets of `targets` judged on the suite `report` of the model file `document`, point by point, in
/// the file's order; and its packaging constraints.
pub fn judge<'a>(
    report: &KcReport,
    document: &Value,
    targets: &'a Targets,
) -> (Vec<TargetPoint<'a>>, Vec<ConstraintCheck<'a>>) {
    let mut points = Vec::new();
    for target in &targets.targets {
        let analysis = report.analyses.iter().find(|a| a.analysis == target.analysis);
        match &target.aim {
            Aim::Figure { key, value } => {
                let reached = analysis.ok_or_else(|| not_run(report, target)).and_then(|a| figure(a, key));
                points.push(TargetPoint { target, at: None, weight: 1.0, aim: *value, reached, whole: None });
            }
            Aim::Curve { column, points: aims, measure } => {
                let first = points.len();
                // The rows' load parameters, where the analysis ran, for a measure over the points' span.
                let rows = analysis.map(|a| along(&a.table)).unwrap_or_default();
                for CurveReading { at, aim, weight } in readings(aims, *measure, &rows) {
                    let reached = analysis.ok_or_else(|| not_run(report, target)).and_then(|a| curve(a, column, at));
                    points.push(TargetPoint { target, at: Some(at), weight, aim, reached, whole: None });
                }
                if target.scale == MissScale::Noise || *measure != CurveMeasure::Points {
                    // Judged whole: every reading read, and their measure within the tolerance or the noise.
                    let met = misses_and_weights(&points[first..]).is_some_and(|(m, w)| target.met_by(&m, &w));
                    points[first..].iter_mut().for_each(|p| p.whole = Some(met));
                }
            }
        }
    }
    let constraints = targets
        .constraints
        .iter()
        .map(|c| ConstraintCheck {
            constraint: c,
            reached: linearise(c, document, &[]).map(|l| (l.value, l.min, l.max)).map_err(|e| e.to_string()),
        })
        .collect();
    (points, constraints)
}

/// Why the analysis of `target` gave nothing: failed (with its error), or not run.
fn not_run(report: &KcReport, target: &Target) -> String {
    let name = target.analysis.name();
    match report.failed.iter().find(|f| f.analysis == target.analysis) {
        Some(f) => format!("{name} failed: {}", f.reason),
        None => format!("{name} was not run"),
    }
}

/// The figure `key` of `a` in the unit it is written in under the default units, as a target gives it.
fn figure(a: &AnalysisReport, key: &str) -> Result<f64, String> {
    let f = a.figure(key).ok_or_else(|| {
        let has: Vec<&str> = a.figures.iter().map(|f| f.key.as_str()).collect();
        format!("{} has no figure '{key}' (it has {})", a.analysis.name(), has.join(", "))
    })?;
    let value = f.value.ok_or_else(|| f.reason.clone().unwrap_or_default())?;
    Ok(value * f.unit.shown().factor)
}

/// The column `column` of `a`'s table at the load parameter `at`, by the interpolation `tune` reads curves
/// with.
fn curve(a: &AnalysisReport, column: &str, at: f64) -> Result<f64, String> {
    let table = &a.table;
    let values = table.column(column).ok_or_else(|| {
        format!("{} has no column '{column}' (it has {})", a.analysis.name(), table.columns.join(", "))
    })?;
    let along = along(table);
    let weights = interpolation(&along, at).map_err(|(lo, hi)| {
        format!("{at} is outside the rows run, {lo} to {hi}: run the analysis over a range that holds it")
    })?;
    weights.iter().try_fold(0.0, |sum, &(j, w)| {
        let v = values[j].ok_or_else(|| format!("the cell of '{column}' at {} is empty", along[j]))?;
        Ok(sum + w * v)
    })
}

/// The load parameter of each of `table`'s rows, its first column.
fn along(table: &Table) -> Vec<f64> {
    table.rows.iter().map(|r| r.first().and_then(Cell::number).unwrap_or(f64::NAN)).collect()
}

/// A row of the targets judged: a target's point or a packaging constraint.
enum Row<'r, 'a> {
    Point(&'r TargetPoint<'a>),
    Constraint(&'r ConstraintCheck<'a>),
}

impl Row<'_, '_> {
    fn met(&self) -> bool {
        match self {
            Row::Point(p) => p.met(),
            Row::Constraint(c) => c.met(),
        }
    }

    fn not_judged_because(&self) -> Option<&str> {
        match self {
            Row::Point(p) => p.reached.as_ref().err(),
            Row::Constraint(c) => c.reached.as_ref().err(),
        }
        .map(String::as_str)
    }
}

/// The targets judged as `targets.csv` lists them: a row per target point (its label, the load parameter
/// of a curve's point, the aim and tolerance in the target's unit) and per packaging constraint (its
/// bounds, m); what the run reached, met as 1 or 0, and why a row could not be judged.
pub fn judged_table(points: &[TargetPoint], constraints: &[ConstraintCheck]) -> Table {
    let point = |r: &Row, f: &dyn Fn(&TargetPoint) -> Option<f64>| match r {
        Row::Point(p) => Cell::from(f(p)),
        Row::Constraint(_) => Cell::Empty,
    };
    let bound = |r: &Row, f: &dyn Fn(&(f64, f64, f64)) -> f64| match r {
        Row::Constraint(c) => Cell::from(c.reached.as_ref().ok().map(f)),
        Row::Point(_) => Cell::Empty,
    };
    let columns: [Column<Row>; 9] = [
        Column::new("target", |r: &Row| {
            Cell::Text(match r {
                Row::Point(p) => p.target.label.clone(),
                Row::Constraint(c) => c.constraint.said(),
            })
        }),
        Column::new("at", move |r: &Row| point(r, &|p| p.at)),
        Column::new("aim", move |r: &Row| point(r, &|p| Some(p.aim))),
        Column::new("tolerance", move |r: &Row| point(r, &|p| Some(p.target.tolerance))),
        Column::new("min_m", move |r: &Row| bound(r, &|b| b.1)),
        Column::new("max_m", move |r: &Row| bound(r, &|b| b.2)),
        Column::new("reached", move |r: &Row| match r {
            Row::Point(p) => Cell::from(p.reached.as_ref().ok().copied()),
            Row::Constraint(c) => Cell::from(c.reached.as_ref().ok().map(|b| b.0)),
        }),
        Column::new("met", |r: &Row| Cell::from(if r.met() { 1.0 } else { 0.0 })),
        Column::new("not_judged_because", |r: &Row| Cell::Text(r.not_judged_because().unwrap_or("").to_string())),
    ];
    let rows: Vec<Row> = points.iter().map(Row::Point).chain(constraints.iter().map(Row::Constraint)).collect();
    Table::of_columns("targets", &columns, &rows)
}
