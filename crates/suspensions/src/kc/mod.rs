//! The K&C suite: which analyses a K&C rig runs on a suspension, and the typed, serialisable report each
//! produces (table, headline figures with error estimates, plots, warnings). Front ends (the `elastokin`
//! command, the HTML report, bindings) only render it.
//!
//! Every analysis estimates its own error. Each row is read twice: as walked, and one exact Newton
//! iteration away ([`StaticSolver::newton_correction`](elastokin_solver::StaticSolver::newton_correction)),
//! which lands on the equilibrium at the row's load parameter to second order in the row's distance
//! from it. The difference, column by column and figure by figure, is the estimate: paper mode's drift,
//! or what remains after a corrected step converged. It costs one factorization per row.

pub mod chart;
mod loads;
pub mod report;
mod travel;

pub use travel::ideal_outer_steer;

pub use chart::{Chart, Scale, Series, YAxis};
pub use report::{significant, Accuracy, AnalysisReport, Cell, Figure, KcReport, Skipped, Table, Warning};

use crate::analysis::{SweepExtras, SweepLimit, SweepOutput, WheelLoad};
use crate::file::SuspensionFile;
use elastokin_solver::Mode;
use serde::Serialize;

/// One K&C test.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(into = "&'static str")]
pub enum Analysis {
    /// Both wheel-centre heights driven together.
    ParallelTravel,
    /// Opposite wheel travel on the full axle: the body rolls relative to the wheels.
    Roll,
    /// Rack travel on the full axle, wheel-centre heights held.
    Steering,
    /// Vertical force at the contact patch, wheel free (the paper's case).
    VerticalForce,
    /// A road load at the wheel: lateral or braking force at the contact patch, traction force at the
    /// wheel centre, aligning torque.
    Road(WheelLoad),
    /// The corner at rest under the vehicle's corner load, from the design position.
    StaticLoad,
    /// The model file's own load case (`loads` of the general form), from zero to its full value.
    ModelLoads,
}

impl From<Analysis> for &'static str {
    fn from(a: Analysis) -> &'static str {
        a.name()
    }
}

/// Every analysis, in the order the suite runs them.
pub const ALL: [Analysis; 10] = [
    Analysis::ParallelTravel,
    Analysis::Roll,
    Analysis::Steering,
    Analysis::VerticalForce,
    Analysis::Road(WheelLoad::Lateral),
    Analysis::Road(WheelLoad::Braking),
    Analysis::Road(WheelLoad::Traction),
    Analysis::Road(WheelLoad::AligningTorque),
    Analysis::StaticLoad,
    Analysis::ModelLoads,
];

impl Analysis {
    /// The name used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Analysis::ParallelTravel => "parallel-travel",
            Analysis::Roll => "roll",
            Analysis::Steering => "steering",
            Analysis::VerticalForce => "vertical-force",
            Analysis::Road(WheelLoad::Lateral) => "lateral-force",
            Analysis::Road(WheelLoad::Braking) => "braking-force",
            Analysis::Road(WheelLoad::Traction) => "traction-force",
            Analysis::Road(WheelLoad::AligningTorque) => "aligning-torque",
            Analysis::StaticLoad => "static-load",
            Analysis::ModelLoads => "loads",
        }
    }

    /// The analysis of a name.
    pub fn from_name(name: &str) -> Option<Analysis> {
        ALL.into_iter().find(|a| a.name() == name)
    }

    /// What the load parameter is, with its unit.
    pub fn parameter(self) -> &'static str {
        match self {
            Analysis::ParallelTravel => "wheel travel, m, bump +",
            Analysis::Roll => "left wheel travel, m (right opposite)",
            Analysis::Steering => "rack travel, m, towards +y (left)",
            Analysis::VerticalForce => "vertical force at the contact patch, N, up +",
            Analysis::Road(WheelLoad::Lateral) => "lateral force at the contact patch, N, inboard +",
            Analysis::Road(WheelLoad::Braking) => "braking force at the contact patch, N, rearward +",
            Analysis::Road(WheelLoad::Traction) => "traction force at the wheel centre, N, forward +",
            Analysis::Road(WheelLoad::AligningTorque) => "aligning torque, N·m, about +z",
            Analysis::StaticLoad => "the model file's vehicle.corner_load, N, applied at once",
            Analysis::ModelLoads => "fraction of the model file's loads applied, 0 to 1",
        }
    }

    /// The unit of the load parameter (and of `--range` and `--arc-step`).
    pub fn unit(self) -> &'static str {
        match self {
            Analysis::ParallelTravel | Analysis::Roll | Analysis::Steering => "m",
            Analysis::Road(WheelLoad::AligningTorque) => "N·m",
            Analysis::VerticalForce | Analysis::Road(_) | Analysis::StaticLoad => "N",
            Analysis::ModelLoads => "of the load case",
        }
    }

    /// Whether the load parameter drives a travel (else it is a force or torque).
    fn is_travel(self) -> bool {
        self.unit() == "m"
    }

    /// Where the design position sits on the load parameter (the vertical force sweep's is the design
    /// wheel load, known only once the model is solved, so `None` there).
    pub fn design_parameter(self) -> Option<f64> {
        match self {
            Analysis::VerticalForce | Analysis::StaticLoad => None,
            _ => Some(0.0),
        }
    }
}

