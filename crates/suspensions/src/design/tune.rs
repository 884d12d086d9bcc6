//! Tuning to targets: the free numbers of a model moved within their bounds, and within its packaging,
//! until its figures and curves meet the targets ([`super::targets`]) as nearly as they can, by
//! bound-constrained Gauss–Newton with Levenberg–Marquardt damping. Every iteration takes the exact
//! Jacobian of the residuals from the sensitivities ([`super::sensitivity`]) and solves one convex
//! quadratic program for the step — the Gauss–Newton model, damped, inside the bounds and the linearised
//! packaging — with Clarabel's interior-point solver.
//!
//! Why this method: a tune is a nonlinear least-squares problem whose every evaluation costs a K&C run
//! with its sensitivities, so the method must spend few. Gauss–Newton converges quadratically where the
//! targets can be met (the common case: a curve reachable by moving two points) and takes the damping
//! only where the model bends. Measured against a first-order method for box-constrained problems
//! (`optimization_engine`'s PANOC with L-BFGS) on the MacPherson's toe curve with both tie-rod points free
//! (`cargo xtask bench`, section `tuning`).
//!
//! A residual is a target's miss over its tolerance, times its weight (1 unless given): a target is met when
//! its miss over its tolerance is at most one.
//! What is not met is said, and why: a bound or the packaging holds a number that would otherwise
//! move, or the targets fight one another (the least-squares optimum leaves the miss).

use super::fit::FitUncertainty;
use super::parameter::hardpoint_pointer;
use super::parameter::{ParameterError, Parameters};
use super::sensitivity::{analysis_sensitivity, AnalysisSensitivity, NoDerivative, SensitivityError};
use super::targets::{
    interpolation, readings, Aim, Constraint, CurveMeasure, CurveReading, Free, MissScale, Target, Targets,
};
use crate::kc::report::Column;
use crate::kc::{self, Analysis, AnalysisReport, Cell, Chart, Scale, Series, Settings, Table, YAxis};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus, SupportedConeT,
};
use serde_json::Value;

/// The most iterations a tune takes.
pub const MAX_ITERATIONS: usize = 60;

/// A tune stops when every residual (miss over tolerance) is this small: the targets are met, to far
/// below anything a tolerance means.
pub const MET_EXACTLY: f64 = 1e-6;

/// A run's residuals and their Jacobian at one point of the free numbers.
#[derive(Debug, Clone)]
pub struct Evaluation {
    /// The free numbers.
    pub x: Vec<f64>,
    /// Each residual: the miss over its tolerance, one per figure target and per curve point.
    pub residuals: Vec<f64>,
    /// Their rates with respect to the free numbers: residual × free number.
    pub jacobian: Vec<Vec<f64>>,
    /// For each residual: its target (index into [`Targets::targets`]), the value reached and the value aimed
    /// at, in the target's unit.
    pub rows: Vec<Row>,
    /// Each packaging constraint's value, rates and allowed range, in the file's order; with an objective,
    /// then each target's residual as a bound, within ±1.
    pub packaging: Vec<Linearised>,
    /// The objective's figure, when the targets have one.
    pub goal: Option<Goal>,
    /// The analyses run, one per analysis and range the targets name.
    pub reports: Vec<AnalysisReport>,
}

/// An objective's figure at one point of the free numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct Goal {
    /// The figure, in the unit it is written in (as a figure target gives its value).
    pub figure: f64,
    /// Its rates with respect to the free numbers.
    pub rates: Vec<f64>,
    /// +1 where the least is sought, −1 for the most: the tune makes `sign × figure` least.
    pub sign: f64,
}

/// One residual's provenance.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// The target it belongs to.
    pub target: usize,
    /// The load parameter of a curve point (`None` for a figure).
    pub at: Option<f64>,
    /// The value reached.
    pub value: f64,
    /// The value aimed at.
    pub aim: f64,
    /// The reading's weight in its target's measure ([`CurveReading::weight`]; 1 for a figure and a point).
    pub weight: f64,
}

/// A packaging constraint at a point: `min ≤ value + rates · d ≤ max` to first order.
#[derive(Debug, Clone, PartialEq)]
pub struct Linearised {
    /// Its value (m).
    pub value: f64,
    /// Its rates with respect to the free numbers.
    pub rates: Vec<f64>,
    /// Allowed range.
    pub min: f64,
    /// Allowed range.
    pub max: f64,
}

impl Evaluation {
    /// What the tune makes least: `½ Σ r²`, or with an objective, its figure (negated for the most).
    pub fn objective(&self) -> f64 {
        match &self.goal {
            Some(g) => g.sign * g.figure,
            None => 0.5 * self.residuals.iter().map(|r| r * r).sum::<f64>(),
        }
    }

    /// `½ Σ (r + J d)²`: the objective the Gauss–Newton model predicts a step `d` leads to.
    fn predicted_objective(&self, d: &[f64]) -> f64 {
        let moved = |(r, row): (&f64, &Vec<f64>)| {
            let m = r + row.iter().zip(d).map(|(j, d)| j * d).sum::<f64>();
            m * m
        };
        self.residuals.iter().zip(&self.jacobian).map(moved).sum::<f64>() * 0.5
    }

    /// `Jᵀ r`.
    pub fn gradient(&self) -> Vec<f64> {
        let n = self.x.len();
        (0..n).map(|k| self.residuals.iter().zip(&self.jacobian).map(|(r, row)| r * row[k]).sum()).collect()
    }
}

/// Why the targets could not be evaluated on a model: they ask what its analyses do not give (a figure or
/// column it has not, a point outside the range walked, an aim too far to be worked with, a constraint on a
/// hardpoint it has not), or the model could not be analysed. At the start of a tune the first is bad
/// input; a step that meets either is stepped back from.
#[derive(Debug, Clone, thiserror::Error)]
pub enum TuneError {
    /// The targets ask what the model's analyses do not give.
    #[error(transparent)]
    Targets(#[from] NotGiven),
    /// A target cannot be read off the model's analyses.
    #[error(transparent)]
    Model(#[from] NoReading),
    /// The model with the free numbers where they are cannot be read.
    #[error(transparent)]
    Parameters(#[from] ParameterError),
    /// An analysis the targets run has no sensitivities on the model.
    #[error("{analysis}: {error}")]
    Analysis {
        /// The analysis's name.
        analysis: &'static str,
        /// Why it has none.
        error: SensitivityError,
    },
}

/// What the targets ask that the model's analyses do not give, naming the target (its label) or the free
/// number: bad input, as a bad TARGETS file is.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NotGiven {
    /// A figure the analysis does not report.
    #[error("{label}: {analysis} has no figure '{key}' (it has: {})", has.join(", "))]
    NoFigure {
        /// The target's label.
        label: String,
        /// The analysis's name.
        analysis: &'static str,
        /// The figure asked for.
        key: String,
        /// The figures it reports.
        has: Vec<String>,
    },
    /// A figure without a value on the model.
    #[error("{label}: the figure has no value here: {reason}")]
    NoValue {
        /// The target's label.
        label: String,
        /// Why, as the report says it.
        reason: String,
    },
    /// A column the analysis's table has not.
    #[error("{label}: {analysis}'s table has no column '{column}' (it has: {})", has.join(", "))]
    NoColumn {
        /// The target's label.
        label: String,
        /// The analysis's name.
        analysis: &'static str,
        /// The column asked for.
        column: String,
        /// The table's columns.
        has: Vec<String>,
    },
    /// A curve target on rows that move with a free number (a default range that follows the model).
    #[error(
        "{label}: the analysis's rows move with '{pointer}' (its default range follows the model); give the target a \
         \"range\""
    )]
    RowsMove {
        /// The target's label.
        label: String,
        /// The free number's pointer.
        pointer: String,
    },
    /// A curve's point outside the range the analysis walks.
    #[error(
        "{label}: the point at {at} lies outside the range {lo}..{hi} the analysis walks ({parameter}); give the \
         target a \"range\" that holds it"
    )]
    OutsideRange {
        /// The target's label.
        label: String,
        /// The point's load parameter.
        at: f64,
        /// The lowest row's.
        lo: f64,
        /// The highest row's.
        hi: f64,
        /// The load parameter, in words.
        parameter: &'static str,
    },
    /// A miss too large to be squared (an aim of 1e308, a tolerance of 1e-300), which the objective is.
    #[error(
        "{label}: the miss of {reached} from the aim {aim}, over the tolerance {tolerance}, is too large to be worked \
         with; give the aim and the tolerance in the unit of what is aimed at"
    )]
    TooFar {
        /// The target's label.
        label: String,
        /// The value reached.
        reached: f64,
        /// The aim.
        aim: f64,
        /// The target's tolerance.
        tolerance: f64,
    },
    /// A constraint on a hardpoint the model has not.
    #[error("the model has no hardpoint '{name}'")]
    NoHardpoint {
        /// The name.
        name: String,
    },
    /// A constraint on a hardpoint that is no list of coordinates.
    #[error("hardpoint '{name}'")]
    NotPlaced {
        /// The name.
        name: String,
    },
    /// A free number's bounds so wide that the targets' rates times their span are no finite numbers.
    #[error(
        "free[\"{pointer}\"]: the bounds {} to {} are too wide for a step to be computed (the targets' rates times \
         their span are no finite numbers): give it bounds of the size it may move",
        crate::kc::plain(*lo),
        crate::kc::plain(*hi)
    )]
    TooWide {
        /// The free number's pointer.
        pointer: String,
        /// Lower bound.
        lo: f64,
        /// Upper bound.
        hi: f64,
    },
}

