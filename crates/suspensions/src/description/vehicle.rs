//! The vehicle around a corner, as a model file's `vehicle` section gives it: the corner's share of the
//! weight, the wheelbase, the centre of gravity's height, the brake and drive splits, and the optional
//! tyre rate and steering ratio.

use serde::{Deserialize, Serialize};

/// Which axle a corner is on: it decides which pitch the braking and drive forces resist.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AxlePosition {
    /// Front axle: braking dives it, drive lifts it.
    Front,
    /// Rear axle: braking lifts it, drive squats it.
    Rear,
}

/// What the vehicle-level analyses need from the vehicle (SI units): the static load case and the road
/// loads carry `corner_load`, the anti-pitch percentages use the rest. A model file's `vehicle` section.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VehicleParameters {
    /// The corner's share of the vehicle's weight, N: the vertical force at the contact patch at rest.
    pub corner_load: f64,
    /// Wheelbase `L` (m).
    pub wheelbase: f64,
    /// Height `h` of the centre of gravity above the ground (m).
    pub cg_height: f64,
    /// Share `p_f` of the braking force made by the front axle, 0 to 1.
    pub brake_front_fraction: f64,
    /// Share `d_f` of the drive force made by the front axle, 0 to 1 (0: rear drive, 1: front drive).
    pub drive_front_fraction: f64,
    /// The axle the corner is on.
    pub axle: AxlePosition,
    /// Vertical rate of the tyre (N/m), for the ride rate (wheel rate and tyre in series); optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tyre_rate: Option<f64>,
    /// Rack travel per turn of the steering wheel (m/rev, the pinion's "c-factor"), for the overall
    /// steering ratio; optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rack_travel_per_revolution: Option<f64>,
    /// The drive shaft of a driven corner, for its plunge and its joints' angles over travel and steer;
    /// optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub half_shaft: Option<HalfShaft>,
}

/// A drive shaft at design (m, the left corner's coordinates): the centre of its inner joint, fixed to
/// the chassis at the differential's output, and of its outer joint, on the wheel's spin axis inboard of
/// the wheel centre, carried by the upright.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HalfShaft {
    /// The inner joint's centre.
    pub inner: [f64; 3],
    /// The outer joint's centre.
    pub outer: [f64; 3],
}

impl HalfShaft {
    /// The distance between its joints' centres at design (m).
    pub fn length(&self) -> f64 {
        (0..3).map(|i| (self.outer[i] - self.inner[i]).powi(2)).sum::<f64>().sqrt()
    }
}

impl VehicleParameters {
    /// Refuses values no vehicle has, naming the field.
    pub fn validate(&self) -> Result<(), VehicleError> {
        // Upper bounds well beyond any road vehicle: past them the figures (anti-pitch = slope × L / h, the
        // forces of the corner load) lose their meaning and then overflow.
        for (field, value, what, limit) in [
            ("wheelbase", Some(self.wheelbase), "a length in metres", 50.0),
            ("cg_height", Some(self.cg_height), "a height in metres", 20.0),
            ("corner_load", Some(self.corner_load), "a force in newtons", 1e7),
            ("tyre_rate", self.tyre_rate, "a rate in N/m", 1e10),
            ("rack_travel_per_revolution", self.rack_travel_per_revolution, "a rack travel in metres", 1.0),
        ] {
            if let Some(got) = value.filter(|v| !(*v > 0.0 && *v <= limit)) {
                return Err(VehicleError::OutOfRange { field, what, limit, got });
            }
        }
        for (field, got) in
            [("brake_front_fraction", self.brake_front_fraction), ("drive_front_fraction", self.drive_front_fraction)]
        {
            if !(0.0..=1.0).contains(&got) {
                return Err(VehicleError::NotShare { field, got });
            }
        }
        Ok(())
    }
}

/// A value of the vehicle section no vehicle has, naming the field and what it must be.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum VehicleError {
    /// A size, load or rate not above zero, or beyond any road vehicle's.
    #[error(
        "`{field}` must be {what}, above 0 and at most {}, got {}",
        crate::description::limits::plain(*limit),
        crate::description::limits::plain(*got)
    )]
    OutOfRange {
        /// The field.
        field: &'static str,
        /// What it is, in its unit.
        what: &'static str,
        /// The largest it may be.
        limit: f64,
        /// What it is.
        got: f64,
    },
    /// A front axle's share outside [0, 1].
    #[error(
        "`{field}` is the front axle's share of the force and must lie in [0, 1], got {}",
        crate::description::limits::plain(*got)
    )]
    NotShare {
        /// The field.
        field: &'static str,
        /// What it is.
        got: f64,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A wheelbase of zero is refused naming the field, what it must be and what it is.
    #[test]
    fn a_wheelbase_of_zero_is_refused_naming_it() {
        let vehicle = VehicleParameters {
            corner_load: 4000.0,
            wheelbase: 0.0,
            cg_height: 0.5,
            brake_front_fraction: 0.6,
            drive_front_fraction: 1.0,
            axle: AxlePosition::Front,
            tyre_rate: None,
            rack_travel_per_revolution: None,
            half_shaft: None,
        };
        let e = vehicle.validate().unwrap_err();
        assert!(matches!(e, VehicleError::OutOfRange { field: "wheelbase", .. }), "{e:?}");
        assert_eq!(e.to_string(), "`wheelbase` must be a length in metres, above 0 and at most 50, got 0");
    }
}
