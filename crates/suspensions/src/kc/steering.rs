//! Steering: rack travel on the full axle, wheel-centre heights held; the steer angles, the steering
//! ratio and the Ackermann error.

use crate::analysis::{axle_sweep_with, AxleRow};
use crate::assembly::AxleRig;
use crate::description::Side;
use crate::file::SuspensionFile;
use crate::kc::chart::Chart;
use crate::kc::figures;
use crate::kc::models::Models;
use crate::kc::reduce::{
    axis, axle_drawing, chart, deg, drive_shaft, finish, half_shaft_columns, needs_vehicle, Curve, Design, Reduction,
};
use crate::kc::report::{AnalysisReport, Cell, Column, Figure, Table};
use crate::kc::settings::{Analysis, Cause, Declaration, DefaultRange, FigureRows, Quantity, Settings};
use crate::wheel::{DriveShaft, WheelAttitude};
use elastokin_solver::replay::Taping;

/// Steering, as the command and the reports name it.
pub(super) const DECLARATION: Declaration = Declaration {
    name: "steering",
    parameter: "rack travel, m, towards +y (left)",
    quantity: Quantity::Travel,
    rig_words: Some("full axle, wheel-centre heights held"),
    default_range: DefaultRange::Ends(RACK_TRAVEL.0, RACK_TRAVEL.1),
    design_parameter: Some(0.0),
    figure_rows: FigureRows::Extremes,
};

/// The rack travel steering walks when none is given (m, towards +y): a car's rack to near full lock.
pub(super) const RACK_TRAVEL: (f64, f64) = (-0.04, 0.04);

/// The steering table of `rows`: steer angles, and Ackermann's ideal outer steer and the error from it
/// where the `wheelbase` is known (with the contact patches' `track` at design), and each wheel's drive
/// shaft of `shafts`.
fn steering_table(rows: &[AxleRow], track: f64, wheelbase: Option<f64>, shafts: &[(Side, DriveShaft)]) -> Table {
    let a = move |r: &AxleRow| wheelbase.and_then(|l| ackermann(r, track, l));
    let mut columns: Vec<Column<AxleRow>> = vec![
        Column::new("rack_travel_m", |r: &AxleRow| r.travel.into()),
        Column::new("left_steer_deg", |r: &AxleRow| deg(steer_angle(r.left.toe, Side::Left)).into()),
        Column::new("right_steer_deg", |r: &AxleRow| deg(steer_angle(r.right.toe, Side::Right)).into()),
        Column::new("left_toe_deg", |r: &AxleRow| deg(r.left.toe).into()),
        Column::new("right_toe_deg", |r: &AxleRow| deg(r.right.toe).into()),
        Column::new("left_camber_deg", |r: &AxleRow| deg(r.left.camber).into()),
        Column::new("right_camber_deg", |r: &AxleRow| deg(r.right.camber).into()),
        Column::new("ideal_outer_steer_deg", move |r: &AxleRow| Cell::from(a(r).map(|(_, _, ideal)| deg(ideal)))),
        Column::new("ackermann_error_deg", move |r: &AxleRow| {
            Cell::from(a(r).map(|(_, outer, ideal)| deg(outer - ideal)))
        }),
        Column::new("ackermann_percent", move |r: &AxleRow| {
            Cell::from(a(r).map(|(inner, outer, ideal)| 100.0 * (inner - outer) / (inner - ideal)))
        }),
    ];
    for &(side, shaft) in shafts {
        let (prefix, attitude): (&str, fn(&AxleRow) -> &WheelAttitude) = match side {
            Side::Left => ("left_", |r| &r.left),
            Side::Right => ("right_", |r| &r.right),
        };
        columns.extend(half_shaft_columns(prefix, shaft, side, attitude));
    }
    Table::of_columns("steering", &columns, rows)
}

