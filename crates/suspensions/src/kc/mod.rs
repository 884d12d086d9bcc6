//! The K&C suite: which analyses a K&C rig runs on a suspension, and the typed, serialisable report each
//! produces (table, headline figures with error estimates, plots, warnings). Front ends (the `elastokin`
//! command, the HTML report, bindings) only render it. One analysis is one file, which declares it
//! ([`Declaration`]) and runs it; this module lists them ([`Analysis::declaration`], [`run_on`]).
//!
//! Every analysis estimates its own error. Each row is read twice: as walked, and one exact Newton
//! iteration away ([`StaticSolver::newton_correction`](elastokin_solver::StaticSolver::newton_correction)),
//! which lands on the equilibrium at the row's load parameter to second order in the row's distance
//! from it. The difference, column by column and figure by figure, is the estimate: paper mode's drift,
//! or what remains after a corrected step converged. It costs one factorization per row.

pub mod chart;
pub mod figures;
mod load_sweep;
mod model_loads;
pub mod models;
mod parallel_travel;
mod reduce;
pub mod report;
mod road_load;
mod roll;
pub mod settings;
mod static_load;
mod steering;
pub mod unit;
mod vertical_force;
mod wheel_envelope;

pub use crate::description::limits::plain;
pub use chart::{Chart, Scale, Series, YAxis};
pub use models::Models;
pub use reduce::{COMPLIANCE_LOAD, COMPLIANCE_RESPONSE};
pub use report::{
    figure_column, fixed, significant, significant_among, Accuracy, AnalysisReport, Cell, Construction, Envelope,
    Failed, Figure, FigureKind, KcReport, NoFigure, Skipped, Table, Warning, Written,
};
pub use settings::{
    mode_from_word, mode_word, Analysis, AnalysisError, Cause, Declaration, DefaultRange, FigureRows, Quantity,
    Settings, Tolerance, ALL, MAX_RANGE_FRACTION, MAX_RANGE_LOAD, MAX_RANGE_TRAVEL, MIN_RANGE,
};
pub use steering::ideal_outer_steer;
pub use unit::{Shown, Unit, Units};
pub use wheel_envelope::{clearance, grid_steps};

use crate::analysis::WheelLoad;
use crate::file::SuspensionFile;
use elastokin_solver::replay::Taping;
use elastokin_solver::LoadPath;

impl Analysis {
    /// What the analysis declares of itself, in its own file: the one list of them.
    pub fn declaration(self) -> &'static Declaration {
        match self {
            Analysis::ParallelTravel => &parallel_travel::DECLARATION,
            Analysis::Roll => &roll::DECLARATION,
            Analysis::Steering => &steering::DECLARATION,
            Analysis::VerticalForce => &vertical_force::DECLARATION,
            Analysis::Road(WheelLoad::Lateral) => &road_load::LATERAL,
            Analysis::Road(WheelLoad::Braking) => &road_load::BRAKING,
            Analysis::Road(WheelLoad::Traction) => &road_load::TRACTION,
            Analysis::Road(WheelLoad::AligningTorque) => &road_load::ALIGNING_TORQUE,
            Analysis::StaticLoad => &static_load::DECLARATION,
            Analysis::ModelLoads => &model_loads::DECLARATION,
            Analysis::WheelEnvelope => &wheel_envelope::DECLARATION,
        }
    }
}

/// Runs one analysis on the model in `file`.
pub fn run(analysis: Analysis, file: &SuspensionFile, settings: &Settings) -> Result<AnalysisReport, AnalysisError> {
    run_on(analysis, &Models::new(file), settings)
}

/// Runs one analysis on the model of `models`, building only what no analysis run on them built before.
pub fn run_on(analysis: Analysis, models: &Models, settings: &Settings) -> Result<AnalysisReport, AnalysisError> {
    run_taped(analysis, models, settings, &Taping::default())
}

/// [`run_on`] with every solver of the analysis taking part in `taping`: a recording of its solves, or a
/// replay of one ([`elastokin_solver::replay`]).
pub fn run_taped(
    analysis: Analysis,
    models: &Models,
    settings: &Settings,
    taping: &Taping,
) -> Result<AnalysisReport, AnalysisError> {
    check_settings(analysis, settings)?;
    let result = match analysis {
        Analysis::ParallelTravel => parallel_travel::parallel_travel(models, settings, taping),
        Analysis::Roll => roll::roll(models, settings, taping),
        Analysis::Steering => steering::steering(models, settings, taping),
        Analysis::VerticalForce => vertical_force::vertical_force(models, settings, taping),
        Analysis::Road(load) => road_load::road_load(models, load, settings, taping),
        Analysis::StaticLoad => static_load::static_load(models, settings, taping),
        Analysis::ModelLoads => model_loads::model_loads(models, settings, taping),
        Analysis::WheelEnvelope => wheel_envelope::wheel_envelope(models, settings, taping),
    };
    result.map_err(|cause| AnalysisError { analysis: analysis.name(), cause })
}

