//! The K&C tests `elastokin run` offers. Each walks one load path of the engine and reduces it to a table
//! (one CSV), plots (one SVG per curve family), summary figures (JSON) and headline lines for the terminal.

use elastokin::plot::{self, Chart, Scale, Series, YAxis};
use elastokin::solver::Mode;
use elastokin::suspensions::analysis::{
    anti_pitch, design_wheel_load, parallel_wheel_travel, patch_compliance, slope_at, static_load_case,
    vertical_force_sweep, wheel_compliance, wheel_load_sweep, ComponentForces, LoadRow, TravelRow, WheelLoad,
};
use elastokin::suspensions::axle::{axle_sweep, AxleRow};
use elastokin::suspensions::{Axle, AxleRig, Rig, Side, SuspensionFile};
use serde_json::{json, Value};

/// One K&C test.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
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
}

/// Every analysis, in the order `run` performs them by default.
pub const ALL: [Analysis; 9] = [
    Analysis::ParallelTravel,
    Analysis::Roll,
    Analysis::Steering,
    Analysis::VerticalForce,
    Analysis::Road(WheelLoad::Lateral),
    Analysis::Road(WheelLoad::Braking),
    Analysis::Road(WheelLoad::Traction),
    Analysis::Road(WheelLoad::AligningTorque),
    Analysis::StaticLoad,
];

impl Analysis {
    /// The command-line name.
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
        }
    }

    /// The analysis of a command-line name.
    pub fn from_name(name: &str) -> Option<Analysis> {
        ALL.into_iter().find(|a| a.name() == name)
    }

    /// What the load parameter is, for help and reports.
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
        }
    }
}

/// How to walk the path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// `(from, to)` in the analysis's own parameter, or its default.
    pub range: Option<(f64, f64)>,
    /// Load steps.
    pub steps: usize,
    /// Paper or corrected stepping.
    pub mode: Mode,
    /// Road loads: the wheel-centre height held by the rig (`true`) or the wheel free on its spring.
    pub height_held: bool,
}

/// One CSV cell: a number, a name, or nothing (a value the row does not have — never NaN).
#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    /// A number (written with 12 significant digits; a non-finite one is written as an empty cell).
    Number(f64),
    /// A name (quoted where CSV needs it).
    Text(String),
    /// No value.
    Empty,
}

impl From<f64> for Cell {
    fn from(v: f64) -> Cell {
        Cell::Number(v)
    }
}

impl From<Option<f64>> for Cell {
    fn from(v: Option<f64>) -> Cell {
        v.map_or(Cell::Empty, Cell::Number)
    }
}

/// A table of rows, written as CSV by `output::write_table`.
pub struct Table {
    /// File name in the output directory.
    pub file: String,
    /// Column headers, with units.
    pub columns: Vec<String>,
    /// Rows, one cell per column.
    pub rows: Vec<Vec<Cell>>,
}

impl Table {
    /// A table of numbers.
    fn numbers<const N: usize>(file: &str, columns: [&str; N], rows: impl Iterator<Item = [f64; N]>) -> Table {
        Table {
            file: file.into(),
            columns: columns.map(String::from).to_vec(),
            rows: rows.map(|r| r.map(Cell::from).to_vec()).collect(),
        }
    }
}

/// What one analysis produced.
pub struct Report {
    /// Its table.
    pub table: Table,
    /// `(file name, SVG text)` per curve family.
    pub plots: Vec<(String, String)>,
    /// Summary figures (a JSON object).
    pub summary: Value,
    /// Headline lines for the terminal.
    pub headline: Vec<String>,
}

fn deg(rad: f64) -> f64 {
    rad.to_degrees()
}

/// A vertical axis: its label with the unit, and `(legend name, points)` per curve.
fn axis<'a>(label: &str, curves: impl IntoIterator<Item = (&'a str, Vec<(f64, f64)>)>) -> YAxis {
    YAxis {
        label: label.into(),
        scale: Scale::Linear,
        series: curves.into_iter().map(|(name, points)| Series { name: name.into(), points }).collect(),
    }
}

