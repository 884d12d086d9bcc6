//! Plots of K&C curves and benchmark results, drawn with [plotters]: the one renderer of the `elastokin`
//! command and of `cargo xtask bench`.
//!
//! A [`Chart`] says what to draw (curves on a left axis and, for a second unit, a right one, the design
//! position, linear or log scales); [`svg`] returns it as an SVG document and [`png()`] as PNG bytes.
//!
//! - Tick labels are rounded to the precision the tick step needs (`-0.02`, not `-0.019999999999999997`).
//! - The title and the subtitle (the model's name, smaller, on a second line) are measured with the
//!   shipped font and shortened with an ellipsis only when they would not fit the width.
//! - The legend sits under the plotting area, never over the curves; on a two-axis chart each entry says
//!   which axis its curve is read against.
//! - The design position is a thin dashed vertical line labelled "design" above the plotting area.
//! - A point with a non-finite coordinate, or a non-positive one on a log scale, is left out (the curve is
//!   broken there rather than joined across the gap) and counted in a note under the plot.
//! - A chart without a drawable point is an empty frame with that note, not an error.
//!
//! Text is measured and, in PNG, drawn with DejaVu Sans compiled into the program
//! (`assets/fonts/DejaVuSans.ttf`, licence beside it), so a machine without system fonts draws the same
//! plot. SVG names the generic `sans-serif` family; widths are measured conservatively, so the viewer's
//! own sans-serif fits in the room left for it.

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::ops::Range;
use std::sync::OnceLock;

pub use elastokin_suspensions::kc::{Chart, Scale, Series, YAxis};

/// Why a plot could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The built-in font did not load (the program was built with a damaged font file).
    #[error("the font for the plot text could not be loaded")]
    Font,
    /// The drawing library reported a failure.
    #[error("the plot could not be drawn: {0}")]
    Draw(String),
    /// The drawn image could not be encoded as PNG.
    #[error("the plot could not be encoded as PNG: {0}")]
    Png(#[from] png::EncodingError),
}

/// The plot as an SVG document.
pub fn svg(chart: &Chart) -> Result<String, PlotError> {
    let layout = Layout::new(chart)?;
    let mut text = String::new();
    draw(SVGBackend::with_string(&mut text, (layout.width, layout.height)).into_drawing_area(), &layout)?;
    Ok(text)
}

/// The plot as the bytes of a PNG image (8-bit RGB), ready to be written to a `.png` file.
pub fn png(chart: &Chart) -> Result<Vec<u8>, PlotError> {
    let layout = Layout::new(chart)?;
    let (width, height) = (layout.width, layout.height);
    let mut rgb = vec![0u8; width as usize * height as usize * 3];
    draw(BitMapBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area(), &layout)?;
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&rgb)?;
    writer.finish()?;
    Ok(bytes)
}

const FONT: &[u8] = include_bytes!("../assets/fonts/DejaVuSans.ttf");
/// The family every text of the plot asks for; the shipped font is registered under it.
const FAMILY: &str = "sans-serif";

const WIDTH: u32 = 820;
/// Height of the plotting area with its axis labels.
const PLOT_HEIGHT: u32 = 440;
const OUTER_MARGIN: u32 = 10;
/// Room above the plotting area for the "design" label.
const MARKER_ROOM: u32 = 28;
// Text sizes as plotters takes them (its SVG writes 1/1.24 of each as the font size), chosen so that a chart
// shown two to a row in the report, at about 0.65 of its width, has no label under 10 px (the layout test
// in `xtask/src/browser.rs` holds it).
const TITLE_SIZE: f64 = 23.0;
const SUBTITLE_SIZE: f64 = 19.0;
const TICK_SIZE: f64 = 19.0;
const AXIS_LABEL_SIZE: f64 = 20.0;
const LEGEND_SIZE: f64 = 19.0;
const NOTE_SIZE: f64 = 19.0;
const LEGEND_ROW: u32 = 28;
/// Space between the horizontal axis label and the legend.
const LEGEND_GAP: u32 = 8;
const SWATCH: i32 = 28;
/// A right-axis curve's dashes and gaps (px).
const DASH: u32 = 9;
const GAP: u32 = 6;
/// Series with at most this many drawn points also get a dot at each point, so a sparse or single-point
/// curve is visible.
const MARKED_POINTS: usize = 20;
/// Values beyond this magnitude are treated like non-finite ones: a range spanning them cannot be divided
/// into ticks.
const LARGEST_VALUE: f64 = 1e300;
const GRID: RGBColor = RGBColor(221, 221, 221);
const MINOR_GRID: RGBColor = RGBColor(238, 238, 238);
const MUTED: RGBColor = RGBColor(96, 96, 96);
const COLOURS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
];

