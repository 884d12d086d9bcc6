//! `Scene` and `SceneSweep`: a multibody scene built in code, body by body, and its equilibria along a
//! load path. The engine level under the model files: bodies, joints, bushings, springs, stops and loads
//! are the library's (`elastokin_core`, `elastokin_elements`), an entry is turned into them by the same
//! functions that read a model file's general form (`elastokin_suspensions::description::general`, built by `elastokin_suspensions::assembly::general`), and the solver is
//! `elastokin_solver::StaticSolver`. This converts arguments and results, maps the library's errors to
//! Python exceptions, and lets go of the GIL while the solver works.

use crate::errors::{AnalysisError, ModelError};
use elastokin_core::{BodyRef, ElementReport, JointKind, Model, Pose, Vec3};
use elastokin_elements::{beam, BeamSpec, PointForce, PointTorque, RotationLaw, Section};
use elastokin_solver::{JointReaction, LoadPath, Mode, SolverError, SolverOptions, StaticSolver, StepResult};
use elastokin_suspensions::analysis::{walk, ArcEnd, SweepExtras, SweepLimit};
use elastokin_suspensions::assembly::general::FramedEntry;
use elastokin_suspensions::assembly::{joint_spec, JointGeometry};
use elastokin_suspensions::description::general::{
    Axis, BushingDef, FieldDef, Place, SpringDef, Stiffness, StopDef, StopType, CHASSIS,
};
use elastokin_suspensions::kc::mode_word;
use elastokin_suspensions::Side;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyKeyError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// The other name of the ground, besides the model files' `"chassis"`.
const GROUND: &str = "ground";

/// The rotation laws of a bushing, by their model-file words.
const ROTATION_LAWS: [RotationLaw; 3] = [RotationLaw::Energy, RotationLaw::Linear, RotationLaw::TaitBryanXyz];

/// A library enum's model-file word (its serde name).
fn word<T: serde::Serialize>(value: &T) -> String {
    serde_json::to_value(value).ok().and_then(|v| v.as_str().map(str::to_string)).unwrap_or_default()
}

/// The value of an enum whose model-file word is `given`, or a `ValueError` listing the words.
fn by_word<T: serde::Serialize + Copy>(what: &str, given: &str, all: &[T]) -> PyResult<T> {
    all.iter().copied().find(|v| word(v) == given).ok_or_else(|| {
        let words: Vec<String> = all.iter().map(|v| format!("'{}'", word(v))).collect();
        PyValueError::new_err(format!("{what} '{given}': give one of {}", words.join(", ")))
    })
}

fn model_error(e: impl std::fmt::Display) -> PyErr {
    ModelError::new_err(e.to_string())
}

/// A bad scene is a `ModelError`; a solver that finds no equilibrium (or a free motion) an `AnalysisError`.
fn solver_error(e: SolverError) -> PyErr {
    match e {
        SolverError::Model(e) => ModelError::new_err(e.to_string()),
        other => AnalysisError::new_err(other.to_string()),
    }
}

/// A point or direction from Python, refused by name when not finite.
fn finite(item: &str, what: &'static str, v: [f64; 3]) -> PyResult<Vec3> {
    if v.iter().all(|c| c.is_finite()) {
        Ok(Vec3::from(v))
    } else {
        Err(model_error(elastokin_core::ModelError::NonFinite { item: item.to_string(), what }))
    }
}

/// A direction from Python: finite and of non-zero length.
fn direction(item: &str, what: &'static str, v: [f64; 3]) -> PyResult<Vec3> {
    let v = finite(item, what, v)?;
    if v.norm() < 1e-12 {
        return Err(model_error(elastokin_core::ModelError::ZeroLengthAxis { item: item.to_string(), what }));
    }
    Ok(v)
}

