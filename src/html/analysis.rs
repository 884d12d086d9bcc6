//! One analysis's section of the K&C report: what was run, its headline figures, the accuracy line, its
//! warnings, its plots, the wheel compliance at design and, folded, its tables.

use super::charts::write_chart;
use super::figures::write_figures;
use super::tables::{cell, plain, write_table};
use crate::markup::{attr, text};
use crate::suspensions::kc::{significant, AnalysisReport, Cell, Chart, KcReport};
use std::fmt::Write;

/// The section of the analysis `a` of `report`, its plots drawn by `render_chart`.
pub(super) fn write_analysis(
    out: &mut String,
    a: &AnalysisReport,
    report: &KcReport,
    render_chart: &dyn Fn(&Chart) -> Result<String, String>,
) -> std::fmt::Result {
    writeln!(out, "<section class=\"analysis\" id=\"{}\">", attr(a.analysis.name()))?;
    writeln!(out, "<h2>{}</h2>", text(a.analysis.name()))?;
    writeln!(out, "<p class=\"description\">{}</p>", text(&a.description))?;
    // The static load is one equilibrium at one load: no range, no steps to count.
    let walked = if a.range.0 == a.range.1 {
        format!("at {}", plain(a.range.0))
    } else {
        let steps = if a.steps == 1 { "1 step".to_string() } else { format!("{} steps", a.steps) };
        format!("{} to {}, {steps}", plain(a.range.0), plain(a.range.1))
    };
    writeln!(out, "<p class=\"note\">load parameter: {}; {walked}</p>", text(&a.parameter))?;

    write_figures(out, &a.figures, a.units, report.settings.tolerance.relative)?;
    write_accuracy(out, a, report)?;
    if !a.warnings.is_empty() {
        writeln!(out, "<ul class=\"warnings\">")?;
        for w in &a.warnings {
            writeln!(out, "<li><code>{}</code> {}</li>", text(w.code), text(&w.message))?;
        }
        writeln!(out, "</ul>")?;
    }

    if !a.charts.is_empty() {
        writeln!(out, "<div class=\"charts\">")?;
        for chart in &a.charts {
            write_chart(out, chart, render_chart)?;
        }
        writeln!(out, "</div>")?;
    }

    if let Some(c) = &a.wheel_compliance_at_design {
        write_compliance_matrix(out, c)?;
    }
    write_table(out, &a.table, "the rows")?;
    if let Some(c) = &a.compliance {
        write_table(out, c, "the wheel compliance at every row")?;
    }
    writeln!(out, "</section>")
}

/// The accuracy line: the estimated angle and length errors against the tolerance, and the residuals.
fn write_accuracy(out: &mut String, a: &AnalysisReport, report: &KcReport) -> std::fmt::Result {
    let acc = &a.accuracy;
    let tol = report.settings.tolerance;
    // An estimate the report could not make is said so, never printed as a number.
    let or_not = |v: f64, scale: f64, unit: &str| {
        if v.is_finite() {
            format!("{}{unit}", significant(v * scale, 2))
        } else {
            "not estimated".into()
        }
    };
    let verdict = if acc.within_tolerance {
        "<span class=\"ok\">within tolerance</span>"
    } else {
        "<span class=\"bad\">over tolerance</span>"
    };
    writeln!(
        out,
        "<p class=\"accuracy\">error estimate: angles {}, lengths {} — {verdict} ({} deg, {} mm, {} % on figures); \
         force residual {} (relative to the force scale), constraint residual {} (m, rad). \
         <span class=\"quiet\">{}</span></p>",
        text(&or_not(acc.angle_error_deg, 1.0, " deg")),
        text(&or_not(acc.length_error_m, 1e3, " mm")),
        text(&significant(tol.angle_deg, 2)),
        text(&significant(tol.length_m * 1e3, 2)),
        text(&significant(tol.relative * 100.0, 2)),
        text(&or_not(acc.force_residual, 1.0, "")),
        text(&or_not(acc.constraint_residual, 1.0, "")),
        text(&acc.method)
    )
}

/// The 6×6 wheel compliance at design, folded.
fn write_compliance_matrix(out: &mut String, c: &[[f64; 6]; 6]) -> std::fmt::Result {
    let rows = ["x [m]", "y [m]", "z [m]", "rot x [rad]", "rot y [rad]", "rot z [rad]"];
    let columns = ["Fx [N]", "Fy [N]", "Fz [N]", "Mx [N·m]", "My [N·m]", "Mz [N·m]"];
    writeln!(out, "<details>")?;
    writeln!(out, "<summary>wheel compliance at design: wheel-centre response per unit load there</summary>")?;
    writeln!(out, "<div class=\"scroll\"><table class=\"numbers\">")?;
    write!(out, "<thead><tr><th>response per</th>")?;
    for c in columns {
        write!(out, "<th>{}</th>", text(c))?;
    }
    writeln!(out, "</tr></thead><tbody>")?;
    for (name, row) in rows.iter().zip(c) {
        write!(out, "<tr><th>{}</th>", text(name))?;
        for &v in row {
            write!(out, "<td>{}</td>", cell(&Cell::from(v), 3))?;
        }
        writeln!(out, "</tr>")?;
    }
    writeln!(out, "</tbody></table></div>")?;
    writeln!(out, "</details>")
}
