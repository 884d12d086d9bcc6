//! Coil spring with a push-force curve: a straight two-point table is the linear spring, the force of a
//! parabolic table against its closed-form energy, the string tangent with the curve's slope, the stiffness
//! against finite differences in every piece of a table and past its ends, the free length from the design
//! force, and refusals.

mod common;

use common::*;
use elastokin_core::{BodyId, BodyRef, ForceElement, Mat3, ModelError, Pose, Vec3};
use elastokin_elements::{Characteristic, CoilSpring, Curve, SpringLength};

/// `y = a c² + b c`: a rising parabola (a progressive spring), which the curve reproduces exactly between
/// the points of its table (tests/curve.rs).
const A: f64 = 2.0e5;
const B: f64 = 1.5e4;
const PARABOLA_END: f64 = 0.1;

fn parabola(c: f64) -> f64 {
    A * c * c + B * c
}

fn parabola_table() -> Curve {
    Curve::new("spring", [0.0, 0.02, 0.035, 0.06, PARABOLA_END].map(|c| [c, parabola(c)])).unwrap()
}

/// A data sheet's table: uneven steps, a pull side below zero compression, a progressive end with a steep
/// step at 0.05–0.06 m, where step 3 of Fritsch–Carlson limits the slopes of the interval before it
/// (worked out: (α, β) = (0.93, 4.07) there, scaled onto the circle of radius 3).
fn data_sheet() -> Curve {
    Curve::new(
        "spring",
        [[-0.02, -300.0], [0.0, 0.0], [0.015, 320.0], [0.03, 700.0], [0.05, 1200.0], [0.06, 2600.0], [0.08, 4000.0]],
    )
    .unwrap()
}

/// A random spring geometry and moved poses; returns the seats' global positions at the moved poses too.
struct Geometry {
    point_i: Vec3,
    point_j: Vec3,
    design_i: Pose,
    design_j: Pose,
    pi: Pose,
    pj: Pose,
    gi: bool,
    gj: bool,
}

impl Geometry {
    fn random(rng: &mut Rng, gi: bool, gj: bool) -> Self {
        let point_i = rng.vec(0.3);
        let point_j = point_i + rng.unit() * rng.uniform(0.2, 0.4);
        let design_i = if gi { Pose::IDENTITY } else { rng.pose(0.5) };
        let design_j = if gj { Pose::IDENTITY } else { rng.pose(0.5) };
        let moved = |rng: &mut Rng, p: &Pose, g: bool| {
            if g {
                return Pose::IDENTITY;
            }
            let mut q = *p;
            q.apply_increment(&rng.vec(0.05), &rng.rotvec(0.2, 1.2));
            q
        };
        let pi = moved(rng, &design_i, gi);
        let pj = moved(rng, &design_j, gj);
        Geometry { point_i, point_j, design_i, design_j, pi, pj, gi, gj }
    }

    /// Seats at poses `a`, `b`, from the design data (independent of the element).
    fn seats(&self, a: &Pose, b: &Pose) -> (Vec3, Vec3) {
        let si0 = self.design_i.rotation().transpose() * (self.point_i - self.design_i.position);
        let sj0 = self.design_j.rotation().transpose() * (self.point_j - self.design_j.position);
        (a.position + a.rotation() * si0, b.position + b.rotation() * sj0)
    }

    fn length(&self, a: &Pose, b: &Pose) -> f64 {
        let (p, q) = self.seats(a, b);
        (q - p).norm()
    }

    /// A spring with `curve` whose compression at the moved poses is `c`, bound at design.
    fn spring(&self, curve: Curve, c: f64) -> CoilSpring {
        let free_length = self.length(&self.pi, &self.pj) + c;
        let (bi, bj) = (body(self.gi, 0), body(self.gj, 1));
        let mut s = CoilSpring::seated(
            "spring",
            [(bi, self.point_i), (bj, self.point_j)],
            Characteristic::Curve(curve),
            SpringLength::Free(free_length),
        )
        .unwrap();
        s.bind(&self.design_i, &self.design_j).unwrap();
        s
    }
}

