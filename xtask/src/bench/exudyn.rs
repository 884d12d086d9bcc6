//! An established multibody code side by side: the shipped MacPherson's vertical force sweep in Exudyn
//! (`bench/exudyn/macpherson.py`, its `SolveStatic` in C++) and in elastokin, at 10, 100 and 1000 equal
//! steps from the equilibrium at the first load, timed in the same run, with the two codes' toe and camber
//! compared step by step.
//!
//! Optional: it needs Python with Exudyn (`pip install exudyn`). Without it the section says how to install
//! it and skips, and the rest of the bench runs as before.

use super::models::{self, Case, Sweep};
use super::report::{slug, Cell, Judge, Kind, SectionOutput, Table, Target};
use super::Settings;
use elastokin_solver::{LoadPath, Mode, SolverOptions, StaticSolver};
use elastokin_suspensions::{SuspensionFile, Template};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The sweeps compared: equal load steps from the first load to the last.
const STEPS: [usize; 3] = [10, 100, 1000];

/// The sweep the target is judged on.
const TARGET_STEPS: usize = 100;

/// The Python interpreter the script runs on.
const PYTHON: &str = "python3";

/// The script, under the workspace root.
const SCRIPT: &str = "bench/exudyn/macpherson.py";

/// Exudyn's two Newton variants: `--newton` of the script.
const NEWTON: [&str; 2] = ["full", "modified"];

const GOAL: &str =
    "MacPherson vertical force sweep of 100 steps: elastokin's corrected sweep at least 30× faster than \
                    Exudyn's SolveStatic (the faster of its full and modified Newton), same machine, same run";
const GOAL_LIMIT: f64 = 30.0;

/// One Exudyn run of the script: its curve and the median time of its `SolveStatic` calls.
struct ExudynRun {
    /// Rows of load (N), wheel centre x, y, z (m), toe, camber (rad).
    rows: Vec<[f64; 6]>,
    /// Median wall time of the whole sweep's `SolveStatic` (s).
    seconds: f64,
    /// Exudyn's Newton iterations and Jacobians over the sweep, as the script counted them.
    counts: String,
}

/// Runs the section.
pub fn run(s: &Settings) -> SectionOutput {
    let mut out = SectionOutput {
        title: "Exudyn side by side".into(),
        intro: format!(
            "The shipped MacPherson's vertical force sweep (wheel free on its spring, a vertical force at the \
             contact patch from 0.5 to 1.5 times the design wheel load) built in Exudyn from the model's \
             general form by `{SCRIPT}` and solved by Exudyn's `SolveStatic` (C++) with elastokin's default \
             tolerance (Newton's relative residual 1e-9), with its full Newton (its default) and its modified \
             Newton. Both codes start from the equilibrium at the first load and take 10, 100 and 1000 equal \
             steps; the times are medians of repetitions in this run: the script times `SolveStatic` alone, and \
             elastokin's time is a new `StaticSolver` and its corrected sweep. The differences are the largest \
             over the sweep's steps. Needs Python with Exudyn (`pip install exudyn`); skipped without it."
        ),
        ..SectionOutput::default()
    };
    let version = match exudyn_version() {
        Ok(v) => v,
        Err(why) => {
            let hint = format!("skipped: {why}. Install it with `pip install exudyn` to run this section.");
            eprint!("\n  exudyn: {hint}\n  ");
            out.notes.push(hint);
            return out;
        }
    };
    let mut table = Table::new(
        "Exudyn's SolveStatic and elastokin on the same sweep",
        "exudyn.csv",
        &[
            "steps",
            "Exudyn Newton",
            "Exudyn (s)",
            "elastokin (s)",
            "Exudyn / elastokin",
            "max |Δ wheel centre| (m)",
            "max |Δ toe| (rad)",
            "max |Δ camber| (rad)",
            "Exudyn's Newton iterations, Jacobians",
            "status",
        ],
    );
    let mut target = Err("the 100-step sweep was not measured".to_string());
    let mut detail = String::new();
    match compare(s, &version, &mut table, &mut out) {
        Ok(at_target) => {
            if let Some((ratio, text)) = at_target {
                target = Ok(ratio);
                detail = text;
            }
        }
        Err(e) => table.failed_row(vec![Cell::text("all")], e),
    }
    out.tables.push(table);
    out.targets.push(Target {
        goal: GOAL.into(),
        measured: target,
        limit: GOAL_LIMIT,
        unit: "×".into(),
        judge: Judge::AtLeast,
        detail,
    });
    out.notes.push(format!(
        "Exudyn {version}. Its bushings are `ObjectConnectorRigidBodySpringDamper` (not intrinsic): the force \
         is elastokin's, the moment is the rates times the Tait-Bryan angles of the relative rotation where \
         elastokin takes the derivative of the rotation vector's energy. The two laws agree to first order \
         in the twist, so the curves meet at the design load and part at second order away from it; with \
         elastokin's law given to Exudyn as a user function they agree to 1e-11 (`tests/exudyn.rs`)."
    ));
    out
}

