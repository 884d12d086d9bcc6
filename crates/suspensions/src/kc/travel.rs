//! The driven K&C tests: parallel wheel travel on a corner, roll and steering on the full axle.

use crate::analysis::anti_pitch::anti_pitch_at;
use crate::analysis::compliance::{compliance_at, compliance_with, patch_compliance_from};
use crate::analysis::{axle_sweep_with, AxleRow};
use crate::analysis::{parallel_wheel_travel_with, TravelRow};
use crate::assembly::{AxleRig, Corner, Rig};
use crate::description::Side;
use crate::file::SuspensionFile;
use crate::kc::chart::Chart;
use crate::kc::figures;
use crate::kc::models::Models;
use crate::kc::reduce::{
    axis, axle_drawing, bushings_share, chart, corner_drawing, deg, finish, needs_vehicle, Design, Reduction,
};
use crate::kc::report::{slug, AnalysisReport, Cell, Column, Figure, FigureKind, Table, Warning};
use crate::kc::settings::{Analysis, Cause, Settings, NO_ROWS};
use crate::kc::unit::Unit;
use elastokin_solver::replay::ReplayRows;

pub(super) fn parallel_travel(models: &Models, s: &Settings) -> Result<AnalysisReport, Cause> {
    let file = models.file();
    let range = Analysis::ParallelTravel.range_or_default(s.range)?;
    let corner = models.corner_ref(Rig::WheelTravel)?;
    let out =
        parallel_wheel_travel_with(corner, range.0, range.1, s.steps, s.mode, s.extras_reading(range, 0.0, NO_ROWS))?;
    let wheel = &corner.wheel;
    let sign = wheel.side.sign();
    let table = |rows: &[TravelRow]| parallel_travel_table(corner, rows);
    let figures = |_: &[TravelRow], design: Design<TravelRow>| parallel_travel_figures(file, corner, design);
    let x = |r: &TravelRow| r.travel * 1e3;
    let charts = vec![
        chart(
            file,
            "parallel_travel_toe_camber",
            "toe and camber in parallel wheel travel",
            "wheel travel [mm], bump +",
            axis(
                "angle [deg]",
                &out.rows,
                x,
                &[
                    ("toe (in +)", &|r: &TravelRow| Some(deg(r.attitude.toe))),
                    ("camber (top out +)", &|r: &TravelRow| Some(deg(r.attitude.camber))),
                ],
            ),
            None,
            Some(0.0),
        ),
        chart(
            file,
            "parallel_travel_wheel_centre",
            "wheel-centre motion in parallel wheel travel",
            "wheel travel [mm], bump +",
            axis(
                "displacement [mm]",
                &out.rows,
                x,
                &[
                    ("half-track change (out +)", &|r: &TravelRow| {
                        Some(sign * (r.steering.contact_patch.y - wheel.contact_patch.y) * 1e3)
                    }),
                    ("wheelbase change (forward +)", &|r: &TravelRow| {
                        Some((r.attitude.wheel_centre.x - wheel.wheel_centre.x) * 1e3)
                    }),
                ],
            ),
            Some(axis("wheel load [N]", &out.rows, x, &[("wheel load", &|r: &TravelRow| Some(r.wheel_load))])),
            Some(0.0),
        ),
    ];
    let description =
        format!("parallel wheel travel {:+.0}..{:+.0} mm, {} steps", range.0 * 1e3, range.1 * 1e3, s.steps);
    let mut report = finish(
        Analysis::ParallelTravel,
        description,
        range,
        s,
        &out,
        Reduction { table: &table, figures: &figures, drawing: corner_drawing(corner, s) },
        charts,
    );
    // Toe, camber and wheel rate no car has, inside the travel asked for.
    report.warnings.extend(crate::check::check_travel_rows(&out.rows));
    // Figures of the design position itself, from the tangent there (not read off the rows): at the
    // equilibrium, and one exact Newton iteration on for their error estimate.
    let mut design = compliance_at(corner, 0.0)?;
    let compliance = design.wheel;
    // The joints alone may hold the patch inboard or rearward (ideal joints, no bushing in the load path):
    // the compliance that way is then rounding, and its inverse no stiffness. Decided once by a recording,
    // for its replays (a property of the joints' form).
    let inboard = elastokin_core::Vec3::new(0.0, -corner.wheel.side.sign(), 0.0);
    let rearward = elastokin_core::Vec3::new(-1.0, 0.0, 0.0);
    let held = elastokin_solver::replay::decided(|| {
        crate::assembly::mobility::holds_point(
            &corner.model,
            corner.wheel.upright,
            corner.wheel.contact_patch,
            &[inboard, rearward],
        )
    });
    let read =
        |solver: &mut _, state: &_, compliance: &_| compliance_figures(corner, file, &held, solver, state, compliance);
    let mut figures = read(&mut design.solver, &design.state, &compliance)?;
    if s.error_estimate {
        let next = design.solver.newton_correction(&design.at)?;
        let state = design.solver.state_of(&next);
        let wheel = compliance_with(&mut design.solver, &corner.wheel, corner.partner.as_ref(), &state)?;
        let again = read(&mut design.solver, &state, &wheel)?;
        for (f, g) in figures.iter_mut().zip(again) {
            f.error = f.value.zip(g.value).map(|(a, b)| (a - b).abs());
        }
    }
    report.figures.extend(figures);
    // JSON has no NaN: a matrix with a non-finite entry (a motion nothing holds) is left out, and said so.
    if compliance.iter().flatten().all(|v| v.is_finite()) {
        report.wheel_compliance_at_design = Some(compliance);
    } else {
        report.warnings.push(Warning {
            code: "compliance-not-finite",
            hardpoints: Vec::new(),
            message: "the wheel compliance at design is not finite: some motion of the wheel is held by \
                      nothing; run `elastokin check` on the model"
                .into(),
        });
    }
    Ok(report)
}