/// The most load steps a sweep may take: every step keeps its solved state in memory and costs solver time.
pub const MAX_STEPS: usize = 20_000;

/// The largest estimated error a run accepts before it warns.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Tolerance {
    /// Angles (toe, camber, steer, caster, …), degrees.
    pub angle_deg: f64,
    /// Lengths (wheel-centre position, patch displacement, scrub radius, …), metres.
    pub length_m: f64,
    /// Headline figures (slopes, rates, ratios), relative to their value.
    pub relative: f64,
}

impl Default for Tolerance {
    /// 0.001° and 0.001 mm: a tenth of the finest figure engineers read (toe to 0.01°, hardpoints to
    /// 0.01 mm); 0.5 % on derived figures such as the wheel rate.
    fn default() -> Self {
        Tolerance { angle_deg: 1e-3, length_m: 1e-6, relative: 5e-3 }
    }
}

/// How the suite walks its paths.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Settings {
    /// `(from, to)` in the analysis's own parameter, or its default. Only for a run of one analysis.
    pub range: Option<(f64, f64)>,
    /// Load steps.
    pub steps: usize,
    /// Paper or corrected stepping.
    #[serde(serialize_with = "mode_name")]
    pub mode: Mode,
    /// Road loads: the wheel-centre height held by the rig (`true`) or the wheel free on its spring.
    pub height_held: bool,
    /// Where the vertical, lateral and braking forces act (traction always acts at the wheel centre).
    pub load_point: crate::build::LoadPoint,
    /// The 6×6 wheel compliance at every step of the sweeps that have one wheel to read it at.
    pub compliance: bool,
    /// When the error estimate is worth a warning.
    pub tolerance: Tolerance,
    /// At a limit point (a load the suspension cannot carry, a travel its linkage cannot reach): `false`
    /// stops the sweep there, with a warning (`limit-point`); `true` follows the path on through it by
    /// arc length, from the last step before it (see [`SweepExtras::through_limits`]; those rows are exact
    /// equilibria in either mode).
    pub through_limits: bool,
    /// The arc-length step with `through_limits`, in the analysis's own unit ([`Analysis::unit`]: m, N or
    /// N·m): the change of load or travel of the first arc-length step (later steps have the same length
    /// in the scaled space of load and displacement, so they change the load less where the suspension
    /// gives way). `None`: one load step, `|to − from| / steps`. Only for a run of one analysis.
    pub arc_step: Option<f64>,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            range: None,
            steps: 32,
            mode: Mode::Corrected,
            height_held: true,
            load_point: crate::build::LoadPoint::ContactPatch,
            compliance: false,
            tolerance: Tolerance::default(),
            through_limits: false,
            arc_step: None,
        }
    }
}

fn mode_name<S: serde::Serializer>(mode: &Mode, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(mode_word(*mode))
}

