//! The twist-beam axle against mechanics written here: roll stiffness and the cross member's twist of a
//! simple geometry against their closed form (`docs/twist-beam.md`), and the shipped example's every
//! analysis, its right side the mirror of its left, every row within its error estimate; the template
//! builds what the general example describes, and refuses a cross member that misses its arms.

use elastokin_suspensions::kc::{self, Analysis, Settings};
use elastokin_suspensions::{Rig, Side, SuspensionFile};
use serde_json::json;

/// The simple geometry of `docs/twist-beam.md`: each arm pivots on an ideal hinge across the car at
/// `(a, ±y_p, z)`, runs straight back to its wheel carrier at `(0, ±y_p, z)`, the wheel centre `dy`
/// further out; the cross member joins the two arm eyes along the hinge axis.
struct Simple {
    a: f64,
    y_p: f64,
    dy: f64,
    /// Cross member: G·J (N·m²).
    cross_j: f64,
    /// Arm: E·I about its horizontal axis, G·J (N·m²).
    arm_ei: f64,
    arm_gj: f64,
    segments: usize,
}

const E: f64 = 210e9;
const G: f64 = 80e9;

impl Simple {
    fn file(&self) -> SuspensionFile {
        let z = 0.3;
        let section = |ei: f64, gj: f64| json!({ "youngs_modulus": E, "shear_modulus": G, "area": 1e-3, "iy": ei / E, "iz": 2.0 * ei / E, "j": gj / G });
        let doc = json!({
            "name": "twist beam on ideal hinges",
            "suspension": { "general": {
                "hardpoints": {
                    "wheel_centre": [0.0, self.y_p + self.dy, z],
                    "wheel_top": [0.0, self.y_p + self.dy, z + 0.1],
                    "pivot": [self.a, self.y_p, z],
                    "arm_end": [0.0, self.y_p, z]
                },
                "bodies": [ { "name": "arm eye", "at": "pivot" }, { "name": "carrier", "at": "wheel_centre" } ],
                "joints": [ { "name": "hinge", "kind": "revolute", "bodies": ["chassis", "arm eye"], "at": "pivot",
                              "axis": [0, 1, 0] } ],
                "beams": [ { "name": "arm", "bodies": ["arm eye", "carrier"], "from": "pivot", "to": "arm_end",
                             "y_axis": [0, 1, 0], "section": section(self.arm_ei, self.arm_gj) } ],
                "axle": { "bodies": [], "beams": [ {
                    "name": "cross member", "bodies": ["left arm eye", "right arm eye"],
                    "from": "left pivot", "to": "right pivot", "y_axis": [1, 0, 0], "segments": self.segments,
                    "section": section(1e6, self.cross_j) } ] },
                "corner": { "upright": "carrier", "wheel_centre": "wheel_centre", "loaded_radius": 0.3,
                            "steering_axis": [ { "body": "carrier", "at": "wheel_centre" },
                                               { "body": "carrier", "at": "wheel_top" } ] }
            } }
        });
        SuspensionFile::from_json(&doc.to_string(), "twist beam").unwrap_or_else(|e| panic!("{e}"))
    }

    /// Wheel-centre travel per newton of opposite vertical wheel forces: the cross member's torsion under
    /// the moment F·a, the arm's bending as a cantilever, and the arm's torsion under F·dy.
    fn compliance(&self) -> f64 {
        let l = 2.0 * self.y_p;
        self.a * self.a * l / (2.0 * self.cross_j)
            + self.a.powi(3) / (3.0 * self.arm_ei)
            + self.dy * self.dy * self.a / self.arm_gj
    }
}

fn figure(report: &kc::AnalysisReport, key: &str) -> f64 {
    let f = report.figures.iter().find(|f| f.key == key).unwrap_or_else(|| panic!("no figure {key}"));
    f.value.unwrap_or_else(|| panic!("{key}: {:?}", f.reason))
}

