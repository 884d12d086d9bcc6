//! The HTML K&C report: well-formed, self-contained, and showing what the report holds — every analysis,
//! figure (or its reason), plot, warning, hardpoint and skipped analysis — with nothing non-finite.

use elastokin::html::{report_html, report_html_with, Extras, Judged, TABLE_ROW_LIMIT};
use elastokin::suspensions::design::judge::judge;
use elastokin::suspensions::design::targets::{read_targets_as, Reading};
use elastokin::suspensions::drawing::Spot;
use elastokin::suspensions::kc::{self, Cell, Chart, Figure, KcReport, Settings, Table, Warning};
use elastokin::suspensions::SuspensionFile;
use serde_json::json;
use std::path::Path;
use std::sync::OnceLock;

fn model() -> SuspensionFile {
    SuspensionFile::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/generic/macpherson.json")).unwrap()
}

/// The whole suite on the MacPherson example, in few steps: run once, shared by the tests.
fn suite() -> &'static KcReport {
    static REPORT: OnceLock<KcReport> = OnceLock::new();
    REPORT.get_or_init(|| {
        kc::run_suite(&model(), &[], &Settings { steps: 8, ..Default::default() }, |_| {}).complete().unwrap()
    })
}

fn provenance() -> serde_json::Value {
    json!({
        "elastokin_version": "0.1.0",
        "model_file": "examples/generic/macpherson.json",
        "model_sha256": "0123abcd",
        "mode": "corrected",
        "steps": 8,
        "tolerance": { "angle_deg": 1e-3, "length_m": 1e-6 },
        "date": "2026-11-22T20:00:00Z"
    })
}

/// A small valid SVG naming the chart and joining the finite points of its left axis's first curve.
fn title_svg(chart: &Chart) -> Result<String, String> {
    let points: Vec<String> = chart
        .left
        .series
        .first()
        .map(|s| s.points.iter().filter(|p| p.0.is_finite() && p.1.is_finite()).map(|p| format!("{},{}", p.0, p.1)))
        .into_iter()
        .flatten()
        .collect();
    Ok(format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 10 10\">\
         <title>{}</title><polyline fill=\"none\" points=\"{}\"/></svg>",
        html_escape::encode_text(&chart.title),
        points.join(" ")
    ))
}

/// Parses `html` as XML (the doctype is HTML's, which an XML parser need not know) and returns the
/// document's element names, in order.
fn element_names(html: &str) -> Vec<String> {
    let body = html.strip_prefix("<!DOCTYPE html>").expect("starts with the HTML doctype");
    let doc = roxmltree::Document::parse(body).unwrap_or_else(|e| panic!("not well-formed: {e}"));
    assert_eq!(doc.root_element().tag_name().name(), "html");
    doc.descendants().filter(|n| n.is_element()).map(|n| n.tag_name().name().to_string()).collect()
}

/// A length error in mm as the accuracy line prints it, for the lengths this suite reaches (its
/// estimates are below 1e-4 mm, printed in scientific notation, or exactly zero).
fn significant_mm(m: f64) -> String {
    let mm = m * 1e3;
    assert!(mm < 1e-4, "a length error of {mm} mm: extend this helper");
    if mm == 0.0 {
        "0".into()
    } else {
        format!("{mm:.1e}")
    }
}

/// The words of `html` that are a non-finite number as Rust or JavaScript would print it.
fn non_finite_words(html: &str) -> Vec<String> {
    html.split(|c: char| !c.is_ascii_alphanumeric())
        .filter(|w| matches!(w.to_ascii_lowercase().as_str(), "nan" | "inf" | "infinity"))
        .map(String::from)
        .collect()
}

