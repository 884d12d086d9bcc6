//! Project Chrono's suspension files: every shipped one runs or is refused with its reason; the double
//! wishbone and MacPherson readings against the loop closures; each convention on a hand-checked case.

use elastokin_core::Vec3;
use elastokin_solver::Mode;
use elastokin_suspensions::analysis::parallel_wheel_travel;
use elastokin_suspensions::document::import_chrono;
use elastokin_suspensions::import::chrono::Imported;
use elastokin_suspensions::kc::{self, Settings};
use elastokin_suspensions::{DoubleWishboneHardpoints, MacPhersonHardpoints, Rig, Side, Template};
use serde_json::Value;

mod common;

use common::chrono::{chrono_json, every_file, fixture};

fn read(name: &str) -> Imported {
    import_chrono(&fixture(name), name, None).unwrap()
}

/// A point of the Chrono file, read here from its JSON.
fn point(v: &Value, object: &str, key: &str) -> Vec3 {
    let p = &v[object][key];
    Vec3::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap(), p[2].as_f64().unwrap())
}

/// The double wishbone's hardpoints from a Chrono file, the spring's lower seat at `spring` (object, key).
fn dw_hardpoints(v: &Value, spring: (&str, &str)) -> DoubleWishboneHardpoints {
    DoubleWishboneHardpoints {
        wheel_centre: point(v, "Spindle", "COM"),
        upper_ball_joint: point(v, "Upper Control Arm", "Location Upright"),
        upper_arm_front: point(v, "Upper Control Arm", "Location Chassis Front"),
        upper_arm_rear: point(v, "Upper Control Arm", "Location Chassis Back"),
        lower_ball_joint: point(v, "Lower Control Arm", "Location Upright"),
        lower_arm_front: point(v, "Lower Control Arm", "Location Chassis Front"),
        lower_arm_rear: point(v, "Lower Control Arm", "Location Chassis Back"),
        tie_rod_inner: point(v, "Tierod", "Location Chassis"),
        tie_rod_outer: point(v, "Tierod", "Location Upright"),
        spring_chassis: point(v, spring.0, "Location Chassis"),
        spring_arm: point(v, spring.0, spring.1),
    }
}

/// The largest toe or camber difference (rad) between a double wishbone file's reading and the double
/// wishbone's loop closure on the file's own points (read here from its JSON), the spring's lower seat at
/// `spring` (object, key).
fn double_wishbone_against_closure(name: &str, spring: (&str, &str)) -> f64 {
    let h = dw_hardpoints(&chrono_json(name), spring);
    let corner = read(name).file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    common::travel_against_closure(&corner, |t, g| common::double_wishbone_closure(&h, t, g))
}

/// Every shipped file: read and run through every analysis that applies, or refused with the reason the
/// table in `tests/data/chrono/README.md` gives for it.
#[test]
fn every_shipped_chrono_file_runs_or_is_refused_as_the_readme_says() {
    let readme = fixture("README.md");
    let files = every_file();
    assert!(files.len() >= 15, "{files:?}");
    let (mut ran, mut refused) = (0, 0);
    for name in &files {
        let row = readme
            .lines()
            .find(|l| l.starts_with(&format!("| `{name}`")))
            .unwrap_or_else(|| panic!("{name} not in the README"));
        match import_chrono(&fixture(name), name, None) {
            Ok(imported) => {
                assert!(row.ends_with("| yes |"), "{name} reads, but the README says: {row}");
                let settings = Settings { steps: 4, ..Settings::default() };
                let report = kc::run_suite(&imported.file, &[], &settings, |_| {})
                    .complete()
                    .unwrap_or_else(|e| panic!("{name}: {e}"));
                // Every analysis ran or was left out with its reason (steering without a tie rod, the static load
                // and the load case without their sections).
                assert_eq!(report.analyses.len() + report.skipped.len(), kc::ALL.len(), "{name}");
                assert!(report.analyses.len() >= 6, "{name}: {} analyses", report.analyses.len());
                ran += 1;
            }
            Err(e) => {
                let e = e.to_string();
                let reason = row
                    .split("refused: ")
                    .nth(1)
                    .unwrap_or_else(|| panic!("{name} is refused ({e}) but the README says {row}"));
                let reason = reason.trim_end_matches(" |");
                assert!(
                    e.contains(reason) || (reason == "not read yet" && e.contains("Project Chrono template")),
                    "{name}: {e}"
                );
                refused += 1;
            }
        }
    }
    // Chrono's rigid suspension (nothing moves) is refused, whatever else comes to be read.
    assert!(ran >= 6 && refused >= 1, "{ran} read, {refused} refused");
}

