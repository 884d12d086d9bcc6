//! How parts meet the chassis and each other: an ideal joint or a rubber bushing, and the coil spring.

use elastokin_core::joint::orthonormal_complement;
use elastokin_core::{BodyRef, JointSpec, Mat3, Model, ModelError, Vec3};
use elastokin_elements::{Bushing, RotationLaw};
use serde::{Deserialize, Serialize};

/// Rates of a cylindrical rubber bushing (SI: N/m and N·m/rad), in its own frame whose x axis is the
/// bushing's axis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BushingRates {
    /// Radial rate (both directions across the axis), N/m.
    pub radial: f64,
    /// Axial rate, N/m.
    pub axial: f64,
    /// Torsion about the axis, N·m/rad.
    pub torsion: f64,
    /// Conical (tilt of the axis), N·m/rad.
    pub conical: f64,
    /// How the moment follows the twist: `"energy"` (default), `"linear"` (M = Kθ of the rotation vector)
    /// or `"tait_bryan_xyz"` (the energy of body-fixed x-y-z angles); see [`RotationLaw`].
    #[serde(default, skip_serializing_if = "is_default_law")]
    pub law: RotationLaw,
}

fn is_default_law(law: &RotationLaw) -> bool {
    *law == RotationLaw::default()
}

impl BushingRates {
    /// Rates with the default rotation law.
    pub fn new(radial: f64, axial: f64, torsion: f64, conical: f64) -> Self {
        BushingRates { radial, axial, torsion, conical, law: RotationLaw::default() }
    }

    /// Every rate multiplied by `factor` (for stiffness studies).
    pub fn scaled(self, factor: f64) -> Self {
        BushingRates {
            radial: self.radial * factor,
            axial: self.axial * factor,
            torsion: self.torsion * factor,
            conical: self.conical * factor,
            law: self.law,
        }
    }
}

/// A connection of a template: ideal kinematic joint, or bushing.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Connection {
    /// The template's ideal joint (revolute arm pivot, spherical ball joint, …).
    #[default]
    Ideal,
    /// A bushing with these rates.
    Bushing(BushingRates),
}

/// Coil spring of a template: rate and push force at design.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringSpec {
    /// Rate, N/m.
    pub rate: f64,
    /// Push force at the design position, N.
    pub design_force: f64,
}

/// Mounts an arm on the chassis through its front and rear pivots: a revolute about the pivot axis, or a
/// bushing at each pivot with its axis along the pivot axis.
pub(crate) fn arm_mounts(
    model: &mut Model,
    arm_name: &str,
    arm: BodyRef,
    front: Vec3,
    rear: Vec3,
    connection: Connection,
) -> Result<(), ModelError> {
    let axis = rear - front;
    match connection {
        Connection::Ideal => {
            model.add_joint(JointSpec::revolute(&format!("{arm_name} pivot"), BodyRef::Ground, arm, front, axis))?;
        }
        Connection::Bushing(rates) => {
            for (end, point) in [("front", front), ("rear", rear)] {
                let name = format!("{arm_name} {end} bushing");
                model.add_element(axial_bushing(&name, BodyRef::Ground, arm, point, axis, rates)?)?;
            }
        }
    }
    Ok(())
}

/// A bushing between `carrier` (whose frame it moves with) and `body` at `point`, its local x along `axis`.
pub(crate) fn axial_bushing(
    name: &str,
    carrier: BodyRef,
    body: BodyRef,
    point: Vec3,
    axis: Vec3,
    r: BushingRates,
) -> Result<Bushing, ModelError> {
    let n = axis.norm();
    if !(n.is_finite() && n > 1e-9) {
        return Err(ModelError::CoincidentPoints { item: name.to_string(), distance: n });
    }
    // The rates were checked by their model-file keys when the corner began (`corner::check_connection`).
    let x = axis / n;
    let (y, z) = orthonormal_complement(&x);
    Bushing::new(
        name,
        carrier,
        body,
        point,
        Mat3::from_columns(&[x, y, z]),
        Vec3::new(r.axial, r.radial, r.radial),
        Vec3::new(r.torsion, r.conical, r.conical),
    )
    .map(|b| b.with_rotation_law(r.law))
}
