//! An analysis's headline figures: each with its value, unit and error estimate, or "n/a" and the reason it
//! is missing. The estimate is written out only where it matters (over the tolerance on figures, and
//! showing in the printed decimals); elsewhere a mark says it is within, the estimate itself on hover.

use crate::markup::{attr, text};
use crate::suspensions::kc::{significant, Figure, Units};
use std::fmt::Write;

/// The table of `figures` in `units`, their estimates judged against `relative` (the tolerance on
/// figures), or that there are none.
pub(super) fn write_figures(out: &mut String, figures: &[Figure], units: Units, relative: f64) -> std::fmt::Result {
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
                writeln!(
                    out,
                    "<td class=\"value\">{}</td><td>{}</td>{}</tr>",
                    w.number(v),
                    text(w.unit),
                    estimate_cell(f, units, relative)
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

/// The error-estimate cell of the figure `f` (which has a value) in `units`: `± e` in red where the estimate
/// matters against `relative`, a quiet mark otherwise; the estimate is its hover text either way.
pub(super) fn estimate_cell(f: &Figure, units: Units, relative: f64) -> String {
    match estimate_words(f, units) {
        Some(e) if f.estimate_matters(relative) => format!("<td class=\"error-estimate over\">{}</td>", text(&e)),
        Some(e) => format!(
            "<td class=\"error-estimate\" title=\"{}\">within</td>",
            attr(&format!("{e}: within the tolerance"))
        ),
        None => "<td class=\"error-estimate over\">not estimated</td>".into(),
    }
}

/// The error estimate of `f` as written in `units`, `± e unit`; `None` when it has none.
pub(super) fn estimate_words(f: &Figure, units: Units) -> Option<String> {
    let w = f.written(units);
    let e = w.error.filter(|e| e.is_finite())?;
    Some(if w.unit == "-" {
        format!("± {}", significant(e, 2))
    } else {
        format!("± {} {}", significant(e, 2), w.unit)
    })
}
