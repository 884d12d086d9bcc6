//! A suspension corner ready to solve: its model, the rig that holds it, and where its wheel is.

use crate::assembly::map::BuildMap;
use crate::assembly::rig::{
    add_both_corners, add_rack, add_travel_drivers, add_wheel_travel_driver, mount_tie_rod, no_steering_input, Rig,
};
use crate::assembly::template::CornerTemplate;
use crate::description::general::part_name;
use crate::description::GeneralCorner;
use crate::description::Side;
use crate::wheel::Wheel;
use elastokin_core::{BodyId, BodyRef, ElementId, Model, ModelError, Vec3};
use elastokin_elements::{PointForce, PointTorque};

/// A suspension corner ready to solve: its model, how it is held and where its wheel is.
#[derive(Debug, Clone)]
pub struct Corner {
    /// The multibody model.
    pub model: Model,
    /// How it is held.
    pub rig: Rig,
    /// The wheel.
    pub wheel: Wheel,
    /// The corner's own spring (see [`CornerParts::spring`](crate::assembly::CornerParts::spring)).
    pub spring: Option<ElementId>,
    /// The wheel across the axle when the corner cannot stand alone (a solid axle; see [`Corner::build`]):
    /// held by the same rig and loaded as `wheel` is, in phase.
    pub partner: Option<Wheel>,
    /// Where the rig applies the vertical, lateral and braking forces of the load analyses.
    pub load_point: LoadPoint,
}

/// Where a K&C rig applies its forces to the wheel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LoadPoint {
    /// At the contact patch, as the tyre does (the default): the force's lever about the wheel centre
    /// (the loaded radius) turns the wheel too.
    #[default]
    ContactPatch,
    /// At the wheel centre, as a rig that loads the hub does: the force alone, without the tyre's lever.
    WheelCentre,
}

impl Corner {
    /// The design point where the rig's forces act (see [`LoadPoint`]): `patch` (a contact-patch point) or
    /// the wheel centre.
    pub fn load_point_at(&self, patch: Vec3) -> Vec3 {
        match self.load_point {
            LoadPoint::ContactPatch => patch,
            LoadPoint::WheelCentre => self.wheel.wheel_centre,
        }
    }

    /// Builds `template`'s corner on `side` with its tie rod and held as `rig` says: a rack on a lateral
    /// slide when steering (else the tie rod's inner end is on the chassis), and the wheel-centre height
    /// driver the rig needs.
    ///
    /// A template whose corners share parts ([`CornerTemplate::builds_on_axle_only`], a solid axle) is
    /// built whole: the corner on `side` named as a lone corner's (`"upright"`, `"wheel travel"`), its
    /// partner on the other side named `"left …"` or `"right …"` and held by the same rig, so that travel
    /// moves both wheels alike; the loads of [`Corner::add_wheel_force`] and [`Corner::add_wheel_torque`]
    /// act on both, in phase (see there).
    pub fn build(template: &impl CornerTemplate, side: Side, rig: Rig) -> Result<Corner, ModelError> {
        Corner::build_in(Model::new(), template, side, rig)
    }

    /// [`Corner::build`] into `model`, an empty model (one that places its bodies' reference points
    /// where another build of the template put them: [`Model::with_body_origins`]).
    pub fn build_in(model: Model, template: &impl CornerTemplate, side: Side, rig: Rig) -> Result<Corner, ModelError> {
        let mut model = model;
        let travel_rate = match rig {
            Rig::WheelTravel => Some(1.0),
            Rig::Steering | Rig::HeightHeld => Some(0.0),
            Rig::Free => None,
        };
        if template.builds_on_axle_only() {
            let other = partner_prefix(side);
            let prefixes = match side {
                Side::Left => ["", other],
                Side::Right => [other, ""],
            };
            let (left, right, _) = add_both_corners(&mut model, template, prefixes, rig == Rig::Steering)?;
            let (own, partner) = match side {
                Side::Left => (left, right),
                Side::Right => (right, left),
            };
            let (spring, own, partner) = (own.spring, own.wheel, partner.wheel);
            if let Some(rate) = travel_rate {
                add_travel_drivers(&mut model, true, ("", &own, rate), (other, &partner, rate))?;
            }
            let load_point = LoadPoint::default();
            return Ok(Corner { model, rig, wheel: own, spring, partner: Some(partner), load_point });
        }
        let parts = template.add_corner(&mut model, side, "")?;
        match (parts.tie_rod, rig) {
            (Some(tie_rod), Rig::Steering) => {
                let rack = add_rack(&mut model, tie_rod.inner, Vec3::y())?;
                mount_tie_rod(&mut model, "", rack, &parts.wheel, tie_rod)?;
            }
            (Some(tie_rod), _) => mount_tie_rod(&mut model, "", BodyRef::Ground, &parts.wheel, tie_rod)?,
            (None, Rig::Steering) => return Err(no_steering_input()),
            (None, _) => {}
        }
        if let Some(rate) = travel_rate {
            add_wheel_travel_driver(&mut model, "", &parts.wheel, rate)?;
        }
        let spring = parts.spring;
        Ok(Corner { model, rig, wheel: parts.wheel, spring, partner: None, load_point: LoadPoint::default() })
    }

