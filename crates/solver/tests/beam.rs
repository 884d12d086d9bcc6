//! Beams solved: a cantilever's tip under a small force and torque against the closed forms of a
//! Timoshenko beam (deflection PL³/3EI + PL/κGA, rotation PL²/2EI, twist TL/GJ, a shear centre's offset
//! coupling twist and lateral deflection), and a segmented cantilever under an end moment converging to
//! the exact circular arc as the segments shorten.

use elastokin_core::{BodyRef, Model, Pose, Vec3};
use elastokin_elements::{beam, BeamSpec, PointForce, PointTorque, Section};
use elastokin_solver::{LoadPath, Mode, SolverOptions, StaticSolver};

const L: f64 = 0.8;

/// A steel tube-like section: E 210 GPa, G 80 GPa, A 4e-4 m², I 2e-8 and 3e-8 m⁴, J 5e-8 m⁴.
fn section(shear: bool, shear_centre: (f64, f64)) -> Section {
    Section {
        youngs_modulus: 210e9,
        shear_modulus: 80e9,
        area: 4e-4,
        iy: 2e-8,
        iz: 3e-8,
        j: 5e-8,
        shear_areas: shear.then_some((2e-4, 1.5e-4)),
        shear_centre,
    }
}

fn tight() -> SolverOptions {
    SolverOptions { force_tolerance: 1e-13, constraint_tolerance: 1e-14, ..SolverOptions::default() }
}

/// A cantilever along x from the ground at the origin to a tip body, loaded at its end by `force` and
/// `torque` (global); returns the tip's displacement and rotation vector.
fn cantilever(section: Section, force: Vec3, torque: Vec3) -> (Vec3, Vec3) {
    let mut model = Model::new();
    let tip = Vec3::new(L, 0.0, 0.0);
    let body = model.add_body("tip", Pose::at(tip)).unwrap();
    let spec = BeamSpec {
        name: "beam".into(),
        body_i: BodyRef::Ground,
        body_j: BodyRef::Body(body),
        from: Vec3::zeros(),
        to: tip,
        y_axis: Vec3::y(),
        section,
    };
    model.add_element(beam(&spec).unwrap()).unwrap();
    model.add_element(PointForce::new("force", BodyRef::Body(body), tip, force).unwrap()).unwrap();
    model.add_element(PointTorque::new("torque", BodyRef::Body(body), torque).unwrap()).unwrap();
    let mut solver = StaticSolver::new(&model, tight()).unwrap();
    let mut state = solver.design_state(1.0);
    let step = solver.equilibrium(&mut state).unwrap();
    let pose = step.poses[body.0];
    (pose.position - tip, elastokin_core::math::quat_log(&pose.orientation))
}

#[test]
fn a_cantilevers_tip_moves_as_the_closed_forms_say() {
    let s = section(true, (0.0, 0.0));
    let (e, g) = (s.youngs_modulus, s.shear_modulus);
    let (ay, az) = s.shear_areas.unwrap();
    // A force small enough that the tip turns by microradians: the closed forms are first order. Measured:
    // bending and twist to 4e-16 relative (allowed 1e-13), the axial pull to 6e-11 (allowed 5e-9).
    let p = 2.0;
    let (d, r) = cantilever(s, Vec3::new(0.0, 0.0, p), Vec3::zeros());
    let dz = p * L.powi(3) / (3.0 * e * s.iy) + p * L / (g * az);
    let ry = -p * L * L / (2.0 * e * s.iy);
    assert!((d.z - dz).abs() < 1e-13 * dz.abs(), "{} against {dz}", d.z);
    assert!((r.y - ry).abs() < 1e-13 * ry.abs(), "{} against {ry}", r.y);
    let (d, r) = cantilever(s, Vec3::new(0.0, p, 0.0), Vec3::zeros());
    let dy = p * L.powi(3) / (3.0 * e * s.iz) + p * L / (g * ay);
    let rz = p * L * L / (2.0 * e * s.iz);
    assert!((d.y - dy).abs() < 1e-13 * dy.abs() && (r.z - rz).abs() < 1e-13 * rz.abs(), "{d:?} {r:?}");
    // Twist, and an axial pull.
    let t = 0.5;
    let (_, r) = cantilever(s, Vec3::zeros(), Vec3::new(t, 0.0, 0.0));
    let rx = t * L / (g * s.j);
    assert!((r.x - rx).abs() < 1e-13 * rx, "{} against {rx}", r.x);
    let (d, _) = cantilever(s, Vec3::new(50.0, 0.0, 0.0), Vec3::zeros());
    let dx = 50.0 * L / (e * s.area);
    assert!((d.x - dx).abs() < 5e-9 * dx, "{} against {dx}", d.x);
}

