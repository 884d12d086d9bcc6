//! Sensitivities through the equilibrium: the derivatives of every figure and every table cell of a K&C
//! analysis with respect to numbers of the model file, each with its error estimate, for any analysis of
//! the suite and any model it runs on, with no equilibrium solved again.
//!
//! The analysis is run once as it is, its solves recorded
//! ([`replay::record`](elastokin_solver::replay::record)), then once per parameter and move
//! `δ ∈ {+h, −h, +2h, −2h}` on the model read with the parameter moved, replaying the recording
//! ([`replay::replay`](elastokin_solver::replay::replay)): each equilibrium the analysis asks for is the
//! recorded one moved by one Newton iteration of the moved model, solved with the recorded model's tangent
//! there. At an equilibrium `F(z, p) = 0` that iteration lands at `z − A⁻¹F(z, p+δ)`, whose rate at
//! `δ = 0` is `−A⁻¹ ∂F/∂p = dz/dp`, the implicit function theorem's (`A = [K Jᵀ; J 0]`, the exact tangent
//! at `z`, factorized once by the recording for all the replays). Everything the analysis
//! reads off its equilibria (rows, slopes and fits of rows, compliances from the tangent, reactions) is
//! read by its own code on the moved model at the moved equilibria, so each figure is differentiated as it
//! is defined; the four replays' central differences over `h` and `2h`, Richardson extrapolated, give the
//! derivative with an error of order `h⁴` (a parameter at the end of its allowed range, a fraction at 1 or
//! a rate at its largest, has no model beyond it: its differences are one-sided over one to four steps, of
//! the fourth order too); the solver's tolerance enters only as the recorded equilibria's
//! distance from the exact ones (a relative error of about 1e-9), not divided by the step. They are
//! differences, not derivatives carried forward in closed form: each has its own error estimate ([`rate`]),
//! which `crates/suspensions/tests/sensitivity.rs` holds against re-runs of the moved models.
//!
//! Each moved model is built in the coordinates of the model as it is, its bodies' reference points where
//! the model's are ([`Models::in_coordinates_of`]): a hardpoint that also places a body (the wheel centre the
//! upright) then moves that point alone, and the recorded pose is the moved model's to within what the
//! move changes. Built with its bodies where the move puts them, the iteration would first carry each
//! such body by the move itself, and its error, of the second order in that, is as large as the rate
//! sought where the parameter changes little.
//!
//! A derivative that does not exist is said to: an analysis whose path meets a limit point is refused;
//! where a stop whose force rises at once on contact touches or leaves between the moves (the replay
//! tells), the model itself is replayed too, and a figure whose slopes either side of it disagree as no
//! smooth figure's do is [`NoDerivative::Kink`].
//!
//! Only corrected-mode rows are equilibria: sensitivities are of the corrected path.

pub use super::parameter::effect_unit;
use super::parameter::{is_length, ParameterError, Parameters};
use crate::kc::{self, Analysis, AnalysisReport, Cell, Failed, Figure, Models, Settings, Skipped, Table};
use elastokin_solver::replay::{record, replay, Replay, Tape};
use elastokin_solver::Mode;
use rayon::prelude::*;
use std::sync::{Arc, OnceLock};

/// A parameter is moved by this fraction of its size, and by twice that: of a length at least of 0.1 m
/// (50 µm of a hardpoint near the origin), of anything else its own size (a torsion constant of 3e-8 m⁴
/// moves by 1.5e-11), or of 0.1 where it is zero. What the replays read is smooth in the move: the
/// error of the extrapolated difference is of order `step⁴`, its rounding of order `ε / step` (1e-6 left
/// 2e-4 of a small toe rate to rounding; 1e-3 left 5e-6 of a double wishbone's wheel rate against its
/// upper arm's front mount to the `step⁴` term, whose one Newton iteration from the recorded equilibrium
/// meets a mode of the tangent the move changes much).
pub const RELATIVE_STEP: f64 = 5e-4;

/// The moves of a parameter the differences take, in steps: `+h, −h, +2h, −2h`.
const SHIFTS: [f64; 4] = [1.0, -1.0, 2.0, -2.0];