/// `(file name, SVG text)` of one plot: `what` as the title, the model's name under it, the design
/// position marked at `design_x` on the horizontal axis.
fn plot(
    file: &SuspensionFile,
    stem: &str,
    what: &str,
    x_label: &str,
    design_x: f64,
    left: YAxis,
    right: Option<YAxis>,
) -> Result<(String, String), String> {
    let chart = Chart {
        name: stem.into(),
        title: what.into(),
        subtitle: file.name.clone(),
        x_label: x_label.into(),
        x_scale: Scale::Linear,
        left,
        right,
        design_x: Some(design_x),
    };
    let svg = plot::svg(&chart).map_err(|e| format!("{stem}: {e}"))?;
    Ok((format!("{}.svg", chart.name), svg))
}

/// Runs `analysis` on the model in `file`.
pub fn run(analysis: Analysis, file: &SuspensionFile, settings: Settings) -> Result<Report, String> {
    let err = |e: &dyn std::fmt::Display| format!("{}: {e}", analysis.name());
    match analysis {
        Analysis::ParallelTravel => parallel_travel(file, settings).map_err(|e| err(&e)),
        Analysis::Roll => roll(file, settings).map_err(|e| err(&e)),
        Analysis::Steering => steering(file, settings).map_err(|e| err(&e)),
        Analysis::VerticalForce => vertical_force(file, settings).map_err(|e| err(&e)),
        Analysis::Road(load) => road_load(file, load, settings).map_err(|e| err(&e)),
        Analysis::StaticLoad => static_load(file).map_err(|e| err(&e)),
    }
}