/// The installed Exudyn's version, or why there is none.
fn exudyn_version() -> Result<String, String> {
    let output = Command::new(PYTHON)
        .args(["-c", "import exudyn; print(exudyn.__version__)"])
        .output()
        .map_err(|e| format!("{PYTHON} could not be started ({e})"))?;
    if !output.status.success() {
        return Err(format!("`{PYTHON} -c \"import exudyn\"` failed: Exudyn is not installed for {PYTHON}"));
    }
    Ok(String::from_utf8_lossy(&output.stdout).trim().to_string())
}

/// Fills the table; returns the target's ratio at [`TARGET_STEPS`] with its detail.
fn compare(
    s: &Settings,
    version: &str,
    table: &mut Table,
    out: &mut SectionOutput,
) -> Result<Option<(f64, String)>, String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let file = models::shipped("generic/macpherson")?;
    let case = models::case(&file, Sweep::VerticalForce)?;
    let dir = std::env::temp_dir().join(format!("elastokin-bench-exudyn-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let result = (|| {
        let model = write_general_form(&file, &dir)?;
        let mut solver = StaticSolver::new(&case.corner.model, SolverOptions::default()).map_err(|e| err(&e))?;
        let mut start = solver.design_state(case.from);
        solver.equilibrium(&mut start).map_err(|e| err(&e))?;
        // What elastokin's times include besides the steps, as Exudyn's include its own set-up.
        let setup =
            s.budget().time(|| StaticSolver::new(&case.corner.model, SolverOptions::default()).map(drop)).median;
        out.figure("exudyn.elastokin_static_solver_new_s", setup, "s", Kind::Time);
        out.notes.push(format!("elastokin's times include `StaticSolver::new`, {:.3} ms (median).", setup * 1e3));
        let mut at_target = None;
        for steps in STEPS {
            let path = LoadPath::new(case.from, case.to, steps);
            // Both of elastokin's policies for corrected steps, the faster one compared: full Newton, and
            // the extrapolating predictor with chord iterations (`reuse_factorization`).
            let elastokin_sweep = |start: &elastokin_solver::State, reuse_factorization: bool| {
                let options = SolverOptions { reuse_factorization, ..SolverOptions::default() };
                StaticSolver::new(&case.corner.model, options)
                    .and_then(|mut solver| solver.sweep_from(&mut start.clone(), path, Mode::Corrected))
                    .and_then(elastokin_solver::Sweep::complete)
            };
            let sweep = elastokin_sweep(&start, false).map_err(|e| format!("elastokin, {steps} steps: {e}"))?;
            let newton = s.budget().time(|| elastokin_sweep(&start, false).map(drop)).median;
            let chord = s.budget().time(|| elastokin_sweep(&start, true).map(drop)).median;
            let (elastokin, policy) =
                if chord < newton { (chord, "predictor and chord") } else { (newton, "full Newton") };
            out.figure(&format!("exudyn.{steps}_steps.elastokin_full_newton_s"), newton, "s", Kind::Time);
            out.figure(&format!("exudyn.{steps}_steps.elastokin_chord_s"), chord, "s", Kind::Time);
            let key = format!("exudyn.{steps}_steps");
            out.figure(&format!("{key}.elastokin_s"), elastokin, "s", Kind::Time);
            let mut fastest: Option<(f64, &str)> = None;
            for newton in NEWTON {
                let leading = vec![Cell::count(steps as u64), Cell::text(newton)];
                let run = match run_script(s, &model, &case, steps, newton, &dir) {
                    Ok(run) => run,
                    Err(e) => {
                        table.failed_row(leading, e);
                        continue;
                    }
                };
                let diff = match differences(&case, &sweep, &run) {
                    Ok(d) => d,
                    Err(e) => {
                        table.failed_row(leading, e);
                        continue;
                    }
                };
                let ratio = run.seconds / elastokin;
                let mut row = leading;
                row.extend([
                    Cell::num(run.seconds),
                    Cell::num(elastokin),
                    Cell::num(ratio),
                    Cell::Num(diff[0], 2),
                    Cell::Num(diff[1], 2),
                    Cell::Num(diff[2], 2),
                    Cell::text(run.counts.clone()),
                    Cell::Empty,
                ]);
                table.row(row);
                out.figure(&format!("{key}.exudyn_{}_s", slug(newton)), run.seconds, "s", Kind::Time);
                out.figure(&format!("{key}.ratio_{}", slug(newton)), ratio, "", Kind::Other);
                for ((what, unit), d) in [("wheel_centre", "m"), ("toe", "rad"), ("camber", "rad")].iter().zip(diff) {
                    out.figure(&format!("{key}.{}_max_difference_{what}", slug(newton)), d, unit, Kind::Accuracy);
                }
                if fastest.is_none_or(|(t, _)| run.seconds < t) {
                    fastest = Some((run.seconds, newton));
                }
            }
            if steps == TARGET_STEPS {
                at_target = fastest.map(|(exudyn, newton)| {
                    let text = format!(
                        "{steps} steps, Exudyn {version}: its {newton} Newton {:.3} ms, elastokin's corrected \
                         sweep ({policy}) {:.3} ms (medians, same run)",
                        exudyn * 1e3,
                        elastokin * 1e3
                    );
                    (exudyn / elastokin, text)
                });
            }
        }
        out.notes.push(format!(
            "The Exudyn curve at {TARGET_STEPS} steps is `tests/data/exudyn/macpherson_vertical_force.csv`, made by \
             `{PYTHON} {SCRIPT} MODEL --contact-patch {} {} {} --load-range {} {} --steps {TARGET_STEPS}` with MODEL \
             the output of `elastokin expand examples/generic/macpherson.json`.",
            case.corner.wheel.contact_patch.x,
            case.corner.wheel.contact_patch.y,
            case.corner.wheel.contact_patch.z,
            case.from,
            case.to
        ));
        Ok(at_target)
    })();
    // The temporary files are the section's own; a failure to remove them does not change any figure.
    let _ = std::fs::remove_dir_all(&dir);
    result
}

