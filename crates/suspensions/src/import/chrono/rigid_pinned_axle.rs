//! Chrono's `RigidPinnedAxle` (`ChRigidPinnedAxle`): read, and refused by name.
//!
//! What Chrono builds: one axle tube (`Tube / COM`) on a revolute joint to the chassis at `Tube / Pin
//! Location`, its axis the chassis's x (the frame turned a quarter about y); each spindle on a revolute
//! joint about y on the tube at `Spindle / COM` (no camber, no toe: the template reads neither). Nothing
//! else: no spring, no shock, no link; the rest of the file (`Spindle`, `Tube` and `Axle` masses, inertias
//! and sizes) is dynamics. The axle rolls freely about its pin, as a trunnion-mounted axle does, its roll
//! held on the road by the tyres alone.
//!
//! On a K&C rig that holds the body, such an axle has nothing to analyse: the pin holds both wheels'
//! height, so they cannot travel together, and in roll no spring carries a wheel load, so no load test has
//! an equilibrium to find. The reader reads the file's points (a malformed one is reported by its key) and
//! then refuses the file with that reason, rather than leaving the solver to fail on it.

use super::doc::Doc;
use super::error::Refusal;

/// `RigidPinnedAxle`: its points read, then refused.
pub(super) fn read(doc: &Doc) -> Result<(), Refusal> {
    for point in ["Spindle/COM", "Tube/COM", "Tube/Pin Location"] {
        doc.point(point)?;
    }
    Err(Refusal::unusable(
        &["Tube", "Pin Location"],
        "\"Tube\" / \"Pin Location\": a RigidPinnedAxle turns freely about this pin and no spring holds it: on the \
         K&C rig its wheels cannot travel together (the pin holds their height) and in roll nothing carries a wheel \
         load; to analyse such an axle, give it springs in a template that has them (a PushPipeAxle, say)",
    ))
}
