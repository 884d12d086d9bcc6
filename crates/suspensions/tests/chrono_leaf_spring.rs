//! Project Chrono's leaf-spring axles (`LeafspringAxle`, `ToeBarLeafspringAxle`; files copied unchanged into
//! `tests/data/chrono/`, BSD-3-Clause) read into the general model with an `axle`: each wheel's toe, camber
//! and centre follow, in parallel and opposite travel, in uneven travel and in steering, the closure
//! equations of Chrono's own guide and links written out here from the Chrono file (not from the import);
//! the wheels carry what the springs push, by virtual work on the closure's spring lengths.

mod common;

use common::chrono::{
    axle_rows_of, edited, fixture, mirror, number, point, read_edited, spread, toe_camber, walk_out, Travel, Tube, V,
};
use common::newton_fd;
use elastokin_core::JointSpec;
use elastokin_solver::{LoadPath, Mode, StaticSolver};
use elastokin_suspensions::document::import_chrono;
use elastokin_suspensions::kc::{self, Settings};
use elastokin_suspensions::{Axle, AxleRig, SuspensionFile, WheelAttitude};
use nalgebra::{DVector, Rotation3, Unit};
use serde_json::Value;

/// Chrono's `LeafspringAxle` file (its spring's stops overlap: refused as shipped, read here without them).
const LEAF: &str = "citybus/CityBus_LeafspringAxle.json";
/// Chrono's `ToeBarLeafspringAxle` file.
const TOE_BAR: &str = "mtv/FMTV_ToeBarLeafSpringAxle.json";

/// The leaf-spring axle's file with its spring's `Minimum Length` and `Maximum Length` (0.5 and 0.3 m: both
/// stops would press at every length) taken out, as the refusal asks.
fn leaf() -> (Value, SuspensionFile) {
    let e = import_chrono(&fixture(LEAF), LEAF, None).unwrap_err().to_string();
    assert!(e.contains("\"Minimum Length\" 0.5 m is not below \"Maximum Length\" 0.3 m"), "{e}");
    read_edited(LEAF, |v| {
        let spring = v["Spring"].as_object_mut().unwrap();
        spring.remove("Minimum Length").unwrap();
        spring.remove("Maximum Length").unwrap();
    })
}

/// The toe-bar axle's file as shipped.
fn toe_bar() -> (Value, SuspensionFile) {
    read_edited(TOE_BAR, |_| {})
}

/// The toe-bar axle's file with the drag link moved to the right knuckle: `Knuckle / Location Draglink`
/// and `Draglink / Location Chassis` at their mirror images (Chrono takes a negative y of the knuckle's
/// point as the right knuckle's arm, and both points as given).
fn toe_bar_right() -> (Value, SuspensionFile) {
    read_edited(TOE_BAR, |v| {
        for (object, key) in [("Knuckle", "Location Draglink"), ("Draglink", "Location Chassis")] {
            let y = &mut v[object][key][1];
            *y = (-y.as_f64().unwrap()).into();
        }
    })
}

/// The closure's answer: each wheel's centre and outward spin axis, each spring's length (left, right).
struct Solved {
    centre: [V; 2],
    spin: [V; 2],
    springs: [f64; 2],
}

/// Chrono's `ChLinkLockRevolutePrismatic` guide between the chassis (first body) and the tube (second),
/// both markers at the tube's `COM` in the frame G, the chassis's turned a quarter about y (its axes
/// x = −z, y = y, z = x of the chassis). `ChLinkMarkers` takes the first marker's offset from the
/// second in the second's frame (the tube's, turned by R: axes R·G), and the first's rotation relative
/// to the second; the REVOLUTEPRISMATIC mask locks the offset's y and z and the rotation's e1 and e2 (it
/// turns about G's z alone). Four residuals.
fn guide(tube: &Tube, x: &[f64]) -> [f64; 4] {
    let r = tube.rotation(x);
    let (y_g, z_g, x_g) = (V::y(), V::x(), -V::z());
    let offset = tube.centre - tube.moved(x, tube.centre);
    [(r * y_g).dot(&offset), (r * z_g).dot(&offset), (r * z_g).dot(&x_g), (r * z_g).dot(&y_g)]
}

