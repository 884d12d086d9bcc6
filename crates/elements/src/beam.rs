//! Beam: a straight elastic member between two bodies, by its section and length — large rigid motion,
//! small strain.
//!
//! # Formulation
//!
//! A beam from its end `A` on body `i` to its end `B` on body `j` stores the energy of its end `B`'s
//! deflection and rotation relative to where `B` would be were the beam rigid and carried by `i`: the
//! cantilever's, `U = ½ qᵀ K_c q`, `q = (δ, θ)` in the beam's frame at `A` (x along the beam, y and z the
//! section's axes), `K_c` the inverse of the cantilever's tip flexibility. That is a [`Field`] at `B` with
//! the frame carried by `i`, so the beam inherits the field's exact finite rotations: any rigid motion of
//! the pair stores nothing, and a small deformation stores the linear beam's energy exactly (the six
//! relative motions of its ends are all a beam's energy depends on). Within one beam the deformation's own
//! rotation must stay small (the cantilever is linear); a member bending far is split into segments with
//! bodies between them, and converges to the elastica as the segments shorten (see
//! `crates/elements/tests/beam.rs` for the order).
//!
//! # The cantilever's flexibility (Timoshenko)
//!
//! For a tip force `(Fx, Fy, Fz)` and moment `(Mx, My, Mz)` at `B`, length `L`:
//! `δx = Fx L/EA`; `δy = Fy (L³/3EI_z + L/GA_y) + Mz L²/2EI_z`, `θz = Fy L²/2EI_z + Mz L/EI_z`;
//! `δz = Fz (L³/3EI_y + L/GA_z) − My L²/2EI_y`, `θy = −Fz L²/2EI_y + My L/EI_y`; `θx = Mx' L/GJ` with the
//! twist taken about the shear centre at `(e_y, e_z)` from the centroid: `Mx' = Mx + e_z Fy − e_y Fz`, and
//! by reciprocity the twist moves the centroid by `δy += e_z θx`, `δz −= e_y θx`.

use crate::field::{Field, FieldSpec};
use elastokin_core::{
    BodyRef, ElementEval, ElementReport, ElementRole, ForceElement, Mat3, ModelError, Pose, Sketch, SketchKind, Vec3,
};
use nalgebra::{Matrix6, Vector6};

/// A beam's section and material (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Young's modulus `E` (Pa).
    pub youngs_modulus: f64,
    /// Shear modulus `G` (Pa).
    pub shear_modulus: f64,
    /// Area `A` (m²).
    pub area: f64,
    /// Second moment about the section's y axis, `I_y` (m⁴): bending in the x–z plane.
    pub iy: f64,
    /// Second moment about the section's z axis, `I_z` (m⁴): bending in the x–y plane.
    pub iz: f64,
    /// Torsion constant `J` (m⁴).
    pub j: f64,
    /// Shear areas `(A_y, A_z)` (m²), `κA`; `None`: no shear deformation (Euler–Bernoulli).
    pub shear_areas: Option<(f64, f64)>,
    /// Shear centre `(e_y, e_z)` (m) from the centroid, in the section's axes.
    pub shear_centre: (f64, f64),
}

/// The largest Young's or shear modulus a section may have (Pa): ten times diamond's.
pub const MOST_MODULUS: f64 = 1e13;

/// How far from the centroid a shear centre may lie, in multiples of `√A`: an open channel's lies about
/// one section depth out; ten is no section.
pub const SHEAR_CENTRE_REACH: f64 = 10.0;

impl Section {
    /// Refuses values no section has, naming the beam (`item`) and the value.
    fn check(&self, item: &str) -> Result<(), ModelError> {
        let refuse = |why: String| Err(ModelError::OutOfRange { item: item.to_string(), why });
        let mut values = vec![
            ("Young's modulus E", self.youngs_modulus),
            ("shear modulus G", self.shear_modulus),
            ("area A", self.area),
            ("second moment Iy", self.iy),
            ("second moment Iz", self.iz),
            ("torsion constant J", self.j),
        ];
        if let Some((ay, az)) = self.shear_areas {
            values.extend([("shear area Ay", ay), ("shear area Az", az)]);
        }
        for (what, v) in values {
            if !(v.is_finite() && v > 0.0) {
                return refuse(format!("the {what} must be a positive number, got {v:e}"));
            }
            // Beyond these the cantilever's flexibility rounds to nothing against its stiffness and the
            // stiffness overflows: no section is made of such numbers.
            let (most, unit) = if what.contains("modulus") { (MOST_MODULUS, "Pa") } else { (1.0, "in SI units") };
            if v > most {
                return refuse(format!(
                    "the {what} is {v:e} {unit}, beyond {most:e}: no section has it; give SI units (Pa, m², m⁴)"
                ));
            }
        }
        let (ey, ez) = self.shear_centre;
        if !(ey.is_finite() && ez.is_finite()) {
            return Err(ModelError::NonFinite { item: item.to_string(), what: "shear centre" });
        }
        let reach = SHEAR_CENTRE_REACH * self.area.sqrt();
        if ey.hypot(ez) > reach {
            return refuse(format!(
                "the shear centre lies {:.4} m from the centroid, beyond any section of area {:e} m² \
                 ({reach:.4} m): give its offset in metres, in the section's axes",
                ey.hypot(ez),
                self.area
            ));
        }
        Ok(())
    }

