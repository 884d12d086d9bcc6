//! An anti-roll bar given by its section: its middle twists and its arms bend, and the axle feels it as
//! the rate of the closed form, `1 / (L/GJ + 2a/3EI)` for a middle of length `L` between the bearings and
//! arms of length `a` whose drop links pull square to them (`examples/double_wishbone_axle.json`'s bar:
//! L = 1.4 m, a = 0.2 m, vertical drop links on horizontal arms).

use elastokin_suspensions::kc::{self, Analysis, Settings};
use elastokin_suspensions::SuspensionFile;
use serde_json::{json, Value};

const E: f64 = 210e9;
const G: f64 = 80e9;

fn axle(bar: Value) -> SuspensionFile {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/double_wishbone_axle.json");
    let mut doc: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let entry = doc.pointer_mut("/suspension/general/anti_roll_bars/0").unwrap().as_object_mut().unwrap();
    entry.remove("rate");
    for (k, v) in bar.as_object().unwrap() {
        entry.insert(k.clone(), v.clone());
    }
    SuspensionFile::from_json(&doc.to_string(), "axle").unwrap_or_else(|e| panic!("{e}"))
}

fn figures(file: &SuspensionFile) -> (f64, f64) {
    // Read at design off the path's expansion there, whatever the range walked.
    let settings = Settings::default();
    let report = kc::run(Analysis::Roll, file, &settings).unwrap_or_else(|e| panic!("{e}"));
    let figure = |key: &str| report.figures.iter().find(|f| f.key == key).and_then(|f| f.value).unwrap();
    (figure("roll_stiffness"), figure("anti_roll_bar_roll_stiffness"))
}

#[test]
fn a_bar_by_its_section_is_the_rate_of_its_torsion_and_its_arms_bending() {
    let mut worst = (0.0f64, 0.0f64);
    for d in [0.018_f64, 0.024] {
        let j = std::f64::consts::PI * d.powi(4) / 32.0;
        let i = j / 2.0;
        let section = json!({ "youngs_modulus": E, "shear_modulus": G, "area": std::f64::consts::PI * d * d / 4.0,
                              "iy": i, "iz": i, "j": j });
        let (l, a) = (1.4, 0.2);
        let rate = 1.0 / (l / (G * j) + 2.0 * a / (3.0 * E * i));
        let (total, bar) = figures(&axle(json!({ "section": section })));
        let (total_rate, bar_rate) = figures(&axle(json!({ "rate": rate })));
        let errors = ((total / total_rate - 1.0).abs(), (bar / bar_rate - 1.0).abs());
        println!(
            "d {d}: rate {rate:.1} N·m/rad; roll stiffness {total} against {total_rate}, the bar's {bar} against \
             {bar_rate} N·m/deg: {:e} {:e}",
            errors.0, errors.1
        );
        worst = (worst.0.max(errors.0), worst.1.max(errors.1));
    }
    // Measured 8.5e-9 and 2.2e-8: the same 1.7e-5 N·m/deg in both figures (the bar's rate itself).
    assert!(worst.0 < 1e-7 && worst.1 < 1e-6, "{:e} {:e}", worst.0, worst.1);
}

#[test]
fn a_bar_with_a_rate_and_a_section_or_neither_is_refused_by_key() {
    let section = json!({ "youngs_modulus": E, "shear_modulus": G, "area": 3e-4, "iy": 7e-9, "iz": 7e-9, "j": 1.4e-8 });
    let both = axle(json!({ "rate": 1000.0, "section": section }));
    let e = kc::run(Analysis::Roll, &both, &Settings::default()).expect_err("refused").to_string();
    assert!(e.contains("anti_roll_bars[0]") && e.contains("not both"), "{e}");
    let neither = axle(json!({}));
    let e = kc::run(Analysis::Roll, &neither, &Settings::default()).expect_err("refused").to_string();
    assert!(e.contains("anti_roll_bars[0]") && e.contains("rate (N·m/rad) or its section"), "{e}");
    let mut bad = section.clone();
    bad["j"] = json!(-1.0);
    let e = kc::run(Analysis::Roll, &axle(json!({ "section": bad })), &Settings::default()).expect_err("refused");
    assert!(e.to_string().contains("anti_roll_bars[0] (anti-roll bar).section"), "{e}");
}

#[test]
fn a_bar_by_its_section_is_one_item_of_the_build_map_on_each_side_and_once_across() {
    use elastokin_suspensions::description::Template;
    use elastokin_suspensions::{Axle, AxleRig, Side};
    let section = json!({ "youngs_modulus": E, "shear_modulus": G, "area": 3e-4, "iy": 7e-9, "iz": 7e-9, "j": 1.4e-8 });
    let file = axle(json!({ "section": section }));
    let axle = Axle::build(&file.suspension, AxleRig::OppositeTravel).unwrap();
    let Template::General(g) = &file.suspension else { panic!("general") };
    let map = axle.build_map(g);
    let items: Vec<_> = map.find("anti_roll_bars[0]").collect();
    let name = |b: &elastokin_core::BodyId| axle.model.bodies()[b.0].name.clone();
    for (side, prefix) in [(Side::Left, "left "), (Side::Right, "right ")] {
        let item = items.iter().find(|i| i.side == Some(side)).expect("each side");
        let bodies: Vec<String> = item.bodies.iter().map(name).collect();
        assert_eq!(bodies, [format!("{prefix}anti-roll bar half"), format!("{prefix}anti-roll bar arm end")]);
        assert_eq!((item.joints.len(), item.elements.len()), (2, 1), "bearing and drop link; the arm's beam");
    }
    let across = items.iter().find(|i| i.side.is_none()).expect("the middle");
    assert_eq!((across.bodies.len(), across.elements.len()), (0, 1));
    // The bar's elastic elements are the axle's bars: the middle and both arms.
    assert_eq!(axle.anti_roll_bars.len(), 3);
}
