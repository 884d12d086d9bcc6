//! Where each described item went: the bodies, joints and elements that one entry of a general
//! description became in a built corner or axle, on each side. This is where a described number meets
//! the built model's quantity: a bushing's rate in `bushings[2]` is the stiffness of the elements listed
//! under that key, a hardpoint of `joints[0]` places the joints listed under it.
//!
//! The builder names every part it adds after its entry (`part_name(prefix, name)`, the anti-roll bar's
//! [`AntiRollBar::part_names`](crate::description::AntiRollBar::part_names), the load labels of `load_labels`), and the rig names its own parts by the
//! constants of [`crate::assembly::rig`]; the map is read back by those names, so it needs nothing threaded
//! through the builder. A template's items are those of its expansion into the general form.

use crate::assembly::rig::{RACK, RACK_SLIDE, RACK_TRAVEL, STEERING_LINK, TIE_ROD, WHEEL_TRAVEL};
use crate::description::general::{BodyDef, ElementLists, GeneralCorner, JointDef, LoadDef};
use crate::description::place::part_name;
use crate::description::Side;
use elastokin_core::{BodyId, ElementId, JointId, Model};

/// What one described item became on one side.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Built {
    /// The item's key in the description, as errors name it: `bodies[1]`, `bushings[0]`, `axle.joints[2]`,
    /// `anti_roll_bars[0]`, `loads[0]`; the rig's parts are `corner.tie_rod`, `axle.steering_link` and
    /// `rig`.
    pub key: String,
    /// The item's name in the description.
    pub name: String,
    /// The corner it was built for; `None` for the parts an axle has once (its shared parts, the bars'
    /// torsion elements, the rack).
    pub side: Option<Side>,
    /// The bodies it became.
    pub bodies: Vec<BodyId>,
    /// The joints it became.
    pub joints: Vec<JointId>,
    /// The elements it became.
    pub elements: Vec<ElementId>,
}

/// Every described item of a built model with what it became (see the [module docs](self)).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct BuildMap {
    /// The items, in description order, each side's in turn.
    pub items: Vec<Built>,
}

/// The element names a load entry becomes: its name alone for a force or a moment, `"{name} force"` and
/// `"{name} torque"` for both.
pub(crate) fn load_labels(load: &LoadDef, prefix: &str) -> (Option<String>, Option<String>) {
    let name = part_name(prefix, &load.name);
    let both = load.force.is_some() && load.torque.is_some();
    let force = load.force.map(|_| if both { format!("{name} force") } else { name.clone() });
    let torque = load.torque.map(|_| if both { format!("{name} torque") } else { name.clone() });
    (force, torque)
}

/// Each entry's key under `under` (`""` or `"axle."`) with its name and the names of what it became on
/// a corner whose names start with `prefix` (`""` on the axle): the bodies, the joints, then every element
/// kind in the order [`ElementLists`] declares them.
fn entries<'a>(
    under: &str,
    prefix: &str,
    bodies: &'a [BodyDef],
    joints: &'a [JointDef],
    elements: ElementLists<'a>,
) -> Vec<(String, &'a str, Vec<String>)> {
    let mut out = Vec::new();
    let named = |name: &str| vec![part_name(prefix, name)];
    for (k, b) in bodies.iter().enumerate() {
        out.push((format!("{under}bodies[{k}]"), b.name.as_str(), named(&b.name)));
    }
    for (k, j) in joints.iter().enumerate() {
        out.push((format!("{under}joints[{k}]"), j.name.as_str(), named(&j.name)));
    }
    for (list, kind) in elements.by_kind() {
        for (k, e) in kind.into_iter().enumerate() {
            out.push((format!("{under}{list}[{k}]"), e.name(), e.part_names(prefix)));
        }
    }
    out
}

impl BuildMap {
    /// The map of `model`, built from `general` with its corners on `sides` (each side with its parts'
    /// name prefix: `[(Left, "")]` for a lone corner, `[(Left, "left "), (Right, "right ")]` for an axle).
    /// Loads appear when they have been added ([`GeneralCorner::add_loads`]).
    pub fn of(general: &GeneralCorner, model: &Model, sides: &[(Side, &str)]) -> BuildMap {
        let mut items = Vec::new();
        let mut item = |key: String, name: &str, side: Option<Side>, names: &[String]| {
            let bodies: Vec<BodyId> = names.iter().filter_map(|n| model.body_id(n)).collect();
            let joints: Vec<JointId> = names.iter().filter_map(|n| model.joint_id(n)).collect();
            let elements: Vec<ElementId> = names.iter().filter_map(|n| model.element_id(n)).collect();
            if !(bodies.is_empty() && joints.is_empty() && elements.is_empty()) {
                items.push(Built { key, name: name.to_string(), side, bodies, joints, elements });
            }
        };
        // A rod mounted by the rig: a distance joint alone, or a body with a joint or bushing at each end.
        let rod = |name: &str| -> Vec<String> {
            let mut names = vec![name.to_string()];
            for end in ["inner", "outer"] {
                names.push(format!("{name} {end} joint"));
                names.push(format!("{name} {end} bushing"));
            }
            names
        };
        for &(side, prefix) in sides {
            let named = |n: &str| vec![part_name(prefix, n)];
            let s = Some(side);
            for (key, name, names) in entries("", prefix, &general.bodies, &general.joints, general.elements()) {
                item(key, name, s, &names);
            }
            for (k, bar) in general.anti_roll_bars.iter().enumerate() {
                let names: Vec<String> = bar.part_names(prefix).into_iter().chain(bar.arm_names(prefix)).collect();
                item(format!("anti_roll_bars[{k}]"), &bar.name, s, &names);
            }
            for (k, load) in general.loads.iter().enumerate() {
                let (force, torque) = load_labels(load, prefix);
                item(format!("loads[{k}]"), &load.name, s, &force.into_iter().chain(torque).collect::<Vec<_>>());
            }
            if general.corner.tie_rod.is_some() {
                item("corner.tie_rod".into(), TIE_ROD, s, &rod(&part_name(prefix, TIE_ROD)));
            }
            item("rig".into(), WHEEL_TRAVEL, s, &named(WHEEL_TRAVEL));
        }
        for (k, bar) in general.anti_roll_bars.iter().enumerate() {
            item(format!("anti_roll_bars[{k}]"), &bar.name, None, std::slice::from_ref(&bar.name));
        }
        if let Some(axle) = &general.axle {
            for (key, name, names) in entries("axle.", "", &axle.bodies, &axle.joints, axle.elements()) {
                item(key, name, None, &names);
            }
            if axle.steering_link.is_some() {
                item("axle.steering_link".into(), STEERING_LINK, None, &rod(STEERING_LINK));
            }
        }
        item("rig".into(), RACK, None, &[RACK, RACK_SLIDE, RACK_TRAVEL].map(str::to_string));
        BuildMap { items }
    }

    /// The items under `key` (one per side it was built on).
    pub fn find<'a>(&'a self, key: &'a str) -> impl Iterator<Item = &'a Built> + 'a {
        self.items.iter().filter(move |b| b.key == key)
    }
}
