//! `elastokin live`: the server's share of a move, from the edit's request to its answer (the edited model
//! read and built, every analysis of the suite run again, the state written as JSON with every chart's
//! data), on the shipped MacPherson, through the same function the server hands each request to
//! (`elastokin::live::Live::handle`), without the socket.

use super::report::{Cell, Judge, Kind, SectionOutput, Table, Target};
use super::Settings;
use elastokin::live::{Admission, FrameAncestors, Head, Live, Served, Token};
use elastokin::suspensions::design::live::LiveDesign;
use elastokin::suspensions::kc;

/// The issue's budget from a move to every chart redrawn (s): the server's share must fit in it.
const MOVE_LIMIT_S: f64 = 0.05;

/// Runs the section.
pub fn run(s: &Settings) -> SectionOutput {
    let mut out = SectionOutput {
        title: "Live design".into(),
        intro: "A hardpoint moved in `elastokin live` on the shipped MacPherson (every analysis of its suite, \
                default ranges, 32 corrected steps with their error estimates): the server's answer to the edit, \
                from its request to the JSON of the new design with every figure and every chart's data, \
                through the function the server hands each request to, without the socket. The tie rod's inner \
                z moves between two values 1 mm apart, each move a new design. Median of repeated moves. The \
                browser's share (drawing every chart again) is not in it. Then the suite alone, one analysis \
                after another and on every thread as the server runs it."
            .into(),
        ..SectionOutput::default()
    };
    let mut table = Table::new("Live design", "live.csv", &["what", "median time (s)", "answer (kB)", "status"]);
    let measured = measure(s);
    match &measured {
        Ok((t, size)) => {
            table.row(vec![
                Cell::text("a hardpoint moved: the suite run again, the state written"),
                Cell::num(*t),
                Cell::num(*size as f64 / 1e3),
                Cell::text("ok"),
            ]);
            out.figure("live.move_macpherson_s", *t, "s", Kind::Time);
        }
        Err(e) => table.failed_row(vec![Cell::text("a hardpoint moved")], e.clone()),
    }
    // The analyses run at once on the threads against one after another, measured in this run: the
    // ratio is what to read on a shared machine.
    match suites(s) {
        Ok((in_turn, on_threads)) => {
            for (what, t) in
                [("the suite, one analysis after another", in_turn), ("the suite on every thread", on_threads)]
            {
                table.row(vec![Cell::text(what), Cell::num(t), Cell::text(""), Cell::text("ok")]);
            }
            out.figure("live.suite_in_turn_s", in_turn, "s", Kind::Time);
            out.figure("live.suite_on_threads_s", on_threads, "s", Kind::Time);
        }
        Err(e) => table.failed_row(vec![Cell::text("the suite")], e),
    }
    out.targets.push(Target {
        goal: "a hardpoint moved on the MacPherson's suite answered by the server".into(),
        measured: measured.map(|(t, _)| t),
        limit: MOVE_LIMIT_S,
        unit: "s".into(),
        judge: Judge::AtMost,
        detail: "the server's share of the 50 ms from a move to every chart redrawn".into(),
    });
    out.tables.push(table);
    out
}

/// The median time of the server's answer to a move, and the answer's size.
fn measure(s: &Settings) -> Result<(f64, usize), String> {
    let root = crate::workspace_root();
    let path = root.join("examples/macpherson.json");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let design =
        LiveDesign::open(&text, "examples/macpherson.json", &[], kc::Settings::default()).map_err(|e| e.to_string())?;
    let bound = "127.0.0.1:1".parse().map_err(|e| format!("{e}"))?;
    let token = Token::random()?;
    let url = format!("/{}/edit", token.as_str());
    // A save is never asked: the path is only where one would go.
    let admission = Admission::new(token, bound, FrameAncestors::none());
    let mut live = Live::new(Served { design, text, model: path }, admission);
    let head = Head { method: "POST", url: &url, host: Some("127.0.0.1:1"), origin: None, content_length: None };
    let mut moves = 0u32;
    let mut failed = None;
    let mut size = 0;
    let timing = s.batch_budget().time(|| {
        moves += 1;
        let z = if moves.is_multiple_of(2) { -0.0374 } else { -0.0384 };
        let body = format!(r#"{{"pointer": "/suspension/macpherson/hardpoints/tie_rod_inner/2", "value": {z}}}"#);
        let answer = live.handle(&head, body.as_bytes());
        if answer.status != 200 {
            failed = Some(String::from_utf8_lossy(&answer.body).into_owned());
        }
        size = answer.body.len();
    });
    match failed {
        Some(why) => Err(format!("an edit was refused: {why}")),
        None => Ok((timing.median, size)),
    }
}

/// The median times of the MacPherson's suite run one analysis after another on one thread (`kc::run_suite`) and on
/// every thread (`kc::run_suite_on_threads`, as the server runs it).
fn suites(s: &Settings) -> Result<(f64, f64), String> {
    let path = crate::workspace_root().join("examples/macpherson.json");
    let file = elastokin::suspensions::SuspensionFile::read(&path).map_err(|e| e.to_string())?;
    let settings = kc::Settings::default();
    // One after another on one thread: an analysis that runs parts of itself at once does not here.
    let one_thread = rayon::ThreadPoolBuilder::new().num_threads(1).build().map_err(|e| e.to_string())?;
    let in_turn =
        s.batch_budget().time(|| one_thread.install(|| kc::run_suite(&file, &[], &settings, |_| {}).analyses.len()));
    let on_threads = s.batch_budget().time(|| kc::run_suite_on_threads(&file, &[], &settings).analyses.len());
    Ok((in_turn.median, on_threads.median))
}
