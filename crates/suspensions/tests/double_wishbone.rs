//! Double wishbone against an independent loop closure, stiff bushings against ideal joints, mirror symmetry.

use elastokin_core::Vec3;
use elastokin_solver::Mode;
use elastokin_suspensions::analysis::parallel_wheel_travel;
use elastokin_suspensions::{
    BushingRates, Connection, DoubleWishbone, DoubleWishboneHardpoints, Rig, Side, SpringSpec,
};

mod common;

fn template(mounts: Connection) -> DoubleWishbone {
    DoubleWishbone {
        hardpoints: DoubleWishboneHardpoints::generic(),
        upper_arm_mounts: mounts.into(),
        lower_arm_mounts: mounts.into(),
        spring: SpringSpec { rate: 30e3, design_force: 4000.0 },
        tie_rod: Connection::Ideal,
        loaded_radius: 0.30,
    }
}

#[test]
fn toe_and_camber_match_an_independent_loop_closure() {
    let dw = template(Connection::Ideal);
    let corner = dw.build(Side::Left, Rig::WheelTravel).unwrap();
    let rows = parallel_wheel_travel(&corner, -0.08, 0.08, 32, Mode::Corrected).unwrap();
    let mut guess = [0.0; 3];
    let mut largest_camber: f64 = 0.0;
    // Walk outwards from design so the loop closure's Newton always starts close.
    let mut order: Vec<usize> = (0..rows.len()).collect();
    order.sort_by(|&a, &b| rows[a].travel.abs().total_cmp(&rows[b].travel.abs()));
    let mut guesses = [[0.0; 3]; 2];
    for k in order {
        let row = rows[k];
        let g = &mut guesses[usize::from(row.travel > 0.0)];
        guess.copy_from_slice(g);
        let (toe, camber) = common::double_wishbone_closure(&dw.hardpoints, row.travel, &mut guess);
        g.copy_from_slice(&guess);
        assert!((row.attitude.toe - toe).abs() < 1e-9, "travel {}: toe {} vs {toe}", row.travel, row.attitude.toe);
        assert!(
            (row.attitude.camber - camber).abs() < 1e-9,
            "travel {}: camber {} vs {camber}",
            row.travel,
            row.attitude.camber
        );
        assert!((row.attitude.wheel_centre.z - (dw.hardpoints.wheel_centre.z + row.travel)).abs() < 1e-10);
        largest_camber = largest_camber.max(camber.abs());
    }
    // The test must exercise real motion: the generic set gains over a degree of camber in ±80 mm.
    assert!(largest_camber.to_degrees() > 1.0, "{}", largest_camber.to_degrees());
}

#[test]
fn stiffer_bushings_converge_to_the_ideal_joint_curves() {
    let ideal = parallel_wheel_travel(
        &template(Connection::Ideal).build(Side::Left, Rig::WheelTravel).unwrap(),
        -0.06,
        0.06,
        12,
        Mode::Corrected,
    )
    .unwrap();
    // Realistic control-arm bushings: radial 5 kN/mm, axial 1 kN/mm, torsion 10 N·m/deg, conical 100 N·m/deg.
    let rates = BushingRates::new(5e6, 1e6, 10f64.to_degrees(), 100f64.to_degrees());
    let deviation = |scale: f64| {
        // The ideal revolute turns freely about its axis, so the torsion rate stays; the directions the
        // joint locks get stiffer. (Scaling torsion too leaves a gap that does not close: the torsion
        // moment and the radial rate that resists it grow together.)
        let stiffer = BushingRates { torsion: rates.torsion, ..rates.scaled(scale) };
        let corner = template(Connection::Bushing(stiffer)).build(Side::Left, Rig::WheelTravel).unwrap();
        let rows = parallel_wheel_travel(&corner, -0.06, 0.06, 12, Mode::Corrected).unwrap();
        rows.iter()
            .zip(&ideal)
            .map(|(b, i)| (b.attitude.toe - i.attitude.toe).abs().max((b.attitude.camber - i.attitude.camber).abs()))
            .fold(0.0, f64::max)
    };
    let (d1, d100, d10000) = (deviation(1.0), deviation(1e2), deviation(1e4));
    // Compliance deflections scale with 1/stiffness: each factor 100 in rates cuts the gap ~100×.
    assert!(d1 > 1e-6, "realistic bushings must show compliance: {d1}");
    assert!(d100 < d1 / 30.0 && d10000 < d100 / 30.0, "{d1:e} {d100:e} {d10000:e}");
    assert!(d10000 < 1e-6, "{d10000:e}");
}

