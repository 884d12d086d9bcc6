//! Validation of design data, small block helpers, and the line between two seats that springs and stops
//! share.

use elastokin_core::math::{quat_log, skew};
use elastokin_core::{BodyRef, ElementEval, Mat3, ModelError, PairMatrix, Pose, RowGradient, Sketch, SketchKind, Vec3};
use nalgebra::{Rotation3, SMatrix, UnitQuaternion};

/// Largest deviation of `EᵀE` from `I` accepted for an element's frame; a frame within it is replaced
/// by the rotation it is closest to (round-off in typed-in axes is tolerated, a wrong frame is not).
pub const FRAME_TOLERANCE: f64 = 1e-6;

/// A 3×12 Jacobian of a 3-vector over the coordinates `(Δrᵢ, Δπᵢ, Δrⱼ, Δπⱼ)`.
pub(crate) type Jac3 = SMatrix<f64, 3, 12>;

/// Every component finite, else [`ModelError::NonFinite`].
pub(crate) fn check_finite(item: &str, what: &'static str, v: &Vec3) -> Result<(), ModelError> {
    if v.iter().all(|c| c.is_finite()) {
        Ok(())
    } else {
        Err(ModelError::NonFinite { item: item.to_string(), what })
    }
}

/// A finite, strictly positive scalar, else [`ModelError::NonFinite`] / [`ModelError::NotPositive`].
pub(crate) fn check_positive(item: &str, what: &'static str, value: f64) -> Result<(), ModelError> {
    if !value.is_finite() {
        return Err(ModelError::NonFinite { item: item.to_string(), what });
    }
    if value <= 0.0 {
        return Err(ModelError::NotPositive { item: item.to_string(), what, value });
    }
    Ok(())
}

/// A finite scalar, else [`ModelError::NonFinite`].
pub(crate) fn check_finite_scalar(item: &str, what: &'static str, value: f64) -> Result<(), ModelError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(ModelError::NonFinite { item: item.to_string(), what })
    }
}

/// A point and a frame carried by body `i`, and their copies carried by `j`, coincident at design: what a
/// bushing and a field element measure their deflection and rotation between.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct FramedPoint {
    on_i: Vec3,
    on_j: Vec3,
    /// The frame relative to each body: `E = Aᵢ E'ᵢ`, `Eⱼ = Aⱼ E'ⱼ`.
    frame_i: UnitQuaternion<f64>,
    frame_j: UnitQuaternion<f64>,
}

/// A framed point at one configuration.
pub(crate) struct Framed {
    /// The frame carried by `i`, as a matrix.
    pub e: Mat3,
    /// `j`'s copy relative to it, and its rotation vector `θ` (local).
    pub relative: UnitQuaternion<f64>,
    pub theta: Vec3,
    /// `sⱼ = Aⱼ s'ⱼ`.
    pub s_j: Vec3,
    /// `w = Pⱼ − rᵢ`, the lever of the force on `i`.
    pub w: Vec3,
    /// The deflection `δ = Eᵀ (Pⱼ − Pᵢ)` (local).
    pub delta: Vec3,
}

impl FramedPoint {
    /// The point and frame (global) with both bodies at the identity pose, until bound.
    pub fn unbound(point: Vec3, frame: UnitQuaternion<f64>) -> Self {
        FramedPoint { on_i: point, on_j: point, frame_i: frame, frame_j: frame }
    }

    /// Fixes the point and frame on each body from the design poses.
    pub fn bind(
        &mut self,
        name: &str,
        pi: &Pose,
        pj: &Pose,
        point: &Vec3,
        frame: UnitQuaternion<f64>,
    ) -> Result<(), ModelError> {
        if !pi.is_finite() || !pj.is_finite() {
            return Err(ModelError::NonFinite { item: name.to_string(), what: "design pose" });
        }
        self.on_i = pi.to_local_point(point);
        self.on_j = pj.to_local_point(point);
        self.frame_i = pi.orientation.inverse() * frame;
        self.frame_j = pj.orientation.inverse() * frame;
        Ok(())
    }

    /// Where things are at the poses.
    pub fn at(&self, pi: &Pose, pj: &Pose) -> Framed {
        let q_e = pi.orientation * self.frame_i;
        let q_ej = pj.orientation * self.frame_j;
        let e = q_e.to_rotation_matrix().into_inner();
        let relative = q_e.inverse() * q_ej;
        let theta = quat_log(&relative);
        let s_i = pi.direction(&self.on_i);
        let s_j = pj.direction(&self.on_j);
        let d = (pj.position + s_j) - (pi.position + s_i);
        Framed { e, relative, theta, s_j, w: s_i + d, delta: e.transpose() * d }
    }

    /// How a drawing places it: its point on each body, its axes in `i`'s frame.
    pub fn sketch(&self) -> Sketch {
        Sketch {
            kind: SketchKind::Bushing,
            on_i: self.on_i,
            on_j: self.on_j,
            axes_i: Some(self.frame_i.to_rotation_matrix().into_inner()),
        }
    }
}

