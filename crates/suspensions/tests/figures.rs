//! Every figure of every shipped model: the same at 4, 8, 32 and 160 steps (a figure at design is read
//! off the equilibrium there and its tangent, not the rows), its printed error estimate bounding its
//! distance from a fine reference, and the rates at design against a second method written here: the
//! slopes of a narrow sweep's own rows, Richardson extrapolated.

mod common;
use elastokin_suspensions::kc::{self, Analysis, AnalysisReport, Figure, KcReport, Settings};
use elastokin_suspensions::SuspensionFile;
use std::path::Path;

use common::{examples, models, MODELS};

#[test]
fn the_list_of_models_is_every_json_file_shipped_outside_targets() {
    let mut found = Vec::new();
    for dir in ["", "generic", "vehicle"] {
        for entry in std::fs::read_dir(examples().join(dir)).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "json") {
                let name = path.file_name().unwrap().to_str().unwrap();
                found.push(if dir.is_empty() { name.to_string() } else { format!("{dir}/{name}") });
            }
        }
    }
    found.sort();
    let mut listed: Vec<String> = MODELS.iter().map(|m| m.to_string()).collect();
    listed.sort();
    assert_eq!(found, listed);
}

/// Every analysis of the suite that applies to `file` (a model without a load case of its own has no
/// `loads`, a corner without a tie rod no `steering`: those fail with their reason, alike at any steps).
fn suite(file: &SuspensionFile, settings: &Settings) -> KcReport {
    kc::run_suite(file, &kc::ALL, settings, |_| {})
}

/// `a` and `b` agree within their printed estimates and `relative` of their size, plus the rounding of
/// their last bits; a figure that is zero (a five-link's camber under a traction force) is rounding in both,
/// and 1e-12 of its printed unit is allowed.
fn agree(a: &Figure, b: &Figure, relative: f64) -> Result<(), String> {
    match (a.value, b.value) {
        (Some(x), Some(y)) => {
            let (ex, ey) = (a.error.unwrap_or(0.0), b.error.unwrap_or(0.0));
            let zero = 1e-12 / a.unit.shown().factor;
            let allowed = ex + ey + relative * x.abs().max(y.abs()) + 8.0 * f64::EPSILON * x.abs().max(y.abs()) + zero;
            if (x - y).abs() <= allowed {
                Ok(())
            } else {
                Err(format!("{} {x:e} ± {ex:e} against {y:e} ± {ey:e}", a.key))
            }
        }
        (None, None) => Ok(()),
        _ => Err(format!("{}: {:?} against {:?}", a.key, a.value, b.value)),
    }
}

#[test]
fn every_figure_is_the_same_from_4_to_160_steps_and_its_estimate_bounds_its_distance_from_a_fine_run() {
    let (mut figures, mut different) = (0, 0);
    for (name, file) in models() {
        let reference = suite(&file, &Settings { steps: 640, ..Settings::default() });
        for steps in [4, 8, 32, 160] {
            let report = suite(&file, &Settings { steps, ..Settings::default() });
            assert_eq!(report.skipped.len(), reference.skipped.len(), "{name}");
            assert_eq!(report.failed, reference.failed, "{name}");
            for (a, r) in report.analyses.iter().zip(&reference.analyses) {
                assert_eq!(a.analysis, r.analysis);
                for (f, g) in a.figures.iter().zip(&r.figures) {
                    assert_eq!(f.key, g.key, "{name} {}", a.analysis.name());
                    assert!(declared(f), "{name} {}: `{}` is not in kc::figures", a.analysis.name(), f.key);
                    // Every figure with a value has an estimate.
                    assert!(
                        f.value.is_none() || f.error.is_some(),
                        "{name} {} {}: no estimate",
                        a.analysis.name(),
                        f.key
                    );
                    // A figure at design is the same at any steps: 1e-9 of it.
                    if let Err(e) = agree(f, g, 1e-9) {
                        panic!("{name} {} at {steps} steps: {e}", a.analysis.name());
                    }
                    if let (Some(x), Some(y)) = (f.value, g.value) {
                        different += usize::from(x != y);
                    }
                    figures += 1;
                }
            }
        }
    }
    // Measured: 2528 figures (11 models at 4 step counts), 454 of them not the fine run's to the bit (those
    // read off the rows: at the range's end, largest over it), each within its estimate.
    eprintln!("{figures} figures compared, {different} not the fine run's to the bit");
    assert!(figures > 2000 && different > 0, "{figures} figures compared, {different} different");
}

