//! The wheel's swept envelope: the tyre over wheel travel × rack travel on the full axle, and its least
//! clearance to each point and box of the body the model file names (`packaging`).
//!
//! Each row is a wheel height: the axle on the steering rig with both wheel-centre heights held there
//! ([`Model::hold_driver`](elastokin_core::Model::hold_driver)) and the rack swept over its travel
//! (`packaging.rack_travel`, else the steering analysis's range); a corner without steering is walked over
//! its travel alone. A row holds, for each obstacle, the least clearance of either tyre over the rack's
//! sweep there (the right wheel's to the obstacle's mirror image) and the rack travel where it is least.
//! The tyre is a solid cylinder about the spin axis ([`Tyre`]); a clearance is its signed distance from
//! the obstacle, negative the depth it reaches in.
//!
//! The least clearance is a grid's: between the grid's points the tyre may come closer. Its estimate is
//! twice the dip below the least grid value of the parabola through it and its neighbours, in travel and
//! in rack travel (the amount a smooth clearance falls between samples); at the grid's edge, where the
//! least clearance of a tyre moving towards an obstacle usually is, the grid is exact and the parabola's
//! vertex lies outside.

use crate::analysis::{axle_sweep_with, AxleRow, SweepOutput};
use crate::assembly::{Axle, AxleRig};
use crate::description::{Obstacle, Packaging, PackagingBox, Side, Tyre};
use crate::kc::figures;
use crate::kc::models::Models;
use crate::kc::reduce::{axle_drawing, chart, finish, Design, Reduction};
use crate::kc::report::slug;
use crate::kc::report::{AnalysisReport, Cell, Column, Envelope, Figure, Table, Warning};
use crate::kc::settings::{Analysis, Cause, Declaration, DefaultRange, FigureRows, Quantity, Settings};
use crate::kc::steering;
use crate::kc::{Series, YAxis};
use crate::wheel::WheelAttitude;
use elastokin_core::{JointId, Vec3};
use elastokin_solver::replay::Taping;
use parry3d_f64::math::{Pose, Rotation, Vector};
use parry3d_f64::shape::{Cuboid, Cylinder};
use rayon::prelude::*;

/// The wheel's envelope, as the command and the reports name it.
pub(super) const DECLARATION: Declaration = Declaration {
    name: "wheel-envelope",
    parameter: "wheel travel, m, bump +",
    quantity: Quantity::Travel,
    rig_words: Some("full axle, the rack swept at each wheel height"),
    default_range: DefaultRange::Ends(-0.08, 0.08),
    design_parameter: Some(0.0),
    figure_rows: FigureRows::Extremes,
};

/// The steps of the grid in wheel travel and in rack travel alike, for the analyses' `steps`: a quarter of
/// them, and at least eight. Each point of the grid is an equilibrium of its own rig, and the clearance is
/// smooth in both: a grid as fine as the other analyses' rows would cost a suite many times over and
/// change the least clearance by less than its estimate.
pub fn grid_steps(steps: usize) -> usize {
    (steps / 4).max(8)
}

/// The error allowed the depth of a tyre's overlap with a box (m): EPA's, which stops on a curved shape
/// within a tolerance of its own (the distance apart is exact, [`distance_apart`]).
const OVERLAP_TOLERANCE: f64 = 1e-8;

/// Clearances closer than this are one (m): far below what the solve and the distance query resolve.
const TIE: f64 = 1e-9;

/// How far the distance query looks (m): beyond any packaging's reach, so that every distance is found.
const FARTHEST: f64 = 1e3;

/// The tyre's signed clearance to `obstacle` with the wheel at `attitude` on `side` (m; negative, the depth
/// the tyre reaches into it): a right wheel's obstacle is the left's mirrored (y → −y). `None` where the
/// distance query cannot measure it.
pub fn clearance(tyre: &Tyre, attitude: &WheelAttitude, side: Side, obstacle: Obstacle) -> Option<f64> {
    let axis = side.spin_axis(attitude.toe, attitude.camber);
    let centre = attitude.wheel_centre;
    let place = |p: [f64; 3]| side.place(Vec3::new(p[0], p[1], p[2]));
    match obstacle {
        Obstacle::Point(p) => Some(point_clearance(tyre, centre, axis, place(p.at))),
        Obstacle::Box(b) => box_clearance(tyre, centre, axis, mirrored_box(b, side)),
    }
}