/// The parallel-travel figures read off the tangent at an equilibrium `state` of `corner` (`solver` has
/// its tangent factorized there, and `compliance` is the wheel's): the compliances at the patch, its
/// stiffnesses (none the way the joints alone hold it, `held` inboard and rearward), and with a vehicle
/// section the anti-pitch and swing-arm angles from the path's tangent.
fn compliance_figures(
    corner: &Corner,
    file: &SuspensionFile,
    held: &[bool],
    solver: &mut elastokin_solver::StaticSolver,
    state: &elastokin_solver::State,
    compliance: &[[f64; 6]; 6],
) -> Result<Vec<Figure>, elastokin_solver::SolverError> {
    let pc = patch_compliance_from(corner, compliance, &state.poses);
    let finite = compliance.iter().flatten().all(|v| v.is_finite());
    let stiffness = |kind: &FigureKind, n_per_m: f64, rigid: bool| {
        let value = (finite && !rigid && n_per_m.is_finite()).then_some(n_per_m);
        let reason = if rigid {
            "rigid: the joints alone hold the patch this way (no bushing or spring yields to the force)"
        } else {
            "the wheel compliance at design is not finite: some motion of the wheel is held by nothing"
        };
        Figure::of(kind, value, reason)
    };
    let mut figures = vec![
        Figure::of(&figures::LATERAL_STEER, Some(pc.lateral_steer), ""),
        Figure::of(&figures::LATERAL_CAMBER, Some(pc.lateral_camber), ""),
        Figure::of(&figures::BRAKING_STEER, Some(pc.braking_steer), ""),
        Figure::of(&figures::ALIGNING_TORQUE_STEER, Some(pc.aligning_torque_steer), ""),
        stiffness(&figures::LATERAL_STIFFNESS, pc.lateral_stiffness, held[0]),
        stiffness(&figures::LONGITUDINAL_STIFFNESS, pc.longitudinal_stiffness, held[1]),
    ];
    match &file.vehicle {
        Some(vehicle) => {
            let rates = solver.path_tangent_factored()?;
            let a = anti_pitch_at(corner, vehicle, &state.poses, &rates)?;
            let (braking, traction) = match vehicle.axle {
                crate::description::AxlePosition::Front => ("anti-dive", "anti-lift (drive)"),
                crate::description::AxlePosition::Rear => ("anti-lift (braking)", "anti-squat"),
            };
            figures.extend([
                Figure::of(&figures::BRAKING_ANTI_PITCH, Some(a.braking), "").labelled(braking),
                Figure::of(&figures::TRACTION_ANTI_PITCH, Some(a.traction), "").labelled(traction),
                Figure::of(&figures::SWING_ARM_ANGLE_AT_PATCH, Some(a.patch_swing_arm_angle), ""),
                Figure::of(&figures::SWING_ARM_ANGLE_AT_WHEEL_CENTRE, Some(a.wheel_centre_swing_arm_angle), ""),
            ]);
        }
        None => figures.push(Figure::of(
            &figures::BRAKING_ANTI_PITCH,
            None,
            &needs_vehicle("wheelbase and cg_height (a vehicle section)"),
        )),
    }
    Ok(figures)
}

