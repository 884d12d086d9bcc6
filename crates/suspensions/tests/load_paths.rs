//! Road loads walked by the engine (lateral, braking, traction, aligning torque), the static load case and
//! anti-pitch geometry, each against a second method: the linear tangent, the chassis holding the corner
//! in equilibrium, driven equilibria, virtual work, a closed-form side view, mirror symmetry.

use elastokin_core::Vec3;
use elastokin_elements::PointForce;
use elastokin_solver::{Mode, SolverError, SolverOptions, StaticSolver, StepResult};
use elastokin_suspensions::analysis::{
    anti_pitch, parallel_wheel_travel, patch_compliance, static_load_case, vertical_force_sweep, wheel_compliance,
    wheel_load_sweep, ComponentForces, LoadRow, WheelLoad,
};
use elastokin_suspensions::description::{AxlePosition, VehicleParameters};
use elastokin_suspensions::{
    Connection, Corner, DoubleWishbone, DoubleWishboneHardpoints, MacPherson, Rig, Side, SpringSpec, SuspensionFile,
    Template,
};

/// The shipped bushed MacPherson (also the one of `tests/compliance.rs`).
fn bushed_macpherson() -> MacPherson {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/generic/macpherson.json");
    match SuspensionFile::read(path.as_ref()).unwrap().suspension {
        Template::MacPherson(mp) => mp,
        other => panic!("{other:?}"),
    }
}

/// The vertical load the sweeps carry: near the bushed MacPherson's design corner load (the rig holds the
/// design height with 4143 N, see `parallel_wheel_travel`), so the free wheel rides near design.
const CORNER_LOAD: f64 = 4100.0;

/// Adds a constant upward force `load` at the design contact patch, as the load analyses do.
fn add_constant_corner_load(corner: &mut Corner, load: f64) {
    let force =
        PointForce::new("probe corner load", corner.wheel.upright.into(), corner.wheel.contact_patch, Vec3::zeros())
            .unwrap()
            .with_constant(Vec3::new(0.0, 0.0, load))
            .unwrap();
    corner.model.add_element(force).unwrap();
}

/// Slope of `y` over a three-row sweep from −h to h.
fn slope(rows: &[LoadRow], y: impl Fn(&LoadRow) -> f64) -> f64 {
    assert_eq!(rows.len(), 3);
    (y(&rows[2]) - y(&rows[0])) / (rows[2].load - rows[0].load)
}

fn close(a: f64, b: f64, relative: f64, what: &str) {
    assert!((a - b).abs() <= relative * b.abs(), "{what}: {a:e} vs {b:e} (relative {:e})", (a - b).abs() / b.abs());
}

#[test]
fn slopes_at_zero_load_equal_the_patch_compliance_for_both_rigs() {
    let mp = bushed_macpherson();
    for rig in [Rig::HeightHeld, Rig::Free] {
        // Second method: the compliance from the tangent at the same equilibrium.
        let mut reference = mp.build(Side::Left, rig).unwrap();
        add_constant_corner_load(&mut reference, CORNER_LOAD);
        let pc = patch_compliance(&reference, 0.0).unwrap();
        let c = wheel_compliance(&reference, 0.0).unwrap();
        let sweep = |load: WheelLoad, h: f64| {
            wheel_load_sweep(mp.build(Side::Left, rig).unwrap(), load, CORNER_LOAD, -h, h, 2, Mode::Corrected).unwrap()
        };
        let inboard = Vec3::new(0.0, -1.0, 0.0);
        let rearward = Vec3::new(-1.0, 0.0, 0.0);
        // ±10 N, ±10 N·m: deep in the linear range. Measured: every slope agrees to < 1e-6 relative.
        let lateral = sweep(WheelLoad::Lateral, 10.0);
        close(slope(&lateral, |r| r.attitude.toe), pc.lateral_steer, 1e-5, "lateral steer");
        close(slope(&lateral, |r| r.attitude.camber), pc.lateral_camber, 1e-5, "lateral camber");
        close(
            1.0 / slope(&lateral, |r| r.patch_displacement.dot(&inboard)),
            pc.lateral_stiffness,
            1e-5,
            "lateral stiffness",
        );
        let braking = sweep(WheelLoad::Braking, 10.0);
        close(slope(&braking, |r| r.attitude.toe), pc.braking_steer, 1e-5, "braking steer");
        close(
            1.0 / slope(&braking, |r| r.patch_displacement.dot(&rearward)),
            pc.longitudinal_stiffness,
            1e-5,
            "longitudinal stiffness",
        );
        let torque = sweep(WheelLoad::AligningTorque, 10.0);
        close(slope(&torque, |r| r.attitude.toe), pc.aligning_torque_steer, 1e-5, "aligning-torque steer");
        // Traction acts at the wheel centre: the first column of the wheel compliance.
        let traction = sweep(WheelLoad::Traction, 10.0);
        close(slope(&traction, |r| r.attitude.wheel_centre.x), c[0][0], 1e-5, "fore-aft compliance");
        close(slope(&traction, |r| r.attitude.wheel_centre.y), c[1][0], 1e-5, "lateral response to traction");
        println!(
            "{rig:?}: lateral steer {:.4} °/kN, camber {:.4} °/kN, stiffness {:.0} N/mm; braking steer {:.4} °/kN, \
             longitudinal stiffness {:.0} N/mm; aligning-torque steer {:.4} °/(kN·m); fore-aft compliance {:.4} mm/kN",
            pc.lateral_steer.to_degrees() * 1e3,
            pc.lateral_camber.to_degrees() * 1e3,
            pc.lateral_stiffness * 1e-3,
            pc.braking_steer.to_degrees() * 1e3,
            pc.longitudinal_stiffness * 1e-3,
            pc.aligning_torque_steer.to_degrees() * 1e3,
            c[0][0] * 1e6
        );
    }
}

