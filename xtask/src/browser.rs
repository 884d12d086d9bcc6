//! Headless Chromium (Debian's `chromium` package, found by `elastokin_chromium::find`) for the report:
//! its page as a picture, and its page as the browser leaves it once the scripts have run, with everything
//! the browser logged. Used by `cargo xtask screenshot` and by the test that loads every shipped example's
//! report in a real browser.
//!
//! Each run gets a fresh profile, removed after, so no earlier state (cache, settings) changes what is
//! seen; everything that would reach the network is off, since a report needs nothing outside itself.

use elastokin::provenance::Provenance;
use elastokin::suspensions::kc::{self, Settings};
use elastokin::suspensions::SuspensionFile;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A run that takes longer than this has hung (a first start of Chromium takes a few seconds).
const TIME_LIMIT: Duration = Duration::from_secs(120);

/// How long the page's scripts may run (virtual time) before the DOM is read.
const SCRIPT_TIME_MS: u32 = 3000;

/// The report `elastokin run MODEL` writes (every analysis of the suite, the plots, the geometry views),
/// made through the library as the command makes it; `shown_path` names the model in the provenance.
pub fn report_page(root: &Path, shown_path: &str) -> Result<String, String> {
    let model_path = root.join(shown_path);
    // Read once: the bytes hashed for the provenance are the ones parsed.
    let text = std::fs::read_to_string(&model_path).map_err(|e| format!("{}: {e}", model_path.display()))?;
    let file = SuspensionFile::from_json(&text, shown_path).map_err(|e| e.to_string())?;
    let settings = Settings { motion: true, ..Settings::default() };
    let report = kc::run_suite(&file, &[], &settings, |_| {});
    let mut provenance =
        Provenance::new(Path::new(shown_path), text.as_bytes(), kc::mode_word(settings.mode), settings.steps);
    provenance.tolerance = Some(settings.tolerance);
    Ok(elastokin::html::report_html(&report, &file, &provenance.to_json(), elastokin::plot::svg))
}

/// Runs Chromium headless on `page` (with `query`) with `extra` arguments; returns its standard output and
/// error. `profile` is made fresh and removed after.
#[cfg(test)]
fn run(
    chromium: &Path,
    page: &Path,
    query: &str,
    extra: &[String],
    profile: &Path,
) -> Result<(String, String), String> {
    let page = page.canonicalize().map_err(|e| format!("{}: {e}", page.display()))?;
    run_at(chromium, &format!("file://{}{query}", page.display()), extra, profile)
}

/// Runs Chromium headless on the address `url` with `extra` arguments; returns its standard output and
/// error. `profile` is made fresh and removed after.
fn run_at(chromium: &Path, url: &str, extra: &[String], profile: &Path) -> Result<(String, String), String> {
    let _ = std::fs::remove_dir_all(profile);
    std::fs::create_dir_all(profile).map_err(|e| format!("{}: {e}", profile.display()))?;
    let mut cmd = Command::new(chromium);
    cmd.args([
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--hide-scrollbars",
        "--enable-logging=stderr",
        "--v=0",
    ])
    .arg(format!("--user-data-dir={}", profile.display()))
    .args(extra)
    .arg(url)
    .stdout(Stdio::piped())
    .stderr(Stdio::piped());
    let mut child = cmd.spawn().map_err(|e| format!("could not start {}: {e}", chromium.display()))?;
    // Read both pipes while waiting, so a full pipe cannot stall the browser.
    let (mut out, mut err) = (child.stdout.take().expect("piped"), child.stderr.take().expect("piped"));
    let out = std::thread::spawn(move || std::io::read_to_string(&mut out).unwrap_or_default());
    let err = std::thread::spawn(move || std::io::read_to_string(&mut err).unwrap_or_default());
    let started = Instant::now();
    let status = loop {
        match child.try_wait().map_err(|e| e.to_string())? {
            Some(status) => break status,
            None if started.elapsed() > TIME_LIMIT => {
                let _ = child.kill();
                let _ = child.wait();
                let _ = std::fs::remove_dir_all(profile);
                return Err(format!("chromium took longer than {} s; stopped", TIME_LIMIT.as_secs()));
            }
            None => std::thread::sleep(Duration::from_millis(50)),
        }
    };
    let (out, err) = (out.join().unwrap_or_default(), err.join().unwrap_or_default());
    let _ = std::fs::remove_dir_all(profile);
    if !status.success() {
        return Err(format!("chromium failed ({status}):\n{err}"));
    }
    Ok((out, err))
}

