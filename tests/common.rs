//! Shared scenes of the whole-pipeline tests (each scene has a closed-form answer in the test that uses it).
#![allow(dead_code, reason = "each test file uses the helpers it needs")]

use elastokin::elements::{Bushing, CoilSpring, PointForce};
use elastokin::prelude::*;

/// Lever of the lever test: pivot at the origin about +y, tip at `(A, 0, 0)`, spring seat on the lever
/// at `(B, 0, 0)`, chassis seat at `(0, 0, H)`, downward tip force `F` at t = 1.
pub const A: f64 = 0.5;
pub const B: f64 = 0.3;
pub const H: f64 = 0.2;
pub const K_SPRING: f64 = 20_000.0;
pub const F_TIP: f64 = 500.0;

/// How the lever is held at its pivot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pivot {
    /// Ideal revolute joint.
    Revolute,
    /// Two identical revolute joints (one is redundant).
    DoubleRevolute,
    /// Bushing with the given translational/tilt stiffness and a negligible torsional rate about y.
    Bushing(f64),
}

pub fn lever(pivot: Pivot, free_length: f64) -> Model {
    let mut m = Model::new();
    let lever = m.add_body("lever", Pose::at(Vec3::new(0.25, 0.0, 0.0))).unwrap();
    match pivot {
        Pivot::Revolute => {
            m.add_joint(JointSpec::revolute("pivot", BodyRef::Ground, lever, Vec3::zeros(), Vec3::y())).unwrap();
        }
        Pivot::DoubleRevolute => {
            m.add_joint(JointSpec::revolute("pivot", BodyRef::Ground, lever, Vec3::zeros(), Vec3::y())).unwrap();
            m.add_joint(JointSpec::revolute("pivot copy", BodyRef::Ground, lever, Vec3::zeros(), Vec3::y())).unwrap();
        }
        Pivot::Bushing(k) => {
            m.add_element(
                Bushing::new(
                    "pivot",
                    BodyRef::Ground,
                    lever.into(),
                    Vec3::zeros(),
                    Mat3::identity(),
                    Vec3::new(k, k, k),
                    Vec3::new(k, 1e-6, k),
                )
                .unwrap(),
            )
            .unwrap();
        }
    }
    m.add_element(
        CoilSpring::new(
            "spring",
            BodyRef::Ground,
            Vec3::new(0.0, 0.0, H),
            lever.into(),
            Vec3::new(B, 0.0, 0.0),
            K_SPRING,
            free_length,
        )
        .unwrap(),
    )
    .unwrap();
    m.add_element(
        PointForce::new("tip load", lever.into(), Vec3::new(A, 0.0, 0.0), Vec3::new(0.0, 0.0, -F_TIP)).unwrap(),
    )
    .unwrap();
    m
}

/// Design length of the lever spring (free at design).
pub fn lever_spring_design_length() -> f64 {
    (B * B + H * H).sqrt()
}

/// Closed form of the lever: with tip force `f` and free length `l0`, the moment balance
/// `a f cos φ = k (L − L₀) b h cos φ / L` gives `L = L₀ / (1 − a f / (k b h))` and
/// `sin φ = (L² − b² − h²) / (2 b h)`. Returns φ (rotation about +y; the tip goes down).
pub fn lever_angle(f: f64, l0: f64) -> f64 {
    let l = l0 / (1.0 - A * f / (K_SPRING * B * H));
    ((l * l - B * B - H * H) / (2.0 * B * H)).asin()
}

/// Rotation angle of the lever about +y from its pose.
pub fn rotation_about_y(p: &Pose) -> f64 {
    let x = p.orientation * Vec3::x();
    (-x.z).atan2(x.x)
}

/// Tolerances for comparisons with closed forms: the default 1e-9 relative force residual leaves
/// ~1e-9 rad in a lever angle; these leave roundoff only.
pub fn tight() -> SolverOptions {
    SolverOptions { force_tolerance: 1e-11, constraint_tolerance: 1e-12, ..SolverOptions::default() }
}