/// Sums the forces the ground applies to the moving parts through the components of `forces`.
fn forces_from_ground(forces: &ComponentForces) -> (Vec3, f64) {
    let mut sum = Vec3::zeros();
    let mut largest: f64 = 0.0;
    for c in forces.joints.iter().chain(&forces.elements) {
        largest = largest.max(c.force.norm());
        if &*c.other_body == "ground" {
            sum += c.force;
        } else if &*c.body == "ground" {
            sum -= c.force;
        }
    }
    (sum, largest)
}

/// Conservation law: the chassis (ground) holds the loaded corner, so the forces it applies through the
/// chassis-side joints, bushings, spring and rig, with the applied loads, add up to zero.
#[test]
fn chassis_forces_balance_the_applied_loads_along_a_sweep() {
    let mp = bushed_macpherson();
    for (rig, load) in [(Rig::HeightHeld, WheelLoad::Lateral), (Rig::Free, WheelLoad::Braking)] {
        let rows =
            wheel_load_sweep(mp.build(Side::Left, rig).unwrap(), load, CORNER_LOAD, 0.0, 3000.0, 6, Mode::Corrected)
                .unwrap();
        let last = rows.last().unwrap();
        let (sum, largest) = forces_from_ground(&last.forces);
        // Each of the few bodies is in equilibrium to 1e-9 of the largest force (the solver's tolerance).
        // Measured: 2e-13.
        assert!(sum.norm() < 1e-8 * largest, "{rig:?} {load:?}: ΣF = {sum:?} against {largest} N");
        // The applied loads are in the list, at their full value.
        let applied = last.forces.elements.iter().find(|e| e.name.ends_with(" force")).unwrap();
        assert!((applied.force.norm() - 3000.0).abs() < 1e-9, "{applied:?}");
        assert!((last.forces.element("corner load").unwrap().force.z - CORNER_LOAD).abs() < 1e-9);
        // The rig's holding force is the wheel-travel driver's force.
        let driver = last.forces.joint("wheel travel").map_or(0.0, |d| d.force.z);
        assert_eq!(driver, last.wheel_load);
        if rig == Rig::Free {
            assert_eq!(last.wheel_load, 0.0);
        } else {
            assert!(last.wheel_load.abs() > 1.0);
        }
    }
}

