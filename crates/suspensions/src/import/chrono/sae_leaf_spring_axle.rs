//! Chrono's SAE leaf-spring axles: `SAELeafspringAxle` (`ChSAELeafspringAxle`, the spindles turn on the
//! tube) and `SAEToeBarLeafspringAxle` (`ChSAEToeBarLeafspringAxle`, knuckles on kingpins, a toe bar across
//! and a drag link). Chrono models each leaf spring as the SAE Spring Design Handbook's linkage: rigid
//! bodies on joints, with rotational spring-dampers (`ChLinkRSDA`) for the leaf's bending and the clamp's
//! lateral give. That is joints and springs, read as they are: the tube (and the toe bar and drag link)
//! on the model's `axle` ([`crate::description::general::AxleDef`]), each side's leaf as the left corner's parts,
//! mirrored.
//!
//! Each side's leaf, as `InitializeSide` builds it:
//! - the front leaf, from `Location Front Hanger` (a ball joint to the chassis) to `Location Clamp A`;
//! - the rear leaf, from `Location Shackle` (a ball joint to the shackle) to `Location Clamp B`;
//! - the shackle, on a revolute joint to the chassis at `Location Rear Hanger` about y;
//! - the half clamps A and B, each on a revolute joint to the tube about z at its point, and each leaf on a
//!   revolute joint about y to its half clamp there;
//! - four RSDAs, each on one of those revolute joints, about its axis, between its two bodies (Chrono
//!   initialises each with the joint's own frame): the clamps' lateral springs (clamp to tube, about z)
//!   and the leaves' vertical springs (clamp to leaf, about −y, the frame's z). Each is a torsion bushing
//!   on its joint ([`Builder::torsion_spring`]): `ChLinkRSDA` applies `P − k (θ − θ₀)` about its axis to
//!   its second body, θ₀ the angle at construction (zero), so the rate is `k` and the moment at design
//!   `P`. Chrono keeps the same frames on the right side, not mirrored: a turn about y is its own mirror
//!   image, so the vertical springs, preload and all, are the left's mirror image, and the lateral springs
//!   about z carry no preload, so they are too; the general model's right corner is that mirror image.
//!
//! Chrono converts `Vertical Stiffness` `K_v`, `Lateral Stiffness` `K_l` (translational, N/m) and
//! `Stiffness Bias` `b` to the rotational rates: `K_A = K/(1 + b)` for the front leaf, `K_B = b K_A` for the
//! rear, times the squared length of the leaf, `|r_A|²` (clamp A from the front hanger) or `|r_B|²` (clamp B
//! from the shackle). `Vertical Preload Force` `F` gives the moments `M = (0, 0, F/2) × r` and from them
//! `M_y / k_vertical`, which Chrono meant as the leaves' rest angles (the torque functor's third argument
//! once was one). At the Chrono commit read, `LinearSpringDamperTorque`'s third argument is the preload
//! torque `P`: Chrono builds each vertical spring with `P = M_y / k` in N·m (a few hundredths for the UAZ:
//! the preload force bends no leaf) and rest angle zero. elastokin follows what Chrono builds, and says so
//! in the notes.
//!
//! Otherwise:
//! - `SAELeafspringAxle`: the spindle turns on the tube: each side's upright is welded to it at the wheel
//!   centre, and the steering axis is the wheel's vertical.
//! - `SAEToeBarLeafspringAxle`: a knuckle on a kingpin (revolute, `Location Upper` to `Location Lower`) at
//!   each end of the tube, the kingpin the steering axis. The toe bar (`Tierod`) across, a body on a ball
//!   joint to the left knuckle and a universal joint to the right, is the distance between its ends; so is
//!   the drag link (a ball joint at Chrono's steering link, a universal at the knuckle), from
//!   `Draglink / Location Chassis` to `Knuckle / Location Draglink` on the left knuckle, or the right one
//!   when that point's y is negative (Chrono then joins the right knuckle at the point as given): the
//!   axle's steering link, its steering-box end moved along its own line when steering.
//! - `Auxiliary Spring` (with its stops from `Minimum Length` / `Maximum Length`) and `Shock` run from the
//!   chassis to the tube on each side. A spring of `Spring Coefficient` 0 without preload (the UAZ rear's)
//!   pushes nothing: it is left out, its stops kept.
//! - Bushing data: Chrono reads `Leafspring Bushing Data` into the shackle's bushing (in place of `Shackle
//!   Bushing Data`), so the shackle's joint is a bushing with it and the leaves' joints stay revolute, as
//!   Chrono builds them. `Clamp Bushing Data` would make the clamps' joints bushings under the lateral RSDAs:
//!   a rotational spring on a bushing is not a torsion bushing on a revolute joint, and is refused by name.

