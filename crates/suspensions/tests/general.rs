//! The general model file: every template expands into it and builds the same model through the one
//! builder; any corner written in it runs every analysis.

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

/// Largest difference between two suites' tables, relative to each column's largest magnitude.
fn largest_difference(a: &kc::KcReport, b: &kc::KcReport) -> f64 {
    let mut worst: f64 = 0.0;
    assert_eq!(a.analyses.len(), b.analyses.len());
    for (x, y) in a.analyses.iter().zip(&b.analyses) {
        assert_eq!(x.table.columns, y.table.columns, "{}", x.analysis.name());
        assert_eq!(x.table.rows.len(), y.table.rows.len());
        for (c, d) in x.table.column_differences(&y.table).into_iter().enumerate() {
            let scale = x.table.rows.iter().filter_map(|r| r[c].number()).fold(1e-300_f64, |m, v| m.max(v.abs()));
            if let Some(d) = d {
                if d / scale > 1e-12 {
                    eprintln!("{} {}: {d:e} of {scale:e}", x.analysis.name(), x.table.columns[c]);
                }
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
    for name in ["macpherson.json", "double_wishbone.json"] {
        let file = example(name);
        let general = expanded(&file);
        assert!(matches!(general.suspension, Template::General(_)));
        let settings = Settings { steps: 8, ..Settings::default() };
        let a = kc::run_suite(&file, &[], &settings, |_| {}).unwrap();
        let b = kc::run_suite(&general, &[], &settings, |_| {}).unwrap();
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