#[test]
fn report_is_well_formed_self_contained_and_shows_every_analysis() {
    let report = suite();
    let file = model();
    let html = report_html(report, &file, &provenance(), title_svg);
    let elements = element_names(&html);

    assert!(report.analyses.len() >= 8, "the suite ran {} analyses", report.analyses.len());
    for a in &report.analyses {
        assert!(html.contains(&*html_escape::encode_text(&a.description)), "{} missing", a.description);
        for f in &a.figures {
            assert!(html.contains(&*html_escape::encode_text(&f.label)), "figure {} missing", f.label);
        }
        for f in &a.figures {
            // Each figure's row: value to its decimals, unit, and its error estimate or its reason.
            let w = f.written(a.units);
            let unit = html_escape::encode_text(w.unit);
            match w.value {
                Some(v) => {
                    let mut value = format!("{:.*}", w.decimals, v);
                    if value.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
                        value = value.trim_start_matches('-').to_string(); // a rounded zero has no sign
                    }
                    // The estimate written out where it matters, else on hover beside "within".
                    let relative = report.settings.tolerance.relative;
                    let error = match f.error {
                        Some(_) if f.estimate_matters(relative) => "<td class=\"error-estimate over\">± ",
                        Some(_) => "<td class=\"error-estimate\" title=\"± ",
                        None => "<td class=\"error-estimate over\">not estimated",
                    };
                    let row = format!("<td class=\"value\">{value}</td><td>{unit}</td>{error}");
                    assert!(html.contains(&row), "{}: {row}", f.label);
                }
                None => assert!(html.contains(&*html_escape::encode_text(f.reason.as_deref().unwrap()))),
            }
        }
        let verdict = if a.accuracy.within_tolerance { "within tolerance" } else { "over tolerance" };
        let accuracy = format!("lengths {} mm", significant_mm(a.accuracy.length_error_m));
        assert!(html.contains(verdict) && html.contains(&accuracy), "{}: {accuracy}", a.analysis.name());
        // The table and its size are in the collapsible part.
        assert!(html.contains(&format!("<code>{}.csv</code>, {} rows", a.table.name, a.table.rows.len())));
    }
    let json: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/generic/macpherson.json"))
            .unwrap(),
    )
    .unwrap();
    let hardpoints = json["suspension"]["macpherson"]["hardpoints"].as_object().unwrap();
    assert_eq!(hardpoints.len(), 8);
    for (name, xyz) in hardpoints {
        // Name and the x coordinate in mm, two decimals, in the same row.
        let x_mm = format!("{:.2}", xyz[0].as_f64().unwrap() * 1e3);
        assert!(html.contains(&format!("<tr><td><code>{name}</code></td><td>{x_mm}</td>")), "hardpoint {name} {x_mm}");
    }

    assert_eq!(non_finite_words(&html), Vec::<String>::new());
    for outside in ["src=\"http", "href=\"http", "<script src", "<link", "url(", "@import", "import("] {
        assert!(!html.contains(outside), "the page reaches outside itself: {outside}");
    }
    let charts: usize = report.analyses.iter().map(|a| a.charts.len()).sum();
    assert!(charts >= 8, "{charts} charts");
    assert_eq!(html.matches("<svg").count(), charts);
    assert_eq!(elements.iter().filter(|e| *e == "svg").count(), charts);
    // One script, inline, draws the charts interactively from each chart's data: the chart's own curves,
    // their finite points only.
    assert_eq!(elements.iter().filter(|e| *e == "script").count(), 1);
    let body = html.strip_prefix("<!DOCTYPE html>").unwrap();
    let doc = roxmltree::Document::parse(body).unwrap();
    let figures: Vec<_> = doc.descendants().filter(|n| n.attribute("data-chart").is_some()).collect();
    assert_eq!(figures.len(), charts);
    for (figure, chart) in figures.iter().zip(report.analyses.iter().flat_map(|a| &a.charts)) {
        let data: serde_json::Value = serde_json::from_str(figure.attribute("data-chart").unwrap()).unwrap();
        assert_eq!(data["title"], chart.title.as_str());
        let axes = std::iter::once(&chart.left).chain(chart.right.as_ref());
        for (shown, axis) in data["axes"].as_array().unwrap().iter().zip(axes) {
            assert_eq!(shown["label"], axis.label.as_str());
            for (s, series) in shown["series"].as_array().unwrap().iter().zip(&axis.series) {
                let finite: Vec<&(f64, f64)> =
                    series.points.iter().filter(|p| p.0.is_finite() && p.1.is_finite()).collect();
                let x = s["x"].as_array().unwrap();
                assert_eq!(x.len(), finite.len(), "{}", series.name);
                for (k, p) in finite.iter().enumerate() {
                    assert_eq!(x[k].as_f64(), Some(p.0));
                    assert_eq!(s["y"][k].as_f64(), Some(p.1));
                }
            }
        }
    }
    assert!(elements.iter().filter(|e| *e == "details").count() > report.analyses.len());
    assert!(!html.contains("<?xml"), "the SVG's XML declaration is left out inline");

    for shown in
        ["<dt>model sha256</dt><dd>0123abcd</dd>", "<dd>2026-11-22T20:00:00Z</dd>", "<dt>angle deg</dt><dd>0.001</dd>"]
    {
        assert!(html.contains(shown), "provenance: {shown}");
    }
    assert!(html.contains("no warnings") == (report.all_warnings().count() == 0));
}

