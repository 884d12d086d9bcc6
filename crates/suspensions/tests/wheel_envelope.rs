//! The wheel's swept envelope (`packaging`, the `wheel-envelope` analysis): its grid of wheel poses agrees
//! with parallel travel at the rack's centre and with steering at the design height (two other rigs);
//! each clearance equals a second reading written here (a plate's closed form over the tyre's highest
//! point, and the distance to the tyre's surface sampled and refined); the least clearance's estimate
//! bounds its distance from a finer grid's; a tyre reaching into a box is a negative clearance and a
//! warning; a corner without steering is swept over its travel; packaging mistakes are named.

use elastokin_core::Vec3;
use elastokin_suspensions::kc::{self, figures, Analysis, AnalysisReport, Figure, Settings};
use elastokin_suspensions::SuspensionFile;
use serde_json::{json, Value};

fn document(name: &str) -> Value {
    let path = format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn file(doc: &Value) -> SuspensionFile {
    SuspensionFile::from_json(&doc.to_string(), "m.json").unwrap()
}

fn run(doc: &Value, analysis: Analysis, steps: usize) -> AnalysisReport {
    kc::run(analysis, &file(doc), &Settings { steps, ..Settings::default() }).unwrap()
}

fn column(a: &AnalysisReport, name: &str) -> Vec<f64> {
    let cells = a.table.column(name).unwrap_or_else(|| panic!("no column {name} in {:?}", a.table.columns));
    cells.into_iter().map(Option::unwrap).collect()
}

/// The outward spin axis of a left wheel at `toe` and `camber` (deg), written here from ISO 8855's
/// definitions: toe-in turns the front inward, negative camber tilts the top inward.
fn spin_axis(toe_deg: f64, camber_deg: f64) -> Vec3 {
    let (t, c) = (toe_deg.to_radians(), camber_deg.to_radians());
    Vec3::new(t.sin() * c.cos(), t.cos() * c.cos(), -c.sin())
}

/// The envelope's grid: `placements[i][j]`, height `i` and rack position `j`, each the left wheel's centre
/// and spin axis.
fn grid(a: &AnalysisReport) -> Vec<Vec<(Vec3, Vec3)>> {
    let e = a.envelope.as_ref().expect("the envelope");
    let heights = a.table.rows.len();
    assert_eq!(e.placements.len() % heights, 0);
    e.placements.chunks(e.placements.len() / heights).map(<[_]>::to_vec).collect()
}

#[test]
fn the_grid_agrees_with_parallel_travel_at_the_rack_centre_and_with_steering_at_design_height() {
    let doc = document("macpherson.json");
    // Steps 32: a grid of 8 × 8 over ±80 mm of travel and ±40 mm of rack travel.
    let envelope = run(&doc, Analysis::WheelEnvelope, 32);
    let g = grid(&envelope);
    assert_eq!((g.len(), g[0].len()), (9, 9));
    let travel = run(&doc, Analysis::ParallelTravel, 8);
    assert_eq!(column(&travel, "travel_m"), column(&envelope, "travel_m"));
    let (toe, camber) = (column(&travel, "toe_deg"), column(&travel, "camber_deg"));
    let centre = ["x", "y", "z"].map(|c| column(&travel, &format!("wheel_centre_{c}_m")));
    let mut worst = (0.0f64, 0.0f64);
    for (i, row) in g.iter().enumerate() {
        let (c, s) = row[4];
        let expected = Vec3::new(centre[0][i], centre[1][i], centre[2][i]);
        worst.0 = worst.0.max((c - expected).norm());
        worst.1 = worst.1.max((s - spin_axis(toe[i], camber[i])).norm());
    }
    // Measured 8.9e-13 m and 2.9e-12: one equilibrium, reached on two rigs, each solved to 1e-9.
    assert!(worst.0 < 1e-10 && worst.1 < 1e-10, "{worst:?}");
    let steering = run(&doc, Analysis::Steering, 8);
    let (toe, camber) = (column(&steering, "left_toe_deg"), column(&steering, "left_camber_deg"));
    let mut worst = 0.0f64;
    for (j, &(_, s)) in g[4].iter().enumerate() {
        worst = worst.max((s - spin_axis(toe[j], camber[j])).norm());
    }
    // Measured 2.4e-16.
    assert!(worst < 1e-12, "{worst}");
    // The grid moves: 160 mm of wheel travel, and the rack steers the wheel by more than 25 degrees.
    let rise = g[8][4].0.z - g[0][4].0.z;
    let steer = g[4][0].1.angle(&g[4][8].1).to_degrees();
    assert!(rise > 0.15 && steer > 25.0, "{rise} {steer}");
}

/// The tyre of the shipped MacPherson: radius and width (m).
const TYRE: (f64, f64) = (0.316, 0.205);

/// The distance from `p` to the nearest point of the tyre (centre `c`, spin axis `s`) found by sampling its
/// surface (tread and both sidewalls) and refining around the nearest sample; `p` lies outside.
fn sampled_distance(c: Vec3, s: Vec3, p: Vec3) -> f64 {
    let (r, half) = (TYRE.0, TYRE.1 / 2.0);
    let u = s.cross(&Vec3::z()).normalize();
    let v = s.cross(&u);
    // A surface point by (angle, along the axis, radius): the tread at the full radius, the sidewalls at
    // the ends of the axis.
    let at = |theta: f64, along: f64, radius: f64| c + s * along + (u * theta.cos() + v * theta.sin()) * radius;
    // The nearest sample: (distance, angle, along, radius).
    let mut best = (f64::INFINITY, 0.0, 0.0, 0.0);
    let look = |best: &mut (f64, f64, f64, f64), theta: f64, along: f64, radius: f64| {
        let (along, radius) = (along.clamp(-half, half), radius.clamp(0.0, r));
        let d = (at(theta, along, radius) - p).norm();
        if d < best.0 {
            *best = (d, theta, along, radius);
        }
    };
    let n = 720;
    for k in 0..n {
        let theta = std::f64::consts::TAU * k as f64 / n as f64;
        for m in 0..=40 {
            look(&mut best, theta, -half + 2.0 * half * m as f64 / 40.0, r);
            look(&mut best, theta, -half, r * m as f64 / 40.0);
            look(&mut best, theta, half, r * m as f64 / 40.0);
        }
    }
    // Refined: ever finer grids about the best sample.
    let (mut dt, mut da, mut dr) = (std::f64::consts::TAU / n as f64, half / 20.0, r / 40.0);
    for _ in 0..30 {
        let (_, t0, a0, r0) = best;
        for i in -4..=4 {
            for k in -4..=4 {
                let (t, a) = (t0 + dt * i as f64 / 4.0, a0 + da * k as f64 / 4.0);
                look(&mut best, t, a, r0);
                look(&mut best, t, a0, r0 + dr * k as f64 / 4.0);
            }
        }
        (dt, da, dr) = (dt / 2.0, da / 2.0, dr / 2.0);
    }
    best.0
}

/// The distance from a box to the tyre, sampled: the tyre's surface points' distance to the box.
fn sampled_box_distance(c: Vec3, s: Vec3, lo: Vec3, hi: Vec3) -> f64 {
    // The nearest point of the box to the tyre's nearest point, found by alternating the two projections.
    let mut p = (lo + hi) * 0.5;
    for _ in 0..200 {
        let q = nearest_on_tyre(c, s, p);
        p = Vec3::new(q.x.clamp(lo.x, hi.x), q.y.clamp(lo.y, hi.y), q.z.clamp(lo.z, hi.z));
    }
    sampled_distance(c, s, p)
}

/// The tyre's (solid) nearest point to `p`, in closed form: `p` clamped to the cylinder in its axis frame.
fn nearest_on_tyre(c: Vec3, s: Vec3, p: Vec3) -> Vec3 {
    let d = p - c;
    let along = d.dot(&s).clamp(-TYRE.1 / 2.0, TYRE.1 / 2.0);
    let radial = d - s * d.dot(&s);
    let radial = if radial.norm() > TYRE.0 { radial.normalize() * TYRE.0 } else { radial };
    c + s * along + radial
}

#[test]
fn each_clearance_is_a_second_reading_of_the_tyre_and_the_packaging() {
    let doc = document("macpherson.json");
    let envelope = run(&doc, Analysis::WheelEnvelope, 32);
    let g = grid(&envelope);
    // The wheel-arch liner is a plate over the tyre, wider than it: its clearance is its underside's height
    // less the tyre's highest point, c_z + r·√(1 − s_z²) + w/2·|s_z|.
    let liner = column(&envelope, "clearance_wheel_arch_liner_m");
    let underside = 0.430;
    let mut worst = 0.0f64;
    for (i, row) in g.iter().enumerate() {
        let closed = row
            .iter()
            .map(|(c, s)| underside - c.z - TYRE.0 * (1.0 - s.z * s.z).sqrt() - TYRE.1 / 2.0 * s.z.abs())
            .fold(f64::INFINITY, f64::min);
        worst = worst.max((liner[i] - closed).abs());
    }
    // Measured 2.8e-15 m.
    assert!(worst < 1e-13, "{worst}");
    // The brake line clip and the frame rail by sampling the tyre's surface (left wheel: the right's grid
    // is its mirror image over a rack travel symmetric about the centre).
    let clip = column(&envelope, "clearance_brake_line_clip_m");
    let rail = column(&envelope, "clearance_frame_rail_m");
    let (p, lo, hi) = (Vec3::new(0.12, 0.54, 0.18), Vec3::new(-0.6, 0.42, -0.05), Vec3::new(-0.36, 0.58, 0.15));
    let mut worst = (0.0f64, 0.0f64);
    for i in [0, 4, 8] {
        let least = |f: &dyn Fn(&(Vec3, Vec3)) -> f64| g[i].iter().map(f).fold(f64::INFINITY, f64::min);
        worst.0 = worst.0.max((clip[i] - least(&|(c, s)| sampled_distance(*c, *s, p))).abs());
        worst.1 = worst.1.max((rail[i] - least(&|(c, s)| sampled_box_distance(*c, *s, lo, hi))).abs());
    }
    // Measured 3.5e-14 m and 9.0e-17 m.
    assert!(worst.0 < 1e-12 && worst.1 < 1e-12, "{worst:?}");
    // The figure is the least of every clearance.
    let least = envelope.figure_of(&figures::LEAST_WHEEL_CLEARANCE).and_then(|f| f.value).unwrap();
    let every = column(&envelope, "least_clearance_m").into_iter().fold(f64::INFINITY, f64::min);
    assert_eq!(least, every);
    assert!((least - liner.iter().copied().fold(f64::INFINITY, f64::min)).abs() < 1e-15);
}

#[test]
fn the_least_clearances_estimate_bounds_its_distance_from_a_finer_grid() {
    // A point ahead of the tyre at 13 mm above the wheel centre: the tyre comes closest to it between the
    // coarse grid's heights (20 mm apart), and near the rack's centre; and the shipped packaging, closest
    // at the grid's edge (full bump, full lock), where the grid is exact.
    let shipped = document("macpherson.json");
    let mut ahead = shipped.clone();
    ahead["packaging"]["points"] = json!([{ "name": "bumper beam corner", "at": [0.37, 0.77, 0.013] }]);
    ahead["packaging"]["boxes"] = json!([]);
    let mut interior = 0.0f64;
    for doc in [&ahead, &shipped] {
        let read = |steps| {
            let a = run(doc, Analysis::WheelEnvelope, steps);
            let f: Figure = a.figure_of(&figures::LEAST_WHEEL_CLEARANCE).unwrap().clone();
            (f.value.unwrap(), f.error.unwrap())
        };
        // Grids of 8, 16 and 40 steps each way.
        let (fine, fine_error) = read(160);
        for steps in [32, 64] {
            let (coarse, estimate) = read(steps);
            let error = (coarse - fine).abs();
            assert!(
                error <= estimate + fine_error,
                "{steps} steps: {coarse} is {error:e} from {fine}, estimated {estimate:e}"
            );
            interior = interior.max(error);
        }
    }
    // The grid's own error is real where the least lies between its points: measured 9.8e-5 m on the grid of
    // 8 (estimated 2.0e-4) and 1.3e-5 m on that of 16 (estimated 2.8e-5).
    assert!(interior > 1e-6, "{interior}");
}

#[test]
fn a_tyre_reaching_into_a_box_is_a_negative_clearance_and_a_warning() {
    let mut doc = document("macpherson.json");
    // The liner lowered to 40 mm above the tyre's top at design: full bump (80 mm) reaches into it.
    doc["packaging"]["boxes"][0]["min"][2] = json!(0.356);
    let envelope = run(&doc, Analysis::WheelEnvelope, 32);
    let g = grid(&envelope);
    let least = envelope.figure_of(&figures::LEAST_WHEEL_CLEARANCE).and_then(|f| f.value).unwrap();
    let closed = g
        .iter()
        .flatten()
        .map(|(c, s)| 0.356 - c.z - TYRE.0 * (1.0 - s.z * s.z).sqrt() - TYRE.1 / 2.0 * s.z.abs())
        .fold(f64::INFINITY, f64::min);
    // Measured 3.6e-15 m: the depth of the overlap is as exact as a distance apart.
    assert!(least < -0.02 && (least - closed).abs() < 1e-11, "{least} against {closed}");
    let warning = envelope.warnings.iter().find(|w| w.code == "wheel-interference").expect("a warning");
    assert!(
        warning.message.contains("'wheel arch liner'") && warning.message.contains("+80.0 mm"),
        "{}",
        warning.message
    );
    // Clear of it, no warning.
    let clear = run(&document("macpherson.json"), Analysis::WheelEnvelope, 32);
    assert!(clear.warnings.iter().all(|w| w.code != "wheel-interference"), "{:?}", clear.warnings);
}

#[test]
fn a_corner_without_steering_is_swept_over_its_travel_alone() {
    let mut doc = document("twist_beam.json");
    doc["packaging"] = json!({
        "tyre": { "radius": 0.3, "width": 0.195 },
        "boxes": [{ "name": "wheel arch", "min": [-0.4, 0.5, 0.4], "max": [0.4, 0.9, 0.42] }]
    });
    let f = file(&doc);
    assert_eq!(kc::left_out(&f, Analysis::WheelEnvelope), None);
    let envelope = run(&doc, Analysis::WheelEnvelope, 32);
    let g = grid(&envelope);
    assert_eq!((g.len(), g[0].len()), (9, 1));
    let travel = run(&doc, Analysis::ParallelTravel, 8);
    let z = column(&travel, "wheel_centre_z_m");
    let worst = g.iter().zip(&z).map(|(row, z)| (row[0].0.z - z).abs()).fold(0.0, f64::max);
    // Measured 0: the same sweep's rows.
    assert!(worst < 1e-12, "{worst}");
    // Without packaging the suite leaves it out, and asked for by name it says what it lacks.
    let plain = file(&document("twist_beam.json"));
    assert!(kc::left_out(&plain, Analysis::WheelEnvelope).unwrap().contains("\"packaging\""));
    let refused = kc::run(Analysis::WheelEnvelope, &plain, &Settings::default()).unwrap_err().to_string();
    assert!(refused.contains("no \"packaging\" section"), "{refused}");
}

#[test]
fn packaging_mistakes_are_named_with_how_to_mend_them() {
    let shipped = document("macpherson.json");
    let refused = |edit: &dyn Fn(&mut Value)| {
        let mut doc = shipped.clone();
        edit(&mut doc);
        SuspensionFile::from_json(&doc.to_string(), "m.json").unwrap_err().to_string()
    };
    type Edit<'a> = &'a dyn Fn(&mut Value);
    let cases: [(Edit, &str); 5] = [
        (&|d| d["packaging"]["tyre"]["radius"] = json!(316), "millimetres? in metres that is 0.316"),
        (&|d| d["packaging"]["boxes"][1]["max"][2] = json!(-0.1), "its min z is not below its max z"),
        (&|d| d["packaging"]["points"][0]["name"] = json!("frame rail"), "'frame rail' is named twice"),
        (&|d| d["packaging"]["rack_travel"] = json!([0.04, -0.04]), "packaging.rack_travel: give the rack's travel"),
        (&|d| d["packaging"]["points"][0]["at"] = json!([120, 540, 180]), "give it in metres"),
    ];
    for (edit, words) in cases {
        let message = refused(edit);
        assert!(message.contains(words), "{words}: {message}");
    }
}

#[test]
fn the_heights_run_at_once_give_the_envelope_of_one_thread_to_the_bit() {
    let doc = document("macpherson.json");
    let one_thread = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let two_threads = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
    let alone = one_thread.install(|| run(&doc, Analysis::WheelEnvelope, 32));
    let at_once = two_threads.install(|| run(&doc, Analysis::WheelEnvelope, 32));
    assert_eq!(alone.table, at_once.table);
    assert_eq!(alone.figures, at_once.figures);
    assert_eq!(alone.envelope, at_once.envelope);
    // A recorded run (as sensitivities record it) takes the heights in turn and reads the same.
    let (recorded, _) = elastokin_solver::replay::record(|taping| {
        kc::run_taped(
            Analysis::WheelEnvelope,
            &kc::Models::new(&file(&doc)),
            &Settings { steps: 32, ..Settings::default() },
            taping,
        )
    });
    assert_eq!(recorded.unwrap().table, at_once.table);
}
