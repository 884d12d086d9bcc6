//! Bump and rebound stops: one-sided elastic limits of travel along the spring or damper axis.
//!
//! # Model
//!
//! A stop acts along the line between a point on body `i` and a point on body `j` (the same geometry as a
//! [`CoilSpring`](crate::CoilSpring): `d = Pⱼ − Pᵢ`, `L = |d|`, `n = d / L`). Its clearance `e` is
//! measured from the design length `L_d = |Pⱼ − Pᵢ|` at design (negative: the stop is already in contact
//! at design by `−e`, as another tool's data may have it); past it, the penetration `p` drives a force
//! from the stop's curve `F(p)` (N against m, the rubber's data sheet):
//!
//! * a **bump stop** ([`StopKind::Bump`]) touches when the length has shortened by the clearance,
//!   `p = (L_d − e) − L`, and **pushes the points apart** with `F(p)`;
//! * a **rebound stop** ([`StopKind::Rebound`]) touches when the length has grown by the clearance,
//!   `p = L − (L_d + e)`, and **pulls them together** with `F(p)`.
//!
//! Before contact (`p ≤ 0`) the stop applies no force and has no stiffness. The curve starts at `(0, 0)`:
//! the force grows from zero at first contact, monotone cubic through the table and **linear past its last
//! point** with the slope there ([`Curve`]). Its force must never decrease.
//!
//! # Smoothness at contact
//!
//! The force is continuous at contact. Its rate jumps from zero to the curve's slope at `p = 0`: a
//! progressive table sampled from `F = c p²` (points `(0, 0)`, `(h, c h²)`, `(2h, 4c h²)`, …) starts with
//! slope zero (see the [curve's end slopes](crate::curve)), so the force is C¹ through contact and Newton's
//! method converges quadratically there as everywhere. A table whose first segment rises at once (a
//! linear stop, `(0, 0)`, `(h, k h)`) puts a kink in the force at contact. The load step on which such a
//! stop engages starts before contact, with a tangent that does not see the stop: Newton's first iteration
//! overshoots into it and gains nothing, and the step may take one iteration more than its neighbours;
//! from there the convergence is quadratic again (`crates/solver/tests/nonlinear_elements.rs` measures
//! both). Exactly at `p = 0` the stop counts as not in contact.
//!
//! # Stiffness
//!
//! The push force (`F(p)` for a bump stop, `−F(p)` for a rebound stop) has the axial rate
//! `−∂F_push/∂L = F'(p)` for both kinds; `K` is the spring's (module docs of
//! [`coil_spring`](crate::coil_spring)), with the transverse term `F_push/L` and the skew part of the
//! lever arms, and zero before contact.

use crate::coil_spring::{check_seats, MIN_SPRING_LENGTH};
use crate::curve::{Anchor, Curve};
use crate::geometry::{check_distinct, check_finite, push_along, Seats};
use elastokin_core::{
    BodyRef, ElementEval, ElementReport, ElementRole, ForceElement, ModelError, Pose, Sketch, SketchKind, Vec3,
};

/// Which way a stop limits the travel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize), serde(rename_all = "snake_case"))]
pub enum StopKind {
    /// Acts when the points come closer than the design length less the clearance; pushes them apart.
    Bump,
    /// Acts when the points move further apart than the design length plus the clearance; pulls them
    /// together.
    Rebound,
}

/// Global design data of a bump or rebound stop: what a user writes. SI units throughout.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct StopSpec {
    /// Unique name, used in diagnostics and results.
    pub name: String,
    /// Body `i` (may be the ground).
    pub body_i: BodyRef,
    /// Point on `i` at design (global, m), on the stop's axis.
    pub point_i: Vec3,
    /// Body `j` (may be the ground); [`ElementReport`] gives the force applied to it.
    pub body_j: BodyRef,
    /// Point on `j` at design (global, m), on the stop's axis.
    pub point_j: Vec3,
    /// Bump or rebound.
    pub kind: StopKind,
    /// Travel from the design length to first contact, m (zero: touching at design).
    pub clearance: f64,
    /// Force (N) against penetration past first contact (m), starting at `(0, 0)`.
    pub curve: Curve,
}

impl StopSpec {
    fn validate(&self) -> Result<(), ModelError> {
        let name = self.name.as_str();
        check_distinct(name, self.body_i, self.body_j)?;
        check_finite(name, "point on i", &self.point_i)?;
        check_finite(name, "point on j", &self.point_j)?;
        check_seats(name, &self.point_i, &self.point_j)?;
        let refuse = |why: String| Err(ModelError::OutOfRange { item: name.to_string(), why });
        if !self.clearance.is_finite() {
            return Err(ModelError::NonFinite { item: name.to_string(), what: "clearance" });
        }
        if self.contact_length() < MIN_SPRING_LENGTH {
            let design = self.design_length();
            return refuse(match self.kind {
                StopKind::Rebound => format!(
                    "a rebound-stop clearance of {} m puts first contact at a length of zero or less (the design \
                     length is {design} m): give the travel from design to first contact, negative only when the \
                     stop is already in contact at design",
                    self.clearance
                ),
                StopKind::Bump => format!(
                    "a bump-stop clearance of {} m is not shorter than the design length {design} m between its \
                     points: the stop could never touch; give the travel to first contact",
                    self.clearance
                ),
            });
        }
        self.curve.check_rising(name, "stop force", Anchor::StartsAtOrigin)
    }

    /// Design length `|point_j − point_i|`.
    pub fn design_length(&self) -> f64 {
        (self.point_j - self.point_i).norm()
    }

