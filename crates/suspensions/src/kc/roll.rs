//! Roll: opposite wheel travel on the full axle, the body rolling relative to the wheels; the roll
//! centre, roll steer and camber, and the roll stiffness with its anti-roll bars' share.

use crate::analysis::{axle_sweep_with, AxleRow};
use crate::assembly::AxleRig;
use crate::description::Side;
use crate::file::SuspensionFile;
use crate::kc::chart::Chart;
use crate::kc::figures;
use crate::kc::models::Models;
use crate::kc::reduce::{axis, axle_drawing, bushings_share, chart, deg, finish, Design, Reduction};
use crate::kc::report::{slug, AnalysisReport, Cell, Column, Figure, Table};
use crate::kc::settings::{Analysis, Cause, Declaration, DefaultRange, FigureRows, Quantity, Settings};
use crate::kc::unit::Unit;
use elastokin_solver::replay::Taping;

/// Roll, as the command and the reports name it.
pub(super) const DECLARATION: Declaration = Declaration {
    name: "roll",
    parameter: "left wheel travel, m (right opposite)",
    quantity: Quantity::Travel,
    rig_words: Some("full axle"),
    default_range: DefaultRange::Ends(-0.05, 0.05),
    design_parameter: Some(0.0),
    figure_rows: FigureRows::DesignOnly,
};

/// Camber of a wheel relative to the ground when the body rolls by `roll` (about +x) relative to it:
/// the roll tips the top of the left wheel inboard (−y) and the right wheel's outboard.
fn ground_camber(camber_to_body: f64, side: Side, roll: f64) -> f64 {
    camber_to_body - side.sign() * roll
}

pub(super) fn roll(models: &Models, s: &Settings, taping: &Taping) -> Result<AnalysisReport, Cause> {
    let file = models.file();
    let range = Analysis::Roll.range_or_default(s.range)?;
    let axle = models.axle_ref(AxleRig::OppositeTravel)?;
    let has_bars = !axle.anti_roll_bars.is_empty();
    // The shared beams' names as keys and columns: a twist-beam axle's cross member is read in roll.
    let members: Vec<(&str, String)> = axle.members.iter().map(|m| (m.name.as_str(), slug(&m.name))).collect();
    let out = axle_sweep_with(
        axle,
        range.0,
        range.1,
        s.steps,
        s.mode,
        s.extras_reading(range, 0.0, DECLARATION.figure_rows, taping),
    )?;
    let table = |rows: &[AxleRow]| roll_table(rows, &members);
    let figures = |_: &[AxleRow], design: Design<AxleRow>| roll_figures(design, &members, has_bars);
    let charts = roll_charts(file, &out.rows);
    let description = format!(
        "roll (opposite wheel travel {:+.0}..{:+.0} mm on the full axle), {} steps",
        range.0 * 1e3,
        range.1 * 1e3,
        s.steps
    );
    let reduce = Reduction { table: &table, figures: &figures, drawing: axle_drawing(axle, s) };
    let mut report = finish(Analysis::Roll, description, range, s, &out, reduce, charts);
    if let Some(rigid) = models.rigid() {
        bushings_share(&mut report, "roll_steer", "roll steer", roll(rigid, &Settings { motion: false, ..*s }, taping));
    }
    Ok(report)
}

/// The roll table of `rows`, with a twist column per shared beam of `members` (name, key).
fn roll_table(rows: &[AxleRow], members: &[(&str, String)]) -> Table {
    let ground = |side: Side| {
        move |r: &AxleRow| {
            let camber = if side == Side::Left { r.left.camber } else { r.right.camber };
            Cell::from(deg(ground_camber(camber, side, r.roll_angle)))
        }
    };
    let mut columns: Vec<Column<AxleRow>> = vec![
        Column::new("left_travel_m", |r: &AxleRow| r.travel.into()),
        Column::new("roll_angle_deg", |r: &AxleRow| deg(r.roll_angle).into()),
        Column::new("left_toe_deg", |r: &AxleRow| deg(r.left.toe).into()),
        Column::new("left_camber_deg", |r: &AxleRow| deg(r.left.camber).into()),
        Column::new("left_camber_to_ground_deg", ground(Side::Left)),
        Column::new("right_toe_deg", |r: &AxleRow| deg(r.right.toe).into()),
        Column::new("right_camber_deg", |r: &AxleRow| deg(r.right.camber).into()),
        Column::new("right_camber_to_ground_deg", ground(Side::Right)),
        Column::new("track_m", |r: &AxleRow| r.track.into()),
        Column::new("roll_centre_lateral_m", |r: &AxleRow| Cell::from(r.roll_centre.map(|c| c.lateral))),
        Column::new("roll_centre_height_m", |r: &AxleRow| Cell::from(r.roll_centre.map(|c| c.height))),
        Column::new("left_wheel_load_n", |r: &AxleRow| r.left_load.into()),
        Column::new("right_wheel_load_n", |r: &AxleRow| r.right_load.into()),
        Column::new("roll_moment_nm", |r: &AxleRow| r.roll_moment.into()),
        Column::new("anti_roll_bar_energy_j", |r: &AxleRow| r.anti_roll_bar_energy.into()),
    ];
    columns.extend(members.iter().enumerate().map(|(k, (_, key))| {
        Column::new(format!("{key}_twist_deg"), move |r: &AxleRow| Cell::from(r.member_twists.get(k).map(|&t| deg(t))))
    }));
    Table::of_columns("roll", &columns, rows)
}

