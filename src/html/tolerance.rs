//! The tolerance stack-up's page: the figures left out, every spread, and each figure's largest contributors.

use super::charts::write_bars;
use super::tables::write_open_table;
use super::{write_foot, write_head, NAME_SHOWN};
use crate::markup::text;
use crate::suspensions::design::parameter_words;
use crate::suspensions::kc::significant;
use serde_json::Value;
use std::fmt::Write;

/// The stack-up's report as one self-contained HTML page: per figure, its value, first-order worst case
/// and standard deviation beside the Monte Carlo's when run, and its largest contributors as a bar chart;
/// the figures left out and the samples that failed, with why; how the run was made.
pub fn tolerance_html(
    stack: &crate::suspensions::design::tolerance::StackUp,
    model_name: &str,
    provenance: &Value,
) -> String {
    let mut page = String::new();
    // Writing into a String cannot fail.
    let _ = write_tolerance_page(&mut page, stack, model_name, provenance);
    page
}

fn write_tolerance_page(
    out: &mut String,
    stack: &crate::suspensions::design::tolerance::StackUp,
    model_name: &str,
    provenance: &Value,
) -> std::fmt::Result {
    let name = crate::plot::shown(model_name, NAME_SHOWN);
    let lede = format!(
        "{} numbers within their tolerances, {} figures; first order from the sensitivities (worst case: \
         every number at the end of its band that moves the figure the same way; σ: the numbers independent and \
         uniform over their bands){}.",
        stack.bands.len(),
        stack.spreads.len(),
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
    write_contributors(out, stack)?;
    write_foot(out, provenance)
}

/// The section "Left out": the analyses that failed, the figures left out and the samples that failed, each
/// with why; nothing when there are none.
fn write_left_out(out: &mut String, stack: &crate::suspensions::design::tolerance::StackUp) -> std::fmt::Result {
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

/// The section "The largest contributors": per figure, its value, worst case and σ (and the sampled σ), its
/// eight largest contributors as a bar chart.
fn write_contributors(out: &mut String, stack: &crate::suspensions::design::tolerance::StackUp) -> std::fmt::Result {
    writeln!(out, "<section id=\"contributors\">")?;
    writeln!(out, "<h2>The largest contributors</h2>")?;
    for s in &stack.spreads {
        let unit = s.unit.shown();
        writeln!(out, "<figure>")?;
        writeln!(
            out,
            "<figcaption>{} {}: {} {symbol}, ±{} worst case, σ {}{}</figcaption>",
            text(s.analysis.name()),
            text(&s.figure),
            text(&significant(s.value * unit.factor, 4)),
            text(&significant(s.worst_case * unit.factor, 3)),
            text(&significant(s.sigma * unit.factor, 3)),
            s.sampled.map_or(String::new(), |m| format!(" (sampled σ {})", significant(m.sigma * unit.factor, 3))),
            symbol = text(unit.symbol),
        )?;
        let bars: Vec<(String, f64)> = s
            .contributions
            .iter()
            .take(8)
            .map(|(p, c)| (parameter_words(&stack.parameters.pointers[*p]), *c * unit.factor))
            .collect();
        write_bars(out, &bars, unit.symbol)?;
        writeln!(out, "</figure>")?;
    }
    writeln!(out, "</section>")
}
