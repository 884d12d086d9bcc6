//! The templates built: each checks what only it says (its spring, its mounts, a strut that cannot spin)
//! and then builds its expansion into the general form, by the one builder.

use crate::build::corner::Corner;
use crate::build::rig::Rig;
use crate::build::template::{CornerParts, CornerTemplate, CrossAxle};
use crate::description::limits::{check_arm_mounts, check_connection, check_spring};
use crate::description::{Connection, DoubleWishbone, MacPherson, Side, StrutJoint, Template};
use elastokin_core::{Model, ModelError};

impl MacPherson {
    /// Builds the corner on `side`, held as `rig` says (see [`Corner::build`]).
    pub fn build(&self, side: Side, rig: Rig) -> Result<Corner, ModelError> {
        Corner::build(self, side, rig)
    }
}

impl CornerTemplate for MacPherson {
    fn add_corner(&self, model: &mut Model, side: Side, prefix: &str) -> Result<CornerParts, ModelError> {
        let h = &self.hardpoints;
        check_spring(&self.spring, (h.top_mount - h.strut_lower).norm())?;
        check_arm_mounts("lower_arm_mounts", &self.lower_arm_mounts)?;
        check_connection("top_mount", &self.top_mount)?;
        check_connection("tie_rod", &self.tie_rod)?;
        if self.strut == StrutJoint::Cylindrical && self.top_mount == Connection::Ideal {
            return Err(ModelError::OutOfRange {
                item: "strut".into(),
                why: "strut is \"cylindrical\" but top_mount is \"ideal\": nothing would hold the strut rod's spin; \
                      give top_mount a bushing (its torsion holds the rod) or make the strut \"translational\""
                    .into(),
            });
        }
        // The hardpoints' reach, the steering axis and the tie rod's lever are the general builder's checks,
        // which name the same hardpoints.
        self.expand().add_corner(model, side, prefix)
    }
}

impl DoubleWishbone {
    /// Builds the corner on `side`, held as `rig` says (see [`Corner::build`]).
    pub fn build(&self, side: Side, rig: Rig) -> Result<Corner, ModelError> {
        Corner::build(self, side, rig)
    }
}

impl CornerTemplate for DoubleWishbone {
    fn add_corner(&self, model: &mut Model, side: Side, prefix: &str) -> Result<CornerParts, ModelError> {
        let h = &self.hardpoints;
        check_spring(&self.spring, (h.spring_arm - h.spring_chassis).norm())?;
        check_arm_mounts("upper_arm_mounts", &self.upper_arm_mounts)?;
        check_arm_mounts("lower_arm_mounts", &self.lower_arm_mounts)?;
        check_connection("tie_rod", &self.tie_rod)?;
        // The hardpoints' reach, the steering axis and the tie rod's lever are the general builder's checks,
        // which name the same hardpoints.
        self.expand().add_corner(model, side, prefix)
    }
}

impl Template {
    /// Builds the corner (see [`Corner::build`]).
    pub fn build(&self, side: Side, rig: Rig) -> Result<Corner, ModelError> {
        Corner::build(self, side, rig)
    }
}

impl CornerTemplate for Template {
    fn add_corner(&self, model: &mut Model, side: Side, prefix: &str) -> Result<CornerParts, ModelError> {
        match self {
            Template::DoubleWishbone(t) => t.add_corner(model, side, prefix),
            Template::MacPherson(t) => t.add_corner(model, side, prefix),
            Template::General(g) => g.add_corner(model, side, prefix),
        }
    }

    fn builds_on_axle_only(&self) -> bool {
        matches!(self, Template::General(g) if g.builds_on_axle_only())
    }

    fn add_axle_bodies(&self, model: &mut Model) -> Result<(), ModelError> {
        match self {
            Template::General(g) => g.add_axle_bodies(model),
            _ => Ok(()),
        }
    }

    fn add_cross_axle(
        &self,
        model: &mut Model,
        left: (&str, &CornerParts),
        right: (&str, &CornerParts),
    ) -> Result<CrossAxle, ModelError> {
        match self {
            Template::General(g) => g.add_cross_axle(model, left, right),
            _ => Ok(Default::default()),
        }
    }
}