use super::builder::Builder;
use super::doc::Doc;
use super::error::Refusal;
use super::solid_axle::{knuckle, knuckle_drag_link, toe_bar, wheel_on_tube, AXLE_TUBE};
use crate::description::general::Place;
use crate::description::general::CHASSIS;
use crate::description::limits::ROTATIONAL_RATE_RANGE;
use elastokin_core::{JointKind, Vec3};

/// `SAELeafspringAxle`.
pub(super) fn read_sae(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    axle_tube(doc, b)?;
    wheel_on_tube(doc, b)?;
    leaf_spring(doc, b)?;
    springs(doc, b)
}

/// `SAEToeBarLeafspringAxle`.
pub(super) fn read_toe_bar(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.wheel(doc)?;
    axle_tube(doc, b)?;
    knuckle(doc, b, &[])?;
    toe_bar(doc, b)?;
    knuckle_drag_link(doc, b)?;
    leaf_spring(doc, b)?;
    springs(doc, b)
}

/// The axle tube (`Axle Tube / COM`), read onto the axle.
fn axle_tube(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    b.on_axle(true);
    let at = b.hardpoint(doc, "axle_tube", "Axle Tube/COM")?;
    b.body(AXLE_TUBE, &at);
    doc.dynamics("Axle Tube", &["Mass", "Inertia", "Radius"], &mut b.notes);
    b.on_axle(false);
    if doc.has("Output") {
        doc.expect("Output");
        b.notes.push("Output: Chrono's output switch, not part of the suspension".into());
    }
    Ok(())
}

/// The path of the bushing Chrono puts on the shackle's joint, if any.
fn shackle_bushing(doc: &Doc, b: &mut Builder) -> Option<&'static str> {
    const SHACKLE: &str = "Leafspring/Shackle Bushing Data";
    const LEAF: &str = "Leafspring/Leafspring Bushing Data";
    if !doc.has(LEAF) {
        return doc.has(SHACKLE).then_some(SHACKLE);
    }
    b.notes.push(
        "Leafspring / Leafspring Bushing Data: Chrono reads it into the shackle's bushing, not the leaves' joints \
         (which stay revolute): the shackle's joint is that bushing"
            .into(),
    );
    if doc.has(SHACKLE) {
        doc.expect(SHACKLE);
        b.notes.push(
            "Leafspring / Shackle Bushing Data: replaced by Leafspring Bushing Data, as Chrono reads them; left out"
                .into(),
        );
    }
    Some(LEAF)
}

/// One side's leaf spring: the leaves, the half clamps and the shackle on their joints, and the four
/// rotational springs on the clamps' and leaves' revolute joints.
fn leaf_spring(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    let leaf = Leaf::read(doc, b)?;
    let rates = LeafRates::read(doc, &leaf)?;
    rates.note(b);
    leaf_bodies(b, &leaf);
    leaf_joints(doc, b, &leaf)?;
    rates.torsion_springs(b, &leaf);
    Ok(())
}

/// One side's leaf spring as the file places it: its hardpoints, by name and where they are.
struct Leaf {
    hanger: String,
    clamp_a: String,
    clamp_b: String,
    shackle: String,
    rear_hanger: String,
    /// Where the front hanger, clamp A, clamp B, the shackle's end of the rear leaf and the rear hanger are.
    at: [Vec3; 5],
}

