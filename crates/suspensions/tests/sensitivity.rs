//! Sensitivities through the equilibrium against central differences of full re-solves, Richardson
//! extrapolated: every row's toe, camber and wheel centre and the bump steer and camber gain, for
//! hardpoints, rates and a design force of the shipped models. Allowed: 1e-6 of the largest derivative of
//! its kind, or 1e-9 absolute near zero (derivatives times the parameter's size); measured: at most 0.18
//! of that, and 4e-9 (MacPherson), 5e-8 (double wishbone), 4e-9 (five-link) relative where the derivative
//! is not near zero.

use elastokin_solver::Mode;
use elastokin_suspensions::analysis::parallel_wheel_travel;
use elastokin_suspensions::design::{hardpoint_pointers, parallel_travel_sensitivity, Parameters};
use elastokin_suspensions::study::batch::base_document;
use elastokin_suspensions::{Rig, Side};

fn document(name: &str) -> serde_json::Value {
    let path = format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"));
    base_document(&std::fs::read_to_string(&path).unwrap(), &path).unwrap()
}

const FROM: f64 = -0.05;
const TO: f64 = 0.05;
const STEPS: usize = 10;

/// Toe, camber and wheel-centre z of every row, bump steer and camber gain (rad/m, by the rows' central
/// difference at design, as the report reads them), of the model with parameter `k` moved by `delta`: read
/// here from the engine's rows, not by the report's reduction.
fn figures(p: &Parameters, k: usize, delta: f64) -> Vec<f64> {
    let corner = p.file_moved(k, delta).unwrap().suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let rows = parallel_wheel_travel(&corner, FROM, TO, STEPS, Mode::Corrected).unwrap();
    let mut out = Vec::new();
    for r in &rows {
        out.extend([r.attitude.toe, r.attitude.camber, r.attitude.wheel_centre.z]);
    }
    let design = STEPS / 2;
    let dt = rows[design + 1].travel - rows[design - 1].travel;
    out.push((rows[design + 1].attitude.toe - rows[design - 1].attitude.toe) / dt);
    out.push((rows[design + 1].attitude.camber - rows[design - 1].attitude.camber) / dt);
    out
}

/// The largest difference of the sensitivities from Richardson-extrapolated central differences of
/// re-solves, over every parameter and row, as a fraction of what is allowed: 1e-6 of the largest derivative
/// of the same kind (toe, camber, height, each slope) for that parameter, or 1e-9 absolute for a derivative
/// near zero. Also the largest relative difference where the derivative is not near zero.
fn worst_against_re_solves(name: &str, pointers: &[String]) -> (f64, f64) {
    worst_against_re_solves_of(document(name), pointers)
}

fn worst_against_re_solves_of(document: serde_json::Value, pointers: &[String]) -> (f64, f64) {
    let p = Parameters::new(&document, pointers).unwrap();
    let s = parallel_travel_sensitivity(&p, FROM, TO, STEPS).unwrap();
    let (mut worst, mut relative): (f64, f64) = (0.0, 0.0);
    for k in 0..p.len() {
        let h = 1e-3 * p.values[k].abs().max(0.1);
        let [a, b, c, d] = [2.0, 1.0, -1.0, -2.0].map(|m| figures(&p, k, m * h));
        let fd: Vec<f64> = (0..a.len()).map(|i| (8.0 * (b[i] - c[i]) - (a[i] - d[i])) / (12.0 * h)).collect();
        let (toe, camber, height) =
            (s.d_column("toe_deg", k), s.d_column("camber_deg", k), s.d_column("wheel_centre_z_m", k));
        // The report gives angles in degrees; compared here in radians, as the engine's rows are.
        let mut exact = Vec::new();
        for r in 0..toe.len() {
            exact.extend([toe[r].unwrap().to_radians(), camber[r].unwrap().to_radians(), height[r].unwrap()]);
        }
        exact.extend(["bump_steer", "camber_gain"].map(|f| s.figure(f).unwrap().1[k].unwrap().to_radians()));
        // Each kind against its own scale: toe, camber and height per row, then the two slopes.
        let rows = toe.len();
        let kinds: [Vec<usize>; 5] = [
            (0..rows).map(|r| 3 * r).collect(),
            (0..rows).map(|r| 3 * r + 1).collect(),
            (0..rows).map(|r| 3 * r + 2).collect(),
            vec![3 * rows],
            vec![3 * rows + 1],
        ];
        for kind in kinds {
            // Derivatives times the parameter's size: the effect of moving it by its whole size (0.1 m at
            // least for a hardpoint coordinate), comparable across parameters of any unit.
            let size = p.values[k].abs().max(0.1);
            let scale = kind.iter().map(|&i| fd[i].abs() * size).fold(0.0, f64::max);
            for i in kind {
                let e = (exact[i] - fd[i]).abs() * size;
                worst = worst.max(e / (1e-6 * scale).max(1e-9));
                if scale > 1e-3 {
                    relative = relative.max(e / scale);
                }
            }
        }
        // The figures the sensitivity reads at design are the re-solve's own.
        let base = figures(&p, k, 0.0);
        let bump_steer = s.figure("bump_steer").unwrap().0.value.unwrap().to_radians();
        assert!((bump_steer - base[3 * rows]).abs() < 1e-12, "{bump_steer} vs {}", base[3 * rows]);
    }
    (worst, relative)
}

