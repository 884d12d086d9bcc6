//! Curve: the Fritsch–Carlson slopes of a small table worked by hand, the Hermite cubic against its
//! textbook basis, exact reproduction of straight and parabolic data, monotone tables giving monotone
//! curves, the slope as the derivative of the value, continuity at the points, and refusals.

mod common;

use common::Rng;
use elastokin_core::ModelError;
use elastokin_elements::Curve;

/// The cubic Hermite interpolant on `[x0, x1]` from its textbook basis
/// (`h00 = 2t³ − 3t² + 1`, `h10 = t³ − 2t² + t`, `h01 = −2t³ + 3t²`, `h11 = t³ − t²`): value and slope.
fn hermite(x0: f64, x1: f64, y0: f64, y1: f64, m0: f64, m1: f64, x: f64) -> (f64, f64) {
    let h = x1 - x0;
    let t = (x - x0) / h;
    let (t2, t3) = (t * t, t * t * t);
    let value = (2.0 * t3 - 3.0 * t2 + 1.0) * y0
        + (t3 - 2.0 * t2 + t) * h * m0
        + (-2.0 * t3 + 3.0 * t2) * y1
        + (t3 - t2) * h * m1;
    let slope = ((6.0 * t2 - 6.0 * t) * y0
        + (3.0 * t2 - 4.0 * t + 1.0) * h * m0
        + (-6.0 * t2 + 6.0 * t) * y1
        + (3.0 * t2 - 2.0 * t) * h * m1)
        / h;
    (value, slope)
}

/// The table x = (0, 1, 2, 4), y = (0, 0.5, 4, 4.5), worked by hand with Fritsch & Carlson's steps
/// (three-point initial slopes, flat intervals, the circle of radius 3):
///
/// * widths h = (1, 1, 2), secants Δ = (0.5, 3.5, 0.25);
/// * step 1: m₁ = (h₁Δ₀ + h₀Δ₁)/(h₀ + h₁) = (0.5 + 3.5)/2 = 2, m₂ = (h₂Δ₁ + h₁Δ₂)/(h₁ + h₂) = 7.25/3;
///   m₀ = ((2h₀ + h₁)Δ₀ − h₀Δ₁)/(h₀ + h₁) = (1.5 − 3.5)/2 = −1, against Δ₀: 0;
///   m₃ = ((2h₂ + h₁)Δ₂ − h₂Δ₁)/(h₁ + h₂) = (1.25 − 7)/3 < 0, against Δ₂: 0;
/// * step 2: no flat interval;
/// * step 3: interval 0, (α, β) = (0, 2/0.5) = (0, 4), outside the circle: τ = 3/4, m₁ = τ·4·0.5 = 1.5;
///   interval 1, (1.5/3.5, (7.25/3)/3.5) = (0.43, 0.69), inside; interval 2, ((7.25/3)/0.25, 0) =
///   (9.67, 0): τ = 3/9.67, m₂ = 3·0.25 = 0.75.
///
/// Slopes (0, 1.5, 0.75, 0).
#[test]
fn fritsch_carlson_slopes_of_a_four_point_table_worked_by_hand() {
    let table = [[0.0, 0.0], [1.0, 0.5], [2.0, 4.0], [4.0, 4.5]];
    let curve = Curve::new("table", table).unwrap();
    let expected = [0.0, 1.5, 0.75, 0.0];
    for (k, (got, want)) in curve.point_slopes().iter().zip(expected).enumerate() {
        // Measured: exact (difference 0); allowed, two units in the last place of 1.5.
        assert!((got - want).abs() <= 2.0 * f64::EPSILON * 1.5, "slope at point {k}: {got} vs {want}");
    }
    // Between the points, the Hermite cubic of those slopes; past the ends, lines with the end slopes.
    for x in [0.25, 0.5, 0.9, 1.3, 1.5, 1.99, 2.0, 2.5, 3.0, 3.7] {
        let k = [0.0, 1.0, 2.0, 4.0].iter().rposition(|&xk| xk <= x).unwrap().min(2);
        let (y, m) =
            hermite(table[k][0], table[k + 1][0], table[k][1], table[k + 1][1], expected[k], expected[k + 1], x);
        let (value, slope) = curve.value_and_slope(x);
        // Measured: differences up to 8.9e-16 (value) and 2.0e-15 (slope), rounding of the two forms.
        assert!((value - y).abs() < 1e-14 && (slope - m).abs() < 1e-14, "x = {x}: ({value}, {slope}) vs ({y}, {m})");
    }
    // By hand at x = 3 (t = ½ on [2, 4]): y = ½·4 + ⅛·2·0.75 + ½·4.5 = 4.4375, y' = (−6 − 0.375 + 6.75)/2
    // (measured: exact; allowed, about one unit in the last place).
    assert!((curve.value(3.0) - 4.4375).abs() < 1e-15 && (curve.slope(3.0) - 0.1875).abs() < 1e-15);
    assert_eq!(curve.value_and_slope(5.0), (4.5, 0.0));
    assert_eq!(curve.value_and_slope(-1.0), (0.0, 0.0));
    // The plain Hermite cubic with the unlimited slopes (2 and 7.25/3 inside) overshoots the last point
    // between 2 and 4; the limited one does not.
    let unlimited = hermite(2.0, 4.0, 4.0, 4.5, 7.25 / 3.0, 0.0, 3.0).0;
    assert!(unlimited > 4.5 && curve.value(3.0) < 4.5, "{unlimited}");
}