impl Leaf {
    /// The hardpoints of `Leafspring`, its parts' dynamics left out; refused when the clamps' joints are
    /// bushings or a leaf has no length.
    fn read(doc: &Doc, b: &mut Builder) -> Result<Self, Refusal> {
        let hanger = b.hardpoint(doc, "front_hanger", "Leafspring/Location Front Hanger")?;
        let clamp_a = b.hardpoint(doc, "clamp_a", "Leafspring/Location Clamp A")?;
        let clamp_b = b.hardpoint(doc, "clamp_b", "Leafspring/Location Clamp B")?;
        let shackle = b.hardpoint(doc, "shackle", "Leafspring/Location Shackle")?;
        let rear_hanger = b.hardpoint(doc, "rear_hanger", "Leafspring/Location Rear Hanger")?;
        for part in ["Frontleaf", "Rearleaf", "Half Clamp", "Shackle"] {
            doc.dynamics(&format!("Leafspring/{part}"), &["Mass", "Inertia"], &mut b.notes);
        }
        if doc.has("Leafspring/Clamp Bushing Data") {
            return Err(Refusal::unusable(
                &["Leafspring", "Clamp Bushing Data"],
                "\"Leafspring\" / \"Clamp Bushing Data\": Chrono makes the half clamps' joints to the tube \
                        bushings, and its lateral rotational springs act on them; elastokin reads a rotational spring \
                        as a torsion bushing on a revolute joint, which holds its other directions: remove the \
                        \"Clamp Bushing Data\" to keep the clamps' revolute joints",
            ));
        }
        let [h, a, c, s, r] = [&hanger, &clamp_a, &clamp_b, &shackle, &rear_hanger].map(|n| b.point_of(n));
        let leaf = Leaf { hanger, clamp_a, clamp_b, shackle, rear_hanger, at: [h?, a?, c?, s?, r?] };
        for (length, [one, other]) in [
            (leaf.front(), ["Location Clamp A", "Location Front Hanger"]),
            (leaf.rear(), ["Location Clamp B", "Location Shackle"]),
        ] {
            if length.norm() < 1e-6 {
                return Err(Refusal::unusable(
                    &["Leafspring", one, other],
                    format!(
                        "\"Leafspring\" / \"{one}\" and \"{other}\" coincide: they are the ends of a leaf, whose rates \
                         Chrono scales by its squared length; give the leaf its length"
                    ),
                ));
            }
        }
        Ok(leaf)
    }

    /// The front leaf, from the front hanger to clamp A (Chrono's `r_A`).
    fn front(&self) -> Vec3 {
        self.at[1] - self.at[0]
    }

    /// The rear leaf, from the shackle to clamp B (Chrono's `r_B`).
    fn rear(&self) -> Vec3 {
        self.at[2] - self.at[3]
    }
}

/// The rates and preloads of a leaf's four rotational springs, as Chrono converts the leaf's translational
/// ones (`SAELeafspringAxle::Create`): lateral about z and vertical about −y, of the front (A) and rear (B)
/// leaf.
struct LeafRates {
    lateral_a: f64,
    lateral_b: f64,
    vertical_a: f64,
    vertical_b: f64,
    /// What Chrono builds: the torque functor's third argument, the preload P, is given M_y / k.
    preload_a: f64,
    preload_b: f64,
}