/// Writes the shipped MacPherson in the general form (what `elastokin expand` prints), which the script reads.
fn write_general_form(file: &SuspensionFile, dir: &Path) -> Result<PathBuf, String> {
    let general = SuspensionFile { suspension: Template::General(Box::new(file.suspension.expand())), ..file.clone() };
    let path = dir.join("macpherson_general.json");
    std::fs::write(&path, general.to_json()).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(path)
}

/// Runs the script for `steps` equal steps with Exudyn's `newton` variant and reads its curve back.
fn run_script(
    s: &Settings,
    model: &Path,
    case: &Case,
    steps: usize,
    newton: &str,
    dir: &Path,
) -> Result<ExudynRun, String> {
    let csv = dir.join(format!("exudyn_{steps}_{newton}.csv"));
    let patch = case.corner.wheel.contact_patch;
    // Numbers in Rust's shortest round-trip form, which Python reads back to the same doubles.
    let output = Command::new(PYTHON)
        .arg(models::root().join(SCRIPT))
        .arg(model)
        .arg("--contact-patch")
        .args([patch.x, patch.y, patch.z].map(|v| v.to_string()))
        .arg("--load-range")
        .args([case.from, case.to].map(|v| v.to_string()))
        .args(["--steps", &steps.to_string(), "--repeat", &s.budget().min_reps.to_string(), "--newton", newton])
        .arg("--csv")
        .arg(&csv)
        .output()
        .map_err(|e| format!("{PYTHON} {SCRIPT} could not be started: {e}"))?;
    if !output.status.success() {
        let stderr = String::from_utf8_lossy(&output.stderr);
        let last = stderr.lines().rev().find(|l| !l.trim().is_empty()).unwrap_or("no message");
        return Err(format!("{SCRIPT} failed: {last}"));
    }
    let text = std::fs::read_to_string(&csv).map_err(|e| format!("{}: {e}", csv.display()))?;
    parse_curve(&text)
}

