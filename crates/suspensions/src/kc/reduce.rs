//! How a sweep's rows become a report: the table and its error estimate, the headline figures and their
//! accuracy, the warnings of a limit point or of an error over tolerance, compliance tables, charts, and
//! the wording every analysis shares.

use crate::analysis::{ArcEnd, ArcLengthRows, AtDesign, SweepLimit, SweepOutput};
use crate::assembly::{Axle, Corner};
use crate::drawing::{Drawing, Motion};
use crate::file::SuspensionFile;
use crate::kc::chart::{Chart, Scale, Series, YAxis};
use crate::kc::report::{significant, Accuracy, AnalysisReport, Cell, Column, Figure, Table, Warning};
use crate::kc::settings::{mode_word, Analysis, Cause, Settings};
use crate::kc::unit::Unit;
use crate::wheel::Wheel;
use elastokin_solver::{Mode, MAX_STEPS};

/// Short model name for plot subtitles (the part before any parenthesis).
pub(super) fn short_name(file: &SuspensionFile) -> String {
    file.name.split(" (").next().unwrap_or(&file.name).to_string()
}

pub(super) fn deg(rad: f64) -> f64 {
    rad.to_degrees()
}

/// What an analysis's figures read at design ([`AtDesign`]), or why there is nothing to read there, in
/// words.
pub(super) type Design<'a, R> = Result<&'a AtDesign<R>, &'a str>;

/// An analysis's figures from its rows and its readings at design.
pub(super) type Figures<'a, R> = dyn Fn(&[R], Design<R>) -> Vec<Figure> + 'a;

/// What every analysis does with its sweep: the table and charts from the rows, the figures from the
/// readings at design (and from rows where a figure is defined over the range: at its end, its largest),
/// and the error estimate from the same reading of the corrected rows and design.
pub(super) struct Reduction<'a, R> {
    pub(super) table: &'a dyn Fn(&[R]) -> Table,
    /// The figures; any error estimate one sets is its own (a discretization's), to which the readings'
    /// is added.
    pub(super) figures: &'a Figures<'a, R>,
    /// The drawing of the model walked, made only when the settings ask for the motion.
    pub(super) drawing: Option<Drawing>,
}

/// The drawing of a corner (both wheels of a solid axle's), when `settings` ask for the motion.
pub(super) fn corner_drawing(corner: &Corner, settings: &Settings) -> Option<Drawing> {
    let wheels: Vec<&Wheel> = std::iter::once(&corner.wheel).chain(corner.partner.as_ref()).collect();
    settings.motion.then(|| Drawing::of(&corner.model, &wheels))
}

/// The drawing of an axle, when `settings` ask for the motion.
pub(super) fn axle_drawing(axle: &Axle, settings: &Settings) -> Option<Drawing> {
    settings.motion.then(|| Drawing::of(&axle.model, &[&axle.left, &axle.right]))
}

/// Builds the report of a sweep: reads `table` and `figures` off the rows and the readings at design,
/// and again off the corrected rows and design; a figure's error estimate is its own (if it set one), the
/// difference of the two readings (the solve's error), and how far the design's rates move unextrapolated
/// (their differencing's).
pub(super) fn finish<R: Clone>(
    analysis: Analysis,
    mut description: String,
    range: (f64, f64),
    settings: &Settings,
    out: &SweepOutput<R>,
    reduce: Reduction<R>,
    charts: Vec<Chart>,
) -> AnalysisReport {
    let table = (reduce.table)(&out.rows);
    let reason = match &out.design {
        Some(Err(e)) => format!("the equilibrium at design or its tangent could not be had: {e}"),
        _ => "the analysis reads nothing at design".to_string(),
    };
    let design: Design<R> = match &out.design {
        Some(Ok(d)) => Ok(d),
        _ => Err(&reason),
    };
    let mut figures = (reduce.figures)(&out.rows, design);
    let (columns, method) = estimate(&table, &mut figures, out, &reduce, design, settings);
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
        warnings.push(error_warning(analysis, settings, &figures, (angle_error_deg, length_error_m), &over_figures));
    }
    let compliance = out.compliance.as_ref().map(|c| compliance_table(analysis, &table, c));
    AnalysisReport {
        analysis,
        parameter: analysis.parameter().into(),
        description,
        range,
        steps: settings.steps,
        figures,
        units: settings.units,
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
        motion: out.poses.clone().zip(reduce.drawing).map(|(frames, drawing)| Motion { drawing, frames }),
        construction: Vec::new(),
        envelope: None,
    }
}

