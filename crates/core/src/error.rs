//! Typed errors for building a model. Each names the offending item and says how to fix it.

use thiserror::Error;

/// A model that cannot be built or solved as given.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum ModelError {
    /// Two items share a name.
    #[error("the name '{name}' is used twice: give every body, joint and element its own name")]
    DuplicateName {
        /// The repeated name.
        name: String,
    },
    /// A reference to a body the model does not have.
    #[error("'{item}' refers to body #{index}, but the model has {count} bodies: add the body first")]
    UnknownBody {
        /// The referring item.
        item: String,
        /// The index given.
        index: usize,
        /// Bodies in the model.
        count: usize,
    },
    /// NaN or infinity in the input.
    #[error("'{item}': {what} is not finite (NaN or infinity): give a finite value")]
    NonFinite {
        /// Item.
        item: String,
        /// Which value.
        what: &'static str,
    },
    /// An axis or direction of zero length.
    #[error("'{item}': {what} has zero length: give a non-zero direction")]
    ZeroLengthAxis {
        /// Item.
        item: String,
        /// Which axis.
        what: &'static str,
    },
    /// Two points that must differ coincide.
    #[error("'{item}': its two points are {distance:.3e} m apart; they must be distinct to define a line")]
    CoincidentPoints {
        /// Item.
        item: String,
        /// Their distance.
        distance: f64,
    },
    /// A joint that connects a body to itself.
    #[error("joint '{joint}' connects a body to itself: choose two different bodies")]
    SelfJoint {
        /// The joint.
        joint: String,
    },
    /// Two axes that must be perpendicular at design are not.
    #[error("joint '{joint}': its two axes must be perpendicular at design, but their cosine is {cosine:.3e}")]
    NotPerpendicular {
        /// The joint.
        joint: String,
        /// Cosine of the angle between the axes.
        cosine: f64,
    },
    /// A joint kind lacks a piece of geometry it needs.
    #[error("joint '{joint}' needs {what}: add it to the joint's description")]
    MissingGeometry {
        /// The joint.
        joint: String,
        /// What is missing.
        what: &'static str,
    },
    /// A stiffness, length or similar value that must be positive is not.
    #[error("'{item}': {what} must be positive, got {value}")]
    NotPositive {
        /// Item.
        item: String,
        /// Which value.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A body no joint, element or driver touches.
    #[error("body '{body}' is held by nothing: connect it with a joint, bushing or spring, or remove it")]
    NothingHolds {
        /// The body.
        body: String,
    },
    /// Geometry or a value outside what the engine can take (a hardpoint kilometres away, a spring that
    /// would need a negative free length), with what to change.
    #[error("'{item}': {why}")]
    OutOfRange {
        /// Item.
        item: String,
        /// What is wrong and what to change.
        why: String,
    },
    /// A frame that is not a rotation.
    #[error("'{item}': the frame is not orthonormal (error {error:.3e}): give orthonormal axes")]
    NotOrthonormal {
        /// Item.
        item: String,
        /// Largest deviation of AᵀA from I.
        error: f64,
    },
}

impl ModelError {
    /// A value out of range, named as `item` instead (the key a file gives the value where the element's
    /// own name would not find it); any other error as it is.
    pub fn out_of_range_as(self, item: String) -> ModelError {
        match self {
            ModelError::OutOfRange { why, .. } => ModelError::OutOfRange { item, why },
            other => other,
        }
    }
}
