//! Project Chrono's solid axles (`SolidAxle`, `SolidThreeLinkAxle`, `SolidBellcrankThreeLinkAxle`; files
//! copied unchanged into `tests/data/chrono/`, BSD-3-Clause) read into the general model with an `axle`:
//! each wheel follows, in parallel and opposite travel, the closure equations of Chrono's own linkage written
//! out here from the Chrono file (not from the import); a symmetric axle is its own mirror image; the loads
//! of a corner analysis act on both wheels alike.

mod common;

use common::chrono::{
    against, assert_roll_locked, axle_rows, corner_rows, mirror, point, read, toe_camber, wheels_on_tube, Travel, Tube,
    V,
};
use common::newton_fd;
use elastokin_solver::Mode;
use elastokin_suspensions::analysis::axle_sweep;
use elastokin_suspensions::analysis::{parallel_wheel_travel, vertical_force_sweep};
use elastokin_suspensions::{Axle, AxleRig, Rig, Side};
use nalgebra::{DVector, Rotation3, Unit};
use serde_json::Value;

/// The tube of a three-link axle: the triangular link turns about y at the midpoint of its chassis points
/// (its apex, the midpoint of its axle points, stays in the plane across y at its distance from that axis);
/// each longitudinal link keeps its length.
#[derive(Clone, Copy)]
struct ThreeLinks {
    tube: Tube,
    pivot: V,
    apex: V,
    link: (V, V),
}

impl ThreeLinks {
    fn of(chrono: &Value) -> ThreeLinks {
        let centred = |p: V| (p + mirror(p)) / 2.0;
        ThreeLinks {
            tube: Tube { centre: point(chrono, "Axle Tube/COM") },
            pivot: centred(point(chrono, "Triangular Link/Location Chassis")),
            apex: centred(point(chrono, "Triangular Link/Location Axle")),
            link: (
                point(chrono, "Longitudinal Link/Location Chassis"),
                point(chrono, "Longitudinal Link/Location Axle"),
            ),
        }
    }

    /// The four residuals of the tube's pose `x[0..6]`: the triangle's two, each link's length change.
    fn residuals(&self, x: &[f64]) -> Vec<f64> {
        let arm = |a: V| (a.x - self.pivot.x).hypot(a.z - self.pivot.z);
        let a = self.tube.moved(x, self.apex);
        let mut f = vec![a.y - self.apex.y, arm(a) - arm(self.apex)];
        let (c, p) = self.link;
        for (c, p) in [(c, p), (mirror(c), mirror(p))] {
            f.push((self.tube.moved(x, p) - c).norm() - (p - c).norm());
        }
        f
    }
}

/// `ChSolidThreeLinkAxle`: the three-link tube ([`ThreeLinks`]); the wheels turn with the tube. Unknowns:
/// the tube's six.
fn three_link_closure(chrono: &Value, travel: Travel) -> impl Fn(f64, &mut [f64; 6]) -> [(f64, f64); 2] {
    let links = ThreeLinks::of(chrono);
    let tube = links.tube;
    let wc = point(chrono, "Spindle/COM");
    assert!(chrono.get("Camber Angle (deg)").is_none() && chrono.get("Toe Angle (deg)").is_none());
    wheels_on_tube(tube, wc, travel, move |x| links.residuals(x))
}