/// The colour of the `k`-th curve of a chart (counted over both axes), also a design's colour wherever
/// designs are compared (its curves and its geometry).
pub fn series_colour(k: usize) -> RGBColor {
    COLOURS[k % COLOURS.len()]
}

/// The same as `#rrggbb`, for SVG and CSS.
pub fn series_colour_hex(k: usize) -> String {
    let RGBColor(r, g, b) = series_colour(k);
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// Registers the shipped font once per process; plotters looks fonts up by family name.
fn font_ready() -> Result<(), PlotError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| plotters::style::register_font(FAMILY, FontStyle::Normal, FONT).is_ok());
    if ok {
        Ok(())
    } else {
        Err(PlotError::Font)
    }
}

fn text_size(text: &str, size: f64) -> Result<(u32, u32), PlotError> {
    (FAMILY, size).into_font().box_size(text).map_err(|_| PlotError::Font)
}

/// Bidirectional-text controls (embeddings, overrides, isolates and marks): pasted with a name from
/// elsewhere, an unterminated override turns every later character of a line around. A drawn text goes
/// without them.
const BIDI_CONTROLS: [char; 12] = [
    '\u{061C}', '\u{200E}', '\u{200F}', '\u{202A}', '\u{202B}', '\u{202C}', '\u{202D}', '\u{202E}', '\u{2066}',
    '\u{2067}', '\u{2068}', '\u{2069}',
];

/// `text` as it is drawn or shown in a heading: without bidirectional-text controls, each character no
/// text is written with as its escape (`printable`), and at most `most`
/// characters, the rest an ellipsis. Linear in the length of `text`, however long.
pub fn shown(text: &str, most: usize) -> String {
    let text = crate::suspensions::file::key_path::printable(text);
    let mut kept = text.chars().filter(|c| !BIDI_CONTROLS.contains(c));
    let mut out: String = kept.by_ref().take(most).collect();
    if kept.next().is_some() {
        out.truncate(out.trim_end().len());
        out.push('…');
    }
    out
}

/// `text`, shortened with an ellipsis until it is at most `width` pixels wide, in time linear in its
/// length: no glyph is narrower than a pixel, so at most `width` characters are measured, and the longest
/// prefix that fits is found by bisection (a longer prefix is never narrower). Each character no text is
/// written with is drawn as its escape (an SVG with a control character in it is no XML).
fn fit(text: &str, size: f64, width: u32) -> Result<String, PlotError> {
    let text = &*crate::suspensions::file::key_path::printable(text);
    let most = width as usize;
    if text.chars().nth(most).is_none() && text_size(text, size)?.0 <= width {
        return Ok(text.to_string());
    }
    let chars: Vec<char> = text.chars().take(most).collect();
    let candidate = |n: usize| format!("{}…", chars[..n].iter().collect::<String>().trim_end());
    // The longest prefix whose candidate fits: `lo` fits (or is 0), `hi` does not.
    let (mut lo, mut hi) = (0, chars.len().min(text.chars().count() - 1) + 1);
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if text_size(&candidate(mid), size)?.0 <= width {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(if lo == 0 { "…".to_string() } else { candidate(lo) })
}

/// One axis as drawn: its range and ticks in drawn units (log10 of the value on a log scale).
#[derive(Debug, Clone, PartialEq)]
struct Axis {
    lo: f64,
    hi: f64,
    /// Tick positions with their labels (an empty label: a grid line without a number).
    ticks: Vec<(f64, String)>,
    /// Unlabelled thin grid lines (2…9 within each decade on a log scale).
    minor: Vec<f64>,
}

impl Axis {
    /// An axis covering `values` (drawn units). `pad` leaves a margin so curves do not run along the frame.
    fn new(scale: Scale, values: &[f64], pad: bool) -> Axis {
        match scale {
            Scale::Linear => linear_axis(values, pad),
            Scale::Log => log_axis(values),
        }
    }

    /// The label of the tick at `at` (plotters hands the formatter back the positions it was given).
    fn label(&self, at: f64) -> String {
        self.ticks
            .iter()
            .min_by(|a, b| (a.0 - at).abs().total_cmp(&(b.0 - at).abs()))
            .map(|t| t.1.clone())
            .unwrap_or_default()
    }

    fn widest_label(&self) -> Result<(u32, u32), PlotError> {
        self.ticks.iter().try_fold((0, 0), |(w, h), t| {
            let (tw, th) = text_size(&t.1, TICK_SIZE)?;
            Ok((w.max(tw), h.max(th)))
        })
    }
}

/// The axis as plotters' coordinate: a linear map of drawn units with our ticks as its key points (the
/// grid lines) and our minor lines as its light points.
impl Ranged for Axis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let along = (value - self.lo) / (self.hi - self.lo);
        limit.0 + (f64::from(limit.1 - limit.0) * along).round() as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.minor.clone()
        } else {
            self.ticks.iter().map(|t| t.0).collect()
        }
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

