//! MacPherson strut template: upright with wheel and strut tube, strut rod sliding in it, top mount on the
//! chassis, lower control arm, tie rod, coil spring from the top mount to the spring seat on the strut.

use crate::description::connection::{ArmMounts, Connection, SpringSpec};
use crate::description::general::{Axis, BushingDef, GeneralCorner, Place, CHASSIS};
use crate::description::layout::{named_pair, Layout};
use crate::description::limits::default_loaded_radius;
use elastokin_core::JointKind;
use elastokin_core::Vec3;
use serde::{Deserialize, Serialize};

/// Hardpoints of a left MacPherson corner (ISO 8855, metres).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MacPhersonHardpoints {
    /// Wheel centre; the spin axis is +y at design.
    #[serde(deserialize_with = "crate::description::side::point")]
    pub wheel_centre: Vec3,
    /// Lower ball joint (arm – upright).
    #[serde(deserialize_with = "crate::description::side::point")]
    pub lower_ball_joint: Vec3,
    /// Lower arm front pivot on the chassis.
    #[serde(deserialize_with = "crate::description::side::point")]
    pub lower_arm_front: Vec3,
    /// Lower arm rear pivot on the chassis.
    #[serde(deserialize_with = "crate::description::side::point")]
    pub lower_arm_rear: Vec3,
    /// Tie rod outer end (upright).
    #[serde(deserialize_with = "crate::description::side::point")]
    pub tie_rod_outer: Vec3,
    /// Tie rod inner end (rack).
    #[serde(deserialize_with = "crate::description::side::point")]
    pub tie_rod_inner: Vec3,
    /// Strut lower point and spring seat on the upright; the strut axis runs from here to the top mount.
    #[serde(deserialize_with = "crate::description::side::point")]
    pub strut_lower: Vec3,
    /// Strut top mount on the chassis.
    #[serde(deserialize_with = "crate::description::side::point")]
    pub top_mount: Vec3,
}

impl MacPhersonHardpoints {
    /// Every hardpoint with its model-file name, the wheel centre first.
    pub fn named(&self) -> Vec<(&'static str, Vec3)> {
        vec![
            ("wheel_centre", self.wheel_centre),
            ("lower_ball_joint", self.lower_ball_joint),
            ("lower_arm_front", self.lower_arm_front),
            ("lower_arm_rear", self.lower_arm_rear),
            ("tie_rod_outer", self.tie_rod_outer),
            ("tie_rod_inner", self.tie_rod_inner),
            ("strut_lower", self.strut_lower),
            ("top_mount", self.top_mount),
        ]
    }

    /// The generic set: the hardpoints of Project Chrono's generic vehicle.
    pub fn generic() -> Self {
        MacPhersonHardpoints {
            wheel_centre: Vec3::new(-0.040, 1.100, -0.026),
            lower_ball_joint: Vec3::new(-0.02165371, 0.94057703, -0.17402826),
            lower_arm_front: Vec3::new(0.220, 0.520, -0.156),
            lower_arm_rear: Vec3::new(-0.300, 0.507, -0.137),
            tie_rod_outer: Vec3::new(-0.2373756, 0.89495045, -0.01605418),
            tie_rod_inner: Vec3::new(-0.300, 0.520, -0.059),
            strut_lower: Vec3::new(-0.07402507, 0.8532915, 0.2484536),
            top_mount: Vec3::new(-0.115, 0.785, 0.579),
        }
    }
}

/// How the strut rod slides in the strut tube.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StrutJoint {
    /// The rod slides without turning: it steers with the upright, so a top-mount bushing's torsion
    /// resists steering.
    #[default]
    Translational,
    /// The rod slides and turns in the tube: the upright steers about it, and the top-mount bushing's
    /// torsion holds the rod's spin (so the top mount must be a bushing).
    Cylindrical,
}

fn is_default_strut(strut: &StrutJoint) -> bool {
    *strut == StrutJoint::default()
}

