//! The anti-roll bar built: each half a body on a revolute bearing to the chassis, the two halves joined
//! at the centre line by a torsion element of the bar's rate, each drop link a distance constraint from
//! the arm's end to its point on the corner (see [`AntiRollBar`] for the description).

use crate::build::general::Resolver;
use crate::description::anti_roll_bar::{AntiRollBar, MIN_BEARING_OFFSET};
use crate::description::limits::{check_rate, ROTATIONAL_RATE_RANGE};
use elastokin_core::joint::orthonormal_complement;
use elastokin_core::{BodyRef, ElementId, JointSpec, Mat3, Model, ModelError, Pose, Vec3};
use elastokin_elements::Bushing;

impl AntiRollBar {
    /// Adds the bar (`k`: its index in the file, for messages) between the corners resolved by `sides`.
    /// Returns the torsion element.
    pub(crate) fn add(
        &self,
        model: &mut Model,
        k: usize,
        sides: (Resolver, Resolver),
    ) -> Result<ElementId, ModelError> {
        let key = format!("anti_roll_bars[{k}] ({})", self.name);
        check_rate(&format!("{key}.rate"), self.rate, ROTATIONAL_RATE_RANGE, "N·m/rad")?;
        let pivot = sides.0.point(&format!("{key}.pivot"), &self.pivot)?;
        if pivot.y < MIN_BEARING_OFFSET {
            return Err(ModelError::OutOfRange {
                item: key.clone(),
                why: format!(
                    "pivot lies {:.4} m left of the centre line: give the left bearing, at least \
                     {MIN_BEARING_OFFSET} m out, so that the two bearings define the bar's axis",
                    pivot.y
                ),
            });
        }
        let axis = Vec3::y();
        let mut halves = [BodyRef::Ground; 2];
        for (half, r) in halves.iter_mut().zip([&sides.0, &sides.1]) {
            let [body, bearing, link] = self.part_names(r.prefix());
            let (pivot, arm_end) =
                (r.point(&format!("{key}.pivot"), &self.pivot)?, r.point(&format!("{key}.arm_end"), &self.arm_end)?);
            let link_end = r.point(&format!("{key}.link_end"), &self.link_end)?;
            let on = r.body(model, &format!("{key}.link_body"), &self.link_body)?;
            let bar = model.add_body(&body, Pose::at(pivot))?;
            model.add_joint(JointSpec::revolute(&bearing, BodyRef::Ground, bar, pivot, axis))?;
            model.add_joint(JointSpec::distance(&link, bar, on, arm_end, link_end))?;
            *half = bar.into();
        }
        // The torsion element at the centre line: x along the bar. Its other rates meet no deflection (the
        // bearings hold both halves on one axis), so they take the torsion rate's size, to keep the tangent
        // well scaled.
        let (u, v) = orthonormal_complement(&axis);
        let centre = Vec3::new(pivot.x, 0.0, pivot.z);
        let frame = Mat3::from_columns(&[axis, u, v]);
        let rates = Vec3::repeat(self.rate);
        model.add_element(Bushing::new(&self.name, halves[0], halves[1], centre, frame, rates, rates)?)
    }
}
