//! The roll centre of the whole axle over parallel travel: at design the roll analysis's, on every shipped
//! model (solid axles and an anti-roll bar among them); over the travel, where the front-view lines from
//! each patch through its corner's instant centre meet (the swing arms of a lone corner, mirrored).

mod common;
use elastokin_solver::{Mode, SolverOptions, StaticSolver};
use elastokin_suspensions::analysis::{parallel_wheel_travel_with, SweepExtras};
use elastokin_suspensions::kc::{self, Analysis, AnalysisReport, Models, Settings};
use elastokin_suspensions::{AxleRig, Rig, SuspensionFile};

fn example(name: &str) -> SuspensionFile {
    SuspensionFile::read(&common::examples().join(name)).unwrap()
}

/// The cell of `column` in the row of `report`'s table whose load parameter is zero.
fn at_zero(report: &AnalysisReport, column: &str) -> Option<f64> {
    let c = report.table.columns.iter().position(|n| n == column).unwrap();
    let row = report.table.rows.iter().find(|r| r[0].number() == Some(0.0)).unwrap();
    row[c].number()
}

#[test]
fn at_design_the_roll_centre_in_heave_is_the_roll_analysis_s() {
    let mut worst: f64 = 0.0;
    for (name, file) in common::models() {
        let settings = Settings { steps: 8, ..Settings::default() };
        let heave = kc::run(Analysis::ParallelTravel, &file, &settings).unwrap();
        let roll = kc::run(Analysis::Roll, &file, &settings).unwrap();
        for (column, key) in
            [("roll_centre_height_m", "roll_centre_height"), ("roll_centre_lateral_m", "roll_centre_lateral")]
        {
            let figure = roll.figures.iter().find(|f| f.key == key).unwrap();
            let (Some(expected), Some(got)) = (figure.value, at_zero(&heave, column)) else {
                panic!("{name}: {column} {:?} against the roll's {:?}", at_zero(&heave, column), figure.value);
            };
            // The row of the roll's own sweep at zero travel: the same state reached another way.
            let row = at_zero(&roll, column).unwrap();
            let miss = (got - expected).abs().max((got - row).abs());
            worst = worst.max(miss);
            // Measured: 4.1e-12 m at most (the equilibria's tolerance).
            assert!(miss < 1e-10, "{name}: {column} {got} against the roll's {expected} (its row {row})");
        }
    }
    eprintln!("roll centre at design, heave against roll: {worst:e} m at most");
}

/// With nothing joining the two sides (no anti-roll bar, no shared member), each wheel of the axle moves
/// as the lone corner does in parallel travel, in roll as in heave: the roll centre is where the line from
/// the left patch through the corner's front-view instant centre meets its mirror image, on the centre
/// plane at `(IC_z − P_z) · P_y / (P_y − IC_y)` above the ground through the patches.
#[test]
fn over_the_travel_the_roll_centre_is_where_the_patches_lines_through_the_instant_centres_meet() {
    let mut worst: f64 = 0.0;
    for name in ["macpherson.json", "double_wishbone.json", "five_link.json", "generic/double_wishbone.json"] {
        let file = example(name);
        let settings = Settings { steps: 8, ..Settings::default() };
        let heave = kc::run(Analysis::ParallelTravel, &file, &settings).unwrap();
        let corner = Models::new(&file).corner(Rig::WheelTravel).unwrap();
        let out = parallel_wheel_travel_with(&corner, -0.08, 0.08, 8, Mode::Corrected, SweepExtras::default()).unwrap();
        let column = |name: &str| heave.table.columns.iter().position(|c| c == name).unwrap();
        for (row, cells) in out.rows.iter().zip(&heave.table.rows) {
            assert_eq!(cells[0].number(), Some(row.travel));
            let p = row.steering.contact_patch;
            let ic = row.swing_arms.unwrap().front.unwrap();
            let expected = (ic.z - p.z) * p.y / (p.y - ic.horizontal);
            let height = cells[column("roll_centre_height_m")].number().unwrap();
            let lateral = cells[column("roll_centre_lateral_m")].number().unwrap();
            let miss = (height - expected).abs().max(lateral.abs());
            worst = worst.max(miss);
            // Measured: 1.6e-14 m at most.
            assert!(
                miss < 1e-12,
                "{name} travel {}: roll centre {height} (lateral {lateral}) against {expected}",
                row.travel
            );
        }
    }
    eprintln!("roll centre over heave against the instant centres' lines: {worst:e} m at most");
}

/// An anti-roll bar twists in roll and not in heave, and on bushings its moment moves the wheels in roll
/// otherwise than in heave: the lines through the patches perpendicular to their velocities in heave meet
/// elsewhere than the roll's. The roll centre over heave is the roll's (above), not that point.
#[test]
fn the_roll_centre_in_heave_of_an_axle_with_a_bar_is_read_off_the_roll_s_motion_not_the_heave_s() {
    let file = example("vehicle/front_macpherson_with_bar.json");
    let heave = kc::run(Analysis::ParallelTravel, &file, &Settings { steps: 8, ..Settings::default() }).unwrap();
    let axle = Models::new(&file).axle(AxleRig::ParallelTravel).unwrap();
    let mut solver = StaticSolver::new(&axle.model, SolverOptions::default()).unwrap();
    let mut state = solver.design_state(0.0);
    solver.equilibrium(&mut state).unwrap();
    let rates = solver.path_tangent(&state).unwrap();
    let of_heave = axle.roll_centre(&state.poses, &rates).unwrap();
    let got = at_zero(&heave, "roll_centre_height_m").unwrap();
    // Measured: 0.99 mm apart (82.8 mm against 81.8 mm).
    assert!((got - of_heave.height).abs() > 1e-4, "{got} against the heave's own {}", of_heave.height);
}

/// The chart draws the table's column, in millimetres.
#[test]
fn the_roll_centre_chart_is_the_table_s_column() {
    let report =
        kc::run(Analysis::ParallelTravel, &example("macpherson.json"), &Settings { steps: 8, ..Settings::default() })
            .unwrap();
    let c = report.table.columns.iter().position(|n| n == "roll_centre_height_m").unwrap();
    let chart = report.charts.iter().find(|c| c.name == "parallel_travel_roll_centre").unwrap();
    let points = &chart.left.series[0].points;
    assert_eq!(points.len(), report.table.rows.len());
    for (&(x, y), row) in points.iter().zip(&report.table.rows) {
        assert_eq!((x, y), (row[0].number().unwrap() * 1e3, row[c].number().unwrap() * 1e3));
    }
}
