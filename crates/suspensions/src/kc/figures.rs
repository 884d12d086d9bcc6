//! Every headline figure an analysis reports, declared once: key, words, the unit it is written in and its
//! decimals. The analyses make their figures from these; the layers above read them by these (never by a
//! key they spell); `docs/figures.md` defines each (a test keeps the two in step). Figures whose key or
//! words name a part of the model (a shared beam's twist) or a load (toe at the range's end) are made
//! where they are read.

use crate::kc::report::FigureKind;
use crate::kc::unit::Unit;

const fn kind(key: &'static str, label: &'static str, unit: Unit, decimals: usize) -> FigureKind {
    FigureKind { key, label, unit, decimals }
}

// parallel-travel
/// d(toe)/d(wheel travel) at design.
pub const BUMP_STEER: FigureKind = kind("bump_steer", "bump steer (toe-in +)", Unit::DegreePerMetre, 3);
/// d(camber)/d(wheel travel) at design.
pub const CAMBER_GAIN: FigureKind = kind("camber_gain", "camber gain (top out +)", Unit::DegreePerMetre, 3);
/// d(rig force)/d(wheel travel) at design.
pub const WHEEL_RATE: FigureKind = kind("wheel_rate", "wheel rate", Unit::NewtonPerMillimetre, 2);
/// |d(spring length)/d(wheel travel)| at design.
pub const SPRING_MOTION_RATIO: FigureKind = kind("spring_motion_ratio", "spring motion ratio", Unit::Ratio, 3);
/// The wheel rate and the tyre's in series.
pub const RIDE_RATE: FigureKind =
    kind("ride_rate", "ride rate (wheel rate and tyre in series)", Unit::NewtonPerMillimetre, 2);
/// The rig's force at the wheel centre at design.
pub const WHEEL_LOAD_AT_DESIGN: FigureKind = kind("wheel_load_at_design", "wheel load at design", Unit::Newton, 1);
/// The steering axis against the vertical, side view.
pub const CASTER: FigureKind = kind("caster", "caster (top rearward +)", Unit::Degree, 2);
/// The steering axis against the vertical, front view.
pub const KINGPIN_INCLINATION: FigureKind =
    kind("kingpin_inclination", "kingpin inclination (top inboard +)", Unit::Degree, 2);
/// Ground-plane distance from the patch to the steering axis, front view.
pub const SCRUB_RADIUS: FigureKind =
    kind("scrub_radius", "scrub radius (axis inboard of patch +)", Unit::Millimetre, 1);
/// Ground-plane distance from the patch to the steering axis, side view.
pub const MECHANICAL_TRAIL: FigureKind = kind("mechanical_trail", "mechanical trail", Unit::Millimetre, 1);
/// The wheel centre's lateral distance from the steering axis.
pub const KINGPIN_OFFSET: FigureKind = kind("kingpin_offset", "kingpin offset at wheel centre", Unit::Millimetre, 1);
/// Toe per lateral force at the patch.
pub const LATERAL_STEER: FigureKind =
    kind("lateral_steer", "compliance steer, lateral force (inboard +)", Unit::DegreePerKilonewton, 4);
/// Camber per lateral force at the patch.
pub const LATERAL_CAMBER: FigureKind =
    kind("lateral_camber", "compliance camber, lateral force", Unit::DegreePerKilonewton, 4);
/// Toe per braking force at the patch.
pub const BRAKING_STEER: FigureKind =
    kind("braking_steer", "compliance steer, braking force", Unit::DegreePerKilonewton, 4);
/// Toe per aligning torque.
pub const ALIGNING_TORQUE_STEER: FigureKind =
    kind("aligning_torque_steer", "compliance steer, aligning torque", Unit::DegreePerKilonewtonMetre, 4);
/// Lateral force per lateral motion of the patch.
pub const LATERAL_STIFFNESS: FigureKind =
    kind("lateral_stiffness", "lateral stiffness at the patch", Unit::NewtonPerMillimetre, 0);
/// Longitudinal force per longitudinal motion of the patch.
pub const LONGITUDINAL_STIFFNESS: FigureKind =
    kind("longitudinal_stiffness", "longitudinal stiffness at the patch", Unit::NewtonPerMillimetre, 0);
/// Anti-dive (front) or anti-lift (rear) under braking.
pub const BRAKING_ANTI_PITCH: FigureKind = kind("braking_anti_pitch", "anti-dive / anti-lift", Unit::Percent, 1);
/// Anti-lift (front drive) or anti-squat (rear drive).
pub const TRACTION_ANTI_PITCH: FigureKind =
    kind("traction_anti_pitch", "anti-lift (drive) / anti-squat", Unit::Percent, 1);