fn parallel_travel(file: &SuspensionFile, s: Settings) -> Result<Report, String> {
    let (from, to) = s.range.unwrap_or((-0.08, 0.08));
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel).map_err(|e| e.to_string())?;
    let rows = parallel_wheel_travel(&corner, from, to, s.steps, s.mode).map_err(|e| e.to_string())?;
    let y0 = corner.wheel.wheel_centre.y;
    let table = Table::numbers(
        "parallel_travel.csv",
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
                corner.wheel.side.sign() * (g.contact_patch.y - corner.wheel.contact_patch.y),
                w.x - corner.wheel.wheel_centre.x,
                deg(g.caster),
                deg(g.kingpin_inclination),
                g.scrub_radius,
                g.mechanical_trail,
                g.kingpin_offset,
                r.wheel_load,
                r.spring_deflection,
            ]
        }),
    );
    let curve = |f: &dyn Fn(&TravelRow) -> f64| rows.iter().map(|r| (r.travel * 1e3, f(r))).collect();
    let plots = vec![plot(
        file,
        "parallel_travel_toe_camber",
        "toe and camber in parallel wheel travel",
        "wheel travel [mm], bump +",
        0.0,
        axis(
            "angle [deg]",
            [
                ("toe (in +)", curve(&|r| deg(r.attitude.toe))),
                ("camber (top out +)", curve(&|r| deg(r.attitude.camber))),
            ],
        ),
        None,
    )?];
    let mut summary = json!({ "range_m": [from, to], "steps": s.steps });
    let mut headline =
        vec![format!("parallel wheel travel {:+.0}..{:+.0} mm, {} steps", from * 1e3, to * 1e3, s.steps)];
    headline.push(format!("{:>10} {:>10} {:>12} {:>14}", "travel mm", "toe °", "camber °", "half track Δ mm"));
    for r in rows.iter().step_by((rows.len() / 8).max(1)) {
        headline.push(format!(
            "{:>10.1} {:>10.4} {:>12.4} {:>14.2}",
            r.travel * 1e3,
            deg(r.attitude.toe),
            deg(r.attitude.camber),
            (r.attitude.wheel_centre.y - y0) * corner.wheel.side.sign() * 1e3
        ));
    }
    let slope = |y: &dyn Fn(&TravelRow) -> f64| slope_at(&rows, 0.0, |r| r.travel, y);
    if let (Some(bump), Some(gain)) = (slope(&|r| deg(r.attitude.toe)), slope(&|r| deg(r.attitude.camber))) {
        headline.push(format!("bump steer {:+.4} °/10 mm toe; camber gain {:+.4} °/10 mm", bump * 0.01, gain * 0.01));
        summary["bump_steer_deg_per_m"] = bump.into();
        summary["camber_gain_deg_per_m"] = gain.into();
    }
    if let (Some(rate), Some(ratio)) = (slope(&|r| r.wheel_load), slope(&|r| r.spring_deflection)) {
        headline.push(format!("wheel rate {:.2} N/mm; spring motion ratio {:.3}", rate * 1e-3, ratio.abs()));
        summary["wheel_rate_n_per_m"] = rate.into();
        summary["spring_motion_ratio"] = ratio.abs().into();
    }
    if let Some(design) = rows.iter().find(|r| r.travel == 0.0) {
        let g = design.steering;
        summary["steering_axis_at_design"] = json!({
            "caster_deg": deg(g.caster),
            "kingpin_inclination_deg": deg(g.kingpin_inclination),
            "scrub_radius_m": g.scrub_radius,
            "mechanical_trail_m": g.mechanical_trail,
            "kingpin_offset_m": g.kingpin_offset,
        });
        headline.push(format!(
            "steering axis: caster {:.2}°, kingpin inclination {:.2}°, scrub radius {:.1} mm, trail {:.1} mm, \
             kingpin offset {:.1} mm",
            deg(g.caster),
            deg(g.kingpin_inclination),
            g.scrub_radius * 1e3,
            g.mechanical_trail * 1e3,
            g.kingpin_offset * 1e3
        ));
        summary["wheel_load_at_design_n"] = design.wheel_load.into();
        let pc = patch_compliance(&corner, 0.0).map_err(|e| e.to_string())?;
        // Rows: wheel-centre translation (m) and rotation (rad); columns: unit force (N) and torque (N·m)
        // at the wheel centre, global axes; the vertical row and column are zero with the height held.
        summary["wheel_compliance_at_design"] =
            json!(wheel_compliance(&corner, 0.0).map_err(|e| e.to_string())?.map(|row| row.to_vec()).to_vec());
        let per_kn = |rad_per_n: f64| deg(rad_per_n) * 1e3;
        summary["compliance_at_design"] = json!({
            "lateral_steer_deg_per_kn": per_kn(pc.lateral_steer),
            "lateral_camber_deg_per_kn": per_kn(pc.lateral_camber),
            "braking_steer_deg_per_kn": per_kn(pc.braking_steer),
            "aligning_torque_steer_deg_per_knm": per_kn(pc.aligning_torque_steer),
            "lateral_stiffness_n_per_m": pc.lateral_stiffness,
            "longitudinal_stiffness_n_per_m": pc.longitudinal_stiffness,
        });
        headline.push(format!(
            "compliance at design (wheel-centre height held): lateral steer {:+.4} °/kN, lateral camber {:+.4} °/kN, \
             braking steer {:+.4} °/kN, aligning-torque steer {:+.4} °/(100 N·m), lateral stiffness {:.0} N/mm, \
             longitudinal stiffness {:.0} N/mm",
            per_kn(pc.lateral_steer),
            per_kn(pc.lateral_camber),
            per_kn(pc.braking_steer),
            deg(pc.aligning_torque_steer) * 100.0,
            pc.lateral_stiffness * 1e-3,
            pc.longitudinal_stiffness * 1e-3
        ));
    }
    if let Some(vehicle) = &file.vehicle {
        let a = anti_pitch(&corner, vehicle).map_err(|e| e.to_string())?;
        let (braking, traction) = match vehicle.axle {
            elastokin::suspensions::analysis::AxlePosition::Front => ("anti-dive", "anti-lift"),
            elastokin::suspensions::analysis::AxlePosition::Rear => ("anti-lift", "anti-squat"),
        };
        summary["anti_pitch"] = json!({
            "axle": format!("{:?}", vehicle.axle).to_lowercase(),
            "side_view_swing_arm_angle_at_patch_deg": deg(a.patch_swing_arm_angle),
            "side_view_swing_arm_angle_at_wheel_centre_deg": deg(a.wheel_centre_swing_arm_angle),
            "braking_percent": a.braking,
            "braking_name": braking,
            "traction_percent": a.traction,
            "traction_name": traction,
        });
        headline.push(format!(
            "side-view swing arm: {:+.2}° at the patch, {:+.2}° at the wheel centre; {braking} {:+.1} % (brakes \
             {:.0} % front), {traction} {:+.1} % (drive {:.0} % front), wheelbase {:.2} m, CG {:.2} m",
            deg(a.patch_swing_arm_angle),
            deg(a.wheel_centre_swing_arm_angle),
            a.braking,
            vehicle.brake_front_fraction * 100.0,
            a.traction,
            vehicle.drive_front_fraction * 100.0,
            vehicle.wheelbase,
            vehicle.cg_height
        ));
    }
    Ok(Report { table, plots, summary, headline })
}

