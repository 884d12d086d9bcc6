//! The build map accounts for every part: on every shipped model and every Project Chrono file the
//! importer reads, each body, joint and element the builder and the rig add to a model is what exactly one
//! described item became, and every described item became something on each side it was built on.

use elastokin_suspensions::document::parse_model;
use elastokin_suspensions::{Axle, AxleRig, BuildMap, Rig, Side, SuspensionFile};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn repository() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The shipped examples and the Chrono files that read (some are refused on purpose: a rigid
/// suspension, a leaf spring whose stops overlap), each with its name.
fn models() -> Vec<(String, SuspensionFile)> {
    let root = repository();
    let mut paths: Vec<PathBuf> = std::fs::read_dir(root.join("examples"))
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    fn chrono(dir: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                chrono(&p, out);
            } else if p.extension().is_some_and(|e| e == "json") {
                out.push(p);
            }
        }
    }
    chrono(&root.join("tests/data/chrono"), &mut paths);
    paths.sort();
    paths
        .into_iter()
        .filter_map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            let name = p.strip_prefix(&root).unwrap().display().to_string();
            parse_model(&text, &name).ok().map(|(file, _)| (name, file))
        })
        .collect()
}

/// How many items claim each body, joint and element of `model`, and what no item claims.
fn claims(map: &BuildMap, model: &elastokin_core::Model) -> Vec<String> {
    let mut count: BTreeMap<(char, usize), Vec<String>> = BTreeMap::new();
    for item in &map.items {
        let who = format!("{} {:?}", item.key, item.side);
        for b in &item.bodies {
            count.entry(('b', b.0)).or_default().push(who.clone());
        }
        for j in &item.joints {
            count.entry(('j', j.0)).or_default().push(who.clone());
        }
        for e in &item.elements {
            count.entry(('e', e.0)).or_default().push(who.clone());
        }
    }
    let mut wrong = Vec::new();
    let parts = model.bodies().iter().map(|b| ('b', b.name.clone()));
    let parts = parts.chain(model.joints().iter().map(|j| ('j', j.spec.name.clone())));
    let parts = parts.chain(model.elements().iter().map(|e| ('e', e.name().to_string())));
    let mut index: BTreeMap<char, usize> = BTreeMap::new();
    for (kind, name) in parts {
        let k = index.entry(kind).or_default();
        match count.get(&(kind, *k)).map(Vec::len) {
            Some(1) => {}
            None => wrong.push(format!("'{name}' is no described item's")),
            Some(_) => wrong.push(format!("'{name}' is claimed by {:?}", count[&(kind, *k)])),
        }
        *k += 1;
    }
    wrong
}

#[test]
fn every_part_of_every_model_is_what_exactly_one_described_item_became() {
    let models = models();
    assert_eq!(models.len(), 35, "the 8 examples and the 27 Chrono files that read");
    let mut checked = 0;
    for (name, file) in &models {
        let general = file.suspension.expand();
        let rig = if general.is_steered() { Rig::Steering } else { Rig::WheelTravel };
        let corner = file.suspension.build(Side::Left, rig).unwrap_or_else(|e| panic!("{name}: {e}"));
        let map = corner.build_map(&general);
        let wrong = claims(&map, &corner.model);
        assert!(wrong.is_empty(), "{name} (corner): {wrong:?}");
        // Every entry of the general form became something on each side built.
        let sides = corner.sides().len();
        for (key, count) in [
            ("bodies", general.bodies.len()),
            ("joints", general.joints.len()),
            ("bushings", general.bushings.len()),
            ("springs", general.springs.len()),
            ("stops", general.stops.len()),
        ] {
            for k in 0..count {
                let key = format!("{key}[{k}]");
                assert_eq!(map.find(&key).count(), sides, "{name}: {key}");
            }
        }
        checked += 1;
        if let Ok(axle) = Axle::build(&file.suspension, AxleRig::ParallelTravel) {
            let map = axle.build_map(&general);
            let wrong = claims(&map, &axle.model);
            assert!(wrong.is_empty(), "{name} (axle): {wrong:?}");
            for (k, bar) in general.anti_roll_bars.iter().enumerate() {
                // Each side's half, bearing and drop link, and the torsion element once.
                let key = format!("anti_roll_bars[{k}]");
                let built: Vec<_> = map.find(&key).collect();
                assert_eq!(built.len(), 3, "{name}: {key} ({})", bar.name);
                assert_eq!(built.iter().map(|b| b.bodies.len() + b.joints.len()).sum::<usize>(), 6, "{name}: {key}");
                assert_eq!(built.iter().map(|b| b.elements.len()).sum::<usize>(), 1, "{name}: {key}");
            }
        }
    }
    assert_eq!(checked, models.len());
}

#[test]
fn a_load_entry_is_found_in_the_elements_it_became_on_both_sides() {
    let text = std::fs::read_to_string(repository().join("examples/double_wishbone_axle.json")).unwrap();
    let (file, _) = parse_model(&text, "double_wishbone_axle.json").unwrap();
    let general = file.suspension.expand();
    let mut axle = Axle::build(&file.suspension, AxleRig::HeightHeld).unwrap();
    let before = axle.model.elements().len();
    // A force and a moment together: two elements a side, named after the entry.
    let mut with_load = general.clone();
    with_load.loads = serde_json::from_str(
        r#"[{"name": "hub", "body": "upright", "at": "wheel_centre", "force": [0, 100, 0], "torque": [0, 0, 5]}]"#,
    )
    .unwrap();
    with_load.add_loads(&mut axle.model, Side::Left, "left ").unwrap();
    with_load.add_loads(&mut axle.model, Side::Right, "right ").unwrap();
    let map = axle.build_map(&with_load);
    let built: Vec<_> = map.find("loads[0]").collect();
    assert_eq!(built.len(), 2);
    let names: Vec<&str> =
        built.iter().flat_map(|b| b.elements.iter().map(|e| axle.model.elements()[e.0].name())).collect();
    assert_eq!(names, ["left hub force", "left hub torque", "right hub force", "right hub torque"]);
    assert_eq!(axle.model.elements().len(), before + 4);
    assert!(claims(&map, &axle.model).is_empty());
}
