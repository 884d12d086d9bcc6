//! The top of the K&C report, what the colleague must know before reading any figure: every warning with its
//! code, and the analyses that failed with why.

use crate::markup::text;
use crate::suspensions::kc::{KcReport, Warning};
use std::fmt::Write;

/// The section "Warnings": the model's and each analysis's, a row each with its code, or "no warnings".
pub(super) fn write_warnings(out: &mut String, report: &KcReport) -> std::fmt::Result {
    let warnings: Vec<(&str, &Warning)> = report
        .warnings
        .iter()
        .map(|w| ("model", w))
        .chain(report.analyses.iter().flat_map(|a| a.warnings.iter().map(move |w| (a.analysis.name(), w))))
        .collect();
    writeln!(out, "<section id=\"warnings\">")?;
    writeln!(out, "<h2>Warnings</h2>")?;
    if warnings.is_empty() {
        writeln!(out, "<p class=\"none\">no warnings</p>")?;
    } else {
        writeln!(out, "<table class=\"warnings\">")?;
        writeln!(out, "<thead><tr><th>about</th><th>code</th><th>what to do</th></tr></thead>")?;
        writeln!(out, "<tbody>")?;
        for (about, w) in warnings {
            writeln!(
                out,
                "<tr><td>{}</td><td><code>{}</code></td><td>{}</td></tr>",
                text(about),
                text(w.code),
                text(&w.message)
            )?;
        }
        writeln!(out, "</tbody></table>")?;
    }
    writeln!(out, "</section>")
}

/// Analyses that failed, with the engine's reason, at the top beside the warnings: the figures below are
/// of the others only.
pub(super) fn write_failed(out: &mut String, report: &KcReport) -> std::fmt::Result {
    if report.failed.is_empty() {
        return Ok(());
    }
    writeln!(out, "<section id=\"failed\">")?;
    writeln!(out, "<h2>Analyses that failed</h2>")?;
    writeln!(out, "<ul class=\"failed\">")?;
    for f in &report.failed {
        writeln!(out, "<li><strong>{}</strong>: {}</li>", text(f.analysis.name()), text(&f.reason))?;
    }
    writeln!(out, "</ul>")?;
    writeln!(out, "</section>")
}