fn min_max(values: &[f64]) -> Option<(f64, f64)> {
    values.iter().fold(None, |acc, &v| match acc {
        None => Some((v, v)),
        Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
    })
}

/// A tick step of 1, 2 or 5 × 10^`exponent` giving 4 to 8 ticks over `span`, with that exponent.
fn tick_step(span: f64) -> (f64, i32) {
    let exponent = (span / 6.0).log10().floor() as i32;
    let magnitude = 10f64.powi(exponent);
    for m in [1.0, 2.0, 5.0] {
        // The slack keeps a span of exactly 8 steps from tipping over on rounding.
        if span / (m * magnitude) <= 8.0 + 1e-9 {
            return (m * magnitude, exponent);
        }
    }
    (10.0 * magnitude, exponent + 1)
}

/// `value`, a multiple of 10^`exponent`, with as many digits as that step needs; `largest` is the
/// largest tick magnitude on the axis, which decides between plain and scientific notation.
fn tick_label(value: f64, exponent: i32, largest: f64) -> String {
    if value == 0.0 {
        return "0".to_string();
    }
    let trim = |s: &str| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    };
    if exponent < -4 || largest >= 1e6 {
        let lead = largest.log10().floor() as i32;
        let text = format!("{:.*e}", (lead - exponent).max(0) as usize, value);
        match text.split_once('e') {
            Some((mantissa, power)) => format!("{}e{power}", trim(mantissa)),
            None => text,
        }
    } else {
        let text = trim(&format!("{:.*}", (-exponent).max(0) as usize, value));
        if text == "-0" {
            "0".to_string()
        } else {
            text
        }
    }
}

fn linear_axis(values: &[f64], pad: bool) -> Axis {
    let (mut lo, mut hi) = min_max(values).unwrap_or((0.0, 1.0));
    let size = lo.abs().max(hi.abs());
    // One value, or values equal to rounding noise: centre them in a band of ±10 % (±1 about zero)
    // instead of blowing noise up to the full height.
    if hi - lo <= 1e-9 * size || hi - lo == 0.0 {
        let half = if size > 0.0 { 0.1 * size } else { 1.0 };
        let mid = 0.5 * (lo + hi);
        (lo, hi) = (mid - half, mid + half);
    } else if pad {
        let margin = 0.05 * (hi - lo);
        (lo, hi) = (lo - margin, hi + margin);
    }
    let (step, exponent) = tick_step(hi - lo);
    // Multiples of the step inside the range; the slack keeps an end tick that rounding put a hair outside.
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    let positions: Vec<f64> = (first..=last).map(|i| i as f64 * step).collect();
    let largest = positions.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let ticks = positions.iter().map(|&v| (v, tick_label(v, exponent, largest))).collect();
    Axis { lo, hi, ticks, minor: Vec::new() }
}