/// The steering figures: the steer per rack travel at design, the steering ratio (with the rack's travel
/// per turn of the hand wheel, `c_factor`), and Ackermann at full steer and its largest error, read off the
/// rows, where the `wheelbase` is known. The rows they are read from are named to `taping`.
fn steering_figures(
    taping: &Taping,
    rows: &[AxleRow],
    design: Design<AxleRow>,
    track: f64,
    wheelbase: Option<f64>,
    c_factor: Option<f64>,
) -> Vec<Figure> {
    let why = design.err().unwrap_or_default();
    let mean_steer = |r: &AxleRow| 0.5 * (steer_angle(r.left.toe, Side::Left) + steer_angle(r.right.toe, Side::Right));
    let per_rack = design.ok().map(|d| d.rate(mean_steer));
    let mut f = vec![Figure::of(&figures::STEER_PER_RACK_TRAVEL, per_rack, why)];
    f.push(match (per_rack, c_factor) {
        // A rack that does not steer the wheels at design has no ratio (a hand wheel turning forever).
        (Some(d), Some(_)) if d.abs() < 1e-11 => Figure::of(
            &figures::STEERING_RATIO,
            None,
            "the rack travel does not steer the wheels at design: check the tie rods (tie_rod_inner, \
             tie_rod_outer) and their bushings",
        ),
        // A turn of the hand wheel moves the rack by c, which turns the wheels by c·d.
        (Some(d), Some(c)) => Figure::of(&figures::STEERING_RATIO, Some(std::f64::consts::TAU / (c * d.abs())), ""),
        (None, _) => Figure::of(&figures::STEERING_RATIO, None, why),
        (_, None) => Figure::of(&figures::STEERING_RATIO, None, &needs_vehicle("rack_travel_per_revolution")),
    });
    match wheelbase {
        Some(l) => {
            // At the end of the rack travel that steers most: where Ackermann is read on a rig; and the
            // largest error, the row where it is largest. Both are read off the rows (`every` k-th, the
            // last among them), so they are as fine as the steps: every other row reads them again, and
            // the difference is their discretization's estimate.
            let read = |every: usize| {
                let angles = || {
                    let first = (rows.len() + every - 1) % every;
                    rows.iter()
                        .enumerate()
                        .skip(first)
                        .step_by(every)
                        .filter_map(|(i, r)| Some((i, ackermann(r, track, l)?)))
                };
                let end = angles().max_by(|a, b| a.1 .0.total_cmp(&b.1 .0));
                let worst = angles()
                    .map(|(i, (_, outer, ideal))| (i, outer - ideal))
                    .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()));
                (end, worst)
            };
            let (end, worst) = read(1);
            // A recording's replays move these rows too (they are found by their values).
            let named: Vec<usize> = [end.map(|r| r.0), worst.map(|r| r.0)].into_iter().flatten().collect();
            taping.rows_read(&named);
            let (end, worst) = (end.map(|r| r.1), worst.map(|r| r.1));
            let (coarse_end, coarse_worst) = read(2);
            let (coarse_end, coarse_worst) = (coarse_end.map(|r| r.1), coarse_worst.map(|r| r.1));
            // Steer angles are read from the design's straight ahead: wheels toed in or out at rack
            // centre by more than the rack turns them never both turn one way.
            let turned = rows.iter().any(|r| r.left.toe.abs() > 1e-9 || r.right.toe.abs() > 1e-9);
            let none = if turned {
                "no rack position turns both wheels the same way: their toe at rack centre outweighs the steer \
                 the rack gives (check the tie rods and their bushings)"
            } else {
                "the rack travel steers neither wheel"
            };
            let fraction = |(i, o, ideal): (f64, f64, f64)| (i - o) / (i - ideal);
            let inner = |(i, _, _): (f64, f64, f64)| i;
            let discretized = |mut f: Figure, coarse: Option<f64>| {
                f.error = f.value.zip(coarse).map(|(a, b)| (a - b).abs()).filter(|e| e.is_finite());
                f
            };
            f.push(discretized(Figure::of(&figures::ACKERMANN, end.map(fraction), none), coarse_end.map(fraction)));
            f.push(discretized(
                Figure::of(&figures::INNER_STEER_AT_FULL_RACK, end.map(inner), none),
                coarse_end.map(inner),
            ));
            f.push(discretized(Figure::of(&figures::ACKERMANN_ERROR, worst, none), coarse_worst));
        }
        None => f.push(Figure::of(&figures::ACKERMANN, None, &needs_vehicle("wheelbase")).labelled("Ackermann")),
    }
    f
}

/// Steer angle of a wheel (positive turning left, about +z) from its toe (toe-in positive).
fn steer_angle(toe: f64, side: Side) -> f64 {
    -side.sign() * toe
}

/// The outer wheel's steer angle that ideal (Ackermann) geometry gives for the inner wheel's `inner`
/// (both positive, rad): the two wheels' axes meet on the rear axle line, `cot δo − cot δi = T / L`.
pub fn ideal_outer_steer(inner: f64, track: f64, wheelbase: f64) -> f64 {
    (1.0 / (1.0 / inner.tan() + track / wheelbase)).atan()
}

/// The mean steer angle below which a row counts as straight ahead (rad, 0.01°): there Ackermann's
/// figures are ratios of differences of static toe, noise with no meaning (1e8 % was printed at zero rack
/// travel).
const STRAIGHT_AHEAD: f64 = 1.75e-4;