/// `ChSolidBellcrankThreeLinkAxle`: the three-link tube; the bell crank turns by φ about the tube's z at its
/// pivot, each knuckle by ψ about its kingpin (lower to upper point) on the tube; the drag link from the
/// steering box (held, or moved along the drag link when steering) to the crank and each tie rod from the crank to its knuckle keep their lengths.
/// Unknowns: the tube's six, φ, ψ left, ψ right.
fn bellcrank_closure(chrono: &Value, travel: Travel) -> impl Fn(f64, &mut [f64; 9]) -> [(f64, f64); 2] {
    let links = ThreeLinks::of(chrono);
    let tube = links.tube;
    let wc = point(chrono, "Spindle/COM");
    let (kl, ku) = (point(chrono, "Knuckle/Location Lower"), point(chrono, "Knuckle/Location Upper"));
    let knuckle_rod = point(chrono, "Knuckle/Location Tierod");
    let crank_pivot = point(chrono, "Bellcrank/Location Axle");
    let crank_rod = point(chrono, "Bellcrank/Location Tierod");
    let (box_end, crank_drag) =
        (point(chrono, "Draglink/Location Steering"), point(chrono, "Draglink/Location Bellcrank"));
    // A knuckle point (left, or mirrored for the right) turned by ψ about its kingpin, on the tube.
    let knuckle = move |x: &[f64], side: f64, psi: f64, p: V| {
        let m = |q: V| if side > 0.0 { q } else { mirror(q) };
        let (lower, upper) = (m(kl), m(ku));
        let turned = lower + Rotation3::from_axis_angle(&Unit::new_normalize(upper - lower), psi) * (m(p) - lower);
        tube.moved(x, turned)
    };
    let crank = move |x: &[f64], p: V| {
        tube.moved(x, crank_pivot + Rotation3::from_axis_angle(&V::z_axis(), x[6]) * (p - crank_pivot))
    };
    move |t, x| {
        let residual = |x: &[f64; 9]| {
            let mut f = links.residuals(x);
            let (left, right, rack) = travel.at(t);
            f.push(knuckle(x, 1.0, x[7], wc).z - wc.z - left);
            f.push(knuckle(x, -1.0, x[8], wc).z - wc.z - right);
            let box_now = box_end + (crank_drag - box_end).normalize() * rack;
            f.push((crank(x, crank_drag) - box_now).norm() - (crank_drag - box_end).norm());
            for (side, psi) in [(1.0, x[7]), (-1.0, x[8])] {
                let c = if side > 0.0 { crank_rod } else { mirror(crank_rod) };
                let k = if side > 0.0 { knuckle_rod } else { mirror(knuckle_rod) };
                f.push((crank(x, c) - knuckle(x, side, psi, knuckle_rod)).norm() - (c - k).norm());
            }
            DVector::from_vec(f)
        };
        newton_fd(residual, x);
        // Each wheel's outward spin axis (the left's design axis, or its mirror image) turned with its knuckle.
        let spin = |side: f64, psi: f64| knuckle(x, side, psi, wc + V::y()) - knuckle(x, side, psi, wc);
        [toe_camber(spin(1.0, x[7]), 1.0), toe_camber(spin(-1.0, x[8]), -1.0)]
    }
}

