//! The sweep the load analyses share: a road load or the model file's own loads, swept with the corner
//! load carried; its table, figures and charts.

use crate::analysis::{
    design_wheel_load_estimated, model_load_sweep_with, wheel_load_sweep_with, ComponentForces, LoadRow, WheelLoad,
};
use crate::assembly::{LoadPoint, Rig};
use crate::description::Side;
use crate::file::SuspensionFile;
use crate::kc::chart::Chart;
use crate::kc::figures;
use crate::kc::models::Models;
use crate::kc::reduce::{axis, bushings_share, chart, corner_drawing, deg, finish, Design, Reduction};
use crate::kc::report::{AnalysisReport, Cell, Column, Figure, FigureKind, Table};
use crate::kc::settings::{Analysis, Cause, Quantity, Settings};
use crate::kc::unit::Unit;
use elastokin_solver::replay::Taping;
use elastokin_solver::LoadPath;

/// Why the `loads` analysis cannot run.
pub(super) const NO_LOADS: &str = "the model has no load case: give \"loads\" in the general form (a force at a point \
                                    of a body, or a moment), see docs/model-file.md";

/// Where the rig's forces act, in words.
pub(super) fn where_loaded(s: &Settings) -> &'static str {
    match s.load_point {
        LoadPoint::ContactPatch => "contact patch",
        LoadPoint::WheelCentre => "wheel centre",
    }
}

/// Columns of the force in every joint and element: `name force_x_n`, … for each.
/// The columns of the force and torque each joint and element carries (by the components of `forces`, a
/// row's, every row naming the same in the same order): `"<name> force_x_n"` … `"<name> torque_z_nm"`.
fn component_columns<'a>(forces: &ComponentForces) -> Vec<Column<'a, LoadRow>> {
    let mut columns = Vec::new();
    for (k, c) in forces.all().enumerate() {
        for (what, unit, torque) in [("force", "n", false), ("torque", "nm", true)] {
            for (axis, name) in ["x", "y", "z"].into_iter().enumerate() {
                columns.push(Column::new(format!("{} {what}_{name}_{unit}", c.name), move |r: &LoadRow| {
                    Cell::from(r.forces.get(k).map(|c| if torque { c.torque[axis] } else { c.force[axis] }))
                }));
            }
        }
    }
    columns
}

/// A road load or the model's own loads, swept with the corner load carried.
pub(super) fn loaded(
    models: &Models,
    analysis: Analysis,
    s: &Settings,
    taping: &Taping,
) -> Result<AnalysisReport, Cause> {
    let file = models.file();
    let quantity = analysis.declaration().quantity;
    let unit = quantity.unit();
    let range = analysis.range_or_default(s.range)?;
    let corner_load = match &file.vehicle {
        Some(v) => v.corner_load,
        None => design_wheel_load_estimated(models.corner_ref(Rig::WheelTravel)?, false, taping)?.0,
    };
    let rig = if s.height_held { Rig::HeightHeld } else { Rig::Free };
    let mut corner = models.corner(rig)?;
    corner.load_point = s.load_point;
    // Drawn as walked: with the model's own loads, once they are added.
    let drawing;
    // The figures read the rates at zero load (at design) and the last row.
    let extras = s.extras_reading(range, 0.0, analysis.declaration().figure_rows, taping);
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
    let table = |rows: &[LoadRow]| load_sweep_table(&stem, quantity, rows);
    let figures = |rows: &[LoadRow], design: Design<LoadRow>| load_sweep_figures(quantity, rows, design);
    let charts = load_sweep_charts(file, analysis, &stem, &out.rows);
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
        let rigid = loaded(rigid, analysis, &Settings { motion: false, ..*s }, taping);
        bushings_share(&mut report, "steer", "lateral-force compliance steer", rigid);
    }
    Ok(report)
}

/// A load sweep's table `stem`: the load parameter (of `quantity`), the wheel's attitude and the patch's
/// motion, the wheel load, and the force and torque of every joint and element.
fn load_sweep_table(stem: &str, quantity: Quantity, rows: &[LoadRow]) -> Table {
    let column = match quantity {
        Quantity::Force => "load_n",
        Quantity::Torque => "load_nm",
        Quantity::Travel | Quantity::Fraction => "fraction",
    };
    let mut columns: Vec<Column<LoadRow>> = vec![
        Column::new(column, |r: &LoadRow| r.load.into()),
        Column::new("toe_deg", |r: &LoadRow| deg(r.attitude.toe).into()),
        Column::new("camber_deg", |r: &LoadRow| deg(r.attitude.camber).into()),
        Column::new("wheel_centre_x_m", |r: &LoadRow| r.attitude.wheel_centre.x.into()),
        Column::new("wheel_centre_y_m", |r: &LoadRow| r.attitude.wheel_centre.y.into()),
        Column::new("wheel_centre_z_m", |r: &LoadRow| r.attitude.wheel_centre.z.into()),
        Column::new("patch_dx_m", |r: &LoadRow| r.patch_displacement.x.into()),
        Column::new("patch_dy_m", |r: &LoadRow| r.patch_displacement.y.into()),
        Column::new("patch_dz_m", |r: &LoadRow| r.patch_displacement.z.into()),
        Column::new("wheel_load_n", |r: &LoadRow| r.wheel_load.into()),
    ];
    if let Some(first) = rows.first() {
        columns.extend(component_columns(&first.forces));
    }
    Table::of_columns(stem, &columns, rows)
}

/// A load sweep's figures: the compliance steer and camber at design, per unit of the load of
/// `quantity`, and toe and camber at the last row.
fn load_sweep_figures(quantity: Quantity, rows: &[LoadRow], design: Design<LoadRow>) -> Vec<Figure> {
    let unit = quantity.unit();
    // Per kN of a force, per kN·m of a torque, per load case of the model's own.
    let per_unit = match quantity {
        Quantity::Force => Unit::DegreePerKilonewton,
        Quantity::Torque => Unit::DegreePerKilonewtonMetre,
        Quantity::Travel | Quantity::Fraction => Unit::DegreePerLoadCase,
    };
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
}

/// A load sweep's chart `stem`: toe and camber, and the contact patch's motion, over the load.
fn load_sweep_charts(file: &SuspensionFile, analysis: Analysis, stem: &str, rows: &[LoadRow]) -> Vec<Chart> {
    let (name, unit) = (analysis.name(), analysis.unit());
    vec![chart(
        file,
        stem,
        &format!("toe and camber under {}", name.replace('-', " ")),
        &format!("{} [{unit}]", analysis.parameter().split(',').next().unwrap_or(name)),
        axis(
            "angle [deg]",
            rows,
            |r| r.load,
            &[
                ("toe (in +)", &|r: &LoadRow| Some(deg(r.attitude.toe))),
                ("camber (top out +)", &|r: &LoadRow| Some(deg(r.attitude.camber))),
            ],
        ),
        Some(axis(
            "contact patch displacement [mm]",
            rows,
            |r| r.load,
            &[
                ("patch x", &|r: &LoadRow| Some(r.patch_displacement.x * 1e3)),
                ("patch y", &|r: &LoadRow| Some(r.patch_displacement.y * 1e3)),
            ],
        )),
        Some(0.0),
    )]
}
