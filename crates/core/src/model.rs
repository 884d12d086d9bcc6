//! The [`Model`]: bodies, joints, drivers, elements and loads, by name.

use crate::body::{Body, BodyId, BodyRef};
use crate::element::ForceElement;
use crate::error::ModelError;
use crate::joint::{build_joint, Joint, JointSpec};
use crate::math::Vec3;
use crate::pose::{Pose, BODY_DOFS};
use std::collections::hash_map::Entry;
use std::collections::HashMap;
use std::sync::Arc;

/// Index of a joint in a [`Model`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct JointId(pub usize);
/// Index of an element in a [`Model`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ElementId(pub usize);

/// Where a constraint row comes from, for diagnostics.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RowOrigin {
    /// The joint.
    pub joint: JointId,
    /// The row within the joint.
    pub row: usize,
}

/// Where bodies' reference points are to be, by body name ([`Model::with_body_origins`]).
pub type BodyOrigins = HashMap<String, Vec3>;

/// What a name of a [`Model`] names: an index into its bodies, joints or elements.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Named {
    Body(usize),
    Joint(usize),
    Element(usize),
}

/// A scene of rigid bodies held by joints and force elements and loaded by loads and drivers.
///
/// The model owns exactly what the scene contains; the solver sizes and assembles only that. Bodies get
/// six coordinates each, in the order they were added; joint rows are numbered in the order the joints
/// were added (see [`Model::row_origin`]).
#[derive(Debug, Default, Clone)]
pub struct Model {
    bodies: Vec<Body>,
    joints: Vec<Joint>,
    /// After each joint, the number of constraint rows of it and all before it: joint `k`'s rows are
    /// `row_end[k - 1]..row_end[k]`. Kept as joints are added, so that a row's joint is found by bisection
    /// (a scan of the joints for each row made setting up a model quadratic in its size).
    row_end: Vec<usize>,
    elements: Vec<Box<dyn ForceElement>>,
    /// Every name given, with what it names: unique across bodies, joints and elements, and found at once
    /// (a scan per lookup made building a model of many bodies quadratic in their number).
    names: HashMap<String, Named>,
    /// Where the bodies named here get their reference point, whatever their builder asks.
    origins: Option<Arc<BodyOrigins>>,
}

impl Model {
    /// An empty model.
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty model whose bodies named in `origins` get their reference point there instead of where
    /// [`Model::add_body`] is asked to put it: what is built on them (joints, elements, loads, given in
    /// global design coordinates) is the same scene, in coordinates about those points. For a model built
    /// again with some of its numbers moved, kept in the coordinates of the model it was built from
    /// ([`Model::body_origins`]): a hardpoint that is also a body's reference point (an upright's at its
    /// wheel centre) then moves that point alone, not the body's coordinates, and a pose of the first model
    /// is the same placement of every material point in the second. (A replay's Newton iteration from a
    /// recorded equilibrium is then of the order of what the move changes, not of the move: its curvature
    /// in the move fell ten thousandfold on a steered MacPherson's toe.)
    pub fn with_body_origins(origins: Arc<BodyOrigins>) -> Self {
        Model { origins: Some(origins), ..Self::default() }
    }

    /// Each body's reference point at design, by name.
    pub fn body_origins(&self) -> BodyOrigins {
        self.bodies.iter().map(|b| (b.name.clone(), b.design_pose.position)).collect()
    }

    fn claim_name(&mut self, name: &str, named: Named) -> Result<(), ModelError> {
        match self.names.entry(name.to_string()) {
            Entry::Occupied(_) => Err(ModelError::DuplicateName { name: name.to_string() }),
            Entry::Vacant(v) => {
                v.insert(named);
                Ok(())
            }
        }
    }

    fn check_ref(&self, item: &str, r: BodyRef) -> Result<(), ModelError> {
        match r {
            BodyRef::Body(BodyId(index)) if index >= self.bodies.len() => {
                Err(ModelError::UnknownBody { item: item.to_string(), index, count: self.bodies.len() })
            }
            _ => Ok(()),
        }
    }

    fn design_pose(&self, r: BodyRef) -> Pose {
        match r {
            BodyRef::Ground => Pose::IDENTITY,
            BodyRef::Body(b) => self.bodies[b.0].design_pose,
        }
    }

    /// Adds a rigid body at its design pose.
    pub fn add_body(&mut self, name: &str, design_pose: Pose) -> Result<BodyId, ModelError> {
        if !design_pose.is_finite() {
            return Err(ModelError::NonFinite { item: name.to_string(), what: "design pose" });
        }
        self.claim_name(name, Named::Body(self.bodies.len()))?;
        let mut design_pose = design_pose;
        if let Some(at) = self.origins.as_ref().and_then(|o| o.get(name)) {
            design_pose.position = *at;
        }
        self.bodies.push(Body { name: name.to_string(), design_pose });
        Ok(BodyId(self.bodies.len() - 1))
    }

    /// Adds a joint or driver described by its global design geometry.
    pub fn add_joint(&mut self, spec: JointSpec) -> Result<JointId, ModelError> {
        self.check_ref(&spec.name, spec.body_i)?;
        self.check_ref(&spec.name, spec.body_j)?;
        if self.names.contains_key(&spec.name) {
            return Err(ModelError::DuplicateName { name: spec.name });
        }
        let (pi, pj) = (self.design_pose(spec.body_i), self.design_pose(spec.body_j));
        let joint = build_joint(spec, &pi, &pj)?;
        self.claim_name(joint.name(), Named::Joint(self.joints.len()))?;
        self.row_end.push(self.constraint_rows() + joint.rows.len());
        self.joints.push(joint);
        Ok(JointId(self.joints.len() - 1))
    }

