//! The K&C report's contents: the analyses run, each a link to its section.

use crate::markup::{attr, text};
use crate::suspensions::kc::KcReport;
use std::fmt::Write;

/// The list of the analyses run, linked to their sections; nothing when none ran.
pub(super) fn write_contents(out: &mut String, report: &KcReport) -> std::fmt::Result {
    if report.analyses.is_empty() {
        return Ok(());
    }
    writeln!(out, "<nav>")?;
    writeln!(out, "<h2>Analyses</h2>")?;
    writeln!(out, "<ol>")?;
    for a in &report.analyses {
        writeln!(
            out,
            "<li><a href=\"#{}\">{}</a>: {}</li>",
            attr(a.analysis.name()),
            text(a.analysis.name()),
            text(&a.description)
        )?;
    }
    writeln!(out, "</ol>")?;
    writeln!(out, "</nav>")
}
