//! The general model being written from a Chrono file: hardpoints, bodies, joints, bushings, springs and
//! shocks added as Chrono's templates place them, with the frames Chrono gives its joints and what was
//! noted on the way.

use super::error::{Expected, KeyPath, Refusal};
use crate::description::general::{
    Axis, AxleDef, BodyDef, BodyPoint, BushingDef, GeneralCorner, Hardpoints, JointDef, Place, SpringDef, StopDef,
    StopType, TieRodDef, CHASSIS,
};
use crate::description::limits::{
    default_loaded_radius, MAX_COORDINATE, ROTATIONAL_RATE_RANGE, TRANSLATIONAL_RATE_RANGE,
};
use crate::description::{Connection, Side};
use crate::import::chrono::doc::Doc;
use elastokin_core::{JointKind, Vec3};
use elastokin_elements::RotationLaw;

/// The general model being written, and what was noted on the way.
pub(crate) struct Builder {
    pub(crate) general: GeneralCorner,
    pub(crate) notes: Vec<String>,
    /// Whether parts go to the axle (the parts the two corners share, [`AxleDef`]) rather than the corner.
    shared: bool,
}

impl Builder {
    pub(crate) fn new(doc: &Doc, loaded_radius: Option<f64>) -> Self {
        let mut notes = Vec::new();
        if loaded_radius.is_none() {
            notes.push(format!(
                "loaded tyre radius: not in a Chrono suspension file; {} m taken (edit corner.loaded_radius)",
                default_loaded_radius()
            ));
        }
        doc.expect("Name");
        // The steering axis is the reader's to give; until then it is a point.
        let at_centre = || BodyPoint { body: "upright".into(), at: Place::named("wheel_centre") };
        let loaded_radius = loaded_radius.unwrap_or_else(default_loaded_radius);
        let general = GeneralCorner::empty(loaded_radius, [at_centre(), at_centre()], None);
        Builder { general, notes, shared: false }
    }

    /// Sends the parts that follow to the axle (`true`: shared by both corners, written as they are, not
    /// mirrored) or to the corner (`false`).
    pub(crate) fn on_axle(&mut self, shared: bool) {
        if shared && self.general.axle.is_none() {
            self.general.axle = Some(AxleDef::default());
        }
        self.shared = shared;
    }

    /// The axle's parts; made by [`Builder::on_axle`].
    pub(crate) fn axle(&mut self) -> &mut AxleDef {
        self.general.axle.as_mut().expect("on_axle(true) came first")
    }

    pub(crate) fn hardpoints_mut(&mut self) -> &mut Hardpoints {
        if self.shared {
            &mut self.axle().hardpoints
        } else {
            &mut self.general.hardpoints
        }
    }

    pub(crate) fn bodies_mut(&mut self) -> &mut Vec<BodyDef> {
        if self.shared {
            &mut self.axle().bodies
        } else {
            &mut self.general.bodies
        }
    }

    pub(crate) fn joints_mut(&mut self) -> &mut Vec<JointDef> {
        if self.shared {
            &mut self.axle().joints
        } else {
            &mut self.general.joints
        }
    }

    pub(crate) fn bushings_mut(&mut self) -> &mut Vec<BushingDef> {
        if self.shared {
            &mut self.axle().bushings
        } else {
            &mut self.general.bushings
        }
    }

    pub(crate) fn springs_mut(&mut self) -> &mut Vec<SpringDef> {
        if self.shared {
            &mut self.axle().springs
        } else {
            &mut self.general.springs
        }
    }

    pub(crate) fn stops_mut(&mut self) -> &mut Vec<StopDef> {
        if self.shared {
            &mut self.axle().stops
        } else {
            &mut self.general.stops
        }
    }

    /// The point of the hardpoint `name` where the parts go: the corner's (left side), or on the axle its
    /// own or a corner's as `"left …"` / `"right …"` placed on that side.
    pub(crate) fn point_of(&self, name: &str) -> Result<Vec3, Refusal> {
        let corner = |n: &str| self.general.hardpoints.get(n);
        let found = match (&self.general.axle, self.shared) {
            (Some(axle), true) => axle.hardpoints.get(name).or_else(|| {
                let (side, rest) = match name.strip_prefix("left ") {
                    Some(rest) => (Side::Left, rest),
                    None => (Side::Right, name.strip_prefix("right ")?),
                };
                corner(rest).map(|p| side.place(p))
            }),
            _ => corner(name),
        };
        found.ok_or_else(|| Refusal::no_hardpoint(name))
    }

