//! The comparison's page: the figures side by side, the geometry of every model overlaid, every curve
//! overlaid.

use super::charts::{write_chart, write_chart_script};
use super::figures::estimate_words;
use super::{write_foot, write_head, NAME_SHOWN};
use crate::markup::{attr, text};
use crate::suspensions::kc::{fixed, Chart, Figure, KcReport};
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
        comparison.figures.len(),
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
    if !comparison.charts.is_empty() {
        write_chart_script(out)?;
    }
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
        "<p class=\"note\">each model's value at the figure's decimals (its error estimate on hover, written out in \
         red where it is over the tolerance on figures), then each later model's difference to the first; every \
         number, with every estimate, is in compare.csv</p>"
    )?;
    write_figure_rows(out, comparison, models, &letters)?;
    writeln!(out, "</section>")
}

/// The figures' table: a row per analysis, then its figures in words with their unit, each model's value and
/// each later model's difference to the first, at the figure's decimals; the estimate is a value's hover text,
/// and written under it where it matters.
fn write_figure_rows(
    out: &mut String,
    comparison: &crate::suspensions::compare::Comparison,
    models: &[(&str, &KcReport)],
    letters: &[(String, &str)],
) -> std::fmt::Result {
    let n = models.len();
    writeln!(out, "<div class=\"scroll\"><table class=\"numbers comparison\">")?;
    write!(out, "<thead><tr><th>figure</th><th>unit</th>")?;
    for (l, _) in letters {
        write!(out, "<th>{}</th>", text(l))?;
    }
    for (l, _) in letters.iter().skip(1) {
        write!(out, "<th>{} − {}</th>", text(l), text(&letters[0].0))?;
    }
    writeln!(out, "</tr></thead><tbody>")?;
    let mut analysis_shown = None;
    let units = comparison.units;
    for compared in &comparison.figures {
        let first = compared.first();
        if analysis_shown != Some(compared.analysis) {
            let name = compared.analysis.name();
            writeln!(out, "<tr class=\"group\"><th colspan=\"{}\">{}</th></tr>", 2 + 2 * n - 1, text(name))?;
            analysis_shown = Some(compared.analysis);
        }
        let shown = first.written(units);
        let number = |f: Option<&Figure>| {
            f.and_then(|f| f.written(units).value).map_or(String::new(), |v| fixed(v, shown.decimals))
        };
        write!(out, "<tr><td>{}</td><td>{}</td>", text(&first.label), text(shown.unit))?;
        for (k, figure) in compared.figures.iter().enumerate() {
            // The value and its estimate in the first model's units, against that model's own tolerance.
            let relative = models[k].1.settings.tolerance.relative;
            let matters = figure.as_ref().is_some_and(|f| f.estimate_matters(relative));
            let estimate = figure.as_ref().and_then(|f| estimate_words(f, units)).unwrap_or_default();
            if matters {
                write!(
                    out,
                    "<td>{}<br/><span class=\"over\">{}</span></td>",
                    number(figure.as_ref()),
                    text(&estimate)
                )?;
            } else {
                write!(out, "<td title=\"{}\">{}</td>", attr(&estimate), number(figure.as_ref()))?;
            }
        }
        for k in 1..compared.figures.len() {
            write!(out, "<td>{}</td>", number(compared.difference(k).as_ref()))?;
        }
        writeln!(out, "</tr>")?;
    }
    writeln!(out, "</tbody></table></div>")
}