#[test]
fn paper_mode_converges_to_corrected_mode_as_the_steps_shrink() {
    let mp = bushed_macpherson();
    for load in [WheelLoad::Braking, WheelLoad::Traction] {
        let run = |steps: usize, mode: Mode| {
            let corner = mp.build(Side::Left, Rig::HeightHeld).unwrap();
            let rows = wheel_load_sweep(corner, load, CORNER_LOAD, 0.0, 4000.0, steps, mode).unwrap();
            let last = rows.last().unwrap().attitude;
            assert_eq!(rows.last().unwrap().load, 4000.0);
            (last.toe, last.camber)
        };
        let exact = run(8, Mode::Corrected);
        // The corrected walk does not depend on its step.
        let finer = run(64, Mode::Corrected);
        assert!((exact.0 - finer.0).abs() < 1e-12 && (exact.1 - finer.1).abs() < 1e-12);
        let errors: Vec<(f64, f64)> = [8, 16, 32, 64]
            .iter()
            .map(|&n| {
                let paper = run(n, Mode::Paper);
                (paper.0 - exact.0, paper.1 - exact.1)
            })
            .collect();
        println!("{load:?}: paper-mode (toe, camber) error at 4 kN for 8, 16, 32, 64 steps: {errors:?}");
        // O(Δf): each halving of the step halves the error of toe and of camber (measured ratios 1.87–2.02;
        // the toe and camber changes at 4 kN are 3e-4 to 9e-4 rad).
        for pair in errors.windows(2) {
            let ratios = (pair[0].0 / pair[1].0, pair[0].1 / pair[1].1);
            assert!((1.7..2.3).contains(&ratios.0) && (1.7..2.3).contains(&ratios.1), "{load:?}: {errors:?}");
        }
        // A real error to shrink: measured 5e-7 to 7e-6 rad at 8 steps.
        assert!(errors[0].0.abs() > 1e-7 && errors[0].1.abs() > 1e-7, "{errors:?}");
    }
}

#[test]
fn right_corner_mirrors_the_left_under_every_load() {
    let mp = bushed_macpherson();
    for load in [WheelLoad::Lateral, WheelLoad::Braking, WheelLoad::Traction, WheelLoad::AligningTorque] {
        // Mirroring y → −y turns a torque about +z into one about −z; forces keep their meaning (lateral is
        // inboard on either side).
        let right_sign = if load == WheelLoad::AligningTorque { -1.0 } else { 1.0 };
        let sweep = |side: Side, sign: f64| {
            let corner = mp.build(side, Rig::HeightHeld).unwrap();
            wheel_load_sweep(corner, load, CORNER_LOAD, 0.0, sign * 2000.0, 4, Mode::Corrected).unwrap()
        };
        let (left, right) = (sweep(Side::Left, 1.0), sweep(Side::Right, right_sign));
        let mirror = |v: Vec3| Vec3::new(v.x, -v.y, v.z);
        let mut largest_toe: f64 = 0.0;
        for (l, r) in left.iter().zip(&right) {
            assert!(
                (l.attitude.toe - r.attitude.toe).abs() < 1e-12,
                "{load:?}: {} vs {}",
                l.attitude.toe,
                r.attitude.toe
            );
            assert!((l.attitude.camber - r.attitude.camber).abs() < 1e-12);
            assert!((l.attitude.wheel_centre - mirror(r.attitude.wheel_centre)).norm() < 1e-12);
            assert!((l.patch_displacement - mirror(r.patch_displacement)).norm() < 1e-12);
            assert!((l.wheel_load - r.wheel_load).abs() < 1e-12 * l.wheel_load.abs());
            largest_toe = largest_toe.max((l.attitude.toe - left[0].attitude.toe).abs());
        }
        assert!(largest_toe > 1e-5, "{load:?} must steer the bushed corner: {largest_toe:e}");
    }
}

#[test]
fn load_sweeps_refuse_other_rigs() {
    let mp = bushed_macpherson();
    let refused = |e: SolverError, needs: &str| match e {
        SolverError::InvalidInput { what: "corner", why } => assert!(why.contains(needs), "{why}"),
        other => panic!("{other:?}"),
    };
    let e = wheel_load_sweep(
        mp.build(Side::Left, Rig::WheelTravel).unwrap(),
        WheelLoad::Lateral,
        0.0,
        0.0,
        1.0,
        1,
        Mode::Paper,
    )
    .unwrap_err();
    refused(e, "the wheel-centre height held or the wheel free on its spring");
    refused(
        vertical_force_sweep(mp.build(Side::Left, Rig::Steering).unwrap(), 0.0, 1.0, 1, Mode::Paper).unwrap_err(),
        "the wheel free on its spring",
    );
    // A corner load that is no number.
    let e = wheel_load_sweep(
        mp.build(Side::Left, Rig::Free).unwrap(),
        WheelLoad::Braking,
        f64::NAN,
        0.0,
        1.0,
        1,
        Mode::Paper,
    )
    .unwrap_err();
    assert!(matches!(e, SolverError::InvalidInput { what: "corner load", .. }), "{e:?}");
}

