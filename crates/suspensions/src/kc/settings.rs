//! What a K&C suite is asked: the analyses a rig runs ([`Analysis`]), how they are run ([`Settings`]:
//! ranges, steps, mode, tolerances, load point) and the limits a request is held to.

use crate::analysis::{SweepExtras, WheelLoad};
use crate::description::limits::plain;
use crate::kc::unit::Units;
use elastokin_solver::replay::{ReplayRows, Taping};
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
    /// The tyre swept over wheel travel and rack travel on the full axle, and its least clearance to the
    /// body's packaging.
    WheelEnvelope,
}

impl From<Analysis> for &'static str {
    fn from(a: Analysis) -> &'static str {
        a.name()
    }
}

/// Every analysis, in the order the suite runs them.
pub const ALL: [Analysis; 11] = [
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
    Analysis::WheelEnvelope,
];

impl Analysis {
    /// The analysis of a name.
    pub fn from_name(name: &str) -> Option<Analysis> {
        ALL.into_iter().find(|a| a.name() == name)
    }

    /// The name used on the command line and in reports.
    pub fn name(self) -> &'static str {
        self.declaration().name
    }

    /// What the load parameter is, with its unit.
    pub fn parameter(self) -> &'static str {
        self.declaration().parameter
    }

    /// The unit of the load parameter (and of `--range` and `--arc-step`).
    pub fn unit(self) -> &'static str {
        self.declaration().quantity.unit()
    }

    /// Whether the load parameter drives a travel (else it is a force, a torque or a fraction of loads).
    pub(super) fn is_travel(self) -> bool {
        self.declaration().quantity == Quantity::Travel
    }

    /// What the rig holds or leaves free, where it is more than one corner on its own rig: for the
    /// command's help.
    pub fn rig_words(self) -> Option<&'static str> {
        self.declaration().rig_words
    }

    /// The range the analysis walks when none is given, in its own unit (see [`DefaultRange`]).
    pub fn default_range(self) -> DefaultRange {
        self.declaration().default_range
    }

    /// The range to walk: `given`, else the analysis's default ends. An analysis whose default depends on
    /// the model (the vertical force) or that walks no range (the static load) finds its own.
    pub(super) fn range_or_default(self, given: Option<(f64, f64)>) -> Result<(f64, f64), Cause> {
        match (given, self.default_range()) {
            (Some(range), _) => Ok(range),
            (None, DefaultRange::Ends(from, to)) => Ok((from, to)),
            (None, default) => Err(Cause::Settings(format!("{}: {default}: give the range", self.name()))),
        }
    }

    /// Where the design position sits on the load parameter (the vertical force sweep's is the design
    /// wheel load, known only once the model is solved, so `None` there).
    pub fn design_parameter(self) -> Option<f64> {
        self.declaration().design_parameter
    }
}

/// What an analysis declares of itself, in its own file (`kc/parallel_travel.rs`, `kc/roll.rs`, …): its
/// name, its load parameter and the range it walks when none is given. The command's help, Python, the
/// reports and the table of `docs/analyses.md` read these ([`Analysis::declaration`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Declaration {
    /// The name used on the command line and in reports.
    pub name: &'static str,
    /// What the load parameter is, with its unit and sign.
    pub parameter: &'static str,
    /// What the load parameter is a quantity of.
    pub quantity: Quantity,
    /// What the rig holds or leaves free, where it is more than one corner on its own rig.
    pub rig_words: Option<&'static str>,
    /// The range walked when none is given.
    pub default_range: DefaultRange,
    /// Where the design position sits on the load parameter; `None` where only the solved model knows it
    /// (the design wheel load) or the analysis walks no range.
    pub design_parameter: Option<f64>,
    /// The rows of its sweep its figures read besides the design position.
    pub figure_rows: FigureRows,
}

