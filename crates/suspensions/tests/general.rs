//! The general model file: every template expands into it and builds the same model through the one
//! builder; any corner written in it runs every analysis.

mod common;

use elastokin_suspensions::kc::{self, Settings};
use elastokin_suspensions::{SuspensionFile, Template};
use std::path::Path;

fn example_path(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(name)
}

fn example(name: &str) -> SuspensionFile {
    SuspensionFile::read(&example_path(name)).unwrap()
}

/// The template's file with its suspension expanded, written out and read back as a user would.
fn expanded(file: &SuspensionFile) -> SuspensionFile {
    let general = SuspensionFile { suspension: Template::General(Box::new(file.suspension.expand())), ..file.clone() };
    SuspensionFile::from_json(&general.to_json(), "expanded").unwrap()
}

/// Largest difference between two suites' tables, relative to each column's largest magnitude, or to
/// 1e-3 in the column's unit where that is smaller (the moments of ideal ball joints are rounding noise
/// about zero).
fn largest_difference(a: &kc::KcReport, b: &kc::KcReport) -> f64 {
    let mut worst: f64 = 0.0;
    assert_eq!(a.analyses.len(), b.analyses.len());
    for (x, y) in a.analyses.iter().zip(&b.analyses) {
        assert_eq!(x.table.columns, y.table.columns, "{}", x.analysis.name());
        assert_eq!(x.table.rows.len(), y.table.rows.len());
        for (c, d) in x.table.column_differences(&y.table).into_iter().enumerate() {
            let scale = x.table.rows.iter().filter_map(|r| r[c].number()).fold(1e-3_f64, |m, v| m.max(v.abs()));
            if let Some(d) = d {
                worst = worst.max(d / scale);
            }
        }
        for (f, g) in x.figures.iter().zip(&y.figures) {
            if let (Some(u), Some(v)) = (f.value, g.value) {
                worst = worst.max((u - v).abs() / u.abs().max(1e-300));
            }
        }
    }
    worst
}

#[test]
fn template_expand_run_equals_the_template_run() {
    for name in ["generic/macpherson.json", "generic/double_wishbone.json"] {
        let file = example(name);
        let general = expanded(&file);
        assert!(matches!(general.suspension, Template::General(_)));
        let settings = Settings { steps: 8, ..Settings::default() };
        let a = kc::run_suite(&file, &[], &settings, |_| {}).complete().unwrap();
        let b = kc::run_suite(&general, &[], &settings, |_| {}).complete().unwrap();
        // Measured: 0 (the same model, number for number, through the one builder; the file's numbers
        // are read back exactly).
        let worst = largest_difference(&a, &b);
        assert!(worst <= 1e-12, "{name}: {worst:e}");
        // Expanding the general form again changes nothing.
        assert_eq!(general.suspension.expand(), file.suspension.expand());
    }
}

/// The five-link corner's travel, solved in the test by its own loop closure: the wheel carrier's pose
/// (position and rotation vector) such that each of the five links keeps its length and the wheel centre
/// is at the asked height, by Newton's method with a finite-difference Jacobian.
fn five_link_closure(file: &SuspensionFile, travel: f64, guess: [f64; 6]) -> ([f64; 6], nalgebra::Vector3<f64>) {
    use nalgebra::{Rotation3, SMatrix, SVector, Vector3};
    let points = file.suspension.hardpoints();
    let p = |n: &str| points.iter().find(|(m, _)| m == n).unwrap().1;
    let wc = p("wheel_centre");
    let links: Vec<(Vector3<f64>, Vector3<f64>)> =
        ["upper_front", "upper_rear", "lower_front", "lower_rear", "toe_link"]
            .iter()
            .map(|l| (p(&format!("{l}_inner")), p(&format!("{l}_outer"))))
            .collect();
    let residual = |x: &SVector<f64, 6>| {
        let r = Rotation3::new(Vector3::new(x[3], x[4], x[5]));
        let moved = |q: Vector3<f64>| wc + Vector3::new(x[0], x[1], x[2]) + r * (q - wc);
        let mut f = SVector::<f64, 6>::zeros();
        for (k, (inner, outer)) in links.iter().enumerate() {
            f[k] = (moved(*outer) - inner).norm() - (outer - inner).norm();
        }
        f[5] = x[2] - travel;
        f
    };
    let mut x = SVector::<f64, 6>::from(guess);
    for _ in 0..50 {
        let f = residual(&x);
        if f.amax() < 1e-15 {
            break;
        }
        let mut jac = SMatrix::<f64, 6, 6>::zeros();
        for c in 0..6 {
            let h = 1e-7;
            let (mut a, mut b) = (x, x);
            a[c] += h;
            b[c] -= h;
            jac.set_column(c, &((residual(&a) - residual(&b)) / (2.0 * h)));
        }
        x -= jac.lu().solve(&f).unwrap();
    }
    assert!(residual(&x).amax() < 1e-13, "the loop does not close at {travel}");
    let spin = Rotation3::new(Vector3::new(x[3], x[4], x[5])) * Vector3::y();
    (x.into(), spin)
}

#[test]
fn five_link_travel_matches_its_loop_closure() {
    use elastokin_solver::Mode;
    use elastokin_suspensions::{Rig, Side};
    let file = example("five_link.json");
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let rows =
        elastokin_suspensions::analysis::parallel_wheel_travel(&corner, -0.08, 0.08, 16, Mode::Corrected).unwrap();
    let mut worst: f64 = 0.0;
    // From the design position outwards in both directions, each closure starting from its neighbour.
    for half in [rows[8..].iter().collect::<Vec<_>>(), rows[..=8].iter().rev().collect()] {
        let mut guess = [0.0; 6];
        for row in half {
            let (x, a) = five_link_closure(&file, row.travel, guess);
            guess = x;
            let toe = a.x.atan2(a.y);
            let camber = (-a.z).atan2(a.x.hypot(a.y));
            worst = worst.max((toe - row.attitude.toe).abs()).max((camber - row.attitude.camber).abs());
        }
    }
    // Measured: 9.5e-11 rad (the engine's rows converge to its force and constraint tolerances).
    assert!(worst < 1e-9, "{worst:e}");
    // The corner toes and cambers by a measurable amount over the travel: the comparison has content.
    let toe_range = rows.iter().map(|r| r.attitude.toe).fold(f64::MIN, f64::max)
        - rows.iter().map(|r| r.attitude.toe).fold(f64::MAX, f64::min);
    assert!(toe_range > 1e-4, "{toe_range}");
}

/// Vertical velocity of the hardpoint `point` of `body` per metre of wheel travel at design, from the
/// corner's path tangent (no bar: a lone corner has none).
fn motion_ratio_at_design(file: &SuspensionFile, body: &str, point: &str) -> f64 {
    use elastokin_solver::{SolverOptions, StaticSolver};
    use elastokin_suspensions::{Rig, Side};
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default()).unwrap();
    let mut state = solver.design_state(0.0);
    solver.equilibrium(&mut state).unwrap();
    let rates = solver.path_tangent(&state).unwrap();
    let b = corner.model.body_id(body).unwrap().0;
    let p = file.suspension.hardpoints().into_iter().find(|(n, _)| n == point).unwrap().1;
    let (v, w) = (
        nalgebra::Vector3::new(rates[6 * b], rates[6 * b + 1], rates[6 * b + 2]),
        nalgebra::Vector3::new(rates[6 * b + 3], rates[6 * b + 4], rates[6 * b + 5]),
    );
    (v + w.cross(&(p - state.poses[b].position))).z
}

