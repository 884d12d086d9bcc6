//! How every sweep walks its load path and reads its rows: the walk itself (steps, limit points, arc
//! length through them), the extras a sweep may read at each step (error estimate, compliance), the rig
//! an analysis needs, and the slope of a figure at a point of its rows.

use crate::analysis::compliance::compliance_with;
use crate::assembly::{Corner, Rig};
use crate::wheel::Wheel;
use elastokin_core::Pose;
use elastokin_solver::replay::{ReplayRows, Taping, NO_TAPING};
use elastokin_solver::{ArcStep, LoadPath, Mode, SolverError, State, StaticSolver, StepResult, Sweep, MAX_STEPS};

/// Refuses a corner held differently from what the analysis needs: `rigs` lists the rigs it accepts.
pub(crate) fn require_rig(corner: &Corner, rigs: &[Rig]) -> Result<(), SolverError> {
    if rigs.contains(&corner.rig) {
        return Ok(());
    }
    let held = |rig: &Rig| match rig {
        Rig::WheelTravel => "the wheel-centre height driven",
        Rig::Steering => "the rack driven and the wheel-centre height held",
        Rig::HeightHeld => "the wheel-centre height held",
        Rig::Free => "the wheel free on its spring",
    };
    let accepted: Vec<&str> = rigs.iter().map(held).collect();
    Err(SolverError::InvalidInput {
        what: "corner",
        why: format!(
            "this analysis needs the corner on the rig with {}, but it is held with {}",
            accepted.join(" or "),
            held(&corner.rig)
        ),
    })
}

/// Slope of `y` against `x` at `x = at` over sweep rows (in either order): a central difference of the
/// rows on either side when a row sits at `at` (to [`AT_ROW`] of the rows' span, so that the rounding of
/// a computed `at`, such as a design wheel load, does not switch the reading to a chord), else the chord
/// of the two rows that bracket it. `None` when `at` is outside the rows' range or there are fewer than
/// two rows.
pub fn slope_at<R>(rows: &[R], at: f64, x: impl Fn(&R) -> f64, y: impl Fn(&R) -> f64) -> Option<f64> {
    let xs: Vec<f64> = rows.iter().map(&x).collect();
    let span = xs.iter().fold(0.0f64, |m, &v| m.max((v - xs[0]).abs()));
    let (a, b) = match xs.iter().position(|&v| (v - at).abs() <= AT_ROW * span) {
        Some(k) if rows.len() >= 2 => (k.saturating_sub(1), (k + 1).min(rows.len() - 1)),
        Some(_) => return None,
        None => {
            let i = xs.windows(2).position(|w| (w[0] - at) * (w[1] - at) < 0.0)?;
            (i, i + 1)
        }
    };
    Some((y(&rows[b]) - y(&rows[a])) / (xs[b] - xs[a]))
}

/// How near a row's load parameter must be to a point, relative to the rows' span, for [`slope_at`] to
/// take the row as at the point: far below any step (a sweep has at most `MAX_STEPS` of them), far above
/// rounding.
pub const AT_ROW: f64 = 1e-9;

