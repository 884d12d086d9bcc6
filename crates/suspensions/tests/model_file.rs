//! Model files: the shipped examples parse and round-trip; bad files name the key and position.

use elastokin_suspensions::{FileError, SuspensionFile, Template};
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

/// The shipped MacPherson as a JSON value, edited by `edit`, as text.
fn macpherson_edited(edit: impl FnOnce(&mut serde_json::Value)) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/generic/macpherson.json");
    let mut v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    edit(&mut v);
    serde_json::to_string_pretty(&v).unwrap()
}

/// The error's message, its line and the line of `key` in `text`.
fn invalid(text: &str, key: &str) -> (String, usize, usize) {
    let expected = text.lines().position(|l| l.contains(&format!("\"{key}\""))).map_or(0, |k| k + 1);
    match SuspensionFile::from_json(text, "m.json").unwrap_err() {
        FileError::Invalid { message, line, .. } => (message, line, expected),
        other => panic!("not a file error with a position: {other}"),
    }
}

#[test]
fn a_point_of_four_numbers_names_the_hardpoint_and_the_count() {
    let text = macpherson_edited(|v| {
        v["suspension"]["macpherson"]["hardpoints"]["lower_ball_joint"] = serde_json::json!([0.0, 0.9, -0.17, 1.0])
    });
    let (message, line, expected) = invalid(&text, "lower_ball_joint");
    assert_eq!(message, "hardpoint 'lower_ball_joint': a point is 3 numbers in metres [x, y, z], got 4");
    // The array spans several lines when pretty-printed: the error sits at its end, after the key.
    assert!(line >= expected && line <= expected + 6, "{line} vs {expected}");
}

#[test]
fn a_byte_order_mark_is_accepted() {
    let text = format!("\u{feff}{}", first_example_text());
    let with = SuspensionFile::from_json(&text, "bom.json").unwrap();
    assert_eq!(with, SuspensionFile::from_json(&first_example_text(), "plain").unwrap());
}

#[test]
fn two_templates_or_an_unknown_one_are_named() {
    let text = macpherson_edited(|v| {
        let dw = serde_json::json!({ "hardpoints": {} });
        v["suspension"]["double_wishbone"] = dw;
    });
    let (message, line, expected) = invalid(&text, "suspension");
    assert_eq!(
        message,
        "suspension: give one template (macpherson, double_wishbone, twist_beam or general), found 2: macpherson, double_wishbone"
    );
    assert_eq!(line, expected);
    let text = macpherson_edited(|v| {
        let t = v["suspension"]["macpherson"].take();
        v["suspension"] = serde_json::json!({ "trailing_arm": t });
    });
    let (message, _, _) = invalid(&text, "suspension");
    assert_eq!(
        message,
        "suspension: unknown template 'trailing_arm': give one of macpherson, double_wishbone, twist_beam or general"
    );
}