/// A target that cannot be read off the model's analyses: a figure or cell without a rate, a row without
/// the column's value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NoReading {
    /// A figure without a rate.
    #[error("{label}: {}", why.reason())]
    FigureRate {
        /// The target's label.
        label: String,
        /// Why it has none.
        why: NoDerivative,
    },
    /// A row without a value in the column.
    #[error("{label}: the row at {at} has no {column}")]
    NoCell {
        /// The target's label.
        label: String,
        /// The row's load parameter.
        at: f64,
        /// The column.
        column: String,
    },
    /// A cell without a rate.
    #[error("{label}: at {at}: {}", why.reason())]
    CellRate {
        /// The target's label.
        label: String,
        /// The row's load parameter.
        at: f64,
        /// Why it has none.
        why: NoDerivative,
    },
}

/// An analysis run for the targets: which, over what range, and its sensitivities.
type Run = (crate::kc::Analysis, Option<(f64, f64)>, AnalysisSensitivity);

/// The targets' residuals and Jacobian with the free numbers of `parameters` at `x`.
pub fn evaluate(parameters: &Parameters, targets: &Targets, x: &[f64]) -> Result<Evaluation, TuneError> {
    let p = parameters.at(x)?;
    let runs = runs_for(targets, &p)?;
    let mut misses = Misses::default();
    for (k, t) in targets.targets.iter().enumerate() {
        let s = &runs.iter().find(|(a, r, _)| *a == t.analysis && *r == t.range).expect("run for every target").2;
        match &t.aim {
            Aim::Figure { key, value } => misses.figure(k, t, s, key, *value)?,
            Aim::Curve { .. } => misses.curve(k, t, s, &p)?,
        }
    }
    let mut packaging: Vec<Linearised> =
        targets.constraints.iter().map(|c| linearise(c, p.document(), &p.pointers)).collect::<Result<_, _>>()?;
    let goal = match &targets.objective {
        None => None,
        Some(o) => {
            // With an objective the targets are bounds: each miss over its tolerance within ±1.
            let bounds = misses.residuals.iter().zip(&misses.jacobian);
            packaging.extend(bounds.map(|(r, rates)| Linearised {
                value: *r,
                rates: rates.clone(),
                min: -1.0,
                max: 1.0,
            }));
            let s = &runs.iter().find(|(a, r, _)| *a == o.analysis && *r == o.range).expect("run for the objective").2;
            let (figure, rates) = figure_reading(&o.label, o.analysis, s, &o.key)?;
            Some(Goal { figure, rates, sign: if o.sense == super::targets::Sense::Least { 1.0 } else { -1.0 } })
        }
    };
    Ok(Evaluation {
        x: x.to_vec(),
        residuals: misses.residuals,
        jacobian: misses.jacobian,
        rows: misses.rows,
        packaging,
        goal,
        reports: runs.into_iter().map(|(_, _, s)| s.report).collect(),
    })
}

/// The analyses the targets read, with their sensitivities to the free numbers of `p`: one run per
/// analysis and range, its rows read only as far as its figures read them where only figures are aimed at.
fn runs_for(targets: &Targets, p: &Parameters) -> Result<Vec<Run>, TuneError> {
    let mut runs: Vec<Run> = Vec::new();
    let objective = targets.objective.iter().map(|o| (o.analysis, o.range));
    for (analysis, range) in targets.targets.iter().map(|t| (t.analysis, t.range)).chain(objective) {
        if runs.iter().any(|(a, r, _)| *a == analysis && *r == range) {
            continue;
        }
        let figures_only = targets
            .targets
            .iter()
            .filter(|u| u.analysis == analysis && u.range == range)
            .all(|u| matches!(u.aim, Aim::Figure { .. }));
        let settings = Settings { range, steps: targets.steps, figures_only, ..Settings::default() };
        let s = analysis_sensitivity(analysis, p, &settings)
            .map_err(|error| TuneError::Analysis { analysis: analysis.name(), error })?;
        runs.push((analysis, range, s));
    }
    Ok(runs)
}

/// The residuals, their rates and their provenance, target by target.
#[derive(Default)]
struct Misses {
    residuals: Vec<f64>,
    jacobian: Vec<Vec<f64>>,
    rows: Vec<Row>,
}

impl Misses {
    /// The residual of `row`, of the target `t`, whose value's rates are `gradient`.
    fn push(&mut self, t: &Target, row: Row, gradient: &[f64]) -> Result<(), TuneError> {
        let (residual, rates) = scaled_miss(t, row.weight, row.value, row.aim, gradient)?;
        self.residuals.push(residual);
        self.jacobian.push(rates);
        self.rows.push(row);
        Ok(())
    }

    /// The residual of target `k`, `t`, that aims the figure `key` of `s` at `value`.
    fn figure(
        &mut self,
        k: usize,
        t: &Target,
        s: &AnalysisSensitivity,
        key: &str,
        value: f64,
    ) -> Result<(), TuneError> {
        let (reached, gradient) = figure_reading(&t.label, t.analysis, s, key)?;
        self.push(t, Row { target: k, at: None, value: reached, aim: value, weight: 1.0 }, &gradient)
    }

    /// The residuals of target `k`, `t`, a curve that aims a column of `s`'s table at its points (load
    /// parameter, aim) under its measure, each reading ([`readings`]) between the rows about it; `p` are the
    /// free numbers.
    fn curve(&mut self, k: usize, t: &Target, s: &AnalysisSensitivity, p: &Parameters) -> Result<(), TuneError> {
        let Aim::Curve { column, points, measure } = &t.aim else { return Ok(()) };
        let table = &s.report.table;
        if !table.columns.iter().any(|c| c == column) {
            let has = table.columns.clone();
            let (label, analysis, column) = (t.label.clone(), t.analysis.name(), column.to_string());
            return Err(NotGiven::NoColumn { label, analysis, column, has }.into());
        }
        let along: Vec<f64> = s.column(&table.columns[0]).iter().map(|v| v.unwrap_or(f64::NAN)).collect();
        rows_stay(t, s, p, &along)?;
        let values = s.column(column);
        let rates: Vec<Vec<super::sensitivity::Rate>> = (0..p.len()).map(|q| s.d_column(column, q)).collect();
        for CurveReading { at, aim, weight } in readings(points, *measure, &along) {
            let weights = interpolation(&along, at).map_err(|(lo, hi)| NotGiven::OutsideRange {
                label: t.label.clone(),
                at,
                lo,
                hi,
                parameter: t.analysis.parameter(),
            })?;
            let (mut reached, mut gradient) = (0.0, vec![0.0; p.len()]);
            for &(j, w) in &weights {
                let v = values[j].ok_or_else(|| NoReading::NoCell {
                    label: t.label.clone(),
                    at: along[j],
                    column: column.to_string(),
                })?;
                reached += w * v;
                for (g, rates) in gradient.iter_mut().zip(&rates) {
                    let d =
                        rates[j].map_err(|why| NoReading::CellRate { label: t.label.clone(), at: along[j], why })?;
                    *g += w * d.value;
                }
            }
            self.push(t, Row { target: k, at: Some(at), value: reached, aim, weight }, &gradient)?;
        }
        Ok(())
    }
}

