//! Kinematic joints and drivers, built from the rows of [`constraint`](crate::constraint).
//!
//! A joint is described by its *design geometry* in global coordinates (a hardpoint, an axis), the way a
//! suspension engineer gives it; [`Model::add_joint`](crate::Model::add_joint) turns it into body-fixed
//! rows using the design poses. Orientation rows use two unit vectors orthogonal to the axis rather than a
//! 3-row cross product, so the rows stay independent.
//!
//! | joint | rows | removes |
//! |---|---|---|
//! | spherical | 3 | translations |
//! | revolute | 5 | all but rotation about the axis |
//! | cylindrical | 4 | all but translation along and rotation about the axis |
//! | translational | 5 | all but translation along the axis |
//! | universal | 4 | translations, rotation about the common normal of the two axes |
//! | fixed | 6 | everything |
//! | distance | 1 | change of the distance of two points |
//! | in-plane | 1 | motion of a point of `i` normal to a plane of `j` |
//! | in-line | 2 | motion of a point of `i` off a line of `j` |
//! | perpendicular | 1 | tilt of an axis of `i` towards an axis of `j` |
//! | parallel axes | 2 | tilt of an axis of `i` away from an axis of `j` |
//! | point driver | 1 | `e·P − e·P₀ = travel · t` for a point of `j` |
//! | travel driver | 1 | `h·(Pⱼ − Pᵢ) = travel · t` along a translational/cylindrical axis |

use crate::body::BodyRef;
use crate::constraint::{ConstraintRow, KinVec, Side};
use crate::error::ModelError;
use crate::math::Vec3;
use crate::pose::Pose;

/// What kind of joint a [`Joint`] is. Each kind declares here, once, what it is: its constraint rows
/// ([`build_joint`]), the geometry it takes ([`JointKind::geometry`]), whether it is a rig's driver and how
/// it is drawn; the model file, Python and the drawing read these. [`JointKind::all`] lists every kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, strum::EnumIter)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum JointKind {
    /// Ball joint: 3 rows.
    Spherical,
    /// Hinge: 5 rows.
    Revolute,
    /// Slides along and turns about an axis: 4 rows.
    Cylindrical,
    /// Slides along an axis: 5 rows.
    Translational,
    /// Cardan joint: 4 rows.
    Universal,
    /// Welds two bodies: 6 rows.
    Fixed,
    /// Massless rigid link between two points: 1 row.
    Distance,
    /// A point of `i` stays on a plane of `j`: 1 row.
    InPlane,
    /// A point of `i` stays on a line of `j`: 2 rows.
    InLine,
    /// An axis of `i` stays perpendicular to an axis of `j`: 1 row.
    Perpendicular,
    /// An axis of `i` stays parallel to an axis of `j`: 2 rows.
    ParallelAxes,
    /// Prescribed travel of a point of `j` along a global direction: 1 row.
    PointDriver,
    /// Prescribed relative travel along a translational or cylindrical axis: 1 row.
    TravelDriver,
}

/// Whether a joint kind takes a piece of its geometry ([`JointKind::geometry`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Takes {
    /// It needs it.
    Needed,
    /// It takes it if given (an in-plane or in-line joint's point on the second body, where it differs).
    Optional,
    /// It means nothing to the kind.
    Unused,
}

/// Which pieces of a [`JointSpec`]'s geometry a joint kind takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct JointGeometryTaken {
    /// `point`, where the joint is.
    pub point: Takes,
    /// `point_j`, a second point (a distance joint's other end).
    pub point_j: Takes,
    /// `axis`.
    pub axis: Takes,
    /// `axis_j`, the second body's axis.
    pub axis_j: Takes,
}

impl JointKind {
    /// Every kind, in the order declared.
    pub fn all() -> impl Iterator<Item = JointKind> {
        <JointKind as strum::IntoEnumIterator>::iter()
    }

    /// Whether it prescribes a motion (the rig's wheel or rack travel) rather than joins two parts.
    pub fn is_driver(self) -> bool {
        use JointKind as K;
        match self {
            K::PointDriver | K::TravelDriver => true,
            K::Spherical
            | K::Revolute
            | K::Cylindrical
            | K::Translational
            | K::Universal
            | K::Fixed
            | K::Distance
            | K::InPlane
            | K::InLine
            | K::Perpendicular
            | K::ParallelAxes => false,
        }
    }