/// A MacPherson corner: hardpoints, mounts and spring.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MacPherson {
    /// Hardpoints of the left corner.
    pub hardpoints: MacPhersonHardpoints,
    /// Lower arm to chassis: an ideal revolute about the pivot axis, or a bushing at each pivot (the same,
    /// or its own at each end).
    pub lower_arm_mounts: ArmMounts,
    /// Strut rod to chassis: an ideal ball joint, or a top-mount bushing whose axis is the strut axis.
    pub top_mount: Connection,
    /// The strut's sliding joint (default translational).
    #[serde(default, skip_serializing_if = "is_default_strut")]
    pub strut: StrutJoint,
    /// Coil spring from the top mount to the spring seat at the strut lower point.
    pub spring: SpringSpec,
    /// Tie rod: a distance constraint (`"ideal"`, the default), or a rod with a bushing at each end.
    #[serde(default)]
    pub tie_rod: Connection,
    /// Loaded tyre radius (m): the contact patch sits this far below the wheel centre at design.
    #[serde(default = "default_loaded_radius")]
    pub loaded_radius: f64,
}

impl MacPherson {
    /// The corner in the general form: the bodies `upright`, `strut rod` and `lower arm`, the joints
    /// and bushings named as in its results, the spring, and the corner description.
    pub fn expand(&self) -> GeneralCorner {
        let h = &self.hardpoints;
        let mut g = GeneralCorner::template(
            h.named(),
            vec![
                ("upright", Place::named("wheel_centre")),
                ("strut rod", Place::At((h.strut_lower + h.top_mount) / 2.0)),
                ("lower arm", Place::named("lower_ball_joint")),
            ],
            self.loaded_radius,
            [("upright", "lower_ball_joint"), ("strut rod", "top_mount")],
            self.tie_rod,
            (&self.spring, [CHASSIS, "upright"], ["top_mount", "strut_lower"]),
        );
        g.push_arm_mounts(&self.lower_arm_mounts, "lower arm", "lower_arm_front", "lower_arm_rear");
        g.push_joint("lower ball joint", JointKind::Spherical, ["lower arm", "upright"], "lower_ball_joint", None);
        let strut_axis = Axis::through("strut_lower", "top_mount");
        let strut = match self.strut {
            StrutJoint::Translational => JointKind::Translational,
            StrutJoint::Cylindrical => JointKind::Cylindrical,
        };
        g.push_joint("strut", strut, ["upright", "strut rod"], "strut_lower", Some(strut_axis.clone()));
        match self.top_mount {
            Connection::Ideal => {
                g.push_joint("top mount", JointKind::Spherical, [CHASSIS, "strut rod"], "top_mount", None)
            }
            Connection::Bushing(r) => g.bushings.push(BushingDef::cylindrical(
                "top mount",
                [CHASSIS, "strut rod"],
                Place::named("top_mount"),
                strut_axis,
                &r,
            )),
        }
        g
    }
}

impl From<&MacPherson> for GeneralCorner {
    fn from(template: &MacPherson) -> GeneralCorner {
        template.expand()
    }
}

impl MacPherson {
    /// Where its parts are, by hardpoint name (see [`Layout`]).
    pub(crate) fn layout(&self) -> Layout {
        Layout {
            wheel_centre: "wheel_centre".into(),
            steering_axis: named_pair(["lower_ball_joint", "top_mount"]),
            tie_rod: named_pair(["tie_rod_inner", "tie_rod_outer"]),
            arms: vec![("lower arm", ["lower_arm_front", "lower_arm_rear", "lower_ball_joint"], self.lower_arm_mounts)],
            spring: Some((
                ["top_mount".into(), "strut_lower".into()],
                "upright".into(),
                "the strut should lean with the wheel's travel: check 'top_mount', 'strut_lower' and the lower arm"
                    .into(),
            )),
        }
    }
}