/// `paper` or `corrected`.
pub fn mode_word(mode: Mode) -> &'static str {
    match mode {
        Mode::Paper => "paper",
        Mode::Corrected => "corrected",
    }
}

/// The mode a word of [`mode_word`] names, for front ends that take it as text.
pub fn mode_from_word(word: &str) -> Option<Mode> {
    [Mode::Corrected, Mode::Paper].into_iter().find(|&m| mode_word(m) == word)
}

impl Settings {
    /// What the sweeps over `range` take besides their rows.
    fn extras(&self, range: (f64, f64)) -> SweepExtras {
        let one_step = (range.1 - range.0).abs() / self.steps as f64;
        SweepExtras {
            error_estimate: true,
            compliance: self.compliance,
            through_limits: self.through_limits.then(|| self.arc_step.unwrap_or(one_step)),
        }
    }
}

/// Why an analysis failed: which one, and the engine's reason.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{analysis}: {message}")]
pub struct AnalysisError {
    /// The analysis's name.
    pub analysis: &'static str,
    /// What went wrong, and what to change.
    pub message: String,
}

/// Narrowest range an analysis walks, in its own parameter's unit (m, N, N·m).
pub const MIN_RANGE: f64 = 1e-9;
/// The largest travel a range may reach (m).
pub const MAX_RANGE_TRAVEL: f64 = 1e3;
/// The largest force or torque a range may reach (N, N·m).
pub const MAX_RANGE_LOAD: f64 = 1e8;
/// The largest multiple of the model's own load case a range may reach.
pub const MAX_RANGE_FRACTION: f64 = 1e6;

/// Runs one analysis on the model in `file`.
pub fn run(analysis: Analysis, file: &SuspensionFile, settings: &Settings) -> Result<AnalysisReport, AnalysisError> {
    if settings.steps == 0 || settings.steps > MAX_STEPS {
        return Err(AnalysisError {
            analysis: analysis.name(),
            message: format!("--steps must be from 1 to {MAX_STEPS}, got {}", settings.steps),
        });
    }
    if let Some(step) = settings.arc_step.filter(|v| !(v.is_finite() && *v > 0.0)) {
        let got = if step.is_finite() { format!("{step:e}") } else { "a value that is not a finite number".into() };
        return Err(AnalysisError {
            analysis: analysis.name(),
            message: format!(
                "--arc-step must be a positive length in the {} (the change of load or travel of an \
                 arc-length step), got {got}",
                analysis.parameter()
            ),
        });
    }
    if let Some((from, to)) = settings.range {
        // An empty range walks one point: every slope at design would be 0 / 0; one narrower than
        // MIN_RANGE (a nanometre, a nanonewton) takes slopes of rounding noise, or overflows them.
        if !(from.is_finite() && to.is_finite()) || (to - from).abs() < MIN_RANGE {
            let got =
                if from.is_finite() && to.is_finite() { format!(", got {from:e} to {to:e}") } else { String::new() };
            return Err(AnalysisError {
                analysis: analysis.name(),
                message: format!(
                    "the range needs two finite ends at least {MIN_RANGE:e} apart in the {}{got}",
                    analysis.parameter()
                ),
            });
        }
        // Far beyond what a suspension meets, the solver's numbers overflow before the linkage says
        // anything: a travel of kilometres, a force of a thousand tonnes.
        let most = match analysis.unit() {
            "m" => MAX_RANGE_TRAVEL,
            "N" | "N·m" => MAX_RANGE_LOAD,
            _ => MAX_RANGE_FRACTION,
        };
        if from.abs().max(to.abs()) > most {
            return Err(AnalysisError {
                analysis: analysis.name(),
                message: format!(
                    "the range {from:e} to {to:e} reaches beyond {most:e} in the {}: no suspension meets that; \
                     give a range in the analysis's own units",
                    analysis.parameter()
                ),
            });
        }
    }
    let result = match analysis {
        Analysis::ParallelTravel => travel::parallel_travel(file, settings),
        Analysis::Roll => travel::roll(file, settings),
        Analysis::Steering => travel::steering(file, settings),
        Analysis::VerticalForce => loads::vertical_force(file, settings),
        Analysis::Road(load) => loads::road_load(file, load, settings),
        Analysis::StaticLoad => loads::static_load(file, settings),
        Analysis::ModelLoads => loads::model_loads(file, settings),
    };
    result.map_err(|message| AnalysisError { analysis: analysis.name(), message })
}