const GROUNDINGS: [(bool, bool); 3] = [(false, false), (true, false), (false, true)];

#[test]
fn a_straight_two_point_table_is_the_linear_spring() {
    let mut rng = Rng::new(0x11E);
    let mut worst: f64 = 0.0;
    for (gi, gj) in GROUNDINGS {
        for _ in 0..6 {
            let g = Geometry::random(&mut rng, gi, gj);
            let (k, preload) = (rng.uniform(2e4, 1e5), rng.uniform(-1000.0, 1000.0));
            let free_length = (g.point_j - g.point_i).norm() + rng.uniform(-0.05, 0.1);
            let (bi, bj) = (body(gi, 0), body(gj, 1));
            let line = Curve::new("spring", [[0.0, 0.0], [0.1, 0.1 * k]]).unwrap();
            let mut linear = CoilSpring::new("spring", bi, g.point_i, bj, g.point_j, k, free_length).unwrap();
            let mut curved = CoilSpring::seated(
                "spring",
                [(bi, g.point_i), (bj, g.point_j)],
                Characteristic::Curve(line),
                SpringLength::Free(free_length),
            )
            .unwrap();
            linear = linear.with_preload(preload).unwrap();
            curved = curved.with_preload(preload).unwrap();
            linear.bind(&g.design_i, &g.design_j).unwrap();
            curved.bind(&g.design_i, &g.design_j).unwrap();
            let (a, b) = (eval(&linear, &g.pi, &g.pj, 0.0), eval(&curved, &g.pi, &g.pj, 0.0));
            worst = worst
                .max((a.force - b.force).amax() / a.force.amax())
                .max((a.stiffness - b.stiffness).amax() / a.stiffness.amax());
        }
    }
    // Measured: 2.8e-16 (the slope 0.1k/0.1 is k to rounding).
    assert!(worst < 2e-14, "{worst}");
}

/// A parabolic table at compressions inside it: the push force is `a c² + b c + P` along the spring, and
/// the generalized force is minus the gradient of `U = a c³/3 + b c²/2 − P L` (c = L₀ − L).
#[test]
fn force_of_a_parabolic_table_against_its_closed_form_energy() {
    let mut rng = Rng::new(0xE4E);
    for (gi, gj) in GROUNDINGS {
        for trial in 0..5 {
            let g = Geometry::random(&mut rng, gi, gj);
            let c = rng.uniform(0.005, 0.095);
            let preload = if trial % 2 == 1 { rng.uniform(-500.0, 500.0) } else { 0.0 };
            let spring = g.spring(parabola_table(), c).with_preload(preload).unwrap();
            let free_length = spring.spec().free_length;
            let energy = |a: &Pose, b: &Pose| {
                let l = g.length(a, b);
                let c = free_length - l;
                A * c * c * c / 3.0 + B * c * c / 2.0 - preload * l
            };
            let ev = eval(&spring, &g.pi, &g.pj, 0.0);
            let grad = fd_scalar(&g.pi, &g.pj, energy);
            // Measured: 2.1e-9 at worst (central differences of the energy).
            assert_vec_close(&format!("({gi},{gj}) trial {trial}: Q = −∇U"), &ev.force, &(-grad), 1e-7);
            let (p, q) = g.seats(&g.pi, &g.pj);
            let push = parabola(c) + preload;
            let rep = spring.report(&g.pi, &g.pj, 0.0);
            // Measured: 1.9e-14 of the push at worst (the compression is a difference of lengths ≈ 0.3 m).
            assert!((rep.force - push * (q - p).normalize()).norm() < 1e-12 * push.abs(), "{rep:?} vs {push}");
        }
    }
}

