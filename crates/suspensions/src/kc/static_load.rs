//! The static load case: the corner at rest under the vehicle's corner load, applied at once from the
//! design position.

use crate::analysis::{static_load_case_estimated, ComponentForce, StaticLoad};
use crate::assembly::Rig;
use crate::kc::figures;
use crate::kc::models::Models;
use crate::kc::report::{Accuracy, AnalysisReport, Cell, Column, Figure, Table, Warning};
use crate::kc::settings::{mode_word, Analysis, Cause, Declaration, DefaultRange, FigureRows, Quantity, Settings};
use elastokin_solver::replay::Taping;

/// The static load case: no range, the corner load applied at once.
pub(super) const DECLARATION: Declaration = Declaration {
    name: "static-load",
    parameter: "corner load of the model file's vehicle section, N, applied at once",
    quantity: Quantity::Force,
    rig_words: None,
    default_range: DefaultRange::NoRange,
    design_parameter: None,
    figure_rows: FigureRows::DesignOnly,
};

pub(super) fn static_load(models: &Models, s: &Settings, taping: &Taping) -> Result<AnalysisReport, Cause> {
    let file = models.file();
    let vehicle = file.vehicle.as_ref().ok_or_else(|| {
        Cause::Lacks(
            "the model file has no \"vehicle\" section with the corner_load to carry (see examples/macpherson.json)"
                .into(),
        )
    })?;
    let corner = models.corner(Rig::Free)?;
    let (rest, corrected) = static_load_case_estimated(corner, vehicle.corner_load, s.error_estimate, taping)?;
    let table = static_load_table(&rest);
    let mut at_rest = rest_figures(&rest);
    let columns = match &corrected {
        Some(corrected) => estimate(&mut at_rest, &rest, corrected, &table),
        None => Vec::new(),
    };
    let angle_error = [&figures::TOE_AT_REST, &figures::CAMBER_AT_REST]
        .iter()
        .filter_map(|kind| at_rest.iter().find(|f| f.key == kind.key)?.error)
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
        figures: at_rest,
        units: s.units,
        table,
        compliance: None,
        wheel_compliance_at_design: None,
        charts: Vec::new(),
        motion: None,
        construction: Vec::new(),
        envelope: None,
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

/// The static load's table: the force and torque each joint and element carries at rest, by name and the
/// bodies either side.
fn static_load_table(rest: &StaticLoad) -> Table {
    let text = |name: &str| Cell::Text(name.to_string());
    let columns: [Column<ComponentForce>; 9] = [
        Column::new("component", |c: &ComponentForce| text(&c.name)),
        Column::new("body", |c: &ComponentForce| text(&c.body)),
        Column::new("other_body", |c: &ComponentForce| text(&c.other_body)),
        Column::new("force_x_n", |c: &ComponentForce| c.force.x.into()),
        Column::new("force_y_n", |c: &ComponentForce| c.force.y.into()),
        Column::new("force_z_n", |c: &ComponentForce| c.force.z.into()),
        Column::new("torque_x_nm", |c: &ComponentForce| c.torque.x.into()),
        Column::new("torque_y_nm", |c: &ComponentForce| c.torque.y.into()),
        Column::new("torque_z_nm", |c: &ComponentForce| c.torque.z.into()),
    ];
    Table::of_columns("static_load", &columns, rest.forces.all())
}

/// The static load's figures at `rest`.
fn rest_figures(rest: &StaticLoad) -> Vec<Figure> {
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
}

/// Each figure's error estimate: its change one exact Newton iteration on (`corrected`, as a sweep's rows
/// are read again), added to `figures`; and the component forces' likewise, column by column of `table`.
fn estimate(
    figures: &mut [Figure],
    rest: &StaticLoad,
    corrected: &StaticLoad,
    table: &Table,
) -> Vec<(String, Option<f64>)> {
    for (f, g) in figures.iter_mut().zip(rest_figures(corrected)) {
        f.error = f.value.zip(g.value).map(|(a, b)| (a - b).abs());
    }
    let components = |r: &StaticLoad| -> Vec<[f64; 6]> {
        r.forces.all().map(|c| [c.force.x, c.force.y, c.force.z, c.torque.x, c.torque.y, c.torque.z]).collect()
    };
    let (at, on) = (components(rest), components(corrected));
    let mut columns: Vec<(String, Option<f64>)> = table.columns.iter().map(|c| (c.clone(), None)).collect();
    for k in 0..6 {
        let largest = at.iter().zip(&on).map(|(a, b)| (a[k] - b[k]).abs()).fold(0.0, f64::max);
        columns[3 + k].1 = Some(largest);
    }
    columns
}
