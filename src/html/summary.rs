//! The K&C report's first section, the answer: what the run found in a sentence (targets met, warnings,
//! estimates over the tolerance), the targets judged when a TARGETS file was given (`run --targets`), and
//! every analysis's headline figures side by side, each linked to its section.

use super::figures::estimate_words;
use crate::markup::{attr, text};
use crate::suspensions::design::judge::{by_target, judged_whole, ConstraintCheck, TargetPoint};
use crate::suspensions::design::targets::{Aim, Target};
use crate::suspensions::kc::{plain, significant, AnalysisReport, KcReport};
use std::fmt::Write;

/// A run's targets judged: each target's points and each packaging constraint.
#[derive(Debug, Clone, Copy)]
pub struct Judged<'a> {
    /// Every point of every target, in the TARGETS file's order.
    pub points: &'a [TargetPoint<'a>],
    /// Every packaging constraint.
    pub constraints: &'a [ConstraintCheck<'a>],
}

/// The section "Summary" of `report`, with the targets `judged` when given.
pub(super) fn write_summary(out: &mut String, report: &KcReport, judged: Option<Judged>) -> std::fmt::Result {
    writeln!(out, "<section id=\"summary\">")?;
    writeln!(out, "<h2>Summary</h2>")?;
    write_verdict(out, report, judged)?;
    if let Some(judged) = judged {
        write_targets(out, judged)?;
    }
    writeln!(out, "<div class=\"summary-grid\">")?;
    for a in &report.analyses {
        write_card(out, a, report.settings.tolerance.relative, judged)?;
    }
    writeln!(out, "</div>")?;
    writeln!(out, "</section>")
}

/// The run's answer in a sentence: the targets met, the warnings, the estimates over the tolerance.
fn write_verdict(out: &mut String, report: &KcReport, judged: Option<Judged>) -> std::fmt::Result {
    let mut said = Vec::new();
    if let Some(j) = judged {
        let missed = j.points.iter().filter(|p| !p.met()).count() + j.constraints.iter().filter(|c| !c.met()).count();
        let all = j.points.len() + j.constraints.len();
        said.push(if missed == 0 {
            format!("<span class=\"ok\">every target met</span> ({all} points and constraints)")
        } else {
            format!("<span class=\"bad\">{missed} of {all} target points and constraints not met</span>")
        });
    }
    let warnings = report.all_warnings().count();
    said.push(match warnings {
        0 => "<span class=\"ok\">no warnings</span>".to_string(),
        1 => "<a href=\"#warnings\" class=\"bad\">1 warning</a>".to_string(),
        n => format!("<a href=\"#warnings\" class=\"bad\">{n} warnings</a>"),
    });
    let relative = report.settings.tolerance.relative;
    let over: usize =
        report.analyses.iter().map(|a| a.figures.iter().filter(|f| f.estimate_matters(relative)).count()).sum();
    said.push(if over == 0 {
        format!(
            "every figure's error estimate within {} % of it (hover over a figure for its estimate)",
            significant(relative * 100.0, 2)
        )
    } else {
        let figures = if over == 1 { "figure" } else { "figures" };
        format!("<span class=\"bad\">{over} {figures} with an error estimate over the tolerance</span>")
    });
    if !report.failed.is_empty() {
        said.push(format!("<a href=\"#failed\" class=\"bad\">{} analyses failed</a>", report.failed.len()));
    }
    writeln!(out, "<p class=\"verdict\">{}.</p>", said.join("; "))
}

/// What target `t` aims at, in the table's words: the analysis and the figure or column.
fn what_aimed(t: &Target) -> String {
    match &t.aim {
        Aim::Figure { key, .. } => format!("{} {key}", t.analysis.name()),
        Aim::Curve { column, .. } => format!("{} {column}", t.analysis.name()),
    }
}

/// The cell that says whether a target or constraint is met.
fn met_cell(met: bool) -> &'static str {
    if met {
        "<td class=\"ok\">met</td>"
    } else {
        "<td class=\"bad\">not met</td>"
    }
}