/// The shipped axle example with ideal arm pivots and tie rod, so that the corner's motion is the
/// linkage's alone (with bushings the bar's link force also deflects them, and the closed forms below
/// describe a rigid linkage).
fn ideal_axle_with_bar() -> SuspensionFile {
    use elastokin_suspensions::Connection;
    let mut file = example("generic/double_wishbone.json");
    let Template::DoubleWishbone(ref mut dw) = file.suspension else { panic!("double wishbone") };
    dw.upper_arm_mounts = Connection::Ideal.into();
    dw.lower_arm_mounts = Connection::Ideal.into();
    dw.tie_rod = Connection::Ideal;
    let mut general = file.suspension.expand();
    let Template::General(axle) = example("double_wishbone_axle.json").suspension else { panic!("general form") };
    for name in ["bar_bearing", "bar_arm_end", "bar_link_lower"] {
        general.hardpoints.0.push((name.into(), axle.hardpoints.get(name).unwrap()));
    }
    general.anti_roll_bars = axle.anti_roll_bars.clone();
    SuspensionFile { suspension: Template::General(Box::new(general)), ..file }
}

/// The example's bar: its arm (0.2 m, along x) is square to its vertical drop link, so in opposite travel
/// `s` each link end moves by ±MR·s, each half of the bar turns by MR·s/a, the bar twists by 2·MR·s/a and
/// by virtual work adds 2·k·MR²/a² to each wheel's rate.
#[test]
fn anti_roll_bar_adds_its_closed_form_wheel_rate_in_opposite_travel() {
    use elastokin_solver::Mode;
    use elastokin_suspensions::{analysis::axle_sweep, Axle, AxleRig};
    let file = ideal_axle_with_bar();
    let Template::General(ref g) = file.suspension else { panic!("general form") };
    let bar = &g.anti_roll_bars[0];
    let p = |n: &str| g.hardpoints.get(n).unwrap();
    let arm = (p("bar_arm_end") - p("bar_bearing")).norm();
    let mut bare = file.clone();
    let Template::General(ref mut without) = bare.suspension else { unreachable!() };
    without.anti_roll_bars.clear();
    let h = 1e-4;
    let rate = |f: &SuspensionFile| {
        let axle = Axle::build(&f.suspension, AxleRig::OppositeTravel).unwrap();
        let rows = axle_sweep(&axle, -h, h, 2, Mode::Corrected).unwrap();
        (rows[2].left_load - rows[0].left_load) / (2.0 * h)
    };
    let added = rate(&file) - rate(&bare);
    let mr = motion_ratio_at_design(&bare, "lower arm", "bar_link_lower");
    let closed_form = 2.0 * bar.rate.expect("a rate") * mr * mr / (arm * arm);
    // Measured: 3.3e-8 relative (the central difference over ±0.1 mm).
    let relative = (added - closed_form).abs() / closed_form;
    assert!(relative < 1e-6, "bar adds {added} N/m, closed form {closed_form} N/m ({relative:e})");
    assert!(mr > 0.3, "the link end moves with the wheel: {mr}");
}

/// The roll analysis's bar stiffness (the curvature of the bar's energy against roll) equals the roll
/// stiffness it adds (the model with the bar less the model without, from the wheel loads): two methods,
/// equal when the linkage is ideal (with bushings, the bar also changes how they deflect).
#[test]
fn anti_roll_bar_share_of_roll_stiffness_is_what_it_adds() {
    let file = ideal_axle_with_bar();
    let mut bare = file.clone();
    let Template::General(ref mut without) = bare.suspension else { panic!("general form") };
    without.anti_roll_bars.clear();
    let figure = |f: &SuspensionFile, key: &str| {
        let report = kc::run(kc::Analysis::Roll, f, &Settings::default()).unwrap();
        report.figures.iter().find(|x| x.key == key).unwrap().value
    };
    let total = figure(&file, "roll_stiffness").unwrap();
    let bar = figure(&file, "anti_roll_bar_roll_stiffness").unwrap();
    let added = total - figure(&bare, "roll_stiffness").unwrap();
    // Measured: 2.4e-13 relative.
    assert!((bar - added).abs() < 1e-11 * added, "bar {bar}, added {added} N·m/rad");
    let share = figure(&file, "anti_roll_bar_share").unwrap();
    assert!((share - bar / total).abs() < 1e-11, "{share}");
    assert_eq!(figure(&bare, "anti_roll_bar_roll_stiffness"), None);
}

/// A general model with one edit: the error names the item and says what to give.
/// An edit of a model file, and the words its refusal must say.
type Refusal = (fn(&mut serde_json::Value), &'static [&'static str]);

/// Each edit of `base` is refused with every one of its words in the message.
fn refused_as_said(base: &serde_json::Value, cases: &[Refusal]) {
    for (edit, expected) in cases {
        let mut value = base.clone();
        edit(&mut value);
        let err = SuspensionFile::from_json(&value.to_string(), "edited").unwrap_err().to_string();
        for e in *expected {
            assert!(err.contains(e), "'{e}' not in: {err}");
        }
    }
}

#[test]
fn mistakes_in_a_general_model_are_named() {
    let text = std::fs::read_to_string(example_path("five_link.json")).unwrap();
    let base: serde_json::Value = serde_json::from_str(&text).unwrap();
    let cases: [Refusal; 7] = [
        (
            |v| v["suspension"]["general"]["joints"][0]["bodies"][1] = "carrier".into(),
            &["joints[0] (upper front link)", "no body 'carrier'", "'wheel carrier'"],
        ),
        (
            |v| v["suspension"]["general"]["joints"][1]["to"] = "nowhere".into(),
            &["joints[1] (upper rear link).to", "no hardpoint 'nowhere'"],
        ),
        (
            |v| {
                let joint = &mut v["suspension"]["general"]["joints"][2];
                joint["kind"] = "revolute".into();
                joint.as_object_mut().unwrap().remove("to");
            },
            &["joints[2] (lower front link)", "a revolute joint needs 'axis'"],
        ),
        (
            |v| v["suspension"]["general"]["joints"][3]["kind"] = "spherical".into(),
            &["'to' means nothing to a spherical joint"],
        ),
        (|v| v["suspension"]["general"]["bodies"][0]["name"] = "chassis".into(), &["'chassis' names the ground"]),
        (|v| v["suspension"]["general"]["corner"]["upright"] = "hub".into(), &["corner.upright", "no body 'hub'"]),
        (
            |v| {
                v["suspension"]["general"]["bushings"] = serde_json::json!([{ "name": "b", "bodies": ["chassis", "wheel carrier"],
                    "at": "wheel_centre", "radial": 1e6, "translation": [1e6, 1e6, 1e6] }])
            },
            &["bushings[0] (b)", "both sets of rates are given", "radial, axial, torsion and conical"],
        ),
    ];
    refused_as_said(&base, &cases);
}

/// A rate out of range in the general form is located at the named part's own key.
#[test]
fn a_general_model_rate_out_of_range_is_located_at_its_part() {
    let text = std::fs::read_to_string(example_path("double_wishbone_axle.json")).unwrap();
    let edited = text.replacen("\"rate\": 6000.0", "\"rate\": -6000.0", 1);
    assert_ne!(edited, text);
    let err = SuspensionFile::from_json(&edited, "axle.json").unwrap_err().to_string();
    let line = edited.lines().position(|l| l.contains("-6000.0")).unwrap() + 1;
    assert!(err.starts_with(&format!("axle.json:{line}:")), "{err}");
    assert!(err.contains("anti_roll_bars.anti-roll bar.rate") && err.contains("N·m/rad"), "{err}");
}

