//! Project Chrono's De Dion axles (`DeDionAxle`, `ToeBarDeDionAxle`; the generic set's files and the Duro's,
//! copied unchanged into `tests/data/chrono/`, BSD-3-Clause) read into the general model with an `axle`:
//! each wheel follows, in parallel and opposite travel and (the toe-bar axle) in steering, the closure
//! equations of Chrono's own linkage written out here from the Chrono file (not from the import); the
//! Watt pivot where Chrono builds it; the De Dion files' crossed stops, and a broken file, refused by name.

mod common;

use common::chrono::{
    against, axle_rows, corner_rows, fixture, mirror, point, read_edited, toe_camber, uncross_stops, Travel, Tube, V,
};
use common::newton_fd;
use elastokin_suspensions::document::import_chrono;
use elastokin_suspensions::{AxleRig, SuspensionFile, Template};
use nalgebra::{DVector, Rotation3, Unit};
use serde_json::Value;

/// The Chrono file as JSON with its spring's `Minimum Length` and `Maximum Length` swapped where they are
/// crossed (the De Dion files', refused as given: see `crossed_stops_are_refused_by_name`), and the model
/// imported from it; neither length moves the linkage.
fn read(path: &str) -> (Value, SuspensionFile) {
    read_edited(path, |v| {
        uncross_stops(&mut v["Spring"]);
    })
}

/// The import of the file at `path` (stops put right) edited by `edit`: its model, or the error's text.
fn edited(path: &str, edit: impl FnOnce(&mut Value)) -> Result<SuspensionFile, String> {
    common::chrono::edited(path, |v| {
        uncross_stops(&mut v["Spring"]);
        edit(v);
    })
    .map(|i| i.file)
}

/// Chrono's De Dion axle, from `ChDeDionAxle::Construct` / `ChToeBarDeDionAxle::Construct`: the tube on a
/// ball joint to the chassis at `Location Connector Chassis`; the Watt centre link turning by φ about x on
/// the tube at its pivot (`DeDionAxle`: `Left Link to Center + Right Link to Center / 2`, as its code
/// writes it; `ToeBarDeDionAxle`: their midpoint), each side link (chassis to centre link, points as
/// given) keeping its length. `DeDionAxle`: the wheels turn on the tube (ψ = 0). `ToeBarDeDionAxle`: each
/// knuckle turns by ψ about its kingpin (lower to upper point) on the tube, the toe bar from knuckle to
/// knuckle and the drag link from the steering arm (held, or moved along the drag link when steering) to
/// the knuckle the sign of `Knuckle / Location Draglink`'s y picks keep their lengths. Unknowns: the
/// tube's six, φ, ψ left, ψ right.
fn de_dion_closure(chrono: &Value, travel: Travel) -> impl Fn(f64, &mut [f64; 9]) -> [(f64, f64); 2] {
    let tube = Tube { centre: point(chrono, "Axle Tube/COM") };
    let ball = point(chrono, "Axle Tube/Location Connector Chassis");
    let w = |k: &str| point(chrono, &format!("Watt Mechanism/Location {k}"));
    let (le, ri) = (w("Left Link to Center"), w("Right Link to Center"));
    let side_links = [(w("Left Link to Chassis"), le), (w("Right Link to Chassis"), ri)];
    let toe_bar = chrono["Template"] == "ToeBarDeDionAxle";
    let pivot = if toe_bar { (le + ri) / 2.0 } else { le + ri / 2.0 };
    let wc = point(chrono, "Spindle/COM");
    assert_eq!(chrono["Camber Angle (deg)"], 0.0);
    assert_eq!(chrono["Toe Angle (deg)"], 0.0);
    // Each side's kingpin (lower, upper), the toe bar's knuckle point, the drag link's ends (the steering
    // arm's; the knuckle's as the left point, on the side `drag_side`).
    let steered = toe_bar.then(|| {
        let drl = point(chrono, "Knuckle/Location Draglink");
        (
            (point(chrono, "Knuckle/Location Lower"), point(chrono, "Knuckle/Location Upper")),
            point(chrono, "Tierod/Location Knuckle"),
            (point(chrono, "Draglink/Location Chassis"), drl),
            if drl.y < 0.0 { -1.0 } else { 1.0 },
        )
    });
    // A wheel-side point (left, or mirrored for the right) turned by ψ about its kingpin, on the tube.
    let knuckle = move |x: &[f64], side: f64, psi: f64, p: V| {
        let m = |q: V| if side > 0.0 { q } else { mirror(q) };
        let turned = match steered {
            Some(((kl, ku), ..)) => {
                m(kl) + Rotation3::from_axis_angle(&Unit::new_normalize(m(ku) - m(kl)), psi) * (m(p) - m(kl))
            }
            None => m(p),
        };
        tube.moved(x, turned)
    };
    let centre_link =
        move |x: &[f64], p: V| tube.moved(x, pivot + Rotation3::from_axis_angle(&V::x_axis(), x[6]) * (p - pivot));
    move |t, x| {
        let residual = |x: &[f64; 9]| {
            let mut f: Vec<f64> = (tube.moved(x, ball) - ball).iter().copied().collect();
            for (c, p) in side_links {
                f.push((centre_link(x, p) - c).norm() - (p - c).norm());
            }
            let (left, right, arm) = travel.at(t);
            f.push(knuckle(x, 1.0, x[7], wc).z - wc.z - left);
            f.push(knuckle(x, -1.0, x[8], wc).z - wc.z - right);
            match steered {
                Some((_, rod, (arm_end, drl), side)) => {
                    let k = |s: f64| knuckle(x, s, if s > 0.0 { x[7] } else { x[8] }, rod);
                    f.push((k(1.0) - k(-1.0)).norm() - 2.0 * rod.y);
                    let arm_now = arm_end + (drl - arm_end).normalize() * arm;
                    let drl_left = if side > 0.0 { drl } else { mirror(drl) };
                    let psi = if side > 0.0 { x[7] } else { x[8] };
                    f.push((knuckle(x, side, psi, drl_left) - arm_now).norm() - (drl - arm_end).norm());
                }
                None => f.extend([x[7], x[8]]),
            }
            DVector::from_vec(f)
        };
        newton_fd(residual, x);
        // Each wheel's outward spin axis (the left's design axis, or its mirror image) turned with its knuckle.
        let spin = |side: f64, psi: f64| knuckle(x, side, psi, wc + V::y()) - knuckle(x, side, psi, wc);
        [toe_camber(spin(1.0, x[7]), 1.0), toe_camber(spin(-1.0, x[8]), -1.0)]
    }
}

