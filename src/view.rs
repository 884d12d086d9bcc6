//! The report's views of the model: its geometry in three projections as inline SVG (front y–z, side
//! x–z, plan x–y, in mm, the design position drawn and the sweep's extremes ghosted), and a 3D view
//! that moves the parts through each analysis as solved (a canvas, orbit, zoom, a slider and play).
//!
//! Both draw the same [`Stroke`]s and [`Dot`]s of the library's [`Drawing`](crate::suspensions::drawing::Drawing), placed by the poses of a
//! row of [`Motion`]: a stroke's points are anchored on the bodies that carry them, so a view only
//! places and projects. The 3D view is a small hand-written script (`src/view3d.js`, 8.8 kB): the scene
//! is a few dozen lines and dots, which a 2D canvas draws in well under a frame. three.js inlined instead
//! (release 0.187.0: `three.module.js` and `three.core.js`, 2.13 MB, and 41 kB of orbit controls) would
//! alone exceed the 2 MB a report may weigh, for triangles it never draws. The page still opens with no
//! network, and everything but the 3D view works with scripts off.

use crate::markup::{attr, text};
use crate::suspensions::drawing::{Anchor, Dot, Motion, Pen, Spot, Stroke, DEFLECTION_SCALE};
use crate::suspensions::kc::{AnalysisReport, Construction, KcReport};
use elastokin_core::{BodyRef, Pose, Vec3};
use serde_json::{json, Value};
use std::fmt::Write;

/// A projection of the model onto the page.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Projection {
    /// Seen from the front: y to the right, z up.
    Front,
    /// Seen from the left: x to the left (the front of the car on the left), z up.
    Side,
    /// Seen from above: x up (the front at the top), y to the left.
    Plan,
}

impl Projection {
    /// All three, in the order the report shows them.
    pub const ALL: [Projection; 3] = [Projection::Front, Projection::Side, Projection::Plan];

    /// Its name, for ids and captions.
    pub fn name(self) -> &'static str {
        match self {
            Projection::Front => "front",
            Projection::Side => "side",
            Projection::Plan => "plan",
        }
    }

    /// The page's horizontal and upward coordinates of a global point: each a global coordinate, its
    /// sign, and the axis's name (so the grid labels the global coordinate itself).
    fn axes(self) -> [(usize, f64, &'static str); 2] {
        match self {
            Projection::Front => [(1, 1.0, "y"), (2, 1.0, "z")],
            Projection::Side => [(0, -1.0, "x"), (2, 1.0, "z")],
            Projection::Plan => [(1, -1.0, "y"), (0, 1.0, "x")],
        }
    }

    fn caption(self) -> &'static str {
        match self {
            Projection::Front => "front view (y–z), seen from the front",
            Projection::Side => "side view (x–z), seen from the left, the front to the left",
            Projection::Plan => "plan view (x–y), seen from above, the front at the top",
        }
    }

    fn project(self, p: &Vec3) -> (f64, f64) {
        let [(a, sa, _), (b, sb, _)] = self.axes();
        (sa * p[a], sb * p[b])
    }
}

/// The points of a stroke as drawn at `poses`: a deflection scaled about its point on body `j`.
pub fn stroke_points(stroke: &Stroke, poses: &[Pose]) -> Vec<Vec3> {
    let points: Vec<Vec3> = stroke.anchors.iter().map(|a| a.placed(poses)).collect();
    match (stroke.pen, points.as_slice()) {
        (Pen::Deflection, [i, j]) => vec![*j, j + (j - i) * DEFLECTION_SCALE],
        _ => points,
    }
}

/// A pen's colour, width and dash pattern (SVG and the 3D view's style alike).
fn pen_style(pen: Pen) -> (&'static str, f64, &'static str) {
    match pen {
        Pen::Part => ("#1f77b4", 3.0, ""),
        Pen::Link => ("#555555", 2.0, ""),
        Pen::Spring => ("#2ca02c", 3.0, "6 3"),
        Pen::Stop => ("#8c564b", 4.0, ""),
        Pen::Beam => ("#17becf", 4.0, ""),
        Pen::Bushing => ("#9467bd", 2.0, ""),
        Pen::Deflection => ("#d62728", 2.0, ""),
        Pen::Wheel => ("#333333", 1.5, ""),
        Pen::SteeringAxis => ("#ff7f0e", 1.5, "8 3 2 3"),
    }
}

/// A spot's colour and radius (px).
fn spot_style(spot: Spot) -> (&'static str, f64) {
    match spot {
        Spot::Joint => ("#222222", 3.5),
        Spot::Bushing => ("#9467bd", 4.5),
        Spot::Mount => ("#444444", 4.0),
        Spot::WheelCentre => ("#333333", 3.0),
    }
}