    /// Adds the hardpoint `name` at the point read from `path`; returns its name.
    pub(crate) fn hardpoint(&mut self, doc: &Doc, name: &str, path: &str) -> Result<String, Refusal> {
        let p = doc.point(path)?;
        // Refused here, by the file's key, before a frame or a midpoint is taken from it.
        if p.amax() > MAX_COORDINATE {
            return Err(Refusal::unusable(&path.split('/').collect::<Vec<_>>(), format!(
                "\"{}\" [{:?}, {:?}, {:?}]: a coordinate beyond ±{MAX_COORDINATE} m; Chrono's points are in metres from the \
                 suspension's reference point",
                path.replace('/', "\" / \""),
                p.x,
                p.y,
                p.z
            )));
        }
        self.hardpoints_mut().0.push((name.to_string(), p));
        Ok(name.to_string())
    }

    /// The wheel: the spindle's centre, camber and toe, and the upright that carries it.
    pub(crate) fn wheel(&mut self, doc: &Doc) -> Result<(), Refusal> {
        self.hardpoint(doc, "wheel_centre", "Spindle/COM")?;
        self.general.bodies.push(BodyDef { name: "upright".into(), at: Place::named("wheel_centre") });
        doc.dynamics("Spindle", &["Mass", "Inertia", "Radius", "Width"], &mut self.notes);
        doc.dynamics(
            "Upright",
            &["Mass", "COM", "Inertia", "Moments of Inertia", "Products of Inertia", "Radius"],
            &mut self.notes,
        );
        doc.dynamics("Axle", &["Inertia"], &mut self.notes);
        doc.expect("Vehicle-Frame Inertia");
        let camber = doc.optional_number("Camber Angle (deg)")?.unwrap_or(0.0).to_radians();
        let toe = doc.optional_number("Toe Angle (deg)")?.unwrap_or(0.0).to_radians();
        self.general.corner.spin_axis = Side::Left.spin_axis(toe, camber).into();
        Ok(())
    }

    /// A rigid link named `name` from `from` on `bodies[0]` to `to` on `bodies[1]` (hardpoint names): a
    /// distance constraint.
    pub(crate) fn link(&mut self, name: &str, bodies: [&str; 2], from: &str, to: &str) {
        self.joints_mut().push(JointDef {
            name: name.into(),
            kind: JointKind::Distance,
            bodies: bodies.map(str::to_string),
            at: Some(Place::named(from)),
            to: Some(Place::named(to)),
            axis: None,
            axis_j: None,
        });
    }

    /// Adds a body at the hardpoint `at`.
    pub(crate) fn body(&mut self, name: &str, at: &str) {
        self.body_at(name, Place::named(at));
    }

    /// Adds a body with its reference point at `at`.
    pub(crate) fn body_at(&mut self, name: &str, at: Place) {
        self.bodies_mut().push(BodyDef { name: name.into(), at });
    }

    /// A rotational spring of `rate` (N·m/rad) about `axis` between `bodies`, pushing `preload` (N·m) about
    /// it on the second at design: a bushing of that torsion rate on the revolute joint the two bodies turn
    /// on about that axis, which holds its other directions (their rates, the least the engine takes, meet
    /// no deflection there), with Chrono's law `M = Kθ`.
    pub(crate) fn torsion_spring(
        &mut self,
        name: &str,
        bodies: [&str; 2],
        at: Place,
        axis: Vec3,
        rate: f64,
        preload: f64,
    ) {
        let (t, r) = (TRANSLATIONAL_RATE_RANGE.0, ROTATIONAL_RATE_RANGE.0);
        self.bushings_mut().push(BushingDef {
            name: name.into(),
            bodies: bodies.map(str::to_string),
            at,
            axis: Some(Axis::Vector(axis)),
            y_axis: None,
            radial: None,
            axial: None,
            torsion: None,
            conical: None,
            translation: Some([t.into(), t.into(), t.into()]),
            rotation: Some([rate.into(), r.into(), r.into()]),
            law: RotationLaw::Linear,
            preload_force: None,
            preload_torque: (preload != 0.0).then_some([preload, 0.0, 0.0]),
        });
    }