    /// The corners built, each with its parts' name prefix: the own corner's (`""`), and the partner's on
    /// a solid axle.
    pub fn sides(&self) -> Vec<(Side, &'static str)> {
        let own = (self.wheel.side, "");
        match self.partner_prefix() {
            Some(prefix) => vec![own, (self.wheel.side.other(), prefix)],
            None => vec![own],
        }
    }

    /// What each item of `general` (the description it was built from, a template's expansion) became in
    /// this corner's model.
    pub fn build_map(&self, general: &GeneralCorner) -> BuildMap {
        BuildMap::of(general, &self.model, &self.sides())
    }

    /// The prefix of the partner wheel's part names, when the corner has one.
    pub fn partner_prefix(&self) -> Option<&'static str> {
        self.partner.map(|_| partner_prefix(self.wheel.side))
    }

    /// Adds a world-fixed force `force · t` (N per unit load parameter) at the global design point `point`
    /// of the upright: a contact-patch or wheel-centre load of a K&C test. With a partner wheel (a solid
    /// axle), the same force acts on the partner too, at the mirror image of `point`: in phase, as a K&C
    /// rig loads an axle in a turn (the lateral forces of both tyres point the same way; mirror images would
    /// only squeeze the tube).
    pub fn add_wheel_force(&mut self, name: &str, point: Vec3, force: Vec3) -> Result<ElementId, ModelError> {
        self.add_wheel_force_with_constant(name, point, force, Vec3::zeros())
    }

    /// [`Corner::add_wheel_force`] with a constant part `constant` (N) beside the ramped `force · t`.
    pub fn add_wheel_force_with_constant(
        &mut self,
        name: &str,
        point: Vec3,
        force: Vec3,
        constant: Vec3,
    ) -> Result<ElementId, ModelError> {
        let element = |upright: BodyId, name: &str, point: Vec3, force: Vec3, constant: Vec3| {
            PointForce::new(name, upright.into(), point, force)?.with_constant(constant)
        };
        let id = self.model.add_element(element(self.wheel.upright, name, point, force, constant)?)?;
        if let (Some(partner), Some(prefix)) = (self.partner, self.partner_prefix()) {
            let point = Vec3::new(point.x, -point.y, point.z);
            self.model.add_element(element(partner.upright, &part_name(prefix, name), point, force, constant)?)?;
        }
        Ok(id)
    }

    /// Adds a world-fixed torque `torque · t` (N·m per unit load parameter) on the upright; with a partner
    /// wheel, the same torque on the partner (in phase, as [`Corner::add_wheel_force`]).
    pub fn add_wheel_torque(&mut self, name: &str, torque: Vec3) -> Result<ElementId, ModelError> {
        let id = self.model.add_element(PointTorque::new(name, self.wheel.upright.into(), torque)?)?;
        if let (Some(partner), Some(prefix)) = (self.partner, self.partner_prefix()) {
            self.model.add_element(PointTorque::new(&part_name(prefix, name), partner.upright.into(), torque)?)?;
        }
        Ok(id)
    }
}

/// The part-name prefix of the wheel across the axle from one on `side`.
fn partner_prefix(side: Side) -> &'static str {
    match side {
        Side::Left => "right ",
        Side::Right => "left ",
    }
}
