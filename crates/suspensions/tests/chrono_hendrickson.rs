//! Project Chrono's `HendricksonPRIMAXX` (the generic file, copied unchanged into `tests/data/chrono/`,
//! BSD-3-Clause) read into the general model with an `axle`: both wheels follow, in parallel travel and in
//! steering, the closure equations of the linkage `ChHendricksonPRIMAXX` builds, written out here from the
//! Chrono file (not from the import); the rig's force is the virtual work of the springs as Chrono attaches
//! them; the axle cannot roll, and opposite travel is refused by name.

mod common;

use common::chrono::{
    assert_roll_locked, axle_rows_of, corner_rows_of, edited, fixture, mirror, point, read, spread, toe_camber,
    walk_out, Travel, V,
};
use common::newton_least_squares;
use elastokin_suspensions::document::import_chrono;
use elastokin_suspensions::{AxleRig, Rig, Side, SuspensionFile};
use nalgebra::{DVector, Rotation3, Unit};
use serde_json::Value;

const FILE: &str = "HendricksonPRIMAXX.json";

/// A left point, or its mirror image for the right side (`side` −1).
fn on_side(side: f64, p: V) -> V {
    if side > 0.0 {
        p
    } else {
        mirror(p)
    }
}

/// The closure's answer: per wheel (left, right) toe, camber and the wheel centre's fore-aft position
/// (m); and the length of each side's `Shock Lower Beam` (m).
#[derive(Clone, Copy, Debug)]
struct Solved {
    wheels: [(f64, f64, f64); 2],
    springs: [f64; 2],
}

/// `ChHendricksonPRIMAXX`: the axle housing moves by `x[0..3]` and turns by the rotation vector `x[3..6]`
/// about its `COM`; each torque rod and each lower beam (left torque rod, right, left lower beam, right)
/// turns by `x[6..10]` about the line across the car (y) through its `Chassis Attachment Point`, and its
/// `Axle Housing Attachment Point` is the housing's (a revolute joint to the chassis, a ball joint to the
/// housing); each knuckle turns by ψ (`x[10]` left, `x[11]` right) about its kingpin (lower to upper
/// attachment point) on the housing; each tie rod (a distance constraint) from its chassis point — moved
/// across the car when steering — to its knuckle point keeps its length; the left wheel centre is at the
/// asked height (the right's follows: the axle cannot roll). Fifteen equations in twelve unknowns, three of
/// them repeating others (the rods of the two sides hold the housing against the same motions across the
/// car).
fn closure(chrono: &Value, travel: Travel) -> impl Fn(f64, &mut [f64; 12]) -> Solved {
    let centre = point(chrono, "Axle Housing/COM");
    let rods: Vec<(V, V)> = ["Torque Rod", "Lower Beam"]
        .iter()
        .flat_map(|k| {
            let c = point(chrono, &format!("{k}/Chassis Attachment Point"));
            let a = point(chrono, &format!("{k}/Axle Housing Attachment Point"));
            [(c, a), (mirror(c), mirror(a))]
        })
        .collect();
    let wc = point(chrono, "Spindle/COM");
    let (kl, ku) = (point(chrono, "Knuckle/Lower Attachment Point"), point(chrono, "Knuckle/Upper Attachment Point"));
    let (rod_inner, rod_outer) = (point(chrono, "Tierod/Location Chassis"), point(chrono, "Tierod/Location Knuckle"));
    let (spring_chassis, spring_housing) =
        (point(chrono, "Shock Lower Beam/Location Chassis"), point(chrono, "Shock Lower Beam/Location Lower Beam"));
    assert!(chrono.get("Camber Angle (deg)").is_none() && chrono.get("Toe Angle (deg)").is_none());
    let housing = move |x: &[f64], p: V| {
        centre + V::new(x[0], x[1], x[2]) + Rotation3::new(V::new(x[3], x[4], x[5])) * (p - centre)
    };
    // A knuckle point (left, or mirrored for the right) turned by ψ about its kingpin, on the housing.
    let knuckle = move |x: &[f64], side: f64, psi: f64, p: V| {
        let (lower, upper) = (on_side(side, kl), on_side(side, ku));
        let turned =
            lower + Rotation3::from_axis_angle(&Unit::new_normalize(upper - lower), psi) * (on_side(side, p) - lower);
        housing(x, turned)
    };
    move |t, x| {
        let (height, _, rack) = travel.at(t);
        let residual = |x: &[f64; 12]| {
            let mut f: Vec<f64> = Vec::new();
            for (k, (c, a)) in rods.iter().enumerate() {
                let on_rod = c + Rotation3::from_axis_angle(&V::y_axis(), x[6 + k]) * (a - c);
                f.extend((housing(x, *a) - on_rod).iter());
            }
            for (side, psi) in [(1.0, x[10]), (-1.0, x[11])] {
                let inner = on_side(side, rod_inner) + V::y() * rack;
                f.push((knuckle(x, side, psi, rod_outer) - inner).norm() - (rod_outer - rod_inner).norm());
            }
            f.push(knuckle(x, 1.0, x[10], wc).z - wc.z - height);
            DVector::from_vec(f)
        };
        newton_least_squares(residual, x);
        let wheel = |side: f64, psi: f64| {
            let at = knuckle(x, side, psi, wc);
            let (toe, camber) = toe_camber(knuckle(x, side, psi, wc + V::y()) - at, side);
            (toe, camber, at.x)
        };
        let spring = |side: f64| (housing(x, on_side(side, spring_housing)) - on_side(side, spring_chassis)).norm();
        Solved { wheels: [wheel(1.0, x[10]), wheel(-1.0, x[11])], springs: [spring(1.0), spring(-1.0)] }
    }
}

