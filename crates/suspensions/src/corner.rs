//! A built suspension corner and its wheel characteristics.

use crate::hardpoint::Side;
use elastokin_core::{BodyId, BodyRef, ElementId, JointSpec, Model, ModelError, Pose, Vec3};
use elastokin_elements::{PointForce, PointTorque};

/// How the corner is held on the K&C rig, and what the load parameter `t` drives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rig {
    /// Wheel-centre height driven, `t` = travel in metres (bump positive); rack fixed.
    WheelTravel,
    /// Rack driven, `t` = rack travel in metres (towards +y); wheel-centre height held.
    Steering,
    /// Wheel-centre height held at design, rack fixed: for forces with the height held as a rig does.
    HeightHeld,
    /// No drivers, rack fixed: the wheel rides on the spring (force sweeps with the wheel free).
    Free,
}

/// Adds the tie rod, the rack (a body on a lateral slide when steering) and the rig's drivers.
pub(crate) fn mount_rig(
    model: &mut Model,
    rig: Rig,
    upright: BodyId,
    wheel_centre: Vec3,
    tie_rod_inner: Vec3,
    tie_rod_outer: Vec3,
) -> Result<(), ModelError> {
    let inner_body: BodyRef = if rig == Rig::Steering {
        let rack = model.add_body("rack", Pose::at(tie_rod_inner))?;
        model.add_joint(JointSpec::translational("rack slide", BodyRef::Ground, rack, tie_rod_inner, Vec3::y()))?;
        model.add_joint(JointSpec::travel_driver(
            "rack travel",
            BodyRef::Ground,
            rack,
            tie_rod_inner,
            Vec3::y(),
            1.0,
        ))?;
        rack.into()
    } else {
        BodyRef::Ground
    };
    model.add_joint(JointSpec::distance("tie rod", inner_body, upright, tie_rod_inner, tie_rod_outer))?;
    let travel = match rig {
        Rig::WheelTravel => Some(1.0),
        Rig::Steering | Rig::HeightHeld => Some(0.0),
        Rig::Free => None,
    };
    if let Some(travel) = travel {
        model.add_joint(JointSpec::point_driver("wheel travel", upright, wheel_centre, Vec3::z(), travel))?;
    }
    Ok(())
}

/// A suspension corner ready to solve: its model and where its wheel is.
#[derive(Debug)]
pub struct Corner {
    /// The multibody model.
    pub model: Model,
    /// Which side it was built for.
    pub side: Side,
    /// How it is held.
    pub rig: Rig,
    /// The upright (knuckle with the wheel).
    pub upright: BodyId,
    /// Wheel centre at design (global).
    pub wheel_centre: Vec3,
    /// Wheel centre as a local point of the upright.
    pub wheel_centre_local: Vec3,
    /// Outward spin axis as a local direction of the upright.
    pub spin_axis_local: Vec3,
    /// Contact patch centre at design (global): below the wheel centre by the loaded radius.
    pub contact_patch: Vec3,
    /// The steering axis: its lower and upper points as body-fixed points (lower ball joint on the upright;
    /// upper ball joint, or the top mount on the strut rod).
    pub steering_axis: [(BodyRef, Vec3); 2],
}

/// Steering-axis geometry at one configuration (angles in radians, lengths in metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteeringGeometry {
    /// Caster: the axis leans back at the top (positive).
    pub caster: f64,
    /// Kingpin inclination: the axis leans inboard at the top (positive).
    pub kingpin_inclination: f64,
    /// Scrub radius at the ground: positive when the axis meets the ground inboard of the contact patch.
    pub scrub_radius: f64,
    /// Mechanical (caster) trail at the ground: positive when the axis meets the ground ahead of the
    /// contact patch.
    pub mechanical_trail: f64,
    /// Kingpin offset at wheel-centre height: lateral distance from the axis to the wheel centre,
    /// positive when the axis is inboard.
    pub kingpin_offset: f64,
    /// Contact patch centre: the lowest point of the wheel-plane circle of the loaded radius.
    pub contact_patch: Vec3,
}

/// Loaded tyre radius when a model file does not give one (m); `shared/data/hardpoints.md` quotes ~0.30.
pub fn default_loaded_radius() -> f64 {
    0.30
}

/// Wheel position and orientation at one configuration (angles in radians, ISO 8855 / SAE J670 signs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelAttitude {
    /// Toe, toe-in positive.
    pub toe: f64,
    /// Camber, top of the wheel outward positive.
    pub camber: f64,
    /// Wheel-centre position (global).
    pub wheel_centre: Vec3,
}

