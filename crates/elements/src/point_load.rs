//! World-fixed point loads ramped by the load parameter `t` (role [`ElementRole::Load`]).
//!
//! A load acts on one moving body, reported as body `j`; body `i` is the ground. The applied value is
//! `F(t) = F₀ + t·F` (a constant part `F₀`, zero unless set, plus the ramped part `F` reached at `t = 1`),
//! fixed in direction in the global frame whatever the body does.
//!
//! * [`PointForce`]: the force `F(t)` at a body-fixed point `P = rⱼ + s`, `s = Aⱼ s'`. It does work through
//!   `(F, s × F)`, so `Qⱼ = (F(t), s × F(t))`. As the body turns, `δ(s × F) = δs × F = F̃ s̃ δπ`, hence the
//!   *load stiffness* `K_πⱼπⱼ = −F̃(t) s̃` (non-symmetric; zero when `s ∥ F`), all other blocks zero.
//!   `∂Q/∂t = (F, s × F)`.
//! * [`PointTorque`]: the moment `M(t)`: `Qⱼ = (0, M(t))`, `K = 0`, `∂Q/∂t = (0, M)`.

use crate::geometry::{add_block, check_finite};
use elastokin_core::math::skew;
use elastokin_core::{
    BodyRef, ElementEval, ElementReport, ElementRole, ForceElement, ModelError, Pose, RowGradient, Sketch, SketchKind,
    Vec3,
};

/// A load on the ground does nothing; it is refused as [`ModelError::SelfJoint`] (its two bodies, ground
/// and ground, are the same).
fn check_body(name: &str, body: BodyRef) -> Result<(), ModelError> {
    if body == BodyRef::Ground {
        Err(ModelError::SelfJoint { joint: name.to_string() })
    } else {
        Ok(())
    }
}

/// Global data of a world-fixed point force.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PointForceSpec {
    /// Unique name.
    pub name: String,
    /// The loaded body (not the ground).
    pub body: BodyRef,
    /// Application point at design (global, m); it moves with the body.
    pub point: Vec3,
    /// Ramped part: force at `t = 1` (global, N).
    pub force: Vec3,
    /// Constant part, present at every `t` (global, N).
    #[cfg_attr(feature = "serde", serde(default))]
    pub constant: Vec3,
}

impl PointForceSpec {
    fn validate(&self) -> Result<(), ModelError> {
        check_body(&self.name, self.body)?;
        check_finite(&self.name, "application point", &self.point)?;
        check_finite(&self.name, "force", &self.force)?;
        check_finite(&self.name, "constant force", &self.constant)
    }
}

/// A world-fixed force at a body point, `F(t) = F₀ + t F` (see the [module docs](self)).
#[derive(Debug, Clone, PartialEq)]
pub struct PointForce {
    spec: PointForceSpec,
    on_body: Vec3,
}

impl PointForce {
    /// A force `t · force` (global, N at `t = 1`) at the global design point `point` of `body`.
    /// Errors: ground body ([`ModelError::SelfJoint`]), non-finite data ([`ModelError::NonFinite`]).
    pub fn new(name: &str, body: BodyRef, point: Vec3, force: Vec3) -> Result<Self, ModelError> {
        Self::from_spec(PointForceSpec { name: name.to_string(), body, point, force, constant: Vec3::zeros() })
    }

    /// Adds a constant part `F₀` (global, N), present at every `t`: `F(t) = F₀ + t F`.
    pub fn with_constant(mut self, constant: Vec3) -> Result<Self, ModelError> {
        self.spec.constant = constant;
        self.spec.validate()?;
        Ok(self)
    }

    /// A force from its full description.
    pub fn from_spec(spec: PointForceSpec) -> Result<Self, ModelError> {
        spec.validate()?;
        Ok(PointForce { on_body: spec.point, spec })
    }

    /// The data.
    pub fn spec(&self) -> &PointForceSpec {
        &self.spec
    }

    /// `F(t) = F₀ + t F`.
    pub fn force_at(&self, t: f64) -> Vec3 {
        self.spec.constant + self.spec.force * t
    }
}

impl ForceElement for PointForce {
    fn name(&self) -> &str {
        &self.spec.name
    }

    fn bodies(&self) -> [BodyRef; 2] {
        [BodyRef::Ground, self.spec.body]
    }

    fn role(&self) -> ElementRole {
        ElementRole::Load
    }

    fn bind(&mut self, _pi: &Pose, pj: &Pose) -> Result<(), ModelError> {
        self.spec.validate()?;
        if !pj.is_finite() {
            return Err(ModelError::NonFinite { item: self.spec.name.clone(), what: "design pose" });
        }
        self.on_body = pj.to_local_point(&self.spec.point);
        Ok(())
    }