/// Each figure's error estimate added to it (its change one exact Newton iteration on, and against the
/// rows' own differences at design), and each column's largest change with how it was estimated; none
/// where the sweep was not read again.
fn estimate<R: Clone>(
    table: &Table,
    figures: &mut [Figure],
    out: &SweepOutput<R>,
    reduce: &Reduction<R>,
    design: Design<R>,
    settings: &Settings,
) -> (Vec<Option<f64>>, String) {
    match &out.corrected {
        Some(corrected) => {
            let other = (reduce.table)(corrected);
            let corrected_design = out.design_corrected.as_ref().map_or(design, Ok);
            let unextrapolated = design.ok().map(AtDesign::unextrapolated);
            let unextrapolated = unextrapolated.as_ref().map_or(design, Ok);
            let again = (reduce.figures)(corrected, corrected_design);
            let differenced = (reduce.figures)(&out.rows, unextrapolated);
            for ((f, g), u) in figures.iter_mut().zip(again).zip(differenced) {
                if let (Some(a), Some(b), Some(c)) = (f.value, g.value, u.value) {
                    f.error = Some(f.error.unwrap_or(0.0) + (a - b).abs() + (a - c).abs());
                }
            }
            (
                table.column_differences(&other),
                format!("every row against one exact Newton iteration from it ({} mode)", mode_word(settings.mode)),
            )
        }
        None => (vec![None; table.columns.len()], "not estimated".to_string()),
    }
}

/// The warning of an analysis whose estimated error is over its tolerance: what is over (angles and
/// lengths of the table, `errors`, and the figures `over`) and what would bring it within.
fn error_warning(
    analysis: Analysis,
    settings: &Settings,
    figures: &[Figure],
    (angle_error_deg, length_error_m): (f64, f64),
    over: &[String],
) -> Warning {
    let tol = settings.tolerance;
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
            "paper mode's error falls in proportion to the step: about {needed:.0} steps would meet the \
             tolerance (steps, --steps), or corrected mode (mode, --mode)"
        ),
        Mode::Paper => format!(
            "paper mode's error falls in proportion to the step, and more than {MAX_STEPS} steps would be \
             needed: use corrected mode (mode, --mode)"
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
    if !over.is_empty() {
        what.push(format!("figures {} (tolerance {:.1} %)", over.join(", "), tol.relative * 100.0));
    }
    Warning {
        code: "error-over-tolerance",
        hardpoints: Vec::new(),
        message: format!("{}: estimated error {}; {fix}", analysis.name(), what.join(", ")),
    }
}

/// A load or travel in the analysis's unit, as the descriptions and warnings give it.
pub(super) fn amount(analysis: Analysis, v: f64) -> String {
    format!("{} {}", significant(v, 6), analysis.unit())
}

/// The end of the description line of a sweep that met a limit point.
pub(super) fn limit_description(analysis: Analysis, limit: &SweepLimit) -> String {
    match limit.through {
        None => format!(", stopped at the limit point at {}", amount(analysis, limit.at)),
        Some(_) => format!(", through the limit point at {} by arc length", amount(analysis, limit.at)),
    }
}

/// The warning of a sweep that met a limit point: where the suspension gives way (or its linkage reaches
/// the end of its travel), what the table holds, and how to see beyond. `last` is the last row's load.
pub(super) fn limit_warning(analysis: Analysis, limit: &SweepLimit, last: f64) -> Warning {
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
        None => "the table and plots stop there, their last row at the limit point; run the analysis \
                 through limits (through_limits, --through-limits) to follow the path through it by arc length"
            .to_string(),
        Some(ArcLengthRows { end: ArcEnd::LeftRange, step, .. }) => format!(
            "the table and plots follow the path through it by arc length (steps of {} at first) until it leaves \
             the range at {}",
            amount(analysis, step),
            amount(analysis, last)
        ),
        Some(ArcLengthRows { end: ArcEnd::Stuck, step, .. }) => format!(
            "the table and plots follow the path through it by arc length (steps of {} at first) as far as {}, \
             where the path branches or bends too sharply to follow on (no step, however short, stays on it): \
             the rows stop there, inside the range",
            amount(analysis, step),
            amount(analysis, last)
        ),
        Some(arc) => format!(
            "the table and plots follow the path through it by arc length (steps of {} at first), but the path \
             stopped after the most steps allowed at {}, inside the range; give a larger arc-length step (arc_step, --arc-step)",
            amount(analysis, arc.step),
            amount(analysis, last)
        ),
    };
    Warning { code: "limit-point", hardpoints: Vec::new(), message: format!("{}: {what}; {then}", analysis.name()) }
}