/// The figure `key` of `s`, a run of `analysis` read for what `label` names, and its rates, in the unit
/// the figure is written in (the unit a target gives its value in; the figure and its rates are held in
/// SI).
fn figure_reading(
    label: &str,
    analysis: Analysis,
    s: &AnalysisSensitivity,
    key: &str,
) -> Result<(f64, Vec<f64>), TuneError> {
    let (figure, rates) = s.figure(key).ok_or_else(|| NotGiven::NoFigure {
        label: label.to_string(),
        analysis: analysis.name(),
        key: key.to_string(),
        has: s.report.figures.iter().map(|f| f.key.clone()).collect(),
    })?;
    let reached = figure.value.ok_or_else(|| NotGiven::NoValue {
        label: label.to_string(),
        reason: figure.reason.clone().unwrap_or_default(),
    })?;
    let factor = figure.unit.shown().factor;
    let gradient = rates
        .iter()
        .map(|r| r.map(|r| r.value * factor).map_err(|why| NoReading::FigureRate { label: label.to_string(), why }))
        .collect::<Result<Vec<f64>, _>>()?;
    Ok((reached * factor, gradient))
}

/// Refuses a curve target whose rows move with the free numbers: the rows must sit where they sit for
/// every model, and a range that moves with the model (the vertical-force sweep's, around its design load)
/// moves the curve under its points. `along` is the rows' load parameter, `p` the free numbers.
fn rows_stay(t: &Target, s: &AnalysisSensitivity, p: &Parameters, along: &[f64]) -> Result<(), TuneError> {
    let first = &s.report.table.columns[0];
    let span = along.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (q, xq) in p.values.iter().enumerate() {
        let moved = s.d_column(first, q).iter().filter_map(|d| d.ok()).fold(0.0f64, |m, d| m.max(d.value.abs()));
        if moved * xq.abs().max(0.1) > 1e-9 * span {
            return Err(NotGiven::RowsMove { label: t.label.clone(), pointer: p.pointers[q].clone() }.into());
        }
    }
    Ok(())
}

/// The miss of `reached` from `aim` over the target's tolerance, and its rates from the figure's `gradient`:
/// refused, naming the target, where they are too large to be squared (an aim of 1e308, a tolerance of
/// 1e-300), which the objective `½ Σ r²` is.
fn scaled_miss(t: &Target, weight: f64, reached: f64, aim: f64, gradient: &[f64]) -> Result<(f64, Vec<f64>), NotGiven> {
    let scale = t.weight / t.tolerance * reading_scale(t, weight);
    let residual = (reached - aim) * scale;
    let rates: Vec<f64> = gradient.iter().map(|g| g * scale).collect();
    if (residual * residual).is_finite() && rates.iter().all(|r| (r * r).is_finite()) {
        Ok((residual, rates))
    } else {
        Err(NotGiven::TooFar { label: t.label.clone(), reached, aim, tolerance: t.tolerance })
    }
}

/// What a reading of quadrature weight `weight` ([`CurveReading::weight`]) of target `t` counts in the
/// objective `½ Σ r²`, its miss over the tolerance times this: 1 at a point; `√(w / L)` for a curve
/// measured by its root mean square over its span `L`, so that `Σ r²` is that measure over the tolerance,
/// squared; `√(w L)` for one measured by the area between the curves, so that `Σ r²` is `L` times the
/// root mean square over the tolerance, squared, which bounds the area over the tolerance from above
/// (`∫|e| ≤ √(L ∫e²)`): a tune that brings its objective within 1 meets the area.
fn reading_scale(t: &Target, weight: f64) -> f64 {
    let Aim::Curve { points, measure, .. } = &t.aim else { return 1.0 };
    let span = points.last().map_or(0.0, |l| l.0) - points[0].0;
    match measure {
        CurveMeasure::Points => 1.0,
        CurveMeasure::Rms => (weight / span).sqrt(),
        CurveMeasure::Area => (weight * span).sqrt(),
    }
}

/// A hardpoint's position in `document`, and for each free pointer, which of its coordinates it is.
fn point(document: &Value, name: &str, pointers: &[String]) -> Result<([f64; 3], Vec<Option<usize>>), NotGiven> {
    let at = hardpoint_pointer(document, name).ok_or_else(|| NotGiven::NoHardpoint { name: name.into() })?;
    let xyz =
        document.pointer(&at).and_then(Value::as_array).ok_or_else(|| NotGiven::NotPlaced { name: name.into() })?;
    let c = |i: usize| xyz.get(i).and_then(Value::as_f64).unwrap_or(f64::NAN);
    let which = pointers.iter().map(|p| (0..3).find(|i| *p == format!("{at}/{i}"))).collect();
    Ok(([c(0), c(1), c(2)], which))
}

pub(super) fn linearise(c: &Constraint, document: &Value, pointers: &[String]) -> Result<Linearised, NotGiven> {
    let n = pointers.len();
    let rates_of = |which: &[Option<usize>], along: [f64; 3]| -> Vec<f64> {
        which.iter().map(|w| w.map_or(0.0, |i| along[i])).collect()
    };
    Ok(match c {
        Constraint::Distance { points, min, max } => {
            let (a, wa) = point(document, &points[0], pointers)?;
            let (b, wb) = point(document, &points[1], pointers)?;
            let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
            let value = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let u = d.map(|v| v / value.max(1e-300));
            let (ra, rb) = (rates_of(&wa, u), rates_of(&wb, u.map(|v| -v)));
            Linearised { value, rates: (0..n).map(|k| ra[k] + rb[k]).collect(), min: *min, max: *max }
        }
        Constraint::OutsideSphere { point: name, centre, radius } => {
            let (p, w) = point(document, name, pointers)?;
            let d = [p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]];
            let value = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let u = d.map(|v| v / value.max(1e-300));
            Linearised { value, rates: rates_of(&w, u), min: *radius, max: f64::INFINITY }
        }
        Constraint::OutsideBox { point: name, min, max } => {
            // Outside along the axis where it is furthest out (or, inside, least deep): that face's plane,
            // a half-space the point is kept in.
            let (p, w) = point(document, name, pointers)?;
            // (axis, side: +1 beyond max, −1 below min, how far out)
            let (axis, side, _) = (0..3)
                .flat_map(|i| [(i, 1.0, p[i] - max[i]), (i, -1.0, min[i] - p[i])])
                .max_by(|a, b| a.2.total_cmp(&b.2))
                .expect("three axes");
            let mut along = [0.0; 3];
            along[axis] = side;
            let face = if side > 0.0 { max[axis] } else { -min[axis] };
            Linearised { value: side * p[axis], rates: rates_of(&w, along), min: face, max: f64::INFINITY }
        }
    })
}