/// A box's lowest and highest corners on `side` (the right's is the left's mirrored).
fn mirrored_box(b: &PackagingBox, side: Side) -> (Vec3, Vec3) {
    let (a, c) = (Vec3::from(b.min), Vec3::from(b.max));
    match side {
        Side::Left => (a, c),
        Side::Right => (Vec3::new(a.x, -c.y, a.z), Vec3::new(c.x, -a.y, c.z)),
    }
}

/// The signed distance from the tyre (centre, unit spin `axis`) to point `p`: in the axis's frame, `q` is
/// how far beyond the tread and beyond the sidewall it lies; outside, the length of the positive parts;
/// inside, the nearer face's (negative).
fn point_clearance(tyre: &Tyre, centre: Vec3, axis: Vec3, p: Vec3) -> f64 {
    let d = p - centre;
    let along = d.dot(&axis);
    let radial = (d - axis * along).norm();
    let q = (radial - tyre.radius, along.abs() - 0.5 * tyre.width);
    q.0.max(q.1).min(0.0) + q.0.max(0.0).hypot(q.1.max(0.0))
}

/// The signed distance from the tyre to the box between `corners`: the convex shapes' distance apart, or
/// minus the depth of their overlap. The convex shapes' query (GJK and EPA) tells which; apart, whose GJK
/// stops within about 1e-7 of the distance, the distance is then found exactly ([`distance_apart`]), so
/// that it is as smooth in the wheel's pose as the pose is (its derivatives are differences of it).
fn box_clearance(tyre: &Tyre, centre: Vec3, axis: Vec3, corners: (Vec3, Vec3)) -> Option<f64> {
    let v = |p: Vec3| Vector::new(p.x, p.y, p.z);
    let cylinder = Cylinder::new(0.5 * tyre.width, tyre.radius);
    let tyre_pose = Pose::from_parts(v(centre), Rotation::from_rotation_arc(Vector::Y, v(axis)));
    let (lo, hi) = corners;
    let cuboid = Cuboid::new(v((hi - lo) * 0.5));
    let box_pose = Pose::from_translation(v((hi + lo) * 0.5));
    Some(match parry3d_f64::query::contact(&tyre_pose, &cylinder, &box_pose, &cuboid, FARTHEST) {
        Ok(Some(contact)) if contact.dist > 0.0 => distance_apart(tyre, centre, axis, corners),
        Ok(Some(contact)) => contact.dist,
        // Farther than any packaging reaches: at least as far as it looks.
        Ok(None) => FARTHEST,
        // The query measures every pair of convex shapes it is built with, a cylinder and a cuboid among them.
        Err(_) => return None,
    })
}

