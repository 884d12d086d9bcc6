//! Coil spring between two body points, linear or with the push force of a data sheet.
//!
//! # Model
//!
//! Points `Pᵢ = rᵢ + sᵢ` on `i` and `Pⱼ = rⱼ + sⱼ` on `j` (`s = A s'`), separation `d = Pⱼ − Pᵢ`, length
//! `L = |d|`, unit vector `n = d / L` (from `i` to `j`). The spring **pushes the points apart** with
//!
//! ```text
//! F_push = F(c) + P,   c = L₀ − L
//! ```
//!
//! with the compression `c` from the free length `L₀` > 0 and a constant preload `P` (compressive positive).
//! The force applied to `j` is `F_push n` at `Pⱼ`, the force applied to `i` is `−F_push n` at `Pᵢ`;
//! `F_push > 0` is compression. The characteristic `F` ([`Characteristic`]) is either
//!
//! * a rate: `F(c) = k c` (`k` > 0), the linear spring, energy `U = ½ k (L − L₀)² − P L`; or
//! * a curve: the data sheet's table of **push force (N) against compression from the free length (m)**,
//!   interpolated by the monotone cubic of [`Curve`](crate::curve::Curve) — continuous force and rate, no overshoot between the
//!   points — and continued **linearly past each end** with the end slope. A negative compression is an
//!   extension beyond the free length, where the spring pulls as the linear one does (it is held in its
//!   seats): below the table's first point the force follows the slope there. The push force must never
//!   decrease with compression. A two-point table `(0, 0)`, `(c₁, k c₁)` is the linear spring.
//!
//! The free length is given, or found from the push force at the design length
//! ([`CoilSpring::seated`] with [`SpringLength::DesignForce`]): the compression at
//! design is the least `c` with `F(c)` equal to it, and `L₀ = L_design + c`. Past an end where the table's
//! slope is zero (a table that starts flat, as a progressive one can) the curve never leaves that end's
//! force; a design force it never reaches is refused, naming the spring.
//!
//! # Stiffness
//!
//! With `φ = F_push n` (force on `j`), `∂φ/∂d = T = −F'(c) nnᵀ + (F_push/L)(I − nnᵀ)` and
//! `δd = B Δq`, `B = [−I, s̃ᵢ, I, −s̃ⱼ]`:
//!
//! ```text
//! K = −∂Q/∂Δq = −Bᵀ T B + diag(0, φ̃ s̃ᵢ, 0, −φ̃ s̃ⱼ)
//! ```
//!
//! The axial rate `F'(c)` is `k`, or the curve's slope at the current compression;
//! `−T = F'(c) nnᵀ + (tension/L)(I − nnᵀ)` is the familiar string tangent (tension = −F_push, so a
//! compressed spring has a *negative* transverse stiffness). The second term, from the lever arms
//! turning with the bodies, makes `K` non-symmetric unless `sᵢ` and `sⱼ` are parallel to the spring:
//! `K − Kᵀ = diag(0, [Q_πᵢ]~, 0, [Q_πⱼ]~)`, the skew part every left-increment tangent carries.
//!
//! # Degenerate length
//!
//! If at run time `L` falls below `1e-9 · L_design` the direction is undefined. The element then uses the
//! design direction carried by body `i` as `n`, keeps `F_push = F(L₀ − L) + P` and drops the transverse
//! term `(F_push/L)(I − nnᵀ)` from the tangent, so that it returns finite values; such a configuration
//! (the two spring seats through each other) is not physical.

use crate::curve::{Anchor, Characteristic};
use crate::geometry::{check_distinct, check_finite, check_finite_scalar, check_positive, push_along, Seats};
use elastokin_core::{
    BodyRef, ElementEval, ElementReport, ElementRole, ForceElement, ModelError, Pose, Sketch, SketchKind, Vec3,
};

/// Smallest design length of a spring or stop (m); shorter is [`ModelError::CoincidentPoints`].
pub const MIN_SPRING_LENGTH: f64 = 1e-9;

/// Global design data of a coil spring: what a user writes. SI units throughout.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CoilSpringSpec {
    /// Unique name, used in diagnostics and results.
    pub name: String,
    /// Body `i` (may be the ground).
    pub body_i: BodyRef,
    /// Spring seat on `i` at design (global, m).
    pub point_i: Vec3,
    /// Body `j` (may be the ground); [`ElementReport`] gives the force applied to it.
    pub body_j: BodyRef,
    /// Spring seat on `j` at design (global, m).
    pub point_j: Vec3,
    /// Push force against compression `c = L₀ − L`: a rate `k` (N/m), or a curve (N against m).
    pub characteristic: Characteristic,
    /// Free length `L₀`, m.
    pub free_length: f64,
    /// Constant preload `P` added to the characteristic's force, N (compressive positive).
    #[cfg_attr(feature = "serde", serde(default))]
    pub preload: f64,
}

impl CoilSpringSpec {
    fn validate(&self) -> Result<(), ModelError> {
        let name = self.name.as_str();
        check_distinct(name, self.body_i, self.body_j)?;
        check_finite(name, "point on i", &self.point_i)?;
        check_finite(name, "point on j", &self.point_j)?;
        self.characteristic.check(name, "spring rate", Anchor::Free)?;
        check_positive(name, "free length", self.free_length)?;
        check_finite_scalar(name, "preload", self.preload)?;
        check_seats(name, &self.point_i, &self.point_j)
    }

    /// Design length `|point_j − point_i|`.
    pub fn design_length(&self) -> f64 {
        (self.point_j - self.point_i).norm()
    }
}