#[test]
fn macpherson_hardpoint_rate_and_force_sensitivities_match_re_solves() {
    let h = "/suspension/macpherson/hardpoints";
    let pointers: Vec<String> = [
        format!("{h}/tie_rod_inner/2"),
        format!("{h}/tie_rod_outer/0"),
        format!("{h}/top_mount/1"),
        format!("{h}/lower_arm_front/2"),
        format!("{h}/wheel_centre/2"),
        "/suspension/macpherson/lower_arm_mounts/bushing/radial".into(),
        "/suspension/macpherson/top_mount/bushing/conical".into(),
        "/suspension/macpherson/spring/design_force".into(),
        "/suspension/macpherson/loaded_radius".into(),
    ]
    .to_vec();
    let (worst, relative) = worst_against_re_solves("macpherson.json", &pointers);
    println!("MacPherson: {worst:.3} of the allowed difference, relative {relative:e}");
    assert!(worst <= 1.0, "{worst:e}");
}

#[test]
fn double_wishbone_and_five_link_hardpoint_sensitivities_match_re_solves() {
    for name in ["double_wishbone.json", "five_link.json"] {
        let all = hardpoint_pointers(&document(name));
        // Every fifth coordinate of every hardpoint: each kind of point, each axis.
        let pointers: Vec<String> = all.iter().step_by(5).cloned().collect();
        assert!(pointers.len() >= 6, "{name}: {all:?}");
        let (worst, relative) = worst_against_re_solves(name, &pointers);
        println!("{name}: {worst:.3} of the allowed difference, relative {relative:e}, {} parameters", pointers.len());
        assert!(worst <= 1.0, "{name}: {worst:e}");
    }
}

/// A Chrono file's own points are parameters too, told per mm, and the sensitivity of its double wishbone
/// matches re-solves as the elastokin models' do.
#[test]
fn chrono_double_wishbone_point_sensitivities_match_re_solves() {
    let path = format!("{}/../../tests/data/chrono/DoubleWishbone.json", env!("CARGO_MANIFEST_DIR"));
    let doc = base_document(&std::fs::read_to_string(&path).unwrap(), &path).unwrap();
    let all = hardpoint_pointers(&doc);
    assert!(all.contains(&"/Tierod/Location Chassis/2".to_string()) && all.len() >= 27, "{all:?}");
    assert!(all.iter().all(|p| elastokin_suspensions::design::sensitivity::effect_unit(p) == "mm"));
    let pointers: Vec<String> = all.iter().step_by(4).cloned().collect();
    let (worst, relative) = worst_against_re_solves_of(doc, &pointers);
    println!("Chrono double wishbone: {worst:.3} of the allowed difference, relative {relative:e}");
    assert!(worst <= 1.0, "{worst:e}");
}