/// `'a', 'b' or 'c'` for messages.
fn listed(names: &[String]) -> String {
    let names: Vec<String> = names.iter().map(|n| format!("'{n}'")).collect();
    match names.as_slice() {
        [] => "none (add one with Scene.body first)".into(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}

/// A stiffness from Python: a rate, or a curve of `(deflection, force)` points.
#[derive(Debug, FromPyObject)]
enum StiffnessArg {
    Rate(f64),
    Curve(Vec<[f64; 2]>),
}

impl From<StiffnessArg> for Stiffness {
    fn from(s: StiffnessArg) -> Self {
        match s {
            StiffnessArg::Rate(k) => Stiffness::Rate(k),
            StiffnessArg::Curve(points) => Stiffness::Curve(points),
        }
    }
}

fn three(item: &str, what: &str, rates: Option<Vec<StiffnessArg>>) -> PyResult<Option<[Stiffness; 3]>> {
    let Some(rates) = rates else { return Ok(None) };
    let n = rates.len();
    let rates: Vec<Stiffness> = rates.into_iter().map(Stiffness::from).collect();
    <[Stiffness; 3]>::try_from(rates).map(Some).map_err(|_| {
        PyValueError::new_err(format!("bushing '{item}': {what} takes three rates or curves (x, y, z), got {n}"))
    })
}

/// What kind of element an element of the scene is, for what its report means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ElementKind {
    Bushing,
    Field,
    Beam,
    Spring,
    Stop,
    Force,
    Torque,
}

impl ElementKind {
    fn name(self) -> &'static str {
        match self {
            ElementKind::Bushing => "bushing",
            ElementKind::Field => "field",
            ElementKind::Beam => "beam",
            ElementKind::Spring => "spring",
            ElementKind::Stop => "stop",
            ElementKind::Force => "force",
            ElementKind::Torque => "torque",
        }
    }
}

/// A multibody scene: rigid bodies, kinematic joints, bushings, springs, stops and loads, built one at a
/// time. Points are global, at design, in metres; `"chassis"` (or `"ground"`) is the fixed ground.
#[pyclass(module = "elastokin._native")]
#[derive(Debug, Default)]
pub struct Scene {
    model: Model,
    kinds: Vec<ElementKind>,
}

impl Scene {
    /// The body named `name` (the ground for `"chassis"` or `"ground"`); `item` names the referring part.
    fn body_ref(&self, item: &str, name: &str) -> PyResult<BodyRef> {
        if name == CHASSIS || name == GROUND {
            return Ok(BodyRef::Ground);
        }
        match self.model.body_id(name) {
            Some(id) => Ok(id.into()),
            None => {
                let names: Vec<String> = self.model.bodies().iter().map(|b| b.name.clone()).collect();
                Err(ModelError::new_err(format!(
                    "'{item}': there is no body '{name}': add it with Scene.body first, or use \"{CHASSIS}\" or one \
                     of {}",
                    listed(&names)
                )))
            }
        }
    }

    fn pair(&self, item: &str, bodies: (String, String)) -> PyResult<[BodyRef; 2]> {
        Ok([self.body_ref(item, &bodies.0)?, self.body_ref(item, &bodies.1)?])
    }

    /// Refuses a name already taken before anything is built from it (the model refuses it too, later).
    fn fresh(&self, name: &str) -> PyResult<()> {
        let taken = self.model.body_id(name).is_some()
            || self.model.joint_id(name).is_some()
            || self.model.element_id(name).is_some();
        if taken {
            return Err(model_error(elastokin_core::ModelError::DuplicateName { name: name.to_string() }));
        }
        Ok(())
    }

    /// The loaded body: a moving one (a load on the ground would do nothing).
    fn loaded_body(&self, item: &str, name: &str) -> PyResult<BodyRef> {
        match self.body_ref(item, name)? {
            BodyRef::Ground => Err(ModelError::new_err(format!(
                "'{item}': a load on the ground (\"{name}\") moves nothing: put it on one of the scene's bodies"
            ))),
            body => Ok(body),
        }
    }

    fn add(&mut self, kind: ElementKind, element: impl elastokin_core::ForceElement + 'static) -> PyResult<()> {
        self.model.add_element(element).map_err(model_error)?;
        self.kinds.push(kind);
        Ok(())
    }

    fn options(force_tolerance: f64, constraint_tolerance: f64) -> PyResult<SolverOptions> {
        let options = SolverOptions { force_tolerance, constraint_tolerance, ..SolverOptions::default() };
        options.validate().map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(options)
    }
}

