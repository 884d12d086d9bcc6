//! Measured characteristics: a table of points from a data sheet and the smooth curve through it.
//!
//! A [`Curve`] holds the `(x, y)` points a data sheet or a rig test gives — push force against
//! compression for a coil spring, force against deflection or moment against twist for a bushing, force
//! against penetration for a bump stop — and passes a C¹ curve through them: the force and the rate are
//! continuous everywhere, so the stiffness the solver sees never jumps and Newton's method keeps its
//! quadratic convergence when a deflection crosses a point of the table. A [`Characteristic`] is what an
//! element direction is given: a constant rate, or a curve.
//!
//! # Inside the table: monotone cubic (Fritsch–Carlson)
//!
//! With points `(xₖ, yₖ)`, `k = 0…n−1`, `x` strictly increasing, widths `hₖ = xₖ₊₁ − xₖ` and secants
//! `Δₖ = (yₖ₊₁ − yₖ)/hₖ`, the slopes `mₖ` at the points are chosen in the three steps of Fritsch & Carlson
//! (SIAM J. Numer. Anal. 17, 1980), initialised with the three-point formula (the slope of the parabola
//! through a point and its two neighbours):
//!
//! 1. inside, `mₖ = (hₖ Δₖ₋₁ + hₖ₋₁ Δₖ)/(hₖ₋₁ + hₖ)` when `Δₖ₋₁` and `Δₖ` have the same sign, else `0` (a
//!    peak or a flat of the data stays one); at the ends, `m₀ = ((2h₀ + h₁) Δ₀ − h₀ Δ₁)/(h₀ + h₁)` and its
//!    mirror image for `mₙ₋₁`, set to `0` when its sign differs from the end secant's; with two points,
//!    `m₀ = m₁ = Δ₀`;
//! 2. on every flat interval (`Δₖ = 0`), `mₖ = mₖ₊₁ = 0`;
//! 3. interval by interval in increasing `k`, with `αₖ = mₖ/Δₖ`, `βₖ = mₖ₊₁/Δₖ`: where
//!    `αₖ² + βₖ² > 9`, both are scaled by `τ = 3/√(αₖ² + βₖ²)` (`mₖ = τ αₖ Δₖ`, `mₖ₊₁ = τ βₖ Δₖ`).
//!
//! On each interval the curve is the cubic Hermite polynomial with the values `yₖ`, `yₖ₊₁` and the slopes
//! `mₖ`, `mₖ₊₁` at its ends. Step 3 puts `(αₖ, βₖ)` in the region where that cubic is monotone, so a table
//! whose `y` never decreases gives a curve that never decreases: no overshoot between points. Data from a
//! parabola are reproduced exactly (the three-point slopes are its slopes and step 3 leaves them alone) —
//! in particular a progressive table `y = c x²` starting at `(0, 0)` starts with slope zero — and so are
//! data on a straight line.
//!
//! # Past the ends: linear
//!
//! Before the first point and after the last, the curve continues as a straight line with the slope at
//! that end, `y = y₀ + m₀ (x − x₀)` and `y = yₙ₋₁ + mₙ₋₁ (x − xₙ₋₁)`: value and slope stay continuous, and
//! a deflection beyond the measured range keeps the last measured rate (which may be zero, see step 1).
//! Give points up to the largest deflection the analysis should see if that rate is not what the part does
//! beyond.
//!
//! # Example
//!
//! ```
//! use elastokin_core::{BodyRef, Model, Pose, Vec3};
//! use elastokin_elements::{Characteristic, CoilSpring, Curve, SpringLength, Stop};
//!
//! let mut model = Model::new();
//! let arm = model.add_body("lower arm", Pose::at(Vec3::new(0.0, 0.6, 0.0))).unwrap();
//! let (top, seat) = (Vec3::new(0.0, 0.5, 0.55), Vec3::new(0.0, 0.5, 0.2));
//! // The data sheet: push force (N) against compression from the free length (m).
//! let sheet = Curve::new("spring", [[0.0, 0.0], [0.03, 900.0], [0.06, 2000.0], [0.09, 3600.0]]).unwrap();
//! // 2000 N at the design length (0.35 m): the free length is where the sheet's 0.06 m puts it.
//! let spring =
//!     CoilSpring::seated("spring", [(BodyRef::Ground, top), (arm.into(), seat)], Characteristic::Curve(sheet), SpringLength::DesignForce(2000.0))
//!         .unwrap();
//! assert!((spring.spec().free_length - 0.41).abs() < 1e-12);
//! model.add_element(spring).unwrap();
//! // A progressive bump stop that touches after 40 mm more compression.
//! let rubber = Curve::new("bump stop", [[0.0, 0.0], [0.01, 200.0], [0.02, 800.0]]).unwrap();
//! let stop = Stop::bump("bump stop", BodyRef::Ground, top, arm.into(), seat, 0.04, rubber).unwrap();
//! model.add_element(stop).unwrap();
//!
//! // A table must list its points by increasing x; the error names the curve and the point.
//! let err = Curve::new("spring", [[0.0, 0.0], [0.03, 900.0], [0.02, 1200.0]]).unwrap_err();
//! assert!(err.to_string().contains("'spring': point 2"));
//! ```

