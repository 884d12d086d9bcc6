//! The K&C report as one self-contained HTML file, the one an engineer mails to a colleague: the
//! headline figures with their error estimates, the plots inline, the accuracy of every analysis, the
//! warnings, the hardpoints and the model itself, under a block saying how the run was made.
//!
//! The page needs nothing but itself: CSS inline, no font, no link out of the file, and two scripts,
//! inline: the 3D view's ([`crate::view`]) and the interactive charts' (uPlot, `assets/uplot/`, with
//! `src/charts.js`: a read-out under the pointer, curves toggled from the legend, zoom by dragging), drawn
//! from each chart's data in place of its SVG. Everything else, the geometry's projections included, is
//! SVG and shows with scripts off, and the SVG charts are what prints. It is written as XHTML-compatible
//! HTML (every element closed, only the five XML entities, the scripts in CDATA sections) so an XML
//! parser can check that it is well-formed.
//!
//! Every number on the page comes from the report or the model file: a figure without a value shows
//! its reason, an empty table cell stays empty, and nothing non-finite is printed.
//!
//! This module is the skeleton every page shares: its head with the style inline ([`style`]), its header,
//! and its foot, how the run was made ([`provenance`]). Each page is a module ([`report`], the K&C report;
//! [`sensitivity`], [`tolerance`], [`tune`], [`compare`], [`vehicle`], and `elastokin live`'s page, [`live`]), and each section of the K&C report
//! one more (warnings, hardpoints, the analyses' contents, each analysis with its figures, the analyses not
//! run, the model file); the geometry's projections and 3D view are [`crate::view`]'s.

use crate::markup::{attr, text};
use serde_json::Value;
use std::fmt::Write;
use style::STYLE;

mod analysis;
mod charts;
mod compare;
mod contents;
mod figures;
mod hardpoints;
mod live;
mod model;
mod provenance;
mod report;
mod sensitivity;
mod skipped;
mod style;
mod summary;
mod tables;
mod tolerance;
mod tune;
mod vehicle;
mod warnings;

pub use compare::compare_html;
pub use live::{live_chart_data, live_estimate_words, live_html};
pub use report::{report_html, report_html_with, Extras, Sensitivities};
pub use sensitivity::sensitivity_html;
pub use summary::Judged;
pub use tables::TABLE_ROW_LIMIT;
pub use tolerance::{outside_words, tolerance_html};
pub use tune::tune_html;
pub use vehicle::vehicle_html;

/// The most characters of the model's name shown in the page's title and heading.
pub const NAME_SHOWN: usize = 120;

/// The page's opening: the document type, the head (its `title` as given, the style inline), `<body>`, and
/// the page's header: `title` again as its heading, and the `lede` beneath it.
fn write_head(out: &mut String, title: &str, lede: &str) -> std::fmt::Result {
    writeln!(out, "<!DOCTYPE html>")?;
    writeln!(out, r#"<html xmlns="http://www.w3.org/1999/xhtml" lang="en">"#)?;
    writeln!(out, "<head>")?;
    writeln!(out, r#"<meta charset="utf-8"/>"#)?;
    writeln!(out, r#"<meta name="viewport" content="width=device-width, initial-scale=1"/>"#)?;
    writeln!(out, r#"<meta name="generator" content="elastokin {}"/>"#, attr(env!("CARGO_PKG_VERSION")))?;
    writeln!(out, "<title>{}</title>", text(title))?;
    writeln!(out, "<style>{STYLE}{}</style>", charts::UPLOT_STYLE)?;
    writeln!(out, "</head>")?;
    writeln!(out, "<body>")?;
    writeln!(out, "<header>")?;
    writeln!(out, "<h1>{}</h1>", text(title))?;
    writeln!(out, "<p class=\"lede\">{}</p>", text(lede))?;
    writeln!(out, "</header>")
}

/// The page's end: how the run was made, and the closing tags.
fn write_foot(out: &mut String, provenance: &Value) -> std::fmt::Result {
    provenance::write_provenance(out, provenance)?;
    writeln!(out, "</body>")?;
    writeln!(out, "</html>")
}
