//! The K&C analyses of the engine: load paths walked on a built corner or axle and read into wheel
//! characteristics, row by row. One module per kind of sweep: [`travel`] (wheel travel, steering),
//! [`loads`] (vertical force, road loads, the model's loads, the static load case), [`compliance`] (the
//! wheel's 6×6 compliance and the contact patch's), [`anti_pitch`](mod@anti_pitch), [`swing_arm`] (the instant centres in front and side view), and [`axle`] (both wheels: roll,
//! parallel travel, steering, the roll centre). [`sweep`] is how each of them walks and reads.
//!
//! Invariant: an analysis takes a built model and solves it; it reads no file and builds no description.

pub mod anti_pitch;
pub mod axle;
pub mod compliance;
pub mod loads;
pub mod sweep;
pub mod swing_arm;
pub mod travel;

pub use anti_pitch::{anti_pitch, AntiPitch};
pub use axle::{axle_sweep, axle_sweep_with, AxleRow, RollCentre};
pub use compliance::{patch_compliance, wheel_compliance, PatchCompliance};
pub use loads::{
    design_wheel_load, design_wheel_load_estimated, model_load_sweep_with, static_load_case,
    static_load_case_estimated, vertical_force_sweep, vertical_force_sweep_with, wheel_load_sweep,
    wheel_load_sweep_with, ComponentForce, ComponentForces, ComponentNames, LoadRow, StaticLoad, WheelLoad,
};
pub use sweep::{
    slope_at, walk, ArcEnd, ArcLengthRows, AtDesign, Reading, SweepExtras, SweepLimit, SweepOutput, Walked,
    EXPANSION_REACH, MAX_ARC_STEPS_PER_RANGE,
};
pub use swing_arm::{InstantCentre, SwingArms};
pub use travel::{parallel_wheel_travel, parallel_wheel_travel_with, steering, TravelRow};
