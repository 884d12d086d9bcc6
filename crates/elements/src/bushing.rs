//! Rubber bushing: six uncoupled springs in a local frame, linear or with measured curves, with the exact
//! finite-rotation energy (paper eqs. 5–8).
//!
//! # Model
//!
//! The bushing has a hardpoint `P` and a frame `E` (columns: its local x, y, z axes, global components) at
//! design. The frame is carried by body `i`: `E = Aᵢ E'ᵢ`. Body `j` carries a copy `Eⱼ = Aⱼ E'ⱼ` that
//! coincides with `E` at design. The hardpoint is fixed on each body, `Pᵢ = rᵢ + sᵢ`, `Pⱼ = rⱼ + sⱼ`
//! (`s = A s'`), coincident at design. With
//!
//! * the deflection `δ = Eᵀ (Pⱼ − Pᵢ)` (local components, m),
//! * the relative rotation `R = Eᵀ Eⱼ` and its rotation vector `θ = log R` (local, rad, |θ| ≤ π),
//!
//! the energy is
//!
//! ```text
//! U = ½ δᵀ K_T δ + ½ θᵀ K_R θ − F_preᵀ δ − M_preᵀ θ,   K_T = diag(Kx, Ky, Kz), K_R = diag(Ku, Kv, Kw).
//! ```
//!
//! # Measured curves
//!
//! Each of the six directions has a [`Characteristic`]: its rate, as above, or a curve from a rig test —
//! the force along that local axis against the deflection along it (N against m), or the moment about it
//! against that component of the rotation (N·m against rad). The curve is the monotone cubic through the
//! table, **linear past its ends** with the end slopes ([`Curve`](crate::Curve)); it passes through
//! `(0, 0)` (a force at zero deflection is the preload, given separately) and never decreases. The terms
//! `K_T δ` and `K_R θ` become the vectors of curve values `(Fx(δx), Fy(δy), Fz(δz))` and
//! `(Mu(θu), Mv(θv), Mw(θw))`, and `K_T`, `K_R` in the tangent the diagonals of their slopes; the energy
//! is the sum of the six curves' integrals. A curve's direction is uncoupled from the others, as a rate's
//! is.
//!
//! # Signs
//!
//! * Forces are those the bushing **applies**: on `j` the force `−f` at `Pⱼ` and the moment `−E g`, on `i`
//!   the force `+f` and the moment `+E g`, where `f = E (K_T δ − F_pre)` and `g = J_l(θ)⁻ᵀ (K_R θ − M_pre)`
//!   is the moment conjugate to a left rotation increment of `j` relative to `i` (local components); with
//!   curves, `K_T δ` and `K_R θ` are the curves' values.
//! * Preload: `F_pre` (N) and `M_pre` (N·m), local components, are the force and moment the bushing
//!   applies **to body `j`** at zero deflection (so `F_pre = (0, 0, 500)` pushes `j` up along the local z
//!   axis by 500 N in the design configuration). Equivalently, the bushing applies `−F_pre`, `−M_pre` to
//!   `i` at design.
//! * Because the frame rides on `i`, the force on `i` has its line of action through `Pⱼ`: the moment on
//!   `i` about `rᵢ` is `(Pⱼ − rᵢ) × f + E g`. The element is then exactly in self-equilibrium at every
//!   configuration (the energy is invariant under rigid motions of the pair).
//!
//! # Stiffness
//!
//! `K = −∂Q/∂Δq` is the derivative of the energy gradient along the exact left increments
//! `A ← exp(Δπ̃) A` (what a finite difference along [`Pose::apply_increment6`] measures), not the
//! symmetric second derivative: away from equilibrium of the element its `πᵢπᵢ` and `πⱼπⱼ` blocks carry the
//! skew parts `[Q_πᵢ]~` and `[Q_πⱼ]~` (`K − Kᵀ = diag(0, [Q_πᵢ]~, 0, [Q_πⱼ]~)`); all other blocks are
//! symmetric. At design without preload it is the paper's `Bᵀ K_T B + Cᵀ K_R C`.
//!
//! # Rotation laws
//!
//! How the moment follows the relative rotation is chosen per bushing ([`RotationLaw`]); the energy above
//! is the default. The three agree to first order in the rotation and differ at second order when the
//! rotational rates differ (see [`RotationLaw`] for the measured differences).
//!
//! # Range
//!
//! The rotation vector is taken from the relative quaternion (robust up to and including |θ| = π); the
//! energy is continuous but its gradient jumps where the relative rotation passes π, far outside any
//! rubber bushing's range.