/// The two springs' lengths, from `Spring / Location Chassis` to `Location Axle` on the tube, and its
/// mirror image.
fn spring_lengths(chrono: &Value, tube: Tube, x: &[f64]) -> [f64; 2] {
    let (c, a) = (point(chrono, "Spring/Location Chassis"), point(chrono, "Spring/Location Axle"));
    [(tube.moved(x, a) - c).norm(), (tube.moved(x, mirror(a)) - mirror(c)).norm()]
}

/// `ChLeafspringAxle`: the tube on its guide; each spindle turns on the tube (the wheel moves with it).
/// Driven by the left and right wheel-centre rises and the steering travel ([`Travel::at`]). Unknowns:
/// the tube's six.
fn leaf_closure(chrono: &Value) -> impl Fn((f64, f64, f64), &mut [f64; 6]) -> Solved + '_ {
    let tube = Tube { centre: point(chrono, "Axle Tube/COM") };
    let wc = point(chrono, "Spindle/COM");
    assert!(chrono.get("Camber Angle (deg)").is_none() && chrono.get("Toe Angle (deg)").is_none());
    move |(left, right, _), x| {
        let residual = |x: &[f64; 6]| {
            let mut f = guide(&tube, x).to_vec();
            f.push(tube.moved(x, wc).z - wc.z - left);
            f.push(tube.moved(x, mirror(wc)).z - wc.z - right);
            DVector::from_vec(f)
        };
        newton_fd(residual, x);
        let r = tube.rotation(x);
        Solved {
            centre: [tube.moved(x, wc), tube.moved(x, mirror(wc))],
            spin: [r * V::y(), r * -V::y()],
            springs: spring_lengths(chrono, tube, x),
        }
    }
}

/// `ChToeBarLeafspringAxle`: the tube on its guide; each knuckle turns by ψ about its kingpin (lower to
/// upper point) on the tube; the toe bar (a body on a ball joint to the left knuckle and a universal joint
/// to the right one, which only stops it spinning on its own axis) keeps the distance of its ends; the drag
/// link (a ball joint at the steering end, a universal joint at the knuckle) keeps its length from the
/// steering end (held, or moved along the drag link) to the knuckle's arm, on the left knuckle unless the
/// arm's point has a negative y, both points as given. Driven as [`leaf_closure`] is. Unknowns: the tube's
/// six, ψ left, ψ right.
fn toe_bar_closure(chrono: &Value) -> impl Fn((f64, f64, f64), &mut [f64; 8]) -> Solved + '_ {
    let tube = Tube { centre: point(chrono, "Axle Tube/COM") };
    let wc = point(chrono, "Spindle/COM");
    assert!(chrono.get("Camber Angle (deg)").is_none() && chrono.get("Toe Angle (deg)").is_none());
    let (kl, ku) = (point(chrono, "Knuckle/Location Lower"), point(chrono, "Knuckle/Location Upper"));
    let bar = point(chrono, "Tierod/Location Knuckle");
    let (arm, steering_end) = (point(chrono, "Knuckle/Location Draglink"), point(chrono, "Draglink/Location Chassis"));
    let arm_side = if arm.y < 0.0 { -1.0 } else { 1.0 };
    let on = |side: f64, p: V| if side > 0.0 { p } else { mirror(p) };
    // A point of the knuckle on `side`, given where it is on that side at design, turned by ψ about its
    // kingpin, on the tube.
    let knuckle = move |x: &[f64], side: f64, psi: f64, p: V| {
        let (lower, upper) = (on(side, kl), on(side, ku));
        tube.moved(x, lower + Rotation3::from_axis_angle(&Unit::new_normalize(upper - lower), psi) * (p - lower))
    };
    let psi = |x: &[f64], side: f64| if side > 0.0 { x[6] } else { x[7] };
    move |(left, right, steer), x| {
        let residual = |x: &[f64; 8]| {
            let mut f = guide(&tube, x).to_vec();
            f.push(knuckle(x, 1.0, x[6], wc).z - wc.z - left);
            f.push(knuckle(x, -1.0, x[7], mirror(wc)).z - wc.z - right);
            let ends = knuckle(x, 1.0, x[6], bar) - knuckle(x, -1.0, x[7], mirror(bar));
            f.push(ends.norm() - 2.0 * bar.y);
            let steering_now = steering_end + (arm - steering_end).normalize() * steer;
            f.push((knuckle(x, arm_side, psi(x, arm_side), arm) - steering_now).norm() - (arm - steering_end).norm());
            DVector::from_vec(f)
        };
        newton_fd(residual, x);
        let centre = |side: f64| knuckle(x, side, psi(x, side), on(side, wc));
        let spin = |side: f64| knuckle(x, side, psi(x, side), on(side, wc + V::y())) - centre(side);
        Solved {
            centre: [centre(1.0), centre(-1.0)],
            spin: [spin(1.0), spin(-1.0)],
            springs: spring_lengths(chrono, tube, x),
        }
    }
}

