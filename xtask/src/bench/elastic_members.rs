//! Elastic members: the twist-beam axle's parallel travel (161 points) per point against the MacPherson
//! corner's, as shipped (its cross member in six segments) and with the cross member in twenty. A twist
//! beam's corners share the cross member, so its smallest model is the axle, both corners solved at once:
//! a corner's share of a row is half the axle's, and that is what the targets compare.

use super::models;
use super::report::{Cell, Judge, Kind, SectionOutput, Table, Target};
use super::Settings;
use elastokin_suspensions::kc::{self, Analysis};
use elastokin_suspensions::SuspensionFile;

/// Rows of each parallel travel (±80 mm in 160 steps).
const POINTS: usize = 161;
/// The twist beam's time per corner and point over the MacPherson's, at most.
const TWIST_BEAM_RATIO: f64 = 2.0;
/// The same with a 20-segment cross member, at most.
const SEGMENTS_RATIO: f64 = 5.0;

/// The shipped twist beam with its cross member in `segments`.
fn twist_beam(segments: usize) -> Result<SuspensionFile, String> {
    let mut doc = models::shipped_document("twist_beam")?;
    let n = doc
        .pointer_mut("/suspension/general/axle/beams/0/segments")
        .ok_or("examples/twist_beam.json: no cross member")?;
    *n = serde_json::json!(segments);
    SuspensionFile::from_json(&doc.to_string(), "examples/twist_beam.json").map_err(|e| e.to_string())
}

/// Median time of one parallel travel of `file`, per row (s).
fn per_point(s: &Settings, file: &SuspensionFile) -> Result<f64, String> {
    let settings = kc::Settings { steps: POINTS - 1, ..kc::Settings::default() };
    let once = || kc::run(Analysis::ParallelTravel, file, &settings).map(|r| r.table.rows.len());
    let rows = once().map_err(|e| e.to_string())?;
    if rows != POINTS {
        return Err(format!("{rows} rows, not {POINTS}"));
    }
    Ok(s.budget().time(once).median / POINTS as f64)
}

/// Runs the section.
pub fn run(s: &Settings) -> SectionOutput {
    let mut out = SectionOutput {
        title: "Elastic members".into(),
        intro: "Parallel travel over ±80 mm in 161 rows (corrected mode, every row's error estimate), median wall \
                time per row: the MacPherson corner (`examples/generic/macpherson.json`), the twist-beam axle \
                (`examples/twist_beam.json`: both sides, which share the cross member, with pivot bushings and \
                four arm beams, the cross member in six segments) and the same with the cross member in twenty."
            .into(),
        ..SectionOutput::default()
    };
    let mut table = Table::new(
        "Time per row",
        "elastic_members.csv",
        &["model", "bodies", "per row (µs)", "per corner and row (µs)", "ratio per corner"],
    );
    let macpherson = models::shipped("generic/macpherson").and_then(|f| per_point(s, &f));
    let cases = [("twist beam, 6 segments", 6, TWIST_BEAM_RATIO), ("twist beam, 20 segments", 20, SEGMENTS_RATIO)];
    if let Ok(m) = &macpherson {
        table.row(vec![
            Cell::text("MacPherson"),
            Cell::text("3"),
            Cell::num(m * 1e6),
            Cell::num(m * 1e6),
            Cell::num(1.0),
        ]);
        out.figure("elastic_members.macpherson_per_row_s", *m, "s", Kind::Time);
    }
    for (name, segments, limit) in cases {
        let measured = twist_beam(segments).and_then(|f| {
            let bodies =
                elastokin_suspensions::Axle::build(&f.suspension, elastokin_suspensions::AxleRig::ParallelTravel)
                    .map(|a| a.model.bodies().len())
                    .map_err(|e| e.to_string())?;
            Ok((bodies, per_point(s, &f)?))
        });
        let ratio = match (&measured, &macpherson) {
            (Ok((bodies, t)), Ok(m)) => {
                let per_corner = t / 2.0;
                table.row(vec![
                    Cell::text(name),
                    Cell::text(bodies.to_string()),
                    Cell::num(t * 1e6),
                    Cell::num(per_corner * 1e6),
                    Cell::num(per_corner / m),
                ]);
                out.figure(&format!("elastic_members.twist_beam_{segments}_per_row_s"), *t, "s", Kind::Time);
                Ok(per_corner / m)
            }
            (Err(e), _) | (_, Err(e)) => {
                table.failed_row(vec![Cell::text(name)], e.clone());
                Err(e.clone())
            }
        };
        out.targets.push(Target {
            goal: format!("{name}: parallel travel per corner and row against the MacPherson's"),
            measured: ratio,
            limit,
            unit: "×".into(),
            judge: Judge::AtMost,
            detail: "161 rows, ±80 mm, corrected mode; the axle's row (both corners) halved".into(),
        });
    }
    out.tables.push(table);
    out
}