/// The moves a replay may ask for, in steps: [`SHIFTS`]; none (the model itself, read again where a stop
/// touched between the moves, and for one-sided differences: [`AT_MODEL`]); and three and four steps, which
/// one-sided differences take with one and two ([`ONE_SIDED`]).
const MOVES: [f64; 9] = [SHIFTS[0], SHIFTS[1], SHIFTS[2], SHIFTS[3], 0.0, 3.0, -3.0, 4.0, -4.0];

/// The index in [`MOVES`] of the model itself.
const AT_MODEL: usize = 4;

/// The indices in [`MOVES`] of one, two, three and four steps up, and down: the one-sided differences of a
/// parameter at the end of its allowed range (a rate at its largest, a fraction at 1), which has no model
/// on the other side.
const ONE_SIDED: [[usize; 4]; 2] = [[0, 2, 5, 7], [1, 3, 6, 8]];

/// How a parameter's derivatives are differenced: central where the model reads moved both ways, else
/// one-sided, up or down, where it reads on that side alone.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Differences {
    Central,
    /// One-sided, the moves [`ONE_SIDED`]`[side]` (0 up, 1 down).
    OneSided(usize),
}

/// The step of parameter `k`: [`RELATIVE_STEP`] of its size (see there).
fn step(parameters: &Parameters, k: usize) -> f64 {
    let pointer = &parameters.pointers[k];
    let size = parameters.values[k].abs();
    let size = if is_length(pointer) || size == 0.0 { size.max(0.1) } else { size };
    RELATIVE_STEP * size
}

/// The model read with each parameter moved by each of [`MOVES`], each read once, when first asked for,
/// and built once per rig, for every analysis that replays it, in the coordinates of the model as it is
/// (`base`, [`Models::in_coordinates_of`]).
struct MovedModels<'p> {
    parameters: &'p Parameters,
    base: Arc<Models<'static>>,
    files: Vec<[OnceLock<Result<Models<'static>, ParameterError>>; MOVES.len()]>,
}

impl<'p> MovedModels<'p> {
    /// The moves of `parameters`, whose file as it is `base` builds.
    fn new(parameters: &'p Parameters, base: Arc<Models<'static>>) -> Self {
        MovedModels { parameters, base, files: (0..parameters.len()).map(|_| Default::default()).collect() }
    }

    /// The model with parameter `k` moved by `MOVES[m]` steps.
    fn models(&self, k: usize, m: usize) -> Result<&Models<'static>, ParameterError> {
        let moved = |file| Models::in_coordinates_of(file, self.base.clone());
        // Built at once for the analyses that replay it, each of which says why a build fails.
        let read = || self.parameters.file_moved_to_build(k, MOVES[m] * step(self.parameters, k)).map(moved);
        self.files[k][m].get_or_init(read).as_ref().map_err(Clone::clone)
    }
}

/// Where a stop touched or left between the moves, the largest relative disagreement of a figure's slopes
/// either side of the model as it is (one-sided second-order differences) for it to have a derivative. A
/// smooth figure's differ by `h³ f⁗ / 2`, far less; a kink between the moves (a stop whose force rises at
/// once on contact) makes them differ by a share of the jump of slope of order one (all of it when the
/// stop touches at the model itself, where central differences see only the mean of the two slopes).
const KINK: f64 = 1e-2;

/// Why a figure or table cell has no derivative.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoDerivative {
    /// It has no value: the report leaves it out, or the cell holds text.
    Missing,
    /// It has a value, but not at every moved model (it exists on one side of the model as it is).
    MissingWhenMoved,
    /// It is not smooth in the parameter here: its slopes over one and two steps disagree (a stop touching,
    /// a switch of what is read, between the moves).
    Kink,
    /// A table cell when the figures alone were asked for ([`Settings::figures_only`]): the replays move
    /// only the rows the figures read.
    FiguresOnly,
}

impl NoDerivative {
    /// Why, in the user's words.
    pub fn reason(self) -> &'static str {
        match self {
            NoDerivative::Missing => "the figure has no value",
            NoDerivative::MissingWhenMoved => "the figure has no value once the parameter is moved",
            NoDerivative::Kink => {
                "not smooth in the parameter here (a stop touching or a reading switching as it moves): no derivative"
            }
            NoDerivative::FiguresOnly => "the figures alone were asked for: no derivative of the table",
        }
    }
}

