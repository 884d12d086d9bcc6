//! The full axle: roll centre against finite differences of a lone corner, mirror symmetry in roll, both
//! wheels of the axle against their own corners, one rack steering both wheels, and the bushed tie rod
//! against the distance constraint.

use elastokin_solver::{Mode, SolverOptions, StaticSolver};
use elastokin_suspensions::analysis::axle_sweep;
use elastokin_suspensions::analysis::{parallel_wheel_travel, steering};
use elastokin_suspensions::{
    Axle, AxleRig, BushingRates, Connection, DoubleWishbone, DoubleWishboneHardpoints, MacPherson,
    MacPhersonHardpoints, Rig, Side, SpringSpec,
};

fn double_wishbone(tie_rod: Connection) -> DoubleWishbone {
    DoubleWishbone {
        hardpoints: DoubleWishboneHardpoints::generic(),
        upper_arm_mounts: Connection::Ideal.into(),
        lower_arm_mounts: Connection::Ideal.into(),
        spring: SpringSpec { rate: 30e3, design_force: 4000.0 },
        tie_rod,
        loaded_radius: 0.30,
    }
}

fn macpherson() -> MacPherson {
    MacPherson {
        hardpoints: MacPhersonHardpoints::generic(),
        lower_arm_mounts: Connection::Ideal.into(),
        top_mount: Connection::Ideal,
        strut: Default::default(),
        spring: SpringSpec { rate: 30e3, design_force: 4500.0 },
        tie_rod: Connection::Ideal,
        loaded_radius: 0.30,
    }
}

/// Front-view roll-centre height of a symmetric axle from a lone left corner, by central differences of
/// driven equilibria: the upright's material point at the contact patch moves with (v_y, v_z) per metre
/// of travel; the line through the patch perpendicular to that meets the centre plane y = 0 at height
/// y_P · v_y / v_z above the patch.
fn roll_centre_height_by_finite_differences(corner: &elastokin_suspensions::Corner) -> f64 {
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default()).unwrap();
    let wheel = &corner.wheel;
    let local = corner.model.bodies()[wheel.upright.0].design_pose.to_local_point(&wheel.contact_patch);
    let mut at = |travel: f64| {
        let mut state = solver.design_state(travel);
        solver.equilibrium(&mut state).unwrap();
        state.poses[wheel.upright.0].point(&local)
    };
    let h = 1e-5;
    let v = (at(h) - at(-h)) / (2.0 * h);
    wheel.contact_patch.y * v.y / v.z
}

#[test]
fn pure_roll_puts_the_roll_centre_on_the_centre_plane() {
    for (name, template, axle) in [
        (
            "double wishbone",
            double_wishbone(Connection::Ideal).build(Side::Left, Rig::WheelTravel).unwrap(),
            Axle::build(&double_wishbone(Connection::Ideal), AxleRig::OppositeTravel).unwrap(),
        ),
        (
            "MacPherson",
            macpherson().build(Side::Left, Rig::WheelTravel).unwrap(),
            Axle::build(&macpherson(), AxleRig::OppositeTravel).unwrap(),
        ),
    ] {
        let rows = axle_sweep(&axle, -0.04, 0.04, 8, Mode::Corrected).unwrap();
        let design = &rows[4];
        assert_eq!(design.travel, 0.0);
        let rc = design.roll_centre.expect("the force lines of a symmetric axle cross");
        let expected = roll_centre_height_by_finite_differences(&template);
        // Measured: lateral ~1e-15 m; height agrees to ~1e-10 m (the finite difference's own error).
        assert!(rc.lateral.abs() < 1e-12, "{name}: roll centre {} m off the centre plane", rc.lateral);
        assert!((rc.height - expected).abs() < 1e-7, "{name}: height {} vs finite differences {expected}", rc.height);
        // A real car's roll centre sits between the ground and the wheel centre.
        assert!(rc.height > 0.0 && rc.height < 0.3, "{name}: implausible roll centre height {}", rc.height);
        // Left bump and right rebound roll the body's left side down: negative roll about +x.
        assert!(rows[8].roll_angle < 0.0 && rows[0].roll_angle > 0.0);
    }
}