impl LeafRates {
    /// The leaf's rates, bias and preload force, refused unless positive and within what the engine takes.
    fn read(doc: &Doc, leaf: &Leaf) -> Result<Self, Refusal> {
        let vertical = doc.number("Leafspring/Vertical Stiffness")?;
        let bias = doc.number("Leafspring/Stiffness Bias")?;
        let lateral = doc.number("Leafspring/Lateral Stiffness")?;
        let force = doc.number("Leafspring/Vertical Preload Force")?;
        for (value, key) in [(vertical, "Vertical Stiffness"), (bias, "Stiffness Bias"), (lateral, "Lateral Stiffness")]
        {
            if !(value.is_finite() && value > 0.0) {
                return Err(Refusal::unusable(
                    &["Leafspring", key],
                    format!(
                        "\"Leafspring\" / \"{key}\" {value}: Chrono shares the leaf's rates between its front and \
                         rear halves by \"Stiffness Bias\" (the rear's over the front's); give positive rates and bias"
                    ),
                ));
            }
        }
        let (ra, rb) = (leaf.front(), leaf.rear());
        let preload = Vec3::new(0.0, 0.0, force / 2.0);
        let (ma, mb) = (preload.cross(&ra), preload.cross(&rb));
        let (front_share, rear_share) = (1.0 / (1.0 + bias), bias / (1.0 + bias));
        let lateral_a = lateral * front_share * ra.norm_squared();
        let lateral_b = lateral * rear_share * rb.norm_squared();
        let vertical_a = vertical * front_share * ra.norm_squared();
        let vertical_b = vertical * rear_share * rb.norm_squared();
        let (least, most) = ROTATIONAL_RATE_RANGE;
        for (rate, what) in [
            (lateral_a, "the front leaf's lateral rate"),
            (lateral_b, "the rear leaf's lateral rate"),
            (vertical_a, "the front leaf's vertical rate"),
            (vertical_b, "the rear leaf's vertical rate"),
        ] {
            if !(least..=most).contains(&rate) {
                return Err(Refusal::unusable(
                    &["Leafspring", "Vertical Stiffness", "Lateral Stiffness", "Stiffness Bias"],
                    format!(
                        "\"Leafspring\" / \"Vertical Stiffness\", \"Lateral Stiffness\", \"Stiffness Bias\": {what} \
                         is {rate:e} N·m/rad (Chrono's rate times the leaf's squared length), outside the {least:e} \
                         to {most:e} the engine takes; give rates of a leaf spring"
                    ),
                ));
            }
        }
        let (preload_a, preload_b) = (ma.y / vertical_a, mb.y / vertical_b);
        Ok(LeafRates { lateral_a, lateral_b, vertical_a, vertical_b, preload_a, preload_b })
    }

    /// The notes saying the rates and preloads, as Chrono builds them.
    fn note(&self, b: &mut Builder) {
        let LeafRates { lateral_a, lateral_b, vertical_a, vertical_b, preload_a, preload_b } = self;
        b.notes.push(format!(
            "Leafspring: rotational springs on the clamps' and leaves' revolute joints, as Chrono converts the \
             rates: lateral {lateral_a:.6e} (front) and {lateral_b:.6e} (rear) N·m/rad about z, vertical \
             {vertical_a:.6e} and {vertical_b:.6e} N·m/rad about −y"
        ));
        b.notes.push(format!(
            "Leafspring / Vertical Preload Force: Chrono passes M_y / k (meant as a rest angle) as the vertical \
             springs' preload torque: {preload_a:.6e} and {preload_b:.6e} N·m, rest angle zero; read as Chrono \
             builds it"
        ));
    }

    /// The four rotational springs, each a torsion bushing on its revolute joint.
    fn torsion_springs(&self, b: &mut Builder, leaf: &Leaf) {
        let (clamp_a, clamp_b) = (&leaf.clamp_a, &leaf.clamp_b);
        for (name, bodies, point, axis, rate, moment) in [
            ("clamp A lateral spring", ["clamp A", AXLE_TUBE], clamp_a, about_z().1, self.lateral_a, 0.0),
            ("clamp B lateral spring", ["clamp B", AXLE_TUBE], clamp_b, about_z().1, self.lateral_b, 0.0),
            ("front leaf spring", ["clamp A", "front leaf"], clamp_a, about_y().1, self.vertical_a, self.preload_a),
            ("rear leaf spring", ["clamp B", "rear leaf"], clamp_b, about_y().1, self.vertical_b, self.preload_b),
        ] {
            b.torsion_spring(name, bodies, Place::named(point), axis, rate, moment);
        }
    }
}