/// A derivative and its error estimate (of the derivative, in its unit): how far it may be from the
/// derivative of the exact equilibria (see [`rate`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Derivative {
    /// The derivative.
    pub value: f64,
    /// Its estimated error.
    pub error: f64,
}

/// A derivative, or why there is none.
pub type Rate = Result<Derivative, NoDerivative>;

/// One K&C analysis as the report gives it, and the derivatives of its figures and table with respect to
/// each parameter, per unit of the parameter as the file gives it: of a figure in SI, as the figure is
/// held; of a cell in its column's unit.
#[derive(Debug, Clone, PartialEq)]
pub struct AnalysisSensitivity {
    /// The analysis as [`kc::run`] reports it on the model as it is.
    pub report: AnalysisReport,
    /// The figures' derivatives: parameter × figure (in the order of [`AnalysisReport::figures`]).
    pub figures: Vec<Vec<Rate>>,
    /// The table's derivatives: parameter × row × column.
    pub table: Vec<Vec<Vec<Rate>>>,
}

impl AnalysisSensitivity {
    /// The values of the table's column `name` (`None` where a cell is empty, or there is no such column).
    pub fn column(&self, name: &str) -> Vec<Option<f64>> {
        let table = &self.report.table;
        table.column(name).unwrap_or_else(|| vec![None; table.rows.len()])
    }

    /// The derivatives of column `name` with respect to parameter `k`, row by row.
    pub fn d_column(&self, name: &str, k: usize) -> Vec<Rate> {
        let c = self.report.table.columns.iter().position(|x| x == name);
        self.table[k].iter().map(|r| c.map_or(Err(NoDerivative::Missing), |c| r[c])).collect()
    }

    /// The figure `key` and its derivatives, one per parameter.
    pub fn figure(&self, key: &str) -> Option<(&Figure, Vec<Rate>)> {
        let j = self.report.figures.iter().position(|f| f.key == key)?;
        Some((&self.report.figures[j], self.figures.iter().map(|d| d[j]).collect()))
    }

    /// The parameters with the largest effects on figure `j` (per mm or per %, see [`effect`]), largest
    /// first, at most `count`: `(parameter, effect)`.
    pub fn largest_effects(&self, j: usize, parameters: &Parameters, count: usize) -> Vec<(usize, f64)> {
        let mut ranked: Vec<(usize, f64)> = (0..parameters.len())
            .filter_map(|k| {
                let d = self.figures[k][j].ok()?;
                Some((k, effect(&parameters.pointers[k], parameters.values[k], d.value)))
            })
            .collect();
        ranked.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
        ranked.truncate(count);
        ranked
    }

    /// The table's derivatives as a table of their own (`sensitivity_<analysis>.csv`): per parameter and
    /// row, the load parameter and the derivative of every other column and its error estimate (named
    /// `d_<column>` and `d_<column>_error`, per unit of the parameter in the file; empty where there is
    /// none).
    pub fn row_table(&self, parameters: &Parameters) -> Table {
        let table = &self.report.table;
        let mut columns = vec!["parameter".to_string(), table.columns[0].clone()];
        columns.extend(table.columns.iter().skip(1).flat_map(|c| [format!("d_{c}"), format!("d_{c}_error")]));
        let mut rows = Vec::new();
        for (k, pointer) in parameters.pointers.iter().enumerate() {
            for (r, base) in table.rows.iter().enumerate() {
                let mut row = vec![Cell::Text(pointer.clone()), base[0].clone()];
                row.extend(self.table[k][r].iter().skip(1).flat_map(|d| {
                    let d = d.ok();
                    [Cell::from(d.map(|d| d.value)), Cell::from(d.map(|d| d.error))]
                }));
                rows.push(row);
            }
        }
        Table { name: format!("sensitivity_{}", table.name), columns, rows }
    }
}

/// Sensitivities of a K&C suite: each analysis that ran, and those left out or failed, with why.
#[derive(Debug, Clone, PartialEq)]
pub struct SuiteSensitivity {
    /// The analyses, in the suite's order.
    pub analyses: Vec<AnalysisSensitivity>,
    /// Analyses the suite leaves out for this model (as [`kc::run_suite`] does).
    pub skipped: Vec<Skipped>,
    /// Analyses whose sensitivities could not be had, with the reason.
    pub failed: Vec<Failed>,
}