#[test]
fn roll_left_and_roll_right_are_mirror_images() {
    let axle = Axle::build(&double_wishbone(Connection::Ideal), AxleRig::OppositeTravel).unwrap();
    let rows = axle_sweep(&axle, -0.04, 0.04, 8, Mode::Corrected).unwrap();
    for k in 0..rows.len() {
        let (a, b) = (&rows[k], &rows[rows.len() - 1 - k]);
        assert!((a.travel + b.travel).abs() < 1e-15);
        let (ra, rb) = (a.roll_centre.unwrap(), b.roll_centre.unwrap());
        assert!((ra.lateral + rb.lateral).abs() < 1e-9, "roll centre lateral {} vs {}", ra.lateral, rb.lateral);
        assert!((ra.height - rb.height).abs() < 1e-9);
        // The two rows are reached by different Newton histories (one is the sweep's start, the other its
        // end): they agree to the equilibrium tolerance, measured 1.7e-10 rad.
        assert!((a.left.toe - b.right.toe).abs() < 1e-9 && (a.left.camber - b.right.camber).abs() < 1e-9);
        assert!((a.roll_angle + b.roll_angle).abs() < 1e-9);
        assert!((a.roll_moment + b.roll_moment).abs() < 1e-6 * a.roll_moment.abs().max(1.0));
    }
    // Under roll the roll centre leaves the centre plane (the geometric roll centre migrates sideways).
    assert!(rows[0].roll_centre.unwrap().lateral.abs() > 1e-3);
}

/// With the rack fixed and nothing coupling the sides, each wheel of the axle in opposite travel moves as
/// its own corner in parallel travel (the left by +t, the right by −t): a second model of the same motion.
#[test]
fn opposite_travel_moves_each_wheel_as_its_own_corner() {
    let template = double_wishbone(Connection::Ideal);
    let axle = Axle::build(&template, AxleRig::OppositeTravel).unwrap();
    let rows = axle_sweep(&axle, -0.04, 0.04, 8, Mode::Corrected).unwrap();
    let left =
        parallel_wheel_travel(&template.build(Side::Left, Rig::WheelTravel).unwrap(), -0.04, 0.04, 8, Mode::Corrected)
            .unwrap();
    let right =
        parallel_wheel_travel(&template.build(Side::Right, Rig::WheelTravel).unwrap(), 0.04, -0.04, 8, Mode::Corrected)
            .unwrap();
    for ((a, l), r) in rows.iter().zip(&left).zip(&right) {
        assert!((a.left.toe - l.attitude.toe).abs() < 1e-10 && (a.left.camber - l.attitude.camber).abs() < 1e-10);
        assert!((a.right.toe - r.attitude.toe).abs() < 1e-10 && (a.right.camber - r.attitude.camber).abs() < 1e-10);
        assert!((a.left_load - l.wheel_load).abs() < 1e-6 && (a.right_load - r.wheel_load).abs() < 1e-6);
        let expected_track = l.steering.contact_patch.y - r.steering.contact_patch.y;
        assert!((a.track - expected_track).abs() < 1e-10);
    }
}

#[test]
fn parallel_travel_keeps_the_roll_centre_on_the_centre_plane() {
    let template = double_wishbone(Connection::Ideal);
    let axle = Axle::build(&template, AxleRig::ParallelTravel).unwrap();
    let rows = axle_sweep(&axle, -0.06, 0.06, 6, Mode::Corrected).unwrap();
    let roll =
        axle_sweep(&Axle::build(&template, AxleRig::OppositeTravel).unwrap(), -0.01, 0.01, 2, Mode::Corrected).unwrap();
    for row in &rows {
        let rc = row.roll_centre.unwrap();
        assert!(rc.lateral.abs() < 1e-10, "parallel travel: roll centre {} m off the centre plane", rc.lateral);
        assert!(row.roll_angle.abs() < 1e-12);
    }
    // At design both tests see the same instantaneous motion: the same roll centre.
    let (a, b) = (rows[3].roll_centre.unwrap(), roll[1].roll_centre.unwrap());
    assert!((a.height - b.height).abs() < 1e-12);
    // Track at design: twice the contact patch's lateral position, from the hardpoints.
    assert!((rows[3].track - 2.0 * template.hardpoints.wheel_centre.y).abs() < 1e-12);
    // The roll centre migrates with heave (it drops in bump for this geometry): not a constant.
    assert!((rows[0].roll_centre.unwrap().height - rows[6].roll_centre.unwrap().height).abs() > 1e-3);
}

