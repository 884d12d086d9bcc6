//! `elastokin live`: a move on the shipped MacPherson, from the edit to every chart redrawn, measured in
//! headless Chromium on the page the server serves (`elastokin_chromium`); the server's share of it,
//! through the same function the server hands each request to (`elastokin::live::Live::handle`), without
//! the socket; and the suite alone, one analysis after another and on every thread.

use super::report::{Cell, Judge, Kind, SectionOutput, Table, Target};
use super::stats::median;
use super::Settings;
use elastokin::live::{Admission, FrameAncestors, Head, Live, LiveServer, Served, Token};
use elastokin::suspensions::kc;
use std::path::PathBuf;

/// The budget from a move to every chart redrawn (s).
const MOVE_LIMIT_S: f64 = 0.05;

/// The number moved: the tie rod's inner height, between two values 1 mm apart (m).
const MOVED: &str = "/suspension/macpherson/hardpoints/tie_rod_inner/2";
const HEIGHTS: [f64; 2] = [-0.0374, -0.0384];

/// Runs the section.
pub fn run(s: &Settings) -> SectionOutput {
    let mut out = SectionOutput {
        title: "Live design".into(),
        intro: "A hardpoint moved in `elastokin live` on the shipped MacPherson (every analysis of its suite, \
                default ranges, 32 corrected steps and the parts' poses at every row, as the server runs it: \
                an edit is answered without the error estimates, which the page asks for once the design has \
                rested on screen for 300 ms, timed apart below). In the browser: headless Chromium on the \
                served page, the tie rod's inner z typed between two values 1 mm apart, each a new design, \
                timed by the page's clock from the field's change to the frame after the new design is shown \
                (every figure, chart with its ghost, projection and the 3D view drawn). The server's share: \
                from the edit's request to the JSON of the new design, through the function the server hands \
                each request to, without the socket; and the same for the estimates of a design an edit \
                made. Medians of repeated moves. Then the suite alone with its estimates, one analysis after \
                another on one thread and on every thread."
            .into(),
        ..SectionOutput::default()
    };
    let mut table = Table::new("Live design", "live.csv", &["what", "median time (s)", "answer (kB)", "status"]);
    let in_browser = in_browser(s);
    match &in_browser {
        Ok(t) => {
            let what = "a hardpoint typed in the browser: every chart redrawn";
            table.row(vec![Cell::text(what), Cell::num(*t), Cell::text(""), Cell::text("ok")]);
            out.figure("live.move_in_browser_s", *t, "s", Kind::Time);
        }
        Err(e) => table.failed_row(vec![Cell::text("a hardpoint typed in the browser")], e.clone()),
    }
    let server_share = server_share(s);
    match &server_share {
        Ok(share) => {
            table.row(vec![
                Cell::text("the server's share: the suite run again, the state written"),
                Cell::num(share.edit),
                Cell::num(share.size as f64 / 1e3),
                Cell::text("ok"),
            ]);
            table.row(vec![
                Cell::text("the server's share of the estimates, once the design rests"),
                Cell::num(share.estimate),
                Cell::text(""),
                Cell::text("ok"),
            ]);
            out.figure("live.move_macpherson_s", share.edit, "s", Kind::Time);
            out.figure("live.estimate_macpherson_s", share.estimate, "s", Kind::Time);
        }
        Err(e) => table.failed_row(vec![Cell::text("the server's share")], e.clone()),
    }
    // The analyses run at once on the threads against one after another, measured in this run: the
    // ratio is what to read on a shared machine.
    match suites(s) {
        Ok((in_turn, on_threads)) => {
            for (what, t) in [
                ("the suite, one analysis after another on one thread", in_turn),
                ("the suite on every thread", on_threads),
            ] {
                table.row(vec![Cell::text(what), Cell::num(t), Cell::text(""), Cell::text("ok")]);
            }
            out.figure("live.suite_in_turn_s", in_turn, "s", Kind::Time);
            out.figure("live.suite_on_threads_s", on_threads, "s", Kind::Time);
        }
        Err(e) => table.failed_row(vec![Cell::text("the suite")], e),
    }
    let detail = match &server_share {
        Ok(share) => format!(
            "the server's share {:.1} ms; the estimates once the design rests {:.1} ms more",
            share.edit * 1e3,
            share.estimate * 1e3
        ),
        Err(e) => format!("the server's share not measured: {e}"),
    };
    out.targets.push(Target {
        goal: "a hardpoint moved on the MacPherson's suite in the browser, every chart redrawn".into(),
        measured: in_browser,
        limit: MOVE_LIMIT_S,
        unit: "s".into(),
        judge: Judge::AtMost,
        detail,
    });
    out.tables.push(table);
    out
}

/// The shipped MacPherson as the server serves it, and its path.
fn served() -> Result<(Served, PathBuf), String> {
    let path = crate::workspace_root().join("examples/macpherson.json");
    let served = Served::open(&path, &[], kc::Settings::default().steps).map_err(|e| e.to_string())?;
    Ok((served, path))
}

/// The server's share of a move and of its estimates.
struct ServerShare {
    /// The median time of the answer to an edit (s).
    edit: f64,
    /// The answer's size (bytes).
    size: usize,
    /// The median time of the answer to the estimates of the design an edit made (s).
    estimate: f64,
}