/// `10^decade` as a label: plain from 0.001 to 10000, `1e-5` style beyond.
fn decade_label(decade: i32) -> String {
    if (-3..=4).contains(&decade) {
        tick_label(10f64.powi(decade), decade.min(0), 10f64.powi(decade))
    } else {
        format!("1e{decade}")
    }
}

/// A log axis over whole decades covering `values` (log10 of the data).
fn log_axis(values: &[f64]) -> Axis {
    let (lo, hi) = min_max(values).map(|(lo, hi)| (lo.floor(), hi.ceil())).unwrap_or((0.0, 1.0));
    let hi = if hi <= lo { lo + 1.0 } else { hi };
    let (first, last) = (lo as i32, hi as i32);
    // At most twelve numbers on the axis (about 30 px apart); the other decades keep their grid line.
    let stride = (last - first) / 12 + 1;
    let ticks = (first..=last)
        .map(|d| (d as f64, if (d - first) % stride == 0 { decade_label(d) } else { String::new() }))
        .collect();
    let minor = if last - first <= 6 {
        (first..last).flat_map(|d| (2..10).map(move |m| d as f64 + (m as f64).log10())).collect()
    } else {
        Vec::new()
    };
    Axis { lo, hi, ticks, minor }
}

/// One series as drawn.
#[derive(Debug)]
struct Curve {
    legend: String,
    colour: RGBColor,
    on_right: bool,
    /// Unbroken stretches of drawable points, drawn units.
    runs: Vec<Vec<(f64, f64)>>,
    marked: bool,
}

/// Counts of points left out.
#[derive(Debug, Default)]
struct LeftOut {
    not_finite: usize,
    not_positive: usize,
}

/// A value in drawn units, or `None` with the reason counted.
fn drawn(value: f64, scale: Scale, left_out: &mut LeftOut) -> Option<f64> {
    if !value.is_finite() || value.abs() > LARGEST_VALUE {
        left_out.not_finite += 1;
        return None;
    }
    match scale {
        Scale::Linear => Some(value),
        Scale::Log if value > 0.0 => Some(value.log10()),
        Scale::Log => {
            left_out.not_positive += 1;
            None
        }
    }
}

fn curve(series: &Series, x_scale: Scale, y_scale: Scale, left_out: &mut LeftOut) -> Vec<Vec<(f64, f64)>> {
    let mut runs = vec![Vec::new()];
    for &(x, y) in &series.points {
        // Both coordinates are checked so that one bad point counts once.
        let mut reasons = LeftOut::default();
        match (drawn(x, x_scale, &mut reasons), drawn(y, y_scale, &mut reasons)) {
            (Some(x), Some(y)) => {
                if let Some(run) = runs.last_mut() {
                    run.push((x, y));
                }
            }
            _ => {
                if reasons.not_finite > 0 {
                    left_out.not_finite += 1;
                } else {
                    left_out.not_positive += 1;
                }
                if runs.last().is_some_and(|run| !run.is_empty()) {
                    runs.push(Vec::new());
                }
            }
        }
    }
    runs.retain(|run| !run.is_empty());
    runs
}

/// Everything measured before drawing: sizes, axes, curves, legend rows.
#[derive(Debug)]
struct Layout {
    width: u32,
    height: u32,
    title: String,
    subtitle: String,
    title_band: u32,
    x: Axis,
    x_label: String,
    left: Axis,
    left_label: String,
    right: Option<(Axis, String)>,
    left_area: u32,
    right_area: u32,
    bottom_area: u32,
    right_margin: u32,
    curves: Vec<Curve>,
    /// Per legend row, `(curve index, x offset from the row start)`.
    legend_rows: Vec<Vec<(usize, i32)>>,
    legend_x: i32,
    note: Option<String>,
    /// Design position in drawn units, when inside the horizontal range.
    design_x: Option<f64>,
}