fn double_wishbone(hardpoints: DoubleWishboneHardpoints, spring_rate: f64) -> DoubleWishbone {
    DoubleWishbone {
        hardpoints,
        upper_arm_mounts: Connection::Ideal.into(),
        lower_arm_mounts: Connection::Ideal.into(),
        spring: SpringSpec { rate: spring_rate, design_force: 4000.0 },
        tie_rod: Connection::Ideal,
        loaded_radius: 0.30,
    }
}

/// Equilibrium of `corner` at load parameter `t`, found from design.
fn equilibrium(corner: &Corner, t: f64) -> StepResult {
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default()).unwrap();
    let mut state = solver.design_state(t);
    solver.equilibrium(&mut state).unwrap()
}

/// Holding force of the wheel-travel rig at `travel` with the corner load on the patch as well.
fn holding_force_with_corner_load(template: &MacPherson, load: f64, travel: f64) -> (f64, StepResult, Corner) {
    let mut corner = template.build(Side::Left, Rig::WheelTravel).unwrap();
    add_constant_corner_load(&mut corner, load);
    let step = equilibrium(&corner, travel);
    let driver = corner.model.joint_id("wheel travel").unwrap();
    (step.joint_reactions(&corner.model)[driver.0].force.z, step, corner)
}

/// Second method: the rest position under the corner load is the wheel travel at which the wheel-travel
/// rig, with the same corner load on the patch, needs no force to hold the wheel — a scalar root of driven
/// equilibria (secant method).
fn rest_travel_by_driven_equilibria(template: &MacPherson, load: f64) -> (f64, StepResult, Corner) {
    let f = |z: f64| holding_force_with_corner_load(template, load, z).0;
    let (mut a, mut b) = (0.0, 0.01);
    let (mut fa, mut fb) = (f(a), f(b));
    for _ in 0..50 {
        let c = b - fb * (b - a) / (fb - fa);
        (a, fa) = (b, fb);
        b = c;
        fb = f(b);
        if fb.abs() < 1e-7 {
            break;
        }
    }
    assert!(fb.abs() < 1e-7, "secant did not close: {fb}");
    let (_, step, corner) = holding_force_with_corner_load(template, load, b);
    (b, step, corner)
}

#[test]
fn static_rest_position_equals_the_travel_where_the_rig_needs_no_force() {
    let mp = bushed_macpherson();
    // 3 kN: below the design corner load (the wheel droops); 9 kN = 2× the spring's design force, so Newton
    // starts from a design position 5 kN out of balance and the wheel rises by more than 0.1 m.
    for load in [3000.0, 2.0 * mp.spring.design_force] {
        let rest = static_load_case(mp.build(Side::Left, Rig::Free).unwrap(), load).unwrap();
        let (travel, step, corner) = rest_travel_by_driven_equilibria(&mp, load);
        let driven = corner.wheel.attitude(&step.poses);
        println!(
            "corner load {load} N: ride height {:+.3} mm (driven root {:+.3} mm), toe {:+.4}°, camber {:+.4}°, \
             spring {:.1} N, wheel rate {:.1} N/mm",
            rest.wheel_centre_displacement.z * 1e3,
            travel * 1e3,
            rest.attitude.toe.to_degrees(),
            rest.attitude.camber.to_degrees(),
            rest.spring_force,
            rest.wheel_rate * 1e-3
        );
        // Measured: 1e-10 m and 1e-10 rad at 9 kN (1e-16 at 3 kN); both solves close to 1e-9 of the forces.
        assert!(
            (rest.wheel_centre_displacement.z - travel).abs() < 1e-9,
            "{} vs {travel}",
            rest.wheel_centre_displacement.z
        );
        assert!((rest.attitude.wheel_centre - driven.wheel_centre).norm() < 1e-9);
        assert!((rest.attitude.toe - driven.toe).abs() < 1e-9, "{} vs {}", rest.attitude.toe, driven.toe);
        assert!((rest.attitude.camber - driven.camber).abs() < 1e-9);
        // The spring law with the template's rate: push = −k (L − L₀).
        assert!((rest.spring_force + mp.spring.rate * rest.spring_deflection).abs() < 1e-6 * rest.spring_force.abs());
        // Every joint and element is reported by name, with finite forces.
        for c in rest.forces.joints.iter().chain(&rest.forces.elements) {
            assert!(c.force.iter().chain(c.torque.iter()).all(|v| v.is_finite()), "{c:?}");
        }
        assert_eq!(rest.forces.elements.len(), corner.model.elements().len());
    }
}