#[test]
fn right_side_mirrors_the_left() {
    let dw = template(Connection::Ideal);
    let left =
        parallel_wheel_travel(&dw.build(Side::Left, Rig::WheelTravel).unwrap(), -0.05, 0.05, 10, Mode::Corrected)
            .unwrap();
    let right =
        parallel_wheel_travel(&dw.build(Side::Right, Rig::WheelTravel).unwrap(), -0.05, 0.05, 10, Mode::Corrected)
            .unwrap();
    for (l, r) in left.iter().zip(&right) {
        assert!((l.attitude.toe - r.attitude.toe).abs() < 1e-12, "{} {}", l.attitude.toe, r.attitude.toe);
        assert!((l.attitude.camber - r.attitude.camber).abs() < 1e-12);
        let (wl, wr) = (l.attitude.wheel_centre, r.attitude.wheel_centre);
        assert!((wl - Vec3::new(wr.x, -wr.y, wr.z)).norm() < 1e-12);
    }
}

/// Vertical force sweep on the ideal double wishbone against a second method: the kinematic sweep gives
/// the spring length L(z) and contact-patch height along the path, and virtual work with the closed-form
/// spring law gives the force that holds each position, F = −F_push(L) · dL/dz_cp.
#[test]
fn vertical_force_sweep_balances_the_spring_by_virtual_work() {
    let dw = template(Connection::Ideal);
    let rows = elastokin_suspensions::analysis::vertical_force_sweep(
        dw.build(Side::Left, Rig::Free).unwrap(),
        // Around the design corner load (~1.5 kN here: 4 kN of spring force through a motion ratio of ~0.37).
        1200.0,
        1800.0,
        6,
        Mode::Corrected,
    )
    .unwrap();
    let h = dw.hardpoints;
    let spring_length_at = |travel: f64| {
        // Lower arm angle for this travel from a short driven sweep, then the seat position on the arm.
        let corner = dw.build(Side::Left, Rig::WheelTravel).unwrap();
        let mut solver =
            elastokin_solver::StaticSolver::new(&corner.model, elastokin_solver::SolverOptions::default()).unwrap();
        let mut state = solver.design_state(travel);
        let eq = solver.equilibrium(&mut state).unwrap();
        let arm = eq.poses[corner.model.body_id("lower arm").unwrap().0];
        let seat = arm.point(&corner.model.bodies()[2].design_pose.to_local_point(&h.spring_arm));
        let upright = eq.poses[corner.wheel.upright.0];
        let patch = upright.point(&(corner.wheel.contact_patch - corner.wheel.wheel_centre));
        ((seat - h.spring_chassis).norm(), patch.z)
    };
    let free_length = (h.spring_arm - h.spring_chassis).norm() + dw.spring.design_force / dw.spring.rate;
    for row in &rows {
        let travel = row.attitude.wheel_centre.z - h.wheel_centre.z;
        let e = 1e-5;
        let (lp, zp) = spring_length_at(travel + e);
        let (lm, zm) = spring_length_at(travel - e);
        let (l, _) = spring_length_at(travel);
        let push = dw.spring.rate * (free_length - l);
        // Virtual work: F δz_cp = δU_spring = −push δL (the spring pushes its seats apart) → F = −push dL/dz_cp.
        let force = -push * (lp - lm) / (zp - zm);
        assert!((force - row.load).abs() < 1e-4 * row.load, "F = {} vs virtual work {force}", row.load);
    }
}

#[test]
fn steering_axis_geometry_at_design_and_mirrored() {
    let dw = template(Connection::Ideal);
    let left = dw.build(Side::Left, Rig::WheelTravel).unwrap();
    let g = left.wheel.steering_geometry(&left.model.design_poses());
    // By hand from the generic hardpoints: u = UBJ − LBJ = (−0.048, −0.090, 0.508); the ground is 0.30 m
    // below the wheel centre (z = −0.326).
    let u = Vec3::new(-0.048, -0.090, 0.508);
    let lbj = Vec3::new(-0.040, 0.898, -0.265);
    let ground = lbj + u * ((-0.326 - -0.265) / 0.508);
    let at_wc = lbj + u * ((-0.026 - -0.265) / 0.508);
    assert!((g.caster - (0.048f64 / 0.508).atan()).abs() < 1e-12, "{}", g.caster.to_degrees());
    assert!((g.kingpin_inclination - (0.090f64 / 0.508).atan()).abs() < 1e-12);
    assert!((g.scrub_radius - (1.100 - ground.y)).abs() < 1e-12, "{}", g.scrub_radius);
    assert!((g.mechanical_trail - (ground.x - -0.040)).abs() < 1e-12, "{}", g.mechanical_trail);
    assert!((g.kingpin_offset - (1.100 - at_wc.y)).abs() < 1e-12, "{}", g.kingpin_offset);
    // Through travel, the right corner gives the same numbers.
    let right = dw.build(Side::Right, Rig::WheelTravel).unwrap();
    for t in [-0.05, 0.04] {
        let geometry = |c: &elastokin_suspensions::Corner| {
            let mut solver =
                elastokin_solver::StaticSolver::new(&c.model, elastokin_solver::SolverOptions::default()).unwrap();
            let mut state = solver.design_state(t);
            solver.equilibrium(&mut state).unwrap();
            c.wheel.steering_geometry(&state.poses)
        };
        let (l, r) = (geometry(&left), geometry(&right));
        for (a, b) in [
            (l.caster, r.caster),
            (l.kingpin_inclination, r.kingpin_inclination),
            (l.scrub_radius, r.scrub_radius),
            (l.mechanical_trail, r.mechanical_trail),
            (l.kingpin_offset, r.kingpin_offset),
        ] {
            assert!((a - b).abs() < 1e-12, "{a} vs {b}");
        }
    }
}