impl Layout {
    fn new(chart: &Chart) -> Result<Layout, PlotError> {
        font_ready()?;
        let mut left_out = LeftOut::default();
        let mut curves = curves_of(chart, &mut left_out);
        let values = |pick: &dyn Fn(&(f64, f64)) -> f64, right: Option<bool>| -> Vec<f64> {
            curves
                .iter()
                .filter(|c| right.is_none_or(|r| c.on_right == r))
                .flat_map(|c| c.runs.iter().flatten().map(pick))
                .collect()
        };
        let x = Axis::new(chart.x_scale, &values(&|p| p.0, None), false);
        let left = Axis::new(chart.left.scale, &values(&|p| p.1, Some(false)), true);
        let right = chart.right.as_ref().map(|axis| Axis::new(axis.scale, &values(&|p| p.1, Some(true)), true));

        let plot_height = PLOT_HEIGHT - MARKER_ROOM;
        // Each label area holds the widest tick label, the tick and its gap, and the axis label turned
        // on its side, so the two never overlap.
        let side_area = |axis: &Axis| -> Result<u32, PlotError> {
            Ok(axis.widest_label()?.0 + text_size("Mg", AXIS_LABEL_SIZE)?.1 + 30)
        };
        let left_area = side_area(&left)?;
        let right_area = match &right {
            Some(axis) => side_area(axis)?,
            None => 0,
        };
        let (x_tick_w, x_tick_h) = x.widest_label()?;
        let bottom_area = x_tick_h + text_size("Mg", AXIS_LABEL_SIZE)?.1 + 26;
        // Without a right axis, the last x tick label is centred on the frame's edge: leave it room.
        let right_margin = if right.is_some() { OUTER_MARGIN } else { OUTER_MARGIN + x_tick_w / 2 + 4 };
        let frame_width = WIDTH.saturating_sub(OUTER_MARGIN + left_area + right_area + right_margin).max(100);
        let axis_label_room = plot_height.saturating_sub(bottom_area + 20);
        let x_label = fit(&chart.x_label, AXIS_LABEL_SIZE, frame_width)?;
        let left_label = fit(&chart.left.label, AXIS_LABEL_SIZE, axis_label_room)?;
        let right = match (right, &chart.right) {
            (Some(axis), Some(spec)) => Some((axis, fit(&spec.label, AXIS_LABEL_SIZE, axis_label_room)?)),
            _ => None,
        };

        let text_width = WIDTH - 2 * OUTER_MARGIN;
        let title = fit(&chart.title, TITLE_SIZE, text_width)?;
        let subtitle = fit(&shown(&chart.subtitle, text_width as usize), SUBTITLE_SIZE, text_width)?;
        let title_band = 16 + text_size("Mg", TITLE_SIZE)?.1 + if subtitle.is_empty() { 0 } else { 24 };

        let legend_rows = legend_rows(&mut curves, frame_width as i32)?;
        let note = note(&curves, &left_out, text_width)?;

        let design_x = chart
            .design_x
            .and_then(|v| drawn(v, chart.x_scale, &mut LeftOut::default()))
            .filter(|v| (x.lo..=x.hi).contains(v));
        let legend_height = legend_rows.len() as u32 * LEGEND_ROW;
        let note_height = if note.is_some() { 20 } else { 0 };
        let height = title_band + PLOT_HEIGHT + LEGEND_GAP + legend_height + note_height + OUTER_MARGIN;
        Ok(Layout {
            width: WIDTH,
            height,
            title,
            subtitle,
            title_band,
            x,
            x_label,
            left,
            left_label,
            right,
            left_area,
            right_area,
            bottom_area,
            right_margin,
            curves,
            legend_rows,
            legend_x: (OUTER_MARGIN + left_area) as i32,
            note,
            design_x,
        })
    }
}

/// The chart's curves, left axis first, each with its legend (naming its axis where there are two), colour
/// and runs of drawable points; what cannot be drawn is counted in `left_out`.
fn curves_of(chart: &Chart, left_out: &mut LeftOut) -> Vec<Curve> {
    let two_axes = chart.right.is_some();
    let mut curves = Vec::new();
    let axes = std::iter::once((&chart.left, false)).chain(chart.right.iter().map(|axis| (axis, true)));
    for (axis, on_right) in axes {
        for series in &axis.series {
            let runs = curve(series, chart.x_scale, axis.scale, left_out);
            let count: usize = runs.iter().map(Vec::len).sum();
            let legend = match (two_axes, on_right) {
                (false, _) => series.name.clone(),
                (true, false) => format!("{} (left axis)", series.name),
                (true, true) => format!("{} (right axis)", series.name),
            };
            let colour = series_colour(curves.len());
            curves.push(Curve { legend, colour, on_right, runs, marked: count <= MARKED_POINTS });
        }
    }
    curves
}

