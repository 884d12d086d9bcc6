//! A drawing of a built model: what a geometry view or a 3D view shows of it, and where each thing sits
//! on its body, so that the poses of any solved configuration place the whole drawing.
//!
//! Everything is read off the built [`Model`] (its joints and its elements' [`Sketch`](elastokin_core::Sketch)es) and its wheels,
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
            if !spec.kind.has_place() {
                continue;
            }
            let on_j = spec.point_j.unwrap_or(spec.point);
            let ends =
                [Anchor::at_design(model, spec.body_i, &spec.point), Anchor::at_design(model, spec.body_j, &on_j)];
            let guided = spec.kind.guided_by_axis();
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

/// What a stroke of a view is: each is drawn in its own colour and weight.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Pen {
    /// A part's outline: a link's line, an arm's triangle, or spokes from a larger part's centre.
    Part,
    /// A link that is a constraint, not a body (an ideal tie rod, a drop link).
    Link,
    /// A spring between its seats.
    Spring,
    /// A stop between its points.
    Stop,
    /// An elastic beam, from its start to its end.
    Beam,
    /// A bushing's axis, through its point.
    Bushing,
    /// A bushing's deflection, [`DEFLECTION_SCALE`] times its length, from its point on body `j`.
    Deflection,
    /// A wheel: the circle of its loaded radius.
    Wheel,
    /// A steering axis, from its lower point through its upper.
    SteeringAxis,
}

impl Pen {
    /// The pen's name in a view's data and its style sheet.
    pub fn name(self) -> &'static str {
        match self {
            Pen::Part => "part",
            Pen::Link => "link",
            Pen::Spring => "spring",
            Pen::Stop => "stop",
            Pen::Beam => "beam",
            Pen::Bushing => "bushing",
            Pen::Deflection => "deflection",
            Pen::Wheel => "wheel",
            Pen::SteeringAxis => "steering-axis",
        }
    }
}

/// How many times its length a bushing's deflection is drawn: a tenth of a millimetre shows as 2 mm.
pub const DEFLECTION_SCALE: f64 = 20.0;

/// Half the length of a bushing's axis as drawn (m).
const BUSHING_MARK: f64 = 0.03;

/// Points on a wheel's circle as drawn.
const WHEEL_POINTS: usize = 48;

/// A line through anchored points (closed back to the first when `closed`): the one thing a view draws
/// besides dots, so that every view (the report's projections, its 3D view) draws the same lines.
#[derive(Debug, Clone, PartialEq)]
pub struct Stroke {
    /// How it is drawn.
    pub pen: Pen,
    /// What it belongs to (a part's, joint's, element's or wheel's name).
    pub name: String,
    /// Its points.
    pub anchors: Vec<Anchor>,
    /// Whether it closes back to its first point.
    pub closed: bool,
}

/// What a dot of a view marks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Spot {
    /// A joint's point.
    Joint,
    /// A bushing's point.
    Bushing,
    /// A point fixed to the chassis (a mount of a joint or an element on the ground).
    Mount,
    /// A wheel centre.
    WheelCentre,
}

impl Spot {
    /// The spot's name in a view's data and its style sheet.
    pub fn name(self) -> &'static str {
        match self {
            Spot::Joint => "joint",
            Spot::Bushing => "bushing",
            Spot::Mount => "mount",
            Spot::WheelCentre => "wheel-centre",
        }
    }
}

/// A dot of a view.
#[derive(Debug, Clone, PartialEq)]
pub struct Dot {
    /// What it marks.
    pub spot: Spot,
    /// What it belongs to.
    pub name: String,
    /// Where.
    pub at: Anchor,
}

impl Drawing {
    /// The lines a view draws: parts, links, springs, stops, bushings (their axes and deflections),
    /// wheels and steering axes, in that order (later ones over earlier ones).
    pub fn strokes(&self) -> Vec<Stroke> {
        let mut out = Vec::new();
        for (b, part) in self.parts.iter().enumerate() {
            let on = |point: Vec3| Anchor { body: BodyRef::Body(elastokin_core::BodyId(b)), point };
            let stroke = |anchors: Vec<Anchor>, closed: bool| Stroke {
                pen: Pen::Part,
                name: part.name.clone(),
                anchors,
                closed,
            };
            match part.points.len() {
                0 | 1 => {}
                2 | 3 => out.push(stroke(part.points.iter().map(|&p| on(p)).collect(), part.points.len() == 3)),
                n => {
                    let centre = part.points.iter().sum::<Vec3>() / n as f64;
                    out.extend(part.points.iter().map(|&p| stroke(vec![on(centre), on(p)], false)));
                }
            }
        }
        for j in self.joints.iter().filter(|j| j.kind == JointKind::Distance) {
            out.push(Stroke { pen: Pen::Link, name: j.name.clone(), anchors: j.ends.to_vec(), closed: false });
        }
        for e in &self.elements {
            let pen = match e.kind {
                SketchKind::Spring => Pen::Spring,
                SketchKind::Stop => Pen::Stop,
                SketchKind::Beam => Pen::Beam,
                SketchKind::Bushing => {
                    if let Some(axes) = e.axes {
                        let x = axes.column(0) * BUSHING_MARK;
                        let anchors =
                            [-1.0, 1.0].map(|s| Anchor { body: e.ends[0].body, point: e.ends[0].point + x * s });
                        out.push(Stroke {
                            pen: Pen::Bushing,
                            name: e.name.clone(),
                            anchors: anchors.to_vec(),
                            closed: false,
                        });
                    }
                    Pen::Deflection
                }
                SketchKind::Load => continue,
            };
            out.push(Stroke { pen, name: e.name.clone(), anchors: e.ends.to_vec(), closed: false });
        }
        for w in &self.wheels {
            let (u, v) = elastokin_core::joint::orthonormal_complement(&w.spin_axis);
            let anchors = (0..WHEEL_POINTS)
                .map(|k| {
                    let a = std::f64::consts::TAU * k as f64 / WHEEL_POINTS as f64;
                    Anchor { body: w.upright, point: w.centre + (u * a.cos() + v * a.sin()) * w.radius }
                })
                .collect();
            out.push(Stroke { pen: Pen::Wheel, name: "wheel".into(), anchors, closed: true });
            out.push(Stroke {
                pen: Pen::SteeringAxis,
                name: "steering axis".into(),
                anchors: w.steering_axis.to_vec(),
                closed: false,
            });
        }
        out
    }

    /// The dots a view draws: joints, bushings, chassis mounts and wheel centres.
    pub fn dots(&self) -> Vec<Dot> {
        let mut out = Vec::new();
        let mut mark = |spot: Spot, name: &str, at: Anchor| {
            let spot = if at.body == BodyRef::Ground { Spot::Mount } else { spot };
            out.push(Dot { spot, name: name.to_string(), at });
        };
        for j in &self.joints {
            for end in &j.ends {
                mark(Spot::Joint, &j.name, *end);
            }
        }
        // A beam's ends are points of the bodies it joins, not joints: its line says where it is.
        for e in self.elements.iter().filter(|e| !matches!(e.kind, SketchKind::Load | SketchKind::Beam)) {
            let spot = if e.kind == SketchKind::Bushing { Spot::Bushing } else { Spot::Joint };
            for end in &e.ends {
                mark(spot, &e.name, *end);
            }
        }
        for w in &self.wheels {
            mark(Spot::WheelCentre, "wheel centre", Anchor { body: w.upright, point: w.centre });
        }
        out
    }
}