impl SuiteSensitivity {
    /// `sensitivity.csv`: one row per figure of every analysis and parameter — the analysis, the figure,
    /// its unit and value, the parameter and its value, the derivative (figure unit per unit of the
    /// parameter in the file) and its error estimate, the effect per millimetre or per percent, and why a
    /// derivative is missing.
    pub fn figure_table(&self, parameters: &Parameters) -> Table {
        let columns = [
            "analysis",
            "figure",
            "figure_unit",
            "value",
            "parameter",
            "parameter_value",
            "derivative",
            "derivative_error",
            "effect",
            "effect_per",
            "no_derivative",
        ];
        let mut rows = Vec::new();
        for a in &self.analyses {
            for (j, figure) in a.report.figures.iter().enumerate() {
                let written = figure.written(a.report.units);
                for (k, pointer) in parameters.pointers.iter().enumerate() {
                    let d = a.figures[k][j];
                    let value = d.ok().map(|d| d.value * written.factor);
                    rows.push(vec![
                        Cell::Text(a.report.analysis.name().into()),
                        Cell::Text(figure.key.clone()),
                        Cell::Text(written.unit.into()),
                        Cell::from(written.value),
                        Cell::Text(pointer.clone()),
                        Cell::from(parameters.values[k]),
                        Cell::from(value),
                        Cell::from(d.ok().map(|d| d.error * written.factor)),
                        Cell::from(value.map(|v| effect(pointer, parameters.values[k], v))),
                        Cell::Text(effect_unit(pointer).into()),
                        d.err().map_or(Cell::Empty, |e| Cell::Text(e.reason().into())),
                    ]);
                }
            }
        }
        Table { name: "sensitivity".into(), columns: columns.map(String::from).to_vec(), rows }
    }
}

/// The settings sensitivities are taken with: `settings` walked in corrected mode (only its rows are
/// equilibria), stopping at a limit point (past one the path has no derivative), with no views' motion
/// (the replays would draw what nobody looks at).
pub fn sensitivity_settings(settings: &Settings) -> Settings {
    Settings { mode: Mode::Corrected, through_limits: false, motion: false, ..*settings }
}

/// The rounding a replayed value carries, in ulps of the largest value differenced, or of one unit of what
/// is printed where the values are smaller (a figure near zero is the difference of larger numbers and
/// carries their rounding, not its own). A rate at design is itself a difference along the path over a
/// tenth of a millimetre, which carries a thousand ulps of the readings it differences (the
/// vertical-force wheel rate's derivatives carry twice that many of the rate).
const ROUNDING_ULPS: f64 = 1e4;

/// The derivative from the values at the [`SHIFTS`] of `h`: central differences over one and two steps,
/// Richardson extrapolated, with its error estimate. Where a stop touched or left between the moves,
/// `at_model` is the value at the model itself (replayed as the others), and a figure whose slopes either
/// side of it disagree as no smooth figure's do has no derivative. `unit` is the size of a unit of what
/// is printed, in the values' (a millimetre of a length held in metres: 1e-3); `relative`, the value's own
/// error estimate relative to its size (the recorded equilibria's distance from the exact ones).
///
/// The estimate is the sum of the extrapolation's move of the one-step difference (which bounds the
/// truncation of the extrapolated one, as a rate at design's is bounded), the values' rounding over the
/// step, and what the recorded equilibria's own error leaves in it (the replays differentiate those, not
/// the exact ones): `relative` of the derivative, or of the value per the parameter's size where the
/// derivative is smaller (a derivative near zero carries the error of the value it is the rate of).
fn rate(values: [Option<f64>; 4], at_model: Option<Option<f64>>, h: f64, unit: f64, relative: f64) -> Rate {
    let [Some(a), Some(b), Some(c), Some(d)] = values else { return Err(NoDerivative::MissingWhenMoved) };
    let largest = |floor: f64, more: f64| [a, b, c, d, more].iter().fold(floor, |m, v| m.max(v.abs()));
    if let Some(at) = at_model {
        let f0 = at.ok_or(NoDerivative::MissingWhenMoved)?;
        let (right, left) = ((-3.0 * f0 + 4.0 * a - c) / (2.0 * h), (3.0 * f0 - 4.0 * b + d) / (2.0 * h));
        // The one-sided differences' rounding: ten thousand ulps of the largest value, or of a thousand
        // printed units (a symmetric axle's lateral roll-centre offset in mm is the difference of
        // coordinates of that order).
        let noise = 1e4 * f64::EPSILON * largest(1e3 * unit, f0) / h;
        if (right - left).abs() > KINK * right.abs().max(left.abs()) + noise {
            return Err(NoDerivative::Kink);
        }
    }
    let value = (8.0 * (a - b) - (c - d)) / (12.0 * h);
    let one_step = (a - b) / (2.0 * h);
    let rounding = ROUNDING_ULPS * f64::EPSILON * largest(unit, 0.0) / h;
    derivative(value, one_step, rounding, relative, a / (h / RELATIVE_STEP))
}

