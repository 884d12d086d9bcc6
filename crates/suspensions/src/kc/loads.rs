//! The force-driven K&C tests: vertical force with the wheel free, the road loads, the static load case.

use crate::analysis::{
    design_wheel_load, design_wheel_load_estimated, model_load_sweep_with, static_load_case_estimated,
    vertical_force_sweep_with, wheel_load_sweep_with, ComponentForces, LoadRow, StaticLoad, WheelLoad,
};
use crate::assembly::{LoadPoint, Rig};
use crate::description::Side;
use crate::kc::figures;
use crate::kc::models::Models;
use crate::kc::reduce::{axis, bushings_share, chart, corner_drawing, deg, finish, Design, Reduction};
use crate::kc::report::{Accuracy, AnalysisReport, Cell, Figure, FigureKind, Table, Warning};
use crate::kc::settings::{mode_word, Analysis, Cause, DefaultRange, Settings, NO_ROWS};
use crate::kc::unit::Unit;
use elastokin_solver::replay::ReplayRows;
use elastokin_solver::LoadPath;

/// Why the `loads` analysis cannot run.
pub(super) const NO_LOADS: &str = "the model has no load case: give \"loads\" in the general form (a force at a point \
                                    of a body, or a moment), see docs/model-file.md";

/// Where the rig's forces act, in words.
fn where_loaded(s: &Settings) -> &'static str {
    match s.load_point {
        LoadPoint::ContactPatch => "contact patch",
        LoadPoint::WheelCentre => "wheel centre",
    }
}