    /// Length at first contact: `L_d − e` for a bump stop, `L_d + e` for a rebound stop.
    pub fn contact_length(&self) -> f64 {
        match self.kind {
            StopKind::Bump => self.design_length() - self.clearance,
            StopKind::Rebound => self.design_length() + self.clearance,
        }
    }
}

/// A bump or rebound stop between two body points (see the [module docs](self)).
#[derive(Debug, Clone, PartialEq)]
pub struct Stop {
    spec: StopSpec,
    seats: Seats,
    contact_length: f64,
}

impl Stop {
    /// A bump stop: pushes the points apart with `curve(p)` once they have come `clearance` (m) closer
    /// than at design, `p` the travel past that. Errors: same bodies ([`ModelError::SelfJoint`]),
    /// non-finite data ([`ModelError::NonFinite`]), points closer than
    /// [`MIN_SPRING_LENGTH`] ([`ModelError::CoincidentPoints`]),
    /// and [`ModelError::OutOfRange`] for a contact length of zero or less (a clearance not shorter than the design
    /// length, or a curve that does not start at `(0, 0)`, decreases somewhere or is flat.
    pub fn bump(
        name: &str,
        body_i: BodyRef,
        point_i: Vec3,
        body_j: BodyRef,
        point_j: Vec3,
        clearance: f64,
        curve: Curve,
    ) -> Result<Self, ModelError> {
        let kind = StopKind::Bump;
        Self::from_spec(StopSpec { name: name.to_string(), body_i, point_i, body_j, point_j, kind, clearance, curve })
    }

    /// A rebound stop: pulls the points together with `curve(p)` once they have moved `clearance` (m)
    /// further apart than at design. Errors as [`Stop::bump`] (any clearance ≥ 0 is possible).
    pub fn rebound(
        name: &str,
        body_i: BodyRef,
        point_i: Vec3,
        body_j: BodyRef,
        point_j: Vec3,
        clearance: f64,
        curve: Curve,
    ) -> Result<Self, ModelError> {
        let kind = StopKind::Rebound;
        Self::from_spec(StopSpec { name: name.to_string(), body_i, point_i, body_j, point_j, kind, clearance, curve })
    }

    /// A stop from its full description (validated as in [`Stop::bump`]).
    pub fn from_spec(spec: StopSpec) -> Result<Self, ModelError> {
        spec.validate()?;
        Ok(Stop { seats: Seats::new(&spec.point_i, &spec.point_j), contact_length: spec.contact_length(), spec })
    }

    /// The design data.
    pub fn spec(&self) -> &StopSpec {
        &self.spec
    }

    /// Penetration past first contact at length `L` (m): positive in contact, minus the remaining gap
    /// before.
    pub fn penetration(&self, length: f64) -> f64 {
        match self.spec.kind {
            StopKind::Bump => self.contact_length - length,
            StopKind::Rebound => length - self.contact_length,
        }
    }

    /// Push force at length `L` (N, positive pushes the points apart: a bump stop's force is ≥ 0, a
    /// rebound stop's ≤ 0), zero before contact.
    pub fn push_force(&self, length: f64) -> f64 {
        self.push_and_rate(length).0
    }

    /// Push force and axial rate `−∂F_push/∂L`.
    fn push_and_rate(&self, length: f64) -> (f64, f64) {
        let p = self.penetration(length);
        // `p ≤ 0` is no contact; so is a NaN length, whose direction then carries NaN to the result.
        if p > 0.0 {
            let (force, rate) = self.spec.curve.value_and_slope(p);
            match self.spec.kind {
                StopKind::Bump => (force, rate),
                StopKind::Rebound => (-force, rate),
            }
        } else {
            (0.0, 0.0)
        }
    }
}

impl ForceElement for Stop {
    fn name(&self) -> &str {
        &self.spec.name
    }

    fn bodies(&self) -> [BodyRef; 2] {
        [self.spec.body_i, self.spec.body_j]
    }

    fn role(&self) -> ElementRole {
        ElementRole::Elastic
    }

    fn bind(&mut self, pi: &Pose, pj: &Pose) -> Result<(), ModelError> {
        self.spec.validate()?;
        self.seats.bind(&self.spec.name, pi, pj, &self.spec.point_i, &self.spec.point_j)
    }

    fn sketch(&self) -> Option<Sketch> {
        Some(self.seats.sketch(SketchKind::Stop))
    }

    fn evaluate(&self, pi: &Pose, pj: &Pose, _t: f64, out: &mut ElementEval, with_stiffness: bool) {
        let line = self.seats.line(pi, pj);
        let (push, rate) = self.push_and_rate(line.length);
        push_along(&line, push, rate, out, with_stiffness);
    }

    /// In contact or not, when the curve's rate at contact is not zero (the force's rate jumps there);
    /// a progressive curve, starting with zero rate, is one piece.
    fn piece(&self, pi: &Pose, pj: &Pose, _t: f64) -> u8 {
        let jumps = self.spec.curve.value_and_slope(0.0).1 != 0.0;
        u8::from(jumps && self.penetration(self.seats.line(pi, pj).length) > 0.0)
    }

    /// Force on `j`; the deflection's x component is the penetration (positive in contact).
    fn report(&self, pi: &Pose, pj: &Pose, _t: f64) -> ElementReport {
        let line = self.seats.line(pi, pj);
        ElementReport {
            force: line.n * self.push_force(line.length),
            torque: Vec3::zeros(),
            deflection: Vec3::new(self.penetration(line.length), 0.0, 0.0),
            rotation: Vec3::zeros(),
        }
    }
}
