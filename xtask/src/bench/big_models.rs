//! Big model files, as a user writes them: the shipped five-link corner with a chain of N more bodies, each
//! on a bushing to the chassis and tied to the one before by a bushing (the first to the wheel carrier) or
//! by a hinge (the first to the chassis: a chain of hinges dragged by the wheel carrier would stiffen the
//! corner N-fold, and its Newton iterations would grow with that load, which is the model's mechanics,
//! not the cost of its size). What `elastokin check` and `elastokin run --analysis parallel-travel` do on them, through
//! the library: reading the file, the plausibility check (mobility and the condition at design), the run.
//! Time and peak memory against N, and their fitted exponents.

use super::alloc;
use super::models::root;
use super::report::{Cell, Judge, Kind, SectionOutput, Table, Target};
use super::stats::{power_law_exponent, Budget};
use super::Settings;
use elastokin_suspensions::kc::{self, Analysis};
use elastokin_suspensions::{check_model, Rig, Side, SuspensionFile};
use serde_json::{json, Value};

const MIB: f64 = 1024.0 * 1024.0;

/// How each added body is tied to the one before.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Tie {
    Bushing,
    Hinge,
}

impl Tie {
    fn name(self) -> &'static str {
        match self {
            Tie::Bushing => "bushings",
            Tie::Hinge => "hinges",
        }
    }
}

/// The shipped five-link corner with `n` bodies added, as model file text.
fn model_text(n: usize, tie: Tie) -> Result<String, String> {
    let path = root().join("examples/five_link.json");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut doc: Value = serde_json::from_str(&text).map_err(|e| e.to_string())?;
    let general = &mut doc["suspension"]["general"];
    general["bushings"] = json!([]);
    let mut previous = match tie {
        Tie::Bushing => "wheel carrier",
        Tie::Hinge => "chassis",
    }
    .to_string();
    for i in 0..n {
        // On a helix inboard of the wheel carrier, 0.25 m about it: every point apart, all near the corner.
        let turn = 0.7 * i as f64;
        let point = format!("mass_{i}");
        let at = [0.25 * turn.cos(), 0.55 + 0.2 * i as f64 / n as f64, 0.25 * turn.sin()];
        let body = format!("mass {i}");
        general["hardpoints"][&point] = json!(at);
        push(&mut general["bodies"], json!({ "name": body, "at": point }))?;
        let mount = json!({ "name": format!("mount {i}"), "bodies": ["chassis", body], "at": point, "axis": [0, 1, 0],
            "radial": 2e5, "axial": 1e5, "torsion": 500, "conical": 2000 });
        push(&mut general["bushings"], mount)?;
        match tie {
            Tie::Bushing => {
                let tie = json!({ "name": format!("tie {i}"), "bodies": [previous, body], "at": point,
                    "axis": [1, 0, 0], "radial": 1e6, "axial": 5e5, "torsion": 1000, "conical": 5000 });
                push(&mut general["bushings"], tie)?;
            }
            Tie::Hinge => {
                let hinge = json!({ "name": format!("hinge {i}"), "kind": "revolute", "bodies": [previous, body],
                    "at": point, "axis": [1, 0, 0] });
                push(&mut general["joints"], hinge)?;
            }
        }
        previous = body;
    }
    Ok(doc.to_string())
}

fn push(list: &mut Value, item: Value) -> Result<(), String> {
    list.as_array_mut().ok_or("the five-link example's lists are lists")?.push(item);
    Ok(())
}

struct Measured {
    n: usize,
    tie: Tie,
    coordinates: usize,
    read: f64,
    check: f64,
    run: f64,
    check_peak: usize,
    run_peak: usize,
    rows: usize,
}

fn measure(n: usize, tie: Tie, budget: Budget) -> Result<Measured, String> {
    let text = model_text(n, tie)?;
    let name = format!("five-link with {n} more bodies on {}", tie.name());
    let read = budget.time(|| SuspensionFile::from_json(&text, &name).map(drop));
    let file = SuspensionFile::from_json(&text, &name).map_err(|e| e.to_string())?;
    let check = budget.time(|| check_model(&file).map(drop));
    let (checked, check_usage) = alloc::track(|| check_model(&file));
    checked.map_err(|e| e.to_string())?;
    let corner = file.suspension.build(Side::Left, Rig::Free).map_err(|e| e.to_string())?;
    let coordinates = corner.model.dofs();
    let run = || kc::run_suite(&file, &[Analysis::ParallelTravel], &kc::Settings::default(), |_| {});
    let (report, run_usage) = alloc::track(run);
    let report = report.complete().map_err(|e| e.to_string())?;
    let rows = report.analyses.iter().map(|a| a.table.rows.len()).sum();
    let run = budget.time(run);
    Ok(Measured {
        n,
        tie,
        coordinates,
        read: read.median,
        check: check.median,
        run: run.median,
        check_peak: check_usage.peak_bytes,
        run_peak: run_usage.peak_bytes,
        rows,
    })
}