/// Camber of a wheel relative to the ground when the body rolls by `roll` (about +x) relative to it:
/// the roll tips the top of the left wheel inboard (−y) and the right wheel's outboard.
fn ground_camber(camber_to_body: f64, side: Side, roll: f64) -> f64 {
    camber_to_body - side.sign() * roll
}

fn roll(file: &SuspensionFile, s: Settings) -> Result<Report, String> {
    let (from, to) = s.range.unwrap_or((-0.05, 0.05));
    let axle = Axle::build(&file.suspension, AxleRig::OppositeTravel).map_err(|e| e.to_string())?;
    let rows = axle_sweep(&axle, from, to, s.steps, s.mode).map_err(|e| e.to_string())?;
    let table = Table {
        file: "roll.csv".into(),
        columns: [
            "left_travel_m",
            "roll_angle_deg",
            "left_toe_deg",
            "left_camber_deg",
            "left_camber_to_ground_deg",
            "right_toe_deg",
            "right_camber_deg",
            "right_camber_to_ground_deg",
            "track_m",
            "roll_centre_lateral_m",
            "roll_centre_height_m",
            "left_wheel_load_n",
            "right_wheel_load_n",
            "roll_moment_nm",
        ]
        .map(String::from)
        .to_vec(),
        rows: rows
            .iter()
            .map(|r| {
                let rc = r.roll_centre;
                vec![
                    r.travel.into(),
                    deg(r.roll_angle).into(),
                    deg(r.left.toe).into(),
                    deg(r.left.camber).into(),
                    deg(ground_camber(r.left.camber, Side::Left, r.roll_angle)).into(),
                    deg(r.right.toe).into(),
                    deg(r.right.camber).into(),
                    deg(ground_camber(r.right.camber, Side::Right, r.roll_angle)).into(),
                    r.track.into(),
                    rc.map(|c| c.lateral).into(),
                    rc.map(|c| c.height).into(),
                    r.left_load.into(),
                    r.right_load.into(),
                    r.roll_moment.into(),
                ]
            })
            .collect(),
    };
    let curve = |f: &dyn Fn(&AxleRow) -> Option<f64>| {
        rows.iter().filter_map(|r| f(r).map(|y| (deg(r.roll_angle), y))).collect()
    };
    let plots = vec![
        plot(
            file,
            "roll_toe_camber",
            "toe and camber in roll",
            "body roll [deg], left side up +",
            0.0,
            axis(
                "angle [deg]",
                [
                    ("left toe", curve(&|r| Some(deg(r.left.toe)))),
                    ("right toe", curve(&|r| Some(deg(r.right.toe)))),
                    (
                        "left camber to ground",
                        curve(&|r| Some(deg(ground_camber(r.left.camber, Side::Left, r.roll_angle)))),
                    ),
                    (
                        "right camber to ground",
                        curve(&|r| Some(deg(ground_camber(r.right.camber, Side::Right, r.roll_angle)))),
                    ),
                ],
            ),
            None,
        )?,
        // The height (about 100 mm) and the lateral migration (up to metres) on one axis would flatten
        // the height: each gets its own.
        plot(
            file,
            "roll_centre",
            "roll centre in roll",
            "body roll [deg], left side up +",
            0.0,
            axis(
                "roll centre height above ground [mm]",
                [("height", curve(&|r| r.roll_centre.map(|c| c.height * 1e3)))],
            ),
            Some(axis(
                "roll centre lateral position [mm], left +",
                [("lateral position", curve(&|r| r.roll_centre.map(|c| c.lateral * 1e3)))],
            )),
        )?,
    ];
    let mut summary = json!({ "range_m": [from, to], "steps": s.steps });
    let mut headline = vec![format!(
        "roll (opposite wheel travel {:+.0}..{:+.0} mm on the full axle), {} steps",
        from * 1e3,
        to * 1e3,
        s.steps
    )];
    if let Some(rc) = rows.iter().find(|r| r.travel == 0.0).and_then(|r| r.roll_centre) {
        summary["roll_centre_height_at_design_m"] = rc.height.into();
        headline.push(format!(
            "roll centre at design: {:.1} mm above ground, {:+.2} mm off centre",
            rc.height * 1e3,
            rc.lateral * 1e3
        ));
    }
    let slope = |y: &dyn Fn(&AxleRow) -> f64| slope_at(&rows, 0.0, |r| r.travel, y);
    let (dphi, dtoe, dcamber, dmoment) = (
        slope(&|r| r.roll_angle),
        slope(&|r| r.left.toe),
        slope(&|r| ground_camber(r.left.camber, Side::Left, r.roll_angle)),
        slope(&|r| r.roll_moment),
    );
    if let (Some(dphi), Some(dtoe), Some(dcamber), Some(dmoment)) = (dphi, dtoe, dcamber, dmoment) {
        let (roll_steer, roll_camber, stiffness) = (dtoe / dphi, dcamber / dphi, -dmoment / dphi);
        summary["roll_steer_deg_per_deg"] = roll_steer.into();
        summary["roll_camber_deg_per_deg"] = roll_camber.into();
        summary["roll_stiffness_nm_per_rad"] = stiffness.into();
        headline.push(format!(
            "left wheel: roll steer {roll_steer:+.4} °/° (toe-in +), roll camber to ground {roll_camber:+.4} °/°; \
             roll stiffness of the springs {:.0} N·m/°",
            stiffness.to_radians()
        ));
    }
    Ok(Report { table, plots, summary, headline })
}