    fn evaluate(&self, _pi: &Pose, pj: &Pose, t: f64, out: &mut ElementEval, with_stiffness: bool) {
        let f = self.force_at(t);
        let s = pj.direction(&self.on_body);
        out.force.fill(0.0);
        out.force.fixed_rows_mut::<3>(6).copy_from(&f);
        out.force.fixed_rows_mut::<3>(9).copy_from(&s.cross(&f));
        if with_stiffness {
            out.stiffness.fill(0.0);
            add_block(&mut out.stiffness, 3, 3, &(-(skew(&f) * skew(&s))));
        }
    }

    fn load_rate(&self, _pi: &Pose, pj: &Pose, _t: f64, out: &mut RowGradient) {
        let s = pj.direction(&self.on_body);
        out.fill(0.0);
        out.fixed_rows_mut::<3>(6).copy_from(&self.spec.force);
        out.fixed_rows_mut::<3>(9).copy_from(&s.cross(&self.spec.force));
    }

    fn report(&self, _pi: &Pose, _pj: &Pose, t: f64) -> ElementReport {
        ElementReport { force: self.force_at(t), ..ElementReport::default() }
    }

    fn sketch(&self) -> Option<Sketch> {
        Some(Sketch { kind: SketchKind::Load, on_i: self.spec.point, on_j: self.on_body, axes_i: None })
    }
}

/// Global data of a world-fixed moment.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PointTorqueSpec {
    /// Unique name.
    pub name: String,
    /// The loaded body (not the ground).
    pub body: BodyRef,
    /// Ramped part: moment at `t = 1` (global, N·m).
    pub torque: Vec3,
    /// Constant part (global, N·m).
    #[cfg_attr(feature = "serde", serde(default))]
    pub constant: Vec3,
}

impl PointTorqueSpec {
    fn validate(&self) -> Result<(), ModelError> {
        check_body(&self.name, self.body)?;
        check_finite(&self.name, "torque", &self.torque)?;
        check_finite(&self.name, "constant torque", &self.constant)
    }
}

/// A world-fixed moment on a body, `M(t) = M₀ + t M` (see the [module docs](self)).
#[derive(Debug, Clone, PartialEq)]
pub struct PointTorque {
    spec: PointTorqueSpec,
}

impl PointTorque {
    /// A moment `t · torque` (global, N·m at `t = 1`) on `body`.
    pub fn new(name: &str, body: BodyRef, torque: Vec3) -> Result<Self, ModelError> {
        Self::from_spec(PointTorqueSpec { name: name.to_string(), body, torque, constant: Vec3::zeros() })
    }

    /// Adds a constant part `M₀` (global, N·m): `M(t) = M₀ + t M`.
    pub fn with_constant(mut self, constant: Vec3) -> Result<Self, ModelError> {
        self.spec.constant = constant;
        self.spec.validate()?;
        Ok(self)
    }

    /// A moment from its full description.
    pub fn from_spec(spec: PointTorqueSpec) -> Result<Self, ModelError> {
        spec.validate()?;
        Ok(PointTorque { spec })
    }

    /// The data.
    pub fn spec(&self) -> &PointTorqueSpec {
        &self.spec
    }

    /// `M(t) = M₀ + t M`.
    pub fn torque_at(&self, t: f64) -> Vec3 {
        self.spec.constant + self.spec.torque * t
    }
}

impl ForceElement for PointTorque {
    fn name(&self) -> &str {
        &self.spec.name
    }

    fn bodies(&self) -> [BodyRef; 2] {
        [BodyRef::Ground, self.spec.body]
    }

    fn role(&self) -> ElementRole {
        ElementRole::Load
    }

    fn bind(&mut self, _pi: &Pose, _pj: &Pose) -> Result<(), ModelError> {
        self.spec.validate()
    }

    fn evaluate(&self, _pi: &Pose, _pj: &Pose, t: f64, out: &mut ElementEval, with_stiffness: bool) {
        out.force.fill(0.0);
        out.force.fixed_rows_mut::<3>(9).copy_from(&self.torque_at(t));
        if with_stiffness {
            out.stiffness.fill(0.0);
        }
    }

    fn load_rate(&self, _pi: &Pose, _pj: &Pose, _t: f64, out: &mut RowGradient) {
        out.fill(0.0);
        out.fixed_rows_mut::<3>(9).copy_from(&self.spec.torque);
    }

    fn report(&self, _pi: &Pose, _pj: &Pose, t: f64) -> ElementReport {
        ElementReport { torque: self.torque_at(t), ..ElementReport::default() }
    }
}