/// One engine row: travel, and per wheel toe, camber and wheel-centre x.
type Row = (f64, [(f64, f64, f64); 2]);

/// Largest toe or camber difference (rad) and wheel-centre x difference (m) of both wheels between `rows`
/// and `closure`, walked outwards from the design row (index `design`) in both directions, each closure
/// starting from its neighbour's solution; and the largest range over the rows, of either wheel, of its
/// toe (rad), its camber (rad) and its wheel centre's x (m).
fn against(rows: &[Row], design: usize, closure: impl Fn(f64, &mut [f64; 12]) -> Solved) -> ([f64; 2], [f64; 3]) {
    let (mut angle, mut along): (f64, f64) = (0.0, 0.0);
    walk_out(rows, design, |(t, engine), guess| {
        let reference = closure(*t, guess);
        for (e, r) in engine.iter().zip(reference.wheels) {
            angle = angle.max((e.0 - r.0).abs()).max((e.1 - r.1).abs());
            along = along.max((e.2 - r.2).abs());
        }
    });
    let range = |value: &dyn Fn(&(f64, f64, f64)) -> f64| {
        let mut widest: f64 = 0.0;
        for w in 0..2 {
            widest = widest.max(spread(rows, |r| value(&r.1[w])));
        }
        widest
    };
    ([angle, along], [range(&|w| w.0), range(&|w| w.1), range(&|w| w.2)])
}

/// The corner's parallel travel of ±80 mm in 16 steps (design at row 8): the axle built whole, both wheels
/// (the partner's read from the same poses); and the rig's force at each row.
fn corner_rows(file: &SuspensionFile) -> (Vec<Row>, Vec<f64>) {
    corner_rows_of(file, |r, p| {
        let a = r.attitude;
        ((r.travel, [(a.toe, a.camber, a.wheel_centre.x), (p.toe, p.camber, p.wheel_centre.x)]), r.wheel_load)
    })
    .into_iter()
    .unzip()
}