/// Straight-line data whose numbers are all exact in binary (x in 1/1024 m, integer rates): every
/// operation of the interpolation is then exact, and so is the curve — the line itself, inside the table
/// and past both ends, to the last bit.
#[test]
fn straight_line_data_give_the_straight_line_exactly() {
    let mut rng = Rng::new(0xC1);
    let dyadic = |rng: &mut Rng, lo: i64, hi: i64| (lo + (rng.next_u64() % (hi - lo) as u64) as i64) as f64;
    for _ in 0..20 {
        let n = 2 + (rng.next_u64() % 6) as usize;
        let (a, b) = (dyadic(&mut rng, -4000, 4000) / 8.0, dyadic(&mut rng, -30_000, 30_000));
        let mut x = dyadic(&mut rng, -100, 0) / 1024.0;
        let mut points = Vec::new();
        for _ in 0..n {
            points.push([x, a + b * x]);
            x += dyadic(&mut rng, 1, 50) / 1024.0;
        }
        let curve = Curve::new("line", points.clone()).unwrap();
        let (lo, hi) = (points[0][0] - 0.2, points[n - 1][0] + 0.2);
        let mut x = (lo * 1024.0).floor() / 1024.0;
        while x <= hi {
            assert_eq!(curve.value_and_slope(x), (a + b * x, b), "x = {x}, table {points:?}");
            x += 1.0 / 1024.0;
        }
    }
}

/// The three-point slopes are a parabola's own, and a rising parabola stays inside the circle of step 3
/// (β ≤ 2): its table's curve is the parabola between the points, and the tangent line past the ends.
#[test]
fn parabola_data_give_the_parabola_inside_and_its_tangents_outside() {
    let (c, b) = (2.0e5, 1.5e3); // y = c x² + b x, rising for x ≥ 0
    let f = |x: f64| c * x * x + b * x;
    let xs = [0.0, 0.004, 0.01, 0.013, 0.025, 0.04];
    let curve = Curve::new("parabola", xs.map(|x| [x, f(x)])).unwrap();
    let mut worst: f64 = 0.0;
    for i in 0..=400 {
        let x = 0.04 * i as f64 / 400.0;
        let (value, slope) = curve.value_and_slope(x);
        worst = worst.max((value - f(x)).abs() / f(0.04)).max((slope - (2.0 * c * x + b)).abs() / (2.0 * c * 0.04 + b));
    }
    // Measured: 6.2e-16.
    assert!(worst < 1e-14, "{worst}");
    let end = 2.0 * c * 0.04 + b;
    for x in [0.05, 0.1] {
        assert!((curve.value(x) - (f(0.04) + end * (x - 0.04))).abs() < 1e-12 * f(x), "{x}");
        assert!((curve.slope(x) - end).abs() < 1e-12 * end);
    }
    // Before the first point, the tangent at 0: slope b.
    assert!((curve.value(-0.01) + b * 0.01).abs() < 1e-12 && (curve.slope(-0.01) - b).abs() < 1e-12 * b);
    // A pure progressive table y = c x² starts with slope zero.
    let progressive = Curve::new("progressive", [0.0, 0.01, 0.02, 0.03].map(|x| [x, c * x * x])).unwrap();
    assert_eq!(progressive.point_slopes()[0], 0.0);
    assert_eq!(progressive.value_and_slope(-0.005), (0.0, 0.0));
}