#[test]
fn absurd_magnitudes_are_refused_with_the_key_and_the_range() {
    // (edit, key whose line the error points at, words the message must contain)
    type Edit = fn(&mut serde_json::Value);
    let cases: [(Edit, &str, &[&str]); 9] = [
        (
            |v| v["suspension"]["macpherson"]["hardpoints"]["tie_rod_inner"][2] = 1e293.into(),
            "tie_rod_inner",
            &["hardpoint 'tie_rod_inner'", "z = ", "±1000 m"],
        ),
        (
            |v| v["suspension"]["macpherson"]["hardpoints"]["tie_rod_inner"][1] = 1e6.into(),
            "tie_rod_inner",
            &["hardpoint 'tie_rod_inner'", "y = 1e6 m"],
        ),
        (
            |v| v["suspension"]["macpherson"]["spring"]["rate"] = 1e308.into(),
            "rate",
            &["spring.rate: 1e308 N/m", "(0, 1e12] N/m"],
        ),
        (|v| v["suspension"]["macpherson"]["spring"]["rate"] = 0.0.into(), "rate", &["spring.rate: 0 N/m"]),
        (
            |v| v["suspension"]["macpherson"]["top_mount"]["bushing"]["torsion"] = (-1.0).into(),
            "torsion",
            &["top_mount.bushing.torsion: -1 N·m/rad"],
        ),
        (
            |v| v["suspension"]["macpherson"]["loaded_radius"] = 300.0.into(),
            "loaded_radius",
            &["loaded_radius: 300 m", "0.05–2 m"],
        ),
        (|v| v["vehicle"]["wheelbase"] = 1e308.into(), "wheelbase", &["vehicle.wheelbase: 1e308 m", "0.5–20 m"]),
        (|v| v["vehicle"]["corner_load"] = 0.5.into(), "corner_load", &["vehicle.corner_load: 0.5 N", "1–1e6 N"]),
        (
            |v| v["vehicle"]["brake_front_fraction"] = 1.5.into(),
            "brake_front_fraction",
            &["vehicle.brake_front_fraction: 1.5 is outside 0–1 (the front axle's share"],
        ),
    ];
    for (edit, key, words) in cases {
        let text = macpherson_edited(edit);
        let (message, line, expected) = invalid(&text, key);
        for w in words {
            assert!(message.contains(w), "{message} lacks {w}");
        }
        assert_eq!(line, expected, "{message}");
    }
}

#[test]
fn a_model_in_millimetres_is_refused_with_the_hint() {
    let text = macpherson_edited(|v| {
        for (_, p) in v["suspension"]["macpherson"]["hardpoints"].as_object_mut().unwrap() {
            for c in p.as_array_mut().unwrap() {
                *c = (c.as_f64().unwrap() * 1000.0).into();
            }
        }
    });
    let (message, _, _) = invalid(&text, "wheel_centre");
    assert!(message.contains("look like millimetres: divide every coordinate by 1000"), "{message}");
    // Studies that scale a model on purpose can still read it.
    assert!(SuspensionFile::from_json_any_magnitude(&text, "mm.json").is_ok());
}

#[test]
fn bushing_rates_are_named_by_their_file_keys() {
    // Built from code, without the file's range checks: the corner's own check names the key.
    let mut file = SuspensionFile::from_json(&first_example_text(), "plain").unwrap();
    let elastokin_suspensions::Template::DoubleWishbone(ref mut dw) = file.suspension else {
        panic!("the first example is the double wishbone")
    };
    let elastokin_suspensions::Connection::Bushing(mut rates) = dw.lower_arm_mounts.front else { panic!("bushed") };
    rates.conical = 0.0;
    dw.lower_arm_mounts = elastokin_suspensions::Connection::Bushing(rates).into();
    let err = file.suspension.build(elastokin_suspensions::Side::Left, elastokin_suspensions::Rig::Free).unwrap_err();
    let text = err.to_string();
    assert!(text.contains("lower_arm_mounts.bushing.conical must be a rate in N·m/rad"), "{text}");
    assert!(!text.contains("Kv") && !text.contains("Ky"), "{text}");
}

#[test]
fn wrong_shapes_are_said_in_the_files_words() {
    type Edit = fn(&mut serde_json::Value);
    let cases: [(Edit, &str, &str); 6] = [
        (
            |v| v["suspension"]["macpherson"]["spring"]["rate"] = "30000".into(),
            "rate",
            "invalid type: string \"30000\", expected a number",
        ),
        (
            |v| v["suspension"]["macpherson"]["spring"] = "30000".into(),
            "spring",
            "expected {\"rate\": N/m, \"design_force\": N}",
        ),
        (
            |v| v["suspension"]["macpherson"]["lower_arm_mounts"] = serde_json::json!({"bushing": "stiff"}),
            "lower_arm_mounts",
            "expected {\"radial\": N/m",
        ),
        (
            |v| v["suspension"]["macpherson"]["hardpoints"]["top_mount"] = "0,0,0".into(),
            "top_mount",
            "hardpoint 'top_mount': a point is 3 numbers in metres [x, y, z], got \"0,0,0\"",
        ),
        (|v| v["suspension"] = "macpherson".into(), "suspension", "suspension: give one template as an object"),
        (
            |v| v["suspension"] = serde_json::json!({}),
            "suspension",
            "suspension: give one template (macpherson, double_wishbone, twist_beam or general), found none",
        ),
    ];
    for (edit, key, words) in cases {
        let text = macpherson_edited(edit);
        let (message, line, expected) = invalid(&text, key);
        assert!(message.contains(words), "{message} lacks {words}");
        assert!(!message.contains("struct") && !message.contains("f64"), "{message}");
        assert!(line >= expected && line <= expected + 4, "{message}: line {line}, key on {expected}");
    }
}