/// The patch's side-view path against the vertical.
pub const SWING_ARM_ANGLE_AT_PATCH: FigureKind =
    kind("side_view_swing_arm_angle_at_patch", "side-view swing arm angle at the patch", Unit::Degree, 2);
/// The wheel centre's side-view path against the vertical.
pub const SWING_ARM_ANGLE_AT_WHEEL_CENTRE: FigureKind =
    kind("side_view_swing_arm_angle_at_wheel_centre", "side-view swing arm angle at the wheel centre", Unit::Degree, 2);
/// The lateral distance from the patch to the front-view instant centre at design.
pub const FRONT_VIEW_SWING_ARM_LENGTH: FigureKind =
    kind("front_view_swing_arm_length", "front-view swing arm length at design", Unit::Millimetre, 0);
/// The longitudinal distance from the patch to the side-view instant centre at design.
pub const SIDE_VIEW_SWING_ARM_LENGTH: FigureKind =
    kind("side_view_swing_arm_length", "side-view swing arm length at design", Unit::Millimetre, 0);

// roll
/// The lateral distance between the contact patches at design.
pub const TRACK: FigureKind = kind("track", "track at design (between the contact patches)", Unit::Millimetre, 1);
/// Roll centre height at design.
pub const ROLL_CENTRE_HEIGHT: FigureKind =
    kind("roll_centre_height", "roll centre height at design", Unit::Millimetre, 1);
/// Roll centre's offset from the centre plane at design.
pub const ROLL_CENTRE_LATERAL: FigureKind =
    kind("roll_centre_lateral", "roll centre lateral offset at design (left +)", Unit::Millimetre, 2);
/// d(left toe)/d(roll).
pub const ROLL_STEER: FigureKind = kind("roll_steer", "roll steer, left wheel (toe-in +)", Unit::DegreePerDegree, 4);
/// d(left camber to ground)/d(roll).
pub const ROLL_CAMBER: FigureKind = kind("roll_camber", "roll camber to ground, left wheel", Unit::DegreePerDegree, 4);
/// −d(rolling moment)/d(roll).
pub const ROLL_STIFFNESS: FigureKind =
    kind("roll_stiffness", "roll stiffness (springs, bushings and bars)", Unit::NewtonMetrePerDegree, 0);
/// d²(bars' energy)/d(roll)².
pub const ANTI_ROLL_BAR_ROLL_STIFFNESS: FigureKind =
    kind("anti_roll_bar_roll_stiffness", "roll stiffness of the anti-roll bars", Unit::NewtonMetrePerDegree, 0);
/// The bars' part of the roll stiffness.
pub const ANTI_ROLL_BAR_SHARE: FigureKind =
    kind("anti_roll_bar_share", "anti-roll bars' share of the roll stiffness", Unit::Percent, 1);

// steering
/// d(mean steer)/d(rack travel) at design.
pub const STEER_PER_RACK_TRAVEL: FigureKind = kind(
    "steer_per_rack_travel",
    "steer per rack travel at design (mean of both wheels)",
    Unit::DegreePerMillimetre,
    4,
);
/// Hand wheel to road wheel at design.
pub const STEERING_RATIO: FigureKind =
    kind("steering_ratio", "overall steering ratio at design (hand wheel : road wheel)", Unit::ToOne, 2);
/// (inner − outer) / (inner − ideal outer) at full steer.
pub const ACKERMANN: FigureKind = kind("ackermann", "Ackermann at full steer (100 % = ideal)", Unit::Percent, 1);
/// The inner wheel's steer at full rack travel.
pub const INNER_STEER_AT_FULL_RACK: FigureKind =
    kind("inner_steer_at_full_rack", "inner wheel steer at full rack travel", Unit::Degree, 2);
/// The outer wheel's largest departure from ideal Ackermann.
pub const ACKERMANN_ERROR: FigureKind =
    kind("ackermann_error", "largest outer-wheel error against ideal Ackermann", Unit::Degree, 3);

// vertical-force
/// The rig's force at design height.
pub const DESIGN_WHEEL_LOAD: FigureKind =
    kind("design_wheel_load", "design wheel load (rig force at design height)", Unit::Newton, 1);
/// 1 / d(wheel-centre height)/d(force) at the design load.
pub const VERTICAL_FORCE_WHEEL_RATE: FigureKind =
    kind("wheel_rate", "wheel rate at the design load (force over wheel-centre travel)", Unit::NewtonPerMillimetre, 2);