/// The derivative from the values `f0` at the model and `values` at one to four steps `h` one way (`h`
/// negative for down), for a parameter at the end of its allowed range: the one-sided difference of
/// fourth order, with the same estimate as [`rate`]'s, the second-order one-sided difference for the
/// extrapolation's move. A stop that touched or left between the moves (`kinked`) leaves no way to tell a
/// kink from a curve with one side alone: no derivative.
fn one_sided_rate(f0: Option<f64>, values: [Option<f64>; 4], h: f64, unit: f64, relative: f64, kinked: bool) -> Rate {
    let (Some(f0), [Some(a), Some(b), Some(c), Some(d)]) = (f0, values) else {
        return Err(NoDerivative::MissingWhenMoved);
    };
    if kinked {
        return Err(NoDerivative::Kink);
    }
    let value = (-25.0 * f0 + 48.0 * a - 36.0 * b + 16.0 * c - 3.0 * d) / (12.0 * h);
    let second_order = (-3.0 * f0 + 4.0 * a - b) / (2.0 * h);
    // The weights' sum, 128/12, against the central difference's 18/12: that much more rounding.
    let largest = [f0, a, b, c, d].iter().fold(unit, |m, v| m.max(v.abs()));
    let rounding = ROUNDING_ULPS * f64::EPSILON * largest * (128.0 / 18.0) / h.abs();
    derivative(value, second_order, rounding, relative, f0 / (h.abs() / RELATIVE_STEP))
}

/// A difference `value` with its error estimate: its distance from the lower-order difference `coarser`,
/// the rounding, and the recorded equilibria's `relative` error of it or, where it is smaller, of the
/// value per the parameter's size (`per_size`).
fn derivative(value: f64, coarser: f64, rounding: f64, relative: f64, per_size: f64) -> Rate {
    let error = (value - coarser).abs() + rounding + relative * value.abs().max(per_size.abs());
    if value.is_finite() && error.is_finite() {
        Ok(Derivative { value, error })
    } else {
        Err(NoDerivative::MissingWhenMoved)
    }
}

/// One analysis of the K&C suite on the model of `parameters`, and the derivatives of its figures and table
/// with respect to each parameter (see the module's documentation). Refused, with the reason: an analysis
/// that fails or meets a limit point; a parameter whose move changes the model's parts or what the
/// analysis does (it has no derivative), or leaves the model unreadable.
pub fn analysis_sensitivity(
    analysis: Analysis,
    parameters: &Parameters,
    settings: &Settings,
) -> Result<AnalysisSensitivity, SensitivityError> {
    let models = MovedModels::new(parameters, Arc::new(Models::owning(parameters.file()?)));
    analysis_sensitivity_of(analysis, &models, &sensitivity_settings(settings))
}

fn analysis_sensitivity_of(
    analysis: Analysis,
    models: &MovedModels,
    settings: &Settings,
) -> Result<AnalysisSensitivity, SensitivityError> {
    let parameters = models.parameters;
    let (report, tape) = record(|taping| kc::run_taped(analysis, &models.base, settings, taping));
    let report = report.map_err(|e| SensitivityError::Analysis(e.cause))?;
    if let Some(at) = tape.limit_point() {
        return Err(SensitivityError::LimitPoint { at, unit: analysis.unit() });
    }
    let tape: Arc<Tape> = Arc::new(tape);
    // The replays read the rows only: no error estimate (a Newton iteration more per row, for a figure
    // the derivatives do not use).
    let replayed = Settings { error_estimate: false, ..*settings };
    let derivatives = (0..parameters.len())
        .into_par_iter()
        .map(|k| parameter_rates(analysis, models, k, &tape, &replayed, &report))
        .collect::<Result<Vec<_>, SensitivityError>>()?;
    let (figures, table) = derivatives.into_iter().unzip();
    Ok(AnalysisSensitivity { report, figures, table })
}

