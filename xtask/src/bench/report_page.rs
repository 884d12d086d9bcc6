//! The report with its geometry views: the time to write `report.html` as `elastokin run` does (the model
//! read, every analysis of the suite with the parts' motion, the plots, the projections and the 3D view's
//! data) and the size of the page, for every shipped example.

use super::report::{Cell, Judge, Kind, SectionOutput, Table, Target};
use super::Settings;
use crate::browser::report_page;

/// The report of the MacPherson with its 3D view is written in at most this (s).
const MACPHERSON_LIMIT_S: f64 = 0.5;
/// No report with its 3D view is larger than this (bytes).
const SIZE_LIMIT: f64 = 2e6;
/// Five models compared in at most this (s).
const COMPARE_LIMIT_S: f64 = 1.0;

/// Runs the section.
pub fn run(s: &Settings) -> SectionOutput {
    let mut out = SectionOutput {
        title: "Report with the geometry views".into(),
        intro: "Each shipped example's `report.html` as `elastokin run` writes it: the model read, every analysis \
                of the suite with the parts' poses at every row, the plots, the three projections and the 3D \
                view's data and script, the page written to disk. Median wall time of repeated runs, and the \
                page's size. Then five models compared as `elastokin compare` compares them."
            .into(),
        ..SectionOutput::default()
    };
    let mut table = Table::new("Report pages", "report_page.csv", &["model", "median time (s)", "size (kB)", "status"]);
    let root = crate::workspace_root();
    let dir = root.join("target/bench-report-page");
    let _ = std::fs::create_dir_all(&dir);
    let mut largest: Result<f64, String> = Ok(0.0);
    let mut macpherson: Result<f64, String> = Err("not run".into());
    for stem in [
        "macpherson",
        "double_wishbone",
        "five_link",
        "double_wishbone_axle",
        "four_link_axle",
        "twist_beam",
        "pushrod_rocker",
    ] {
        let path = format!("examples/{stem}.json");
        let page = dir.join(format!("{stem}.html"));
        let write = || -> Result<usize, String> {
            let html = report_page(&root, &path)?;
            std::fs::write(&page, &html).map_err(|e| format!("{}: {e}", page.display()))?;
            Ok(html.len())
        };
        let size = match write() {
            Ok(size) => size,
            Err(e) => {
                table.failed_row(vec![Cell::text(stem)], e.clone());
                largest = Err(e);
                continue;
            }
        };
        let timing = s.batch_budget().time(write);
        table.row(vec![Cell::text(stem), Cell::num(timing.median), Cell::num(size as f64 / 1e3), Cell::text("ok")]);
        out.figure(&format!("report_page.{stem}_s"), timing.median, "s", Kind::Time);
        out.figure(&format!("report_page.{stem}_bytes"), size as f64, "bytes", Kind::Memory);
        if let Ok(l) = &mut largest {
            *l = l.max(size as f64);
        }
        if stem == "macpherson" {
            macpherson = Ok(timing.median);
        }
    }
    let compared = compare_five(s, &dir);
    if let Ok(t) = &compared {
        table.row(vec![Cell::text("compare: 5 MacPherson variants"), Cell::num(*t), Cell::text(""), Cell::text("ok")]);
        out.figure("report_page.compare_5_s", *t, "s", Kind::Time);
    }
    out.targets.push(Target {
        goal: "five models compared: each suite run and the comparison's report written".into(),
        measured: compared,
        limit: COMPARE_LIMIT_S,
        unit: "s".into(),
        judge: Judge::AtMost,
        detail: "the MacPherson's first five variants of examples/generic/macpherson_variants.txt, every analysis"
            .into(),
    });
    out.targets.push(Target {
        goal: "the MacPherson's report with every analysis and the 3D view written".into(),
        measured: macpherson,
        limit: MACPHERSON_LIMIT_S,
        unit: "s".into(),
        judge: Judge::AtMost,
        detail: "model read, suite with motion, plots, views, page written".into(),
    });
    out.targets.push(Target {
        goal: "the largest shipped example's report with the 3D view".into(),
        measured: largest.map(|b| b / 1e6),
        limit: SIZE_LIMIT / 1e6,
        unit: "MB".into(),
        judge: Judge::AtMost,
        detail: "of the seven shipped examples".into(),
    });
    out.tables.push(table);
    out
}

/// The median time to compare the shipped MacPherson's first five variants (`examples/generic/macpherson_variants.txt`)
/// as `elastokin compare` does: each model's suite with the parts' motion, the comparison and its report
/// written.
fn compare_five(s: &Settings, dir: &std::path::Path) -> Result<f64, String> {
    use elastokin::suspensions::compare::{compare, Design};
    use elastokin::suspensions::kc;
    use elastokin::suspensions::study::batch::{apply, base_document, parse_variants};
    let root = crate::workspace_root();
    let read = |p: &str| std::fs::read_to_string(root.join(p)).map_err(|e| format!("{p}: {e}"));
    let base = base_document(&read("examples/generic/macpherson.json")?, "examples/generic/macpherson.json")
        .map_err(|e| e.to_string())?;
    let variants =
        parse_variants(&read("examples/generic/macpherson_variants.txt")?, "examples/generic/macpherson_variants.txt")
            .map_err(|e| e.to_string())?;
    let files =
        variants.iter().take(5).map(|v| apply(&base, v)).collect::<Result<Vec<_>, _>>().map_err(|e| e.to_string())?;
    if files.len() < 5 {
        return Err("fewer than five variants".into());
    }
    let settings = kc::Settings { motion: true, ..kc::Settings::default() };
    let once = || -> Result<usize, String> {
        let designs: Vec<Design> =
            files.iter().map(|f| Design::model(f, kc::run_suite(f, &[], &settings, |_| {}))).collect();
        let comparison = compare(&designs).map_err(|e| e.to_string())?;
        let models = comparison.models(&designs);
        let html = elastokin::html::compare_html(&comparison, &models, &serde_json::json!({}), elastokin::plot::svg);
        std::fs::write(dir.join("compare.html"), &html).map_err(|e| e.to_string())?;
        Ok(html.len())
    };
    once()?;
    Ok(s.batch_budget().time(once).median)
}