#[test]
fn static_wheel_rate_equals_finite_differences_of_rest_positions() {
    let mp = bushed_macpherson();
    let rest = |load: f64| static_load_case(mp.build(Side::Left, Rig::Free).unwrap(), load).unwrap();
    let at = rest(4000.0);
    let (up, down) = (rest(4010.0), rest(3990.0));
    let fd = 20.0 / (up.contact_patch.z - down.contact_patch.z);
    // Measured: ~1e-7 relative (the O(h²) term of a 10 N difference).
    close(at.wheel_rate, fd, 1e-5, "wheel rate");
}

/// Conservation law on the static load case: the chassis holds the corner, so the forces and the moments
/// (about the origin) that it applies through the chassis-side parts, with the corner load, vanish.
#[test]
fn static_load_case_forces_and_moments_balance() {
    let mp = bushed_macpherson();
    let rest = static_load_case(mp.build(Side::Left, Rig::Free).unwrap(), 5000.0).unwrap();
    let design = mp.build(Side::Left, Rig::Free).unwrap().model;
    let h = mp.hardpoints;
    // Each component's force acts on its body at the design hardpoint the body carries (the tie rod's
    // reaction at its outer end, the spring's at its seat on the upright).
    let point_of = |name: &str| match name {
        "lower arm front bushing" => h.lower_arm_front,
        "lower arm rear bushing" => h.lower_arm_rear,
        "top mount" => h.top_mount,
        "spring" => h.strut_lower,
        "tie rod" => h.tie_rod_outer,
        "corner load" => h.wheel_centre - Vec3::new(0.0, 0.0, mp.loaded_radius),
        other => panic!("unexpected chassis-side component {other}"),
    };
    let (mut force, mut moment, mut largest) = (Vec3::zeros(), Vec3::zeros(), 0.0f64);
    for c in rest.forces.joints.iter().chain(&rest.forces.elements) {
        if &*c.other_body != "ground" {
            assert_ne!(&*c.body, "ground");
            continue;
        }
        let body = design.body_id(&c.body).unwrap();
        let local = design.bodies()[body.0].design_pose.to_local_point(&point_of(&c.name));
        let at = rest.poses[body.0].point(&local);
        force += c.force;
        moment += at.cross(&c.force) + c.torque;
        largest = largest.max(c.force.norm());
    }
    // Each of the few bodies is in equilibrium to 1e-9 of the largest force; measured 7e-14 (N, and N·m
    // at ~1 m).
    assert!(force.norm() < 1e-8 * largest, "ΣF = {force:?}");
    assert!(moment.norm() < 1e-8 * largest, "ΣM = {moment:?}");
    // The spring carries most of the corner load: more than the load itself through a motion ratio < 1.
    assert!(rest.spring_force > 5000.0, "{}", rest.spring_force);
}