/// Steer angle of a wheel (positive turning left, about +z) from its toe (toe-in positive).
fn steer_angle(toe: f64, side: Side) -> f64 {
    -side.sign() * toe
}

fn steering(file: &SuspensionFile, s: Settings) -> Result<Report, String> {
    let (from, to) = s.range.unwrap_or((-0.04, 0.04));
    let axle = Axle::build(&file.suspension, AxleRig::Steering).map_err(|e| e.to_string())?;
    let rows = axle_sweep(&axle, from, to, s.steps, s.mode).map_err(|e| e.to_string())?;
    let table = Table::numbers(
        "steering.csv",
        [
            "rack_travel_m",
            "left_steer_deg",
            "right_steer_deg",
            "left_toe_deg",
            "right_toe_deg",
            "left_camber_deg",
            "right_camber_deg",
        ],
        rows.iter().map(|r| {
            [
                r.travel,
                deg(steer_angle(r.left.toe, Side::Left)),
                deg(steer_angle(r.right.toe, Side::Right)),
                deg(r.left.toe),
                deg(r.right.toe),
                deg(r.left.camber),
                deg(r.right.camber),
            ]
        }),
    );
    let curve = |f: &dyn Fn(&AxleRow) -> f64| rows.iter().map(|r| (r.travel * 1e3, f(r))).collect();
    let plots = vec![plot(
        file,
        "steering",
        "steer angles",
        "rack travel [mm], towards left +",
        0.0,
        axis(
            "steer angle [deg], left turn +",
            [
                ("left wheel", curve(&|r| deg(steer_angle(r.left.toe, Side::Left)))),
                ("right wheel", curve(&|r| deg(steer_angle(r.right.toe, Side::Right)))),
            ],
        ),
        None,
    )?];
    let mut summary = json!({ "range_m": [from, to], "steps": s.steps });
    let mut headline =
        vec![format!("steering (rack {:+.0}..{:+.0} mm, heights held), {} steps", from * 1e3, to * 1e3, s.steps)];
    if let Some(ratio) = slope_at(&rows, 0.0, |r| r.travel, |r| steer_angle(r.left.toe, Side::Left)) {
        summary["steer_per_rack_travel_deg_per_m"] = deg(ratio).into();
        headline.push(format!("steer at design: {:.3} ° per mm of rack travel", deg(ratio) * 1e-3));
    }
    for r in [rows.first(), rows.last()].into_iter().flatten() {
        headline.push(format!(
            "rack {:+.1} mm: left wheel {:+.3}°, right wheel {:+.3}°",
            r.travel * 1e3,
            deg(steer_angle(r.left.toe, Side::Left)),
            deg(steer_angle(r.right.toe, Side::Right))
        ));
    }
    Ok(Report { table, plots, summary, headline })
}