/// Chrono's generic double wishbone, read, against the double wishbone's loop closure on the file's own
/// points.
#[test]
fn the_double_wishbone_reading_matches_the_loop_closure() {
    for name in ["DoubleWishbone.json", "hmmwv/HMMWV_DoubleWishboneFront.json"] {
        let worst = double_wishbone_against_closure(name, ("Spring", "Location Arm"));
        // Measured: 1.7e-14 rad (generic), 1.6e-11 rad (HMMWV).
        assert!(worst < 1e-9, "{name}: {worst:e}");
    }
}

/// Chrono's MacPherson strut — a cylindrical joint on a strut held by a universal joint, so the upright
/// steers about the strut — has the kinematics of the strut line through the top mount: the MacPherson
/// loop closure on the file's points.
#[test]
fn the_macpherson_reading_matches_the_loop_closure() {
    let v = chrono_json("MacPhersonStrut.json");
    let h = MacPhersonHardpoints {
        wheel_centre: point(&v, "Spindle", "COM"),
        lower_ball_joint: point(&v, "Control Arm", "Location Upright"),
        lower_arm_front: point(&v, "Control Arm", "Location Chassis Front"),
        lower_arm_rear: point(&v, "Control Arm", "Location Chassis Back"),
        tie_rod_outer: point(&v, "Tierod", "Location Upright"),
        tie_rod_inner: point(&v, "Tierod", "Location Chassis"),
        strut_lower: point(&v, "Spring", "Location Upright"),
        top_mount: point(&v, "Spring", "Location Chassis"),
    };
    let corner = read("MacPhersonStrut.json").file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let worst = common::travel_against_closure(&corner, |t, g| common::macpherson_closure(&h, t, g));
    // Measured: 4.5e-12 rad.
    assert!(worst < 1e-10, "{worst:e}");
}

/// Regression: Chrono's ideal MacPherson, height held, under a lateral force in four steps. Nothing moves
/// (every part is held by ideal joints and the rig), so the step's predictor is nothing, and the corrector
/// closing the start's joint gaps (within their tolerance) was taken for Newton leaving the path: every
/// step was cut to nothing.
#[test]
fn a_road_load_on_an_ideal_linkage_is_not_cut_to_nothing() {
    let file = read("MacPhersonStrut.json").file;
    let settings = Settings { steps: 4, ..Settings::default() };
    let report =
        kc::run(kc::Analysis::Road(elastokin_suspensions::analysis::WheelLoad::Lateral), &file, &settings).unwrap();
    let toe = report.table.columns.iter().position(|c| c == "toe_deg").unwrap();
    let moved = report.table.rows.iter().map(|r| r[toe].number().unwrap().abs()).fold(0.0, f64::max);
    // Measured: 2.9e-10 deg: an ideal linkage on the rig does not steer (the rest is its joints closed to
    // their 1e-10 m tolerance).
    assert!(moved < 1e-8, "{moved:e} deg");
}

/// The file's JSON with `edit` applied, read.
fn edited(name: &str, edit: impl FnOnce(&mut Value)) -> Imported {
    common::chrono::edited(name, edit).unwrap()
}