#[test]
fn loads_the_corner_cannot_carry_are_refused() {
    let generic = DoubleWishboneHardpoints::generic();
    let dw = double_wishbone(generic, 30e3);
    // Independent: with 3.5 kN on the patch, the wheel-travel rig has to pull the wheel down at every
    // travel it can reach — the linkage carries no more than ~3.3 kN at the patch.
    let mut corner = dw.build(Side::Left, Rig::WheelTravel).unwrap();
    add_constant_corner_load(&mut corner, 3500.0);
    let rows = parallel_wheel_travel(&corner, -0.2, 0.4, 60, Mode::Corrected).unwrap();
    let most = rows.iter().map(|r| r.wheel_load).fold(f64::NEG_INFINITY, f64::max);
    assert!(most < 0.0, "the rig would need no force somewhere: {most}");
    match static_load_case(dw.build(Side::Left, Rig::Free).unwrap(), 3500.0) {
        Err(SolverError::LimitPoint { reached }) => {
            // The largest load the walk reached: 3.5 kN minus the rig's least pull.
            println!("limit point at {reached} N; least pull {most} N");
            assert!(reached < 3500.0 && (reached - (3500.0 + most)).abs() < 0.05 * 3500.0, "{reached} vs {most}");
        }
        other => panic!("{other:?}"),
    }
    // A spring so soft that the falling motion ratio outweighs it: every equilibrium is unstable, as the
    // independent driven travel shows (the holding force falls in bump).
    let soft = double_wishbone(generic, 100.0);
    let rows =
        parallel_wheel_travel(&soft.build(Side::Left, Rig::WheelTravel).unwrap(), -0.01, 0.01, 2, Mode::Corrected)
            .unwrap();
    assert!(rows[2].wheel_load < rows[0].wheel_load, "{} {}", rows[0].wheel_load, rows[2].wheel_load);
    match static_load_case(soft.build(Side::Left, Rig::Free).unwrap(), rows[1].wheel_load) {
        Err(SolverError::InvalidInput { what: "corner load", why }) => assert!(why.contains("unstable"), "{why}"),
        other => panic!("{other:?}"),
    }
    // Far beyond anything the MacPherson carries (its linkage locks near 105 kN): a typed error, no NaN.
    match static_load_case(bushed_macpherson().build(Side::Left, Rig::Free).unwrap(), 1e6) {
        Err(SolverError::InvalidInput { what: "corner load", .. } | SolverError::LimitPoint { .. }) => {}
        other => panic!("{other:?}"),
    }
    // Not a number.
    let e = static_load_case(dw.build(Side::Left, Rig::Free).unwrap(), f64::INFINITY).unwrap_err();
    assert!(matches!(e, SolverError::InvalidInput { what: "corner load", .. }), "{e:?}");
    // Only a wheel free on its spring comes to rest under a load.
    match static_load_case(dw.build(Side::Left, Rig::HeightHeld).unwrap(), 2000.0).unwrap_err() {
        SolverError::InvalidInput { what: "corner", why } => {
            assert!(why.contains("the wheel free on its spring"), "{why}")
        }
        other => panic!("{other:?}"),
    }
}

fn front_vehicle() -> VehicleParameters {
    VehicleParameters {
        corner_load: 3800.0,
        wheelbase: 2.7,
        cg_height: 0.55,
        brake_front_fraction: 0.65,
        drive_front_fraction: 1.0,
        axle: AxlePosition::Front,
        tyre_rate: None,
        rack_travel_per_revolution: None,
        half_shaft: None,
    }
}

/// Builds one corner held by the given rig.
type CornerOnRig = Box<dyn Fn(Rig) -> Corner>;

/// Virtual work: with the wheel-centre height held, a small force `F` at a point of the upright moving
/// with `v` per metre of bump changes the rig's holding force by `−F·v / v_W,z` (the rig's force does
/// work through `v_W,z`, and the linear response does no other work along the bump motion).
#[test]
fn holding_force_changes_by_the_virtual_work_of_the_load() {
    let dw = double_wishbone(DoubleWishboneHardpoints::generic(), 30e3);
    let mp = bushed_macpherson();
    let cases: [(&str, CornerOnRig); 2] = [
        ("double wishbone", Box::new(move |rig| dw.build(Side::Left, rig).unwrap())),
        ("bushed MacPherson", Box::new(move |rig| mp.build(Side::Left, rig).unwrap())),
    ];
    for (name, build) in &cases {
        let geometry = anti_pitch(&build(Rig::WheelTravel), &front_vehicle()).unwrap();
        let (v_p, v_w) = (geometry.patch_velocity, geometry.wheel_centre_velocity);
        let holding_slope = |load: WheelLoad| {
            let rows = wheel_load_sweep(build(Rig::HeightHeld), load, 0.0, -100.0, 100.0, 2, Mode::Corrected).unwrap();
            slope(&rows, |r| r.wheel_load)
        };
        let braking = holding_slope(WheelLoad::Braking);
        let traction = holding_slope(WheelLoad::Traction);
        let lateral = holding_slope(WheelLoad::Lateral);
        println!(
            "{name}: tanθ_P {:.5}, tanθ_W {:.5}; dR/dF braking {braking:.6} vs {:.6}, traction {traction:.6} vs {:.6}, \
             lateral {lateral:.6} vs {:.6}",
            geometry.patch_slope,
            geometry.wheel_centre_slope,
            v_p.x / v_w.z,
            -v_w.x / v_w.z,
            v_p.y / v_w.z
        );
        // The equilibria are solved to 1e-9 of ~1e4 N, which leaves up to ~5e-8 in a slope over ±100 N.
        // Measured: ≤ 1e-12 on the ideal double wishbone (a structure once held: statics is exact), ≤ 2e-9
        // on the bushed MacPherson (the O(F²) term; the bushings' small non-symmetric tangent, which the
        // identity neglects, stays below it).
        let tolerance = 2e-7;
        // Braking is rearward: F = (−B, 0, 0) → ΔR = B v_P,x / v_W,z.
        assert!((braking - v_p.x / v_w.z).abs() < tolerance, "{name} braking: {braking} vs {}", v_p.x / v_w.z);
        // Traction is forward at the wheel centre: ΔR = −T v_W,x / v_W,z.
        assert!((traction + v_w.x / v_w.z).abs() < tolerance, "{name} traction: {traction} vs {}", -v_w.x / v_w.z);
        // Lateral is inboard, −y on the left: ΔR = L v_P,y / v_W,z (jacking).
        assert!((lateral - v_p.y / v_w.z).abs() < tolerance, "{name} lateral: {lateral} vs {}", v_p.y / v_w.z);
        // At design the patch is below the wheel centre: both rise alike, and the slope is the ratio above.
        assert!((v_p.z - v_w.z).abs() < 1e-3 && (v_w.z - 1.0).abs() < 1e-12, "{v_p:?} {v_w:?}");
    }
}