#[test]
fn warnings_appear_with_their_code_at_the_top() {
    let mut report = suite().clone();
    report.warnings.push(Warning {
        code: "implausible-spring",
        hardpoints: Vec::new(),
        message: "the spring rate is 3 N/m & low".into(),
    });
    report.analyses[1].warnings.push(Warning {
        code: "error-over-tolerance",
        hardpoints: Vec::new(),
        message: "roll: too coarse".into(),
    });
    let html = report_html(&report, &model(), &provenance(), title_svg);
    element_names(&html);
    let warnings = html.find("<section id=\"warnings\">").unwrap();
    let first_analysis = html.find("<section class=\"analysis\"").unwrap();
    assert!(warnings < first_analysis, "warnings come before the analyses");
    assert!(warnings < html.find("<section id=\"provenance\">").unwrap(), "warnings come first");
    let section = &html[warnings..first_analysis];
    assert!(section.contains("<code>implausible-spring</code>"));
    assert!(section.contains("the spring rate is 3 N/m &amp; low"));
    assert!(section.contains("<code>error-over-tolerance</code>"));
    assert!(section.contains("roll: too coarse"));
    assert!(!section.contains("no warnings"));

    report.warnings.clear();
    for a in &mut report.analyses {
        a.warnings.clear();
    }
    let html = report_html(&report, &model(), &provenance(), title_svg);
    assert!(html.contains("no warnings"));
}

#[test]
fn a_chart_that_cannot_be_drawn_shows_why_and_the_report_goes_on() {
    let report = suite();
    let fails_on_roll = |chart: &Chart| {
        if chart.name.starts_with("roll") {
            Err(format!("no room for {} < here", chart.name))
        } else {
            title_svg(chart)
        }
    };
    let html = report_html(report, &model(), &provenance(), fails_on_roll);
    element_names(&html);
    let roll = report.analysis(kc::Analysis::Roll).unwrap();
    assert!(!roll.charts.is_empty());
    for chart in &roll.charts {
        assert!(html.contains(&format!("no room for {} &lt; here", chart.name)), "{}", chart.name);
    }
    let drawn: usize = report.analyses.iter().flat_map(|a| &a.charts).filter(|c| !c.name.starts_with("roll")).count();
    assert_eq!(html.matches("<svg").count(), drawn);
    let last = report.analyses.last().unwrap();
    assert!(html.contains(&*html_escape::encode_text(&last.description)), "the analyses after the failure are there");
}

