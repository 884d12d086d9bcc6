//! Plots of a K&C report, as data: what to draw, not how. The `elastokin` command and the HTML report
//! render them (SVG or PNG) with one plot module; Python users get the same curves as arrays.

use serde::{Deserialize, Serialize};

/// One curve: a legend name and its points in drawing order. Points with a non-finite coordinate are
/// left out when drawn.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// `(x, y)` points in the axes' units.
    pub points: Vec<(f64, f64)>,
}

/// How an axis maps numbers to length.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Scale {
    /// Evenly spaced numbers.
    #[default]
    Linear,
    /// Evenly spaced decades (positive values only; others are left out and counted under the plot).
    Log,
}

/// A vertical axis with the curves drawn against it: one unit per axis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct YAxis {
    /// Label with its unit, e.g. `angle [deg]`.
    pub label: String,
    /// Its scale.
    pub scale: Scale,
    /// The curves read against it.
    pub series: Vec<Series>,
}

/// One plot: curves against a shared horizontal axis, on one or two vertical axes (left, and right when
/// a second unit is needed), with the design position marked.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Chart {
    /// File stem for the rendered plot, e.g. `parallel_travel_toe_camber`.
    pub name: String,
    /// What the plot shows, e.g. `toe and camber in parallel wheel travel`.
    pub title: String,
    /// The model's name, shown under the title.
    pub subtitle: String,
    /// Horizontal axis label with its unit.
    pub x_label: String,
    /// Horizontal scale.
    pub x_scale: Scale,
    /// The left axis.
    pub left: YAxis,
    /// The right axis, for a second unit.
    pub right: Option<YAxis>,
    /// Where the design position sits on the horizontal axis (a vertical marker line), if inside.
    pub design_x: Option<f64>,
}
