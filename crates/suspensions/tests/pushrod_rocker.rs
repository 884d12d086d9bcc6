//! The Formula Student pushrod and rocker corner (`examples/pushrod_rocker.json`): what the analyses read
//! through the rocker against a second way to the same number — the wheel load against the coilover's
//! force times its motion ratio (virtual work), the anti-roll bar's roll stiffness from its energy against
//! the axle's roll stiffness with and without the bar.

use elastokin_suspensions::kc::{self, Analysis, Settings};
use elastokin_suspensions::SuspensionFile;

fn example() -> SuspensionFile {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/pushrod_rocker.json");
    SuspensionFile::read(&path).unwrap_or_else(|e| panic!("{e}"))
}

fn figure(file: &SuspensionFile, analysis: Analysis, key: &str) -> f64 {
    // The figures are read at design, off the equilibrium there and its path.
    let report = kc::run(analysis, file, &Settings::default()).unwrap_or_else(|e| panic!("{e}"));
    let f = report.figures.iter().find(|f| f.key == key).unwrap_or_else(|| panic!("no figure {key}"));
    f.value.unwrap_or_else(|| panic!("{key}: {:?}", f.reason))
}

#[test]
fn the_wheel_load_is_the_coilovers_force_through_the_rocker() {
    let file = example();
    // Ideal joints: the rig's force at the wheel centre does the coilover's work, F_w = F_s · dL/dz.
    let ratio = figure(&file, Analysis::ParallelTravel, "spring_motion_ratio");
    let load = figure(&file, Analysis::ParallelTravel, "wheel_load_at_design");
    let spring_force = 850.0; // the coilover's design_force in the file
    let error = (load / (spring_force * ratio) - 1.0).abs();
    println!("motion ratio {ratio}, wheel load {load} N against {} N: {error:e}", spring_force * ratio);
    // Measured 2.9e-12.
    assert!(error < 1e-10, "{error:e}");
    // Through the rocker, not a direct spring: the ratio is the pushrod's and the rocker's levers together.
    assert!((0.5..1.0).contains(&ratio), "{ratio}");
}

#[test]
fn the_bars_roll_stiffness_is_what_the_bar_adds_to_the_axle() {
    let with = example();
    let mut without = example();
    if let elastokin_suspensions::description::Template::General(g) = &mut without.suspension {
        g.anti_roll_bars.clear();
    }
    let bar = figure(&with, Analysis::Roll, "anti_roll_bar_roll_stiffness");
    let added = figure(&with, Analysis::Roll, "roll_stiffness") - figure(&without, Analysis::Roll, "roll_stiffness");
    let error = (bar / added - 1.0).abs();
    println!("bar {bar} N·m/deg from its energy, {added} N·m/deg added to the axle: {error:e}");
    // Measured 3.4e-12.
    assert!(error < 1e-10, "{error:e}");
}