#[test]
fn a_figure_without_a_value_shows_its_reason() {
    let mut report = suite().clone();
    let reason = "needs vehicle.wheelbase in the model file";
    report.analyses[0].figures.push(Figure::maybe("anti_dive", "anti-dive", kc::Unit::Percent, 1, None, reason));
    report.analyses[0].figures.push(Figure::new(
        "wheel_rate_x",
        "wheel rate at the stop",
        kc::Unit::NewtonPerMillimetre,
        2,
        f64::NAN,
    ));
    let html = report_html(&report, &model(), &provenance(), title_svg);
    element_names(&html);
    assert!(html.contains(&format!("<td class=\"reason\">n/a — {reason}</td>")), "missing reason");
    assert!(html.contains("n/a — not a finite number here"));
    assert_eq!(non_finite_words(&html), Vec::<String>::new());
}

#[test]
fn long_tables_are_cut_with_a_note_and_text_is_escaped() {
    let mut report = suite().clone();
    report.model = "strut <b>\"A&B\"</b>".into();
    let a = &mut report.analyses[0];
    let rows = 1000;
    a.table = Table {
        name: "long_sweep".into(),
        columns: vec!["travel_m".into(), "toe_deg".into(), "note".into()],
        rows: (0..rows)
            .map(|i| vec![Cell::Number(i as f64 * 1e-4), Cell::from(f64::NAN), Cell::Text(format!("<row {i}>"))])
            .collect(),
    };
    let html = report_html(&report, &model(), &provenance(), title_svg);
    let body = html.strip_prefix("<!DOCTYPE html>").unwrap();
    let doc = roxmltree::Document::parse(body).unwrap();
    let title = doc.descendants().find(|n| n.has_tag_name("title")).unwrap();
    assert_eq!(title.text(), Some("K&C report: strut <b>\"A&B\"</b>"));
    assert!(!html.contains("<b>"));
    assert!(html.contains(&format!("the first {TABLE_ROW_LIMIT} of {rows} rows; every row is in long_sweep.csv")));
    let table = doc
        .descendants()
        .filter(|n| n.has_tag_name("details"))
        .find(|d| d.descendants().any(|n| n.text() == Some("long_sweep.csv")))
        .unwrap();
    let body_rows = table
        .descendants()
        .filter(|n| n.has_tag_name("tbody"))
        .flat_map(|b| b.children())
        .filter(|n| n.has_tag_name("tr"));
    assert_eq!(body_rows.count(), TABLE_ROW_LIMIT);
    assert!(html.contains("<td>&lt;row 399&gt;</td>") && !html.contains("row 400&gt;"));
    assert_eq!(non_finite_words(&html), Vec::<String>::new());
}

#[test]
fn skipped_analyses_are_listed_with_their_reason() {
    let mut report = suite().clone();
    report.analyses.retain(|a| a.analysis != kc::Analysis::StaticLoad);
    report.skipped.push(kc::Skipped {
        analysis: kc::Analysis::StaticLoad,
        reason: "the model file has no \"vehicle\" section with the corner_load to carry".into(),
    });
    let html = report_html(&report, &model(), &serde_json::Value::Null, title_svg);
    element_names(&html);
    assert!(html.contains(
        "<strong>static-load</strong>: the model file has no \"vehicle\" section with the corner_load to carry"
    ));
    assert!(html.contains("no provenance given"));
    // A template has no load case of its own, and this one no packaging: the suite leaves those analyses
    // out, and says so.
    let left_out = [kc::Analysis::ModelLoads, kc::Analysis::WheelEnvelope];
    assert!(suite().skipped.iter().all(|s| left_out.contains(&s.analysis)), "{:?}", suite().skipped);
    let mut everything = suite().clone();
    everything.skipped.clear();
    let all = report_html(&everything, &model(), &provenance(), title_svg);
    assert!(all.contains("none: every analysis asked for was run"));
}