/// The inner and outer wheels' steer angles of one steering row (rad, positive in the turn); `None`
/// straight ahead.
fn inner_and_outer(r: &AxleRow) -> Option<(f64, f64)> {
    let (left, right) = (steer_angle(r.left.toe, Side::Left), steer_angle(r.right.toe, Side::Right));
    // Turning left, the left wheel is the inner one.
    let (inner, outer) = if left + right > 0.0 { (left, right) } else { (-right, -left) };
    (0.5 * (left + right).abs() > STRAIGHT_AHEAD && inner > 0.0).then_some((inner, outer))
}

/// Ackermann figures of one steering row: `(inner, outer, ideal outer)` steer angles (rad, positive);
/// `None` straight ahead.
fn ackermann(r: &AxleRow, track: f64, wheelbase: f64) -> Option<(f64, f64, f64)> {
    let (inner, outer) = inner_and_outer(r)?;
    Some((inner, outer, ideal_outer_steer(inner, track, wheelbase)))
}

/// The outer wheel's steer against the inner's over the `rows`, both turns folded into one (positive in the
/// turn), with Ackermann's ideal outer steer where the `wheelbase` is known (and the patches' `track`).
fn ackermann_chart(file: &SuspensionFile, rows: &[AxleRow], track: f64, wheelbase: Option<f64>) -> Chart {
    let inner = |r: &AxleRow| inner_and_outer(r).map_or(f64::NAN, |(i, _)| deg(i));
    let outer = |r: &AxleRow| inner_and_outer(r).map(|(_, o)| deg(o));
    let ideal = |r: &AxleRow| Some(deg(ackermann(r, track, wheelbase?)?.2));
    let curves: Vec<Curve<AxleRow>> = match wheelbase {
        Some(_) => vec![("outer wheel", &outer), ("Ackermann's ideal outer wheel", &ideal)],
        None => vec![("outer wheel", &outer)],
    };
    chart(
        file,
        "steering_ackermann",
        "outer against inner wheel steer, and Ackermann's ideal",
        "inner wheel steer [deg]",
        axis("outer wheel steer [deg]", rows, inner, &curves),
        None,
        None,
    )
}

pub(super) fn steering(models: &Models, s: &Settings, taping: &Taping) -> Result<AnalysisReport, Cause> {
    let file = models.file();
    let range = Analysis::Steering.range_or_default(s.range)?;
    let axle = models.axle_ref(AxleRig::Steering)?;
    // Besides the readings at design, the figures read the row of full steer and that of the largest
    // Ackermann error, found by their values (named below).
    let out = axle_sweep_with(
        axle,
        range.0,
        range.1,
        s.steps,
        s.mode,
        s.extras_reading(range, 0.0, DECLARATION.figure_rows, taping),
    )?;
    let wheelbase = file.vehicle.as_ref().map(|v| v.wheelbase);
    // Track between the contact patches at design: the lateral distance Ackermann's rule uses.
    let track = axle.left.contact_patch.y - axle.right.contact_patch.y;
    // The drive shafts of both wheels, when the file names one (mirrored for the right).
    let poses = axle.model.design_poses();
    let (mut shafts, mut shaft_warnings) = (Vec::new(), Vec::new());
    for (side, wheel) in [(Side::Left, &axle.left), (Side::Right, &axle.right)] {
        match drive_shaft(file, wheel, &poses) {
            Ok(shaft) => shafts.extend(shaft.map(|s| (side, s))),
            Err(w) => shaft_warnings.push(w),
        }
    }
    // Both wheels' shafts are off their axes alike (one is the other mirrored): said once.
    shaft_warnings.truncate(1);
    let table = |rows: &[AxleRow]| steering_table(rows, track, wheelbase, &shafts);
    let c_factor = file.vehicle.as_ref().and_then(|v| v.rack_travel_per_revolution);
    let figures =
        |rows: &[AxleRow], design: Design<AxleRow>| steering_figures(taping, rows, design, track, wheelbase, c_factor);
    let x = |r: &AxleRow| r.travel * 1e3;
    let mut charts = vec![chart(
        file,
        "steering",
        "steer angles",
        "rack travel [mm], towards left +",
        axis(
            "steer angle [deg], left turn +",
            &out.rows,
            x,
            &[
                ("left wheel", &|r: &AxleRow| Some(deg(steer_angle(r.left.toe, Side::Left)))),
                ("right wheel", &|r: &AxleRow| Some(deg(steer_angle(r.right.toe, Side::Right)))),
            ],
        ),
        None,
        Some(0.0),
    )];
    charts.push(ackermann_chart(file, &out.rows, track, wheelbase));
    let description =
        format!("steering (rack {:+.0}..{:+.0} mm, heights held), {} steps", range.0 * 1e3, range.1 * 1e3, s.steps);
    let reduce = Reduction { table: &table, figures: &figures, drawing: axle_drawing(axle, s) };
    let mut report = finish(Analysis::Steering, description, range, s, &out, reduce, charts);
    report.warnings.extend(shaft_warnings);
    Ok(report)
}