    /// The pieces of geometry the kind takes: what a model file's joint entry must give, may give, and
    /// may not (a driver's are the rig's to set).
    pub fn geometry(self) -> JointGeometryTaken {
        use JointKind as K;
        use Takes::{Needed as N, Optional as O, Unused as U};
        let (point, point_j, axis, axis_j) = match self {
            K::Spherical | K::Fixed => (N, U, U, U),
            K::Revolute | K::Cylindrical | K::Translational => (N, U, N, U),
            K::Universal => (N, U, N, N),
            K::Distance => (N, N, U, U),
            K::InPlane | K::InLine => (N, O, N, U),
            K::Perpendicular => (U, U, N, N),
            K::ParallelAxes => (U, U, N, U),
            K::PointDriver | K::TravelDriver => (N, U, N, U),
        };
        JointGeometryTaken { point, point_j, axis, axis_j }
    }

    /// Whether the joint sits at a point a drawing marks: every kind but the drivers and those that hold
    /// only directions (perpendicular, parallel axes).
    pub fn has_place(self) -> bool {
        !self.is_driver() && self.geometry().point == Takes::Needed
    }

    /// Whether the joint's motion follows an axis a drawing marks through its point (a hinge, a slider, a
    /// cardan joint); an in-plane or in-line joint's axis is a plane's normal or a line, not drawn.
    pub fn guided_by_axis(self) -> bool {
        use JointKind as K;
        match self {
            K::Revolute | K::Cylindrical | K::Translational | K::Universal => true,
            K::Spherical
            | K::Fixed
            | K::Distance
            | K::InPlane
            | K::InLine
            | K::Perpendicular
            | K::ParallelAxes
            | K::PointDriver
            | K::TravelDriver => false,
        }
    }
}

/// Global design geometry of a joint: what a user writes.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct JointSpec {
    /// Unique name, used in diagnostics and results.
    pub name: String,
    /// Kind.
    pub kind: JointKind,
    /// First body (`i`).
    pub body_i: BodyRef,
    /// Second body (`j`); reactions are reported as acting on this body.
    pub body_j: BodyRef,
    /// Hardpoint at design (global). For a distance joint, the point on `i`; for a point driver, the
    /// driven point of `j`.
    pub point: Vec3,
    /// Second hardpoint: the point on `j` of a distance joint; the point of `j` a plane or line passes
    /// through (defaults to `point`).
    pub point_j: Option<Vec3>,
    /// Axis (global): hinge/slide axis; plane normal; line direction; axis of `i` (universal,
    /// perpendicular, parallel); driver direction.
    pub axis: Option<Vec3>,
    /// Second axis: the axis of `j` of a universal or perpendicular joint.
    pub axis_j: Option<Vec3>,
    /// Driver travel per unit load parameter (metres).
    pub travel: f64,
}

