//! Vertical force at the contact patch, the wheel free (the paper's case): the wheel rate and what the
//! load does to toe and camber.

use crate::analysis::{design_wheel_load_estimated, vertical_force_sweep_with, LoadRow};
use crate::assembly::Rig;
use crate::kc::figures;
use crate::kc::models::Models;
use crate::kc::reduce::{axis, chart, corner_drawing, deg, finish, Design, Reduction};
use crate::kc::report::{AnalysisReport, Column, Figure, Table};
use crate::kc::settings::{Analysis, Cause, Declaration, DefaultRange, FigureRows, Quantity, Settings};
use elastokin_solver::replay::Taping;

/// The vertical force sweep, as the command and the reports name it: its design position is the design
/// wheel load, which only the solved model gives.
pub(super) const DECLARATION: Declaration = Declaration {
    name: "vertical-force",
    parameter: "vertical force at the contact patch, N, up +",
    quantity: Quantity::Force,
    rig_words: Some("wheel free (or at --load-point)"),
    default_range: DefaultRange::AroundDesignLoad,
    design_parameter: None,
    figure_rows: FigureRows::DesignOnly,
};

pub(super) fn vertical_force(models: &Models, s: &Settings, taping: &Taping) -> Result<AnalysisReport, Cause> {
    let file = models.file();
    let held = models.corner_ref(Rig::WheelTravel)?;
    let (design_load, design_load_error) = design_wheel_load_estimated(held, s.error_estimate, taping)?;
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
        s.extras_reading(range, design_load, DECLARATION.figure_rows, taping),
    )?;
    let table = |rows: &[LoadRow]| {
        let columns: [Column<LoadRow>; 5] = [
            Column::new("force_n", |r: &LoadRow| r.load.into()),
            Column::new("wheel_travel_m", |r: &LoadRow| (r.attitude.wheel_centre.z - z0).into()),
            Column::new("toe_deg", |r: &LoadRow| deg(r.attitude.toe).into()),
            Column::new("camber_deg", |r: &LoadRow| deg(r.attitude.camber).into()),
            Column::new("contact_patch_z_m", |r: &LoadRow| r.contact_patch.z.into()),
        ];
        Table::of_columns("vertical_force", &columns, rows)
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
        &format!("vertical force at the {} [N]", super::load_sweep::where_loaded(s)),
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
        super::load_sweep::where_loaded(s),
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