/// The server's share: the median time of its answer to a move, the answer's size, and the median time
/// of its answer to the estimates of the design a move made.
fn server_share(s: &Settings) -> Result<ServerShare, String> {
    let (served, _) = served()?;
    let bound = "127.0.0.1:1".parse().map_err(|e| format!("{e}"))?;
    let token = Token::random()?;
    let (url, estimate_url) = (format!("/{}/edit", token.as_str()), format!("/{}/estimate", token.as_str()));
    // A save is never asked: the path is only where one would go.
    let mut live = Live::new(served, Admission::new(token, bound, FrameAncestors::none()));
    let head = Head { method: "POST", url: &url, host: Some("127.0.0.1:1"), origin: None, content_length: None };
    let estimate_head = Head { url: &estimate_url, ..head };
    let mut moves = 0usize;
    let mut failed = None;
    let mut size = 0;
    // Each answer refused is noted in `failed`.
    let ask = |live: &mut Live, head: &Head, body: String, failed: &mut Option<String>| {
        let answer = live.handle(head, body.as_bytes());
        if answer.status != 200 {
            *failed = Some(String::from_utf8_lossy(&answer.body).into_owned());
        }
        answer.body.len()
    };
    let edit = |moves: &mut usize| {
        *moves += 1;
        format!(r#"{{"pointer": "{MOVED}", "value": {}}}"#, HEIGHTS[*moves % 2])
    };
    let timing = s.batch_budget().time(|| size = ask(&mut live, &head, edit(&mut moves), &mut failed));
    let mut estimates = Vec::new();
    for _ in 0..if s.quick { 3 } else { 11 } {
        ask(&mut live, &head, edit(&mut moves), &mut failed);
        let body = format!(r#"{{"version": {}}}"#, live.design().version());
        let start = std::time::Instant::now();
        ask(&mut live, &estimate_head, body, &mut failed);
        estimates.push(start.elapsed().as_secs_f64());
    }
    match (failed, median(&estimates)) {
        (Some(why), _) => Err(format!("an edit or its estimates were refused: {why}")),
        (None, None) => Err("no estimate was timed".into()),
        (None, Some(estimate)) => Ok(ServerShare { edit: timing.median, size, estimate }),
    }
}

/// The median time in the browser from a hardpoint's field changed to the frame after the new design is
/// drawn, by the page's own clock (`performance.now()`): the server started in this process, the page
/// opened in headless Chromium, each move waited for before the next.
fn in_browser(s: &Settings) -> Result<f64, String> {
    let chromium = elastokin_chromium::find()?;
    let (served, _) = served()?;
    let bind = "127.0.0.1:0".parse().map_err(|e| format!("{e}"))?;
    let mut server = LiveServer::start(served, bind, FrameAncestors::none()).map_err(|e| e.to_string())?;
    let profile = std::env::temp_dir().join(format!("elastokin-bench-live-{}", std::process::id()));
    let mut browser = elastokin_chromium::Browser::start(&chromium, profile)?;
    let page = browser.open(server.address())?;
    let first = |state: &serde_json::Value| state["version"].as_u64().unwrap_or(0) >= 1;
    browser.output_when(&page, "live-state", first, std::time::Duration::from_secs(60))?;
    let moves = if s.quick { 5 } else { 21 };
    let mut times = Vec::with_capacity(moves);
    for k in 0..moves {
        let typed = HEIGHTS[k % 2] * 1e3;
        // The field changed as leaving it after typing changes it; timed to the frame after the page says
        // it shows the next design (its report is written last, once everything is drawn).
        let expression = format!(
            "(async () => {{
               const report = document.getElementById('live-state');
               const version = () => JSON.parse(report.textContent || '{{}}').version || 0;
               const before = version();
               const input = document.querySelector('input[data-pointer=\"{MOVED}\"]');
               const shown = new Promise((resolve) => {{
                 const watch = new MutationObserver(() => {{
                   if (version() > before) {{ watch.disconnect(); resolve(); }}
                 }});
                 watch.observe(report, {{ childList: true, characterData: true, subtree: true }});
               }});
               const start = performance.now();
               input.value = '{typed}';
               input.dispatchEvent(new Event('change'));
               await shown;
               await new Promise((resolve) => requestAnimationFrame(() => setTimeout(resolve, 0)));
               const errors = JSON.parse(report.textContent).errors;
               return errors.length ? 'the page said: ' + errors.join('; ') : performance.now() - start;
             }})()"
        );
        match browser.evaluate(&page, &expression)? {
            serde_json::Value::Number(ms) => times.push(ms.as_f64().unwrap_or(f64::NAN) * 1e-3),
            other => return Err(format!("move {}: {other}", k + 1)),
        }
    }
    let page_said: Vec<&String> = browser.console.iter().filter(|(s, _)| *s == page).map(|(_, l)| l).collect();
    if !page_said.is_empty() {
        return Err(format!("the page's console: {page_said:?}"));
    }
    drop(browser);
    server.stop();
    median(&times).ok_or_else(|| "no move was timed".into())
}

/// The median times of the MacPherson's suite run one analysis after another on one thread
/// (`kc::run_suite`) and on every thread (`kc::run_suite_on_threads`, as the server runs it).
fn suites(s: &Settings) -> Result<(f64, f64), String> {
    let path = crate::workspace_root().join("examples/macpherson.json");
    let file = elastokin::suspensions::SuspensionFile::read(&path).map_err(|e| e.to_string())?;
    let settings = kc::Settings { motion: true, ..kc::Settings::default() };
    // One after another on one thread: an analysis that runs parts of itself at once does not here.
    let one_thread = rayon::ThreadPoolBuilder::new().num_threads(1).build().map_err(|e| e.to_string())?;
    let in_turn =
        s.batch_budget().time(|| one_thread.install(|| kc::run_suite(&file, &[], &settings, |_| {}).analyses.len()));
    let on_threads = s.batch_budget().time(|| kc::run_suite_on_threads(&file, &[], &settings).analyses.len());
    Ok((in_turn.median, on_threads.median))
}