/// `page` (with `query`, e.g. `?view=side`) as the browser leaves it once its scripts have run, and the
/// lines the browser logged from the page's console (errors and messages; its own start-up chatter left
/// out).
#[cfg(test)]
pub fn loaded(chromium: &Path, page: &Path, query: &str, profile: &Path) -> Result<(String, Vec<String>), String> {
    let extra = [format!("--virtual-time-budget={SCRIPT_TIME_MS}"), "--dump-dom".to_string()];
    let (dom, log) = run(chromium, page, query, &extra, profile)?;
    Ok((dom, console_lines(&log)))
}

/// `page` as the browser leaves it once its scripts have run in a `window` of pixels, and its console's
/// lines, as [`loaded`] gives them.
#[cfg(test)]
pub fn loaded_in(
    chromium: &Path,
    page: &Path,
    window: (u32, u32),
    profile: &Path,
) -> Result<(String, Vec<String>), String> {
    let page = page.canonicalize().map_err(|e| format!("{}: {e}", page.display()))?;
    loaded_at(chromium, &format!("file://{}", page.display()), window, profile)
}

/// Has Chromium draw `page` (with `query`) in a `window` of pixels and save it as `picture`.
pub fn screenshot(
    chromium: &Path,
    page: &Path,
    query: &str,
    picture: &Path,
    window: (u32, u32),
    profile: &Path,
) -> Result<(), String> {
    let page = page.canonicalize().map_err(|e| format!("{}: {e}", page.display()))?;
    screenshot_at(chromium, &format!("file://{}{query}", page.display()), picture, window, profile)
}

/// Has Chromium draw the page at the address `url` in a `window` of pixels, once its scripts have run and
/// every request they made has been answered, and save it as `picture`.
pub fn screenshot_at(
    chromium: &Path,
    url: &str,
    picture: &Path,
    window: (u32, u32),
    profile: &Path,
) -> Result<(), String> {
    let _ = std::fs::remove_file(picture);
    let extra = [
        format!("--virtual-time-budget={SCRIPT_TIME_MS}"),
        format!("--screenshot={}", picture.display()),
        format!("--window-size={},{}", window.0, window.1),
    ];
    run_at(chromium, url, &extra, profile)?;
    if !picture.is_file() {
        return Err(format!("chromium wrote no {}", picture.display()));
    }
    Ok(())
}

/// The page at the address `url` as the browser leaves it once its scripts have run (every request they
/// made answered, virtual time), in a `window` of pixels, and its console's lines.
#[cfg(test)]
pub fn loaded_at(
    chromium: &Path,
    url: &str,
    window: (u32, u32),
    profile: &Path,
) -> Result<(String, Vec<String>), String> {
    let extra = [
        format!("--virtual-time-budget={SCRIPT_TIME_MS}"),
        format!("--window-size={},{}", window.0, window.1),
        "--dump-dom".to_string(),
    ];
    let (dom, log) = run_at(chromium, url, &extra, profile)?;
    Ok((dom, console_lines(&log)))
}

/// The lines Chromium logged from a page's console (its messages and uncaught errors), its own start-up
/// chatter left out.
#[cfg(test)]
fn console_lines(log: &str) -> Vec<String> {
    log.lines().filter(|l| l.contains(":CONSOLE(") || l.contains("Uncaught")).map(String::from).collect()
}

/// The part of a report page from the start of the element with `id` (opened by `open`, e.g.
/// `<figure`) to the end of that element, and, for the 3D view, its two scripts: a page of it alone
/// draws what the report draws there.
pub fn part_of_page(page: &str, open: &str, id: &str, close: &str) -> Option<String> {
    let marker = format!("id=\"{id}\"");
    let at = page
        .match_indices(open)
        .map(|(i, _)| i)
        .find(|&i| page[i..].split('>').next().is_some_and(|tag| tag.contains(&marker)))?;
    let end = at + page[at..].find(close)? + close.len();
    let head = &page[..page.find("<body>")? + "<body>".len()];
    Some(format!("{head}\n{}\n</body>\n</html>\n", &page[at..end]))
}