use crate::geometry::check_positive;
use elastokin_core::ModelError;

/// The table of a measured characteristic and the monotone C¹ cubic through it (see the
/// [module docs](self) for the interpolation and the linear extrapolation past the ends).
///
/// A `Curve` is valid by construction: at least two finite points, `x` strictly increasing. What the table
/// means (force against compression, moment against twist, …) and what else it must satisfy (passing
/// through `(0, 0)`, force never decreasing) is the element's to say and check.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(try_from = "Vec<[f64; 2]>", into = "Vec<[f64; 2]>")
)]
pub struct Curve {
    points: Vec<[f64; 2]>,
    /// Fritsch–Carlson slope at each point.
    slopes: Vec<f64>,
}

impl Curve {
    /// A curve through `points`, `[x, y]` each, in order of strictly increasing `x`.
    ///
    /// `item` is the name errors carry: the element the curve belongs to (and, for a bushing, which
    /// direction). Errors, all [`ModelError::OutOfRange`] naming `item` and the point's index (from 0):
    /// fewer than two points, a non-finite coordinate, an `x` not above the previous one, two points so
    /// close or so far apart in value that the slope between them overflows.
    pub fn new(item: &str, points: impl Into<Vec<[f64; 2]>>) -> Result<Self, ModelError> {
        let points = points.into();
        let refuse = |why: String| Err(ModelError::OutOfRange { item: item.to_string(), why });
        if points.len() < 2 {
            return refuse(format!(
                "a curve needs at least two points (x, y), got {}: give the table of the measured characteristic",
                points.len()
            ));
        }
        for (k, p) in points.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return refuse(format!(
                    "point {k} of the curve, ({}, {}), is not finite (NaN or infinity): give finite numbers",
                    p[0], p[1]
                ));
            }
            if k > 0 {
                let before = points[k - 1];
                if p[0] <= before[0] {
                    return refuse(format!(
                        "point {k} of the curve has x = {}, not above x = {} of point {}: list the points in \
                         order of strictly increasing x, each x once",
                        p[0],
                        before[0],
                        k - 1
                    ));
                }
                if !secant(&points, k - 1).is_finite() {
                    return refuse(format!(
                        "the slope from point {} to point {k} of the curve overflows: rescale the table (SI units)",
                        k - 1
                    ));
                }
            }
        }
        let slopes = fritsch_carlson_slopes(&points);
        Ok(Curve { points, slopes })
    }

    /// The table, `[x, y]` per point.
    pub fn points(&self) -> &[[f64; 2]] {
        &self.points
    }

    /// The curve's slope at each point of the table (steps 1–3 of the [module docs](self)).
    pub fn point_slopes(&self) -> &[f64] {
        &self.slopes
    }

    /// The curve's value at `x` (linear past the ends).
    pub fn value(&self, x: f64) -> f64 {
        self.value_and_slope(x).0
    }

    /// The curve's slope `dy/dx` at `x` (the end slope past the ends).
    pub fn slope(&self, x: f64) -> f64 {
        self.value_and_slope(x).1
    }

    /// Value and slope at `x` in one lookup. A NaN `x` gives NaN.
    pub fn value_and_slope(&self, x: f64) -> (f64, f64) {
        let p = &self.points;
        let last = p.len() - 1;
        if x >= p[last][0] {
            let m = self.slopes[last];
            return (p[last][1] + m * (x - p[last][0]), m);
        }
        // Number of points at or left of x: 0 before the table (and for NaN, which compares false).
        let at_or_left = p.partition_point(|q| q[0] <= x);
        if at_or_left == 0 {
            let m = self.slopes[0];
            return (p[0][1] + m * (x - p[0][0]), m);
        }
        let k = at_or_left - 1;
        let h = p[k + 1][0] - p[k][0];
        let d = secant(p, k);
        let (m0, m1) = (self.slopes[k], self.slopes[k + 1]);
        // Hermite cubic in powers of s = x − xₖ: y = yₖ + s (m₀ + s (c₂ + s c₃)).
        let c2 = (3.0 * d - 2.0 * m0 - m1) / h;
        let c3 = (m0 + m1 - 2.0 * d) / (h * h);
        let s = x - p[k][0];
        (p[k][1] + s * (m0 + s * (c2 + s * c3)), m0 + s * (2.0 * c2 + 3.0 * s * c3))
    }

    /// The least `x` at which a curve whose `y` never decreases takes the value `y`, or `None` when it
    /// never does (past an end with slope zero the curve stays at that end's value).
    pub(crate) fn inverse(&self, y: f64) -> Option<f64> {
        if !y.is_finite() {
            return None;
        }
        let p = &self.points;
        let last = p.len() - 1;
        if y < p[0][1] {
            let m = self.slopes[0];
            return (m > 0.0).then(|| p[0][0] - (p[0][1] - y) / m);
        }
        if y > p[last][1] {
            let m = self.slopes[last];
            return (m > 0.0).then(|| p[last][0] + (y - p[last][1]) / m);
        }
        // The first point at or above y; the cubic before it rises from below y to at least y.
        let j = p.partition_point(|q| q[1] < y);
        if j == 0 {
            return Some(p[0][0]);
        }
        let (mut below, mut above) = (p[j - 1][0], p[j][0]);
        loop {
            let mid = 0.5 * (below + above);
            if mid <= below || mid >= above {
                return Some(above);
            }
            if self.value(mid) < y {
                below = mid;
            } else {
                above = mid;
            }
        }
    }

    /// The ends of the range of `y` the curve covers (±∞ where an end slope is positive), for messages.
    pub(crate) fn reach(&self) -> (f64, f64) {
        let last = self.points.len() - 1;
        let low = if self.slopes[0] > 0.0 { f64::NEG_INFINITY } else { self.points[0][1] };
        let high = if self.slopes[last] > 0.0 { f64::INFINITY } else { self.points[last][1] };
        (low, high)
    }

    /// An element's checks on its curve: `y` never decreases and rises somewhere (a force that falls as
    /// the deflection grows is a negative stiffness; a flat table gives none), and the anchor at `(0, 0)`.
    pub(crate) fn check_rising(&self, item: &str, what: &str, anchor: Anchor) -> Result<(), ModelError> {
        let refuse = |why: String| Err(ModelError::OutOfRange { item: item.to_string(), why });
        let p = &self.points;
        for k in 1..p.len() {
            if p[k][1] < p[k - 1][1] {
                return refuse(format!(
                    "the curve for the {what} falls from y = {} at point {} to y = {} at point {k}: a force that \
                     drops as the deflection grows is a negative stiffness; give a table whose y never decreases",
                    p[k - 1][1],
                    k - 1,
                    p[k][1]
                ));
            }
        }
        if p[p.len() - 1][1] == p[0][1] {
            return refuse(format!(
                "the curve for the {what} is flat (y = {} at every point): it gives no stiffness; give a rising table",
                p[0][1]
            ));
        }
        match anchor {
            Anchor::Free => Ok(()),
            Anchor::ThroughOrigin => {
                if p.iter().any(|q| q[0] == 0.0 && q[1] == 0.0) {
                    Ok(())
                } else {
                    refuse(format!(
                        "the curve for the {what} has no point (0, 0): it gives the force of the deflection \
                         alone, zero at zero deflection; add the point (0, 0) and give a force at zero deflection \
                         as the preload"
                    ))
                }
            }
            Anchor::StartsAtOrigin => {
                if p[0] == [0.0, 0.0] {
                    Ok(())
                } else {
                    refuse(format!(
                        "the curve for the {what} starts at ({}, {}), not (0, 0): it gives the force against the \
                         penetration past first contact, where the force is zero; start the table at (0, 0)",
                        p[0][0], p[0][1]
                    ))
                }
            }
        }
    }
}