use crate::curve::{Anchor, Characteristic};
use crate::geometry::{
    check_distinct, check_finite, frame_rotation, framed_force, framed_stiffness, set_jac_block, Framed, FramedPoint,
    Jac3,
};
use elastokin_core::math::{left_jacobian_inv, rotation_vector_moment, skew, tait_bryan_xyz, tait_bryan_xyz_axes};
use elastokin_core::{
    BodyRef, ElementEval, ElementReport, ElementRole, ForceElement, Mat3, ModelError, PairMatrix, Pose, Sketch, Vec3,
};
use nalgebra::UnitQuaternion;

/// How a bushing's moment follows the relative rotation `R = Eᵀ Eⱼ` of its two frames (rotation vector
/// `θ`, local components). All three give `M = K θ` for a rotation about one of the bushing's axes; they
/// differ at second order when the rotational rates differ. At the twist `θ = (0.10, 0, 0.01)` rad of a
/// bushing with torsion rate 500 and conical rates 4000 N·m/rad, the moment on `j` (local, N·m) is
/// `(−50.003, 1.750, −39.971)` under [`Energy`](RotationLaw::Energy), `(−50, 0, −40)` under
/// [`Linear`](RotationLaw::Linear) and `(−49.999, 1.996, −39.909)` under
/// [`TaitBryanXyz`](RotationLaw::TaitBryanXyz): the law moves the conical moment by up to 5 % of its size
/// (`tests/bushing_laws.rs`). To match another tool's results, use its law.
///
/// With measured curves for the rotations, each law takes the vector of the curves' moments where it
/// takes `K θ` (or `K φ`), and the diagonal of their slopes where it takes `K`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize), serde(rename_all = "snake_case"))]
pub enum RotationLaw {
    /// The energy `½ θᵀ K_R θ` of the rotation vector (paper eqs. 5–8): conservative, and frame
    /// independent; the moment is `J_l(θ)⁻ᵀ K_R θ`, its component across `θ` growing with the twist.
    #[default]
    Energy,
    /// `M = K_R θ` as stated, the rotation vector times the rates, applied about the bushing's axes.
    /// Not derived from an energy: its tangent is not symmetric away from `θ = 0`. Project Chrono's
    /// generic body–body bushing (`ChLoadBodyBodyBushingGeneric`) computes its torque this way.
    Linear,
    /// The energy `½ φᵀ K_R φ` of the body-fixed x-y-z (Tait-Bryan) angles `φ` of `R = Rx Ry Rz`:
    /// conservative; the moment's component about each gimbal axis is its rate times its angle. Simbody's
    /// `Force::LinearBushing` uses these angles. Singular at a 90° tilt about the local y axis, far outside
    /// rubber's range.
    TaitBryanXyz,
}