/// What a sweep can do besides walking its rows: read more at every step, at the cost of more
/// factorizations, and go on through a limit point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SweepExtras<'t> {
    /// Every row read again one exact Newton iteration away ([`StaticSolver::newton_correction`]): the
    /// difference is the row's error estimate. One factorization per row.
    pub error_estimate: bool,
    /// The 6×6 wheel compliance ([`wheel_compliance`](crate::analysis::wheel_compliance)) at every step. One factorization and six
    /// back-substitutions per row.
    pub compliance: bool,
    /// What to do at a limit point (a load the corner cannot carry, a travel its linkage cannot reach):
    /// `None` stops there; `Some(step)` follows the path on through it by arc length
    /// ([`StaticSolver::arc_length_sweep_from`]) from the last step before it, with steps of `step` in the
    /// sweep's own unit (N, N·m or m): the change of load or travel of the first arc-length step
    /// ([`ArcStep::Load`]). At most [`MAX_ARC_STEPS_PER_RANGE`] steps of that size per range are taken,
    /// and at most [`MAX_STEPS`].
    pub through_limits: Option<f64>,
    /// The bodies' poses at every step, for a view that moves the parts as solved.
    pub poses: bool,
    /// Each row read for the K&C figures alone ([`crate::kc::Settings::figures_only`]): a load sweep's
    /// rows without the force in every joint and element ([`LoadRow::forces`] empty), an axle sweep's
    /// roll centre only in its reading at design.
    ///
    /// [`LoadRow::forces`]: crate::analysis::LoadRow::forces
    pub figures_only: bool,
    /// The rows the K&C figures read, when the rows are read for the figures alone: a replay
    /// ([`elastokin_solver::replay`]) moves those alone, and its rows are those alone (found by their load
    /// parameters, as the figures find them).
    pub figure_rows: Option<ReplayRows>,
    /// The design load parameter (m, N, N·m or a fraction: the sweep's own unit), where the sweep reads
    /// [`AtDesign`] besides its rows: the exact equilibrium there and the path's expansion to second order through
    /// it. One equilibrium and one factorization more (two of each with the error estimate).
    pub at_design: Option<f64>,
    /// The recording or replay the sweep's solvers take part in ([`elastokin_solver::replay`]), if any.
    pub taping: Option<&'t Taping>,
}

impl SweepExtras<'_> {
    /// The recording or replay the sweep's solvers take part in: [`SweepExtras::taping`], or none.
    pub fn taping(&self) -> &Taping {
        self.taping.unwrap_or(&NO_TAPING)
    }
}

/// How many arc-length steps of [`SweepExtras::through_limits`] a path through a limit point may take,
/// per step that would span the sweep's range: room for the displacement the path makes where it
/// carries no more load.
pub const MAX_ARC_STEPS_PER_RANGE: f64 = 10.0;

/// Where a sweep met a limit point, and what it did there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweepLimit {
    /// The load parameter of the limit point (N, N·m or m: the sweep's own unit), located to
    /// [`elastokin_solver::LIMIT_POINT_TOLERANCE`] of the range.
    pub at: f64,
    /// How the rows go on past it: `None` when the sweep stopped there (its last row is then the
    /// equilibrium at the limit point).
    pub through: Option<ArcLengthRows>,
}

/// The rows of a sweep that followed its path through a limit point by arc length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcLengthRows {
    /// Index of the first row walked by arc length: the rows before it are the sweep's own steps, up to
    /// the last one before the limit point.
    pub first_row: usize,
    /// The arc-length step asked for ([`SweepExtras::through_limits`]).
    pub step: f64,
    /// How the path ended.
    pub end: ArcEnd,
}

/// How a path followed by arc length ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArcEnd {
    /// It left the range: its last row lies just beyond it.
    LeftRange,
    /// It took the most steps allowed inside the range.
    MostSteps,
    /// It could be followed no further on its branch from its last row (it branches or bends too sharply
    /// there: [`Sweep::stuck`](elastokin_solver::Sweep::stuck)).
    Stuck,
}

/// A sweep's rows, and what [`SweepExtras`] asked for, row by row.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepOutput<R> {
    /// The rows: every step of the sweep; up to the limit point, or through it, if it met one.
    pub rows: Vec<R>,
    /// Where the sweep met a limit point, if it did.
    pub limit: Option<SweepLimit>,
    /// The rows read one Newton iteration closer to the exact equilibrium at their load parameter.
    pub corrected: Option<Vec<R>>,
    /// The force and constraint residuals of every step: `(‖Φ_qᵀλ − Q‖∞ / force scale, ‖Φ‖∞)`.
    pub residuals: Vec<(f64, f64)>,
    /// The 6×6 wheel compliance at every step (rows: wheel-centre translation, rotation; columns: unit
    /// force, torque at the wheel centre).
    pub compliance: Option<Vec<[[f64; 6]; 6]>>,
    /// The bodies' poses at every step (in the model's order of bodies).
    pub poses: Option<Vec<Vec<Pose>>>,
    /// What [`SweepExtras::at_design`] asked for: the readings at design, or why the equilibrium there
    /// or its tangent could not be had.
    pub design: Option<Result<AtDesign<R>, SolverError>>,
    /// The same one exact Newton iteration on from the design equilibrium, with the error estimate: the
    /// difference of what is read off the two is the design readings' error estimate.
    pub design_corrected: Option<AtDesign<R>>,
}