/// The JSON a page's script wrote into its `<output id="ID">`, read from the page as the browser left it
/// (`dom`, as `--dump-dom` writes it).
#[cfg(test)]
pub fn output_in(dom: &str, id: &str) -> Result<serde_json::Value, String> {
    let text = dom
        .split(&format!("id=\"{id}\""))
        .nth(1)
        .and_then(|s| s.split('>').nth(1))
        .and_then(|s| s.split("</output").next())
        .ok_or_else(|| format!("no output {id} in the page"))?;
    serde_json::from_str(&html_unescape(text)).map_err(|e| format!("output {id} ({e}): {text}"))
}

/// The text of an element as `--dump-dom` serialises it: the three entities it writes in text.
#[cfg(test)]
fn html_unescape(s: &str) -> String {
    s.replace("&quot;", "\"").replace("&lt;", "<").replace("&gt;", ">").replace("&amp;", "&")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every shipped example's report (as `elastokin run` writes it) loaded in headless Chromium: no error
    /// on the console, and the 3D view's scene has what the model's drawing has — a stroke for each of
    /// its parts, links, springs, bushings and wheels, a dot for each joint — all of them drawn, for every
    /// analysis that moves; on the first example each preset view is taken as asked, and its front and side
    /// views draw the instant centres' construction of the row shown (the library's, line for line).
    ///
    /// Needs Debian's chromium: `.ci/run` installs it. Without it the test says so and passes on a
    /// developer's machine, and fails under CI (`CI` set), where it must run.
    #[test]
    fn every_shipped_examples_report_loads_in_chromium_without_error_and_draws_its_scene() {
        let Some(chromium) = chromium_or_skip() else { return };
        let root = crate::workspace_root();
        let dir = root.join("target/report-in-browser");
        std::fs::create_dir_all(&dir).unwrap();
        let mut examples: Vec<String> = std::fs::read_dir(root.join("examples"))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".json"))
            .collect();
        examples.sort();
        assert!(examples.len() >= 5, "{examples:?}");
        for (k, name) in examples.iter().enumerate() {
            let shown = format!("examples/{name}");
            let html = report_page(&root, &shown).unwrap();
            let page = dir.join(name.replace(".json", ".html"));
            std::fs::write(&page, &html).unwrap();
            // What the scene should hold, from the library.
            let file = SuspensionFile::read(&root.join(&shown)).unwrap();
            let settings = Settings { motion: true, ..Settings::default() };
            let suite = kc::run_suite(&file, &[], &settings, |_| {});
            let moving: Vec<_> = suite.analyses.iter().filter_map(|a| Some((a, a.motion.as_ref()?))).collect();
            assert!(!moving.is_empty(), "{name}: nothing moves");
            let (first, motion) = moving[0];
            let queries: &[&str] = if k == 0 { &["", "?view=front", "?view=side", "?view=plan"] } else { &[""] };
            for query in queries {
                let (dom, console) = loaded(&chromium, &page, query, &dir.join("profile")).unwrap();
                assert!(console.is_empty(), "{name}{query}: the console says {console:#?}");
                let state = output_in(&dom, "view3d-state")
                    .unwrap_or_else(|e| panic!("{name}{query}: the 3D view did not report: {e}"));
                assert_eq!(state["errors"], serde_json::json!([]), "{name}{query}");
                assert_eq!(state["analyses"], moving.len(), "{name}{query}");
                assert_eq!(state["analysis"], first.analysis.name(), "{name}{query}");
                assert_eq!(state["rows"], first.table.rows.len(), "{name}{query}");
                let strokes = motion.drawing.strokes().len();
                assert_eq!(state["strokes"], strokes, "{name}{query}");
                assert_eq!(state["drawn"], strokes, "{name}{query}: every stroke drawn");
                assert_eq!(state["dots"], motion.drawing.dots().len(), "{name}{query}");
                let view = query.strip_prefix("?view=").unwrap_or("3d");
                assert_eq!(state["view"], view, "{name}{query}");
                // The instant centres' construction at the row shown, in the front and side views alone.
                let c = first.construction.get(first.design_row());
                let lines = match (view, c) {
                    ("front", Some(c)) => {
                        usize::from(c.front_view_centre.is_some()) + usize::from(c.roll_centre.is_some())
                    }
                    ("side", Some(c)) => 2 * usize::from(c.side_view_centre.is_some()),
                    _ => 0,
                };
                assert_eq!(state["construction"], lines, "{name}{query}");
                if first.analysis.name() == "parallel-travel" && view != "3d" && view != "plan" {
                    assert!(lines > 0, "{name}{query}: the construction is drawn");
                }
            }
        }
    }

    /// The shipped MacPherson's report with its wheel envelope shown (`?analysis=wheel-envelope`): the 3D
    /// view draws the tyre at every point of the envelope's grid on both wheels, and the packaging's points
    /// and boxes on both sides, in 3D and in the front view; the console stays clean.
    #[test]
    fn the_wheel_envelope_and_its_packaging_are_drawn_in_the_3d_view() {
        let Some(chromium) = chromium_or_skip() else { return };
        let root = crate::workspace_root();
        let dir = root.join("target/report-in-browser");
        std::fs::create_dir_all(&dir).unwrap();
        let shown = "examples/macpherson.json";
        let page = dir.join("envelope.html");
        std::fs::write(&page, report_page(&root, shown).unwrap()).unwrap();
        let file = SuspensionFile::read(&root.join(shown)).unwrap();
        let settings = Settings { motion: true, ..Settings::default() };
        let envelope = kc::run(kc::Analysis::WheelEnvelope, &file, &settings).unwrap();
        let placements = envelope.envelope.as_ref().unwrap().placements.len();
        let packaging = file.packaging.as_ref().unwrap();
        assert!(placements >= 81, "{placements}");
        for query in ["?analysis=wheel-envelope", "?analysis=wheel-envelope&view=front"] {
            let (dom, console) = loaded(&chromium, &page, query, &dir.join("profile-envelope")).unwrap();
            assert!(console.is_empty(), "{query}: the console says {console:#?}");
            let state = output_of(&dom, "view3d-state");
            assert_eq!(state["errors"], serde_json::json!([]), "{query}");
            assert_eq!(state["analysis"], "wheel-envelope", "{query}");
            assert_eq!(state["rows"], envelope.table.rows.len(), "{query}");
            let drawn = &state["envelope"];
            assert_eq!(drawn["tyres"], 2 * placements, "{query}");
            assert_eq!(drawn["points"], 2 * packaging.points.len(), "{query}");
            assert_eq!(drawn["boxes"], 2 * packaging.boxes.len(), "{query}");
        }
        // Another analysis shown draws no envelope.
        let (dom, _) = loaded(&chromium, &page, "", &dir.join("profile-envelope")).unwrap();
        assert_eq!(output_of(&dom, "view3d-state")["envelope"], serde_json::Value::Null);
    }

    /// A script the layout test adds to a report's page: it measures, as the browser lays the page out,
    /// every non-empty text of every SVG shown (the plots and the geometry's projections) and writes what
    /// it finds as JSON into `<output id="layout-check">`: a label whose box leaves its picture (cut off),
    /// two labels of one picture whose boxes overlap, the smallest label's size in CSS pixels, and whether
    /// the page is wider than the window (a table or chart that does not fit).
    const LAYOUT_CHECK: &str = r#"<script>//<![CDATA[
