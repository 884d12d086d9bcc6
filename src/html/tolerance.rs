//! The tolerance stack-up's page: the figures left out, every spread, the alignment's adjusters, each
//! figure's largest contributors and, from a Monte Carlo, its samples' histogram.

use super::charts::{write_bars, write_histogram};
use super::tables::write_open_table;
use super::{write_foot, write_head, NAME_SHOWN};
use crate::markup::text;
use crate::suspensions::design::tolerance::StackUp;
use crate::suspensions::kc::significant;
use serde_json::Value;
use std::fmt::Write;

/// The stack-up's report as one self-contained HTML page: per figure, its value, first-order worst case
/// and standard deviation beside the Monte Carlo's when run, the share of cars outside its limit, its
/// largest contributors as a bar chart and its samples as a histogram; the adjusters' ranges; the figures
/// left out and the samples that failed, with why; how the run was made.
pub fn tolerance_html(stack: &StackUp, model_name: &str, provenance: &Value) -> String {
    let mut page = String::new();
    // Writing into a String cannot fail.
    let _ = write_tolerance_page(&mut page, stack, model_name, provenance);
    page
}

/// The share of cars outside a limit in words: the first order's (the figure taken as normal), and the
/// samples' with its standard error.
pub fn outside_words(first_order: f64, sampled: Option<(f64, f64)>) -> String {
    let percent = |p: f64| significant(p * 100.0, 3);
    let sampled = sampled.map_or(String::new(), |(p, e)| format!(", sampled {} ± {} %", percent(p), percent(e)));
    format!("outside its limit: {} % (first order, normal){sampled}", percent(first_order))
}

fn write_tolerance_page(out: &mut String, stack: &StackUp, model_name: &str, provenance: &Value) -> std::fmt::Result {
    let name = crate::plot::shown(model_name, NAME_SHOWN);
    let lede = format!(
        "{} sources within their tolerances, {} figures{}; first order from the sensitivities (worst case: \
         every source at the end of its band that moves the figure the same way, a normal band's end at 3σ; σ: \
         the sources independent, a uniform band ±t of σ t/√3){}.",
        stack.sources.len(),
        stack.spreads.len(),
        match stack.adjusters.len() {
            0 => String::new(),
            n => format!(", {n} set at alignment"),
        },
        match stack.spreads.iter().find_map(|s| s.sampled) {
            Some(m) => format!(", checked by a Monte Carlo of {} sampled models", m.count),
            None => String::new(),
        }
    );
    write_head(out, &format!("Tolerance stack-up: {name}"), &lede)?;
    write_left_out(out, stack)?;
    writeln!(out, "<section id=\"spreads\">")?;
    writeln!(out, "<h2>Spreads</h2>")?;
    write_open_table(out, &stack.table())?;
    writeln!(out, "</section>")?;
    if let Some(table) = stack.adjustment_table() {
        writeln!(out, "<section id=\"alignment\">")?;
        writeln!(out, "<h2>Set at alignment</h2>")?;
        writeln!(out, "<p>Each number set so its figure is back at nominal; how far from nominal it is set, in the file's units.</p>")?;
        write_open_table(out, &table)?;
        writeln!(out, "</section>")?;
    }
    write_contributors(out, stack)?;
    write_foot(out, provenance)
}

/// The section "Left out": the analyses that failed, the figures left out and the samples that failed, each
/// with why; nothing when there are none.
fn write_left_out(out: &mut String, stack: &StackUp) -> std::fmt::Result {
    if stack.failed.is_empty() && stack.failed_samples.is_empty() && stack.left_out.is_empty() {
        return Ok(());
    }
    writeln!(out, "<section id=\"left-out\">")?;
    writeln!(out, "<h2>Left out</h2><ul>")?;
    for f in &stack.failed {
        writeln!(out, "<li class=\"error\">{}: {}</li>", text(f.analysis.name()), text(&f.reason))?;
    }
    for (a, f, why) in &stack.left_out {
        writeln!(out, "<li>{} {}: {}</li>", text(a), text(f), text(why))?;
    }
    for why in &stack.failed_samples {
        writeln!(out, "<li class=\"error\">{}</li>", text(why))?;
    }
    writeln!(out, "</ul></section>")
}

/// The section "The largest contributors": per figure, its value, worst case and σ (and the sampled σ), the
/// share of cars outside its limit, its eight largest contributors (ranked by their share of the variance)
/// as a bar chart of their share of the worst case, and its samples' histogram.
fn write_contributors(out: &mut String, stack: &StackUp) -> std::fmt::Result {
    writeln!(out, "<section id=\"contributors\">")?;
    writeln!(out, "<h2>The largest contributors</h2>")?;
    for (j, s) in stack.spreads.iter().enumerate() {
        let unit = s.unit.shown();
        writeln!(out, "<figure>")?;
        writeln!(
            out,
            "<figcaption>{} {}: {} {symbol}, ±{} worst case, σ {}{}{}</figcaption>",
            text(s.analysis.name()),
            text(&s.figure),
            text(&significant(s.value * unit.factor, 4)),
            text(&significant(s.worst_case * unit.factor, 3)),
            text(&significant(s.sigma * unit.factor, 3)),
            s.sampled.map_or(String::new(), |m| format!(" (sampled σ {})", significant(m.sigma * unit.factor, 3))),
            s.outside
                .map_or(String::new(), |p| format!("; {}", text(&outside_words(p, s.sampled.and_then(|m| m.outside))))),
            symbol = text(unit.symbol),
        )?;
        let bars: Vec<(String, f64)> = s
            .contributions
            .iter()
            .take(8)
            .map(|c| (stack.source_words(c.source).to_string(), c.worst * unit.factor))
            .collect();
        write_bars(out, &bars, unit.symbol)?;
        let samples: Vec<f64> = stack.sampled_values(j).iter().map(|v| v * unit.factor).collect();
        if samples.len() >= 2 {
            let limit = s.limit.as_ref().map(|l| (l.min, l.max));
            write_histogram(out, &samples, s.value * unit.factor, limit, unit.symbol)?;
        }
        writeln!(out, "</figure>")?;
    }
    writeln!(out, "</section>")
}