/// The five-link corner's own load case: on the wheel carrier, held at its design height, the links, the
/// rig, the spring, the corner load and the file's loads balance at every row (the force each applies
/// to the carrier sums to zero), and the full row carries the file's force.
#[test]
fn model_loads_balance_on_the_wheel_carrier() {
    let file = example("five_link.json");
    let report = kc::run(kc::Analysis::ModelLoads, &file, &Settings { steps: 4, ..Settings::default() }).unwrap();
    let t = &report.table;
    let mut worst: f64 = 0.0;
    for row in &t.rows {
        for axis in ["x", "y", "z"] {
            let suffix = format!(" force_{axis}_n");
            let sum: f64 = t
                .columns
                .iter()
                .zip(row)
                .filter(|(c, _)| c.ends_with(&suffix))
                .map(|(_, v)| v.number().unwrap_or(0.0))
                .sum();
            worst = worst.max(sum.abs());
        }
    }
    // Measured: 3.5e-7 N against loads of 4000 N: the rows' converged force residual.
    assert!(worst < 1e-5, "{worst:e} N");
    let last = t.rows.last().unwrap();
    let column = |name: &str| t.columns.iter().position(|c| c == name).unwrap();
    assert_eq!(last[0].number(), Some(1.0));
    assert!((last[column("cornering force force_y_n")].number().unwrap() + 4000.0).abs() < 1e-9);
    // Without a load case the suite says why it leaves the analysis out.
    let template =
        kc::run_suite(&example("generic/macpherson.json"), &[], &Settings { steps: 2, ..Settings::default() }, |_| {});
    let skipped = template.complete().unwrap().skipped;
    assert!(skipped.iter().any(|s| s.analysis == kc::Analysis::ModelLoads && s.reason.contains("no load case")));
}

/// The shipped axle example's corner on ideal pivots (as [`ideal_axle_with_bar`]) with its stops.
fn ideal_corner_with_stops() -> (SuspensionFile, SuspensionFile) {
    let with = ideal_axle_with_bar();
    let Template::General(axle) = example("double_wishbone_axle.json").suspension else { panic!("general form") };
    let mut stops = with.clone();
    let Template::General(ref mut g) = stops.suspension else { unreachable!() };
    g.stops = axle.stops.clone();
    (stops, with)
}

/// Bump and rebound stops against virtual work: with the wheel-centre height driven on an ideal linkage,
/// a stop changes no position, only the rig's force, by the stop's push times the rate at which the wheel
/// travel shortens the stop (its length's path derivative, from the exact tangent). Nothing at all
/// changes before a stop touches.
#[test]
fn stops_add_their_push_times_their_motion_ratio_to_the_wheel_load() {
    use elastokin_solver::{LoadPath, Mode, SolverOptions, StaticSolver};
    use elastokin_suspensions::{Rig, Side};
    let (with, without) = ideal_corner_with_stops();
    let points = with.suspension.hardpoints();
    let p = |n: &str| points.iter().find(|(m, _)| m == n).unwrap().1;
    let (chassis, seat) = (p("spring_chassis"), p("spring_arm"));
    let run = |file: &SuspensionFile| {
        let corner = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
        let mut solver = StaticSolver::new(&corner.model, SolverOptions::default()).unwrap();
        let sweep = solver.sweep(LoadPath::new(-0.08, 0.08, 32), Mode::Corrected).unwrap();
        let driver = corner.model.joint_id("wheel travel").unwrap();
        let arm = corner.model.body_id("lower arm").unwrap().0;
        let local = corner.model.bodies()[arm].design_pose.to_local_point(&seat);
        let mut rows = Vec::new();
        for step in &sweep.steps {
            let load = step.joint_reactions(&corner.model)[driver.0].force.z;
            let rates = solver.path_tangent(&solver.state_of(step)).unwrap();
            let pose = step.poses[arm];
            let at = pose.point(&local);
            let (v, w) = (
                nalgebra::Vector3::new(rates[6 * arm], rates[6 * arm + 1], rates[6 * arm + 2]),
                nalgebra::Vector3::new(rates[6 * arm + 3], rates[6 * arm + 4], rates[6 * arm + 5]),
            );
            let length_rate = (at - chassis).normalize().dot(&(v + w.cross(&(at - pose.position))));
            let push: f64 = ["bump stop", "rebound stop"]
                .iter()
                .filter_map(|n| corner.model.element_id(n))
                .map(|e| {
                    let r = step.element_reports(&corner.model)[e.0];
                    // The force on the arm along the stop's line, from the chassis towards the seat: its push.
                    r.force.dot(&(at - chassis).normalize())
                })
                .sum();
            rows.push((step.t, load, length_rate, push));
        }
        rows
    };
    let (a, b) = (run(&with), run(&without));
    let (mut touched, mut worst, mut before) = (0, 0.0_f64, 0.0_f64);
    for ((t, load, length_rate, push), (_, bare, _, _)) in a.iter().zip(&b) {
        if push.abs() > 0.0 {
            touched += 1;
            // Virtual work: the rig's force times δs balances the stop's push times −δL.
            let expected = -push * length_rate;
            worst = worst.max((load - bare - expected).abs() / expected.abs());
            assert!(expected.signum() == (if *t > 0.0 { 1.0 } else { -1.0 }), "{t}: the stop resists the travel");
        } else {
            before = before.max((load - bare).abs());
        }
    }
    // Both stops touch inside ±80 mm: the bump stop from about +50 mm, the rebound stop from about −70 mm.
    assert!(touched >= 4, "{touched}");
    // Measured: 1.6e-12 N before contact, 7.5e-9 relative in contact (the rows' converged residuals), over
    // 9 rows in contact.
    assert!(before < 1e-10, "{before:e} N");
    assert!(worst < 5e-7, "{worst:e}");
}

/// The right corner is the mirror image of the left, also for what mirroring could get wrong: a bushing
/// with six different rates, a frame set by `axis` and `y_axis`, a preload force and moment in its frame,
/// the Tait-Bryan law, and a load case. On the axle in parallel travel, and under the load case, every
/// row's right wheel is the left one mirrored.
#[test]
fn the_right_corner_mirrors_the_left_with_preloaded_six_rate_bushings() {
    use elastokin_solver::Mode;
    use elastokin_suspensions::description::general::{Axis, BushingDef, Place};
    use elastokin_suspensions::{analysis::axle_sweep, Axle, AxleRig};
    let mut file = example("five_link.json");
    let Template::General(ref mut g) = file.suspension else { panic!("general form") };
    // The toe link's inner end on a bushing instead of a ball joint on the chassis.
    let toe_link = g.joints.iter().position(|j| j.name == "toe link").unwrap();
    g.joints.remove(toe_link);
    g.bodies.push(elastokin_suspensions::description::general::BodyDef {
        name: "toe link".into(),
        at: Place::named("toe_link_inner"),
    });
    g.joints.push(elastokin_suspensions::description::general::JointDef {
        name: "toe link outer".into(),
        kind: elastokin_core::JointKind::Spherical,
        bodies: ["toe link".into(), "wheel carrier".into()],
        at: Some(Place::named("toe_link_outer")),
        to: None,
        axis: None,
        axis_j: None,
    });
    g.bushings.push(BushingDef {
        name: "toe link bushing".into(),
        bodies: ["chassis".into(), "toe link".into()],
        at: Place::named("toe_link_inner"),
        axis: Some(Axis::through("toe_link_inner", "toe_link_outer")),
        y_axis: Some(Axis::Vector(nalgebra::Vector3::new(0.3, 0.2, 1.0))),
        radial: None,
        axial: None,
        torsion: None,
        conical: None,
        translation: Some([3e6.into(), 8e6.into(), 5e6.into()]),
        rotation: Some([200.0.into(), 900.0.into(), 1500.0.into()]),
        law: elastokin_elements::RotationLaw::TaitBryanXyz,
        preload_force: Some([150.0, -80.0, 60.0]),
        preload_torque: Some([4.0, -7.0, 3.0]),
    });
    let worst = |rows: &[elastokin_suspensions::AxleRow]| {
        rows.iter().fold(0.0_f64, |m, r| {
            let (l, rr) = (r.left.wheel_centre, r.right.wheel_centre);
            m.max((r.left.toe - r.right.toe).abs())
                .max((r.left.camber - r.right.camber).abs())
                .max((l.y + rr.y).abs())
                .max((l.z - rr.z).abs())
                .max((l.x - rr.x).abs())
                .max((r.left_load - r.right_load).abs() / 1e4)
        })
    };
    let axle = Axle::build(&file.suspension, AxleRig::ParallelTravel).unwrap();
    let rows = axle_sweep(&axle, -0.06, 0.06, 8, Mode::Corrected).unwrap();
    // The preload turns the wheel: the mirror test has something to mirror.
    assert!(rows[4].left.toe.abs() > 1e-5, "{}", rows[4].left.toe);
    // Measured: 7.4e-16 (radians, metres, and wheel loads over 10 kN); with the preload force's z left
    // unmirrored, 8.2e-6.
    let w = worst(&rows);
    assert!(w < 1e-13, "{w:e}");
    // The file's load case on both wheels, ramped with the travel: still mirrored.
    let mut loaded = Axle::build(&file.suspension, AxleRig::ParallelTravel).unwrap();
    let Template::General(ref g) = file.suspension else { unreachable!() };
    g.add_loads(&mut loaded.model, elastokin_suspensions::Side::Left, "left ").unwrap();
    g.add_loads(&mut loaded.model, elastokin_suspensions::Side::Right, "right ").unwrap();
    let rows = axle_sweep(&loaded, 0.0, 0.06, 4, Mode::Corrected).unwrap();
    let w = worst(&rows);
    // Measured: 9.1e-17, with the toe moving by 1.2e-3 rad.
    assert!(w < 1e-13, "{w:e}");
}

