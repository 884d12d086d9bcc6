//! Double-wishbone template: upright with wheel, upper and lower arms on the chassis, tie rod, coil spring
//! on the lower arm.

use crate::description::connection::{ArmMounts, Connection, SpringSpec};
use crate::description::general::{GeneralCorner, Place, CHASSIS};
use crate::description::layout::{named_pair, Layout};
use crate::description::limits::default_loaded_radius;
use elastokin_core::JointKind;
use elastokin_core::Vec3;
use serde::{Deserialize, Serialize};

/// Hardpoints of a left double-wishbone corner (ISO 8855, metres).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DoubleWishboneHardpoints {
    /// Wheel centre; the spin axis is +y at design.
    #[serde(deserialize_with = "crate::description::side::point")]
    pub wheel_centre: Vec3,
    /// Upper ball joint (upper arm – upright).
    #[serde(deserialize_with = "crate::description::side::point")]
    pub upper_ball_joint: Vec3,
    /// Upper arm front pivot on the chassis.
    #[serde(deserialize_with = "crate::description::side::point")]
    pub upper_arm_front: Vec3,
    /// Upper arm rear pivot on the chassis.
    #[serde(deserialize_with = "crate::description::side::point")]
    pub upper_arm_rear: Vec3,
    /// Lower ball joint (lower arm – upright).
    #[serde(deserialize_with = "crate::description::side::point")]
    pub lower_ball_joint: Vec3,
    /// Lower arm front pivot on the chassis.
    #[serde(deserialize_with = "crate::description::side::point")]
    pub lower_arm_front: Vec3,
    /// Lower arm rear pivot on the chassis.
    #[serde(deserialize_with = "crate::description::side::point")]
    pub lower_arm_rear: Vec3,
    /// Tie rod inner end (rack, fixed to the chassis when not steering).
    #[serde(deserialize_with = "crate::description::side::point")]
    pub tie_rod_inner: Vec3,
    /// Tie rod outer end (upright).
    #[serde(deserialize_with = "crate::description::side::point")]
    pub tie_rod_outer: Vec3,
    /// Spring seat on the chassis.
    #[serde(deserialize_with = "crate::description::side::point")]
    pub spring_chassis: Vec3,
    /// Spring seat on the lower arm.
    #[serde(deserialize_with = "crate::description::side::point")]
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

    /// The generic set: the hardpoints of Project Chrono's generic vehicle.
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
    /// Upper arm to chassis: an ideal revolute about the front–rear pivot axis, or a bushing at each pivot
    /// (the same, or its own at each end).
    pub upper_arm_mounts: ArmMounts,
    /// Lower arm to chassis, likewise.
    pub lower_arm_mounts: ArmMounts,
    /// Coil spring from the chassis seat to the lower arm seat.
    pub spring: SpringSpec,
    /// Tie rod: a distance constraint (`"ideal"`, the default), or a rod with a bushing at each end.
    #[serde(default)]
    pub tie_rod: Connection,
    /// Loaded tyre radius (m): the contact patch sits this far below the wheel centre at design.
    #[serde(default = "default_loaded_radius")]
    pub loaded_radius: f64,
}

impl DoubleWishbone {
    /// The corner in the general form: the bodies `upright`, `upper arm` and `lower arm`, the joints and
    /// bushings named as in its results, the spring, and the corner description.
    pub fn expand(&self) -> GeneralCorner {
        let mut g = GeneralCorner::template(
            self.hardpoints.named(),
            vec![
                ("upright", Place::named("wheel_centre")),
                ("upper arm", Place::named("upper_ball_joint")),
                ("lower arm", Place::named("lower_ball_joint")),
            ],
            self.loaded_radius,
            [("upright", "lower_ball_joint"), ("upright", "upper_ball_joint")],
            self.tie_rod,
            (&self.spring, [CHASSIS, "lower arm"], ["spring_chassis", "spring_arm"]),
        );
        g.push_arm_mounts(&self.upper_arm_mounts, "upper arm", "upper_arm_front", "upper_arm_rear");
        g.push_arm_mounts(&self.lower_arm_mounts, "lower arm", "lower_arm_front", "lower_arm_rear");
        for arm in ["upper", "lower"] {
            let (name, joint) = (format!("{arm} arm"), format!("{arm} ball joint"));
            g.push_joint(&joint, JointKind::Spherical, [&name, "upright"], &format!("{arm}_ball_joint"), None);
        }
        g
    }
}

impl From<&DoubleWishbone> for GeneralCorner {
    fn from(template: &DoubleWishbone) -> GeneralCorner {
        template.expand()
    }
}

impl DoubleWishbone {
    /// Where its parts are, by hardpoint name (see [`Layout`]).
    pub(crate) fn layout(&self) -> Layout {
        Layout {
            wheel_centre: "wheel_centre".into(),
            steering_axis: named_pair(["lower_ball_joint", "upper_ball_joint"]),
            tie_rod: named_pair(["tie_rod_inner", "tie_rod_outer"]),
            arms: vec![
                ("upper arm", ["upper_arm_front", "upper_arm_rear", "upper_ball_joint"], self.upper_arm_mounts),
                ("lower arm", ["lower_arm_front", "lower_arm_rear", "lower_ball_joint"], self.lower_arm_mounts),
            ],
            spring: Some((
                ["spring_chassis".into(), "spring_arm".into()],
                "lower arm".into(),
                "move 'spring_arm' outboard along the arm".into(),
            )),
        }
    }
}