#[test]
fn hardpoints_of_a_double_wishbone_are_listed_in_mm() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/generic/double_wishbone.json");
    let file = SuspensionFile::read(&path).unwrap();
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let hardpoints = json["suspension"]["double_wishbone"]["hardpoints"].as_object().unwrap();
    // No analysis run: the page still stands, with the model and nothing else made up.
    let report = KcReport {
        model: file.name.clone(),
        settings: Settings::default(),
        analyses: vec![],
        skipped: vec![],
        failed: vec![],
        model_check: None,
        warnings: vec![],
    };
    let html = report_html(&report, &file, &provenance(), title_svg);
    element_names(&html);
    assert!(html.contains("(double_wishbone, left corner)"));
    assert!(hardpoints.len() >= 8);
    for (name, xyz) in hardpoints {
        let mm: Vec<String> = (0..3).map(|i| format!("<td>{:.2}</td>", xyz[i].as_f64().unwrap() * 1e3)).collect();
        let row =
            format!("<tr><td><code>{name}</code></td>{}</tr>", mm.concat()).replace("<td>-0.00</td>", "<td>0.00</td>");
        assert!(html.contains(&row), "{row}");
    }
    assert!(!html.contains("<svg") && html.contains("no warnings"));
}

#[test]
fn non_finite_numbers_put_in_the_report_never_reach_the_page() {
    let mut report = suite().clone();
    let a = report.analyses.iter_mut().find(|a| a.wheel_compliance_at_design.is_some()).unwrap();
    a.range = (f64::NAN, f64::INFINITY);
    a.accuracy.angle_error_deg = f64::NAN;
    a.accuracy.length_error_m = f64::INFINITY;
    a.accuracy.force_residual = f64::NEG_INFINITY;
    a.accuracy.constraint_residual = f64::NAN;
    a.wheel_compliance_at_design.as_mut().unwrap()[2][2] = f64::NAN;
    a.table.rows[0][0] = Cell::Number(f64::INFINITY); // past `Cell::from`, which would have made it empty
    a.figures[0].error = Some(f64::NAN);
    a.figures[1].value = Some(f64::INFINITY);
    let html = report_html(&report, &model(), &provenance(), title_svg);
    element_names(&html);
    assert_eq!(non_finite_words(&html), Vec::<String>::new());
    assert!(html.contains("error estimate: angles not estimated, lengths not estimated — "));
    assert!(
        html.contains("force residual not estimated (relative to the force scale), constraint residual not estimated")
    );
}

/// The suite of [`suite`] with the parts' motion, for the geometry views.
fn suite_with_motion() -> &'static KcReport {
    static REPORT: OnceLock<KcReport> = OnceLock::new();
    REPORT.get_or_init(|| {
        let settings = Settings { steps: 8, motion: true, ..Default::default() };
        kc::run_suite(&model(), &[], &settings, |_| {}).complete().unwrap()
    })
}