/// Velocity of the upright's point at the design contact patch and of the wheel centre from driven
/// equilibria at ±1e-4 m (central differences), against the path tangent.
#[test]
fn path_tangent_equals_finite_differences_of_driven_equilibria() {
    let corners = [
        bushed_macpherson().build(Side::Left, Rig::WheelTravel).unwrap(),
        double_wishbone(DoubleWishboneHardpoints::generic(), 30e3).build(Side::Left, Rig::WheelTravel).unwrap(),
    ];
    for corner in &corners {
        let geometry = anti_pitch(corner, &front_vehicle()).unwrap();
        let centre = equilibrium(corner, 0.0);
        let patch = corner.wheel.steering_geometry(&centre.poses).contact_patch;
        let upright = corner.wheel.upright.0;
        let patch_local = centre.poses[upright].to_local_point(&patch);
        let (up, down) = (equilibrium(corner, 1e-4), equilibrium(corner, -1e-4));
        let fd = |local: Vec3| (up.poses[upright].point(&local) - down.poses[upright].point(&local)) / 2e-4;
        let (v_p, v_w) = (fd(patch_local), fd(corner.wheel.wheel_centre_local));
        // Measured: ~1e-8 (the O(h²) term of a 0.1 mm difference).
        assert!((v_p - geometry.patch_velocity).norm() < 1e-6, "{v_p:?} vs {:?}", geometry.patch_velocity);
        assert!(
            (v_w - geometry.wheel_centre_velocity).norm() < 1e-6,
            "{v_w:?} vs {:?}",
            geometry.wheel_centre_velocity
        );
        close(v_p.x / v_p.z, geometry.patch_slope, 1e-5, "patch slope");
        println!(
            "anti-pitch at design: tanθ_P {:.4} ({:.2}°), tanθ_W {:.4} ({:.2}°); front anti-dive {:.1} %, anti-lift {:.1} %",
            geometry.patch_slope,
            geometry.patch_swing_arm_angle.to_degrees(),
            geometry.wheel_centre_slope,
            geometry.wheel_centre_swing_arm_angle.to_degrees(),
            100.0 * geometry.braking,
            100.0 * geometry.traction
        );
    }
}

