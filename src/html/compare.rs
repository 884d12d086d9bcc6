//! The comparison's page: the figures side by side, the geometry of every model overlaid, every curve
//! overlaid.

use super::charts::write_chart;
use super::tables::write_open_table;
use super::{write_foot, write_head, NAME_SHOWN};
use crate::markup::text;
use crate::suspensions::kc::{Cell, Chart, KcReport};
use serde_json::Value;
use std::fmt::Write;

/// The comparison of designs as one page: the figures side by side with their differences and error
/// estimates, the geometry of every model overlaid, every curve overlaid (a colour and a legend entry per
/// design), and the analyses a model could not run. `models` are the compared models' names and suites
/// (their geometry); `render_chart` as for [`report_html`](super::report_html).
pub fn compare_html<E: std::fmt::Display>(
    comparison: &crate::suspensions::compare::Comparison,
    models: &[(&str, &KcReport)],
    provenance: &Value,
    render_chart: impl Fn(&Chart) -> Result<String, E>,
) -> String {
    let render = |chart: &Chart| render_chart(chart).map_err(|e| e.to_string());
    let mut page = String::new();
    // Writing into a String cannot fail.
    let _ = write_compare_page(&mut page, comparison, models, provenance, &render);
    page
}

fn write_compare_page(
    out: &mut String,
    comparison: &crate::suspensions::compare::Comparison,
    models: &[(&str, &KcReport)],
    provenance: &Value,
    render_chart: &dyn Fn(&Chart) -> Result<String, String>,
) -> std::fmt::Result {
    let names: Vec<String> = comparison.names.iter().map(|n| crate::plot::shown(n, NAME_SHOWN)).collect();
    let lede = format!(
        "{} designs; {} figures side by side, {} curves overlaid; written by elastokin {}.",
        names.len(),
        comparison.figures.rows.len(),
        comparison.charts.len(),
        env!("CARGO_PKG_VERSION")
    );
    write_head(out, &format!("Comparison: {}", names.join(", ")), &lede)?;
    for (name, report) in models {
        for f in &report.failed {
            writeln!(
                out,
                "<p class=\"bad\">{}: {} failed: {}</p>",
                text(&crate::plot::shown(name, NAME_SHOWN)),
                text(f.analysis.name()),
                text(&f.reason)
            )?;
        }
    }
    write_figures(out, comparison, models)?;
    crate::view::write_overlay(out, models)?;
    writeln!(out, "<section id=\"curves\">")?;
    writeln!(out, "<h2>Curves</h2>")?;
    writeln!(out, "<div class=\"charts\">")?;
    for chart in &comparison.charts {
        write_chart(out, chart, render_chart)?;
    }
    writeln!(out, "</div>")?;
    writeln!(out, "</section>")?;
    write_foot(out, provenance)
}

/// The section "Figures": the designs by letter, then each figure's value and error estimate per model and
/// each later model's difference to the first.
fn write_figures(
    out: &mut String,
    comparison: &crate::suspensions::compare::Comparison,
    models: &[(&str, &KcReport)],
) -> std::fmt::Result {
    writeln!(out, "<section id=\"figures\">")?;
    writeln!(out, "<h2>Figures</h2>")?;
    // The designs by letter in the table's header, so that long names do not make it unreadable; the
    // names are whole in compare.csv's header and in the legends.
    let letter = |k: usize| if k < 26 { char::from(b'A' + k as u8).to_string() } else { format!("#{}", k + 1) };
    let letters: Vec<(String, &str)> = models.iter().enumerate().map(|(k, (name, _))| (letter(k), *name)).collect();
    writeln!(out, "<ul class=\"designs\">")?;
    for (k, (l, name)) in letters.iter().enumerate() {
        writeln!(
            out,
            "<li><b style=\"color: {}\">{l}</b> {}</li>",
            crate::plot::series_colour_hex(k),
            text(&crate::plot::shown(name, NAME_SHOWN))
        )?;
    }
    writeln!(out, "</ul>")?;
    writeln!(
        out,
        "<p class=\"note\">each model's value and its error estimate (±), then each later model's difference to \
         the first; every number is in compare.csv</p>"
    )?;
    let mut shown = comparison.figures.clone();
    // Each figure in words (compare.csv keeps its key, which the tools that read it look up).
    let words = |analysis: &str, key: &str| {
        let analyses = models.iter().flat_map(|(_, r)| &r.analyses).filter(|a| a.analysis.name() == analysis);
        analyses.filter_map(|a| a.figure(key)).map(|f| f.label.clone()).next()
    };
    for row in &mut shown.rows {
        if let [Cell::Text(analysis), Cell::Text(key), ..] = &row[..] {
            if let Some(label) = words(analysis, key) {
                row[1] = Cell::Text(label);
            }
        }
    }
    shown.columns.truncate(3);
    for (l, _) in &letters {
        shown.columns.push(l.clone());
        shown.columns.push(format!("± {l}"));
    }
    for (l, _) in letters.iter().skip(1) {
        shown.columns.push(format!("{l} − {}", letters[0].0));
    }
    write_open_table(out, &shown)?;
    writeln!(out, "</section>")
}
