//! `elastokin live`'s page: the report's style, interactive charts (uPlot with `src/charts.js`) and 3D
//! view (`src/view3d.js`), and `src/live.js`, which asks the server for the design, shows its figures,
//! charts, hardpoints and rates, sends a hardpoint typed in millimetres (a rate in SI) as an edit, and draws
//! each chart's previous design under the new one; `src/live_views.js` makes the projections' hardpoints
//! draggable, draws the guidance's arrows and animates a tune's move. Everything it shows comes from the
//! server's state; the page holds no figure of its own.

use super::charts::{chart_data, CHARTS_SCRIPT, UPLOT_SCRIPT};
use super::write_head;
use crate::suspensions::kc::{Chart, Figure, Units};
use crate::view::{write_viewer_figure, VIEWER_SCRIPT};
use std::fmt::Write;

/// The page's own script.
const LIVE_SCRIPT: &str = include_str!("../live.js");

/// The projections' hardpoints, arrows and animation, used by [`LIVE_SCRIPT`].
const LIVE_VIEWS_SCRIPT: &str = include_str!("../live_views.js");

/// The page of the design of the model named `model`: its skeleton, filled in by its script from the
/// server's state.
pub fn live_html(model: &str) -> String {
    let mut out = String::new();
    write_page(&mut out, model).expect("writing to a String cannot fail");
    out
}

fn write_page(out: &mut String, model: &str) -> std::fmt::Result {
    let lede = "Type a hardpoint's coordinate in millimetres, or drag the point in a view: every figure and \
                chart answers; the previous design's curves stay in grey beneath.";
    write_head(out, model, lede)?;
    // No icon to ask the server for: a request without the token would be refused, in the console.
    *out = out.replacen("</head>", "<link rel=\"icon\" href=\"data:,\"/>\n</head>", 1);
    // Every design redraws every chart: those out of the window are laid out and painted only when
    // scrolled to, and a chart's own changes never lay out the page around it. The figures' table, wide
    // with the guidance beside each figure, scrolls within its column.
    *out = out.replacen("</head>", "<style>#charts figure.chart { content-visibility: auto; contain-intrinsic-size: auto 480px; } #figures { overflow-x: auto; }</style>\n</head>", 1);
    writeln!(
        out,
        r#"<p class="live-bar"><button id="undo" type="button" disabled="disabled">Undo</button> <button id="redo" type="button" disabled="disabled">Redo</button> <button id="save" type="button">Save</button> <button id="tune" type="button" hidden="hidden">Tune to the targets</button> <span id="status" role="status" class="note"></span></p>"#
    )?;
    writeln!(out, r#"<p id="error" class="error" hidden="hidden"></p>"#)?;
    writeln!(
        out,
        r#"<div class="columns"><section id="figures"></section><section><div id="hardpoints"></div><div id="rates"></div></section></div>"#
    )?;
    writeln!(out, r#"<section id="geometry"><h2>Geometry</h2>"#)?;
    writeln!(
        out,
        r#"<p id="views-hint" class="note">Drag a hardpoint's ring in a view to move the point along one of the view's two axes, the one the pointer first moves most along, in steps of 0.1 mm; it is sent as an edit when released, and Escape cancels it. A click on a ring selects the point: arrows at it show the way that raises the figure chosen (click a figure's row to choose another).</p>"#
    )?;
    writeln!(out, r#"<div id="projections"></div>"#)?;
    writeln!(out, r#"<p id="arrows-legend" class="note" hidden="hidden"></p>"#)?;
    write_viewer_figure(
        out,
        "3D view of the design shown: drag to turn, wheel to zoom; the slider moves the parts through the \
         analysis as solved",
    )?;
    writeln!(out, "</section>")?;
    writeln!(out, r#"<section id="charts" class="charts"></section>"#)?;
    writeln!(out, r#"<output id="charts-state" hidden="hidden"></output>"#)?;
    writeln!(out, r#"<output id="live-state" hidden="hidden"></output>"#)?;
    writeln!(
        out,
        "<script>//<![CDATA[\n{UPLOT_SCRIPT}\n{CHARTS_SCRIPT}\n{VIEWER_SCRIPT}\n{LIVE_VIEWS_SCRIPT}\n{LIVE_SCRIPT}\n//]]></script>"
    )?;
    writeln!(out, "</body>")?;
    writeln!(out, "</html>")
}

/// A figure's error estimate as the report writes it (`± e unit` under `units`), for the page to show
/// beside its value; `None` when it has none.
pub fn live_estimate_words(figure: &Figure, units: Units) -> Option<String> {
    super::figures::estimate_words(figure, units)
}

/// Each chart of the state's analyses as the page draws it (the report's data of a chart: its curves'
/// finite points and colours).
pub fn live_chart_data(chart: &Chart) -> serde_json::Value {
    chart_data(chart)
}