/// The generalized force of a framed element applying the force `f` and moment `G` to `i` (its line of
/// action through `Pⱼ`) and their opposites to `j`.
pub(crate) fn framed_force(st: &Framed, f: &Vec3, big_g: &Vec3, q: &mut RowGradient) {
    q.fixed_rows_mut::<3>(0).copy_from(f);
    q.fixed_rows_mut::<3>(3).copy_from(&(st.w.cross(f) + big_g));
    q.fixed_rows_mut::<3>(6).copy_from(&(-f));
    q.fixed_rows_mut::<3>(9).copy_from(&(-st.s_j.cross(f) - big_g));
}

/// `K = −∂Q/∂Δq` of [`framed_force`] from the Jacobians `df` of `f` and `dgg` of `G` over `(Δrᵢ, Δπᵢ,
/// Δrⱼ, Δπⱼ)`, with the terms the levers and the frame's turning add.
pub(crate) fn framed_stiffness(st: &Framed, f: &Vec3, df: &Jac3, dgg: &Jac3, out: &mut PairMatrix) {
    let f_t = skew(f);
    let w_t = skew(&st.w);
    let sj_t = skew(&st.s_j);
    out.fill(0.0);
    // r_i: −f
    add_rows(out, 0, &(-df));
    // π_i: f × w − G = −w̃ f − G
    add_rows(out, 1, &(-(w_t * df) - dgg));
    add_block(out, 1, 0, &(-f_t));
    add_block(out, 1, 2, &f_t);
    add_block(out, 1, 3, &(-f_t * sj_t));
    // r_j: f
    add_rows(out, 2, df);
    // π_j: s_j × f + G
    add_rows(out, 3, &(sj_t * df + dgg));
    add_block(out, 3, 3, &(f_t * sj_t));
}

/// An element's frame (columns: its axes, global components) as a rotation: a frame with a non-finite
/// entry, or that is not orthonormal and right-handed to [`FRAME_TOLERANCE`], is refused by the element's
/// name.
pub(crate) fn frame_rotation(name: &str, e: &Mat3) -> Result<UnitQuaternion<f64>, ModelError> {
    if !e.iter().all(|c| c.is_finite()) {
        return Err(ModelError::NonFinite { item: name.to_string(), what: "frame" });
    }
    let ortho = (e.transpose() * e - Mat3::identity()).amax();
    let det = e.determinant();
    if ortho > FRAME_TOLERANCE || det < 0.0 {
        let error = if det < 0.0 { ortho.max((det - 1.0).abs()) } else { ortho };
        return Err(ModelError::NotOrthonormal { item: name.to_string(), error });
    }
    // Snap to the nearest unit quaternion (Shepperd's formula does not normalise).
    let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(*e));
    Ok(UnitQuaternion::new_normalize(q.into_inner()))
}

/// The two bodies of a two-body element must differ ([`ModelError::SelfJoint`] names the element).
pub(crate) fn check_distinct(item: &str, i: BodyRef, j: BodyRef) -> Result<(), ModelError> {
    if i == j {
        Err(ModelError::SelfJoint { joint: item.to_string() })
    } else {
        Ok(())
    }
}

/// Adds `m` to the 3×3 block of `out` at block row `r`, block column `c` (block indices 0..4).
#[inline]
pub(crate) fn add_block(out: &mut PairMatrix, r: usize, c: usize, m: &Mat3) {
    let mut v = out.fixed_view_mut::<3, 3>(3 * r, 3 * c);
    v += m;
}

/// Adds the 3×12 rows `m` to block row `r` of `out`.
#[inline]
pub(crate) fn add_rows(out: &mut PairMatrix, r: usize, m: &Jac3) {
    let mut v = out.fixed_view_mut::<3, 12>(3 * r, 0);
    v += m;
}

/// Sets the 3×3 block `c` (0..4) of a 3×12 Jacobian.
#[inline]
pub(crate) fn set_jac_block(jac: &mut Jac3, c: usize, m: &Mat3) {
    jac.fixed_view_mut::<3, 3>(0, 3 * c).copy_from(m);
}

/// Below this fraction of the design length the direction of a line falls back to the design direction.
const DEGENERATE_FRACTION: f64 = 1e-9;

/// Two seats, one on each body, and the line between them: the geometry of coil springs and stops.
///
/// Points `Pᵢ = rᵢ + sᵢ`, `Pⱼ = rⱼ + sⱼ` (`s = A s'`), separation `d = Pⱼ − Pᵢ`, length `L = |d|`, unit
/// vector `n = d / L` from `i` to `j`. Below `1e-9 · L_design` the direction is undefined; `n` is then the
/// design direction carried by body `i`, and the transverse term of the tangent is dropped so that the
/// values stay finite (the two seats through each other is not a physical configuration).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Seats {
    on_i: Vec3,
    on_j: Vec3,
    /// Design direction `n` in body-`i` components (fallback when `L → 0`).
    axis_i: Vec3,
    /// Length below which the fallback is used.
    min_length: f64,
}