/// The distance between the tyre and a box apart from it, exactly: the least over the box's surface of a
/// point's distance to the tyre ([`point_clearance`]). Over a face, where the least lies inside it, it is the
/// face plane's distance to the tyre's point farthest towards it (its support point); else it lies on an
/// edge, along which the distance is convex and its least is found by golden sections to rounding.
fn distance_apart(tyre: &Tyre, centre: Vec3, axis: Vec3, (lo, hi): (Vec3, Vec3)) -> f64 {
    let to_point = |p: Vec3| point_clearance(tyre, centre, axis, p);
    let mut least = f64::INFINITY;
    for k in 0..3 {
        for (side, sign) in [(lo, -1.0), (hi, 1.0)] {
            // The face at `side[k]`, its outward normal `sign` along axis k; the tyre's point farthest
            // towards it, against the normal.
            let mut normal = Vec3::zeros();
            normal[k] = sign;
            let across = -normal - axis * (-normal).dot(&axis);
            let radial = if across.norm() > 1e-12 { across.normalize() * tyre.radius } else { Vec3::zeros() };
            let support = centre + axis * (0.5 * tyre.width * (-normal).dot(&axis).signum()) + radial;
            let inside = (0..3).filter(|&j| j != k).all(|j| (lo[j]..=hi[j]).contains(&support[j]));
            let apart = sign * (support[k] - side[k]);
            if inside && apart > 0.0 {
                least = least.min(apart);
            }
        }
    }
    let corner = |m: usize| Vec3::new([lo.x, hi.x][m & 1], [lo.y, hi.y][(m >> 1) & 1], [lo.z, hi.z][(m >> 2) & 1]);
    // The tyre lies within the sphere about its centre through its tread's edges: no point of an edge is
    // nearer the tyre than the edge's distance from the centre less that sphere's radius. The edges are
    // searched nearest bound first, and an edge whose bound is no nearer than the least found is not.
    let sphere = tyre.radius.hypot(0.5 * tyre.width);
    let mut edges: Vec<(f64, Vec3, Vec3)> = (0..8)
        .flat_map(|m| [1, 2, 4].into_iter().filter(move |&bit| m & bit == 0).map(move |bit| (m, m | bit)))
        .map(|(i, j)| {
            let (a, b) = (corner(i), corner(j));
            let length2 = (b - a).norm_squared();
            let t = if length2 > 0.0 { ((centre - a).dot(&(b - a)) / length2).clamp(0.0, 1.0) } else { 0.0 };
            ((a + (b - a) * t - centre).norm() - sphere, a, b)
        })
        .collect();
    edges.sort_by(|x, y| x.0.total_cmp(&y.0));
    for (bound, a, b) in edges {
        if bound >= least {
            break;
        }
        least = least.min(least_along(|t| to_point(a + (b - a) * t)));
    }
    least
}