/// Chrono's `DeDionAxle` (the generic set's and the Duro's rear axle, the same but for the name): both
/// wheels against the closure in parallel travel (the corner, built whole) and in opposite travel (the
/// axle: the tube rolls about its ball joint, the Watt linkage holding it across).
#[test]
fn the_de_dion_axles_travel_matches_its_loop_closure() {
    for path in ["DeDionAxle.json", "duro/duro_dedion_axle.json"] {
        let (chrono, file) = read(path);
        let (worst, range) = against(&corner_rows(&file), 8, de_dion_closure(&chrono, Travel::Parallel));
        // The Watt pivot, off the centre link's midpoint, moves the tube across as it rises, and the ball
        // joint ahead turns that into toe: 5.4 mrad over the travel.
        assert!(range > 1e-3, "{path} travel: the wheels toe and camber {range:e} rad");
        // Measured: 9.6e-12 rad.
        assert!(worst < 1e-10, "{path} travel: {worst:e} rad");
        let (worst, range) =
            against(&axle_rows(&file, AxleRig::OppositeTravel, 0.05), 6, de_dion_closure(&chrono, Travel::Opposite));
        assert!(range > 5e-2, "{path} roll: the wheels toe and camber {range} rad");
        // Measured: 6.3e-11 rad.
        assert!(worst < 1e-9, "{path} roll: {worst:e} rad");
    }
}

/// Chrono's `ToeBarDeDionAxle` (the generic set's and the Duro's front axle): both wheels against the
/// closure in parallel travel, opposite travel and steering (the drag link's steering-arm end moved along
/// the drag link, which on the Duro is where its rotary arm moves it).
#[test]
fn the_toe_bar_de_dion_axles_travel_and_steering_match_its_loop_closure() {
    for path in ["ToeBarDeDionAxle.json", "duro/duro_toebar_dedion.json"] {
        let (chrono, file) = read(path);
        let (worst, range) = against(&corner_rows(&file), 8, de_dion_closure(&chrono, Travel::Parallel));
        assert!(range > 1e-2, "{path} travel: the wheels toe and camber {range:e} rad");
        // Measured: 6.3e-13 rad.
        assert!(worst < 1e-11, "{path} travel: {worst:e} rad");
        let (worst, range) =
            against(&axle_rows(&file, AxleRig::OppositeTravel, 0.05), 6, de_dion_closure(&chrono, Travel::Opposite));
        assert!(range > 5e-2, "{path} roll: {range} rad");
        // Measured: 1.4e-10 rad.
        assert!(worst < 5e-9, "{path} roll: {worst:e} rad");
        let (worst, range) =
            against(&axle_rows(&file, AxleRig::Steering, 0.04), 6, de_dion_closure(&chrono, Travel::Steering));
        assert!(range > 1e-1, "{path} steering: {range} rad");
        // Measured: 2.7e-12 rad.
        assert!(worst < 1e-10, "{path} steering: {worst:e} rad");
    }
}

