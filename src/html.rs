//! The K&C report as one self-contained HTML file, the one an engineer mails to a colleague: the
//! headline figures with their error estimates, the plots inline, the accuracy of every analysis, the
//! warnings, the hardpoints and the model itself, under a block saying how the run was made.
//!
//! The page needs nothing but itself: CSS inline, no font, no link out of the file, and one script, inline:
//! the 3D view's ([`crate::view`]); everything else, the geometry's projections included, is SVG and
//! shows with scripts off. It is written as XHTML-compatible HTML (every element closed, only the five
//! XML entities, the script in a CDATA section) so an XML parser can check that it is well-formed, and it
//! prints on paper as it shows on screen.
//!
//! Every number on the page comes from the report or the model file: a figure without a value shows
//! its reason, an empty table cell stays empty, and nothing non-finite is printed.

use crate::markup::{attr, text};
use crate::suspensions::kc::{
    figures, fixed, significant, AnalysisReport, Cell, Chart, Figure, KcReport, Table, Units, Warning,
};
use crate::suspensions::SuspensionFile;
use serde_json::Value;
use std::fmt::Write;

/// Rows of an analysis table shown in the page; a longer table is cut there with a note (the CSV beside
/// the report holds every row), so a fine sweep does not make a file too large to mail.
pub const TABLE_ROW_LIMIT: usize = 400;

/// The most characters of the model's name shown in the page's title and heading.
pub const NAME_SHOWN: usize = 120;

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
    report_html_with(report, model, provenance, render_chart, None)
}

/// Sensitivities of a suite and the parameters they are taken to, for a page's sensitivity section.
pub type Sensitivities<'a> =
    (&'a crate::suspensions::design::SuiteSensitivity, &'a crate::suspensions::design::Parameters);

/// [`report_html`] with a section of the `sensitivities` (`run --sensitivity`): per analysis and headline
/// figure, the parameters with the largest effects as a bar chart.
pub fn report_html_with<E: std::fmt::Display>(
    report: &KcReport,
    model: &SuspensionFile,
    provenance: &Value,
    render_chart: impl Fn(&Chart) -> Result<String, E>,
    sensitivities: Option<Sensitivities>,
) -> String {
    let render = |chart: &Chart| render_chart(chart).map_err(|e| e.to_string());
    let mut page = String::new();
    // Writing into a String cannot fail.
    let _ = write_page(&mut page, report, model, provenance, &render, sensitivities);
    page
}

type Out<'a> = &'a mut String;

fn write_page(
    out: Out,
    report: &KcReport,
    model: &SuspensionFile,
    provenance: &Value,
    render_chart: &dyn Fn(&Chart) -> Result<String, String>,
    sensitivities: Option<Sensitivities>,
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

    // Warnings first: what the colleague must know before reading any figure.
    write_warnings(out, report)?;
    write_failed(out, report)?;
    writeln!(out, "<div class=\"columns\">")?;
    write_provenance(out, provenance)?;
    write_hardpoints(out, model)?;
    writeln!(out, "</div>")?;
    write_contents(out, report)?;
    crate::view::write_geometry(out, report)?;
    for analysis in &report.analyses {
        write_analysis(out, analysis, report, render_chart)?;
    }
    if let Some((suite, parameters)) = sensitivities {
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
        writeln!(out, "</section>")?;
    }
    write_skipped(out, report)?;
    write_model(out, model)?;

    writeln!(out, "</body>")?;
    writeln!(out, "</html>")
}