#[test]
fn geometry_views_are_inline_svg_and_the_3d_view_is_one_script_that_no_name_can_break() {
    let mut report = suite_with_motion().clone();
    // A part name that would close the script element, the CDATA section and open markup if written raw,
    // and a pose that is no number.
    let hostile = "</script>]]><b>&amp;\"";
    for a in &mut report.analyses {
        if let Some(m) = &mut a.motion {
            m.drawing.parts[0].name = hostile.into();
            m.frames[1][0].position.x = f64::NAN;
        }
    }
    let html = report_html(&report, &model(), &provenance(), title_svg);
    let body = html.strip_prefix("<!DOCTYPE html>").unwrap();
    let doc = roxmltree::Document::parse(body).unwrap_or_else(|e| panic!("not well-formed: {e}"));
    assert_eq!(non_finite_words(&html), Vec::<String>::new());
    assert!(!html.contains("<b>"));
    // The three projections, each an inline SVG: the design position's strokes, and the two extremes'
    // (every stroke but the bushings' deflections) ghosted.
    let travel = report.analyses.iter().find(|a| a.analysis == kc::Analysis::ParallelTravel).unwrap();
    let drawing = &travel.motion.as_ref().unwrap().drawing;
    let strokes = drawing.strokes();
    let deflections = strokes.iter().filter(|s| s.pen == elastokin::suspensions::drawing::Pen::Deflection).count();
    for view in ["front", "side", "plan"] {
        let figure = doc.descendants().find(|n| n.attribute("id") == Some(&*format!("view-{view}"))).unwrap();
        let paths = figure.descendants().filter(|n| n.has_tag_name("path")).count();
        assert_eq!(paths, 3 * strokes.len() - 2 * deflections, "{view} view");
        let text: String = figure.descendants().filter_map(|n| n.text()).collect();
        assert!(text.contains("[mm]"), "{view} view is dimensioned in mm");
    }
    // Two scripts of code, inline (the 3D view's, the charts'), and the 3D view's data: nothing loaded from
    // anywhere.
    let scripts: Vec<_> = doc.descendants().filter(|n| n.has_tag_name("script")).collect();
    assert_eq!(scripts.len(), 3);
    assert!(scripts.iter().all(|s| s.attribute("src").is_none()));
    for outside in ["src=\"http", "href=\"http", "<link", "url(", "@import", "import("] {
        assert!(!html.contains(outside), "the page reaches outside itself: {outside}");
    }
    let data: serde_json::Value = serde_json::from_str(scripts[0].text().unwrap()).unwrap();
    let analyses = data["analyses"].as_array().unwrap();
    let with_motion: Vec<_> = report.analyses.iter().filter(|a| a.motion.is_some()).collect();
    assert_eq!(analyses.len(), with_motion.len());
    for (shown, a) in analyses.iter().zip(&with_motion) {
        assert_eq!(shown["name"], a.analysis.name());
        assert_eq!(shown["frames"].as_array().unwrap().len(), a.table.rows.len());
        let d = &data["drawings"][shown["drawing"].as_u64().unwrap() as usize];
        let m = a.motion.as_ref().unwrap();
        assert_eq!(d["strokes"].as_array().unwrap().len(), m.drawing.strokes().len());
        assert_eq!(d["dots"].as_array().unwrap().len(), m.drawing.dots().len());
    }
    // The name came through whole, as data.
    let names: Vec<&str> = data["drawings"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|d| d["strokes"].as_array().unwrap())
        .filter_map(|s| s["name"].as_str())
        .collect();
    assert!(names.contains(&hostile), "{names:?}");
}

/// The frame given for each projection (what `elastokin live`'s page places its hardpoints and arrows by)
/// puts every joint of the drawing where the projection's SVG draws it, to the SVG's tenth of a pixel.
#[test]
fn each_projections_frame_puts_a_point_where_its_svg_draws_it() {
    let report = suite_with_motion();
    let mut svg = String::new();
    elastokin::view::write_projections(&mut svg, report).unwrap();
    let wrapped = format!("<div>{svg}</div>");
    let doc = roxmltree::Document::parse(&wrapped).unwrap();
    let travel = report.analyses.iter().find(|a| a.analysis == kc::Analysis::ParallelTravel).unwrap();
    let motion = travel.motion.as_ref().unwrap();
    let poses = &motion.frames[travel.design_row()];
    let frames = elastokin::view::projection_frames(report);
    assert_eq!(frames.iter().map(|f| f.id.as_str()).collect::<Vec<_>>(), ["view-front", "view-side", "view-plan"]);
    for frame in &frames {
        let figure = doc.descendants().find(|n| n.attribute("id") == Some(&*frame.id)).unwrap();
        let joints: Vec<_> = motion.drawing.dots().into_iter().filter(|d| d.spot == Spot::Joint).collect();
        assert!(joints.len() >= 3, "{joints:?}");
        for dot in joints {
            let p = dot.at.placed(poses);
            let ((a, sa), (b, sb)) = (frame.horizontal, frame.vertical);
            let placed = [frame.origin[0] + frame.scale * sa * p[a], frame.origin[1] - frame.scale * sb * p[b]];
            // Where the SVG draws the joints of that name (a part may have more than one).
            let drawn: Vec<[f64; 2]> = figure
                .descendants()
                .filter(|n| {
                    n.has_tag_name("circle")
                        && n.children().any(|t| t.has_tag_name("title") && t.text() == Some(dot.name.as_str()))
                })
                .map(|n| ["cx", "cy"].map(|a| n.attribute(a).unwrap().parse().unwrap()))
                .collect();
            // The SVG writes a tenth of a pixel: half of it, and the rounding of the sum.
            let on = |d: &[f64; 2]| (0..2).all(|k| (placed[k] - d[k]).abs() <= 0.05 + 1e-9);
            assert!(drawn.iter().any(on), "{} {}: {placed:?}, drawn at {drawn:?}", frame.id, dot.name);
        }
    }
}

