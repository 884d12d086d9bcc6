//! Double-wishbone template: upright with wheel, upper and lower arms on the chassis, tie rod, coil spring
//! on the lower arm.

use crate::connection::{ArmMounts, Connection, SpringSpec};
use crate::corner::{check_arm_mounts, check_connection, check_spring, Corner, CornerParts, CornerTemplate, Rig};
use crate::general::{GeneralCorner, Place, CHASSIS};
use crate::hardpoint::Side;
use elastokin_core::JointKind;
use elastokin_core::{Model, ModelError, Vec3};
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
    #[serde(default = "crate::corner::default_loaded_radius")]
    pub loaded_radius: f64,
}

impl DoubleWishbone {
    /// Builds the corner on `side`, held as `rig` says (see [`Corner::build`]).
    pub fn build(&self, side: Side, rig: Rig) -> Result<Corner, ModelError> {
        Corner::build(self, side, rig)
    }

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
        self.upper_arm_mounts.expand("upper arm", "upper_arm_front", "upper_arm_rear", &mut g);
        self.lower_arm_mounts.expand("lower arm", "lower_arm_front", "lower_arm_rear", &mut g);
        for arm in ["upper", "lower"] {
            let (name, joint) = (format!("{arm} arm"), format!("{arm} ball joint"));
            g.push_joint(&joint, JointKind::Spherical, [&name, "upright"], &format!("{arm}_ball_joint"), None);
        }
        g
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