/// What [`run_suite`] tells its caller as it goes.
#[derive(Debug, Clone, Copy)]
pub enum SuiteEvent<'a> {
    /// An analysis starts.
    Starting(Analysis),
    /// An analysis is done.
    Done(&'a AnalysisReport),
    /// An analysis is left out.
    Skipped(&'a Skipped),
}

/// Runs `which` (every analysis when empty) on the model in `file`: the K&C suite. The plausibility checks
/// run first ([`KcReport::model_check`]). The static load case is skipped, with its reason, when the file
/// has no vehicle section, and steering when the corner has no tie rod, unless asked for by name. `progress` hears of each analysis as it starts,
/// ends or is skipped.
pub fn run_suite(
    file: &SuspensionFile,
    which: &[Analysis],
    settings: &Settings,
    progress: impl FnMut(SuiteEvent),
) -> Result<KcReport, AnalysisError> {
    // The plausibility checks run first: a model that cannot be what its author meant is said to be so even
    // when an analysis then fails on it. A check that cannot run (the corner does not build) leaves the
    // analyses to report why.
    run_suite_checked(file, crate::check::check_model(file).ok(), which, settings, progress)
}

/// [`run_suite`] with the model's plausibility check already made (`None` when it could not run), for a
/// caller that looked at it first (`run --strict` refuses a model it warns of before spending time on it).
pub fn run_suite_checked(
    file: &SuspensionFile,
    model_check: Option<crate::check::ModelCheck>,
    which: &[Analysis],
    settings: &Settings,
    mut progress: impl FnMut(SuiteEvent),
) -> Result<KcReport, AnalysisError> {
    let chosen: Vec<Analysis> = if which.is_empty() { ALL.to_vec() } else { which.to_vec() };
    let warnings = model_check.as_ref().map_or_else(Vec::new, |c| c.warnings.clone());
    let mut report = KcReport {
        model: file.name.clone(),
        settings: *settings,
        analyses: Vec::new(),
        skipped: Vec::new(),
        model_check,
        warnings,
    };
    report.warnings.extend(crate::check::bushing_deflection_at_design(file));
    let (steered, loaded) = match &file.suspension {
        crate::description::Template::General(g) => (g.is_steered(), !g.loads.is_empty()),
        _ => (true, false),
    };
    // The roll rig's own refusal decides: a solid axle whose joints lock its roll cannot travel opposite.
    let roll_locked = |template: &crate::description::Template| {
        crate::build::CornerTemplate::builds_on_axle_only(template)
            && crate::build::Axle::build(template, crate::build::AxleRig::OppositeTravel).err()
                == Some(crate::build::rig::roll_locked())
    };
    for analysis in chosen {
        let skip = match analysis {
            Analysis::StaticLoad if file.vehicle.is_none() => {
                Some("the model file has no \"vehicle\" section with the corner_load to carry")
            }
            Analysis::Steering if !steered => {
                Some("the corner has no steering input (corner.tie_rod, or axle.steering_link): its toe is held by its own links")
            }
            Analysis::ModelLoads if !loaded => Some("the model file has no load case (\"loads\" of the general form)"),
            Analysis::Roll if roll_locked(&file.suspension) => Some(
                "the axle's joints lock its roll (with the wheels free it has one way to move, in travel): its \
                 wheels cannot travel opposite",
            ),
            _ => None,
        };
        if let (Some(reason), true) = (skip, which.is_empty()) {
            report.skipped.push(Skipped { analysis, reason: reason.into() });
            progress(SuiteEvent::Skipped(&report.skipped[report.skipped.len() - 1]));
            continue;
        }
        progress(SuiteEvent::Starting(analysis));
        // An analysis that fails on such a model fails because of it: say so with the failure.
        let result = run(analysis, file, settings).map_err(|mut e| {
            for w in &report.warnings {
                e.message.push_str(&format!("; note: {}", w.message));
            }
            e
        });
        report.analyses.push(result?);
        progress(SuiteEvent::Done(&report.analyses[report.analyses.len() - 1]));
    }
    Ok(report)
}

/// Short model name for plot subtitles (the part before any parenthesis).
fn short_name(file: &SuspensionFile) -> String {
    file.name.split(" (").next().unwrap_or(&file.name).to_string()
}

fn deg(rad: f64) -> f64 {
    rad.to_degrees()
}

/// An engine error (model or solver) as the analysis's message: the errors already speak the user's
/// words, so this only takes their text.
fn said(e: impl std::fmt::Display) -> String {
    e.to_string()
}

/// What every analysis does with its sweep: the table, figures and charts from the rows, and the error
/// estimate from the same read of the corrected rows.
struct Reduction<'a, R> {
    table: &'a dyn Fn(&[R]) -> Table,
    figures: &'a dyn Fn(&[R]) -> Vec<Figure>,
}