impl JointSpec {
    fn base(name: &str, kind: JointKind, i: impl Into<BodyRef>, j: impl Into<BodyRef>, point: Vec3) -> Self {
        JointSpec {
            name: name.to_string(),
            kind,
            body_i: i.into(),
            body_j: j.into(),
            point,
            point_j: None,
            axis: None,
            axis_j: None,
            travel: 0.0,
        }
    }
    /// Ball joint at `point`.
    pub fn spherical(name: &str, i: impl Into<BodyRef>, j: impl Into<BodyRef>, point: Vec3) -> Self {
        Self::base(name, JointKind::Spherical, i, j, point)
    }
    /// Hinge at `point` about `axis`.
    pub fn revolute(name: &str, i: impl Into<BodyRef>, j: impl Into<BodyRef>, point: Vec3, axis: Vec3) -> Self {
        JointSpec { axis: Some(axis), ..Self::base(name, JointKind::Revolute, i, j, point) }
    }
    /// Cylindrical joint on the line through `point` along `axis`.
    pub fn cylindrical(name: &str, i: impl Into<BodyRef>, j: impl Into<BodyRef>, point: Vec3, axis: Vec3) -> Self {
        JointSpec { axis: Some(axis), ..Self::base(name, JointKind::Cylindrical, i, j, point) }
    }
    /// Prismatic joint along `axis` through `point`.
    pub fn translational(name: &str, i: impl Into<BodyRef>, j: impl Into<BodyRef>, point: Vec3, axis: Vec3) -> Self {
        JointSpec { axis: Some(axis), ..Self::base(name, JointKind::Translational, i, j, point) }
    }
    /// Cardan joint at `point`: `axis_i` fixed in `i`, `axis_j` fixed in `j`, perpendicular at design.
    pub fn universal(
        name: &str,
        i: impl Into<BodyRef>,
        j: impl Into<BodyRef>,
        point: Vec3,
        axis_i: Vec3,
        axis_j: Vec3,
    ) -> Self {
        JointSpec { axis: Some(axis_i), axis_j: Some(axis_j), ..Self::base(name, JointKind::Universal, i, j, point) }
    }
    /// Welds `i` and `j`; reactions reported at `point`.
    pub fn fixed(name: &str, i: impl Into<BodyRef>, j: impl Into<BodyRef>, point: Vec3) -> Self {
        Self::base(name, JointKind::Fixed, i, j, point)
    }
    /// Rigid link from `point_i` on `i` to `point_j` on `j`, length taken at design.
    pub fn distance(name: &str, i: impl Into<BodyRef>, j: impl Into<BodyRef>, point_i: Vec3, point_j: Vec3) -> Self {
        JointSpec { point_j: Some(point_j), ..Self::base(name, JointKind::Distance, i, j, point_i) }
    }
    /// Point `point` of `i` stays on the plane of `j` through `point` with normal `normal`.
    pub fn in_plane(name: &str, i: impl Into<BodyRef>, j: impl Into<BodyRef>, point: Vec3, normal: Vec3) -> Self {
        JointSpec { axis: Some(normal), ..Self::base(name, JointKind::InPlane, i, j, point) }
    }
    /// Point `point` of `i` stays on the line of `j` through `point` along `direction`.
    pub fn in_line(name: &str, i: impl Into<BodyRef>, j: impl Into<BodyRef>, point: Vec3, direction: Vec3) -> Self {
        JointSpec { axis: Some(direction), ..Self::base(name, JointKind::InLine, i, j, point) }
    }
    /// `axis_i` of `i` stays perpendicular to `axis_j` of `j` (perpendicular at design).
    pub fn perpendicular(name: &str, i: impl Into<BodyRef>, j: impl Into<BodyRef>, axis_i: Vec3, axis_j: Vec3) -> Self {
        JointSpec {
            axis: Some(axis_i),
            axis_j: Some(axis_j),
            ..Self::base(name, JointKind::Perpendicular, i, j, Vec3::zeros())
        }
    }
    /// `axis` of `i` stays parallel to the same axis of `j`.
    pub fn parallel_axes(name: &str, i: impl Into<BodyRef>, j: impl Into<BodyRef>, axis: Vec3) -> Self {
        JointSpec { axis: Some(axis), ..Self::base(name, JointKind::ParallelAxes, i, j, Vec3::zeros()) }
    }
    /// Drives `point` of body `j` along the global `direction` by `travel · t` (e.g. wheel-centre height).
    pub fn point_driver(name: &str, j: impl Into<BodyRef>, point: Vec3, direction: Vec3, travel: f64) -> Self {
        JointSpec {
            axis: Some(direction),
            travel,
            ..Self::base(name, JointKind::PointDriver, BodyRef::Ground, j, point)
        }
    }
    /// Drives the relative travel of `j` along `axis` of `i` through `point` by `travel · t` (e.g. rack
    /// travel). Use it together with a translational or cylindrical joint.
    pub fn travel_driver(
        name: &str,
        i: impl Into<BodyRef>,
        j: impl Into<BodyRef>,
        point: Vec3,
        axis: Vec3,
        travel: f64,
    ) -> Self {
        JointSpec { axis: Some(axis), travel, ..Self::base(name, JointKind::TravelDriver, i, j, point) }
    }
}