impl RotationLaw {
    /// The moment `g` (local components) conjugate to a left rotation increment of `j` relative to `i`,
    /// and `∂g/∂θ`, for the relative rotation `relative` with rotation vector `theta`, the characteristics
    /// `kr` about the three axes and the preload moment `m_pre` (applied to `j` at zero rotation).
    fn moment(
        self,
        theta: &Vec3,
        relative: &UnitQuaternion<f64>,
        kr: &[Characteristic; 3],
        m_pre: &Vec3,
    ) -> (Vec3, Mat3) {
        // The law's angles' moments `m = K(angles) − M_pre` (rates times angles, or the curves' values) and
        // `∂m/∂angles`, diagonal: the one place a rate and a curve differ.
        let of = |angles: &Vec3| {
            let (values, slopes) = along_axes(kr, angles);
            (values - m_pre, Mat3::from_diagonal(&slopes))
        };
        match self {
            RotationLaw::Energy => {
                let (m, k) = of(theta);
                rotation_vector_moment(theta, &m, &k)
            }
            RotationLaw::Linear => of(theta),
            RotationLaw::TaitBryanXyz => {
                // U = ½φᵀKφ − M_preᵀφ (with curves, the sum of their integrals); ω = E(φ) φ̇ for the left
                // increment, so g = ∂U/∂ω = E⁻ᵀ (Kφ − M_pre).
                let phi = tait_bryan_xyz(&relative.to_rotation_matrix().into_inner());
                let (e, de_da, de_db) = tait_bryan_xyz_axes(&phi);
                let nan = Mat3::from_element(f64::NAN);
                // At gimbal lock the moment is undefined: a NaN here is refused by the solver as such.
                let e_inv_t = e.transpose().try_inverse().unwrap_or(nan);
                let (m, k) = of(&phi);
                let g = e_inv_t * m;
                // ∂g/∂φₖ = E⁻ᵀ K eₖ − E⁻ᵀ (∂E/∂φₖ)ᵀ g; then ∂φ/∂θ = E⁻¹ J_l(θ).
                let mut dg_dphi = e_inv_t * k;
                for (col, de) in [(0, de_da), (1, de_db)] {
                    let extra = -(e_inv_t * de.transpose() * g);
                    for row in 0..3 {
                        dg_dphi[(row, col)] += extra[row];
                    }
                }
                let j_l = left_jacobian_inv(theta).try_inverse().unwrap_or(nan);
                (g, dg_dphi * e_inv_t.transpose() * j_l)
            }
        }
    }
}

/// The three characteristics' values and slopes at `x` (component by component).
fn along_axes(k: &[Characteristic; 3], x: &Vec3) -> (Vec3, Vec3) {
    let mut values = Vec3::zeros();
    let mut slopes = Vec3::zeros();
    for a in 0..3 {
        (values[a], slopes[a]) = k[a].value_and_slope(x[a]);
    }
    (values, slopes)
}

/// Global design data of a bushing: what a user writes. SI units throughout.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BushingSpec {
    /// Unique name, used in diagnostics and results.
    pub name: String,
    /// Body `i`, which carries the bushing frame (either body may be the ground).
    pub body_i: BodyRef,
    /// Body `j`; [`ElementReport`] gives the force and moment applied to it.
    pub body_j: BodyRef,
    /// Hardpoint at design (global, m), coincident on both bodies.
    pub point: Vec3,
    /// Bushing frame at design: columns are the local x, y, z axes in global components (a rotation).
    pub frame: Mat3,
    /// Along the local x, y, z axes: the rates `(Kx, Ky, Kz)` (N/m) or curves of force (N) against
    /// deflection (m).
    pub translational: [Characteristic; 3],
    /// About the local x, y, z axes: the rates `(Ku, Kv, Kw)` (N·m/rad) or curves of moment (N·m) against
    /// rotation (rad).
    pub rotational: [Characteristic; 3],
    /// Force applied to `j` at zero deflection (local components, N).
    #[cfg_attr(feature = "serde", serde(default))]
    pub preload_force: Vec3,
    /// Moment applied to `j` at zero rotation (local components, N·m).
    #[cfg_attr(feature = "serde", serde(default))]
    pub preload_torque: Vec3,
    /// How the moment follows the relative rotation (default: the rotation-vector energy).
    #[cfg_attr(feature = "serde", serde(default))]
    pub rotation_law: RotationLaw,
}

impl BushingSpec {
    /// Checks the data that do not depend on the design poses; returns the frame as a unit quaternion.
    fn validate(&self) -> Result<UnitQuaternion<f64>, ModelError> {
        let name = self.name.as_str();
        check_distinct(name, self.body_i, self.body_j)?;
        check_finite(name, "hardpoint", &self.point)?;
        let what_t = ["translational stiffness Kx", "translational stiffness Ky", "translational stiffness Kz"];
        let what_r = ["rotational stiffness Ku", "rotational stiffness Kv", "rotational stiffness Kw"];
        for a in 0..3 {
            self.translational[a].check(name, what_t[a], Anchor::ThroughOrigin)?;
            self.rotational[a].check(name, what_r[a], Anchor::ThroughOrigin)?;
        }
        check_finite(name, "preload force", &self.preload_force)?;
        check_finite(name, "preload torque", &self.preload_torque)?;
        frame_rotation(name, &self.frame)
    }
}

