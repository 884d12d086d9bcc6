//! The Chrono templates the importer reads, by the name a file's `"Template"` gives: the list its refusal of
//! any other names (a module of its own, so that the refusals and the reader both take it from here).

/// The Chrono templates [`super::read`] reads.
pub const SUPPORTED: [&str; 22] = [
    "DoubleWishbone",
    "DoubleWishboneReduced",
    "MacPhersonStrut",
    "MultiLink",
    "SemiTrailingArm",
    "SingleWishbone",
    "ThreeLinkIRS",
    "GenericWheeledSuspension",
    "SolidAxle",
    "SolidThreeLinkAxle",
    "SolidBellcrankThreeLinkAxle",
    "RigidPanhardAxle",
    "ToeBarRigidPanhardAxle",
    "HendricksonPRIMAXX",
    "PushPipeAxle",
    "ToeBarPushPipeAxle",
    "DeDionAxle",
    "ToeBarDeDionAxle",
    "SAELeafspringAxle",
    "SAEToeBarLeafspringAxle",
    "LeafspringAxle",
    "ToeBarLeafspringAxle",
];