/// Builds the report of a sweep: reads `table` and `figures` off the rows and off the corrected rows,
/// and takes the differences as the error estimate.
fn finish<R>(
    analysis: Analysis,
    mut description: String,
    range: (f64, f64),
    settings: &Settings,
    out: &SweepOutput<R>,
    reduce: Reduction<R>,
    charts: Vec<Chart>,
) -> AnalysisReport {
    let table = (reduce.table)(&out.rows);
    let mut figures = (reduce.figures)(&out.rows);
    let (columns, method) = match &out.corrected {
        Some(corrected) => {
            let other = (reduce.table)(corrected);
            for (f, g) in figures.iter_mut().zip((reduce.figures)(corrected)) {
                if let (Some(a), Some(b)) = (f.value, g.value) {
                    f.error = Some((a - b).abs());
                }
            }
            (
                table.column_differences(&other),
                format!("every row against one exact Newton iteration from it ({} mode)", mode_word(settings.mode)),
            )
        }
        None => (vec![None; table.columns.len()], "not estimated".to_string()),
    };
    let largest = |suffix: &str| {
        table
            .columns
            .iter()
            .zip(&columns)
            .filter(|(name, _)| name.ends_with(suffix))
            .filter_map(|(_, e)| *e)
            .fold(0.0f64, f64::max)
    };
    let (angle_error_deg, length_error_m) = (largest("_deg"), largest("_m"));
    let force_residual = out.residuals.iter().map(|r| r.0).fold(0.0f64, f64::max);
    let constraint_residual = out.residuals.iter().map(|r| r.1).fold(0.0f64, f64::max);
    let tol = settings.tolerance;
    let mut warnings = Vec::new();
    if let Some(limit) = &out.limit {
        description.push_str(&limit_description(analysis, limit));
        // The table's first column is the load parameter.
        let last = table.rows.last().and_then(|r| r.first()).and_then(Cell::number).unwrap_or(limit.at);
        warnings.push(limit_warning(analysis, limit, last));
    }
    let over_figures: Vec<String> = figures.iter().filter_map(|f| over_tolerance(f, tol.relative)).collect();
    let within = angle_error_deg <= tol.angle_deg && length_error_m <= tol.length_m && over_figures.is_empty();
    if !within {
        // Paper mode's error falls in proportion to the step: the steps that would bring the worst of the
        // errors to its tolerance, with a tenth more for the second-order part of the error (on the
        // MacPherson's parallel travel the first-order count alone leaves it 1 % over).
        let worst = figures
            .iter()
            .filter_map(|f| Some(f.error? / (tol.relative * f.value?.abs())))
            .filter(|r| r.is_finite())
            .fold((angle_error_deg / tol.angle_deg).max(length_error_m / tol.length_m), f64::max);
        let needed = (1.1 * settings.steps as f64 * worst).ceil();
        let fix = match settings.mode {
            Mode::Paper if needed <= MAX_STEPS as f64 => format!(
                "paper mode's error falls in proportion to the step: about --steps {needed:.0} would meet the \
                 tolerance, or --mode corrected"
            ),
            Mode::Paper => format!(
                "paper mode's error falls in proportion to the step, and more than {MAX_STEPS} steps would be \
                 needed: use --mode corrected"
            ),
            Mode::Corrected => "the model is near-singular here; run `elastokin check` on it".to_string(),
        };
        let mut what = Vec::new();
        if angle_error_deg > tol.angle_deg {
            what.push(format!("angles up to {angle_error_deg:.2e} deg (tolerance {:.0e})", tol.angle_deg));
        }
        if length_error_m > tol.length_m {
            what.push(format!("lengths up to {:.2e} mm (tolerance {:.0e})", length_error_m * 1e3, tol.length_m * 1e3));
        }
        if !over_figures.is_empty() {
            what.push(format!("figures {} (tolerance {:.1} %)", over_figures.join(", "), tol.relative * 100.0));
        }
        warnings.push(Warning {
            code: "error-over-tolerance",
            hardpoints: Vec::new(),
            message: format!("{}: estimated error {}; {fix}", analysis.name(), what.join(", ")),
        });
    }
    let compliance = out.compliance.as_ref().map(|c| compliance_table(analysis, &table, c));
    AnalysisReport {
        analysis,
        parameter: analysis.parameter().into(),
        description,
        range,
        steps: settings.steps,
        figures,
        accuracy: Accuracy {
            method,
            angle_error_deg,
            length_error_m,
            force_residual,
            constraint_residual,
            columns: table.columns.iter().cloned().zip(columns).collect(),
            within_tolerance: within,
        },
        table,
        compliance,
        wheel_compliance_at_design: None,
        charts,
        warnings,
    }
}