/// A bushing between two bodies (see the [module docs](self) for the model and its signs).
#[derive(Debug, Clone, PartialEq)]
pub struct Bushing {
    spec: BushingSpec,
    /// The hardpoint and the bushing frame on each body.
    framed: FramedPoint,
}

/// Everything the force, stiffness and report share at one configuration.
struct State {
    /// The frame, the deflection and rotation, the levers.
    at: Framed,
    /// `∂f/∂δ` in local components: the diagonal of `K_T`, or of the curves' slopes at `δ`.
    kt: Vec3,
    /// `f = E (K_T δ − F_pre)` = ∂U/∂d (the force applied to `i`).
    f: Vec3,
    /// `g = J_l⁻ᵀ (K_R θ − M_pre)` (local) and `∂g/∂θ`.
    g: Vec3,
    dg: Mat3,
}

impl Bushing {
    /// A bushing from global design data, without preload. Checks everything that can be checked
    /// without the design poses: distinct bodies ([`ModelError::SelfJoint`]), finite data
    /// ([`ModelError::NonFinite`]), positive stiffnesses ([`ModelError::NotPositive`], naming the
    /// component), an orthonormal right-handed frame ([`ModelError::NotOrthonormal`]).
    ///
    /// `frame` holds the bushing's local x, y, z axes as columns (global components);
    /// `translational = (Kx, Ky, Kz)` in N/m, `rotational = (Ku, Kv, Kw)` in N·m/rad.
    pub fn new(
        name: &str,
        body_i: BodyRef,
        body_j: BodyRef,
        point: Vec3,
        frame: Mat3,
        translational: Vec3,
        rotational: Vec3,
    ) -> Result<Self, ModelError> {
        let (translational, rotational) = (Characteristic::rates(&translational), Characteristic::rates(&rotational));
        Self::with_characteristics(name, body_i, body_j, point, frame, translational, rotational)
    }

    /// A bushing whose directions each have a rate or a measured curve ([`Characteristic`]), without
    /// preload: `translational` along the local x, y, z axes (N/m, or N against m), `rotational` about
    /// them (N·m/rad, or N·m against rad). Checked as in [`Bushing::new`]; a curve that does not pass
    /// through `(0, 0)`, decreases somewhere or is flat is [`ModelError::OutOfRange`], naming the
    /// direction.
    pub fn with_characteristics(
        name: &str,
        body_i: BodyRef,
        body_j: BodyRef,
        point: Vec3,
        frame: Mat3,
        translational: [Characteristic; 3],
        rotational: [Characteristic; 3],
    ) -> Result<Self, ModelError> {
        Self::from_spec(BushingSpec {
            name: name.to_string(),
            body_i,
            body_j,
            point,
            frame,
            translational,
            rotational,
            preload_force: Vec3::zeros(),
            preload_torque: Vec3::zeros(),
            rotation_law: RotationLaw::default(),
        })
    }

    /// Sets how the moment follows the relative rotation.
    pub fn with_rotation_law(mut self, law: RotationLaw) -> Self {
        self.spec.rotation_law = law;
        self
    }

    /// Sets the preload: the force (N) and moment (N·m) the bushing applies to body `j` at zero
    /// deflection, in the bushing's local frame.
    pub fn with_preload(mut self, force: Vec3, torque: Vec3) -> Result<Self, ModelError> {
        self.spec.preload_force = force;
        self.spec.preload_torque = torque;
        self.spec.validate()?;
        Ok(self)
    }

    /// A bushing from its full description (validated as in [`Bushing::new`]).
    pub fn from_spec(spec: BushingSpec) -> Result<Self, ModelError> {
        let frame = spec.validate()?;
        // Until bound, both bodies are taken at the identity pose (as the ground).
        Ok(Bushing { framed: FramedPoint::unbound(spec.point, frame), spec })
    }

    /// The design data.
    pub fn spec(&self) -> &BushingSpec {
        &self.spec
    }

