//! A figure made most subject to another's bounds: the generic MacPherson's bump steer as large as it can
//! be with its camber gain within ±0.5 deg/m of the model's, the inner tie-rod point's and the front lower
//! arm mount's heights free. Checked against the conditions of a constrained optimum taken by re-runs
//! alone: the camber gain on its bound, the mount on its bound, the tie-rod height the root of the camber
//! gain's bound that re-runs find, and the rates of bump steer and camber gain (central differences of
//! re-runs) in the balance a maximum needs, with multipliers of the right sign. And files refused by key.

use elastokin_suspensions::design::targets::{read_targets, TargetsRefusal};
use elastokin_suspensions::design::tune::tune;
use elastokin_suspensions::design::Parameters;
use elastokin_suspensions::kc::{self, Analysis, Settings};
use elastokin_suspensions::study::batch::base_document;
use serde_json::{json, Value};

const INNER_Z: &str = "/suspension/macpherson/hardpoints/tie_rod_inner/2";
const FRONT_Z: &str = "/suspension/macpherson/hardpoints/lower_arm_front/2";
const STEPS: usize = 20;

fn document() -> Value {
    let path = format!("{}/../../examples/generic/macpherson.json", env!("CARGO_MANIFEST_DIR"));
    base_document(&std::fs::read_to_string(&path).unwrap(), &path).unwrap()
}

fn no_file(name: &str) -> Result<String, String> {
    Err(format!("no file {name}"))
}

/// Bump steer and camber gain (deg/m) of `doc` with the inner tie-rod point's and the front mount's heights
/// at `inner` and `front`, by a run of parallel travel as the tune reads them.
fn figures(doc: &Value, inner: f64, front: f64) -> (f64, f64) {
    let mut doc = doc.clone();
    *doc.pointer_mut(INNER_Z).unwrap() = json!(inner);
    *doc.pointer_mut(FRONT_Z).unwrap() = json!(front);
    let file = Parameters::new(&doc, &[]).unwrap().file().unwrap();
    let r = kc::run(Analysis::ParallelTravel, &file, &Settings { steps: STEPS, ..Settings::default() }).unwrap();
    let read = |key: &str| r.figures.iter().find(|f| f.key == key).unwrap().value.unwrap().to_degrees();
    (read("bump_steer"), read("camber_gain"))
}