/// One iteration of a tune, as `tune.csv` lists it.
#[derive(Debug, Clone, PartialEq)]
pub struct Iteration {
    /// Its number (0: the start).
    pub iteration: usize,
    /// `½ Σ r²` after it.
    pub objective: f64,
    /// The largest rate of the objective along a free number that may still move (at a bound, only
    /// inward), per unit of the number.
    pub gradient_norm: f64,
    /// The largest move of a free number in the step taken, relative to its bounds' span.
    pub step: f64,
    /// The damping the step was taken with.
    pub damping: f64,
    /// K&C evaluations (each a run with its sensitivities) so far.
    pub evaluations: usize,
    /// What became of the step: `start`, `taken`, or why it was not.
    pub outcome: String,
}

/// A target's outcome.
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    /// The target's label.
    pub target: String,
    /// Its misses measured against its tolerance ([`Target::measured`]): the largest miss over the
    /// tolerance, a curve's root mean square or area over it, or `χ²/n` over the most noise gives.
    pub worst: f64,
    /// Whether it is met: [`Target::measured`] at most 1 ([`Target::met_by`]).
    pub met: bool,
    /// How it was judged, in words ([`Target::judged_words`]).
    pub judged: String,
    /// Why not, when not.
    pub why: Option<String>,
}

/// A packaging constraint at the end of a tune: a broken one is a miss, as a target not met is.
#[derive(Debug, Clone, PartialEq)]
pub struct PackagingVerdict {
    /// Which, in the TARGETS file's words (`constraints[0]: distance tie_rod_inner–tie_rod_outer`).
    pub constraint: String,
    /// How far outside its allowed range it is (m): zero where it holds.
    pub broken_by: f64,
}

/// What a tune found.
#[derive(Debug, Clone)]
pub struct Tuned {
    /// The model at the start.
    pub start: Evaluation,
    /// The model at the end.
    pub end: Evaluation,
    /// Every iteration.
    pub iterations: Vec<Iteration>,
    /// Each target's outcome.
    pub verdicts: Vec<Verdict>,
    /// Each packaging constraint's outcome, in the file's order.
    pub packaging: Vec<PackagingVerdict>,
    /// Why the iterations stopped.
    pub stopped: String,
    /// The model file with the free numbers at the end, every other key and the order of keys as given.
    pub document: Value,
    /// The objective's figure at the start and the end, and what holds it, when the targets have one.
    pub objective: Option<ObjectiveVerdict>,
    /// What the fit can know of the free numbers at the end: their uncertainties and correlations, those a
    /// bound holds, the directions the targets cannot tell (none with an objective, which is no fit).
    pub uncertainty: Option<FitUncertainty>,
}

/// An objective's outcome: its figure before and after (in the unit it is written in), and what holds it
/// there.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectiveVerdict {
    /// The objective, in the TARGETS file's words: `objective (least parallel-travel/bump_steer)`.
    pub label: String,
    /// The figure at the start.
    pub start: f64,
    /// The figure at the end.
    pub end: f64,
    /// The unit both are in, as the figure is written.
    pub unit: String,
    /// What holds it: the free numbers at a bound, the packaging at its limits, the targets at the ends
    /// of their tolerances, in the engineer's words.
    pub held_by: Vec<String>,
}

impl Tuned {
    /// Whether every target is met and every packaging constraint holds.
    pub fn all_met(&self) -> bool {
        self.verdicts.iter().all(|v| v.met) && self.packaging.iter().all(|p| p.broken_by == 0.0)
    }

    /// `tune.csv`: every iteration — its objective, projected gradient, step, damping, evaluations so far
    /// and what became of the step.
    pub fn iteration_table(&self) -> Table {
        let columns: [Column<Iteration>; 7] = [
            Column::new("iteration", |i: &Iteration| Cell::from(i.iteration as f64)),
            Column::new("objective", |i: &Iteration| Cell::from(i.objective)),
            Column::new("gradient_norm", |i: &Iteration| Cell::from(i.gradient_norm)),
            Column::new("step", |i: &Iteration| Cell::from(i.step)),
            Column::new("damping", |i: &Iteration| Cell::from(i.damping)),
            Column::new("evaluations", |i: &Iteration| Cell::from(i.evaluations as f64)),
            Column::new("outcome", |i: &Iteration| Cell::Text(i.outcome.clone())),
        ];
        Table::of_columns("tune", &columns, &self.iterations)
    }

    /// `tune_targets.csv`: every residual at the start and the end — its target, the load parameter of a
    /// curve point, the value aimed at, the values reached, and the miss over the tolerance (unweighted,
    /// and unscaled by a curve measure's reading weight: each reading's own).
    pub fn residual_table(&self, targets: &Targets) -> Table {
        type Pair<'r> = (&'r Row, &'r Row);
        let miss = |r: &Row| Cell::from((r.value - r.aim) / targets.targets[r.target].tolerance);
        let columns: [Column<Pair>; 7] = [
            Column::new("target", |(end, _): &Pair| Cell::Text(targets.targets[end.target].label.clone())),
            Column::new("at", |(end, _): &Pair| Cell::from(end.at)),
            Column::new("aim", |(end, _): &Pair| Cell::from(end.aim)),
            Column::new("before", |(_, start): &Pair| Cell::from(start.value)),
            Column::new("after", |(end, _): &Pair| Cell::from(end.value)),
            Column::new("miss_over_tolerance_before", move |(_, start): &Pair| miss(start)),
            Column::new("miss_over_tolerance_after", move |(end, _): &Pair| miss(end)),
        ];
        let rows: Vec<Pair> = self.end.rows.iter().zip(&self.start.rows).collect();
        Table::of_columns("tune_targets", &columns, &rows)
    }

    /// The free numbers: each before and after the tune, its move, its standard uncertainty at the end
    /// (empty where the fit gives none) and its bounds.
    pub fn moved_table(&self, targets: &Targets) -> Table {
        let standard = |k: usize| Cell::from(self.uncertainty.as_ref().and_then(|u| u.standard[k]));
        let columns: [Column<(usize, &Free)>; 7] = [
            Column::new("parameter", |(_, f): &(usize, &Free)| Cell::Text(f.pointer.clone())),
            Column::new("before", |&(k, _): &(usize, &Free)| Cell::from(self.start.x[k])),
            Column::new("after", |&(k, _): &(usize, &Free)| Cell::from(self.end.x[k])),
            Column::new("move", |&(k, _): &(usize, &Free)| Cell::from(self.end.x[k] - self.start.x[k])),
            Column::new("standard_uncertainty", move |&(k, _): &(usize, &Free)| standard(k)),
            Column::new("min", |(_, f): &(usize, &Free)| Cell::from(f.min)),
            Column::new("max", |(_, f): &(usize, &Free)| Cell::from(f.max)),
        ];
        let rows: Vec<(usize, &Free)> = targets.free.iter().enumerate().collect();
        Table::of_columns("tune_parameters", &columns, &rows)
    }

    /// `tune_uncertainty.csv`: each free number at the end, its standard uncertainty (empty where the fit
    /// gives none, and throughout for an objective's optimum), whether a bound holds it, and its
    /// correlation with each other free number.
    pub fn uncertainty_table(&self, targets: &Targets) -> Table {
        let u = self.uncertainty.as_ref();
        let mut columns: Vec<Column<(usize, &Free)>> = vec![
            Column::new("parameter", |(_, f): &(usize, &Free)| Cell::Text(f.pointer.clone())),
            Column::new("value", |&(k, _): &(usize, &Free)| Cell::from(self.end.x[k])),
            Column::new("standard_uncertainty", move |&(k, _): &(usize, &Free)| {
                Cell::from(u.and_then(|u| u.standard[k]))
            }),
            Column::new("at_bound", move |&(k, f): &(usize, &Free)| {
                let held = match u {
                    Some(u) => u.at_bound.contains(&k),
                    None => super::fit::held_at(self.end.x[k], (f.min, f.max)).is_some(),
                };
                Cell::Text(if held { "yes" } else { "no" }.into())
            }),
        ];
        for (l, other) in targets.free.iter().enumerate() {
            let name = format!("correlation with {}", super::parameter_words(&other.pointer));
            columns.push(Column::new(name, move |&(k, _): &(usize, &Free)| {
                Cell::from(u.and_then(|u| u.correlation[k][l]))
            }));
        }
        let rows: Vec<(usize, &Free)> = targets.free.iter().enumerate().collect();
        Table::of_columns("tune_uncertainty", &columns, &rows)
    }