    fn state(&self, pi: &Pose, pj: &Pose) -> State {
        let at = self.framed.at(pi, pj);
        let (force, kt) = along_axes(&self.spec.translational, &at.delta);
        let f = at.e * (force - self.spec.preload_force);
        let (g, dg) =
            self.spec.rotation_law.moment(&at.theta, &at.relative, &self.spec.rotational, &self.spec.preload_torque);
        State { at, kt, f, g, dg }
    }
}

impl ForceElement for Bushing {
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
            stiffness(&st, &big_g, &mut out.stiffness);
        }
    }

    fn report(&self, pi: &Pose, pj: &Pose, _t: f64) -> ElementReport {
        let st = self.state(pi, pj);
        ElementReport { force: -st.f, torque: -(st.at.e * st.g), deflection: st.at.delta, rotation: st.at.theta }
    }

    fn sketch(&self) -> Option<Sketch> {
        Some(self.framed.sketch())
    }
}

/// `K = ∂(∇U)/∂Δq` along left increments, with `∇U = (−f, f × w − G, f, sⱼ × f + G)`, `G = E g`.
///
/// Variations (`δs = −s̃ δπ`, `δE = δπ̃ᵢ E`, `ω = Eᵀ(δπⱼ − δπᵢ)`, `δθ = J_l⁻¹ ω`):
/// * `δf = K_g (δd + d̃ δπᵢ) − f̃ δπᵢ`, `K_g = E K_T Eᵀ` (`K_T` the diagonal of the rates or of the
///   curves' slopes), `δd = δrⱼ − s̃ⱼ δπⱼ − δrᵢ + s̃ᵢ δπᵢ`, so `Df = [−K_g, K_g w̃ − f̃, K_g, −K_g s̃ⱼ]`;
/// * `δG = −G̃ δπᵢ + H (δπⱼ − δπᵢ)`, `H = E (∂g/∂θ) J_l⁻¹ Eᵀ`, so `DG = [0, −G̃ − H, 0, H]`;
/// * `δw = δrⱼ − s̃ⱼ δπⱼ − δrᵢ`.
fn stiffness(st: &State, big_g: &Vec3, out: &mut PairMatrix) {
    let e = &st.at.e;
    let kg = e * Mat3::from_diagonal(&st.kt) * e.transpose();
    let f_t = skew(&st.f);
    let w_t = skew(&st.at.w);
    let sj_t = skew(&st.at.s_j);
    let h = e * st.dg * left_jacobian_inv(&st.at.theta) * e.transpose();

    let mut df = Jac3::zeros();
    set_jac_block(&mut df, 0, &(-kg));
    set_jac_block(&mut df, 1, &(kg * w_t - f_t));
    set_jac_block(&mut df, 2, &kg);
    set_jac_block(&mut df, 3, &(-kg * sj_t));
    let mut dgg = Jac3::zeros();
    set_jac_block(&mut dgg, 1, &(-skew(big_g) - h));
    set_jac_block(&mut dgg, 3, &h);
    framed_stiffness(&st.at, &st.f, &df, &dgg, out);
}

#[cfg(test)]
mod tests {
    use super::*;
    use elastokin_core::math::rotation_vector_moment;

    #[test]
    fn preloaded_moment_law_derivative_matches_finite_difference() {
        let k = Mat3::from_diagonal(&Vec3::new(3.0, 2.0, 5.0));
        let m0 = Vec3::new(0.7, -1.3, 0.4);
        let law = |th: &Vec3| rotation_vector_moment(th, &(k * th - m0), &k);
        for th in [Vec3::new(0.3, -0.7, 1.1), Vec3::new(0.02, 0.01, -0.03), Vec3::new(0.099, 0.0, 0.0)] {
            let (_, dg) = law(&th);
            let h = 1e-6;
            for c in 0..3 {
                let (mut tp, mut tm) = (th, th);
                tp[c] += h;
                tm[c] -= h;
                let fd = (law(&tp).0 - law(&tm).0) / (2.0 * h);
                assert!((fd - dg.column(c)).norm() < 1e-8, "{th:?} col {c}: {fd:?} vs {:?}", dg.column(c));
            }
        }
    }
}