/// Where a sweep's reader reads a state: a row, the design equilibrium, or a point of the path's expansion
/// through the design equilibrium ([`AtDesign`]), read only to be differenced: there a reader may leave out
/// what no rate is taken of (a roll centre's own tangent, the force in every component), and a row read
/// for the figures alone ([`SweepExtras::figures_only`]) what only the design's reading gives them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reading {
    /// A row of the sweep.
    Row,
    /// The equilibrium at design.
    Design,
    /// A point of the path's expansion through the design equilibrium.
    Expansion,
}

/// A sweep's readings at its design load parameter, which no step count or range moves: the row of the
/// exact equilibrium there, and rows read at points of the path's expansion to second order through it
/// ([`StaticSolver::along_path`], with [`StaticSolver::path_second_rates`]). A reading `y` of a row has
/// the path's `dy/dt` and `d²y/dt²` as its derivatives along the expansion, which [`AtDesign::rate`] and
/// [`AtDesign::curvature`] take by differences of those rows, Richardson extrapolated: exact but for `y`'s
/// own higher derivatives, to `O(h⁴)`.
#[derive(Debug, Clone, PartialEq)]
pub struct AtDesign<R> {
    /// The row of the equilibrium at the design load parameter `t`.
    pub row: R,
    /// Rows at `t − 2h`, `t − h`, `t + h`, `t + 2h` on the path's expansion.
    expansion: [R; 4],
    /// The expansion's step, in the load parameter's unit: [`EXPANSION_REACH`] over the largest motion per
    /// unit `t`.
    h: f64,
    /// Read as the plain central difference over ±h, for the estimate of the extrapolated one's error.
    unextrapolated: bool,
}

/// How far the expansion's nearest points move the model (m, and rad at a metre's lever): far enough
/// that a reading's rounding (1e-16 of a metre's pose) is 1e-12 of its difference, near enough that its
/// curvature over the step leaves 1e-8 in the plain central difference and nothing in the extrapolated one.
pub const EXPANSION_REACH: f64 = 1e-4;

impl<R> AtDesign<R> {
    /// `dy/dt` at design, Richardson extrapolated from the central differences over ±h and ±2h (the plain
    /// central difference over ±h in [`AtDesign::unextrapolated`]).
    pub fn rate(&self, y: impl Fn(&R) -> f64) -> f64 {
        let [m2, m1, p1, p2] = self.expansion.each_ref().map(&y);
        let near = (p1 - m1) / (2.0 * self.h);
        if self.unextrapolated {
            return near;
        }
        let far = (p2 - m2) / (4.0 * self.h);
        (4.0 * near - far) / 3.0
    }

    /// `d²y/dt²` at design, extrapolated as [`AtDesign::rate`] is.
    pub fn curvature(&self, y: impl Fn(&R) -> f64) -> f64 {
        let [m2, m1, p1, p2] = self.expansion.each_ref().map(&y);
        let y0 = y(&self.row);
        let h2 = self.h * self.h;
        let near = (p1 - 2.0 * y0 + m1) / h2;
        if self.unextrapolated {
            return near;
        }
        let far = (p2 - 2.0 * y0 + m2) / (4.0 * h2);
        (16.0 * near - far) / 15.0
    }