    /// The steering axis of a wheel carrier without a kingpin (a trailing arm that carries the spindle): the
    /// wheel's own vertical through its centre — the z axis of Chrono's spindle frame, the chassis's z turned
    /// by the toe and camber — from the wheel centre to the hardpoint `steering_axis_upper` 0.1 m up it, both
    /// on the upright. With no camber it is the vertical through the wheel centre: caster, kingpin
    /// inclination and kingpin offset zero.
    pub(crate) fn wheel_vertical_steering_axis(&mut self) -> Result<(), Refusal> {
        let centre =
            self.general.hardpoints.get("wheel_centre").ok_or_else(|| Refusal::no_hardpoint("wheel_centre"))?;
        let spin = Vec3::from(self.general.corner.spin_axis);
        let up = Vec3::z() - spin * spin.z;
        // Within the 60° of camber the general model takes, |up| = cos γ ≥ 0.5.
        if up.norm() <= 0.5 {
            return Err(Refusal::unusable(
                &["Camber Angle (deg)"],
                format!(
                "\"Camber Angle (deg)\" {:.1}: the wheel lies too flat to have a vertical; give a camber within ±60°",
                (-spin.z).asin().to_degrees()
            ),
            ));
        }
        self.general.hardpoints.0.push(("steering_axis_upper".into(), centre + 0.1 * up.normalize()));
        self.steering_axis(("upright", "wheel_centre"), ("upright", "steering_axis_upper"));
        Ok(())
    }

    /// The steering axis from `lower` on `lower_body` to `upper` on `upper_body`.
    pub(crate) fn steering_axis(&mut self, lower: (&str, &str), upper: (&str, &str)) {
        let at = |(body, point): (&str, &str)| BodyPoint { body: body.into(), at: Place::named(point) };
        self.general.corner.steering_axis = [at(lower), at(upper)];
    }