    /// Adds a bushing, spring, load or other force element; it is bound to the design poses here.
    pub fn add_element(&mut self, mut element: impl ForceElement + 'static) -> Result<ElementId, ModelError> {
        let name = element.name().to_string();
        let [i, j] = element.bodies();
        self.check_ref(&name, i)?;
        self.check_ref(&name, j)?;
        if self.names.contains_key(&name) {
            return Err(ModelError::DuplicateName { name });
        }
        element.bind(&self.design_pose(i), &self.design_pose(j))?;
        self.claim_name(&name, Named::Element(self.elements.len()))?;
        self.elements.push(Box::new(element));
        Ok(ElementId(self.elements.len() - 1))
    }

    /// Holds driver `joint` at `travel` (m) from design along its direction or axis, whatever the load
    /// parameter: its row no longer moves with `t`. A rig that walks one motion at each position of another
    /// (the rack swept at each wheel height) holds the other's drivers so.
    pub fn hold_driver(&mut self, joint: JointId, travel: f64) -> Result<(), ModelError> {
        let Some(held) = self.joints.get(joint.0).filter(|j| j.is_driver()) else {
            return Err(ModelError::OutOfRange {
                item: format!("joint #{}", joint.0),
                why: "only a driver can be held at a travel: name a point or travel driver".into(),
            });
        };
        if !travel.is_finite() {
            return Err(ModelError::NonFinite { item: held.name().to_string(), what: "hardpoint or travel" });
        }
        let spec = JointSpec { travel: 0.0, ..held.spec.clone() };
        let (pi, pj) = (self.design_pose(spec.body_i), self.design_pose(spec.body_j));
        let mut rebuilt = build_joint(spec, &pi, &pj)?;
        for row in &mut rebuilt.rows {
            row.offset += travel;
        }
        self.joints[joint.0] = rebuilt;
        Ok(())
    }

    /// The bodies, indexed by [`BodyId`].
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }
    /// The joints and drivers, indexed by [`JointId`].
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }
    /// The force elements and loads, indexed by [`ElementId`].
    pub fn elements(&self) -> &[Box<dyn ForceElement>] {
        &self.elements
    }
    /// Looks up a body by name.
    pub fn body_id(&self, name: &str) -> Option<BodyId> {
        match self.names.get(name) {
            Some(Named::Body(i)) => Some(BodyId(*i)),
            _ => None,
        }
    }
    /// Looks up a joint by name.
    pub fn joint_id(&self, name: &str) -> Option<JointId> {
        match self.names.get(name) {
            Some(Named::Joint(i)) => Some(JointId(*i)),
            _ => None,
        }
    }
    /// Looks up an element by name.
    pub fn element_id(&self, name: &str) -> Option<ElementId> {
        match self.names.get(name) {
            Some(Named::Element(i)) => Some(ElementId(*i)),
            _ => None,
        }
    }
    /// Name of a body reference ("ground" for the ground).
    pub fn body_name(&self, r: BodyRef) -> &str {
        match r {
            BodyRef::Ground => "ground",
            BodyRef::Body(b) => &self.bodies[b.0].name,
        }
    }
    /// Design poses of all bodies: the starting configuration.
    pub fn design_poses(&self) -> Vec<Pose> {
        self.bodies.iter().map(|b| b.design_pose).collect()
    }
    /// Number of small-motion coordinates (6 per body).
    pub fn dofs(&self) -> usize {
        BODY_DOFS * self.bodies.len()
    }
    /// Number of constraint rows of all joints and drivers.
    pub fn constraint_rows(&self) -> usize {
        self.row_end.last().copied().unwrap_or(0)
    }
    /// Which joint and row a global constraint row index belongs to.
    pub fn row_origin(&self, row: usize) -> Option<RowOrigin> {
        // The first joint whose rows end after `row` (a joint without rows ends where it starts).
        let k = self.row_end.partition_point(|&end| end <= row);
        let start = if k == 0 { 0 } else { self.row_end[k - 1] };
        (k < self.joints.len()).then(|| RowOrigin { joint: JointId(k), row: row - start })
    }
    /// A readable name of a constraint row: `joint 'name' row 'label'`.
    pub fn describe_row(&self, row: usize) -> String {
        match self.row_origin(row) {
            Some(o) => {
                let j = &self.joints[o.joint.0];
                format!("joint '{}' row '{}'", j.name(), j.rows[o.row].label)
            }
            None => format!("constraint row #{row}"),
        }
    }

    /// Checks what can be checked without solving: every body is touched by some joint or element.
    /// (Directions that nothing restrains are found by the solver from the factorization.)
    pub fn validate(&self) -> Result<(), ModelError> {
        let mut held = vec![false; self.bodies.len()];
        let mut mark = |r: BodyRef| {
            if let BodyRef::Body(b) = r {
                held[b.0] = true;
            }
        };
        for j in &self.joints {
            mark(j.spec.body_i);
            mark(j.spec.body_j);
        }
        for e in self.elements.iter().filter(|e| e.role() == crate::element::ElementRole::Elastic) {
            let [i, j] = e.bodies();
            mark(i);
            mark(j);
        }
        match held.iter().position(|h| !h) {
            Some(b) => Err(ModelError::NothingHolds { body: self.bodies[b].name.clone() }),
            None => Ok(()),
        }
    }
}
