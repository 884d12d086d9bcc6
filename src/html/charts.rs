//! Plots in a page: a chart drawn by the caller's renderer and put inline as SVG (or its error in its place),
//! with its data for the interactive chart drawn over it when scripts run ([`write_chart_script`]); and the
//! pages' own bar charts.

use crate::markup::{attr, text};
use crate::suspensions::kc::{significant_among, Chart, Scale, YAxis};
use serde_json::{json, Value};
use std::fmt::Write;

/// uPlot (`assets/uplot/`, MIT), the charting library the interactive charts are drawn with: 51 kB, with
/// the pointer's read-out, legend toggles and zoom built in, where Chart.js 4.6 weighs 210 kB and needs a
/// plugin to zoom.
pub(super) const UPLOT_SCRIPT: &str = include_str!("../../assets/uplot/uPlot.iife.min.js");
/// uPlot's own style, in every page's head.
pub(super) const UPLOT_STYLE: &str = include_str!("../../assets/uplot/uPlot.min.css");
/// The interactive charts drawn from each figure's data.
pub(super) const CHARTS_SCRIPT: &str = include_str!("../charts.js");

/// `chart` drawn by `render_chart`, inline in a figure with its data (`data-chart`) for the interactive
/// chart; one that could not be drawn shows why.
pub(super) fn write_chart(
    out: &mut String,
    chart: &Chart,
    render_chart: &dyn Fn(&Chart) -> Result<String, String>,
) -> std::fmt::Result {
    // The plot carries its own title; one that could not be drawn is named in its error.
    writeln!(
        out,
        "<figure class=\"chart\" id=\"chart-{}\" data-chart=\"{}\">",
        attr(&chart.name),
        attr(&chart_data(chart).to_string())
    )?;
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

/// The script that draws every chart of the page interactively (uPlot and the page's own), and the state
/// it reports (`charts-state`: charts found, drawn, errors); written once, after the page's charts.
pub(super) fn write_chart_script(out: &mut String) -> std::fmt::Result {
    writeln!(out, "<output id=\"charts-state\" hidden=\"hidden\"></output>")?;
    writeln!(out, "<script>//<![CDATA[\n{UPLOT_SCRIPT}\n{CHARTS_SCRIPT}\n//]]></script>")
}

/// The data of `chart` for the interactive chart: title, axes' labels and scales, the design position, and
/// each curve's finite points with its colour (the SVG's: counted over both axes).
pub(super) fn chart_data(chart: &Chart) -> Value {
    let mut k = 0;
    let mut axis = |a: &YAxis| {
        let series: Vec<Value> = a
            .series
            .iter()
            .map(|s| {
                let finite = s.points.iter().filter(|p| p.0.is_finite() && p.1.is_finite());
                let (x, y): (Vec<f64>, Vec<f64>) = finite.copied().unzip();
                k += 1;
                json!({ "name": s.name, "colour": crate::plot::series_colour_hex(k - 1), "x": x, "y": y })
            })
            .collect();
        json!({ "label": a.label, "log": a.scale == Scale::Log, "series": series })
    };
    let mut axes = vec![axis(&chart.left)];
    axes.extend(chart.right.as_ref().map(&mut axis));
    json!({
        "title": chart.title,
        "x_label": chart.x_label,
        "x_log": chart.x_scale == Scale::Log,
        "design_x": chart.design_x.filter(|x| x.is_finite()),
        "axes": axes,
    })
}

/// A horizontal bar chart as inline SVG: one bar per `(label, value)`, drawn from a centre line (negative
/// to the left), the largest magnitude the full width, each value printed with `unit` (a value that is
/// rounding beside the largest as 0).
pub(super) fn write_bars(out: &mut String, bars: &[(String, f64)], unit: &str) -> std::fmt::Result {
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
            text(&significant_among(*v, 3, largest)),
            text(unit)
        )?;
    }
    writeln!(out, "</svg>")
}

