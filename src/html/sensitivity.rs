//! The sensitivities' page, and its sections, which the K&C report shows too: per analysis and headline
//! figure, the parameters with the largest effects as a bar chart.

use super::charts::write_bars;
use super::{write_foot, write_head, NAME_SHOWN};
use crate::markup::{attr, text};
use crate::suspensions::kc::significant;
use serde_json::Value;
use std::fmt::Write;

/// The sensitivities' report as one self-contained HTML page: per analysis and headline figure, its value
/// and the parameters with the largest effects on it (per mm of a length, per % of anything else) as a bar
/// chart; how the run was made.
pub fn sensitivity_html(
    suite: &crate::suspensions::design::SuiteSensitivity,
    parameters: &crate::suspensions::design::Parameters,
    model_name: &str,
    provenance: &Value,
) -> String {
    let mut page = String::new();
    // Writing into a String cannot fail.
    let _ = write_sensitivity_page(&mut page, suite, parameters, model_name, provenance);
    page
}

fn write_sensitivity_page(
    out: &mut String,
    suite: &crate::suspensions::design::SuiteSensitivity,
    parameters: &crate::suspensions::design::Parameters,
    model_name: &str,
    provenance: &Value,
) -> std::fmt::Result {
    let name = crate::plot::shown(model_name, NAME_SHOWN);
    let lede = format!(
        "{} analyses, {} parameters; derivatives through the equilibrium, each effect per mm of a length or per \
         % of anything else; every derivative, with its error estimate, is in sensitivity.csv.",
        suite.analyses.len(),
        parameters.len()
    );
    write_head(out, &format!("Sensitivities: {name}"), &lede)?;
    write_sensitivity_sections(out, suite, parameters, "h2")?;
    write_foot(out, provenance)
}

/// Each analysis of `suite` as a section headed by `heading` (`h2`, `h3`): per headline figure, its value
/// and the parameters with the largest effects (per mm or per %) as a bar chart; an analysis whose
/// sensitivities failed, with why.
pub(super) fn write_sensitivity_sections(
    out: &mut String,
    suite: &crate::suspensions::design::SuiteSensitivity,
    parameters: &crate::suspensions::design::Parameters,
    heading: &str,
) -> std::fmt::Result {
    use crate::suspensions::design::{parameter_words, sensitivity::effect_unit};
    for f in &suite.failed {
        writeln!(out, "<p class=\"error\">{}: {}</p>", text(f.analysis.name()), text(&f.reason))?;
    }
    for a in &suite.analyses {
        writeln!(out, "<section id=\"sensitivity-{}\">", attr(a.report.analysis.name()))?;
        writeln!(out, "<{heading}>{}</{heading}>", text(&a.report.description))?;
        for (j, figure) in a.report.figures.iter().enumerate() {
            let written = figure.written(a.report.units);
            let Some(value) = written.value else { continue };
            let bars: Vec<(String, f64)> = a
                .largest_effects(j, parameters, 8)
                .into_iter()
                .map(|(k, e)| {
                    (
                        format!(
                            "{} (per {})",
                            parameter_words(&parameters.pointers[k]),
                            effect_unit(&parameters.pointers[k])
                        ),
                        e * written.factor,
                    )
                })
                .collect();
            writeln!(out, "<figure>")?;
            writeln!(
                out,
                "<figcaption>{}: {} {}</figcaption>",
                text(&figure.label),
                text(&significant(value, 5)),
                text(written.unit)
            )?;
            if bars.is_empty() {
                writeln!(out, "<p class=\"none\">no parameter moves it</p>")?;
            } else {
                write_bars(out, &bars, written.unit)?;
            }
            writeln!(out, "</figure>")?;
        }
        writeln!(out, "</section>")?;
    }
    Ok(())
}
