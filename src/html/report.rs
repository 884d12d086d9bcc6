//! The K&C report's page: its sections in order, from the warnings to the model file.

use super::analysis::write_analysis;
use super::charts::write_chart_script;
use super::contents::write_contents;
use super::hardpoints::write_hardpoints;
use super::model::write_model;
use super::provenance::write_provenance;
use super::sensitivity::write_sensitivity_sections;
use super::skipped::write_skipped;
use super::summary::{write_summary, Judged};
use super::warnings::{write_failed, write_warnings};
use super::{write_head, NAME_SHOWN};
use crate::suspensions::kc::{Chart, KcReport};
use crate::suspensions::SuspensionFile;
use serde_json::Value;
use std::fmt::Write;

/// The K&C report `report` of the model `model`, as one self-contained HTML page.
///
/// `provenance` says how the run was made (elastokin version, model file and its sha256, mode, steps,
/// tolerance, date, …): every entry of the JSON object is shown as a definition list, nested objects
/// nested. A value that is not an object is shown as it is.
///
/// `render_chart` draws one chart as an SVG document (`<svg …>…</svg>`), which is put in the page
/// inline. A chart it cannot draw shows the error it returns in its place; the rest of the report is
/// still written.
pub fn report_html<E: std::fmt::Display>(
    report: &KcReport,
    model: &SuspensionFile,
    provenance: &Value,
    render_chart: impl Fn(&Chart) -> Result<String, E>,
) -> String {
    report_html_with(report, model, provenance, render_chart, Extras::default())
}

/// Sensitivities of a suite and the parameters they are taken to, for a page's sensitivity section.
pub type Sensitivities<'a> =
    (&'a crate::suspensions::design::SuiteSensitivity, &'a crate::suspensions::design::Parameters);

/// What a K&C page shows beyond the suite, each when given.
#[derive(Debug, Clone, Copy, Default)]
pub struct Extras<'a> {
    /// A section of the sensitivities (`run --sensitivity`): per analysis and headline figure, the
    /// parameters with the largest effects as a bar chart.
    pub sensitivities: Option<Sensitivities<'a>>,
    /// The targets of a TARGETS file judged on the run (`run --targets`), in the summary.
    pub judged: Option<Judged<'a>>,
}

/// [`report_html`] with the `extras` given.
pub fn report_html_with<E: std::fmt::Display>(
    report: &KcReport,
    model: &SuspensionFile,
    provenance: &Value,
    render_chart: impl Fn(&Chart) -> Result<String, E>,
    extras: Extras,
) -> String {
    let render = |chart: &Chart| render_chart(chart).map_err(|e| e.to_string());
    let mut page = String::new();
    // Writing into a String cannot fail.
    let _ = write_page(&mut page, report, model, provenance, &render, extras);
    page
}

/// The page: the head, the summary (the answer first), the warnings and failed analyses, the contents, the
/// geometry, each analysis, the sensitivities when given, the analyses not run, the provenance beside the
/// hardpoints, the model.
fn write_page(
    out: &mut String,
    report: &KcReport,
    model: &SuspensionFile,
    provenance: &Value,
    render_chart: &dyn Fn(&Chart) -> Result<String, String>,
    extras: Extras,
) -> std::fmt::Result {
    // The name is shown shortened; it is whole in the model below and in summary.json.
    let name = crate::plot::shown(&report.model, NAME_SHOWN);
    let failed = if report.failed.is_empty() { String::new() } else { format!(", {} failed", report.failed.len()) };
    let lede = format!(
        "{} analyses run, {} skipped{failed}; written by elastokin {}.",
        report.analyses.len(),
        report.skipped.len(),
        env!("CARGO_PKG_VERSION")
    );
    write_head(out, &format!("K&C report: {name}"), &lede)?;

    // The answer first, then what the colleague must know before reading any figure further.
    write_summary(out, report, extras.judged)?;
    write_warnings(out, report)?;
    write_failed(out, report)?;
    write_contents(out, report)?;
    crate::view::write_geometry(out, report)?;
    for analysis in &report.analyses {
        write_analysis(out, analysis, report, render_chart)?;
    }
    if report.analyses.iter().any(|a| !a.charts.is_empty()) {
        write_chart_script(out)?;
    }
    if let Some((suite, parameters)) = extras.sensitivities {
        write_sensitivities(out, suite, parameters)?;
    }
    write_skipped(out, report)?;
    writeln!(out, "<div class=\"columns\">")?;
    write_provenance(out, provenance)?;
    write_hardpoints(out, model)?;
    writeln!(out, "</div>")?;
    write_model(out, model)?;

    writeln!(out, "</body>")?;
    writeln!(out, "</html>")
}

/// The section of the sensitivities (`run --sensitivity`): per analysis and headline figure, the parameters
/// with the largest effects as a bar chart.
fn write_sensitivities(
    out: &mut String,
    suite: &crate::suspensions::design::SuiteSensitivity,
    parameters: &crate::suspensions::design::Parameters,
) -> std::fmt::Result {
    writeln!(out, "<section id=\"sensitivities\">")?;
    writeln!(out, "<h2>Sensitivities</h2>")?;
    writeln!(
        out,
        "<p class=\"note\">derivatives through the equilibrium (of the corrected path), to {} parameters; \
         each effect per mm of a length or per % of anything else; every derivative, with its error \
         estimate, is in sensitivity.csv</p>",
        parameters.len()
    )?;
    write_sensitivity_sections(out, suite, parameters, "h3")?;
    writeln!(out, "</section>")
}