    /// The same readings, each made another row by `f` (a reading joined to what another sweep read there).
    pub fn map<S>(&self, f: impl Fn(&R) -> S) -> AtDesign<S> {
        let expansion = self.expansion.each_ref().map(&f);
        AtDesign { row: f(&self.row), expansion, h: self.h, unextrapolated: self.unextrapolated }
    }

    /// The same readings, differenced without extrapolation: how far that moves a figure bounds the
    /// extrapolated figure's truncation (by the factor the extrapolation gains, `h²` and more).
    pub fn unextrapolated(&self) -> AtDesign<R>
    where
        R: Clone,
    {
        AtDesign { unextrapolated: true, ..self.clone() }
    }
}

/// Reads [`AtDesign`] at load parameter `t` with `solver`: the equilibrium there by Newton from the
/// design pose, its tangent factorized, the path's rates, and `read` at the points of the path's
/// expansion; with `estimate`, the same one exact Newton iteration on as well.
fn read_at_design<R>(
    solver: &mut StaticSolver,
    t: f64,
    estimate: bool,
    read: &mut impl FnMut(&mut StaticSolver, &StepResult, Reading) -> Result<R, SolverError>,
) -> Result<(AtDesign<R>, Option<AtDesign<R>>), SolverError> {
    let mut state = solver.design_state(t);
    let at = solver.equilibrium(&mut state)?;
    let design = read_expansion(solver, &at, read)?;
    let corrected = match estimate {
        true => {
            let next = solver.newton_correction(&at)?;
            Some(read_expansion(solver, &next, read)?)
        }
        false => None,
    };
    Ok((design, corrected))
}

/// [`AtDesign`] through the state of `at`.
fn read_expansion<R>(
    solver: &mut StaticSolver,
    at: &StepResult,
    read: &mut impl FnMut(&mut StaticSolver, &StepResult, Reading) -> Result<R, SolverError>,
) -> Result<AtDesign<R>, SolverError> {
    let row = read(solver, at, Reading::Design)?;
    let state = solver.state_of(at);
    solver.factorize_tangent(&state)?;
    let rates = solver.path_rates_factored()?;
    // The largest motion per unit load parameter: translations, and rotations at a metre's lever.
    let reach = rates.dq.iter().fold(0.0f64, |m, v| if v.abs() > m { v.abs() } else { m });
    // Nothing moves along the path (a load the joints carry alone), or next to nothing: the multipliers are
    // linear there, and a unit step reads their rate.
    let h = match EXPANSION_REACH / reach {
        h if h.is_finite() => h,
        _ => 1.0,
    };
    let second = solver.path_second_rates(&state, &rates, h)?;
    let mut at_step =
        |k: f64| read(solver, &solver.along_path(&state, &rates, Some(&second), k * h), Reading::Expansion);
    let expansion = [at_step(-2.0)?, at_step(-1.0)?, at_step(1.0)?, at_step(2.0)?];
    Ok(AtDesign { row, expansion, h, unextrapolated: false })
}

/// The equilibria of a walked load path, and where it met a limit point.
#[derive(Debug, Clone, PartialEq)]
pub struct Walked {
    /// The equilibria in the order of the path: the start, then every step; at a limit point, the
    /// equilibrium there last, or the path on through it (see [`SweepLimit`]).
    pub steps: Vec<StepResult>,
    /// Where the path met a limit point, if it did.
    pub limit: Option<SweepLimit>,
}