/// A joint or driver of a [`Model`](crate::Model): its design description and its body-fixed rows.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// What the user gave.
    pub spec: JointSpec,
    /// Body-fixed rows, in the order reported by diagnostics.
    pub rows: Vec<ConstraintRow>,
    /// The hardpoint as a local offset on `j`, where reactions are reported.
    pub anchor_on_j: Vec3,
}

impl Joint {
    /// Name.
    pub fn name(&self) -> &str {
        &self.spec.name
    }
    /// Kind.
    pub fn kind(&self) -> JointKind {
        self.spec.kind
    }
    /// True for a driver.
    pub fn is_driver(&self) -> bool {
        self.spec.kind.is_driver()
    }
}

fn unit(name: &str, what: &'static str, v: Option<Vec3>) -> Result<Vec3, ModelError> {
    let v = v.ok_or_else(|| ModelError::MissingGeometry { joint: name.to_string(), what })?;
    let n = v.norm();
    if !n.is_finite() {
        return Err(ModelError::NonFinite { item: name.to_string(), what });
    }
    if n < 1e-12 {
        return Err(ModelError::ZeroLengthAxis { item: name.to_string(), what });
    }
    Ok(v / n)
}

/// Two unit vectors completing `h` to a right-handed orthonormal frame.
pub fn orthonormal_complement(h: &Vec3) -> (Vec3, Vec3) {
    let helper = if h.x.abs() < 0.6 {
        Vec3::x()
    } else if h.y.abs() < 0.6 {
        Vec3::y()
    } else {
        Vec3::z()
    };
    let u = h.cross(&helper).normalize();
    let v = h.cross(&u);
    (u, v)
}