/// Each analysis's note says what it walked in words that read: the static load is one equilibrium at the
/// vehicle's corner load ("at 4100", not "4100 to 4100, 1 steps"), a sweep its range and steps.
#[test]
fn each_analysis_says_what_it_walked() {
    let file = SuspensionFile::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/macpherson.json")).unwrap();
    let which = [kc::Analysis::StaticLoad, kc::Analysis::ParallelTravel];
    let report = kc::run_suite(&file, &which, &Settings { steps: 4, ..Default::default() }, |_| {}).complete().unwrap();
    let html = report_html(&report, &file, &provenance(), title_svg);
    // The shipped MacPherson's corner load, as its file gives it.
    assert_eq!(file.vehicle.as_ref().unwrap().corner_load, 4100.0);
    assert!(html.contains("applied at once; at 4100</p>"), "{html}");
    assert!(html.contains("-0.08 to 0.08, 4 steps</p>"), "{html}");
    assert!(!html.contains(" 1 steps"), "{html}");
}

#[test]
fn the_summary_leads_with_every_figure_and_the_targets_judged() {
    let mut report = suite().clone();
    // One figure whose estimate matters: 10 % of its value, over the 0.5 % tolerance on figures.
    let f = &mut report.analyses[0].figures[0];
    f.error = f.value.map(|v| 0.1 * v.abs());
    let matters = f.label.clone();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/generic/macpherson.json");
    let text = std::fs::read_to_string(&path).unwrap();
    let document = elastokin::suspensions::study::batch::base_document(&text, "m.json").unwrap();
    let bump = report.analyses[0].figures.iter().find(|f| f.key == "bump_steer").unwrap();
    let deg_per_m = bump.value.unwrap().to_degrees();
    let targets = json!({ "targets": [
        { "figure": "parallel-travel/bump_steer", "value": deg_per_m, "tolerance": 0.1 },
        { "figure": "parallel-travel/camber_gain", "value": 1e3, "tolerance": 0.1 },
    ]})
    .to_string();
    let targets = read_targets_as(Reading::ToJudge, &targets, "t.json", &document, |_| Err(String::new())).unwrap();
    let (points, constraints) = judge(&report, &document, &targets);
    let extras = Extras { judged: Some(Judged { points: &points, constraints: &constraints }), ..Extras::default() };
    let html = report_html_with(&report, &model(), &provenance(), title_svg, extras);
    element_names(&html);

    let summary = html.find("<section id=\"summary\">").unwrap();
    let warnings = html.find("<section id=\"warnings\">").unwrap();
    let first_analysis = html.find("<section class=\"analysis\"").unwrap();
    assert!(summary < warnings && warnings < first_analysis, "the summary comes first");
    let section = &html[summary..warnings];
    for a in &report.analyses {
        assert!(section.contains(&format!("<a href=\"#{}\">", a.analysis.name())), "{}", a.analysis.name());
        for f in &a.figures {
            let w = f.written(a.units);
            let shown = match w.value {
                Some(v) => w.number(v),
                None => "n/a".into(),
            };
            let label = html_escape::encode_text(&f.label);
            assert!(section.contains(&format!("<td>{label}</td><td class=\"value\" title=")), "{label}");
            assert!(section.contains(&format!("\">{shown}</td>")), "{label}: {shown}");
        }
    }
    // The verdict: one target missed, the estimate that matters counted and shown under its figure.
    assert!(section.contains("1 of 2 target points and constraints not met"), "{section}");
    assert!(section.contains("1 figure with an error estimate over the tolerance"));
    let row = section.find(&*html_escape::encode_text(&matters)).unwrap();
    assert!(section[row..].split("</tr>").nth(1).unwrap().contains("class=\"over\">error estimate ±"));
    assert!(section.contains("<tr class=\"met\"><td>bump steer (toe-in +)</td>"));
    assert!(section.contains("<tr class=\"missed\"><td>camber gain (top out +)</td>"));
    assert_eq!(section.matches("<td class=\"bad\">not met</td>").count(), 1);
    assert_eq!(section.matches("<td class=\"ok\">met</td>").count(), 1);
}

