//! Project Chrono's `MultiLink`, `SemiTrailingArm`, `ThreeLinkIRS` and `SingleWishbone` suspension files
//! (BSD-3-Clause, `projectchrono/chrono`, copied unchanged into `tests/data/chrono/`) read into the general
//! model: each imports with every key read, passes the model check and runs every analysis that applies;
//! its wheel follows, over parallel travel, the closure equations of Chrono's own linkage written out here
//! from the Chrono file (not from the import); and the axle built from it is its own mirror image.

mod common;

use common::chrono::{chrono_json, edited, fixture, point, spread, toe_camber};
use elastokin_solver::Mode;
use elastokin_suspensions::analysis::axle_sweep;
use elastokin_suspensions::analysis::parallel_wheel_travel;
use elastokin_suspensions::document::import_chrono;
use elastokin_suspensions::import::chrono::Imported;
use elastokin_suspensions::kc::{self, Analysis, Settings};
use elastokin_suspensions::{check_model, Axle, AxleRig, Rig, Side, SuspensionFile, Template};
use nalgebra::{DMatrix, DVector, Rotation3, Unit, Vector3};
use serde_json::Value;

fn imported(path: &str) -> Imported {
    import_chrono(&fixture(path), path, None).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The wheel's outward spin axis at design from the file's camber and toe (Chrono: `Rz(−τ) Rx(−γ)` turns
/// the left spindle's y axis).
fn design_spin(chrono: &Value) -> Vector3<f64> {
    let angle = |key: &str| chrono.get(key).and_then(Value::as_f64).unwrap_or(0.0).to_radians();
    let (camber, toe) = (angle("Camber Angle (deg)"), angle("Toe Angle (deg)"));
    Rotation3::from_axis_angle(&Vector3::z_axis(), -toe)
        * Rotation3::from_axis_angle(&Vector3::x_axis(), -camber)
        * Vector3::y()
}

/// Newton's method with a central-difference Jacobian on `residual`, from `x`.
fn newton(residual: &dyn Fn(&DVector<f64>) -> DVector<f64>, mut x: DVector<f64>) -> DVector<f64> {
    let n = x.len();
    for _ in 0..50 {
        let f = residual(&x);
        if f.amax() < 1e-15 {
            break;
        }
        let mut jac = DMatrix::zeros(n, n);
        for c in 0..n {
            let h = 1e-7;
            let (mut a, mut b) = (x.clone(), x.clone());
            a[c] += h;
            b[c] -= h;
            jac.set_column(c, &((residual(&a) - residual(&b)) / (2.0 * h)));
        }
        x -= jac.lu().solve(&f).expect("the closure's Jacobian is regular");
    }
    let left = residual(&x).amax();
    assert!(left < 1e-13, "the loop does not close: residual {left:e}");
    x
}

/// A linkage's closure: at a wheel travel, the residual of its equations in its unknowns, and the wheel's
/// spin axis from a solution.
struct Closure {
    unknowns: usize,
    residual: Residual,
    spin: Spin,
}

type Residual = Box<dyn Fn(&DVector<f64>, f64) -> DVector<f64>>;
type Spin = Box<dyn Fn(&DVector<f64>) -> Vector3<f64>>;
/// A template's closure, from its Chrono file.
type Linkage = fn(&Value) -> Closure;

/// The upright as a free body: `x` = its wheel centre's displacement and its rotation vector; `moved`
/// takes a design point to where `x` puts it.
fn moved(wc: Vector3<f64>, x: &DVector<f64>, q: Vector3<f64>) -> Vector3<f64> {
    wc + Vector3::new(x[0], x[1], x[2]) + Rotation3::new(Vector3::new(x[3], x[4], x[5])) * (q - wc)
}

/// A free upright held by rigid links (`[chassis end, upright end]` pairs) and, for the three-link, a ball
/// joint to the chassis: the residual is each link's length change, the ball joint's gap and the wheel
/// centre's height against the travel.
fn free_upright(chrono: &Value, links: &[(&str, &str)], ball_joint: Option<&str>) -> Closure {
    let wc = point(chrono, "Spindle/COM");
    let links: Vec<(Vector3<f64>, Vector3<f64>)> =
        links.iter().map(|(c, u)| (point(chrono, c), point(chrono, u))).collect();
    let ball = ball_joint.map(|b| point(chrono, b));
    assert_eq!(links.len() + 3 * usize::from(ball.is_some()), 5, "five equations and the travel");
    let spin = design_spin(chrono);
    Closure {
        unknowns: 6,
        residual: Box::new(move |x, travel| {
            let mut f = Vec::new();
            if let Some(b) = ball {
                f.extend((moved(wc, x, b) - b).iter());
            }
            for (inner, outer) in &links {
                f.push((moved(wc, x, *outer) - inner).norm() - (outer - inner).norm());
            }
            f.push(x[2] - travel);
            DVector::from_vec(f)
        }),
        spin: Box::new(move |x| Rotation3::new(Vector3::new(x[3], x[4], x[5])) * spin),
    }
}

/// `ChMultiLink`: the upper arm (a revolute pivot and a ball joint: the ball joint keeps its distance to
/// both pivots), the lateral link, the trailing link and the tie rod (each a universal joint and a ball
/// joint, or a distance: the upright point keeps its distance to the chassis point).
fn multi_link(chrono: &Value) -> Closure {
    free_upright(
        chrono,
        &[
            ("Upper Arm/Location Chassis Front", "Upper Arm/Location Upright"),
            ("Upper Arm/Location Chassis Back", "Upper Arm/Location Upright"),
            ("Lateral/Location Chassis", "Lateral/Location Upright"),
            ("Trailing Link/Location Chassis", "Trailing Link/Location Upright"),
            ("Tierod/Location Chassis", "Tierod/Location Upright"),
        ],
        None,
    )
}

/// `ChThreeLinkIRS`: the arm (the upright) on a ball joint to the chassis and two links.
fn three_link(chrono: &Value) -> Closure {
    free_upright(
        chrono,
        &[
            ("Upper Link/Location Chassis", "Upper Link/Location Arm"),
            ("Lower Link/Location Chassis", "Lower Link/Location Arm"),
        ],
        Some("Trailing Arm/Location Chassis"),
    )
}

/// `ChSemiTrailingArm`: the arm (the upright) turns by θ about the line through its two pivots.
fn semi_trailing_arm(chrono: &Value) -> Closure {
    let wc = point(chrono, "Spindle/COM");
    let inner = point(chrono, "Trailing Arm/Location Chassis Inner");
    let axis = Unit::new_normalize(point(chrono, "Trailing Arm/Location Chassis Outer") - inner);
    let spin = design_spin(chrono);
    Closure {
        unknowns: 1,
        residual: Box::new(move |x, travel| {
            let turned = inner + Rotation3::from_axis_angle(&axis, x[0]) * (wc - inner);
            DVector::from_element(1, turned.z - wc.z - travel)
        }),
        spin: Box::new(move |x| Rotation3::from_axis_angle(&axis, x[0]) * spin),
    }
}

/// `ChSingleWishbone`: the arm turns by α about the chassis's x axis through its pivot, the upright by β
/// about the arm's vertical axis through the arm's upright joint; the tie rod keeps its length.
fn single_wishbone(chrono: &Value) -> Closure {
    let wc = point(chrono, "Spindle/COM");
    let pivot = point(chrono, "Control Arm/Location Chassis");
    let kingpin = point(chrono, "Control Arm/Location Upright");
    let (rod_inner, rod_outer) = (point(chrono, "Tierod/Location Chassis"), point(chrono, "Tierod/Location Upright"));
    let rotation = |x: &DVector<f64>| {
        (Rotation3::from_axis_angle(&Vector3::x_axis(), x[0]), Rotation3::from_axis_angle(&Vector3::z_axis(), x[1]))
    };
    let place = move |x: &DVector<f64>, q: Vector3<f64>| {
        let (arm, upright) = rotation(x);
        pivot + arm * ((kingpin - pivot) + upright * (q - kingpin))
    };
    let spin = design_spin(chrono);
    Closure {
        unknowns: 2,
        residual: Box::new(move |x, travel| {
            DVector::from_vec(vec![
                (place(x, rod_outer) - rod_inner).norm() - (rod_outer - rod_inner).norm(),
                place(x, wc).z - wc.z - travel,
            ])
        }),
        spin: Box::new(move |x| {
            let (arm, upright) = rotation(x);
            arm * upright * spin
        }),
    }
}

/// Largest difference (rad) of toe and camber between the imported corner's parallel travel over ±80 mm
/// and `closure`, and the toe's and camber's ranges over it (that the comparison has content).
fn against_closure(file: &SuspensionFile, closure: &Closure) -> (f64, f64, f64) {
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let rows = parallel_wheel_travel(&corner, -0.08, 0.08, 16, Mode::Corrected).unwrap();
    let mut worst: f64 = 0.0;
    // From the design position outwards in both directions, each closure starting from its neighbour.
    for half in [rows[8..].iter().collect::<Vec<_>>(), rows[..=8].iter().rev().collect()] {
        let mut guess = DVector::zeros(closure.unknowns);
        for row in half {
            guess = newton(&|x| (closure.residual)(x, row.travel), guess);
            let (toe, camber) = toe_camber((closure.spin)(&guess), 1.0);
            worst = worst.max((toe - row.attitude.toe).abs()).max((camber - row.attitude.camber).abs());
        }
    }
    (worst, spread(&rows, |r| r.attitude.toe), spread(&rows, |r| r.attitude.camber))
}

/// The file as Chrono gives it, with every ideal joint: imported, checked, and its toe and camber in
/// parallel travel against `closure`; returns the worst difference (rad).
fn ideal_against_closure(path: &str, closure: Linkage) -> f64 {
    let chrono = chrono_json(path);
    let file = imported(path).file;
    let (worst, toe_range, camber_range) = against_closure(&file, &closure(&chrono));
    // The wheel toes or cambers by a measurable amount over the travel: the comparison has content.
    assert!(toe_range.max(camber_range) > 1e-3, "{path}: toe range {toe_range}, camber range {camber_range}");
    worst
}

/// Each template's travel against its loop closure, with the worst difference allowed (rad).
#[test]
fn each_templates_travel_matches_its_loop_closure() {
    // Measured: 3.5e-15, 1.5e-16, 6.0e-12 and 1.3e-11 rad (the engine's rows converge to its force and
    // constraint tolerances).
    let cases: [(&str, Linkage, f64); 4] = [
        ("MultiLink.json", multi_link, 2e-13),
        ("SemiTrailingArm.json", semi_trailing_arm, 1e-14),
        ("ThreeLinkIRS.json", three_link, 3e-10),
        ("gator/Gator_SingleWishboneFront.json", single_wishbone, 5e-10),
    ];
    for (path, closure, tolerance) in cases {
        let worst = ideal_against_closure(path, closure);
        assert!(worst < tolerance, "{path}: {worst:e}");
    }
}

/// Every file of the four templates: each key read (none "not understood"), Chrono's topology (its moving
/// bodies and joints, a tie rod only where Chrono has one), one degree of freedom, and nothing the model
/// check warns of.
#[test]
fn every_file_is_read_whole_and_passes_the_model_check() {
    let cases: [(&str, &str, &[&str], usize, bool); 9] = [
        ("MultiLink.json", "MultiLink", &["upright", "upper arm", "lateral link", "trailing link"], 6, true),
        (
            "sedan/Sedan_MultiLink.json",
            "MultiLink",
            &["upright", "upper arm", "lateral link", "trailing link"],
            6,
            true,
        ),
        ("audi/audi_MultiLink.json", "MultiLink", &["upright", "upper arm", "lateral link", "trailing link"], 6, true),
        ("SemiTrailingArm.json", "SemiTrailingArm", &["upright"], 1, false),
        ("VW_microbus/van_SemiTrailingArm.json", "SemiTrailingArm", &["upright"], 1, false),
        ("ThreeLinkIRS.json", "ThreeLinkIRS", &["upright", "upper link", "lower link"], 5, false),
        ("hmmwv/HMMWV_ThreeLinkIRS.json", "ThreeLinkIRS", &["upright", "upper link", "lower link"], 5, false),
        ("Polaris/Polaris_Rear_TrailingArm.json", "ThreeLinkIRS", &["upright", "upper link", "lower link"], 5, false),
        ("gator/Gator_SingleWishboneFront.json", "SingleWishbone", &["upright", "control arm"], 2, true),
    ];
    for (path, template, bodies, joints, steered) in cases {
        let read = imported(path);
        assert_eq!(read.template, template, "{path}");
        let unread: Vec<&String> = read.notes.iter().filter(|n| n.contains("not understood")).collect();
        assert!(unread.is_empty(), "{path}: {unread:?}");
        let Template::General(ref g) = read.file.suspension else { panic!("{path}: the general form") };
        assert_eq!(g.bodies.iter().map(|b| b.name.as_str()).collect::<Vec<_>>(), bodies, "{path}");
        assert_eq!(g.joints.len(), joints, "{path}: {:?}", g.joints.iter().map(|j| &j.name).collect::<Vec<_>>());
        assert!(g.bushings.is_empty(), "{path}: no file of these gives bushing data");
        assert_eq!(g.corner.tie_rod.is_some(), steered, "{path}");
        assert_eq!(g.springs.len(), 1, "{path}");
        let check = check_model(&read.file).unwrap_or_else(|e| panic!("{path}: {e}"));
        assert_eq!(
            (check.degrees_of_freedom, check.degrees_of_freedom_on_rig, check.redundant_rows),
            (1, 0, 0),
            "{path}"
        );
        assert!(check.warnings.is_empty(), "{path}: {:?}", check.warnings);
    }
}

/// The suite on each template's generic (or only) file: every analysis that applies runs; the static load
/// and the model's load case are skipped (a Chrono suspension file has no vehicle and no load case), and
/// steering where Chrono has no tie rod. The generic three-link's spring is at its free length at design
/// (0.4 m both), so its corner carries nothing there and the vertical force needs a range of its own.
#[test]
fn every_analysis_that_applies_runs() {
    use Analysis::*;
    let cases = [
        ("MultiLink.json", true, None),
        ("SemiTrailingArm.json", false, None),
        ("ThreeLinkIRS.json", false, Some((0.0, 3000.0))),
        ("gator/Gator_SingleWishboneFront.json", true, None),
    ];
    for (path, steered, vertical_range) in cases {
        let file = imported(path).file;
        let applies: Vec<Analysis> = kc::ALL
            .into_iter()
            .filter(|a| !matches!(a, StaticLoad | ModelLoads | WheelEnvelope))
            .filter(|a| steered || *a != Steering)
            .filter(|a| vertical_range.is_none() || *a != VerticalForce)
            .collect();
        let which = if vertical_range.is_none() { Vec::new() } else { applies.clone() };
        let report = kc::run_suite(&file, &which, &Settings::default(), |_| {})
            .complete()
            .unwrap_or_else(|e| panic!("{path}: {e}"));
        let ran: Vec<Analysis> = report.analyses.iter().map(|a| a.analysis).collect();
        assert_eq!(ran, applies, "{path}");
        if vertical_range.is_none() {
            let mut skipped: Vec<Analysis> = report.skipped.iter().map(|s| s.analysis).collect();
            skipped.sort_by_key(|a| a.name());
            let mut expected = vec![StaticLoad, ModelLoads, WheelEnvelope];
            if !steered {
                expected.push(Steering);
            }
            expected.sort_by_key(|a| a.name());
            assert_eq!(skipped, expected, "{path}");
        }
        if let Some(range) = vertical_range {
            let settings = Settings { range: Some(range), ..Settings::default() };
            let vertical = kc::run(VerticalForce, &file, &settings).unwrap_or_else(|e| panic!("{path}: {e}"));
            assert_eq!(vertical.table.rows.len(), settings.steps + 1, "{path}");
        }
        for a in &report.analyses {
            for f in &a.figures {
                assert!(f.value.is_none_or(f64::is_finite), "{path}: {} {} {:?}", a.analysis.name(), f.key, f.value);
            }
        }
    }
}

/// The axle in parallel travel: the right corner is the left's mirror image, so both wheels toe, camber
/// and carry alike.
#[test]
fn the_axle_is_its_own_mirror_image() {
    let mut worst_angle: f64 = 0.0;
    let mut worst_load: f64 = 0.0;
    for path in ["MultiLink.json", "SemiTrailingArm.json", "ThreeLinkIRS.json", "gator/Gator_SingleWishboneFront.json"]
    {
        let file = imported(path).file;
        let axle = Axle::build(&file.suspension, AxleRig::ParallelTravel).unwrap();
        let rows = axle_sweep(&axle, -0.06, 0.06, 6, Mode::Corrected).unwrap();
        for r in &rows {
            worst_angle = worst_angle.max((r.left.toe - r.right.toe).abs()).max((r.left.camber - r.right.camber).abs());
            worst_load = worst_load.max((r.left_load - r.right_load).abs() / r.left_load.abs().max(1.0));
        }
        // The rows move: the comparison has content.
        assert!((rows[0].left.camber - rows[6].left.camber).abs() + (rows[0].left.toe - rows[6].left.toe).abs() > 1e-3);
    }
    // Measured: 0 and 0 (the right corner is built and solved as the left's exact mirror image).
    assert!(worst_angle < 1e-12 && worst_load < 1e-12, "{worst_angle:e} rad, {worst_load:e} relative");
}

/// Chrono's `Bushing Data` (translations `k` N/m, the rotations a joint holds `k`/100 N·m/rad, those it
/// frees 0) added at `places` (JSON objects; a tie rod also gets Chrono's rod body, whose `Mass` makes it
/// one): the file's text with those edits.
fn with_bushings(path: &str, places: &[&str], k: f64) -> String {
    let mut chrono = chrono_json(path);
    let data = serde_json::json!({
        "Stiffness Linear": k, "Damping Linear": 1e3, "Stiffness Rotational": k / 100.0, "Damping Rotational": 10.0,
        "DOF": { "Stiffness Linear": 0, "Damping Linear": 0, "Stiffness Rotational": 0, "Damping Rotational": 0 }
    });
    for place in places {
        let (object, key) = place.rsplit_once('/').unwrap();
        let target = &mut chrono[object];
        if object == "Tierod" {
            target["Mass"] = 1.0.into();
            target["Inertia"] = serde_json::json!([0.01, 0.01, 0.001]);
            target["Radius"] = 0.01.into();
        }
        target[key] = data.clone();
    }
    serde_json::to_string_pretty(&chrono).unwrap()
}

/// Where Chrono's classes take bushing data on the arms: with it each of those joints is Chrono's bushing
/// instead (in the general model's `bushings`, under the joint's name), and as the bushings stiffen the
/// wheel's travel closes in on the ideal linkage's loop closure at the rate of their compliance: a hundred
/// times stiffer, a hundred times closer.
#[test]
fn bushing_data_becomes_chronos_bushings_and_stiff_ones_approach_the_closure() {
    let cases: [(&str, &[&str], &[&str], Linkage); 3] = [
        ("SemiTrailingArm.json", &["Trailing Arm/Bushing Data"], &["trailing arm pivot"], semi_trailing_arm),
        (
            "ThreeLinkIRS.json",
            &[
                "Trailing Arm/Bushing Data Chassis",
                "Upper Link/Bushing Data Arm",
                "Upper Link/Bushing Data Chassis",
                "Lower Link/Bushing Data Arm",
                "Lower Link/Bushing Data Chassis",
            ],
            &[
                "trailing arm pivot",
                "upper link ball joint",
                "upper link mount",
                "lower link ball joint",
                "lower link mount",
            ],
            three_link,
        ),
        ("gator/Gator_SingleWishboneFront.json", &["Control Arm/Bushing Data"], &["arm pivot"], single_wishbone),
    ];
    for (path, places, bushed, closure) in cases {
        let mut errors = Vec::new();
        for k in [1e7, 1e9] {
            let read =
                import_chrono(&with_bushings(path, places, k), path, None).unwrap_or_else(|e| panic!("{path}: {e}"));
            let unread: Vec<&String> = read.notes.iter().filter(|n| n.contains("not understood")).collect();
            assert!(unread.is_empty(), "{path}: {unread:?}");
            let Template::General(ref g) = read.file.suspension else { panic!("{path}: the general form") };
            assert_eq!(g.bushings.iter().map(|b| b.name.as_str()).collect::<Vec<_>>(), bushed, "{path}");
            for name in bushed {
                assert!(g.joints.iter().all(|j| j.name != *name), "{path}: {name} is a bushing, not a joint");
            }
            check_model(&read.file).unwrap_or_else(|e| panic!("{path}: {e}"));
            errors.push(against_closure(&read.file, &closure(&chrono_json(path))).0);
        }
        // Measured: 1.4e-2 → 1.4e-4 rad (semi-trailing arm), 2.5e-2 → 2.8e-4 (three-link), 9.3e-3 → 9.6e-5
        // (single wishbone): 90 to 98 times closer.
        assert!(errors[0] / errors[1] > 50.0 && errors[1] < 1e-3, "{path}: {errors:?}");
    }
}

/// A tie rod with Chrono's rod body and `Bushing Data` (multi-link, single wishbone) is a rod with a bushing
/// at each end: at the rack Chrono's universal joint (twist held), at the upright its ball joint (twist
/// free). As the bushings stiffen the multi-link closes in on its loop closure, a hundred times stiffer a
/// hundred times closer (with the twist held at both ends it stayed ~2e-3 rad off however stiff).
#[test]
fn a_bushed_tie_rod_is_a_rod_with_a_bushing_at_each_end() {
    use elastokin_suspensions::{Connection, TieRodMounts};
    for path in ["MultiLink.json", "gator/Gator_SingleWishboneFront.json"] {
        let read = import_chrono(&with_bushings(path, &["Tierod/Bushing Data"], 1e8), path, None).unwrap();
        let unread: Vec<&String> = read.notes.iter().filter(|n| n.contains("not understood")).collect();
        assert!(unread.is_empty(), "{path}: {unread:?}");
        let Template::General(ref g) = read.file.suspension else { panic!("{path}: the general form") };
        let rod = g.corner.tie_rod.as_ref().expect("a tie rod");
        let TieRodMounts { inner: Connection::Bushing(inner), outer: Connection::Bushing(outer) } = rod.connection
        else {
            panic!("{path}: {:?}", rod.connection)
        };
        // with_bushings gives Stiffness Rotational k/100 and DOF rates 0 (taken as 1e-3).
        assert_eq!((inner.torsion, inner.conical, outer.torsion, outer.conical), (1e6, 1e-3, 1e-3, 1e-3), "{path}");
        let report = kc::run(Analysis::ParallelTravel, &read.file, &Settings::default()).unwrap();
        assert_eq!(report.table.rows.len(), Settings::default().steps + 1, "{path}");
    }
    let errors: Vec<f64> = [1e7, 1e9]
        .map(|k| {
            let read =
                import_chrono(&with_bushings("MultiLink.json", &["Tierod/Bushing Data"], k), "MultiLink.json", None)
                    .unwrap();
            against_closure(&read.file, &multi_link(&chrono_json("MultiLink.json"))).0
        })
        .to_vec();
    // Measured: 6.5e-4 → 6.5e-6 rad, 99.9 times closer.
    assert!(errors[0] / errors[1] > 50.0 && errors[1] < 1e-4, "{errors:?}");
}

/// A Chrono file with one edit that gives its linkage no geometry: the refusal names the key and says what
/// to give.
#[test]
fn mistakes_are_refused_by_name() {
    type Edit = fn(&mut Value);
    let cases: [(&str, Edit, &[&str]); 9] = [
        (
            "MultiLink.json",
            |v| v["Lateral"]["Universal Joint Axis Link"] = serde_json::json!([0, 0, 1]),
            &[
                "\"Lateral\" / \"Universal Joint Axis Chassis\" and \"Universal Joint Axis Link\"",
                "from perpendicular",
                "give perpendicular directions",
            ],
        ),
        (
            "MultiLink.json",
            |v| v["Upper Arm"]["Location Chassis Front"] = serde_json::json!([60.0, 5470.0, 82.0]),
            &["\"Upper Arm\" / \"Location Chassis Front\" [60.0, 5470.0, 82.0]", "beyond ±1000 m", "in metres"],
        ),
        (
            "MultiLink.json",
            |v| v["Trailing Link"]["Universal Joint Axis Link"] = serde_json::json!([0, 0, 0]),
            &["\"Trailing Link\" / \"Universal Joint Axis Link\" is [0, 0, 0]: give the direction"],
        ),
        (
            "MultiLink.json",
            |v| v["Lateral"]["Universal Joint Axis Chassis"] = "up".into(),
            &["\"Lateral\" / \"Universal Joint Axis Chassis\" must be a direction [x, y, z]"],
        ),
        (
            "MultiLink.json",
            |v| v["Upper Arm"]["Location Upright"] = serde_json::json!([0.277, 0.586, 0.102]),
            &["\"Upper Arm\": \"Location Upright\" lies on the line", "move the upright point off the pivot axis"],
        ),
        (
            "ThreeLinkIRS.json",
            |v| v["Upper Link"]["Universal Joint Axis"] = serde_json::json!([0, 0, 2]),
            &["\"Upper Link\" / \"Universal Joint Axis\" is vertical", "give the link's pin a horizontal direction"],
        ),
        (
            "ThreeLinkIRS.json",
            |v| {
                v["Lower Link"].as_object_mut().unwrap().remove("Location Arm");
            },
            &["\"Lower Link\" / \"Location Arm\" is missing"],
        ),
        (
            "SemiTrailingArm.json",
            |v| v["Trailing Arm"]["Location Spindle"] = serde_json::json!([0.58, 1.2, 0.05]),
            &["\"Trailing Arm\": \"Location Spindle\" lies on the line", "move the spindle point off the pivot axis"],
        ),
        (
            "SemiTrailingArm.json",
            |v| v["Camber Angle (deg)"] = 70.into(),
            &["\"Camber Angle (deg)\" 70.0", "give a camber within ±60°"],
        ),
    ];
    for (path, edit, expected) in cases {
        let message = match edited(path, edit) {
            Ok(_) => panic!("{path}: {expected:?} was read"),
            Err(e) => e,
        };
        for part in expected {
            assert!(message.contains(part), "{path}: '{message}' does not say '{part}'");
        }
    }
}

/// The steering axes the readers choose (see their module docs), and the multi-link's universal joints as
/// Chrono crosses them: the pin `Universal Joint Axis Chassis` fixed in the link (Chrono's first body),
/// `Universal Joint Axis Link` in the chassis.
#[test]
fn steering_axes_and_crosses_are_where_chrono_puts_them() {
    use elastokin_suspensions::description::general::{Axis, Place};
    let at = |g: &elastokin_suspensions::GeneralCorner, place: &Place| match place {
        Place::Named(n) => g.hardpoints.get(n).unwrap(),
        Place::At(p) => *p,
    };
    let axis_of = |path: &str| {
        let chrono = chrono_json(path);
        let Template::General(g) = imported(path).file.suspension else { panic!("{path}: the general form") };
        let [lower, upper] = &g.corner.steering_axis;
        assert_eq!((lower.body.as_str(), upper.body.as_str()), ("upright", "upright"), "{path}");
        (chrono, at(&g, &lower.at), at(&g, &upper.at), g)
    };
    // Multi-link: the upper ball joint over the midpoint of the lateral and trailing links' ball joints.
    let (chrono, lower, upper, g) = axis_of("MultiLink.json");
    let p = |k: &str| point(&chrono, k);
    assert_eq!(upper, p("Upper Arm/Location Upright"));
    assert!((lower - (p("Lateral/Location Upright") + p("Trailing Link/Location Upright")) / 2.0).norm() < 1e-15);
    for (joint, key) in [("lateral link mount", "Lateral"), ("trailing link mount", "Trailing Link")] {
        let j = g.joints.iter().find(|j| j.name == joint).unwrap();
        let link = joint.trim_end_matches(" mount");
        assert_eq!(j.bodies, [link.to_string(), "chassis".to_string()]);
        let (Some(Axis::Vector(on_link)), Some(Axis::Vector(on_chassis))) = (&j.axis, &j.axis_j) else {
            panic!("{joint}")
        };
        let pin = |k: &str| p(&format!("{key}/Universal Joint Axis {k}")).normalize();
        // Measured: 1.2e-16 (the link's pin) and 3.8e-7 (the chassis's: the file's pins are perpendicular to
        // six digits, and the chassis's is made exactly so).
        assert!((on_link.normalize() - pin("Chassis")).norm() < 1e-15, "{joint}");
        assert!((on_chassis.normalize() - pin("Link")).norm() < 1e-6, "{joint}");
    }
    // Single wishbone: the kingpin, vertical through the control arm's upright joint.
    let (chrono, lower, upper, _) = axis_of("gator/Gator_SingleWishboneFront.json");
    assert_eq!(lower, point(&chrono, "Control Arm/Location Upright"));
    assert!((upper - lower - Vector3::new(0.0, 0.0, 0.1)).norm() < 1e-15);
    // Trailing arms: the wheel's vertical through its centre (these files have no camber).
    for path in ["SemiTrailingArm.json", "ThreeLinkIRS.json"] {
        let (chrono, lower, upper, _) = axis_of(path);
        assert_eq!(lower, point(&chrono, "Spindle/COM"), "{path}");
        assert!((upper - lower - Vector3::new(0.0, 0.0, 0.1)).norm() < 1e-15, "{path}");
    }
}