/// The roll figures read at design: the track, the roll centre, roll steer and camber, the roll stiffness
/// and the bars' share of it, and each shared beam's twist per degree of roll.
fn roll_figures(design: Design<AxleRow>, members: &[(&str, String)], has_bars: bool) -> Vec<Figure> {
    let why = design.err().unwrap_or_default().to_string();
    let rc = design.ok().map(|d| d.row.roll_centre);
    let rc_why = if rc.is_some() {
        "the front-view lines through the contact patches are parallel: no roll centre".to_string()
    } else {
        why.clone()
    };
    let rc = rc.flatten();
    let slope = |y: &dyn Fn(&AxleRow) -> f64| design.ok().map(|d| d.rate(y));
    let dphi = slope(&|r| r.roll_angle);
    // Wheels that travel opposite without rolling the axle (its track folded to nothing): no figure is
    // per degree of roll.
    let rolls = dphi.is_some_and(|d| d.is_finite() && d != 0.0);
    let roll_why = if dphi.is_some() && !rolls {
        "the body does not roll as the wheels travel opposite (the roll angle does not change at design): \
         check the track in the hardpoints"
            .to_string()
    } else {
        why.clone()
    };
    let per_roll = |d: Option<f64>| Some(d? / dphi?).filter(|v| v.is_finite());
    // N·m/rad: the wheel loads' moment against the roll angle.
    let total = per_roll(slope(&|r| r.roll_moment)).map(|k| -k);
    // The bars' roll stiffness is their energy's second derivative against the roll angle along the
    // path: d²U/dφ² = (U_tt − U_t φ_tt / φ_t) / φ_t².
    let bars = design.ok().filter(|_| has_bars).and_then(|d| {
        let (u, phi) = (|r: &AxleRow| r.anti_roll_bar_energy, |r: &AxleRow| r.roll_angle);
        let (du, dphi) = (d.rate(u), d.rate(phi));
        let k = (d.curvature(u) - du * d.curvature(phi) / dphi) / (dphi * dphi);
        k.is_finite().then_some(k)
    });
    let bar_why = if !has_bars {
        "the model has no anti-roll bar".to_string()
    } else if design.is_ok() && !rolls {
        roll_why.clone()
    } else if design.is_ok() {
        "the anti-roll bars' energy has no finite second derivative against the roll at design".to_string()
    } else {
        why.clone()
    };
    let twists = members.iter().enumerate().map(|(k, (name, key))| {
        Figure::maybe(
            &format!("{key}_twist_per_roll"),
            &format!("{name}: twist per degree of roll"),
            Unit::DegreePerDegree,
            3,
            per_roll(slope(&|r| r.member_twists[k])),
            &roll_why,
        )
    });
    let mut figures = vec![
        Figure::of(&figures::TRACK, design.ok().map(|d| d.row.track), &why),
        Figure::of(&figures::ROLL_CENTRE_HEIGHT, rc.map(|c| c.height), &rc_why),
        Figure::of(&figures::ROLL_CENTRE_LATERAL, rc.map(|c| c.lateral), &rc_why),
        Figure::of(&figures::ROLL_STEER, per_roll(slope(&|r| r.left.toe)), &roll_why),
        Figure::of(
            &figures::ROLL_CAMBER,
            per_roll(slope(&|r| ground_camber(r.left.camber, Side::Left, r.roll_angle))),
            &roll_why,
        ),
        Figure::of(&figures::ROLL_STIFFNESS, total, &roll_why),
        Figure::of(&figures::ANTI_ROLL_BAR_ROLL_STIFFNESS, bars, &bar_why),
        Figure::of(
            &figures::ANTI_ROLL_BAR_SHARE,
            bars.zip(total).map(|(b, t)| b / t).filter(|v| v.is_finite()),
            if has_bars && total == Some(0.0) { "the roll stiffness is zero" } else { &bar_why },
        ),
    ];
    figures.extend(twists);
    figures
}

/// The roll charts of `rows`: toe and camber, and the roll centre, against the body's roll.
fn roll_charts(file: &SuspensionFile, rows: &[AxleRow]) -> Vec<Chart> {
    let x = |r: &AxleRow| deg(r.roll_angle);
    vec![
        chart(
            file,
            "roll_toe_camber",
            "toe and camber in roll",
            "body roll [deg], left side up +",
            axis(
                "angle [deg]",
                rows,
                x,
                &[
                    ("left toe", &|r: &AxleRow| Some(deg(r.left.toe))),
                    ("right toe", &|r: &AxleRow| Some(deg(r.right.toe))),
                    ("left camber to ground", &|r: &AxleRow| {
                        Some(deg(ground_camber(r.left.camber, Side::Left, r.roll_angle)))
                    }),
                    ("right camber to ground", &|r: &AxleRow| {
                        Some(deg(ground_camber(r.right.camber, Side::Right, r.roll_angle)))
                    }),
                ],
            ),
            None,
            Some(0.0),
        ),
        chart(
            file,
            "roll_centre",
            "roll centre in roll",
            "body roll [deg], left side up +",
            axis(
                "roll centre height above ground [mm]",
                rows,
                x,
                &[("height", &|r: &AxleRow| r.roll_centre.map(|c| c.height * 1e3))],
            ),
            Some(axis(
                "roll centre lateral position [mm], left +",
                rows,
                x,
                &[("lateral position", &|r: &AxleRow| r.roll_centre.map(|c| c.lateral * 1e3))],
            )),
            Some(0.0),
        ),
    ]
}