    /// A joint of `kind` at `at` (hardpoint name or coordinates), or — when `bushing` holds Chrono's
    /// `Bushing Data` — the bushing Chrono puts there instead. `frame` is Chrono's joint frame as `(u, w)`:
    /// w its axis, u its x axis (v = w × u).
    #[allow(
        clippy::too_many_arguments,
        reason = "a Chrono joint entry as the file gives it: name, kind, bodies, place, frame and bushing data"
    )]
    pub(crate) fn joint(
        &mut self,
        doc: &Doc,
        name: &str,
        kind: JointKind,
        bodies: [&str; 2],
        at: Place,
        frame: Option<(Vec3, Vec3)>,
        bushing: Option<&str>,
    ) -> Result<(), Refusal> {
        let data = bushing.filter(|path| doc.has(path));
        let Some(path) = data else {
            // Chrono's universal joint crosses the frame's u (on the first body) and v (on the second).
            let (axis, axis_j) = match (kind, frame) {
                (JointKind::Revolute | JointKind::Cylindrical, Some((_, w))) => (Some(Axis::Vector(w)), None),
                (JointKind::Universal, Some((u, w))) => (Some(Axis::Vector(u)), Some(Axis::Vector(w.cross(&u)))),
                // Chrono's point-line keeps the first body's point on the frame's x axis; point-plane on its
                // xy plane (normal z).
                (JointKind::InLine, Some((u, _))) => (Some(Axis::Vector(u)), None),
                (JointKind::InPlane, Some((_, w))) => (Some(Axis::Vector(w)), None),
                _ => (None, None),
            };
            self.joints_mut().push(JointDef {
                name: name.into(),
                kind,
                bodies: bodies.map(str::to_string),
                at: Some(at),
                to: None,
                axis,
                axis_j,
            });
            return Ok(());
        };
        // Chrono's K: translations all K_lin; rotations K_rot about the axes the joint holds, the DOF rate
        // about the ones it frees. The frame here: x = w (the axis), y = u, z = v.
        let k_lin = doc.number(&format!("{path}/Stiffness Linear"))?;
        let k_rot = doc.number(&format!("{path}/Stiffness Rotational"))?;
        let (k_lin_dof, k_rot_dof) = if doc.has(&format!("{path}/DOF")) {
            (
                doc.number(&format!("{path}/DOF/Stiffness Linear"))?,
                doc.number(&format!("{path}/DOF/Stiffness Rotational"))?,
            )
        } else {
            (0.0, 0.0)
        };
        for damping in ["Damping Linear", "Damping Rotational", "DOF/Damping Linear", "DOF/Damping Rotational"] {
            doc.expect(&format!("{path}/{damping}"));
        }
        let _ = k_lin_dof; // Chrono applies it to no direction of the joints it uses for suspensions.
        let (u, w) = frame.unwrap_or((Vec3::x(), Vec3::z()));
        // About (w, u, v):
        let rotation = match kind {
            JointKind::Spherical => [k_rot_dof; 3],
            JointKind::Revolute => [k_rot_dof, k_rot, k_rot],
            JointKind::Universal => [k_rot, k_rot_dof, k_rot_dof],
            _ => [k_rot; 3],
        };
        let least = |k: f64, (lo, _): (f64, f64), what: &str, notes: &mut Vec<String>| {
            if k < lo {
                notes.push(format!(
                    "{}: {what} rate {k} taken as {lo} (the least the engine takes: a rate of zero holds nothing)",
                    doc.shown(path)
                ));
                lo
            } else {
                k
            }
        };
        let t = least(k_lin, TRANSLATIONAL_RATE_RANGE, "linear", &mut self.notes);
        let mut r = [0.0; 3];
        for (slot, k) in r.iter_mut().zip(rotation) {
            *slot = least(k, ROTATIONAL_RATE_RANGE, "rotational", &mut self.notes);
        }
        self.notes.dedup();
        self.bushings_mut().push(BushingDef {
            name: name.into(),
            bodies: bodies.map(str::to_string),
            at,
            axis: Some(Axis::Vector(w)),
            y_axis: Some(Axis::Vector(u)),
            radial: None,
            axial: None,
            torsion: None,
            conical: None,
            translation: Some([t.into(), t.into(), t.into()]),
            rotation: Some(r.map(Into::into)),
            law: RotationLaw::Linear,
            preload_force: None,
            preload_torque: None,
        });
        Ok(())
    }

    /// A Chrono spring (`ChLinkTSDA` read by its functor) named `name` between `bodies`, seats `from`, `to`
    /// (hardpoint names); with its stops when it has `Minimum Length` and `Maximum Length`. `object` is
    /// its JSON object.
    pub(crate) fn spring(
        &mut self,
        doc: &Doc,
        object: &str,
        name: &str,
        bodies: [&str; 2],
        seats: [&str; 2],
    ) -> Result<(), Refusal> {
        let key = |k: &str| format!("{object}/{k}");
        let free_length = doc.number(&key("Free Length"))?;
        let preload = doc.optional_number(&key("Preload"))?;
        let (rate, curve) = if doc.has(&key("Spring Curve Data")) {
            // Chrono: push = P − f(L − L₀); here: push against compression c = L₀ − L, so (−x, −f).
            let mut table: Vec<[f64; 2]> =
                doc.table(&key("Spring Curve Data"))?.into_iter().map(|[x, f]| [-x, -f]).collect();
            table.reverse();
            (None, Some(table))
        } else {
            (Some(doc.number(&key("Spring Coefficient"))?), None)
        };
        for damping in
            ["Damping Coefficient", "Damping Curve Data", "Degressivity Compression", "Degressivity Expansion"]
        {
            if doc.has(&key(damping)) {
                doc.expect(&key(damping));
                self.notes.push(format!("{} / {damping}: damping, left out (statics: no velocity)", doc.shown(object)));
            }
        }
        self.springs_mut().push(SpringDef {
            name: name.into(),
            bodies: bodies.map(str::to_string),
            from: Place::named(seats[0]),
            to: Place::named(seats[1]),
            rate,
            curve,
            design_force: None,
            free_length: Some(free_length),
            preload: preload.filter(|p| *p != 0.0),
        });
        if let (Some(min), Some(max)) =
            (doc.optional_number(&key("Minimum Length"))?, doc.optional_number(&key("Maximum Length"))?)
        {
            if min >= max {
                // Chrono would press both stops at once: past its table each holds its last force, so between
                // the two they cancel, and the spring meets a wall where either leaves that plateau.
                let design = (self.point_of(seats[1])? - self.point_of(seats[0])?).norm();
                let [.., [reach, most]] = CHRONO_STOP_CURVE;
                return Err(Refusal::unusable(
                    &[object, "Minimum Length", "Maximum Length"],
                    format!(
                    "\"{object}\" / \"Minimum Length\" {min} m is not below \"Maximum Length\" {max} m: the stops are \
                     crossed (the bump stop acts below the minimum, the rebound stop above the maximum, so here both \
                     press at once: in Chrono {most} N each way, cancelling from {:.4} to {:.4} m and stopping the \
                     spring hard outside that); give Minimum Length below the spring's design length {design:.4} m \
                     and Maximum Length above it ({max} and {min}, swapped), or remove them to leave the spring \
                     without stops",
                    max + reach,
                    min - reach
                ),
                ));
            }
            let design = (self.point_of(seats[1])? - self.point_of(seats[0])?).norm();
            for (kind, clearance, what) in
                [(StopType::Bump, design - min, "Minimum Length"), (StopType::Rebound, max - design, "Maximum Length")]
            {
                if clearance < 0.0 {
                    self.notes.push(format!(
                        "{} / {what} {} m: the stop is in contact at the design length {design:.4} m, by {:.4} m",
                        doc.shown(object),
                        if kind == StopType::Bump { min } else { max },
                        -clearance
                    ));
                }
                let stop = if kind == StopType::Bump { "bump stop" } else { "rebound stop" };
                self.stops_mut().push(StopDef {
                    name: format!("{name} {stop}"),
                    kind,
                    bodies: bodies.map(str::to_string),
                    from: Place::named(seats[0]),
                    to: Place::named(seats[1]),
                    clearance,
                    curve: CHRONO_STOP_CURVE.to_vec(),
                });
            }
            self.notes.push(format!(
                "{} / Minimum Length, Maximum Length: a bump and a rebound stop with Chrono's built-in curve",
                doc.shown(object)
            ));
        }
        Ok(())
    }

    /// A Chrono shock: a damper, left out in statics; a spring-damper's spring (`Spring Coefficient` or a
    /// curve) is a spring named `name` between `bodies`, at the shock's points `seats` (JSON keys under
    /// `Shock`).
    pub(crate) fn shock(&mut self, doc: &Doc, name: &str, bodies: [&str; 2], seats: [&str; 2]) -> Result<(), Refusal> {
        if doc.has("Shock/Spring Coefficient") || doc.has("Shock/Spring Curve Data") {
            let from = self.hardpoint(doc, "shock_chassis", &format!("Shock/{}", seats[0]))?;
            let to = self.hardpoint(
                doc,
                &format!("shock_{}", seats[1].trim_start_matches("Location ").to_lowercase()),
                &format!("Shock/{}", seats[1]),
            )?;
            return self.spring(doc, "Shock", name, bodies, [&from, &to]);
        }
        for key in seats.iter().copied().chain([
            "Damping Coefficient",
            "Damping Curve Data",
            "Degressivity Compression",
            "Degressivity Expansion",
            "Map Data",
        ]) {
            doc.expect(&format!("Shock/{key}"));
        }
        if doc.has("Shock") {
            self.notes.push("Shock: a damper, left out (statics: no velocity)".into());
        }
        Ok(())
    }

    /// An arm's points: its pivots `<key> / Location Chassis Front` and `… Back` and its ball joint
    /// `… Location Upright`, as the hardpoints `<short>_arm_front`, `<short>_arm_back` and `<short>_ball_joint`;
    /// its `dynamics` keys read and left out. Returns the three names.
    pub(crate) fn arm_points(
        &mut self,
        doc: &Doc,
        key: &str,
        short: &str,
        dynamics: &[&str],
    ) -> Result<[String; 3], Refusal> {
        let front = self.hardpoint(doc, &format!("{short}_arm_front"), &format!("{key}/Location Chassis Front"))?;
        let back = self.hardpoint(doc, &format!("{short}_arm_back"), &format!("{key}/Location Chassis Back"))?;
        let ball = self.hardpoint(doc, &format!("{short}_ball_joint"), &format!("{key}/Location Upright"))?;
        doc.dynamics(key, dynamics, &mut self.notes);
        Ok([front, back, ball])
    }

    /// The arm `<short> arm` on the points of [`Builder::arm_points`]: a revolute joint `<short> arm pivot` to
    /// the chassis at the pivots' midpoint in [`arm_frame`] (Chrono's bushing there when `bushing`, its path,
    /// holds `Bushing Data`) and the ball joint `<short> ball joint` to the upright. With `degenerate`, an arm
    /// with no plane (its ball joint on its pivot axis) is refused with that message.
    pub(crate) fn arm_joints(
        &mut self,
        doc: &Doc,
        short: &str,
        [front, back, ball]: &[String; 3],
        bushing: Option<&str>,
        degenerate: Option<Refusal>,
    ) -> Result<(), Refusal> {
        let arm = format!("{short} arm");
        self.body(&arm, ball);
        let mut frame = arm_frame(self.point_of(front)?, self.point_of(back)?, self.point_of(ball)?);
        if let Some(why) = degenerate {
            frame = checked_frame(frame, why)?;
        }
        let at = midpoint(self, front, back)?;
        self.joint(doc, &format!("{arm} pivot"), JointKind::Revolute, [CHASSIS, &arm], at, Some(frame), bushing)?;
        self.joint(
            doc,
            &format!("{short} ball joint"),
            JointKind::Spherical,
            [&arm, "upright"],
            Place::named(ball),
            None,
            None,
        )
    }

    /// The spring from `Spring / Location Chassis` to `Spring / Location <seat>` (hardpoints `spring_chassis`
    /// and `spring_<seat>`) and the shock between the same keys under `Shock`, both from the chassis to
    /// `body`.
    pub(crate) fn spring_and_shock(&mut self, doc: &Doc, body: &str, seat: &str) -> Result<(), Refusal> {
        let on_body = format!("Location {seat}");
        let c = self.hardpoint(doc, "spring_chassis", "Spring/Location Chassis")?;
        let s = self.hardpoint(doc, &format!("spring_{}", seat.to_lowercase()), &format!("Spring/{on_body}"))?;
        self.spring(doc, "Spring", "spring", [CHASSIS, body], [&c, &s])?;
        self.shock(doc, "shock", [CHASSIS, body], ["Location Chassis", &on_body])
    }

    /// The tie rod from `inner` to `outer`: a distance link, or Chrono's rod body (`Mass` given) with a
    /// universal joint at the rack and a ball joint at the upright, which with ideal joints is the same
    /// link. With `Bushing Data` on the rod both joints are Chrono's bushings.
    pub(crate) fn tie_rod(&mut self, doc: &Doc, inner: &str, outer: &str) -> Result<(), Refusal> {
        doc.dynamics("Tierod", &["Mass", "Inertia", "Radius"], &mut self.notes);
        if doc.has("Tierod/Bushing Data") {
            let path = "Tierod/Bushing Data";
            let k_lin = doc.number(&format!("{path}/Stiffness Linear"))?;
            let k_rot = doc.number(&format!("{path}/Stiffness Rotational"))?;
            let k_rot_dof = doc.optional_number(&format!("{path}/DOF/Stiffness Rotational"))?.unwrap_or(0.0);
            for k in [
                "Damping Linear",
                "Damping Rotational",
                "DOF/Damping Linear",
                "DOF/Damping Rotational",
                "DOF/Stiffness Linear",
            ] {
                doc.expect(&format!("{path}/{k}"));
            }
            // Chrono's rod has a universal joint at the rack (its twist about the rod held: k_rot) and a ball
            // joint at the upright (every rotation free: the DOF rate), each a bushing with this data.
            let (lo, _) = ROTATIONAL_RATE_RANGE;
            let dof = k_rot_dof.max(lo);
            let rates = |torsion: f64| {
                Connection::Bushing(crate::description::BushingRates {
                    radial: k_lin.max(TRANSLATIONAL_RATE_RANGE.0),
                    axial: k_lin.max(TRANSLATIONAL_RATE_RANGE.0),
                    torsion,
                    conical: dof,
                    law: RotationLaw::Linear,
                    axis: None,
                })
            };
            self.notes.push(format!(
                "Tierod / Bushing Data: a rod with a bushing at each end, radial and axial {k_lin} N/m, conical {dof} \
                 N·m/rad; torsion {} N·m/rad at the rack (Chrono's universal joint), {dof} at the upright (its ball joint)",
                k_rot.max(lo)
            ));
            self.general.corner.tie_rod = Some(TieRodDef {
                inner: Place::named(inner),
                outer: Place::named(outer),
                connection: crate::description::connection::TieRodMounts {
                    inner: rates(k_rot.max(lo)),
                    outer: rates(dof),
                },
            });
        } else {
            self.general.corner.tie_rod = Some(TieRodDef {
                inner: Place::named(inner),
                outer: Place::named(outer),
                connection: Connection::Ideal.into(),
            });
        }
        Ok(())
    }

    /// The notes, with every key of the document that was not read.
    pub(crate) fn finish(&mut self, doc: &Doc) -> Vec<String> {
        let mut notes = std::mem::take(&mut self.notes);
        notes.extend(doc.unread().into_iter().map(|k| format!("{k}: not understood, left out")));
        notes
    }
}

