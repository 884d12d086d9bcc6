//! `elastokin live` over real HTTP on the loopback: who is refused (no token, a wrong one, a foreign Origin
//! or Host, a body over the limit), an edit's figures against `elastokin run` on the file edited by hand,
//! undo, two clients seeing one design, a save writing the file with the moved number alone rewritten, and
//! Ctrl-C stopping the server with nothing left behind. The library's server (`elastokin::live::LiveServer`,
//! which the command and Python start) started and stopped in the test's own process, and its page shown
//! in another origin's frame when, and only when, that origin is given as a frame ancestor.

use elastokin::live::{FrameAncestors, LiveServer, Served};
use elastokin::suspensions::kc::Analysis;
use serde_json::Value;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const RATE: &str = "/suspension/macpherson/spring/rate";
const TIE_ROD_INNER_Z: &str = "/suspension/macpherson/hardpoints/tie_rod_inner/2";

/// A server started on a copy of the MacPherson example in a directory of its own.
struct Server {
    child: Child,
    dir: PathBuf,
    model: PathBuf,
    port: u16,
    token: String,
}

impl Server {
    fn start(name: &str, more: &[&str]) -> Server {
        let dir = std::env::temp_dir().join(format!("elastokin-live-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let model = dir.join("macpherson.json");
        std::fs::copy(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/macpherson.json"), &model).unwrap();
        let mut child = Command::new(env!("CARGO_BIN_EXE_elastokin"))
            .args(["live", "--no-open", "--analysis", "parallel-travel", "--steps", "8"])
            .args(more)
            .arg(&model)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
        let address = lines.find_map(|l| l.ok().filter(|l| l.starts_with("http://"))).expect("the address printed");
        // http://127.0.0.1:PORT/TOKEN/
        let rest = address.strip_prefix("http://127.0.0.1:").unwrap();
        let (port, token) = rest.split_once('/').unwrap();
        let token = token.trim_end_matches('/').to_string();
        assert_eq!(token.len(), 32, "{address}");
        Server { child, dir, model, port: port.parse().unwrap(), token }
    }

    fn host(&self) -> String {
        format!("127.0.0.1:{}", self.port)
    }

    /// A request with the server's own Host and no Origin.
    fn ask(&self, method: &str, path: &str, body: &str) -> (u16, Value) {
        self.raw(method, path, &[("Host", &self.host())], body.as_bytes())
    }

    /// A request under the token.
    fn call(&self, method: &str, route: &str, body: &str) -> (u16, Value) {
        self.ask(method, &format!("/{}/{route}", self.token), body)
    }

    /// A request as written: `headers` and `body` (its Content-Length added), on a connection of its own.
    fn raw(&self, method: &str, path: &str, headers: &[(&str, &str)], body: &[u8]) -> (u16, Value) {
        let mut stream = TcpStream::connect(("127.0.0.1", self.port)).unwrap();
        stream.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
        let mut head = format!("{method} {path} HTTP/1.1\r\nConnection: close\r\nContent-Length: {}\r\n", body.len());
        for (name, value) in headers {
            head.push_str(&format!("{name}: {value}\r\n"));
        }
        head.push_str("\r\n");
        stream.write_all(head.as_bytes()).unwrap();
        // A refused body may be cut off by the server: what matters is its answer.
        let _ = stream.write_all(body);
        read_response(stream)
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// The status and JSON body of a response read to the end of the connection.
fn read_response(mut stream: TcpStream) -> (u16, Value) {
    let mut bytes = Vec::new();
    let _ = stream.read_to_end(&mut bytes);
    let text = String::from_utf8_lossy(&bytes);
    let status = text.split(' ').nth(1).and_then(|s| s.parse().ok()).unwrap_or_else(|| panic!("no status: {text}"));
    let body = text.split_once("\r\n\r\n").map_or("", |(_, b)| b);
    (status, serde_json::from_str(body).unwrap_or_else(|e| panic!("{e}: {text}")))
}

/// The SI value of figure `key` of parallel travel in a state.
fn figure(state: &Value, key: &str) -> f64 {
    let analysis = state["analyses"].as_array().unwrap().iter().find(|a| a["name"] == "parallel-travel").unwrap();
    let figures = analysis["figures"].as_array().unwrap();
    figures.iter().find(|f| f["key"] == key).unwrap()["value"].as_f64().unwrap()
}

/// A request refused or served: what it is, its path, its headers and the status expected.
type Case<'a> = (&'a str, &'a str, Vec<(&'a str, &'a str)>, u16);

#[test]
fn every_request_without_the_token_or_from_elsewhere_is_refused() {
    let server = Server::start("refusals", &["--targets", "examples/targets/macpherson.json"]);
    let host = server.host();
    let state = format!("/{}/state", server.token);
    let wrong = format!("/{}/state", "0".repeat(32));
    let own = format!("http://{host}");
    let cases: [Case; 8] = [
        ("the token's own request", &state, vec![("Host", &host)], 200),
        ("no token", "/state", vec![("Host", &host)], 403),
        ("the root", "/", vec![("Host", &host)], 403),
        ("a wrong token", &wrong, vec![("Host", &host)], 403),
        ("a foreign Origin", &state, vec![("Host", &host), ("Origin", "http://evil.example")], 403),
        ("a foreign Host", &state, vec![("Host", "evil.example")], 403),
        ("another port", &state, vec![("Host", "127.0.0.1:1")], 403),
        ("its own Origin", &state, vec![("Host", &host), ("Origin", &own)], 200),
    ];
    for (what, path, headers, expected) in cases {
        let (status, body) = server.raw("GET", path, &headers, b"");
        assert_eq!(status, expected, "{what}: {body}");
        if expected == 403 {
            assert!(body["error"].is_string() && body.get("state").is_none(), "{what}: {body}");
        }
    }
    // A body over the limit, said by its length or sent in chunks.
    let edit = format!("/{}/edit", server.token);
    let (status, _) = server.raw("POST", &edit, &[("Host", &host)], &vec![b' '; (1 << 20) + 1]);
    assert_eq!(status, 413);
    let mut stream = TcpStream::connect(("127.0.0.1", server.port)).unwrap();
    stream.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
    let head =
        format!("POST {edit} HTTP/1.1\r\nHost: {host}\r\nConnection: close\r\nTransfer-Encoding: chunked\r\n\r\n");
    stream.write_all(head.as_bytes()).unwrap();
    let chunk = format!("{:x}\r\n{}\r\n", 1 << 16, " ".repeat(1 << 16));
    for _ in 0..17 {
        if stream.write_all(chunk.as_bytes()).is_err() {
            break;
        }
    }
    let _ = stream.write_all(b"0\r\n\r\n");
    assert_eq!(read_response(stream).0, 413);
    // Still serving, the design untouched; judged against the targets given.
    let (status, body) = server.call("GET", "state", "");
    assert_eq!((status, body["state"]["version"].as_u64()), (200, Some(1)));
    let targets = body["state"]["targets"].as_array().unwrap();
    let judged: Vec<(&str, bool)> =
        targets.iter().map(|t| (t["figure"].as_str().unwrap(), t["met"].as_bool().unwrap())).collect();
    assert_eq!(judged, [("bump_steer", true), ("wheel_rate", true)], "the shipped example meets its targets");
}

#[test]
fn an_edit_answers_as_the_file_edited_by_hand_runs_and_a_save_writes_that_file() {
    let server = Server::start("edit", &[]);
    let original = std::fs::read_to_string(&server.model).unwrap();
    let (status, first) = server.call("GET", "state", "");
    assert_eq!(status, 200);
    let first_bump = figure(&first["state"], "bump_steer");
    let projections = first["state"]["projections"].as_str().unwrap();
    for view in ["front", "side", "plan"] {
        assert_eq!(projections.matches(&format!("id=\"view-{view}\"")).count(), 1, "the {view} view drawn");
    }

    let edit = format!(r#"{{"pointer": "{TIE_ROD_INNER_Z}", "value": -0.0394}}"#);
    let (status, edited) = server.call("POST", "edit", &edit);
    assert_eq!(status, 200, "{edited}");
    assert_eq!(edited["state"]["version"].as_u64(), Some(2));

    // The file edited by hand, run by `elastokin run`.
    let by_hand = original.replacen("[-0.150, 0.370, -0.0374]", "[-0.150, 0.370, -0.0394]", 1);
    assert_ne!(by_hand, original);
    let hand = server.dir.join("by_hand.json");
    std::fs::write(&hand, &by_hand).unwrap();
    let out = server.dir.join("out");
    let ran = Command::new(env!("CARGO_BIN_EXE_elastokin"))
        .args(["run", "--quiet", "--analysis", "parallel-travel", "--steps", "8", "--out"])
        .args([&out, &hand])
        .output()
        .unwrap();
    assert!(ran.status.success(), "{}", String::from_utf8_lossy(&ran.stderr));
    let summary: Value = serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let ran_figures = summary["analyses"]["parallel-travel"]["figures"].as_object().unwrap();
    for key in ["bump_steer", "camber_gain", "wheel_rate", "caster", "scrub_radius"] {
        let (live, run) = (figure(&edited["state"], key), ran_figures[key]["si_value"].as_f64().unwrap());
        // The same file read the same way: equal to the bit (the issue asks 1e-9).
        assert_eq!(live.to_bits(), run.to_bits(), "{key}: live {live}, run {run}");
    }
    assert!((figure(&edited["state"], "bump_steer") - first_bump).abs() > 1e-3, "the edit moved bump steer");

    // A second client sees the same design.
    let (_, seen) = server.call("GET", "state", "");
    assert_eq!(seen["state"]["version"].as_u64(), Some(2));
    assert_eq!(seen["state"]["moved"][0]["pointer"], TIE_ROD_INNER_Z);

    // A refused edit keeps the design and says why.
    let (status, refused) = server.call("POST", "edit", &format!(r#"{{"pointer": "{RATE}", "value": -1}}"#));
    assert_eq!(status, 422);
    assert!(refused["error"].as_str().unwrap().contains("rate"), "{refused}");
    assert_eq!(refused["state"]["version"].as_u64(), Some(2));

    // Undo, redo, save: the file is the one edited by hand, byte for byte.
    let (status, undone) = server.call("POST", "undo", "");
    assert_eq!((status, figure(&undone["state"], "bump_steer")), (200, first_bump));
    let (status, _) = server.call("POST", "redo", "");
    assert_eq!(status, 200);
    let (status, saved) = server.call("POST", "save", "");
    assert_eq!(status, 200, "{saved}");
    assert_eq!(std::fs::read_to_string(&server.model).unwrap(), by_hand);
    let mut left: Vec<String> =
        std::fs::read_dir(&server.dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into()).collect();
    left.sort();
    assert_eq!(left, ["by_hand.json", "macpherson.json", "out"], "a save leaves no file beside the model");

    // A file changed on disk since is not written over.
    std::fs::write(&server.model, &original).unwrap();
    let (status, refused) = server.call("POST", "save", "");
    assert_eq!(status, 409, "{refused}");
    assert_eq!(std::fs::read_to_string(&server.model).unwrap(), original);
}

#[test]
fn ctrl_c_stops_the_server_and_leaves_nothing_behind() {
    let mut server = Server::start("interrupt", &[]);
    let (status, _) = server.call("POST", "edit", &format!(r#"{{"pointer": "{RATE}", "value": 26000}}"#));
    assert_eq!(status, 200);
    let interrupted = Command::new("kill").args(["-INT", &server.child.id().to_string()]).status().unwrap();
    assert!(interrupted.success());
    let start = Instant::now();
    let status = loop {
        if let Some(status) = server.child.try_wait().unwrap() {
            break status;
        }
        assert!(start.elapsed() < Duration::from_secs(20), "the server did not stop");
        std::thread::sleep(Duration::from_millis(20));
    };
    assert!(status.success(), "{status}");
    let mut said = String::new();
    server.child.stderr.take().unwrap().read_to_string(&mut said).unwrap();
    assert!(said.contains("not in") && said.contains("macpherson.json"), "unsaved edits are told: {said}");
    let left: Vec<_> = std::fs::read_dir(&server.dir).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(left, ["macpherson.json"]);
    assert!(TcpStream::connect(("127.0.0.1", server.port)).is_err(), "the port is closed");
}

/// Headless Chromium driven through its DevTools protocol on a pipe (`--remote-debugging-pipe`: commands
/// on its descriptor 3, answers and events on 4, each a JSON message ended by a NUL byte), with the page's
/// console kept.
struct Browser {
    child: Child,
    to: std::process::ChildStdin,
    from: BufReader<std::process::ChildStdout>,
    profile: PathBuf,
    next: u64,
    /// What each page logged as an error or warning, and every exception it threw, by its session.
    console: Vec<(String, String)>,
    /// The frames of another origin attached to a page (`Target.setAutoAttach`): the page's session, the
    /// frame's session and its address.
    frames: Vec<(String, String, String)>,
}

impl Browser {
    /// Chromium with a fresh profile, or `None` on a machine without it (CI installs it, and there its
    /// absence fails).
    fn start(profile: PathBuf) -> Option<Browser> {
        let found = std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default())
            .map(|d| d.join("chromium"))
            .find(|p| p.is_file());
        let chromium = match found {
            Some(c) => c,
            None if std::env::var_os("CI").is_none() => {
                eprintln!("skipped: chromium is not on PATH (apt-get install chromium)");
                return None;
            }
            None => panic!("chromium is not on PATH: .ci/run installs Debian's chromium"),
        };
        let _ = std::fs::remove_dir_all(&profile);
        std::fs::create_dir_all(&profile).unwrap();
        // The shell hands the pipes over as descriptors 3 and 4.
        let script = r#"exec "$0" --headless --no-sandbox --disable-gpu --no-first-run --disable-background-networking \
            --disable-component-update --disable-sync --remote-debugging-pipe --user-data-dir="$1" \
            3<&0 4>&1 0</dev/null 1>/dev/null 2>/dev/null"#;
        let mut child = Command::new("sh")
            .args(["-c", script])
            .arg(&chromium)
            .arg(&profile)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .unwrap();
        let (to, from) = (child.stdin.take().unwrap(), BufReader::new(child.stdout.take().unwrap()));
        Some(Browser { child, to, from, profile, next: 0, console: Vec::new(), frames: Vec::new() })
    }

    /// Sends `method` with `params` (to the page of `session`, or the browser) and returns its result; the
    /// page's console events read meanwhile are kept.
    fn send(&mut self, session: Option<&str>, method: &str, params: Value) -> Value {
        self.next += 1;
        let mut message = serde_json::json!({ "id": self.next, "method": method, "params": params });
        if let Some(s) = session {
            message["sessionId"] = Value::String(s.into());
        }
        self.to.write_all(message.to_string().as_bytes()).unwrap();
        self.to.write_all(b"\0").unwrap();
        self.to.flush().unwrap();
        loop {
            let mut bytes = Vec::new();
            self.from.read_until(0, &mut bytes).unwrap();
            assert!(bytes.ends_with(b"\0"), "chromium closed its pipe");
            let answer: Value = serde_json::from_slice(&bytes[..bytes.len() - 1]).unwrap();
            if answer["id"].as_u64() == Some(self.next) {
                assert!(answer.get("error").is_none(), "{method}: {answer}");
                return answer["result"].clone();
            }
            let from = answer["sessionId"].as_str().unwrap_or("").to_string();
            let params = &answer["params"];
            if answer["method"] == "Target.attachedToTarget" {
                let (session, url) = (&params["sessionId"], &params["targetInfo"]["url"]);
                self.frames.push((
                    from.clone(),
                    session.as_str().unwrap_or("").into(),
                    url.as_str().unwrap_or("").into(),
                ));
            }
            let said = match answer["method"].as_str() {
                Some("Runtime.consoleAPICalled") if matches!(params["type"].as_str(), Some("error" | "warning")) => {
                    Some(params["args"].to_string())
                }
                Some("Runtime.exceptionThrown") => Some(params["exceptionDetails"].to_string()),
                Some("Log.entryAdded") if params["entry"]["level"] != "info" => Some(params["entry"].to_string()),
                _ => None,
            };
            if let Some(said) = said {
                self.console.push((from, said));
            }
        }
    }

    /// A new page at `url`, attached: its session.
    fn open(&mut self, url: &str) -> String {
        self.open_with_frames(url, false)
    }

    /// A new page at `url`, attached, and with `frames` each frame of another origin it shows attached too
    /// (listed in `frames` once loaded): the page's session.
    fn open_with_frames(&mut self, url: &str, frames: bool) -> String {
        let target = self.send(None, "Target.createTarget", serde_json::json!({ "url": "about:blank" }));
        let attached = self.send(
            None,
            "Target.attachToTarget",
            serde_json::json!({ "targetId": target["targetId"], "flatten": true }),
        );
        let session = attached["sessionId"].as_str().unwrap().to_string();
        for domain in ["Runtime.enable", "Log.enable", "Page.enable"] {
            self.send(Some(&session), domain, serde_json::json!({}));
        }
        if frames {
            let attach = serde_json::json!({ "autoAttach": true, "waitForDebuggerOnStart": false, "flatten": true });
            self.send(Some(&session), "Target.setAutoAttach", attach);
        }
        self.send(Some(&session), "Page.navigate", serde_json::json!({ "url": url }));
        session
    }

    /// The value of the script `expression` in the page of `session` (awaited when it is a promise).
    fn evaluate(&mut self, session: &str, expression: &str) -> Value {
        let params = serde_json::json!({ "expression": expression, "returnByValue": true, "awaitPromise": true });
        let result = self.send(Some(session), "Runtime.evaluate", params);
        assert!(result.get("exceptionDetails").is_none(), "{expression}: {result}");
        result["result"]["value"].clone()
    }

    /// The page's report (`<output id="live-state">`) once `ready` holds of it, within 20 s.
    fn live_state(&mut self, session: &str, ready: impl Fn(&Value) -> bool) -> Value {
        let start = Instant::now();
        loop {
            let text = self.evaluate(session, "(document.getElementById('live-state') || {}).textContent || ''");
            if let Some(state) = text.as_str().and_then(|t| serde_json::from_str::<Value>(t).ok()) {
                if ready(&state) {
                    return state;
                }
            }
            assert!(start.elapsed() < Duration::from_secs(20), "the page did not get there: {text}");
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
        let _ = std::fs::remove_dir_all(&self.profile);
    }
}

/// The page in a real browser: it shows every figure, chart and hardpoint of the design; a hardpoint typed
/// in millimetres is the edit the file edited by hand makes, its figure shown as the server holds it; undo
/// puts the number back; a save writes the file edited by hand; the tune button moves the TARGETS file's
/// free numbers as one design and says how the tune ended; a page of another origin cannot edit the
/// design; the console stays clean.
#[test]
fn the_page_in_chromium_edits_by_typing_undoes_saves_and_no_other_page_drives_it() {
    let server = Server::start("browser", &["--targets", "examples/targets/macpherson.json"]);
    let Some(mut browser) = Browser::start(server.dir.with_extension("profile")) else { return };
    let address = format!("http://127.0.0.1:{}/{}/", server.port, server.token);
    let page = browser.open(&address);
    let shown = browser.live_state(&page, |s| s["version"] == 1);
    let (_, state) = server.call("GET", "state", "");
    let state = &state["state"];
    let analyses = state["analyses"].as_array().unwrap();
    let figures: usize = analyses.iter().map(|a| a["figures"].as_array().unwrap().len()).sum();
    let charts: usize = analyses.iter().map(|a| a["charts"].as_array().unwrap().len()).sum();
    assert_eq!(shown["figures"], figures, "{shown}");
    assert_eq!((&shown["charts"], &shown["drawn"]), (&charts.into(), &charts.into()), "{shown}");
    let numbers = state["hardpoints"].as_array().unwrap().len() + state["rates"].as_array().unwrap().len();
    assert_eq!(shown["inputs"], numbers, "{shown}: a field for every hardpoint coordinate and rate");
    assert_eq!(shown["errors"], serde_json::json!([]));
    assert_eq!(shown["projections"], 3, "{shown}: front, side and plan");

    // Typed: -39.4 mm into the tie rod's inner z, committed as a user does, by leaving the field.
    let input = format!("document.querySelector('input[data-pointer=\"{TIE_ROD_INNER_Z}\"]')");
    browser.evaluate(&page, &format!("{input}.focus(); {input}.select(); true"));
    browser.send(Some(&page), "Input.insertText", serde_json::json!({ "text": "-39.4" }));
    browser.evaluate(&page, &format!("{input}.blur(); true"));
    let shown = browser.live_state(&page, |s| s["version"] == 2);
    let (_, edited) = server.call("GET", "state", "");
    // Every curve of the previous design drawn in grey beneath the new one.
    let curves: usize = edited["state"]["analyses"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|a| a["charts"].as_array().unwrap())
        .flat_map(|c| c["axes"].as_array().unwrap())
        .map(|axis| axis["series"].as_array().unwrap().len())
        .sum();
    assert_eq!(shown["ghosts"], curves, "{shown}");
    assert_eq!(shown["drawn"], shown["charts"], "{shown}");
    assert_eq!(edited["state"]["moved"][0]["pointer"], TIE_ROD_INNER_Z);
    assert_eq!(edited["state"]["moved"][0]["value"].as_f64(), Some(-0.0394), "39.4 mm is 0.0394 m, to the bit");
    // The figure shown is the server's, as written: its SI value times its factor, at its decimals.
    let bump = edited["state"]["analyses"][0]["figures"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["key"] == "bump_steer")
        .unwrap();
    let written = format!(
        "{:.*} {}",
        bump["decimals"].as_u64().unwrap() as usize,
        bump["value"].as_f64().unwrap() * bump["factor"].as_f64().unwrap(),
        bump["unit"].as_str().unwrap()
    );
    let cell = browser
        .evaluate(&page, "document.querySelector('tr[data-key=\"parallel-travel/bump_steer\"] td.value').textContent");
    assert_eq!(cell.as_str(), Some(written.as_str()));
    // The previous design's value stays beside it.
    let before = browser
        .evaluate(&page, "document.querySelector('tr[data-key=\"parallel-travel/bump_steer\"] td.quiet').textContent");
    assert!(before.as_str().is_some_and(|b| b.ends_with("deg/m")), "{before}");

    // The tie rod's inner point selected by its name: every figure's derivatives to it, per mm, as the
    // server's guidance gives them.
    browser.evaluate(&page, "document.querySelector('tr[data-point=\"/suspension/macpherson/hardpoints/tie_rod_inner\"] button').click(); true");
    let guided = browser.live_state(&page, |s| s["guided"].as_u64().unwrap_or(0) > 0);
    let (status, guidance) =
        server.call("POST", "guidance", r#"{"point": "/suspension/macpherson/hardpoints/tie_rod_inner"}"#);
    assert_eq!(status, 200, "{guidance}");
    let derivatives = &guidance["guidance"]["analyses"][0]["figures"];
    let bump_d = derivatives.as_array().unwrap().iter().find(|f| f["key"] == "bump_steer").unwrap();
    let factor = bump["factor"].as_f64().unwrap();
    let per_mm: Vec<f64> =
        bump_d["per_metre"].as_array().unwrap().iter().map(|d| d.as_f64().unwrap() * factor / 1000.0).collect();
    let shown = browser
        .evaluate(&page, "document.querySelector('tr[data-key=\"parallel-travel/bump_steer\"] td.guide').textContent");
    let shown: Vec<f64> =
        shown.as_str().unwrap().trim_end_matches(" deg/m /mm").split(", ").map(|v| v.parse().unwrap()).collect();
    assert_eq!(shown.len(), 3, "{guided}");
    for (s, d) in shown.iter().zip(&per_mm) {
        // Written to three significant digits.
        assert!((s - d).abs() <= 5e-3 * d.abs(), "{shown:?} against {per_mm:?}");
    }
    assert!(per_mm[2].abs() > 1e-3, "the tie rod's height moves bump steer: {per_mm:?}");

    // Undo by its button: the field shows the file's number again; redo; save by its button.
    browser.evaluate(&page, "document.getElementById('undo').click(); true");
    browser.live_state(&page, |s| s["version"] == 3);
    assert_eq!(browser.evaluate(&page, &format!("{input}.value")).as_str(), Some("-37.4"));
    browser.evaluate(&page, "document.getElementById('redo').click(); true");
    browser.live_state(&page, |s| s["version"] == 4);
    let original = std::fs::read_to_string(&server.model).unwrap();
    browser.evaluate(&page, "document.getElementById('save').click(); true");
    let start = Instant::now();
    while std::fs::read_to_string(&server.model).unwrap() == original {
        assert!(start.elapsed() < Duration::from_secs(20), "the page's save wrote nothing");
        std::thread::sleep(Duration::from_millis(20));
    }
    let by_hand = original.replacen("[-0.150, 0.370, -0.0374]", "[-0.150, 0.370, -0.0394]", 1);
    assert_eq!(std::fs::read_to_string(&server.model).unwrap(), by_hand);

    // Tune by its button: one design more, the free numbers moved, how the tune ended said on the page.
    browser.evaluate(&page, "document.getElementById('tune').click(); true");
    browser.live_state(&page, |s| s["version"] == 5);
    let (_, tuned) = server.call("GET", "state", "");
    let moved = tuned["state"]["moved"].as_array().map_or(0, Vec::len);
    assert!(moved > 1, "the tune moved the free numbers: {}", tuned["state"]["moved"]);
    let start = Instant::now();
    loop {
        let status = browser.evaluate(&page, "document.getElementById('status').textContent");
        if status.as_str().is_some_and(|s| s.contains("tuned: ") && s.contains("targets met")) {
            break;
        }
        assert!(start.elapsed() < Duration::from_secs(20), "the page does not say how the tune ended: {status}");
        std::thread::sleep(Duration::from_millis(20));
    }

    // Another page (a file on disk: another origin) posts an edit as a form could: the server refuses it.
    let foreign = server.dir.join("foreign.html");
    let post = format!(
        "<script>fetch('{address}edit', {{ method: 'POST', mode: 'no-cors', body: JSON.stringify({{ pointer: '{RATE}', \
         value: 1000 }}) }}).then(() => document.title = 'sent', () => document.title = 'sent');</script>"
    );
    std::fs::write(&foreign, post).unwrap();
    let other = browser.open(&format!("file://{}", foreign.display()));
    let start = Instant::now();
    while browser.evaluate(&other, "document.title").as_str() != Some("sent") {
        assert!(start.elapsed() < Duration::from_secs(20), "the foreign page sent nothing");
        std::thread::sleep(Duration::from_millis(20));
    }
    let (_, after) = server.call("GET", "state", "");
    assert_eq!(after["state"]["version"].as_u64(), Some(5), "the foreign page's edit was refused");
    assert_eq!(after["state"]["moved"], tuned["state"]["moved"]);

    // What the live page logged: nothing; the foreign page's console has the refusal.
    browser.evaluate(&page, "true");
    let console: Vec<&String> = browser.console.iter().filter(|(s, _)| *s == page).map(|(_, l)| l).collect();
    assert!(console.is_empty(), "the console says {console:#?}");
    assert!(browser.console.iter().any(|(s, l)| *s == other && l.contains("403")), "{:#?}", browser.console);
}

/// Bound to every address as `--bind` asks: the command warns that the design can be edited from
/// elsewhere, and serves its own Host, a literal address or localhost, at its port.
#[test]
fn a_bind_beyond_this_machine_is_warned_of() {
    let mut server = Server::start("bind", &["--bind", "0.0.0.0"]);
    let (status, _) = server.call("GET", "state", "");
    assert_eq!(status, 200);
    let localhost = format!("localhost:{}", server.port);
    let (status, _) = server.raw("GET", &format!("/{}/state", server.token), &[("Host", &localhost)], b"");
    assert_eq!(status, 200);
    let (status, _) = server.raw("GET", &format!("/{}/state", server.token), &[("Host", "rebound.example")], b"");
    assert_eq!(status, 403);
    server.child.kill().unwrap();
    server.child.wait().unwrap();
    let mut said = String::new();
    server.child.stderr.take().unwrap().read_to_string(&mut said).unwrap();
    assert!(said.contains("warning: listening on 0.0.0.0, reachable from other machines"), "{said}");
}

/// A model or targets file that cannot be read is refused before anything listens: exit 2, naming it.
#[test]
fn bad_files_are_refused_by_name_before_the_server_listens() {
    let root = env!("CARGO_MANIFEST_DIR");
    let cases: [(&[&str], &str); 3] = [
        (&["live", "--no-open", "nowhere.json"], "nowhere.json"),
        (&["live", "--no-open", "examples/macpherson.json", "--targets", "nowhere.json"], "nowhere.json"),
        (&["live", "--no-open", "examples/macpherson_variants.txt"], "macpherson_variants.txt"),
    ];
    for (args, named) in cases {
        let o = Command::new(env!("CARGO_BIN_EXE_elastokin")).args(args).current_dir(root).output().unwrap();
        let said = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {said}");
        assert!(said.contains(named) && !said.contains("panicked"), "{args:?}: {said}");
        assert!(!String::from_utf8_lossy(&o.stdout).contains("http://"), "{args:?}: nothing served");
    }
}

/// A copy of the MacPherson example in a directory of its own, opened as the library serves it: parallel
/// travel in 8 steps.
fn served_copy(name: &str) -> (Served, PathBuf) {
    let dir = std::env::temp_dir().join(format!("elastokin-live-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("macpherson.json");
    std::fs::copy(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/macpherson.json"), &model).unwrap();
    (Served::open(&model, &[Analysis::ParallelTravel], 8).unwrap(), dir)
}

/// A request as written to `at`, on a connection of its own: the status, the head (in lower case) and the
/// body as text.
fn request(at: SocketAddr, method: &str, path: &str, headers: &[(&str, &str)], body: &str) -> (u16, String, String) {
    let mut stream = TcpStream::connect(at).unwrap();
    stream.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
    let mut head = format!("{method} {path} HTTP/1.1\r\nContent-Length: {}\r\n", body.len());
    for (name, value) in headers {
        head.push_str(&format!("{name}: {value}\r\n"));
    }
    stream.write_all(format!("{head}\r\n{body}").as_bytes()).unwrap();
    // Read as a browser reads it: the head, then as many bytes as its Content-Length says.
    let mut bytes = Vec::new();
    let mut chunk = [0u8; 4096];
    let split = loop {
        let n = stream.read(&mut chunk).unwrap();
        assert!(n > 0, "the connection closed before the answer: {}", String::from_utf8_lossy(&bytes));
        bytes.extend_from_slice(&chunk[..n]);
        if let Some(at) = bytes.windows(4).position(|w| w == b"\r\n\r\n") {
            break at;
        }
    };
    let head = String::from_utf8_lossy(&bytes[..split]).to_ascii_lowercase();
    let length: usize = head
        .lines()
        .find_map(|l| l.strip_prefix("content-length: "))
        .and_then(|l| l.trim().parse().ok())
        .unwrap_or_else(|| panic!("no length: {head}"));
    while bytes.len() < split + 4 + length {
        let n = stream.read(&mut chunk).unwrap();
        assert!(n > 0, "the answer was cut short");
        bytes.extend_from_slice(&chunk[..n]);
    }
    let body = String::from_utf8_lossy(&bytes[split + 4..]).into_owned();
    let status = head.split(' ').nth(1).and_then(|s| s.parse().ok()).unwrap_or_else(|| panic!("{head}"));
    (status, head, body)
}

/// The library's server in this process: started on any free port, serving its token's requests (each on
/// a connection it closes), refusing others; stopped, its thread ended and its port free at once, however
/// it is stopped: by `stop`, by a stopper from another thread, or by being dropped.
#[test]
fn the_library_server_starts_on_a_free_port_serves_and_stops_leaving_its_port_free() {
    let (served, dir) = served_copy("library");
    let model = served.model.clone();
    let any = "127.0.0.1:0".parse().unwrap();
    let mut server = LiveServer::start(served, any, FrameAncestors::none()).unwrap();
    let at = server.bound();
    assert_ne!(at.port(), 0);
    let address = server.address().to_string();
    let token = address.trim_end_matches('/').rsplit('/').next().unwrap().to_string();
    assert_eq!(address, format!("http://127.0.0.1:{}/{token}/", at.port()));
    let host = at.to_string();
    let (status, head, body) = request(at, "GET", &format!("/{token}/state"), &[("Host", &host)], "");
    assert_eq!(status, 200, "{body}");
    assert!(head.contains("\r\nconnection: close"), "{head}");
    assert!(head.contains("\r\ncontent-security-policy: frame-ancestors 'self'\r\n"), "{head}");
    assert!(head.contains("\r\nx-frame-options: sameorigin"), "{head}");
    let state: Value = serde_json::from_str(&body).unwrap();
    assert_eq!(state["state"]["version"].as_u64(), Some(1));
    assert_eq!(request(at, "GET", "/state", &[("Host", &host)], "").0, 403);
    let edit = format!(r#"{{"pointer": "{RATE}", "value": 26000}}"#);
    let (status, _, _) = request(at, "POST", &format!("/{token}/edit"), &[("Host", &host)], &edit);
    assert_eq!(status, 200);

    let live = server.stop().expect("the design as the server left it");
    assert!(live.unsaved(), "the edit was not saved");
    assert_eq!(live.design().version(), 2);
    assert!(TcpStream::connect(at).is_err(), "nothing listens at {at} once stopped");
    drop(TcpListener::bind(at).expect("the port is free once stopped"));
    assert!(server.stop().is_none(), "a second stop has nothing to stop");
    assert_eq!(std::fs::read_to_string(&model).unwrap(), include_str!("../examples/macpherson.json"));

    // Stopped from another thread, as Ctrl-C stops the command, and waited for.
    let (served, _) = served_copy("library");
    let mut server = LiveServer::start(served, any, FrameAncestors::none()).unwrap();
    let (at, stopper) = (server.bound(), server.stopper());
    std::thread::spawn(move || stopper.stop()).join().unwrap();
    assert!(server.wait().is_some());
    assert!(TcpStream::connect(at).is_err(), "nothing listens at {at} once stopped by a stopper");

    // Dropped.
    let (served, _) = served_copy("library");
    let server = LiveServer::start(served, any, FrameAncestors::none()).unwrap();
    let at = server.bound();
    drop(server);
    assert!(TcpStream::connect(at).is_err(), "nothing listens at {at} once dropped");
    drop(TcpListener::bind(at).expect("the port is free once dropped"));

    // A port taken is refused by name.
    let taken = TcpListener::bind("127.0.0.1:0").unwrap();
    let (served, _) = served_copy("library");
    let refused = LiveServer::start(served, taken.local_addr().unwrap(), FrameAncestors::none()).unwrap_err();
    let said = refused.to_string();
    assert!(
        said.starts_with(&format!("cannot listen on 127.0.0.1 port {}", taken.local_addr().unwrap().port())),
        "{said}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A page of another origin (a notebook's, here `http://localhost:PORT`) that shows the live page in a
/// frame, served by a thread of the test to every request.
fn framing_page(live: &str) -> (SocketAddr, String) {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let at = listener.local_addr().unwrap();
    let page = format!(
        "<!DOCTYPE html><html><head><title>notebook</title><link rel=\"icon\" href=\"data:,\"></head><body>\
         <iframe src=\"{live}\" width=\"1200\" height=\"800\"></iframe></body></html>"
    );
    std::thread::spawn(move || {
        for stream in listener.incoming().flatten() {
            let mut stream = stream;
            let mut asked = [0u8; 4096];
            let _ = stream.read(&mut asked);
            let answer = format!(
                "HTTP/1.1 200 OK\r\nContent-Type: text/html\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{page}",
                page.len()
            );
            let _ = stream.write_all(answer.as_bytes());
        }
    });
    (at, format!("http://localhost:{}/", at.port()))
}

/// The live page in a notebook's frame, in Chromium: given the notebook's origin as a frame ancestor
/// (`http://localhost:*`, Python's default), the frame shows the design, every chart drawn, and an edit
/// posted by the framed page is made, while one posted by the notebook's page is refused; without it (the
/// command's server), the browser refuses to show the page in the frame.
#[test]
fn the_page_is_framed_by_a_notebook_given_as_a_frame_ancestor_and_by_no_other() {
    let (served, dir) = served_copy("framed");
    let notebook = FrameAncestors::new(["http://localhost:*", "http://127.0.0.1:*"]).unwrap();
    let server = LiveServer::start(served, "127.0.0.1:0".parse().unwrap(), notebook).unwrap();
    let Some(mut browser) = Browser::start(dir.with_extension("profile")) else { return };
    let (_, parent) = framing_page(server.address());
    let page = browser.open_with_frames(&parent, true);
    let start = Instant::now();
    let frame = loop {
        // The page's one frame, attached before it navigated.
        if let Some((_, frame, _)) = browser.frames.iter().find(|(p, ..)| *p == page) {
            break frame.clone();
        }
        assert!(start.elapsed() < Duration::from_secs(20), "no frame of the live page attached: {:?}", browser.frames);
        browser.evaluate(&page, "true");
        std::thread::sleep(Duration::from_millis(20));
    };
    let shown = browser
        .live_state(&frame, |s| s["version"] == 1 && s["charts"].as_u64() > Some(0) && s["drawn"] == s["charts"]);
    assert_eq!(shown["errors"], serde_json::json!([]), "{shown}");
    // An edit the framed page posts comes from its own origin, with the token: made.
    let post = format!(
        "fetch('edit', {{ method: 'POST', body: JSON.stringify({{ pointer: '{RATE}', value: 26000 }}) }}).then(r => r.status)"
    );
    assert_eq!(browser.evaluate(&frame, &post), 200);
    // The notebook's page posts the same, knowing the address: another origin, refused.
    let foreign = format!(
        "fetch('{}edit', {{ method: 'POST', mode: 'no-cors', body: JSON.stringify({{ pointer: '{RATE}', value: 1000 }}) }}).then(() => 'sent')",
        server.address()
    );
    assert_eq!(browser.evaluate(&page, &foreign), "sent");
    let state = browser
        .evaluate(&frame, "fetch('state').then(r => r.json()).then(b => [b.state.version, b.state.moved[0].value])");
    assert_eq!(state, serde_json::json!([2, 26000]), "the framed page's edit alone was made");
    let refused: Vec<&String> = browser.console.iter().filter(|(s, _)| *s == page).map(|(_, l)| l).collect();
    assert!(refused.iter().any(|l| l.contains("403")), "the notebook's post is refused: {refused:#?}");
    assert!(!refused.iter().any(|l| l.contains("frame-ancestors")), "{refused:#?}");
    // Stopped, the server leaves the page nothing to wait on: its next request is refused at once.
    drop(server);
    let next = "Promise.race([fetch('state').then(() => 'answered', () => 'refused'), \
                new Promise(r => setTimeout(() => r('still waiting'), 10000))])";
    assert_eq!(browser.evaluate(&frame, next), "refused");

    // The command's server: framed by its own origin alone.
    let (served, _) = served_copy("framed");
    let server = LiveServer::start(served, "127.0.0.1:0".parse().unwrap(), FrameAncestors::none()).unwrap();
    let (_, parent) = framing_page(server.address());
    let page = browser.open_with_frames(&parent, true);
    let start = Instant::now();
    loop {
        let said =
            browser.console.iter().filter(|(s, _)| *s == page).any(|(_, l)| l.contains("frame-ancestors 'self'"));
        if said {
            break;
        }
        assert!(start.elapsed() < Duration::from_secs(20), "the frame was not refused: {:#?}", browser.console);
        browser.evaluate(&page, "true");
        std::thread::sleep(Duration::from_millis(20));
    }
    let _ = std::fs::remove_dir_all(&dir);
}