/// One row of the engine's sweep: the driven parameter, each wheel, and the rig's vertical force at each
/// wheel centre (N, up +).
struct Row {
    t: f64,
    wheels: [WheelAttitude; 2],
    loads: [f64; 2],
}

/// Both wheels of the axle over `rig`'s sweep of ±`reach`, in 12 steps (design at row 6).
fn axle_rows(file: &SuspensionFile, rig: AxleRig, reach: f64) -> Vec<Row> {
    axle_rows_of(file, rig, reach, |r| Row {
        t: r.travel,
        wheels: [r.left, r.right],
        loads: [r.left_load, r.right_load],
    })
}

/// Both wheels over ±`reach` of uneven travel (the left wheel centre rises by t, the right by t/2: the axle
/// travels and rolls at once), in 12 steps: the axle held by nothing but two wheel-height drivers of its own.
fn uneven_rows(file: &SuspensionFile, reach: f64) -> Vec<Row> {
    let mut axle = Axle::build(&file.suspension, AxleRig::Free).unwrap();
    for (name, wheel, rate) in [("left height", axle.left, 1.0), ("right height", axle.right, 0.5)] {
        let spec = JointSpec::point_driver(name, wheel.upright, wheel.wheel_centre, V::z(), rate);
        axle.model.add_joint(spec).unwrap();
    }
    let mut solver = StaticSolver::new(&axle.model, Default::default()).unwrap();
    let mut state = solver.design_state(-reach);
    let sweep = solver.sweep_from(&mut state, LoadPath::new(-reach, reach, 12), Mode::Corrected).unwrap();
    sweep
        .steps
        .iter()
        .map(|s| Row { t: s.t, wheels: [axle.left.attitude(&s.poses), axle.right.attitude(&s.poses)], loads: [0.0; 2] })
        .collect()
}

/// What a comparison found: the largest toe or camber difference (rad) and wheel-centre difference (m)
/// against the closure, and the largest range of those angles and of the wheel centres' x and y over the
/// rows (their content).
#[derive(Debug, Default)]
struct Found {
    angle: f64,
    centre: f64,
    angle_range: f64,
    centre_range: f64,
}

/// `rows` against `closure` driven by `travel` at each row's `t`, walked out from the design row (index 6;
/// see [`walk_out`]).
fn against<const N: usize>(
    rows: &[Row],
    travel: Travel,
    closure: impl Fn((f64, f64, f64), &mut [f64; N]) -> Solved,
) -> Found {
    let mut found = Found::default();
    walk_out(rows, 6, |row, guess| {
        let reference = closure(travel.at(row.t), guess);
        for (k, (wheel, side)) in row.wheels.iter().zip([1.0, -1.0]).enumerate() {
            let (toe, camber) = toe_camber(reference.spin[k], side);
            found.angle = found.angle.max((wheel.toe - toe).abs()).max((wheel.camber - camber).abs());
            found.centre = found.centre.max((wheel.wheel_centre - reference.centre[k]).amax());
        }
    });
    for k in 0..2 {
        let range = |f: &dyn Fn(&WheelAttitude) -> f64| spread(rows, |r| f(&r.wheels[k]));
        found.angle_range = found.angle_range.max(range(&|w| w.toe)).max(range(&|w| w.camber));
        found.centre_range = found.centre_range.max(range(&|w| w.wheel_centre.x)).max(range(&|w| w.wheel_centre.y));
    }
    found
}

