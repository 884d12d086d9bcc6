//! The front-view and side-view swing arms of parallel travel against two other methods: where the arms'
//! lines meet in the front view of a double wishbone whose arms turn about axes along x (its upright then
//! moves in the front view's plane), and the instant centres of the upright's velocities taken as finite
//! differences of equilibria, for the shipped double wishbone and MacPherson strut.

use elastokin_core::{Pose, Vec3};
use elastokin_solver::{Mode, SolverOptions, StaticSolver};
use elastokin_suspensions::analysis::{parallel_wheel_travel_with, SweepExtras, SwingArms};
use elastokin_suspensions::kc::{self, Analysis, Models, Settings};
use elastokin_suspensions::{
    Connection, Corner, DoubleWishbone, DoubleWishboneHardpoints, Rig, Side, SpringSpec, SuspensionFile,
};
use std::path::Path;

/// A double wishbone whose arms turn about axes along x, its ball joints and wheel centre at x = 0, and its
/// tie rod the lower arm moved 0.14 m rearward: every joint then holds the upright moving in the plane
/// x = 0, turning about x alone.
fn planar_double_wishbone() -> DoubleWishbone {
    DoubleWishbone {
        hardpoints: DoubleWishboneHardpoints {
            wheel_centre: Vec3::new(0.0, 0.78, 0.0),
            upper_ball_joint: Vec3::new(0.0, 0.68, 0.20),
            upper_arm_front: Vec3::new(0.15, 0.46, 0.24),
            upper_arm_rear: Vec3::new(-0.15, 0.46, 0.24),
            lower_ball_joint: Vec3::new(0.0, 0.74, -0.15),
            lower_arm_front: Vec3::new(0.20, 0.38, -0.13),
            lower_arm_rear: Vec3::new(-0.20, 0.38, -0.13),
            tie_rod_inner: Vec3::new(-0.14, 0.38, -0.13),
            tie_rod_outer: Vec3::new(-0.14, 0.74, -0.15),
            spring_chassis: Vec3::new(0.0, 0.58, 0.15),
            spring_arm: Vec3::new(0.0, 0.62, -0.135),
        },
        upper_arm_mounts: Connection::Ideal.into(),
        lower_arm_mounts: Connection::Ideal.into(),
        spring: SpringSpec { rate: 30e3, design_force: 4000.0 },
        tie_rod: Connection::Ideal,
        loaded_radius: 0.30,
    }
}

/// Where the line through `a` and `b` meets the line through `c` and `d`, all in the front view (y, z).
fn meet(a: (f64, f64), b: (f64, f64), c: (f64, f64), d: (f64, f64)) -> (f64, f64) {
    let (r, s) = ((b.0 - a.0, b.1 - a.1), (d.0 - c.0, d.1 - c.1));
    // a + λ r = c + μ s, by Cramer's rule.
    let det = r.0 * -s.1 + s.0 * r.1;
    let lambda = ((c.0 - a.0) * -s.1 + s.0 * (c.1 - a.1)) / det;
    (a.0 + lambda * r.0, a.1 + lambda * r.1)
}

