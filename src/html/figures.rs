//! An analysis's headline figures: each with its value, unit and error estimate, or "n/a" and the reason it
//! is missing.

use crate::markup::text;
use crate::suspensions::kc::{significant, Figure, Units};
use std::fmt::Write;

/// The table of `figures` in `units`, or that there are none.
pub(super) fn write_figures(out: &mut String, figures: &[Figure], units: Units) -> std::fmt::Result {
    if figures.is_empty() {
        return writeln!(out, "<p class=\"none\">no headline figures</p>");
    }
    writeln!(out, "<table class=\"figures\">")?;
    writeln!(out, "<thead><tr><th>figure</th><th>value</th><th>unit</th><th>error estimate</th></tr></thead>")?;
    writeln!(out, "<tbody>")?;
    for f in figures {
        let w = f.written(units);
        write!(out, "<tr><td>{}</td>", text(&f.label))?;
        match w.value.filter(|v| v.is_finite()) {
            Some(v) => {
                let error = match w.error.filter(|e| e.is_finite()) {
                    Some(e) => format!("± {}", significant(e, 2)),
                    None => "not estimated".into(),
                };
                writeln!(
                    out,
                    "<td class=\"value\">{}</td><td>{}</td><td class=\"error-estimate\">{}</td></tr>",
                    w.number(v),
                    text(w.unit),
                    text(&error)
                )?;
            }
            None => {
                let reason = f.reason.as_deref().unwrap_or("no reason given");
                writeln!(
                    out,
                    "<td class=\"value\">n/a</td><td>{}</td><td class=\"reason\">n/a — {}</td></tr>",
                    text(w.unit),
                    text(reason)
                )?;
            }
        }
    }
    writeln!(out, "</tbody></table>")
}