/// Camber of a wheel relative to the ground when the body rolls by `roll` (about +x) relative to it:
/// the roll tips the top of the left wheel inboard (−y) and the right wheel's outboard.
fn ground_camber(camber_to_body: f64, side: Side, roll: f64) -> f64 {
    camber_to_body - side.sign() * roll
}

/// The parallel-travel table of `rows` of `corner` (half-track and wheelbase change from its design wheel).
fn parallel_travel_table(corner: &Corner, rows: &[TravelRow]) -> Table {
    let wheel = &corner.wheel;
    let sign = wheel.side.sign();
    Table::numbers(
        "parallel_travel",
        [
            "travel_m",
            "toe_deg",
            "camber_deg",
            "wheel_centre_x_m",
            "wheel_centre_y_m",
            "wheel_centre_z_m",
            "half_track_change_m",
            "wheelbase_change_m",
            "caster_deg",
            "kingpin_inclination_deg",
            "scrub_radius_m",
            "mechanical_trail_m",
            "kingpin_offset_m",
            "wheel_load_n",
            "spring_deflection_m",
        ],
        rows.iter().map(|r| {
            let (w, g) = (r.attitude.wheel_centre, r.steering);
            [
                r.travel,
                deg(r.attitude.toe),
                deg(r.attitude.camber),
                w.x,
                w.y,
                w.z,
                sign * (g.contact_patch.y - wheel.contact_patch.y),
                w.x - wheel.wheel_centre.x,
                deg(g.caster),
                deg(g.kingpin_inclination),
                g.scrub_radius,
                g.mechanical_trail,
                g.kingpin_offset,
                r.wheel_load,
                r.spring_deflection,
            ]
        }),
    )
}

/// The parallel-travel headline figures of `corner` read at design, of the model in `file` (its tyre rate):
/// rates and values at design.
fn parallel_travel_figures(file: &SuspensionFile, corner: &Corner, design: Design<TravelRow>) -> Vec<Figure> {
    let tyre_rate = file.vehicle.as_ref().and_then(|v| v.tyre_rate);
    let why = design.err().unwrap_or_default();
    let slope = |y: &dyn Fn(&TravelRow) -> f64| design.ok().map(|d| d.rate(y));
    let at_design =
        |kind: &FigureKind, y: &dyn Fn(&TravelRow) -> f64| Figure::of(kind, design.ok().map(|d| y(&d.row)), why);
    let rate = slope(&|r| r.wheel_load);
    let mut f = vec![
        Figure::of(&figures::BUMP_STEER, slope(&|r| r.attitude.toe), why),
        Figure::of(&figures::CAMBER_GAIN, slope(&|r| r.attitude.camber), why),
        Figure::of(&figures::WHEEL_RATE, rate, why),
        match corner.spring {
            Some(_) => Figure::of(&figures::SPRING_MOTION_RATIO, slope(&|r| r.spring_deflection).map(f64::abs), why),
            None => Figure::of(
                &figures::SPRING_MOTION_RATIO,
                None,
                "the corner has no spring of its own (corner springs: none)",
            ),
        },
    ];
    f.push(match (rate, tyre_rate) {
        (Some(k), Some(kt)) => Figure::of(&figures::RIDE_RATE, Some(k * kt / (k + kt)), ""),
        (None, _) => Figure::of(&figures::RIDE_RATE, None, why),
        (_, None) => Figure::of(&figures::RIDE_RATE, None, &needs_vehicle("tyre_rate")),
    });
    f.extend([
        at_design(&figures::WHEEL_LOAD_AT_DESIGN, &|r| r.wheel_load),
        at_design(&figures::CASTER, &|r| r.steering.caster),
        at_design(&figures::KINGPIN_INCLINATION, &|r| r.steering.kingpin_inclination),
        at_design(&figures::SCRUB_RADIUS, &|r| r.steering.scrub_radius),
        at_design(&figures::MECHANICAL_TRAIL, &|r| r.steering.mechanical_trail),
        at_design(&figures::KINGPIN_OFFSET, &|r| r.steering.kingpin_offset),
    ]);
    f
}