    /// Before-and-after plots: each curve target's column against its load parameter at the start and
    /// the end, with the target's points.
    pub fn charts(&self, targets: &Targets, model: &str) -> Vec<Chart> {
        let mut charts = Vec::new();
        for (k, t) in targets.targets.iter().enumerate() {
            let Aim::Curve { column, points, .. } = &t.aim else { continue };
            let curve = |e: &Evaluation, name: &str| -> Option<Series> {
                let report = e.reports.iter().find(|r| r.analysis == t.analysis)?;
                let c = report.table.columns.iter().position(|x| x == column)?;
                let pts = report.table.rows.iter().filter_map(|r| Some((r[0].number()?, r[c].number()?))).collect();
                Some(Series { name: name.into(), points: pts })
            };
            let series: Vec<Series> = [curve(&self.start, "before"), curve(&self.end, "after")]
                .into_iter()
                .flatten()
                .chain([Series { name: "target".into(), points: points.clone() }])
                .collect();
            let report = self.end.reports.iter().find(|r| r.analysis == t.analysis);
            charts.push(Chart {
                name: format!("tune_target_{k}"),
                title: format!("{}: before and after the tune", t.label),
                subtitle: model.into(),
                x_label: report.map_or_else(|| t.analysis.parameter().to_string(), |r| r.table.columns[0].clone()),
                x_scale: Scale::Linear,
                left: YAxis { label: column.clone(), scale: Scale::Linear, series },
                right: None,
                design_x: None,
            });
        }
        charts
    }
}

/// Why no step can be computed at `e`, if a free number's bounds' span, times the targets' rates against
/// it (the Jacobian in the numbers scaled by their spans, which [`step`] solves with), is no finite number:
/// bounds such as `[-1e308, 0]` on a hardpoint coordinate.
fn too_wide(e: &Evaluation, targets: &Targets, free: &[(f64, f64)]) -> Option<NotGiven> {
    let k = (0..free.len()).find(|&k| {
        let span = free[k].1 - free[k].0;
        !(span * span).is_finite() || e.jacobian.iter().any(|row| !(row[k] * span).is_finite())
    })?;
    let (lo, hi) = free[k];
    Some(NotGiven::TooWide { pointer: targets.free[k].pointer.clone(), lo, hi })
}

/// The largest rate of `½ Σ r²` along a free number that may still move: at a bound only inward.
fn projected_gradient(e: &Evaluation, free: &[(f64, f64)]) -> f64 {
    e.gradient()
        .iter()
        .zip(&e.x)
        .zip(free)
        .map(|((g, x), (lo, hi))| {
            let blocked = (*x <= *lo && *g > 0.0) || (*x >= *hi && *g < 0.0);
            if blocked {
                0.0
            } else {
                g.abs()
            }
        })
        .fold(0.0, f64::max)
}

/// Why no step could be computed.
#[derive(Debug, thiserror::Error)]
enum NoStep {
    /// The rates or residuals are no finite numbers.
    #[error("the step's least squares: its rates or residuals are no finite numbers")]
    NotFinite,
    /// The least-squares solve refused.
    #[error("the step's least squares: {0}")]
    LeastSquares(&'static str),
    /// The quadratic program could not be set up.
    #[error("the step's QP: {0}")]
    Program(String),
    /// The quadratic program ended unsolved.
    #[error("the step's QP ended {0:?}")]
    Ended(SolverStatus),
}

/// The damped Gauss–Newton step within the bounds and the linearised packaging:
/// `min ½‖J d + r‖² + ½ μ Σ Dₖ dₖ²` over `lo − x ≤ d ≤ hi − x`, `min ≤ g + G d ≤ max`. In the numbers scaled
/// by `√Dₖ` (so that each moves its residuals alike); first as the least-squares solution of
/// `[J; √μ I] d = [−r; 0]` by a singular-value decomposition, which stays accurate where the targets leave a
/// combination of the numbers free (rank-deficient `J`); where that step leaves the bounds or the packaging,
/// as the quadratic program it is, by Clarabel.
///
/// With an objective (`e.goal`, and its `curvature`, `B`), the step of sequential quadratic programming
/// instead: `min g·d + ½ dᵀ B d + ½ μ Σ Dₖ dₖ²` of the objective's gradient `g` within the same bounds, the
/// packaging and the targets' bounds, linearised.
fn step(
    e: &Evaluation,
    free: &[(f64, f64)],
    damping: f64,
    scale: &[f64],
    margins: &[f64],
    curvature: Option<&nalgebra::DMatrix<f64>>,
) -> Result<Vec<f64>, NoStep> {
    let n = e.x.len();
    let unscale: Vec<f64> = scale.iter().map(|d| 1.0 / d.sqrt()).collect();
    let (p_full, q) = match (&e.goal, curvature) {
        (Some(goal), Some(b)) => {
            let mut p = nalgebra::DMatrix::<f64>::identity(n, n) * damping;
            for i in 0..n {
                for j in 0..n {
                    p[(i, j)] += unscale[i] * b[(i, j)] * unscale[j];
                }
            }
            let q: Vec<f64> = goal.rates.iter().zip(&unscale).map(|(r, u)| goal.sign * r * u).collect();
            if !(p.iter().chain(&q).all(|v| v.is_finite())) {
                return Err(NoStep::NotFinite);
            }
            (p, q)
        }
        _ => match least_squares_step(e, damping, &unscale, free, margins)? {
            Ok(d) => return Ok(d),
            Err(program) => program,
        },
    };
    constrained_step(e, free, margins, &unscale, &p_full, &q)
}

/// The damped Gauss–Newton step by least squares where it stays within the bounds and the packaging, else
/// the quadratic program's `(P, q)` in the scaled numbers.
#[allow(clippy::type_complexity, reason = "a step, or the program that gives it")]
fn least_squares_step(
    e: &Evaluation,
    damping: f64,
    unscale: &[f64],
    free: &[(f64, f64)],
    margins: &[f64],
) -> Result<Result<Vec<f64>, (nalgebra::DMatrix<f64>, Vec<f64>)>, NoStep> {
    let n = e.x.len();
    let m = e.residuals.len();
    // The scaled Jacobian J S, stacked over √μ I.
    let mut a = nalgebra::DMatrix::<f64>::zeros(m + n, n);
    let mut b = nalgebra::DVector::<f64>::zeros(m + n);
    for (i, row) in e.jacobian.iter().enumerate() {
        for k in 0..n {
            a[(i, k)] = row[k] * unscale[k];
        }
        b[i] = -e.residuals[i];
    }
    for k in 0..n {
        a[(m + k, k)] = damping.sqrt();
    }
    // The decomposition panics on a number that is not finite ([`too_wide`] stops the tune before).
    if !(a.iter().all(|v| v.is_finite()) && b.iter().all(|v| v.is_finite())) {
        return Err(NoStep::NotFinite);
    }
    // A combination of the numbers the targets barely see (a singular value a billionth of the largest)
    // is left where it is: a step along it would follow rounding, not the targets.
    let svd = a.clone().svd(true, true);
    let floor = 1e-9 * svd.singular_values.max();
    let free_step = svd.solve(&b, floor).map_err(NoStep::LeastSquares)?;
    let d: Vec<f64> = (0..n).map(|k| free_step[k] * unscale[k]).collect();
    let inside = d.iter().zip(&e.x).zip(free).all(|((d, x), (lo, hi))| (*lo..=*hi).contains(&(x + d)));
    let packed = e.packaging.iter().zip(margins).all(|(c, m)| {
        let v = c.value + c.rates.iter().zip(&d).map(|(r, d)| r * d).sum::<f64>();
        v >= c.min + m && v <= c.max - m
    });
    if inside && packed {
        return Ok(Ok(d));
    }
    // The quadratic program in the scaled numbers: P = (JS)ᵀ(JS) + μI, q = (JS)ᵀ r.
    let js = a.rows(0, m);
    let p_full = js.transpose() * js + nalgebra::DMatrix::<f64>::identity(n, n) * damping;
    let q: Vec<f64> =
        (js.transpose() * nalgebra::DVector::from_iterator(m, e.residuals.iter().copied())).iter().copied().collect();
    Ok(Err((p_full, q)))
}

/// The step as the quadratic program `min ½ uᵀ P u + q·u` in the scaled numbers `u` (`d = S u`, `S` =
/// `unscale`), within the bounds and the linearised packaging (kept inside by its `margins`, a broken
/// constraint brought back).
fn constrained_step(
    e: &Evaluation,
    free: &[(f64, f64)],
    margins: &[f64],
    unscale: &[f64],
    p_full: &nalgebra::DMatrix<f64>,
    q: &[f64],
) -> Result<Vec<f64>, NoStep> {
    let n = e.x.len();
    // Rows of `A d ≤ b` (Clarabel's `A d + s = b`, `s ≥ 0`).
    let (mut rows, mut bound): (Vec<Vec<f64>>, Vec<f64>) = (Vec::new(), Vec::new());
    for (k, &(lo, hi)) in free.iter().enumerate() {
        let mut up = vec![0.0; n];
        up[k] = unscale[k];
        rows.push(up.clone());
        bound.push(hi - e.x[k]);
        rows.push(up.iter().map(|v| -v).collect());
        bound.push(e.x[k] - lo);
    }
    for (c, m) in e.packaging.iter().zip(margins) {
        if c.rates.iter().all(|r| *r == 0.0) {
            continue;
        }
        let scaled: Vec<f64> = c.rates.iter().zip(unscale).map(|(r, u)| r * u).collect();
        // A broken constraint is brought back inside by the step, to first order; one that holds stays
        // inside, by its margin where it can.
        let restore = broken_by(c) > 0.0;
        let room = |room: f64| if restore { room } else { (room - m).max(0.0) };
        if c.max.is_finite() {
            rows.push(scaled.clone());
            bound.push(room(c.max - c.value));
        }
        if c.min.is_finite() {
            rows.push(scaled.iter().map(|r| -r).collect());
            bound.push(room(c.value - c.min));
        }
    }
    let upper: Vec<Vec<f64>> =
        (0..n).map(|i| (0..n).map(|j| if j >= i { p_full[(i, j)] } else { 0.0 }).collect()).collect();
    let p = CscMatrix::from(&upper);
    let a_matrix = CscMatrix::from(&rows);
    let cones: [SupportedConeT<f64>; 1] = [NonnegativeConeT(bound.len())];
    let settings =
        DefaultSettingsBuilder::default().verbose(false).build().map_err(|e| NoStep::Program(e.to_string()))?;
    let mut solver = DefaultSolver::new(&p, q, &a_matrix, &bound, &cones, settings)
        .map_err(|e| NoStep::Program(format!("{e:?}")))?;
    solver.solve();
    match solver.solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => {
            Ok(solver.solution.x.iter().zip(unscale).map(|(v, u)| v * u).collect())
        }
        other => Err(NoStep::Ended(other)),
    }
}

