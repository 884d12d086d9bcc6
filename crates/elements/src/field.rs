//! Field element: a general 6×6 stiffness between a frame on each of two bodies, the coupled terms of a
//! bushing's data sheet allowed (a radial force from a twist, a moment from a deflection).
//!
//! # Model
//!
//! As a [`Bushing`](crate::Bushing): a hardpoint `P` and a frame `E` at design, carried by body `i`
//! (`E = Aᵢ E'ᵢ`), a copy on `j` coinciding at design; the deflection `δ = Eᵀ (Pⱼ − Pᵢ)` and the
//! relative rotation's vector `θ = log(Eᵀ Eⱼ)`, local components. With `q = (δ, θ)` the energy is
//!
//! ```text
//! U = ½ qᵀ K q − F_preᵀ δ − M_preᵀ θ,   K = [K_tt K_tr; K_rt K_rr] symmetric, positive semi-definite,
//! ```
//!
//! the rotation-vector energy of the bushing's default law ([`RotationLaw::Energy`](crate::RotationLaw))
//! with the blocks coupled. A diagonal `K` is the bushing with those rates, to rounding. The force applied
//! to `i` is `f = E (K_tt δ + K_tr θ − F_pre)`, the moment `G = E g`, `g = J_l(θ)⁻ᵀ (K_rt δ + K_rr θ −
//! M_pre)`; to `j` their opposites (signs, preload and lines of action as the bushing's).
//!
//! # Stiffness
//!
//! The bushing's, with the coupled blocks' two terms more: the force follows the relative rotation,
//! `δf = … + E K_tr J_l⁻¹ Eᵀ (δπⱼ − δπᵢ)`, and the moment the deflection, `δG = … + E J_l⁻ᵀ K_rt Eᵀ (δd +
//! d̃ δπᵢ)`. Checked against finite differences in `crates/elements/tests/field.rs`.

use crate::geometry::{
    check_distinct, check_finite, frame_rotation, framed_force, framed_stiffness, set_jac_block, Framed, FramedPoint,
    Jac3,
};
use elastokin_core::math::{left_jacobian_inv, rotation_vector_moment, skew};
use elastokin_core::{
    BodyRef, ElementEval, ElementReport, ElementRole, ForceElement, Mat3, ModelError, PairMatrix, Pose, Sketch, Vec3,
};
use nalgebra::{Matrix6, UnitQuaternion, Vector6};

/// How far from symmetric a field's matrix may be, relative to its largest entry: rounding of a data
/// sheet's numbers, not a matrix meant otherwise.
pub const SYMMETRY_TOLERANCE: f64 = 1e-9;

/// Global design data of a field element.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldSpec {
    /// Unique name, used in diagnostics and results.
    pub name: String,
    /// Body `i`, which carries the frame.
    pub body_i: BodyRef,
    /// Body `j`; [`ElementReport`] gives the force and moment applied to it.
    pub body_j: BodyRef,
    /// Hardpoint at design (global, m), coincident on both bodies.
    pub point: Vec3,
    /// Frame at design: columns are the local x, y, z axes in global components (a rotation).
    pub frame: Mat3,
    /// `K` over `(δx, δy, δz, θx, θy, θz)` in the local frame: N/m, N/rad (= N·m/m), N·m/rad.
    pub stiffness: Matrix6<f64>,
    /// Force (N) the element applies to `j` at zero deflection, local components.
    pub preload_force: Vec3,
    /// Moment (N·m) it applies to `j` at zero rotation, local components.
    pub preload_torque: Vec3,
}

impl FieldSpec {
    /// Checks the data; returns the frame as a rotation. A matrix not symmetric (beyond
    /// [`SYMMETRY_TOLERANCE`]) or with a negative eigenvalue is [`ModelError::OutOfRange`], naming the entry
    /// or the eigenvalue.
    fn validate(&self) -> Result<UnitQuaternion<f64>, ModelError> {
        check_distinct(&self.name, self.body_i, self.body_j)?;
        check_finite(&self.name, "hardpoint", &self.point)?;
        check_finite(&self.name, "preload force", &self.preload_force)?;
        check_finite(&self.name, "preload torque", &self.preload_torque)?;
        let k = &self.stiffness;
        if k.iter().any(|v| !v.is_finite()) {
            return Err(ModelError::NonFinite { item: self.name.clone(), what: "stiffness matrix" });
        }
        let largest = k.amax();
        for r in 0..6 {
            for c in r + 1..6 {
                if (k[(r, c)] - k[(c, r)]).abs() > SYMMETRY_TOLERANCE * largest {
                    return Err(ModelError::OutOfRange {
                        item: self.name.clone(),
                        why: format!(
                            "the stiffness matrix is not symmetric: entry ({r}, {c}) is {:e} and ({c}, {r}) is {:e}; \
                             an elastic element's stiffness is symmetric, give the mean of the two",
                            k[(r, c)],
                            k[(c, r)]
                        ),
                    });
                }
            }
        }
        let least = k.symmetric_eigenvalues().min();
        if least < -SYMMETRY_TOLERANCE * largest {
            return Err(ModelError::OutOfRange {
                item: self.name.clone(),
                why: format!(
                    "the stiffness matrix has the negative eigenvalue {least:e}: some deflection would give energy \
                     back; check the coupled terms, which must be smaller than the rates they couple"
                ),
            });
        }
        frame_rotation(&self.name, &self.frame)
    }
}