/// Whether `settings` make sense for `analysis` (steps, arc step, range in its units), before any model is
/// read: a front end refuses bad settings as bad input rather than as a failed run.
pub fn check_settings(analysis: Analysis, settings: &Settings) -> Result<(), AnalysisError> {
    if let Err(e) = LoadPath::check_steps(settings.steps) {
        return Err(AnalysisError { analysis: analysis.name(), cause: Cause::Settings(e.to_string()) });
    }
    if let Some(step) = settings.arc_step.filter(|v| !(v.is_finite() && *v > 0.0)) {
        let got = plain(step);
        return Err(AnalysisError {
            analysis: analysis.name(),
            cause: Cause::Settings(format!(
                "the arc-length step (arc_step, --arc-step) must be a positive length in the {} (the change of \
                 load or travel of an arc-length step), got {got}",
                analysis.parameter()
            )),
        });
    }
    if analysis == Analysis::StaticLoad && settings.range.is_some() {
        return Err(AnalysisError {
            analysis: analysis.name(),
            cause: Cause::Settings(
                "static-load applies the vehicle section's corner load at once, with no range to walk: leave the \
                 range out (vertical-force walks a range of loads)"
                    .into(),
            ),
        });
    }
    if let Some((from, to)) = settings.range {
        // An empty range walks one point: every slope at design would be 0 / 0; one narrower than
        // MIN_RANGE (a nanometre, a nanonewton) takes slopes of rounding noise, or overflows them.
        if !(from.is_finite() && to.is_finite()) || (to - from).abs() < MIN_RANGE {
            let got = if from.is_finite() && to.is_finite() {
                format!(", got {} to {}", plain(from), plain(to))
            } else {
                String::new()
            };
            return Err(AnalysisError {
                analysis: analysis.name(),
                cause: Cause::Settings(format!(
                    "the range needs two finite ends at least {MIN_RANGE:e} apart in the {}{got}",
                    analysis.parameter()
                )),
            });
        }
        // Far beyond what a suspension meets, the solver's numbers overflow before the linkage says
        // anything: a travel of a metre, a force of a thousand tonnes.
        let quantity = analysis.declaration().quantity;
        let most = quantity.largest_range_end();
        if from.abs().max(to.abs()) > most {
            // A travel in millimetres is the likely slip: say what it is in metres.
            let in_metres = if quantity == Quantity::Travel && from.abs().max(to.abs()) * 1e-3 <= most {
                format!(" (millimetres? in metres that is --range {},{})", plain(from * 1e-3), plain(to * 1e-3))
            } else {
                String::new()
            };
            return Err(AnalysisError {
                analysis: analysis.name(),
                cause: Cause::Settings(format!(
                    "the range {} to {} reaches beyond {} in the {}: no suspension meets that; \
                     give a range in the analysis's own units{in_metres}",
                    plain(from),
                    plain(to),
                    plain(most),
                    analysis.parameter()
                )),
            });
        }
    }
    Ok(())
}

/// Why the suite leaves `analysis` out for the model in `file`, when it does: the static load case without
/// a vehicle section, steering of a corner without a steering input, the model's own loads when it has
/// none, roll of an axle whose joints lock it. Asked for by name, an analysis runs anyway.
pub fn left_out(file: &SuspensionFile, analysis: Analysis) -> Option<&'static str> {
    let general = file.suspension.expand();
    let (steered, loaded) = (general.is_steered(), !general.loads.is_empty());
    // The roll rig's own refusal decides: a solid axle whose joints lock its roll cannot travel opposite.
    let roll_locked = |template: &crate::description::Template| {
        crate::assembly::CornerTemplate::builds_on_axle_only(template)
            && crate::assembly::Axle::build(template, crate::assembly::AxleRig::OppositeTravel).err()
                == Some(crate::assembly::rig::roll_locked())
    };
    match analysis {
        Analysis::StaticLoad if file.vehicle.is_none() => {
            Some("the model file has no \"vehicle\" section with the corner_load to carry")
        }
        Analysis::Steering if !steered => {
            Some("the corner has no steering input (corner.tie_rod, or axle.steering_link): its toe is held by its own links")
        }
        Analysis::ModelLoads if !loaded => Some("the model file has no load case (\"loads\" of the general form)"),
        Analysis::WheelEnvelope if file.packaging.is_none() => {
            Some("the model file has no \"packaging\" section with the tyre's size and what the wheel must clear")
        }
        Analysis::Roll if roll_locked(&file.suspension) => Some(
            "the axle's joints lock its roll (with the wheels free it has one way to move, in travel): its \
             wheels cannot travel opposite",
        ),
        _ => None,
    }
}