    /// The cantilever's tip stiffness over `(δ, θ)` of a beam of length `length` (the inverse of the
    /// flexibility of the module docs).
    pub fn cantilever_stiffness(&self, length: f64) -> Matrix6<f64> {
        let (e, g, l) = (self.youngs_modulus, self.shear_modulus, length);
        let (ay, az) = self.shear_areas.map_or((f64::INFINITY, f64::INFINITY), |s| s);
        let mut f = Matrix6::zeros();
        f[(0, 0)] = l / (e * self.area);
        f[(1, 1)] = l.powi(3) / (3.0 * e * self.iz) + l / (g * ay);
        f[(1, 5)] = l * l / (2.0 * e * self.iz);
        f[(5, 1)] = f[(1, 5)];
        f[(5, 5)] = l / (e * self.iz);
        f[(2, 2)] = l.powi(3) / (3.0 * e * self.iy) + l / (g * az);
        f[(2, 4)] = -l * l / (2.0 * e * self.iy);
        f[(4, 2)] = f[(2, 4)];
        f[(4, 4)] = l / (e * self.iy);
        // Twist about the shear centre: Mx' = bᵀ (F, M) with b = (0, e_z, −e_y, 1, 0, 0), its flexibility
        // L/GJ; reciprocity puts the same b on the displacements.
        let (ey, ez) = self.shear_centre;
        let b = Vector6::new(0.0, ez, -ey, 1.0, 0.0, 0.0);
        f += b * b.transpose() * (l / (g * self.j));
        // Positive definite for any section `check` admits; its inverse symmetrized against rounding.
        let k = f.try_inverse().unwrap_or_else(Matrix6::zeros);
        (k + k.transpose()) * 0.5
    }
}

/// A beam's design data.
#[derive(Debug, Clone, PartialEq)]
pub struct BeamSpec {
    /// Unique name.
    pub name: String,
    /// Body `i`, at the beam's start (may be the ground).
    pub body_i: BodyRef,
    /// Body `j`, at its end.
    pub body_j: BodyRef,
    /// The start (global, m, at design).
    pub from: Vec3,
    /// The end (global, m, at design).
    pub to: Vec3,
    /// A direction the section's y axis leans towards (made perpendicular to the beam).
    pub y_axis: Vec3,
    /// The section and material.
    pub section: Section,
}

/// A beam as a model holds it: the field of its cantilever (see the module docs), which is all its
/// mechanics, and its start on body `i`, where a drawing begins the line it draws to the end on `j`.
#[derive(Debug, Clone, PartialEq)]
pub struct Beam {
    field: Field,
    /// The start: global until bound, then in body `i`'s frame.
    start: Vec3,
}

impl ForceElement for Beam {
    fn name(&self) -> &str {
        self.field.name()
    }

    fn bodies(&self) -> [BodyRef; 2] {
        self.field.bodies()
    }

    fn role(&self) -> ElementRole {
        self.field.role()
    }

    fn bind(&mut self, pi: &Pose, pj: &Pose) -> Result<(), ModelError> {
        self.field.bind(pi, pj)?;
        self.start = pi.to_local_point(&self.start);
        Ok(())
    }

    fn evaluate(&self, pi: &Pose, pj: &Pose, t: f64, out: &mut ElementEval, with_stiffness: bool) {
        self.field.evaluate(pi, pj, t, out, with_stiffness);
    }

    fn report(&self, pi: &Pose, pj: &Pose, t: f64) -> ElementReport {
        self.field.report(pi, pj, t)
    }

    fn energy(&self, pi: &Pose, pj: &Pose) -> Option<f64> {
        Some(self.field.energy(pi, pj))
    }

    fn sketch(&self) -> Option<Sketch> {
        let end = self.field.sketch()?;
        Some(Sketch { kind: SketchKind::Beam, on_i: self.start, on_j: end.on_j, axes_i: end.axes_i })
    }
}

/// The beam of `spec` (see the module docs). Refused by name: a length of zero, a section value that is
/// not positive, a shear centre outside any plausible section, a `y_axis` along the beam.
pub fn beam(spec: &BeamSpec) -> Result<Beam, ModelError> {
    let refuse = |why: String| Err(ModelError::OutOfRange { item: spec.name.clone(), why });
    for (what, v) in [("start", spec.from), ("end", spec.to), ("y_axis", spec.y_axis)] {
        if !v.iter().all(|c| c.is_finite()) {
            return refuse(format!("its {what} must be three finite numbers"));
        }
    }
    let axis = spec.to - spec.from;
    let length = axis.norm();
    if length.is_nan() || length <= 1e-6 {
        return refuse(format!("its length is {length:e} m: give a start and an end apart"));
    }
    spec.section.check(&spec.name)?;
    let x = axis / length;
    let y = spec.y_axis - x * x.dot(&spec.y_axis);
    if y.norm().is_nan() || y.norm() <= 1e-6 * spec.y_axis.norm() {
        return refuse("its y_axis lies along the beam: give a direction across it".into());
    }
    let y = y.normalize();
    let stiffness = spec.section.cantilever_stiffness(length);
    if !stiffness.iter().all(|k| k.is_finite()) {
        return refuse(format!(
            "its section is too soft or too stiff for its length of {length:e} m to give a stiffness in double \
             precision: give the section in SI units (Pa, m², m⁴)"
        ));
    }
    let field = Field::from_spec(FieldSpec {
        name: spec.name.clone(),
        body_i: spec.body_i,
        body_j: spec.body_j,
        point: spec.to,
        frame: Mat3::from_columns(&[x, y, x.cross(&y)]),
        stiffness,
        preload_force: Vec3::zeros(),
        preload_torque: Vec3::zeros(),
    })?;
    Ok(Beam { field, start: spec.from })
}