// road loads and the model's loads (per kN here; per kN·m under an aligning torque, per load case under
// the model's loads)
/// d(toe)/d(load) at zero load.
pub const COMPLIANCE_STEER: FigureKind =
    kind("steer", "compliance steer at zero load (toe-in +)", Unit::DegreePerKilonewton, 4);
/// d(camber)/d(load) at zero load.
pub const COMPLIANCE_CAMBER: FigureKind =
    kind("camber", "compliance camber at zero load", Unit::DegreePerKilonewton, 4);
/// Toe at the range's last load.
pub const TOE_AT_END: FigureKind = kind("toe_at_end", "toe at the range's end", Unit::Degree, 4);
/// Camber at the range's last load.
pub const CAMBER_AT_END: FigureKind = kind("camber_at_end", "camber at the range's end", Unit::Degree, 4);

// static-load
/// The corner's share of the weight, as given.
pub const CORNER_LOAD: FigureKind = kind("corner_load", "corner load", Unit::Newton, 0);
/// The wheel centre's height change at rest.
pub const RIDE_HEIGHT_CHANGE: FigureKind =
    kind("ride_height_change", "ride height change at the wheel centre (bump +)", Unit::Millimetre, 2);
/// Toe at rest.
pub const TOE_AT_REST: FigureKind = kind("toe", "toe at rest", Unit::Degree, 4);
/// Camber at rest.
pub const CAMBER_AT_REST: FigureKind = kind("camber", "camber at rest", Unit::Degree, 4);
/// Wheel rate at rest.
pub const WHEEL_RATE_AT_REST: FigureKind = kind("wheel_rate", "wheel rate at rest", Unit::NewtonPerMillimetre, 2);
/// Spring force at rest.
pub const SPRING_FORCE: FigureKind = kind("spring_force", "spring force (compression +)", Unit::Newton, 0);
/// Spring deflection at rest.
pub const SPRING_DEFLECTION: FigureKind =
    kind("spring_deflection", "spring deflection (compression -)", Unit::Millimetre, 2);

// wheel-envelope
/// The tyre's least clearance to the body's packaging over travel and rack travel.
pub const LEAST_WHEEL_CLEARANCE: FigureKind =
    kind("least_wheel_clearance", "least clearance of the tyre to the packaging", Unit::Millimetre, 1);

/// Every declared figure (`crates/suspensions/tests/figures.rs` keeps it in step with this file).
pub const ALL: [&FigureKind; 50] = [
    &BUMP_STEER,
    &CAMBER_GAIN,
    &WHEEL_RATE,
    &SPRING_MOTION_RATIO,
    &RIDE_RATE,
    &WHEEL_LOAD_AT_DESIGN,
    &CASTER,
    &KINGPIN_INCLINATION,
    &SCRUB_RADIUS,
    &MECHANICAL_TRAIL,
    &KINGPIN_OFFSET,
    &LATERAL_STEER,
    &LATERAL_CAMBER,
    &BRAKING_STEER,
    &ALIGNING_TORQUE_STEER,
    &LATERAL_STIFFNESS,
    &LONGITUDINAL_STIFFNESS,
    &BRAKING_ANTI_PITCH,
    &TRACTION_ANTI_PITCH,
    &SWING_ARM_ANGLE_AT_PATCH,
    &SWING_ARM_ANGLE_AT_WHEEL_CENTRE,
    &FRONT_VIEW_SWING_ARM_LENGTH,
    &SIDE_VIEW_SWING_ARM_LENGTH,
    &TRACK,
    &ROLL_CENTRE_HEIGHT,
    &ROLL_CENTRE_LATERAL,
    &ROLL_STEER,
    &ROLL_CAMBER,
    &ROLL_STIFFNESS,
    &ANTI_ROLL_BAR_ROLL_STIFFNESS,
    &ANTI_ROLL_BAR_SHARE,
    &STEER_PER_RACK_TRAVEL,
    &STEERING_RATIO,
    &ACKERMANN,
    &INNER_STEER_AT_FULL_RACK,
    &ACKERMANN_ERROR,
    &DESIGN_WHEEL_LOAD,
    &VERTICAL_FORCE_WHEEL_RATE,
    &COMPLIANCE_STEER,
    &COMPLIANCE_CAMBER,
    &TOE_AT_END,
    &CAMBER_AT_END,
    &CORNER_LOAD,
    &RIDE_HEIGHT_CHANGE,
    &TOE_AT_REST,
    &CAMBER_AT_REST,
    &WHEEL_RATE_AT_REST,
    &SPRING_FORCE,
    &SPRING_DEFLECTION,
    &LEAST_WHEEL_CLEARANCE,
];