/// The Watt centre link turns on the tube where Chrono builds its joint: `DeDionAxle` at `Left Link to
/// Center + Right Link to Center / 2` (its code's precedence), `ToeBarDeDionAxle` at the midpoint. The drag
/// link goes to the knuckle the sign of `Knuckle / Location Draglink`'s y picks, at the point as given.
#[test]
fn the_watt_pivot_and_the_drag_link_are_where_chrono_builds_them() {
    let axle = |file: &SuspensionFile| {
        let Template::General(g) = &file.suspension else { panic!("general form") };
        g.axle.clone().expect("an axle section")
    };
    for (path, pivot) in
        [("DeDionAxle.json", V::new(-0.3, 0.0, 0.275)), ("ToeBarDeDionAxle.json", V::new(0.15, 0.0, 0.15))]
    {
        let (_, file) = read(path);
        let at = axle(&file).hardpoints.get("watt_pivot").unwrap();
        assert!((at - pivot).norm() < 1e-15, "{path}: {at:?}");
    }
    let (chrono, file) = read("ToeBarDeDionAxle.json");
    let link = axle(&file).steering_link.unwrap();
    assert_eq!(link.body, "right upright");
    assert_eq!(link.outer, elastokin_suspensions::description::general::Place::named("drag_link_knuckle"));
    assert_eq!(axle(&file).hardpoints.get("drag_link_knuckle"), Some(point(&chrono, "Knuckle/Location Draglink")));
    // y positive: the left knuckle.
    let left =
        edited("ToeBarDeDionAxle.json", |v| v["Knuckle"]["Location Draglink"] = serde_json::json!([0.22, 0.65, 0.1]))
            .unwrap();
    assert_eq!(axle(&left).steering_link.unwrap().body, "left upright");
}

/// The De Dion files' `Minimum Length` (0.28 m) is above their `Maximum Length` (0.12 m): at the design
/// length (0.2 m) both stops would press, 80 mm deep. Refused by name, with the two swapped as the fix.
#[test]
fn crossed_stops_are_refused_by_name() {
    for path in ["DeDionAxle.json", "duro/duro_dedion_axle.json"] {
        let e = import_chrono(&fixture(path), path, None).unwrap_err().to_string();
        assert!(
            e.contains("\"Spring\" / \"Minimum Length\" 0.28 m is not below \"Maximum Length\" 0.12 m")
                && e.contains("(0.12 and 0.28, swapped)"),
            "{path}: {e}"
        );
    }
}

/// A broken file is refused by the key at fault.
#[test]
fn a_broken_de_dion_file_is_refused_by_name() {
    let remove = |path: &'static str, object: &'static str, key: &'static str| {
        edited(path, |v| {
            v[object].as_object_mut().unwrap().remove(key);
        })
        .unwrap_err()
    };
    for (path, object, key) in [
        ("DeDionAxle.json", "Watt Mechanism", "Location Left Link to Center"),
        ("DeDionAxle.json", "Axle Tube", "Location Connector Chassis"),
        ("ToeBarDeDionAxle.json", "Knuckle", "Location Draglink"),
        ("ToeBarDeDionAxle.json", "Tierod", "Location Knuckle"),
        ("ToeBarDeDionAxle.json", "Draglink", "Location Chassis"),
    ] {
        let e = remove(path, object, key);
        assert!(e.contains(&format!("\"{object}\" / \"{key}\" is missing")), "{path}: {e}");
    }
    let e = edited("DeDionAxle.json", |v| {
        v["Watt Mechanism"]["Location Right Link to Center"] =
            v["Watt Mechanism"]["Location Right Link to Chassis"].clone()
    })
    .unwrap_err();
    assert!(e.contains("\"Location Right Link to Chassis\" and \"Location Right Link to Center\" coincide"), "{e}");
    let e = edited("ToeBarDeDionAxle.json", |v| {
        v["Draglink"]["Location Chassis"] = v["Knuckle"]["Location Draglink"].clone()
    })
    .unwrap_err();
    assert!(e.contains("coincide: they are the drag link's two ends"), "{e}");
}
