//! The tune's page: the targets met or not and why, the free numbers before and after, each curve target
//! before and after, every residual and iteration.

use super::charts::{write_chart, write_chart_script};
use super::tables::{write_open_table, write_table};
use super::{write_foot, write_head, NAME_SHOWN};
use crate::markup::text;
use crate::suspensions::design::fit::FitUncertainty;
use crate::suspensions::design::parameter::{is_length, parameter_words};
use crate::suspensions::kc::{significant, Cell, Chart, Table};
use serde_json::Value;
use std::fmt::Write;

/// The tune's report as one self-contained HTML page: whether every target is met and why one is not,
/// the free numbers before and after, each curve target's column before and after with its points, every
/// residual and every iteration, and how the run was made. `render_chart` as for [`report_html`](super::report_html).
pub fn tune_html<E: std::fmt::Display>(
    tuned: &crate::suspensions::design::tune::Tuned,
    targets: &crate::suspensions::design::targets::Targets,
    model_name: &str,
    provenance: &Value,
    render_chart: impl Fn(&Chart) -> Result<String, E>,
) -> String {
    let render = |chart: &Chart| render_chart(chart).map_err(|e| e.to_string());
    let mut page = String::new();
    // Writing into a String cannot fail.
    let _ = write_tune_page(&mut page, tuned, targets, model_name, provenance, &render);
    page
}

fn write_tune_page(
    out: &mut String,
    tuned: &crate::suspensions::design::tune::Tuned,
    targets: &crate::suspensions::design::targets::Targets,
    model_name: &str,
    provenance: &Value,
    render_chart: &dyn Fn(&Chart) -> Result<String, String>,
) -> std::fmt::Result {
    let name = crate::plot::shown(model_name, NAME_SHOWN);
    let met = tuned.verdicts.iter().filter(|v| v.met).count();
    let last = tuned.iterations.last().map_or(0, |i| i.evaluations);
    let broken = tuned.packaging.iter().filter(|p| p.broken_by > 0.0).count();
    let packaging = match (tuned.packaging.len(), broken) {
        (0, _) => String::new(),
        (_, 0) => "; the packaging holds".to_string(),
        (all, broken) => format!("; {broken} of {all} packaging constraints broken"),
    };
    let lede = format!(
        "{met} of {} targets met{packaging}; {} iterations, {last} K&C evaluations; {}.",
        tuned.verdicts.len(),
        tuned.iterations.len().saturating_sub(1),
        tuned.stopped
    );
    write_head(out, &format!("Tune: {name}"), &lede)?;
    write_targets(out, tuned)?;
    writeln!(out, "<section id=\"parameters\">")?;
    writeln!(out, "<h2>The free numbers</h2>")?;
    write_open_table(out, &moved_in_words(tuned, targets))?;
    write_uncertainty(out, tuned, targets)?;
    writeln!(out, "</section>")?;
    writeln!(out, "<section id=\"curves\">")?;
    writeln!(out, "<h2>Before and after</h2>")?;
    let charts = tuned.charts(targets, model_name);
    if charts.is_empty() {
        writeln!(out, "<p class=\"none\">no curve targets: the figures are in the table of targets</p>")?;
    }
    for chart in &charts {
        write_chart(out, chart, render_chart)?;
    }
    if !charts.is_empty() {
        write_chart_script(out)?;
    }
    writeln!(out, "</section>")?;
    writeln!(out, "<section id=\"residuals\">")?;
    writeln!(out, "<h2>Every residual</h2>")?;
    write_table(out, &tuned.residual_table(targets), "each figure and curve point, before and after")?;
    write_table(out, &tuned.iteration_table(), "each iteration")?;
    writeln!(out, "</section>")?;
    write_foot(out, provenance)
}

