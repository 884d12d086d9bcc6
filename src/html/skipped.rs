//! The K&C report's analyses not run, each with why.

use crate::markup::text;
use crate::suspensions::kc::KcReport;
use std::fmt::Write;

/// The section "Analyses not run": each with its reason, or that every analysis asked for was run.
pub(super) fn write_skipped(out: &mut String, report: &KcReport) -> std::fmt::Result {
    writeln!(out, "<section id=\"skipped\">")?;
    writeln!(out, "<h2>Analyses not run</h2>")?;
    if report.skipped.is_empty() {
        writeln!(out, "<p class=\"none\">none: every analysis asked for was run</p>")?;
    } else {
        writeln!(out, "<ul>")?;
        for s in &report.skipped {
            writeln!(out, "<li><strong>{}</strong>: {}</li>", text(s.analysis.name()), text(&s.reason))?;
        }
        writeln!(out, "</ul>")?;
    }
    writeln!(out, "</section>")
}
