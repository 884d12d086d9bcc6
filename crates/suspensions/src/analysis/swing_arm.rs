//! The wheel's swing arms in wheel travel: the front-view and side-view instant centres of its upright,
//! read off the path's exact tangent.

use crate::wheel::Wheel;
use elastokin_core::Pose;

/// Where a view's instant centre of the upright lies, in vehicle axes, and the swing arm from the contact
/// patch to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InstantCentre {
    /// Its horizontal coordinate in the view (m): y in the front view, x in the side view.
    pub horizontal: f64,
    /// Its z (m).
    pub z: f64,
    /// The horizontal distance from the contact patch to it (m).
    pub swing_arm_length: f64,
}

/// The front-view and side-view instant centres of the upright at one state; `None` in a view where the
/// upright does not turn (its arms parallel there: the centre at infinity).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwingArms {
    /// In the front view, the vertical plane across the car through the contact patch.
    pub front: Option<InstantCentre>,
    /// In the side view, the vertical plane along the car through the contact patch.
    pub side: Option<InstantCentre>,
}

/// How far from the patch an instant centre may lie (m) before the view counts as not turning: beyond it
/// the upright's turn in that view is rounding of the tangent, and its centre's place rounding too.
pub const FARTHEST_INSTANT_CENTRE: f64 = 1e6;

impl SwingArms {
    /// The swing arms of `wheel` at `poses` for body velocities `rates` along a wheel-travel path (from
    /// [`elastokin_solver::StaticSolver::path_tangent`]).
    ///
    /// The upright's velocities projected on a view's plane through the contact patch `P` are those of a
    /// rigid motion of the plane: the patch's velocity `v` and a turn at the rate of the upright's angular
    /// velocity `ω` about the view's normal. The point of the plane that does not move is the instant
    /// centre: `P + (−v_z, v_y)/ω_x` in the front view (y, z) and `P + (v_z, −v_x)/ω_y` in the side view
    /// (x, z). It lies on the line through `P` perpendicular to `v`, the line the roll centre is read
    /// from ([`crate::assembly::Axle::roll_centre`]). For a double wishbone whose arms turn about axes
    /// along x it is where the arms' lines meet in the front view.
    pub fn of(wheel: &Wheel, poses: &[Pose], rates: &[f64]) -> SwingArms {
        let p = wheel.steering_geometry(poses).contact_patch;
        let v = wheel.point_velocity(poses, rates, p);
        let w = wheel.angular_velocity(rates);
        // The centre `along` from the patch horizontally and `up` above it, for a turn at `turn`.
        let centre = |turn: f64, along: f64, up: f64, at: f64| {
            let (along, up) = (along / turn, up / turn);
            let far = along.hypot(up);
            (far.is_finite() && far <= FARTHEST_INSTANT_CENTRE).then_some(InstantCentre {
                horizontal: at + along,
                z: p.z + up,
                swing_arm_length: along.abs(),
            })
        };
        SwingArms { front: centre(w.x, -v.z, v.y, p.y), side: centre(w.y, v.z, -v.x, p.x) }
    }
}