/// The tune ends where a maximum under the bounds sits (measured: the tie-rod height 8.6e-11 m from the
/// root that re-runs find, the camber gain 7.0e-9 deg/m inside its bound; the multipliers 8.5 and 736,
/// both positive), and bump steer gained 33.7 deg/m on the model's.
#[test]
fn the_most_bump_steer_within_a_camber_gain_band_is_a_constrained_maximum() {
    let doc = document();
    let (inner0, front0) =
        (doc.pointer(INNER_Z).unwrap().as_f64().unwrap(), doc.pointer(FRONT_Z).unwrap().as_f64().unwrap());
    let (bump0, camber0) = figures(&doc, inner0, front0);
    let text = json!({
        "free": { INNER_Z: [inner0 - 0.04, inner0 + 0.04], FRONT_Z: [front0 - 0.04, front0 + 0.04] },
        "objective": { "most": "parallel-travel/bump_steer" },
        "targets": [ { "figure": "parallel-travel/camber_gain", "value": camber0, "tolerance": 0.5 } ],
        "steps": STEPS })
    .to_string();
    let targets = read_targets(&text, "t.json", &doc, no_file).unwrap();
    let parameters = Parameters::new(&doc, &[INNER_Z.to_string(), FRONT_Z.to_string()]).unwrap();
    let tuned = tune(&parameters, &targets, |_| {}).unwrap();
    let (inner, front) = (tuned.end.x[0], tuned.end.x[1]);
    let objective = tuned.objective.as_ref().unwrap();
    assert!(objective.end > bump0 + 30.0, "{objective:?}");
    assert!(tuned.verdicts[0].met && tuned.uncertainty.is_none(), "{:?}", tuned.verdicts);
    // The mount on its lower bound, the camber gain on the lower end of its band, both named as holding it.
    assert_eq!(front, front0 - 0.04);
    let (bump, camber) = figures(&doc, inner, front);
    let bound = camber0 - 0.5;
    assert!((camber - bound).abs() < 1e-7 && camber >= bound - 1e-12, "{camber} against {bound}");
    assert!((bump - objective.end).abs() < 1e-9, "the figure the tune reports is a re-run's: {bump} {objective:?}");
    let said = objective.said();
    assert!(
        said.contains("lower_arm_front z at its lower bound") && said.contains("at the lower end of its tolerance"),
        "{said}"
    );
    // The tie-rod height is where the camber gain meets its bound along the mount's bound, by secants of
    // re-runs.
    let (mut a, mut b) = (inner - 1e-3, inner + 1e-3);
    let (mut fa, mut fb) = (figures(&doc, a, front).1 - bound, figures(&doc, b, front).1 - bound);
    for _ in 0..8 {
        let c = b - fb * (b - a) / (fb - fa);
        (a, fa) = (b, fb);
        (b, fb) = (c, figures(&doc, c, front).1 - bound);
        if fb.abs() < 1e-12 {
            break;
        }
    }
    assert!((inner - b).abs() < 2e-9, "tuned {inner}, root {b}");
    // The balance of a maximum: ∇bump = −λ ∇camber − μ e_front with λ, μ ≥ 0 (no direction that keeps the
    // camber gain above its bound and the mount above its own raises bump steer), by central differences.
    let h = 1e-5;
    let rates = |k: usize| {
        let at = |d: f64| if k == 0 { figures(&doc, inner + d, front) } else { figures(&doc, inner, front + d) };
        let (up, down) = (at(h), at(-h));
        ((up.0 - down.0) / (2.0 * h), (up.1 - down.1) / (2.0 * h))
    };
    let ((bump_inner, camber_inner), (bump_front, camber_front)) = (rates(0), rates(1));
    // −bump_inner = λ camber_inner; −bump_front = λ camber_front + μ.
    let lambda = -bump_inner / camber_inner;
    let mu = -bump_front - lambda * camber_front;
    assert!(lambda > 0.0 && mu > 0.0, "multipliers {lambda} {mu}");
}

#[test]
fn an_objective_is_refused_by_key_where_it_cannot_be_sought() {
    let doc = document();
    let z = doc.pointer(INNER_Z).unwrap().as_f64().unwrap();
    let file = |objective: Value, target: Value| {
        json!({ "free": { INNER_Z: [z - 0.01, z + 0.01] }, "objective": objective, "targets": [target] }).to_string()
    };
    let figure = json!({ "figure": "parallel-travel/camber_gain", "value": -15.0, "tolerance": 0.5 });
    let cases = [
        (
            file(
                json!({ "least": "parallel-travel/bump_steer", "most": "parallel-travel/bump_steer" }),
                figure.clone(),
            ),
            "give one of \"least\" or \"most\"",
        ),
        (file(json!({ "fewest": "parallel-travel/bump_steer" }), figure.clone()), "unknown key 'fewest'"),
        (file(json!({ "least": "bump_steer" }), figure.clone()), "objective"),
        (
            file(
                json!({ "least": "parallel-travel/bump_steer" }),
                json!({ "curve": "parallel-travel/toe_deg", "points": [[-0.01, 0.0], [0.01, 0.0]], "measure": "rms", "tolerance": 0.1 }),
            ),
            "with an objective each target is a bound",
        ),
        (
            file(
                json!({ "least": "parallel-travel/bump_steer" }),
                json!({ "figure": "parallel-travel/camber_gain", "value": -15.0, "tolerance": 0.5, "weight": 2 }),
            ),
            "leave out \"weight\"",
        ),
    ];
    for (text, said) in cases {
        let e = read_targets(&text, "t.json", &doc, no_file).unwrap_err();
        assert!(e.to_string().contains(said), "{e}");
        assert!(!matches!(*e.refusal, TargetsRefusal::NotObject), "{e}");
    }
}