/// `ChSolidAxle`: four links from the chassis to the tube and, when the file has one, the Panhard rod
/// (`Trackbar`, its two points as given); each knuckle turns by ψ about its kingpin on the tube; the tie rod
/// is a body (translation and rotation vector about its design centre) on a ball joint to the left knuckle
/// and a universal joint to the right one, whose cross keeps the rod's x axis square to the knuckle's z
/// axis; the bell crank turns by φ about the tube's z at `Bell Crank / Location Axle`, its tie-rod point
/// staying on the rod's plane normal to its y axis; the drag link from the steering box (held) to the crank
/// keeps its length. Unknowns: the tube's six, ψ left, ψ right, φ, the rod's six. With the Panhard rod the
/// axle has one way to move and only the left wheel's height is driven.
fn solid_axle_closure(chrono: &Value) -> impl Fn(f64, &mut [f64; 15]) -> [(f64, f64); 2] {
    let tube = Tube { centre: point(chrono, "Axle Tube/COM") };
    let links: Vec<(V, V)> = ["Upper Link", "Lower Link"]
        .iter()
        .flat_map(|k| {
            let (c, a) =
                (point(chrono, &format!("{k}/Location Chassis")), point(chrono, &format!("{k}/Location Axle")));
            [(c, a), (mirror(c), mirror(a))]
        })
        .collect();
    let trackbar = chrono
        .get("Trackbar")
        .map(|_| (point(chrono, "Trackbar/Location Chassis"), point(chrono, "Trackbar/Location Axle")));
    let wc = point(chrono, "Spindle/COM");
    let (kl, ku) = (point(chrono, "Knuckle/Location Lower"), point(chrono, "Knuckle/Location Upper"));
    let knuckle_rod = point(chrono, "Tierod/Location Knuckle");
    let crank_pivot = point(chrono, "Bell Crank/Location Axle");
    let crank_rod = point(chrono, "Bell Crank/Location Tierod");
    let (box_end, crank_drag) =
        (point(chrono, "Draglink/Location Chassis"), point(chrono, "Draglink/Location Bell Crank"));
    let rod_centre = (knuckle_rod + mirror(knuckle_rod)) / 2.0;
    let kingpin = move |side: f64, psi: f64| {
        let m = |q: V| if side > 0.0 { q } else { mirror(q) };
        (m(kl), Rotation3::from_axis_angle(&Unit::new_normalize(m(ku) - m(kl)), psi))
    };
    // A knuckle point (left, or mirrored for the right) turned by ψ about its kingpin, on the tube.
    let knuckle = move |x: &[f64], side: f64, psi: f64, p: V| {
        let (lower, turn) = kingpin(side, psi);
        tube.moved(x, lower + turn * (if side > 0.0 { p } else { mirror(p) } - lower))
    };
    let crank = move |x: &[f64], p: V| {
        tube.moved(x, crank_pivot + Rotation3::from_axis_angle(&V::z_axis(), x[8]) * (p - crank_pivot))
    };
    let rod_turn = |x: &[f64]| Rotation3::new(V::new(x[12], x[13], x[14]));
    let rod = move |x: &[f64], p: V| rod_centre + V::new(x[9], x[10], x[11]) + rod_turn(x) * (p - rod_centre);
    move |t, x| {
        let residual = |x: &[f64; 15]| {
            let mut f: Vec<f64> = links.iter().map(|(c, a)| (tube.moved(x, *a) - c).norm() - (a - c).norm()).collect();
            f.push(knuckle(x, 1.0, x[6], wc).z - wc.z - t);
            match trackbar {
                Some((c, a)) => f.push((tube.moved(x, a) - c).norm() - (a - c).norm()),
                None => f.push(knuckle(x, -1.0, x[7], wc).z - wc.z - t),
            }
            f.extend((rod(x, knuckle_rod) - knuckle(x, 1.0, x[6], knuckle_rod)).iter());
            f.extend((rod(x, mirror(knuckle_rod)) - knuckle(x, -1.0, x[7], knuckle_rod)).iter());
            let right_knuckle = tube.rotation(x) * kingpin(-1.0, x[7]).1;
            f.push((rod_turn(x) * V::x()).dot(&(right_knuckle * V::z())));
            f.push((crank(x, crank_rod) - rod(x, crank_rod)).dot(&(rod_turn(x) * V::y())));
            f.push((crank(x, crank_drag) - box_end).norm() - (crank_drag - box_end).norm());
            DVector::from_vec(f)
        };
        newton_fd(residual, x);
        let spin = |side: f64, psi: f64| knuckle(x, side, psi, wc + V::y()) - knuckle(x, side, psi, wc);
        [toe_camber(spin(1.0, x[6]), 1.0), toe_camber(spin(-1.0, x[7]), -1.0)]
    }
}

/// Each solid axle's travel against its loop closure: parallel travel of the corner (built whole) and of
/// the axle, and opposite travel where the axle can roll.
#[test]
fn each_solid_axles_travel_matches_its_loop_closure() {
    let (mtv, mtv_file) = read("mtv/MTV_SolidThreeLinkAxleF.json");
    let (worst, range) =
        against(&axle_rows(&mtv_file, AxleRig::OppositeTravel, 0.05), 6, three_link_closure(&mtv, Travel::Opposite));
    assert!(range > 1e-2, "three-link roll: the wheels camber {range} rad");
    // Measured: 3.3e-14 rad.
    assert!(worst < 3e-12, "three-link roll: {worst:e} rad");

    let (man, man_file) = read("MAN_Kat1/MAN_5t_FrontSolidThreeLinkAxle.json");
    let (worst, range) = against(&corner_rows(&man_file), 8, bellcrank_closure(&man, Travel::Parallel));
    assert!(range > 1e-2, "bell-crank axle travel: the wheels toe {range} rad");
    // Measured: 1.7e-12 rad.
    assert!(worst < 1e-10, "bell-crank axle travel: {worst:e} rad");
    let (worst, range) =
        against(&axle_rows(&man_file, AxleRig::OppositeTravel, 0.05), 6, bellcrank_closure(&man, Travel::Opposite));
    assert!(range > 1e-2, "bell-crank axle roll: {range} rad");
    // Measured: 5.6e-12 rad.
    assert!(worst < 5e-10, "bell-crank axle roll: {worst:e} rad");
    let (worst, range) =
        against(&axle_rows(&man_file, AxleRig::Steering, 0.04), 6, bellcrank_closure(&man, Travel::Steering));
    assert!(range > 1e-1, "bell-crank axle steering: {range} rad");
    // Measured: 1.3e-12 rad.
    assert!(worst < 1e-10, "bell-crank axle steering: {worst:e} rad");

    // Measured: 2.3e-11 rad (the generic axle, one way to move, its right wheel following) and 4.8e-15 rad
    // (the city bus's, without a Panhard rod: both heights driven).
    for (path, tolerance) in [("SolidAxle.json", 2e-9), ("citybus/CityBus_SolidAxleFront.json", 5e-13)] {
        let (chrono, file) = read(path);
        let (worst, range) = against(&corner_rows(&file), 8, solid_axle_closure(&chrono));
        assert!(range > 1e-2, "{path}: the wheels toe and camber {range} rad");
        assert!(worst < tolerance, "{path}: {worst:e} rad");
    }
}

