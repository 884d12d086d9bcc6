//! The wheel of a built corner, and what is read from its poses: toe, camber, the wheel-centre position,
//! the steering-axis geometry (caster, kingpin inclination, scrub radius, trail, kingpin offset) and the
//! velocity of the upright's points. Nothing here builds or solves: a [`Wheel`] is placed once on a model
//! and then reads any configuration of it.

use crate::description::limits::MAX_LOADED_RADIUS;
use crate::description::{HalfShaft, Side};
use elastokin_core::{BodyId, BodyRef, Model, ModelError, Pose, Vec3, BODY_DOFS};

/// Where a wheel is in a model: its upright, and the wheel's points and axes on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wheel {
    /// Which side it is on.
    pub side: Side,
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

impl Wheel {
    /// The wheel on `upright`: its centre `wheel_centre` and outward `spin_axis` at design (global, this
    /// side), the contact patch a loaded radius from the centre down the wheel plane; `steering_axis`
    /// holds global design points with their bodies. Refuses a loaded radius that is not a length.
    pub fn on(
        model: &Model,
        side: Side,
        upright: BodyId,
        wheel_centre: Vec3,
        spin_axis: Vec3,
        loaded_radius: f64,
        steering_axis: [(BodyRef, Vec3); 2],
    ) -> Result<Wheel, ModelError> {
        if loaded_radius > MAX_LOADED_RADIUS {
            return Err(ModelError::OutOfRange {
                item: "suspension".into(),
                why: format!(
                    "loaded_radius must be a tyre radius in metres, at most {MAX_LOADED_RADIUS}, got {}",
                    crate::description::limits::plain(loaded_radius)
                ),
            });
        }
        if !(loaded_radius.is_finite() && loaded_radius > 0.0) {
            return Err(ModelError::NotPositive {
                item: "suspension".into(),
                what: "loaded_radius (m)",
                value: loaded_radius,
            });
        }
        let local = |(body, point): (BodyRef, Vec3)| {
            let pose = match body {
                BodyRef::Ground => Pose::IDENTITY,
                BodyRef::Body(b) => model.bodies()[b.0].design_pose,
            };
            (body, pose.to_local_point(&point))
        };
        let pose = model.bodies()[upright.0].design_pose;
        let a = spin_axis / spin_axis.norm();
        Ok(Wheel {
            side,
            upright,
            wheel_centre,
            wheel_centre_local: pose.to_local_point(&wheel_centre),
            spin_axis_local: pose.to_local_direction(&a),
            contact_patch: wheel_centre + down_the_wheel_plane(&a) * loaded_radius,
            steering_axis: [local(steering_axis[0]), local(steering_axis[1])],
        })
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

    /// Velocity of the upright's material point now at global `point`, for body velocities `rates`
    /// (`BODY_DOFS` per body: translation of the reference point, then angular velocity, as in Δq).
    pub fn point_velocity(&self, poses: &[Pose], rates: &[f64], point: Vec3) -> Vec3 {
        let base = self.upright.0 * BODY_DOFS;
        let v = Vec3::new(rates[base], rates[base + 1], rates[base + 2]);
        v + self.angular_velocity(rates).cross(&(point - poses[self.upright.0].position))
    }

    /// Angular velocity of the upright for body velocities `rates` (as [`Wheel::point_velocity`] takes).
    pub fn angular_velocity(&self, rates: &[f64]) -> Vec3 {
        let base = self.upright.0 * BODY_DOFS;
        Vec3::new(rates[base + 3], rates[base + 4], rates[base + 5])
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
        let down = down_the_wheel_plane(&a);
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

/// The downward direction in the plane of a wheel whose spin axis is `a` (unit).
fn down_the_wheel_plane(a: &Vec3) -> Vec3 {
    let up_in_plane = Vec3::z() - a * a.z;
    -up_in_plane / up_in_plane.norm()
}

/// A drive shaft's plunge and its joints' angles at a wheel position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShaftReading {
    /// Change of the distance between the joints' centres from design (m, longer +).
    pub plunge: f64,
    /// Angle between the shaft and the lateral axis, the differential's output (rad).
    pub inner_angle: f64,
    /// Angle between the shaft and the wheel's spin axis (rad).
    pub outer_angle: f64,
}

/// A corner's drive shaft as the wheel carries it: its inner joint's centre fixed, its outer joint's on
/// the spin axis `inboard` of the wheel centre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriveShaft {
    inner: Vec3,
    inboard: f64,
    length: f64,
}

/// Most an outer joint's centre may lie off the wheel's spin axis at design (m): a driven wheel's sits on it.
pub const SHAFT_OFF_AXIS: f64 = 1e-3;

impl DriveShaft {
    /// The shaft `shaft` (given for the left corner; mirrored in y for a right one) on `wheel` at its design
    /// `poses`; `Err` with the outer joint's distance from the spin axis (m) when over [`SHAFT_OFF_AXIS`].
    pub fn on(shaft: &HalfShaft, wheel: &Wheel, poses: &[Pose]) -> Result<DriveShaft, f64> {
        let (inner, outer) = (wheel.side.place(shaft.inner.into()), wheel.side.place(shaft.outer.into()));
        let attitude = wheel.attitude(poses);
        let axis = attitude.spin_axis(wheel.side);
        let inboard = (attitude.wheel_centre - outer).dot(&axis);
        let off = (attitude.wheel_centre - axis * inboard - outer).norm();
        // A NaN distance (coordinates no number) is off the axis too.
        if off.is_nan() || off > SHAFT_OFF_AXIS {
            return Err(off);
        }
        Ok(DriveShaft { inner, inboard, length: (outer - inner).norm() })
    }

    /// The shaft with the wheel at `attitude` on `side`.
    pub fn at(&self, side: Side, attitude: &WheelAttitude) -> ShaftReading {
        let axis = attitude.spin_axis(side);
        let outer = attitude.wheel_centre - axis * self.inboard;
        let shaft = outer - self.inner;
        let length = shaft.norm();
        let u = shaft / length;
        // Angles by atan2 of sine and cosine: an arccosine of a cosine near 1 (a straight shaft) would
        // carry rounding as its square root.
        ShaftReading {
            plunge: length - self.length,
            inner_angle: u.x.hypot(u.z).atan2(u.y.abs()),
            outer_angle: u.cross(&axis).norm().atan2(u.dot(&axis)),
        }
    }
}

impl WheelAttitude {
    /// The outward spin axis its toe and camber say, on `side` ([`Side::spin_axis`], the inverse of
    /// [`Wheel::attitude`]'s formulas).
    pub fn spin_axis(&self, side: Side) -> Vec3 {
        side.spin_axis(self.toe, self.camber)
    }
}