/// Curves that are straight lines of a part's rate are that rate: a bushing given curves per direction
/// and a spring given a two-point data sheet build the same corner as their rates, to rounding.
#[test]
fn straight_curves_in_a_model_file_are_their_rates() {
    use elastokin_suspensions::description::general::Stiffness;
    let file = example("double_wishbone_axle.json");
    let mut curved = file.clone();
    let Template::General(ref mut g) = curved.suspension else { panic!("general form") };
    let line =
        |rate: f64, reach: f64| Stiffness::Curve(vec![[-reach, -rate * reach], [0.0, 0.0], [reach, rate * reach]]);
    for b in &mut g.bushings {
        for (k, reach) in [(&mut b.radial, 0.01), (&mut b.axial, 0.01), (&mut b.torsion, 0.2), (&mut b.conical, 0.2)] {
            let rate = k.as_ref().and_then(Stiffness::rate).unwrap();
            *k = Some(line(rate, reach));
        }
    }
    let spring = &mut g.springs[0];
    let rate = spring.rate.take().unwrap();
    spring.curve = Some(vec![[0.0, 0.0], [0.1, 0.1 * rate]]);
    let settings = Settings { steps: 4, ..Settings::default() };
    let which = [kc::Analysis::ParallelTravel, kc::Analysis::Road(elastokin_suspensions::analysis::WheelLoad::Lateral)];
    let a = kc::run_suite(&file, &which, &settings, |_| {}).complete().unwrap();
    let b = kc::run_suite(&curved, &which, &settings, |_| {}).complete().unwrap();
    // Measured: 1.1e-10 (a ball joint's moment of 1e-13 N·m against the 1e-3 floor; a curve's value is a
    // cubic of the same line, so rounding differs).
    let worst = largest_difference(&a, &b);
    assert!(worst < 1e-8, "{worst:e}");
}

/// A progressive spring from its data sheet: the wheel load is the sheet's push times the spring's motion
/// ratio (virtual work on the ideal-pivot corner, where the spring is the only elastic part).
#[test]
fn a_curve_spring_carries_the_wheel_by_virtual_work() {
    use elastokin_solver::{LoadPath, Mode, SolverOptions, StaticSolver};
    use elastokin_suspensions::{Rig, Side};
    let mut file = ideal_axle_with_bar();
    let Template::General(ref mut g) = file.suspension else { panic!("general form") };
    // Push (N) against compression (m): progressive, 20 → 50 N/mm.
    let sheet = [[0.0, 0.0], [0.05, 1000.0], [0.1, 2300.0], [0.15, 4000.0], [0.2, 6500.0]];
    let spring = &mut g.springs[0];
    spring.rate = None;
    spring.curve = Some(sheet.to_vec());
    let points = file.suspension.hardpoints();
    let p = |n: &str| points.iter().find(|(m, _)| m == n).unwrap().1;
    let (chassis, seat) = (p("spring_chassis"), p("spring_arm"));
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let free_length = {
        let e = corner.model.element_id("spring").unwrap();
        let mut solver = StaticSolver::new(&corner.model, SolverOptions::default()).unwrap();
        let mut state = solver.design_state(0.0);
        let step = solver.equilibrium(&mut state).unwrap();
        // The report's deflection is L − L₀.
        (seat - chassis).norm() - step.element_reports(&corner.model)[e.0].deflection.x
    };
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default()).unwrap();
    let sweep = solver.sweep(LoadPath::new(-0.05, 0.05, 10), Mode::Corrected).unwrap();
    let driver = corner.model.joint_id("wheel travel").unwrap();
    let arm = corner.model.body_id("lower arm").unwrap().0;
    let local = corner.model.bodies()[arm].design_pose.to_local_point(&seat);
    // The sheet's curve, written here from its points: the cubic Hermite pieces with the three-point slopes
    // of Fritsch and Carlson's first step (17, 23, 30, 42, 58 kN/m), which their limiting step leaves
    // alone on this table (no slope exceeds three times its secants).
    let slopes = {
        let h = |k: usize| sheet[k + 1][0] - sheet[k][0];
        let d = |k: usize| (sheet[k + 1][1] - sheet[k][1]) / h(k);
        let n = sheet.len();
        let mut m = vec![0.0; n];
        m[0] = ((2.0 * h(0) + h(1)) * d(0) - h(0) * d(1)) / (h(0) + h(1));
        for k in 1..n - 1 {
            m[k] = (h(k) * d(k - 1) + h(k - 1) * d(k)) / (h(k - 1) + h(k));
        }
        m[n - 1] = ((2.0 * h(n - 2) + h(n - 3)) * d(n - 2) - h(n - 2) * d(n - 3)) / (h(n - 2) + h(n - 3));
        m
    };
    let push = |x: f64| {
        let k = (0..sheet.len() - 1).find(|&k| x <= sheet[k + 1][0]).unwrap_or(sheet.len() - 2);
        let (x0, y0, x1, y1) = (sheet[k][0], sheet[k][1], sheet[k + 1][0], sheet[k + 1][1]);
        let (h, t) = (x1 - x0, (x - x0) / (x1 - x0));
        let (h00, h10, h01, h11) = (
            2.0 * t.powi(3) - 3.0 * t * t + 1.0,
            t.powi(3) - 2.0 * t * t + t,
            -2.0 * t.powi(3) + 3.0 * t * t,
            t.powi(3) - t * t,
        );
        h00 * y0 + h10 * h * slopes[k] + h01 * y1 + h11 * h * slopes[k + 1]
    };
    let mut worst: f64 = 0.0;
    for step in &sweep.steps {
        let load = step.joint_reactions(&corner.model)[driver.0].force.z;
        let rates = solver.path_tangent(&solver.state_of(step)).unwrap();
        let pose = step.poses[arm];
        let at = pose.point(&local);
        let v = nalgebra::Vector3::new(rates[6 * arm], rates[6 * arm + 1], rates[6 * arm + 2])
            + nalgebra::Vector3::new(rates[6 * arm + 3], rates[6 * arm + 4], rates[6 * arm + 5])
                .cross(&(at - pose.position));
        let n = (at - chassis).normalize();
        let compression = free_length - (at - chassis).norm();
        // The rig holds the wheel against the spring's push: F·δs = P·(−δL).
        let expected = -push(compression) * n.dot(&v);
        worst = worst.max((load - expected).abs() / expected.abs());
    }
    // Measured: 6.0e-11 relative.
    assert!(worst < 1e-9, "{worst:e}");
}