/// The slope of the mean of columns `ys` against column `x` at the middle row of `report`'s five rows
/// (evenly spaced): the central differences over one and two rows, Richardson extrapolated, and its
/// uncertainty: the extrapolation's step, and what the columns' own error estimates leave in the
/// differences.
fn slope_of(report: &AnalysisReport, x: &str, ys: &[&str]) -> (f64, f64) {
    let column = |name: &str| {
        let k = report.table.columns.iter().position(|c| c == name).unwrap_or_else(|| panic!("no column {name}"));
        report.table.rows.iter().map(|r| r[k].number().unwrap()).collect::<Vec<f64>>()
    };
    let error =
        |name: &str| report.accuracy.columns.iter().find(|(c, _)| c == name).and_then(|(_, e)| *e).unwrap_or(0.0);
    let xs = column(x);
    let mut y = vec![0.0; xs.len()];
    for name in ys {
        for (v, c) in y.iter_mut().zip(column(name)) {
            *v += c / ys.len() as f64;
        }
    }
    assert_eq!(xs.len(), 5);
    let near = (y[3] - y[1]) / (xs[3] - xs[1]);
    let far = (y[4] - y[0]) / (xs[4] - xs[0]);
    let value = (4.0 * near - far) / 3.0;
    let ey = ys.iter().map(|c| error(c)).fold(0.0f64, f64::max);
    // The rows are equilibria to the solver's force tolerance (1e-9 of the force scale), which one Newton
    // iteration on no longer shows once they have converged: that much of the slope is allowed too.
    let uncertainty =
        (near - far).abs() / 3.0 + 2.0 * (ey + error(x) * value.abs()) / (xs[3] - xs[1]).abs() + 1e-9 * value.abs();
    (value, uncertainty)
}

/// A rate at design and how the rows give it: the analysis, its narrow range's step (in its unit), the
/// figure, the table's columns it is the slope of (their mean against `x`), the figure's printed unit per
/// the table's, and its size on a passenger car (printed unit).
struct Case {
    analysis: Analysis,
    step: f64,
    key: &'static str,
    x: &'static str,
    ys: &'static [&'static str],
    scale: f64,
    size: f64,
}

#[test]
fn the_rates_at_design_are_the_slopes_of_a_narrow_sweep_s_rows() {
    use elastokin_suspensions::analysis::WheelLoad;
    let lateral = Analysis::Road(WheelLoad::Lateral);
    let case = |analysis, step, key, x, ys, scale, size| Case { analysis, step, key, x, ys, scale, size };
    let cases = [
        case(Analysis::ParallelTravel, 1e-3, "bump_steer", "travel_m", &["toe_deg"][..], 1.0, 1.0),
        case(Analysis::ParallelTravel, 1e-3, "camber_gain", "travel_m", &["camber_deg"], 1.0, 10.0),
        case(Analysis::ParallelTravel, 1e-3, "wheel_rate", "travel_m", &["wheel_load_n"], 1e-3, 30.0),
        case(
            Analysis::Steering,
            1e-3,
            "steer_per_rack_travel",
            "rack_travel_m",
            &["left_steer_deg", "right_steer_deg"],
            1e-3,
            0.3,
        ),
        case(lateral, 10.0, "steer", "load_n", &["toe_deg"], 1e3, 0.05),
        case(lateral, 10.0, "camber", "load_n", &["camber_deg"], 1e3, 0.05),
        case(Analysis::Road(WheelLoad::Braking), 10.0, "steer", "load_n", &["toe_deg"], 1e3, 0.05),
        case(Analysis::Road(WheelLoad::AligningTorque), 1.0, "steer", "load_nm", &["toe_deg"], 1e3, 0.3),
    ];
    let mut worst = (0.0f64, String::new());
    let mut compared = 0;
    for (name, file) in models() {
        for &Case { analysis, step, key, x, ys, scale, size } in &cases {
            let Ok(report) = kc::run(analysis, &file, &Settings::default()) else { continue };
            // Compared in the unit the figure is printed in, `scale` of the table's.
            let figure = report.figures.iter().find(|f| f.key == key).unwrap().written(kc::Units::DegPerM);
            let Some(value) = figure.value else { continue };
            let narrow = Settings { range: Some((-2.0 * step, 2.0 * step)), steps: 4, ..Settings::default() };
            let rows = kc::run(analysis, &file, &narrow).unwrap();
            let (slope, uncertainty) = slope_of(&rows, x, ys);
            // The rows are equilibria to the solver's force tolerance (1e-9 of the force scale), which one
            // Newton iteration on no longer shows once they have converged: 1e-9 of the figure's size on a
            // car is allowed too (a steer the joints alone hold reads 2.7e-11 deg/kN·m off the rows).
            let (slope, uncertainty) = (slope * scale, uncertainty * scale + 1e-9 * size);
            let e = figure.error.unwrap();
            let miss = (value - slope).abs();
            assert!(
                miss <= e + uncertainty,
                "{name} {} {key}: {value:e} ± {e:e} against the rows' {slope:e} ± {uncertainty:e}",
                analysis.name()
            );
            compared += 1;
            let ratio = miss / (e + uncertainty);
            if ratio > worst.0 {
                worst = (ratio, format!("{name} {} {key}", analysis.name()));
            }
        }
    }
    eprintln!("{compared} rates compared; the largest miss {:.3} of what is allowed ({})", worst.0, worst.1);
    assert!(compared > 40, "{compared}");
}

