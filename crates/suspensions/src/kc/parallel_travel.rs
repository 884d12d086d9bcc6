//! Parallel wheel travel: both wheel-centre heights driven together on a corner; the rates at design
//! (bump steer, camber gain, wheel rate), the steering axis and the compliances there.

use crate::analysis::anti_pitch::anti_pitch_at;
use crate::analysis::compliance::{compliance_at, compliance_with, patch_compliance_from};
use crate::analysis::{
    axle_sweep_with, parallel_wheel_travel_with, AxleRow, InstantCentre, RollCentre, SweepExtras, SweepOutput,
    SwingArms, TravelRow,
};
use crate::assembly::{AxleRig, Corner, Rig};
use crate::file::SuspensionFile;
use crate::kc::chart::Chart;
use crate::kc::figures;
use crate::kc::models::Models;
use crate::kc::reduce::{
    axis, chart, corner_drawing, deg, drive_shaft, finish, half_shaft_columns, needs_vehicle, Design, Reduction,
};
use crate::kc::report::{AnalysisReport, Column, Construction, Figure, FigureKind, Table, Warning};
use crate::kc::settings::{Analysis, Cause, Declaration, DefaultRange, FigureRows, Quantity, Settings};
use crate::wheel::DriveShaft;
use elastokin_solver::replay::Taping;

/// Parallel travel, as the command and the reports name it.
pub(super) const DECLARATION: Declaration = Declaration {
    name: "parallel-travel",
    parameter: "wheel travel, m, bump +",
    quantity: Quantity::Travel,
    rig_words: None,
    default_range: DefaultRange::Ends(-0.08, 0.08),
    design_parameter: Some(0.0),
    figure_rows: FigureRows::DesignOnly,
};

pub(super) fn parallel_travel(models: &Models, s: &Settings, taping: &Taping) -> Result<AnalysisReport, Cause> {
    let file = models.file();
    let range = Analysis::ParallelTravel.range_or_default(s.range)?;
    let corner = models.corner_ref(Rig::WheelTravel)?;
    let out = parallel_wheel_travel_with(
        corner,
        range.0,
        range.1,
        s.steps,
        s.mode,
        s.extras_reading(range, 0.0, DECLARATION.figure_rows, taping),
    )?;
    // Toe, camber and wheel rate no car has, inside the travel asked for.
    let travel_warnings = crate::check::check_travel_rows(&out.rows);
    let axle = axle_in_parallel_travel(models, range, s, taping);
    let (shaft, shaft_warning) = match drive_shaft(file, &corner.wheel, &corner.model.design_poses()) {
        Ok(shaft) => (shaft, None),
        Err(w) => (None, Some(w)),
    };
    let mut charts = parallel_travel_charts(file, corner, &out.rows);
    charts.extend(shaft.map(|shaft| half_shaft_chart(file, corner, shaft, &out.rows)));
    let out = with_roll_centres(out, axle.as_ref().and_then(|a| a.as_ref().ok()));
    charts.push(roll_centre_chart(file, &out.rows));
    let table = |rows: &[Row]| parallel_travel_table(corner, shaft, rows);
    let figures = |_: &[Row], design: Design<Row>| parallel_travel_figures(file, corner, design);
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
    if s.motion {
        report.construction = out.rows.iter().map(construction).collect();
    }
    report.warnings.extend(travel_warnings);
    report.warnings.extend(shaft_warning);
    if let Some(Err(why)) = axle {
        report.warnings.push(Warning {
            code: "no-roll-centre-in-parallel-travel",
            hardpoints: Vec::new(),
            message: format!(
                "parallel-travel: the roll centre columns are empty: the whole axle driven alike gives none ({why})"
            ),
        });
    }
    design_compliance(file, corner, s, taping, &mut report)?;
    Ok(report)
}

/// How far from the patch an instant centre is drawn (m): beyond it the arms are near parallel in that view,
/// and a centre running off towards infinity would flatten the rest of the curve (the table has it).
const DRAWN_REACH: f64 = 100.0;