/// The script's CSV: `#` comment lines (one with the Newton counts), a header, then load, wheel centre
/// x, y, z, toe, camber and the median `SolveStatic` time on every row.
fn parse_curve(text: &str) -> Result<ExudynRun, String> {
    // "# SolveStatic of N load steps, full Newton: I iterations, J Jacobians; …": the part after the colon.
    let counts = text
        .lines()
        .find_map(|l| l.strip_prefix("# SolveStatic of "))
        .and_then(|l| l.split(';').next())
        .and_then(|l| l.split_once(": "))
        .map_or(String::new(), |(_, counts)| counts.trim().to_string());
    let mut rows = Vec::new();
    let mut seconds = None;
    for line in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
        let values: Vec<f64> = line
            .split(',')
            .map(|v| v.trim().parse::<f64>().map_err(|e| format!("the script's CSV: '{v}': {e}")))
            .collect::<Result<_, _>>()?;
        let [load, x, y, z, toe, camber, time] = values[..] else {
            return Err(format!("the script's CSV: {} values in a row, 7 expected", values.len()));
        };
        rows.push([load, x, y, z, toe, camber]);
        seconds = Some(time);
    }
    let seconds = seconds.ok_or("the script's CSV has no rows")?;
    Ok(ExudynRun { rows, seconds, counts })
}

/// The largest differences over the sweep between elastokin's steps and Exudyn's rows: wheel centre (m),
/// toe and camber (rad). Refuses curves whose steps are not at the same loads.
fn differences(case: &Case, sweep: &elastokin_solver::Sweep, run: &ExudynRun) -> Result<[f64; 3], String> {
    if sweep.steps.len() != run.rows.len() {
        return Err(format!("Exudyn has {} rows, elastokin {} steps", run.rows.len(), sweep.steps.len()));
    }
    let mut max = [0.0f64; 3];
    for (step, row) in sweep.steps.iter().zip(&run.rows) {
        if (step.t - row[0]).abs() > 1e-9 * step.t.abs().max(1.0) {
            return Err(format!("Exudyn's step at {} N is elastokin's at {} N", row[0], step.t));
        }
        let a = case.corner.wheel.attitude(&step.poses);
        let centre = (a.wheel_centre - elastokin_core::Vec3::new(row[1], row[2], row[3])).norm();
        for (m, d) in max.iter_mut().zip([centre, (a.toe - row[4]).abs(), (a.camber - row[5]).abs()]) {
            *m = m.max(d);
        }
    }
    Ok(max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scripts_curve_is_read_with_its_counts_and_time() {
        let text = "# Exudyn 1.13.6, Python 3.11.7, 2026-11-23\n# command: python3 …\n\
                    # SolveStatic of 2 load steps, full Newton: 9 iterations, 9 Jacobians; 3 runs (s): 0.1 0.2 0.3\n\
                    load_n,wheel_centre_x_m,wheel_centre_y_m,wheel_centre_z_m,toe_rad,camber_rad,solve_static_s\n\
                    1.0,2.0,3.0,4.0,0.5,0.25,0.2\n2.0,2.0,3.0,4.5,0.25,0.125,0.2\n";
        let run = parse_curve(text).unwrap();
        assert_eq!(run.rows.len(), 2);
        assert_eq!(run.rows[1], [2.0, 2.0, 3.0, 4.5, 0.25, 0.125]);
        assert_eq!(run.seconds, 0.2);
        assert_eq!(run.counts, "9 iterations, 9 Jacobians");
        assert!(parse_curve("load_n\n1,2\n").is_err());
        assert!(parse_curve("load_n,a\n").is_err());
    }
}
