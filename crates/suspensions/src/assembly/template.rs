//! What a template adds to a model: the [`CornerTemplate`] interface every description builds through,
//! and the parts it hands to the rig ([`CornerParts`], [`CrossAxle`]).

use crate::description::connection::TieRodMounts;
use crate::description::Side;
use crate::wheel::Wheel;
use elastokin_core::{BodyRef, ElementId, Model, ModelError, Vec3};

/// A suspension template: something that adds one corner's parts to a model.
///
/// The rig (rack, tie-rod inner attachment, drivers) is not the template's: [`Corner::build`](crate::assembly::Corner::build) and
/// [`crate::Axle::build`] add it, so one template serves a lone corner and both sides of an axle.
pub trait CornerTemplate {
    /// Adds the corner on `side` to `model`, every body, joint and element name starting with `prefix`
    /// (`""` for a lone corner, `"left "` / `"right "` on an axle). The tie rod is not added: it is
    /// returned in [`CornerParts::tie_rod`] for the rig to attach to the rack or the chassis.
    fn add_corner(&self, model: &mut Model, side: Side, prefix: &str) -> Result<CornerParts, ModelError>;

    /// Whether the two corners share parts (a solid axle's tube): then the template builds only on a whole
    /// axle, and [`Corner::build`](crate::assembly::Corner::build) builds both sides. False by default.
    fn builds_on_axle_only(&self) -> bool {
        false
    }

    /// Adds the bodies the two corners share, before either corner. None by default.
    fn add_axle_bodies(&self, _model: &mut Model) -> Result<(), ModelError> {
        Ok(())
    }

    /// Adds the parts that join the two corners of an axle (anti-roll bars, the shared parts' joints and
    /// elements), after both corners, each given with its name prefix. None by default.
    fn add_cross_axle(
        &self,
        _model: &mut Model,
        _left: (&str, &CornerParts),
        _right: (&str, &CornerParts),
    ) -> Result<CrossAxle, ModelError> {
        Ok(CrossAxle::default())
    }
}

/// What a template added across the two corners of an axle.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CrossAxle {
    /// The anti-roll bars' elastic elements: a bar's torsion element, or the beams of a bar given by its
    /// section (its middle and its arms).
    pub anti_roll_bars: Vec<ElementId>,
    /// The axle's steering input, still to be attached to the rack or the chassis, when its corners have
    /// no tie rods of their own.
    pub steering_link: Option<SteeringLink>,
    /// The shared elastic beams (a twist-beam axle's cross member), whose twist the roll analysis reads.
    pub members: Vec<ElasticMember>,
}

/// A shared elastic beam of an axle, in its segments from the first end to the last.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ElasticMember {
    /// The beam's name in the description.
    pub name: String,
    /// Its segments' elements, in order along it.
    pub segments: Vec<ElementId>,
}

/// A solid axle's steering input: a rod from the steering box (the rack, or the chassis when the rack is
/// fixed) to a part of the axle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteeringLink {
    /// The part it pushes.
    pub body: BodyRef,
    /// The rod: `inner` at the steering box, `outer` on `body`.
    pub rod: TieRod,
    /// Unit direction in which the steering input moves the inner end.
    pub rack_axis: Vec3,
}

/// What a template added for one corner.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CornerParts {
    /// The wheel: upright, wheel centre, contact patch, steering axis.
    pub wheel: Wheel,
    /// The tie rod, still to be attached; `None` when the corner has no steering input (its toe is held
    /// by its own links).
    pub tie_rod: Option<TieRod>,
    /// The corner's own spring (its first), whose deflection gives the spring's motion ratio; `None` when
    /// it has none.
    pub spring: Option<ElementId>,
}

/// A tie rod between the rack (or the chassis when the rack is fixed) and the upright.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TieRod {
    /// Inner end (rack), global design point.
    pub inner: Vec3,
    /// Outer end (upright), global design point.
    pub outer: Vec3,
    /// Both ends ideal: a distance constraint (ball joints at both ends). A bushing at either end: a tie-rod
    /// body, each bushing's axis along the rod, so the steering compliance of the rod's mounts is modelled;
    /// an ideal end of it is a universal joint at the rack (holding the rod's spin) or a ball joint at the
    /// upright.
    pub connection: TieRodMounts,
}