/// Camber and toe: Chrono turns the left spindle by Rz(−τ) Rx(−γ) (`ChDoubleWishbone::InitializeSide`,
/// sign −1 on the left); elastokin reads that spindle's camber (top out +) and toe (in +) as γ and τ.
#[test]
fn chrono_camber_and_toe_are_the_wheels_at_design() {
    let (gamma, tau) = (1.5_f64, -0.4_f64);
    let imported = edited("DoubleWishbone.json", |v| {
        v["Camber Angle (deg)"] = gamma.into();
        v["Toe Angle (deg)"] = tau.into();
    });
    let corner = imported.file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let a = corner.wheel.attitude(&corner.model.design_poses());
    // The spindle axis, rotated here as Chrono does: Rz(−τ) Rx(−γ) applied to the wheel's +y.
    let r = nalgebra::Rotation3::from_axis_angle(&nalgebra::Vector3::z_axis(), -tau.to_radians())
        * nalgebra::Rotation3::from_axis_angle(&nalgebra::Vector3::x_axis(), -gamma.to_radians());
    let spin = r * Vec3::y();
    // Chrono's Rz(−τ) turns a left spindle's axis forward for τ < 0: toe-in is +τ in elastokin's sign.
    assert!((spin.x.atan2(spin.y).to_degrees() - tau).abs() < 1e-12);
    // Measured: 2e-16 deg.
    assert!((a.toe.to_degrees() - tau).abs() < 1e-12 && (a.camber.to_degrees() - gamma).abs() < 1e-12, "{a:?}");
}

/// Free length, rate and preload: at design the spring pushes P + k (L₀ − L) with L its design length
/// between the file's two points (Chrono's `LinearSpringForce`: P − k (L − L₀)).
#[test]
fn a_chrono_spring_pushes_its_preload_plus_rate_times_compression() {
    let v = chrono_json("DoubleWishbone.json");
    let (k, free) = (v["Spring"]["Spring Coefficient"].as_f64().unwrap(), v["Spring"]["Free Length"].as_f64().unwrap());
    let length = (point(&v, "Spring", "Location Arm") - point(&v, "Spring", "Location Chassis")).norm();
    for preload in [0.0, 750.0] {
        let imported = edited("DoubleWishbone.json", |v| v["Spring"]["Preload"] = preload.into());
        let corner = imported.file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
        let e = corner.model.element_id("spring").unwrap();
        let poses = corner.model.design_poses();
        let r = corner.model.elements()[e.0].report(
            &elastokin_core::Pose::IDENTITY,
            &poses[corner.model.body_id("lower arm").unwrap().0],
            0.0,
        );
        let push = preload + k * (free - length);
        // Measured: 0 N (|force| against the hand-computed push of about 11 kN).
        assert!((r.force.norm() - push.abs()).abs() < 1e-8 * push.abs(), "{} vs {push}", r.force.norm());
    }
}

/// `Spring Curve Data` (extension, force) is the curve of push against compression (−x, −f): on the
/// generic file, whose table is a straight line of 369 150 N/m, the wheel rate is that of the linear file
/// (369 149 N/m) to their rates' ratio.
#[test]
fn a_chrono_spring_curve_is_its_push_against_compression() {
    let rate = |name: &str| {
        let report =
            kc::run(kc::Analysis::ParallelTravel, &read(name).file, &Settings { steps: 8, ..Settings::default() })
                .unwrap();
        report.figure("wheel_rate").unwrap().value.unwrap()
    };
    let (curve, linear) = (rate("DoubleWishboneCurve.json"), rate("DoubleWishbone.json"));
    // Measured: 2.7e-6 against the rates' ratio 369150/369149 − 1 = 2.7e-6.
    assert!(((curve / linear - 1.0) - (369150.0 / 369149.0 - 1.0)).abs() < 1e-8, "{curve} vs {linear}");
    let imported = read("DoubleWishboneCurve.json");
    let Template::General(g) = &imported.file.suspension else { panic!("general form") };
    let table = g.springs[0].curve.as_ref().unwrap();
    assert_eq!(table.first(), Some(&[-0.1, -36915.0]));
    assert_eq!(table.last(), Some(&[0.1, 36915.0]));
}

