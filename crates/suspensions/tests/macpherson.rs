//! MacPherson strut against an independent loop closure, and its top-mount bushing against the ball joint.

use elastokin_core::Vec3;
use elastokin_solver::Mode;
use elastokin_suspensions::analysis::parallel_wheel_travel;
use elastokin_suspensions::{BushingRates, Connection, MacPherson, MacPhersonHardpoints, Rig, Side, SpringSpec};

mod common;

fn template(arm: Connection, top: Connection) -> MacPherson {
    MacPherson {
        hardpoints: MacPhersonHardpoints::generic(),
        lower_arm_mounts: arm.into(),
        top_mount: top,
        strut: Default::default(),
        spring: SpringSpec { rate: 30e3, design_force: 4500.0 },
        tie_rod: Connection::Ideal,
        loaded_radius: 0.30,
    }
}

#[test]
fn toe_and_camber_match_an_independent_loop_closure() {
    let mp = template(Connection::Ideal, Connection::Ideal);
    let corner = mp.build(Side::Left, Rig::WheelTravel).unwrap();
    let rows = parallel_wheel_travel(&corner, -0.08, 0.08, 32, Mode::Corrected).unwrap();
    let mut order: Vec<usize> = (0..rows.len()).collect();
    order.sort_by(|&a, &b| rows[a].travel.abs().total_cmp(&rows[b].travel.abs()));
    let mut guesses = [[0.0; 4]; 2];
    let (mut largest_toe, mut largest_camber): (f64, f64) = (0.0, 0.0);
    for k in order {
        let row = rows[k];
        let g = &mut guesses[usize::from(row.travel > 0.0)];
        let (toe, camber) = common::macpherson_closure(&mp.hardpoints, row.travel, g);
        assert!((row.attitude.toe - toe).abs() < 1e-9, "travel {}: toe {} vs {toe}", row.travel, row.attitude.toe);
        assert!(
            (row.attitude.camber - camber).abs() < 1e-9,
            "travel {}: camber {} vs {camber}",
            row.travel,
            row.attitude.camber
        );
        largest_toe = largest_toe.max(toe.abs());
        largest_camber = largest_camber.max(camber.abs());
    }
    assert!(largest_toe.to_degrees() > 0.05 && largest_camber.to_degrees() > 0.3, "{largest_toe} {largest_camber}");
}

#[test]
fn bushed_macpherson_converges_to_the_ideal_one() {
    let ideal = parallel_wheel_travel(
        &template(Connection::Ideal, Connection::Ideal).build(Side::Left, Rig::WheelTravel).unwrap(),
        -0.05,
        0.05,
        10,
        Mode::Corrected,
    )
    .unwrap();
    let arm = BushingRates::new(5e6, 1e6, 10f64.to_degrees(), 100f64.to_degrees());
    // Top mount: stiff radially, soft in torsion about the strut (it carries the steering rotation).
    let top = BushingRates::new(2e6, 1e6, 2f64.to_degrees(), 50f64.to_degrees());
    let deviation = |scale: f64| {
        // Rotations the ideal joints leave free keep their rates; the locked directions stiffen.
        let a = BushingRates { torsion: arm.torsion, ..arm.scaled(scale) };
        let t = BushingRates { torsion: top.torsion, conical: top.conical, ..top.scaled(scale) };
        let rows = parallel_wheel_travel(
            &template(Connection::Bushing(a), Connection::Bushing(t)).build(Side::Left, Rig::WheelTravel).unwrap(),
            -0.05,
            0.05,
            10,
            Mode::Corrected,
        )
        .unwrap();
        rows.iter()
            .zip(&ideal)
            .map(|(b, i)| (b.attitude.toe - i.attitude.toe).abs().max((b.attitude.camber - i.attitude.camber).abs()))
            .fold(0.0, f64::max)
    };
    let (d1, d100, d10000) = (deviation(1.0), deviation(1e2), deviation(1e4));
    assert!(d1 > 1e-6 && d100 < d1 / 30.0 && d10000 < d100 / 30.0, "{d1:e} {d100:e} {d10000:e}");
}