#[test]
fn roll_stiffness_and_twist_of_a_simple_twist_beam_equal_the_closed_form() {
    // The figures are rates at design, the closed form's linear statics (measured 6.2e-12 apart at most).
    let settings = Settings::default();
    let mut worst = (0.0_f64, 0.0_f64);
    for (cross_j, arm_ei, arm_gj, segments) in
        [(2400.0, 1.5e5, 6.0e4, 1), (2400.0, 1.5e5, 6.0e4, 5), (9000.0, 4.0e4, 2.0e4, 3), (800.0, 1e7, 1e7, 2)]
    {
        let s = Simple { a: 0.45, y_p: 0.55, dy: 0.2, cross_j, arm_ei, arm_gj, segments };
        let report = kc::run(Analysis::Roll, &s.file(), &settings).unwrap_or_else(|e| panic!("{e}"));
        let c = s.compliance();
        let y_w = s.y_p + s.dy;
        // Opposite forces ±F at ±y_w: the moment 2·y_w·F rolls the axle by F·c / y_w.
        let roll_stiffness = 2.0 * y_w * y_w / c; // N·m/rad
        let got = figure(&report, "roll_stiffness");
        // The cross member twists by 2θ, θ = F·a·L / (2 G J), while the axle rolls by F·c / y_w; its twist
        // (about its direction, left to right) is positive as the left wheel rises, when the roll is negative.
        let twist_per_roll = -s.a * 2.0 * s.y_p * y_w / (cross_j * c);
        let twist = figure(&report, "cross_member_twist_per_roll");
        let errors = ((got / roll_stiffness - 1.0).abs(), (twist / twist_per_roll - 1.0).abs());
        println!("{cross_j} {arm_ei} {arm_gj} {segments}: roll stiffness {got} against {roll_stiffness} N·m/rad, twist {twist} against {twist_per_roll}: {:e} {:e}", errors.0, errors.1);
        worst = (worst.0.max(errors.0), worst.1.max(errors.1));
    }
    assert!(worst.0 < 1e-10 && worst.1 < 1e-10, "{:e} {:e}", worst.0, worst.1);
}