/// How far a packaging constraint lies outside its allowed range (m), within 1e-9 m counting as inside.
fn broken_by(c: &Linearised) -> f64 {
    let out = (c.min - c.value).max(c.value - c.max).max(0.0);
    if out <= 1e-9 {
        0.0
    } else {
        out
    }
}

/// How far the packaging at `e` is broken, all its constraints together (m).
fn broken(e: &Evaluation) -> f64 {
    e.packaging.iter().map(broken_by).sum()
}

/// Where the packaging at `e` is broken, what a step works on first: each broken constraint's signed
/// distance outside its range as a residual (its rates the rows of the Jacobian), the constraints that hold
/// kept as packaging with their `margins`; the targets wait until the packaging holds.
fn restoration(e: &Evaluation, margins: &[f64]) -> Option<(Evaluation, Vec<f64>)> {
    if packaged(e) {
        return None;
    }
    let (broken, holding): (Vec<_>, Vec<_>) = e.packaging.iter().zip(margins).partition(|(c, _)| broken_by(c) > 0.0);
    let outside = |c: &Linearised| if c.value < c.min { c.value - c.min } else { c.value - c.max };
    let restoring = Evaluation {
        x: e.x.clone(),
        residuals: broken.iter().map(|(c, _)| outside(c)).collect(),
        jacobian: broken.iter().map(|(c, _)| c.rates.clone()).collect(),
        rows: Vec::new(),
        packaging: holding.iter().map(|(c, _)| (*c).clone()).collect(),
        goal: None,
        reports: Vec::new(),
    };
    Some((restoring, holding.iter().map(|(_, m)| **m).collect()))
}

/// Whether a packaging constraint is at a limit (within 1e-7 m), where it holds the tune.
fn at_limit(c: &Linearised) -> bool {
    (c.value - c.min).abs() <= 1e-7 || (c.max - c.value).abs() <= 1e-7
}

/// Whether the packaging holds at `e`, to 1e-9 m.
fn packaged(e: &Evaluation) -> bool {
    broken(e) == 0.0
}

/// Tunes the model of `parameters` (its free numbers, in the order of `targets.free`) to `targets`.
/// `progress` hears of each iteration. Fails only when the model as it is cannot be evaluated: because the
/// targets ask what its analyses do not give ([`TuneError::Targets`]) or it cannot be analysed
/// ([`TuneError::Model`]); a step whose model cannot be built or run is stepped back from.
pub fn tune(
    parameters: &Parameters,
    targets: &Targets,
    mut progress: impl FnMut(&Iteration),
) -> Result<Tuned, TuneError> {
    let free: Vec<(f64, f64)> = targets.free.iter().map(|f| (f.min, f.max)).collect();
    let start = evaluate(parameters, targets, &parameters.values)?;
    if let Some(why) = too_wide(&start, targets, &free) {
        return Err(TuneError::Targets(why));
    }
    let mut search = Search::new(parameters, targets, free, start.clone());
    let mut iterations = vec![Iteration { damping: 0.0, ..search.record(0, 0.0, "start") }];
    progress(&iterations[0]);
    let (mut stopped, no_step) = search.run(|iteration| {
        progress(&iteration);
        iterations.push(iteration);
    });
    let Search { here, free, unbuildable, .. } = search;
    let (packaging, bounds) = here.packaging.split_at(targets.constraints.len());
    if packaging.iter().any(|c| broken_by(c) > 0.0) {
        stopped = "the packaging is still broken, and no step within the bounds brings it back further".into();
    } else if bounds.iter().any(|c| broken_by(c) > 0.0) {
        stopped = "a target is still beyond its tolerance, and no step within the bounds brings it back further".into();
    }
    let verdicts = verdicts(&here, targets, &free, unbuildable.as_ref(), no_step.as_ref());
    let packaging = targets
        .constraints
        .iter()
        .zip(&here.packaging)
        .enumerate()
        .map(|(k, (c, at))| PackagingVerdict {
            constraint: format!("constraints[{k}]: {}", c.said()),
            broken_by: broken_by(at),
        })
        .collect();
    let document = parameters.document_at(&here.x)?;
    // An objective's optimum is no fit: its numbers have no uncertainty to give.
    let uncertainty = targets.objective.is_none().then(|| {
        let held: Vec<Vec<f64>> = here.packaging[..targets.constraints.len()]
            .iter()
            .filter(|c| at_limit(c))
            .map(|c| c.rates.clone())
            .collect();
        FitUncertainty::of(&here.x, &free, &here.residuals, &here.jacobian, &held)
    });
    let objective = targets.objective.as_ref().zip(start.goal.as_ref().zip(here.goal.as_ref())).map(|(o, (a, b))| {
        ObjectiveVerdict {
            label: o.label.clone(),
            start: a.figure,
            end: b.figure,
            unit: here
                .reports
                .iter()
                .filter(|r| r.analysis == o.analysis)
                .find_map(|r| r.figure(&o.key))
                .map_or_else(String::new, |f| f.unit.shown().symbol.to_string()),
            held_by: held_by(&here, targets, &free),
        }
    });
    Ok(Tuned { start, end: here, iterations, verdicts, packaging, objective, stopped, document, uncertainty })
}