/// Where an element's curve must pass at zero deflection.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Anchor {
    /// Anywhere (a spring's push force may be non-zero at zero compression).
    Free,
    /// Through `(0, 0)`, the table may extend to both sides (a bushing direction).
    ThroughOrigin,
    /// The first point is `(0, 0)` (a stop: force against penetration).
    StartsAtOrigin,
}

#[cfg(feature = "serde")]
impl TryFrom<Vec<[f64; 2]>> for Curve {
    type Error = ModelError;
    /// A curve read from a file: errors name it "curve" (the file reader adds where it stands).
    fn try_from(points: Vec<[f64; 2]>) -> Result<Self, ModelError> {
        Curve::new("curve", points)
    }
}

#[cfg(feature = "serde")]
impl From<Curve> for Vec<[f64; 2]> {
    fn from(curve: Curve) -> Self {
        curve.points
    }
}

/// `Δₖ`, the secant of interval `k`.
fn secant(p: &[[f64; 2]], k: usize) -> f64 {
    (p[k + 1][1] - p[k][1]) / (p[k + 1][0] - p[k][0])
}

/// Steps 1–3 of the module docs.
fn fritsch_carlson_slopes(p: &[[f64; 2]]) -> Vec<f64> {
    let n = p.len();
    let h = |k: usize| p[k + 1][0] - p[k][0];
    let d = |k: usize| secant(p, k);
    let mut m = vec![0.0; n];
    if n == 2 {
        m.fill(d(0));
    } else {
        for k in 1..n - 1 {
            m[k] = if d(k - 1) * d(k) > 0.0 { (h(k) * d(k - 1) + h(k - 1) * d(k)) / (h(k - 1) + h(k)) } else { 0.0 };
        }
        m[0] = end_slope(h(0), h(1), d(0), d(1));
        m[n - 1] = end_slope(h(n - 2), h(n - 3), d(n - 2), d(n - 3));
    }
    for k in 0..n - 1 {
        if d(k) == 0.0 {
            m[k] = 0.0;
            m[k + 1] = 0.0;
        }
    }
    for k in 0..n - 1 {
        let dk = d(k);
        if dk == 0.0 {
            continue;
        }
        let (a, b) = (m[k] / dk, m[k + 1] / dk);
        let r2 = a * a + b * b;
        if r2 > 9.0 {
            let tau = 3.0 / r2.sqrt();
            m[k] = tau * a * dk;
            m[k + 1] = tau * b * dk;
        }
    }
    m
}