/// Every joint kind a general model takes builds the joint the core builds from the same geometry (a
/// point, a second point, axes from two points or a vector), on the right corner mirrored.
#[test]
fn every_joint_kind_builds_what_the_core_builds() {
    use elastokin_core::{BodyRef, JointSpec, Model, Pose};
    use elastokin_suspensions::assembly::CornerTemplate;
    use elastokin_suspensions::Side;
    let text = r#"{ "general": {
        "hardpoints": { "wheel_centre": [0, 0.8, 0], "a": [0.1, 0.6, 0.05], "b": [0.1, 0.5, 0.3],
                        "c": [-0.2, 0.55, 0.1], "top": [0, 0.75, 0.4], "bottom": [0, 0.78, -0.2] },
        "bodies": [ { "name": "upright", "at": "wheel_centre" } ],
        "joints": [
          { "name": "s", "kind": "spherical", "bodies": ["chassis", "upright"], "at": "a" },
          { "name": "r", "kind": "revolute", "bodies": ["chassis", "upright"], "at": "a", "axis": ["a", "b"] },
          { "name": "c", "kind": "cylindrical", "bodies": ["chassis", "upright"], "at": "b", "axis": [0, 0.3, 1] },
          { "name": "t", "kind": "translational", "bodies": ["chassis", "upright"], "at": "c", "axis": ["c", "a"] },
          { "name": "u", "kind": "universal", "bodies": ["chassis", "upright"], "at": "a", "axis": [1, 0, 0], "axis_j": [0, 1, 0] },
          { "name": "f", "kind": "fixed", "bodies": ["chassis", "upright"], "at": "c" },
          { "name": "d", "kind": "distance", "bodies": ["chassis", "upright"], "at": "a", "to": "c" },
          { "name": "p", "kind": "in_plane", "bodies": ["upright", "chassis"], "at": "b", "axis": [0, 0, 1], "to": "c" },
          { "name": "l", "kind": "in_line", "bodies": ["upright", "chassis"], "at": "b", "axis": ["a", "b"] },
          { "name": "x", "kind": "perpendicular", "bodies": ["chassis", "upright"], "axis": [1, 0, 0], "axis_j": [0, 0, 1] },
          { "name": "q", "kind": "parallel_axes", "bodies": ["chassis", "upright"], "axis": ["a", "c"] } ],
        "corner": { "upright": "upright", "wheel_centre": "wheel_centre",
                    "steering_axis": [ { "body": "upright", "at": "bottom" }, { "body": "upright", "at": "top" } ] } } }"#;
    let Template::General(g) = serde_json::from_str::<Template>(text).unwrap() else { panic!("general form") };
    let p = |n: &str| g.hardpoints.get(n).unwrap();
    for side in [Side::Left, Side::Right] {
        let mut built = Model::new();
        g.add_corner(&mut built, side, "").unwrap();
        let mut code = Model::new();
        let at = |v| side.place(v);
        let upright = code.add_body("upright", Pose::at(at(p("wheel_centre")))).unwrap();
        let (ground, u) = (BodyRef::Ground, BodyRef::from(upright));
        let v = |x: f64, y: f64, z: f64| side.place(nalgebra::Vector3::new(x, y, z));
        let specs = [
            JointSpec::spherical("s", ground, u, at(p("a"))),
            JointSpec::revolute("r", ground, u, at(p("a")), at(p("b")) - at(p("a"))),
            JointSpec::cylindrical("c", ground, u, at(p("b")), v(0.0, 0.3, 1.0)),
            JointSpec::translational("t", ground, u, at(p("c")), at(p("a")) - at(p("c"))),
            JointSpec::universal("u", ground, u, at(p("a")), v(1.0, 0.0, 0.0), v(0.0, 1.0, 0.0)),
            JointSpec::fixed("f", ground, u, at(p("c"))),
            JointSpec::distance("d", ground, u, at(p("a")), at(p("c"))),
            JointSpec {
                point_j: Some(at(p("c"))),
                ..JointSpec::in_plane("p", u, ground, at(p("b")), v(0.0, 0.0, 1.0))
            },
            JointSpec::in_line("l", u, ground, at(p("b")), at(p("b")) - at(p("a"))),
            JointSpec::perpendicular("x", ground, u, v(1.0, 0.0, 0.0), v(0.0, 0.0, 1.0)),
            JointSpec::parallel_axes("q", ground, u, at(p("c")) - at(p("a"))),
        ];
        for spec in specs {
            code.add_joint(spec).unwrap();
        }
        assert_eq!(built.joints(), code.joints(), "{side:?}");
    }
}

/// A wheel's centre and outward spin axis.
type WheelPose = (nalgebra::Vector3<f64>, nalgebra::Vector3<f64>);

/// The live axle of `examples/four_link_axle.json`, solved in the test by its own loop closure: the tube's
/// pose (translation and rotation vector about its reference point) such that the four links keep their
/// lengths (the right ones the left's mirror images) and the wheel centres are at the heights the rig asks
/// (`left`, `right` per unit travel). Returns both wheel centres and spin axes.
fn four_link_closure(
    file: &SuspensionFile,
    (left, right): (f64, f64),
) -> impl Fn(f64, &mut [f64; 6]) -> [WheelPose; 2] {
    use nalgebra::{DVector, Rotation3, Vector3};
    let Template::General(g) = &file.suspension else { panic!("the example is in the general form") };
    let p = |n: &str| g.hardpoints.get(n).unwrap();
    let centre = g.axle.as_ref().unwrap().hardpoints.get("axle_centre").unwrap();
    let mirror = |q: Vector3<f64>| Vector3::new(q.x, -q.y, q.z);
    let links: Vec<(Vector3<f64>, Vector3<f64>)> = ["lower_link", "upper_link"]
        .iter()
        .flat_map(|l| {
            let (c, a) = (p(&format!("{l}_chassis")), p(&format!("{l}_axle")));
            [(c, a), (mirror(c), mirror(a))]
        })
        .collect();
    let wc = p("wheel_centre");
    let moved = move |x: &[f64], q: Vector3<f64>| {
        centre + Vector3::new(x[0], x[1], x[2]) + Rotation3::new(Vector3::new(x[3], x[4], x[5])) * (q - centre)
    };
    move |t, x| {
        let residual = |x: &[f64; 6]| {
            let mut f: Vec<f64> = links.iter().map(|(c, a)| (moved(x, *a) - c).norm() - (a - c).norm()).collect();
            f.push(moved(x, wc).z - wc.z - left * t);
            f.push(moved(x, mirror(wc)).z - wc.z - right * t);
            DVector::from_vec(f)
        };
        common::newton_fd(residual, x);
        let turn = Rotation3::new(Vector3::new(x[3], x[4], x[5]));
        [(moved(x, wc), turn * Vector3::y()), (moved(x, mirror(wc)), turn * -Vector3::y())]
    }
}

