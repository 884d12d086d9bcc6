//! The K&C tests `elastokin run` offers. Each walks one load path of the engine and reduces it to a table
//! (one CSV), plots (one SVG per curve family), summary figures (JSON) and headline lines for the terminal.

use crate::plot::{line_plot, Series};
use elastokin::solver::Mode;
use elastokin::suspensions::analysis::{
    design_wheel_load, parallel_wheel_travel, patch_compliance, slope_at, vertical_force_sweep, TravelRow,
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
}

/// Every analysis, in the order `run` performs them by default.
pub const ALL: [Analysis; 4] = [Analysis::ParallelTravel, Analysis::Roll, Analysis::Steering, Analysis::VerticalForce];

impl Analysis {
    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Analysis::ParallelTravel => "parallel-travel",
            Analysis::Roll => "roll",
            Analysis::Steering => "steering",
            Analysis::VerticalForce => "vertical-force",
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
}

/// A table of rows, written as CSV; an empty cell is a value the row does not have (never NaN).
pub struct Table {
    /// File name in the output directory.
    pub file: String,
    /// Column headers, with units.
    pub columns: Vec<&'static str>,
    /// Rows, one value per column.
    pub rows: Vec<Vec<Option<f64>>>,
}

impl Table {
    /// The CSV text.
    pub fn csv(&self) -> String {
        let mut out = self.columns.join(",");
        out.push('\n');
        for row in &self.rows {
            let cells: Vec<String> = row
                .iter()
                .map(|v| match v {
                    Some(v) if v.is_finite() => format!("{v:.9}"),
                    _ => String::new(),
                })
                .collect();
            out += &cells.join(",");
            out.push('\n');
        }
        out
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

/// Short model name for plot titles (the part before any parenthesis).
fn title(file: &SuspensionFile, what: &str) -> String {
    format!("{}: {what}", file.name.split(" (").next().unwrap_or(&file.name))
}

/// Runs `analysis` on the model in `file`.
pub fn run(analysis: Analysis, file: &SuspensionFile, settings: Settings) -> Result<Report, String> {
    let err = |e: &dyn std::fmt::Display| format!("{}: {e}", analysis.name());
    match analysis {
        Analysis::ParallelTravel => parallel_travel(file, settings).map_err(|e| err(&e)),
        Analysis::Roll => roll(file, settings).map_err(|e| err(&e)),
        Analysis::Steering => steering(file, settings).map_err(|e| err(&e)),
        Analysis::VerticalForce => vertical_force(file, settings).map_err(|e| err(&e)),
    }
}

fn parallel_travel(file: &SuspensionFile, s: Settings) -> Result<Report, String> {
    let (from, to) = s.range.unwrap_or((-0.08, 0.08));
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel).map_err(|e| e.to_string())?;
    let rows = parallel_wheel_travel(&corner, from, to, s.steps, s.mode).map_err(|e| e.to_string())?;
    let y0 = corner.wheel.wheel_centre.y;
    let table = Table {
        file: "parallel_travel.csv".into(),
        columns: vec![
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
        rows: rows
            .iter()
            .map(|r| {
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
                .map(Some)
                .to_vec()
            })
            .collect(),
    };
    let curve = |f: &dyn Fn(&TravelRow) -> f64| rows.iter().map(|r| (r.travel * 1e3, f(r))).collect();
    let plots = vec![(
        "parallel_travel_toe_camber.svg".into(),
        line_plot(
            &title(file, "toe and camber in parallel wheel travel"),
            "wheel travel [mm], bump +",
            "angle [deg]",
            &[
                Series { name: "toe (in +)", points: curve(&|r| deg(r.attitude.toe)) },
                Series { name: "camber (top out +)", points: curve(&|r| deg(r.attitude.camber)) },
            ],
        ),
    )];
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
        columns: vec![
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
        ],
        rows: rows
            .iter()
            .map(|r| {
                let rc = r.roll_centre;
                vec![
                    Some(r.travel),
                    Some(deg(r.roll_angle)),
                    Some(deg(r.left.toe)),
                    Some(deg(r.left.camber)),
                    Some(deg(ground_camber(r.left.camber, Side::Left, r.roll_angle))),
                    Some(deg(r.right.toe)),
                    Some(deg(r.right.camber)),
                    Some(deg(ground_camber(r.right.camber, Side::Right, r.roll_angle))),
                    Some(r.track),
                    rc.map(|c| c.lateral),
                    rc.map(|c| c.height),
                    Some(r.left_load),
                    Some(r.right_load),
                    Some(r.roll_moment),
                ]
            })
            .collect(),
    };
    let curve = |f: &dyn Fn(&AxleRow) -> Option<f64>| {
        rows.iter().filter_map(|r| f(r).map(|y| (deg(r.roll_angle), y))).collect()
    };
    let plots = vec![
        (
            "roll_toe_camber.svg".into(),
            line_plot(
                &title(file, "toe and camber in roll"),
                "body roll [deg], left side up +",
                "angle [deg]",
                &[
                    Series { name: "left toe", points: curve(&|r| Some(deg(r.left.toe))) },
                    Series { name: "right toe", points: curve(&|r| Some(deg(r.right.toe))) },
                    Series {
                        name: "left camber to ground",
                        points: curve(&|r| Some(deg(ground_camber(r.left.camber, Side::Left, r.roll_angle)))),
                    },
                    Series {
                        name: "right camber to ground",
                        points: curve(&|r| Some(deg(ground_camber(r.right.camber, Side::Right, r.roll_angle)))),
                    },
                ],
            ),
        ),
        (
            "roll_centre.svg".into(),
            line_plot(
                &title(file, "roll centre in roll"),
                "body roll [deg], left side up +",
                "roll centre [mm]",
                &[
                    Series { name: "height above ground", points: curve(&|r| r.roll_centre.map(|c| c.height * 1e3)) },
                    Series { name: "lateral (left +)", points: curve(&|r| r.roll_centre.map(|c| c.lateral * 1e3)) },
                ],
            ),
        ),
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
    let table = Table {
        file: "steering.csv".into(),
        columns: vec![
            "rack_travel_m",
            "left_steer_deg",
            "right_steer_deg",
            "left_toe_deg",
            "right_toe_deg",
            "left_camber_deg",
            "right_camber_deg",
        ],
        rows: rows
            .iter()
            .map(|r| {
                [
                    r.travel,
                    deg(steer_angle(r.left.toe, Side::Left)),
                    deg(steer_angle(r.right.toe, Side::Right)),
                    deg(r.left.toe),
                    deg(r.right.toe),
                    deg(r.left.camber),
                    deg(r.right.camber),
                ]
                .map(Some)
                .to_vec()
            })
            .collect(),
    };
    let curve = |f: &dyn Fn(&AxleRow) -> f64| rows.iter().map(|r| (r.travel * 1e3, f(r))).collect();
    let plots = vec![(
        "steering.svg".into(),
        line_plot(
            &title(file, "steer angles"),
            "rack travel [mm], towards left +",
            "steer angle [deg], left turn +",
            &[
                Series { name: "left wheel", points: curve(&|r| deg(steer_angle(r.left.toe, Side::Left))) },
                Series { name: "right wheel", points: curve(&|r| deg(steer_angle(r.right.toe, Side::Right))) },
            ],
        ),
    )];
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
    let table = Table {
        file: "vertical_force.csv".into(),
        columns: vec!["force_n", "wheel_travel_m", "toe_deg", "camber_deg", "contact_patch_z_m"],
        rows: rows
            .iter()
            .map(|r| {
                [
                    r.load,
                    r.attitude.wheel_centre.z - z0,
                    deg(r.attitude.toe),
                    deg(r.attitude.camber),
                    r.contact_patch.z,
                ]
                .map(Some)
                .to_vec()
            })
            .collect(),
    };
    let plots = vec![(
        "vertical_force.svg".into(),
        line_plot(
            &title(file, "wheel travel under vertical force"),
            "vertical force at the contact patch [N]",
            "wheel travel [mm], bump +",
            &[Series {
                name: "wheel travel",
                points: rows.iter().map(|r| (r.load, (r.attitude.wheel_centre.z - z0) * 1e3)).collect(),
            }],
        ),
    )];
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
