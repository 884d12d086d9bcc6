//! What the analyses build of a model file ([`Models`]), built once for every analysis run on it.

use crate::build::{Axle, AxleRig, Corner, Rig};
use crate::description::Side;
use crate::file::SuspensionFile;
use crate::kc::reduce::{said, with_rigid_bushings};
use std::borrow::Cow;
use std::sync::OnceLock;

/// A model file and what the K&C analyses build of it — its left corner on each rig, its axle on each
/// axle rig, the file with its bushings made rigid — each built when an analysis first asks for it and
/// kept for every other analysis run on the same `Models` (a suite, the replays of sensitivities on one
/// moved model). An analysis takes its own copy of a corner or axle to load and solve: what it gets is
/// the model a build of the file gives, number for number.
#[derive(Debug)]
pub struct Models<'f> {
    file: Cow<'f, SuspensionFile>,
    corners: [OnceLock<Result<Corner, String>>; 4],
    axles: [OnceLock<Result<Axle, String>>; 5],
    rigid: OnceLock<Option<Box<Models<'static>>>>,
}

impl<'f> Models<'f> {
    /// Nothing built yet of `file`.
    pub fn new(file: &'f SuspensionFile) -> Self {
        Models::of(Cow::Borrowed(file))
    }

    /// Nothing built yet of `file`, kept here.
    pub fn owning(file: SuspensionFile) -> Models<'static> {
        Models::of(Cow::Owned(file))
    }

    fn of(file: Cow<'f, SuspensionFile>) -> Self {
        Models { file, corners: Default::default(), axles: Default::default(), rigid: OnceLock::new() }
    }

    /// The model file.
    pub fn file(&self) -> &SuspensionFile {
        &self.file
    }

    /// The left corner on `rig`, as [`crate::description::Template::build`] builds it (its error in the
    /// user's words).
    pub fn corner(&self, rig: Rig) -> Result<Corner, String> {
        let index = match rig {
            Rig::WheelTravel => 0,
            Rig::Steering => 1,
            Rig::HeightHeld => 2,
            Rig::Free => 3,
        };
        self.corners[index].get_or_init(|| self.file.suspension.build(Side::Left, rig).map_err(said)).clone()
    }

    /// The axle on `rig`, as [`Axle::build`] builds it (its error in the user's words).
    pub fn axle(&self, rig: AxleRig) -> Result<Axle, String> {
        let index = match rig {
            AxleRig::ParallelTravel => 0,
            AxleRig::OppositeTravel => 1,
            AxleRig::Steering => 2,
            AxleRig::HeightHeld => 3,
            AxleRig::Free => 4,
        };
        self.axles[index].get_or_init(|| Axle::build(&self.file.suspension, rig).map_err(said)).clone()
    }

    /// The model with every bushing rigid ([`with_rigid_bushings`]), if it has bushings to make rigid.
    pub(super) fn rigid(&self) -> Option<&Models<'static>> {
        self.rigid.get_or_init(|| with_rigid_bushings(&self.file).map(|f| Box::new(Models::owning(f)))).as_deref()
    }
}