pub(super) fn roll(models: &Models, s: &Settings) -> Result<AnalysisReport, Cause> {
    let file = models.file();
    let range = Analysis::Roll.range_or_default(s.range)?;
    let axle = models.axle_ref(AxleRig::OppositeTravel)?;
    let has_bars = !axle.anti_roll_bars.is_empty();
    // The shared beams' names as keys and columns: a twist-beam axle's cross member is read in roll.
    let members: Vec<(&str, String)> = axle.members.iter().map(|m| (m.name.as_str(), slug(&m.name))).collect();
    let out = axle_sweep_with(axle, range.0, range.1, s.steps, s.mode, s.extras_reading(range, 0.0, NO_ROWS))?;
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
        bushings_share(&mut report, "roll_steer", "roll steer", roll(rigid, &Settings { motion: false, ..*s }));
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

/// The steering table of `rows`: steer angles, and Ackermann's ideal outer steer and the error from it
/// where the `wheelbase` is known (with the contact patches' `track` at design).
fn steering_table(rows: &[AxleRow], track: f64, wheelbase: Option<f64>) -> Table {
    let a = move |r: &AxleRow| wheelbase.and_then(|l| ackermann(r, track, l));
    let columns: Vec<Column<AxleRow>> = vec![
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
    Table::of_columns("steering", &columns, rows)
}

/// The steering figures: the steer per rack travel at design, the steering ratio (with the rack's travel
/// per turn of the hand wheel, `c_factor`), and Ackermann at full steer and its largest error, read off the
/// rows, where the `wheelbase` is known.
fn steering_figures(
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
            elastokin_solver::replay::rows_read(&named);
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

/// Ackermann figures of one steering row: `(inner, outer, ideal outer)` steer angles (rad, positive);
/// `None` straight ahead.
fn ackermann(r: &AxleRow, track: f64, wheelbase: f64) -> Option<(f64, f64, f64)> {
    let (left, right) = (steer_angle(r.left.toe, Side::Left), steer_angle(r.right.toe, Side::Right));
    // Turning left, the left wheel is the inner one.
    let (inner, outer) = if left + right > 0.0 { (left, right) } else { (-right, -left) };
    (0.5 * (left + right).abs() > STRAIGHT_AHEAD && inner > 0.0)
        .then(|| (inner, outer, ideal_outer_steer(inner, track, wheelbase)))
}

pub(super) fn steering(models: &Models, s: &Settings) -> Result<AnalysisReport, Cause> {
    let file = models.file();
    let range = Analysis::Steering.range_or_default(s.range)?;
    let axle = models.axle_ref(AxleRig::Steering)?;
    // Besides the readings at design, the figures read the row of full steer and that of the largest
    // Ackermann error, found by their values (named below).
    let rows = ReplayRows { near: None, last: false, extremes: true };
    let out = axle_sweep_with(axle, range.0, range.1, s.steps, s.mode, s.extras_reading(range, 0.0, rows))?;
    let wheelbase = file.vehicle.as_ref().map(|v| v.wheelbase);
    // Track between the contact patches at design: the lateral distance Ackermann's rule uses.
    let track = axle.left.contact_patch.y - axle.right.contact_patch.y;
    let table = |rows: &[AxleRow]| steering_table(rows, track, wheelbase);
    let c_factor = file.vehicle.as_ref().and_then(|v| v.rack_travel_per_revolution);
    let figures =
        |rows: &[AxleRow], design: Design<AxleRow>| steering_figures(rows, design, track, wheelbase, c_factor);
    let x = |r: &AxleRow| r.travel * 1e3;
    let charts = vec![chart(
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
    let description =
        format!("steering (rack {:+.0}..{:+.0} mm, heights held), {} steps", range.0 * 1e3, range.1 * 1e3, s.steps);
    let reduce = Reduction { table: &table, figures: &figures, drawing: axle_drawing(axle, s) };
    Ok(finish(Analysis::Steering, description, range, s, &out, reduce, charts))
}