/// Random tables whose y never decreases (with flats and steep steps): the curve never decreases, its
/// slope is never negative, and it passes through every point.
#[test]
fn a_monotone_table_gives_a_monotone_curve() {
    let mut rng = Rng::new(0x303);
    for trial in 0..50 {
        let n = 2 + (rng.next_u64() % 8) as usize;
        let mut points = Vec::new();
        let (mut x, mut y) = (rng.uniform(-1.0, 0.0), rng.uniform(-10.0, 10.0));
        for _ in 0..n {
            points.push([x, y]);
            x += rng.uniform(0.01, 1.0);
            // A flat, a small rise or a steep step.
            y += match rng.next_u64() % 3 {
                0 => 0.0,
                1 => rng.uniform(0.0, 1.0),
                _ => rng.uniform(10.0, 100.0),
            };
        }
        let curve = Curve::new("monotone", points.clone()).unwrap();
        for p in &points {
            assert!((curve.value(p[0]) - p[1]).abs() <= 1e-12 * p[1].abs().max(1.0), "trial {trial}");
        }
        let (lo, hi) = (points[0][0] - 0.5, points[n - 1][0] + 0.5);
        let mut last = f64::NEG_INFINITY;
        for i in 0..=3000 {
            let x = lo + (hi - lo) * i as f64 / 3000.0;
            let (value, slope) = curve.value_and_slope(x);
            let scale = value.abs().max(1.0);
            assert!(value >= last - 1e-12 * scale, "trial {trial}: falls at x = {x}: {last} -> {value}");
            assert!(slope >= -1e-12 * scale, "trial {trial}: slope {slope} at x = {x}");
            last = value;
        }
    }
}

/// The slope is the derivative of the value (central differences, inside and past the ends), and value
/// and slope are continuous at every point of the table: on either side of a point, one floating-point
/// number apart, they agree to rounding.
#[test]
fn slope_is_the_derivative_of_the_value_and_both_are_continuous_at_the_points() {
    let mut rng = Rng::new(0x51);
    let mut worst_fd: f64 = 0.0;
    let mut worst_jump: f64 = 0.0;
    for _ in 0..20 {
        let n = 3 + (rng.next_u64() % 6) as usize;
        let mut points = Vec::new();
        let mut x = 0.01;
        for _ in 0..n {
            // Not monotone: peaks and valleys too.
            points.push([x, rng.uniform(-1e3, 1e3)]);
            x += rng.uniform(0.005, 0.05);
        }
        let curve = Curve::new("wavy", points.clone()).unwrap();
        let scale = curve.point_slopes().iter().fold(1.0f64, |a, m| a.max(m.abs()));
        for _ in 0..200 {
            let x = rng.uniform(-0.05, points[n - 1][0] + 0.05);
            if points.iter().any(|p| (p[0] - x).abs() < 1e-4) {
                continue; // keep the stencil inside one piece
            }
            let h = 1e-7;
            let fd = (curve.value(x + h) - curve.value(x - h)) / (2.0 * h);
            worst_fd = worst_fd.max((fd - curve.slope(x)).abs() / scale);
        }
        for p in &points {
            let (left, right) = (curve.value_and_slope(p[0].next_down()), curve.value_and_slope(p[0]));
            let jump = ((left.0 - right.0).abs() / scale).max((left.1 - right.1).abs() / scale);
            worst_jump = worst_jump.max(jump);
        }
    }
    // Measured: 2.7e-9 (the central difference's truncation and rounding at h = 1e-7), and 1.3e-13 across
    // a point (rounding of the two pieces' forms).
    assert!(worst_fd < 2e-7, "{worst_fd}");
    assert!(worst_jump < 1e-12, "{worst_jump}");
}

fn refusal(points: &[[f64; 2]]) -> String {
    match Curve::new("front bush", points) {
        Err(e @ ModelError::OutOfRange { .. }) => e.to_string(),
        other => panic!("{other:?}"),
    }
}

#[test]
fn bad_tables_are_refused_with_the_point_and_the_fix() {
    let one = refusal(&[[0.0, 0.0]]);
    assert!(one.contains("'front bush'") && one.contains("at least two points") && one.contains("got 1"), "{one}");
    assert!(refusal(&[]).contains("got 0"));
    let nan = refusal(&[[0.0, 0.0], [0.01, f64::NAN], [0.02, 3.0]]);
    assert!(nan.contains("point 1") && nan.contains("give finite numbers"), "{nan}");
    let inf = refusal(&[[0.0, 0.0], [0.01, 1.0], [f64::INFINITY, 3.0]]);
    assert!(inf.contains("point 2") && inf.contains("not finite"), "{inf}");
    let back = refusal(&[[0.0, 0.0], [0.02, 1.0], [0.01, 3.0]]);
    assert!(back.contains("point 2") && back.contains("strictly increasing x"), "{back}");
    let repeat = refusal(&[[0.0, 0.0], [0.01, 1.0], [0.01, 3.0]]);
    assert!(repeat.contains("point 2") && repeat.contains("each x once"), "{repeat}");
    let steep = refusal(&[[0.0, -1e308], [1e-300, 1e308]]);
    assert!(steep.contains("point 0 to point 1") && steep.contains("overflows"), "{steep}");
}