/// What became of an iteration's step.
enum Outcome {
    /// None could be computed.
    NoStep(NoStep),
    /// It was taken.
    Taken,
    /// Stepped back from: the model there could not be evaluated, for this reason.
    Unbuildable(String),
    /// Stepped back from: it broke the packaging.
    BrokePackaging,
    /// Stepped back from: it gained nothing.
    GainedNothing,
    /// Not taken: with an objective, the step vanishes (the bounds, the packaging and the targets' bounds
    /// hold the objective where it is, or its rate vanishes).
    Vanished,
}

impl std::fmt::Display for Outcome {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Outcome::NoStep(why) => write!(f, "{why}"),
            Outcome::Taken => f.write_str("taken"),
            Outcome::Unbuildable(why) => write!(f, "stepped back: {why}"),
            Outcome::BrokePackaging => f.write_str("stepped back: it broke the packaging"),
            Outcome::GainedNothing => f.write_str("stepped back: it gained nothing"),
            Outcome::Vanished => f.write_str("no step: the objective can gain no more within the bounds"),
        }
    }
}

/// Where a tune stands between iterations, and what shapes its next step.
struct Search<'a> {
    parameters: &'a Parameters,
    targets: &'a Targets,
    /// Each free number's bounds.
    free: Vec<(f64, f64)>,
    /// Each number measured by the span of its bounds: the damping, and the step where the targets leave
    /// a combination of the numbers free, then prefer the smallest moves relative to what each may move (a
    /// millimetre of a hardpoint free over ±20 mm weighs as much as 10 N/mm of a rate free over
    /// ±200 N/mm). (Marquardt's scaling by each number's own curvature instead sends an insensitive
    /// number, such as a tie-rod point along the rod, far in every step: the MacPherson's toe curve then
    /// crept for 60 steps.)
    scale: Vec<f64>,
    /// The model where the tune stands.
    here: Evaluation,
    damping: f64,
    /// How far inside its linearised bounds each packaging constraint is kept: a distance bends away from
    /// its linearisation (it is convex), so a step to its bound overshoots by the bend; a step that broke
    /// it is retried with the overshoot held back.
    margins: Vec<f64>,
    /// How far a step may reach (relative to the bounds' span): unlimited until a step is stepped back
    /// from, then half of that step's, so that a model that cannot be built or run beyond some point is
    /// approached, not stepped over again and again (damping alone shortens a step slowly where the
    /// targets see the number strongly).
    reach: f64,
    /// Why the model could not be evaluated at the last step stepped back from, if that was why.
    unbuildable: Option<TuneError>,
    /// How many times the targets were evaluated.
    evaluations: usize,
    /// A step taken that gained next to nothing, or moved next to nothing: the last.
    converged: bool,
    /// With an objective, the curvature of its figure the steps have measured (BFGS, in the numbers'
    /// own units; zero at the start, where the damping alone shapes the step).
    curvature: nalgebra::DMatrix<f64>,
}

impl<'a> Search<'a> {
    /// A search from `start`, the model as it is.
    fn new(parameters: &'a Parameters, targets: &'a Targets, free: Vec<(f64, f64)>, start: Evaluation) -> Self {
        Search {
            parameters,
            targets,
            scale: free.iter().map(|(lo, hi)| 1.0 / ((hi - lo) * (hi - lo))).collect(),
            margins: vec![0.0; start.packaging.len()],
            free,
            here: start,
            damping: 1e-3,
            reach: f64::INFINITY,
            unbuildable: None,
            evaluations: 1,
            converged: false,
            curvature: nalgebra::DMatrix::zeros(parameters.len(), parameters.len()),
        }
    }

    /// Iterates until the targets are met, no step gains any more, or the iteration limit; `heard` hears
    /// of each iteration. Why it stopped, and the step that could not be computed if that was why.
    fn run(&mut self, mut heard: impl FnMut(Iteration)) -> (String, Option<NotGiven>) {
        let mut rejected = 0;
        for iteration in 1..=MAX_ITERATIONS {
            let sought = self.here.goal.is_some();
            if !sought && self.here.residuals.iter().all(|r| r.abs() <= MET_EXACTLY) && packaged(&self.here) {
                return (format!("every target is met to {MET_EXACTLY:e} of its tolerance"), None);
            }
            // Bounds that are too wide where the tune starts are refused there; the rates may grow on the way.
            if let Some(why) = too_wide(&self.here, self.targets, &self.free) {
                return (why.to_string(), Some(why));
            }
            let (outcome, size) = self.iterate();
            rejected = if matches!(outcome, Outcome::Taken) { 0 } else { rejected + 1 };
            heard(self.record(iteration, size, &outcome.to_string()));
            if self.converged {
                return ("the steps no longer gain: the targets are met as nearly as they can be".into(), None);
            }
            let objective = self.here.objective();
            if !sought
                && projected_gradient(&self.here, &self.free) <= 1e-13 * (1.0 + objective) * self.here.x.len() as f64
            {
                let why = "the gradient vanishes within the bounds: the targets are met as nearly as they can be";
                return (why.into(), None);
            }
            if rejected >= 12 || self.damping > 1e12 {
                return ("no step gains any more: the targets are met as nearly as they can be".into(), None);
            }
        }
        (format!("the iteration limit ({MAX_ITERATIONS}) was reached"), None)
    }

    /// One iteration: a step computed (for bringing the packaging back where it is broken, else for the
    /// targets), evaluated, and taken or stepped back from. What became of it, and its size.
    fn iterate(&mut self) -> (Outcome, f64) {
        let restoring = restoration(&self.here, &self.margins);
        let (basis, margins) = restoring.as_ref().map_or((&self.here, &self.margins[..]), |(e, m)| (e, &m[..]));
        let curvature = (restoring.is_none() && self.here.goal.is_some()).then_some(&self.curvature);
        match step(basis, &self.free, self.damping, &self.scale, margins, curvature) {
            Err(why) => {
                self.damping *= 10.0;
                (Outcome::NoStep(why), 0.0)
            }
            Ok(d) => self.try_step(&d, restoring.is_some()),
        }
    }

    /// The step `d`, within the reach a step back left, evaluated, and taken or stepped back from; where
    /// `restoring`, it is taken for bringing the packaging back, whatever it does to the targets, else for
    /// gaining on the targets and keeping the packaging.
    fn try_step(&mut self, d: &[f64], restoring: bool) -> (Outcome, f64) {
        let f = self.here.objective();
        // The largest move relative to the bounds' span.
        let wanted = d.iter().zip(&self.free).map(|(d, (lo, hi))| d.abs() / (hi - lo)).fold(0.0, f64::max);
        let shrink = if wanted > self.reach { self.reach / wanted } else { 1.0 };
        let d: Vec<f64> = d.iter().map(|v| v * shrink).collect();
        let x: Vec<f64> =
            self.here.x.iter().zip(&d).zip(&self.free).map(|((x, d), (lo, hi))| (x + d).clamp(*lo, *hi)).collect();
        let size = wanted * shrink;
        if self.here.goal.is_some() && !restoring && size < 1e-9 {
            self.converged = true;
            return (Outcome::Vanished, size);
        }
        let predicted = match &self.here.goal {
            // The quadratic model's gain: −(g·d + ½ dᵀ B d).
            Some(g) => {
                let bd = &self.curvature * nalgebra::DVector::from_column_slice(&d);
                -(g.rates.iter().zip(&d).map(|(r, d)| g.sign * r * d).sum::<f64>()
                    + 0.5 * bd.iter().zip(&d).map(|(b, d)| b * d).sum::<f64>())
            }
            None => f - self.here.predicted_objective(&d),
        };
        self.evaluations += 1;
        match evaluate(self.parameters, self.targets, &x) {
            Err(e) => {
                self.damping *= 4.0;
                self.reach = 0.5 * size;
                let outcome = Outcome::Unbuildable(e.to_string());
                self.unbuildable = Some(e);
                (outcome, size)
            }
            Ok(next)
                if (restoring && broken(&next) < broken(&self.here))
                    || (!restoring && next.objective() < f && packaged(&next)) =>
            {
                self.take(next, predicted, size, restoring);
                (Outcome::Taken, size)
            }
            Ok(next) if !restoring && !packaged(&next) => {
                self.reach = 0.5 * size;
                for ((m, c), was) in self.margins.iter_mut().zip(&next.packaging).zip(&self.here.packaging) {
                    // The bend of the constraint over the step, held back next time.
                    *m += 2.0 * broken_by(c) + 1e-12 * was.value.abs();
                }
                (Outcome::BrokePackaging, size)
            }
            Ok(_) => {
                self.damping *= 4.0;
                self.reach = 0.5 * size;
                (Outcome::GainedNothing, size)
            }
        }
    }