/// The live axle in parallel and opposite travel: both wheels' centres, toe and camber against the
/// closure; the axle moves both wheels alike in the corner's parallel travel.
#[test]
fn four_link_axle_travel_and_roll_match_their_loop_closure() {
    use elastokin_solver::Mode;
    use elastokin_suspensions::analysis::axle_sweep;
    use elastokin_suspensions::{Axle, AxleRig};
    let file = example("four_link_axle.json");
    let toe_camber = |a: nalgebra::Vector3<f64>, s: f64| (a.x.atan2(s * a.y), (-a.z).atan2(a.x.hypot(a.y)));
    let mut worst_angle: f64 = 0.0;
    let mut worst_centre: f64 = 0.0;
    let mut moved: f64 = 0.0;
    for (rig, rates) in [(AxleRig::ParallelTravel, (1.0, 1.0)), (AxleRig::OppositeTravel, (1.0, -1.0))] {
        let axle = Axle::build(&file.suspension, rig).unwrap();
        let rows = axle_sweep(&axle, -0.06, 0.06, 12, Mode::Corrected).unwrap();
        let closure = four_link_closure(&file, rates);
        for half in [rows[6..].iter().collect::<Vec<_>>(), rows[..=6].iter().rev().collect()] {
            let mut guess = [0.0; 6];
            for row in half {
                let reference = closure(row.travel, &mut guess);
                for ((attitude, s), (centre, spin)) in [(row.left, 1.0), (row.right, -1.0)].into_iter().zip(reference) {
                    let (toe, camber) = toe_camber(spin, s);
                    worst_angle = worst_angle.max((attitude.toe - toe).abs()).max((attitude.camber - camber).abs());
                    worst_centre = worst_centre.max((attitude.wheel_centre - centre).amax());
                }
            }
        }
        // Content: the wheel centres move fore and aft in travel, the wheels camber and steer in roll.
        moved = moved.max((rows[0].left.wheel_centre.x - rows[12].left.wheel_centre.x).abs());
        if rig == AxleRig::OppositeTravel {
            assert!((rows[0].left.camber - rows[12].left.camber).abs() > 0.05);
            assert!((rows[0].left.toe - rows[12].left.toe).abs() > 1e-3);
        }
    }
    assert!(moved > 1e-3, "{moved} m");
    // Measured: 3.0e-13 rad and 3.5e-13 m.
    assert!(worst_angle < 3e-11 && worst_centre < 3e-11, "{worst_angle:e} rad, {worst_centre:e} m");
}

/// Mistakes in the axle section, or in the names across it, are refused by the item and the name.
#[test]
fn mistakes_in_an_axle_section_are_named() {
    let text = std::fs::read_to_string(example_path("four_link_axle.json")).unwrap();
    let base: serde_json::Value = serde_json::from_str(&text).unwrap();
    let cases: [Refusal; 7] = [
        (
            |v| v["suspension"]["general"]["axle"]["anti_roll_bar_springs"] = serde_json::json!(["bar"]),
            &["axle.anti_roll_bar_springs[0]", "no axle bushing 'bar'"],
        ),
        (
            |v| v["suspension"]["general"]["axle"]["bodies"][0]["name"] = "upright".into(),
            &["axle.bodies[0] (upright)", "a corner's body has this name"],
        ),
        (
            |v| v["suspension"]["general"]["axle"]["bodies"][0]["name"] = "left tube".into(),
            &["axle.bodies[0] (left tube)", "give the axle's body another name"],
        ),
        (
            |v| v["suspension"]["general"]["joints"][1]["bodies"][1] = "axle tub".into(),
            &["joints[1] (lower link)", "no body 'axle tub'", "'axle tube'"],
        ),
        (
            |v| {
                v["suspension"]["general"]["axle"]["joints"] = serde_json::json!([{ "name": "panhard rod",
                    "kind": "distance", "bodies": ["axle tube", "left hub"], "at": "axle_centre", "to": "left wheel_centre" }])
            },
            &["axle.joints[0] (panhard rod)", "no body 'left hub'", "\"left …\"", "'upright'"],
        ),
        (
            |v| {
                v["suspension"]["general"]["axle"]["joints"] = serde_json::json!([{ "name": "panhard rod",
                    "kind": "distance", "bodies": ["axle tube", "chassis"], "at": "axle_centre", "to": "middle" }])
            },
            &["axle.joints[0] (panhard rod).to", "no hardpoint 'middle'", "axle.hardpoints", "'axle_centre'"],
        ),
        (
            |v| {
                v["suspension"]["general"]["axle"]["steering_link"] =
                    serde_json::json!({ "body": "drag link", "inner": [0.5, 0.3, 0.3], "outer": "left wheel_top" })
            },
            &["axle.steering_link.body", "no body 'drag link'"],
        ),
    ];
    refused_as_said(&base, &cases);
}

