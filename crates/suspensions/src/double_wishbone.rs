//! Double-wishbone template: upright with wheel, upper and lower arms on the chassis, tie rod, coil spring
//! on the lower arm.

use crate::connection::{arm_mounts, Connection, SpringSpec};
use crate::corner::{
    check_connection, check_hardpoints, check_spring, check_steering_arm, check_steering_axis, part_name, Corner,
    CornerParts, CornerTemplate, Rig, TieRod, Wheel,
};
use crate::hardpoint::Side;
use elastokin_core::{BodyRef, JointSpec, Model, ModelError, Pose, Vec3};
use elastokin_elements::CoilSpring;
use serde::{Deserialize, Serialize};

/// Hardpoints of a left double-wishbone corner (ISO 8855, metres).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DoubleWishboneHardpoints {
    /// Wheel centre; the spin axis is +y at design.
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub wheel_centre: Vec3,
    /// Upper ball joint (upper arm – upright).
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub upper_ball_joint: Vec3,
    /// Upper arm front pivot on the chassis.
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub upper_arm_front: Vec3,
    /// Upper arm rear pivot on the chassis.
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub upper_arm_rear: Vec3,
    /// Lower ball joint (lower arm – upright).
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub lower_ball_joint: Vec3,
    /// Lower arm front pivot on the chassis.
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub lower_arm_front: Vec3,
    /// Lower arm rear pivot on the chassis.
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub lower_arm_rear: Vec3,
    /// Tie rod inner end (rack, fixed to the chassis when not steering).
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub tie_rod_inner: Vec3,
    /// Tie rod outer end (upright).
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub tie_rod_outer: Vec3,
    /// Spring seat on the chassis.
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub spring_chassis: Vec3,
    /// Spring seat on the lower arm.
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub spring_arm: Vec3,
}

impl DoubleWishboneHardpoints {
    /// Every hardpoint with its model-file name, the wheel centre first.
    pub fn named(&self) -> Vec<(&'static str, Vec3)> {
        vec![
            ("wheel_centre", self.wheel_centre),
            ("upper_ball_joint", self.upper_ball_joint),
            ("upper_arm_front", self.upper_arm_front),
            ("upper_arm_rear", self.upper_arm_rear),
            ("lower_ball_joint", self.lower_ball_joint),
            ("lower_arm_front", self.lower_arm_front),
            ("lower_arm_rear", self.lower_arm_rear),
            ("tie_rod_inner", self.tie_rod_inner),
            ("tie_rod_outer", self.tie_rod_outer),
            ("spring_chassis", self.spring_chassis),
            ("spring_arm", self.spring_arm),
        ]
    }

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
    /// Tie rod: a distance constraint (`"ideal"`, the default), or a rod with a bushing at each end.
    #[serde(default)]
    pub tie_rod: Connection,
    /// Loaded tyre radius (m): the contact patch sits this far below the wheel centre at design.
    #[serde(default = "crate::corner::default_loaded_radius")]
    pub loaded_radius: f64,
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
        check_hardpoints(&h.named())?;
        check_spring(&self.spring, (h.spring_arm - h.spring_chassis).norm())?;
        check_connection("upper_arm_mounts", &self.upper_arm_mounts)?;
        check_connection("lower_arm_mounts", &self.lower_arm_mounts)?;
        check_connection("tie_rod", &self.tie_rod)?;
        check_steering_axis((h.lower_ball_joint, h.upper_ball_joint), ("lower_ball_joint", "upper_ball_joint"))?;
        check_steering_arm(
            (h.lower_ball_joint, h.upper_ball_joint),
            ("lower_ball_joint", "upper_ball_joint"),
            h.tie_rod_inner,
            h.tie_rod_outer,
        )?;
        let p = |v: Vec3| side.place(v);
        let n = |name: &str| part_name(prefix, name);
        let (upright, _) = Wheel::add_upright(model, side, prefix, h.wheel_centre, self.loaded_radius)?;
        let upper = model.add_body(&n("upper arm"), Pose::at(p(h.upper_ball_joint)))?;
        let lower = model.add_body(&n("lower arm"), Pose::at(p(h.lower_ball_joint)))?;
        let (uf, ur) = (p(h.upper_arm_front), p(h.upper_arm_rear));
        arm_mounts(model, &n("upper arm"), upper.into(), uf, ur, self.upper_arm_mounts)?;
        let (lf, lr) = (p(h.lower_arm_front), p(h.lower_arm_rear));
        arm_mounts(model, &n("lower arm"), lower.into(), lf, lr, self.lower_arm_mounts)?;
        model.add_joint(JointSpec::spherical(&n("upper ball joint"), upper, upright, p(h.upper_ball_joint)))?;
        model.add_joint(JointSpec::spherical(&n("lower ball joint"), lower, upright, p(h.lower_ball_joint)))?;
        model.add_element(CoilSpring::with_design_force(
            &n("spring"),
            BodyRef::Ground,
            p(h.spring_chassis),
            lower.into(),
            p(h.spring_arm),
            self.spring.rate,
            self.spring.design_force,
        )?)?;
        let steering_axis = [(upright.into(), p(h.lower_ball_joint)), (upright.into(), p(h.upper_ball_joint))];
        Ok(CornerParts {
            wheel: Wheel::new(model, side, upright, self.loaded_radius, steering_axis),
            tie_rod: TieRod { inner: p(h.tie_rod_inner), outer: p(h.tie_rod_outer), connection: self.tie_rod },
        })
    }
}