/// The largest relative difference between the rig's work on the wheels and the springs' by virtual work:
/// at each row, `Σ Fᵢ·dzᵢ/dt = −Σ push_k·dL_k/dt` over the springs (push `k (L₀ − L)`, lengths from the
/// closure, their rates by central differences of it), the wheel rises `dzᵢ/dt` those of `travel`.
fn virtual_work<const N: usize>(
    chrono: &Value,
    rows: &[Row],
    travel: Travel,
    closure: impl Fn((f64, f64, f64), &mut [f64; N]) -> Solved,
) -> f64 {
    let (k, free) = (number(chrono, "Spring/Spring Coefficient"), number(chrono, "Spring/Free Length"));
    assert!(chrono["Spring"].get("Preload").is_none());
    let h = 1e-4;
    let mut worst: f64 = 0.0;
    walk_out(rows, 6, |row, guess| {
        let at = closure(travel.at(row.t), guess);
        let (mut up, mut down) = (*guess, *guess);
        let (ahead, behind) = (closure(travel.at(row.t + h), &mut up), closure(travel.at(row.t - h), &mut down));
        let work: Vec<f64> =
            (0..2).map(|s| -k * (free - at.springs[s]) * (ahead.springs[s] - behind.springs[s]) / (2.0 * h)).collect();
        let (rise, start) = (travel.at(1.0), travel.at(0.0));
        let rig = row.loads[0] * (rise.0 - start.0) + row.loads[1] * (rise.1 - start.1);
        // Relative to the springs' shares: in opposite travel at design the two cancel.
        worst = worst.max((rig - work.iter().sum::<f64>()).abs() / work.iter().map(|w| w.abs()).sum::<f64>());
    });
    worst
}

/// `LeafspringAxle`: in parallel travel the wheels rise with the tube, square (their toe, camber and
/// centre's x and y held), the springs carrying them at their own rate; in opposite travel the tube rolls
/// about its centre, cambering the wheels and drawing them in; in uneven travel it rolls while its centre
/// slides along its own tilted vertical (Chrono's guide line turns with the tube: a line fixed in the
/// chassis would put the wheel centres 1.3 mm aside at +80 mm).
#[test]
fn the_leaf_spring_axle_matches_its_loop_closure() {
    let (chrono, file) = leaf();

    let rows = axle_rows(&file, AxleRig::ParallelTravel, 0.05);
    let found = against(&rows, Travel::Parallel, leaf_closure(&chrono));
    // Nothing but the height moves: measured 5.3e-17 rad and 0 m of range, as the closure has it.
    assert!(found.angle_range < 1e-12 && found.centre_range < 1e-12, "{found:?}");
    // Measured: 5.0e-17 rad, 5.5e-11 m (the wheel-height drivers closed to their tolerance).
    assert!(found.angle < 5e-15 && found.centre < 5e-9, "{found:?}");
    // The springs carry 71 kN more over the travel: the comparison by virtual work has content.
    assert!(rows[12].loads[0] - rows[0].loads[0] > 5e4, "{} N", rows[12].loads[0] - rows[0].loads[0]);
    let worst = virtual_work(&chrono, &rows, Travel::Parallel, leaf_closure(&chrono));
    // Measured: 7.4e-10 relative.
    assert!(worst < 5e-8, "parallel travel by virtual work: {worst:e}");

    let rows = axle_rows(&file, AxleRig::OppositeTravel, 0.05);
    let found = against(&rows, Travel::Opposite, leaf_closure(&chrono));
    // The wheels camber over 0.106 rad and their centres move in by 1.3 mm.
    assert!(found.angle_range > 0.1 && found.centre_range > 1e-3, "{found:?}");
    // Measured: 7.0e-14 rad, 1.5e-12 m.
    assert!(found.angle < 5e-12 && found.centre < 1e-10, "{found:?}");
    let worst = virtual_work(&chrono, &rows, Travel::Opposite, leaf_closure(&chrono));
    // Measured: 1.2e-9 relative.
    assert!(worst < 1e-7, "opposite travel by virtual work: {worst:e}");

    let rows = uneven_rows(&file, 0.08);
    let found = against(&rows, Travel::Uneven, leaf_closure(&chrono));
    // The wheels camber over 0.043 rad and their centres move across by 1.5 mm.
    assert!(found.angle_range > 0.04 && found.centre_range > 1e-3, "{found:?}");
    // Measured: 4.3e-14 rad, 3.0e-13 m.
    assert!(found.angle < 4e-12 && found.centre < 3e-11, "{found:?}");

    // The wheel rate of parallel travel is the spring's rate: the spring stands on the tube, which rises
    // with the wheel.
    let report = kc::run(kc::Analysis::ParallelTravel, &file, &Settings { steps: 8, ..Settings::default() }).unwrap();
    let rate = report.figure("wheel_rate").unwrap().value.unwrap();
    let k = number(&chrono, "Spring/Spring Coefficient");
    // Measured: 7.7e-8 N/m of 710 402, the rounding of the rig's force over the 0.1 mm its rate is read
    // across.
    assert!((rate - k).abs() < 3e-6, "{rate} N/m against {k}");
}