/// Why an analysis's sensitivities cannot be had. Each names the parameter where one is to blame.
#[derive(Debug, Clone, thiserror::Error)]
pub enum SensitivityError {
    /// The model with a parameter moved cannot be read (or the model as it is).
    #[error(transparent)]
    Parameter(#[from] ParameterError),
    /// The analysis fails on the model as it is.
    #[error(transparent)]
    Analysis(kc::Cause),
    /// The analysis's path meets a limit point, where it has no derivative.
    #[error(
        "the path meets a limit point at {at:.6} {unit}, where it has no derivative: narrow the range to end before it"
    )]
    LimitPoint {
        /// The load parameter there.
        at: f64,
        /// Its unit.
        unit: &'static str,
    },
    /// A parameter whose move makes the analysis take another path than its recording.
    #[error(
        "parameter '{pointer}' changes what the analysis does when moved ({diverged}): it has no derivative; give a \
         number that moves a part, not one that chooses what the parts are"
    )]
    ChangesAnalysis {
        /// The parameter.
        pointer: String,
        /// Where the replay left its recording.
        diverged: elastokin_solver::replay::Diverged,
    },
    /// The analysis fails on the model with a parameter moved.
    #[error("parameter '{pointer}' moved by {by:e}: {cause}")]
    MovedFails {
        /// The parameter.
        pointer: String,
        /// How far it was moved, in the file's units.
        by: f64,
        /// What stopped the analysis.
        cause: kc::Cause,
    },
    /// A parameter whose move changes the rows or columns of the analysis's table.
    #[error(
        "parameter '{pointer}' changes the rows or columns of the analysis's table when moved: it has no derivative"
    )]
    ChangesTable {
        /// The parameter.
        pointer: String,
    },
}

/// How parameter `k`'s derivatives are differenced: central where the model reads at every central move;
/// else one-sided to the side where it reads at one to four steps (a parameter at the end of its allowed
/// range); else the first central move's reason it does not read.
fn differences(models: &MovedModels, k: usize) -> Result<Differences, ParameterError> {
    let reads = |moves: &[usize]| moves.iter().try_for_each(|&m| models.models(k, m).map(drop));
    match reads(&[0, 1, 2, 3]) {
        Ok(()) => Ok(Differences::Central),
        Err(why) => (0..2).find(|&side| reads(&ONE_SIDED[side]).is_ok()).map(Differences::OneSided).ok_or(why),
    }
}