impl Corner {
    /// Starts a template's model: checks the loaded radius and adds the upright with its reference point
    /// at the wheel centre (axes global at design). Returns the model, the upright and the wheel centre.
    pub(crate) fn start(
        side: Side,
        left_wheel_centre: Vec3,
        loaded_radius: f64,
    ) -> Result<(Model, BodyId, Vec3), ModelError> {
        if !(loaded_radius.is_finite() && loaded_radius > 0.0) {
            return Err(ModelError::NotPositive {
                item: "suspension".into(),
                what: "loaded radius",
                value: loaded_radius,
            });
        }
        let mut model = Model::new();
        let wc = side.place(left_wheel_centre);
        let upright = model.add_body("upright", Pose::at(wc))?;
        Ok((model, upright, wc))
    }

    /// Completes a template's corner: the spin axis is outward (±y) at design, the contact patch a loaded
    /// radius below the wheel centre; `steering_axis` holds global design points with their bodies.
    pub(crate) fn finish(
        model: Model,
        side: Side,
        rig: Rig,
        upright: BodyId,
        loaded_radius: f64,
        steering_axis: [(BodyRef, Vec3); 2],
    ) -> Corner {
        let wheel_centre = model.bodies()[upright.0].design_pose.position;
        let local = |(body, point): (BodyRef, Vec3)| {
            let pose = match body {
                BodyRef::Ground => Pose::IDENTITY,
                BodyRef::Body(b) => model.bodies()[b.0].design_pose,
            };
            (body, pose.to_local_point(&point))
        };
        let steering_axis = [local(steering_axis[0]), local(steering_axis[1])];
        Corner {
            side,
            rig,
            upright,
            wheel_centre,
            wheel_centre_local: Vec3::zeros(),
            spin_axis_local: Vec3::new(0.0, side.sign(), 0.0),
            contact_patch: wheel_centre - Vec3::new(0.0, 0.0, loaded_radius),
            steering_axis,
            model,
        }
    }

    /// Adds a world-fixed force `force · t` (N per unit load parameter) at the global design point `point`
    /// of the upright: a contact-patch or wheel-centre load of a K&C test.
    pub fn add_wheel_force(&mut self, name: &str, point: Vec3, force: Vec3) -> Result<ElementId, ModelError> {
        self.model.add_element(PointForce::new(name, self.upright.into(), point, force)?)
    }

    /// Adds a world-fixed torque `torque · t` (N·m per unit load parameter) on the upright.
    pub fn add_wheel_torque(&mut self, name: &str, torque: Vec3) -> Result<ElementId, ModelError> {
        self.model.add_element(PointTorque::new(name, self.upright.into(), torque)?)
    }

    /// Toe, camber and wheel centre at the given poses.
    ///
    /// With `a` the outward spin axis and `s` = +1 left, −1 right: toe = atan2(aₓ, s·a_y) (a toe-in left
    /// wheel turns its spin axis forward), camber = atan2(−a_z, √(aₓ² + a_y²)) (top outward tips the outward
    /// axis down).
    pub fn attitude(&self, poses: &[Pose]) -> WheelAttitude {
        let pose = poses[self.upright.0];
        let a = pose.direction(&self.spin_axis_local);
        WheelAttitude {
            toe: a.x.atan2(self.side.sign() * a.y),
            camber: (-a.z).atan2((a.x * a.x + a.y * a.y).sqrt()),
            wheel_centre: pose.point(&self.wheel_centre_local),
        }
    }

    /// Caster, kingpin inclination, scrub radius, trail and kingpin offset at the given poses.
    ///
    /// With the axis `u` from its lower to its upper point and `s` = +1 left, −1 right: caster =
    /// atan2(−uₓ, u_z), KPI = atan2(−s·u_y, u_z). The contact patch is the wheel-plane point a loaded
    /// radius below the wheel centre, the ground the horizontal plane through it, and `G` the point where
    /// the axis meets that plane: scrub = s·(P_y − G_y), trail = Gₓ − Pₓ; the kingpin offset is
    /// s·(W_y − A_y) with `A` the axis point at wheel-centre height `W`.
    pub fn steering_geometry(&self, poses: &[Pose]) -> SteeringGeometry {
        let [(lb, ll), (ub, ul)] = self.steering_axis;
        let lower = lb.pose(poses).point(&ll);
        let upper = ub.pose(poses).point(&ul);
        let u = upper - lower;
        let s = self.side.sign();
        let pose = poses[self.upright.0];
        let a = pose.direction(&self.spin_axis_local);
        let wc = pose.point(&self.wheel_centre_local);
        // Downward direction in the wheel plane.
        let up_in_plane = Vec3::z() - a * a.z;
        let down = -up_in_plane / up_in_plane.norm();
        let radius = (self.wheel_centre - self.contact_patch).norm();
        let patch = wc + down * radius;
        let at_height = |z: f64| lower + u * ((z - lower.z) / u.z);
        let g = at_height(patch.z);
        let w = at_height(wc.z);
        SteeringGeometry {
            caster: (-u.x).atan2(u.z),
            kingpin_inclination: (-s * u.y).atan2(u.z),
            scrub_radius: s * (patch.y - g.y),
            mechanical_trail: g.x - patch.x,
            kingpin_offset: s * (wc.y - w.y),
            contact_patch: patch,
        }
    }
}