/// The swing arm of one view (`words`: front or side) over `rows`: its length and its instant centre's
/// height, where the centre lies within [`DRAWN_REACH`].
fn swing_arm_chart(
    file: &SuspensionFile,
    rows: &[TravelRow],
    words: &str,
    view: &dyn Fn(&SwingArms) -> Option<InstantCentre>,
) -> Chart {
    let drawn = |r: &TravelRow| {
        r.swing_arms.as_ref().and_then(view).filter(|c| c.swing_arm_length <= DRAWN_REACH && c.z.abs() <= DRAWN_REACH)
    };
    let x = |r: &TravelRow| r.travel * 1e3;
    chart(
        file,
        &format!("parallel_travel_{words}_view_swing_arm"),
        &format!("{words}-view swing arm in parallel wheel travel (instant centres within {DRAWN_REACH:.0} m drawn)"),
        "wheel travel [mm], bump +",
        axis("swing arm length [mm]", rows, x, &[("length", &|r: &TravelRow| Some(drawn(r)?.swing_arm_length * 1e3))]),
        Some(axis(
            "instant centre height z [mm]",
            rows,
            x,
            &[("instant centre height", &|r: &TravelRow| Some(drawn(r)?.z * 1e3))],
        )),
        Some(0.0),
    )
}

/// A row of parallel travel: the corner's, and the roll centre of the whole axle driven alike at its
/// travel (none where the axle's sweep has no row at that travel, and when the figures alone are read).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Row {
    corner: TravelRow,
    roll_centre: Option<RollCentre>,
}

impl std::ops::Deref for Row {
    type Target = TravelRow;
    fn deref(&self) -> &TravelRow {
        &self.corner
    }
}

/// The construction of `r`'s instant centres, in global coordinates: the roll centre's height is above
/// the ground line through the patches, the patch's z.
fn construction(r: &Row) -> Construction {
    let patch = r.steering.contact_patch;
    let centre = |c: Option<InstantCentre>| c.map(|c| [c.horizontal, c.z]);
    Construction {
        patch: [patch.x, patch.y, patch.z],
        wheel_centre: [r.attitude.wheel_centre.x, r.attitude.wheel_centre.y, r.attitude.wheel_centre.z],
        front_view_centre: centre(r.swing_arms.and_then(|s| s.front)),
        side_view_centre: centre(r.swing_arms.and_then(|s| s.side)),
        roll_centre: r.roll_centre.map(|c| [c.lateral, patch.z + c.height]),
    }
}

/// The whole axle driven alike over the range of parallel travel, its roll centre read at every row; or
/// why it could not be built or walked. Nothing when the figures alone are read: no figure reads it.
fn axle_in_parallel_travel(
    models: &Models,
    range: (f64, f64),
    s: &Settings,
    taping: &Taping,
) -> Option<Result<SweepOutput<AxleRow>, String>> {
    if s.figures_only {
        return None;
    }
    let axle = match models.axle_ref(AxleRig::ParallelTravel) {
        Ok(axle) => axle,
        Err(e) => return Some(Err(e.to_string())),
    };
    let extras = SweepExtras { compliance: false, poses: false, ..s.extras(range, taping) };
    Some(axle_sweep_with(axle, range.0, range.1, s.steps, s.mode, extras).map_err(|e| e.to_string()))
}

/// The corner's sweep `out` with the roll centre of the `axle`'s row at each row's travel (its corrected
/// row at each corrected row's).
fn with_roll_centres(out: SweepOutput<TravelRow>, axle: Option<&SweepOutput<AxleRow>>) -> SweepOutput<Row> {
    let pair = |rows: Vec<TravelRow>, axle_rows: Option<&Vec<AxleRow>>| -> Vec<Row> {
        let centre =
            |k: usize, r: &TravelRow| axle_rows?.get(k).filter(|a| a.travel == r.travel).and_then(|a| a.roll_centre);
        rows.into_iter().enumerate().map(|(k, r)| Row { roll_centre: centre(k, &r), corner: r }).collect()
    };
    let alone = |r: &TravelRow| Row { corner: *r, roll_centre: None };
    SweepOutput {
        rows: pair(out.rows, axle.map(|a| &a.rows)),
        limit: out.limit,
        corrected: out.corrected.map(|c| pair(c, axle.and_then(|a| a.corrected.as_ref()))),
        residuals: out.residuals,
        compliance: out.compliance,
        poses: out.poses,
        design: out.design.map(|d| d.map(|d| d.map(alone))),
        design_corrected: out.design_corrected.map(|d| d.map(alone)),
    }
}