/// `ToeBarLeafspringAxle`: the wheels toe in travel as the drag link's arc turns the knuckle it steers
/// (and the toe bar the other), camber as the tube rolls, and steer as the steering end moves along the
/// drag link; the springs carry the wheels by virtual work. The same with the drag link on the right
/// knuckle.
#[test]
fn the_toe_bar_leaf_spring_axle_matches_its_loop_closure() {
    for (what, (chrono, file)) in [("left drag link", toe_bar()), ("right drag link", toe_bar_right())] {
        let rows = axle_rows(&file, AxleRig::ParallelTravel, 0.05);
        let found = against(&rows, Travel::Parallel, toe_bar_closure(&chrono));
        // The wheels toe over 6.8 mrad (the drag link's arc over ±50 mm) and their centres move by 0.6 mm.
        assert!(found.angle_range > 5e-3 && found.centre_range > 1e-4, "{what}: {found:?}");
        // Measured: 3.6e-11 rad, 3.4e-12 m (both sides).
        assert!(found.angle < 3e-9 && found.centre < 3e-10, "{what}: {found:?}");
        let worst = virtual_work(&chrono, &rows, Travel::Parallel, toe_bar_closure(&chrono));
        // Measured: 1.2e-10 relative.
        assert!(worst < 1e-8, "{what}: parallel travel by virtual work: {worst:e}");

        let rows = axle_rows(&file, AxleRig::OppositeTravel, 0.05);
        let found = against(&rows, Travel::Opposite, toe_bar_closure(&chrono));
        // The wheels camber over 0.1 rad.
        assert!(found.angle_range > 0.05, "{what}: {found:?}");
        // Measured: 1.7e-11 rad, 1.6e-12 m.
        assert!(found.angle < 1e-9 && found.centre < 1e-10, "{what}: {found:?}");
        let worst = virtual_work(&chrono, &rows, Travel::Opposite, toe_bar_closure(&chrono));
        // Measured: 2.9e-9 relative.
        assert!(worst < 2e-7, "{what}: opposite travel by virtual work: {worst:e}");

        let rows = axle_rows(&file, AxleRig::Steering, 0.04);
        let found = against(&rows, Travel::Steering, toe_bar_closure(&chrono));
        // The wheels steer over 0.44 rad.
        assert!(found.angle_range > 0.1, "{what}: {found:?}");
        // Measured: 1.2e-12 rad, 1.1e-13 m.
        assert!(found.angle < 1e-10 && found.centre < 1e-11, "{what}: {found:?}");

        let rows = uneven_rows(&file, 0.08);
        let found = against(&rows, Travel::Uneven, toe_bar_closure(&chrono));
        // The wheels camber over 0.04 rad.
        assert!(found.angle_range > 0.03, "{what}: {found:?}");
        // Measured: 1.8e-11 rad, 1.7e-12 m (4.8e-14 rad, 1.3e-13 m with the drag link on the left).
        assert!(found.angle < 1e-9 && found.centre < 1e-10, "{what}: {found:?}");
    }
}

/// A toe-bar axle whose points leave a part without length is refused by the key to fix.
#[test]
fn a_toe_bar_axle_without_a_part_is_refused_by_its_key() {
    let refused = |edit: fn(&mut Value)| edited(TOE_BAR, edit).unwrap_err();
    let e = refused(|v| v["Tierod"]["Location Knuckle"][1] = 0.0.into());
    assert!(e.contains("\"Tierod\" / \"Location Knuckle\"") && e.contains("centre line"), "{e}");
    let e = refused(|v| v["Draglink"]["Location Chassis"] = v["Knuckle"]["Location Draglink"].clone());
    assert!(e.contains("\"Draglink\" / \"Location Chassis\" and \"Knuckle\" / \"Location Draglink\" coincide"), "{e}");
    let e = refused(|v| v["Knuckle"]["Location Upper"] = v["Knuckle"]["Location Lower"].clone());
    assert!(e.contains("\"Location Lower\" and \"Location Upper\" coincide"), "{e}");
    let e = refused(|v| {
        v["Knuckle"].as_object_mut().unwrap().remove("Location Draglink");
    });
    assert!(e.contains("\"Knuckle\" / \"Location Draglink\" is missing"), "{e}");
}