fn example() -> SuspensionFile {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/twist_beam.json");
    SuspensionFile::read(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn the_shipped_twist_beam_runs_every_analysis_and_its_right_side_mirrors_its_left() {
    let file = example();
    let suite = kc::run_suite(&file, &[], &Settings::default(), |_| {});
    for a in &suite.analyses {
        for f in &a.figures {
            assert!(f.value.is_some() || f.reason.is_some(), "{}: {}", a.analysis.name(), f.key);
        }
    }
    assert!(suite.failed.is_empty(), "{:?}", suite.failed);
    // Every analysis but steering (a rear axle's toe is held by its own parts), the load case and the wheel
    // envelope (it has neither loads nor packaging).
    assert_eq!(suite.analyses.len(), kc::ALL.len() - 3);
    let roll = suite.analyses.iter().find(|a| a.analysis == Analysis::Roll).expect("roll ran");
    let col = |name: &str| -> Vec<f64> {
        let c = roll.table.columns.iter().position(|x| x == name).unwrap_or_else(|| panic!("no column {name}"));
        roll.table.rows.iter().map(|r| r[c].number().unwrap()).collect()
    };
    // Opposite travel turned end for end is the mirror image: the right wheel's toe at −t is the left's at t,
    // and the cross member twists the other way.
    let (left, right, twist) = (col("left_toe_deg"), col("right_toe_deg"), col("cross_member_twist_deg"));
    let n = left.len() - 1;
    let toe = (0..=n).map(|k| (left[k] - right[n - k]).abs()).fold(0.0, f64::max);
    let turned = (0..=n).map(|k| (twist[k] + twist[n - k]).abs()).fold(0.0, f64::max);
    println!("left toe against mirrored right: {toe:e} deg; twist against its turned self: {turned:e} deg");
    // Measured 3.1e-14 and 2.0e-14 deg.
    assert!(toe < 1e-12 && turned < 1e-12, "{toe:e} {turned:e}");
    // The cross member carries the roll: it twists more than the body rolls (the arms are shorter than
    // the half track), the other way.
    assert!(figure(roll, "cross_member_twist_per_roll") < -1.0);
}

fn template() -> SuspensionFile {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/twist_beam_template.json");
    SuspensionFile::read(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn the_template_builds_the_axle_the_general_example_describes() {
    // examples/twist_beam_template.json is examples/twist_beam.json's axle as the template; the general
    // file gives the wheel's spin axis of 0.1° toe-in and 1° negative camber to ten digits.
    let (t, g) = (template(), example());
    let settings = Settings::default();
    let (a, b) = (kc::run_suite(&t, &[], &settings, |_| {}), kc::run_suite(&g, &[], &settings, |_| {}));
    assert_eq!(a.analyses.len(), b.analyses.len());
    let mut worst = 0.0f64;
    for (x, y) in a.analyses.iter().zip(&b.analyses) {
        assert_eq!(x.analysis, y.analysis);
        for (f, h) in x.figures.iter().zip(&y.figures) {
            assert_eq!((&f.key, f.value.is_some()), (&h.key, h.value.is_some()), "{}", x.analysis.name());
            if let (Some(u), Some(v)) = (f.value, h.value) {
                worst = worst.max((u - v).abs() / (1.0 + v.abs()));
            }
        }
    }
    println!("template against general form: {worst:e}");
    // Measured 2.9e-9: the spin axis's tenth digit.
    assert!(worst < 1e-8, "{worst:e}");
    // The static toe and camber are the template's: the built wheel's at the design poses.
    let built = t.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let at = built.wheel.attitude(&built.model.design_poses());
    let (toe, camber) = (at.toe.to_degrees(), at.camber.to_degrees());
    println!("toe {toe} deg, camber {camber} deg as built");
    // Measured 1.4e-15 and 2.2e-16 deg.
    assert!((toe - 0.1).abs() < 1e-13 && (camber + 1.0).abs() < 1e-13, "{toe} {camber}");
}

/// Why a twist-beam template edited at `edits` (JSON pointer, value) is refused: by the reading, which
/// builds the model, or else by an analysis.
fn refusal(edits: &[(String, serde_json::Value)]) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/twist_beam_template.json");
    let mut doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    for (pointer, value) in edits {
        *doc.pointer_mut(pointer).unwrap() = value.clone();
    }
    match SuspensionFile::from_json(&doc.to_string(), "edited") {
        Err(e) => e.to_string(),
        Ok(file) => kc::run(Analysis::ParallelTravel, &file, &Settings::default()).expect_err("refused").to_string(),
    }
}

#[test]
fn a_twist_beam_whose_cross_member_misses_its_arms_is_refused_by_key() {
    let h = "/suspension/twist_beam/hardpoints";
    let junction = format!("{h}/junction");
    let cases = [
        // Ahead of the pivot, and 150 mm inboard of the arm.
        (vec![(junction.clone(), json!([0.60, 0.60, 0.31]))], "hardpoints.junction", "does not meet the arm"),
        (vec![(junction.clone(), json!([0.20, 0.45, 0.31]))], "hardpoints.junction", "does not meet the arm"),
        // The left side drawn across the centre plane.
        (
            ["pivot", "junction", "arm_end"].map(|k| (format!("{h}/{k}/1"), json!(0.02))).to_vec(),
            "hardpoints.junction",
            "centre plane",
        ),
        (vec![("/suspension/twist_beam/toe".to_string(), json!(15.0))], "toe", "within ±10"),
    ];
    for (edits, key, says) in cases {
        let message = refusal(&edits);
        println!("{message}");
        assert!(message.contains(key) && message.contains(says), "{message}");
    }
}

#[test]
fn every_analysis_of_the_twist_beam_is_within_its_error_estimate_and_converges_with_the_steps() {
    use elastokin_solver::Mode;
    let file = example();
    let (mut worst_ratio, mut worst_corrected) = (0.0f64, 0.0f64);
    for analysis in kc::ALL {
        if kc::left_out(&file, analysis).is_some() || analysis == Analysis::StaticLoad {
            continue;
        }
        let run = |mode: Mode, steps: usize| {
            let settings = Settings { mode, steps, ..Settings::default() };
            kc::run(analysis, &file, &settings).unwrap_or_else(|e| panic!("{}: {e}", analysis.name()))
        };
        let reference = run(Mode::Corrected, 128);
        // The largest difference of the angle columns from the reference's rows at the same load parameters.
        let off = |report: &kc::AnalysisReport, steps: usize| {
            let stride = 128 / steps;
            let angles: Vec<usize> =
                (0..reference.table.columns.len()).filter(|&c| reference.table.columns[c].ends_with("_deg")).collect();
            let mut error = 0.0f64;
            for (k, row) in report.table.rows.iter().enumerate() {
                for &c in &angles {
                    if let (Some(a), Some(b)) = (row[c].number(), reference.table.rows[k * stride][c].number()) {
                        error = error.max((a - b).abs());
                    }
                }
            }
            error
        };
        // Corrected rows are equilibria at any step: 32 steps land on the 128-step rows.
        let corrected = run(Mode::Corrected, 32);
        let (error, estimate) =
            (off(&corrected, 32), corrected.accuracy.angle_error_deg + reference.accuracy.angle_error_deg);
        println!("{} corrected: {error:e} deg against its estimate {estimate:e}", analysis.name());
        worst_corrected = worst_corrected.max(error);
        // Within the two rows' estimates summed (measured up to 1.0 times them, vertical force): twice that.
        assert!(error <= 2.0 * estimate.max(1e-12), "{}: {error:e} over {estimate:e}", analysis.name());
        // The paper's linear steps drift in proportion to the step; their estimate says how far.
        let mut errors = Vec::new();
        for steps in [32, 128] {
            let paper = run(Mode::Paper, steps);
            let (error, estimate) = (off(&paper, steps), paper.accuracy.angle_error_deg);
            println!("{} paper {steps} steps: {error:e} deg, estimated {estimate:e}", analysis.name());
            worst_ratio = worst_ratio.max(error / estimate.max(1e-15));
            errors.push(error);
        }
        assert!(errors[1] < errors[0], "{}: {errors:?}", analysis.name());
    }
    println!(
        "corrected rows off by {worst_corrected:e} deg; paper rows off by at most {worst_ratio} times their estimate"
    );
    // Measured 3.6 (vertical force at 32 steps, where the drift is far from linear); 1.0 elsewhere.
    assert!(worst_ratio < 10.0, "{worst_ratio}");
}

/// The shipped twist beam without its springs, by a second method written here: a linear frame analysis
/// (the textbook 12×12 Euler–Bernoulli element, its bending taken on the shear-centre line; each pivot
/// bushing a 6×6 spring to the ground; each part a rigid node at its reference point), the wheel centres
/// driven ±h; with `rigid_bushings`, each arm eye held still instead of on its bushing. Returns the roll
/// stiffness (N·m/rad), the cross member's twist per roll (rad/rad) and the left wheel's roll steer
/// (rad/rad).
fn linear_frame(file: &SuspensionFile, rigid_bushings: bool) -> (f64, f64, f64) {
    use nalgebra::{DMatrix, DVector, Matrix3, SMatrix, Vector3};
    type Mat12 = SMatrix<f64, 12, 12>;
    let elastokin_suspensions::description::Template::General(g) = &file.suspension else { panic!("general") };
    let hp = |name: &str, s: f64| {
        let p = g.hardpoints.0.iter().find(|(n, _)| n == name).unwrap().1;
        Vector3::new(p.x, s * p.y, p.z)
    };
    let skew = |r: Vector3<f64>| Matrix3::new(0.0, -r.z, r.y, r.z, 0.0, -r.x, -r.y, r.x, 0.0);
    // Bodies: per side arm eye, arm, wheel carrier; then the cross member's nodes.
    let segments = g.axle.as_ref().unwrap().beams[0].segments.unwrap();
    let side_body = |s: usize, k: usize| 3 * s + k; // s: 0 left, 1 right; k: 0 eye, 1 arm, 2 carrier
    let node = |k: usize| 6 + k - 1; // k = 1 .. segments − 1
    let n = 6 * (6 + segments - 1);
    let mut reference = vec![Vector3::zeros(); n / 6];
    for (s, sign) in [(0, 1.0), (1, -1.0)] {
        reference[side_body(s, 0)] = hp("pivot", sign);
        reference[side_body(s, 1)] = hp("junction", sign);
        reference[side_body(s, 2)] = hp("wheel_centre", sign);
    }
    let (jl, jr) = (hp("junction", 1.0), hp("junction", -1.0));
    for k in 1..segments {
        reference[node(k)] = jl + (jr - jl) * (k as f64 / segments as f64);
    }
    let mut big_k = DMatrix::<f64>::zeros(n, n);
    // A 12×12 element stiffness between point `a` of body `bi` and point `b` of body `bj` (None: ground).
    let mut add = |k: &Mat12, bi: Option<usize>, a: Vector3<f64>, bj: Option<usize>, b: Vector3<f64>| {
        let mut t = [SMatrix::<f64, 6, 6>::identity(), SMatrix::<f64, 6, 6>::identity()];
        for (ti, (body, p)) in t.iter_mut().zip([(bi, a), (bj, b)]) {
            if let Some(body) = body {
                // A point's motion from its body's: u + θ × r.
                ti.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-skew(p - reference[body])));
            }
        }
        for (e1, b1) in [(0, bi), (1, bj)] {
            for (e2, b2) in [(0, bi), (1, bj)] {
                let (Some(b1), Some(b2)) = (b1, b2) else { continue };
                let block = t[e1].transpose() * k.fixed_view::<6, 6>(6 * e1, 6 * e2) * t[e2];
                let mut target = big_k.view_mut((6 * b1, 6 * b2), (6, 6));
                target += block;
            }
        }
    };
    let rotate = |k: &Mat12, r: &Matrix3<f64>| {
        let mut big = Mat12::zeros();
        for q in 0..4 {
            big.fixed_view_mut::<3, 3>(3 * q, 3 * q).copy_from(r);
        }
        big * k * big.transpose()
    };
    // The textbook element, local axes x along the beam, y and z the section's.
    let frame = |d: &elastokin_suspensions::description::general::SectionDef, l: f64| {
        let (e, gm) = (d.youngs_modulus, d.shear_modulus);
        let mut k = Mat12::zeros();
        let mut put = |dofs: [usize; 2], m: [[f64; 2]; 2]| {
            for a in 0..2 {
                for b in 0..2 {
                    k[(dofs[a], dofs[b])] += m[a][b];
                }
            }
        };
        let axial = e * d.area / l;
        put([0, 6], [[axial, -axial], [-axial, axial]]);
        let torsion = gm * d.j / l;
        put([3, 9], [[torsion, -torsion], [-torsion, torsion]]);
        let bend = |k: &mut Mat12, ei: f64, dofs: [usize; 4], s: f64| {
            let c = ei / l.powi(3);
            let m = [
                [12.0, s * 6.0 * l, -12.0, s * 6.0 * l],
                [s * 6.0 * l, 4.0 * l * l, -s * 6.0 * l, 2.0 * l * l],
                [-12.0, -s * 6.0 * l, 12.0, -s * 6.0 * l],
                [s * 6.0 * l, 2.0 * l * l, -s * 6.0 * l, 4.0 * l * l],
            ];
            for a in 0..4 {
                for b in 0..4 {
                    k[(dofs[a], dofs[b])] += c * m[a][b];
                }
            }
        };
        bend(&mut k, e * d.iz, [1, 5, 7, 11], 1.0);
        bend(&mut k, e * d.iy, [2, 4, 8, 10], -1.0);
        // Bending on the shear-centre line: its points move by v − e_z θx, w + e_y θx at each end.
        let [ey, ez] = d.shear_centre.unwrap_or([0.0, 0.0]);
        let mut t = Mat12::identity();
        for end in [0, 6] {
            t[(end + 1, end + 3)] = -ez;
            t[(end + 2, end + 3)] = ey;
        }
        t.transpose() * k * t
    };
    let beam = |from: Vector3<f64>, to: Vector3<f64>, y: Vector3<f64>, d| {
        let x = (to - from).normalize();
        let y = (y - x * x.dot(&y)).normalize();
        let r = Matrix3::from_columns(&[x, y, x.cross(&y)]);
        rotate(&frame(d, (to - from).norm()), &r)
    };
    let arms = g.beams.iter().find(|b| b.name == "arm front").unwrap().section;
    for (s, sign) in [(0, 1.0), (1, -1.0)] {
        let lateral = Vector3::new(0.0, sign, 0.0);
        let (pivot, junction, arm_end) = (hp("pivot", sign), hp("junction", sign), hp("arm_end", sign));
        let k = beam(pivot, junction, lateral, &arms);
        add(&k, Some(side_body(s, 0)), pivot, Some(side_body(s, 1)), junction);
        let k = beam(junction, arm_end, lateral, &arms);
        add(&k, Some(side_body(s, 1)), junction, Some(side_body(s, 2)), arm_end);
        // The pivot bushing: radial and conical across its axis, axial and torsion along it.
        let b = &g.bushings[0];
        let rate =
            |s: &Option<elastokin_suspensions::description::general::Stiffness>| s.as_ref().unwrap().rate().unwrap();
        let elastokin_suspensions::description::general::Axis::Vector(a) = b.axis.as_ref().unwrap() else { panic!() };
        let x = Vector3::new(a.x, sign * a.y, a.z).normalize();
        let along = x * x.transpose();
        let across = Matrix3::identity() - along;
        let mut k = Mat12::zeros();
        k.fixed_view_mut::<3, 3>(6, 6).copy_from(&(along * rate(&b.axial) + across * rate(&b.radial)));
        k.fixed_view_mut::<3, 3>(9, 9).copy_from(&(along * rate(&b.torsion) + across * rate(&b.conical)));
        add(&k, None, pivot, Some(side_body(s, 0)), pivot);
    }
    let cross = &g.axle.as_ref().unwrap().beams[0];
    for k in 1..=segments {
        let ends = [k - 1, k].map(|e| jl + (jr - jl) * (e as f64 / segments as f64));
        let bodies = [k - 1, k].map(|e| match e {
            0 => side_body(0, 1),
            e if e == segments => side_body(1, 1),
            e => node(e),
        });
        let stiffness = beam(ends[0], ends[1], Vector3::x(), &cross.section);
        add(&stiffness, Some(bodies[0]), ends[0], Some(bodies[1]), ends[1]);
    }
    // The rig: left wheel centre up h, right down h; everything else free.
    let h = 1.0;
    let driven = [6 * side_body(0, 2) + 2, 6 * side_body(1, 2) + 2];
    let held: Vec<usize> = if rigid_bushings {
        (0..2).flat_map(|s| (0..6).map(move |c| 6 * side_body(s, 0) + c)).collect()
    } else {
        vec![]
    };
    let free: Vec<usize> = (0..n).filter(|d| !driven.contains(d) && !held.contains(d)).collect();
    let kff = DMatrix::from_fn(free.len(), free.len(), |a, b| big_k[(free[a], free[b])]);
    let rhs = DVector::from_fn(free.len(), |a, _| -(big_k[(free[a], driven[0])] * h - big_k[(free[a], driven[1])] * h));
    let uf = kff.lu().solve(&rhs).expect("the frame is held");
    let mut u = DVector::zeros(n);
    for (a, &d) in free.iter().enumerate() {
        u[d] = uf[a];
    }
    u[driven[0]] = h;
    u[driven[1]] = -h;
    let forces = &big_k * &u;
    let (fl, fr) = (forces[driven[0]], forces[driven[1]]);
    let (wl, wr) = (hp("wheel_centre", 1.0), hp("wheel_centre", -1.0));
    let moment = wl.y * fl + wr.y * fr;
    // The contact patches: the loaded radius down each wheel's plane, carried by the carrier's rotation.
    let spin = |sign: f64| {
        let s = g.corner.spin_axis;
        Vector3::new(s[0], sign * s[1], s[2]).normalize()
    };
    let rotation = |b: usize| Vector3::new(u[6 * b + 3], u[6 * b + 4], u[6 * b + 5]);
    let patch = |s: usize, sign: f64| {
        let sp = spin(sign);
        let down = -(Vector3::z() - sp * sp.z).normalize() * g.corner.loaded_radius;
        let w = hp("wheel_centre", sign);
        let carrier = side_body(s, 2);
        let moved =
            Vector3::new(u[6 * carrier], u[6 * carrier + 1], u[6 * carrier + 2]) + rotation(carrier).cross(&down);
        (w + down, moved)
    };
    let ((pl, dl), (pr, dr)) = (patch(0, 1.0), patch(1, -1.0));
    let roll = -(dl.z - dr.z) / (pl.y - pr.y);
    let stiffness = -moment / roll;
    let twist = (rotation(side_body(1, 1)) - rotation(side_body(0, 1))).dot(&(jr - jl).normalize());
    // Toe-in of the left wheel from its spin axis, turned by the carrier's rotation.
    let (s, ds) = (spin(1.0), rotation(side_body(0, 2)).cross(&spin(1.0)));
    let toe = (s.y * ds.x - s.x * ds.y) / (s.x * s.x + s.y * s.y);
    (stiffness, twist / roll, toe / roll)
}

#[test]
fn the_shipped_twist_beam_without_springs_is_the_linear_frame_of_its_beams_and_bushings() {
    let mut file = example();
    if let elastokin_suspensions::description::Template::General(g) = &mut file.suspension {
        g.springs.clear();
    }
    let (stiffness, twist, steer) = linear_frame(&file, false);
    let report = kc::run(Analysis::Roll, &file, &Settings::default()).unwrap_or_else(|e| panic!("{e}"));
    let got = [
        figure(&report, "roll_stiffness"),
        figure(&report, "cross_member_twist_per_roll"),
        figure(&report, "roll_steer"),
    ];
    let errors: Vec<f64> = got.iter().zip([stiffness, twist, steer]).map(|(g, f)| (g / f - 1.0).abs()).collect();
    println!("roll stiffness {} against {stiffness} N·m/rad, twist {} against {twist}, roll steer {} against {steer}: {errors:?}", got[0], got[1], got[2]);
    // Measured 1.2e-12, 9.6e-13, 1.8e-12.
    assert!(errors.iter().all(|e| *e < 1e-10), "{errors:?}");
    // With the pivot bushings rigid, the arm eyes held: the roll steer the bushings' share is taken against.
    let (_, _, rigid) = linear_frame(&file, true);
    let got = figure(&report, "roll_steer_rigid_bushings");
    let share = figure(&report, "bushing_share_of_roll_steer");
    let error = (got / rigid - 1.0).abs();
    println!("roll steer with the bushings rigid {got} against {rigid}: {error:e}; their share {share}");
    // Measured 3.0e-13.
    assert!(error < 1e-11, "{error:e}");
    let expected = 1.0 - rigid / steer;
    assert!((share - expected).abs() < 1e-6 * expected.abs(), "{share} against {expected}");
}

#[test]
fn the_twist_beams_figures_move_with_its_sections_as_re_runs_of_the_moved_model_say() {
    use elastokin_suspensions::design::{analysis_sensitivity, Parameters};
    use elastokin_suspensions::study::batch::base_document;
    // A torsion constant of 3e-8 m⁴ and a second moment of 1e-6 m⁴: moved by their own size's fraction,
    // not by a length's 0.1 floor (which would move J through zero).
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/twist_beam.json");
    let path = path.to_string_lossy().to_string();
    let doc = base_document(&std::fs::read_to_string(&path).unwrap(), &path).unwrap();
    let pointers =
        ["/suspension/general/axle/beams/0/section/j", "/suspension/general/axle/beams/0/section/iy"].map(String::from);
    let p = Parameters::new(&doc, &pointers).unwrap();
    let settings = Settings { range: Some((-0.02, 0.02)), steps: 8, ..Settings::default() };
    let s = analysis_sensitivity(Analysis::Roll, &p, &settings).unwrap_or_else(|e| panic!("{e}"));
    let mut worst = 0.0f64;
    for (k, pointer) in pointers.iter().enumerate() {
        // Central differences of re-runs at ±5e-4 and ±1e-3 of the value, Richardson extrapolated.
        let rerun = |by: f64| {
            let mut values = p.values.clone();
            values[k] *= 1.0 + by;
            kc::run(Analysis::Roll, &p.at(&values).unwrap().file().unwrap(), &settings).unwrap()
        };
        let [up2, up, down, down2] = [1e-3, 5e-4, -5e-4, -1e-3].map(rerun);
        for key in ["roll_stiffness", "cross_member_twist_per_roll", "roll_steer", "bushing_share_of_roll_steer"] {
            let (_, rates) = s.figure(key).unwrap_or_else(|| panic!("no {key}"));
            let exact = rates[k].unwrap_or_else(|e| panic!("{key}: {}", e.reason())).value;
            let value = |r: &kc::AnalysisReport| figure(r, key);
            let differenced =
                (8.0 * (value(&up) - value(&down)) - (value(&up2) - value(&down2))) / (12.0 * 5e-4 * p.values[k]);
            // Against the derivative, or where it is small (roll stiffness moves by 3e-5 of itself with the
            // second moment's relative change) against a thousandth of the figure per the parameter: both
            // methods difference figures whose rounding (1e-13 of them) that leaves in such a derivative.
            let floor = 1e-3 * value(&s.report).abs() / p.values[k].abs();
            let error = (exact - differenced).abs() / differenced.abs().max(floor);
            println!("d {key} / d {pointer}: {exact:e} against {differenced:e}: {error:e}");
            worst = worst.max(error);
        }
    }
    // Measured 1.1e-6 (the cross member's twist per roll against the second moment).
    assert!(worst < 1e-5, "{worst:e}");
}