#[test]
fn the_views_draw_the_instant_centres_construction_at_the_row_drawn() {
    let report = suite_with_motion();
    let html = report_html(report, &model(), &provenance(), title_svg);
    let body = html.strip_prefix("<!DOCTYPE html>").unwrap();
    let doc = roxmltree::Document::parse(body).unwrap();
    let number = |n: &roxmltree::Node, a: &str| n.attribute(a).unwrap().parse::<f64>().unwrap();
    let view = |id: &str| doc.descendants().find(|n| n.attribute("id") == Some(id)).unwrap();
    let construction = |figure: roxmltree::Node<'_, '_>| {
        let g = figure.descendants().find(|n| n.attribute("class") == Some("construction")).expect("a construction");
        let lines: Vec<[f64; 4]> = g
            .descendants()
            .filter(|n| n.has_tag_name("line"))
            .map(|l| [number(&l, "x1"), number(&l, "y1"), number(&l, "x2"), number(&l, "y2")])
            .collect();
        let ring = g.descendants().find(|n| n.has_tag_name("circle")).map(|c| [number(&c, "cx"), number(&c, "cy")]);
        let square =
            g.descendants().find(|n| n.has_tag_name("rect")).map(|r| [number(&r, "x") + 4.5, number(&r, "y") + 4.5]);
        (lines, ring, square)
    };
    // Front view: the patch's line runs to the instant centre, the roll centre on its extension (the
    // generic MacPherson has nothing joining the sides), to the 0.1 px the coordinates are written to.
    let (lines, ring, square) = construction(view("view-front"));
    let ([x1, y1, x2, y2], ring, square) = (lines[0], ring.unwrap(), square.unwrap());
    assert!((x2 - ring[0]).abs() < 1e-9 && (y2 - ring[1]).abs() < 1e-9);
    let off = ((square[0] - x1) * (y2 - y1) - (square[1] - y1) * (x2 - x1)).abs() / (x2 - x1).hypot(y2 - y1);
    // Measured 0.062 px.
    assert!(off < 0.3, "the roll centre is {off} px off the patch's line");
    // Side view: the patch's and the wheel centre's lines meet at the side-view instant centre.
    let (lines, ring, square) = construction(view("view-side"));
    let ring = ring.unwrap();
    assert_eq!(lines.len(), 2);
    assert!(lines.iter().all(|l| (l[2] - ring[0]).abs() < 1e-9 && (l[3] - ring[1]).abs() < 1e-9));
    assert!(square.is_none());
    assert!(html.contains("instant centres (ring) and roll centre (square)"));
    // The plan view draws none.
    assert!(!view("view-plan").descendants().any(|n| n.attribute("class") == Some("construction")));
}