/// The live axle with its lower links made bushings, so that the wheels give under load: a corner of a
/// solid axle loads both wheels alike, in phase, and its compliance matrix (the tangent, with the same unit
/// load on both wheel centres) equals finite differences of small constant loads put on both wheels by
/// `Corner::add_wheel_force_with_constant` and `Corner::add_wheel_torque` (a second method).
#[test]
fn a_solid_axles_compliance_is_finite_differences_of_in_phase_loads() {
    use elastokin_solver::{SolverOptions, StaticSolver};
    use elastokin_suspensions::analysis::wheel_compliance;
    use elastokin_suspensions::{Rig, Side};
    let text = std::fs::read_to_string(example_path("four_link_axle.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let g = &mut v["suspension"]["general"];
    g["joints"].as_array_mut().unwrap().retain(|j| j["name"] != "lower link");
    g["bushings"] = serde_json::json!([{ "name": "lower link bushing", "bodies": ["chassis", "axle tube"],
        "at": "lower_link_axle", "axis": ["lower_link_chassis", "lower_link_axle"],
        "radial": 2e6, "axial": 4e5, "torsion": 300, "conical": 2000 }]);
    let file = SuspensionFile::from_json(&v.to_string(), "bushed").unwrap();
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    assert!(corner.partner.is_some());
    let c = wheel_compliance(&corner, 0.0).unwrap();
    let response = |k: usize, size: f64| {
        let mut corner = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
        let mut unit = elastokin_core::Vec3::zeros();
        unit[k % 3] = size;
        let zero = elastokin_core::Vec3::zeros();
        if k < 3 {
            corner.add_wheel_force_with_constant("probe", corner.wheel.wheel_centre, zero, unit).unwrap();
        } else {
            // A constant torque: the load parameter also drives the wheel-travel drivers, held at zero here.
            let upright = corner.wheel.upright.into();
            let probe =
                elastokin_elements::PointTorque::new("probe", upright, zero).unwrap().with_constant(unit).unwrap();
            corner.model.add_element(probe).unwrap();
            let partner = corner.partner.unwrap().upright.into();
            let probe = elastokin_elements::PointTorque::new("right probe", partner, zero)
                .unwrap()
                .with_constant(unit)
                .unwrap();
            corner.model.add_element(probe).unwrap();
        }
        let options = SolverOptions { force_tolerance: 1e-13, ..SolverOptions::default() };
        let mut solver = StaticSolver::new(&corner.model, options).unwrap();
        let mut state = solver.design_state(0.0);
        solver.equilibrium(&mut state).unwrap();
        let pose = state.poses[corner.wheel.upright.0];
        (pose.point(&corner.wheel.wheel_centre_local), pose.orientation)
    };
    let scale = c.iter().flat_map(|row| row.iter()).fold(0.0f64, |a, v| a.max(v.abs()));
    let mut worst: f64 = 0.0;
    for k in 0..6 {
        let h = if k < 3 { 1.0 } else { 0.5 };
        let ((wp, qp), (wm, qm)) = (response(k, h), response(k, -h));
        let (dw, dq) = (wp - wm, (qp * qm.inverse()).scaled_axis());
        let diff = [dw.x, dw.y, dw.z, dq.x, dq.y, dq.z];
        for r in 0..6 {
            worst = worst.max((diff[r] / (2.0 * h) - c[r][k]).abs() / scale);
        }
    }
    // The wheel gives under load: the comparison has content (m/N).
    assert!(scale > 1e-7, "{scale:e}");
    // Measured: 1.6e-5 of the largest entry (4.6e-5 rad/(N·m), the axle's wind-up), the same with loads ten
    // times smaller: the tangent's own solve, whose entries that symmetry makes zero come out near 2e-10. With
    // the tangent's partner loads mirrored instead, 1.4e-2.
    assert!(worst < 1e-3, "{worst:e} of the largest entry");
}

/// The model's own load case on a solid axle acts on both sides: 1000 N up at each contact patch (the right
/// the left's mirror image; the patch is 0.31 m below the wheel centre), with the wheels free and carrying
/// the vehicle's corner load there, lands the wheel where the vertical-force analysis (a force at both
/// patches alike) puts it under the same total, 5200 N. On the left wheel alone, the axle would roll and
/// the wheel centre land elsewhere.
#[test]
fn a_solid_axles_own_load_case_acts_on_both_sides() {
    use elastokin_suspensions::kc::Analysis;
    let text = std::fs::read_to_string(example_path("four_link_axle.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["suspension"]["general"]["loads"] = serde_json::json!([{ "name": "lift", "body": "upright", "at": [0.0, 0.75, -0.01], "force": [0.0, 0.0, 1000.0] }]);
    let file = SuspensionFile::from_json(&v.to_string(), "loaded").unwrap();
    assert_eq!(file.vehicle.as_ref().unwrap().corner_load, 4200.0);
    let z = |analysis: Analysis, range: (f64, f64)| {
        let settings = Settings { range: Some(range), steps: 4, height_held: false, ..Settings::default() };
        let report = kc::run_suite(&file, &[analysis], &settings, |_| {}).complete().unwrap();
        let table = &report.analyses[0].table;
        let column = table.columns.iter().position(|c| c == "wheel_centre_z_m" || c == "wheel_travel_m").unwrap();
        table.rows.last().unwrap()[column].number().unwrap()
    };
    let design_z = 0.30;
    let by_loads = z(Analysis::ModelLoads, (0.0, 1.0)) - design_z;
    let by_force = z(Analysis::VerticalForce, (4200.0, 5200.0));
    // The wheel rises by centimetres: the comparison has content.
    assert!(by_loads > 0.01, "{by_loads} m");
    // Measured: 5.6e-17 m (with the load case on the left only, 2.4e-3 m).
    assert!((by_loads - by_force).abs() < 5e-15, "{by_loads} m by the load case, {by_force} m by the vertical force");
    // And against virtual work on the tube's loop closure, independent of the engine: the travel t where
    // the springs' work balances the 5200 N at each patch, k (L₀ − L) (−dL/dt) = 5200 dz_patch/dt, with the
    // spring's design push 4200 N at rate 30 kN/m.
    let closure = four_link_closure(&file, (1.0, 1.0));
    let Template::General(g) = &file.suspension else { panic!("general form") };
    let centre = g.axle.as_ref().unwrap().hardpoints.get("axle_centre").unwrap();
    let (seat_chassis, seat_axle) =
        (g.hardpoints.get("spring_chassis").unwrap(), g.hardpoints.get("spring_axle").unwrap());
    let patch = nalgebra::Vector3::new(0.0, 0.75, -0.01);
    let (rate, design_push) = (30000.0, 4200.0);
    let free_length = (seat_axle - seat_chassis).norm() + design_push / rate;
    let pose = |t: f64| {
        let mut x = [0.0; 6];
        closure(t, &mut x);
        let moved = |q: nalgebra::Vector3<f64>| {
            centre
                + nalgebra::Vector3::new(x[0], x[1], x[2])
                + nalgebra::Rotation3::new(nalgebra::Vector3::new(x[3], x[4], x[5])) * (q - centre)
        };
        ((moved(seat_axle) - seat_chassis).norm(), moved(patch).z)
    };
    let balance = |t: f64| {
        let h = 1e-6;
        let ((l_plus, z_plus), (l_minus, z_minus), (l, _)) = (pose(t + h), pose(t - h), pose(t));
        rate * (free_length - l) * -(l_plus - l_minus) / (2.0 * h) - 5200.0 * (z_plus - z_minus) / (2.0 * h)
    };
    let (mut a, mut b) = (0.0, 0.06);
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        if balance(a) * balance(m) <= 0.0 {
            b = m;
        } else {
            a = m;
        }
    }
    let by_work = 0.5 * (a + b);
    // Measured: 1.2e-12 m of a 33.4 mm rise (the closure's central differences and bisection).
    assert!((by_loads - by_work).abs() < 1e-10, "{by_loads} m by the load case, {by_work} m by virtual work");
}

/// Every joint kind, as the core declares it once (`JointKind::all`, `JointKind::geometry`): a kind a model
/// file takes builds from exactly the geometry it declares, is refused without a piece it needs or with
/// one it does not use, joins two bodies of a model, and is drawn at its point when it has one; a driver
/// (the rig's) is refused. A kind added to the core without its geometry, or with a geometry the builder
/// does not read, fails here.
#[test]
fn every_joint_kind_builds_from_the_geometry_it_declares_and_is_drawn_as_it_says() {
    use elastokin_core::{BodyRef, JointKind, Model, Pose, Takes, Vec3};
    use elastokin_suspensions::assembly::general::{joint_spec, JointGeometry};
    use elastokin_suspensions::drawing::Drawing;
    let full = JointGeometry {
        at: Some(Vec3::new(0.1, 0.2, 0.3)),
        to: Some(Vec3::new(0.4, 0.2, 0.3)),
        axis: Some(Vec3::x()),
        axis_j: Some(Vec3::y()),
    };
    let mut kinds = 0;
    for kind in JointKind::all() {
        kinds += 1;
        let taken = kind.geometry();
        let pieces = [taken.point, taken.point_j, taken.axis, taken.axis_j];
        let with = |keep: [bool; 4]| JointGeometry {
            at: full.at.filter(|_| keep[0]),
            to: full.to.filter(|_| keep[1]),
            axis: full.axis.filter(|_| keep[2]),
            axis_j: full.axis_j.filter(|_| keep[3]),
        };
        let mut model = Model::new();
        let a = model.add_body("a", Pose::at(Vec3::new(0.1, 0.2, 0.3))).unwrap();
        let b = model.add_body("b", Pose::at(Vec3::new(0.4, 0.2, 0.3))).unwrap();
        let bodies = [BodyRef::from(a), BodyRef::from(b)];
        let needed = pieces.map(|p| p == Takes::Needed);
        let built = joint_spec("joints[0]", "j", kind, bodies, &with(needed));
        if kind.is_driver() {
            let e = built.unwrap_err().to_string();
            assert!(e.contains("a driver is the rig's"), "{kind:?}: {e}");
            continue;
        }
        let spec = built.unwrap_or_else(|e| panic!("{kind:?}: {e}"));
        assert_eq!(spec.kind, kind);
        model.add_joint(spec).unwrap_or_else(|e| panic!("{kind:?}: {e}"));
        for (k, takes) in pieces.iter().enumerate() {
            let mut keep = needed;
            keep[k] = !keep[k];
            let e = joint_spec("joints[0]", "j", kind, bodies, &with(keep)).err().map(|e| e.to_string());
            match takes {
                Takes::Needed => assert!(e.as_ref().is_some_and(|e| e.contains("needs")), "{kind:?} {k}: {e:?}"),
                Takes::Unused => {
                    assert!(e.as_ref().is_some_and(|e| e.contains("means nothing")), "{kind:?} {k}: {e:?}")
                }
                Takes::Optional => assert!(e.is_none(), "{kind:?} {k}: {e:?}"),
            }
        }
        let drawn = Drawing::of(&model, &[]).joints.iter().any(|j| j.name == "j");
        assert_eq!(drawn, kind.has_place(), "{kind:?}");
    }
    assert_eq!(kinds, 13);
}

/// The geometry each joint kind declares (`JointKind::geometry`) is what the model file's documentation
/// says it takes: `docs/model-file.md`'s joint table lists every kind a file may use with its keys, a key
/// after "optional" taken if given.
#[test]
fn every_joint_kind_takes_the_keys_its_documentation_lists() {
    use elastokin_core::{JointKind, Takes};
    let docs = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/model-file.md")).unwrap();
    let mut documented = 0;
    for kind in JointKind::all().filter(|k| !k.is_driver()) {
        let word = serde_json::to_value(kind).unwrap().as_str().unwrap().to_string();
        let row = docs.lines().find(|l| l.starts_with(&format!("| `{word}` |"))).unwrap_or_else(|| panic!("{word}"));
        let keys = row.split('|').nth(2).unwrap();
        let takes = |key: &str| {
            let at = keys.find(&format!("`{key}`"));
            match at {
                None => Takes::Unused,
                Some(i) if keys[..i].trim_end().ends_with("optional") => Takes::Optional,
                Some(_) => Takes::Needed,
            }
        };
        let g = kind.geometry();
        assert_eq!([g.point, g.point_j, g.axis, g.axis_j], ["at", "to", "axis", "axis_j"].map(takes), "{word}: {row}");
        documented += 1;
    }
    assert_eq!(documented, 11);
}

/// The element kinds a model file takes, corner and axle alike, in the order a written file lists them.
const ELEMENT_KINDS: [&str; 5] = ["bushings", "fields", "beams", "springs", "stops"];

/// An entry of the element kind `kind` named `name`, between `bodies`, from `from` to `to` (a bushing or
/// a field at `to`): what each kind needs to build.
fn element_entry(kind: &str, name: &str, bodies: [&str; 2], from: serde_json::Value, to: &str) -> serde_json::Value {
    use serde_json::json;
    let diagonal: Vec<Vec<f64>> = (0..6)
        .map(|r| {
            (0..6)
                .map(|c| {
                    if r != c {
                        0.0
                    } else if r < 3 {
                        1e6
                    } else {
                        1e3
                    }
                })
                .collect()
        })
        .collect();
    match kind {
        "bushings" => json!({ "name": name, "bodies": bodies, "at": to, "axis": [0.0, 0.0, 1.0],
            "radial": 1e6, "axial": 1e5, "torsion": 100.0, "conical": 1000.0 }),
        "fields" => json!({ "name": name, "bodies": bodies, "at": to, "stiffness": diagonal }),
        "beams" => json!({ "name": name, "bodies": bodies, "from": from, "to": to, "y_axis": [1.0, 0.0, 0.0],
            "section": { "youngs_modulus": 2.1e11, "shear_modulus": 8.1e10, "area": 1e-4, "iy": 1e-9, "iz": 1e-9,
                         "j": 2e-9 } }),
        "springs" => json!({ "name": name, "bodies": bodies, "from": from, "to": to, "rate": 20000.0,
            "design_force": 500.0 }),
        "stops" => json!({ "name": name, "kind": "bump", "bodies": bodies, "from": from, "to": to,
            "clearance": 0.05, "curve": [[0.0, 0.0], [0.01, 1000.0]] }),
        other => panic!("no entry of the kind '{other}' is written here: add one"),
    }
}

/// The names of the entries of `list` (a kind's list in a model file).
fn entry_names(list: &serde_json::Value) -> Vec<String> {
    let entries = list.as_array().map(Vec::as_slice).unwrap_or_default();
    entries.iter().map(|e| e["name"].as_str().unwrap().to_string()).collect()
}

/// The live axle with an entry of every element kind added to its corner and to its axle section: each
/// reads, is written back under its kind's key in its place, builds into its element (the corner's on
/// each side, the axle's once) found in the build map under its key, and a mistake in it is named by that
/// key (the axle's under `axle.`). The kinds are this test's own list: one declared in `ElementLists`
/// and not here, or one the builder or the build map leaves out, fails here.
#[test]
fn every_element_kind_reads_writes_builds_and_is_mapped_in_a_corner_and_in_an_axle() {
    use elastokin_suspensions::description::general::ElementLists;
    use elastokin_suspensions::{Axle, AxleRig};
    assert_eq!(ElementLists::KINDS, ELEMENT_KINDS, "the declared element kinds are the ones this test writes");
    let text = std::fs::read_to_string(example_path("four_link_axle.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let g = &mut v["suspension"]["general"];
    let push = |list: &mut serde_json::Value, entry: serde_json::Value| match list.as_array_mut() {
        Some(entries) => entries.push(entry),
        None => *list = serde_json::json!([entry]),
    };
    for kind in ELEMENT_KINDS {
        let bodies = ["chassis", "axle tube"];
        let corner = element_entry(kind, &format!("corner {kind}"), bodies, "spring_chassis".into(), "spring_axle");
        push(&mut g[kind], corner);
        let axle =
            element_entry(kind, &format!("axle {kind}"), bodies, serde_json::json!([0.2, 0.0, 0.6]), "axle_centre");
        push(&mut g["axle"][kind], axle);
    }
    let file = SuspensionFile::from_json(&v.to_string(), "every kind").unwrap();
    let written: serde_json::Value = serde_json::from_str(&file.to_json()).unwrap();
    let (general, axle) = (&v["suspension"]["general"], &v["suspension"]["general"]["axle"]);
    let keys = |section: &serde_json::Value| -> Vec<String> { section.as_object().unwrap().keys().cloned().collect() };
    let corner_keys = ["hardpoints", "bodies", "joints"].into_iter().chain(ELEMENT_KINDS);
    let corner_keys: Vec<&str> = corner_keys.chain(["anti_roll_bars", "axle", "corner"]).collect();
    assert_eq!(keys(&written["suspension"]["general"]), corner_keys);
    let axle_keys: Vec<&str> = ["hardpoints", "bodies"].into_iter().chain(ELEMENT_KINDS).collect();
    assert_eq!(keys(&written["suspension"]["general"]["axle"]), axle_keys);
    for kind in ELEMENT_KINDS {
        assert_eq!(entry_names(&written["suspension"]["general"][kind]), entry_names(&general[kind]), "{kind}");
        assert_eq!(
            entry_names(&written["suspension"]["general"]["axle"][kind]),
            entry_names(&axle[kind]),
            "axle.{kind}"
        );
    }
    // Built: every entry is one element on each side (the corner's) or once (the axle's), under its key.
    let built = Axle::build(&file.suspension, AxleRig::ParallelTravel).unwrap();
    let count = |name: &str| built.model.elements().iter().filter(|e| e.name() == name).count();
    let Template::General(described) = &file.suspension else { panic!("general form") };
    let map = built.build_map(described);
    let element_names = |key: &str| -> Vec<Vec<&str>> {
        let items = map.find(key).map(|b| b.elements.iter().map(|e| built.model.elements()[e.0].name()).collect());
        items.collect()
    };
    let mut entries = 0;
    for kind in ELEMENT_KINDS {
        for (k, name) in entry_names(&general[kind]).iter().enumerate() {
            for side in ["left", "right"] {
                assert_eq!(count(&format!("{side} {name}")), 1, "{side} {kind}[{k}] ({name})");
            }
            let expected = vec![vec![format!("left {name}")], vec![format!("right {name}")]];
            assert_eq!(element_names(&format!("{kind}[{k}]")), expected, "{kind}[{k}]");
            entries += 1;
        }
        for (k, name) in entry_names(&axle[kind]).iter().enumerate() {
            assert_eq!(count(name), 1, "axle.{kind}[{k}] ({name})");
            assert_eq!(element_names(&format!("axle.{kind}[{k}]")), vec![vec![name.as_str()]], "axle.{kind}[{k}]");
            entries += 1;
        }
    }
    // The example's spring and the ten added.
    assert_eq!(entries, 11);
    // A mistake in an entry is named by its key.
    for kind in ELEMENT_KINDS {
        for under in ["", "axle."] {
            let mut edited = v.clone();
            let section = &mut edited["suspension"]["general"];
            let list = if under.is_empty() { &mut section[kind] } else { &mut section["axle"][kind] };
            let k = list.as_array().unwrap().len() - 1;
            let name = list[k]["name"].as_str().unwrap().to_string();
            list[k]["bodies"][1] = "no such body".into();
            let err = SuspensionFile::from_json(&edited.to_string(), "edited").unwrap_err().to_string();
            let key = format!("{under}{kind}[{k}] ({name}).bodies");
            assert!(err.contains(&key) && err.contains("no body 'no such body'"), "'{key}' not in: {err}");
        }
    }
}