/// Runs the solver on `model` with the GIL released; a panic, which the library does not raise on any
/// input, becomes an `AnalysisError` rather than reaching Python.
fn solve_detached<T: Send>(py: Python<'_>, work: impl FnOnce() -> Result<T, SolverError> + Send) -> PyResult<T> {
    py.detach(|| catch_unwind(AssertUnwindSafe(work)))
        .map_err(|_| AnalysisError::new_err("the solver stopped on an internal error; please report the scene"))?
        .map_err(solver_error)
}

#[pymethods]
impl Scene {
    /// An empty scene.
    #[new]
    fn new() -> Self {
        Scene::default()
    }

    /// Adds a rigid body whose reference point is `at` at design (axes global); gives its name.
    fn body(&mut self, name: &str, at: [f64; 3]) -> PyResult<String> {
        if name == CHASSIS || name == GROUND {
            return Err(ModelError::new_err(format!(
                "body '{name}': \"{CHASSIS}\" and \"{GROUND}\" name the fixed ground: give the body another name"
            )));
        }
        let at = finite(name, "reference point 'at'", at)?;
        self.model.add_body(name, Pose::at(at)).map_err(model_error)?;
        Ok(name.to_string())
    }

    /// Adds a kinematic joint of `kind` between `bodies` (reactions are those on the second), with the
    /// keys its kind uses, as a model file's joint entry.
    #[pyo3(signature = (name, kind, bodies, at=None, to=None, axis=None, axis_j=None))]
    #[allow(clippy::too_many_arguments, reason = "a Python method's keyword arguments, each named by its caller")]
    fn joint(
        &mut self,
        name: &str,
        kind: &str,
        bodies: (String, String),
        at: Option<[f64; 3]>,
        to: Option<[f64; 3]>,
        axis: Option<[f64; 3]>,
        axis_j: Option<[f64; 3]>,
    ) -> PyResult<()> {
        // Every kind a model file takes: the drivers are a rig's.
        let kinds: Vec<JointKind> = JointKind::all().filter(|k| !k.is_driver()).collect();
        let kind = by_word("joint kind", kind, &kinds)?;
        let bodies = self.pair(name, bodies)?;
        self.fresh(name)?;
        let geometry = JointGeometry {
            at: at.map(|p| finite(name, "point 'at'", p)).transpose()?,
            to: to.map(|p| finite(name, "point 'to'", p)).transpose()?,
            axis: axis.map(|a| direction(name, "axis", a)).transpose()?,
            axis_j: axis_j.map(|a| direction(name, "axis_j", a)).transpose()?,
        };
        let spec = joint_spec(&format!("joint '{name}'"), name, kind, bodies, &geometry).map_err(model_error)?;
        self.model.add_joint(spec).map_err(model_error)?;
        Ok(())
    }