/// A bushing's rotation law is chosen in the file (`"law"`); the three laws agree to first order in the
/// twist, so on a corner whose bushings twist little the wheel compliance and the travel barely move with
/// the law, yet do move. An unknown law is named with the ones there are.
#[test]
fn a_bushing_law_is_chosen_in_the_file() {
    use elastokin_solver::Mode;
    use elastokin_suspensions::analysis::{parallel_wheel_travel, wheel_compliance};
    use elastokin_suspensions::{Rig, Side};
    let run = |law: &str| {
        let text = macpherson_edited(|v| {
            let t = &mut v["suspension"]["macpherson"];
            t["lower_arm_mounts"]["bushing"]["law"] = law.into();
            t["top_mount"]["bushing"]["law"] = law.into();
        });
        let file = SuspensionFile::from_json(&text, "law.json").unwrap();
        let corner = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
        let rows = parallel_wheel_travel(&corner, -0.08, 0.08, 16, Mode::Corrected).unwrap();
        (wheel_compliance(&corner, 0.0).unwrap(), rows)
    };
    let (c_energy, rows_energy) = run("energy");
    for law in ["linear", "tait_bryan_xyz"] {
        let (c, rows) = run(law);
        let scale = c_energy.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
        for r in 0..6 {
            for k in 0..6 {
                // Second order in the bushings' small twist at the design equilibrium: measured up to 2.5e-6
                // of the largest entry (linear), 1.1e-7 (Tait-Bryan).
                assert!((c[r][k] - c_energy[r][k]).abs() < 1e-5 * scale, "{law} ({r},{k})");
            }
        }
        let toe_gap =
            rows.iter().zip(&rows_energy).map(|(a, b)| (a.attitude.toe - b.attitude.toe).abs()).fold(0.0f64, f64::max);
        // The laws differ at second order in the twist: on this corner by 1.1e-6 rad of toe (linear) and
        // 8.3e-8 rad (Tait-Bryan) over ±80 mm, measured.
        assert!(toe_gap > 1e-9 && toe_gap < 1e-4, "{law}: {toe_gap}");
    }
    let text =
        macpherson_edited(|v| v["suspension"]["macpherson"]["top_mount"]["bushing"]["law"] = "quaternion".into());
    let message = SuspensionFile::from_json(&text, "law.json").unwrap_err().to_string();
    assert!(message.contains("quaternion") && message.contains("tait_bryan_xyz"), "{message}");
}

/// The expanded MacPherson (general form) as a JSON value, to edit one mistake into.
fn general_macpherson() -> serde_json::Value {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/generic/macpherson.json");
    let file = SuspensionFile::read(&path).unwrap();
    let text = SuspensionFile { suspension: Template::General(Box::new(file.suspension.expand())), ..file }.to_json();
    serde_json::from_str(&text).unwrap()
}

/// The error of a document given as one line of compact JSON (as a Python dict or an edited variant reaches
/// the library), in the words of a document.
fn document_error(doc: &serde_json::Value) -> String {
    let text = serde_json::to_string(doc).unwrap();
    assert_eq!(text.lines().count(), 1);
    SuspensionFile::from_json(&text, "<dict>").unwrap_err().in_document(&text).to_string()
}

