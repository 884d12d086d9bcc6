//! Tolerance stack-up: the first-order spread of the figures from the sensitivities against a Monte
//! Carlo of the model sampled within its tolerances, and bad TOLERANCES files refused by key.

use elastokin_suspensions::design::tolerance::{read_tolerances, stack_up, StackUpError};
use elastokin_suspensions::study::batch::base_document;
use serde_json::{json, Value};

fn document(name: &str) -> Value {
    let path = format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"));
    base_document(&std::fs::read_to_string(&path).unwrap(), &path).unwrap()
}

/// Every hardpoint ±1 mm and the lower-arm bushing's radial rate ±15 %: each parallel-travel figure's
/// first-order standard deviation (the numbers independent and uniform, σ = t/√3 each) is what 400 sampled
/// models give, within the sampling's own error (a standard deviation from n samples is known to
/// 1/√(2(n−1)), 3.5 % here, and the largest of 21 such errors some 2.5 of them; allowed four; measured at
/// most 6.8 % apart, over the 21 figures whose spread is not rounding); the samples never leave the
/// first-order worst case by more than the second order can (5 %).
#[test]
fn first_order_spreads_are_what_a_monte_carlo_of_the_model_gives() {
    let doc = document("macpherson.json");
    let text = json!({
        "hardpoints": 0.001,
        "tolerances": { "/suspension/macpherson/lower_arm_mounts/bushing/radial": "15%" },
        "analyses": ["parallel-travel"],
        "steps": 16,
    })
    .to_string();
    let t = read_tolerances(&text, "tolerances.json", &doc).unwrap();
    assert_eq!(t.bands.len(), 25);
    let mut s = stack_up(&doc, &t).unwrap();
    let n = 400;
    s.monte_carlo(n, 7);
    assert!(s.failed_samples.is_empty(), "{:?}", s.failed_samples);
    let standard_error = 1.0 / (2.0 * (n as f64 - 1.0)).sqrt();
    let (mut worst, mut compared) = (0.0_f64, 0);
    for spread in &s.spreads {
        let m = spread.sampled.unwrap();
        // A figure the tolerances do not move (a ratio fixed by the rig) has a spread of rounding.
        if spread.sigma <= 1e-9 * spread.value.abs().max(1.0) {
            continue;
        }
        let apart = (m.sigma / spread.sigma - 1.0).abs();
        worst = worst.max(apart);
        compared += 1;
        let out = (m.max - spread.value).abs().max((m.min - spread.value).abs());
        assert!(out <= 1.05 * spread.worst_case, "{}: {out} beyond ±{}", spread.figure, spread.worst_case);
    }
    assert!(compared >= 10 && worst < 4.0 * standard_error, "{worst}");
    // The contributors are ranked, largest first, and the largest of the bump steer is a tie-rod point.
    let bump = s.spreads.iter().find(|x| x.figure == "bump_steer").unwrap();
    assert!(bump.contributions.windows(2).all(|w| w[0].1.abs() >= w[1].1.abs()));
    assert!(s.parameters.pointers[bump.contributions[0].0].contains("tie_rod"));
}

#[test]
fn bad_tolerances_are_refused_by_key() {
    let doc = document("macpherson.json");
    for (text, says) in [
        (
            json!({ "tolerances": { "/suspension/macpherson/nowhere": 0.001 } }),
            "'/suspension/macpherson/nowhere' names nothing",
        ),
        (json!({ "tolerances": { "/suspension/macpherson/spring/rate": "15 percent" } }), "or a percent (\"15%\")"),
        (
            json!({ "tolerances": { "/suspension/macpherson/spring/rate": -1.0 } }),
            "a tolerance must be a positive band",
        ),
        (json!({ "hardpoints": 0.001, "analyses": ["rol"] }), "analyses: no analysis 'rol'"),
        (json!({ "hardpoint": 0.001 }), "unknown key 'hardpoint'"),
        // An empty list ran the whole suite.
        (json!({ "hardpoints": 0.001, "analyses": [] }), "analyses: give one analysis name at least"),
        (json!({}), "no tolerances"),
    ] {
        let e = read_tolerances(&text.to_string(), "tolerances.json", &doc).unwrap_err().to_string();
        assert!(e.starts_with("tolerances.json: ") && e.contains(says), "{says}: {e}");
    }
}

/// A band of 1e308 made every spread it touched infinite, written as blank figures and empty cells with
/// exit 0: the stack-up is refused, naming the number whose band it is and what it spreads.
#[test]
fn a_band_that_spreads_a_figure_beyond_any_number_is_refused_by_its_number() {
    let doc = document("macpherson.json");
    let pointer = "/suspension/macpherson/hardpoints/tie_rod_inner/2";
    let text = json!({ "tolerances": { pointer: 1e308 }, "analyses": ["parallel-travel"], "steps": 4 }).to_string();
    let t = read_tolerances(&text, "tolerances.json", &doc).unwrap();
    let e = stack_up(&doc, &t).unwrap_err();
    assert!(
        matches!(&e, StackUpError::Unbounded { pointer: p, analysis: "parallel-travel", .. } if p == pointer),
        "{e:?}"
    );
    let e = e.to_string();
    assert!(e.contains(pointer) && e.contains("±1e308") && e.contains("parallel-travel"), "{e}");
    // A band a part is made to is not.
    let text = json!({ "tolerances": { pointer: 1e-3 }, "analyses": ["parallel-travel"], "steps": 4 }).to_string();
    let spreads = stack_up(&doc, &read_tolerances(&text, "tolerances.json", &doc).unwrap()).unwrap().spreads;
    assert!(!spreads.is_empty() && spreads.iter().all(|s| s.worst_case.is_finite() && s.sigma.is_finite()));
}

/// A band written as a word: `TolerancesRefusal::NotBand`, naming the file, the key and what it holds as
/// written.
#[test]
fn a_band_that_is_no_number_or_percent_is_refused_naming_its_key() {
    use elastokin_suspensions::design::tolerance::TolerancesRefusal;
    let doc = document("macpherson.json");
    let pointer = "/suspension/macpherson/spring/rate";
    let text = json!({ "tolerances": { pointer: "some" } }).to_string();
    let e = read_tolerances(&text, "mine.json", &doc).unwrap_err();
    assert!(matches!(*e.refusal, TolerancesRefusal::NotBand { .. }), "{e:?}");
    assert_eq!(
        e.to_string(),
        format!("mine.json: tolerances[\"{pointer}\"]: give ± in the file's units (0.001) or a percent (\"15%\"), got \"some\"")
    );
}