    /// Adds a rubber bushing between `bodies` centred at `at`, as a model file's bushing entry: its frame
    /// moves with the first body, x along `axis`, y towards `y_axis`; four cylindrical rates or six.
    #[pyo3(signature = (name, bodies, at, axis=None, y_axis=None, radial=None, axial=None, torsion=None,
                        conical=None, translation=None, rotation=None, law="energy", preload_force=None,
                        preload_torque=None))]
    #[allow(clippy::too_many_arguments, reason = "a Python method's keyword arguments, each named by its caller")]
    fn bushing(
        &mut self,
        name: &str,
        bodies: (String, String),
        at: [f64; 3],
        axis: Option<[f64; 3]>,
        y_axis: Option<[f64; 3]>,
        radial: Option<StiffnessArg>,
        axial: Option<StiffnessArg>,
        torsion: Option<StiffnessArg>,
        conical: Option<StiffnessArg>,
        translation: Option<Vec<StiffnessArg>>,
        rotation: Option<Vec<StiffnessArg>>,
        law: &str,
        preload_force: Option<[f64; 3]>,
        preload_torque: Option<[f64; 3]>,
    ) -> PyResult<()> {
        let law = by_word("rotation law", law, &ROTATION_LAWS)?;
        let [body_i, body_j] = self.pair(name, bodies.clone())?;
        self.fresh(name)?;
        let point = finite(name, "centre 'at'", at)?;
        let x = axis.map(|a| direction(name, "axis", a)).transpose()?.unwrap_or(Vec3::x());
        let y = y_axis.map(|a| direction(name, "y_axis", a)).transpose()?;
        let preload_force = preload_force.map(|f| finite(name, "preload_force", f)).transpose()?;
        let preload_torque = preload_torque.map(|m| finite(name, "preload_torque", m)).transpose()?;
        let def = BushingDef {
            name: name.to_string(),
            bodies: [bodies.0, bodies.1],
            at: Place::At(point),
            axis: Some(Axis::Vector(x)),
            y_axis: y.map(Axis::Vector),
            radial: radial.map(Stiffness::from),
            axial: axial.map(Stiffness::from),
            torsion: torsion.map(Stiffness::from),
            conical: conical.map(Stiffness::from),
            translation: three(name, "translation", translation)?,
            rotation: three(name, "rotation", rotation)?,
            law,
            preload_force: preload_force.map(Into::into),
            preload_torque: preload_torque.map(Into::into),
        };
        // The model file's reading of the rates, the frame and the preload; the scene is not mirrored.
        let bushing = def
            .bushing("bushing", name, &FramedEntry { bodies: [body_i, body_j], point, x, y }, Side::Left)
            .map_err(model_error)?;
        self.add(ElementKind::Bushing, bushing)
    }

    /// Adds a field element between `bodies` at `at`, as a model file's field entry: a 6×6 stiffness
    /// (six rows of six over the deflection along x, y, z and the rotation about them, in its frame),
    /// symmetric and positive semi-definite, coupled terms allowed; the frame as a bushing's.
    #[pyo3(signature = (name, bodies, at, stiffness, axis=None, y_axis=None, preload_force=None, preload_torque=None))]
    #[allow(clippy::too_many_arguments, reason = "a Python method's keyword arguments, each named by its caller")]
    fn field(
        &mut self,
        name: &str,
        bodies: (String, String),
        at: [f64; 3],
        stiffness: [[f64; 6]; 6],
        axis: Option<[f64; 3]>,
        y_axis: Option<[f64; 3]>,
        preload_force: Option<[f64; 3]>,
        preload_torque: Option<[f64; 3]>,
    ) -> PyResult<()> {
        let [body_i, body_j] = self.pair(name, bodies.clone())?;
        self.fresh(name)?;
        let point = finite(name, "point 'at'", at)?;
        let x = axis.map(|a| direction(name, "axis", a)).transpose()?.unwrap_or(Vec3::x());
        let y = y_axis.map(|a| direction(name, "y_axis", a)).transpose()?;
        let preload_force = preload_force.map(|f| finite(name, "preload_force", f)).transpose()?;
        let preload_torque = preload_torque.map(|m| finite(name, "preload_torque", m)).transpose()?;
        let def = FieldDef {
            name: name.to_string(),
            bodies: [bodies.0, bodies.1],
            at: Place::At(point),
            axis: Some(Axis::Vector(x)),
            y_axis: y.map(Axis::Vector),
            stiffness,
            preload_force: preload_force.map(Into::into),
            preload_torque: preload_torque.map(Into::into),
        };
        // The model file's reading of the matrix, the frame and the preload; the scene is not mirrored.
        let field = def.field("field", name, [body_i, body_j], point, x, y, Side::Left).map_err(model_error)?;
        self.add(ElementKind::Field, field)
    }

    /// Adds a straight elastic beam from `from_` on the first body to `to` on the second, by its section (SI:
    /// Pa, m², m⁴), the section's y axis leaning towards `y_axis`: one segment, large rigid motion and small
    /// strain (a member that bends far is split by adding bodies between beams).
    #[pyo3(signature = (name, bodies, from_, to, y_axis, youngs_modulus, shear_modulus, area, iy, iz, j,
                        shear_areas=None, shear_centre=None))]
    #[allow(clippy::too_many_arguments, reason = "a Python method's keyword arguments, each named by its caller")]
    fn beam(
        &mut self,
        name: &str,
        bodies: (String, String),
        from_: [f64; 3],
        to: [f64; 3],
        y_axis: [f64; 3],
        youngs_modulus: f64,
        shear_modulus: f64,
        area: f64,
        iy: f64,
        iz: f64,
        j: f64,
        shear_areas: Option<(f64, f64)>,
        shear_centre: Option<(f64, f64)>,
    ) -> PyResult<()> {
        let [body_i, body_j] = self.pair(name, bodies)?;
        self.fresh(name)?;
        let (from, to) = (finite(name, "start 'from_'", from_)?, finite(name, "end 'to'", to)?);
        let section = Section {
            youngs_modulus,
            shear_modulus,
            area,
            iy,
            iz,
            j,
            shear_areas,
            shear_centre: shear_centre.unwrap_or((0.0, 0.0)),
        };
        let y_axis = direction(name, "y_axis", y_axis)?;
        let spec = BeamSpec { name: name.to_string(), body_i, body_j, from, to, y_axis, section };
        self.add(ElementKind::Beam, beam(&spec).map_err(model_error)?)
    }

    /// Adds a coil spring pushing its seats apart, from `from_` on the first body to `to` on the second,
    /// as a model file's spring entry: a rate or a curve, its push at design or its free length.
    #[pyo3(signature = (name, bodies, from_, to, rate=None, curve=None, design_force=None, free_length=None,
                        preload=None))]
    #[allow(clippy::too_many_arguments, reason = "a Python method's keyword arguments, each named by its caller")]
    fn spring(
        &mut self,
        name: &str,
        bodies: (String, String),
        from_: [f64; 3],
        to: [f64; 3],
        rate: Option<f64>,
        curve: Option<Vec<[f64; 2]>>,
        design_force: Option<f64>,
        free_length: Option<f64>,
        preload: Option<f64>,
    ) -> PyResult<()> {
        let pair = self.pair(name, bodies.clone())?;
        self.fresh(name)?;
        let (from, to) = (finite(name, "seat 'from_'", from_)?, finite(name, "seat 'to'", to)?);
        let def = SpringDef {
            name: name.to_string(),
            bodies: [bodies.0, bodies.1],
            from: Place::At(from),
            to: Place::At(to),
            rate,
            curve,
            design_force,
            free_length,
            preload,
        };
        let spring = def.spring(&format!("spring ({name})"), name, pair, from, to).map_err(model_error)?;
        self.add(ElementKind::Spring, spring)
    }

    /// Adds a bump or rebound stop along the line from `from_` on the first body to `to` on the second, as
    /// a model file's stop entry.
    #[pyo3(signature = (name, kind, bodies, from_, to, clearance, curve))]
    #[allow(clippy::too_many_arguments, reason = "a Python method's keyword arguments, each named by its caller")]
    fn stop(
        &mut self,
        name: &str,
        kind: &str,
        bodies: (String, String),
        from_: [f64; 3],
        to: [f64; 3],
        clearance: f64,
        curve: Vec<[f64; 2]>,
    ) -> PyResult<()> {
        let kind = by_word("stop kind", kind, &[StopType::Bump, StopType::Rebound])?;
        let pair = self.pair(name, bodies.clone())?;
        self.fresh(name)?;
        let (from, to) = (finite(name, "point 'from_'", from_)?, finite(name, "point 'to'", to)?);
        let def = StopDef {
            name: name.to_string(),
            kind,
            bodies: [bodies.0, bodies.1],
            from: Place::At(from),
            to: Place::At(to),
            clearance,
            curve,
        };
        let stop = def.stop(&format!("stop ({name})"), name, pair, from, to).map_err(model_error)?;
        self.add(ElementKind::Stop, stop)
    }

    /// Adds a force at the point `at` of `body`, fixed in direction: `constant + t · force` (N, global).
    #[pyo3(signature = (name, body, at, force, constant=None))]
    fn force(
        &mut self,
        name: &str,
        body: &str,
        at: [f64; 3],
        force: [f64; 3],
        constant: Option<[f64; 3]>,
    ) -> PyResult<()> {
        let body = self.loaded_body(name, body)?;
        self.fresh(name)?;
        let at = finite(name, "point 'at'", at)?;
        let force = finite(name, "force", force)?;
        let constant = constant.map(|c| finite(name, "constant", c)).transpose()?.unwrap_or_default();
        let load =
            PointForce::new(name, body, at, force).and_then(|f| f.with_constant(constant)).map_err(model_error)?;
        self.add(ElementKind::Force, load)
    }

    /// Adds a moment on `body`, fixed in direction: `constant + t · torque` (N·m, global).
    #[pyo3(signature = (name, body, torque, constant=None))]
    fn torque(&mut self, name: &str, body: &str, torque: [f64; 3], constant: Option<[f64; 3]>) -> PyResult<()> {
        let body = self.loaded_body(name, body)?;
        self.fresh(name)?;
        let torque = finite(name, "torque", torque)?;
        let constant = constant.map(|c| finite(name, "constant", c)).transpose()?.unwrap_or_default();
        let load = PointTorque::new(name, body, torque).and_then(|m| m.with_constant(constant)).map_err(model_error)?;
        self.add(ElementKind::Torque, load)
    }

    /// The bodies' names, in the order they were added.
    #[getter]
    fn bodies(&self) -> Vec<String> {
        self.model.bodies().iter().map(|b| b.name.clone()).collect()
    }

    /// The joints' names, in the order they were added.
    #[getter]
    fn joints(&self) -> Vec<String> {
        self.model.joints().iter().map(|j| j.name().to_string()).collect()
    }

    /// The elements' names (bushings, springs, stops, loads), in the order they were added.
    #[getter]
    fn elements(&self) -> Vec<String> {
        self.model.elements().iter().map(|e| e.name().to_string()).collect()
    }

    /// Walks the load parameter from `start` to `end` in `steps` equal steps, in `mode` ("corrected" or
    /// "paper"), from the equilibrium at `start` found from the design pose, as the K&C analyses walk
    /// theirs: at a limit point the rows stop with the equilibrium there, or, `through_limits`, go on
    /// through it by arc length, the first arc-length step changing the load by `arc_step` (default one
    /// load step).
    #[pyo3(signature = (start, end, steps, mode="corrected", through_limits=false, arc_step=None,
                        force_tolerance=1e-9, constraint_tolerance=1e-10))]
    #[allow(clippy::too_many_arguments, reason = "a Python method's keyword arguments, each named by its caller")]
    fn sweep(
        &self,
        py: Python<'_>,
        start: f64,
        end: f64,
        steps: usize,
        mode: &str,
        through_limits: bool,
        arc_step: Option<f64>,
        force_tolerance: f64,
        constraint_tolerance: f64,
    ) -> PyResult<SceneSweep> {
        let mode = crate::words::mode_from_word(mode)?;
        LoadPath::check_steps(steps).map_err(|e| PyValueError::new_err(e.to_string()))?;
        if let Some(step) = arc_step.filter(|v| !(v.is_finite() && *v > 0.0)) {
            return Err(PyValueError::new_err(format!(
                "arc_step must be a positive change of the load parameter, got {step}"
            )));
        }
        let through = through_limits.then(|| arc_step.unwrap_or((end - start).abs() / steps as f64));
        let options = Self::options(force_tolerance, constraint_tolerance)?;
        let model = &self.model;
        let walked = solve_detached(py, || {
            let mut solver = StaticSolver::new(model, options)?;
            let mut state = solver.design_state(start);
            let extras = SweepExtras { through_limits: through, ..SweepExtras::default() };
            walk(&mut solver, &mut state, LoadPath::new(start, end, steps), mode, &extras)
        })?;
        Ok(SceneSweep::new(self, mode, walked.steps, walked.limit))
    }

    /// The equilibrium at load parameter `t`, found by Newton's method from the design pose.
    #[pyo3(signature = (t, force_tolerance=1e-9, constraint_tolerance=1e-10))]
    fn solve(&self, py: Python<'_>, t: f64, force_tolerance: f64, constraint_tolerance: f64) -> PyResult<SceneSweep> {
        if !t.is_finite() {
            return Err(PyValueError::new_err(format!("t = {t}: give a finite load parameter")));
        }
        let options = Self::options(force_tolerance, constraint_tolerance)?;
        let model = &self.model;
        let step = solve_detached(py, || {
            let mut solver = StaticSolver::new(model, options)?;
            let mut state = solver.design_state(t);
            solver.equilibrium(&mut state)
        })?;
        Ok(SceneSweep::new(self, Mode::Corrected, vec![step], None))
    }
}

