//! The interface between the model and force elements (bushings, springs, loads).
//!
//! An element acts on at most two bodies `i`, `j`. It returns the *generalized force it applies* to them,
//! `Q = (Fᵢ, Mᵢ, Fⱼ, Mⱼ)` with moments about each body's reference point (paper: force `F` at `P` does
//! work through `(F, s × F)`), and its *stiffness* `K = −∂Q/∂Δq` over the 12 coordinates `(Δqᵢ, Δqⱼ)`.
//! For a conservative elastic element `K` is the Hessian of its energy along left increments and is
//! symmetric at rest; a world-fixed load at a body point has the non-symmetric load stiffness `−F̃ s̃`.
//! Equilibrium is `Σ Q − Φ_qᵀ λ = 0`.

use crate::body::BodyRef;
use crate::constraint::{PairMatrix, RowGradient};
use crate::error::ModelError;
use crate::math::Vec3;
use crate::pose::Pose;

/// Whether an element is part of the structure or an applied load (the paper's `K` holds only the former;
/// the load increment `Δf` only the latter).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElementRole {
    /// Bushings, springs: stiffness of the structure.
    Elastic,
    /// Applied loads, ramped by the load parameter.
    Load,
}

/// Output of [`ForceElement::evaluate`].
#[derive(Debug, Clone)]
pub struct ElementEval {
    /// Generalized force applied to `(i, j)`.
    pub force: RowGradient,
    /// `K = −∂force/∂Δq` (filled only when asked).
    pub stiffness: PairMatrix,
}

impl Default for ElementEval {
    fn default() -> Self {
        ElementEval { force: RowGradient::zeros(), stiffness: PairMatrix::zeros() }
    }
}

/// What an element does at a configuration, for results tables.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ElementReport {
    /// Force the element applies to body `j` (global, N).
    pub force: Vec3,
    /// Moment it applies to body `j` about the element's point on `j` (global, N·m).
    pub torque: Vec3,
    /// Deflection: relative translation in the element's frame (m); for a spring, `(L − L₀, 0, 0)`.
    pub deflection: Vec3,
    /// Relative rotation vector in the element's frame (rad).
    pub rotation: Vec3,
}

/// What kind of thing an element is, for a drawing of the model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SketchKind {
    /// A bushing or any element with a frame of its own: drawn at its point, with its axes.
    Bushing,
    /// A spring between two seats.
    Spring,
    /// A stop between two points on its axis.
    Stop,
    /// An applied load at a point of one body.
    Load,
    /// An elastic beam, drawn as the line from its start on body `i` to its end on body `j`.
    Beam,
}

/// Where an element sits, for a drawing of the model: its point on each of its two bodies in that body's
/// own frame (on the ground, globally), as [`ForceElement::bind`] fixed them, so that the poses of any
/// configuration place it. A bushing's two points coincide at design; their distance apart elsewhere is
/// its deflection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sketch {
    /// What it is.
    pub kind: SketchKind,
    /// Its point on body `i`, in `i`'s frame.
    pub on_i: Vec3,
    /// Its point on body `j`, in `j`'s frame.
    pub on_j: Vec3,
    /// Its own axes (columns: local x, y, z) in body `i`'s frame, for an element that has them.
    pub axes_i: Option<crate::math::Mat3>,
}

/// A force element copied and compared behind its box: what lets a [`Model`](crate::Model) be cloned (a
/// model built once and loaded two ways) and two models be told apart element by element (a replay's
/// moved model, whose move touched a few). Every element that is `Clone` and `PartialEq` has it.
pub trait CloneElement {
    /// A boxed copy of the element.
    fn clone_box(&self) -> Box<dyn ForceElement>;
    /// Whether `other` is an element of the same kind with the same numbers.
    fn same_as(&self, other: &dyn ForceElement) -> bool;
    /// The element as `Any`, for [`CloneElement::same_as`].
    fn as_any(&self) -> &dyn std::any::Any;
}

impl<T: ForceElement + Clone + PartialEq + 'static> CloneElement for T {
    fn clone_box(&self) -> Box<dyn ForceElement> {
        Box::new(self.clone())
    }

    fn same_as(&self, other: &dyn ForceElement) -> bool {
        other.as_any().downcast_ref::<T>() == Some(self)
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
}

impl Clone for Box<dyn ForceElement> {
    fn clone(&self) -> Self {
        self.clone_box()
    }
}

/// A bushing, spring, load or any other source of generalized force on one or two bodies.
pub trait ForceElement: std::fmt::Debug + Send + Sync + CloneElement {
    /// Unique name.
    fn name(&self) -> &str;
    /// The two bodies (`j` may be the ground; a load uses `i = Ground`).
    fn bodies(&self) -> [BodyRef; 2];
    /// Structure or load.
    fn role(&self) -> ElementRole;
    /// Validates the element and fixes its body-fixed geometry from the design poses. Called once by
    /// [`Model::add_element`](crate::Model::add_element).
    fn bind(&mut self, pi: &Pose, pj: &Pose) -> Result<(), ModelError>;
    /// Generalized force applied at the poses and load parameter `t`; stiffness too when
    /// `with_stiffness`.
    fn evaluate(&self, pi: &Pose, pj: &Pose, t: f64, out: &mut ElementEval, with_stiffness: bool);
    /// `∂Q/∂t` at fixed poses: the load increment direction (zero for elastic elements).
    fn load_rate(&self, _pi: &Pose, _pj: &Pose, _t: f64, out: &mut RowGradient) {
        out.fill(0.0);
    }
    /// Force, moment and deflection, for reports.
    fn report(&self, pi: &Pose, pj: &Pose, t: f64) -> ElementReport;
    /// The strain energy it stores at the poses (J), for an element whose law keeps one in closed form (a
    /// field, a beam); `None` for the others.
    fn energy(&self, _pi: &Pose, _pj: &Pose) -> Option<f64> {
        None
    }
    /// Which piece of its force law the element is on at the poses, for a law whose rate jumps between
    /// pieces (a stop whose force rises at once on contact: out of contact 0, in contact 1). Across such a
    /// jump the equilibrium has a kink and no derivative. A law whose rate is continuous (every other
    /// element, a progressive stop) is one piece: 0.
    fn piece(&self, _pi: &Pose, _pj: &Pose, _t: f64) -> u8 {
        0
    }
    /// Where the element sits, for drawings ([`Sketch`]); `None` for an element that has no place to
    /// draw (a pure moment).
    fn sketch(&self) -> Option<Sketch> {
        None
    }
}