/// Turns a joint's global design geometry into body-fixed rows.
pub(crate) fn build_joint(spec: JointSpec, pi: &Pose, pj: &Pose) -> Result<Joint, ModelError> {
    let name = spec.name.as_str();
    let finite = |v: &Vec3| v.iter().all(|c| c.is_finite());
    if !finite(&spec.point) || spec.point_j.is_some_and(|p| !finite(&p)) || !spec.travel.is_finite() {
        return Err(ModelError::NonFinite { item: name.to_string(), what: "hardpoint or travel" });
    }
    if spec.body_i == spec.body_j {
        return Err(ModelError::SelfJoint { joint: name.to_string() });
    }
    let p = spec.point;
    let sep = |a: Vec3, b: Vec3| KinVec::Separation { on_i: pi.to_local_point(&a), on_j: pj.to_local_point(&b) };
    let dir_i = |v: Vec3| KinVec::Direction(Side::I, pi.to_local_direction(&v));
    let dir_j = |v: Vec3| KinVec::Direction(Side::J, pj.to_local_direction(&v));
    let c = KinVec::Constant;
    let mut rows = Vec::with_capacity(6);
    let spherical = |rows: &mut Vec<ConstraintRow>| {
        rows.push(ConstraintRow::new("x", c(Vec3::x()), sep(p, p)));
        rows.push(ConstraintRow::new("y", c(Vec3::y()), sep(p, p)));
        rows.push(ConstraintRow::new("z", c(Vec3::z()), sep(p, p)));
    };
    // Axis of i kept parallel to the same axis of j: h_i ⊥ u_j, h_i ⊥ v_j.
    let parallel = |rows: &mut Vec<ConstraintRow>, h: Vec3| {
        let (u, v) = orthonormal_complement(&h);
        rows.push(ConstraintRow::new("axis ⊥ u", dir_i(h), dir_j(u)));
        rows.push(ConstraintRow::new("axis ⊥ v", dir_i(h), dir_j(v)));
    };
    // A point of j kept on the line of i through p along h: u_i·d = v_i·d = 0.
    let on_line = |rows: &mut Vec<ConstraintRow>, h: Vec3| {
        let (u, v) = orthonormal_complement(&h);
        rows.push(ConstraintRow::new("off-axis u", dir_i(u), sep(p, p)));
        rows.push(ConstraintRow::new("off-axis v", dir_i(v), sep(p, p)));
    };
    let mut anchor = p;
    match spec.kind {
        JointKind::Spherical => spherical(&mut rows),
        JointKind::Revolute => {
            let h = unit(name, "axis", spec.axis)?;
            spherical(&mut rows);
            parallel(&mut rows, h);
        }
        JointKind::Cylindrical | JointKind::Translational => {
            let h = unit(name, "axis", spec.axis)?;
            parallel(&mut rows, h);
            on_line(&mut rows, h);
            if spec.kind == JointKind::Translational {
                let (u, v) = orthonormal_complement(&h);
                rows.push(ConstraintRow::new("twist", dir_i(u), dir_j(v)));
            }
        }
        JointKind::Universal => {
            let hi = unit(name, "axis of i", spec.axis)?;
            let hj = unit(name, "axis of j", spec.axis_j)?;
            if hi.dot(&hj).abs() > 1e-6 {
                return Err(ModelError::NotPerpendicular { joint: name.to_string(), cosine: hi.dot(&hj) });
            }
            spherical(&mut rows);
            rows.push(ConstraintRow::new("cross axes ⊥", dir_i(hi), dir_j(hj)));
        }
        JointKind::Fixed => {
            spherical(&mut rows);
            rows.push(ConstraintRow::new("twist x", dir_i(Vec3::y()), dir_j(Vec3::z())));
            rows.push(ConstraintRow::new("twist y", dir_i(Vec3::z()), dir_j(Vec3::x())));
            rows.push(ConstraintRow::new("twist z", dir_i(Vec3::x()), dir_j(Vec3::y())));
        }
        JointKind::Distance => {
            let q = spec.point_j.ok_or(ModelError::MissingGeometry { joint: name.to_string(), what: "point on j" })?;
            let len = (q - p).norm();
            if len < 1e-9 {
                return Err(ModelError::CoincidentPoints { item: name.to_string(), distance: len });
            }
            let d = sep(p, q);
            rows.push(ConstraintRow { scale: 0.5 / len, offset: 0.5 * len, ..ConstraintRow::new("length", d, d) });
            anchor = q;
        }
        JointKind::InPlane => {
            let n = unit(name, "plane normal", spec.axis)?;
            let q = spec.point_j.unwrap_or(p);
            rows.push(ConstraintRow { offset: n.dot(&(q - p)), ..ConstraintRow::new("normal", dir_j(n), sep(p, q)) });
        }
        JointKind::InLine => {
            let h = unit(name, "line direction", spec.axis)?;
            let q = spec.point_j.unwrap_or(p);
            let (u, v) = orthonormal_complement(&h);
            rows.push(ConstraintRow {
                offset: u.dot(&(q - p)),
                ..ConstraintRow::new("off-line u", dir_j(u), sep(p, q))
            });
            rows.push(ConstraintRow {
                offset: v.dot(&(q - p)),
                ..ConstraintRow::new("off-line v", dir_j(v), sep(p, q))
            });
        }
        JointKind::Perpendicular => {
            let hi = unit(name, "axis of i", spec.axis)?;
            let hj = unit(name, "axis of j", spec.axis_j)?;
            if hi.dot(&hj).abs() > 1e-6 {
                return Err(ModelError::NotPerpendicular { joint: name.to_string(), cosine: hi.dot(&hj) });
            }
            rows.push(ConstraintRow::new("axes ⊥", dir_i(hi), dir_j(hj)));
        }
        JointKind::ParallelAxes => {
            let h = unit(name, "axis", spec.axis)?;
            parallel(&mut rows, h);
        }
        JointKind::PointDriver => {
            let e = unit(name, "driver direction", spec.axis)?;
            let s = pj.to_local_point(&p);
            rows.push(ConstraintRow {
                offset: e.dot(&p),
                driver_rate: spec.travel,
                ..ConstraintRow::new("travel", c(e), KinVec::Point(Side::J, s))
            });
        }
        JointKind::TravelDriver => {
            let h = unit(name, "driver axis", spec.axis)?;
            rows.push(ConstraintRow { driver_rate: spec.travel, ..ConstraintRow::new("travel", dir_i(h), sep(p, p)) });
        }
    }
    Ok(Joint { anchor_on_j: pj.to_local_point(&anchor), spec, rows })
}