/// The equilibria of a scene along a load path, with every body's pose, every joint's reaction and every
/// element's report at each, as the library computes them.
#[pyclass(frozen, module = "elastokin._native")]
#[derive(Debug)]
pub struct SceneSweep {
    mode: Mode,
    /// Name and design pose of every body.
    bodies: Vec<(String, Pose)>,
    joints: Vec<String>,
    elements: Vec<(String, ElementKind)>,
    steps: Vec<StepResult>,
    reactions: Vec<Vec<JointReaction>>,
    reports: Vec<Vec<ElementReport>>,
    /// Where the path met a limit point, and whether it went on through it.
    limit: Option<SweepLimit>,
}

impl SceneSweep {
    /// The results of `steps` of `scene`, read now: the sweep keeps no reference to the scene, which may
    /// grow after it.
    fn new(scene: &Scene, mode: Mode, steps: Vec<StepResult>, limit: Option<SweepLimit>) -> Self {
        let model = &scene.model;
        let reactions = steps.iter().map(|s| s.joint_reactions(model)).collect();
        let reports = steps.iter().map(|s| s.element_reports(model)).collect();
        SceneSweep {
            mode,
            bodies: model.bodies().iter().map(|b| (b.name.clone(), b.design_pose)).collect(),
            joints: model.joints().iter().map(|j| j.name().to_string()).collect(),
            elements: model.elements().iter().map(|e| e.name().to_string()).zip(scene.kinds.iter().copied()).collect(),
            steps,
            reactions,
            reports,
            limit,
        }
    }