/// Three-point slope at an end (`h0`, `d0` the end interval, `h1`, `d1` its neighbour), zero when it
/// points against the end secant.
fn end_slope(h0: f64, h1: f64, d0: f64, d1: f64) -> f64 {
    let m = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if m * d0 > 0.0 {
        m
    } else {
        0.0
    }
}

/// What an element direction is given: a constant rate, or a measured curve of force (or moment) against
/// deflection (or twist). For a coil spring the deflection is the compression and the force its push; for
/// a bushing, each of its six directions has its own.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize), serde(rename_all = "snake_case"))]
pub enum Characteristic {
    /// `F = k x`: the rate `k` (N/m, or N·m/rad for a twist), positive.
    Rate(f64),
    /// `F = curve(x)`, monotone cubic through the table, linear past its ends.
    Curve(Curve),
}

impl Characteristic {
    /// Three rates, one per axis (a linear bushing's translational or rotational stiffnesses).
    pub fn rates(k: &elastokin_core::Vec3) -> [Characteristic; 3] {
        [Characteristic::Rate(k.x), Characteristic::Rate(k.y), Characteristic::Rate(k.z)]
    }

    /// Force and rate `(F(x), dF/dx)` at the deflection `x`.
    pub fn value_and_slope(&self, x: f64) -> (f64, f64) {
        match self {
            Characteristic::Rate(k) => (k * x, *k),
            Characteristic::Curve(c) => c.value_and_slope(x),
        }
    }

    /// The least deflection at which the force is `force`, `None` when it never is.
    pub(crate) fn inverse(&self, force: f64) -> Option<f64> {
        match self {
            Characteristic::Rate(k) => Some(force / k),
            Characteristic::Curve(c) => c.inverse(force),
        }
    }

    /// A rate must be positive and finite (`what` names it); a curve must rise and meet its anchor.
    pub(crate) fn check(&self, item: &str, what: &'static str, anchor: Anchor) -> Result<(), ModelError> {
        match self {
            Characteristic::Rate(k) => check_positive(item, what, *k),
            Characteristic::Curve(c) => c.check_rising(item, what, anchor),
        }
    }
}