/// The legend's rows under a frame `width` wide: entries flow left to right, wrapping to new rows, each
/// `(curve, offset)`; each curve's legend is cut to fit a row.
fn legend_rows(curves: &mut [Curve], width: i32) -> Result<Vec<Vec<(usize, i32)>>, PlotError> {
    let mut rows: Vec<Vec<(usize, i32)>> = Vec::new();
    let mut cursor = 0;
    for (k, c) in curves.iter_mut().enumerate() {
        c.legend = fit(&c.legend, LEGEND_SIZE, (width - SWATCH - 8).max(40) as u32)?;
        let entry = SWATCH + 8 + text_size(&c.legend, LEGEND_SIZE)?.0 as i32 + 24;
        match rows.last_mut() {
            Some(row) if cursor + entry - 24 <= width => row.push((k, cursor)),
            _ => {
                rows.push(vec![(k, 0)]);
                cursor = 0;
            }
        }
        cursor += entry;
    }
    Ok(rows)
}

/// The note under the legend, fitted to `width`: nothing to draw, or how many points were left out and why.
fn note(curves: &[Curve], left_out: &LeftOut, width: u32) -> Result<Option<String>, PlotError> {
    let mut notes = Vec::new();
    if curves.iter().all(|c| c.runs.is_empty()) {
        notes.push("no point to draw".to_string());
    }
    if left_out.not_finite > 0 {
        notes.push(format!("{} point(s) with a non-finite value are not drawn", left_out.not_finite));
    }
    if left_out.not_positive > 0 {
        notes.push(format!("{} point(s) at or below zero are not drawn on the log scale", left_out.not_positive));
    }
    if notes.is_empty() {
        return Ok(None);
    }
    Ok(Some(fit(&notes.join("; "), NOTE_SIZE, width)?))
}

fn draw_error(e: impl std::fmt::Display) -> PlotError {
    PlotError::Draw(e.to_string())
}

fn style(size: f64, colour: &RGBColor, h: HPos, v: VPos) -> TextStyle<'static> {
    (FAMILY, size).into_font().color(colour).pos(Pos::new(h, v))
}

fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, layout: &Layout) -> Result<(), PlotError> {
    root.fill(&WHITE).map_err(draw_error)?;
    draw_titles(&root, layout)?;

    let (_, below_title) = root.split_vertically(layout.title_band);
    let (block, below_plot) = below_title.split_vertically(PLOT_HEIGHT);
    let (_, legend_area) = below_plot.split_vertically(LEGEND_GAP);
    let (x, left) = (&layout.x, &layout.left);
    let right = layout.right.as_ref().map(|r| &r.0).unwrap_or(left);
    let mut chart = ChartBuilder::on(&block)
        .margin_top(MARKER_ROOM)
        .margin_left(OUTER_MARGIN)
        .margin_right(layout.right_margin)
        .x_label_area_size(layout.bottom_area)
        .y_label_area_size(layout.left_area)
        .right_y_label_area_size(layout.right_area)
        .build_cartesian_2d(x.clone(), left.clone())
        .map_err(draw_error)?
        // Without a right axis the secondary coordinates repeat the left ones and are never shown: one
        // chart type for both cases.
        .set_secondary_coord(x.clone(), right.clone());

    let x_format = |v: &f64| x.label(*v);
    let left_format = |v: &f64| left.label(*v);
    let right_format = |v: &f64| right.label(*v);
    chart
        .configure_mesh()
        .x_desc(layout.x_label.as_str())
        .y_desc(layout.left_label.as_str())
        .x_label_formatter(&x_format)
        .y_label_formatter(&left_format)
        .label_style((FAMILY, TICK_SIZE))
        .axis_desc_style((FAMILY, AXIS_LABEL_SIZE))
        .bold_line_style(GRID)
        .light_line_style(MINOR_GRID)
        .draw()
        .map_err(draw_error)?;
    if let Some((_, label)) = &layout.right {
        chart
            .configure_secondary_axes()
            .y_desc(label.as_str())
            .y_label_formatter(&right_format)
            .label_style((FAMILY, TICK_SIZE))
            .axis_desc_style((FAMILY, AXIS_LABEL_SIZE))
            .draw()
            .map_err(draw_error)?;
    }
    chart
        .plotting_area()
        .draw(&Rectangle::new([(x.lo, left.lo), (x.hi, left.hi)], BLACK.stroke_width(1)))
        .map_err(draw_error)?;

    if let Some(design) = layout.design_x {
        chart
            .draw_series(DashedLineSeries::new([(design, left.lo), (design, left.hi)], 6, 4, MUTED.stroke_width(1)))
            .map_err(draw_error)?;
        let (px, py) = chart.backend_coord(&(design, left.hi));
        // Centred on the line, except where half of it would reach past the frame's edge, over the tick
        // labels beside it: there it reads inward from the line.
        let (left_edge, _) = chart.backend_coord(&(x.lo, left.hi));
        let (right_edge, _) = chart.backend_coord(&(x.hi, left.hi));
        let half = text_size("design", NOTE_SIZE)?.0 as i32 / 2;
        let anchor = if px - half < left_edge {
            HPos::Left
        } else if px + half > right_edge {
            HPos::Right
        } else {
            HPos::Center
        };
        root.draw(&Text::new("design", (px, py - 4), style(NOTE_SIZE, &MUTED, anchor, VPos::Bottom)))
            .map_err(draw_error)?;
    }

    for c in &layout.curves {
        for run in &c.runs {
            let line = LineSeries::new(run.iter().copied(), c.colour.stroke_width(2));
            let dots = run.iter().filter(|_| c.marked).map(|&p| Circle::new(p, 3, c.colour.filled()));
            // A right-axis curve is dashed: where the two axes' autoscaled curves fall on one another (two
            // quantities proportional to the load), the left one shows between its dashes.
            if c.on_right {
                let dashed = DashedLineSeries::new(run.iter().copied(), DASH, GAP, c.colour.stroke_width(3));
                chart.draw_secondary_series(dashed).map_err(draw_error)?;
                chart.draw_secondary_series(dots).map_err(draw_error)?;
            } else {
                chart.draw_series(line).map_err(draw_error)?;
                chart.draw_series(dots).map_err(draw_error)?;
            }
        }
    }

    draw_legend(&legend_area, layout)?;
    root.present().map_err(draw_error)
}

/// The title, centred at the top, and the subtitle under it.
fn draw_titles<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, layout: &Layout) -> Result<(), PlotError> {
    let centre = layout.width as i32 / 2;
    root.draw(&Text::new(layout.title.as_str(), (centre, 12), style(TITLE_SIZE, &BLACK, HPos::Center, VPos::Top)))
        .map_err(draw_error)?;
    if !layout.subtitle.is_empty() {
        let top = 16 + text_size("Mg", TITLE_SIZE)?.1 as i32;
        root.draw(&Text::new(
            layout.subtitle.as_str(),
            (centre, top),
            style(SUBTITLE_SIZE, &MUTED, HPos::Center, VPos::Top),
        ))
        .map_err(draw_error)?;
    }
    Ok(())
}