/// The analysis the projections show: parallel travel when the report has its motion, else the first
/// analysis that has one.
fn shown_analysis(report: &KcReport) -> Option<(&AnalysisReport, &Motion)> {
    let with_motion = || report.analyses.iter().filter_map(|a| Some((a, a.motion.as_ref()?)));
    with_motion().find(|(a, _)| a.analysis.name() == "parallel-travel").or_else(|| with_motion().next())
}

/// The load parameter of row `r` of `a` as a person reads it: the table's first column in its unit
/// (`travel_m` shown in mm).
pub fn row_label(a: &AnalysisReport, r: usize) -> String {
    let column = a.table.columns.first().map_or("", String::as_str);
    let v = a.table.rows.get(r).and_then(|row| row.first()).and_then(|c| c.number()).unwrap_or(f64::NAN);
    let (name, value, unit) = if let Some(name) = column.strip_suffix("_m") {
        (name, v * 1e3, "mm")
    } else if let Some(name) = column.strip_suffix("_deg") {
        (name, v, "deg")
    } else if let Some(name) = column.strip_suffix("_nm") {
        (name, v, "N·m")
    } else if let Some(name) = column.strip_suffix("_n") {
        (name, v, "N")
    } else {
        (column, v, "")
    };
    let value = if value.is_finite() { format!("{value:.1}") } else { "—".into() };
    format!("{} {value} {unit}", name.replace('_', " ")).trim_end().to_string()
}

/// A grid line's coordinate in whole millimetres, a rounded zero without a sign.
fn mm(metres: f64) -> f64 {
    (metres * 1e3).round() + 0.0
}

/// Page size of a projection's drawing area (px), its margin for the grid's labels.
const VIEW_WIDTH: f64 = 380.0;
const VIEW_MAX_HEIGHT: f64 = 420.0;
const LABEL_ROOM: f64 = 44.0;
/// Room right of and above the grid, for the half of a tick label centred on the last grid line.
const EDGE_ROOM: f64 = 18.0;
/// The grid labels' size (px of the view, drawn at about its own size in the report).
const GRID_FONT: f64 = 12.0;
const PAD_M: f64 = 0.03;

/// A grid step (m) giving four to ten lines over `span` (m).
fn grid_step(span: f64) -> f64 {
    [0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0].into_iter().find(|s| span / s <= 10.0).unwrap_or(10.0)
}

/// One layer of a projection: a motion's row drawn, ghosted or not, in its pens' colours or in one.
struct Layer<'a> {
    motion: &'a Motion,
    row: usize,
    ghost: bool,
    /// One colour for every stroke (a design among designs compared), or each pen's own.
    colour: Option<String>,
}

/// The layers of the projections of a motion: its design row drawn over its extremes ghosted (`rows`:
/// design, first, last).
fn design_layers(motion: &Motion, rows: [usize; 3]) -> [Layer<'_>; 3] {
    let [design, first, last] = rows;
    let layer = |row, ghost| Layer { motion, row, ghost, colour: None };
    [layer(first, true), layer(last, true), layer(design, false)]
}

/// One projection of the model at its design row, its extremes ghosted, as an inline SVG.
fn projection_svg(
    out: &mut String,
    motion: &Motion,
    rows: [usize; 3],
    projection: Projection,
    construction: Option<&Construction>,
) -> std::fmt::Result {
    let layers = design_layers(motion, rows);
    layers_svg(out, &layers, projection, &format!("view-{}", projection.name()), construction)
}

/// Where one of the projections [`write_projections`] draws puts a global point on its SVG (px of its
/// viewBox): x is `origin[0] + scale · sign · p[axis]` of its `horizontal` (axis, sign), y is
/// `origin[1] − scale · sign · p[axis]` of its `vertical` (the SVG's y runs down).
#[derive(Debug, Clone, PartialEq)]
pub struct ProjectionFrame {
    /// The id of the projection's figure (`view-front`, `view-side`, `view-plan`).
    pub id: String,
    /// The global coordinate (0 x, 1 y, 2 z) the page's x runs along, and its sign.
    pub horizontal: (usize, f64),
    /// The global coordinate the page's y runs up along, and its sign.
    pub vertical: (usize, f64),
    /// Where the global origin lands (px).
    pub origin: [f64; 2],
    /// Pixels per metre.
    pub scale: f64,
}

