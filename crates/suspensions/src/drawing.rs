//! A drawing of a built model: what a geometry view or a 3D view shows of it, and where each thing sits
//! on its body, so that the poses of any solved configuration place the whole drawing.
//!
//! Everything is read off the built [`Model`] (its joints and its elements' [`Sketch`]es) and its wheels,
//! so a template, the general form, an axle and a Chrono file are drawn alike. Each point is kept on the
//! body that carries it, in that body's frame (the ground's points are global): a joint's point on each
//! of its two bodies, which coincide at design and stay together wherever the joint holds them; a
//! bushing's point on each of its bodies, whose distance apart in any configuration is its deflection; a
//! spring's two seats.

use crate::wheel::Wheel;
use elastokin_core::{BodyRef, JointKind, Mat3, Model, Pose, SketchKind, Vec3};

/// A point carried by a body: in the body's frame, or globally on the ground.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Anchor {
    /// The body (or the ground).
    pub body: BodyRef,
    /// The point in the body's frame.
    pub point: Vec3,
}

impl Anchor {
    /// The anchor of the global design point `global` on `body`.
    fn at_design(model: &Model, body: BodyRef, global: &Vec3) -> Anchor {
        Anchor { body, point: body.pose(&model.design_poses()).to_local_point(global) }
    }

    /// Where it is at `poses` (global).
    pub fn placed(&self, poses: &[Pose]) -> Vec3 {
        self.body.pose(poses).point(&self.point)
    }
}

/// A joint as drawn: its point on each of its two bodies (the two ends of a distance link), and the axis
/// it guides along or about, if it has one.
#[derive(Debug, Clone, PartialEq)]
pub struct JointMark {
    /// The joint's name.
    pub name: String,
    /// What joint it is.
    pub kind: JointKind,
    /// Its point on body `i`, and on body `j`.
    pub ends: [Anchor; 2],
    /// Two points of its axis on body `i`, [`AXIS_MARK`] either side of its point, for a joint with an axis.
    pub axis: Option<[Anchor; 2]>,
}

/// An element as drawn: what it is, its points on its two bodies, and its axes where it has them.
#[derive(Debug, Clone, PartialEq)]
pub struct ElementMark {
    /// The element's name.
    pub name: String,
    /// What it is.
    pub kind: SketchKind,
    /// Its point on body `i`, and on body `j`.
    pub ends: [Anchor; 2],
    /// Its own x, y and z axes as directions in body `i`'s frame (columns), where it has them (a bushing).
    pub axes: Option<Mat3>,
}

/// A wheel as drawn: the circle of its loaded radius in the wheel plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelMark {
    /// The upright that carries it.
    pub upright: BodyRef,
    /// The wheel centre, in the upright's frame.
    pub centre: Vec3,
    /// The outward spin axis, in the upright's frame.
    pub spin_axis: Vec3,
    /// The loaded radius (m).
    pub radius: f64,
    /// Its steering axis: the lower and upper points, each on the body that carries it.
    pub steering_axis: [Anchor; 2],
}

/// A part as drawn: the points of it that joints, elements and its wheel use, in its frame.
#[derive(Debug, Clone, PartialEq)]
pub struct PartMark {
    /// The body's name.
    pub name: String,
    /// Its points, each once, in the order they were met.
    pub points: Vec<Vec3>,
}

/// How far either side of a joint's point its axis is drawn (m).
pub const AXIS_MARK: f64 = 0.04;

/// Two points closer than this (m) are drawn as one.
const SAME_POINT: f64 = 1e-6;

/// Everything a view of one built model draws.
#[derive(Debug, Clone, PartialEq)]
pub struct Drawing {
    /// The parts, one per body of the model, in the model's order.
    pub parts: Vec<PartMark>,
    /// The joints that have a place (not the rig's drivers, not pure orientation constraints).
    pub joints: Vec<JointMark>,
    /// The elements that have a place.
    pub elements: Vec<ElementMark>,
    /// The wheels.
    pub wheels: Vec<WheelMark>,
}

impl Drawing {
    /// The drawing of `model`, with its `wheels`.
    pub fn of(model: &Model, wheels: &[&Wheel]) -> Drawing {
        let mut joints = Vec::new();
        for joint in model.joints() {
            let spec = &joint.spec;
            let has_place = !joint.is_driver()
                && !matches!(spec.kind, JointKind::Perpendicular | JointKind::ParallelAxes);
            if !has_place {
                continue;
            }
            let on_j = spec.point_j.unwrap_or(spec.point);
            let ends = [
                Anchor::at_design(model, spec.body_i, &spec.point),
                Anchor::at_design(model, spec.body_j, &on_j),
            ];
            let guided = matches!(
                spec.kind,
                JointKind::Revolute | JointKind::Cylindrical | JointKind::Translational | JointKind::Universal
            );
            let axis = spec.axis.filter(|a| guided && a.norm() > 0.0).map(|a| {
                let a = a.normalize() * AXIS_MARK;
                [spec.point - a, spec.point + a].map(|p| Anchor::at_design(model, spec.body_i, &p))
            });
            joints.push(JointMark { name: spec.name.clone(), kind: spec.kind, ends, axis });
        }
        let mut elements = Vec::new();
        for element in model.elements() {
            let Some(sketch) = element.sketch() else { continue };
            let [bi, bj] = element.bodies();
            elements.push(ElementMark {
                name: element.name().to_string(),
                kind: sketch.kind,
                ends: [Anchor { body: bi, point: sketch.on_i }, Anchor { body: bj, point: sketch.on_j }],
                axes: sketch.axes_i,
            });
        }
        let wheels: Vec<WheelMark> = wheels
            .iter()
            .map(|w| WheelMark {
                upright: BodyRef::Body(w.upright),
                centre: w.wheel_centre_local,
                spin_axis: w.spin_axis_local,
                radius: (w.wheel_centre - w.contact_patch).norm(),
                steering_axis: w.steering_axis.map(|(body, point)| Anchor { body, point }),
            })
            .collect();
        let mut parts: Vec<PartMark> =
            model.bodies().iter().map(|b| PartMark { name: b.name.clone(), points: Vec::new() }).collect();
        let mut add = |a: &Anchor| {
            if let Some(b) = a.body.id() {
                let points = &mut parts[b.0].points;
                if !points.iter().any(|p| (p - a.point).norm() < SAME_POINT) {
                    points.push(a.point);
                }
            }
        };
        for j in &joints {
            j.ends.iter().for_each(&mut add);
        }
        for e in elements.iter().filter(|e| e.kind != SketchKind::Load) {
            e.ends.iter().for_each(&mut add);
        }
        for w in &wheels {
            add(&Anchor { body: w.upright, point: w.centre });
        }
        Drawing { parts, joints, elements, wheels }
    }
}

/// A drawing and the configurations an analysis solved, one per row of its table: what a view moves
/// through as its slider moves.
#[derive(Debug, Clone, PartialEq)]
pub struct Motion {
    /// The model drawn.
    pub drawing: Drawing,
    /// The bodies' poses at each row (in the model's order of bodies).
    pub frames: Vec<Vec<Pose>>,
}