/// The analyses a suite of `which` runs on the model in `file`, in order: every analysis when `which` is
/// empty, each either to run or left out with why ([`left_out`]); asked for by name, every one runs.
pub fn planned(file: &SuspensionFile, which: &[Analysis]) -> Vec<Result<Analysis, Skipped>> {
    if !which.is_empty() {
        return which.iter().map(|&a| Ok(a)).collect();
    }
    ALL.iter()
        .map(|&analysis| match left_out(file, analysis) {
            Some(reason) => Err(Skipped { analysis, reason: reason.into() }),
            None => Ok(analysis),
        })
        .collect()
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
    /// An analysis failed; the suite goes on.
    Failed(&'a Failed),
}

/// Runs `which` (every analysis when empty) on the model in `file`: the K&C suite. The plausibility checks
/// run first ([`KcReport::model_check`]). The static load case is skipped, with its reason, when the file
/// has no vehicle section, and steering when the corner has no tie rod, unless asked for by name.
/// An analysis that fails costs only itself: it is reported in [`KcReport::failed`] with its reason and
/// the suite goes on ([`KcReport::complete`] turns a failure into an error). `progress` hears of each
/// analysis as it starts, ends, fails or is skipped.
pub fn run_suite(
    file: &SuspensionFile,
    which: &[Analysis],
    settings: &Settings,
    progress: impl FnMut(SuiteEvent),
) -> KcReport {
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
) -> KcReport {
    let mut report = suite_report(file, model_check, settings);
    let models = Models::new(file);
    for planned in planned(file, which) {
        let analysis = match planned {
            Ok(analysis) => analysis,
            Err(skipped) => {
                report.skipped.push(skipped);
                progress(SuiteEvent::Skipped(&report.skipped[report.skipped.len() - 1]));
                continue;
            }
        };
        progress(SuiteEvent::Starting(analysis));
        let result = run_on(analysis, &models, settings);
        record(&mut report, analysis, result, &mut progress);
    }
    report
}

/// [`run_suite`] with its analyses, and the plausibility checks, run at once on rayon's threads: the same
/// report, to the bit (each analysis reports on models built once for the suite what it reports alone),
/// sooner on more than one core. For a caller that waits for the whole report (`elastokin live`).
pub fn run_suite_on_threads(file: &SuspensionFile, which: &[Analysis], settings: &Settings) -> KcReport {
    use rayon::prelude::*;
    let models = Models::new(file);
    let (model_check, results) = rayon::join(
        || crate::check::check_model(file).ok(),
        || {
            let run = |planned: Result<Analysis, Skipped>| planned.map(|a| (a, run_on(a, &models, settings)));
            planned(file, which).into_par_iter().map(run).collect::<Vec<_>>()
        },
    );
    let mut report = suite_report(file, model_check, settings);
    for result in results {
        match result {
            Ok((analysis, result)) => record(&mut report, analysis, result, &mut |_| {}),
            Err(skipped) => report.skipped.push(skipped),
        }
    }
    report
}

/// A suite's report before any analysis: the model's name, the settings, the plausibility check and its
/// warnings, and the bushings' deflection at design.
fn suite_report(file: &SuspensionFile, model_check: Option<crate::check::ModelCheck>, settings: &Settings) -> KcReport {
    let warnings = model_check.as_ref().map_or_else(Vec::new, |c| c.warnings.clone());
    let mut report = KcReport {
        model: file.name.clone(),
        settings: *settings,
        analyses: Vec::new(),
        skipped: Vec::new(),
        failed: Vec::new(),
        model_check,
        warnings,
    };
    report.warnings.extend(crate::check::bushing_deflection_at_design(file));
    report
}

/// An analysis's result put in the suite's `report`, and `progress` told.
fn record(
    report: &mut KcReport,
    analysis: Analysis,
    result: Result<AnalysisReport, AnalysisError>,
    progress: &mut impl FnMut(SuiteEvent),
) {
    match result {
        Ok(done) => {
            report.analyses.push(done);
            progress(SuiteEvent::Done(&report.analyses[report.analyses.len() - 1]));
        }
        Err(e) => {
            // An analysis that fails on an implausible model fails because of it: say so with the failure.
            let mut reason = e.cause.to_string();
            for w in &report.warnings {
                reason.push_str(&format!("; note: {}", w.message));
            }
            report.failed.push(Failed { analysis, reason });
            progress(SuiteEvent::Failed(&report.failed[report.failed.len() - 1]));
        }
    }
}
