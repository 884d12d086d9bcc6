//! The templates built: each checks what only it says (its spring, its mounts, a strut that cannot spin)
//! and then builds its expansion into the general form, by the one builder.

use crate::assembly::corner::Corner;
use crate::assembly::rig::Rig;
use crate::assembly::template::{CornerParts, CornerTemplate, CrossAxle};
use crate::description::limits::{check_arm_mounts, check_connection, check_spring};
use crate::description::{Connection, DoubleWishbone, MacPherson, Side, StrutJoint, Template, TwistBeam};
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

impl TwistBeam {
    /// What only the template says, checked: the spring, the pivots, the static toe and camber, and that
    /// the cross member meets each arm between its pivot and its end, on the car's own side.
    fn check(&self) -> Result<(), ModelError> {
        let h = &self.hardpoints;
        check_spring(&self.spring, (h.spring_seat - h.spring_chassis).norm())?;
        check_connection("pivots", &self.pivots)?;
        for (key, angle) in [("toe", self.toe), ("camber", self.camber)] {
            if !(angle.is_finite() && angle.abs() <= 10.0) {
                return Err(ModelError::OutOfRange {
                    item: key.into(),
                    why: format!("give the static {key} in degrees, within ±10, got {angle}"),
                });
            }
        }
        let arm = h.arm_end - h.pivot;
        if arm.norm() < 0.05 {
            return Err(ModelError::OutOfRange {
                item: "hardpoints.arm_end".into(),
                why: format!(
                    "the arm from 'pivot' to 'arm_end' is {:.1} mm long: put its end at the wheel carrier, behind \
                     the pivot",
                    1e3 * arm.norm()
                ),
            });
        }
        let along = (h.junction - h.pivot).dot(&arm) / arm.norm_squared();
        let off = (h.junction - h.pivot - arm * along).norm();
        if !(along > 0.0 && along < 1.0 && off <= 0.25 * arm.norm()) {
            return Err(ModelError::OutOfRange {
                item: "hardpoints.junction".into(),
                why: format!(
                    "the cross member does not meet the arm: 'junction' lies {:.0} % of the way from 'pivot' to \
                     'arm_end' and {:.0} mm off that line; put it on the arm, between its pivot and its end",
                    100.0 * along,
                    1e3 * off
                ),
            });
        }
        if h.junction.y < 0.05 {
            return Err(ModelError::OutOfRange {
                item: "hardpoints.junction".into(),
                why: format!(
                    "the cross member would run from y = {:.3} m to its mirror image: give the left side's junction, \
                     at least 50 mm left of the centre plane",
                    h.junction.y
                ),
            });
        }
        Ok(())
    }

    /// Builds the axle's corner on `side`, held as `rig` says (see [`Corner::build`]): the whole axle.
    pub fn build(&self, side: Side, rig: Rig) -> Result<Corner, ModelError> {
        Corner::build(self, side, rig)
    }
}

impl CornerTemplate for TwistBeam {
    fn add_corner(&self, model: &mut Model, side: Side, prefix: &str) -> Result<CornerParts, ModelError> {
        self.check()?;
        self.expand().add_corner(model, side, prefix)
    }

    fn builds_on_axle_only(&self) -> bool {
        true
    }

    fn add_axle_bodies(&self, model: &mut Model) -> Result<(), ModelError> {
        self.expand().add_axle_bodies(model)
    }

    fn add_cross_axle(
        &self,
        model: &mut Model,
        left: (&str, &CornerParts),
        right: (&str, &CornerParts),
    ) -> Result<CrossAxle, ModelError> {
        self.expand().add_cross_axle(model, left, right)
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
            Template::TwistBeam(t) => t.add_corner(model, side, prefix),
            Template::General(g) => g.add_corner(model, side, prefix),
        }
    }

    fn builds_on_axle_only(&self) -> bool {
        match self {
            Template::TwistBeam(t) => t.builds_on_axle_only(),
            Template::General(g) => g.builds_on_axle_only(),
            _ => false,
        }
    }

    fn add_axle_bodies(&self, model: &mut Model) -> Result<(), ModelError> {
        match self {
            Template::TwistBeam(t) => t.add_axle_bodies(model),
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
            Template::TwistBeam(t) => t.add_cross_axle(model, left, right),
            Template::General(g) => g.add_cross_axle(model, left, right),
            _ => Ok(Default::default()),
        }
    }
}