#[test]
fn right_macpherson_mirrors_the_left() {
    let mp = template(Connection::Ideal, Connection::Ideal);
    let left =
        parallel_wheel_travel(&mp.build(Side::Left, Rig::WheelTravel).unwrap(), -0.05, 0.05, 10, Mode::Corrected)
            .unwrap();
    let right =
        parallel_wheel_travel(&mp.build(Side::Right, Rig::WheelTravel).unwrap(), -0.05, 0.05, 10, Mode::Corrected)
            .unwrap();
    for (l, r) in left.iter().zip(&right) {
        assert!(
            (l.attitude.toe - r.attitude.toe).abs() < 1e-12 && (l.attitude.camber - r.attitude.camber).abs() < 1e-12
        );
    }
}

#[test]
fn rack_travel_steers_left_and_right_wheels_the_same_way() {
    let mp = template(Connection::Ideal, Connection::Ideal);
    let steer = |side: Side| {
        let corner = mp.build(side, Rig::Steering).unwrap();
        elastokin_suspensions::analysis::steering(&corner, -0.02, 0.02, 8, Mode::Corrected).unwrap()
    };
    let (left, right) = (steer(Side::Left), steer(Side::Right));
    // The rack moving +y swings both wheels the same way, so toe-in on one side is toe-out on the other.
    // The right corner is the left one mirrored, and mirroring flips the rack direction: the right wheel at
    // rack travel +s matches the left one at −s with toe kept (toe is defined per side).
    for (l, r) in left.iter().zip(right.iter().rev()) {
        assert!((l.travel + r.travel).abs() < 1e-12);
        assert!((l.attitude.toe - r.attitude.toe).abs() < 1e-10, "{} vs {}", l.attitude.toe, r.attitude.toe);
    }
    // Steering moves the wheel a lot in toe and the held wheel centre not at all in height.
    let (first, last) = (left.first().unwrap(), left.last().unwrap());
    assert!((last.attitude.toe - first.attitude.toe).abs().to_degrees() > 2.0);
    for row in &left {
        assert!((row.attitude.wheel_centre.z - mp.hardpoints.wheel_centre.z).abs() < 1e-10);
    }
}

/// The strut's sliding joint decides whether the top mount turns with the steering. Translational: the rod
/// turns with the upright, so the top-mount bushing's twist about the strut axis is the upright's rotation
/// about it. Cylindrical: the upright turns about the rod, and the bushing, holding only the rod's spin,
/// barely twists.
#[test]
fn a_cylindrical_strut_leaves_the_top_mount_out_of_the_steering() {
    use elastokin_core::math::rotation_log;
    use elastokin_solver::{LoadPath, SolverOptions, StaticSolver};
    use elastokin_suspensions::description::macpherson::StrutJoint;
    let bushed = Connection::Bushing(BushingRates::new(2e6, 1e6, 115.0, 2865.0));
    let h = MacPhersonHardpoints::generic();
    let strut_axis = (h.top_mount - h.strut_lower).normalize();
    let mut twists = Vec::new();
    for strut in [StrutJoint::Translational, StrutJoint::Cylindrical] {
        let mut t = template(bushed, bushed);
        t.strut = strut;
        let corner = t.build(Side::Left, Rig::Steering).unwrap();
        let model = &corner.model;
        let mut solver = StaticSolver::new(model, SolverOptions::default()).unwrap();
        let sweep = solver.sweep(LoadPath::new(0.0, 0.02, 4), Mode::Corrected).unwrap();
        let last = sweep.steps.last().unwrap();
        let top = model.element_id("top mount").unwrap();
        let twist = last.element_reports(model)[top.0].rotation.x;
        let upright = rotation_log(&last.poses[corner.wheel.upright.0].rotation()).dot(&strut_axis);
        twists.push((twist, upright));
    }
    let (translational, cylindrical) = (twists[0], twists[1]);
    // The rack's 20 mm steers the upright by several degrees about the strut axis either way.
    assert!(translational.1.abs() > 0.05 && cylindrical.1.abs() > 0.05, "{twists:?}");
    // Measured: 1.4e-17 rad: the rod turns with the upright exactly.
    assert!((translational.0 - translational.1).abs() < 1e-15, "{twists:?}");
    // Measured: 1.2e-16 rad of 0.10 rad: the cylindrical joint passes no moment about its axis, so nothing
    // twists the rod.
    assert!(cylindrical.0.abs() < 1e-14, "{twists:?}");
}

