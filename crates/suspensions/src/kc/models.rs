//! What the analyses build of a model file ([`Models`]), built once for every analysis run on it.

use crate::assembly::{Axle, AxleRig, Corner, Rig};
use crate::description::Side;
use crate::file::SuspensionFile;
use crate::kc::reduce::with_rigid_bushings;
use elastokin_core::{Model, ModelError};
use std::borrow::Cow;
use std::sync::{Arc, OnceLock};

/// A model file and what the K&C analyses build of it — its left corner on each rig, its axle on each
/// axle rig, the file with its bushings made rigid — each built when an analysis first asks for it and
/// kept for every other analysis run on the same `Models` (a suite, the replays of a recorded run on
/// one variant). An analysis takes its own copy of a corner or axle to load and solve: what it gets is
/// the model a build of the file gives, number for number (in the coordinates of another file's
/// models for [`Models::in_coordinates_of`]).
#[derive(Debug)]
pub struct Models<'f> {
    file: Cow<'f, SuspensionFile>,
    corners: [OnceLock<Result<Corner, ModelError>>; 4],
    axles: [OnceLock<Result<Axle, ModelError>>; 5],
    rigid: OnceLock<Option<Arc<Models<'static>>>>,
    /// The models whose bodies' reference points these are built with ([`Models::in_coordinates_of`]).
    from: Option<Arc<Models<'static>>>,
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

    /// Nothing built yet of `file`, a variant of the file of `from` (a number of it changed), whose
    /// models are each built with the bodies' reference points of the same model of `from`
    /// ([`Model::with_body_origins`]): the same scenes as [`Models::owning`] builds, in `from`'s
    /// coordinates, so that a pose of one of `from`'s models places every material point of the variant
    /// as it placed it in `from`'s (a run replayed on them moves by what the variant changes, not by a
    /// shift of coordinates).
    pub fn in_coordinates_of(file: SuspensionFile, from: Arc<Models<'static>>) -> Models<'static> {
        Models { from: Some(from), ..Models::owning(file) }
    }

    fn of(file: Cow<'f, SuspensionFile>) -> Self {
        Models { file, corners: Default::default(), axles: Default::default(), rigid: OnceLock::new(), from: None }
    }

    /// An empty model for a build of this file, in the coordinates of `model` of [`Models::in_coordinates_of`]'s
    /// `from` (where it has that model: else a build's own).
    fn empty(&self, model: impl for<'m> FnOnce(&'m Models<'static>) -> Option<&'m Model>) -> Model {
        match self.from.as_deref().and_then(model) {
            Some(m) => Model::with_body_origins(Arc::new(m.body_origins())),
            None => Model::new(),
        }
    }

    /// The model file.
    pub fn file(&self) -> &SuspensionFile {
        &self.file
    }

    /// The left corner on `rig`, as [`crate::description::Template::build`] builds it (its error in the
    /// user's words).
    pub fn corner(&self, rig: Rig) -> Result<Corner, ModelError> {
        self.built_corner(rig).clone()
    }

    /// [`Models::corner`] as built, for an analysis that changes nothing of it (no copy).
    pub fn corner_ref(&self, rig: Rig) -> Result<&Corner, ModelError> {
        self.built_corner(rig).as_ref().map_err(Clone::clone)
    }

    /// The left corner on `rig`, built once.
    fn built_corner(&self, rig: Rig) -> &Result<Corner, ModelError> {
        let index = match rig {
            Rig::WheelTravel => 0,
            Rig::Steering => 1,
            Rig::HeightHeld => 2,
            Rig::Free => 3,
        };
        let build = || {
            let model = self.empty(|from| from.built_corner(rig).as_ref().ok().map(|c| &c.model));
            Corner::build_in(model, &self.file.suspension, Side::Left, rig)
        };
        self.corners[index].get_or_init(build)
    }

    /// The axle on `rig`, as [`Axle::build`] builds it (its error in the user's words).
    pub fn axle(&self, rig: AxleRig) -> Result<Axle, ModelError> {
        self.built_axle(rig).clone()
    }

    /// [`Models::axle`] as built, for an analysis that changes nothing of it (no copy).
    pub fn axle_ref(&self, rig: AxleRig) -> Result<&Axle, ModelError> {
        self.built_axle(rig).as_ref().map_err(Clone::clone)
    }

    /// The axle on `rig`, built once.
    fn built_axle(&self, rig: AxleRig) -> &Result<Axle, ModelError> {
        let index = match rig {
            AxleRig::ParallelTravel => 0,
            AxleRig::OppositeTravel => 1,
            AxleRig::Steering => 2,
            AxleRig::HeightHeld => 3,
            AxleRig::Free => 4,
        };
        let build = || {
            let model = self.empty(|from| from.built_axle(rig).as_ref().ok().map(|a| &a.model));
            Axle::build_in(model, &self.file.suspension, rig)
        };
        self.axles[index].get_or_init(build)
    }

    /// The model with every bushing rigid ([`with_rigid_bushings`]), if it has bushings to make rigid.
    pub(super) fn rigid(&self) -> Option<&Models<'static>> {
        self.built_rigid().map(Arc::as_ref)
    }

    /// [`Models::rigid`], built once (in the coordinates of `from`'s own, for [`Models::in_coordinates_of`]).
    fn built_rigid(&self) -> Option<&Arc<Models<'static>>> {
        let build = |f| match self.from.as_deref().and_then(Models::built_rigid) {
            Some(from) => Arc::new(Models::in_coordinates_of(f, from.clone())),
            None => Arc::new(Models::owning(f)),
        };
        self.rigid.get_or_init(|| with_rigid_bushings(&self.file).map(build)).as_ref()
    }
}