#[test]
fn the_front_view_instant_centre_of_arms_turning_about_x_is_where_the_arms_lines_meet() {
    let dw = planar_double_wishbone();
    let hp = dw.hardpoints;
    let corner = dw.build(Side::Left, Rig::WheelTravel).unwrap();
    let extras = SweepExtras { poses: true, ..SweepExtras::default() };
    let out = parallel_wheel_travel_with(&corner, -0.08, 0.08, 16, Mode::Corrected, extras).unwrap();
    let upright = corner.wheel.upright.0;
    let design = corner.model.bodies()[upright].design_pose;
    let (lower, upper) = (design.to_local_point(&hp.lower_ball_joint), design.to_local_point(&hp.upper_ball_joint));
    let yz = |p: Vec3| (p.y, p.z);
    let mut worst: f64 = 0.0;
    for (row, poses) in out.rows.iter().zip(out.poses.as_ref().unwrap()) {
        // The ball joints where the row's upright carries them; each arm's axis is a point in this view.
        let (l, u) = (poses[upright].point(&lower), poses[upright].point(&upper));
        let (y, z) = meet(yz(hp.lower_arm_front), yz(l), yz(hp.upper_arm_front), yz(u));
        let arms = row.swing_arms.expect("read in wheel travel");
        let front = arms.front.expect("the arms are not parallel in the front view");
        let length = (y - row.steering.contact_patch.y).abs();
        let miss = (front.horizontal - y).abs().max((front.z - z).abs()).max((front.swing_arm_length - length).abs());
        worst = worst.max(miss);
        // Measured: 6.7e-11 m at most over the rows (the centre 1.5 to 5 m from the patch).
        assert!(
            miss < 1e-9,
            "travel {}: instant centre ({}, {}) against the arms' ({y}, {z})",
            row.travel,
            front.horizontal,
            front.z
        );
        // The upright does not turn in the side view: no instant centre there.
        assert_eq!(arms.side, None, "travel {}", row.travel);
    }
    eprintln!("front-view instant centre against the arms' lines: {worst:e} m at most");
}

/// The upright's pose at the equilibrium at `travel`: solved by Newton from the design state, then two
/// exact Newton iterations on, which leave rounding where the solver's tolerance (1e-9 of the force scale)
/// leaves up to 1e-8 rad in a soft bushing's twist.
fn polished_upright(solver: &mut StaticSolver, corner: &Corner, travel: f64) -> Pose {
    let mut state = solver.design_state(travel);
    let mut step = solver.equilibrium(&mut state).unwrap();
    for _ in 0..2 {
        step = solver.newton_correction(&step).unwrap();
    }
    step.poses[corner.wheel.upright.0]
}

/// The upright's angular velocity and the velocity of its material point now at `patch`, per metre of
/// travel, at `travel`: central differences of the equilibria at `travel ± h` and `± 2h`, Richardson
/// extrapolated (the bushings bend the path enough that a plain difference over 1 mm is off by 1e-5 of
/// the angular velocity).
fn differenced_velocities(corner: &Corner, travel: f64, patch: Vec3) -> (Vec3, Vec3) {
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default()).unwrap();
    let here = polished_upright(&mut solver, corner, travel);
    let local = here.to_local_point(&patch);
    let mut over = |h: f64| {
        let (ahead, behind) =
            (polished_upright(&mut solver, corner, travel + h), polished_upright(&mut solver, corner, travel - h));
        let v = (ahead.point(&local) - behind.point(&local)) / (2.0 * h);
        // dR/dt Rᵀ is the skew matrix of the angular velocity.
        let w = (ahead.rotation() - behind.rotation()) / (2.0 * h) * here.rotation().transpose();
        (Vec3::new(w[(2, 1)], w[(0, 2)], w[(1, 0)]), v)
    };
    let h = 1e-4;
    let ((w1, v1), (w2, v2)) = (over(h), over(2.0 * h));
    ((4.0 * w1 - w2) / 3.0, (4.0 * v1 - v2) / 3.0)
}