/// A load or travel in the analysis's unit, as the descriptions and warnings give it.
fn amount(analysis: Analysis, v: f64) -> String {
    format!("{} {}", significant(v, 6), analysis.unit())
}

/// The end of the description line of a sweep that met a limit point.
fn limit_description(analysis: Analysis, limit: &SweepLimit) -> String {
    match limit.through {
        None => format!(", stopped at the limit point at {}", amount(analysis, limit.at)),
        Some(_) => format!(", through the limit point at {} by arc length", amount(analysis, limit.at)),
    }
}

/// The warning of a sweep that met a limit point: where the suspension gives way (or its linkage reaches
/// the end of its travel), what the table holds, and how to see beyond. `last` is the last row's load.
fn limit_warning(analysis: Analysis, limit: &SweepLimit, last: f64) -> Warning {
    let at = amount(analysis, limit.at);
    let what = if analysis.is_travel() {
        format!(
            "the linkage cannot go beyond {at}: an arm or the tie rod reaches the end of its travel there, and \
             beyond it the mechanism would have to fold over"
        )
    } else {
        format!(
            "the suspension gives way at {at}: it carries no more load there, and under a load that keeps rising \
             the wheel would snap through"
        )
    };
    let then = match limit.through {
        None => "the table and plots stop there, their last row at the limit point; run the analysis with \
                 --through-limits to follow the path through it by arc length"
            .to_string(),
        Some(arc) if arc.left_range => format!(
            "the table and plots follow the path through it by arc length (steps of {} at first) until it leaves \
             the range at {}",
            amount(analysis, arc.step),
            amount(analysis, last)
        ),
        Some(arc) => format!(
            "the table and plots follow the path through it by arc length (steps of {} at first), but the path \
             stopped after the most steps allowed at {}, inside the range; give a larger --arc-step",
            amount(analysis, arc.step),
            amount(analysis, last)
        ),
    };
    Warning { code: "limit-point", hardpoints: Vec::new(), message: format!("{}: {what}; {then}", analysis.name()) }
}

/// A figure whose estimated error is over `relative` of its value (and shows in its printed decimals), as
/// the warning names it: `label ±x %`, or `label ±e unit` where a percentage means nothing (a figure at or
/// near zero).
fn over_tolerance(f: &Figure, relative: f64) -> Option<String> {
    let (v, e) = (f.value?, f.error?);
    let ratio = e / v.abs();
    (e > relative * v.abs() && f.shows(e)).then(|| {
        if ratio < 10.0 {
            format!("{} ±{:.1} %", f.label, 100.0 * ratio)
        } else {
            format!("{} ±{e:.2e} {}", f.label, f.unit)
        }
    })
}