/// Body `j`'s reference point at its seat, `i` the ground: the translational block is
/// `F'(c) nnᵀ − (F_push/L)(I − nnᵀ)`, the axial rate the curve's slope `2ac + b` and the transverse
/// geometric term unchanged.
#[test]
fn string_tangent_with_the_curve_slope() {
    let mut rng = Rng::new(0x57);
    for c in [0.01, 0.045, 0.09, 0.15] {
        let point_i = rng.vec(0.3);
        let point_j = point_i + rng.unit() * 0.3;
        let design_j = Pose { position: point_j, orientation: rng.orientation() };
        let mut pj = design_j;
        pj.apply_increment(&rng.vec(0.03), &rng.rotvec(0.0, 1.0));
        let d = pj.position - point_i;
        let (l, n) = (d.norm(), d.normalize());
        let curve = parabola_table();
        let mut s = CoilSpring::seated(
            "s",
            [(BodyRef::Ground, point_i), (BodyRef::Body(BodyId(0)), point_j)],
            Characteristic::Curve(curve),
            SpringLength::Free(l + c),
        )
        .unwrap();
        s.bind(&Pose::IDENTITY, &design_j).unwrap();
        // Past the table's end (c = 0.15), the line with the end slope.
        let (push, rate) = if c <= PARABOLA_END {
            (parabola(c), 2.0 * A * c + B)
        } else {
            let end = 2.0 * A * PARABOLA_END + B;
            (parabola(PARABOLA_END) + end * (c - PARABOLA_END), end)
        };
        let kjj: Mat3 = eval(&s, &Pose::IDENTITY, &pj, 0.0).stiffness.fixed_view::<3, 3>(6, 6).into();
        let t = n.cross(&rng.unit()).normalize();
        // Measured: 4.0e-16 and 1.6e-16 of the rate at worst.
        assert!((kjj * n - rate * n).norm() < 2e-14 * rate, "c = {c}: {} vs {rate}", (kjj * n).dot(&n));
        assert!((kjj * t + push / l * t).norm() < 1e-14 * rate, "c = {c}: {} vs {}", (kjj * t).dot(&t), -push / l);
    }
}

/// The stiffness is the derivative of the force at compressions in every piece of a data sheet's table,
/// and on the straight continuations past both ends, at random poses with lever arms.
#[test]
fn stiffness_is_the_force_derivative_in_every_piece_of_the_table_and_past_its_ends() {
    let mut rng = Rng::new(0xD5);
    // Past the first point, in each of the six pieces, past the last point.
    let compressions = [-0.035, -0.01, 0.007, 0.022, 0.04, 0.055, 0.07, 0.1];
    let mut worst: f64 = 0.0;
    for (gi, gj) in GROUNDINGS {
        for &c in &compressions {
            for _ in 0..2 {
                let g = Geometry::random(&mut rng, gi, gj);
                let spring = g.spring(data_sheet(), c);
                let ev = eval(&spring, &g.pi, &g.pj, 0.0);
                let k_fd = fd_stiffness(&spring, &g.pi, &g.pj, 0.0);
                worst = worst.max(mat_close_error(&ev.stiffness, &k_fd));
                // Measured: 6.7e-9 at worst over the 48 configurations.
                assert_mat_close(&format!("({gi},{gj}) c = {c}"), &ev.stiffness, &k_fd, 1e-7);
                let skew_part = ev.stiffness - ev.stiffness.transpose();
                // Measured: 9.3e-11 at worst (rounding; no differences taken).
                assert_mat_close("K − Kᵀ", &skew_part, &expected_skew_part(&ev.force), 1e-9);
            }
        }
    }
}