fn vertical_force(file: &SuspensionFile, s: Settings) -> Result<Report, String> {
    let held = file.suspension.build(Side::Left, Rig::WheelTravel).map_err(|e| e.to_string())?;
    let design_load = design_wheel_load(&held).map_err(|e| e.to_string())?;
    let (from, to) = s.range.unwrap_or((0.5 * design_load, 1.5 * design_load));
    let corner = file.suspension.build(Side::Left, Rig::Free).map_err(|e| e.to_string())?;
    let z0 = corner.wheel.wheel_centre.z;
    let rows = vertical_force_sweep(corner, from, to, s.steps, s.mode).map_err(|e| e.to_string())?;
    let table = Table::numbers(
        "vertical_force.csv",
        ["force_n", "wheel_travel_m", "toe_deg", "camber_deg", "contact_patch_z_m"],
        rows.iter().map(|r| {
            [r.load, r.attitude.wheel_centre.z - z0, deg(r.attitude.toe), deg(r.attitude.camber), r.contact_patch.z]
        }),
    );
    let plots = vec![plot(
        file,
        "vertical_force",
        "wheel travel under vertical force",
        "vertical force at the contact patch [N]",
        design_load,
        axis(
            "wheel travel [mm], bump +",
            [("wheel travel", rows.iter().map(|r| (r.load, (r.attitude.wheel_centre.z - z0) * 1e3)).collect())],
        ),
        None,
    )?];
    let mut summary = json!({ "range_n": [from, to], "steps": s.steps, "design_wheel_load_n": design_load });
    let mut headline =
        vec![format!("vertical force {from:.0}..{to:.0} N at the contact patch, wheel free, {} steps", s.steps)];
    headline.push(format!("design wheel load (rig force holding design height): {design_load:.1} N"));
    if let Some(rate) = slope_at(&rows, design_load, |r| r.load, |r| r.attitude.wheel_centre.z).map(|d| 1.0 / d) {
        summary["wheel_rate_n_per_m"] = rate.into();
        headline
            .push(format!("wheel rate at the design load: {:.2} N/mm (force over wheel-centre travel)", rate * 1e-3));
    }
    Ok(Report { table, plots, summary, headline })
}