/// Seats at least [`MIN_SPRING_LENGTH`] apart, else [`ModelError::CoincidentPoints`].
pub(crate) fn check_seats(name: &str, point_i: &Vec3, point_j: &Vec3) -> Result<(), ModelError> {
    let distance = (point_j - point_i).norm();
    if distance < MIN_SPRING_LENGTH {
        return Err(ModelError::CoincidentPoints { item: name.to_string(), distance });
    }
    Ok(())
}

/// How a spring's free length is given ([`CoilSpring::seated`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpringLength {
    /// The free length `L₀` itself (m).
    Free(f64),
    /// The push force at design (N), from which `L₀` follows: the design length plus the compression at
    /// which the characteristic pushes so.
    DesignForce(f64),
}

/// A coil spring between two body points (see the [module docs](self)).
#[derive(Debug, Clone, PartialEq)]
pub struct CoilSpring {
    spec: CoilSpringSpec,
    seats: Seats,
}

impl CoilSpring {
    /// A linear spring from its seats, rate `k` (N/m) and free length `L₀` (m), without preload.
    /// Errors: same bodies ([`ModelError::SelfJoint`]), non-finite data ([`ModelError::NonFinite`]),
    /// `k ≤ 0` or `L₀ ≤ 0` ([`ModelError::NotPositive`]), seats closer than [`MIN_SPRING_LENGTH`]
    /// ([`ModelError::CoincidentPoints`]).
    pub fn new(
        name: &str,
        body_i: BodyRef,
        point_i: Vec3,
        body_j: BodyRef,
        point_j: Vec3,
        rate: f64,
        free_length: f64,
    ) -> Result<Self, ModelError> {
        Self::seated(
            name,
            [(body_i, point_i), (body_j, point_j)],
            Characteristic::Rate(rate),
            SpringLength::Free(free_length),
        )
    }

    /// A spring seated at `ends` (each end's body and seat, global at design), pushing by
    /// `characteristic` (a rate or a data sheet's curve) against compression from its free length, which
    /// `length` gives or has follow from the push at design; without preload. Errors as
    /// [`CoilSpring::new`], and [`ModelError::OutOfRange`] for a curve whose force decreases somewhere or
    /// is flat, or never reaches the design force (past an end with slope zero); a design force that
    /// needs `L₀ ≤ 0` is [`ModelError::NotPositive`] on the free length.
    pub fn seated(
        name: &str,
        ends: [(BodyRef, Vec3); 2],
        characteristic: Characteristic,
        length: SpringLength,
    ) -> Result<Self, ModelError> {
        let [(body_i, point_i), (body_j, point_j)] = ends;
        let free_length = match length {
            SpringLength::Free(free_length) => free_length,
            SpringLength::DesignForce(design_force) => {
                // The compression at design is the least `c` with `characteristic(c) = design_force`.
                characteristic.check(name, "spring rate", Anchor::Free)?;
                check_finite_scalar(name, "design force", design_force)?;
                let Some(compression) = characteristic.inverse(design_force) else {
                    let (low, high) = match &characteristic {
                        Characteristic::Curve(c) => c.reach(),
                        Characteristic::Rate(_) => (f64::NEG_INFINITY, f64::INFINITY),
                    };
                    return Err(ModelError::OutOfRange {
                        item: name.to_string(),
                        why: format!(
                            "its force curve never reaches the design force {design_force} N: past the table's ends \
                             it continues along the end slopes and covers {low} N to {high} N only; extend the \
                             table to the design force"
                        ),
                    });
                };
                (point_j - point_i).norm() + compression
            }
        };
        Self::from_spec(CoilSpringSpec {
            name: name.to_string(),
            body_i,
            point_i,
            body_j,
            point_j,
            characteristic,
            free_length,
            preload: 0.0,
        })
    }

    /// Sets the constant preload `P` (N, compressive positive) added to the characteristic's force.
    pub fn with_preload(mut self, preload: f64) -> Result<Self, ModelError> {
        self.spec.preload = preload;
        self.spec.validate()?;
        Ok(self)
    }

    /// A spring from its full description (validated as in [`CoilSpring::new`] and
    /// [`CoilSpring::seated`]).
    pub fn from_spec(spec: CoilSpringSpec) -> Result<Self, ModelError> {
        spec.validate()?;
        Ok(CoilSpring { seats: Seats::new(&spec.point_i, &spec.point_j), spec })
    }

    /// The design data.
    pub fn spec(&self) -> &CoilSpringSpec {
        &self.spec
    }

    /// Push force `F(L₀ − L) + P` at length `L` (N, compression positive).
    pub fn push_force(&self, length: f64) -> f64 {
        self.push_and_rate(length).0
    }

    /// Push force and axial rate `−∂F_push/∂L = F'(L₀ − L)` at length `L`.
    fn push_and_rate(&self, length: f64) -> (f64, f64) {
        let (force, rate) = self.spec.characteristic.value_and_slope(self.spec.free_length - length);
        (force + self.spec.preload, rate)
    }
}

impl ForceElement for CoilSpring {
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
        Some(self.seats.sketch(SketchKind::Spring))
    }

    fn evaluate(&self, pi: &Pose, pj: &Pose, _t: f64, out: &mut ElementEval, with_stiffness: bool) {
        let line = self.seats.line(pi, pj);
        let (push, rate) = self.push_and_rate(line.length);
        push_along(&line, push, rate, out, with_stiffness);
    }

    fn report(&self, pi: &Pose, pj: &Pose, _t: f64) -> ElementReport {
        let line = self.seats.line(pi, pj);
        ElementReport {
            force: line.n * self.push_force(line.length),
            torque: Vec3::zeros(),
            deflection: Vec3::new(line.length - self.spec.free_length, 0.0, 0.0),
            rotation: Vec3::zeros(),
        }
    }
}