/// What an analysis's load parameter is a quantity of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// A travel, m: of a wheel or of the rack.
    Travel,
    /// A force, N.
    Force,
    /// A torque, N·m.
    Torque,
    /// A fraction of the model file's load case, 0 to 1.
    Fraction,
}

impl Quantity {
    /// Its unit, as the command and the reports write it.
    pub fn unit(self) -> &'static str {
        match self {
            Quantity::Travel => "m",
            Quantity::Force => "N",
            Quantity::Torque => "N·m",
            Quantity::Fraction => "of the load case",
        }
    }

    /// The largest end a range of it may have ([`MAX_RANGE_TRAVEL`], [`MAX_RANGE_LOAD`],
    /// [`MAX_RANGE_FRACTION`]).
    pub(super) fn largest_range_end(self) -> f64 {
        match self {
            Quantity::Travel => MAX_RANGE_TRAVEL,
            Quantity::Force | Quantity::Torque => MAX_RANGE_LOAD,
            Quantity::Fraction => MAX_RANGE_FRACTION,
        }
    }
}

/// The range an analysis walks when none is given ([`Analysis::default_range`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DefaultRange {
    /// These ends, in the analysis's own unit.
    Ends(f64, f64),
    /// From half to one and a half times the design wheel load, or from 0 to [`UNLOADED_RANGE_TOP`] N
    /// where that is next to nothing (a range around nothing would have no width).
    AroundDesignLoad,
    /// None: the analysis applies its load at once.
    NoRange,
}

/// The top of the vertical force's default range for a corner that carries next to nothing at design (its
/// spring at its free length, as some imported data have it), N.
const UNLOADED_RANGE_TOP: f64 = 3000.0;

impl DefaultRange {
    /// The ends of [`DefaultRange::AroundDesignLoad`] for a corner carrying `design_load` (N).
    pub(super) fn around_design_load(design_load: f64) -> (f64, f64) {
        if design_load.abs() < 1.0 {
            (0.0, UNLOADED_RANGE_TOP)
        } else {
            (0.5 * design_load, 1.5 * design_load)
        }
    }
}

impl std::fmt::Display for DefaultRange {
    /// As the command's help says it: `default -0.08,0.08`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DefaultRange::Ends(from, to) => write!(f, "default {},{}", plain(*from), plain(*to)),
            DefaultRange::AroundDesignLoad => write!(
                f,
                "default 0.5..1.5 x the design wheel load (0..{} N when it is nothing)",
                plain(UNLOADED_RANGE_TOP)
            ),
            DefaultRange::NoRange => write!(f, "no range"),
        }
    }
}

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
    pub load_point: crate::assembly::LoadPoint,
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
    /// Every row read again one exact Newton iteration away, for the error estimate (one factorization
    /// more per row). Off only where the estimate is not wanted (a sensitivity's replays, which read the
    /// rows alone); a report without it says "not estimated".
    #[serde(skip)]
    pub error_estimate: bool,
    /// The parts' poses at every row and a drawing of the model, for the report's views
    /// ([`AnalysisReport::motion`](crate::kc::AnalysisReport::motion)). Off unless a view is to be drawn.
    #[serde(skip)]
    pub motion: bool,
    /// Each row read for the figures alone: a load sweep's rows without the force in every joint and
    /// element, an axle's roll centre only in its reading at design. The figures are those read with the whole rows, to
    /// the bit; the table lacks those columns and cells. For the sensitivities of the figures alone,
    /// which then replay no more than the figures read: a sweep's replays move only the rows its figures
    /// read ([`SweepExtras::figure_rows`](crate::analysis::SweepExtras::figure_rows)), and the table has no
    /// derivatives.
    #[serde(skip)]
    pub figures_only: bool,
    /// The units of the slopes against wheel travel and of the aligning-torque compliances.
    pub units: Units,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            range: None,
            steps: 32,
            mode: Mode::Corrected,
            height_held: true,
            load_point: crate::assembly::LoadPoint::ContactPatch,
            compliance: false,
            tolerance: Tolerance::default(),
            through_limits: false,
            arc_step: None,
            error_estimate: true,
            motion: false,
            figures_only: false,
            units: Units::DegPerM,
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