/// `Minimum Length` and `Maximum Length`: a bump and a rebound stop touching at those lengths, with Chrono's
/// built-in curve.
#[test]
fn chrono_minimum_and_maximum_lengths_are_stops_that_touch_there() {
    let v = chrono_json("DoubleWishbone.json");
    let length = (point(&v, "Spring", "Location Arm") - point(&v, "Spring", "Location Chassis")).norm();
    let imported = edited("DoubleWishbone.json", |v| {
        v["Spring"]["Minimum Length"] = (length - 0.02).into();
        v["Spring"]["Maximum Length"] = (length + 0.03).into();
    });
    let Template::General(g) = &imported.file.suspension else { panic!("general form") };
    assert_eq!(g.stops.len(), 2);
    assert!((g.stops[0].clearance - 0.02).abs() < 1e-15 && (g.stops[1].clearance - 0.03).abs() < 1e-15);
    // Chrono's bump and rebound curve, as `SpringForce::enable_stops` (chrono/utils/ChForceFunctors.cpp) adds
    // its points: travel past contact (m), force (N); its table (not extrapolating) holds the last force
    // beyond, written out as a last, flat interval.
    let chrono_curve = vec![
        [0.0, 0.0],
        [2.0e-3, 200.0],
        [4.0e-3, 400.0],
        [6.0e-3, 600.0],
        [8.0e-3, 800.0],
        [10.0e-3, 1000.0],
        [20.0e-3, 2500.0],
        [30.0e-3, 4500.0],
        [40.0e-3, 7500.0],
        [50.0e-3, 12500.0],
        [60.0e-3, 125000.0],
        [70.0e-3, 125000.0],
    ];
    assert_eq!(g.stops[0].curve, chrono_curve);
    assert_eq!(g.stops[1].curve, chrono_curve);
    // Past the table the stop holds 125 kN, as Chrono's does (its slope there zero).
    let curve = elastokin_elements::Curve::new("stop", chrono_curve.clone()).unwrap();
    for x in [0.065, 0.08, 0.2] {
        assert_eq!(curve.value_and_slope(x), (125000.0, 0.0), "{x}");
    }
    // The bump stop touches once the spring is 20 mm shorter: beyond, the wheel carries more.
    let run = |f: &elastokin_suspensions::SuspensionFile| {
        let corner = f.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
        parallel_wheel_travel(&corner, -0.06, 0.06, 12, Mode::Corrected).unwrap()
    };
    let (with, without) = (run(&imported.file), run(&read("DoubleWishbone.json").file));
    let extra: Vec<f64> = with.iter().zip(&without).map(|(a, b)| a.wheel_load - b.wheel_load).collect();
    // From −40 to +40 mm neither touches: measured 1.7e-11 N.
    assert!(extra[2..=10].iter().all(|e| e.abs() < 1e-9), "{extra:?}");
    // At +60 mm the bump stop pushes the wheel down (231 and 468 N more at +50, +60 mm); at −60 mm the
    // rebound stop holds it up (24 N less).
    assert!(extra[11] > 100.0 && extra[12] > extra[11] && extra[0] < -10.0, "{extra:?}");
}

/// `Bushing Data` on a control arm: Chrono's revolute joint becomes its six-way bushing at the pivots'
/// midpoint, x along the pivot axis (front − back), y Chrono's u, translations `Stiffness Linear`,
/// rotations the DOF rate about the axis and `Stiffness Rotational` across it, M = Kθ.
#[test]
fn chrono_bushing_data_is_the_joints_bushing() {
    let name = "hmmwv/HMMWV_DoubleWishboneFront_bushings.json";
    let v = chrono_json(name);
    let imported = read(name);
    let Template::General(g) = &imported.file.suspension else { panic!("general form") };
    let b = g.bushings.iter().find(|b| b.name == "lower arm pivot").unwrap();
    let data = &v["Lower Control Arm"]["Bushing Data"];
    let (k_lin, k_rot) = (data["Stiffness Linear"].as_f64().unwrap(), data["Stiffness Rotational"].as_f64().unwrap());
    let rates = |s: &Option<[elastokin_suspensions::description::general::Stiffness; 3]>| {
        s.as_ref().unwrap().clone().map(|k| k.rate().unwrap())
    };
    assert_eq!(rates(&b.translation), [k_lin; 3]);
    // The DOF rate of the file is 0: taken as the least rate the engine takes.
    assert_eq!(rates(&b.rotation), [1e-3, k_rot, k_rot]);
    assert_eq!(b.law, elastokin_elements::RotationLaw::Linear);
    let (f, back, ball) = (
        point(&v, "Lower Control Arm", "Location Chassis Front"),
        point(&v, "Lower Control Arm", "Location Chassis Back"),
        point(&v, "Lower Control Arm", "Location Upright"),
    );
    let w = (f - back).normalize();
    let vv = (back - ball).cross(&(f - ball)).normalize();
    let u = vv.cross(&w);
    match (&b.axis, &b.y_axis, &b.at) {
        (
            Some(elastokin_suspensions::description::general::Axis::Vector(x)),
            Some(elastokin_suspensions::description::general::Axis::Vector(y)),
            elastokin_suspensions::description::general::Place::At(p),
        ) => {
            assert!((x - w).norm() < 1e-15 && (y - u).norm() < 1e-15 && (p - (f + back) / 2.0).norm() < 1e-15);
        }
        other => panic!("{other:?}"),
    }
    assert!(imported.notes.iter().any(|n| n.contains("taken as 0.001")), "{:?}", imported.notes);
}