impl ProjectionFrame {
    /// As JSON: `{"id", "horizontal": [axis, sign], "vertical": [axis, sign], "origin": [x, y], "scale"}`.
    pub fn json(&self) -> Value {
        json!({ "id": self.id, "horizontal": self.horizontal, "vertical": self.vertical, "origin": self.origin,
                "scale": self.scale })
    }
}

/// The frame of each projection [`write_projections`] draws of `report`, in its order: what a page needs
/// to put its own marks on them. Empty when it draws none.
pub fn projection_frames(report: &KcReport) -> Vec<ProjectionFrame> {
    let Some((_, motion, rows)) = projected(report) else { return Vec::new() };
    let layers = design_layers(motion, rows);
    let strokes: Vec<Vec<Stroke>> = layers.iter().map(|l| l.motion.drawing.strokes()).collect();
    Projection::ALL
        .into_iter()
        .filter_map(|projection| {
            let canvas = Canvas::over(&layers, &strokes, projection)?;
            let [(a, sa, _), (b, sb, _)] = projection.axes();
            Some(ProjectionFrame {
                id: format!("view-{}", projection.name()),
                horizontal: (a, sa),
                vertical: (b, sb),
                origin: [canvas.x(0.0), canvas.y(0.0)],
                scale: canvas.scale,
            })
        })
        .collect()
}

/// `layers` in one projection, as an inline SVG in a figure of id `id`, the grid over all of them.
fn layers_svg(
    out: &mut String,
    layers: &[Layer],
    projection: Projection,
    id: &str,
    construction: Option<&Construction>,
) -> std::fmt::Result {
    // Each layer's strokes, made once for the extents and the drawing.
    let strokes: Vec<Vec<Stroke>> = layers.iter().map(|l| l.motion.drawing.strokes()).collect();
    let Some(canvas) = Canvas::over(layers, &strokes, projection) else { return Ok(()) };
    let (w, h) = (canvas.w, canvas.h);
    writeln!(out, "<figure class=\"view\" id=\"{}\">", attr(id))?;
    writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.1} {h:.1}" role="img" aria-label="{}">"#,
        projection.caption()
    )?;
    let step = grid_svg(out, &canvas, projection)?;
    for (layer, strokes) in layers.iter().zip(&strokes) {
        layer_svg(out, &canvas, projection, layer, strokes)?;
    }
    if let Some(c) = construction {
        construction_svg(out, &canvas, projection, c)?;
    }
    writeln!(out, "</svg>")?;
    writeln!(out, "<figcaption>{}; grid {:.0} mm</figcaption>", projection.caption(), step * 1e3)?;
    writeln!(out, "</figure>")
}

/// The colour of the instant centres' construction.
const CONSTRUCTION: &str = "#b8860b";

/// The colour of the wheel's swept envelope (drawn faint) and of the packaging it clears.
const ENVELOPE: &str = "#7f7f7f";
const PACKAGING: &str = "#d62728";