#[test]
fn a_document_s_error_names_the_keys_that_lead_to_it_not_a_column_of_one_line() {
    let mut doc = general_macpherson();
    doc["suspension"]["general"]["bodies"][1]["mass"] = 3.0.into();
    assert_eq!(
        document_error(&doc),
        "<dict>: unknown field `mass`, expected `name` or `at` (at suspension.general.bodies[1].mass)"
    );

    let mut doc = general_macpherson();
    doc["suspension"]["general"]["bushings"][2]["radial"] = (-5.0).into();
    let said = document_error(&doc);
    assert!(said.starts_with("<dict>: "), "{said}");
    assert!(said.contains("-5 N/m is outside the accepted range"), "{said}");
    assert!(said.ends_with("(at suspension.general.bushings[2].radial)"), "{said}");

    // Keys with quotes and brackets in them, and arrays of arrays before the mistake, are stepped over.
    let mut doc = general_macpherson();
    let hardpoints = doc["suspension"]["general"]["hardpoints"].as_object_mut().unwrap();
    hardpoints.insert("odd \"name\" [1], {2}".into(), serde_json::json!([0.1, 0.2, 0.3]));
    doc["suspension"]["general"]["joints"][1]["kind"] = "screw".into();
    let said = document_error(&doc);
    assert!(said.starts_with("<dict>: unknown variant `screw`"), "{said}");
    assert!(said.ends_with("(at suspension.general.joints[1].kind)"), "{said}");
}

/// Bushing rates given as a list, `{"bushing": [5e6, 1e6, 573, 5730]}`, were read in field order where
/// every other value of a model file is named: a list says nothing of which rate is which. It is refused
/// at its line, with the named form in the message; the named form still reads as before.
#[test]
fn bushing_rates_given_as_a_list_are_refused_with_the_named_form() {
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/generic/macpherson.json"))
            .unwrap();
    let named = r#"{"radial": 5000000.0, "axial": 1000000.0, "torsion": 573.0, "conical": 5730.0}"#;
    let mut value: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mounts = &mut value["suspension"]["macpherson"]["lower_arm_mounts"];
    assert_eq!(mounts["bushing"], serde_json::from_str::<serde_json::Value>(named).unwrap());
    mounts["bushing"] = serde_json::json!([5e6, 1e6, 573.0, 5730.0]);
    let listed = serde_json::to_string_pretty(&value).unwrap();
    let line = listed.lines().position(|l| l.contains("\"bushing\": [")).unwrap() + 1;
    match SuspensionFile::from_json(&listed, "listed.json").unwrap_err() {
        FileError::Invalid { line: l, message, .. } => {
            assert!(
                message.starts_with("a list of numbers; give the rates by name, {\"radial\": N/m, \"axial\": N/m, ")
                    && !message.contains("sequence"),
                "{message}"
            );
            // At the list: serde places the error just past its closing bracket (measured: the list on lines
            // 48–53 of the pretty-printed file, the error on 54).
            assert!((line..=line + 6).contains(&l), "line {l}, the list starts at {line}: {message}");
        }
        other => panic!("{other}"),
    }
    assert!(SuspensionFile::from_json(&text, "macpherson.json").is_ok());
}

/// A document (no file) with a body's key misspelt: `DocumentError::Document`, placed by the keys.
#[test]
fn a_document_refused_by_its_reader_is_placed_by_its_keys() {
    use elastokin_suspensions::document::{parse_document, DocumentError};
    let mut doc = general_macpherson();
    doc["suspension"]["general"]["bodies"][0]["masss"] = 3.0.into();
    let e = parse_document(&serde_json::to_string(&doc).unwrap(), "my dict").unwrap_err();
    assert!(matches!(e, DocumentError::Document(_)), "{e:?}");
    let said = e.to_string();
    assert!(said.starts_with("my dict: unknown field `masss`"), "{said}");
    assert!(said.ends_with("(at suspension.general.bodies[0].masss)"), "{said}");
}
