//! Model files: the shipped examples parse and round-trip; bad files name the key and position.

use elastokin_suspensions::{FileError, SuspensionFile};
use std::path::Path;

fn examples() -> Vec<std::path::PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    files
}

#[test]
fn shipped_examples_round_trip() {
    let files = examples();
    assert!(files.len() >= 2, "{files:?}");
    for path in files {
        let first = SuspensionFile::read(&path).unwrap();
        let again = SuspensionFile::from_json(&first.to_json(), "round trip").unwrap();
        assert_eq!(first, again, "{}", path.display());
    }
}

fn first_example_text() -> String {
    std::fs::read_to_string(&examples()[0]).unwrap()
}

#[test]
fn unknown_key_is_named_with_its_position() {
    let text = first_example_text().replacen("\"wheel_centre\"", "\"wheel_center\"", 1);
    let line = text.lines().position(|l| l.contains("wheel_center")).unwrap() + 1;
    match SuspensionFile::from_json(&text, "typo.json").unwrap_err() {
        FileError::Invalid { origin, line: l, message, .. } => {
            assert_eq!(origin, "typo.json");
            assert!(message.contains("unknown field `wheel_center`"), "{message}");
            assert_eq!(l, line, "{message}");
        }
        other => panic!("{other}"),
    }
}

#[test]
fn missing_hardpoint_is_named() {
    let text: String =
        first_example_text().lines().filter(|l| !l.contains("\"tie_rod_outer\"")).collect::<Vec<_>>().join("\n");
    let err = SuspensionFile::from_json(&text, "short.json").unwrap_err();
    assert!(err.to_string().contains("missing field `tie_rod_outer`"), "{err}");
}

#[test]
fn inconsistent_geometry_is_refused_with_the_item_named() {
    // Put the spring's arm seat on its chassis seat: a zero-length spring.
    let mut file = SuspensionFile::read(&examples()[0]).unwrap();
    if let elastokin_suspensions::Template::DoubleWishbone(ref mut dw) = file.suspension {
        dw.hardpoints.spring_arm = dw.hardpoints.spring_chassis;
    } else if let elastokin_suspensions::Template::MacPherson(ref mut mp) = file.suspension {
        mp.hardpoints.strut_lower = mp.hardpoints.top_mount;
    }
    let err = SuspensionFile::from_json(&file.to_json(), "bad.json").unwrap_err();
    assert!(matches!(err, FileError::Model { .. }), "{err}");
    assert!(err.to_string().starts_with("bad.json"), "{err}");
}

#[test]
fn a_bushed_tie_rod_round_trips_and_builds_a_rod() {
    let text = first_example_text().replacen(
        "\"spring\"",
        "\"tie_rod\": { \"bushing\": { \"radial\": 2e7, \"axial\": 2e7, \"torsion\": 50.0, \"conical\": 50.0 } },\n      \"spring\"",
        1,
    );
    let file = SuspensionFile::from_json(&text, "bushed tie rod").unwrap();
    let again = SuspensionFile::from_json(&file.to_json(), "round trip").unwrap();
    assert_eq!(file, again);
    let corner =
        file.suspension.build(elastokin_suspensions::Side::Left, elastokin_suspensions::Rig::WheelTravel).unwrap();
    assert!(corner.model.body_id("tie rod").is_some());
    assert!(corner.model.joint_id("tie rod").is_none(), "the distance constraint is replaced, not doubled");
    // The default, when the key is absent, is the distance constraint.
    let plain = SuspensionFile::from_json(&first_example_text(), "plain").unwrap();
    let corner =
        plain.suspension.build(elastokin_suspensions::Side::Left, elastokin_suspensions::Rig::WheelTravel).unwrap();
    assert!(corner.model.joint_id("tie rod").is_some() && corner.model.body_id("tie rod").is_none());
}