/// The construction of the instant centres `c` in `projection`, its lines dashed over the parts: in the
/// front view the line from the contact patch through the wheel's instant centre and on to the roll
/// centre; in the side view the lines from the patch and from the wheel centre to the side-view instant
/// centre. An instant centre is a ring, the roll centre a square; a centre far off the view runs its line
/// out of the picture. Nothing in the plan view.
fn construction_svg(out: &mut String, canvas: &Canvas, projection: Projection, c: &Construction) -> std::fmt::Result {
    let at = |p: [f64; 3]| {
        let (u, v) = projection.project(&Vec3::new(p[0], p[1], p[2]));
        (canvas.x(u), canvas.y(v))
    };
    let [px, py, _] = c.patch;
    let (lines, rings, squares) = match projection {
        Projection::Front => {
            let ic = c.front_view_centre.map(|[y, z]| at([px, y, z]));
            let rc = c.roll_centre.map(|[y, z]| at([px, y, z]));
            let from = at(c.patch);
            let mut lines: Vec<[(f64, f64); 2]> = ic.map(|ic| [from, ic]).into_iter().collect();
            lines.extend(rc.map(|rc| [ic.unwrap_or(from), rc]));
            (lines, ic.into_iter().collect::<Vec<_>>(), rc.into_iter().collect::<Vec<_>>())
        }
        Projection::Side => match c.side_view_centre.map(|[x, z]| at([x, py, z])) {
            Some(ic) => (vec![[at(c.patch), ic], [at(c.wheel_centre), ic]], vec![ic], Vec::new()),
            None => (Vec::new(), Vec::new(), Vec::new()),
        },
        Projection::Plan => (Vec::new(), Vec::new(), Vec::new()),
    };
    if lines.is_empty() && rings.is_empty() && squares.is_empty() {
        return Ok(());
    }
    // A viewport over the grid clips what runs off it, as the grid's own area (no reference out of the
    // element, which a clip path would need).
    let (x0, y0) = (LABEL_ROOM, EDGE_ROOM);
    let (w, h) = (canvas.w - LABEL_ROOM - EDGE_ROOM, canvas.h - LABEL_ROOM - EDGE_ROOM);
    writeln!(
        out,
        r#"<svg x="{x0:.1}" y="{y0:.1}" width="{w:.1}" height="{h:.1}" viewBox="{x0:.1} {y0:.1} {w:.1} {h:.1}" overflow="hidden">"#
    )?;
    writeln!(out, r#"<g class="construction" stroke="{CONSTRUCTION}" stroke-width="1.5" fill="none">"#)?;
    for [(x1, y1), (x2, y2)] in lines {
        writeln!(out, r#"<line x1="{x1:.1}" y1="{y1:.1}" x2="{x2:.1}" y2="{y2:.1}" stroke-dasharray="5 3"/>"#)?;
    }
    for (x, y) in rings {
        writeln!(out, r#"<circle class="instant-centre" cx="{x:.1}" cy="{y:.1}" r="5"/>"#)?;
    }
    for (x, y) in squares {
        writeln!(
            out,
            r#"<rect class="roll-centre" x="{:.1}" y="{:.1}" width="9" height="9" fill="{CONSTRUCTION}"/>"#,
            x - 4.5,
            y - 4.5
        )?;
    }
    writeln!(out, "</g>")?;
    writeln!(out, "</svg>")
}

/// Where a projection's coordinates (m) land on its SVG: the extents of every row drawn, padded, at one
/// scale, with room for the grid's labels to the left and below.
struct Canvas {
    lo: (f64, f64),
    hi: (f64, f64),
    scale: f64,
    /// The SVG's width and height (px).
    w: f64,
    h: f64,
}

impl Canvas {
    /// The canvas over the `strokes` of each of `layers` in `projection`; `None` when nothing drawn has a
    /// finite place.
    fn over(layers: &[Layer], strokes: &[Vec<Stroke>], projection: Projection) -> Option<Canvas> {
        let (mut lo, mut hi) = ((f64::INFINITY, f64::INFINITY), (f64::NEG_INFINITY, f64::NEG_INFINITY));
        let mut grow = |p: &Vec3| {
            let (u, v) = projection.project(p);
            if u.is_finite() && v.is_finite() {
                lo = (lo.0.min(u), lo.1.min(v));
                hi = (hi.0.max(u), hi.1.max(v));
            }
        };
        for (layer, strokes) in layers.iter().zip(strokes) {
            for s in strokes {
                stroke_points(s, &layer.motion.frames[layer.row]).iter().for_each(&mut grow);
            }
        }
        if !(lo.0.is_finite() && hi.0.is_finite()) {
            return None;
        }
        let (lo, hi) = ((lo.0 - PAD_M, lo.1 - PAD_M), (hi.0 + PAD_M, hi.1 + PAD_M));
        let room = LABEL_ROOM + EDGE_ROOM;
        let scale = ((VIEW_WIDTH - room) / (hi.0 - lo.0)).min((VIEW_MAX_HEIGHT - room) / (hi.1 - lo.1));
        let (w, h) = ((hi.0 - lo.0) * scale + room, (hi.1 - lo.1) * scale + room);
        Some(Canvas { lo, hi, scale, w, h })
    }

    /// The SVG's x of the horizontal coordinate `u`.
    fn x(&self, u: f64) -> f64 {
        LABEL_ROOM + (u - self.lo.0) * self.scale
    }

    /// The SVG's y of the vertical coordinate `v` (up in the model, down in the SVG).
    fn y(&self, v: f64) -> f64 {
        EDGE_ROOM + (self.hi.1 - v) * self.scale
    }

    /// The SVG path through `points` projected, closed if `closed`.
    fn path(&self, projection: Projection, points: &[Vec3], closed: bool) -> String {
        let mut d = String::new();
        for (i, p) in points.iter().enumerate() {
            let (u, v) = projection.project(p);
            let _ = write!(d, "{}{:.1} {:.1}", if i == 0 { "M" } else { " L" }, self.x(u), self.y(v));
        }
        if closed {
            d.push_str(" Z");
        }
        d
    }
}

/// The grid of `canvas`, labelled with the global coordinate in mm, and the axes' names; its step (m).
fn grid_svg(out: &mut String, canvas: &Canvas, projection: Projection) -> Result<f64, std::fmt::Error> {
    let Canvas { lo, hi, w, h, .. } = *canvas;
    let [(_, su, nu), (_, sv, nv)] = projection.axes();
    let step = grid_step((hi.0 - lo.0).max(hi.1 - lo.1));
    writeln!(out, r##"<g stroke="#e4e4e4" stroke-width="1" font-size="{GRID_FONT}" fill="#666">"##)?;
    let mut k = (lo.0 / step).ceil() as i64;
    while (k as f64) * step <= hi.0 {
        let u = k as f64 * step;
        writeln!(out, r#"<line x1="{0:.1}" y1="{EDGE_ROOM}" x2="{0:.1}" y2="{1:.1}"/>"#, canvas.x(u), h - LABEL_ROOM)?;
        writeln!(
            out,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="middle" stroke="none">{:.0}</text>"#,
            canvas.x(u),
            h - LABEL_ROOM + GRID_FONT + 3.0,
            mm(su * u)
        )?;
        k += 1;
    }
    let mut k = (lo.1 / step).ceil() as i64;
    while (k as f64) * step <= hi.1 {
        let v = k as f64 * step;
        writeln!(
            out,
            r#"<line x1="{:.1}" y1="{1:.1}" x2="{2:.1}" y2="{1:.1}"/>"#,
            LABEL_ROOM,
            canvas.y(v),
            w - EDGE_ROOM
        )?;
        writeln!(
            out,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="end" stroke="none">{:.0}</text>"#,
            LABEL_ROOM - 4.0,
            canvas.y(v) + 0.35 * GRID_FONT,
            mm(sv * v)
        )?;
        k += 1;
    }
    writeln!(
        out,
        r#"<text x="{:.1}" y="{:.1}" text-anchor="middle" stroke="none">{nu} [mm]</text>"#,
        LABEL_ROOM + (w - LABEL_ROOM - EDGE_ROOM) / 2.0,
        h - 6.0
    )?;
    writeln!(
        out,
        r#"<text x="12" y="{:.1}" text-anchor="middle" stroke="none" transform="rotate(-90 12 {0:.1})">{nv} [mm]</text>"#,
        (EDGE_ROOM + h - LABEL_ROOM) / 2.0
    )?;
    writeln!(out, "</g>")?;
    Ok(step)
}

/// One layer's `strokes` on `canvas`: ghosted faint without its deflections, else with its dots too.
fn layer_svg(
    out: &mut String,
    canvas: &Canvas,
    projection: Projection,
    layer: &Layer,
    strokes: &[Stroke],
) -> std::fmt::Result {
    let (ghost, poses) = (layer.ghost, &layer.motion.frames[layer.row]);
    let opacity = if ghost { " opacity=\"0.25\"" } else { "" };
    writeln!(out, "<g fill=\"none\" stroke-linecap=\"round\"{opacity}>")?;
    for s in strokes {
        if ghost && s.pen == Pen::Deflection {
            continue;
        }
        let points = stroke_points(s, poses);
        if points.len() < 2 || points.iter().any(|p| !p.iter().all(|c| c.is_finite())) {
            continue;
        }
        let (own, width, dash) = pen_style(s.pen);
        let colour = layer.colour.as_deref().unwrap_or(own);
        let dash = if dash.is_empty() { String::new() } else { format!(" stroke-dasharray=\"{dash}\"") };
        writeln!(
            out,
            r#"<path d="{}" stroke="{colour}" stroke-width="{width}"{dash}><title>{}</title></path>"#,
            canvas.path(projection, &points, s.closed),
            text(&s.name)
        )?;
    }
    if !ghost && layer.colour.is_none() {
        for d in &layer.motion.drawing.dots() {
            write_dot(out, d, poses, &|p| {
                let (u, v) = projection.project(p);
                (canvas.x(u), canvas.y(v))
            })?;
        }
    }
    writeln!(out, "</g>")
}

fn write_dot(out: &mut String, d: &Dot, poses: &[Pose], at: &dyn Fn(&Vec3) -> (f64, f64)) -> std::fmt::Result {
    let p = d.at.placed(poses);
    if !p.iter().all(|c| c.is_finite()) {
        return Ok(());
    }
    let (cx, cy) = at(&p);
    let (colour, r) = spot_style(d.spot);
    let title = text(&d.name);
    match d.spot {
        Spot::Mount => writeln!(
            out,
            r#"<rect x="{:.1}" y="{:.1}" width="{:.1}" height="{2:.1}" fill="{colour}" stroke="none"><title>{title}</title></rect>"#,
            cx - r,
            cy - r,
            2.0 * r
        ),
        Spot::Joint => writeln!(
            out,
            r##"<circle cx="{cx:.1}" cy="{cy:.1}" r="{r}" fill="#ffffff" stroke="{colour}" stroke-width="1.5"><title>{title}</title></circle>"##
        ),
        _ => writeln!(
            out,
            r#"<circle cx="{cx:.1}" cy="{cy:.1}" r="{r}" fill="{colour}" stroke="none"><title>{title}</title></circle>"#
        ),
    }
}

/// The legend of the views: a swatch per pen and spot, and the deflections' scale.
fn write_legend(out: &mut String, construction: bool) -> std::fmt::Result {
    writeln!(out, "<ul class=\"view-legend\">")?;
    for (pen, label) in [
        (Pen::Part, "part"),
        (Pen::Link, "link (tie rod, drop link)"),
        (Pen::Spring, "spring"),
        (Pen::Stop, "stop"),
        (Pen::Beam, "elastic beam"),
        (Pen::Bushing, "bushing axis"),
        (Pen::Deflection, "bushing deflection ×20"),
        (Pen::Wheel, "wheel (loaded radius)"),
        (Pen::SteeringAxis, "steering axis"),
    ] {
        let (colour, width, dash) = pen_style(pen);
        let dash = if dash.is_empty() { String::new() } else { format!(" stroke-dasharray=\"{dash}\"") };
        writeln!(
            out,
            r#"<li><svg xmlns="http://www.w3.org/2000/svg" width="28" height="10"><line x1="2" y1="5" x2="26" y2="5" stroke="{colour}" stroke-width="{width}"{dash}/></svg> {}</li>"#,
            text(label)
        )?;
    }
    if construction {
        writeln!(
            out,
            r#"<li><svg xmlns="http://www.w3.org/2000/svg" width="28" height="10"><line x1="2" y1="5" x2="26" y2="5" stroke="{CONSTRUCTION}" stroke-width="1.5" stroke-dasharray="5 3"/></svg> instant centres (ring) and roll centre (square) with their construction, at the row drawn</li>"#
        )?;
    }
    writeln!(out, "</ul>")
}

/// The geometry section of the report: the three projections of the analysis shown (parallel travel
/// where there is one) and the 3D view of every analysis with a motion. Nothing when no analysis has
/// one (a report run without [`Settings::motion`](crate::suspensions::kc::Settings::motion)).
pub fn write_geometry(out: &mut String, report: &KcReport) -> std::fmt::Result {
    let mut projections = String::new();
    write_projections(&mut projections, report)?;
    if projections.is_empty() {
        return Ok(());
    }
    writeln!(out, "<section id=\"geometry\">")?;
    writeln!(out, "<h2>Geometry</h2>")?;
    out.push_str(&projections);
    write_viewer(out, report)?;
    writeln!(out, "</section>")
}

/// The analysis the projections show, its motion, and the rows they draw: its design row, its first and
/// its last. `None` when no analysis has a motion with a row.
fn projected(report: &KcReport) -> Option<(&AnalysisReport, &Motion, [usize; 3])> {
    let (a, motion) = shown_analysis(report)?;
    let last = motion.frames.len().checked_sub(1)?;
    Some((a, motion, [a.design_row(), 0, last]))
}

/// The three projections of the analysis shown (parallel travel where there is one), with what is drawn
/// and ghosted said above them and their legend below: the geometry section without the 3D view, which
/// `elastokin live`'s page draws anew with every design. Nothing when no analysis has a motion.
pub fn write_projections(out: &mut String, report: &KcReport) -> std::fmt::Result {
    let Some((a, motion, rows)) = projected(report) else { return Ok(()) };
    writeln!(
        out,
        "<p class=\"note\">{}: {} drawn, {} and {} ghosted</p>",
        text(a.analysis.name()),
        text(&row_label(a, rows[0])),
        text(&row_label(a, rows[1])),
        text(&row_label(a, rows[2]))
    )?;
    writeln!(out, "<div class=\"views\">")?;
    let construction = a.construction.get(rows[0]);
    for projection in Projection::ALL {
        projection_svg(out, motion, rows, projection, construction)?;
    }
    writeln!(out, "</div>")?;
    write_legend(out, construction.is_some())
}

/// A global or body-fixed point as the 3D view reads it: `[body, x, y, z]`, body −1 for the ground.
fn anchor_json(a: &Anchor) -> Value {
    let body = match a.body {
        BodyRef::Ground => -1,
        BodyRef::Body(b) => b.0 as i64,
    };
    json!([body, round(a.point.x), round(a.point.y), round(a.point.z)])
}

/// A coordinate to the tenth of a micrometre, a quaternion component to 1e-7: what a view can show.
fn round(v: f64) -> f64 {
    if v.is_finite() {
        (v * 1e7).round() / 1e7
    } else {
        0.0
    }
}

/// The 3D view's data: each distinct drawing once (its strokes, with their pens' styles, and dots), and
/// each analysis with a motion: its name, the drawing it moves, the label and the poses of every row.
pub fn viewer_data(report: &KcReport) -> Value {
    let mut drawings: Vec<Value> = Vec::new();
    let mut analyses = Vec::new();
    for a in &report.analyses {
        let Some(motion) = &a.motion else { continue };
        let strokes: Vec<Value> = motion
            .drawing
            .strokes()
            .iter()
            .map(|s| {
                json!({ "pen": s.pen.name(), "name": s.name, "closed": s.closed,
                        "points": s.anchors.iter().map(anchor_json).collect::<Vec<_>>() })
            })
            .collect();
        let dots: Vec<Value> = motion
            .drawing
            .dots()
            .iter()
            .map(|d| json!({ "spot": d.spot.name(), "name": d.name, "at": anchor_json(&d.at) }))
            .collect();
        let drawing = json!({ "strokes": strokes, "dots": dots });
        let index = drawings.iter().position(|d| *d == drawing).unwrap_or_else(|| {
            drawings.push(drawing);
            drawings.len() - 1
        });
        let frames: Vec<Value> = motion
            .frames
            .iter()
            .map(|poses| {
                Value::Array(
                    poses
                        .iter()
                        .map(|p| {
                            let q = p.orientation.quaternion();
                            json!([
                                round(p.position.x),
                                round(p.position.y),
                                round(p.position.z),
                                round(q.w),
                                round(q.i),
                                round(q.j),
                                round(q.k)
                            ])
                        })
                        .collect(),
                )
            })
            .collect();
        let labels: Vec<String> = (0..motion.frames.len()).map(|r| row_label(a, r)).collect();
        // The instant centres' construction at every row (parallel travel's), drawn in the front and side
        // views as the projections draw it at design.
        let pair = |p: Option<[f64; 2]>| p.map(|[u, v]| json!([round(u), round(v)]));
        let construction: Vec<Value> = a
            .construction
            .iter()
            .map(|c| {
                json!({ "patch": c.patch.map(round), "wheel_centre": c.wheel_centre.map(round),
                        "front": pair(c.front_view_centre), "side": pair(c.side_view_centre),
                        "roll": pair(c.roll_centre) })
            })
            .collect();
        // The wheel's swept envelope (the wheel envelope's): the tyre at every point of the grid, drawn at
        // every row, with the body's points and boxes it clears.
        let envelope = a.envelope.as_ref().map(|e| {
            let placements: Vec<[f64; 6]> =
                e.placements.iter().map(|(c, s)| [c.x, c.y, c.z, s.x, s.y, s.z].map(round)).collect();
            let points: Vec<[f64; 3]> = e.packaging.points.iter().map(|p| p.at.map(round)).collect();
            let boxes: Vec<[[f64; 3]; 2]> =
                e.packaging.boxes.iter().map(|b| [b.min.map(round), b.max.map(round)]).collect();
            json!({ "tyre": [round(e.tyre.radius), round(e.tyre.width)], "placements": placements,
                    "points": points, "boxes": boxes })
        });
        analyses.push(json!({ "name": a.analysis.name(), "drawing": index, "design": a.design_row(),
                              "labels": labels, "frames": frames, "construction": construction,
                              "envelope": envelope }));
    }
    let pens: serde_json::Map<String, Value> = [
        Pen::Part,
        Pen::Link,
        Pen::Spring,
        Pen::Stop,
        Pen::Beam,
        Pen::Bushing,
        Pen::Deflection,
        Pen::Wheel,
        Pen::SteeringAxis,
    ]
    .into_iter()
    .map(|p| {
        let (colour, width, dash) = pen_style(p);
        let dash: Vec<f64> = dash.split(' ').filter_map(|d| d.parse().ok()).collect();
        (p.name().to_string(), json!({ "colour": colour, "width": width, "dash": dash }))
    })
    .collect();
    let spots: serde_json::Map<String, Value> = [Spot::Joint, Spot::Bushing, Spot::Mount, Spot::WheelCentre]
        .into_iter()
        .map(|s| {
            let (colour, r) = spot_style(s);
            (s.name().to_string(), json!({ "colour": colour, "radius": r }))
        })
        .collect();
    json!({ "drawings": drawings, "analyses": analyses, "pens": pens, "spots": spots, "construction": CONSTRUCTION,
            "envelope": ENVELOPE, "packaging": PACKAGING, "deflection_scale": DEFLECTION_SCALE })
}

/// The 3D view's script: it draws the data of `<script id="view3d-data">` when the page has one, and
/// `window.elastokinView3d.show(data)` draws new data in the same view (`elastokin live`'s page, at every
/// design).
pub const VIEWER_SCRIPT: &str = include_str!("view3d.js");

/// JSON put inside a script element: every `<`, `>` and `&` written as a `\u` escape, so that no text of
/// the data (a part's name) can close the element or the page's CDATA section.
fn script_safe(json: &str) -> String {
    json.replace('<', "\\u003c").replace('>', "\\u003e").replace('&', "\\u0026")
}

/// The 3D view: its canvas and controls, its data, and its script.
fn write_viewer(out: &mut String, report: &KcReport) -> std::fmt::Result {
    let data = viewer_data(report);
    write_viewer_figure(
        out,
        "3D view: drag to turn, wheel to zoom; the slider moves the parts through the analysis as solved \
         (scripts off, the projections above still show the geometry)",
    )?;
    writeln!(out, "<script type=\"application/json\" id=\"view3d-data\">{}</script>", script_safe(&data.to_string()))?;
    writeln!(out, "<script>//<![CDATA[\n{VIEWER_SCRIPT}\n//]]></script>")
}

/// The 3D view's figure, its data and script aside: its controls, its canvas, `caption`, and the
/// `<output id="view3d-state">` its script reports what it drew in.
pub fn write_viewer_figure(out: &mut String, caption: &str) -> std::fmt::Result {
    writeln!(out, "<figure class=\"view3d\" id=\"view-3d\">")?;
    writeln!(out, "<div class=\"view3d-controls\">")?;
    writeln!(out, "<label>analysis <select id=\"view3d-analysis\"></select></label>")?;
    writeln!(out, "<button type=\"button\" id=\"view3d-play\">play</button>")?;
    writeln!(out, "<input type=\"range\" id=\"view3d-row\" min=\"0\" max=\"0\" value=\"0\"/>")?;
    writeln!(out, "<output id=\"view3d-label\"></output>")?;
    for (view, label) in [("3d", "3D"), ("front", "front"), ("side", "side"), ("plan", "plan")] {
        writeln!(out, "<button type=\"button\" data-view=\"{view}\">{label}</button>")?;
    }
    writeln!(out, "</div>")?;
    writeln!(out, "<canvas id=\"view3d-canvas\" width=\"900\" height=\"560\"></canvas>")?;
    writeln!(out, "<figcaption>{}</figcaption>", text(caption))?;
    writeln!(out, "<output id=\"view3d-state\" hidden=\"hidden\"></output>")?;
    writeln!(out, "</figure>")
}

/// The geometry of designs compared, overlaid in each projection: each model at its design row, in its
/// colour (its curves' colour in the charts), with a legend of names. Nothing when no model has a motion.
pub fn write_overlay(out: &mut String, models: &[(&str, &KcReport)]) -> std::fmt::Result {
    let shown: Vec<(usize, &str, &AnalysisReport, &Motion)> = models
        .iter()
        .enumerate()
        .filter_map(|(k, (name, report))| {
            let (a, m) = shown_analysis(report)?;
            (!m.frames.is_empty()).then_some((k, *name, a, m))
        })
        .collect();
    if shown.is_empty() {
        return Ok(());
    }
    writeln!(out, "<section id=\"geometry\">")?;
    writeln!(out, "<h2>Geometry</h2>")?;
    writeln!(out, "<p class=\"note\">each design at its design position ({})</p>", text(shown[0].2.analysis.name()))?;
    writeln!(out, "<div class=\"views\">")?;
    let layers: Vec<Layer> = shown
        .iter()
        .map(|&(k, _, a, motion)| Layer {
            motion,
            row: a.design_row(),
            ghost: false,
            colour: Some(crate::plot::series_colour_hex(k)),
        })
        .collect();
    for projection in Projection::ALL {
        layers_svg(out, &layers, projection, &format!("overlay-{}", projection.name()), None)?;
    }
    writeln!(out, "</div>")?;
    writeln!(out, "<ul class=\"view-legend\">")?;
    for &(k, name, _, _) in &shown {
        writeln!(
            out,
            r#"<li><svg xmlns="http://www.w3.org/2000/svg" width="28" height="10"><line x1="2" y1="5" x2="26" y2="5" stroke="{}" stroke-width="3"/></svg> {}</li>"#,
            crate::plot::series_colour_hex(k),
            text(&crate::plot::shown(name, 120))
        )?;
    }
    writeln!(out, "</ul>")?;
    writeln!(out, "</section>")
}