/// Columns of the force in every joint and element: `name force_x_n`, … for each.
fn component_columns(forces: &ComponentForces) -> Vec<String> {
    let mut out = Vec::new();
    for c in forces.joints.iter().chain(&forces.elements) {
        for (what, unit) in [("force", "n"), ("torque", "nm")] {
            for axis in ["x", "y", "z"] {
                out.push(format!("{} {what}_{axis}_{unit}", c.name));
            }
        }
    }
    out
}

fn component_values(forces: &ComponentForces) -> Vec<Cell> {
    forces
        .joints
        .iter()
        .chain(&forces.elements)
        .flat_map(|c| [c.force, c.torque])
        .flat_map(|v| [v.x, v.y, v.z])
        .map(Cell::from)
        .collect()
}

fn road_load(file: &SuspensionFile, load: WheelLoad, s: Settings) -> Result<Report, String> {
    let (unit, default_range) = match load {
        WheelLoad::Lateral => ("N", (-3000.0, 3000.0)),
        WheelLoad::Braking | WheelLoad::Traction => ("N", (0.0, 3000.0)),
        WheelLoad::AligningTorque => ("N·m", (-200.0, 200.0)),
    };
    let (from, to) = s.range.unwrap_or(default_range);
    let corner_load = match &file.vehicle {
        Some(v) => v.corner_load,
        None => design_wheel_load(&file.suspension.build(Side::Left, Rig::WheelTravel).map_err(|e| e.to_string())?)
            .map_err(|e| e.to_string())?,
    };
    let rig = if s.height_held { Rig::HeightHeld } else { Rig::Free };
    let corner = file.suspension.build(Side::Left, rig).map_err(|e| e.to_string())?;
    let rows = wheel_load_sweep(corner, load, corner_load, from, to, s.steps, s.mode).map_err(|e| e.to_string())?;
    let name = Analysis::Road(load).name();
    let stem = name.replace('-', "_");
    let mut columns: Vec<String> = [
        "load",
        "toe_deg",
        "camber_deg",
        "wheel_centre_x_m",
        "wheel_centre_y_m",
        "wheel_centre_z_m",
        "patch_dx_m",
        "patch_dy_m",
        "patch_dz_m",
        "wheel_load_n",
    ]
    .map(String::from)
    .to_vec();
    columns[0] = format!("load_{}", if unit == "N" { "n" } else { "nm" });
    if let Some(first) = rows.first() {
        columns.extend(component_columns(&first.forces));
    }
    let table = Table {
        file: format!("{stem}.csv"),
        columns,
        rows: rows
            .iter()
            .map(|r| {
                let (w, d) = (r.attitude.wheel_centre, r.patch_displacement);
                let mut row: Vec<Cell> =
                    [r.load, deg(r.attitude.toe), deg(r.attitude.camber), w.x, w.y, w.z, d.x, d.y, d.z, r.wheel_load]
                        .map(Cell::from)
                        .to_vec();
                row.extend(component_values(&r.forces));
                row
            })
            .collect(),
    };
    let held = if s.height_held { "wheel-centre height held" } else { "wheel free on its spring" };
    let curve = |f: &dyn Fn(&LoadRow) -> f64| rows.iter().map(|r| (r.load, f(r))).collect();
    let plots = vec![plot(
        file,
        &stem,
        &format!("toe and camber under {}", name.replace('-', " ")),
        &format!("{} [{unit}]", Analysis::Road(load).parameter().split(',').next().unwrap_or(name)),
        0.0,
        axis(
            "angle [deg]",
            [
                ("toe (in +)", curve(&|r| deg(r.attitude.toe))),
                ("camber (top out +)", curve(&|r| deg(r.attitude.camber))),
            ],
        ),
        None,
    )?];
    let mut summary =
        json!({ "range": [from, to], "steps": s.steps, "corner_load_n": corner_load, "height_held": s.height_held });
    let mut headline = vec![format!(
        "{} {from:.0}..{to:.0} {unit} ({held}, corner load {corner_load:.0} N), {} steps",
        name.replace('-', " "),
        s.steps
    )];
    let per = if unit == "N" { ("°/kN", 1e3) } else { ("°/(100 N·m)", 100.0) };
    let slope = |y: &dyn Fn(&LoadRow) -> f64| slope_at(&rows, 0.0, |r| r.load, y);
    if let (Some(steer), Some(camber)) = (slope(&|r| r.attitude.toe), slope(&|r| r.attitude.camber)) {
        summary["steer_deg_per_unit"] = deg(steer).into();
        summary["camber_deg_per_unit"] = deg(camber).into();
        headline.push(format!(
            "at zero load: steer {:+.4} {}, camber {:+.4} {}",
            deg(steer) * per.1,
            per.0,
            deg(camber) * per.1,
            per.0
        ));
    }
    if let Some(last) = rows.last() {
        headline.push(format!(
            "at {:.0} {unit}: toe {:+.4}°, camber {:+.4}°, contact patch moved ({:+.2}, {:+.2}, {:+.2}) mm",
            last.load,
            deg(last.attitude.toe),
            deg(last.attitude.camber),
            last.patch_displacement.x * 1e3,
            last.patch_displacement.y * 1e3,
            last.patch_displacement.z * 1e3
        ));
    }
    Ok(Report { table, plots, summary, headline })
}