/// A field element between two bodies (see the [module docs](self)).
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    spec: FieldSpec,
    /// The point and the frame on each body.
    framed: FramedPoint,
}

/// Everything the force, stiffness and report share at one configuration.
struct State {
    /// The frame, the deflection and rotation, the levers.
    at: Framed,
    /// `J_l(θ)⁻¹`.
    jl_inv: Mat3,
    /// The force on `i`, `f = E (K_tt δ + K_tr θ − F_pre)`.
    f: Vec3,
    /// `g = J_l⁻ᵀ (K_rt δ + K_rr θ − M_pre)` (local) and `∂g/∂θ`.
    g: Vec3,
    dg: Mat3,
}

impl Field {
    /// A field element from its design data (see [`FieldSpec`]).
    pub fn from_spec(spec: FieldSpec) -> Result<Self, ModelError> {
        let frame = spec.validate()?;
        Ok(Field { framed: FramedPoint::unbound(spec.point, frame), spec })
    }

    /// The design data.
    pub fn spec(&self) -> &FieldSpec {
        &self.spec
    }

    fn block(&self, r: usize, c: usize) -> Mat3 {
        self.spec.stiffness.fixed_view::<3, 3>(3 * r, 3 * c).into_owned()
    }

    fn state(&self, pi: &Pose, pj: &Pose) -> State {
        let at = self.framed.at(pi, pj);
        let (delta, theta) = (at.delta, at.theta);
        let (ktt, ktr, krt, krr) = (self.block(0, 0), self.block(0, 1), self.block(1, 0), self.block(1, 1));
        let f = at.e * (ktt * delta + ktr * theta - self.spec.preload_force);
        let m = krt * delta + krr * theta - self.spec.preload_torque;
        let (g, dg) = rotation_vector_moment(&theta, &m, &krr);
        State { jl_inv: left_jacobian_inv(&theta), at, f, g, dg }
    }

    /// The generalized deflection `q = (δ, θ)` at the poses (local components).
    pub fn deflection(&self, pi: &Pose, pj: &Pose) -> Vector6<f64> {
        let at = self.framed.at(pi, pj);
        let mut q = Vector6::zeros();
        q.fixed_rows_mut::<3>(0).copy_from(&at.delta);
        q.fixed_rows_mut::<3>(3).copy_from(&at.theta);
        q
    }

    /// The energy at the poses (J).
    pub fn energy(&self, pi: &Pose, pj: &Pose) -> f64 {
        let q = self.deflection(pi, pj);
        let pre =
            q.fixed_rows::<3>(0).dot(&self.spec.preload_force) + q.fixed_rows::<3>(3).dot(&self.spec.preload_torque);
        0.5 * q.dot(&(self.spec.stiffness * q)) - pre
    }

    fn stiffness(&self, st: &State, big_g: &Vec3, out: &mut PairMatrix) {
        let e = &st.at.e;
        let kg = e * self.block(0, 0) * e.transpose();
        let ctr = e * self.block(0, 1) * st.jl_inv * e.transpose();
        let crt = e * st.jl_inv.transpose() * self.block(1, 0) * e.transpose();
        let f_t = skew(&st.f);
        let w_t = skew(&st.at.w);
        let sj_t = skew(&st.at.s_j);
        let h = e * st.dg * st.jl_inv * e.transpose();

        let mut df = Jac3::zeros();
        set_jac_block(&mut df, 0, &(-kg));
        set_jac_block(&mut df, 1, &(kg * w_t - f_t - ctr));
        set_jac_block(&mut df, 2, &kg);
        set_jac_block(&mut df, 3, &(-kg * sj_t + ctr));
        let mut dgg = Jac3::zeros();
        set_jac_block(&mut dgg, 0, &(-crt));
        set_jac_block(&mut dgg, 1, &(-skew(big_g) - h + crt * w_t));
        set_jac_block(&mut dgg, 2, &crt);
        set_jac_block(&mut dgg, 3, &(h - crt * sj_t));
        framed_stiffness(&st.at, &st.f, &df, &dgg, out);
    }
}

impl ForceElement for Field {
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
        let frame = self.spec.validate()?;
        self.framed.bind(&self.spec.name, pi, pj, &self.spec.point, frame)
    }

    fn evaluate(&self, pi: &Pose, pj: &Pose, _t: f64, out: &mut ElementEval, with_stiffness: bool) {
        let st = self.state(pi, pj);
        let big_g = st.at.e * st.g;
        framed_force(&st.at, &st.f, &big_g, &mut out.force);
        if with_stiffness {
            self.stiffness(&st, &big_g, &mut out.stiffness);
        }
    }

    fn energy(&self, pi: &Pose, pj: &Pose) -> Option<f64> {
        Some(Field::energy(self, pi, pj))
    }

    fn report(&self, pi: &Pose, pj: &Pose, _t: f64) -> ElementReport {
        let st = self.state(pi, pj);
        ElementReport { force: -st.f, torque: -(st.at.e * st.g), deflection: st.at.delta, rotation: st.at.theta }
    }

    fn sketch(&self) -> Option<Sketch> {
        Some(self.framed.sketch())
    }
}
