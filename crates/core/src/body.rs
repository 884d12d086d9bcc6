//! Bodies and references to them.

use crate::pose::Pose;

/// Index of a moving body in a [`Model`](crate::Model).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BodyId(pub usize);

/// A body a joint, element or load attaches to: the ground (chassis, not a variable) or a moving body.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum BodyRef {
    /// The fixed ground (the chassis on a K&C rig).
    Ground,
    /// A moving rigid body.
    Body(BodyId),
}

impl BodyRef {
    /// The moving body, if any.
    #[inline]
    pub fn id(self) -> Option<BodyId> {
        match self {
            BodyRef::Ground => None,
            BodyRef::Body(b) => Some(b),
        }
    }

    /// Pose of this body in `poses` (identity for the ground).
    #[inline]
    pub fn pose(self, poses: &[Pose]) -> Pose {
        match self {
            BodyRef::Ground => Pose::IDENTITY,
            BodyRef::Body(b) => poses[b.0],
        }
    }
}

impl From<BodyId> for BodyRef {
    fn from(b: BodyId) -> Self {
        BodyRef::Body(b)
    }
}

/// A rigid part: a name and its pose at design.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Body {
    /// Unique name (upright, lower arm, …), used in every diagnostic.
    pub name: String,
    /// Pose at design (the starting configuration).
    pub design_pose: Pose,
}