/// The rig's holding force (from the driver's multiplier) against virtual work with the spring law and
/// the kinematic spring length, and the wheel rate from it against the same second method.
#[test]
fn wheel_load_and_wheel_rate_match_virtual_work() {
    let dw = template(Connection::Ideal);
    let corner = dw.build(Side::Left, Rig::WheelTravel).unwrap();
    let rows = parallel_wheel_travel(&corner, -0.04, 0.04, 16, Mode::Corrected).unwrap();
    let free_length =
        (dw.hardpoints.spring_arm - dw.hardpoints.spring_chassis).norm() + dw.spring.design_force / dw.spring.rate;
    // Virtual work with the rig holding the wheel centre: F δz_wc = δU_spring = −push δL,
    // push = k (L₀ − L) = −k · deflection.
    let virtual_force = |k: usize| {
        let dl =
            (rows[k + 1].spring_deflection - rows[k - 1].spring_deflection) / (rows[k + 1].travel - rows[k - 1].travel);
        let push = -dw.spring.rate * rows[k].spring_deflection;
        -push * dl
    };
    for k in 1..rows.len() - 1 {
        let expected = virtual_force(k);
        // The central difference of L(z) over 5 mm is good to ~1e-4 here.
        assert!(
            (rows[k].wheel_load - expected).abs() < 2e-3 * expected.abs(),
            "travel {}: {} vs {expected}",
            rows[k].travel,
            rows[k].wheel_load
        );
    }
    // Spring deflection at design is the design preload over the rate.
    let design = &rows[8];
    assert!(design.travel.abs() < 1e-12);
    let design_length = (dw.hardpoints.spring_arm - dw.hardpoints.spring_chassis).norm();
    assert!((design.spring_deflection - (design_length - free_length)).abs() < 1e-12);
    // Wheel rate: positive and of the size k·MR² (MR from the spring's travel ratio).
    let mr = (rows[9].spring_deflection - rows[7].spring_deflection) / (rows[9].travel - rows[7].travel);
    let rate = (rows[9].wheel_load - rows[7].wheel_load) / (rows[9].travel - rows[7].travel);
    assert!(
        rate > 0.0 && (rate - dw.spring.rate * mr * mr).abs() < 0.3 * rate,
        "rate {rate}, k·MR² {}",
        dw.spring.rate * mr * mr
    );
}

/// The general-form axle example (`examples/double_wishbone_axle.json`) with its arm bushings made ideal
/// pivots: its travel is the loop closure of its own hardpoints, stops and all (a stop changes the rig's
/// force, not the driven linkage's positions).
#[test]
fn the_general_axle_example_matches_the_loop_closure() {
    use elastokin_core::JointKind;
    use elastokin_suspensions::description::general::{Axis, JointDef, Place};
    use elastokin_suspensions::{SuspensionFile, Template};
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/double_wishbone_axle.json");
    let mut file = SuspensionFile::read(&path).unwrap();
    let Template::General(ref mut g) = file.suspension else { panic!("general form") };
    assert!(!g.stops.is_empty() && !g.anti_roll_bars.is_empty());
    g.bushings.retain(|b| !b.name.contains("arm"));
    for arm in ["upper", "lower"] {
        let (front, rear) = (format!("{arm}_arm_front"), format!("{arm}_arm_rear"));
        g.joints.push(JointDef {
            name: format!("{arm} arm pivot"),
            kind: JointKind::Revolute,
            bodies: ["chassis".into(), format!("{arm} arm")],
            at: Some(Place::named(&front)),
            to: None,
            axis: Some(Axis::through(&front, &rear)),
            axis_j: None,
        });
    }
    let p = |n: &str| g.hardpoints.get(n).unwrap();
    let h = DoubleWishboneHardpoints {
        wheel_centre: p("wheel_centre"),
        upper_ball_joint: p("upper_ball_joint"),
        upper_arm_front: p("upper_arm_front"),
        upper_arm_rear: p("upper_arm_rear"),
        lower_ball_joint: p("lower_ball_joint"),
        lower_arm_front: p("lower_arm_front"),
        lower_arm_rear: p("lower_arm_rear"),
        tie_rod_inner: p("tie_rod_inner"),
        tie_rod_outer: p("tie_rod_outer"),
        spring_chassis: p("spring_chassis"),
        spring_arm: p("spring_arm"),
    };
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let worst = common::travel_against_closure(&corner, |t, g| common::double_wishbone_closure(&h, t, g));
    // Measured: 7.7e-13 rad.
    assert!(worst < 1e-11, "{worst:e}");
}