/// Both wheels over the steering rig's ±40 mm of tie-rod travel across the car, in 12 steps (design at
/// row 6), both wheel heights held.
fn steering_rows(file: &SuspensionFile) -> Vec<Row> {
    axle_rows_of(file, AxleRig::Steering, 0.04, |r| {
        let (l, rt) = (r.left, r.right);
        (r.travel, [(l.toe, l.camber, l.wheel_centre.x), (rt.toe, rt.camber, rt.wheel_centre.x)])
    })
}

/// The axle's travel and steering against the closure of Chrono's linkage: both wheels' toe, camber and
/// fore-aft position. The housing pitches as it travels (the two rods of a side are not parallel), so the
/// knuckles steer against the tie rods held on the chassis.
#[test]
fn the_hendrickson_axle_travels_and_steers_as_its_loop_closure() {
    let (chrono, file) = read(FILE);
    let ([angle, along], [toe, camber, fore_aft]) =
        against(&corner_rows(&file).0, 8, closure(&chrono, Travel::Parallel));
    // Over ±80 mm the wheels toe out by up to 0.096 rad, camber by 0.024 rad and move 16 mm fore and aft.
    assert!(toe > 5e-2 && camber > 1e-2 && fore_aft > 1e-2, "travel: {toe} rad, {camber} rad, {fore_aft} m");
    // Measured: 4.9e-10 rad and 1.5e-11 m (the rows are closed to the joints' 1e-10 m: the two wheels of
    // the engine's own rows differ by as much).
    assert!(angle < 2e-8 && along < 1e-9, "travel: {angle:e} rad, {along:e} m");

    let ([angle, along], [toe, camber, fore_aft]) =
        against(&steering_rows(&file), 6, closure(&chrono, Travel::Steering));
    // Over ±40 mm across the car the wheels steer by 0.84 rad, camber by 0.13 rad (the kingpins lean) and
    // their centres swing 60 mm fore and aft about the kingpins.
    assert!(toe > 0.5 && camber > 0.1 && fore_aft > 0.05, "steering: {toe} rad, {camber} rad, {fore_aft} m");
    // Measured: 6.7e-10 rad and 5.5e-11 m.
    assert!(angle < 3e-8 && along < 3e-9, "steering: {angle:e} rad, {along:e} m");
}

/// The rig's force in parallel travel is the springs' virtual work as Chrono builds them: each side's
/// `Shock Lower Beam` from the chassis to the axle housing (not the lower beam), its rest length its design
/// length (Chrono sets none), pushing `k (L₀ − L)`; `Shock Axle Housing`, of rate zero, pushes nothing.
/// The rate at which the travel changes each spring's length is the closure's, by central differences.
#[test]
fn the_rigs_force_is_the_virtual_work_of_chronos_springs() {
    let (chrono, file) = read(FILE);
    let (rows, loads) = corner_rows(&file);
    let k = chrono["Shock Lower Beam"]["Spring Coefficient"].as_f64().unwrap();
    let rest = (point(&chrono, "Shock Lower Beam/Location Lower Beam")
        - point(&chrono, "Shock Lower Beam/Location Chassis"))
    .norm();
    let solve = closure(&chrono, Travel::Parallel);
    let mut worst: f64 = 0.0;
    let h = 1e-5;
    for ((t, _), load) in rows.iter().zip(&loads) {
        let mut guess = [0.0; 12];
        let at = |s: f64, g: &mut [f64; 12]| solve(s, g).springs;
        let (ahead, behind, here) = (at(t + h, &mut guess.clone()), at(t - h, &mut guess.clone()), at(*t, &mut guess));
        // The rig's work F dz stores k (L − L₀) dL in each spring.
        let expected: f64 = (0..2).map(|s| k * (here[s] - rest) * (ahead[s] - behind[s]) / (2.0 * h)).sum();
        worst = worst.max((load - expected).abs());
    }
    // The springs carry 84 kN at +80 mm and 79 kN at −80 mm (nothing at design, their rest length): the
    // comparison has content.
    assert!(loads[16] > 8e4 && loads[0] < -7.5e4 && loads[8].abs() < 1e-6, "{loads:?}");
    // Measured: 2.0e-4 N (2.4e-9 of the load; the closure's central differences over 10 µm).
    assert!(worst < 1e-2, "{worst:e} N");
}