#[test]
fn one_rack_steers_both_wheels() {
    let template = macpherson();
    let axle = Axle::build(&template, AxleRig::Steering).unwrap();
    let rows = axle_sweep(&axle, -0.02, 0.02, 8, Mode::Corrected).unwrap();
    let left = steering(&template.build(Side::Left, Rig::Steering).unwrap(), -0.02, 0.02, 8, Mode::Corrected).unwrap();
    for (k, row) in rows.iter().enumerate() {
        let mirror = &rows[rows.len() - 1 - k];
        // Mirror: rack travel +s turns the left wheel as −s turns the right.
        assert!((row.left.toe - mirror.right.toe).abs() < 1e-12);
        // The shared rack moves the left tie rod as a corner's own rack does.
        assert!((row.left.toe - left[k].attitude.toe).abs() < 1e-10);
        // Heights held on both sides.
        assert!((row.left.wheel_centre.z - template.hardpoints.wheel_centre.z).abs() < 1e-12);
        assert!((row.right.wheel_centre.z - template.hardpoints.wheel_centre.z).abs() < 1e-12);
        assert!(row.roll_centre.is_none());
    }
    // Rack to the left (+y) pulls the right wheel's tie rod: both wheels steer the same way (left toe-out
    // when the right toes in, or the reverse), by more than a degree over 20 mm.
    let last = rows.last().unwrap();
    assert!(last.left.toe * last.right.toe < 0.0 && last.left.toe.abs() > 1f64.to_radians());
}

#[test]
fn axle_rigs_that_drive_nothing_are_refused() {
    let axle = Axle::build(&macpherson(), AxleRig::HeightHeld).unwrap();
    let err = axle_sweep(&axle, 0.0, 1.0, 2, Mode::Corrected).unwrap_err().to_string();
    assert!(err.contains("HeightHeld"), "{err}");
}

/// A tie rod as a rod with a bushing at each end converges to the distance constraint as its axial and
/// radial rates grow (torsion and conical, which a pair of ball joints leaves free, stay soft).
#[test]
fn stiff_bushed_tie_rod_converges_to_the_distance_constraint() {
    let ideal = parallel_wheel_travel(
        &double_wishbone(Connection::Ideal).build(Side::Left, Rig::WheelTravel).unwrap(),
        -0.06,
        0.06,
        4,
        Mode::Corrected,
    )
    .unwrap();
    // Rates up to 1e10 N/m: beyond that the rod's spin (held by 10 N·m/rad of torsion) is below the
    // restraint check's pivot tolerance relative to the radial rates, and the model is refused as
    // unrestrained.
    let mut gaps = Vec::new();
    for rate in [1e6, 1e8, 1e10] {
        let rates = BushingRates::new(rate, rate, 10.0, 10.0);
        let corner = double_wishbone(Connection::Bushing(rates)).build(Side::Left, Rig::WheelTravel).unwrap();
        assert!(
            corner.model.body_id("tie rod").is_some() && corner.model.element_id("tie rod inner bushing").is_some()
        );
        let rows = parallel_wheel_travel(&corner, -0.06, 0.06, 4, Mode::Corrected).unwrap();
        let gap = rows.iter().zip(&ideal).map(|(a, b)| (a.attitude.toe - b.attitude.toe).abs()).fold(0.0, f64::max);
        gaps.push(gap);
    }
    // Measured gaps 3.6e-3, 3.6e-5, 3.6e-7 rad: 100× per 100× in rate, as the rod's series compliance.
    assert!(gaps[0] > 30.0 * gaps[1] && gaps[1] > 30.0 * gaps[2], "toe gaps {gaps:?}");
    assert!(gaps[2] < 1e-6, "toe gaps {gaps:?}");
    // And a soft rod really does steer under travel differently (the test can see the bushings).
    assert!(gaps[0] > 1e-6, "toe gaps {gaps:?}");
}
