//! The cost of exact sensitivities: the parallel travel of the shipped MacPherson (±80 mm, 32 corrected
//! steps) with the derivatives of every row and of the bump steer and camber gain with respect to all 24
//! hardpoint coordinates (`design::parallel_travel_sensitivity`), against the same travel alone and against
//! the 48 re-solved travels a central-difference gradient takes.

use super::models;
use super::report::{Cell, Judge, Kind, SectionOutput, Table, Target};
use super::Settings;
use elastokin_solver::Mode;
use elastokin_suspensions::analysis::parallel_wheel_travel;
use elastokin_suspensions::design::{hardpoint_pointers, parallel_travel_sensitivity, Parameters};
use elastokin_suspensions::{Rig, Side};

const RANGE: (f64, f64) = (-0.08, 0.08);
const STEPS: usize = 32;

/// Runs the section.
pub fn run(s: &Settings) -> SectionOutput {
    let mut out = SectionOutput {
        title: "Sensitivities".into(),
        intro: format!(
            "Parallel travel of the shipped MacPherson, {:+.0}..{:+.0} mm in {STEPS} corrected steps: alone (the \
             model read and built, the travel walked), with the exact derivatives of every row and of the bump \
             steer and camber gain with respect to its 24 hardpoint coordinates (one back-substitution per \
             parameter and row, each parameter's model read four times for the residual's differences), and the \
             48 re-solved travels of a central-difference gradient. Medians of repeated runs, one thread.",
            RANGE.0 * 1e3,
            RANGE.1 * 1e3
        ),
        ..SectionOutput::default()
    };
    let mut table = Table::new(
        "Sensitivities",
        "sensitivity.csv",
        &["what", "parameters", "median time (s)", "time / travel alone", "status"],
    );
    let base = match models::shipped_document("macpherson") {
        Ok(v) => v,
        Err(e) => {
            table.failed_row(Vec::new(), e);
            out.tables.push(table);
            return out;
        }
    };
    let pointers = hardpoint_pointers(&base);
    let parameters = match Parameters::new(&base, &pointers) {
        Ok(p) => p,
        Err(e) => {
            table.failed_row(Vec::new(), e);
            out.tables.push(table);
            return out;
        }
    };
    let travel = |p: &Parameters, k: Option<(usize, f64)>| -> Result<f64, String> {
        let file = match k {
            Some((k, d)) => p.file_moved(k, d)?,
            None => p.file()?,
        };
        let corner = file.suspension.build(Side::Left, Rig::WheelTravel).map_err(|e| e.to_string())?;
        let rows =
            parallel_wheel_travel(&corner, RANGE.0, RANGE.1, STEPS, Mode::Corrected).map_err(|e| e.to_string())?;
        Ok(rows[STEPS / 2].attitude.toe)
    };
    let alone = s.budget().time(|| travel(&parameters, None));
    let exact = s.budget().time(|| parallel_travel_sensitivity(&parameters, RANGE.0, RANGE.1, STEPS));
    let differences = s.batch_budget().time(|| {
        (0..parameters.len())
            .flat_map(|k| [1.0, -1.0].map(|d| travel(&parameters, Some((k, d * 1e-5)))))
            .collect::<Vec<_>>()
    });
    if let Err(e) = parallel_travel_sensitivity(&parameters, RANGE.0, RANGE.1, STEPS) {
        table.failed_row(vec![Cell::text("exact sensitivities")], e);
    }
    let n = parameters.len() as u64;
    for (what, count, median) in [
        ("travel alone", 0, alone.median),
        ("travel with exact sensitivities", n, exact.median),
        ("48 re-solved travels (central differences)", n, differences.median),
    ] {
        table.row(vec![
            Cell::text(what),
            Cell::count(count),
            Cell::num(median),
            Cell::num(median / alone.median),
            Cell::text("ok"),
        ]);
    }
    out.figure("sensitivity.travel_alone_s", alone.median, "s", Kind::Time);
    out.figure("sensitivity.exact_24_s", exact.median, "s", Kind::Time);
    out.figure("sensitivity.differences_48_s", differences.median, "s", Kind::Time);
    out.targets.push(Target {
        goal: "all derivatives of parallel travel's rows and headline figures to 24 hardpoint coordinates, time \
               over the travel alone"
            .into(),
        measured: Ok(exact.median / alone.median),
        limit: 3.0,
        unit: "×".into(),
        judge: Judge::AtMost,
        detail: format!(
            "exact {:.2} ms, travel alone {:.2} ms, central differences {:.2} ms ({:.1}× the exact)",
            exact.median * 1e3,
            alone.median * 1e3,
            differences.median * 1e3,
            differences.median / exact.median
        ),
    });
    out.tables.push(table);
    out
}