/// The least of a convex `f` over [0, 1], by golden sections down to rounding.
fn least_along(f: impl Fn(f64) -> f64) -> f64 {
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (0.0, 1.0);
    let (mut c, mut d) = (b - ratio * (b - a), a + ratio * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    while b - a > 1e-12 {
        if fc < fd {
            (b, d, fd) = (d, c, fc);
            c = b - ratio * (b - a);
            fc = f(c);
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + ratio * (b - a);
            fd = f(d);
        }
    }
    [f(0.0), f(1.0), fc, fd].into_iter().fold(f64::INFINITY, f64::min)
}

/// One wheel height of the envelope, read off the rack's sweep there.
#[derive(Debug, Clone)]
struct Height {
    /// The wheel travel (m, bump +).
    travel: f64,
    /// Per obstacle, in the packaging's order: where over the rack's sweep either tyre comes closest.
    least: Vec<Least>,
    /// The left wheel at each rack position of the sweep.
    left: Vec<WheelAttitude>,
}

/// Where over a rack sweep the tyre comes closest to an obstacle.
#[derive(Debug, Clone, Copy)]
struct Least {
    /// The clearance (m).
    clearance: f64,
    /// The rack travel there (m).
    rack: f64,
    /// Its place in the rack's sweep.
    at: usize,
    /// How far a parabola through it and its neighbours in rack travel falls below it (m), the rack grid's
    /// share of the estimate.
    dip: f64,
}

/// How far the parabola through `values` at `k − 1, k, k + 1` (or the three nearest `k` at an end) falls
/// below `values[k]` between its samples: where it opens upwards and its vertex lies within one step of
/// `k` and within the samples, the drop to the vertex; else none.
fn dip(values: &[f64], k: usize) -> f64 {
    if values.len() < 3 {
        return 0.0;
    }
    let mid = k.clamp(1, values.len() - 2);
    let (a, b, c) = (values[mid - 1], values[mid], values[mid + 1]);
    let curvature = a - 2.0 * b + c;
    if curvature.is_nan() || curvature <= 0.0 {
        return 0.0;
    }
    // The vertex, in steps from `mid`.
    let s = 0.5 * (a - c) / curvature;
    let from_k = s + mid as f64 - k as f64;
    if from_k.abs() > 1.0 || (mid as f64 + s) < 0.0 || (mid as f64 + s) > (values.len() - 1) as f64 {
        return 0.0;
    }
    let vertex = b - 0.25 * (a - c) * s;
    (values[k] - vertex).max(0.0)
}

/// The height `travel` read off the rows of the rack's sweep there: per obstacle, where either tyre comes
/// closest; or why a clearance could not be measured.
fn height(tyre: &Tyre, obstacles: &[Obstacle], travel: f64, rows: &[AxleRow]) -> Result<Height, Cause> {
    let least = obstacles
        .iter()
        .map(|&o| {
            let per_rack: Option<Vec<f64>> = rows
                .iter()
                .map(|r| Some(clearance(tyre, &r.left, Side::Left, o)?.min(clearance(tyre, &r.right, Side::Right, o)?)))
                .collect();
            let per_rack = per_rack.ok_or_else(|| {
                Cause::Lacks(format!(
                    "the tyre's distance to packaging '{}' could not be measured: give it as a box with a size in \
                     every direction",
                    o.name()
                ))
            })?;
            // The first rack position within a rounding of the least: a symmetric axle's mirror positions tie,
            // and the pick must not flip between readings of one height.
            let least = per_rack.iter().copied().fold(f64::INFINITY, f64::min);
            let k = per_rack.iter().position(|&c| c <= least + TIE).unwrap_or(0);
            Ok(Least { clearance: per_rack[k], rack: rows[k].travel, at: k, dip: dip(&per_rack, k) })
        })
        .collect::<Result<_, Cause>>()?;
    Ok(Height { travel, least, left: rows.iter().map(|r| r.left).collect() })
}

/// The envelope's table: per height, each obstacle's least clearance and the rack travel where, and the
/// least of all.
fn envelope_table(names: &[String], rows: &[Height]) -> Table {
    let mut columns: Vec<Column<Height>> = vec![
        Column::new("travel_m", |h: &Height| h.travel.into()),
        Column::new("least_clearance_m", |h: &Height| Cell::from(least_of(h).map(|(l, _)| l.clearance))),
    ];
    for (k, name) in names.iter().enumerate() {
        let column = format!("clearance_{}", slug(name));
        columns.push(Column::new(format!("{column}_m"), move |h: &Height| h.least[k].clearance.into()));
        columns.push(Column::new(format!("{column}_rack_travel_m"), move |h: &Height| h.least[k].rack.into()));
    }
    Table::of_columns("wheel_envelope", &columns, rows)
}

/// The obstacle a height's tyre comes closest to, with its index.
fn least_of(h: &Height) -> Option<(Least, usize)> {
    h.least.iter().enumerate().map(|(k, l)| (*l, k)).min_by(|a, b| a.0.clearance.total_cmp(&b.0.clearance))
}

/// The least clearance over every height and obstacle, with its estimate of what the grid leaves out, and
/// where: `(clearance, estimate, obstacle, height's row)`.
fn least_clearance(rows: &[Height]) -> Option<(f64, f64, usize, usize)> {
    let (row, (least, obstacle)) = rows
        .iter()
        .enumerate()
        .filter_map(|(i, h)| Some((i, least_of(h)?)))
        .min_by(|a, b| a.1 .0.clearance.total_cmp(&b.1 .0.clearance))?;
    let over_travel: Vec<f64> = rows.iter().map(|h| h.least[obstacle].clearance).collect();
    let estimate = 2.0 * (dip(&over_travel, row) + least.dip);
    Some((least.clearance, estimate, obstacle, row))
}

/// The envelope's figure: the least clearance, with its estimate.
fn envelope_figures(rows: &[Height], obstacles: usize) -> Vec<Figure> {
    let why = if obstacles == 0 { "the packaging names no point or box to clear" } else { "no height was solved" };
    let least = least_clearance(rows);
    let mut f = Figure::of(&figures::LEAST_WHEEL_CLEARANCE, least.map(|l| l.0), why);
    f.error = least.map(|l| l.1 + if l.0 < 0.0 { OVERLAP_TOLERANCE } else { 0.0 });
    vec![f]
}

/// The drivers of both wheel-centre heights of the axle on the steering rig, which each height holds.
fn height_drivers(axle: &Axle) -> Vec<JointId> {
    ["left ", "right "]
        .iter()
        .filter_map(|side| axle.model.joint_id(&format!("{side}{}", crate::assembly::rig::WHEEL_TRAVEL)))
        .collect()
}

pub(super) fn wheel_envelope(models: &Models, s: &Settings, taping: &Taping) -> Result<AnalysisReport, Cause> {
    let file = models.file();
    let packaging = file.packaging.as_ref().ok_or_else(|| {
        Cause::Lacks(
            "the model file has no \"packaging\" section: give the tyre's size and the points and boxes of the body \
             the wheel must clear (docs/model-file.md)"
                .into(),
        )
    })?;
    let range = Analysis::WheelEnvelope.range_or_default(s.range)?;
    let obstacles: Vec<Obstacle> = packaging.obstacles().collect();
    let names: Vec<String> = obstacles.iter().map(|o| o.name().to_string()).collect();
    let steered = file.suspension.expand().is_steered();
    let extras = || s.extras(range, taping);
    let n = grid_steps(s.steps);
    let (out, rack_range, drawing_axle) = if steered {
        let rack = rack_range(packaging);
        let axle = models.axle_ref(AxleRig::Steering)?;
        let drivers = height_drivers(axle);
        let travels: Vec<f64> = (0..=n).map(|i| range.0 + (range.1 - range.0) * i as f64 / n as f64).collect();
        // Each height is swept on its own, on a copy of the axle (`held`) per thread whose heights are held
        // anew at each travel (a hold is from design, not cumulative): the heights run at once on rayon's
        // threads unless a taping records or replays them, which takes its solves in order.
        let at_height = |held: &mut Axle, travel: f64| -> Result<(f64, SweepOutput<AxleRow>), Cause> {
            for &d in &drivers {
                held.model.hold_driver(d, travel)?;
            }
            Ok((travel, axle_sweep_with(held, rack.0, rack.1, n, s.mode, extras())?))
        };
        let heights: Vec<Result<_, Cause>> = if taping.takes_part() {
            let mut held = axle.clone();
            travels.iter().map(|&t| at_height(&mut held, t)).collect()
        } else {
            travels.par_iter().map_init(|| axle.clone(), |held, &t| at_height(held, t)).collect()
        };
        let mut out = SweepOutput {
            rows: Vec::new(),
            limit: None,
            corrected: s.error_estimate.then(Vec::new),
            residuals: Vec::new(),
            compliance: None,
            poses: s.motion.then(Vec::new),
            design: None,
            design_corrected: None,
        };
        for height_swept in heights {
            let (travel, swept) = height_swept?;
            if let Some(limit) = swept.limit {
                return Err(Cause::Lacks(format!(
                    "at a wheel travel of {:+.1} mm the rack cannot travel beyond {:+.1} mm: the linkage reaches \
                     the end of its travel there; give packaging.rack_travel within it, or a narrower range",
                    travel * 1e3,
                    limit.at * 1e3
                )));
            }
            out.rows.push(height(&packaging.tyre, &obstacles, travel, &swept.rows)?);
            if let (Some(all), Some(corrected)) = (out.corrected.as_mut(), swept.corrected.as_ref()) {
                all.push(height(&packaging.tyre, &obstacles, travel, corrected)?);
            }
            out.residuals.extend(swept.residuals);
            if let (Some(all), Some(poses)) = (out.poses.as_mut(), swept.poses) {
                // The height's frame: the rack where the tyre comes closest to anything.
                let k = least_of(out.rows.last().expect("just pushed")).map_or(swept.rows.len() / 2, |(l, _)| l.at);
                all.push(poses[k].clone());
            }
        }
        (out, Some(rack), axle)
    } else {
        let axle = models.axle_ref(AxleRig::ParallelTravel)?;
        let swept = axle_sweep_with(axle, range.0, range.1, n, s.mode, extras())?;
        let each = |rows: &[AxleRow]| -> Result<Vec<Height>, Cause> {
            rows.iter().map(|r| height(&packaging.tyre, &obstacles, r.travel, std::slice::from_ref(r))).collect()
        };
        let out = SweepOutput {
            rows: each(&swept.rows)?,
            limit: swept.limit,
            corrected: swept.corrected.as_deref().map(each).transpose()?,
            residuals: swept.residuals,
            compliance: None,
            poses: swept.poses,
            design: None,
            design_corrected: None,
        };
        (out, None, axle)
    };
    let table = |rows: &[Height]| envelope_table(&names, rows);
    let count = obstacles.len();
    let figures = move |rows: &[Height], _: Design<Height>| envelope_figures(rows, count);
    let x = |h: &Height| h.travel * 1e3;
    let series = names
        .iter()
        .enumerate()
        .map(|(k, name)| Series {
            name: name.clone(),
            points: out.rows.iter().map(|h| (x(h), h.least[k].clearance * 1e3)).collect(),
        })
        .collect();
    let charts = vec![chart(
        file,
        "wheel_envelope_clearance",
        "the tyre's least clearance at each wheel height, over the rack's travel",
        "wheel travel [mm], bump +",
        YAxis { label: "least clearance [mm]".into(), scale: crate::kc::Scale::Linear, series },
        None,
        Some(0.0),
    )];
    let description = match rack_range {
        Some(r) => format!(
            "wheel envelope (travel {:+.0}..{:+.0} mm, {} steps; rack {:+.0}..{:+.0} mm at each height, {} steps)",
            range.0 * 1e3,
            range.1 * 1e3,
            n,
            r.0 * 1e3,
            r.1 * 1e3,
            n
        ),
        None => {
            format!("wheel envelope (travel {:+.0}..{:+.0} mm, {} steps; no steering)", range.0 * 1e3, range.1 * 1e3, n)
        }
    };
    let reduce = Reduction { table: &table, figures: &figures, drawing: axle_drawing(drawing_axle, s) };
    let mut report = finish(Analysis::WheelEnvelope, description, range, s, &out, reduce, charts);
    report.steps = n;
    if let Some((least, _, obstacle, row)) = least_clearance(&out.rows).filter(|l| l.0 < 0.0) {
        let h = &out.rows[row];
        let rack = match rack_range {
            Some(_) => format!(", rack {:+.1} mm", h.least[obstacle].rack * 1e3),
            None => String::new(),
        };
        report.warnings.push(Warning {
            code: "wheel-interference",
            hardpoints: Vec::new(),
            message: format!(
                "wheel-envelope: the tyre reaches {:.1} mm into '{}' at a wheel travel of {:+.1} mm{rack}: move it \
                 or the wheel, or limit the travel or the rack",
                -least * 1e3,
                names[obstacle],
                h.travel * 1e3
            ),
        });
    }
    report.envelope = Some(Envelope {
        tyre: packaging.tyre,
        placements: out
            .rows
            .iter()
            .flat_map(|h| h.left.iter().map(|w| (w.wheel_centre, Side::Left.spin_axis(w.toe, w.camber))))
            .collect(),
        packaging: packaging.clone(),
    });
    Ok(report)
}

/// The rack travel the envelope sweeps at each height: the packaging's, else the steering analysis's.
fn rack_range(packaging: &Packaging) -> (f64, f64) {
    packaging.rack_travel.map_or(steering::RACK_TRAVEL, |[from, to]| (from, to))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plate_above_a_tilted_tyre_clears_its_highest_point() {
        // The highest point of a cylinder whose unit axis has vertical part a_z lies r·√(1 − a_z²) + w/2·|a_z|
        // above its centre: a wide plate's clearance is its underside's height less that.
        let tyre = Tyre { radius: 0.3, width: 0.2 };
        let axis = Vec3::new(0.1, 1.0, -0.05).normalize();
        let centre = Vec3::new(0.0, 0.77, 0.0);
        let top = tyre.radius * (1.0 - axis.z * axis.z).sqrt() + 0.5 * tyre.width * axis.z.abs();
        for underside in [0.5, 0.31, 0.29] {
            let corners = (Vec3::new(-1.0, -0.2, underside), Vec3::new(1.0, 1.8, underside + 0.02));
            let c = box_clearance(&tyre, centre, axis, corners).expect("a cylinder and a box are measured");
            assert!((c - (underside - top)).abs() < 1e-9, "{underside}: {c} against {}", underside - top);
        }
    }
}