    /// The body's index, `None` for the ground; a `KeyError` naming the bodies for another name.
    fn body_index(&self, name: &str) -> PyResult<Option<usize>> {
        if name == CHASSIS || name == GROUND {
            return Ok(None);
        }
        match self.bodies.iter().position(|(n, _)| n == name) {
            Some(k) => Ok(Some(k)),
            None => {
                let names: Vec<String> = self.bodies.iter().map(|(n, _)| n.clone()).collect();
                Err(PyKeyError::new_err(format!("there is no body '{name}': the scene's are {}", listed(&names))))
            }
        }
    }

    fn pose(&self, step: &StepResult, body: Option<usize>) -> Pose {
        body.map_or(Pose::IDENTITY, |k| step.poses[k])
    }

    fn rows<'py>(py: Python<'py>, rows: impl Iterator<Item = Vec3>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let flat: Vec<f64> = rows.flat_map(|v| [v.x, v.y, v.z]).collect();
        let n = flat.len() / 3;
        PyArray1::from_vec(py, flat).reshape([n, 3])
    }
}

#[pymethods]
impl SceneSweep {
    /// "corrected" or "paper".
    #[getter]
    fn mode(&self) -> &'static str {
        mode_word(self.mode)
    }

    /// The load parameter at each step.
    #[getter]
    fn t<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.steps.iter().map(|s| s.t).collect())
    }

    /// Newton iterations of each step (0 for a paper-mode step, which takes none).
    #[getter]
    fn iterations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        PyArray1::from_vec(py, self.steps.iter().map(|s| s.iterations as i64).collect())
    }

    /// `‖Φ_qᵀλ − Q‖∞` at each step (N and N·m).
    #[getter]
    fn force_residual<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.steps.iter().map(|s| s.force_residual).collect())
    }

    /// `‖Φ‖∞` at each step (m and rad).
    #[getter]
    fn constraint_residual<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.steps.iter().map(|s| s.constraint_residual).collect())
    }

    /// The load parameter of the limit point the path met (located to `LIMIT_POINT_TOLERANCE` of the
    /// range), or None when it met none. Without `through_limits` the rows stop there, the last one the
    /// equilibrium at the limit point.
    #[getter]
    fn limit(&self) -> Option<f64> {
        self.limit.map(|l| l.at)
    }

    /// With `through_limits`, the index of the first row walked by arc length past the limit point;
    /// None when the path went through none.
    #[getter]
    fn arc_length_from(&self) -> Option<usize> {
        self.limit.and_then(|l| l.through).map(|r| r.first_row)
    }

    /// Whether the path covered its range: it met no limit point, or went on through it by arc length
    /// until it left the range (rather than after the most steps allowed, or where it could be followed no further).
    #[getter]
    fn complete(&self) -> bool {
        self.limit.is_none_or(|l| l.through.is_some_and(|r| r.end == ArcEnd::LeftRange))
    }

    /// The bodies' names.
    #[getter]
    fn bodies(&self) -> Vec<String> {
        self.bodies.iter().map(|(n, _)| n.clone()).collect()
    }

    /// The joints' names.
    #[getter]
    fn joints(&self) -> Vec<String> {
        self.joints.clone()
    }

    /// The elements' names with their kinds ("bushing", "spring", "stop", "force", "torque").
    #[getter]
    fn elements(&self) -> Vec<(String, &'static str)> {
        self.elements.iter().map(|(n, k)| (n.clone(), k.name())).collect()
    }

    /// Where the body's reference point is at each step (m), one row per step.
    fn position<'py>(&self, py: Python<'py>, body: &str) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let k = self.body_index(body)?;
        Self::rows(py, self.steps.iter().map(|s| self.pose(s, k).position))
    }

    /// The body's rotation from its design attitude at each step: the rotation vector (axis times angle,
    /// rad, global components), one row per step.
    fn rotation<'py>(&self, py: Python<'py>, body: &str) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let k = self.body_index(body)?;
        Self::rows(py, self.steps.iter().map(|s| self.pose(s, k).orientation.scaled_axis()))
    }

    /// Where the body-fixed point that is at `at` at design (global, m) is at each step.
    fn point<'py>(&self, py: Python<'py>, body: &str, at: [f64; 3]) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let k = self.body_index(body)?;
        let at = finite(body, "point", at)?;
        let design = k.map_or(Pose::IDENTITY, |k| self.bodies[k].1);
        let local = design.to_local_point(&at);
        Self::rows(py, self.steps.iter().map(|s| self.pose(s, k).point(&local)))
    }

    /// The joint's reaction on its second body at each step: `(force, torque)`, the force (N) and the
    /// moment about the joint's point (N·m), global, one row per step.
    #[allow(clippy::type_complexity, reason = "the pair of NumPy arrays Python receives, spelled out")]
    fn reaction<'py>(
        &self,
        py: Python<'py>,
        joint: &str,
    ) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>)> {
        let Some(k) = self.joints.iter().position(|n| n == joint) else {
            return Err(PyKeyError::new_err(format!(
                "there is no joint '{joint}': the scene's are {}",
                listed(&self.joints)
            )));
        };
        Ok((
            Self::rows(py, self.reactions.iter().map(|r| r[k].force))?,
            Self::rows(py, self.reactions.iter().map(|r| r[k].torque))?,
        ))
    }

    /// The element's report at each step as a dict of arrays, one row per step: `force` it applies to its
    /// second body (N), `torque` about its point there (N·m), `deflection` (m) and `rotation` (rad) in its
    /// frame; and `kind`.
    fn element<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyDict>> {
        let Some(k) = self.elements.iter().position(|(n, _)| n == name) else {
            let names: Vec<String> = self.elements.iter().map(|(n, _)| n.clone()).collect();
            return Err(PyKeyError::new_err(format!(
                "there is no element '{name}': the scene's are {}",
                listed(&names)
            )));
        };
        let out = PyDict::new(py);
        out.set_item("kind", self.elements[k].1.name())?;
        out.set_item("force", Self::rows(py, self.reports.iter().map(|r| r[k].force))?)?;
        out.set_item("torque", Self::rows(py, self.reports.iter().map(|r| r[k].torque))?)?;
        out.set_item("deflection", Self::rows(py, self.reports.iter().map(|r| r[k].deflection))?)?;
        out.set_item("rotation", Self::rows(py, self.reports.iter().map(|r| r[k].rotation))?)?;
        Ok(out)
    }

    /// Number of steps (equilibria) held.
    fn __len__(&self) -> usize {
        self.steps.len()
    }
}
