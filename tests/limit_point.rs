//! A shallow two-bar truss (von Mises truss) under a vertical apex load snaps through at a limit load with
//! a closed form. Force control must stop there and say so; arc length must follow the path through it.

use elastokin::elements::{CoilSpring, PointForce};
use elastokin::prelude::*;

const HALF_SPAN: f64 = 0.5;
const RISE: f64 = 0.1;
const K: f64 = 1e5;
const P: f64 = 100.0; // apex load at t = 1

fn truss() -> Model {
    let mut m = Model::new();
    let apex = Vec3::new(0.0, 0.0, RISE);
    let body = m.add_body("apex", Pose::at(apex)).unwrap();
    // The apex slides vertically: a translational joint leaves only its height free.
    m.add_joint(JointSpec::translational("guide", BodyRef::Ground, body, apex, Vec3::z())).unwrap();
    let l0 = (HALF_SPAN * HALF_SPAN + RISE * RISE).sqrt();
    for (name, x) in [("left bar", -HALF_SPAN), ("right bar", HALF_SPAN)] {
        m.add_element(
            CoilSpring::new(name, BodyRef::Ground, Vec3::new(x, 0.0, 0.0), body.into(), apex, K, l0).unwrap(),
        )
        .unwrap();
    }
    m.add_element(PointForce::new("apex load", body.into(), apex, Vec3::new(0.0, 0.0, -P)).unwrap()).unwrap();
    m
}

/// Load carried at apex height z: P(z) = 2 k z (L₀ / L − 1), L = √(a² + z²).
fn load_at(z: f64) -> f64 {
    let l0 = (HALF_SPAN * HALF_SPAN + RISE * RISE).sqrt();
    let l = (HALF_SPAN * HALF_SPAN + z * z).sqrt();
    2.0 * K * z * (l0 / l - 1.0)
}

/// Limit load: dP/dz = 0 at L³ = L₀ a².
fn limit_load() -> f64 {
    let l0 = (HALF_SPAN * HALF_SPAN + RISE * RISE).sqrt();
    let l = (l0 * HALF_SPAN * HALF_SPAN).cbrt();
    load_at((l * l - HALF_SPAN * HALF_SPAN).sqrt())
}

#[test]
fn force_control_stops_at_the_limit_load_and_names_it() {
    let m = truss();
    let p_max = limit_load();
    assert!(p_max < 2.0 * P && p_max > 0.5 * P, "test setup: limit load {p_max}");
    let mut solver = StaticSolver::new(&m, SolverOptions::default()).unwrap();
    let err = solver.sweep(LoadPath::new(0.0, 2.0, 40), Mode::Corrected).unwrap_err();
    match err {
        SolverError::LimitPoint { reached } => {
            // The path is cut in halves down to 2⁻¹⁰ of a 0.05 step before giving up.
            assert!((reached * P - p_max).abs() < 0.01 * p_max, "reached {} N, limit {p_max} N", reached * P);
        }
        other => panic!("expected a limit point, got {other}"),
    }
}

#[test]
fn arc_length_follows_the_path_through_the_limit_point() {
    let m = truss();
    let p_max = limit_load();
    let mut solver = StaticSolver::new(&m, SolverOptions::default()).unwrap();
    let sweep = solver.arc_length_sweep(LoadPath::new(0.0, 3.0, 400), 0.01).unwrap();
    let mut peak: f64 = 0.0;
    let mut passed_limit = false;
    for s in &sweep.steps {
        let z = s.poses[0].position.z;
        // Every point is an equilibrium of the closed form.
        assert!((load_at(z) - s.t * P).abs() < 1e-6 * P, "z={z}: P(z)={} vs {}", load_at(z), s.t * P);
        peak = peak.max(s.t * P);
        if s.t * P < 0.9 * peak && z < 0.0 {
            passed_limit = true;
        }
    }
    assert!(passed_limit, "the path must come down past the limit point");
    assert!((peak - p_max).abs() < 0.01 * p_max, "peak {peak} vs {p_max}");
}
