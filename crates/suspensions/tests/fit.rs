//! What a fit can know (`design::fit`): the reported standard uncertainties of bushing rates fitted to
//! noisy K&C data against the scatter of the fits over many noise draws; the covariance against linear
//! least squares' closed form; a number a bound holds left out and named; a direction the data cannot see
//! named in the engineer's words.

mod common;

use common::{lateral_force_rig, ARM_RADIAL, TOP_RADIAL};
use elastokin_suspensions::design::fit::FitUncertainty;
use elastokin_suspensions::design::targets::read_targets;
use elastokin_suspensions::design::tune::tune;
use elastokin_suspensions::design::Parameters;
use elastokin_suspensions::kc::{self, Analysis, Settings};
use elastokin_suspensions::study::batch::base_document;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde_json::{json, Value};

fn document(name: &str) -> Value {
    let path = format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"));
    base_document(&std::fs::read_to_string(&path).unwrap(), &path).unwrap()
}

fn value(doc: &Value, pointer: &str) -> f64 {
    doc.pointer(pointer).unwrap().as_f64().unwrap()
}

/// A normal draw by Box and Muller's transform.
fn normal(rng: &mut ChaCha8Rng) -> f64 {
    let (u, v): (f64, f64) = (rng.random::<f64>().max(1e-300), rng.random());
    (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
}

/// Bushing rates fitted to a lateral-force test whose toe and camber carry noise of 0.005° (one standard
/// deviation, given as the target's noise), 24 draws: each fit is judged met against the noise, where point by
/// point most would not be; the scatter of the fitted rates is what each fit reports as its standard
/// uncertainty, within what 24 draws can tell (a sample's standard deviation is off by 1/√46 = 15 % of
/// itself, one standard deviation).
#[test]
fn the_reported_uncertainty_of_fitted_rates_is_the_scatter_of_noisy_fits() {
    let base = document("macpherson.json");
    let (arm, top) = (ARM_RADIAL, TOP_RADIAL);
    let (rig, [load, toe, camber]) = lateral_force_rig(&base, 1.25, 0.8);
    let noise = 0.005;
    let p = Parameters::new(&base, &[arm.to_string(), top.to_string()]).unwrap();
    let (mut fitted, mut reported): (Vec<[f64; 2]>, Vec<[f64; 2]>) = (Vec::new(), Vec::new());
    let mut within_tolerance = 0;
    for seed in 0..24 {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut csv = "# analysis: lateral-force\nload_n,toe_deg,camber_deg\n".to_string();
        for k in 0..load.len() {
            let (t, c) = (toe[k] + noise * normal(&mut rng), camber[k] + noise * normal(&mut rng));
            csv.push_str(&format!("{},{t},{c}\n", load[k]));
        }
        let text = json!({
            "free": { arm: [2e6, 1e7], top: [1e6, 4e6] },
            "targets": [{ "measured": "rig.csv", "analysis": "lateral-force", "columns": ["toe_deg", "camber_deg"],
                          "noise": { "toe_deg": noise, "camber_deg": noise } }],
            "steps": 16,
        })
        .to_string();
        let targets = read_targets(&text, "fit.json", &base, |_| Ok(csv.clone())).unwrap();
        let tuned = tune(&p, &targets, |_| {}).unwrap();
        // Judged against the noise it is met; point by point against a tolerance of the noise's size, a
        // fit to the truth is not.
        assert!(tuned.all_met(), "{seed}: {:?}", tuned.verdicts);
        within_tolerance += usize::from(tuned.end.residuals.iter().all(|r| r.abs() <= 1.0));
        let u = tuned.uncertainty.as_ref().expect("a fit has an uncertainty");
        assert!(u.at_bound.is_empty() && u.unique(), "{seed}: {u:?}");
        assert_eq!(u.degrees_of_freedom, 2 * load.len() - 2);
        fitted.push([tuned.end.x[0], tuned.end.x[1]]);
        reported.push([u.standard[0].unwrap(), u.standard[1].unwrap()]);
    }
    // Measured 0 of 24: 34 misses all within one standard deviation has a chance of about 0.68^34 = 2e-6.
    assert_eq!(within_tolerance, 0, "{within_tolerance} of 24 fits within the noise point by point");
    let n = fitted.len() as f64;
    for k in 0..2 {
        let mean = fitted.iter().map(|f| f[k]).sum::<f64>() / n;
        let scatter = (fitted.iter().map(|f| (f[k] - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        let claimed = (reported.iter().map(|r| r[k] * r[k]).sum::<f64>() / n).sqrt();
        // The truth within three standard errors of the mean: the fit is unbiased.
        let truth = value(&rig, [arm, top][k]);
        assert!((mean - truth).abs() < 3.0 * claimed / n.sqrt(), "{k}: mean {mean} against {truth} (± {claimed})");
        // Measured ratios 1.02 and 0.84; the band is three standard deviations of a 24-draw scatter.
        let ratio = scatter / claimed;
        assert!((0.55..1.45).contains(&ratio), "{k}: scatter {scatter} against reported {claimed}: {ratio}");
        // Guard: the noise moves the rates (by more than a part in ten thousand).
        assert!(claimed > 1e-4 * truth, "{k}: {claimed}");
    }
}

/// A linear fit's Jacobian `A`, its residuals at the end and the bounds of its two numbers.
const LINEAR: [[f64; 2]; 5] = [[1.0, 0.5], [0.3, 2.0], [1.2, -0.7], [0.1, 0.4], [-0.8, 1.1]];
const LINEAR_RESIDUALS: [f64; 5] = [0.02, -0.01, 0.015, -0.03, 0.005];
const LINEAR_BOUNDS: [(f64, f64); 2] = [(-10.0, 10.0), (-5.0, 5.0)];

/// Linear least squares: for residuals `r = A x − b` the covariance of the fit is `s² (AᵀA)⁻¹`, written out
/// here for two numbers; a number at its bound is left out and named; a column of zeros is a direction the
/// data do not see, and no uncertainty is claimed.
#[test]
fn the_covariance_is_least_squares_closed_form_and_what_it_cannot_see_is_named() {
    let (a, r, bounds) = (LINEAR, LINEAR_RESIDUALS, LINEAR_BOUNDS);
    let jacobian: Vec<Vec<f64>> = a.iter().map(|row| row.to_vec()).collect();
    let u = FitUncertainty::of(&[1.0, 2.0], &bounds, &r, &jacobian, &[]);
    let s2 = r.iter().map(|r| r * r).sum::<f64>() / 3.0;
    let (p, q, t) = (
        a.iter().map(|x| x[0] * x[0]).sum::<f64>(),
        a.iter().map(|x| x[0] * x[1]).sum::<f64>(),
        a.iter().map(|x| x[1] * x[1]).sum::<f64>(),
    );
    let det = p * t - q * q;
    let (c00, c11, c01) = (s2 * t / det, s2 * p / det, -s2 * q / det);
    let (s0, s1) = (u.standard[0].unwrap(), u.standard[1].unwrap());
    let rho = u.correlation[0][1].unwrap();
    // Measured 1e-16 relative.
    assert!((s0 / c00.sqrt() - 1.0).abs() < 1e-13 && (s1 / c11.sqrt() - 1.0).abs() < 1e-13, "{s0} {s1}");
    assert!((rho - c01 / (c00 * c11).sqrt()).abs() < 1e-13, "{rho}");
    assert_eq!(u.degrees_of_freedom, 3);
    assert!(u.unique());
    // The second number at its upper bound: the first alone is fitted, by its own column.
    let held = FitUncertainty::of(&[1.0, 5.0], &bounds, &r, &jacobian, &[]);
    assert_eq!(held.at_bound, [1]);
    assert_eq!(held.standard[1], None);
    let alone = (r.iter().map(|r| r * r).sum::<f64>() / 4.0 / p).sqrt();
    assert!((held.standard[0].unwrap() / alone - 1.0).abs() < 1e-13);
    // A second number the residuals do not move: unseen, named as the second alone, and no uncertainty.
    let blind: Vec<Vec<f64>> = a.iter().map(|row| vec![row[0], 0.0]).collect();
    let u = FitUncertainty::of(&[1.0, 2.0], &bounds, &r, &blind, &[]);
    assert!(!u.unique() && u.unseen.len() == 1 && u.unseen[0].share.is_none(), "{u:?}");
    assert!((u.unseen[0].direction[1] - 1.0).abs() < 1e-12 && u.unseen[0].direction[0].abs() < 1e-12);
    assert!(u.standard.iter().all(Option::is_none));
}

/// A packaging constraint at its limit, `x₀ + 2 x₁` held, leaves the fit one combination, along
/// `(2, −1)`: its uncertainty is the one-number fit's by the column `J (2, −1)ᵀ` over one degree of freedom
/// more, written out here, and the two numbers fully anti-correlated. A constraint along one number alone
/// holds that number: no uncertainty for it, the other fitted by its own column.
#[test]
fn a_packaging_constraint_that_holds_the_fit_takes_its_degree_of_freedom() {
    let (a, r, bounds) = (LINEAR, LINEAR_RESIDUALS, LINEAR_BOUNDS);
    let jacobian: Vec<Vec<f64>> = a.iter().map(|row| row.to_vec()).collect();
    let u = FitUncertainty::of(&[1.0, 2.0], &bounds, &r, &jacobian, &[vec![1.0, 2.0]]);
    // Along the constraint x = (2, −1) t: the column J (2, −1)ᵀ, four degrees of freedom.
    let column: Vec<f64> = a.iter().map(|row| 2.0 * row[0] - row[1]).collect();
    let s2 = r.iter().map(|r| r * r).sum::<f64>() / 4.0;
    let t = (s2 / column.iter().map(|c| c * c).sum::<f64>()).sqrt();
    let (s0, s1) = (u.standard[0].unwrap(), u.standard[1].unwrap());
    // Measured: equal to the bit, and a correlation of exactly −1.
    assert!((s0 / (2.0 * t) - 1.0).abs() < 1e-14 && (s1 / t - 1.0).abs() < 1e-14, "{s0} {s1} {t}");
    assert!((u.correlation[0][1].unwrap() + 1.0).abs() < 1e-14, "{u:?}");
    assert_eq!((u.degrees_of_freedom, u.held_by_packaging), (4, 1));
    assert!(u.basis().contains("along the packaging that holds 1 combination"), "{}", u.basis());
    // Held along the second number alone: the first fitted by its own column, the second not at all.
    let u = FitUncertainty::of(&[1.0, 2.0], &bounds, &r, &jacobian, &[vec![0.0, 3.0]]);
    let alone = (s2 / a.iter().map(|x| x[0] * x[0]).sum::<f64>()).sqrt();
    assert!((u.standard[0].unwrap() / alone - 1.0).abs() < 1e-13 && u.standard[1].is_none(), "{u:?}");
}

/// The MacPherson's toe curve fitted with the inner tie-rod point free in x, along the rod, besides z: the
/// toe barely moves with x, so the fit cannot place it, and says so in the parameters' words.
#[test]
fn a_tie_rod_point_along_the_rod_is_named_as_what_the_toe_curve_cannot_see() {
    let base = document("macpherson.json");
    let (x, z) =
        ("/suspension/macpherson/hardpoints/tie_rod_inner/0", "/suspension/macpherson/hardpoints/tie_rod_inner/2");
    let file = Parameters::new(&base, &[]).unwrap().file().unwrap();
    let settings = Settings { range: Some((-0.05, 0.05)), steps: 10, ..Settings::default() };
    let r = kc::run(Analysis::ParallelTravel, &file, &settings).unwrap();
    let toe = r.table.column("toe_deg").unwrap();
    // The measured toe with noise of 0.01° on each point, alternating in sign.
    let points: Vec<(f64, f64)> = r
        .table
        .rows
        .iter()
        .zip(&toe)
        .enumerate()
        .map(|(k, (row, t))| (row[0].number().unwrap(), t.unwrap() + if k % 2 == 0 { 0.01 } else { -0.01 }))
        .collect();
    let text = json!({
        "free": { x: [value(&base, x) - 0.02, value(&base, x) + 0.02], z: [value(&base, z) - 0.02, value(&base, z) + 0.02] },
        "targets": [{ "curve": "parallel-travel/toe_deg", "range": [-0.05, 0.05], "points": points, "tolerance": 0.01 }],
        "steps": 10,
    })
    .to_string();
    let targets = read_targets(&text, "t.json", &base, |f| Err(format!("no file {f}"))).unwrap();
    let p = Parameters::new(&base, &[x.to_string(), z.to_string()]).unwrap();
    let tuned = tune(&p, &targets, |_| {}).unwrap();
    let u = tuned.uncertainty.as_ref().expect("a fit has an uncertainty");
    assert!(!u.unique(), "{u:?}");
    let said = u.unseen[0].said(&[x.to_string(), z.to_string()]);
    // Measured: x alone (+1.00), uncertain by 80 % of its ±20 mm; z is seen.
    assert!(said.starts_with("tie_rod_inner x (+1.00)") && !said.contains(" z "), "{said}");
    assert!(u.unseen.len() == 1 && u.unseen[0].share.is_some_and(|s| s > 0.5), "{u:?}");
}

/// A model that cannot follow the data: the top mount's rate held at twice the rig's, the arm's alone free.
/// The misses exceed what the noise gives, and the verdict says so in the data's words.
#[test]
fn a_model_that_cannot_follow_noisy_data_is_judged_not_met_against_its_noise() {
    let base = document("macpherson.json");
    let arm = ARM_RADIAL;
    let (_, [load, toe, camber]) = lateral_force_rig(&base, 1.0, 0.5);
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    // The loads too carry the rig's noise: the end rows lie past the analysis's default ±3 kN.
    let mut csv = "# analysis: lateral-force\nload_n,toe_deg,camber_deg\n".to_string();
    for k in 0..load.len() {
        let f = load[k] * (1.0 + 0.01 * normal(&mut rng).abs());
        csv.push_str(&format!("{f},{},{}\n", toe[k] + 0.005 * normal(&mut rng), camber[k] + 0.005 * normal(&mut rng)));
    }
    let text = json!({
        "free": { arm: [2e6, 1e7] },
        "targets": [{ "measured": "rig.csv", "analysis": "lateral-force", "noise": 0.005 }],
        "steps": 16,
    })
    .to_string();
    let targets = read_targets(&text, "fit.json", &base, |_| Ok(csv.clone())).unwrap();
    let range = targets.targets[0].range.unwrap();
    assert!(range.0 < -3000.0 && range.1 > 3000.0, "{range:?}");
    let p = Parameters::new(&base, &[arm.to_string()]).unwrap();
    let tuned = tune(&p, &targets, |_| {}).unwrap();
    let v = tuned.verdicts.iter().find(|v| !v.met).unwrap_or_else(|| panic!("{:?}", tuned.verdicts));
    assert!(v.judged.contains("beyond"), "{v:?}");
    assert!(v.why.as_deref().unwrap().contains("larger than the data's noise"), "{v:?}");
}

#[test]
fn a_measured_targets_noise_and_tolerance_are_read_per_column_and_refused_by_key() {
    let base = document("macpherson.json");
    let csv = "# analysis: lateral-force\nload_n,toe_deg,camber_deg\n-3000,0.1,0.02\n0,0,0\n3000,-0.1,-0.02\n";
    let read = |target: Value| {
        let text = json!({ "free": { "/suspension/macpherson/spring/rate": [2e4, 3e4] }, "targets": [target] });
        let text = text.to_string();
        read_targets(&text, "t.json", &base, |_| Ok(csv.to_string())).map_err(|e| e.to_string())
    };
    let m = |extra: Value| {
        let mut t = json!({ "measured": "rig.csv", "analysis": "lateral-force" });
        t.as_object_mut().unwrap().extend(extra.as_object().unwrap().clone());
        read(t)
    };
    let t = m(json!({ "tolerance": { "toe_deg": 0.01, "camber_deg": 0.02 } })).unwrap();
    assert_eq!(t.targets.iter().map(|t| t.tolerance).collect::<Vec<_>>(), [0.01, 0.02]);
    let refused = [
        (json!({ "tolerance": 0.01, "noise": 0.01 }), "not both"),
        (json!({ "noise": { "toe_deg": 0.01 } }), "give one for 'camber_deg' too"),
        (
            json!({ "noise": { "toe_deg": 0.01, "camber_deg": 0.01, "toe": 0.1 } }),
            "'toe' is not one of the target's columns",
        ),
        (json!({ "noise": -1 }), "targets[0].noise: give a positive miss"),
    ];
    for (extra, words) in refused {
        let e = m(extra.clone()).unwrap_err();
        assert!(e.contains(words), "{extra}: {e}");
    }
}