/// A figure whose estimated error is over `relative` of its value (and shows in its printed decimals), as
/// the warning names it: `label ±x %`, or `label ±e unit` where a percentage means nothing (a figure at or
/// near zero).
pub(super) fn over_tolerance(f: &Figure, relative: f64) -> Option<String> {
    let (v, e) = (f.value?, f.error?);
    let ratio = e / v.abs();
    f.estimate_matters(relative).then(|| {
        if ratio < 10.0 {
            format!("{} ±{:.1} %", f.label, 100.0 * ratio)
        } else {
            let unit = f.unit.shown();
            format!("{} ±{:.2e} {}", f.label, e * unit.factor, unit.symbol)
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
pub(super) fn compliance_table(analysis: Analysis, rows: &Table, c: &[[[f64; 6]; 6]]) -> Table {
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

/// The reason a figure needs a vehicle-section entry the file lacks.
pub(super) fn needs_vehicle(field: &str) -> String {
    format!("needs vehicle.{field} in the model file")
}

/// A chart against the load parameter with one or two axes.
pub(super) fn chart(
    file: &SuspensionFile,
    name: &str,
    title: &str,
    x_label: &str,
    left: YAxis,
    right: Option<YAxis>,
    design_x: Option<f64>,
) -> Chart {
    Chart {
        name: name.into(),
        title: title.into(),
        subtitle: short_name(file),
        x_label: x_label.into(),
        x_scale: Scale::Linear,
        left,
        right,
        design_x,
    }
}

/// A curve of an axis: its legend, and its y read off a row (`None` where the row has none).
pub(super) type Curve<'a, R> = (&'a str, &'a dyn Fn(&R) -> Option<f64>);
/// An axis of curves read off rows.
pub(super) fn axis<R>(label: &str, rows: &[R], x: impl Fn(&R) -> f64, curves: &[Curve<R>]) -> YAxis {
    YAxis {
        label: label.into(),
        scale: Scale::Linear,
        series: curves
            .iter()
            .map(|(name, y)| Series {
                name: (*name).into(),
                points: rows.iter().filter_map(|r| y(r).map(|v| (x(r), v))).collect(),
            })
            .collect(),
    }
}

/// The model with its bushings rigid, for a model with elastic beams and bushings
/// ([`GeneralCorner::with_rigid_bushings`](crate::description::GeneralCorner::with_rigid_bushings)).
pub(super) fn with_rigid_bushings(file: &SuspensionFile) -> Option<SuspensionFile> {
    let general = file.suspension.expand().with_rigid_bushings()?;
    Some(SuspensionFile { suspension: crate::description::Template::General(Box::new(general)), ..file.clone() })
}

/// Adds to `report` its figure `key` of the model with the bushings rigid (`rigid`: that analysis) and the
/// bushings' share of it, `1 − rigid/figure`: how much of the `what` the bushings' give makes. The share's
/// error estimate follows from the two figures' own.
pub(super) fn bushings_share(report: &mut AnalysisReport, key: &str, what: &str, rigid: Result<AnalysisReport, Cause>) {
    let Some(own) = report.figures.iter().find(|f| f.key == key).cloned() else { return };
    let stiff = rigid.as_ref().map_err(Cause::to_string).and_then(|r| {
        r.figures.iter().find(|f| f.key == key).cloned().ok_or_else(|| format!("no {what} with the bushings rigid"))
    });
    let why = |e: &str| format!("with the bushings rigid the analysis gives none: {e}");
    let (value, reason) = match &stiff {
        Ok(f) => (f.value, f.reason.clone().unwrap_or_default()),
        Err(e) => (None, why(e)),
    };
    let label = format!("{} with the bushings rigid", own.label);
    let mut rigid_figure =
        Figure::maybe(&format!("{key}_rigid_bushings"), &label, own.unit, own.decimals, value, &reason);
    // A figure its own error estimate does not tell from zero has no share of anything.
    let nil = own.value.zip(own.error).is_some_and(|(v, e)| v.abs() <= e);
    let pair = stiff.as_ref().ok().filter(|_| !nil).and_then(|f| Some((own.value?, f.value?, own.error, f.error)));
    rigid_figure.error = stiff.as_ref().ok().and_then(|f| f.error);
    let mut share = Figure::maybe(
        &format!("bushing_share_of_{key}"),
        &format!("the bushings' share of the {what}"),
        Unit::Percent,
        1,
        pair.map(|(f, r, _, _)| 1.0 - r / f).filter(|v| v.is_finite()),
        &match (&stiff, own.value) {
            (Err(e), _) => why(e),
            (_, Some(0.0)) => "the figure is zero".to_string(),
            _ if nil => "the figure is zero within its error estimate".to_string(),
            _ => "the figure or its rigid counterpart has no value".to_string(),
        },
    );
    // Only a share that has a value has an estimate: of a figure that is zero it would be 0/0.
    share.error = share
        .value
        .and(pair)
        .and_then(|(f, r, ef, er)| Some(er? / f.abs() + r.abs() * ef? / (f * f)))
        .filter(|e| e.is_finite());
    report.figures.push(rigid_figure);
    report.figures.push(share);
}

/// The drive shaft the file's vehicle section names, on `wheel` of a model at its design `poses`: `None`
/// when it names none; a warning instead when its outer joint is off the wheel's spin axis.
pub(super) fn drive_shaft(
    file: &SuspensionFile,
    wheel: &Wheel,
    poses: &[elastokin_core::Pose],
) -> Result<Option<crate::wheel::DriveShaft>, Warning> {
    let Some(shaft) = file.vehicle.as_ref().and_then(|v| v.half_shaft) else { return Ok(None) };
    crate::wheel::DriveShaft::on(&shaft, wheel, poses).map(Some).map_err(|off| Warning {
        code: "half-shaft-off-axis",
        hardpoints: Vec::new(),
        message: format!(
            "vehicle.half_shaft.outer is {:.1} mm off the wheel's spin axis: a driven wheel's outer joint sits on \
             it; give its centre on the axis (the half-shaft columns are left out)",
            off * 1e3
        ),
    })
}

/// The half-shaft columns of rows whose wheel `attitude` on `side` carries `shaft`, their names after
/// `prefix` (`""`, `"left_"`): plunge (m), the inner and outer joints' angles (deg).
pub(super) fn half_shaft_columns<'a, R: 'a>(
    prefix: &str,
    shaft: crate::wheel::DriveShaft,
    side: crate::description::Side,
    attitude: impl Fn(&R) -> &crate::wheel::WheelAttitude + Copy + 'a,
) -> Vec<Column<'a, R>> {
    let read = move |r: &R| shaft.at(side, attitude(r));
    vec![
        Column::new(format!("{prefix}half_shaft_plunge_m"), move |r: &R| read(r).plunge.into()),
        Column::new(format!("{prefix}half_shaft_inner_angle_deg"), move |r: &R| deg(read(r).inner_angle).into()),
        Column::new(format!("{prefix}half_shaft_outer_angle_deg"), move |r: &R| deg(read(r).outer_angle).into()),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figure_error_at_a_zero_figure_is_given_in_its_unit_not_as_infinite_percent() {
        let mut f = Figure::new("roll_centre_lateral", "roll centre lateral offset", Unit::Millimetre, 1, 0.0);
        f.error = Some(3e-3);
        let line = over_tolerance(&f, 5e-3).unwrap();
        assert_eq!(line, "roll centre lateral offset ±3.00e0 mm");
        // A huge relative error is no percentage either (it printed 300 digits).
        f.value = Some(1e-300);
        assert!(!over_tolerance(&f, 5e-3).unwrap().contains('%'));
        f.value = Some(20e-3);
        assert_eq!(over_tolerance(&f, 5e-3).unwrap(), "roll centre lateral offset ±15.0 %");
        f.error = Some(0.01e-3);
        assert_eq!(over_tolerance(&f, 5e-3), None);
    }
}