/// The three-link axle is symmetric: in parallel travel its right wheel toes, cambers and carries as the
/// left's mirror image; in opposite travel the right wheel at −t is the left's mirror image at t.
#[test]
fn a_symmetric_solid_axle_is_its_own_mirror_image() {
    let (_, file) = read("mtv/MTV_SolidThreeLinkAxleF.json");
    let mut worst_angle: f64 = 0.0;
    let mut worst_load: f64 = 0.0;
    for (rig, opposite) in [(AxleRig::ParallelTravel, false), (AxleRig::OppositeTravel, true)] {
        let axle = Axle::build(&file.suspension, rig).unwrap();
        let rows = axle_sweep(&axle, -0.05, 0.05, 6, Mode::Corrected).unwrap();
        for (k, r) in rows.iter().enumerate() {
            let image = if opposite { &rows[6 - k] } else { r };
            worst_angle =
                worst_angle.max((r.left.toe - image.right.toe).abs()).max((r.left.camber - image.right.camber).abs());
            worst_load = worst_load.max((r.left_load - image.right_load).abs() / r.left_load);
        }
        // The wheels' loads change by kilonewtons and, in roll, their cambers by degrees: the comparison has
        // content.
        assert!((rows[0].left_load - rows[6].left_load).abs() > 1e3);
        assert!(!opposite || (rows[0].left.camber - rows[6].left.camber).abs() > 1e-2);
    }
    // Measured: 5.7e-14 rad and 4.5e-12 (opposite travel: two equilibria, each converged on its own).
    assert!(worst_angle < 5e-12 && worst_load < 4e-10, "{worst_angle:e} rad, {worst_load:e} relative");
}

/// A corner analysis on a solid axle loads both wheels alike: the vertical force at both wheel
/// centres lifts the symmetric three-link axle to the height where parallel travel needs that force, which
/// a force on one wheel alone (the axle would roll) would not.
#[test]
fn a_corner_load_on_a_solid_axle_acts_on_both_wheels() {
    let (_, file) = read("mtv/MTV_SolidThreeLinkAxleF.json");
    let mut free = file.suspension.build(Side::Left, Rig::Free).unwrap();
    free.load_point = elastokin_suspensions::LoadPoint::WheelCentre;
    let loaded = vertical_force_sweep(free, 8_000.0, 20_000.0, 6, Mode::Corrected).unwrap();
    let driven = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let design_height = loaded[0].attitude.wheel_centre.z - loaded[0].patch_displacement.z;
    let mut worst: f64 = 0.0;
    for row in &loaded {
        let travel = row.attitude.wheel_centre.z - design_height;
        let held = parallel_wheel_travel(&driven, travel, travel, 1, Mode::Corrected).unwrap();
        worst = worst.max((held[0].wheel_load - row.load).abs() / row.load);
    }
    // The loads move the wheel: the comparison has content.
    let lift = loaded[6].attitude.wheel_centre.z - loaded[0].attitude.wheel_centre.z;
    assert!(lift > 0.02, "{lift} m");
    // Measured: 1.4e-9, the rows' converged force balance (1.4e-5 N of 10 kN).
    assert!(worst < 1e-7, "{worst:e} relative");
}

/// Chrono's generic solid axle, four angled links and a Panhard rod on ideal joints, cannot roll: opposite
/// travel is refused by name, its corner travels with the right wheel following, and the suite skips roll
/// with that reason.
#[test]
fn a_solid_axle_locked_in_roll_is_refused_opposite_travel_by_name() {
    let (_, file) = read("SolidAxle.json");
    assert_roll_locked(&file);
}