/// Runs the section.
pub fn run(s: &Settings) -> SectionOutput {
    let sizes: &[usize] = if s.quick { &[100, 300, 1000] } else { &[1000, 2000, 5000, 10000] };
    let fit_from = sizes[0];
    let mut out = SectionOutput {
        title: "Big model files: check and run".into(),
        intro: "The shipped five-link corner (`examples/five_link.json`) with N more bodies, each on a bushing to \
                the chassis and tied to the one before by a bushing (the first to the wheel carrier) or by a \
                hinge (the first to the chassis, so that the corner's path is the same at every N), as model \
                file text. Read: `SuspensionFile::from_json`; check: `check_model` (mobility, \
                the condition at design by Lanczos on the sparse factorization, the geometry's checks); run: \
                the parallel-travel analysis through `kc::run_suite`, the plausibility check included, at its \
                default steps. Peak: live bytes above the start. Exponents: least squares of ln time and ln \
                peak against ln N."
            .into(),
        ..SectionOutput::default()
    };
    let mut table = Table::new(
        "Check and run against the number of bodies",
        "big_models.csv",
        &[
            "tie",
            "N bodies",
            "coordinates",
            "read (s)",
            "check (s)",
            "run (s)",
            "check peak (MiB)",
            "run peak (MiB)",
            "rows",
            "status",
        ],
    );
    let mut results = Vec::new();
    for tie in [Tie::Bushing, Tie::Hinge] {
        for &n in sizes {
            let budget = if n >= 2000 { Budget { seconds: 0.0, min_reps: 1, max_reps: 1 } } else { s.budget() };
            match measure(n, tie, budget) {
                Ok(m) => {
                    table.row(vec![
                        Cell::text(tie.name()),
                        Cell::count(m.n as u64),
                        Cell::count(m.coordinates as u64),
                        Cell::num(m.read),
                        Cell::num(m.check),
                        Cell::num(m.run),
                        Cell::num(m.check_peak as f64 / MIB),
                        Cell::num(m.run_peak as f64 / MIB),
                        Cell::count(m.rows as u64),
                        Cell::text("ok"),
                    ]);
                    let key = format!("big_models.{}.n{n}", tie.name());
                    out.figure(&format!("{key}.check_s"), m.check, "s", Kind::Time);
                    out.figure(&format!("{key}.run_s"), m.run, "s", Kind::Time);
                    out.figure(&format!("{key}.run_peak_bytes"), m.run_peak as f64, "B", Kind::Memory);
                    results.push(m);
                }
                Err(e) => {
                    let mut row = vec![Cell::text(tie.name()), Cell::count(n as u64)];
                    row.resize(9, Cell::Empty);
                    row.push(Cell::text(format!("failed: {e}")));
                    table.row(row);
                }
            }
        }
    }
    out.tables.push(table);

    let largest = sizes[sizes.len() - 1];
    let mut fits = Table::new(
        "Fitted exponents of check and run",
        "big_models_exponents.csv",
        &["tie", "quantity", "exponent", "over N", "points"],
    );
    for tie in [Tie::Bushing, Tie::Hinge] {
        let of_tie: Vec<&Measured> = results.iter().filter(|m| m.tie == tie).collect();
        for (what, limit, get) in [
            ("check time", 1.2, (|m: &Measured| m.check) as fn(&Measured) -> f64),
            ("run time", 1.2, |m: &Measured| m.run),
            ("check peak memory", 1.05, |m: &Measured| m.check_peak as f64),
            ("run peak memory", 1.05, |m: &Measured| m.run_peak as f64),
        ] {
            let points: Vec<(f64, f64)> = of_tie.iter().map(|m| (m.n as f64, get(m))).collect();
            let p = power_law_exponent(&points);
            fits.row(vec![
                Cell::text(tie.name()),
                Cell::text(what),
                Cell::Num(p.unwrap_or(f64::NAN), 3),
                Cell::text(format!("{fit_from}–{largest}")),
                Cell::count(points.len() as u64),
            ]);
            if let Some(p) = p {
                let key = format!("big_models.{}.exponent.{}", tie.name(), super::report::slug(what));
                out.figure(&key, p, "", Kind::Other);
            }
            out.targets.push(Target {
                goal: format!(
                    "{what} of a model file on {} growing no faster than N^{limit} from 1 000 to 10 000 bodies",
                    tie.name()
                ),
                measured: p.ok_or_else(|| "too few sizes measured for a fit".to_string()),
                limit,
                unit: "exponent".into(),
                judge: Judge::ExponentAtMost,
                detail: format!(
                    "least-squares fit over N = {fit_from}–{largest} ({} sizes){}",
                    points.len(),
                    if s.quick { "; --quick stops at 1 000, the full run fits 1 000–10 000" } else { "" }
                ),
            });
        }
    }
    out.tables.push(fits);
    out
}