/// The rates of `report`'s figures and cells with respect to parameter `k`, from replays of `tape`.
fn parameter_rates(
    analysis: Analysis,
    models: &MovedModels,
    k: usize,
    tape: &Arc<Tape>,
    settings: &Settings,
    report: &AnalysisReport,
) -> Result<(Vec<Rate>, Vec<Vec<Rate>>), SensitivityError> {
    let pointer = &models.parameters.pointers[k];
    let h = step(models.parameters, k);
    let replayed = |m: usize| -> Result<Replay<AnalysisReport>, SensitivityError> {
        let (moved, shift) = (models.models(k, m)?, MOVES[m]);
        let run = replay(tape, |taping| kc::run_taped(analysis, moved, settings, taping))
            .map_err(|diverged| SensitivityError::ChangesAnalysis { pointer: pointer.clone(), diverged })?;
        let value = run.value.map_err(|e| SensitivityError::MovedFails {
            pointer: pointer.clone(),
            by: shift * h,
            cause: e.cause,
        })?;
        let (moved, own) = (&value.table, &report.table);
        // Read for the figures alone, a replay's table has the rows the figures read alone
        // (`SweepExtras::figure_rows`).
        if moved.columns != own.columns || (moved.rows.len() != own.rows.len() && !settings.figures_only) {
            return Err(SensitivityError::ChangesTable { pointer: pointer.clone() });
        }
        Ok(Replay { value, kinked: run.kinked })
    };
    let differences = differences(models, k)?;
    let shifts = match differences {
        Differences::Central => [0, 1, 2, 3],
        Differences::OneSided(side) => ONE_SIDED[side],
    };
    let mut moved = Vec::with_capacity(shifts.len());
    let mut kinked = false;
    for m in shifts {
        let run = replayed(m)?;
        kinked |= run.kinked;
        moved.push(run.value);
    }
    // A stop touched or left between the moves: the model itself replayed too, to tell a kink. One-sided
    // differences take it always.
    let at_model = if kinked || differences != Differences::Central { Some(replayed(AT_MODEL)?.value) } else { None };
    // The derivative of what `read` reads: central, or one-sided with the step's sign.
    let rate_of = |read: &dyn Fn(&AnalysisReport) -> Option<f64>, unit: f64, relative: f64| match differences {
        Differences::Central => {
            rate([0, 1, 2, 3].map(|i| read(&moved[i])), at_model.as_ref().map(read), h, unit, relative)
        }
        Differences::OneSided(side) => {
            let f0 = at_model.as_ref().and_then(read);
            let signed = if side == 0 { h } else { -h };
            one_sided_rate(f0, [0, 1, 2, 3].map(|i| read(&moved[i])), signed, unit, relative, kinked)
        }
    };
    let value = |run: &AnalysisReport, key: &str| run.figure(key).and_then(|f| f.value);
    let figures = report
        .figures
        .iter()
        .map(|f| match f.value {
            None => Err(NoDerivative::Missing),
            Some(v) => {
                let unit = 1.0 / f.unit.shown().factor;
                let relative = f.error.map_or(0.0, |e| e / v.abs()).min(1.0);
                rate_of(&|run| value(run, &f.key), unit, relative)
            }
        })
        .collect();
    // A cell's own error estimate relative to its column's largest value.
    let column_relative: Vec<f64> = (0..report.table.columns.len())
        .map(|c| {
            let largest = report.table.rows.iter().filter_map(|r| r[c].number()).fold(0.0f64, |m, v| m.max(v.abs()));
            let error = report.accuracy.columns.get(c).and_then(|(_, e)| *e).unwrap_or(0.0);
            if largest > 0.0 {
                (error / largest).min(1.0)
            } else {
                0.0
            }
        })
        .collect();
    let table = (0..report.table.rows.len())
        .map(|r| {
            (0..report.table.columns.len())
                .map(|c| match report.table.rows[r][c] {
                    // The replays read only the rows the figures read (`SweepExtras::figure_rows`).
                    Cell::Number(_) if settings.figures_only => Err(NoDerivative::FiguresOnly),
                    Cell::Number(_) => rate_of(&|run| run.table.rows[r][c].number(), 1.0, column_relative[c]),
                    _ => Err(NoDerivative::Missing),
                })
                .collect()
        })
        .collect();
    Ok((figures, table))
}

/// The K&C suite's analyses `which` (every one the model has when empty, as [`kc::run_suite`] chooses
/// them) on the model of `parameters`, each with its derivatives ([`analysis_sensitivity`]). An analysis
/// whose sensitivities cannot be had costs only itself: it is in [`SuiteSensitivity::failed`] with why.
/// A parameter the model does not read right is refused for all.
pub fn suite_sensitivity(
    parameters: &Parameters,
    which: &[Analysis],
    settings: &Settings,
) -> Result<SuiteSensitivity, ParameterError> {
    let settings = sensitivity_settings(settings);
    let models = MovedModels::new(parameters, Arc::new(Models::owning(parameters.file()?)));
    let mut out = SuiteSensitivity { analyses: Vec::new(), skipped: Vec::new(), failed: Vec::new() };
    for planned in kc::planned(models.base.file(), which) {
        let analysis = match planned {
            Ok(analysis) => analysis,
            Err(skipped) => {
                out.skipped.push(skipped);
                continue;
            }
        };
        match analysis_sensitivity_of(analysis, &models, &settings) {
            Ok(a) => out.analyses.push(a),
            // Written in the report as its reason.
            Err(e) => out.failed.push(Failed { analysis, reason: e.to_string() }),
        }
    }
    Ok(out)
}

/// A figure's derivative as an effect: per millimetre of a length, per percent of its value otherwise.
pub fn effect(pointer: &str, value: f64, derivative: f64) -> f64 {
    if is_length(pointer) {
        derivative * 1e-3
    } else {
        derivative * value.abs() * 1e-2
    }
}
