//! The anti-roll bar built: each half a body on a revolute bearing to the chassis, the two halves joined
//! at the centre line by a torsion element of the bar's rate, each drop link a distance constraint from
//! the arm's end to its point on the corner (see [`AntiRollBar`] for the description).

use crate::assembly::general::Resolver;
use crate::description::anti_roll_bar::{AntiRollBar, MIN_BEARING_OFFSET};
use crate::description::limits::{check_rate, ROTATIONAL_RATE_RANGE};
use crate::description::Side;
use elastokin_core::joint::orthonormal_complement;
use elastokin_core::{BodyRef, ElementId, JointSpec, Mat3, Model, ModelError, Pose, Vec3};
use elastokin_elements::{beam, BeamSpec, Bushing};

impl AntiRollBar {
    /// Adds the bar (`k`: its index in the file, for messages) between the corners resolved by `sides`.
    /// Returns its elastic elements: the torsion element of a rate, or the beams of a section (the middle
    /// and each arm).
    pub(crate) fn add(
        &self,
        model: &mut Model,
        k: usize,
        sides: (Resolver, Resolver),
    ) -> Result<Vec<ElementId>, ModelError> {
        let key = format!("anti_roll_bars[{k}] ({})", self.name);
        let refuse = |why: &str| Err(ModelError::OutOfRange { item: key.clone(), why: why.to_string() });
        match (self.rate, &self.section) {
            (Some(rate), None) => check_rate(format_args!("{key}.rate"), rate, ROTATIONAL_RATE_RANGE, "N·m/rad")?,
            (None, Some(_)) => {}
            (Some(_), Some(_)) => return refuse("give the bar's rate (N·m/rad) or its section, not both"),
            (None, None) => return refuse("give the bar's rate (N·m/rad) or its section (a beam's section)"),
        }
        let pivot = sides.0.point(format_args!("{key}.pivot"), &self.pivot)?;
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
        // A beam's refusal names the bar's section.
        let rekey = |e: ModelError| e.out_of_range_as(format!("{key}.section"));
        let axis = Vec3::y();
        let mut halves = [BodyRef::Ground; 2];
        let mut elements = Vec::new();
        for (half, r) in halves.iter_mut().zip([&sides.0, &sides.1]) {
            let [body, bearing, link] = self.part_names(r.prefix());
            let (pivot, arm_end) = (
                r.point(format_args!("{key}.pivot"), &self.pivot)?,
                r.point(format_args!("{key}.arm_end"), &self.arm_end)?,
            );
            let link_end = r.point(format_args!("{key}.link_end"), &self.link_end)?;
            let on = r.body(model, format_args!("{key}.link_body"), &self.link_body)?;
            let bar = model.add_body(&body, Pose::at(pivot))?;
            model.add_joint(JointSpec::revolute(&bearing, BodyRef::Ground, bar, pivot, axis))?;
            // With a section, the arm bends: the drop link meets a body at its end, on the arm's beam.
            let arm = match &self.section {
                None => BodyRef::from(bar),
                Some(section) => {
                    let [end, arm] = self.arm_names(r.prefix());
                    let end = model.add_body(&end, Pose::at(arm_end))?;
                    let spec = BeamSpec {
                        name: arm,
                        body_i: bar.into(),
                        body_j: end.into(),
                        from: pivot,
                        to: arm_end,
                        y_axis: axis,
                        section: section.section(r.side()),
                    };
                    elements.push(model.add_element(beam(&spec).map_err(rekey)?)?);
                    end.into()
                }
            };
            model.add_joint(JointSpec::distance(&link, arm, on, arm_end, link_end))?;
            *half = bar.into();
        }
        let centre = Vec3::new(pivot.x, 0.0, pivot.z);
        if let Some(section) = &self.section {
            // The middle, from bearing to bearing: a beam across the car, twisting as the halves turn.
            let spec = BeamSpec {
                name: self.name.clone(),
                body_i: halves[0],
                body_j: halves[1],
                from: pivot,
                to: Vec3::new(pivot.x, -pivot.y, pivot.z),
                y_axis: Vec3::x(),
                section: section.section(Side::Left),
            };
            elements.insert(0, model.add_element(beam(&spec).map_err(rekey)?)?);
            return Ok(elements);
        }
        // The torsion element at the centre line: x along the bar. Its other rates meet no deflection (the
        // bearings hold both halves on one axis), so they take the torsion rate's size, to keep the tangent
        // well scaled.
        let (u, v) = orthonormal_complement(&axis);
        let frame = Mat3::from_columns(&[axis, u, v]);
        let rates = Vec3::repeat(self.rate.unwrap_or_default());
        Ok(vec![model.add_element(Bushing::new(&self.name, halves[0], halves[1], centre, frame, rates, rates)?)?])
    }
}