/// The roll centre's height of the whole axle driven alike over parallel travel, from `rows` (its lateral
/// position stays on the centre plane of an axle whose sides mirror each other, the table has it).
fn roll_centre_chart(file: &SuspensionFile, rows: &[Row]) -> Chart {
    chart(
        file,
        "parallel_travel_roll_centre",
        "roll centre in parallel wheel travel (the whole axle)",
        "wheel travel [mm], bump +",
        axis(
            "roll centre height above ground [mm]",
            rows,
            |r: &Row| r.travel * 1e3,
            &[("height", &|r: &Row| r.roll_centre.map(|c| c.height * 1e3))],
        ),
        None,
        Some(0.0),
    )
}

/// The parallel-travel charts of `corner`'s `rows`: toe and camber, the wheel centre's motion with the
/// wheel load, and the swing arms in front and side view.
fn parallel_travel_charts(file: &SuspensionFile, corner: &Corner, rows: &[TravelRow]) -> Vec<Chart> {
    let wheel = &corner.wheel;
    let sign = wheel.side.sign();
    let x = |r: &TravelRow| r.travel * 1e3;
    vec![
        chart(
            file,
            "parallel_travel_toe_camber",
            "toe and camber in parallel wheel travel",
            "wheel travel [mm], bump +",
            axis(
                "angle [deg]",
                rows,
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
                rows,
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
            Some(axis("wheel load [N]", rows, x, &[("wheel load", &|r: &TravelRow| Some(r.wheel_load))])),
            Some(0.0),
        ),
        swing_arm_chart(file, rows, "front", &|a| a.front),
        swing_arm_chart(file, rows, "side", &|a| a.side),
    ]
}

/// The drive shaft's plunge and its joints' angles in parallel travel.
fn half_shaft_chart(file: &SuspensionFile, corner: &Corner, shaft: DriveShaft, rows: &[TravelRow]) -> Chart {
    let side = corner.wheel.side;
    let x = |r: &TravelRow| r.travel * 1e3;
    chart(
        file,
        "parallel_travel_half_shaft",
        "half-shaft joint angles and plunge in parallel wheel travel",
        "wheel travel [mm], bump +",
        axis(
            "joint angle [deg]",
            rows,
            x,
            &[
                ("inner joint", &|r: &TravelRow| Some(deg(shaft.at(side, &r.attitude).inner_angle))),
                ("outer joint", &|r: &TravelRow| Some(deg(shaft.at(side, &r.attitude).outer_angle))),
            ],
        ),
        Some(axis(
            "plunge [mm], longer +",
            rows,
            x,
            &[("plunge", &|r: &TravelRow| Some(shaft.at(side, &r.attitude).plunge * 1e3))],
        )),
        Some(0.0),
    )
}

/// The figures of the design position itself, from the tangent there (not read off the rows): at the
/// equilibrium, and one exact Newton iteration on for their error estimate; and the wheel's compliance
/// matrix there, added to `report`.
fn design_compliance(
    file: &SuspensionFile,
    corner: &Corner,
    s: &Settings,
    taping: &Taping,
    report: &mut AnalysisReport,
) -> Result<(), Cause> {
    let mut design = compliance_at(corner, 0.0, taping)?;
    let compliance = design.wheel;
    // The joints alone may hold the patch inboard or rearward (ideal joints, no bushing in the load path):
    // the compliance that way is then rounding, and its inverse no stiffness. Decided once by a recording,
    // for its replays (a property of the joints' form).
    let inboard = elastokin_core::Vec3::new(0.0, -corner.wheel.side.sign(), 0.0);
    let rearward = elastokin_core::Vec3::new(-1.0, 0.0, 0.0);
    let held = taping.decided(|| {
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
    Ok(())
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

/// The parallel-travel table of `rows` of `corner` (half-track and wheelbase change from its design wheel),
/// with the roll centre of the whole axle.
fn parallel_travel_table(corner: &Corner, shaft: Option<DriveShaft>, rows: &[Row]) -> Table {
    let wheel = &corner.wheel;
    let sign = wheel.side.sign();
    let front = |r: &Row| r.swing_arms.and_then(|s| s.front);
    let side = |r: &Row| r.swing_arms.and_then(|s| s.side);
    let mut columns: Vec<Column<Row>> = vec![
        Column::new("travel_m", |r: &Row| r.travel.into()),
        Column::new("toe_deg", |r: &Row| deg(r.attitude.toe).into()),
        Column::new("camber_deg", |r: &Row| deg(r.attitude.camber).into()),
        Column::new("wheel_centre_x_m", |r: &Row| r.attitude.wheel_centre.x.into()),
        Column::new("wheel_centre_y_m", |r: &Row| r.attitude.wheel_centre.y.into()),
        Column::new("wheel_centre_z_m", |r: &Row| r.attitude.wheel_centre.z.into()),
        Column::new("half_track_change_m", move |r: &Row| {
            (sign * (r.steering.contact_patch.y - wheel.contact_patch.y)).into()
        }),
        Column::new("wheelbase_change_m", |r: &Row| (r.attitude.wheel_centre.x - wheel.wheel_centre.x).into()),
        Column::new("caster_deg", |r: &Row| deg(r.steering.caster).into()),
        Column::new("kingpin_inclination_deg", |r: &Row| deg(r.steering.kingpin_inclination).into()),
        Column::new("scrub_radius_m", |r: &Row| r.steering.scrub_radius.into()),
        Column::new("mechanical_trail_m", |r: &Row| r.steering.mechanical_trail.into()),
        Column::new("kingpin_offset_m", |r: &Row| r.steering.kingpin_offset.into()),
        Column::new("wheel_load_n", |r: &Row| r.wheel_load.into()),
        Column::new("spring_deflection_m", |r: &Row| r.spring_deflection.into()),
        Column::new("front_view_instant_centre_y_m", move |r: &Row| front(r).map(|c| c.horizontal).into()),
        Column::new("front_view_instant_centre_z_m", move |r: &Row| front(r).map(|c| c.z).into()),
        Column::new("front_view_swing_arm_length_m", move |r: &Row| front(r).map(|c| c.swing_arm_length).into()),
        Column::new("side_view_instant_centre_x_m", move |r: &Row| side(r).map(|c| c.horizontal).into()),
        Column::new("side_view_instant_centre_z_m", move |r: &Row| side(r).map(|c| c.z).into()),
        Column::new("side_view_swing_arm_length_m", move |r: &Row| side(r).map(|c| c.swing_arm_length).into()),
        Column::new("roll_centre_lateral_m", |r: &Row| r.roll_centre.map(|c| c.lateral).into()),
        Column::new("roll_centre_height_m", |r: &Row| r.roll_centre.map(|c| c.height).into()),
    ];
    if let Some(shaft) = shaft {
        columns.extend(half_shaft_columns("", shaft, wheel.side, |r: &Row| &r.attitude));
    }
    Table::of_columns("parallel_travel", &columns, rows)
}

/// The parallel-travel headline figures of `corner` read at design, of the model in `file` (its tyre rate):
/// rates and values at design.
fn parallel_travel_figures(file: &SuspensionFile, corner: &Corner, design: Design<Row>) -> Vec<Figure> {
    let tyre_rate = file.vehicle.as_ref().and_then(|v| v.tyre_rate);
    let why = design.err().unwrap_or_default();
    let slope = |y: &dyn Fn(&Row) -> f64| design.ok().map(|d| d.rate(y));
    let at_design = |kind: &FigureKind, y: &dyn Fn(&Row) -> f64| Figure::of(kind, design.ok().map(|d| y(&d.row)), why);
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
    // A view in which the upright does not turn at design has its instant centre at infinity.
    let swing_arm = |kind: &FigureKind, view: &dyn Fn(&SwingArms) -> Option<InstantCentre>, words: &str| {
        let arms = design.ok().and_then(|d| d.row.swing_arms);
        let reason = if arms.is_some() {
            format!("the upright does not turn in the {words} at design (its arms parallel there): no instant centre")
        } else {
            why.to_string()
        };
        Figure::of(kind, arms.as_ref().and_then(view).map(|c| c.swing_arm_length), &reason)
    };
    f.extend([
        swing_arm(&figures::FRONT_VIEW_SWING_ARM_LENGTH, &|a| a.front, "front view"),
        swing_arm(&figures::SIDE_VIEW_SWING_ARM_LENGTH, &|a| a.side, "side view"),
    ]);
    f
}