addEventListener('load', () => {
  // The SVGs as they show with scripts off and on paper, where the interactive charts do not stand in.
  document.querySelectorAll('figure.live').forEach(f => f.classList.remove('live'));
  document.querySelectorAll('.live-chart').forEach(c => { c.style.display = 'none'; });
  const cut = [], overlaps = [];
  let smallest = Infinity, smallestLabel = '', labels = 0;
  document.querySelectorAll('svg').forEach((svg, i) => {
    const box = svg.getBoundingClientRect();
    const texts = Array.from(svg.querySelectorAll('text')).filter(t => t.textContent.trim() !== '');
    if (box.width === 0 || texts.length === 0) return;
    const picture = (svg.querySelector('title') || {}).textContent || (svg.closest('[id]') || {}).id || ('svg ' + i);
    const view = svg.viewBox && svg.viewBox.baseVal && svg.viewBox.baseVal.width ? svg.viewBox.baseVal.width : box.width;
    const scale = box.width / view;
    const rects = texts.map(t => t.getBoundingClientRect());
    texts.forEach((t, k) => {
      const r = rects[k];
      labels += 1;
      const size = parseFloat(getComputedStyle(t).fontSize) * scale;
      if (size < smallest) { smallest = size; smallestLabel = picture + ': ' + t.textContent.trim() + ' (' + box.width + ' px wide, ' + innerWidth + ')'; }
      if (r.left < box.left - 1 || r.right > box.right + 1 || r.top < box.top - 1 || r.bottom > box.bottom + 1) {
        cut.push(picture + ': ' + t.textContent.trim());
      }
      for (let m = 0; m < k; m++) {
        const q = rects[m];
        const w = Math.min(r.right, q.right) - Math.max(r.left, q.left);
        const h = Math.min(r.bottom, q.bottom) - Math.max(r.top, q.top);
        if (w > 1 && h > 1) overlaps.push(picture + ': ' + texts[m].textContent.trim() + ' / ' + t.textContent.trim());
      }
    });
  });
  const out = document.createElement('output');
  out.id = 'layout-check';
  out.textContent = JSON.stringify({
    labels, cut, overlaps, smallest, smallestLabel,
    wider: document.documentElement.scrollWidth > window.innerWidth + 1
  });
  document.body.appendChild(out);
});
//]]></script>"#;

    /// The shipped MacPherson's report, and its comparison with the generic one, as a user sees them in a
    /// window 1280 px wide: every label of their plots and projections inside its picture, clear of the
    /// others and at least 10 px high, and each page no wider than the window.
    #[test]
    fn every_label_of_the_report_is_inside_its_picture_clear_of_the_others_and_legible() {
        let Some(chromium) = chromium_or_skip() else { return };
        let root = crate::workspace_root();
        let dir = root.join("target/report-layout");
        std::fs::create_dir_all(&dir).unwrap();
        let pages = [
            ("macpherson", report_page(&root, "examples/macpherson.json").unwrap()),
            ("compare", compare_page(&root, &["examples/macpherson.json", "examples/generic/macpherson.json"])),
        ];
        for (name, html) in pages {
            let page = dir.join(format!("{name}.html"));
            std::fs::write(&page, html.replace("</body>", &format!("{LAYOUT_CHECK}</body>"))).unwrap();
            let (dom, console) = loaded_in(&chromium, &page, (1280, 1600), &dir.join("profile")).unwrap();
            assert!(console.is_empty(), "{name}: the console says {console:#?}");
            let found = output_of(&dom, "layout-check");
            assert!(found["labels"].as_u64().unwrap() > 100, "{name}: {found}");
            assert_eq!(found["cut"], serde_json::json!([]), "{name}: labels cut off");
            assert_eq!(found["overlaps"], serde_json::json!([]), "{name}: labels over one another");
            let smallest = found["smallest"].as_f64().unwrap();
            assert!(smallest >= 10.0, "{name}: the smallest label is {smallest} px: {}", found["smallestLabel"]);
            assert_eq!(found["wider"], false, "{name}: the page is wider than the window");
        }
    }

    /// The comparison page `elastokin compare` writes of the models at `paths`, made through the library.
    fn compare_page(root: &Path, paths: &[&str]) -> String {
        use elastokin::suspensions::compare::{compare, Design};
        let settings = Settings { motion: true, ..Settings::default() };
        let designs: Vec<Design> = paths
            .iter()
            .map(|p| {
                let file = SuspensionFile::read(&root.join(p)).unwrap();
                let report = kc::run_suite(&file, &[], &settings, |_| {});
                Design::model(&file, report)
            })
            .collect();
        let comparison = compare(&designs).unwrap();
        let models = comparison.models(&designs);
        elastokin::html::compare_html(&comparison, &models, &serde_json::json!({}), elastokin::plot::svg)
    }

    /// The report's print stylesheet as the browser's Print lays it out, on an A4 sheet's printable width
    /// (186 mm, 703 CSS px): its `@media print` rules applied to the screen, every chart then on the
    /// sheet between 0.4 and 0.5 of its printable height (two to a sheet, where the screen's two to a row would
    /// give about a quarter), the 3D view left out.
    #[test]
    fn the_print_stylesheet_gives_plot_sheets_two_charts_to_an_a4_page() {
        let Some(chromium) = chromium_or_skip() else { return };
        let root = crate::workspace_root();
        let dir = root.join("target/report-print");
        std::fs::create_dir_all(&dir).unwrap();
        let html = report_page(&root, "examples/macpherson.json").unwrap();
        // The print rules, as screen rules: the block of `@media print`, without its page size.
        let at = html.find("@media print {").expect("a print stylesheet");
        let body = &html[at + "@media print {".len()..];
        let end = body.find("\n}").expect("the print block closes");
        let rules: String =
            body[..end].lines().filter(|l| !l.trim_start().starts_with("@page")).collect::<Vec<_>>().join("\n");
        let measure = r#"<script>//<![CDATA[
addEventListener('load', () => {
  const charts = Array.from(document.querySelectorAll('.charts figure svg')).map(svg => {
    const r = svg.getBoundingClientRect();
    return [r.width, r.height];
  });
  const view3d = document.querySelector('figure.view3d');
  const out = document.createElement('output');
  out.id = 'print-check';
  out.textContent = JSON.stringify({ charts, view3d: view3d ? view3d.getBoundingClientRect().height : 0 });
  document.body.appendChild(out);
});
//]]></script>"#;
        let page = html
            .replace("</head>", &format!("<style>{rules}</style></head>"))
            .replace("</body>", &format!("{measure}</body>"));
        let path = dir.join("macpherson.html");
        std::fs::write(&path, &page).unwrap();
        let (dom, console) = loaded_in(&chromium, &path, (703, 1000), &dir.join("profile")).unwrap();
        assert!(console.is_empty(), "the console says {console:#?}");
        let found = output_of(&dom, "print-check");
        let charts = found["charts"].as_array().unwrap();
        assert!(charts.len() >= 8, "{found}");
        // A4's printable height under 12 mm margins: 273 mm, 1032 CSS px.
        let sheet = 273.0 / 25.4 * 96.0;
        for c in charts {
            let h = c[1].as_f64().unwrap();
            assert!(h >= 0.4 * sheet && h <= 0.5 * sheet, "a chart {h} px high on a sheet of {sheet} px");
        }
        assert_eq!(found["view3d"], 0.0, "the 3D view is left out of print");
    }

    /// A script the chart test adds to a report's page: on the first interactive chart, the pointer put on
    /// its sixth point's x and the legend's read-out taken, a click on the second curve's legend entry,
    /// and a drag across the middle of the plot; written as JSON into `<output id="chart-check">`.
    const CHART_CHECK: &str = r#"<script>//<![CDATA[