#[test]
fn a_parameter_that_names_nothing_or_no_number_is_refused_by_name() {
    let doc = document("macpherson.json");
    for (pointer, says) in [
        ("/suspension/macpherson/hardpoints/tie_rod_middle/2", "names nothing in the model"),
        (
            "/suspension/macpherson/hardpoints/tie_rod_inner",
            "a list of 3 values (name one of them: '/suspension/macpherson/hardpoints/tie_rod_inner/0')",
        ),
        ("/suspension/macpherson/spring", "a section of the model"),
        ("/name", "not a number"),
    ] {
        let e = Parameters::new(&doc, &[pointer.to_string()]).unwrap_err();
        assert!(e.contains(pointer) && e.contains(says), "{pointer}: {e}");
    }
    let twice = vec!["/suspension/macpherson/loaded_radius".to_string(); 2];
    assert!(Parameters::new(&doc, &twice).unwrap_err().contains("given twice"));
    // Every coordinate of the MacPherson's 8 hardpoints.
    assert_eq!(hardpoint_pointers(&doc).len(), 24);
}

/// Every headline figure the K&C report reads from the parallel-travel rows (wheel rate, motion ratio, ride
/// rate, caster, kingpin inclination, scrub radius, trail, …) and every column of its table, differentiated
/// as the figure is defined, against Richardson differences of the K&C report itself run on the moved model:
/// 55 figures and 825 cells, at most 0.50 of the allowed difference. (A lower-arm conical rate moves the
/// wheel load by 1e-6 N per 0.1 %: the re-runs scatter by 3e-6 of that between steps of 0.01, 0.1 and 1 %,
/// so parameters whose effects the re-runs resolve are taken.)
#[test]
fn every_parallel_travel_figure_and_column_matches_the_report_re_run() {
    use elastokin_suspensions::kc::{self, Analysis, Settings};
    let h = "/suspension/macpherson/hardpoints";
    let pointers: Vec<String> = vec![
        format!("{h}/top_mount/1"),
        format!("{h}/lower_ball_joint/2"),
        format!("{h}/strut_lower/0"),
        "/suspension/macpherson/spring/rate".into(),
        "/suspension/macpherson/spring/design_force".into(),
    ];
    let p = Parameters::new(&document("macpherson.json"), &pointers).unwrap();
    let s = parallel_travel_sensitivity(&p, FROM, TO, STEPS).unwrap();
    assert_eq!(s.report_figures.len(), 11, "{:?}", s.report_figures.iter().map(|f| &f.0.key).collect::<Vec<_>>());
    let rows = s.table.rows.len();
    let settings = Settings { range: Some((FROM, TO)), steps: STEPS, ..Settings::default() };
    let (mut worst, mut figures, mut cells) = (0.0_f64, 0, 0);
    for k in 0..p.len() {
        let d = 1e-3 * p.values[k].abs().max(0.1);
        let runs: Vec<_> = [2.0, 1.0, -1.0, -2.0]
            .map(|m| kc::run(Analysis::ParallelTravel, &p.file_moved(k, m * d).unwrap(), &settings).unwrap())
            .into_iter()
            .collect();
        let size = p.values[k].abs().max(0.1);
        // `scale`: the largest derivative of the kind (a column's over its rows); `None`: the figure's own.
        let mut judge = |exact: Option<f64>, values: [Option<f64>; 4], scale: Option<f64>, what: &str| {
            let [Some(a), Some(b), Some(c), Some(e)] = values else {
                assert!(exact.is_none(), "{what}: a derivative where the figure is missing");
                return;
            };
            let fd = (8.0 * (b - c) - (a - e)) / (12.0 * d);
            let exact = exact.unwrap_or_else(|| panic!("{what}: no derivative, re-runs give {fd}"));
            let allowed = (1e-6 * scale.unwrap_or(fd.abs()) * size).max(1e-9);
            worst = worst.max((exact - fd).abs() * size / allowed);
        };
        for (f, derivatives) in &s.report_figures {
            let values = [0, 1, 2, 3].map(|i| runs[i].figure(&f.key).and_then(|g| g.value));
            judge(derivatives[k], values, None, &format!("{} {}", p.pointers[k], f.key));
            figures += 1;
        }
        for (c, column) in s.table.columns.iter().enumerate() {
            let column_scale = (0..rows).filter_map(|r| s.d_columns[k][r][c]).fold(0.0_f64, |m, v| m.max(v.abs()));
            for r in 0..rows {
                let values = [0, 1, 2, 3].map(|i| runs[i].table.rows[r][c].number());
                judge(s.d_columns[k][r][c], values, Some(column_scale), &format!("{} {column} row {r}", p.pointers[k]));
                cells += 1;
            }
        }
    }
    println!("{figures} figures and {cells} cells: {worst:.3} of the allowed difference");
    assert!(worst <= 1.0, "{worst:e}");
}