/// Chrono's reduced double wishbone (each arm two distance links) has the kinematics of the full one: the
/// double wishbone's loop closure on its points.
#[test]
fn the_reduced_double_wishbone_matches_the_loop_closure() {
    let worst =
        double_wishbone_against_closure("hmmwv/HMMWV_DoubleWishboneReducedFront.json", ("Shock", "Location Upright"));
    // Measured: 4.2e-12 rad.
    assert!(worst < 1e-10, "{worst:e}");
}

/// On the full axle the right corner of each Chrono reading is the left one mirrored.
#[test]
fn chrono_readings_mirror_on_the_axle() {
    use elastokin_suspensions::{analysis::axle_sweep, Axle, AxleRig};
    for name in [
        "DoubleWishbone.json",
        "MacPhersonStrut.json",
        "hmmwv/HMMWV_DoubleWishboneFront_bushings.json",
        "hmmwv/HMMWV_DoubleWishboneReducedFront.json",
    ] {
        let file = read(name).file;
        let axle = Axle::build(&file.suspension, AxleRig::ParallelTravel).unwrap();
        let rows = axle_sweep(&axle, -0.05, 0.05, 4, Mode::Corrected).unwrap();
        let worst = rows.iter().fold(0.0_f64, |m, r| {
            m.max((r.left.toe - r.right.toe).abs())
                .max((r.left.camber - r.right.camber).abs())
                .max((r.left.wheel_centre.y + r.right.wheel_centre.y).abs())
                .max((r.left_load - r.right_load).abs() / 1e4)
        });
        // Measured: 0, and 7.7e-16 with the six-way bushings.
        assert!(worst < 1e-13, "{name}: {worst:e}");
    }
}

/// Chrono's curve spring carries the wheel by virtual work: at every row of the driven travel the rig's
/// force is the push the table gives (`−f(L − L₀)`, interpolated here from the file's table) times the
/// rate at which the travel shortens the spring (from the exact path tangent).
#[test]
fn a_chrono_curve_spring_carries_the_wheel_by_virtual_work() {
    use elastokin_solver::{LoadPath, SolverOptions, StaticSolver};
    let v = chrono_json("DoubleWishboneCurve.json");
    let table: Vec<(f64, f64)> = v["Spring"]["Spring Curve Data"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| (r[0].as_f64().unwrap(), r[1].as_f64().unwrap()))
        .collect();
    let free = v["Spring"]["Free Length"].as_f64().unwrap();
    // Chrono's map, linear between its points (this table is a straight line, so the curve through it is too).
    let map = |x: f64| {
        let k = table.windows(2).position(|w| x <= w[1].0).unwrap_or(table.len() - 2);
        let ((x0, f0), (x1, f1)) = (table[k], table[k + 1]);
        f0 + (f1 - f0) * (x - x0) / (x1 - x0)
    };
    let (chassis, seat) = (point(&v, "Spring", "Location Chassis"), point(&v, "Spring", "Location Arm"));
    let corner = read("DoubleWishboneCurve.json").file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default()).unwrap();
    let sweep = solver.sweep(LoadPath::new(-0.06, 0.06, 12), Mode::Corrected).unwrap();
    let driver = corner.model.joint_id("wheel travel").unwrap();
    let arm = corner.model.body_id("lower arm").unwrap().0;
    let local = corner.model.bodies()[arm].design_pose.to_local_point(&seat);
    let mut worst: f64 = 0.0;
    for step in &sweep.steps {
        let load = step.joint_reactions(&corner.model)[driver.0].force.z;
        let rates = solver.path_tangent(&solver.state_of(step)).unwrap();
        let pose = step.poses[arm];
        let at = pose.point(&local);
        let velocity = Vec3::new(rates[6 * arm], rates[6 * arm + 1], rates[6 * arm + 2])
            + Vec3::new(rates[6 * arm + 3], rates[6 * arm + 4], rates[6 * arm + 5]).cross(&(at - pose.position));
        let length = (at - chassis).norm();
        let push = -map(length - free);
        let expected = -push * (at - chassis).normalize().dot(&velocity);
        worst = worst.max((load - expected).abs() / expected.abs());
    }
    // Measured: 1.5e-13 relative.
    assert!(worst < 1e-11, "{worst:e}");
}