/// The page's opening: the document type, the head (its `title` as given, the style inline), `<body>`, and
/// the page's header: `title` again as its heading, and the `lede` beneath it.
fn write_head(out: Out, title: &str, lede: &str) -> std::fmt::Result {
    writeln!(out, "<!DOCTYPE html>")?;
    writeln!(out, r#"<html xmlns="http://www.w3.org/1999/xhtml" lang="en">"#)?;
    writeln!(out, "<head>")?;
    writeln!(out, r#"<meta charset="utf-8"/>"#)?;
    writeln!(out, r#"<meta name="viewport" content="width=device-width, initial-scale=1"/>"#)?;
    writeln!(out, r#"<meta name="generator" content="elastokin {}"/>"#, attr(env!("CARGO_PKG_VERSION")))?;
    writeln!(out, "<title>{}</title>", text(title))?;
    writeln!(out, "<style>{STYLE}</style>")?;
    writeln!(out, "</head>")?;
    writeln!(out, "<body>")?;
    writeln!(out, "<header>")?;
    writeln!(out, "<h1>{}</h1>", text(title))?;
    writeln!(out, "<p class=\"lede\">{}</p>", text(lede))?;
    writeln!(out, "</header>")
}

/// The page's end: how the run was made, and the closing tags.
fn write_foot(out: Out, provenance: &Value) -> std::fmt::Result {
    write_provenance(out, provenance)?;
    writeln!(out, "</body>")?;
    writeln!(out, "</html>")
}

/// A horizontal bar chart as inline SVG: one bar per `(label, value)`, drawn from a centre line (negative
/// to the left), the largest magnitude the full width, each value printed with `unit`.
fn write_bars(out: Out, bars: &[(String, f64)], unit: &str) -> std::fmt::Result {
    let (width, label_width, row) = (900.0, 430.0, 20.0);
    let half = (width - label_width - 120.0) / 2.0;
    let centre = label_width + half;
    let largest = bars.iter().fold(0.0f64, |m, (_, v)| m.max(v.abs())).max(f64::MIN_POSITIVE);
    let height = row * bars.len() as f64 + 8.0;
    writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" role="img">"#
    )?;
    writeln!(out, r##"<line x1="{centre}" y1="0" x2="{centre}" y2="{height}" stroke="#8c959f"/>"##)?;
    for (k, (label, v)) in bars.iter().enumerate() {
        let y = 4.0 + row * k as f64;
        let w = half * v.abs() / largest;
        let x = if *v < 0.0 { centre - w } else { centre };
        let fill = if *v < 0.0 { "#cf222e" } else { "#0969da" };
        let shown = crate::plot::shown(label, 72);
        writeln!(
            out,
            r#"<text x="{}" y="{}" font-size="11" text-anchor="end" font-family="sans-serif">{}</text>"#,
            label_width - 6.0,
            y + 13.0,
            text(&shown)
        )?;
        writeln!(out, r#"<rect x="{x:.1}" y="{y:.1}" width="{w:.1}" height="{:.1}" fill="{fill}"/>"#, row - 6.0)?;
        writeln!(
            out,
            r#"<text x="{}" y="{}" font-size="11" font-family="sans-serif">{} {}</text>"#,
            centre + half + 6.0,
            y + 13.0,
            text(&significant(*v, 3)),
            text(unit)
        )?;
    }
    writeln!(out, "</svg>")
}

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
    out: Out,
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
fn write_sensitivity_sections(
    out: Out,
    suite: &crate::suspensions::design::SuiteSensitivity,
    parameters: &crate::suspensions::design::Parameters,
    heading: &str,
) -> std::fmt::Result {
    use crate::suspensions::design::sensitivity::effect_unit;
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
                        format!("{} (per {})", parameters.pointers[k], effect_unit(&parameters.pointers[k])),
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
    out: Out,
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
    if !stack.failed.is_empty() || !stack.failed_samples.is_empty() || !stack.left_out.is_empty() {
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
        writeln!(out, "</ul></section>")?;
    }
    writeln!(out, "<section id=\"spreads\">")?;
    writeln!(out, "<h2>Spreads</h2>")?;
    write_open_table(out, &stack.table())?;
    writeln!(out, "</section>")?;
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
            .map(|(p, c)| (stack.parameters.pointers[*p].clone(), *c * unit.factor))
            .collect();
        write_bars(out, &bars, unit.symbol)?;
        writeln!(out, "</figure>")?;
    }
    writeln!(out, "</section>")?;
    write_foot(out, provenance)
}

/// The tune's report as one self-contained HTML page: whether every target is met and why one is not,
/// the free numbers before and after, each curve target's column before and after with its points, every
/// residual and every iteration, and how the run was made. `render_chart` as for [`report_html`].
pub fn tune_html<E: std::fmt::Display>(
    tuned: &crate::suspensions::design::tune::Tuned,
    targets: &crate::suspensions::design::targets::Targets,
    model_name: &str,
    provenance: &Value,
    render_chart: impl Fn(&Chart) -> Result<String, E>,
) -> String {
    let render = |chart: &Chart| render_chart(chart).map_err(|e| e.to_string());
    let mut page = String::new();
    // Writing into a String cannot fail.
    let _ = write_tune_page(&mut page, tuned, targets, model_name, provenance, &render);
    page
}

fn write_tune_page(
    out: Out,
    tuned: &crate::suspensions::design::tune::Tuned,
    targets: &crate::suspensions::design::targets::Targets,
    model_name: &str,
    provenance: &Value,
    render_chart: &dyn Fn(&Chart) -> Result<String, String>,
) -> std::fmt::Result {
    let name = crate::plot::shown(model_name, NAME_SHOWN);
    let met = tuned.verdicts.iter().filter(|v| v.met).count();
    let last = tuned.iterations.last().map_or(0, |i| i.evaluations);
    let broken = tuned.packaging.iter().filter(|p| p.broken_by > 0.0).count();
    let packaging = match (tuned.packaging.len(), broken) {
        (0, _) => String::new(),
        (_, 0) => "; the packaging holds".to_string(),
        (all, broken) => format!("; {broken} of {all} packaging constraints broken"),
    };
    let lede = format!(
        "{met} of {} targets met{packaging}; {} iterations, {last} K&C evaluations; {}.",
        tuned.verdicts.len(),
        tuned.iterations.len().saturating_sub(1),
        tuned.stopped
    );
    write_head(out, &format!("Tune: {name}"), &lede)?;
    writeln!(out, "<section id=\"targets\">")?;
    writeln!(out, "<h2>Targets</h2>")?;
    writeln!(out, "<table class=\"figures\"><thead><tr><th>target</th><th>largest miss / tolerance</th><th>met</th><th>why not</th></tr></thead><tbody>")?;
    for v in &tuned.verdicts {
        let (class, said) = if v.met { ("ok", "yes") } else { ("bad", "no") };
        writeln!(
            out,
            "<tr><td>{}</td><td class=\"value\">{}</td><td class=\"{class}\">{said}</td><td>{}</td></tr>",
            text(&v.target),
            text(&significant(v.worst, 3)),
            text(v.why.as_deref().unwrap_or(""))
        )?;
    }
    writeln!(out, "</tbody></table>")?;
    if !tuned.packaging.is_empty() {
        writeln!(out, "<h3>Packaging</h3>")?;
        writeln!(out, "<table class=\"figures\"><thead><tr><th>constraint</th><th>broken by (mm)</th><th>holds</th></tr></thead><tbody>")?;
        for p in &tuned.packaging {
            let (class, said) = if p.broken_by == 0.0 { ("ok", "yes") } else { ("bad", "no") };
            writeln!(
                out,
                "<tr><td>{}</td><td class=\"value\">{}</td><td class=\"{class}\">{said}</td></tr>",
                text(&p.constraint),
                text(&significant(p.broken_by * 1e3, 3)),
            )?;
        }
        writeln!(out, "</tbody></table>")?;
    }
    writeln!(out, "</section>")?;
    writeln!(out, "<section id=\"parameters\">")?;
    writeln!(out, "<h2>The free numbers</h2>")?;
    write_open_table(out, &tuned.moved_table(targets))?;
    writeln!(out, "</section>")?;
    writeln!(out, "<section id=\"curves\">")?;
    writeln!(out, "<h2>Before and after</h2>")?;
    let charts = tuned.charts(targets, model_name);
    if charts.is_empty() {
        writeln!(out, "<p class=\"none\">no curve targets: the figures are in the table of targets</p>")?;
    }
    for chart in &charts {
        write_chart(out, chart, render_chart)?;
    }
    writeln!(out, "</section>")?;
    writeln!(out, "<section id=\"residuals\">")?;
    writeln!(out, "<h2>Every residual</h2>")?;
    write_table(out, &tuned.residual_table(targets), "each figure and curve point, before and after")?;
    write_table(out, &tuned.iteration_table(), "each iteration")?;
    writeln!(out, "</section>")?;
    write_foot(out, provenance)
}

/// The comparison of designs as one page: the figures side by side with their differences and error
/// estimates, the geometry of every model overlaid, every curve overlaid (a colour and a legend entry per
/// design), and the analyses a model could not run. `models` are the compared models' names and suites
/// (their geometry); `render_chart` as for [`report_html`].
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
    out: Out,
    comparison: &crate::suspensions::compare::Comparison,
    models: &[(&str, &KcReport)],
    provenance: &Value,
    render_chart: &dyn Fn(&Chart) -> Result<String, String>,
) -> std::fmt::Result {
    let names: Vec<String> = comparison.names.iter().map(|n| crate::plot::shown(n, NAME_SHOWN)).collect();
    let lede = format!(
        "{} designs; {} figures side by side, {} curves overlaid; written by elastokin {}.",
        names.len(),
        comparison.figures.rows.len(),
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
        "<p class=\"note\">each model's value and its error estimate (±), then each later model's difference to \
         the first; every number is in compare.csv</p>"
    )?;
    let mut shown = comparison.figures.clone();
    shown.columns.truncate(3);
    for (l, _) in &letters {
        shown.columns.push(l.clone());
        shown.columns.push(format!("± {l}"));
    }
    for (l, _) in letters.iter().skip(1) {
        shown.columns.push(format!("{l} − {}", letters[0].0));
    }
    write_open_table(out, &shown)?;
    writeln!(out, "</section>")?;
    crate::view::write_overlay(out, models)?;
    writeln!(out, "<section id=\"curves\">")?;
    writeln!(out, "<h2>Curves</h2>")?;
    writeln!(out, "<div class=\"charts\">")?;
    for chart in &comparison.charts {
        write_chart(out, chart, render_chart)?;
    }
    writeln!(out, "</div>")?;
    writeln!(out, "</section>")?;
    write_foot(out, provenance)
}

/// The whole car's page: the understeer budget as a bar chart (each term per axle, understeer to the
/// right), the roll and load-transfer figures, each axle's characteristics read off its K&C runs, and
/// how it was made.
pub fn vehicle_html(report: &crate::suspensions::full_vehicle::VehicleReport, provenance: &Value) -> String {
    let mut page = String::new();
    // Writing into a String cannot fail.
    let _ = write_vehicle_page(&mut page, report, provenance);
    page
}

fn write_vehicle_page(
    out: Out,
    report: &crate::suspensions::full_vehicle::VehicleReport,
    provenance: &Value,
) -> std::fmt::Result {
    let b = &report.budget;
    let name = crate::plot::shown(&report.name, NAME_SHOWN);
    let character = if b.understeer_gradient > crate::suspensions::full_vehicle::NEUTRAL {
        "understeers"
    } else if b.understeer_gradient < -crate::suspensions::full_vehicle::NEUTRAL {
        "oversteers"
    } else {
        "is neutral"
    };
    let lede = format!(
        "The car {character}: {} deg/g of road-wheel steer ({} deg/g at the steering wheel); the body rolls {} deg/g.",
        significant(b.understeer_gradient, 3),
        significant(b.steering_wheel_gradient, 3),
        significant(b.roll_gradient, 3)
    );
    write_head(out, &format!("Vehicle: {name}"), &lede)?;
    if !report.warnings.is_empty() {
        writeln!(out, "<ul class=\"warnings\">")?;
        for w in &report.warnings {
            writeln!(out, "<li>{}</li>", text(w))?;
        }
        writeln!(out, "</ul>")?;
    }
    writeln!(out, "<section id=\"budget\">")?;
    writeln!(out, "<h2>Understeer budget</h2>")?;
    writeln!(
        out,
        "<p class=\"note\">each term's share of the understeer gradient, deg/g of road-wheel steer: understeer \
         to the right, oversteer to the left; docs/vehicle.md gives every formula</p>"
    )?;
    let mut bars: Vec<(String, f64)> =
        b.contributions.iter().map(|c| (format!("{}, {}", c.effect, c.axle.name()), c.value)).collect();
    bars.push(("understeer gradient (the sum)".into(), b.understeer_gradient));
    write_bars(out, &bars, "deg/g")?;
    writeln!(out, "</section>")?;
    writeln!(out, "<section id=\"figures\">")?;
    writeln!(out, "<h2>Roll and load transfer</h2>")?;
    write_open_table(out, &report.table())?;
    writeln!(out, "</section>")?;
    writeln!(out, "<section id=\"axles\">")?;
    writeln!(out, "<h2>The axles, from their K&amp;C runs</h2>")?;
    writeln!(
        out,
        "<table class=\"numbers\"><thead><tr><th>figure</th><th>unit</th><th>front</th><th>rear</th></tr></thead><tbody>"
    )?;
    let [f, r] = &report.axles;
    for (kind, x, y) in [
        (&figures::ROLL_STIFFNESS, f.roll_stiffness, r.roll_stiffness),
        (&figures::ROLL_CENTRE_HEIGHT, f.roll_centre_height, r.roll_centre_height),
        (&figures::TRACK, f.track, r.track),
        (&figures::ROLL_STEER, f.roll_steer, r.roll_steer),
        (&figures::ROLL_CAMBER, f.roll_camber, r.roll_camber),
        (&figures::LATERAL_STEER, f.lateral_steer, r.lateral_steer),
        (&figures::LATERAL_CAMBER, f.lateral_camber, r.lateral_camber),
        (&figures::ALIGNING_TORQUE_STEER, f.aligning_torque_steer, r.aligning_torque_steer),
    ] {
        let unit = kind.unit.shown();
        writeln!(
            out,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            text(kind.label),
            text(unit.symbol),
            text(&significant(x * unit.factor, 4)),
            text(&significant(y * unit.factor, 4))
        )?;
    }
    writeln!(out, "</tbody></table>")?;
    writeln!(out, "</section>")?;
    write_foot(out, provenance)
}

/// A table shown open (not folded), every row.
fn write_open_table(out: Out, table: &Table) -> std::fmt::Result {
    writeln!(out, "<div class=\"scroll\"><table class=\"numbers\">")?;
    write!(out, "<thead><tr>")?;
    for c in &table.columns {
        write!(out, "<th>{}</th>", text(c))?;
    }
    writeln!(out, "</tr></thead><tbody>")?;
    for row in &table.rows {
        write!(out, "<tr>")?;
        for c in row {
            write!(out, "<td>{}</td>", cell(c, 6))?;
        }
        writeln!(out, "</tr>")?;
    }
    writeln!(out, "</tbody></table></div>")
}

fn write_provenance(out: Out, provenance: &Value) -> std::fmt::Result {
    writeln!(out, "<section id=\"provenance\">")?;
    writeln!(out, "<h2>How this run was made</h2>")?;
    match provenance {
        Value::Object(map) if map.is_empty() => writeln!(out, "<p class=\"none\">no provenance given</p>")?,
        Value::Object(_) => write_value(out, provenance)?,
        Value::Null => writeln!(out, "<p class=\"none\">no provenance given</p>")?,
        other => writeln!(out, "<p>{}</p>", text(&scalar(other)))?,
    }
    writeln!(out, "</section>")
}

/// A JSON value in words: an object as a definition list (nested ones nested), anything else as text.
fn write_value(out: Out, value: &Value) -> std::fmt::Result {
    match value {
        Value::Object(map) => {
            writeln!(out, "<dl>")?;
            for (key, v) in map {
                write!(out, "<dt>{}</dt><dd>", text(&key.replace('_', " ")))?;
                write_value(out, v)?;
                writeln!(out, "</dd>")?;
            }
            writeln!(out, "</dl>")
        }
        other => write!(out, "{}", text(&scalar(other))),
    }
}

/// A JSON value that is not an object, as text: a string without its quotes, an array of plain values
/// joined by commas, anything else as compact JSON.
fn scalar(value: &Value) -> String {
    match value {
        Value::String(s) => s.clone(),
        Value::Null => "—".into(),
        Value::Array(items) if items.iter().all(|v| !v.is_object() && !v.is_array()) => {
            items.iter().map(scalar).collect::<Vec<_>>().join(", ")
        }
        other => other.to_string(),
    }
}

/// The hardpoints of a model file: its template's name (`macpherson`, `double_wishbone`, `general`) and
/// each point's name and position (m).
struct Hardpoints {
    template: String,
    points: Vec<(String, [f64; 3])>,
}

fn hardpoints(model: &SuspensionFile) -> Result<Hardpoints, String> {
    let points = model.suspension.hardpoints().into_iter().map(|(name, p)| (name, [p.x, p.y, p.z])).collect();
    Ok(Hardpoints { template: model.suspension.kind().to_string(), points })
}

fn write_hardpoints(out: Out, model: &SuspensionFile) -> std::fmt::Result {
    writeln!(out, "<section id=\"hardpoints\">")?;
    match hardpoints(model) {
        Ok(Hardpoints { template, points }) => {
            writeln!(out, "<h2>Hardpoints <span class=\"quiet\">({}, left corner)</span></h2>", text(&template))?;
            writeln!(out, "<table class=\"numbers\">")?;
            writeln!(out, "<thead><tr><th>hardpoint</th><th>x [mm]</th><th>y [mm]</th><th>z [mm]</th></tr></thead>")?;
            writeln!(out, "<tbody>")?;
            for (name, p) in points {
                write!(out, "<tr><td><code>{}</code></td>", text(&name))?;
                for v in p {
                    write!(out, "<td>{}</td>", fixed(v * 1e3, 2))?;
                }
                writeln!(out, "</tr>")?;
            }
            writeln!(out, "</tbody></table>")?;
            writeln!(out, "<p class=\"note\">ISO 8855: x forward, y left, z up.</p>")?;
        }
        Err(e) => {
            writeln!(out, "<h2>Hardpoints</h2>")?;
            writeln!(out, "<p class=\"error\">the hardpoints could not be read: {}</p>", text(&e))?;
        }
    }
    writeln!(out, "</section>")
}

fn write_warnings(out: Out, report: &KcReport) -> std::fmt::Result {
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
fn write_failed(out: Out, report: &KcReport) -> std::fmt::Result {
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

fn write_contents(out: Out, report: &KcReport) -> std::fmt::Result {
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

fn write_analysis(
    out: Out,
    a: &AnalysisReport,
    report: &KcReport,
    render_chart: &dyn Fn(&Chart) -> Result<String, String>,
) -> std::fmt::Result {
    writeln!(out, "<section class=\"analysis\" id=\"{}\">", attr(a.analysis.name()))?;
    writeln!(out, "<h2>{}</h2>", text(a.analysis.name()))?;
    writeln!(out, "<p class=\"description\">{}</p>", text(&a.description))?;
    writeln!(
        out,
        "<p class=\"note\">load parameter: {}; {} to {}, {} steps</p>",
        text(&a.parameter),
        plain(a.range.0),
        plain(a.range.1),
        a.steps
    )?;

    write_figures(out, &a.figures, a.units)?;
    write_accuracy(out, a, report)?;
    if !a.warnings.is_empty() {
        writeln!(out, "<ul class=\"warnings\">")?;
        for w in &a.warnings {
            writeln!(out, "<li><code>{}</code> {}</li>", text(w.code), text(&w.message))?;
        }
        writeln!(out, "</ul>")?;
    }

    if !a.charts.is_empty() {
        writeln!(out, "<div class=\"charts\">")?;
        for chart in &a.charts {
            write_chart(out, chart, render_chart)?;
        }
        writeln!(out, "</div>")?;
    }

    if let Some(c) = &a.wheel_compliance_at_design {
        write_compliance_matrix(out, c)?;
    }
    write_table(out, &a.table, "the rows")?;
    if let Some(c) = &a.compliance {
        write_table(out, c, "the wheel compliance at every row")?;
    }
    writeln!(out, "</section>")
}

fn write_figures(out: Out, figures: &[Figure], units: Units) -> std::fmt::Result {
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

fn write_accuracy(out: Out, a: &AnalysisReport, report: &KcReport) -> std::fmt::Result {
    let acc = &a.accuracy;
    let tol = report.settings.tolerance;
    // An estimate the report could not make is said so, never printed as a number.
    let or_not = |v: f64, scale: f64, unit: &str| {
        if v.is_finite() {
            format!("{}{unit}", significant(v * scale, 2))
        } else {
            "not estimated".into()
        }
    };
    let verdict = if acc.within_tolerance {
        "<span class=\"ok\">within tolerance</span>"
    } else {
        "<span class=\"bad\">over tolerance</span>"
    };
    writeln!(
        out,
        "<p class=\"accuracy\">error estimate: angles {}, lengths {} — {verdict} ({} deg, {} mm, {} % on figures); \
         force residual {} (relative to the force scale), constraint residual {} (m, rad). \
         <span class=\"quiet\">{}</span></p>",
        text(&or_not(acc.angle_error_deg, 1.0, " deg")),
        text(&or_not(acc.length_error_m, 1e3, " mm")),
        text(&significant(tol.angle_deg, 2)),
        text(&significant(tol.length_m * 1e3, 2)),
        text(&significant(tol.relative * 100.0, 2)),
        text(&or_not(acc.force_residual, 1.0, "")),
        text(&or_not(acc.constraint_residual, 1.0, "")),
        text(&acc.method)
    )
}

fn write_chart(out: Out, chart: &Chart, render_chart: &dyn Fn(&Chart) -> Result<String, String>) -> std::fmt::Result {
    // The plot carries its own title; one that could not be drawn is named in its error.
    writeln!(out, "<figure>")?;
    match render_chart(chart) {
        Ok(svg) => writeln!(out, "{}", inline_svg(&svg))?,
        Err(e) => {
            writeln!(out, "<p class=\"error\">the plot “{}” could not be drawn: {}</p>", text(&chart.title), text(&e))?
        }
    }
    writeln!(out, "</figure>")
}

/// An SVG document as an element of the page: without the XML declaration or doctype a standalone file
/// starts with, which may not appear inside a document.
fn inline_svg(svg: &str) -> &str {
    let mut s = svg.trim_start();
    loop {
        let prolog = ["<?xml", "<!DOCTYPE", "<!doctype"].iter().any(|p| s.starts_with(p));
        match s.find('>') {
            Some(end) if prolog => s = s[end + 1..].trim_start(),
            _ => return s.trim_end(),
        }
    }
}

fn write_compliance_matrix(out: Out, c: &[[f64; 6]; 6]) -> std::fmt::Result {
    let rows = ["x [m]", "y [m]", "z [m]", "rot x [rad]", "rot y [rad]", "rot z [rad]"];
    let columns = ["Fx [N]", "Fy [N]", "Fz [N]", "Mx [N·m]", "My [N·m]", "Mz [N·m]"];
    writeln!(out, "<details>")?;
    writeln!(out, "<summary>wheel compliance at design: wheel-centre response per unit load there</summary>")?;
    writeln!(out, "<div class=\"scroll\"><table class=\"numbers\">")?;
    write!(out, "<thead><tr><th>response per</th>")?;
    for c in columns {
        write!(out, "<th>{}</th>", text(c))?;
    }
    writeln!(out, "</tr></thead><tbody>")?;
    for (name, row) in rows.iter().zip(c) {
        write!(out, "<tr><th>{}</th>", text(name))?;
        for &v in row {
            write!(out, "<td>{}</td>", cell(&Cell::from(v), 3))?;
        }
        writeln!(out, "</tr>")?;
    }
    writeln!(out, "</tbody></table></div>")?;
    writeln!(out, "</details>")
}

fn write_table(out: Out, table: &Table, what: &str) -> std::fmt::Result {
    let shown = table.rows.len().min(TABLE_ROW_LIMIT);
    writeln!(out, "<details>")?;
    writeln!(
        out,
        "<summary>{what}: <code>{}.csv</code>, {} rows × {} columns</summary>",
        text(&table.name),
        table.rows.len(),
        table.columns.len()
    )?;
    if shown < table.rows.len() {
        writeln!(
            out,
            "<p class=\"note\">the first {shown} of {} rows; every row is in {}.csv</p>",
            table.rows.len(),
            text(&table.name)
        )?;
    }
    writeln!(out, "<div class=\"scroll\"><table class=\"numbers\">")?;
    write!(out, "<thead><tr>")?;
    for c in &table.columns {
        write!(out, "<th>{}</th>", text(c))?;
    }
    writeln!(out, "</tr></thead>")?;
    writeln!(out, "<tbody>")?;
    for row in &table.rows[..shown] {
        write!(out, "<tr>")?;
        for c in row {
            write!(out, "<td>{}</td>", cell(c, 6))?;
        }
        writeln!(out, "</tr>")?;
    }
    writeln!(out, "</tbody></table></div>")?;
    writeln!(out, "</details>")
}

fn write_skipped(out: Out, report: &KcReport) -> std::fmt::Result {
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

/// The model file itself, so that the colleague who receives the report can run it again.
fn write_model(out: Out, model: &SuspensionFile) -> std::fmt::Result {
    writeln!(out, "<section id=\"model\">")?;
    writeln!(out, "<h2>Model file</h2>")?;
    match serde_json::to_string_pretty(model) {
        Ok(json) => {
            writeln!(out, "<details>")?;
            writeln!(out, "<summary>the model as run (JSON, SI units)</summary>")?;
            writeln!(out, "<pre>{}</pre>", text(&json))?;
            writeln!(out, "</details>")?;
        }
        Err(e) => writeln!(out, "<p class=\"error\">the model could not be written out: {}</p>", text(&e.to_string()))?,
    }
    writeln!(out, "</section>")
}

/// A table cell as text: numbers to `digits` significant digits, names escaped, nothing for an empty cell.
fn cell(c: &Cell, digits: usize) -> String {
    match c {
        Cell::Number(v) if v.is_finite() => significant(*v, digits),
        Cell::Number(_) | Cell::Empty => String::new(),
        Cell::Text(t) => text(t),
    }
}

/// `v` to six significant digits without trailing zeros (`-0.08`, `3800`, `2071.43`): a parameter as
/// a person would type it.
fn plain(v: f64) -> String {
    let s = significant(v, 6);
    if s.contains('.') && !s.contains('e') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// Readable on screen and on paper; system fonts only, so the page looks the same without a network.
const STYLE: &str = r#"
:root { color-scheme: light; }
body { font: 15px/1.45 system-ui, -apple-system, "Segoe UI", "DejaVu Sans", Roboto, sans-serif;
  color: #1b1f24; background: #fff; max-width: 1120px; margin: 0 auto; padding: 24px 32px 48px; }
h1 { font-size: 1.6em; margin: 0 0 4px; }
h2 { font-size: 1.25em; margin: 28px 0 8px; padding-bottom: 4px; border-bottom: 2px solid #d0d7de; }
header { border-bottom: 3px solid #1f4e79; padding-bottom: 10px; }
.lede, .note, .quiet { color: #57606a; }
.note { font-size: 0.9em; margin: 4px 0; }
.quiet { font-weight: normal; font-size: 0.85em; }
.none { color: #1a7f37; font-style: italic; }
.columns { display: flex; flex-wrap: wrap; gap: 8px 40px; }
.columns > section { flex: 1 1 420px; min-width: 0; }
dl { display: grid; grid-template-columns: max-content minmax(0, 1fr); gap: 2px 16px; margin: 0; }
dt { color: #57606a; }
dd { margin: 0; overflow-wrap: anywhere; }
dd dl { font-size: 0.95em; }
table { border-collapse: collapse; margin: 6px 0; }
th, td { padding: 3px 10px; border-bottom: 1px solid #d8dee4; text-align: left; vertical-align: top; }
thead th { border-bottom: 2px solid #8c959f; background: #f6f8fa; }
table.numbers td { text-align: right; font-variant-numeric: tabular-nums; }
table.numbers td:first-child { text-align: left; }
table.figures { min-width: 70%; }
table.figures td.value { text-align: right; font-variant-numeric: tabular-nums; font-weight: 600; }
table.figures td.error-estimate { color: #57606a; font-variant-numeric: tabular-nums; }
td.reason { color: #9a6700; }
table.warnings td:nth-child(2) { white-space: nowrap; }
code { font-family: "DejaVu Sans Mono", Menlo, Consolas, monospace; font-size: 0.9em;
  background: #f6f8fa; padding: 0 3px; border-radius: 3px; }
ul.warnings { color: #9a6700; padding-left: 20px; }
ul.failed { color: #cf222e; padding-left: 20px; }
.ok { color: #1a7f37; font-weight: 600; }
.bad { color: #cf222e; font-weight: 600; }
.error { color: #cf222e; border-left: 3px solid #cf222e; padding: 4px 10px; background: #fff5f5; }
.accuracy { font-size: 0.92em; }
section.analysis { margin-top: 36px; }
section.analysis h2 { font-family: "DejaVu Sans Mono", Menlo, Consolas, monospace; }
.description { font-weight: 600; margin: 4px 0; }
.charts { display: flex; flex-wrap: wrap; gap: 16px; }
figure { margin: 8px 0; flex: 0 1 552px; max-width: 100%; }
figure svg { width: 100%; height: auto; display: block; border: 1px solid #e5e8eb; }
details { margin: 6px 0; }
summary { cursor: pointer; color: #0b5394; }
.scroll { overflow-x: auto; max-width: 100%; }
.scroll table { font-size: 0.85em; }
pre { background: #f6f8fa; padding: 10px; overflow-x: auto; font-size: 0.85em; }
nav ol { columns: 2; margin: 0; }
.views { display: flex; flex-wrap: wrap; gap: 12px; }
.views figure.view { flex: 1 1 300px; margin: 0; }
.views figure.view svg { border: 1px solid #e5e8eb; }
ul.view-legend { list-style: none; padding: 0; display: flex; flex-wrap: wrap; gap: 4px 18px; font-size: 0.85em; }
ul.view-legend svg { vertical-align: middle; }
figure.view3d { margin: 12px 0; }
figure.view3d canvas { width: 100%; height: 560px; display: block; border: 1px solid #e5e8eb; touch-action: none; }
.view3d-controls { display: flex; flex-wrap: wrap; gap: 8px; align-items: center; margin-bottom: 6px; }
.view3d-controls input[type=range] { flex: 1 1 200px; }
@media print {
  body { max-width: none; padding: 0; font-size: 10pt; }
  section.analysis { break-before: page; }
  figure, table.figures, .accuracy { break-inside: avoid; }
  summary { color: inherit; }
  a { color: inherit; text-decoration: none; }
}
"#;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prolog_of_a_standalone_svg_is_dropped() {
        let svg = "<?xml version=\"1.0\"?>\n<!DOCTYPE svg>\n<svg xmlns=\"http://www.w3.org/2000/svg\"></svg>\n";
        assert_eq!(inline_svg(svg), "<svg xmlns=\"http://www.w3.org/2000/svg\"></svg>");
        assert_eq!(inline_svg("<svg/>"), "<svg/>");
    }

    #[test]
    fn numbers_never_print_non_finite_or_negative_zero() {
        assert_eq!(fixed(f64::NAN, 2), "");
        assert_eq!(fixed(f64::INFINITY, 2), "");
        assert_eq!(fixed(-0.001, 2), "0.00");
        assert_eq!(fixed(-1.234, 2), "-1.23");
        assert_eq!(cell(&Cell::Number(f64::NAN), 6), "");
        assert_eq!(significant(0.000123456, 2), "0.00012");
        assert_eq!(significant(1.2e-9, 2), "1.2e-9");
        assert_eq!(plain(-0.08), "-0.08");
        assert_eq!(plain(3800.0), "3800");
        assert_eq!(plain(2071.431612), "2071.43");
        assert_eq!(plain(0.0), "0");
        assert_eq!(plain(f64::NAN), "");
    }

    #[test]
    fn provenance_values_read_as_words() {
        assert_eq!(scalar(&serde_json::json!("corrected")), "corrected");
        assert_eq!(scalar(&serde_json::json!([1, 2.5])), "1, 2.5");
        assert_eq!(scalar(&serde_json::json!(null)), "—");
    }
}