/// The rows of a 6×6 wheel compliance: the wheel centre's response, translation (m) and rotation (rad), global
/// axes. Its entries are named `{row}_per_{column}` in the compliance tables.
pub const COMPLIANCE_RESPONSE: [&str; 6] = ["x_m", "y_m", "z_m", "rx_rad", "ry_rad", "rz_rad"];
/// The columns of a 6×6 wheel compliance: the unit load at the wheel centre, force (N) and torque (N·m).
pub const COMPLIANCE_LOAD: [&str; 6] = ["fx_n", "fy_n", "fz_n", "mx_nm", "my_nm", "mz_nm"];

/// The 6×6 wheel compliance at every row: the load parameter, then the 36 entries by row
/// (wheel-centre x, y, z in m, rotation about x, y, z in rad) and column (force along x, y, z in N,
/// torque about x, y, z in N·m) at the wheel centre.
fn compliance_table(analysis: Analysis, rows: &Table, c: &[[[f64; 6]; 6]]) -> Table {
    let mut columns = vec![rows.columns[0].clone()];
    for r in COMPLIANCE_RESPONSE {
        for l in COMPLIANCE_LOAD {
            columns.push(format!("{r}_per_{l}"));
        }
    }
    Table {
        name: format!("{}_compliance", analysis.name().replace('-', "_")),
        columns,
        rows: rows
            .rows
            .iter()
            .zip(c)
            .map(|(row, m)| {
                let mut out = vec![row[0].clone()];
                out.extend(m.iter().flat_map(|r| r.iter().map(|&v| Cell::from(v))));
                out
            })
            .collect(),
    }
}

/// A figure missing because no row sits at the design position: the range does not reach it, or no
/// step lands on it (an odd number of steps over a symmetric range).
fn outside(range: (f64, f64), at: f64, unit: &str) -> String {
    if (range.0 - at) * (range.1 - at) <= 0.0 {
        return format!(
            "no step of the range {}..{} {unit} lands on the design position ({at} {unit}): give an even --steps \
             over a range symmetric about it",
            range.0, range.1
        );
    }
    format!(
        "the range {}..{} {unit} does not contain the design position ({at} {unit}); give a --range that spans it",
        range.0, range.1
    )
}

/// The reason a figure needs a vehicle-section entry the file lacks.
fn needs_vehicle(field: &str) -> String {
    format!("needs vehicle.{field} in the model file")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mode_word_reads_back_as_its_mode_and_no_other_word_does() {
        for mode in [Mode::Corrected, Mode::Paper] {
            assert_eq!(mode_from_word(mode_word(mode)), Some(mode));
        }
        // The summary.json's words, as the command's --mode takes them.
        assert_eq!(mode_from_word("corrected"), Some(Mode::Corrected));
        assert_eq!(mode_from_word("paper"), Some(Mode::Paper));
        for other in ["Paper", "exact", ""] {
            assert_eq!(mode_from_word(other), None, "{other}");
        }
    }

    #[test]
    fn figure_error_at_a_zero_figure_is_given_in_its_unit_not_as_infinite_percent() {
        let mut f = Figure::new("roll_centre_lateral", "roll centre lateral offset", "mm", 1, 0.0);
        f.error = Some(3.0);
        let line = over_tolerance(&f, 5e-3).unwrap();
        assert_eq!(line, "roll centre lateral offset ±3.00e0 mm");
        // A huge relative error is no percentage either (it printed 300 digits).
        f.value = Some(1e-300);
        assert!(!over_tolerance(&f, 5e-3).unwrap().contains('%'));
        f.value = Some(20.0);
        assert_eq!(over_tolerance(&f, 5e-3).unwrap(), "roll centre lateral offset ±15.0 %");
        f.error = Some(0.01);
        assert_eq!(over_tolerance(&f, 5e-3), None);
    }
}