/// The lateral and longitudinal stiffness at the patch of a corner on ideal joints were the inverse of
/// rounding: -5·10¹⁵ N/mm for the shipped double wishbone on ideal arm pivots, -3·10³¹ N/mm for the shipped
/// five-link, and figures of 10¹¹ to 10³⁵ N/mm for the Chrono files. Where the joints alone hold the patch
/// (the free motions of the joints' Jacobian do not move it that way) the figure is now missing, with
/// "rigid" as its reason; every other corner keeps its number. Checked against the patch compliance
/// itself, read a second way: rounding where rigid (at most 1.8e-15 m/N measured, over the Chrono files),
/// at least 9.9e-8 m/N (a stiffness of at most 1.01·10⁴ N/mm) where not.
#[test]
fn a_corner_its_joints_hold_reported_a_patch_stiffness_of_rounding_and_now_says_rigid() {
    use elastokin_suspensions::analysis::patch_compliance;
    let examples = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples");
    let mut files: Vec<(String, elastokin_suspensions::SuspensionFile)> =
        ["macpherson", "double_wishbone", "five_link"]
            .iter()
            .map(|n| {
                let path = format!("{examples}/{n}.json");
                (path.clone(), elastokin_suspensions::SuspensionFile::read(path.as_ref()).unwrap())
            })
            .collect();
    files.extend(
        every_file().into_iter().filter_map(|n| import_chrono(&fixture(&n), &n, None).ok().map(|i| (n, i.file))),
    );
    let (mut rigid, mut yielding, mut noise, mut softest) = (0, 0, 0.0_f64, f64::INFINITY);
    for (name, file) in &files {
        let Ok(report) = kc::run(kc::Analysis::ParallelTravel, file, &Settings { steps: 2, ..Settings::default() })
        else {
            continue;
        };
        let corner = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
        let pc = patch_compliance(&corner, 0.0).unwrap();
        for (key, k) in
            [("lateral_stiffness", pc.lateral_stiffness), ("longitudinal_stiffness", pc.longitudinal_stiffness)]
        {
            let figure = report.figure(key).unwrap();
            match figure.value {
                None => {
                    assert!(figure.reason.as_deref().unwrap().starts_with("rigid:"), "{name} {key}: {figure:?}");
                    noise = noise.max((1.0 / k).abs());
                    rigid += 1;
                }
                Some(v) => {
                    assert!((v - k).abs() <= 1e-9 * v.abs(), "{name} {key}: {v} vs {k}");
                    softest = softest.min(1.0 / k);
                    yielding += 1;
                }
            }
        }
    }
    println!("{rigid} rigid (compliance at most {noise:e} m/N), {yielding} yielding (at least {softest:e} m/N)");
    assert!(rigid >= 40 && yielding >= 4, "{rigid} rigid, {yielding} yielding");
    assert!(noise < 1e-13, "{noise:e}");
    assert!(softest > 1e-8, "{softest:e}");
}