/// The section "Targets": how each target was judged (its largest miss against its tolerance, or its misses'
/// χ² against the measured data's noise), whether it is met and why not; each packaging constraint, whether
/// it holds.
fn write_targets(out: &mut String, tuned: &crate::suspensions::design::tune::Tuned) -> std::fmt::Result {
    writeln!(out, "<section id=\"targets\">")?;
    writeln!(out, "<h2>Targets</h2>")?;
    if let Some(o) = &tuned.objective {
        writeln!(out, "<p class=\"verdict\">{}; each target below is a bound it keeps.</p>", text(&o.said()))?;
    }
    writeln!(out, "<table class=\"figures\"><thead><tr><th>target</th><th>judged by</th><th>met</th><th>why not</th></tr></thead><tbody>")?;
    for v in &tuned.verdicts {
        let (class, said) = if v.met { ("ok", "yes") } else { ("bad", "no") };
        writeln!(
            out,
            "<tr><td>{}</td><td>{}</td><td class=\"{class}\">{said}</td><td>{}</td></tr>",
            text(&v.target),
            text(&v.judged),
            text(v.why.as_deref().unwrap_or(""))
        )?;
    }
    writeln!(out, "</tbody></table>")?;
    if !tuned.packaging.is_empty() {
        writeln!(out, "<h3>Packaging</h3>")?;
        writeln!(out, "<table class=\"figures\"><thead><tr><th>constraint</th><th>broken by (mm)</th><th>holds</th></tr></thead><tbody>")?;
        for p in &tuned.packaging {
            let (class, said) = if p.broken_by == 0.0 { ("ok", "yes") } else { ("bad", "no") };
            writeln!(
                out,
                "<tr><td>{}</td><td class=\"value\">{}</td><td class=\"{class}\">{said}</td></tr>",
                text(&p.constraint),
                text(&significant(p.broken_by * 1e3, 3)),
            )?;
        }
        writeln!(out, "</tbody></table>")?;
    }
    writeln!(out, "</section>")
}

/// What the fit can know of the free numbers: how the standard uncertainties are taken, the numbers a
/// bound holds, and the directions the targets cannot tell.
fn write_uncertainty(
    out: &mut String,
    tuned: &crate::suspensions::design::tune::Tuned,
    targets: &crate::suspensions::design::targets::Targets,
) -> std::fmt::Result {
    let Some(u) = &tuned.uncertainty else {
        return writeln!(
            out,
            "<p class=\"note\">an objective's optimum is no fit: its numbers have no uncertainty</p>"
        );
    };
    let pointers: Vec<String> = targets.free.iter().map(|f| f.pointer.clone()).collect();
    writeln!(out, "<p class=\"note\">{}</p>", text(&u.basis()))?;
    if !u.at_bound.is_empty() {
        let held: Vec<String> = u.at_bound.iter().map(|&k| parameter_words(&pointers[k])).collect();
        writeln!(out, "<p class=\"note\">held by a bound, not fitted: {}</p>", text(&held.join(", ")))?;
    }
    for unseen in &u.unseen {
        writeln!(out, "<p class=\"over\">{}</p>", text(&FitUncertainty::not_unique(unseen, &pointers)))?;
    }
    Ok(())
}

/// The free numbers before and after as an engineer reads them: a hardpoint's coordinate by the point and
/// its axis, in millimetres; any other number by its pointer, in the file's unit.
fn moved_in_words(
    tuned: &crate::suspensions::design::tune::Tuned,
    targets: &crate::suspensions::design::targets::Targets,
) -> Table {
    let mut table = tuned.moved_table(targets);
    table.columns.insert(1, "unit".into());
    for (row, free) in table.rows.iter_mut().zip(&targets.free) {
        let length = is_length(&free.pointer);
        if length {
            for cell in row.iter_mut().skip(1) {
                if let Some(v) = cell.number() {
                    *cell = Cell::from(v * 1e3);
                }
            }
        }
        row[0] = Cell::Text(parameter_words(&free.pointer));
        row.insert(1, Cell::Text(if length { "mm" } else { "as in the file" }.into()));
    }
    table
}