/// The line between the seats at one configuration.
pub(crate) struct Line {
    pub s_i: Vec3,
    pub s_j: Vec3,
    pub n: Vec3,
    pub length: f64,
    pub degenerate: bool,
}

impl Seats {
    /// Seats at the global design points, with both bodies at the identity pose until bound. The points
    /// must be distinct (checked by the element).
    pub fn new(point_i: &Vec3, point_j: &Vec3) -> Self {
        let d = point_j - point_i;
        let len = d.norm();
        Seats { on_i: *point_i, on_j: *point_j, axis_i: d / len, min_length: DEGENERATE_FRACTION * len }
    }

    /// Fixes the seats on the bodies from their design poses; a non-finite pose is
    /// [`ModelError::NonFinite`] naming the element `name`.
    pub fn bind(&mut self, name: &str, pi: &Pose, pj: &Pose, point_i: &Vec3, point_j: &Vec3) -> Result<(), ModelError> {
        if !pi.is_finite() || !pj.is_finite() {
            return Err(ModelError::NonFinite { item: name.to_string(), what: "design pose" });
        }
        self.on_i = pi.to_local_point(point_i);
        self.on_j = pj.to_local_point(point_j);
        let d = point_j - point_i;
        self.axis_i = pi.to_local_direction(&(d / d.norm()));
        Ok(())
    }

    /// The seats as a drawing places them.
    pub fn sketch(&self, kind: SketchKind) -> Sketch {
        Sketch { kind, on_i: self.on_i, on_j: self.on_j, axes_i: None }
    }

    /// The line at the poses.
    pub fn line(&self, pi: &Pose, pj: &Pose) -> Line {
        let s_i = pi.direction(&self.on_i);
        let s_j = pj.direction(&self.on_j);
        let d = (pj.position + s_j) - (pi.position + s_i);
        let length = d.norm();
        let degenerate = length < self.min_length;
        let n = if degenerate { pi.direction(&self.axis_i) } else { d / length };
        Line { s_i, s_j, n, length, degenerate }
    }
}

/// Generalized force and stiffness of a force `push` along the line that pushes the seats apart (the force
/// on `j` is `φ = push · n` at `Pⱼ`, on `i` its opposite at `Pᵢ`), with the axial rate
/// `rate = −∂push/∂L`.
///
/// `∂φ/∂d = T = −rate nnᵀ + (push/L)(I − nnᵀ)`, `δd = B Δq`, `B = [−I, s̃ᵢ, I, −s̃ⱼ]`, and
/// `K = −∂Q/∂Δq = −Bᵀ T B + diag(0, φ̃ s̃ᵢ, 0, −φ̃ s̃ⱼ)`: rows `(Dφ, s̃ᵢ Dφ + φ̃ s̃ᵢ, −Dφ, −s̃ⱼ Dφ − φ̃ s̃ⱼ)`
/// with `Dφ = T B`. The second term, from the lever arms turning with the bodies, is the skew part
/// `K − Kᵀ = diag(0, [Q_πᵢ]~, 0, [Q_πⱼ]~)` every left-increment tangent carries.
pub(crate) fn push_along(line: &Line, push: f64, rate: f64, out: &mut ElementEval, with_stiffness: bool) {
    let phi = line.n * push;
    let q = &mut out.force;
    q.fixed_rows_mut::<3>(0).copy_from(&(-phi));
    q.fixed_rows_mut::<3>(3).copy_from(&(-line.s_i.cross(&phi)));
    q.fixed_rows_mut::<3>(6).copy_from(&phi);
    q.fixed_rows_mut::<3>(9).copy_from(&line.s_j.cross(&phi));
    if !with_stiffness {
        return;
    }
    let nn = line.n * line.n.transpose();
    let mut t = -rate * nn;
    if !line.degenerate {
        t += (push / line.length) * (Mat3::identity() - nn);
    }
    let si_t = skew(&line.s_i);
    let sj_t = skew(&line.s_j);
    let phi_t = skew(&phi);
    let mut dphi = Jac3::zeros();
    set_jac_block(&mut dphi, 0, &(-t));
    set_jac_block(&mut dphi, 1, &(t * si_t));
    set_jac_block(&mut dphi, 2, &t);
    set_jac_block(&mut dphi, 3, &(-t * sj_t));
    let out = &mut out.stiffness;
    out.fill(0.0);
    add_rows(out, 0, &dphi);
    add_rows(out, 1, &(si_t * dphi));
    add_block(out, 1, 1, &(phi_t * si_t));
    add_rows(out, 2, &(-dphi));
    add_rows(out, 3, &(-(sj_t * dphi)));
    add_block(out, 3, 3, &(-(phi_t * sj_t)));
}
