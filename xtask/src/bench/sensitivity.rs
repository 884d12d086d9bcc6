//! The cost of sensitivities: the K&C suite of the shipped MacPherson with the derivatives of every
//! figure and every table cell with respect to all 24 hardpoint coordinates (`design::suite_sensitivity`),
//! against the suite alone and against the 48 re-run suites a central-difference gradient takes; and the
//! same for parallel travel alone.

use super::models;
use super::report::{Cell, Judge, Kind, SectionOutput, Table, Target};
use super::Settings;
use elastokin_suspensions::design::{hardpoint_pointers, suite_sensitivity, Parameters};
use elastokin_suspensions::kc::{self, Analysis};

/// Runs the section.
pub fn run(s: &Settings) -> SectionOutput {
    let mut out = SectionOutput {
        title: "Sensitivities".into(),
        intro: "The K&C suite of the shipped MacPherson (every analysis it runs, default ranges, 32 corrected \
                steps): alone (the model read, every analysis walked with its error estimate); with the \
                derivatives of every figure and cell with respect to its 24 hardpoint coordinates (the suite's \
                solves recorded with the factors of the tangent at each equilibrium, then replayed on each moved \
                model: one Newton iteration per equilibrium and move solved with those factors, and the path \
                tangents and compliances read there solved with them too, refined once against the moved \
                tangent, four moves per parameter); the same for the figures alone, the target's measure (each row read for the \
                figures: no component forces in the load sweeps, the roll centre at design only; and moved \
                only where the figures read it: the design equilibrium, a load sweep's last row, the \
                steering's rows of full steer and of the largest Ackermann error); and the 48 re-run \
                suites of a central-difference gradient. Then parallel travel alone the same ways. \
                Medians of repeated runs, one thread (the parameters' replays also run in parallel: the \
                2-thread rows)."
            .into(),
        ..SectionOutput::default()
    };
    let mut table = Table::new(
        "Sensitivities",
        "sensitivity.csv",
        &["analyses", "what", "parameters", "median time (s)", "time / analyses alone", "status"],
    );
    let parameters = match models::shipped_document("generic/macpherson")
        .and_then(|base| Parameters::new(&base, &hardpoint_pointers(&base)).map_err(|e| e.to_string()))
    {
        Ok(p) => p,
        Err(e) => {
            table.failed_row(Vec::new(), e);
            out.tables.push(table);
            return out;
        }
    };
    let file = match parameters.file() {
        Ok(f) => f,
        Err(e) => {
            table.failed_row(Vec::new(), e);
            out.tables.push(table);
            return out;
        }
    };
    let settings = kc::Settings::default();
    let suite: Vec<Analysis> = kc::planned(&file, &[]).into_iter().flatten().collect();
    let one_thread = rayon::ThreadPoolBuilder::new().num_threads(1).build();
    let n = parameters.len();
    for (name, which) in [("suite", suite.clone()), ("parallel travel", vec![Analysis::ParallelTravel])] {
        let run = |p: &Parameters, k: Option<(usize, f64)>| -> Result<usize, String> {
            let file = match k {
                Some((k, d)) => p.file_moved(k, d),
                None => p.file(),
            }
            .map_err(|e| e.to_string())?;
            // Built once for all the analyses, as the suite builds them.
            let models = kc::Models::new(&file);
            let mut figures = 0;
            for &a in &which {
                figures += kc::run_on(a, &models, &settings).map_err(|e| e.to_string())?.figures.len();
            }
            Ok(figures)
        };
        let replayed = || suite_sensitivity(&parameters, &which, &settings);
        let figures_alone = kc::Settings { figures_only: true, ..settings };
        let replayed_figures = || suite_sensitivity(&parameters, &which, &figures_alone);
        // The suite alone on one thread too: an analysis that runs parts of itself at once (the wheel
        // envelope's heights) does so only where nothing is taped.
        let (alone, serial, serial_figures) = match &one_thread {
            Ok(pool) => (
                s.budget().time(|| pool.install(|| run(&parameters, None))),
                s.batch_budget().time(|| pool.install(replayed)),
                s.batch_budget().time(|| pool.install(replayed_figures)),
            ),
            Err(e) => {
                table.failed_row(vec![Cell::text(name)], e.to_string());
                continue;
            }
        };
        let parallel = s.batch_budget().time(replayed);
        let differences = s.batch_budget().time(|| {
            (0..n).flat_map(|k| [1.0, -1.0].map(|d| run(&parameters, Some((k, d * 1e-4))))).collect::<Vec<_>>()
        });
        for result in [replayed(), replayed_figures()] {
            match result {
                Err(e) => table.failed_row(vec![Cell::text(name)], e),
                Ok(r) if !r.failed.is_empty() => table.failed_row(vec![Cell::text(name)], format!("{:?}", r.failed)),
                Ok(_) => {}
            }
        }
        let threads = rayon::current_num_threads();
        for (what, count, median) in [
            ("alone".to_string(), 0, alone.median),
            ("with sensitivities, one thread".to_string(), n, serial.median),
            ("with sensitivities of the figures alone, one thread".to_string(), n, serial_figures.median),
            (format!("with sensitivities, {threads} threads"), n, parallel.median),
            (format!("{} re-run (central differences)", 2 * n), n, differences.median),
        ] {
            table.row(vec![
                Cell::text(name),
                Cell::text(&what),
                Cell::count(count as u64),
                Cell::num(median),
                Cell::num(median / alone.median),
                Cell::text("ok"),
            ]);
        }
        let key = name.replace(' ', "_");
        out.figure(&format!("sensitivity.{key}_alone_s"), alone.median, "s", Kind::Time);
        out.figure(&format!("sensitivity.{key}_sensitivities_24_s"), serial.median, "s", Kind::Time);
        out.figure(&format!("sensitivity.{key}_figures_sensitivities_24_s"), serial_figures.median, "s", Kind::Time);
        out.figure(&format!("sensitivity.{key}_differences_48_s"), differences.median, "s", Kind::Time);
        out.targets.push(Target {
            goal: format!(
                "all derivatives of the {name}'s figures to 24 hardpoint coordinates, one thread, time over the \
                 {name} alone"
            ),
            measured: Ok(serial_figures.median / alone.median),
            limit: 3.0,
            unit: "×".into(),
            judge: Judge::AtMost,
            detail: format!(
                "figures alone {:.1} ms, figures and every cell {:.1} ms ({:.1}×; {:.1} ms on {threads} threads), \
                 alone {:.1} ms, central differences {:.1} ms ({:.1}× the replayed of figures and cells)",
                serial_figures.median * 1e3,
                serial.median * 1e3,
                serial.median / alone.median,
                parallel.median * 1e3,
                alone.median * 1e3,
                differences.median * 1e3,
                differences.median / serial.median
            ),
        });
        out.targets.push(Target {
            goal: format!(
                "all derivatives of the {name}'s figures and table cells to 24 hardpoint coordinates, one thread, \
                 time over the {name} alone"
            ),
            measured: Ok(serial.median / alone.median),
            limit: 3.0,
            unit: "×".into(),
            judge: Judge::AtMost,
            detail: format!("figures and every cell {:.1} ms, alone {:.1} ms", serial.median * 1e3, alone.median * 1e3),
        });
    }
    out.tables.push(table);
    out
}