/// Walks `path` from `state` in `mode`, as every analysis walks its sweep. At a limit point the rows
/// stop with the equilibrium there, or, with [`SweepExtras::through_limits`], go on through it by arc
/// length from the last step before it. A replay moves only the steps of [`SweepExtras::figure_rows`].
pub fn walk(
    solver: &mut StaticSolver,
    state: &mut State,
    path: LoadPath,
    mode: Mode,
    extras: &SweepExtras,
) -> Result<Walked, SolverError> {
    let through = extras.through_limits;
    solver.replay_rows(extras.figure_rows);
    let Sweep { mut steps, limit, .. } = solver.sweep_from(state, path, mode)?;
    let Some(limit) = limit else { return Ok(Walked { steps, limit: None }) };
    let Some(step) = through else {
        steps.push(limit.step);
        return Ok(Walked { steps, limit: Some(SweepLimit { at: limit.t, through: None }) });
    };
    let range = (path.end - path.start).abs();
    if !(step.is_finite() && step > 0.0) {
        return Err(SolverError::InvalidInput {
            what: "arc-length step",
            why: format!("it must be a positive length in the sweep's own unit (N, N·m or m), got {step}"),
        });
    }
    let most = (MAX_ARC_STEPS_PER_RANGE * range / step).ceil().clamp(1.0, MAX_STEPS as f64) as usize;
    let first_row = steps.len();
    let mut from = solver.state_of(&steps[first_row - 1]);
    let arc =
        solver.arc_length_sweep_from(&mut from, LoadPath::new(path.start, path.end, most), ArcStep::Load(step))?;
    let (lo, hi) = (path.start.min(path.end), path.start.max(path.end));
    let end = if arc.stuck.is_some() {
        ArcEnd::Stuck
    } else if arc.steps.last().is_some_and(|s| !(lo..=hi).contains(&s.t)) {
        ArcEnd::LeftRange
    } else {
        ArcEnd::MostSteps
    };
    // Its first equilibrium is the last step's.
    steps.extend(arc.steps.into_iter().skip(1));
    let through = Some(ArcLengthRows { first_row, step, end });
    Ok(Walked { steps, limit: Some(SweepLimit { at: limit.t, through }) })
}

/// The rows of a sweep that must cover its whole range: a limit point is [`SolverError::LimitPoint`].
pub(crate) fn whole<R>(out: SweepOutput<R>) -> Result<Vec<R>, SolverError> {
    match out.limit {
        Some(limit) => Err(SolverError::LimitPoint { reached: limit.at }),
        None => Ok(out.rows),
    }
}

/// Reads a sweep's rows, and what `extras` asks for, with the solver that walked it.
pub(crate) fn read_sweep<R>(
    solver: &mut StaticSolver,
    wheel: &Wheel,
    partner: Option<&Wheel>,
    walked: Walked,
    extras: SweepExtras,
    mut read: impl FnMut(&mut StaticSolver, &StepResult, Reading) -> Result<R, SolverError>,
) -> Result<SweepOutput<R>, SolverError> {
    let Walked { steps, limit } = walked;
    let steps = &steps[..];
    let rows = steps.iter().map(|s| read(solver, s, Reading::Row)).collect::<Result<Vec<R>, _>>()?;
    let corrected = if extras.error_estimate {
        let mut out = Vec::with_capacity(steps.len());
        for s in steps {
            let c = solver.newton_correction(s)?;
            out.push(read(solver, &c, Reading::Row)?);
        }
        Some(out)
    } else {
        None
    };
    let compliance = if extras.compliance {
        Some(
            steps
                .iter()
                .map(|s| compliance_with(solver, wheel, partner, &solver.state_of(s)))
                .collect::<Result<_, _>>()?,
        )
    } else {
        None
    };
    let residuals = steps.iter().map(|s| (s.force_residual / s.force_scale, s.constraint_residual)).collect();
    let poses = extras.poses.then(|| steps.iter().map(|s| s.poses.clone()).collect());
    let (design, design_corrected) = match extras.at_design {
        Some(t) => match read_at_design(solver, t, extras.error_estimate, &mut read) {
            Ok((design, corrected)) => (Some(Ok(design)), corrected),
            Err(e) => (Some(Err(e)), None),
        },
        None => (None, None),
    };
    Ok(SweepOutput { rows, limit, corrected, residuals, compliance, poses, design, design_corrected })
}