/// Which rows of its sweep an analysis's figures read besides the design position (every figure at design
/// is read off the exact equilibrium there): a replay for the figures alone moves those and no other.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FigureRows {
    /// None: the figures are read at design alone.
    DesignOnly,
    /// The last row too (a value at the end of the range).
    LastRow,
    /// Rows found by their values once the sweep is read (full steer, the largest Ackermann error), which
    /// the analysis names as it reads them (`Taping::rows_read`).
    Extremes,
}

impl FigureRows {
    /// The rows a replay moves for these.
    fn replayed(self) -> ReplayRows {
        let (last, extremes) = match self {
            FigureRows::DesignOnly => (false, false),
            FigureRows::LastRow => (true, false),
            FigureRows::Extremes => (false, true),
        };
        ReplayRows { near: None, last, extremes }
    }
}

impl Settings {
    /// What the sweeps over `range` take besides their rows.
    pub(super) fn extras<'t>(&self, range: (f64, f64), taping: &'t Taping) -> SweepExtras<'t> {
        let one_step = (range.1 - range.0).abs() / self.steps as f64;
        SweepExtras {
            error_estimate: self.error_estimate,
            compliance: self.compliance,
            through_limits: self.through_limits.then(|| self.arc_step.unwrap_or(one_step)),
            poses: self.motion,
            figures_only: self.figures_only,
            figure_rows: None,
            at_design: None,
            taping: Some(taping),
        }
    }

    /// [`Settings::extras`] of a sweep whose figures read its readings at the design load parameter
    /// `design` ([`SweepExtras::at_design`]) and only `rows` of it: when reading for the figures alone, a
    /// replay moves only those ([`SweepExtras::figure_rows`]). The sweeps' solvers take part in `taping`.
    pub(super) fn extras_reading<'t>(
        &self,
        range: (f64, f64),
        design: f64,
        rows: FigureRows,
        taping: &'t Taping,
    ) -> SweepExtras<'t> {
        let figure_rows = self.figures_only.then_some(rows.replayed());
        SweepExtras { figure_rows, at_design: Some(design), ..self.extras(range, taping) }
    }
}

/// Why an analysis failed: which one, and what stopped it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{analysis}: {cause}")]
pub struct AnalysisError {
    /// The analysis's name.
    pub analysis: &'static str,
    /// What stopped it; its text says what to change.
    pub cause: Cause,
}

/// What stopped an analysis. Each says what went wrong and what to change when written.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Cause {
    /// Settings that cannot work for the analysis (its steps, arc step or range), told before any model
    /// is built: the caller's input, not the model's.
    #[error("{0}")]
    Settings(String),
    /// The model lacks what the analysis needs (a vehicle section, a load case).
    #[error("{0}")]
    Lacks(String),
    /// The model cannot be built on the analysis's rig.
    #[error(transparent)]
    Model(#[from] elastokin_core::ModelError),
    /// The solver found no equilibrium the analysis needs, or the path ended short of it.
    #[error(transparent)]
    Solver(#[from] elastokin_solver::SolverError),
}

/// Narrowest range an analysis walks, in its own parameter's unit (m, N, N·m).
pub const MIN_RANGE: f64 = 1e-9;
/// The largest travel a range may reach (m): no wheel or rack travels a metre, so a range beyond it is
/// taken for one in millimetres, and said so.
pub const MAX_RANGE_TRAVEL: f64 = 1.0;
/// The largest force or torque a range may reach (N, N·m).
pub const MAX_RANGE_LOAD: f64 = 1e8;
/// The largest multiple of the model's own load case a range may reach.
pub const MAX_RANGE_FRACTION: f64 = 1e6;

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
}