fn static_load(file: &SuspensionFile) -> Result<Report, String> {
    let vehicle = file.vehicle.as_ref().ok_or(
        "the model file has no \"vehicle\" section with the corner_load to carry (see examples/macpherson.json)",
    )?;
    let corner = file.suspension.build(Side::Left, Rig::Free).map_err(|e| e.to_string())?;
    let rest = static_load_case(corner, vehicle.corner_load).map_err(|e| e.to_string())?;
    let table = Table {
        file: "static_load.csv".into(),
        columns: [
            "component",
            "body",
            "other_body",
            "force_x_n",
            "force_y_n",
            "force_z_n",
            "torque_x_nm",
            "torque_y_nm",
            "torque_z_nm",
        ]
        .map(String::from)
        .to_vec(),
        rows: rest
            .forces
            .joints
            .iter()
            .chain(&rest.forces.elements)
            .map(|c| {
                let mut row =
                    vec![Cell::Text(c.name.clone()), Cell::Text(c.body.clone()), Cell::Text(c.other_body.clone())];
                row.extend([c.force.x, c.force.y, c.force.z, c.torque.x, c.torque.y, c.torque.z].map(Cell::from));
                row
            })
            .collect(),
    };
    let d = rest.wheel_centre_displacement;
    let summary = json!({
        "corner_load_n": rest.corner_load,
        "ride_height_change_m": d.z,
        "wheel_centre_displacement_m": [d.x, d.y, d.z],
        "toe_deg": deg(rest.attitude.toe),
        "camber_deg": deg(rest.attitude.camber),
        "wheel_rate_n_per_m": rest.wheel_rate,
        "spring_force_n": rest.spring_force,
        "spring_deflection_m": rest.spring_deflection,
    });
    let mut headline =
        vec![format!("static load: {:.0} N at the contact patch, from the design position", rest.corner_load)];
    headline.push(format!(
        "at rest: wheel centre {:+.2} mm (bump +), toe {:+.4}°, camber {:+.4}°, wheel rate {:.2} N/mm, spring {:.0} N",
        d.z * 1e3,
        deg(rest.attitude.toe),
        deg(rest.attitude.camber),
        rest.wheel_rate * 1e-3,
        rest.spring_force
    ));
    for c in rest.forces.joints.iter().chain(&rest.forces.elements).take(12) {
        headline.push(format!("  {:<28} {:>9.1} N {:>9.2} N·m", c.name, c.force.norm(), c.torque.norm()));
    }
    Ok(Report { table, plots: Vec::new(), summary, headline })
}