#[test]
fn a_shear_centre_off_the_centroid_twists_the_beam_under_a_lateral_force() {
    // A lateral force through the centroid, the shear centre e_z above it: the force's moment about the
    // shear centre, e_z·F, twists the beam, and the twist carries the centroid sideways by e_z·θ.
    let ez = 0.01;
    let s = section(true, (0.0, ez));
    let (e, g) = (s.youngs_modulus, s.shear_modulus);
    let ay = s.shear_areas.unwrap().0;
    let p = 2.0;
    let (d, r) = cantilever(s, Vec3::new(0.0, p, 0.0), Vec3::zeros());
    let twist = ez * p * L / (g * s.j);
    let dy = p * L.powi(3) / (3.0 * e * s.iz) + p * L / (g * ay) + ez * twist;
    // Measured 8e-16 and 6e-16 relative.
    assert!((r.x - twist).abs() < 1e-13 * twist, "twist {} against {twist}", r.x);
    assert!((d.y - dy).abs() < 1e-13 * dy, "{} against {dy}", d.y);
}

/// The tip of a cantilever of `n` segments (bodies at their joints) bent by an end moment `m` about z:
/// its position.
fn bent(n: usize, m: f64, s: Section) -> Vec3 {
    let mut model = Model::new();
    let mut previous = BodyRef::Ground;
    let seg = L / n as f64;
    for k in 1..=n {
        let at = Vec3::new(seg * k as f64, 0.0, 0.0);
        let body = BodyRef::Body(model.add_body(&format!("node {k}"), Pose::at(at)).unwrap());
        let spec = BeamSpec {
            name: format!("segment {k}"),
            body_i: previous,
            body_j: body,
            from: at - Vec3::new(seg, 0.0, 0.0),
            to: at,
            y_axis: Vec3::y(),
            section: s,
        };
        model.add_element(beam(&spec).unwrap()).unwrap();
        previous = body;
    }
    model.add_element(PointTorque::new("end moment", previous, Vec3::new(0.0, 0.0, m)).unwrap()).unwrap();
    let mut solver = StaticSolver::new(&model, tight()).unwrap();
    let sweep = solver.sweep(LoadPath::new(0.0, 1.0, 40), Mode::Corrected).unwrap();
    let last = sweep.steps.last().unwrap();
    last.poses[n - 1].position
}

#[test]
fn a_segmented_cantilever_under_an_end_moment_converges_to_the_circular_arc() {
    // An end moment bends a beam into a circle of radius EI/M: here through one radian.
    let s = section(false, (0.0, 0.0));
    let m = s.youngs_modulus * s.iz / L;
    let (radius, angle) = (s.youngs_modulus * s.iz / m, m * L / (s.youngs_modulus * s.iz));
    let exact = Vec3::new(radius * angle.sin(), radius * (1.0 - angle.cos()), 0.0);
    let errors: Vec<f64> = [2, 4, 8, 16, 32].iter().map(|&n| (bent(n, m, s) - exact).norm() / L).collect();
    let orders: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    println!("tip error over L for 2, 4, 8, 16, 32 segments: {errors:?}, orders {orders:?}");
    // Measured: errors 4.0e-2, 1.0e-2, 2.5e-3, 6.2e-4, 1.6e-4 of L; orders 2.006, 2.0016, 2.0004, 2.0001 —
    // second order: each halving of the segments quarters the error.
    for w in errors.windows(2) {
        assert!(w[1] < w[0], "{errors:?}");
    }
    assert!(errors[4] < 2e-4, "{errors:?}");
    for order in &orders {
        assert!((order - 2.0).abs() < 0.01, "orders {orders:?}");
    }
}
