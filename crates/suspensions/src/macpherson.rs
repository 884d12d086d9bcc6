//! MacPherson strut template: upright with wheel and strut tube, strut rod sliding in it, top mount on the
//! chassis, lower control arm, tie rod, coil spring from the top mount to the spring seat on the strut.

use crate::connection::{arm_mounts, axial_bushing, Connection, SpringSpec};
use crate::corner::{
    check_connection, check_hardpoints, check_spring, check_steering_arm, check_steering_axis, part_name, Corner,
    CornerParts, CornerTemplate, Rig, TieRod, Wheel,
};
use crate::hardpoint::Side;
use elastokin_core::{BodyRef, JointSpec, Model, ModelError, Pose, Vec3};
use elastokin_elements::CoilSpring;
use serde::{Deserialize, Serialize};

/// Hardpoints of a left MacPherson corner (ISO 8855, metres).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MacPhersonHardpoints {
    /// Wheel centre; the spin axis is +y at design.
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub wheel_centre: Vec3,
    /// Lower ball joint (arm – upright).
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub lower_ball_joint: Vec3,
    /// Lower arm front pivot on the chassis.
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub lower_arm_front: Vec3,
    /// Lower arm rear pivot on the chassis.
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub lower_arm_rear: Vec3,
    /// Tie rod outer end (upright).
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub tie_rod_outer: Vec3,
    /// Tie rod inner end (rack).
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub tie_rod_inner: Vec3,
    /// Strut lower point and spring seat on the upright; the strut axis runs from here to the top mount.
    #[serde(deserialize_with = "crate::hardpoint::point")]
    pub strut_lower: Vec3,
    /// Strut top mount on the chassis.
    #[serde(deserialize_with = "crate::hardpoint::point")]
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

    /// The generic set of `shared/data/hardpoints.md` (Project Chrono's generic vehicle).
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

/// A MacPherson corner: hardpoints, mounts and spring.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MacPherson {
    /// Hardpoints of the left corner.
    pub hardpoints: MacPhersonHardpoints,
    /// Lower arm to chassis: ideal revolute about the pivot axis, or a bushing at each pivot.
    pub lower_arm_mounts: Connection,
    /// Strut rod to chassis: an ideal ball joint (the rod cannot spin: it slides in the strut tube on a
    /// translational joint), or a top-mount bushing whose axis is the strut axis.
    pub top_mount: Connection,
    /// Coil spring from the top mount to the spring seat at the strut lower point.
    pub spring: SpringSpec,
    /// Tie rod: a distance constraint (`"ideal"`, the default), or a rod with a bushing at each end.
    #[serde(default)]
    pub tie_rod: Connection,
    /// Loaded tyre radius (m): the contact patch sits this far below the wheel centre at design.
    #[serde(default = "crate::corner::default_loaded_radius")]
    pub loaded_radius: f64,
}

impl MacPherson {
    /// Builds the corner on `side`, held as `rig` says (see [`Corner::build`]).
    pub fn build(&self, side: Side, rig: Rig) -> Result<Corner, ModelError> {
        Corner::build(self, side, rig)
    }
}

impl CornerTemplate for MacPherson {
    fn add_corner(&self, model: &mut Model, side: Side, prefix: &str) -> Result<CornerParts, ModelError> {
        let h = &self.hardpoints;
        check_hardpoints(&h.named())?;
        check_spring(&self.spring, (h.top_mount - h.strut_lower).norm())?;
        check_connection("lower_arm_mounts", &self.lower_arm_mounts)?;
        check_connection("top_mount", &self.top_mount)?;
        check_connection("tie_rod", &self.tie_rod)?;
        check_steering_axis((h.lower_ball_joint, h.top_mount), ("lower_ball_joint", "top_mount"))?;
        check_steering_arm(
            (h.lower_ball_joint, h.top_mount),
            ("lower_ball_joint", "top_mount"),
            h.tie_rod_inner,
            h.tie_rod_outer,
        )?;
        let p = |v: Vec3| side.place(v);
        let n = |name: &str| part_name(prefix, name);
        let (upright, _) = Wheel::add_upright(model, side, prefix, h.wheel_centre, self.loaded_radius)?;
        let (lower_pt, top) = (p(h.strut_lower), p(h.top_mount));
        let rod = model.add_body(&n("strut rod"), Pose::at((lower_pt + top) / 2.0))?;
        let arm = model.add_body(&n("lower arm"), Pose::at(p(h.lower_ball_joint)))?;
        let (lf, lr) = (p(h.lower_arm_front), p(h.lower_arm_rear));
        arm_mounts(model, &n("lower arm"), arm.into(), lf, lr, self.lower_arm_mounts)?;
        model.add_joint(JointSpec::spherical(&n("lower ball joint"), arm, upright, p(h.lower_ball_joint)))?;
        let axis = top - lower_pt;
        model.add_joint(JointSpec::translational(&n("strut"), upright, rod, lower_pt, axis))?;
        match self.top_mount {
            Connection::Ideal => {
                model.add_joint(JointSpec::spherical(&n("top mount"), BodyRef::Ground, rod, top))?;
            }
            Connection::Bushing(r) => {
                model.add_element(axial_bushing(&n("top mount"), BodyRef::Ground, rod.into(), top, axis, r)?)?;
            }
        }
        model.add_element(CoilSpring::with_design_force(
            &n("spring"),
            BodyRef::Ground,
            top,
            upright.into(),
            lower_pt,
            self.spring.rate,
            self.spring.design_force,
        )?)?;
        let steering_axis = [(upright.into(), p(h.lower_ball_joint)), (rod.into(), top)];
        Ok(CornerParts {
            wheel: Wheel::new(model, side, upright, self.loaded_radius, steering_axis),
            tie_rod: TieRod { inner: p(h.tie_rod_inner), outer: p(h.tie_rod_outer), connection: self.tie_rod },
        })
    }
}