/// Chrono's built-in stop curve (`SpringForce::enable_stops`, from an ADAMS/Car example): force (N)
/// against travel past contact (m). Chrono's table (`ChFunctionInterp`, not extrapolating) holds its last
/// force past 60 mm; elastokin's curve continues straight with its end slope, so that flat end is written
/// out as a last point at 70 mm (the cubic then arrives level at 60 mm, where Chrono's straight pieces
/// turn sharply: between 50 and 60 mm the two differ by up to 13 kN, as they did without that point, now
/// mostly above Chrono's). It matters where a stop is driven past 60 mm: Chrono's `DeDionAxle` file has
/// both stops 80 mm in contact at design, where they cancel.
pub const CHRONO_STOP_CURVE: [[f64; 2]; 12] = [
    [0.0, 0.0],
    [2.0e-3, 200.0],
    [4.0e-3, 400.0],
    [6.0e-3, 600.0],
    [8.0e-3, 800.0],
    [10.0e-3, 1000.0],
    [20.0e-3, 2500.0],
    [30.0e-3, 4500.0],
    [40.0e-3, 7500.0],
    [50.0e-3, 12500.0],
    [60.0e-3, 125000.0],
    [70.0e-3, 125000.0],
];

/// Chrono's frame of a revolute joint between an arm and the chassis, from the arm's front and back pivots
/// and its outer point: w along the pivot axis (front − back), v normal to the arm's plane, u = v × w.
/// Returns `(u, w)`.
pub(crate) fn arm_frame(front: Vec3, back: Vec3, outer: Vec3) -> (Vec3, Vec3) {
    let v = (back - outer).cross(&(front - outer)).normalize();
    let w = (front - back).normalize();
    (v.cross(&w), w)
}