/// Each end of an arm takes its own bushing: at every step of a lateral load the front and rear bushings'
/// radial force over their radial deflection is the rate written for that end.
#[test]
fn each_arm_end_takes_its_own_bushing_rates() {
    use elastokin_solver::{LoadPath, SolverOptions, StaticSolver};
    use elastokin_suspensions::ArmMounts;
    let (front, rear) = (BushingRates::new(5e6, 1.2e6, 500.0, 5000.0), BushingRates::new(2.5e6, 0.7e6, 500.0, 5000.0));
    let mut t = template(Connection::Ideal, Connection::Ideal);
    t.lower_arm_mounts = ArmMounts { front: Connection::Bushing(front), rear: Connection::Bushing(rear) };
    let mut corner = t.build(Side::Left, Rig::HeightHeld).unwrap();
    let patch = corner.wheel.contact_patch;
    corner.add_wheel_force("lateral", patch, Vec3::new(-200.0, -3000.0, 0.0)).unwrap();
    let model = &corner.model;
    let mut solver = StaticSolver::new(model, SolverOptions::default()).unwrap();
    let sweep = solver.sweep(LoadPath::new(0.0, 1.0, 2), Mode::Corrected).unwrap();
    let last = sweep.steps.last().unwrap();
    let reports = last.element_reports(model);
    for (name, rates) in [("lower arm front bushing", front), ("lower arm rear bushing", rear)] {
        let r = reports[model.element_id(name).unwrap().0];
        let radial = r.deflection.y.hypot(r.deflection.z);
        assert!(radial > 1e-5, "{name} deflects: {radial}");
        // The force is reported in global axes; across the bushing's axis it is the radial rate times the
        // radial deflection (the frame moves with the chassis, which does not move).
        let axis = (t.hardpoints.lower_arm_rear - t.hardpoints.lower_arm_front).normalize();
        let across = (r.force - axis * r.force.dot(&axis)).norm();
        // Measured: 1.9e-16 relative.
        assert!((across / radial - rates.radial).abs() < 1e-14 * rates.radial, "{name}: {}", across / radial);
    }
}

/// A connection's own bushing axis: a bushing as stiff along its axis as across it, and as stiff in torsion
/// as in tilt, has no axis to speak of, so any axis gives the same corner (a symmetry); an anisotropic one
/// turned onto another axis gives another corner.
#[test]
fn a_bushing_axis_matters_only_to_an_anisotropic_bushing() {
    let toe_under_load = |rates: BushingRates| {
        let mut t = template(Connection::Bushing(rates), Connection::Ideal);
        t.tie_rod = Connection::Ideal;
        let mut corner = t.build(Side::Left, Rig::HeightHeld).unwrap();
        let patch = corner.wheel.contact_patch;
        corner.add_wheel_force("lateral", patch, Vec3::new(-500.0, -3000.0, 0.0)).unwrap();
        let mut solver =
            elastokin_solver::StaticSolver::new(&corner.model, elastokin_solver::SolverOptions::default()).unwrap();
        let sweep = solver.sweep(elastokin_solver::LoadPath::new(0.0, 1.0, 2), Mode::Corrected).unwrap();
        corner.wheel.attitude(&sweep.steps.last().unwrap().poses)
    };
    let tilted = Some([0.2, 0.9, 0.4]);
    let isotropic = BushingRates::new(3e6, 3e6, 2000.0, 2000.0);
    let (a, b) = (toe_under_load(isotropic), toe_under_load(BushingRates { axis: tilted, ..isotropic }));
    // Measured: 3.7e-16 rad.
    assert!((a.toe - b.toe).abs() < 1e-14 && (a.camber - b.camber).abs() < 1e-14, "{a:?} {b:?}");
    let anisotropic = BushingRates::new(5e6, 0.5e6, 300.0, 5000.0);
    let (c, d) = (toe_under_load(anisotropic), toe_under_load(BushingRates { axis: tilted, ..anisotropic }));
    // Measured: 4.1e-3 rad.
    assert!((c.toe - d.toe).abs() > 1e-5, "{c:?} {d:?}");
}