/// The free length from the push force at design: the compression that gives it, from the parabola's
/// closed-form root inside the table and from the end lines outside it.
#[test]
fn free_length_from_the_design_force_inverts_the_curve() {
    let (a, b) = (Vec3::new(0.0, 0.5, 0.1), Vec3::new(0.0, 0.55, 0.4));
    let design = (b - a).norm();
    let end_slope = 2.0 * A * PARABOLA_END + B;
    let cases = [
        // Inside the table: a c² + b c = F.
        (300.0, (-B + (B * B + 4.0 * A * 300.0).sqrt()) / (2.0 * A)),
        (2900.0, (-B + (B * B + 4.0 * A * 2900.0).sqrt()) / (2.0 * A)),
        // Past the last point, along the end line.
        (5000.0, PARABOLA_END + (5000.0 - parabola(PARABOLA_END)) / end_slope),
        // Tension below the first point, along the start line (slope B).
        (-100.0, -100.0 / B),
    ];
    for (force, compression) in cases {
        let s = CoilSpring::seated(
            "s",
            [(BodyRef::Ground, a), (BodyRef::Body(BodyId(0)), b)],
            Characteristic::Curve(parabola_table()),
            SpringLength::DesignForce(force),
        )
        .unwrap();
        // Measured: exact (0) for the free length, allowed two units in the last place of it; 1.3e-15 of the
        // force for the push at design.
        let ulp = f64::EPSILON * s.spec().free_length;
        assert!(
            (s.spec().free_length - (design + compression)).abs() <= 2.0 * ulp,
            "{force}: {}",
            s.spec().free_length
        );
        assert!((s.push_force(design) - force).abs() < 1e-13 * force.abs(), "{force}: {}", s.push_force(design));
        let rep = s.report(&Pose::IDENTITY, &Pose::IDENTITY, 0.0);
        // Measured: 1.3e-15 of the force.
        assert!((rep.force - force * (b - a) / design).norm() < 1e-13 * force.abs());
    }
}

fn refused(result: Result<CoilSpring, ModelError>) -> String {
    match result {
        Err(e @ ModelError::OutOfRange { .. }) => {
            let text = e.to_string();
            assert!(text.starts_with("'front spring'"), "{text}");
            text
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn curves_a_spring_cannot_use_are_refused_by_name() {
    let (a, b) = (Vec3::new(0.0, 0.5, 0.1), Vec3::new(0.0, 0.55, 0.4));
    let at = |curve: Curve, force: f64| {
        CoilSpring::seated(
            "front spring",
            [(BodyRef::Ground, a), (BodyRef::Body(BodyId(0)), b)],
            Characteristic::Curve(curve),
            SpringLength::DesignForce(force),
        )
    };
    // A progressive table from (0, 0) starts with slope zero: below it the force stays 0 and never
    // reaches a pull.
    let progressive = Curve::new("front spring", [[0.0, 0.0], [0.02, 80.0], [0.04, 320.0]]).unwrap();
    let never = refused(at(progressive.clone(), -50.0));
    assert!(never.contains("never reaches the design force -50 N") && never.contains("extend the table"), "{never}");
    // Above the last point it does reach any push.
    assert!(at(progressive, 1e5).is_ok());
    // A force that drops as the spring is compressed, and a flat table.
    let drops = Curve::new("front spring", [[0.0, 0.0], [0.02, 400.0], [0.04, 390.0]]).unwrap();
    let text = refused(CoilSpring::seated(
        "front spring",
        [(BodyRef::Ground, a), (BodyRef::Body(BodyId(0)), b)],
        Characteristic::Curve(drops),
        SpringLength::Free(0.35),
    ));
    assert!(text.contains("point 2") && text.contains("never decreases"), "{text}");
    let flat = Curve::new("front spring", [[0.0, 500.0], [0.02, 500.0]]).unwrap();
    let text = refused(at(flat, 500.0));
    assert!(text.contains("flat"), "{text}");
    // A pull the curve reaches only with a free length ≤ 0, as for the linear spring.
    let line = Curve::new("front spring", [[0.0, 0.0], [0.1, 1000.0]]).unwrap();
    assert!(matches!(at(line, -1e5), Err(ModelError::NotPositive { what: "free length", .. })));
}
