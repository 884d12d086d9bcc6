//! Side-view geometry of the wheel's motion in bump and the anti-dive, anti-lift and anti-squat it gives
//! with the vehicle's brake and drive splits.

use crate::analysis::sweep::require_rig;
use crate::assembly::{Corner, Rig};
use crate::description::{AxlePosition, VehicleParameters};
use elastokin_core::{Pose, Vec3};
use elastokin_solver::{SolverError, SolverOptions, StaticSolver};

/// Side-view geometry of the wheel's motion in bump and the anti-pitch it gives: see [`anti_pitch`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AntiPitch {
    /// Velocity of the upright's point at the contact patch per metre of wheel-centre travel (m/m).
    pub patch_velocity: Vec3,
    /// Velocity of the wheel centre per metre of wheel-centre travel (m/m; its z is 1).
    pub wheel_centre_velocity: Vec3,
    /// Side-view swing-arm slope at the contact patch, `tan θ_P = v_P,x / v_P,z`: positive when the patch
    /// moves forward in bump (the side-view instant centre behind and above a front patch).
    pub patch_slope: f64,
    /// Side-view swing-arm slope at the wheel centre, `tan θ_W = v_W,x / v_W,z`.
    pub wheel_centre_slope: f64,
    /// `θ_P = atan(tan θ_P)` (rad).
    pub patch_swing_arm_angle: f64,
    /// `θ_W = atan(tan θ_W)` (rad).
    pub wheel_centre_swing_arm_angle: f64,
    /// Under braking: anti-dive on a front axle, anti-lift on a rear axle, as a fraction: the share of the
    /// load transfer onto (front) or off (rear) the axle that the braking forces carry through the linkage
    /// instead of the springs. 1 (100 %) leaves the springs unchanged; negative adds to the pitch.
    pub braking: f64,
    /// Under drive: anti-lift on a front axle, anti-squat on a rear axle, a fraction likewise.
    pub traction: f64,
}

/// Anti-dive, anti-lift and anti-squat of the corner from the instantaneous motion of its wheel at
/// design (the corner must be built with [`Rig::WheelTravel`]).
///
/// The path tangent at design gives the velocity `v_P` of the upright's point at the contact patch and
/// `v_W` of the wheel centre per metre of bump. By virtual work, a force `F` at a point moving with `v`
/// acts on the wheel's vertical motion like a vertical force `F·v / v_z` at the patch (whose `v_z` equals
/// the wheel centre's while the patch lies below the wheel centre, as it does at design).
///
/// Braking with brakes on the upright puts the force at the patch: `B` rearward on each wheel is
/// equivalent to `−B tan θ_P` upward. Deceleration `a` of a car of mass `m` moves `m a h / L` of load from
/// the rear axle to the front one, and the front wheels brake with `p_f m a` in all:
/// * front: the springs see `ΔF − B tan θ_P` per wheel with `ΔF = m a h / (2L)` and `B = p_f m a / 2`,
///   so the linkage carries the share `anti-dive = p_f tan θ_P L / h`;
/// * rear: the wheel loses `ΔF` and brakes with `B = (1 − p_f) m a / 2`, so `anti-lift = (1 − p_f)
///   (−tan θ_P) L / h`.
///
/// Drive through half-shafts from a chassis-mounted differential puts a forward force `T` at the wheel
/// centre (the chassis reacts the torque), equivalent to `+T tan θ_W` upward. Acceleration moves `m a h / L`
/// onto the rear axle:
/// * front: the wheel loses `ΔF` and pushes with `T = d_f m a / 2`, so `anti-lift = d_f tan θ_W L / h`;
/// * rear: the wheel gains `ΔF` and pushes with `T = (1 − d_f) m a / 2`, so `anti-squat = (1 − d_f)
///   (−tan θ_W) L / h`.
///
/// So the same geometry serves both ends of a car: a front wheel moving forward in bump resists dive and
/// lift, a rear wheel moving rearward in bump resists lift and squat.
pub fn anti_pitch(corner: &Corner, vehicle: &VehicleParameters) -> Result<AntiPitch, SolverError> {
    check(corner, vehicle)?;
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default())?;
    let mut state = solver.design_state(0.0);
    solver.equilibrium(&mut state)?;
    let rates = solver.path_tangent(&state)?;
    anti_pitch_at(corner, vehicle, &state.poses, &rates)
}

/// The rig and vehicle [`anti_pitch`] takes.
fn check(corner: &Corner, vehicle: &VehicleParameters) -> Result<(), SolverError> {
    require_rig(corner, &[Rig::WheelTravel])?;
    // The solver's error holds the refusal in words.
    vehicle.validate().map_err(|e| SolverError::InvalidInput { what: "vehicle parameters", why: e.to_string() })
}

/// [`anti_pitch`] from the design equilibrium's `poses` and the path tangent there (`rates`,
/// [`StaticSolver::path_tangent`]): for a caller that reads more off the tangent there with one solver.
pub(crate) fn anti_pitch_at(
    corner: &Corner,
    vehicle: &VehicleParameters,
    poses: &[Pose],
    rates: &[f64],
) -> Result<AntiPitch, SolverError> {
    check(corner, vehicle)?;
    let wheel = &corner.wheel;
    let patch = wheel.steering_geometry(poses).contact_patch;
    let wheel_centre = wheel.attitude(poses).wheel_centre;
    let patch_velocity = wheel.point_velocity(poses, rates, patch);
    let wheel_centre_velocity = wheel.point_velocity(poses, rates, wheel_centre);
    if !patch_velocity.iter().all(|v| v.is_finite()) {
        return Err(SolverError::InvalidInput {
            what: "corner",
            why: "the contact patch's motion in bump cannot be computed (the path tangent at design is not \
                  finite): no side-view swing arm; check the hardpoints with `elastokin check`"
                .into(),
        });
    }
    if patch_velocity.z.abs() <= 1e-6 {
        return Err(SolverError::InvalidInput {
            what: "corner",
            why: format!(
                "the contact patch does not rise with the wheel centre (it moves ({:.4}, {:.4}, {:.4}) m per metre \
                 of travel): no side-view swing arm; check the hardpoints",
                patch_velocity.x, patch_velocity.y, patch_velocity.z
            ),
        });
    }
    let patch_slope = patch_velocity.x / patch_velocity.z;
    let wheel_centre_slope = wheel_centre_velocity.x / wheel_centre_velocity.z;
    let lever = vehicle.wheelbase / vehicle.cg_height;
    let (p_f, d_f) = (vehicle.brake_front_fraction, vehicle.drive_front_fraction);
    let (braking, traction) = match vehicle.axle {
        AxlePosition::Front => (p_f * patch_slope * lever, d_f * wheel_centre_slope * lever),
        AxlePosition::Rear => ((1.0 - p_f) * -patch_slope * lever, (1.0 - d_f) * -wheel_centre_slope * lever),
    };
    Ok(AntiPitch {
        patch_velocity,
        wheel_centre_velocity,
        patch_slope,
        wheel_centre_slope,
        patch_swing_arm_angle: patch_slope.atan(),
        wheel_centre_swing_arm_angle: wheel_centre_slope.atan(),
        braking,
        traction,
    })
}