/// With ideal joints the torque rods and lower beams hold the housing from rolling: opposite travel is
/// refused by name, a corner's travel drives the left wheel with the right following, and the suite skips
/// roll with that reason (and runs the rest).
#[test]
fn the_hendrickson_axle_cannot_roll_and_says_so() {
    let (_, file) = read(FILE);
    let report = assert_roll_locked(&file);
    assert!(report.analyses.iter().any(|a| a.analysis == elastokin_suspensions::kc::Analysis::Steering));
}

/// Every key of the file is read or noted with its reason: the transverse beam Chrono joins to nothing,
/// the free lengths Chrono does not use, the lower beam's spring on the housing. A camber or toe angle,
/// which this template does not read, leaves the wheel square and is noted.
#[test]
fn every_key_is_read_or_noted() {
    let text = fixture(FILE);
    let notes = import_chrono(&text, FILE, None).unwrap().notes;
    assert!(!notes.iter().any(|n| n.contains("not understood")), "{notes:?}");
    for expected in [
        "Transverse Beam: Mass, COM, Inertia, Radius — Chrono makes this body but joins it to nothing",
        "Lower Beam: Transverse Beam Attachment Point",
        "Shock Lower Beam / Free Length 0.3948 m: not used by Chrono",
        "Shock Lower Beam: Chrono joins it to the axle housing",
        "Shock Axle Housing: a damper",
    ] {
        assert!(notes.iter().any(|n| n.starts_with(expected)), "{expected}: {notes:?}");
    }
    let imported = edited(FILE, |v| v["Camber Angle (deg)"] = 2.0.into()).unwrap();
    assert!(imported.notes.iter().any(|n| n.starts_with("Camber Angle (deg), Toe Angle (deg): not read")));
    let corner = imported.file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let a = corner.wheel.attitude(&corner.model.design_poses());
    // Measured: 0 rad.
    assert!(a.camber.abs() < 1e-15 && a.toe.abs() < 1e-15, "{a:?}");
}

/// Input the linkage cannot be built from is refused, naming the keys and how to fix them.
#[test]
fn bad_input_is_refused_by_its_keys() {
    let refused = |edit: &dyn Fn(&mut Value)| edited(FILE, edit).unwrap_err();
    let e = refused(&|v| v["Knuckle"]["Upper Attachment Point"] = v["Knuckle"]["Lower Attachment Point"].clone());
    assert!(e.contains("\"Knuckle\" / \"Lower Attachment Point\" and \"Upper Attachment Point\" coincide"), "{e}");
    let e = refused(&|v| v["Torque Rod"]["Axle Housing Attachment Point"] = serde_json::json!([0.629, 0.7, 0.1]));
    assert!(e.contains("\"Torque Rod\" / \"Chassis Attachment Point\" and \"Axle Housing Attachment Point\" lie on one line across the car"), "{e}");
    let e = refused(&|v| v["Shock Axle Housing"]["Preload"] = 500.0.into());
    assert!(e.contains("\"Shock Axle Housing\" / \"Preload\" on a spring-damper of rate zero"), "{e}");
    let e = refused(&|v| v["Shock Lower Beam"]["Map Data"] = serde_json::json!([[0.0, 0.0, 0.0]]));
    assert!(e.contains("\"Shock Lower Beam\" / \"Map Data\""), "{e}");
    let e = refused(&|v| v["Lower Beam"]["Chassis Attachment Point"] = serde_json::json!([0.629, 0.65]));
    assert!(e.contains("\"Lower Beam\" / \"Chassis Attachment Point\" must be a point"), "{e}");
}