/// The table of the targets judged: per point, the target, where, the aim with its tolerance, what the run
/// reached, and met or not; then the packaging constraints.
fn write_targets(out: &mut String, judged: Judged) -> std::fmt::Result {
    writeln!(out, "<table class=\"targets\">")?;
    writeln!(out, "<thead><tr><th>target</th><th>at</th><th>aim</th><th>reached</th><th></th></tr></thead><tbody>")?;
    for readings in by_target(judged.points) {
        // A target judged whole is one row: its measure in words.
        if let Some(words) = judged_whole(readings) {
            let t = readings[0].target;
            let mark = met_cell(readings[0].met());
            let span = match (readings.first().and_then(|p| p.at), readings.last().and_then(|p| p.at)) {
                (Some(a), Some(b)) => format!("{} to {}", plain(a), plain(b)),
                _ => String::new(),
            };
            writeln!(
                out,
                "<tr><td title=\"{}\">{}</td><td>{}</td><td colspan=\"2\">{}</td>{mark}</tr>",
                attr(&t.label),
                text(&what_aimed(t)),
                text(&span),
                text(&words)
            )?;
            continue;
        }
        for p in readings {
            let t = p.target;
            let at = p.at.map_or(String::new(), plain);
            let aim = format!("{} ± {}", significant(p.aim, 4), significant(t.tolerance, 2));
            let (reached, mark) = match &p.reached {
                Ok(r) => (significant(*r, 4), met_cell(p.met()).to_string()),
                Err(why) => (String::new(), format!("<td class=\"bad\">not judged: {}</td>", text(why))),
            };
            writeln!(
                out,
                "<tr><td title=\"{}\">{}</td><td>{}</td><td>{}</td><td>{}</td>{mark}</tr>",
                attr(&t.label),
                text(&what_aimed(t)),
                text(&at),
                text(&aim),
                text(&reached)
            )?;
        }
    }
    for c in judged.constraints {
        let (reached, aim, mark) = match &c.reached {
            Ok((v, min, max)) => {
                let mm = |v: f64| if v.is_finite() { significant(v * 1e3, 4) } else { "∞".into() };
                let mark = met_cell(c.met());
                (format!("{} mm", mm(*v)), format!("{} to {} mm", mm(*min), mm(*max)), mark.to_string())
            }
            Err(why) => (String::new(), String::new(), format!("<td class=\"bad\">not judged: {}</td>", text(why))),
        };
        writeln!(
            out,
            "<tr><td>{}</td><td></td><td>{}</td><td>{}</td>{mark}</tr>",
            text(&c.constraint.said()),
            text(&aim),
            text(&reached)
        )?;
    }
    writeln!(out, "</tbody></table>")
}

/// One analysis's card: its name linked to its section, and its headline figures with their values and
/// units, each figure a target names marked met or not.
fn write_card(out: &mut String, a: &AnalysisReport, relative: f64, judged: Option<Judged>) -> std::fmt::Result {
    let name = a.analysis.name();
    writeln!(out, "<div class=\"card\">")?;
    writeln!(out, "<h3><a href=\"#{}\">{}</a></h3>", attr(name), text(name))?;
    if a.figures.is_empty() {
        writeln!(out, "<p class=\"note\">no headline figures; its curves are in its section</p>")?;
        return writeln!(out, "</div>");
    }
    writeln!(out, "<table class=\"figures compact\"><tbody>")?;
    for f in &a.figures {
        let w = f.written(a.units);
        let targeted: Vec<&TargetPoint> = judged
            .into_iter()
            .flat_map(|j| j.points)
            .filter(|p| {
                p.target.analysis == a.analysis && matches!(&p.target.aim, Aim::Figure { key, .. } if *key == f.key)
            })
            .collect();
        // What a figure's row adds, on a line of its own beneath it: its target and whether it is met, and
        // an estimate that matters.
        let met = (!targeted.is_empty()).then(|| targeted.iter().all(|p| p.met()));
        let class = match met {
            Some(true) => " class=\"met\"",
            Some(false) => " class=\"missed\"",
            None => "",
        };
        let estimate = estimate_words(f, a.units).unwrap_or_default();
        let mut aside = Vec::new();
        if let Some(met) = met {
            let aims: Vec<String> = targeted
                .iter()
                .map(|p| format!("{} ± {}", significant(p.aim, 4), significant(p.target.tolerance, 2)))
                .collect();
            aside.push(text(&format!("target {}: {}", aims.join(", "), if met { "met" } else { "not met" })));
        }
        if f.estimate_matters(relative) {
            aside.push(format!("<span class=\"over\">error estimate {}</span>", text(&estimate)));
        }
        let aside = if aside.is_empty() {
            String::new()
        } else {
            format!("<tr{class}><td colspan=\"3\" class=\"aim\">{}</td></tr>", aside.join("; "))
        };
        let unit = if w.unit == "-" { "" } else { w.unit };
        match w.value {
            Some(v) => writeln!(
                out,
                "<tr{class}><td>{}</td><td class=\"value\" title=\"{}\">{}</td><td>{}</td></tr>{aside}",
                text(&f.label),
                attr(&estimate),
                w.number(v),
                text(unit)
            )?,
            None => writeln!(
                out,
                "<tr{class}><td>{}</td><td class=\"value\" title=\"{}\">n/a</td><td>{}</td></tr>{aside}",
                text(&f.label),
                attr(f.reason.as_deref().unwrap_or("")),
                text(unit)
            )?,
        }
    }
    writeln!(out, "</tbody></table>")?;
    writeln!(out, "</div>")
}