/// A histogram of `samples` as inline SVG: twenty bins spanning the samples, the nominal value `nominal` a
/// dark line and a limit's ends (`(min, max)`, either open) red lines where they lie within the samples'
/// span of them (one further would squeeze the bins to a sliver), the axis's ends written with `unit`.
pub(super) fn write_histogram(
    out: &mut String,
    samples: &[f64],
    nominal: f64,
    limit: Option<(Option<f64>, Option<f64>)>,
    unit: &str,
) -> std::fmt::Result {
    const BINS: usize = 20;
    let (width, height, base, margin) = (900.0, 160.0, 130.0, 40.0);
    let range = |values: &mut dyn Iterator<Item = f64>| {
        values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)))
    };
    let (least, most) = range(&mut samples.iter().copied().chain([nominal]));
    let near = |e: &f64| *e >= least - (most - least) && *e <= most + (most - least);
    let ends: Vec<f64> = limit.into_iter().flat_map(|(a, b)| [a, b]).flatten().filter(near).collect();
    let (low, high) = range(&mut [least, most].into_iter().chain(ends.iter().copied()));
    // A spread of rounding is drawn as one bin about its value.
    let span = (high - low).max(1e-12 * low.abs().max(1e-300));
    let x_of = |v: f64| margin + (width - 2.0 * margin) * (v - low) / span;
    let mut counts = [0usize; BINS];
    for v in samples {
        counts[(((v - low) / span * BINS as f64) as usize).min(BINS - 1)] += 1;
    }
    let most = counts.iter().copied().max().unwrap_or(1).max(1) as f64;
    let bin = (width - 2.0 * margin) / BINS as f64;
    writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" role="img">"#
    )?;
    for (k, n) in counts.iter().enumerate() {
        let h = (base - 10.0) * *n as f64 / most;
        writeln!(
            out,
            r##"<rect x="{:.1}" y="{:.1}" width="{:.1}" height="{h:.1}" fill="#0969da"><title>{n}</title></rect>"##,
            margin + bin * k as f64 + 1.0,
            base - h,
            bin - 2.0
        )?;
    }
    writeln!(out, r##"<line x1="{margin}" y1="{base}" x2="{}" y2="{base}" stroke="#8c959f"/>"##, width - margin)?;
    let label = |out: &mut String, x: f64, v: f64, anchor: &str| {
        writeln!(
            out,
            r#"<text x="{x:.1}" y="{}" font-size="11" text-anchor="{anchor}" font-family="sans-serif">{} {}</text>"#,
            base + 16.0,
            text(&significant_among(v, 4, span)),
            text(unit)
        )
    };
    label(out, margin, low, "start")?;
    label(out, width - margin, high, "end")?;
    let mut line = |v: f64, colour: &str| {
        let x = x_of(v);
        writeln!(out, r#"<line x1="{x:.1}" y1="4" x2="{x:.1}" y2="{base}" stroke="{colour}" stroke-width="2"/>"#)
    };
    line(nominal, "#24292f")?;
    for end in ends {
        line(end, "#cf222e")?;
    }
    writeln!(
        out,
        r#"<text x="{}" y="{}" font-size="11" text-anchor="middle" font-family="sans-serif">{} samples</text>"#,
        width / 2.0,
        base + 28.0,
        samples.len()
    )?;
    writeln!(out, "</svg>")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 100 samples evenly over their span fall five to each of the twenty bins; a limit end within the span
    /// is drawn and one a hundred spans away is not; an equal spread of samples draws one full bin.
    #[test]
    fn a_histogram_counts_every_sample_once_and_draws_the_limits_near_them() {
        let samples: Vec<f64> = (0..100).map(|k| k as f64 + 0.5).collect();
        let mut out = String::new();
        write_histogram(&mut out, &samples, 50.0, Some((Some(10.0), Some(1e4))), "mm").unwrap();
        assert_eq!(out.matches("<title>5</title>").count(), 20, "{out}");
        assert_eq!(out.matches("stroke=\"#cf222e\"").count(), 1);
        roxmltree::Document::parse(&out).unwrap();
        let mut out = String::new();
        write_histogram(&mut out, &[2.0; 7], 2.0, None, "deg").unwrap();
        assert!(out.contains("<title>7</title>") && !out.contains("NaN") && !out.contains("inf"), "{out}");
    }

    #[test]
    fn prolog_of_a_standalone_svg_is_dropped() {
        let svg = "<?xml version=\"1.0\"?>\n<!DOCTYPE svg>\n<svg xmlns=\"http://www.w3.org/2000/svg\"></svg>\n";
        assert_eq!(inline_svg(svg), "<svg xmlns=\"http://www.w3.org/2000/svg\"></svg>");
        assert_eq!(inline_svg("<svg/>"), "<svg/>");
    }
}
