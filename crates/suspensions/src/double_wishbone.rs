//! Double-wishbone template: upright with wheel, upper and lower arms on the chassis, tie rod, coil spring
//! on the lower arm.

use crate::connection::{arm_mounts, Connection, SpringSpec};
use crate::corner::{mount_rig, Corner, Rig};
use crate::hardpoint::Side;
use elastokin_core::{BodyRef, JointSpec, ModelError, Pose, Vec3};
use elastokin_elements::CoilSpring;
use serde::{Deserialize, Serialize};

/// Hardpoints of a left double-wishbone corner (ISO 8855, metres).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DoubleWishboneHardpoints {
    /// Wheel centre; the spin axis is +y at design.
    pub wheel_centre: Vec3,
    /// Upper ball joint (upper arm – upright).
    pub upper_ball_joint: Vec3,
    /// Upper arm front pivot on the chassis.
    pub upper_arm_front: Vec3,
    /// Upper arm rear pivot on the chassis.
    pub upper_arm_rear: Vec3,
    /// Lower ball joint (lower arm – upright).
    pub lower_ball_joint: Vec3,
    /// Lower arm front pivot on the chassis.
    pub lower_arm_front: Vec3,
    /// Lower arm rear pivot on the chassis.
    pub lower_arm_rear: Vec3,
    /// Tie rod inner end (rack, fixed to the chassis when not steering).
    pub tie_rod_inner: Vec3,
    /// Tie rod outer end (upright).
    pub tie_rod_outer: Vec3,
    /// Spring seat on the chassis.
    pub spring_chassis: Vec3,
    /// Spring seat on the lower arm.
    pub spring_arm: Vec3,
}

impl DoubleWishboneHardpoints {
    /// The generic set of `shared/data/hardpoints.md` (Project Chrono's generic vehicle).
    pub fn generic() -> Self {
        DoubleWishboneHardpoints {
            wheel_centre: Vec3::new(-0.040, 1.100, -0.026),
            upper_ball_joint: Vec3::new(-0.088, 0.808, 0.243),
            upper_arm_front: Vec3::new(-0.160, 0.539, 0.243),
            upper_arm_rear: Vec3::new(-0.339, 0.587, 0.249),
            lower_ball_joint: Vec3::new(-0.040, 0.898, -0.265),
            lower_arm_front: Vec3::new(0.199, 0.479, -0.206),
            lower_arm_rear: Vec3::new(-0.279, 0.539, -0.200),
            tie_rod_inner: Vec3::new(-0.279, 0.479, -0.026),
            tie_rod_outer: Vec3::new(-0.220, 0.898, -0.026),
            spring_chassis: Vec3::new(-0.064, 0.659, 0.094),
            spring_arm: Vec3::new(-0.040, 0.718, -0.206),
        }
    }
}

/// A double-wishbone corner: hardpoints, how each arm meets the chassis, and the spring.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DoubleWishbone {
    /// Hardpoints of the left corner.
    pub hardpoints: DoubleWishboneHardpoints,
    /// Upper arm to chassis: ideal revolute about the front–rear pivot axis, or a bushing at each pivot.
    pub upper_arm_mounts: Connection,
    /// Lower arm to chassis, likewise.
    pub lower_arm_mounts: Connection,
    /// Coil spring from the chassis seat to the lower arm seat.
    pub spring: SpringSpec,
    /// Loaded tyre radius (m): the contact patch sits this far below the wheel centre at design.
    #[serde(default = "crate::corner::default_loaded_radius")]
    pub loaded_radius: f64,
}

impl DoubleWishbone {
    /// Builds the corner on `side`, held as `rig` says.
    pub fn build(&self, side: Side, rig: Rig) -> Result<Corner, ModelError> {
        let h = &self.hardpoints;
        let p = |v: Vec3| side.place(v);
        let (mut model, upright, wc) = Corner::start(side, h.wheel_centre, self.loaded_radius)?;
        let upper = model.add_body("upper arm", Pose::at(p(h.upper_ball_joint)))?;
        let lower = model.add_body("lower arm", Pose::at(p(h.lower_ball_joint)))?;
        arm_mounts(
            &mut model,
            "upper arm",
            upper.into(),
            p(h.upper_arm_front),
            p(h.upper_arm_rear),
            self.upper_arm_mounts,
        )?;
        arm_mounts(
            &mut model,
            "lower arm",
            lower.into(),
            p(h.lower_arm_front),
            p(h.lower_arm_rear),
            self.lower_arm_mounts,
        )?;
        model.add_joint(JointSpec::spherical("upper ball joint", upper, upright, p(h.upper_ball_joint)))?;
        model.add_joint(JointSpec::spherical("lower ball joint", lower, upright, p(h.lower_ball_joint)))?;
        model.add_element(CoilSpring::with_design_force(
            "spring",
            BodyRef::Ground,
            p(h.spring_chassis),
            lower.into(),
            p(h.spring_arm),
            self.spring.rate,
            self.spring.design_force,
        )?)?;
        mount_rig(&mut model, rig, upright, wc, p(h.tie_rod_inner), p(h.tie_rod_outer))?;
        Ok(Corner::finish(
            model,
            side,
            rig,
            upright,
            self.loaded_radius,
            [(upright.into(), p(h.lower_ball_joint)), (upright.into(), p(h.upper_ball_joint))],
        ))
    }
}