/// The midpoint of two hardpoints of `b`.
pub(crate) fn midpoint(b: &Builder, p: &str, q: &str) -> Result<Place, Refusal> {
    Ok(Place::At((b.point_of(p)? + b.point_of(q)?) / 2.0))
}

/// A direction `[x, y, z]` at `path` (any length but zero).
pub(crate) fn direction(doc: &Doc, path: &str) -> Result<Vec3, Refusal> {
    let wrong = |expected| Refusal::WrongType { at: KeyPath::written(path), expected };
    let d = doc.point(path).map_err(|_| wrong(Expected::Direction))?;
    // Scaled by its largest component, so that its length is finite however long it is given.
    let largest = d.amax();
    if largest == 0.0 {
        return Err(wrong(Expected::NonZeroDirection));
    }
    Ok(d / largest)
}

/// Chrono's frame of a universal joint whose cross pins are `u` (on the first body) and `v` made
/// perpendicular to it (on the second), as [`Builder::joint`] takes it: `(û, ŵ)` with ŵ = û × v
/// normalised, so that the joint crosses û with ŵ × û. `parallel` is the refusal when the two are
/// parallel.
pub(crate) fn cross_frame(u: Vec3, v: Vec3, parallel: Refusal) -> Result<(Vec3, Vec3), Refusal> {
    let (u, v) = (u.normalize(), v.normalize());
    let w = u.cross(&v);
    // Finite: a zero direction is refused by `direction`, which also scales a long one.
    if w.norm() <= 1e-6 {
        return Err(parallel);
    }
    Ok((u, w.normalize()))
}

/// `frame` (a `(u, w)` of [`Builder::joint`]) when it is one: finite, of unit axes. `why` says what makes it
/// fail, and how to fix that.
pub(crate) fn checked_frame(frame: (Vec3, Vec3), why: Refusal) -> Result<(Vec3, Vec3), Refusal> {
    let unit = |a: Vec3| (a.norm() - 1.0).abs() < 1e-9;
    if unit(frame.0) && unit(frame.1) {
        Ok(frame)
    } else {
        Err(why)
    }
}