/// Both arm pivot axes parallel to `d = (cos α, 0, sin α)` and the tie rod along `d`: every part of the
/// linkage can move in planes normal to `d` (the arms turn about `d`, the upright moves as a planar
/// four-bar, the tie rod's outer end moves across the rod), and the linkage has one freedom, so that is its
/// motion. Every upright point then moves normal to `d`: `v_x cos α + v_z sin α = 0`, `tan θ = −tan α`.
#[test]
fn parallel_pivot_axes_give_the_closed_form_swing_arm() {
    let g = DoubleWishboneHardpoints::generic();
    for alpha in [0.0f64, -8f64.to_radians(), 5f64.to_radians()] {
        let d = Vec3::new(alpha.cos(), 0.0, alpha.sin());
        let hardpoints = DoubleWishboneHardpoints {
            upper_arm_rear: g.upper_arm_front - 0.25 * d,
            lower_arm_rear: g.lower_arm_front - 0.45 * d,
            tie_rod_inner: g.tie_rod_outer - 0.35 * d,
            ..g
        };
        let corner = double_wishbone(hardpoints, 30e3).build(Side::Left, Rig::WheelTravel).unwrap();
        for axle in [AxlePosition::Front, AxlePosition::Rear] {
            let vehicle = VehicleParameters { axle, drive_front_fraction: 0.4, ..front_vehicle() };
            let geometry = anti_pitch(&corner, &vehicle).unwrap();
            let slope = -alpha.tan();
            // Measured: 3e-10 with inclined axes; 1.2e-6 with the axes along x, where the sparse solve of the
            // path tangent stops at a constraint residual of 6e-7 (a dense pivoted solve of the same system
            // gives 1e-10).
            let tolerance = 2e-6;
            assert!((geometry.patch_slope - slope).abs() < tolerance, "α {alpha}: {} vs {slope}", geometry.patch_slope);
            assert!((geometry.wheel_centre_slope - slope).abs() < tolerance);
            assert!((geometry.patch_swing_arm_angle + alpha).abs() < tolerance);
            let lever = vehicle.wheelbase / vehicle.cg_height;
            let (braking, traction) = match axle {
                AxlePosition::Front => (0.65 * slope * lever, 0.4 * slope * lever),
                AxlePosition::Rear => (0.35 * -slope * lever, 0.6 * -slope * lever),
            };
            let share = tolerance * lever;
            assert!((geometry.braking - braking).abs() < share, "{} vs {braking}", geometry.braking);
            assert!((geometry.traction - traction).abs() < share);
        }
    }
}

#[test]
fn vehicle_parameters_are_checked_by_field() {
    let good = front_vehicle();
    assert!(good.validate().is_ok());
    let cases = [
        ("wheelbase", VehicleParameters { wheelbase: 0.0, ..good }),
        ("cg_height", VehicleParameters { cg_height: f64::NAN, ..good }),
        ("brake_front_fraction", VehicleParameters { brake_front_fraction: 1.2, ..good }),
        ("drive_front_fraction", VehicleParameters { drive_front_fraction: -0.1, ..good }),
        ("corner_load", VehicleParameters { corner_load: -1.0, ..good }),
    ];
    let corner = bushed_macpherson().build(Side::Left, Rig::WheelTravel).unwrap();
    // Only a driven wheel travel has the path tangent the anti-pitch geometry reads.
    match anti_pitch(&bushed_macpherson().build(Side::Left, Rig::Free).unwrap(), &good).unwrap_err() {
        SolverError::InvalidInput { what: "corner", why } => {
            assert!(why.contains("the wheel-centre height driven"), "{why}")
        }
        other => panic!("{other:?}"),
    }
    for (field, vehicle) in cases {
        match anti_pitch(&corner, &vehicle).unwrap_err() {
            SolverError::InvalidInput { what: "vehicle parameters", why } => {
                assert!(why.contains(&format!("`{field}`")), "{why}")
            }
            other => panic!("{other:?}"),
        }
    }
    // Model-file form: snake-case axle, unknown keys named.
    let json = r#"{"corner_load": 3800.0, "wheelbase": 2.7, "cg_height": 0.55, "brake_front_fraction": 0.65, "drive_front_fraction": 1.0, "axle": "rear"}"#;
    let parsed: VehicleParameters = serde_json::from_str(json).unwrap();
    assert_eq!(parsed, VehicleParameters { axle: AxlePosition::Rear, ..good });
    let typo = json.replace("cg_height", "cog_height");
    let e = serde_json::from_str::<VehicleParameters>(&typo).unwrap_err().to_string();
    assert!(e.contains("cog_height"), "{e}");
}

/// A joint's reaction and an element's report read alone (what a row that needs one of them reads) are
/// those read with every other joint's and element's, to the bit: the rows of a joint are found by its
/// place among the joints, as the full read finds them.
#[test]
fn a_reaction_or_element_report_read_alone_is_the_one_read_with_all_the_others() {
    let corner = bushed_macpherson().build(Side::Left, Rig::WheelTravel).unwrap();
    let step = equilibrium(&corner, 0.03);
    let model = &corner.model;
    let all = step.joint_reactions(model);
    assert!(all.len() > 3 && all.iter().any(|r| r.force.norm() > 1.0));
    for (k, reaction) in all.iter().enumerate() {
        assert_eq!(step.joint_reaction(model, elastokin_core::JointId(k)), *reaction, "joint {k}");
    }
    for (k, report) in step.element_reports(model).iter().enumerate() {
        assert_eq!(step.element_report(model, elastokin_core::ElementId(k)), *report, "element {k}");
    }
}