/// The legend's rows, each entry a swatch (with a dot where the curve's points are marked) and its words,
/// and the note under them.
fn draw_legend<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, layout: &Layout) -> Result<(), PlotError> {
    for (row_index, row) in layout.legend_rows.iter().enumerate() {
        let y = row_index as i32 * LEGEND_ROW as i32 + LEGEND_ROW as i32 / 2;
        for &(k, offset) in row {
            let c = &layout.curves[k];
            let x0 = layout.legend_x + offset;
            if c.on_right {
                let (dash, step) = (DASH as i32, (DASH + GAP) as i32);
                for start in (x0..x0 + SWATCH).step_by(step as usize) {
                    let end = (start + dash).min(x0 + SWATCH);
                    area.draw(&PathElement::new(vec![(start, y), (end, y)], c.colour.stroke_width(3)))
                        .map_err(draw_error)?;
                }
            } else {
                area.draw(&PathElement::new(vec![(x0, y), (x0 + SWATCH, y)], c.colour.stroke_width(2)))
                    .map_err(draw_error)?;
            }
            if c.marked {
                area.draw(&Circle::new((x0 + SWATCH / 2, y), 3, c.colour.filled())).map_err(draw_error)?;
            }
            let words = style(LEGEND_SIZE, &BLACK, HPos::Left, VPos::Center);
            area.draw(&Text::new(c.legend.as_str(), (x0 + SWATCH + 8, y), words)).map_err(draw_error)?;
        }
    }
    if let Some(note) = &layout.note {
        let y = (layout.legend_rows.len() as u32 * LEGEND_ROW + 10) as i32;
        area.draw(&Text::new(note.as_str(), (layout.legend_x, y), style(NOTE_SIZE, &MUTED, HPos::Left, VPos::Center)))
            .map_err(draw_error)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn labels(axis: &Axis) -> Vec<&str> {
        axis.ticks.iter().map(|t| t.1.as_str()).collect()
    }

    #[test]
    fn ticks_of_a_sweep_in_millimetres_are_whole_numbers() {
        let axis = linear_axis(&[-80.0, 80.0], false);
        assert_eq!(labels(&axis), ["-80", "-60", "-40", "-20", "0", "20", "40", "60", "80"]);
    }

    #[test]
    fn ticks_of_small_angles_carry_the_digits_of_the_step_only() {
        // 0.1 - 0.12 is -0.019999999999999997 in binary floating point: the label.
        let axis = linear_axis(&[0.1 - 0.12, 0.12 - 0.1], true);
        assert_eq!(labels(&axis), ["-0.02", "-0.01", "0", "0.01", "0.02"]);
    }

    #[test]
    fn tiny_and_huge_ticks_use_scientific_notation() {
        assert_eq!(
            labels(&linear_axis(&[0.0, 4e-7], false)),
            ["0", "5e-8", "1e-7", "1.5e-7", "2e-7", "2.5e-7", "3e-7", "3.5e-7", "4e-7"]
        );
        assert_eq!(labels(&linear_axis(&[0.0, 3e6], false)), ["0", "5e5", "1e6", "1.5e6", "2e6", "2.5e6", "3e6"]);
    }

    #[test]
    fn equal_values_get_a_band_around_them() {
        let axis = linear_axis(&[100.0, 100.0], true);
        assert_eq!((axis.lo, axis.hi), (90.0, 110.0));
        let zero = linear_axis(&[0.0], true);
        assert_eq!((zero.lo, zero.hi), (-1.0, 1.0));
        assert!(zero.ticks.len() >= 4);
    }

    #[test]
    fn log_axis_labels_whole_decades() {
        let axis = log_axis(&[(3e-5f64).log10(), (2e-2f64).log10()]);
        assert_eq!((axis.lo, axis.hi), (-5.0, -1.0));
        assert_eq!(labels(&axis), ["1e-5", "1e-4", "0.001", "0.01", "0.1"]);
        assert_eq!(axis.minor.len(), 4 * 8);
        // Sixteen decades: every second one numbered.
        let wide = log_axis(&[-16.0, 0.0]);
        assert_eq!(labels(&wide)[..3], ["1e-16", "", "1e-14"]);
    }

    #[test]
    fn curves_break_at_points_left_out() {
        let series = Series {
            name: "s".into(),
            points: vec![(1.0, 1.0), (2.0, f64::NAN), (3.0, 3.0), (4.0, -1.0), (5.0, 5.0), (f64::INFINITY, 1.0)],
        };
        let mut left_out = LeftOut::default();
        let runs = curve(&series, Scale::Linear, Scale::Log, &mut left_out);
        assert_eq!(runs.len(), 3);
        assert_eq!((left_out.not_finite, left_out.not_positive), (2, 1));
    }
}
