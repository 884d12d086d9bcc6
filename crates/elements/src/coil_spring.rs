//! Linear coil spring between two body points.
//!
//! # Model
//!
//! Points `Pᵢ = rᵢ + sᵢ` on `i` and `Pⱼ = rⱼ + sⱼ` on `j` (`s = A s'`), separation `d = Pⱼ − Pᵢ`, length
//! `L = |d|`, unit vector `n = d / L` (from `i` to `j`). The spring **pushes the points apart** with
//!
//! ```text
//! F_push = k (L₀ − L) + P
//! ```
//!
//! (rate `k` > 0, free length `L₀` > 0, constant preload `P`, compressive positive): the force applied to
//! `j` is `F_push n` at `Pⱼ`, the force applied to `i` is `−F_push n` at `Pᵢ`. `F_push > 0` is
//! compression. Its energy is `U = ½ k (L − L₀)² − P L`.
//!
//! # Stiffness
//!
//! With `φ = F_push n` (force on `j`), `∂φ/∂d = T = −k nnᵀ + (F_push/L)(I − nnᵀ)` and
//! `δd = B Δq`, `B = [−I, s̃ᵢ, I, −s̃ⱼ]`:
//!
//! ```text
//! K = −∂Q/∂Δq = −Bᵀ T B + diag(0, φ̃ s̃ᵢ, 0, −φ̃ s̃ⱼ)
//! ```
//!
//! `−T = k nnᵀ + (tension/L)(I − nnᵀ)` is the familiar string tangent (tension = −F_push, so a
//! compressed spring has a *negative* transverse stiffness). The second term, from the lever arms
//! turning with the bodies, makes `K` non-symmetric unless `sᵢ` and `sⱼ` are parallel to the spring:
//! `K − Kᵀ = diag(0, [Q_πᵢ]~, 0, [Q_πⱼ]~)`, the skew part every left-increment tangent carries.
//!
//! # Degenerate length
//!
//! If at run time `L` falls below `1e-9 · L_design` the direction is undefined. The element then uses the
//! design direction carried by body `i` as `n`, keeps `F_push = k (L₀ − L) + P` and drops the transverse
//! term `(F_push/L)(I − nnᵀ)` from the tangent, so that it returns finite values; such a configuration
//! (the two spring seats through each other) is not physical.

use crate::geometry::{
    add_block, add_rows, check_distinct, check_finite, check_finite_scalar, check_positive, set_jac_block, Jac3,
};
use elastokin_core::math::skew;
use elastokin_core::{
    BodyRef, ElementEval, ElementReport, ElementRole, ForceElement, Mat3, ModelError, PairMatrix, Pose, Vec3,
};

/// Smallest design length of a spring (m); shorter is [`ModelError::CoincidentPoints`].
pub const MIN_SPRING_LENGTH: f64 = 1e-9;
/// Below this fraction of the design length the direction falls back to the design direction.
const DEGENERATE_FRACTION: f64 = 1e-9;

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
    /// Rate `k`, N/m.
    pub rate: f64,
    /// Free length `L₀`, m.
    pub free_length: f64,
    /// Constant preload `P` added to `k (L₀ − L)`, N (compressive positive).
    #[cfg_attr(feature = "serde", serde(default))]
    pub preload: f64,
}

impl CoilSpringSpec {
    fn validate(&self) -> Result<(), ModelError> {
        let name = self.name.as_str();
        check_distinct(name, self.body_i, self.body_j)?;
        check_finite(name, "point on i", &self.point_i)?;
        check_finite(name, "point on j", &self.point_j)?;
        check_positive(name, "spring rate", self.rate)?;
        check_positive(name, "free length", self.free_length)?;
        check_finite_scalar(name, "preload", self.preload)?;
        let distance = (self.point_j - self.point_i).norm();
        if distance < MIN_SPRING_LENGTH {
            return Err(ModelError::CoincidentPoints { item: name.to_string(), distance });
        }
        Ok(())
    }

    /// Design length `|point_j − point_i|`.
    pub fn design_length(&self) -> f64 {
        (self.point_j - self.point_i).norm()
    }
}

/// A coil spring between two body points (see the [module docs](self)).
#[derive(Debug, Clone, PartialEq)]
pub struct CoilSpring {
    spec: CoilSpringSpec,
    on_i: Vec3,
    on_j: Vec3,
    /// Design direction `n` in body-`i` components (fallback when `L → 0`).
    axis_i: Vec3,
    /// Length below which the fallback is used.
    min_length: f64,
}

struct State {
    s_i: Vec3,
    s_j: Vec3,
    n: Vec3,
    length: f64,
    push: f64,
    degenerate: bool,
}

