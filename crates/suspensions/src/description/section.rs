//! A beam's section as a model file gives it: shared by the general form's beams, the twist beam's arms and
//! cross member, and an anti-roll bar given by its steel.

use serde::{Deserialize, Serialize};

/// A beam's section and material, as a model file gives them (SI units; see `elastokin_elements::Section`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SectionDef {
    /// Young's modulus `E` (Pa).
    pub youngs_modulus: f64,
    /// Shear modulus `G` (Pa).
    pub shear_modulus: f64,
    /// Area (m²).
    pub area: f64,
    /// Second moment about the section's y axis (m⁴).
    pub iy: f64,
    /// Second moment about the section's z axis (m⁴).
    pub iz: f64,
    /// Torsion constant (m⁴).
    pub j: f64,
    /// Shear areas `[A_y, A_z]` (m²); without them no shear deformation.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear_areas: Option<[f64; 2]>,
    /// Shear centre `[e_y, e_z]` from the centroid in the section's axes (m); default the centroid.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear_centre: Option<[f64; 2]>,
}