addEventListener('load', async () => {
  const frame = () => new Promise(r => setTimeout(r, 30));
  const u = window.elastokinCharts[0];
  const x = u.data[0][5];
  u.setCursor({ left: u.valToPos(x, 'x'), top: 10 });
  const values = Array.from(u.root.querySelectorAll('.u-legend .u-series')).map(r => r.querySelector('.u-value').textContent);
  const entry = u.root.querySelectorAll('.u-legend .u-series')[2];
  entry.querySelector('.u-label').dispatchEvent(new MouseEvent('click', { bubbles: true }));
  const shown = u.series[2].show;
  const before = [u.scales.x.min, u.scales.x.max];
  const box = u.over.getBoundingClientRect();
  const at = (f, type, target) => target.dispatchEvent(new MouseEvent(type, {
    bubbles: true, clientX: box.left + f * box.width, clientY: box.top + 0.5 * box.height, button: 0, buttons: 1,
    movementX: 5, movementY: 0 }));
  at(0.3, 'mousemove', u.over);
  await frame();
  at(0.3, 'mousedown', u.over);
  await frame();
  at(0.5, 'mousemove', u.over);
  await frame();
  at(0.6, 'mousemove', u.over);
  await frame();
  at(0.6, 'mouseup', document);
  await frame();
  const after = [u.scales.x.min, u.scales.x.max];
  const out = document.createElement('output');
  out.id = 'chart-check';
  out.textContent = JSON.stringify({ state: JSON.parse(document.getElementById('charts-state').textContent),
    x, values, shown, before, after });
  document.body.appendChild(out);
});
//]]></script>"#;

    /// The MacPherson's report in Chromium with its charts drawn interactively: every chart drawn, none in
    /// error; the pointer's read-out on the first chart gives each curve's value at that x as the library's
    /// chart holds it; a click on a legend entry hides its curve; a drag zooms into the part dragged over.
    #[test]
    fn the_charts_read_out_under_the_pointer_toggle_and_zoom_in_chromium() {
        let Some(chromium) = chromium_or_skip() else { return };
        let root = crate::workspace_root();
        let dir = root.join("target/report-charts");
        std::fs::create_dir_all(&dir).unwrap();
        let html = report_page(&root, "examples/macpherson.json")
            .unwrap()
            .replace("</body>", &format!("{CHART_CHECK}</body>"));
        let page = dir.join("macpherson.html");
        std::fs::write(&page, &html).unwrap();
        let (dom, console) = loaded_in(&chromium, &page, (1280, 1600), &dir.join("profile")).unwrap();
        assert!(console.is_empty(), "the console says {console:#?}");
        let found = output_of(&dom, "chart-check");
        // What the library's suite charts hold.
        let file = SuspensionFile::read(&root.join("examples/macpherson.json")).unwrap();
        let suite = kc::run_suite(&file, &[], &Settings { motion: true, ..Settings::default() }, |_| {});
        let charts: Vec<_> = suite.analyses.iter().flat_map(|a| &a.charts).collect();
        assert_eq!(found["state"]["charts"], charts.len(), "{found}");
        assert_eq!(found["state"]["drawn"], charts.len(), "{found}");
        assert_eq!(found["state"]["errors"], serde_json::json!([]));
        // The read-out: the x, then each curve's value there, written to 4 significant digits.
        let first = charts[0];
        let x = found["x"].as_f64().unwrap();
        let values = found["values"].as_array().unwrap();
        let curves: Vec<_> = std::iter::once(&first.left).chain(first.right.as_ref()).flat_map(|a| &a.series).collect();
        assert_eq!(values.len(), 1 + curves.len(), "{found}");
        let read = |k: usize| values[k].as_str().unwrap().parse::<f64>().unwrap();
        assert!((read(0) - x).abs() <= 5e-4 * x.abs().max(1e-9), "{found}");
        for (k, s) in curves.iter().enumerate() {
            let y = s.points.iter().find(|p| p.0 == x).expect("a point at the x read").1;
            assert!((read(k + 1) - y).abs() <= 5e-4 * y.abs().max(1e-9), "{}: {} against {y}", s.name, read(k + 1));
        }
        assert_eq!(found["shown"], false, "a click on the legend hides the curve");
        let (before, after) = (found["before"].as_array().unwrap(), found["after"].as_array().unwrap());
        let span = |r: &Vec<serde_json::Value>| r[1].as_f64().unwrap() - r[0].as_f64().unwrap();
        assert!(span(after) < 0.5 * span(before), "a drag over 30 % of the plot zooms: {before:?} → {after:?}");
    }

    /// Chromium, or `None` on a developer's machine without it (the test says so and passes); under CI
    /// (`CI` set), where the tests must run, its absence fails.
    fn chromium_or_skip() -> Option<std::path::PathBuf> {
        match elastokin_chromium::find() {
            Ok(c) => Some(c),
            Err(e) if std::env::var_os("CI").is_none() => {
                eprintln!("skipped: {e}");
                None
            }
            Err(e) => panic!("{e}"),
        }
    }

    /// The JSON a test's script wrote into `<output id="ID">` of the page as the browser left it (`dom`).
    fn output_of(dom: &str, id: &str) -> serde_json::Value {
        output_in(dom, id).unwrap_or_else(|e| panic!("{e}"))
    }

    #[test]
    fn a_part_of_a_page_is_the_element_with_its_id_under_the_pages_head() {
        let page = "<html><head><style>x</style></head><body><figure id=\"a\">A</figure>\
                    <figure class=\"view\" id=\"b\"><svg/></figure></body></html>";
        let part = part_of_page(page, "<figure", "b", "</figure>").unwrap();
        assert!(part.starts_with("<html><head><style>x</style></head><body>"));
        assert!(part.contains("<figure class=\"view\" id=\"b\"><svg/></figure>") && !part.contains(">A<"));
        assert_eq!(part_of_page(page, "<figure", "c", "</figure>"), None);
    }
}