    /// Moves to `next`, a step of `size` whose gain the Gauss–Newton model `predicted`: the damping follows
    /// how well the model predicted it (unless the step `restored` the packaging), the reach doubles.
    fn take(&mut self, next: Evaluation, predicted: f64, size: f64, restored: bool) {
        let f = self.here.objective();
        let gain = f - next.objective();
        self.margins.iter_mut().for_each(|m| *m *= 0.5);
        let ratio = gain / predicted.max(f64::MIN_POSITIVE);
        if !restored && ratio > 0.75 {
            self.damping /= 3.0;
        } else if !restored && ratio < 0.25 {
            self.damping *= 2.0;
        }
        self.damping = self.damping.max(1e-12);
        self.reach *= 2.0;
        self.unbuildable = None;
        if let (Some(was), Some(now)) = (&self.here.goal, &next.goal) {
            let step = next.x.iter().zip(&self.here.x).map(|(a, b)| a - b);
            let change = now.rates.iter().zip(&was.rates).map(|(a, b)| now.sign * (a - b));
            measure_curvature(&mut self.curvature, step.collect(), change.collect());
        }
        let sought = next.goal.is_some();
        self.here = next;
        // An objective's figure may be near zero or negative: its gain is measured against its size and 1.
        let small = if sought { 1e-12 * (1.0 + f.abs()) } else { 1e-9 * f };
        if !restored && (gain <= small || size < 1e-9) {
            self.converged = true;
        }
    }

    /// The record of iteration `iteration`, a step of `size` that ended `outcome`.
    fn record(&self, iteration: usize, size: f64, outcome: &str) -> Iteration {
        Iteration {
            iteration,
            objective: self.here.objective(),
            gradient_norm: projected_gradient(&self.here, &self.free),
            step: size,
            damping: self.damping,
            evaluations: self.evaluations,
            outcome: outcome.into(),
        }
    }
}

impl ObjectiveVerdict {
    /// In words: the figure before and after, and what holds it.
    pub fn said(&self) -> String {
        let held = if self.held_by.is_empty() {
            "where its rate vanishes within the bounds".to_string()
        } else {
            format!("held by {}", self.held_by.join(", "))
        };
        format!(
            "{}: {} -> {} {}, {held}",
            self.label,
            kc::significant(self.start, 4),
            kc::significant(self.end, 4),
            self.unit
        )
    }
}

/// What holds the model at `e`: the free numbers at a bound, the packaging at its limits and, with an
/// objective, the targets at an end of their tolerance, in the engineer's words.
fn held_by(e: &Evaluation, targets: &Targets, free: &[(f64, f64)]) -> Vec<String> {
    let at_bound = e.x.iter().zip(free).zip(&targets.free).filter_map(|((x, &(lo, hi)), f)| {
        let bound = super::fit::held_at(*x, (lo, hi))?;
        let which = if bound == lo { "lower" } else { "upper" };
        let value = super::parameter_value_words(&f.pointer, bound);
        Some(format!("{} at its {which} bound, {value}", super::parameter_words(&f.pointer)))
    });
    let (packaging, bounds) = e.packaging.split_at(targets.constraints.len());
    let packed = packaging.iter().enumerate().filter(|(_, c)| at_limit(c)).map(|(k, c)| {
        let side = if (c.value - c.min).abs() <= 1e-7 { "least" } else { "most" };
        format!("the packaging's {} at its {side} (constraints[{k}])", targets.constraints[k].said())
    });
    // A bound's rows are the targets' residuals, in order.
    let tolerances = bounds.iter().zip(&e.rows).filter(|(c, _)| c.value.abs() >= 1.0 - 1e-6).map(|(c, row)| {
        let t = &targets.targets[row.target];
        let at = row.at.map_or(String::new(), |at| format!(" at {}", kc::plain(at)));
        let side = if c.value > 0.0 { "upper" } else { "lower" };
        format!("{}{at} at the {side} end of its tolerance, {}", t.label, kc::significant(row.value, 4))
    });
    at_bound.chain(packed).chain(tolerances).collect()
}

/// The BFGS update of an objective's `curvature` by a step `s` along which its rates changed by `y`; a
/// step along which the rates fell (no curvature that a least has) is left out.
fn measure_curvature(curvature: &mut nalgebra::DMatrix<f64>, s: Vec<f64>, y: Vec<f64>) {
    let (s, y) = (nalgebra::DVector::from_vec(s), nalgebra::DVector::from_vec(y));
    let sy = s.dot(&y);
    if sy.is_nan() || sy <= 1e-12 * s.norm() * y.norm() {
        return;
    }
    let bs = &*curvature * &s;
    let sbs = s.dot(&bs);
    *curvature += &y * y.transpose() / sy;
    if sbs > 0.0 {
        *curvature -= &bs * bs.transpose() / sbs;
    }
}

/// Each target's outcome at the end, and why one is not met: no step that could be computed (`no_step`),
/// the model that could not be evaluated a step further (`unbuildable`), the bounds or packaging that
/// hold, or the targets that fight it.
fn verdicts(
    e: &Evaluation,
    targets: &Targets,
    free: &[(f64, f64)],
    unbuildable: Option<&TuneError>,
    no_step: Option<&NotGiven>,
) -> Vec<Verdict> {
    let held = held_by(e, targets, free);
    targets
        .targets
        .iter()
        .enumerate()
        .map(|(k, t)| {
            // Judged unweighted: each miss over the tolerance.
            let (own, weights): (Vec<f64>, Vec<f64>) =
                e.rows.iter().filter(|r| r.target == k).map(|r| ((r.value - r.aim) / t.tolerance, r.weight)).unzip();
            let worst = t.measured(&own, &weights);
            let met = t.met_by(&own, &weights);
            let judged = t.judged_words(&own, &weights);
            let why = (!met).then(|| {
                if let Some(why) = no_step {
                    format!("no step could be taken: {why}")
                } else if let Some(why) = unbuildable {
                    format!(
                        "held where the model stops: a step further could not be evaluated ({why}); narrow the \
                         bounds to the numbers the model accepts, or free another number"
                    )
                } else if held.is_empty() && t.scale == MissScale::Noise {
                    "the misses are larger than the data's noise makes them: the model cannot follow the \
                     measurement within its noise (a part it lacks, a free number it needs, or more noise than given)"
                        .to_string()
                } else if held.is_empty() {
                    "the targets fight one another: with every free number inside its bounds, the best compromise \
                     of their tolerances leaves this miss; loosen a tolerance or free another number"
                        .to_string()
                } else {
                    format!("held by {}: widen the bounds or the packaging, or free another number", held.join(", "))
                }
            });
            Verdict { target: t.label.clone(), worst, met, judged, why }
        })
        .collect()
}