/// Whether `f` is one of `kc::figures`, or one whose key names a part of the model or another figure (a
/// shared beam's twist per roll, a figure with the bushings rigid and their share of it).
fn declared(f: &Figure) -> bool {
    let named = f.key.ends_with("_twist_per_roll") || f.key.ends_with("_rigid_bushings");
    named || f.key.starts_with("bushing_share_of_") || kc::figures::ALL.iter().any(|k| k.key == f.key)
}

/// `crates/suspensions/src/kc/figures.rs` lists every figure it declares in `ALL`, once.
#[test]
fn the_list_of_figures_is_every_figure_declared() {
    let source = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("src/kc/figures.rs")).unwrap();
    let declared: Vec<&str> = source
        .lines()
        .filter_map(|l| l.strip_prefix("pub const ")?.split_once(": FigureKind").map(|(name, _)| name))
        .collect();
    let listed: Vec<&str> = source.lines().filter_map(|l| l.trim().strip_prefix('&')?.strip_suffix(',')).collect();
    assert_eq!(declared, listed);
    assert_eq!(declared.len(), kc::figures::ALL.len());
}

/// `docs/figures.md` has a row for every declared figure, with the unit it is printed in and its SI unit as
/// the code has them; and every key it lists is declared (or names a part of the model).
#[test]
fn the_figure_table_in_docs_is_the_declared_figures_with_their_units() {
    let docs = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/figures.md")).unwrap();
    // (keys, printed, SI) of every table row.
    let rows: Vec<(Vec<String>, String, String)> = docs
        .lines()
        .filter(|l| l.starts_with("| `"))
        .map(|l| {
            let cells: Vec<&str> = l.split(" | ").collect();
            let keys = cells[0].split('`').skip(1).step_by(2).map(String::from).collect();
            (keys, cells[1].to_string(), cells[2].to_string())
        })
        .collect();
    for kind in kc::figures::ALL {
        let (symbol, si) = (kind.unit.shown().symbol, kind.unit.si());
        let found = rows.iter().any(|(keys, printed, s)| {
            keys.iter().any(|k| k == kind.key) && printed.starts_with(symbol) && s.starts_with(si)
        });
        assert!(found, "docs/figures.md has no row `{}` | {symbol} | {si}", kind.key);
    }
    for (keys, _, _) in &rows {
        for key in keys {
            let named =
                key.starts_with('<') || key.ends_with("_rigid_bushings") || key.starts_with("bushing_share_of_");
            assert!(named || kc::figures::ALL.iter().any(|k| k.key == key), "docs/figures.md lists `{key}`");
        }
    }
}