/// Chrono's frame as `(u, w)` at the clamps' joints to the tube: the chassis's (z up).
fn about_z() -> (Vec3, Vec3) {
    (Vec3::x(), Vec3::z())
}

/// Chrono's frame as `(u, w)` at the shackle's and the leaves' joints: the chassis's turned a quarter about x
/// (u = x, w = −y).
fn about_y() -> (Vec3, Vec3) {
    (Vec3::x(), -Vec3::y())
}

/// The leaf's bodies, at Chrono's positions.
fn leaf_bodies(b: &mut Builder, leaf: &Leaf) {
    let [h, a, c, s, r] = leaf.at;
    let mid = (a + c) / 2.0;
    b.body_at("front leaf", Place::At((h + a) / 2.0));
    b.body_at("rear leaf", Place::At((s + c) / 2.0));
    b.body_at("clamp A", Place::At((a + mid) / 2.0));
    b.body_at("clamp B", Place::At((c + mid) / 2.0));
    b.body_at("shackle", Place::At((r + s) / 2.0));
}

/// The leaf's joints: the front leaf's ball joint to the chassis, the shackle's pivot (a bushing when the
/// file gives one) and its ball joint to the rear leaf, and each half clamp's pivot on the tube and its leaf's
/// pivot on it.
fn leaf_joints(doc: &Doc, b: &mut Builder, leaf: &Leaf) -> Result<(), Refusal> {
    let ball = JointKind::Spherical;
    b.joint(doc, "front leaf ball joint", ball, ["front leaf", CHASSIS], Place::named(&leaf.hanger), None, None)?;
    let bushing = shackle_bushing(doc, b);
    let (revolute, rear_hanger) = (JointKind::Revolute, Place::named(&leaf.rear_hanger));
    b.joint(doc, "shackle pivot", revolute, ["shackle", CHASSIS], rear_hanger, Some(about_y()), bushing)?;
    b.joint(doc, "rear leaf ball joint", ball, ["rear leaf", "shackle"], Place::named(&leaf.shackle), None, None)?;
    for (clamp, point, part) in [("clamp A", &leaf.clamp_a, "front leaf"), ("clamp B", &leaf.clamp_b, "rear leaf")] {
        let (pivot, on_leaf) = (format!("{clamp} pivot"), format!("{part} clamp"));
        b.joint(doc, &pivot, revolute, [clamp, AXLE_TUBE], Place::named(point), Some(about_z()), None)?;
        b.joint(doc, &on_leaf, revolute, [clamp, part], Place::named(point), Some(about_y()), None)?;
    }
    Ok(())
}

/// The auxiliary spring (and its stops) and the shock of each side, from the chassis to the tube.
fn springs(doc: &Doc, b: &mut Builder) -> Result<(), Refusal> {
    let c = b.hardpoint(doc, "spring_chassis", "Auxiliary Spring/Location Chassis")?;
    let a = b.hardpoint(doc, "spring_axle", "Auxiliary Spring/Location Axle")?;
    b.spring(doc, "Auxiliary Spring", "auxiliary spring", [CHASSIS, AXLE_TUBE], [&c, &a])?;
    let added = b.general.springs.last().filter(|s| s.name == "auxiliary spring" && s.rate == Some(0.0));
    if let Some(spring) = added {
        if spring.preload.is_some() {
            return Err(Refusal::unusable(
                &["Auxiliary Spring", "Spring Coefficient", "Preload"],
                "\"Auxiliary Spring\" / \"Spring Coefficient\" is 0 with a \"Preload\": a constant push, which \
                        elastokin's springs do not take; give the spring a rate",
            ));
        }
        b.general.springs.pop();
        b.notes.push(
            "Auxiliary Spring / Spring Coefficient 0: a spring of no rate and no preload pushes nothing; left out, \
             its stops kept"
                .into(),
        );
    }
    b.shock(doc, "shock", [CHASSIS, AXLE_TUBE], ["Location Chassis", "Location Axle"])
}
