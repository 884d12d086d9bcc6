//! Twist-beam axle template: two trailing arms pivoting on the chassis, welded to a cross member that
//! twists in roll, the wheel carrier at each arm's end with a coil spring on it (`docs/twist-beam.md`).
//! The arms and the cross member are elastic beams; the axle is built whole.

use crate::description::connection::{Connection, SpringSpec};
use crate::description::general::{
    Axis, AxleDef, BeamDef, BodyPoint, BushingDef, GeneralCorner, Place, SpringDef, CHASSIS,
};
use crate::description::layout::Layout;
use crate::description::limits::default_loaded_radius;
use crate::description::section::SectionDef;
use crate::description::side::Side;
use elastokin_core::{JointKind, Vec3};
use serde::{Deserialize, Serialize};

/// Hardpoints of the left side of a twist-beam axle (ISO 8855, metres).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TwistBeamHardpoints {
    /// Wheel centre.
    #[serde(deserialize_with = "crate::description::side::point")]
    pub wheel_centre: Vec3,
    /// The arm's pivot on the chassis (the bushing's centre).
    #[serde(deserialize_with = "crate::description::side::point")]
    pub pivot: Vec3,
    /// Where the cross member meets the arm (the centroid of its end section).
    #[serde(deserialize_with = "crate::description::side::point")]
    pub junction: Vec3,
    /// The arm's end at the wheel carrier.
    #[serde(deserialize_with = "crate::description::side::point")]
    pub arm_end: Vec3,
    /// Spring seat on the chassis.
    #[serde(deserialize_with = "crate::description::side::point")]
    pub spring_chassis: Vec3,
    /// Spring seat on the wheel carrier.
    #[serde(deserialize_with = "crate::description::side::point")]
    pub spring_seat: Vec3,
}

impl TwistBeamHardpoints {
    /// Every hardpoint with its model-file name, the wheel centre first.
    pub fn named(&self) -> Vec<(&'static str, Vec3)> {
        vec![
            ("wheel_centre", self.wheel_centre),
            ("pivot", self.pivot),
            ("junction", self.junction),
            ("arm_end", self.arm_end),
            ("spring_chassis", self.spring_chassis),
            ("spring_seat", self.spring_seat),
        ]
    }
}

/// The cross member: its section (y forward, z up; a shear centre above the centroid has `e_z > 0`) and
/// how many segments it is built of.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CrossMember {
    /// The section.
    pub section: SectionDef,
    /// Segments (default 6: each bends through well under a tenth of a radian in a car's roll).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub segments: Option<usize>,
}

/// A twist-beam axle (see the [module docs](self)).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TwistBeam {
    /// Hardpoints of the left side.
    pub hardpoints: TwistBeamHardpoints,
    /// The arm's pivots on the chassis: an ideal hinge across the car (`"ideal"`), or a bushing (its axis
    /// across the car unless given).
    pub pivots: Connection,
    /// The arms' section (y across the car, z down along the arm's x from pivot to wheel), from the pivot
    /// to the junction and on to the arm's end.
    pub arms: SectionDef,
    /// The cross member.
    pub cross_member: CrossMember,
    /// Coil spring from the chassis seat to the wheel carrier's.
    pub spring: SpringSpec,
    /// Static toe of the left wheel (deg, toe-in +).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub toe: f64,
    /// Static camber of the left wheel (deg, top outward +).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub camber: f64,
    /// Loaded tyre radius (m).
    #[serde(default = "default_loaded_radius")]
    pub loaded_radius: f64,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

impl TwistBeam {
    /// The default number of the cross member's segments.
    pub const SEGMENTS: usize = 6;

    /// The left wheel's outward spin axis at its static toe and camber ([`Side::spin_axis`]).
    pub fn spin_axis(&self) -> [f64; 3] {
        Side::Left.spin_axis(self.toe.to_radians(), self.camber.to_radians()).into()
    }

    /// The axle in the general form: per side the bodies `arm eye` (at the pivot), `arm` (at the junction)
    /// and `wheel carrier` (at the wheel centre), the pivot's bushing or hinge, the beams `arm front` and
    /// `arm rear`, the spring; once, the beam `cross member` from `left arm` to `right arm`.
    pub fn expand(&self) -> GeneralCorner {
        let wheel_top = self.hardpoints.wheel_centre + Vec3::new(0.0, 0.0, 0.1);
        let steering_axis = [
            BodyPoint { body: "wheel carrier".into(), at: Place::named("wheel_centre") },
            BodyPoint { body: "wheel carrier".into(), at: Place::At(wheel_top) },
        ];
        let mut g = GeneralCorner::empty(self.loaded_radius, steering_axis, None);
        g.corner.upright = "wheel carrier".into();
        g.corner.spin_axis = self.spin_axis();
        g.hardpoints.0 = self.hardpoints.named().into_iter().map(|(n, p)| (n.to_string(), p)).collect();
        for (name, at) in [("arm eye", "pivot"), ("arm", "junction"), ("wheel carrier", "wheel_centre")] {
            g.bodies.push(crate::description::general::BodyDef { name: name.into(), at: Place::named(at) });
        }
        let across = Axis::Vector(Vec3::y());
        match self.pivots {
            Connection::Ideal => {
                g.push_joint("pivot", JointKind::Revolute, [CHASSIS, "arm eye"], "pivot", Some(across))
            }
            Connection::Bushing(rates) => g.bushings.push(BushingDef::cylindrical(
                "pivot bushing",
                [CHASSIS, "arm eye"],
                Place::named("pivot"),
                across,
                &rates,
            )),
        }
        let beam = |name: &str, bodies: [&str; 2], ends: [&str; 2], y: Vec3, section: SectionDef, segments| BeamDef {
            name: name.into(),
            bodies: bodies.map(str::to_string),
            from: Place::named(ends[0]),
            to: Place::named(ends[1]),
            y_axis: Axis::Vector(y),
            section,
            segments,
        };
        g.beams.push(beam("arm front", ["arm eye", "arm"], ["pivot", "junction"], Vec3::y(), self.arms, None));
        g.beams.push(beam("arm rear", ["arm", "wheel carrier"], ["junction", "arm_end"], Vec3::y(), self.arms, None));
        g.springs.push(SpringDef {
            name: "spring".into(),
            bodies: [CHASSIS.into(), "wheel carrier".into()],
            from: Place::named("spring_chassis"),
            to: Place::named("spring_seat"),
            rate: Some(self.spring.rate),
            curve: None,
            design_force: Some(self.spring.design_force),
            free_length: None,
            preload: None,
        });
        let segments = Some(self.cross_member.segments.unwrap_or(Self::SEGMENTS));
        g.axle = Some(AxleDef {
            beams: vec![beam(
                "cross member",
                ["left arm", "right arm"],
                ["left junction", "right junction"],
                Vec3::x(),
                self.cross_member.section,
                segments,
            )],
            ..AxleDef::default()
        });
        g
    }

    /// Where its parts are, by hardpoint name (see [`Layout`]).
    pub(crate) fn layout(&self) -> Layout {
        Layout {
            wheel_centre: "wheel_centre".into(),
            steering_axis: None,
            tie_rod: None,
            arms: Vec::new(),
            spring: Some((
                ["spring_chassis".into(), "spring_seat".into()],
                "wheel carrier".into(),
                "move 'spring_seat' further from the pivot, along the arm".into(),
            )),
        }
    }
}

impl From<&TwistBeam> for GeneralCorner {
    fn from(template: &TwistBeam) -> GeneralCorner {
        template.expand()
    }
}