pub(super) fn vertical_force(models: &Models, s: &Settings) -> Result<AnalysisReport, Cause> {
    let file = models.file();
    let held = models.corner_ref(Rig::WheelTravel)?;
    let (design_load, design_load_error) = design_wheel_load_estimated(held, s.error_estimate)?;
    let range = s.range.unwrap_or_else(|| DefaultRange::around_design_load(design_load));
    let mut corner = models.corner(Rig::Free)?;
    corner.load_point = s.load_point;
    let z0 = corner.wheel.wheel_centre.z;
    let drawing = corner_drawing(&corner, s);
    let out = vertical_force_sweep_with(
        corner,
        range.0,
        range.1,
        s.steps,
        s.mode,
        s.extras_reading(range, design_load, NO_ROWS),
    )?;
    let table = |rows: &[LoadRow]| {
        Table::numbers(
            "vertical_force",
            ["force_n", "wheel_travel_m", "toe_deg", "camber_deg", "contact_patch_z_m"],
            rows.iter().map(|r| {
                [r.load, r.attitude.wheel_centre.z - z0, deg(r.attitude.toe), deg(r.attitude.camber), r.contact_patch.z]
            }),
        )
    };
    let figures = |_: &[LoadRow], design: Design<LoadRow>| {
        let why = design.err().unwrap_or_default().to_string();
        let compliance = design.ok().map(|d| d.rate(|r| r.attitude.wheel_centre.z));
        // A wheel the joints hold at its height does not rise under the force: no rate, and that is why.
        let held = "the wheel centre does not rise under the vertical force: the joints hold its height (a link \
                    through the wheel centre, or an axle locked in travel); check the model with `elastokin check`";
        let (rate, why) = match compliance {
            Some(d) if d.abs() > 0.0 => (Some(1.0 / d), why),
            Some(_) => (None, held.to_string()),
            None => (None, why),
        };
        vec![
            Figure::of(&figures::DESIGN_WHEEL_LOAD, Some(design_load), ""),
            Figure::of(&figures::VERTICAL_FORCE_WHEEL_RATE, rate, &why),
        ]
    };
    let charts = vec![chart(
        file,
        "vertical_force",
        "wheel travel under vertical force",
        &format!("vertical force at the {} [N]", where_loaded(s)),
        axis(
            "wheel travel [mm], bump +",
            &out.rows,
            |r| r.load,
            &[("wheel travel", &|r: &LoadRow| Some((r.attitude.wheel_centre.z - z0) * 1e3))],
        ),
        Some(axis(
            "angle [deg]",
            &out.rows,
            |r| r.load,
            &[
                ("toe (in +)", &|r: &LoadRow| Some(deg(r.attitude.toe))),
                ("camber (top out +)", &|r: &LoadRow| Some(deg(r.attitude.camber))),
            ],
        )),
        Some(design_load),
    )];
    let description = format!(
        "vertical force {:.0}..{:.0} N at the {}, wheel free, {} steps",
        range.0,
        range.1,
        where_loaded(s),
        s.steps
    );
    let mut report = finish(
        Analysis::VerticalForce,
        description,
        range,
        s,
        &out,
        Reduction { table: &table, figures: &figures, drawing },
        charts,
    );
    // The design load is not read off the rows, so the rows' estimate says nothing of it: its own.
    if let Some(f) = report.figures.iter_mut().find(|f| f.key == figures::DESIGN_WHEEL_LOAD.key) {
        f.error = design_load_error;
    }
    Ok(report)
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

pub(super) fn road_load(models: &Models, load: WheelLoad, s: &Settings) -> Result<AnalysisReport, Cause> {
    loaded(models, Analysis::Road(load), s)
}

/// The model file's own load case (`loads` of the general form), applied from zero to its full value.
pub(super) fn model_loads(models: &Models, s: &Settings) -> Result<AnalysisReport, Cause> {
    loaded(models, Analysis::ModelLoads, s)
}

/// A road load or the model's own loads, swept with the corner load carried.
fn loaded(models: &Models, analysis: Analysis, s: &Settings) -> Result<AnalysisReport, Cause> {
    let file = models.file();
    let (unit, column) = match analysis {
        Analysis::Road(WheelLoad::Lateral | WheelLoad::Braking | WheelLoad::Traction) => ("N", "load_n"),
        Analysis::Road(WheelLoad::AligningTorque) => ("N·m", "load_nm"),
        _ => ("of the load case", "fraction"),
    };
    let range = analysis.range_or_default(s.range)?;
    let corner_load = match &file.vehicle {
        Some(v) => v.corner_load,
        None => design_wheel_load(models.corner_ref(Rig::WheelTravel)?)?,
    };
    let rig = if s.height_held { Rig::HeightHeld } else { Rig::Free };
    let mut corner = models.corner(rig)?;
    corner.load_point = s.load_point;
    // Drawn as walked: with the model's own loads, once they are added.
    let drawing;
    // The figures read the rates at zero load (at design) and the last row.
    let extras = s.extras_reading(range, 0.0, ReplayRows { near: None, last: true, extremes: false });
    let out = match analysis {
        Analysis::Road(load) => {
            drawing = corner_drawing(&corner, s);
            wheel_load_sweep_with(corner, load, corner_load, LoadPath::new(range.0, range.1, s.steps), s.mode, extras)
        }
        _ => {
            let general = match &file.suspension {
                crate::description::Template::General(g) if !g.loads.is_empty() => g,
                _ => return Err(Cause::Lacks(NO_LOADS.into())),
            };
            general.add_loads(&mut corner.model, Side::Left, "")?;
            if let Some(prefix) = corner.partner_prefix() {
                // A solid axle: the load case on both sides, as the mirror image.
                general.add_loads(&mut corner.model, Side::Right, prefix)?;
            }
            drawing = corner_drawing(&corner, s);
            model_load_sweep_with(corner, corner_load, range.0, range.1, s.steps, s.mode, extras)
        }
    }?;
    let name = analysis.name();
    let stem = name.replace('-', "_");
    let table = |rows: &[LoadRow]| {
        let mut columns: Vec<String> = [
            column,
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
        if let Some(first) = rows.first() {
            columns.extend(component_columns(&first.forces));
        }
        Table {
            name: stem.clone(),
            columns,
            rows: rows
                .iter()
                .map(|r| {
                    let (w, d) = (r.attitude.wheel_centre, r.patch_displacement);
                    let mut row: Vec<Cell> = [
                        r.load,
                        deg(r.attitude.toe),
                        deg(r.attitude.camber),
                        w.x,
                        w.y,
                        w.z,
                        d.x,
                        d.y,
                        d.z,
                        r.wheel_load,
                    ]
                    .map(Cell::from)
                    .to_vec();
                    row.extend(component_values(&r.forces));
                    row
                })
                .collect(),
        }
    };
    // Per kN of a force, per kN·m of a torque, per load case of the model's own.
    let per_unit = match unit {
        "N" => Unit::DegreePerKilonewton,
        "N·m" => Unit::DegreePerKilonewtonMetre,
        _ => Unit::DegreePerLoadCase,
    };
    let figures = |rows: &[LoadRow], design: Design<LoadRow>| {
        let why = design.err().unwrap_or_default();
        let slope = |y: &dyn Fn(&LoadRow) -> f64| design.ok().map(|d| d.rate(y));
        let per_load = |kind: &FigureKind| FigureKind { unit: per_unit, ..*kind };
        let mut f = vec![
            Figure::of(&per_load(&figures::COMPLIANCE_STEER), slope(&|r| r.attitude.toe), why),
            Figure::of(&per_load(&figures::COMPLIANCE_CAMBER), slope(&|r| r.attitude.camber), why),
        ];
        if let Some(last) = rows.last() {
            let at = |what: &str| format!("{what} at {:.0} {unit}", last.load);
            f.push(Figure::of(&figures::TOE_AT_END, Some(last.attitude.toe), "").labelled(at("toe")));
            f.push(Figure::of(&figures::CAMBER_AT_END, Some(last.attitude.camber), "").labelled(at("camber")));
        }
        f
    };
    let charts = vec![chart(
        file,
        &stem,
        &format!("toe and camber under {}", name.replace('-', " ")),
        &format!("{} [{unit}]", analysis.parameter().split(',').next().unwrap_or(name)),
        axis(
            "angle [deg]",
            &out.rows,
            |r| r.load,
            &[
                ("toe (in +)", &|r: &LoadRow| Some(deg(r.attitude.toe))),
                ("camber (top out +)", &|r: &LoadRow| Some(deg(r.attitude.camber))),
            ],
        ),
        Some(axis(
            "contact patch displacement [mm]",
            &out.rows,
            |r| r.load,
            &[
                ("patch x", &|r: &LoadRow| Some(r.patch_displacement.x * 1e3)),
                ("patch y", &|r: &LoadRow| Some(r.patch_displacement.y * 1e3)),
            ],
        )),
        Some(0.0),
    )];
    let held = if s.height_held { "wheel-centre height held" } else { "wheel free on its spring" };
    let at = match analysis {
        Analysis::Road(WheelLoad::Lateral | WheelLoad::Braking) => format!(" at the {}", where_loaded(s)),
        Analysis::Road(WheelLoad::Traction) => " at the wheel centre".into(),
        _ => String::new(),
    };
    let description = format!(
        "{} {:.0}..{:.0} {unit}{at} ({held}, corner load {corner_load:.0} N), {} steps",
        name.replace('-', " "),
        range.0,
        range.1,
        s.steps
    );
    let mut report =
        finish(analysis, description, range, s, &out, Reduction { table: &table, figures: &figures, drawing }, charts);
    if let (Analysis::Road(WheelLoad::Lateral), Some(rigid)) = (analysis, models.rigid()) {
        let rigid = loaded(rigid, analysis, &Settings { motion: false, ..*s });
        bushings_share(&mut report, "steer", "lateral-force compliance steer", rigid);
    }
    Ok(report)
}

pub(super) fn static_load(models: &Models, s: &Settings) -> Result<AnalysisReport, Cause> {
    let file = models.file();
    let vehicle = file.vehicle.as_ref().ok_or_else(|| {
        Cause::Lacks(
            "the model file has no \"vehicle\" section with the corner_load to carry (see examples/macpherson.json)"
                .into(),
        )
    })?;
    let corner = models.corner(Rig::Free)?;
    let (rest, corrected) = static_load_case_estimated(corner, vehicle.corner_load, s.error_estimate)?;
    let table = Table {
        name: "static_load".into(),
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
                let mut row = [&c.name, &c.body, &c.other_body].map(|n| Cell::Text(n.to_string())).to_vec();
                row.extend([c.force.x, c.force.y, c.force.z, c.torque.x, c.torque.y, c.torque.z].map(Cell::from));
                row
            })
            .collect(),
    };
    let figures = |rest: &StaticLoad| {
        let d = rest.wheel_centre_displacement;
        vec![
            Figure::of(&figures::CORNER_LOAD, Some(rest.corner_load), ""),
            Figure::of(&figures::RIDE_HEIGHT_CHANGE, Some(d.z), ""),
            Figure::of(&figures::TOE_AT_REST, Some(rest.attitude.toe), ""),
            Figure::of(&figures::CAMBER_AT_REST, Some(rest.attitude.camber), ""),
            Figure::of(&figures::WHEEL_RATE_AT_REST, Some(rest.wheel_rate), ""),
            Figure::of(&figures::SPRING_FORCE, Some(rest.spring_force), ""),
            Figure::of(&figures::SPRING_DEFLECTION, Some(rest.spring_deflection), ""),
        ]
    };
    let mut figures_at_rest = figures(&rest);
    // Each figure's error estimate: its change one exact Newton iteration on (as a sweep's rows are read
    // again); the component forces' likewise, column by column.
    let mut columns = Vec::new();
    if let Some(corrected) = &corrected {
        for (f, g) in figures_at_rest.iter_mut().zip(figures(corrected)) {
            f.error = f.value.zip(g.value).map(|(a, b)| (a - b).abs());
        }
        let components = |r: &StaticLoad| -> Vec<[f64; 6]> {
            let all = r.forces.joints.iter().chain(&r.forces.elements);
            all.map(|c| [c.force.x, c.force.y, c.force.z, c.torque.x, c.torque.y, c.torque.z]).collect()
        };
        let (at, on) = (components(&rest), components(corrected));
        columns = table.columns.iter().map(|c| (c.clone(), None)).collect();
        for k in 0..6 {
            let largest = at.iter().zip(&on).map(|(a, b)| (a[k] - b[k]).abs()).fold(0.0, f64::max);
            columns[3 + k].1 = Some(largest);
        }
    }
    let figures = figures_at_rest;
    let angle_error = [&figures::TOE_AT_REST, &figures::CAMBER_AT_REST]
        .iter()
        .filter_map(|kind| figures.iter().find(|f| f.key == kind.key)?.error)
        .fold(0.0, f64::max)
        .to_degrees();
    let (force_residual, constraint_residual) = rest.residuals;
    let within = constraint_residual <= s.tolerance.length_m;
    let mut warnings = Vec::new();
    if !within {
        warnings.push(Warning {
            code: "error-over-tolerance",
            hardpoints: Vec::new(),
            message: format!(
                "static-load: the rest position leaves the joints apart by {:.2e} mm; the model is near-singular \
                 there, run `elastokin check` on it",
                constraint_residual * 1e3
            ),
        });
    }
    Ok(AnalysisReport {
        analysis: Analysis::StaticLoad,
        parameter: Analysis::StaticLoad.parameter().into(),
        description: format!("static load: {:.0} N at the contact patch, from the design position", rest.corner_load),
        range: (rest.corner_load, rest.corner_load),
        steps: 1,
        figures,
        units: s.units,
        table,
        compliance: None,
        wheel_compliance_at_design: None,
        charts: Vec::new(),
        motion: None,
        accuracy: Accuracy {
            method: format!(
                "converged residuals of the rest position (Newton on the exact equilibrium; {} mode does not \
                 apply){}",
                mode_word(s.mode),
                if corrected.is_some() {
                    "; each figure and column read again one exact Newton iteration on"
                } else {
                    ""
                }
            ),
            // Newton converged: what is left is the residual's scale, far below any figure printed; the
            // angles' estimate says how far.
            angle_error_deg: angle_error,
            length_error_m: constraint_residual,
            force_residual,
            constraint_residual,
            columns,
            within_tolerance: within,
        },
        warnings,
    })
}