/// The six readings of a row's swing arms, named.
fn readings(arms: SwingArms) -> [(f64, &'static str); 6] {
    let (f, s) = (arms.front.unwrap(), arms.side.unwrap());
    [
        (f.horizontal, "front-view y"),
        (f.z, "front-view z"),
        (f.swing_arm_length, "front-view length"),
        (s.horizontal, "side-view x"),
        (s.z, "side-view z"),
        (s.swing_arm_length, "side-view length"),
    ]
}

/// Each row read again one Newton iteration on (the column's error estimate) is the instant centres of the
/// differenced velocities at the exact equilibrium; the row itself is as far from them as that estimate
/// says.
#[test]
fn the_swing_arms_are_those_of_the_upright_s_velocities_differenced() {
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let (mut worst, mut worst_row): (f64, f64) = (0.0, 0.0);
    for name in ["double_wishbone.json", "macpherson.json"] {
        let file = SuspensionFile::read(&examples.join(name)).unwrap();
        let corner = Models::new(&file).corner(Rig::WheelTravel).unwrap();
        let extras = SweepExtras { error_estimate: true, ..SweepExtras::default() };
        let out = parallel_wheel_travel_with(&corner, -0.06, 0.06, 4, Mode::Corrected, extras).unwrap();
        for (row, corrected) in out.rows.iter().zip(out.corrected.as_ref().unwrap()) {
            let p = corrected.steering.contact_patch;
            let (w, v) = differenced_velocities(&corner, row.travel, p);
            // The point of each view's plane through the patch that the upright's motion leaves where it is.
            let front = (p.y - v.z / w.x, p.z + v.y / w.x);
            let side = (p.x + v.z / w.y, p.z - v.x / w.y);
            let expected = [front.0, front.1, (front.0 - p.y).abs(), side.0, side.1, (side.0 - p.x).abs()];
            let pairs = readings(row.swing_arms.unwrap()).into_iter().zip(readings(corrected.swing_arms.unwrap()));
            for (((got, what), (again, _)), expected) in pairs.zip(expected) {
                let size = expected.abs().max(1.0);
                let miss = (again - expected).abs() / size;
                worst = worst.max(miss);
                // Measured: 1.3e-9 of the value at most (the differences' own error).
                assert!(miss < 1e-8, "{name} travel {}: {what} {again} against {expected}", row.travel);
                // The row's distance from them, beyond its error estimate.
                let beyond = ((got - expected).abs() - (got - again).abs()) / size;
                worst_row = worst_row.max(beyond);
                assert!(
                    beyond < 1e-8,
                    "{name} travel {}: {what} {got} ± {} against {expected}",
                    row.travel,
                    (got - again).abs()
                );
            }
        }
    }
    eprintln!(
        "swing arms against differenced velocities: {worst:e} at most, the rows {worst_row:e} beyond their estimate"
    );
}

#[test]
fn the_swing_arm_columns_and_figures_are_the_rows_and_the_design_reading() {
    let file = SuspensionFile::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/double_wishbone.json"))
        .unwrap();
    let report = kc::run(Analysis::ParallelTravel, &file, &Settings { steps: 8, ..Settings::default() }).unwrap();
    let corner = Models::new(&file).corner(Rig::WheelTravel).unwrap();
    let out = parallel_wheel_travel_with(&corner, -0.08, 0.08, 8, Mode::Corrected, SweepExtras::default()).unwrap();
    let column = |name: &str| report.table.columns.iter().position(|c| c == name).unwrap();
    let design = &out.rows[4];
    assert_eq!(design.travel, 0.0);
    let arms = design.swing_arms.unwrap();
    let (front, side) = (arms.front.unwrap(), arms.side.unwrap());
    for (name, value) in [
        ("front_view_instant_centre_y_m", front.horizontal),
        ("front_view_instant_centre_z_m", front.z),
        ("front_view_swing_arm_length_m", front.swing_arm_length),
        ("side_view_instant_centre_x_m", side.horizontal),
        ("side_view_instant_centre_z_m", side.z),
        ("side_view_swing_arm_length_m", side.swing_arm_length),
    ] {
        assert_eq!(report.table.rows[4][column(name)].number(), Some(value), "{name}");
    }
    let figure = |key: &str| report.figures.iter().find(|f| f.key == key).unwrap();
    // The figures are read at the design equilibrium itself, the row at travel 0 by the sweep's steps:
    // they agree to the equilibria's tolerance, carried out to a side-view centre 45 m away. Measured: 5.8e-10
    // of the length.
    for (key, value) in
        [("front_view_swing_arm_length", front.swing_arm_length), ("side_view_swing_arm_length", side.swing_arm_length)]
    {
        let f = figure(key);
        assert!((f.value.unwrap() - value).abs() < 1e-8 * value, "{key}: {:?} against the row's {value}", f.value);
        assert!(f.error.is_some(), "{key}");
    }
    // The charts draw the table's columns, in millimetres, where the centre lies within 100 m.
    for (view, length, z) in [
        ("front", "front_view_swing_arm_length_m", "front_view_instant_centre_z_m"),
        ("side", "side_view_swing_arm_length_m", "side_view_instant_centre_z_m"),
    ] {
        let chart = report.charts.iter().find(|c| c.name == format!("parallel_travel_{view}_view_swing_arm")).unwrap();
        let drawn: Vec<&Vec<kc::Cell>> = report
            .table
            .rows
            .iter()
            .filter(|r| r[column(length)].number().is_some_and(|l| l <= 100.0))
            .filter(|r| r[column(z)].number().is_some_and(|z| z.abs() <= 100.0))
            .collect();
        let expected = |c: usize| -> Vec<(f64, f64)> {
            drawn.iter().map(|r| (r[0].number().unwrap() * 1e3, r[c].number().unwrap() * 1e3)).collect()
        };
        assert_eq!(chart.left.series[0].points, expected(column(length)), "{view}");
        assert_eq!(chart.right.as_ref().unwrap().series[0].points, expected(column(z)), "{view}");
    }
    // The double wishbone's side-view centre runs off beyond 100 m near full rebound: those rows are left out.
    let side = report.charts.iter().find(|c| c.name == "parallel_travel_side_view_swing_arm").unwrap();
    assert!(side.left.series[0].points.len() < report.table.rows.len());
}

/// The construction the views draw (`AnalysisReport::construction`, with `Settings::motion`) holds, at
/// every row of parallel travel, the table's instant centres and roll centre in global coordinates; and on
/// a corner with nothing joining the sides the roll centre lies on the line from the patch through the
/// front-view instant centre (the construction a front view draws), to rounding.
#[test]
fn the_views_construction_is_the_tables_and_its_roll_centre_lies_on_the_patch_s_line() {
    let file =
        SuspensionFile::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/macpherson.json")).unwrap();
    let a =
        kc::run(Analysis::ParallelTravel, &file, &Settings { steps: 8, motion: true, ..Settings::default() }).unwrap();
    assert_eq!(a.construction.len(), a.table.rows.len());
    let column = |name: &str| a.table.column(name).unwrap();
    let (fy, fz, sx, sz) = (
        column("front_view_instant_centre_y_m"),
        column("front_view_instant_centre_z_m"),
        column("side_view_instant_centre_x_m"),
        column("side_view_instant_centre_z_m"),
    );
    let (rc_y, rc_h, track) =
        (column("roll_centre_lateral_m"), column("roll_centre_height_m"), column("half_track_change_m"));
    assert!(track.iter().all(Option::is_some));
    let mut worst: f64 = 0.0;
    for (r, c) in a.construction.iter().enumerate() {
        assert_eq!(c.front_view_centre, fy[r].zip(fz[r]).map(|(y, z)| [y, z]), "row {r}");
        assert_eq!(c.side_view_centre, sx[r].zip(sz[r]).map(|(x, z)| [x, z]), "row {r}");
        let [_, py, pz] = c.patch;
        let rc = c.roll_centre.unwrap();
        assert_eq!(rc, [rc_y[r].unwrap(), pz + rc_h[r].unwrap()], "row {r}");
        // The roll centre's distance from the line through the patch and the instant centre (m).
        let [iy, iz] = c.front_view_centre.unwrap();
        let (dy, dz) = (iy - py, iz - pz);
        let off = ((rc[0] - py) * dz - (rc[1] - pz) * dy).abs() / (dy * dy + dz * dz).sqrt();
        worst = worst.max(off);
    }
    // Measured 2.8e-17 m.
    assert!(worst < 1e-15, "{worst}");
}