impl CoilSpring {
    /// A spring from its seats, rate `k` (N/m) and free length `L₀` (m), without preload.
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
        Self::from_spec(CoilSpringSpec {
            name: name.to_string(),
            body_i,
            point_i,
            body_j,
            point_j,
            rate,
            free_length,
            preload: 0.0,
        })
    }

    /// A spring given the push force at design instead of the free length:
    /// `L₀ = L_design + design_force / k` (no separate preload). A tensile design force larger than
    /// `k · L_design` gives `L₀ ≤ 0`, refused as [`ModelError::NotPositive`] on the free length.
    pub fn with_design_force(
        name: &str,
        body_i: BodyRef,
        point_i: Vec3,
        body_j: BodyRef,
        point_j: Vec3,
        rate: f64,
        design_force: f64,
    ) -> Result<Self, ModelError> {
        check_positive(name, "spring rate", rate)?;
        check_finite_scalar(name, "design force", design_force)?;
        let free_length = (point_j - point_i).norm() + design_force / rate;
        Self::new(name, body_i, point_i, body_j, point_j, rate, free_length)
    }

    /// Sets the constant preload `P` (N, compressive positive) added to `k (L₀ − L)`.
    pub fn with_preload(mut self, preload: f64) -> Result<Self, ModelError> {
        self.spec.preload = preload;
        self.spec.validate()?;
        Ok(self)
    }

    /// A spring from its full description (validated as in [`CoilSpring::new`]).
    pub fn from_spec(spec: CoilSpringSpec) -> Result<Self, ModelError> {
        spec.validate()?;
        let len = spec.design_length();
        Ok(CoilSpring {
            on_i: spec.point_i,
            on_j: spec.point_j,
            axis_i: (spec.point_j - spec.point_i) / len,
            min_length: DEGENERATE_FRACTION * len,
            spec,
        })
    }

    /// The design data.
    pub fn spec(&self) -> &CoilSpringSpec {
        &self.spec
    }

    /// Push force `k (L₀ − L) + P` at length `L` (N, compression positive).
    pub fn push_force(&self, length: f64) -> f64 {
        self.spec.rate * (self.spec.free_length - length) + self.spec.preload
    }

    fn state(&self, pi: &Pose, pj: &Pose) -> State {
        let s_i = pi.direction(&self.on_i);
        let s_j = pj.direction(&self.on_j);
        let d = (pj.position + s_j) - (pi.position + s_i);
        let length = d.norm();
        let degenerate = length < self.min_length;
        let n = if degenerate { pi.direction(&self.axis_i) } else { d / length };
        State { s_i, s_j, n, length, push: self.push_force(length), degenerate }
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
        if !pi.is_finite() || !pj.is_finite() {
            return Err(ModelError::NonFinite { item: self.spec.name.clone(), what: "design pose" });
        }
        self.on_i = pi.to_local_point(&self.spec.point_i);
        self.on_j = pj.to_local_point(&self.spec.point_j);
        let d = self.spec.point_j - self.spec.point_i;
        self.axis_i = pi.to_local_direction(&(d / d.norm()));
        Ok(())
    }

    fn evaluate(&self, pi: &Pose, pj: &Pose, _t: f64, out: &mut ElementEval, with_stiffness: bool) {
        let st = self.state(pi, pj);
        let phi = st.n * st.push;
        let q = &mut out.force;
        q.fixed_rows_mut::<3>(0).copy_from(&(-phi));
        q.fixed_rows_mut::<3>(3).copy_from(&(-st.s_i.cross(&phi)));
        q.fixed_rows_mut::<3>(6).copy_from(&phi);
        q.fixed_rows_mut::<3>(9).copy_from(&st.s_j.cross(&phi));
        if with_stiffness {
            self.stiffness(&st, &phi, &mut out.stiffness);
        }
    }

    fn report(&self, pi: &Pose, pj: &Pose, _t: f64) -> ElementReport {
        let st = self.state(pi, pj);
        ElementReport {
            force: st.n * st.push,
            torque: Vec3::zeros(),
            deflection: Vec3::new(st.length - self.spec.free_length, 0.0, 0.0),
            rotation: Vec3::zeros(),
        }
    }
}

impl CoilSpring {
    /// `K = −∂Q/∂Δq` (module docs): rows `(Dφ, s̃ᵢ Dφ + φ̃ s̃ᵢ, −Dφ, −s̃ⱼ Dφ − φ̃ s̃ⱼ)` with `Dφ = T B`.
    fn stiffness(&self, st: &State, phi: &Vec3, out: &mut PairMatrix) {
        let nn = st.n * st.n.transpose();
        let mut t = -self.spec.rate * nn;
        if !st.degenerate {
            t += (st.push / st.length) * (Mat3::identity() - nn);
        }
        let si_t = skew(&st.s_i);
        let sj_t = skew(&st.s_j);
        let phi_t = skew(phi);
        let mut dphi = Jac3::zeros();
        set_jac_block(&mut dphi, 0, &(-t));
        set_jac_block(&mut dphi, 1, &(t * si_t));
        set_jac_block(&mut dphi, 2, &t);
        set_jac_block(&mut dphi, 3, &(-t * sj_t));
        out.fill(0.0);
        add_rows(out, 0, &dphi);
        add_rows(out, 1, &(si_t * dphi));
        add_block(out, 1, 1, &(phi_t * si_t));
        add_rows(out, 2, &(-dphi));
        add_rows(out, 3, &(-(sj_t * dphi)));
        add_block(out, 3, 3, &(-(phi_t * sj_t)));
    }
}
