//! A full axle: both corners of one template, mirrored, with one rack shared by the two tie rods — for
//! the tests that need both wheels: opposite wheel travel (roll), parallel travel with track change and
//! roll-centre migration, and steering of both wheels by one rack.

use crate::assembly::map::BuildMap;
use crate::assembly::rig::{add_both_corners, add_travel_drivers, AxleRig};
use crate::assembly::template::{CornerTemplate, ElasticMember};
use crate::description::{GeneralCorner, Side};
use crate::wheel::Wheel;
use elastokin_core::{ElementId, Model, ModelError};

/// Both corners of an axle in one model. Part names start with `"left "` or `"right "` (`"left upright"`,
/// `"right wheel travel"`, …); the rack, when there is one, is `"rack"`.
#[derive(Debug, Clone)]
pub struct Axle {
    /// The multibody model.
    pub model: Model,
    /// How it is held.
    pub rig: AxleRig,
    /// The left wheel.
    pub left: Wheel,
    /// The right wheel (the left mirrored, y → −y).
    pub right: Wheel,
    /// The anti-roll bars' elastic elements: a bar's torsion element, or the beams of a bar given by its
    /// section (its middle and its arms).
    pub anti_roll_bars: Vec<ElementId>,
    /// The shared elastic beams (a twist-beam axle's cross member).
    pub members: Vec<ElasticMember>,
}

impl Axle {
    /// Builds both corners of `template`, the left as described and the right mirrored, their tie rods on
    /// one rack (a body on a lateral slide when steering, else the chassis), held as `rig` says.
    pub fn build(template: &impl CornerTemplate, rig: AxleRig) -> Result<Axle, ModelError> {
        Axle::build_in(Model::new(), template, rig)
    }

    /// [`Axle::build`] into `model`, an empty model (one that places its bodies' reference points where
    /// another build of the template put them: [`Model::with_body_origins`]).
    pub fn build_in(model: Model, template: &impl CornerTemplate, rig: AxleRig) -> Result<Axle, ModelError> {
        let mut model = model;
        let (left, right, cross) =
            add_both_corners(&mut model, template, ["left ", "right "], rig == AxleRig::Steering)?;
        let travel_rates = match rig {
            AxleRig::ParallelTravel => Some((1.0, 1.0)),
            AxleRig::OppositeTravel => Some((1.0, -1.0)),
            AxleRig::Steering | AxleRig::HeightHeld => Some((0.0, 0.0)),
            AxleRig::Free => None,
        };
        if let Some((l, r)) = travel_rates {
            let axle_only = template.builds_on_axle_only();
            add_travel_drivers(&mut model, axle_only, ("left ", &left.wheel, l), ("right ", &right.wheel, r))?;
        }
        let (anti_roll_bars, members) = (cross.anti_roll_bars, cross.members);
        Ok(Axle { model, rig, left: left.wheel, right: right.wheel, anti_roll_bars, members })
    }

    /// What each item of `general` (the description it was built from, a template's expansion) became in
    /// the axle's model, on both sides.
    pub fn build_map(&self, general: &GeneralCorner) -> BuildMap {
        BuildMap::of(general, &self.model, &[(Side::Left, "left "), (Side::Right, "right ")])
    }
}
