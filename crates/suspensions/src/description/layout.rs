//! Where a suspension's parts are, by hardpoint name: what the plausibility check needs to read a
//! geometry (arms, steering lever, spring seats) without knowing the template. Each template says its
//! own layout beside its expansion, so a topology is described once, in its template's file.

use crate::description::connection::ArmMounts;

/// Where the model's parts are, by hardpoint name.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Layout {
    /// The wheel centre.
    pub(crate) wheel_centre: String,
    /// Lower and upper point of the steering axis, when both are hardpoints.
    pub(crate) steering_axis: Option<[String; 2]>,
    /// Inner and outer end of the tie rod, when it has one given by hardpoints.
    pub(crate) tie_rod: Option<[String; 2]>,
    /// Each arm: its name, front pivot, rear pivot, ball joint, and how it meets the chassis.
    pub(crate) arms: Vec<(&'static str, [&'static str; 3], ArmMounts)>,
    /// The spring's seats (chassis, moving), the moving seat's body, and what to do about a small ratio.
    pub(crate) spring: Option<([String; 2], String, String)>,
}

/// Two hardpoint names as owned strings.
pub(crate) fn named_pair(a: [&str; 2]) -> Option<[String; 2]> {
    Some(a.map(str::to_string))
}
